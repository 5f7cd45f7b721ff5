"""Writing tables out as CSV (atomically), e.g. the synchronised latency data set."""

from __future__ import annotations

import os
from collections.abc import Mapping

import numpy as np

from hydrosync_core.atomic import write_text_atomic


def write_csv_table(path: str | os.PathLike, columns: Mapping[str, np.ndarray],
                    precision: int = 6) -> int:
    """Write equal-length numeric 1-D *columns* as a CSV file with a header row.

    *precision* decimals (6: microseconds for times in s, micrometres for lengths in m).
    Returns the number of rows written.
    """
    names = list(columns)
    table = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    formats = [f"%.{precision}f"] * len(names)

    def write(fh) -> None:
        fh.write(",".join(names) + "\n")
        np.savetxt(fh, table, fmt=formats, delimiter=",")

    write_text_atomic(path, write)
    return int(table.shape[0])
