"""Atomic writing of files: a unique temporary beside the target, fsync, rename.

Every save (project, JSON, CSV, PDF) writes a temporary file in the target's folder,
named ``.NAME.XXXXXXXX.PID.tmp`` (unique per save, so two processes never share one),
fsyncs it, gives it the mode and owner of the file it replaces, renames it over the
target and fsyncs the folder. A failure or an exception leaves the target as it was and
removes the temporary; a process killed mid-save leaves its temporary behind, and
:func:`clean_stale_temporaries` removes those of processes that no longer run.

:func:`write_problem` says, before any work, why a target cannot be written.
"""

from __future__ import annotations

import contextlib
import errno
import functools
import hashlib
import json
import logging
import os
import re
import shutil
import socket
import stat
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO

from hydrosync_core import interrupts
from hydrosync_core.errors import DiskFullError, InputError

notice_log = logging.getLogger("hydrosync.notice")
"""Things the user should hear about that are not errors (stale temporaries removed)."""

LEGACY_TMP_AGE_S = 120.0
"""A pre-lock ``NAME.tmp`` untouched for this long is stale (its writer is gone)."""


def _read_first_line(path: str) -> str:
    try:
        with open(path, encoding="ascii", errors="replace") as fh:
            return fh.readline().strip()
    except OSError:
        return ""


def _short_hash(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8", "replace")).hexdigest()[:8]


@functools.cache
def kernel_tag() -> str:
    """8 hex digits naming the running kernel: its boot id (Linux), else the host name.

    Processes under one kernel (containers included) see one ``flock`` table.
    """
    boot = _read_first_line("/proc/sys/kernel/random/boot_id")
    return _short_hash(boot or f"host:{socket.gethostname()}")


@functools.cache
def machine_tag() -> str:
    """8 hex digits naming where our pids mean something: kernel and pid namespace.

    Two processes with the same tag see each other's pids, so ``pid_alive`` is an answer
    between them; a pid from another tag (another machine sharing the folder, another
    container, a Dask worker on another node) says nothing here.
    """
    try:
        namespace = str(os.stat("/proc/self/ns/pid").st_ino)
    except OSError:
        namespace = ""
    return _short_hash(f"{kernel_tag()}:{namespace}")


@functools.cache
def boot_time() -> float:
    """When the running kernel booted (UNIX s; 0 when unknown)."""
    try:
        with open("/proc/stat", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("btime "):
                    return float(line.split()[1])
    except (OSError, ValueError):
        pass
    return 0.0


def temp_prefix(target: Path) -> str:
    return f".{target.name}."


def temp_suffix(pid: int | None = None) -> str:
    return f".{machine_tag()}-{os.getpid() if pid is None else pid}.tmp"


def make_temp(target: Path) -> Path:
    """Create an empty, unique temporary file in *target*'s folder and return its path."""
    fd, name = tempfile.mkstemp(dir=target.parent, prefix=temp_prefix(target),
                                suffix=temp_suffix())
    os.close(fd)
    return Path(name)


def pid_alive(pid: int) -> bool:
    """True if process *pid* exists (or may: it belongs to another user)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    except OSError:
        return True
    return True


def _human(nbytes: int) -> str:
    size = float(nbytes)
    for unit in ("bytes", "KB", "MB", "GB"):
        if size < 1000 or unit == "GB":
            return f"{size:.0f} {unit}" if unit == "bytes" else f"{size:.1f} {unit}"
        size /= 1000
    return f"{size:.1f} GB"


BREAK_LOCK = False
"""``hydrosync --break-lock``: locks and temporaries of another machine or container,
older than :data:`FOREIGN_MIN_AGE_S`, are removed (with a note) instead of reported."""

FOREIGN_MIN_AGE_S = 60.0
"""A lock or temporary of another machine younger than this is a save in progress: it is
neither reported nor broken."""

_TEMP_NAME = r"[A-Za-z0-9_]+\.(?:(?P<tag>[0-9a-f]{8})-)?(?P<pid>\d+)\.tmp$"


def clean_stale_temporaries(target: str | os.PathLike, *, legacy: bool = False) -> list[str]:
    """Remove temporaries of *target* whose writer is proven gone; report the others.

    ``.NAME.XXXXXXXX.TAG-PID.tmp`` files written under our :func:`machine_tag` are
    removed when process PID is gone. Those of another machine or container (another
    tag, or no tag: an older HydroSync) cannot be judged from here: older than
    :data:`FOREIGN_MIN_AGE_S` they are reported, and removed only with
    :data:`BREAK_LOCK`. With *legacy* (the caller holds the project's write lock) an
    old-style ``NAME.tmp`` not modified for :data:`LEGACY_TMP_AGE_S` seconds is removed
    too. Returns (and logs on ``hydrosync.notice``) one message per file removed or
    reported; never raises.
    """
    target = Path(target)
    folder = target.parent if str(target.parent) else Path(".")
    pattern = re.compile(r"^" + re.escape(temp_prefix(target)) + _TEMP_NAME)
    messages: list[str] = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return messages
    for entry in entries:
        match = pattern.match(entry.name)
        if not match and not (legacy and entry.name == f"{target.name}.tmp"):
            continue
        try:
            info = entry.stat(follow_symlinks=False)
        except OSError:
            continue
        if not stat.S_ISREG(info.st_mode):
            continue
        message = _judge_temporary(entry, info, match, target)
        if message:
            notice_log.warning("%s", message)
            messages.append(message)
    return messages


def _judge_temporary(entry: os.DirEntry, info: os.stat_result, match: re.Match | None,
                     target: Path) -> str | None:
    """Remove one temporary if its writer is proven gone; the message, or None."""
    age = time.time() - info.st_mtime
    if match is None:  # NAME.tmp of an older HydroSync, the project lock held
        if age < LEGACY_TMP_AGE_S:
            return None
        who = "by an interrupted save of an older HydroSync"
    else:
        pid, tag = int(match.group("pid")), match.group("tag")
        if tag == machine_tag():
            if pid == os.getpid() or pid_alive(pid):
                return None
            who = f"by HydroSync process {pid}, which ended before finishing its save"
        else:
            if age < FOREIGN_MIN_AGE_S:
                return None
            where = ("another machine or container" if tag else
                     "an older HydroSync, which did not say on which machine")
            if not BREAK_LOCK:
                return (f"left alone the temporary file {entry.name} "
                        f"({_human(info.st_size)}, {age / 60:.0f} min old) beside "
                        f"{target.name}: written by pid {pid} of {where}, which cannot be "
                        "checked from here (hydrosync --break-lock removes it)")
            who = f"by pid {pid} of {where} (--break-lock)"
    try:
        os.unlink(entry.path)
    except OSError:
        return None
    return (f"removed the stale temporary file {entry.name} ({_human(info.st_size)}) "
            f"left beside {target.name} {who}")


def _umask() -> int:
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _access(path: Path, mode: int) -> bool:
    """``os.access`` for the effective user (the one that will write), where supported."""
    if os.access in os.supports_effective_ids:
        return os.access(path, mode, effective_ids=True)
    return os.access(path, mode)


def _may_write(info: os.stat_result, path: Path) -> bool:
    if os.name == "posix" and os.geteuid() == 0:
        return bool(info.st_mode & 0o222)  # root too respects a file marked read-only
    return _access(path, os.W_OK)


def _owner_name(uid: int) -> str:
    try:
        import pwd

        return pwd.getpwuid(uid).pw_name
    except (ImportError, KeyError):
        return f"uid {uid}"


KERNEL_FOLDERS = ("/proc", "/sys", "/dev")
"""Folders of the kernel's own files (a file written there is not data: ``/dev/full``)."""

_KINDS = {stat.S_ISCHR: "a character device", stat.S_ISBLK: "a block device",
          stat.S_ISFIFO: "a named pipe (FIFO)", stat.S_ISSOCK: "a socket"}


def special_file_problem(path: str | os.PathLike) -> str | None:
    """Why *path* is no place for an output (a device, FIFO, socket, /proc …), or None.

    Symbolic links are followed: a link to ``/dev/full`` is ``/dev/full``.
    """
    try:
        real = os.path.realpath(path)
    except (OSError, ValueError) as exc:
        return f"its path cannot be resolved ({exc})"
    for folder in KERNEL_FOLDERS:
        if real == folder or real.startswith(folder + os.sep):
            return f"it is in {folder}, the kernel's own files, not a place for data"
    try:
        info = os.stat(real)
    except FileNotFoundError:
        return None
    except OSError as exc:
        return f"it cannot be examined ({exc.strerror or exc})"
    for test, kind in _KINDS.items():
        if test(info.st_mode):
            return f"it is {kind}, not a regular file; HydroSync writes only plain files"
    return None


def write_problem(path: str | os.PathLike) -> str | None:
    """Why *path* cannot be (re)written atomically by this process now, or None.

    Checks that the folder exists and can be written, that *path* is not a folder, and,
    when it exists, that its permissions allow writing and its owner can be kept. The
    answer reads after the file name: ``"P.h5 cannot be changed: " + problem``.
    """
    path = Path(path)
    special = special_file_problem(path)
    if special is not None:
        return special
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.exists():
        return f"its folder {folder} does not exist"
    if not folder.is_dir():
        return f"{folder} is not a folder"
    if path.is_dir():
        return "it is a folder, not a file"
    if not _access(folder, os.W_OK | os.X_OK):
        return f"its folder {folder} cannot be written (permissions or read-only disk)"
    if path.exists():
        info = path.stat()
        if not _may_write(info, path):
            return (f"it is read-only (mode {stat.S_IMODE(info.st_mode):o}, owner "
                    f"{_owner_name(info.st_uid)})")
        if os.name == "posix" and os.geteuid() not in (0, info.st_uid):
            return (f"it belongs to {_owner_name(info.st_uid)}, and HydroSync cannot replace "
                    "it keeping its owner")
    return None


FREE_SPACE_MARGIN = 1.05
"""Free space asked beyond the expected size of a file about to be written."""

_DISK_FULL_TEXT = ("no space left on device", "disk quota exceeded", "errno = 28",
                   "errno = 122")


def is_disk_full(exc: BaseException) -> bool:
    """True for ``ENOSPC``/``EDQUOT``, also as HDF5 words it (``errno = 28``)."""
    if isinstance(exc, OSError) and exc.errno in (errno.ENOSPC, errno.EDQUOT):
        return True
    text = str(exc).lower()
    return isinstance(exc, OSError) and any(t in text for t in _DISK_FULL_TEXT)


def disk_full(path: str | os.PathLike, exc: BaseException | None = None,
              needed: int | None = None, free: int | None = None) -> DiskFullError:
    """The one-line error of a full disk while writing *path*."""
    amount = (f" (needs about {_human(needed)}, {_human(free)} free)"
              if needed is not None and free is not None else "")
    return DiskFullError(str(path), f"no space left on the disk{amount}: nothing was "
                         "written, the previous file is kept; free some space and run again")


def check_free_space(path: str | os.PathLike, needed: int) -> None:
    """Raise :class:`DiskFullError` if *path*'s folder has not *needed* bytes free."""
    folder = Path(path).parent if str(Path(path).parent) else Path(".")
    try:
        free = shutil.disk_usage(folder).free
    except OSError:
        return  # cannot tell: the write itself will say
    if free < needed * FREE_SPACE_MARGIN:
        raise disk_full(path, needed=needed, free=free)


def check_special(path: str | os.PathLike) -> None:
    """Raise :class:`InputError` if *path* is a device, FIFO, socket or kernel file."""
    problem = special_file_problem(path)
    if problem is not None:
        raise InputError(str(path), f"cannot be written: {problem}")


def check_writable(path: str | os.PathLike, what: str | None = None) -> None:
    """Raise :class:`InputError` naming *path* (or option *what*) if it cannot be written."""
    problem = write_problem(path)
    if problem is not None:
        raise InputError(str(path), ("cannot be written: " if what is None
                                     else f"{what} cannot be written: ") + problem)


def _keep_metadata(tmp: Path, old: os.stat_result | None, target: Path) -> None:
    """Give *tmp* the mode (and owner, where possible) of the file it will replace."""
    if old is None:
        os.chmod(tmp, 0o666 & ~_umask())
        return
    if os.name == "posix":
        mine = os.stat(tmp)
        if (mine.st_uid, mine.st_gid) != (old.st_uid, old.st_gid):
            try:
                os.chown(tmp, old.st_uid, old.st_gid)
            except PermissionError:
                with contextlib.suppress(PermissionError):
                    os.chown(tmp, -1, old.st_gid)
                if os.stat(tmp).st_uid != old.st_uid:
                    raise InputError(str(target), f"cannot be written: it belongs to "
                                     f"{_owner_name(old.st_uid)}, and HydroSync cannot "
                                     "replace it keeping its owner") from None
    os.chmod(tmp, stat.S_IMODE(old.st_mode))


def fsync_file(path: Path) -> None:
    with open(path, "rb+") as fh:
        os.fsync(fh.fileno())


def publish(pairs: list[tuple[Path, Path]]) -> None:
    """Rename each temporary over its target (mode/owner kept), then fsync the folders.

    The renames run with Ctrl-C held back, and each target is recorded in
    :data:`hydrosync_core.interrupts.completed` as it lands.
    """
    olds = []
    for _, target in pairs:
        check_special(target)  # may have appeared since planned
    for tmp, target in pairs:
        fsync_file(tmp)
        try:
            old = os.stat(target)
        except FileNotFoundError:
            old = None
        _keep_metadata(tmp, old, target)
        olds.append(old)
    with interrupts.critical():
        for tmp, target in pairs:
            os.replace(tmp, target)
            interrupts.note_completed(target)
        for folder in {target.parent for _, target in pairs}:
            _fsync_folder(folder)


def real_target(path: str | os.PathLike) -> Path:
    """*path* with symbolic links resolved: a save replaces the file, not the link."""
    path = Path(path)
    return Path(os.path.realpath(path)) if path.is_symlink() else path


@contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a unique temporary path beside *path*; on success publish it as *path*.

    On any exception (Ctrl-C included) the temporary file is removed and *path* is left
    as it was.
    """
    path = real_target(path)
    check_special(path)
    clean_stale_temporaries(path)
    try:
        tmp = make_temp(path)
    except OSError as exc:
        if is_disk_full(exc):
            raise disk_full(path, exc) from None
        raise
    try:
        yield tmp
        publish([(tmp, path)])
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        if is_disk_full(exc):
            raise disk_full(path, exc) from None
        raise
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def _fsync_folder(folder: Path) -> None:
    """Make the rename itself durable (POSIX); silently skipped where unsupported."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_text_atomic(path: str | os.PathLike, writer: Callable[[IO[str]], None]) -> None:
    """Call ``writer(file)`` on a temporary text file, then rename it to *path*."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="") as fh:
        writer(fh)


def write_json_atomic(path: str | os.PathLike, document) -> None:
    """Write *document* as indented JSON to *path* atomically."""
    write_text_atomic(path, lambda fh: json.dump(document, fh, indent=2, allow_nan=False))
