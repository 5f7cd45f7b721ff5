"""Fast reading of the latency CSV files (gnss.csv, attitude.csv) for ``hydrosync latency``.

The parsers live in :mod:`hydrosync_core.importers.fastcsv`, shared with ``hydrosync
import`` (every large numeric CSV import takes them). Here: the two latency readers, which
always try the fast path (whatever the file size) and can leave out columns the estimate
does not need, and their prescans (:class:`~hydrosync_core.importers.fastcsv.Prescan`:
the first pass over a file in a background thread while numba loads). The returned dicts
are identical (float64 columns, same order) to those of
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
from hydrosync_core.importers.fastcsv import Prescan, read_numeric_fast

GNSS_COLUMNS = (("time", "height"), ("lat", "lon", "quality"))
"""Required and optional columns of gnss.csv (formats.md)."""
ATTITUDE_COLUMNS = ("time", "roll", "pitch", "heading", "heave")
"""Columns of attitude.csv (formats.md)."""


def prescan_gnss(path: str | os.PathLike) -> Prescan:
    """Start the first pass over ``gnss.csv`` for :func:`read_gnss_csv`."""
    return Prescan(path, *GNSS_COLUMNS)


def prescan_attitude(path: str | os.PathLike, columns: Sequence[str] | None = None) -> Prescan:
    """Start the first pass over ``attitude.csv`` for :func:`read_attitude_csv` with the same
    *columns*."""
    return Prescan(path, ATTITUDE_COLUMNS, keep=columns)


def read_gnss_csv(path: str | os.PathLike, prescan: Prescan | None = None
                  ) -> dict[str, np.ndarray]:
    """``gnss.csv`` as :func:`hydrosync_core.importers.survey_csv.read_gnss_csv` reads it.

    *prescan*, from :func:`prescan_gnss`, saves the first pass over the file.
    """
    fast = read_numeric_fast(Path(path), *GNSS_COLUMNS, min_rows=2, limits=plausible.GNSS,
                             prescan=prescan)
    if fast is not None:
        return fast
    from hydrosync_core.importers.survey_csv import read_gnss_csv as generic

    return generic(path)


def read_attitude_csv(path: str | os.PathLike, heave_positive: str = "up",
                      columns: Sequence[str] | None = None,
                      prescan: Prescan | None = None) -> dict[str, np.ndarray]:
    """``attitude.csv`` as :func:`~hydrosync_core.importers.survey_csv.read_attitude_csv`.

    *columns*, if given, limits the columns returned (``time`` always is); every column is
    still checked. The latency estimate needs no heading, so leaving it out saves 8 bytes
    per record. *prescan*, from :func:`prescan_attitude` with the same *columns*, saves
    the first pass over the file.
    """
    from hydrosync_core.importers.survey_csv import read_attitude_csv as generic

    fast = None
    if heave_positive in ("up", "down"):
        fast = read_numeric_fast(Path(path), ATTITUDE_COLUMNS, min_rows=2,
                                 limits=plausible.ATTITUDE, keep=columns, prescan=prescan)
    elif prescan is not None:
        prescan.take()  # its columns are not used: free them before the generic reader
    if fast is None:
        table = generic(path, heave_positive)  # the same columns, or the precise error
        return table if columns is None else {
            c: v for c, v in table.items() if c in columns or c == "time"}
    if heave_positive == "down" and "heave" in fast:
        fast["heave"] = -fast["heave"]
    return fast
