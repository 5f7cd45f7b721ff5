"""Fast reading of the latency CSV files (gnss.csv, attitude.csv) for ``hydrosync latency``.

The parsers live in :mod:`hydrosync_core.importers.fastcsv`, shared with ``hydrosync
import`` (every large numeric CSV import takes them). Here: the two latency readers, which
always try the fast path (whatever the file size) and can leave out columns the estimate
does not need. The returned dicts are identical (float64 columns, same order) to those of
:func:`~hydrosync_core.importers.survey_csv.read_gnss_csv` and
:func:`~hydrosync_core.importers.survey_csv.read_attitude_csv`, and a bad file raises the
same one-line :class:`~hydrosync_core.errors.InputError`.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.importers.fastcsv import read_numeric_fast


def read_gnss_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """``gnss.csv`` as :func:`hydrosync_core.importers.survey_csv.read_gnss_csv` reads it."""
    fast = read_numeric_fast(Path(path), ["time", "height"], ["lat", "lon", "quality"],
                             min_rows=2, limits=plausible.GNSS)
    if fast is not None:
        return fast
    from hydrosync_core.importers.survey_csv import read_gnss_csv as generic

    return generic(path)


def read_attitude_csv(path: str | os.PathLike, heave_positive: str = "up",
                      columns: Sequence[str] | None = None) -> dict[str, np.ndarray]:
    """``attitude.csv`` as :func:`~hydrosync_core.importers.survey_csv.read_attitude_csv`.

    *columns*, if given, limits the columns returned (``time`` always is); every column is
    still checked. The latency estimate needs no heading, so leaving it out saves 8 bytes
    per record.
    """
    from hydrosync_core.importers.survey_csv import read_attitude_csv as generic

    fast = None
    if heave_positive in ("up", "down"):
        fast = read_numeric_fast(Path(path), ["time", "roll", "pitch", "heading", "heave"],
                                 min_rows=2, limits=plausible.ATTITUDE, keep=columns)
    if fast is None:
        table = generic(path, heave_positive)  # the same columns, or the precise error
        return table if columns is None else {
            c: v for c, v in table.items() if c in columns or c == "time"}
    if heave_positive == "down" and "heave" in fast:
        fast["heave"] = -fast["heave"]
    return fast
