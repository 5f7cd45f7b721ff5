"""Writing a node tree to HDF5 atomically: temporary file, fsync, rename.

A crash or exception at any point before the rename leaves the previous file untouched;
the temporary file is removed on failure.
"""

from __future__ import annotations

import json
import os

import h5py
import numpy as np

from hydrosync_core.atomic import atomic_path
from hydrosync_core.project.nodes import DatasetNode, GroupNode
from hydrosync_core.project.schema import dataset_options


def _write_attrs(target: h5py.HLObject, attrs: dict) -> None:
    for key, value in attrs.items():
        if isinstance(value, dict):
            value = json.dumps(value)
        elif isinstance(value, list | tuple) and value and isinstance(value[0], str):
            value = np.array(value, dtype=h5py.string_dtype())
        target.attrs[key] = value


def _write_dataset(group: h5py.Group, name: str, node: DatasetNode) -> None:
    if node.data is None and node.source is not None:
        # Copy inside HDF5: chunk by chunk, keeps filters, never loads the whole array.
        node.source.file.copy(node.source, group, name=name)
        ds = group[name]
        for key in list(ds.attrs):
            del ds.attrs[key]
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


def atomic_write(path: str | os.PathLike, root: GroupNode) -> None:
    """Write *root* to *path* through ``path.tmp`` + fsync + ``os.replace``."""
    with atomic_path(path) as tmp, h5py.File(tmp, "w", libver=("earliest", "latest")) as f:
        write_tree(f, root)
        f.flush()
