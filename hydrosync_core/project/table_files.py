"""Tables whose columns live in HDF5 files rather than memory: bind and read by window.

A streamed import (:mod:`hydrosync_core.importers.log_import`) leaves its columns as
chunked datasets of a scratch file. :func:`put_file_table` makes them a project table
without loading them: the nodes point at the datasets, :meth:`Project.save` copies them
chunk by chunk. :func:`table_length` and :func:`read_window` read a table's size and the
rows of a time window without reading the whole of it, so an analysis of one survey line
need not hold the day. :func:`adopt_table` moves such a table between projects (the
GUI reads into a scratch project first) without reading it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import h5py
import numpy as np

from hydrosync_core.project import schema
from hydrosync_core.project.nodes import DatasetNode, GroupNode


def put_file_table(project, path: str, columns: Mapping[str, h5py.Dataset], *,
                   hashes: Mapping[str, str], **attrs) -> None:
    """Make the 1-D datasets *columns* the table *path* of *project* (replacing it).

    *hashes* are the columns' content SHA-256 (as ``Project.put`` computes them), kept as
    their ``sha256`` attribute. The datasets' file stays open with the project.
    """
    lengths = {ds.shape[0] for ds in columns.values()}
    if len(lengths) > 1:
        raise ValueError(f"table '{path}': columns of different lengths {sorted(lengths)}")
    project.delete(path)
    group = project.ensure_group(path)
    group.attrs.update(attrs)
    group.attrs["kind"] = schema.TABLE_KIND
    group.attrs["columns"] = list(columns)
    for name, ds in columns.items():
        node = DatasetNode(attrs={"sha256": hashes[name]}, shape=ds.shape, dtype=ds.dtype,
                           source=ds)
        # The node keeps its file open (a scratch file is gone once closed).
        node.keep_open = ds.file
        group.children[name] = node
    project.dirty = True


def is_file_table(project, path: str) -> bool:
    """True when table *path* has a column read from a file rather than held in memory."""
    node = project._find(path)
    return isinstance(node, GroupNode) and any(
        isinstance(c, DatasetNode) and c.data is None for c in node.children.values())


def adopt_table(src, dst, path: str) -> None:
    """Move table *path* of project *src* into *dst* as it is (file-backed columns stay in
    their file: nothing is read), replacing what *dst* had there."""
    node = src._require(path)
    dst.delete(path)
    parent, name = dst._parent_and_name(path)
    parent.children[name] = node
    dst.dirty = True


def _columns(project, path: str) -> dict[str, DatasetNode]:
    node = project._require(path)
    if not isinstance(node, GroupNode):
        raise ValueError(f"'{path}' is not a table")
    names = node.attrs.get("columns") or list(node.children)
    return {n: node.children[n] for n in names if isinstance(node.children.get(n), DatasetNode)}


def table_length(project, path: str) -> int:
    """Rows of table *path* (from the metadata; nothing is read)."""
    cols = _columns(project, path)
    return int(next(iter(cols.values())).shape[0]) if cols else 0


def _values(node: DatasetNode, a: int, b: int) -> np.ndarray:
    if node.data is not None:
        return node.data[a:b]
    assert node.source is not None
    return node.source[a:b]


def _search(node: DatasetNode, value: float, side: str) -> int:
    """``searchsorted`` on a sorted column without reading it whole (a sample first)."""
    n = node.shape[0]
    if node.data is not None or n <= 1 << 16:
        return int(np.searchsorted(_values(node, 0, n), value, side))
    step = max(1, n // 4096)
    sample = node.source[::step]
    k = int(np.searchsorted(sample, value, side))
    a = max(0, (k - 1) * step)
    b = min(n, k * step + 1)
    return a + int(np.searchsorted(node.source[a:b], value, side))


def read_window(project, path: str, t0: float, t1: float,
                columns: Sequence[str] | None = None, time: str = "time") -> dict[str, np.ndarray]:
    """Rows of table *path* with ``t0 <= time <= t1`` (the time column sorted), for
    *columns* (default all), reading only those rows from the file."""
    cols = _columns(project, path)
    a = _search(cols[time], t0, "left")
    b = _search(cols[time], t1, "right")
    names = list(columns) if columns is not None else list(cols)
    return {n: _values(cols[n], a, b) for n in names}
