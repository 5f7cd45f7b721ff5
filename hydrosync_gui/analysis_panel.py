"""The common shape of an analysis panel, and the plot factory its views share.

Left: the parameter form derived from the analysis's schema, optional extra controls, the
Run button, a one-paragraph summary and optional widgets below it. Right: the views in
tabs. Run validates the parameters on the GUI thread (an invalid value is shown in the
summary, never raised), runs ``spec.run(project, params, progress, cancel)`` in a worker
and redraws from the project when it returns.
"""

from __future__ import annotations

from collections.abc import Iterable

import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QHBoxLayout,
    QLabel,
    QLayout,
    QPushButton,
    QScrollArea,
    QSplitter,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.widgets import ParamForm


def plot_widget(ylabel: str, xlabel: str, equal: bool = False) -> pg.PlotWidget:
    """A white plot with grid, legend and axis labels kept in the units given (no SI
    rescaling such as "(x0.001)"); *equal* locks the aspect ratio (maps, plan views)."""
    w = pg.PlotWidget(background="w")
    w.setLabel("left", ylabel)
    w.setLabel("bottom", xlabel)
    for side in ("left", "bottom"):
        w.getAxis(side).enableAutoSIPrefix(False)
    # A fixed axis width: with the aspect locked, tick labels that change width as the
    # range changes would resize the view, which changes the range again — for ever.
    w.getAxis("left").setWidth(58)
    w.showGrid(x=True, y=True, alpha=0.3)
    w.addLegend(offset=(10, 2), labelTextColor="k")
    if equal:
        w.setAspectLocked(True)
    return w


class AnalysisPanel(PluginPanel):
    """Form, Run and summary on the left; tabs of views on the right (see module doc)."""

    def __init__(self, spec, schema: type[Params], parent: QWidget | None = None,
                 choice_labels: dict[str, dict[str, str]] | None = None) -> None:
        super().__init__(spec, parent)
        self.form = ParamForm(schema, choice_labels=choice_labels)
        self.run_button = QPushButton("Run")
        self.run_button.clicked.connect(self._on_run)
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.tabs = QTabWidget()

    def build(self, before_run: Iterable[QWidget | QLayout] = (),
              after_summary: Iterable[QWidget | QLayout] = ()) -> None:
        """Lay the panel out once the subclass has made its widgets and tabs.

        The form (and *before_run* controls) scroll in a column of their own, so the panel
        fits a 1366×768 screen however many parameters the analysis has; Run, the summary
        and *after_summary* stay below it, outside the scroll area — a word-wrapped label
        inside it makes the scroll bars and the wrapping chase each other forever.
        """
        controls = QWidget()
        inner = QVBoxLayout(controls)
        inner.setContentsMargins(0, 0, 0, 0)
        inner.addWidget(self.form)
        for item in before_run:
            if isinstance(item, QLayout):
                inner.addLayout(item)
            else:
                inner.addWidget(item)
        inner.addStretch(1)
        scroll = QScrollArea()
        scroll.setWidget(controls)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        scroll.setMinimumWidth(300)
        left = QWidget()
        lay = QVBoxLayout(left)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(scroll, 3)
        for item in (self.run_button, self.summary, *after_summary):
            if isinstance(item, QLayout):
                lay.addLayout(item)
            else:
                lay.addWidget(item, 2 if item is not self.run_button and
                              item is not self.summary else 0)
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(left)
        split.addWidget(self.tabs)
        split.setStretchFactor(0, 2)
        split.setStretchFactor(1, 3)
        split.setSizes([470, 530])
        QHBoxLayout(self).addWidget(split)

    def add_tab(self, title: str, *widgets: QWidget, horizontal: bool = False) -> QWidget:
        """A tab holding *widgets* stacked (or side by side); returns the page."""
        if len(widgets) == 1:
            page = widgets[0]
        else:
            page = QWidget()
            layout = QHBoxLayout(page) if horizontal else QVBoxLayout(page)
            for w in widgets:
                layout.addWidget(w)
        self.tabs.addTab(page, title)
        return page

    # ------------------------------------------------------------------ drawing
    def refresh(self) -> None:
        """Redraw from the project (:meth:`redraw`), then fix the range of every plot whose
        aspect is locked: pyqtgraph's auto-range and aspect lock can chase each other
        forever (the view never stops repainting) for some widget sizes."""
        self.redraw()
        for plot in self.findChildren(pg.PlotWidget):
            box = plot.getViewBox()
            if box.state.get("aspectLocked"):
                box.enableAutoRange()
                box.autoRange()
                box.disableAutoRange()

    def redraw(self) -> None:  # pragma: no cover - overridden
        """Draw everything from ``self.project``."""

    # ------------------------------------------------------------------ running
    def _on_run(self) -> None:
        project = self.project
        if project is None:
            return
        try:
            params = self.form.params()
        except InputError as exc:
            self.summary.setText(f"<b>Parameter error</b>: {exc.one_line()}")
            return
        run = self.spec.load_run()
        self.run_button.setEnabled(False)
        self.start_work(lambda progress, cancel: run(project, params, progress, cancel),
                        self._on_run_finished, label=self.spec.name)

    def _on_run_finished(self, _result) -> None:
        self.sig_project_modified.emit()
        self.refresh()

    def work_done(self) -> None:
        self.run_button.setEnabled(True)
