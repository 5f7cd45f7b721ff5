"""HydroSync core: headless science and data handling (no Qt, ever)."""

__version__ = "0.1.0"
