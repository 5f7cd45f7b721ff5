"""The project: an HDF5-backed tree of vessel configuration, raw data and results.

Paths are slash-separated group/dataset names relative to the file root
(``"raw/gnss/time"``). Reading is lazy; every change stays in memory until
:meth:`Project.save`, which writes the whole tree atomically.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import h5py
import numpy as np

from hydrosync_core import __version__
from hydrosync_core.errors import InputError, ProjectFormatError
from hydrosync_core.project import migrations, schema
from hydrosync_core.project.nodes import DatasetNode, GroupNode, load_tree
from hydrosync_core.project.store import atomic_write


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def _split(path: str) -> list[str]:
    parts = [p for p in path.strip("/").split("/") if p]
    if not parts:
        raise ValueError("empty project path")
    return parts


@dataclass(frozen=True)
class NodeInfo:
    """What the project browser shows for one node."""

    path: str
    kind: str  # "group" or "dataset"
    shape: tuple[int, ...] | None
    dtype: str | None
    nbytes: int
    attrs: dict


class Project:
    """A HydroSync project (see ``docs/project-format.md``)."""

    def __init__(self, root: GroupNode, path: Path | None, source: h5py.File | None) -> None:
        self._root = root
        self.path: Path | None = path
        self._source = source
        self.dirty = False

    # ---------------------------------------------------------------- life cycle
    @classmethod
    def new(cls, name: str = "Untitled", vessel: Mapping | None = None) -> Project:
        """Create an empty project with the fixed top-level groups."""
        now = _now()
        root = GroupNode(
            attrs={
                "format": schema.FORMAT_NAME,
                "schema_version": schema.SCHEMA_VERSION,
                "created": now,
                "modified": now,
                "software_version": __version__,
                "name": name,
            }
        )
        project = cls(root, None, None)
        for group in (schema.VESSEL, schema.RAW, schema.RESULTS):
            project.ensure_group(group)
        project.put_json(schema.VESSEL, dict(vessel or default_vessel()))
        project.dirty = True
        return project

    @classmethod
    def open(cls, path: str | os.PathLike) -> Project:
        """Open *path* lazily; upgrade an older schema in memory; refuse a newer one."""
        path = Path(path)
        if not path.exists():
            raise InputError(str(path), "no such project file")
        try:
            source = h5py.File(path, "r")
        except OSError as exc:
            raise ProjectFormatError(str(path), f"not a readable HDF5 file ({exc})") from None
        try:
            root = load_tree(source)
        except Exception as exc:
            source.close()
            raise ProjectFormatError(str(path), f"corrupted project ({exc})") from None
        if root.attrs.get("format") != schema.FORMAT_NAME:
            source.close()
            raise ProjectFormatError(str(path), "not a HydroSync project (no 'format' attribute)")
        project = cls(root, path, source)
        version = root.attrs.get("schema_version")
        if not isinstance(version, int):
            source.close()
            raise ProjectFormatError(str(path), "missing or invalid 'schema_version' attribute")
        try:
            if migrations.migrate(project, version):
                root.attrs["schema_version"] = schema.SCHEMA_VERSION
                project.dirty = True
        except ProjectFormatError:
            source.close()
            raise
        return project

    def close(self) -> None:
        """Release the source file handle (lazy datasets become unreadable)."""
        if self._source is not None:
            self._source.close()
            self._source = None

    def __enter__(self) -> Project:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def save(self, path: str | os.PathLike | None = None) -> Path:
        """Write the project atomically to *path* (default: where it was opened)."""
        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("project has no file name yet: give a path")
        self._root.attrs["modified"] = _now()
        self._root.attrs["software_version"] = __version__
        atomic_write(target, self._root)
        # Re-bind lazy datasets to the file just written: the old one may be gone.
        self.close()
        self._source = h5py.File(target, "r")
        self._root = load_tree(self._source)
        self.path = target
        self.dirty = False
        return target

    # ------------------------------------------------------------------ queries
    @property
    def name(self) -> str:
        return str(self._root.attrs.get("name", ""))

    @property
    def attrs_root(self) -> dict:
        return dict(self._root.attrs)

    def _find(self, path: str) -> GroupNode | DatasetNode | None:
        node: GroupNode | DatasetNode = self._root
        for part in _split(path):
            if not isinstance(node, GroupNode) or part not in node.children:
                return None
            node = node.children[part]
        return node

    def _require(self, path: str) -> GroupNode | DatasetNode:
        node = self._find(path)
        if node is None:
            raise InputError(str(self.path or "<project>"), f"no '{path}' in the project")
        return node

    def exists(self, path: str) -> bool:
        return self._find(path) is not None

    def children(self, path: str = "") -> list[str]:
        node = self._root if not path.strip("/") else self._require(path)
        return list(node.children) if isinstance(node, GroupNode) else []

    def get(self, path: str) -> np.ndarray:
        """Read the dataset at *path* (from memory or, lazily, from the file)."""
        node = self._require(path)
        if not isinstance(node, DatasetNode):
            raise InputError(str(self.path or "<project>"), f"'{path}' is a group, not a dataset")
        return node.read()

    def attrs(self, path: str = "") -> dict:
        node = self._root if not path.strip("/") else self._require(path)
        return dict(node.attrs)

    def get_json(self, path: str, default=None):
        """Return the JSON document stored on *path*, or *default*."""
        node = self._find(path)
        if node is None or schema.JSON_ATTR not in node.attrs:
            return default
        return json.loads(node.attrs[schema.JSON_ATTR])

    def get_table(self, path: str) -> dict[str, np.ndarray]:
        """Return a table group as ``{column: 1-D array}`` in stored column order."""
        node = self._require(path)
        if not isinstance(node, GroupNode):
            raise InputError(str(self.path or "<project>"), f"'{path}' is not a table")
        order = node.attrs.get("columns") or list(node.children)
        return {name: node.children[name].read() for name in order}

    def walk(self, path: str = "") -> Iterator[NodeInfo]:
        """Yield :class:`NodeInfo` for every node below *path*, depth first."""
        start = self._root if not path.strip("/") else self._require(path)
        prefix = path.strip("/")

        def visit(node, here: str) -> Iterator[NodeInfo]:
            for name, child in node.children.items():
                sub = f"{here}/{name}" if here else name
                if isinstance(child, GroupNode):
                    size = sum(i.nbytes for i in visit(child, sub) if i.kind == "dataset")
                    yield NodeInfo(sub, "group", None, None, size, dict(child.attrs))
                    yield from visit(child, sub)
                else:
                    yield NodeInfo(
                        sub, "dataset", child.shape, str(child.dtype), child.nbytes,
                        dict(child.attrs),
                    )

        yield from visit(start, prefix)

    # ------------------------------------------------------------------ changes
    def ensure_group(self, path: str) -> GroupNode:
        node = self._root
        for part in _split(path):
            child = node.children.get(part)
            if child is None:
                child = node.children[part] = GroupNode()
                self.dirty = True
            if not isinstance(child, GroupNode):
                raise ValueError(f"'{path}': '{part}' is a dataset")
            node = child
        return node

    def _parent_and_name(self, path: str) -> tuple[GroupNode, str]:
        parts = _split(path)
        parent = self.ensure_group("/".join(parts[:-1])) if len(parts) > 1 else self._root
        return parent, parts[-1]

    def put(self, path: str, data, attrs: Mapping | None = None) -> None:
        """Store *data* (array-like) at *path*, replacing what was there.

        The dataset's content hash is kept as its ``sha256`` attribute, so results can
        record what they were computed from without re-reading large inputs.
        """
        array = np.asarray(data)
        parent, name = self._parent_and_name(path)
        parent.children[name] = DatasetNode(
            attrs={**dict(attrs or {}), "sha256": content_sha256(array)}, shape=array.shape,
            dtype=array.dtype, data=array,
        )
        self.dirty = True

    def set_attrs(self, path: str, **values) -> None:
        node = self._root if not path.strip("/") else self._require(path)
        node.attrs.update(values)
        self.dirty = True

    def put_json(self, path: str, document) -> None:
        """Store a JSON-serialisable *document* as the ``json`` attribute of group *path*."""
        self.ensure_group(path).attrs[schema.JSON_ATTR] = json.dumps(document)
        self.dirty = True

    def put_table(self, path: str, columns: Mapping[str, np.ndarray], **attrs) -> None:
        """Store a table as a group of equal-length 1-D datasets (replacing *path*)."""
        lengths = {len(np.asarray(v)) for v in columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"table '{path}': columns of different lengths {sorted(lengths)}")
        self.delete(path)
        group = self.ensure_group(path)
        group.attrs.update(attrs)
        group.attrs["kind"] = schema.TABLE_KIND
        group.attrs["columns"] = list(columns)
        for name, values in columns.items():
            self.put(f"{path}/{name}", values)

    def delete(self, path: str) -> None:
        """Remove *path* (group or dataset) if present."""
        parts = _split(path)
        parent = self._find("/".join(parts[:-1])) if len(parts) > 1 else self._root
        if isinstance(parent, GroupNode) and parent.children.pop(parts[-1], None) is not None:
            self.dirty = True

    def move(self, old: str, new: str) -> None:
        node = self._require(old)
        self.delete(old)
        parent, name = self._parent_and_name(new)
        parent.children[name] = node
        self.dirty = True


def content_sha256(array: np.ndarray) -> str:
    """SHA-256 of an array's values, shape and kind (strings hashed as UTF-8 text)."""
    digest = hashlib.sha256(f"{array.dtype.kind}{array.shape}".encode())
    if array.dtype.kind in "USO":
        digest.update("\x1f".join(str(v) for v in array.ravel()).encode("utf-8"))
    else:
        digest.update(np.ascontiguousarray(array).tobytes())
    return digest.hexdigest()


def default_vessel() -> dict:
    """An empty vessel offset sheet (body frame FRD, metres, degrees)."""
    return {
        "name": "",
        "frame": "body FRD: x forward, y starboard, z down; metres; degrees",
        "reference_point": "motion sensor",
        "sensors": {},
    }
