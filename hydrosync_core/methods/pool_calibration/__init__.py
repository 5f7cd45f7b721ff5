"""Pool calibration of multibeam boresight and lever arm against a laser-scanned target.

Seed 003 (CN 105425246 B) and ``methods.md`` section 4. Modules: ``design`` (target
faces), ``georef`` (multibeam georeferencing), ``segment`` (face segmentation),
``planes`` (TLS plane fits), ``roles`` (face roles), ``seed_iteration`` (patent angles),
``lever_arm`` (patent offsets), ``joint`` (joint least squares), ``result``, ``estimator``,
``project_run``, ``demo``.
"""

#: Version of the analysis (stored with its results; ``PluginSpec.version``).
VERSION = "1.1.0"
