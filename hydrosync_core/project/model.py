"""The project: an HDF5-backed tree of vessel configuration, raw data and results.

Paths are slash-separated group/dataset names relative to the file root
(``"raw/gnss/time"``). Reading is lazy; every change stays in memory until
:meth:`Project.save`, which writes the whole tree atomically.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import threading
import weakref
from collections import OrderedDict
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import h5py
import numpy as np

from hydrosync_core import __version__
from hydrosync_core.atomic import clean_stale_temporaries, real_target, write_problem
from hydrosync_core.errors import (
    InputError,
    ProjectChangedError,
    ProjectDataError,
    ProjectFormatError,
    ProjectReadOnlyError,
    quote,
)
from hydrosync_core.project import migrations, schema, validate
from hydrosync_core.project.lock import ProjectLock
from hydrosync_core.project.nodes import DatasetNode, GroupNode, load_tree
from hydrosync_core.project.store import atomic_write

TABLE_CACHE_BYTES = 1 << 30
"""Decoded tables a project keeps for :meth:`Project.get_table` ``(cached=True)``."""


def _signature(path: Path) -> tuple | None:
    """What identifies the file's state on disk (device, inode, size, mtime), or None."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        return None
    return (info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns)


def _same_file(a: Path, b: Path) -> bool:
    return os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b))


def _release(lock: ProjectLock | None) -> None:
    if lock is not None:
        lock.release()


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
        self.readonly = False
        """Opened without the write lock: :meth:`save` to this path is refused."""
        self.readonly_reason = ""
        self.notices: list[str] = []
        """Things done on the user's behalf (stale temporary files removed)."""
        self._lock: ProjectLock | None = None
        self._signature: tuple | None = None
        self._finalizer = None
        self._table_cache: OrderedDict[tuple, tuple[dict, int]] = OrderedDict()
        self._cache_bytes = 0
        self._cache_lock = threading.Lock()

    def _hold(self, lock: ProjectLock | None) -> None:
        """Keep *lock* (releasing the one held before) until :meth:`close`."""
        if self._finalizer is not None:
            self._finalizer.detach()
            self._finalizer = None
        old, self._lock = self._lock, lock
        if lock is not None:
            self._finalizer = weakref.finalize(self, _release, lock)
        if old is not None and old is not lock:
            old.release()

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
    def open(cls, path: str | os.PathLike, *, readonly: bool = False) -> Project:
        """Open *path* lazily; upgrade an older schema in memory; refuse a newer one.

        By default the project is opened to be changed: the file and its folder must be
        writable (else :class:`ProjectReadOnlyError`) and the project's write lock is
        taken and held until :meth:`close` (another process holding it:
        :class:`ProjectLockedError`). ``readonly=True`` takes no lock and checks nothing
        of the kind; :meth:`save` to the same path is then refused (save elsewhere).
        Stale temporary files of killed saves are removed either way (:attr:`notices`).
        """
        path = Path(path)
        if not path.exists():
            raise InputError(str(path), "is a symbolic link that leads nowhere (a loop or a "
                             "missing target)" if path.is_symlink() else "no such project file")
        if path.is_dir():
            raise InputError(str(path), "is a folder, not a project file")
        lock = None
        if not readonly:
            problem = write_problem(real_target(path))
            if problem is not None:
                raise ProjectReadOnlyError(str(path), f"{path} cannot be changed: {problem}")
            lock = ProjectLock.acquire(real_target(path))
        try:
            notices = clean_stale_temporaries(real_target(path), legacy=lock is not None)
            project = cls._load(path)
        except BaseException:
            _release(lock)
            raise
        project.notices = notices
        project.readonly = readonly
        project.readonly_reason = "opened read-only" if readonly else ""
        project._hold(lock)
        return project

    @classmethod
    def _load(cls, path: Path) -> Project:
        signature = _signature(path)
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
        project._signature = signature
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

    @classmethod
    def create(cls, path: str | os.PathLike, name: str | None = None,
               vessel: Mapping | None = None) -> Project:
        """A new, unsaved project that will be saved as *path* (which must not exist yet).

        The folder is checked and the write lock taken now, before any work, so a
        command that builds a project fails at once when it could not save it.
        """
        path = Path(path)
        problem = write_problem(path)
        if problem is not None:
            raise ProjectReadOnlyError(str(path), f"{path} cannot be written: {problem}")
        lock = ProjectLock.acquire(path)
        project = cls.new(name=name or path.stem, vessel=vessel)
        project.path = path
        project._signature = _signature(path)
        project._hold(lock)
        return project

    def close(self) -> None:
        """Release the source file handle (lazy datasets become unreadable) and the lock."""
        if self._source is not None:
            self._source.close()
            self._source = None
        self._hold(None)

    def __enter__(self) -> Project:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def save(self, path: str | os.PathLike | None = None) -> Path:
        """Write the project atomically to *path* (default: where it was opened).

        Refused (:class:`~hydrosync_core.errors.ProjectAccessError`, nothing written)
        when the project was opened read-only, when another process holds the target's
        write lock, when the target or its folder may not be written, or when the file
        changed on disk since it was opened (another program wrote it). The replaced
        file's mode and owner are kept.
        """
        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("project has no file name yet: give a path")
        same = self.path is not None and _same_file(target, self.path)
        if same and self.readonly:
            raise ProjectReadOnlyError(
                str(target), f"{target} was {self.readonly_reason or 'opened read-only'}: "
                "save it under another name")
        problem = write_problem(real_target(target))
        if problem is not None:
            raise ProjectReadOnlyError(str(target), f"{target} cannot be saved: {problem}")
        lock = self._lock if same and self._lock is not None else ProjectLock.acquire(
            real_target(target))
        try:
            if same:
                self._check_unchanged(target)
            self.notices += clean_stale_temporaries(real_target(target), legacy=True)
            self._root.attrs["modified"] = _now()
            self._root.attrs["software_version"] = __version__
            atomic_write(target, self._root)
        except BaseException:
            if lock is not self._lock:
                lock.release()
            raise
        # Re-bind lazy datasets to the file just written: the old one may be gone.
        if self._source is not None:
            self._source.close()
            self._source = None
        self._hold(lock)
        self._source = h5py.File(target, "r")
        self._signature = _signature(target)
        self._root = load_tree(self._source)
        self.path = target
        self.dirty = False
        self.readonly = False
        self.readonly_reason = ""
        return target

    def _check_unchanged(self, target: Path) -> None:
        now = _signature(target)
        if now == self._signature:
            return
        if self._signature is None:
            what = "was created by another program since this project was started"
        elif now is None:
            what = "was moved or deleted since it was opened"
        else:
            what = "changed on disk since it was opened (another program wrote it)"
        raise ProjectChangedError(
            str(target), f"{target} {what}: not overwritten; save under another name or "
            "open it again")

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

    def _where(self) -> str:
        return str(self.path or "<project>")

    def _read(self, path: str, node: DatasetNode) -> np.ndarray:
        """Values of *node*, with a damaged file (broken chunk, bad dtype) as InputError."""
        try:
            return node.read()
        except (OSError, RuntimeError, ValueError, TypeError, KeyError) as exc:
            raise ProjectDataError(self._where(), path,
                                   f"cannot be read, the file is damaged ({exc})") from None

    def get(self, path: str) -> np.ndarray:
        """Read the dataset at *path* (from memory or, lazily, from the file).

        Known inputs (``raw/pool/lidar``, …) are checked (shape, numbers, finite) by
        :mod:`hydrosync_core.project.validate`.
        """
        node = self._require(path)
        if not isinstance(node, DatasetNode):
            raise InputError(self._where(), f"'{path}' is a group, not a dataset")
        return validate.check_dataset(self._where(), path, self._read(path, node))

    def attrs(self, path: str = "") -> dict:
        node = self._root if not path.strip("/") else self._require(path)
        return dict(node.attrs)

    def get_json(self, path: str, default=None):
        """Return the JSON document stored on *path*, or *default*.

        A document that does not parse, or (for the known ones: vessel sheet, pool setup
        and target) has the wrong shape, raises :class:`ProjectDataError`.
        """
        node = self._find(path)
        if node is None or schema.JSON_ATTR not in node.attrs:
            return default
        text = node.attrs[schema.JSON_ATTR]
        try:
            document = json.loads(text)
        except (TypeError, ValueError, RecursionError) as exc:
            raise ProjectDataError(self._where(), f"{path}@{schema.JSON_ATTR}",
                                   f"is not valid JSON ({exc})") from None
        return validate.check_json(self._where(), path, document)

    def get_table(self, path: str, cached: bool = False) -> dict[str, np.ndarray]:
        """Return a table group as ``{column: 1-D array}`` in stored column order.

        *cached*: read-only arrays, kept decoded and checked for the next ``cached`` call
        while the table's content is unchanged (also across :meth:`save`), within
        TABLE_CACHE_BYTES per project. Reading a survey day's attitude (8 million rows)
        from the file and checking it takes ~2.5 s; callers that only read the values (the
        latency run, the panel's per-line plot) take it from memory after the first time.

        Every table is checked: the ``columns`` attribute names datasets that exist,
        columns are 1-D and of one length; known input tables (``raw/gnss``, …) also have
        their required columns, numbers, finite and plausible values
        (:mod:`hydrosync_core.project.validate`).
        """
        node = self._require(path)
        if not isinstance(node, GroupNode):
            raise InputError(self._where(), f"'{path}' is not a table")
        key = self._table_key(path, node) if cached else None
        if key is not None:
            with self._cache_lock:
                hit = self._table_cache.get(key)
                if hit is not None:
                    self._table_cache.move_to_end(key)
                    return dict(hit[0])
        table = self._read_table(path, node)
        if key is not None:
            self._keep(key, table)
        return table

    def _read_table(self, path: str, node: GroupNode) -> dict[str, np.ndarray]:
        order = _column_names(node)
        if order is None:
            raise ProjectDataError(self._where(), f"{path}@columns",
                                   "is not a list of column names")
        table = {}
        for name in order:
            child = node.children.get(name)
            if not isinstance(child, DatasetNode):
                raise ProjectDataError(
                    self._where(), f"{path}/{name}",
                    "is listed in the table's 'columns' attribute but "
                    + ("is a group" if child is not None else "does not exist"))
            table[name] = self._read(f"{path}/{name}", child)
        return validate.check_table(self._where(), path, table)

    def has_cached_table(self, path: str) -> bool:
        """True when ``get_table(path, cached=True)`` would not read the file: the table
        is in the cache, or held in memory."""
        node = self._find(path)
        if not isinstance(node, GroupNode):
            return False
        if all(isinstance(c, DatasetNode) and c.data is not None
               for c in node.children.values()):
            return True
        key = self._table_key(path, node)
        with self._cache_lock:
            return key is not None and key in self._table_cache

    def _table_key(self, path: str, node: GroupNode) -> tuple | None:
        """Cache key of a table read from the file: its path, columns and their content
        hashes (the ``sha256`` attribute :meth:`put` writes), or None when a column is
        in memory (cheap to read again) or has no hash."""
        names = _column_names(node)
        if names is None:
            return None
        hashes = []
        for name in names:
            child = node.children.get(name)
            if not isinstance(child, DatasetNode) or child.data is not None:
                return None
            digest = child.attrs.get("sha256")
            if not isinstance(digest, str):
                return None
            hashes.append(digest)
        return (path, tuple(names), tuple(hashes))

    def _keep(self, key: tuple, table: dict) -> None:
        """Freeze *table*'s arrays and keep them under *key*, least recently used first out."""
        size = sum(np.asarray(v).nbytes for v in table.values())
        if size > TABLE_CACHE_BYTES:
            return
        for values in table.values():
            if isinstance(values, np.ndarray):
                values.flags.writeable = False
        with self._cache_lock:
            if key in self._table_cache:
                return
            self._table_cache[key] = (dict(table), size)
            self._cache_bytes += size
            while self._cache_bytes > TABLE_CACHE_BYTES:
                _, (_, dropped) = self._table_cache.popitem(last=False)
                self._cache_bytes -= dropped

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
        for name, values in columns.items():
            _check_text_column(values, attrs.get("source"), path, name)
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


_CONTROL = re.compile(r"[\x00-\x1f\x7f]")


def _check_text_column(values, source, table: str, name: str) -> None:
    """Names (line names, antennas) with control characters are refused with the row:
    a NUL cannot even be stored (HDF5 strings end at it), the others garble listings."""
    array = np.asarray(values)
    if array.dtype.kind not in "UO":
        return
    for row, value in enumerate(array.tolist()):
        if isinstance(value, str) and _CONTROL.search(value):
            char = _CONTROL.search(value).group()
            raise InputError(source or f"/{table}", f"row {row + 1}: the name {quote(value)} "
                             f"holds the control character {char!r}", field=name)


def _column_names(node: GroupNode) -> list[str] | None:
    """A table group's columns in stored order (its ``columns`` attribute, else its
    children), or None when that attribute is not a list of names."""
    order = node.attrs.get("columns")
    if order is None:
        return list(node.children)
    if isinstance(order, str) or not all(isinstance(n, str) for n in order):
        return None
    return list(order)


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
