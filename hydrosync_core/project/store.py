"""Writing a node tree to HDF5 atomically: temporary file, fsync, rename.

A crash or exception at any point before the rename leaves the previous file untouched;
the temporary file is removed on failure.
"""

from __future__ import annotations

import json
import os

import h5py
import numpy as np

from hydrosync_core.atomic import atomic_path, check_free_space, disk_full, is_disk_full
from hydrosync_core.project.nodes import DatasetNode, GroupNode
from hydrosync_core.project.schema import dataset_options


def _write_attrs(target: h5py.HLObject, attrs: dict) -> None:
    for key, value in attrs.items():
        if isinstance(value, dict):
            value = json.dumps(value)
        elif isinstance(value, list | tuple) and value and isinstance(value[0], str):
            value = np.array(value, dtype=h5py.string_dtype())
        target.attrs[key] = value


COPY_BLOCK_BYTES = 16 << 20
"""Largest slice of an unchunked dataset copied at once (bounded memory)."""


def copy_dataset(source: h5py.Dataset, group: h5py.Group, name: str) -> h5py.Dataset:
    """Copy *source* into *group* as *name*: same type, shape, chunks and filters.

    Chunks are copied as stored (``read_direct_chunk``/``write_direct_chunk``: no
    decompression), unchunked data in bounded slices; the attributes are not copied.
    Not ``Group.copy`` (``H5Ocopy``): on a full disk it aborted the process ("double
    free or corruption", issue #28) where this raises ``OSError``.
    """
    dcpl = source.id.get_create_plist()
    dsid = h5py.h5d.create(group.id, name.encode(), source.id.get_type(),
                           source.id.get_space(), dcpl=dcpl)
    target = h5py.Dataset(dsid)
    if dcpl.get_layout() == h5py.h5d.CHUNKED and h5py.check_vlen_dtype(source.dtype) is None \
            and h5py.check_string_dtype(source.dtype) is None:
        offsets: list[tuple[int, ...]] = []
        if hasattr(source.id, "chunk_iter"):  # one pass over the chunk index
            source.id.chunk_iter(lambda info: offsets.append(info.chunk_offset))
        else:  # pragma: no cover - HDF5 < 1.12.3
            offsets = [source.id.get_chunk_info(i).chunk_offset
                       for i in range(source.id.get_num_chunks())]
        for offset in offsets:
            mask, data = source.id.read_direct_chunk(offset)
            dsid.write_direct_chunk(offset, data, mask)
        return target
    if source.shape == () or source.size == 0:
        if source.shape == ():
            target[()] = source[()]
        return target
    row_bytes = max(1, source.dtype.itemsize * (source.size // max(source.shape[0], 1)))
    step = max(1, COPY_BLOCK_BYTES // row_bytes)
    for start in range(0, source.shape[0], step):
        target[start:start + step] = source[start:start + step]
    return target


def _write_dataset(group: h5py.Group, name: str, node: DatasetNode) -> None:
    if node.data is None and node.source is not None:
        ds = copy_dataset(node.source, group, name)
    else:
        data = node.read()
        if data.dtype.kind in "UO":
            data = np.asarray(data, dtype=object)
            ds = group.create_dataset(
                name, data=data.astype(str).tolist() if data.ndim else str(data),
                dtype=h5py.string_dtype(), **dataset_options(data.shape),
            )
        else:
            ds = group.create_dataset(name, data=data, **dataset_options(data.shape))
    _write_attrs(ds, node.attrs)


def write_tree(group: h5py.Group, node: GroupNode) -> None:
    """Write *node* (attributes and children, recursively) into *group*."""
    _write_attrs(group, node.attrs)
    for name, child in node.children.items():
        if isinstance(child, GroupNode):
            write_tree(group.create_group(name), child)
        else:
            _write_dataset(group, name, child)


def expected_bytes(node: GroupNode) -> int:
    """About how many bytes writing *node* takes: stored sizes of the datasets copied
    from the source file, array sizes of the others, plus HDF5's bookkeeping."""
    total = 4096
    stack = [node]
    while stack:
        group = stack.pop()
        total += 1024 + sum(len(str(v)) for v in group.attrs.values())
        for child in group.children.values():
            if isinstance(child, GroupNode):
                stack.append(child)
            elif child.data is None and child.source is not None:
                total += 1024 + child.source.id.get_storage_size()
            else:
                data = np.asarray(child.data)
                total += 1024 + (sum(len(str(v)) for v in data.flat) if data.dtype.kind in "UOS"
                                 else data.nbytes)
    return total


def atomic_write(path: str | os.PathLike, root: GroupNode) -> None:
    """Write *root* to *path* through a temporary + fsync + ``os.replace``.

    The free space is checked first, and a full disk meanwhile (``ENOSPC``, quota) is a
    :class:`~hydrosync_core.errors.DiskFullError`: the old file and the lock stay as
    they were, the temporary is removed.
    """
    check_free_space(path, expected_bytes(root))
    try:
        with atomic_path(path) as tmp, \
                h5py.File(tmp, "w", libver=("earliest", "latest")) as f:
            write_tree(f, root)
            f.flush()
    except OSError as exc:
        if is_disk_full(exc):
            raise disk_full(path, exc) from None
        raise
