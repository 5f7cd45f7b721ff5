"""The output files of one command: checked before any work, published together at the end.

``formats.md``: a failed command leaves none of its outputs behind. A command therefore

1. names all its outputs first (:meth:`Outputs.plan`): a missing or unwritable folder, a
   read-only file or two options naming one file fail at once, in the first second,
   with exit 2 — not after the computation;
2. writes each output to a temporary file beside its target (:meth:`Outputs.temp`,
   :meth:`Outputs.write_json`, :meth:`Outputs.write_csv`);
3. publishes them all at the end (:meth:`Outputs.publish`): fsync, rename, with Ctrl-C
   held back so the interrupt message knows what was saved.

Leaving the ``with`` block by an exception (or without publishing) removes every
temporary: nothing of a failed command remains. Usage::

    with Outputs() as out:
        out.plan(args.json, "--json")
        out.plan(args.sync_csv, "--sync-csv")
        result = compute(...)
        out.write_json(args.json, result.to_dict())
        out.write_csv(args.sync_csv, columns)
        project.save()          # the project last but one: a refused save publishes nothing
        out.publish()
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import IO

from hydrosync_core import atomic
from hydrosync_core.errors import InputError


def _key(path: Path) -> str:
    return os.path.normcase(os.path.abspath(path))


class Outputs:
    """The planned and written outputs of one command (see the module doc)."""

    def __init__(self, inputs: Mapping[str, str | os.PathLike | None] | None = None) -> None:
        self._planned: dict[str, tuple[Path, str | None]] = {}
        self._temps: dict[str, tuple[Path, Path]] = {}
        self._inputs = {_key(Path(p)): (opt, Path(p)) for opt, p in (inputs or {}).items()
                        if p is not None}

    # ------------------------------------------------------------------- planning
    def plan(self, path: str | os.PathLike | None, option: str | None = None) -> Path | None:
        """Check now that *path* can be written (None: the option was not given)."""
        if path is None:
            return None
        path = atomic.real_target(path)
        key = _key(path)
        if key in self._planned:
            other = self._planned[key][1]
            raise InputError(str(path), f"{option or 'this output'} names the same file as "
                             f"{other or 'another output'}")
        if key in self._inputs:
            opt, _ = self._inputs[key]
            raise InputError(str(path), f"{option or 'an output'} would overwrite the input "
                             f"{opt}")
        atomic.check_writable(path, option)
        atomic.clean_stale_temporaries(path)  # a killed earlier run's (``.R.pdf.….tmp``)
        self._planned[key] = (path, option)
        return path

    @property
    def planned(self) -> list[Path]:
        return [p for p, _ in self._planned.values()]

    # -------------------------------------------------------------------- writing
    def temp(self, path: str | os.PathLike) -> Path:
        """A fresh temporary file beside *path* (planned first if it was not) to write to."""
        path = atomic.real_target(path)
        key = _key(path)
        if key not in self._planned:
            self.plan(path)
        old = self._temps.pop(key, None)
        if old is not None:
            old[0].unlink(missing_ok=True)
        tmp = atomic.make_temp(path)
        self._temps[key] = (tmp, path)
        return tmp

    def write_text(self, path: str | os.PathLike, writer: Callable[[IO[str]], None]) -> Path:
        tmp = self.temp(path)
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            writer(fh)
        return tmp

    def write_json(self, path: str | os.PathLike, document) -> Path:
        """*document* as indented JSON (no NaN: JSON has none) into *path*'s temporary."""
        return self.write_text(path, lambda fh: json.dump(document, fh, indent=2,
                                                          allow_nan=False))

    def write_csv(self, path: str | os.PathLike, columns, precision: int = 6) -> int:
        """Numeric *columns* as CSV into *path*'s temporary; returns the number of rows."""
        from hydrosync_core.exporters import write_csv_table

        tmp = self.temp(path)
        return write_csv_table(tmp, columns, precision)

    # ----------------------------------------------------------------- publishing
    def publish(self) -> list[Path]:
        """Rename every written temporary over its target; return the targets."""
        pairs = list(self._temps.values())
        try:
            atomic.publish(pairs)
        except BaseException:
            self.discard()
            raise
        self._temps.clear()
        return [target for _, target in pairs]

    def discard(self) -> None:
        """Remove every temporary not yet published."""
        for tmp, _ in self._temps.values():
            tmp.unlink(missing_ok=True)
        self._temps.clear()

    def __enter__(self) -> Outputs:
        return self

    def __exit__(self, *exc) -> None:
        self.discard()
