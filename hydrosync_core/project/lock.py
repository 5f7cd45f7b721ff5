"""The write lock of a project: an advisory lock on the side file ``P.h5.lock``.

Whoever opens a project to change it (``hydrosync import/vessel/latency/…``, the GUI)
holds the lock from the open until the project is closed; a second writer — another
command, another window — is refused at once with
``P.h5 is being written by another HydroSync process (pid N)`` and the GUI opens the file
read-only instead. Read-only opens (``info``, ``report``) take no lock.

POSIX: ``fcntl.flock`` on ``P.h5.lock`` (the kernel releases it when the holder dies,
SIGKILL included), which holds the holder's pid for the message; the file is removed
when the lock is released. Elsewhere: exclusive creation of the same file, a stale one
(its pid gone) being taken over. Within one process the lock is shared (reference
counted): two :class:`~hydrosync_core.project.model.Project` objects of one process on
one file are told apart by the changed-on-disk check instead.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

from hydrosync_core import interrupts
from hydrosync_core.atomic import pid_alive
from hydrosync_core.errors import ProjectLockedError, ProjectReadOnlyError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

_registry: dict[str, ProjectLock] = {}
_registry_lock = threading.Lock()


def lock_path(path: str | os.PathLike) -> Path:
    path = Path(path)
    return path.with_name(path.name + ".lock")


def _key(path: Path) -> str:
    return os.path.normcase(os.path.realpath(path))


def _read_pid(fd: int) -> int | None:
    for _ in range(5):
        try:
            text = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
        except OSError:
            return None
        if text.isdigit():
            return int(text)
        time.sleep(0.02)  # the holder may not have written its pid yet
    return None


class ProjectLock:
    """A held write lock on one project file (see the module doc)."""

    def __init__(self, path: Path, key: str, fd: int | None) -> None:
        self.path = path
        self.key = key
        self._fd = fd
        self._count = 1

    # ------------------------------------------------------------------ acquiring
    @classmethod
    def acquire(cls, path: str | os.PathLike) -> ProjectLock:
        """Take (or share, within this process) the write lock of project *path*.

        Raises :class:`ProjectLockedError` when another process holds it and
        :class:`ProjectReadOnlyError` when the lock file cannot be created.
        """
        path = Path(path)
        key = _key(path)
        with _registry_lock:
            held = _registry.get(key)
            if held is not None:
                held._count += 1
                return held
            fd = _lock_posix(path) if fcntl is not None else _lock_exclusive(path)
            lock = cls(path, key, fd)
            _registry[key] = lock
            return lock

    def release(self) -> None:
        """Drop one reference; the last one removes the lock file and unlocks.

        Never raises, and a Ctrl-C arriving meanwhile is held back (it may run in a
        finalizer), so the lock file and the lock always go together.
        """
        with interrupts.deferred(), _registry_lock:
            if self._count <= 0:
                return
            self._count -= 1
            if self._count:
                return
            _registry.pop(self.key, None)
            side = lock_path(self.path)
            fd, self._fd = self._fd, None
            try:
                if fd is not None and os.stat(side).st_ino == os.fstat(fd).st_ino:
                    side.unlink()
                elif fd is None:
                    side.unlink(missing_ok=True)
            except OSError:
                pass
            if fd is not None:
                os.close(fd)

    @property
    def held(self) -> bool:
        return self._count > 0


def holder_pid(path: str | os.PathLike) -> int | None:
    """The pid written in *path*'s lock file, if any (for messages and tests)."""
    try:
        text = lock_path(path).read_text(encoding="ascii", errors="replace").strip()
    except OSError:
        return None
    return int(text) if text.isdigit() else None


def _cannot_create(path: Path, exc: OSError) -> ProjectReadOnlyError:
    return ProjectReadOnlyError(
        str(path), f"{path} cannot be changed: its folder does not accept the lock file "
        f"{lock_path(path).name} ({exc.strerror or exc})")


def _lock_posix(path: Path) -> int:
    side = lock_path(path)
    for _ in range(20):
        try:
            fd = os.open(side, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise _cannot_create(path, exc) from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            pid = _read_pid(fd)
            os.close(fd)
            raise ProjectLockedError(str(path), pid) from None
        try:
            same = os.stat(side).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if not same:  # the previous holder removed the file meanwhile: lock the new one
            os.close(fd)
            continue
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
        return fd
    raise ProjectLockedError(str(path), None)


def _lock_exclusive(path: Path) -> None:  # pragma: no cover - non-POSIX fallback
    side = lock_path(path)
    for _ in range(3):
        try:
            fd = os.open(side, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        except FileExistsError:
            pid = holder_pid(path)
            if pid is not None and not pid_alive(pid):
                side.unlink(missing_ok=True)
                continue
            raise ProjectLockedError(str(path), pid) from None
        except OSError as exc:
            raise _cannot_create(path, exc) from None
        os.write(fd, f"{os.getpid()}\n".encode("ascii"))
        os.close(fd)
        return None
    raise ProjectLockedError(str(path), holder_pid(path))
