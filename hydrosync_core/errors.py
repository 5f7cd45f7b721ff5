"""One exception family for HydroSync.

`InputError` is what bad input raises: the CLI turns it into a one-line message on
stderr and exit code 2; the GUI shows the same line. Everything else is a bug (exit 1).

Messages quote input sparingly: :func:`quote` clips a piece of a file to
:data:`QUOTE_LIMIT` characters, and :meth:`InputError.one_line` never returns more than
:data:`LINE_LIMIT` characters after the file location, whatever a library put into the
message. The location itself is never clipped: a user needs the whole path, and a
message must read the same wherever the data lives (a longer folder name must not cut
the reason short).
"""

from __future__ import annotations

QUOTE_LIMIT = 60
"""Characters of input quoted in a message (beyond that: an ellipsis and the length)."""

LINE_LIMIT = 400
"""Longest one-line message, not counting the file location that starts it."""


def quote(text, limit: int = QUOTE_LIMIT) -> str:
    """``'text'`` with control characters escaped, clipped to *limit* characters."""
    text = text.decode("utf-8", "replace") if isinstance(text, bytes) else str(text)
    text = text.encode("unicode_escape").decode("ascii") if not text.isprintable() else text
    if len(text) > limit:
        return f"'{text[:limit]}…' ({len(text)} characters)"
    return f"'{text}'"


def clip(text, limit: int = 120) -> str:
    """*text* on one line, at most *limit* characters (library messages may quote input)."""
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[: limit - 1] + "…"


class HydroSyncError(Exception):
    """Base class of every error HydroSync raises on purpose."""


class InputError(HydroSyncError):
    """Bad input: a missing file, a wrong column, a non-finite value, too little data.

    Parameters
    ----------
    file : str or None
        The file (or project path) at fault.
    message : str
        What is wrong, in words a surveyor understands.
    line : int or None
        1-based line number in the file, when known.
    field : str or None
        Column or field name, when known.
    """

    def __init__(
        self,
        file: str | None,
        message: str,
        *,
        line: int | None = None,
        field: str | None = None,
    ) -> None:
        self.file = None if file is None else str(file)
        self.line = line
        self.field = field
        self.message = message
        super().__init__(self.one_line())

    def one_line(self) -> str:
        """Return ``file:line: field 'x': message`` with the parts that are known."""
        where = self.file or ""
        if self.line is not None:
            where += f":{self.line}"
        text = f"field '{self.field}': " if self.field else ""
        text = clip(text + self.message, LINE_LIMIT)
        return f"{where}: {text}" if where else text


class ProjectFormatError(InputError):
    """A project file that cannot be read: not HydroSync, corrupted, or too new."""


class ProjectDataError(ProjectFormatError):
    """A project whose content is damaged: names the project file and the HDF5 path."""

    def __init__(self, file, hdf5_path: str, message: str) -> None:
        self.hdf5_path = "/" + str(hdf5_path).strip("/")
        super().__init__(file, f"{self.hdf5_path}: {message}")


class ProjectAccessError(InputError):
    """A project that may not be written now (locked, read-only, changed on disk).

    The message is a whole sentence naming the file (``P.h5 is being written by another
    HydroSync process (pid 42)``), so :meth:`one_line` does not prefix the file again.
    """

    def one_line(self) -> str:
        return clip(self.message, LINE_LIMIT)


class ProjectLockedError(ProjectAccessError):
    """Another HydroSync process holds the project's write lock."""

    def __init__(self, file, pid: int | None) -> None:
        self.pid = pid
        who = f"pid {pid}" if pid else "pid unknown"
        super().__init__(file, f"{file} is being written by another HydroSync process ({who})")

    @classmethod
    def with_message(cls, file, pid: int | None, message: str) -> ProjectLockedError:
        """The same error with another sentence (a lock of another machine, a hard link)."""
        error = cls(file, pid)
        error.message = message
        error.args = (error.one_line(),)
        return error


class ProjectReadOnlyError(ProjectAccessError):
    """The project file or its folder may not be written (permissions, owner, read-only open)."""


class ProjectChangedError(ProjectAccessError):
    """The file changed on disk since the project was opened: not overwritten."""


class DiskFullError(InputError):
    """The disk (or the user's quota) is full: nothing was changed; free space and retry."""


class Cancelled(HydroSyncError):
    """Raised inside a long computation when the user asked to cancel it."""
