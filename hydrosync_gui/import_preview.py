"""The Import dialog's preview: what each chosen file holds, read off the GUI thread.

One row per file: the import kinds its content fits, the sentences found with their
counts, the time span and the size (:func:`hydrosync_core.importers.log_preview.preview_file`,
which reads at most a few MiB from each end of a large file). A new list of files
cancels the survey of the old one; a file whose content does not fit the chosen kind is
marked so the user sees it before OK.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import (
    QHeaderView,
    QLabel,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.importers.log_preview import FilePreview, preview_file
from hydrosync_gui.workers import Worker, start

COLUMNS = ("File", "Looks like", "Time span", "Size")
"""Each file's row; under it, across the columns, the sentences found."""
MISMATCH = QColor(200, 110, 0)
DEBOUNCE_MS = 250
"""Typing a path starts no survey until the user pauses."""


def size_text(size: int) -> str:
    """``812 B``, ``301 KiB``, ``2.4 GiB``."""
    for unit, shift in (("GiB", 30), ("MiB", 20), ("KiB", 10)):
        if size >= 1 << shift:
            value = size / (1 << shift)
            return f"{value:.1f} {unit}" if value < 10 else f"{value:.0f} {unit}"
    return f"{size} B"


def _content_text(p: FilePreview) -> str:
    if p.error:
        return p.error
    if p.sentences:
        head = "in the first and last 4 MiB: " if p.partial else ""
        return head + p.sentences_text()
    return p.first_line or "(empty)"


class ImportPreview(QWidget):
    """A table of :class:`FilePreview` rows, filled by a worker; ``sig_ready`` once done."""

    sig_ready = Signal()

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.status = QLabel("Choose files to see what they hold.")
        self.status.setObjectName("preview_status")
        self.status.setWordWrap(True)
        self.tree = QTreeWidget()
        self.tree.setObjectName("import_preview")
        self.tree.setHeaderLabels(list(COLUMNS))
        self.tree.setRootIsDecorated(False)
        self.tree.setIndentation(12)
        self.tree.setItemsExpandable(False)
        header = self.tree.header()
        header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)
        header.setStretchLastSection(True)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.status)
        layout.addWidget(self.tree, 1)
        self.previews: list[FilePreview] = []
        self._paths: list[str] = []
        self._kind = ""
        self._worker: Worker | None = None
        self._timer = QTimer(self, singleShot=True, interval=DEBOUNCE_MS)
        self._timer.timeout.connect(self._start)

    # ---------------------------------------------------------------- public
    def show_files(self, paths: list[str], kind: str) -> None:
        """Survey *paths* (after a short pause) and mark rows that do not fit *kind*."""
        if paths == self._paths:
            self._kind = kind
            if self.previews and not self.busy():
                self._fill()
            return
        self._paths, self._kind = list(paths), kind
        self.stop()
        self.previews = []
        self.tree.clear()
        if not paths:
            self.status.setText("Choose files to see what they hold.")
            self.sig_ready.emit()
            return
        self.status.setText(f"Reading {len(paths)} file(s)…")
        self._timer.start()

    def busy(self) -> bool:
        """A survey is pending or running."""
        return self._timer.isActive() or self._worker is not None

    def stop(self) -> None:
        """Cancel a pending or running survey (its late results are dropped)."""
        self._timer.stop()
        if self._worker is not None:
            self._worker.cancel()
            self._worker.signals.sig_finished.disconnect()
            self._worker.signals.sig_progress.disconnect()
            self._worker.signals.sig_done.disconnect()
            self._worker = None

    # --------------------------------------------------------------- private
    def _start(self) -> None:
        paths = list(self._paths)

        def work(progress, cancel):
            out = []
            for i, path in enumerate(paths):
                if cancel.is_set():
                    return out
                progress(i / len(paths), f"Reading {i + 1} of {len(paths)}…")
                out.append(preview_file(path, cancel))
            return out

        worker = Worker(work)
        # Each slot names its worker: a late signal of a replaced survey is dropped.
        worker.signals.sig_progress.connect(
            lambda _f, text, w=worker: w is self._worker and self.status.setText(text))
        worker.signals.sig_finished.connect(lambda out, w=worker: self._on_result(w, out))
        worker.signals.sig_done.connect(lambda w=worker: self._on_done(w))
        self._worker = worker
        start(worker)

    def _on_result(self, worker: Worker, previews: list[FilePreview]) -> None:
        if worker is self._worker:
            self.previews = previews
            self._fill()

    def _on_done(self, worker: Worker) -> None:
        if worker is self._worker:
            self._worker = None
            self.sig_ready.emit()

    def _fill(self) -> None:
        self.tree.clear()
        odd = bad = 0
        for p in self.previews:
            # A table or point cloud (no sentences, no kind guessed) is not judged here.
            fits = not p.error and (self._kind in p.kinds or not (p.kinds or p.sentences))
            odd += not fits and not p.error
            bad += bool(p.error)
            row = QTreeWidgetItem(self.tree, [
                p.path.rsplit("/", 1)[-1], ", ".join(p.kinds) or "—", p.span_text() or "—",
                size_text(p.size)])
            row.setToolTip(0, p.path)
            row.setToolTip(2, f"times from {p.time_from}" if p.time_from else "no times found")
            content = QTreeWidgetItem(row, [_content_text(p)])
            content.setFirstColumnSpanned(True)
            content.setToolTip(0, _content_text(p) if not p.sentences else
                               "\n".join(f"{k}: {n}" for k, n in p.sentences.items()))
            row.setExpanded(True)
            if not fits:
                brush = QBrush(MISMATCH if not p.error else QColor(Qt.GlobalColor.red))
                for column in range(len(COLUMNS)):
                    row.setForeground(column, brush)
                content.setForeground(0, brush)
                row.setToolTip(1, p.error or f"holds {', '.join(p.kinds)}, not {self._kind}")
        for column in range(len(COLUMNS) - 1):
            self.tree.resizeColumnToContents(column)
        self.status.setText(self._summary(odd, bad))

    def _summary(self, odd: int, bad: int) -> str:
        n = len(self.previews)
        text = f"{n} file(s), {size_text(sum(p.size for p in self.previews))}"
        spans = [p for p in self.previews if p.first is not None and p.dated]
        if spans:
            first = min(spans, key=lambda p: p.first)
            last = max(spans, key=lambda p: p.last)
            whole = FilePreview("", first=first.first, last=last.last, dated=True)
            text += f"; {whole.span_text()}"
        if odd:
            text += f". {odd} do not look like {self._kind} (marked)"
        if bad:
            text += f". {bad} cannot be read (in red)"
        return text + "."
