"""File → Run campaign…: run a campaign file on Dask without blocking the window.

The dialog reads and checks a campaign file (``docs/formats.md`` "Campaign file"), shows
the plan (what ``hydrosync batch --dry-run`` prints), and runs it in a
:class:`~hydrosync_gui.workers.Worker` thread through
:func:`hydrosync_core.campaign.engine.run_campaign`: a local cluster of worker processes,
or an existing Dask scheduler when an address is given. Progress (steps done / failed /
running, ETA) and the Dask dashboard link are shown while it runs; Cancel stops it (steps
already finished stay saved in their projects). When it is done the table shows, per
project and step, the status, duration and key figures, and the summary page can be
opened.

A project open for writing in this window holds its write lock: the campaign's workers
are then refused and that project is reported as failed (the others run).
"""

from __future__ import annotations

import logging
import os
from pathlib import Path

from PySide6.QtCore import Qt, QUrl, Slot
from PySide6.QtGui import QDesktopServices
from PySide6.QtWidgets import (
    QDialog,
    QFileDialog,
    QFormLayout,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QProgressBar,
    QPushButton,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.errors import HydroSyncError
from hydrosync_gui.workers import Worker, start

log = logging.getLogger("hydrosync_gui.campaign")

CAMPAIGN_FILTER = "Campaign files (*.toml);;All files (*)"
COLOURS = {"done": "#d9f2d9", "up to date": "#e6f0fa", "not applicable": "#f0f0f0",
           "skipped": "#fde9c8", "failed": "#f8d0d0"}


class CampaignDialog(QDialog):
    """Choose a campaign file, see its plan, run it, follow it, see the outcome."""

    def __init__(self, parent: QWidget | None = None, start_dir: str = "") -> None:
        super().__init__(parent)
        self.setWindowTitle("Run campaign")
        self.resize(900, 600)
        self.start_dir = start_dir
        self.campaign = None
        self.result = None
        self.worker: Worker | None = None
        self.dashboard: str | None = None

        self.path_edit = QLineEdit()
        self.path_edit.setReadOnly(True)
        self.path_edit.setPlaceholderText("choose a campaign file (.toml)")
        self.choose_button = QPushButton("Choose…")
        self.choose_button.clicked.connect(self.choose)
        self.workers_spin = QSpinBox()
        self.workers_spin.setRange(1, 256)
        self.workers_spin.setValue(os.cpu_count() or 1)
        self.workers_spin.setToolTip("worker processes of the local cluster")
        self.scheduler_edit = QLineEdit()
        self.scheduler_edit.setPlaceholderText("empty: local cluster (or DASK_SCHEDULER_ADDRESS)"
                                               "; e.g. tcp://host:8786")
        row = QHBoxLayout()
        row.addWidget(self.path_edit, 1)
        row.addWidget(self.choose_button)
        form = QFormLayout()
        form.addRow("Campaign file", row)
        form.addRow("Local workers", self.workers_spin)
        form.addRow("Dask scheduler", self.scheduler_edit)

        self.plan = QPlainTextEdit()
        self.plan.setReadOnly(True)
        self.plan.setMaximumHeight(160)
        self.table = QTableWidget(0, 0)
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        self.status = QLabel("")
        self.status.setWordWrap(True)
        self.status.setTextInteractionFlags(Qt.TextInteractionFlag.TextBrowserInteraction)
        self.status.setOpenExternalLinks(True)
        self.bar = QProgressBar()
        self.bar.setRange(0, 1000)
        self.run_button = QPushButton("Run")
        self.run_button.setEnabled(False)
        self.run_button.clicked.connect(self.run)
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setEnabled(False)
        self.cancel_button.clicked.connect(self.cancel)
        self.summary_button = QPushButton("Open summary")
        self.summary_button.setEnabled(False)
        self.summary_button.clicked.connect(self.open_summary)
        self.close_button = QPushButton("Close")
        self.close_button.clicked.connect(self.close)
        buttons = QHBoxLayout()
        buttons.addWidget(self.bar, 1)
        for b in (self.run_button, self.cancel_button, self.summary_button, self.close_button):
            buttons.addWidget(b)

        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.plan)
        layout.addWidget(self.table, 1)
        layout.addWidget(self.status)
        layout.addLayout(buttons)

    # ------------------------------------------------------------------- choosing
    @Slot()
    def choose(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Campaign file", self.start_dir,
                                              CAMPAIGN_FILTER)
        if path:
            self.load(path)

    def load(self, path: str | os.PathLike) -> bool:
        """Read and check *path*; show its plan (or the one-line error). True if usable."""
        from hydrosync_core.campaign import load_campaign

        self.path_edit.setText(str(path))
        self.start_dir = str(Path(path).parent)
        try:
            self.campaign = load_campaign(path)
        except HydroSyncError as exc:
            self.campaign = None
            self.plan.setPlainText(str(exc))
            self.status.setText("The campaign file has a problem: fix it and choose it again.")
        else:
            self.plan.setPlainText("\n".join(self.campaign.plan_lines()))
            self.status.setText("Ready: up-to-date results are not computed again.")
        self.run_button.setEnabled(self.campaign is not None and self.worker is None)
        return self.campaign is not None

    # -------------------------------------------------------------------- running
    @property
    def busy(self) -> bool:
        return self.worker is not None

    @Slot()
    def run(self) -> Worker | None:
        """Start the campaign in a worker thread; returns the worker (tests wait on it)."""
        if self.campaign is None or self.worker is not None:
            return None
        from hydrosync_core.campaign.engine import Listener, run_campaign

        campaign = self.campaign
        workers = self.workers_spin.value()
        scheduler = self.scheduler_edit.text().strip() or None
        dialog = self

        def work(progress, cancel):
            class Relay(Listener):
                def started(self, result, total):
                    dialog.dashboard = result.dashboard
                    progress(0.0, f"{total} step(s) on {result.where}")

                def update(self, state):
                    progress(state.finished / max(state.total, 1), state.text())

            return run_campaign(campaign, scheduler=scheduler, workers=workers,
                                listener=Relay(), cancel=cancel)

        self.result = None
        self.dashboard = None
        self.table.setRowCount(0)
        self.bar.setValue(0)
        self.status.setText("Starting the Dask cluster…")
        self.worker = Worker(work, min_interval=0.2)
        self.worker.signals.sig_progress.connect(self._on_progress)
        self.worker.signals.sig_finished.connect(self._on_finished)
        self.worker.signals.sig_failed.connect(self._on_failed)
        self.worker.signals.sig_cancelled.connect(self._on_cancelled)
        self.worker.signals.sig_done.connect(self._on_done)
        self._set_running(True)
        log.info("campaign %s started", campaign.name)
        return start(self.worker)

    @Slot()
    def cancel(self) -> None:
        if self.worker is not None:
            self.status.setText("Cancelling: steps already finished stay saved…")
            self.worker.cancel()

    def _set_running(self, running: bool) -> None:
        self.run_button.setEnabled(not running and self.campaign is not None)
        self.choose_button.setEnabled(not running)
        self.cancel_button.setEnabled(running)
        self.workers_spin.setEnabled(not running)
        self.scheduler_edit.setEnabled(not running)

    def _dashboard_html(self) -> str:
        return (f" — <a href='{self.dashboard}'>Dask dashboard</a>" if self.dashboard
                else "")

    @Slot(float, str)
    def _on_progress(self, fraction: float, message: str) -> None:
        self.bar.setValue(int(round(1000 * fraction)))
        self.status.setText(message + self._dashboard_html())

    @Slot(object)
    def _on_finished(self, result) -> None:
        from hydrosync_core.campaign.engine import status_counts

        self.result = result
        self.bar.setValue(1000)
        self.show_outcomes(result)
        text = f"{result.campaign.name}: {status_counts(result)} in {result.wall_s:.1f} s"
        self.status.setText(text)
        self.summary_button.setEnabled(bool(result.summary_files))
        log.log(logging.WARNING if result.failed else logging.INFO, "campaign %s", text)

    @Slot(str)
    def _on_failed(self, message: str) -> None:
        self.status.setText(f"The campaign could not run: {message}")
        log.error("campaign failed: %s", message)

    @Slot()
    def _on_cancelled(self) -> None:
        self.status.setText("Cancelled: the steps that finished are saved in their projects; "
                            "running the campaign again does only the rest.")
        log.info("campaign cancelled")

    @Slot()
    def _on_done(self) -> None:
        self.worker = None
        self._set_running(False)

    def show_outcomes(self, result) -> None:
        """The table project × step: status, duration, key figures, warnings."""
        steps = list(dict.fromkeys(o["step"] for o in result.outcomes))
        projects = list(dict.fromkeys(o["project"] for o in result.outcomes))
        self.table.clear()
        self.table.setColumnCount(len(steps))
        self.table.setRowCount(len(projects))
        self.table.setHorizontalHeaderLabels(steps)
        self.table.setVerticalHeaderLabels(projects)
        column = {s: i for i, s in enumerate(steps)}
        row = {p: i for i, p in enumerate(projects)}
        for o in result.outcomes:
            lines = [f"{o['status']} ({o.get('seconds', 0.0):.1f} s)"]
            lines += [f"{q}: {v}" for q, v in o.get("rows") or []]
            if o["status"] not in ("done", "up to date") and o.get("message"):
                lines.append(o["message"])
            lines += [f"⚠ {w}" for w in o.get("warnings") or []]
            item = QTableWidgetItem(lines[0])
            item.setToolTip("\n".join(lines))
            item.setBackground(_colour(o["status"]))
            self.table.setItem(row[o["project"]], column[o["step"]], item)

    @Slot()
    def open_summary(self) -> None:
        pages = [p for p in (self.result.summary_files if self.result else [])
                 if p.endswith(".html")]
        if pages:
            QDesktopServices.openUrl(QUrl.fromLocalFile(pages[0]))

    def wait_idle(self, timeout: float = 60.0) -> bool:
        worker = self.worker
        return worker is None or worker.finished_event.wait(timeout)

    def closeEvent(self, event) -> None:  # noqa: N802 - Qt override
        if self.worker is not None:
            self.cancel()
            self.wait_idle(60.0)
        super().closeEvent(event)


def _colour(status: str):
    from PySide6.QtGui import QColor

    return QColor(COLOURS.get(status, "#ffffff"))
