"""The report of one device-log import: what was read, used, set aside and why.

Frozen and JSON-serialisable (:meth:`ImportReport.to_dict`); :meth:`ImportReport.attrs`
gives the flat form stored as attributes on the imported table group in the project.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field


@dataclass(frozen=True)
class ImportReport:
    """What one log import read, used and skipped.

    ``skipped`` counts lines and records set aside by reason (bad checksum, no fix,
    empty altitude, binary, unknown sentence, …); ``sentence_counts`` counts the usable
    sentences by kind; ``logger_minus_sentence_s`` is the median of logger tag minus
    sentence time (s) when both exist — the logging delay of the device.
    """

    file: str
    kind: str
    source: str
    time_source: str
    date_source: str
    lines: int
    sentences: int
    used: int
    skipped: dict[str, int] = field(default_factory=dict)
    sentence_counts: dict[str, int] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    logger_minus_sentence_s: float | None = None
    heave_positive: str | None = None

    def to_dict(self) -> dict:
        """JSON-serialisable dictionary of the report."""
        out = asdict(self)
        out["warnings"] = list(self.warnings)
        return out

    def attrs(self) -> dict:
        """HDF5-attribute form: scalars plus the whole report as a JSON string."""
        out: dict = {
            "import_report": json.dumps(self.to_dict()),
            "lines_read": self.lines,
            "sentences_read": self.sentences,
            "records_used": self.used,
            "record_source": self.source,
            "time_source": self.time_source,
        }
        for reason, n in self.skipped.items():
            out[f"skipped: {reason}"] = int(n)
        return out

    def summary(self) -> str:
        """One line for the CLI/GUI."""
        skipped = ", ".join(f"{k} {v}" for k, v in sorted(self.skipped.items()))
        return (
            f"{self.used} {self.source} records ({self.time_source} time) from "
            f"{self.lines} lines" + (f"; set aside: {skipped}" if skipped else "")
            + (f"; warnings: {' / '.join(self.warnings)}" if self.warnings else "")
        )


def stored_warnings(project, path: str) -> list[str]:
    """The warnings of the import that wrote *path* (empty if none or not an import)."""
    if not project.exists(path):
        return []
    try:
        report = json.loads(project.attrs(path).get("import_report") or "{}")
    except (TypeError, ValueError):
        return []
    return [str(w) for w in report.get("warnings") or ()]
