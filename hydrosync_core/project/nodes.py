"""In-memory tree of a project: groups, and datasets that are either loaded or lazy.

A lazy dataset keeps only its shape, dtype and the path in the source HDF5 file; its
values are read when asked for, so opening a large project reads metadata only.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import h5py
import numpy as np


@dataclass
class DatasetNode:
    """A dataset: *data* when loaded or newly written, else read from *source*."""

    attrs: dict
    shape: tuple[int, ...]
    dtype: np.dtype
    data: np.ndarray | None = None
    source: h5py.Dataset | None = None

    @property
    def nbytes(self) -> int:
        count = int(np.prod(self.shape, dtype=np.int64)) if self.shape else 1
        return count * (self.dtype.itemsize if self.dtype.kind != "O" else 8)

    def read(self) -> np.ndarray:
        """Return the values (a fresh read of the file for lazy nodes; not cached)."""
        if self.data is not None:
            return self.data
        assert self.source is not None
        if h5py.check_string_dtype(self.source.dtype) is not None:
            values = self.source.asstr()[()]
            return np.asarray(values, dtype=str)
        return self.source[()]


@dataclass
class GroupNode:
    """A group: attributes and named children."""

    attrs: dict = field(default_factory=dict)
    children: dict[str, GroupNode | DatasetNode] = field(default_factory=dict)


def clean_attr(value):
    """Convert an h5py attribute value to plain Python (str instead of bytes)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.dtype.kind in "OS":
        return [v.decode() if isinstance(v, bytes) else v for v in value.tolist()]
    if isinstance(value, np.generic):
        return value.item()
    return value


def load_tree(group: h5py.Group) -> GroupNode:
    """Build the node tree of *group*, reading attributes but no dataset values."""
    node = GroupNode(attrs={k: clean_attr(v) for k, v in group.attrs.items()})
    for name, item in group.items():
        if isinstance(item, h5py.Group):
            node.children[name] = load_tree(item)
        elif isinstance(item, h5py.Dataset):
            dtype = item.dtype
            if h5py.check_string_dtype(dtype) is not None:
                dtype = np.dtype(object)
            node.children[name] = DatasetNode(
                attrs={k: clean_attr(v) for k, v in item.attrs.items()},
                shape=tuple(item.shape),
                dtype=dtype,
                source=item,
            )
    return node
