"""Latency between GNSS heights and attitude by correlative approximation (seed 000)."""

from hydrosync_core.methods.latency.api import estimate_latency, line_series, synchronise
from hydrosync_core.methods.latency.result import LatencyParams, LatencyResult, LineResult

__all__ = [
    "LatencyParams", "LatencyResult", "LineResult", "estimate_latency", "line_series",
    "synchronise",
]
