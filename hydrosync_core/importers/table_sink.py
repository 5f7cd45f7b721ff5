"""Growing, chunked, compressed HDF5 tables: where a streamed import writes its records.

A :class:`TableSink` appends blocks of rows to one resizable dataset per column in a
scratch HDF5 file, so an import holds one block in memory, never the day. Rows arrive in
file order; the sink drops a row whose time equals the row before it (a repeated epoch:
the first in the file is kept, as a stable sort would) and remembers whether the times
were sorted. :meth:`TableSink.finish` sorts them when they were not (then the time column
and one other column are in memory at once) and returns the final datasets.

Storage: gzip level 1 with the shuffle filter in chunks of 131 072 rows (1 MiB of
float64). Measured on the 24-hour attitude table (8.6 M rows x 5 columns, 346 MB raw;
docs/benchmarks.md, "Streaming import of raw logs"): gzip 1 writes in 36 s to 152 MB,
gzip 4 (the project's default for other tables) in 49 s to 149 MB, lzf in 19 s to 192 MB;
all read back in 9-12 s. gzip is readable by every HDF5 tool, lzf only where h5py's
filter is installed, so gzip at the level that costs least.

The scratch file lives next to the project and is unlinked as soon as it is open (POSIX),
so an interrupted import leaves nothing behind; :func:`scratch_file` returns the open file.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import tempfile
from pathlib import Path

import h5py
import numpy as np

CHUNK_ROWS = 131_072
COMPRESSION = {"compression": "gzip", "compression_opts": 1, "shuffle": True}
READ_ROWS = 1 << 20
"""Rows read at a time when a finished table is copied or hashed."""


def scratch_file(near: str | os.PathLike | None = None) -> h5py.File:
    """A new scratch HDF5 file in the folder of *near* (else the temp folder), already
    unlinked where the system allows, so it disappears when closed or on a crash."""
    folder = Path(near).resolve().parent if near is not None else None
    if folder is not None and not os.access(folder, os.W_OK):
        folder = None
    fd, name = tempfile.mkstemp(prefix=".hydrosync-import-", suffix=".h5", dir=folder)
    os.close(fd)
    handle = h5py.File(name, "w")
    # Windows cannot remove an open file: there it goes when the process ends.
    with contextlib.suppress(OSError):
        os.unlink(name)
    return handle


def memory_file() -> h5py.File:
    """An in-memory HDF5 file (small imports returned as arrays)."""
    return h5py.File(f"hydrosync-mem-{id(object())}.h5", "w", driver="core",
                     backing_store=False)


class TableSink:
    """Append-only table in group *group* of an HDF5 file: one float64 column per name.

    Parameters
    ----------
    group : h5py.Group
        Where the column datasets are created (must be empty of these names).
    names : sequence of str
        Column names; the first is the time (s) by which rows are ordered.
    compress : bool
        Compress (the table kept); False for an intermediate one copied on (one of
        several files, merged into the table kept): written ~9x faster (24 h attitude
        table: 3.8 s against 36 s).
    """

    def __init__(self, group: h5py.Group, names, compress: bool = True) -> None:
        self.group = group
        self.names = list(names)
        self.rows = 0
        self.sorted = True
        self.duplicates = 0
        self._last = -np.inf
        self._ds = {
            name: group.create_dataset(name, shape=(0,), maxshape=(None,), dtype="f8",
                                       chunks=(CHUNK_ROWS,), **(COMPRESSION if compress else {}))
            for name in self.names
        }

    def append(self, columns: dict[str, np.ndarray]) -> None:
        """Append rows (equal-length arrays for every column); drop repeated times."""
        time = np.asarray(columns[self.names[0]], dtype=np.float64)
        if time.size == 0:
            return
        previous = np.concatenate([[self._last], time[:-1]])
        repeat = time == previous
        if repeat.any():
            self.duplicates += int(np.count_nonzero(repeat))
            keep = ~repeat
            time = time[keep]
            columns = {k: np.asarray(v)[keep] for k, v in columns.items()}
        if time.size == 0:
            return
        if time[0] < self._last or np.any(np.diff(time) < 0):
            self.sorted = False
        self._last = float(time[-1])
        n = time.size
        for name in self.names:
            ds = self._ds[name]
            ds.resize((self.rows + n,))
            ds[self.rows:] = np.asarray(columns[name], dtype=np.float64)
        self.rows += n

    def close(self) -> None:
        """Close the column datasets (HDF5 keeps a chunk cache per open dataset) until
        :meth:`reopen`: a sink waiting for later use holds no memory."""
        for ds in self._ds.values():
            ds.flush()
        self._ds = {}

    def reopen(self) -> None:
        self._ds = {name: self.group[name] for name in self.names}

    def column(self, name: str) -> h5py.Dataset:
        return self._ds[name]

    def finish(self) -> dict[str, h5py.Dataset]:
        """The columns sorted by time with repeated times dropped (counted in
        :attr:`duplicates`); sorted in place when the rows came unsorted."""
        if self.sorted or self.rows == 0:
            return dict(self._ds)
        time = self._ds[self.names[0]][()]
        order = np.argsort(time, kind="stable")
        dup = np.concatenate([[False], np.diff(time[order]) == 0.0])
        self.duplicates += int(np.count_nonzero(dup))
        order = order[~dup]
        del time
        for name in self.names:
            values = self._ds[name][()][order]
            ds = self._ds[name]
            ds.resize((values.size,))
            ds[...] = values
            del values
        self.rows = int(order.size)
        self.sorted = True
        return dict(self._ds)

    def drop(self) -> None:
        """Delete the columns (a candidate source that was not chosen)."""
        for name in self.names:
            del self.group[name]
        self._ds = {}


def content_sha256(ds: h5py.Dataset) -> str:
    """SHA-256 of a dataset's values, read in blocks; equal to
    :func:`hydrosync_core.project.model.content_sha256` of the same array in memory."""
    digest = hashlib.sha256(f"{ds.dtype.kind}{ds.shape}".encode())
    for a in range(0, ds.shape[0], READ_ROWS):
        digest.update(np.ascontiguousarray(ds[a:a + READ_ROWS]).tobytes())
    return digest.hexdigest()


def read_columns(datasets: dict[str, h5py.Dataset]) -> dict[str, np.ndarray]:
    """All values of *datasets* in memory (small imports, tests)."""
    return {name: ds[()] for name, ds in datasets.items()}
