"""The write lock of a project: an advisory lock on the side file ``P.h5.lock``.

Whoever opens a project to change it (``hydrosync import/vessel/latency/…``, the GUI)
holds the lock from the open until the project is closed; a second writer — another
command, another window — is refused at once with
``P.h5 is being written by another HydroSync process (pid N)`` and the GUI opens the file
read-only instead. Read-only opens (``info``, ``report``) take no lock.

POSIX: ``fcntl.flock`` on ``P.h5.lock`` (the kernel releases it when the holder dies,
SIGKILL included). The file holds a record of its holder: pid, host, the machine tag of
:func:`hydrosync_core.atomic.machine_tag` (host, boot and pid namespace) and the time.
It is opened with ``O_NOFOLLOW | O_NONBLOCK`` and must be a regular file: a symbolic
link, a folder or a FIFO named ``P.h5.lock`` is refused, never written through (the
classic symlink attack, CVE-2025-68146 of ``filelock``). Its mode follows the folder: a
group-writable folder gets a group-writable lock, so a colleague can take over after a
crash. A lock left by a dead process of this machine (the kernel lock is free and the
record's machine tag is ours) is taken over, whoever owned it; one left by another
machine or container cannot be proven dead from here and is only removed with
``hydrosync --break-lock`` (:data:`hydrosync_core.atomic.BREAK_LOCK`), and then only when older than
:data:`BREAK_LOCK_MIN_AGE_S`. Hard links of one project share one lock: a project with
several names also locks its (device, inode) in a folder of this machine.

Elsewhere: exclusive creation of the same file, a stale one (its pid gone) being taken
over. Within one process the lock is shared (reference counted): two
:class:`~hydrosync_core.project.model.Project` objects of one process on one file are
told apart by the changed-on-disk check instead.
"""

from __future__ import annotations

import contextlib
import errno
import os
import socket
import stat
import tempfile
import threading
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from hydrosync_core import atomic, interrupts
from hydrosync_core.atomic import boot_time, kernel_tag, machine_tag, notice_log, pid_alive
from hydrosync_core.errors import ProjectLockedError, ProjectReadOnlyError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

BREAK_LOCK_MIN_AGE_S = atomic.FOREIGN_MIN_AGE_S
"""A lock younger than this is never broken (``hydrosync --break-lock``, which sets
:data:`hydrosync_core.atomic.BREAK_LOCK`): its holder may be starting a save now."""

_registry: dict[str, ProjectLock] = {}
_registry_lock = threading.Lock()


def lock_path(path: str | os.PathLike) -> Path:
    path = Path(path)
    return path.with_name(path.name + ".lock")


def _key(path: Path) -> str:
    return os.path.normcase(os.path.realpath(path))


@dataclass(frozen=True)
class LockRecord:
    """What a lock file says about its holder (fields missing in old lock files: None)."""

    pid: int | None
    host: str | None = None
    tag: str | None = None
    kernel: str | None = None
    since: float | None = None

    @classmethod
    def parse(cls, text: str) -> LockRecord:
        lines = text.strip().splitlines()
        pid = int(lines[0]) if lines and lines[0].strip().isdigit() else None
        fields = dict(part.split("=", 1) for line in lines[1:] for part in line.split()
                      if "=" in part)
        try:
            since = float(fields["since"]) if "since" in fields else None
        except ValueError:
            since = None
        return cls(pid, fields.get("host"), fields.get("tag"), fields.get("kernel"), since)

    def ours(self) -> bool:
        """Written under the running kernel (whose ``flock`` then proves its holder dead),
        by a machine with our name before its last boot, or by an old HydroSync."""
        if self.kernel is None or self.kernel == kernel_tag():
            return True
        return (self.host == socket.gethostname() and self.since is not None
                and self.since < boot_time())

    def text(self) -> str:
        return (f"{self.pid}\nhost={socket.gethostname()} tag={machine_tag()} "
                f"kernel={kernel_tag()} since={time.time():.3f}\n")

    def who(self) -> str:
        where = f" on {self.host}" if self.host else ""
        when = ""
        if self.since is not None:
            age = max(0.0, time.time() - self.since)
            stamp = datetime.fromtimestamp(self.since, UTC).strftime("%Y-%m-%d %H:%M UTC")
            when = f", since {stamp}, {_age_text(age)} ago"
        return f"pid {self.pid or 'unknown'}{where}{when}"


def _age_text(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def _read_record(fd: int) -> LockRecord:
    for _ in range(5):
        try:
            text = os.pread(fd, 512, 0).decode("ascii", "replace")
        except OSError:
            return LockRecord(None)
        record = LockRecord.parse(text)
        if record.pid is not None:
            return record
        time.sleep(0.02)  # the holder may not have written its record yet
    return LockRecord(None)


class ProjectLock:
    """A held write lock on one project file (see the module doc)."""

    def __init__(self, path: Path, key: str, fd: int | None, inode_fd: int | None = None
                 ) -> None:
        self.path = path
        self.key = key
        self._fd = fd
        self._inode_fd = inode_fd
        self._count = 1

    # ------------------------------------------------------------------ acquiring
    @classmethod
    def acquire(cls, path: str | os.PathLike) -> ProjectLock:
        """Take (or share, within this process) the write lock of project *path*.

        Raises :class:`ProjectLockedError` when another process holds it (or may: a lock
        of another machine) and :class:`ProjectReadOnlyError` when the lock file cannot
        be created or is not a plain file.
        """
        path = Path(path)
        key = _key(path)
        with _registry_lock:
            held = _registry.get(key)
            if held is not None:
                held._count += 1
                return held
            if fcntl is None:  # pragma: no cover - non-POSIX
                lock = cls(path, key, _lock_exclusive(path))
            else:
                inode_fd = _lock_inode(path)
                try:
                    fd = _lock_posix(path)
                except BaseException:
                    if inode_fd is not None:
                        os.close(inode_fd)
                    raise
                lock = cls(path, key, fd, inode_fd)
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
                if fd is not None and os.stat(side, follow_symlinks=False).st_ino == \
                        os.fstat(fd).st_ino:
                    side.unlink()
                elif fd is None:
                    side.unlink(missing_ok=True)
            except OSError:
                pass
            if fd is not None:
                os.close(fd)
            inode_fd, self._inode_fd = self._inode_fd, None
            if inode_fd is not None:
                os.close(inode_fd)

    @property
    def held(self) -> bool:
        return self._count > 0


def holder_pid(path: str | os.PathLike) -> int | None:
    """The pid written in *path*'s lock file, if any (for messages and tests)."""
    return holder(path).pid


def holder(path: str | os.PathLike) -> LockRecord:
    """The record of *path*'s lock file (pid None when there is none)."""
    try:
        fd = os.open(lock_path(path), os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return LockRecord(None)
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return LockRecord(None)
        return LockRecord.parse(os.pread(fd, 512, 0).decode("ascii", "replace"))
    except OSError:
        return LockRecord(None)
    finally:
        os.close(fd)


def _refused(path: Path, problem: str) -> ProjectReadOnlyError:
    return ProjectReadOnlyError(str(path), f"{path} cannot be changed: {problem}")


def _cannot_create(path: Path, exc: OSError) -> ProjectReadOnlyError:
    side = lock_path(path).name
    if exc.errno == errno.ELOOP:
        return _refused(path, f"its lock file {side} is a symbolic link; HydroSync never "
                        "writes through one (remove it if you did not make it)")
    if exc.errno == errno.EISDIR:
        return _refused(path, f"{side} is a folder, not HydroSync's lock file (remove or "
                        "rename it)")
    if exc.errno in (errno.ENOSPC, errno.EDQUOT):
        return _refused(path, f"no space left on the disk for its lock file {side}")
    return _refused(path, f"its folder does not accept the lock file {side} "
                    f"({exc.strerror or exc})")


_OPEN_FLAGS = (getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
               | getattr(os, "O_CLOEXEC", 0))


def _lock_mode(path: Path) -> int:
    """0o664 in a group-writable folder (a shared project folder), else 0o644."""
    try:
        folder = os.stat(path.parent if str(path.parent) else ".")
    except OSError:
        return 0o644
    return 0o664 if folder.st_mode & stat.S_IWGRP else 0o644


def _open_side(path: Path) -> tuple[int, bool]:
    """Open (creating it if needed) the lock file; return (fd, writable).

    A lock file of another user that we may not write is opened read-only: ``flock``
    works on it, and a free one is then known to be stale (taken over by the caller).
    """
    side = lock_path(path)
    mode = _lock_mode(path)
    try:
        fd = os.open(side, os.O_RDWR | os.O_CREAT | _OPEN_FLAGS, mode)
        writable = True
    except PermissionError:
        try:
            fd = os.open(side, os.O_RDONLY | _OPEN_FLAGS)
        except OSError as exc:
            raise _cannot_create(path, exc) from None
        writable = False
    except OSError as exc:
        raise _cannot_create(path, exc) from None
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode):
        os.close(fd)
        raise _refused(path, f"{side.name} is not a plain file (a FIFO, device or socket "
                       "in its place); remove it")
    if writable and info.st_size == 0 and stat.S_IMODE(info.st_mode) != mode:
        # our new file: the umask must not keep the group out of a shared folder
        with contextlib.suppress(OSError):
            os.fchmod(fd, mode)
    return fd, writable


def _lock_posix(path: Path) -> int:
    side = lock_path(path)
    for _ in range(20):
        fd, writable = _open_side(path)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            record = _read_record(fd)
            os.close(fd)
            raise ProjectLockedError(str(path), record.pid) from None
        try:
            same = os.stat(side, follow_symlinks=False).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if not same:  # the previous holder removed the file meanwhile: lock the new one
            os.close(fd)
            continue
        record = _read_record(fd) if os.fstat(fd).st_size else LockRecord(None)
        if not record.ours():
            _foreign(path, fd, record)  # raises unless --break-lock allows it
            continue
        if not writable:  # a stale lock of another user, dead on this machine
            _take_over(path, fd, record, "ended without releasing it")
            continue
        try:
            os.ftruncate(fd, 0)
            os.pwrite(fd, LockRecord(os.getpid()).text().encode("ascii"), 0)
        except OSError as exc:
            _drop(side, fd)
            raise _cannot_create(path, exc) from None
        return fd
    raise ProjectLockedError(str(path), None)


def _drop(side: Path, fd: int) -> None:
    """Remove the lock file *fd* (still ours: same inode) and close it."""
    try:
        if os.stat(side, follow_symlinks=False).st_ino == os.fstat(fd).st_ino:
            side.unlink()
    except OSError:
        pass
    os.close(fd)


def _take_over(path: Path, fd: int, record: LockRecord, why: str) -> None:
    """Remove a stale lock file (we hold its flock) so the next round creates ours."""
    side = lock_path(path)
    try:
        if os.stat(side, follow_symlinks=False).st_ino == os.fstat(fd).st_ino:
            side.unlink()
    except FileNotFoundError:
        pass
    except OSError as exc:
        os.close(fd)
        raise _cannot_create(path, exc) from None
    os.close(fd)
    notice_log.warning("%s", f"removed the stale lock {side.name} of HydroSync "
                       f"{record.who()}, which {why}")


def _foreign(path: Path, fd: int, record: LockRecord) -> None:
    """A lock written on another machine or container: its holder cannot be proven dead."""
    side = lock_path(path)
    age = None if record.since is None else time.time() - record.since
    if atomic.BREAK_LOCK and age is not None and age >= BREAK_LOCK_MIN_AGE_S:
        _take_over(path, fd, record, "--break-lock declared finished")
        return
    os.close(fd)
    if atomic.BREAK_LOCK:
        raise ProjectLockedError.with_message(
            str(path), record.pid, f"{path} is locked by HydroSync {record.who()}: a lock "
            f"younger than {BREAK_LOCK_MIN_AGE_S:.0f} s (or of unknown age) is not broken")
    raise ProjectLockedError.with_message(
        str(path), record.pid, f"{path} is locked by HydroSync {record.who()} (another "
        f"machine or container: it cannot be checked from here); if nothing runs there "
        f"on this project, run again with 'hydrosync --break-lock …' or remove {side.name}")


def _inode_lock_folder() -> Path:
    return Path(tempfile.gettempdir()) / "hydrosync-inode-locks"


def _lock_inode(path: Path) -> int | None:
    """Lock a project with several hard links by (device, inode) on this machine.

    One name's lock file does not see the other names, so a second flock, on a file
    named after the device and inode in a shared folder of this machine, does. Never
    removed (removing would race with a taker); a few bytes each.
    """
    try:
        info = os.stat(path)
    except OSError:
        return None
    if info.st_nlink < 2 or not stat.S_ISREG(info.st_mode):
        return None
    folder = _inode_lock_folder()
    try:
        folder.mkdir(mode=0o777, exist_ok=True)
        if stat.S_IMODE(os.stat(folder).st_mode) != 0o1777:
            os.chmod(folder, 0o1777)
    except OSError:
        pass
    name = folder / f"{info.st_dev}-{info.st_ino}.lock"
    try:
        fd = os.open(name, os.O_RDWR | os.O_CREAT | _OPEN_FLAGS, 0o666)
    except OSError:
        return None  # the machine refuses: the name lock alone still holds
    with contextlib.suppress(OSError):
        os.fchmod(fd, 0o666)
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        raise ProjectLockedError.with_message(
            str(path), None, f"{path} is being written by another HydroSync process under "
            f"another name (a hard link of the same file)") from None
    return fd


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
        os.write(fd, LockRecord(os.getpid()).text().encode("ascii"))
        os.close(fd)
        return None
    raise ProjectLockedError(str(path), holder_pid(path))
