"""One exception family for HydroSync.

`InputError` is what bad input raises: the CLI turns it into a one-line message on
stderr and exit code 2; the GUI shows the same line. Everything else is a bug (exit 1).
"""

from __future__ import annotations


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
        text = f"{where}: " if where else ""
        if self.field:
            text += f"field '{self.field}': "
        return (text + self.message).replace("\n", " ")


class ProjectFormatError(InputError):
    """A project file that cannot be read: not HydroSync, corrupted, or too new."""


class Cancelled(HydroSyncError):
    """Raised inside a long computation when the user asked to cancel it."""
