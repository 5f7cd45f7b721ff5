"""The Pool Calibration panel: parameters, Segment / Iterate / Run all, clouds, faces,
convergence.

A thin view over :mod:`hydrosync_core.methods.pool_calibration`: "Segment" runs
:func:`~hydrosync_core.methods.pool_calibration.estimator.segment` in a
worker and shows the faces found
with the coarse setup (kept in memory, nothing written); "Iterate" runs the angle
iteration, lever-arm steps and joint adjustment on that segmentation
(:func:`~hydrosync_core.methods.pool_calibration.project_run.solve_and_store`); "Run all" runs
:func:`~hydrosync_core.methods.pool_calibration.project_run.run` in a worker, which replaces
``/results/pool_calibration``; everything shown afterwards is read back from there.
"""

from __future__ import annotations

import html
import json

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QCheckBox,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QScrollArea,
    QSplitter,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import estimator, project_run
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.preview import segmentation_preview
from hydrosync_core.methods.pool_calibration.project_run import RESULT
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.widgets.param_form import ParamForm
from plugins.pool_calibration.cloud_box import CloudBox
from plugins.pool_calibration.views import (
    ConvergencePlot,
    FaceTable,
    IterationTable,
    ValuesTable,
    convergence_legend,
)

PLAN = ("laser_xyz", "laser_face", "mbes_before_xyz", "mbes_after_xyz", "mbes_face")
WARN_STYLE = ("QLabel { background: #fff3cd; border: 1px solid #d39e00; border-radius: 3px;"
              " color: #6b3d00; padding: 6px; }")


def passes_text(passes: list[dict]) -> str:
    """One line per session: each pass's soundings and those on referenced faces."""
    if len(passes) < 2:
        return ""
    return (f"<br>{len(passes)} passes adjusted jointly: " + "; ".join(
        f"pass {q['pass']}: {q['soundings']:,} soundings ({q['on_faces']:,} on faces)"
        for q in passes))


class PoolCalibrationPanel(PluginPanel):
    """Multibeam boresight and lever arm from the pool target (CN 105425246 B + joint fit)."""

    def __init__(self, spec=None, parent: QWidget | None = None) -> None:
        if spec is None:
            from plugins.pool_calibration import SPEC

            spec = SPEC
        super().__init__(spec, parent)
        self.segmentation: estimator.Segmentation | None = None
        self._preview: tuple[dict, dict] | None = None  # (faces, clouds) of a Segment
        self._bound_project = None
        self._storing: tuple | None = None  # (project, {"result": …}) of a storing task

        self.form = ParamForm(PoolParams)
        self.segment_button = QPushButton("Segment")
        self.segment_button.setToolTip("find the faces in both clouds with the coarse setup "
                                       "(nothing is stored)")
        self.segment_button.clicked.connect(self._on_segment)
        self.iterate_button = QPushButton("Iterate")
        self.iterate_button.setToolTip("iterate and adjust on the faces found by Segment, "
                                       "then store the results")
        self.iterate_button.clicked.connect(self._on_iterate)
        self.run_button = QPushButton("Run all")
        self.run_button.setToolTip("segment, iterate, adjust and store the results")
        self.run_button.clicked.connect(self._on_run)
        self.summary = QLabel()
        self.summary.setObjectName("pool_summary")
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.warnings = QLabel()
        self.warnings.setObjectName("pool_warnings")
        self.warnings.setWordWrap(True)
        self.warnings.setStyleSheet(WARN_STYLE)
        self.warnings.setVisible(False)
        self.values = ValuesTable()
        self.values.clear_values()

        self.convergence = ConvergencePlot()
        self.log_check = QCheckBox("log |Δ|")
        self.log_check.setChecked(True)
        self.log_check.toggled.connect(self._draw_convergence)
        box = QGroupBox("Parameters")
        QVBoxLayout(box).addWidget(self.form)
        buttons = QHBoxLayout()
        buttons.addWidget(self.segment_button)
        buttons.addWidget(self.iterate_button)
        buttons.addWidget(self.run_button)
        self.apply_button = QPushButton("Apply to vessel sheet…")
        self.apply_button.setObjectName("apply_to_vessel")
        self.apply_button.setToolTip("write the final boresight and lever arm into the vessel "
                                     "sheet's multibeam entry (recorded in the project history)")
        self.apply_button.clicked.connect(self._on_apply)
        values_box = QGroupBox("Boresight and lever arm (body FRD)")
        values_layout = QVBoxLayout(values_box)
        values_layout.addWidget(self.values)
        values_layout.addWidget(self.apply_button)
        conv_box = QGroupBox("Convergence of the patent's angle iteration")
        cv = QVBoxLayout(conv_box)
        conv_top = QHBoxLayout()
        conv_top.addWidget(self.log_check)
        conv_top.addStretch(1)
        conv_top.addWidget(QLabel(convergence_legend()))
        cv.addLayout(conv_top)
        cv.addWidget(self.convergence, 1)
        self.cloud_box = CloudBox()
        # Shortcuts used by the tests and the shell's screenshots.
        self.cloud_view = self.cloud_box.view
        self.before_radio, self.after_radio = (self.cloud_box.before_radio,
                                               self.cloud_box.after_radio)

        self.face_table = FaceTable()
        self.iteration_table = IterationTable()
        # The results sit beside the clouds, not under the parameters: on a 1366×768 laptop
        # the parameter column scrolls, and what a run produced must never be below its fold.
        self.tabs = QTabWidget()
        results = QWidget()
        results_layout = QVBoxLayout(results)
        results_layout.setContentsMargins(0, 0, 0, 0)
        results_layout.addWidget(values_box)
        results_layout.addStretch(1)
        self.results_box = QScrollArea()
        self.results_box.setWidget(results)
        self.results_box.setWidgetResizable(True)
        self.results_box.setFrameShape(QScrollArea.Shape.NoFrame)
        self.tabs.addTab(self.results_box, "Results")
        self.tabs.addTab(conv_box, "Convergence")
        self.tabs.addTab(self.face_table, "Faces")
        self.tabs.addTab(self.iteration_table, "Iterations")
        right = QSplitter(Qt.Orientation.Vertical)
        right.addWidget(self.cloud_box)
        right.addWidget(self.tabs)
        right.setSizes([440, 360])
        # Only the parameters scroll; the buttons and the run's summary stay in view.
        params_scroll = QScrollArea()
        params_scroll.setWidget(box)
        params_scroll.setWidgetResizable(True)
        params_scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        params_scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        left = QWidget()
        left.setMinimumWidth(340)
        lay = QVBoxLayout(left)
        lay.setContentsMargins(0, 0, 4, 0)
        lay.addWidget(params_scroll, 1)
        lay.addLayout(buttons)
        lay.addWidget(self.summary)
        lay.addWidget(self.warnings)
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(left)
        split.addWidget(right)
        split.setStretchFactor(1, 1)
        split.setSizes([475, 925])
        QVBoxLayout(self).addWidget(split)

    # ------------------------------------------------------------- parameters
    def params(self) -> PoolParams | None:
        """The form's parameters, validated; None (and the reason shown) if invalid."""
        try:
            return self.form.params()
        except InputError as exc:
            self.summary.setText(f"<b>Parameter error</b>: {exc.one_line()}")
            self.sig_status.emit(f"Pool calibration: {exc.one_line()}")
            return None

    def _load_params(self) -> None:
        """The last run's parameters, else the schema's defaults."""
        self.form.set_params(project_run.stored_params(self.project) or PoolParams())

    # ---------------------------------------------------------------- drawing
    def refresh(self) -> None:
        project = self.project
        if project is not self._bound_project:
            self._bound_project = project
            self.segmentation, self._preview = None, None
            if project is not None:
                self._load_params()
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self._enable(not missing and not self.busy)
        if missing:
            self.segmentation, self._preview = None, None
            self._clear("<b>Needs data</b>: " + ", ".join(
                f"/{m}" if "/" in m else m for m in missing) + ". Import the laser cloud, "
                "multibeam soundings, INS, setup.json and target.json (or create demo data).")
        elif self._preview is not None:
            self._show_preview()
        elif project.exists(f"{RESULT}/faces"):
            self._show_results()
        else:
            self._clear("Data ready. <b>Segment</b> to check the faces found with the coarse "
                        "setup, or <b>Run all</b> to calibrate.")

    def _enable(self, on: bool) -> None:
        self.apply_button.setEnabled(bool(on and self.project is not None
                                          and self.project.exists(f"{RESULT}/faces")
                                          and not self.stale_reasons()))
        self.segment_button.setEnabled(on)
        self.iterate_button.setEnabled(on and self.segmentation is not None)
        self.run_button.setEnabled(on)

    def _clear(self, text: str) -> None:
        self.summary.setText(text)
        self._set_warnings([])
        self.values.clear_values()
        self.face_table.clear()
        self.iteration_table.clear()
        self.convergence.show_table(None, None, self.log_check.isChecked())
        self.cloud_box.clear()

    def _set_warnings(self, warnings: list[str]) -> None:
        self.warnings.setText("<br>".join(f"⚠ {html.escape(w)}" for w in warnings))
        self.warnings.setVisible(bool(warnings))

    def _show_preview(self) -> None:
        faces, clouds = self._preview
        n_used = int(np.sum((faces["points_laser"] >= self.form.values()["min_points"])
                            & (faces["points_mbes"] >= self.form.values()["min_points"])))
        self.summary.setText(
            f"<b>Segmentation</b> with the coarse setup (not stored): {n_used} of "
            f"{len(faces['face'])} faces have enough points in both clouds"
            + (f" ({len(starts)} passes)" if (starts := self._pass_starts()) is not None
               and len(starts) > 1 else "") + ". "
            "<b>Run all</b> to calibrate"
            + (" (replaces the stored results)." if self.project.exists(f"{RESULT}/faces")
               else "."))
        self._set_warnings(list(self.segmentation.warnings) if self.segmentation else [])
        self.values.clear_values()
        self.face_table.fill(faces)
        self.iteration_table.clear()
        self.convergence.show_table(None, None, self.log_check.isChecked())
        self.cloud_box.draw([str(n) for n in faces["face"]], clouds, faces.get("role"))
        self.tabs.setCurrentWidget(self.face_table)

    def _pass_starts(self):
        seg = self.segmentation
        return None if seg is None else seg.ctx.pass_start

    def _show_results(self) -> None:
        project = self.project
        attrs = project.attrs(RESULT)
        result = project.get_json(f"{RESULT}/result", {}) or {}
        joint = result.get("joint") or {}
        method = "Joint" if attrs.get("method") == "joint" else "Patent method"
        text = (f"<b>{method} solution</b>, "
                f"{'converged' if attrs.get('converged') else '<b>NOT converged</b>'}. "
                f"{result.get('message', '')}")
        if joint.get("sigma0_m") is not None:
            text += (f"<br>σ0 = {1000 * joint['sigma0_m']:.1f} mm from "
                     f"{joint.get('n_observations', 0)} soundings")
        text += passes_text(result.get("passes") or [])
        text += f"<br><span style='color:#666'>run {attrs.get('run_utc', '?')}</span>"
        self.summary.setText(text)
        self._set_warnings(json.loads(attrs.get("warnings", "[]")))
        self.values.fill(attrs, result)
        self.tabs.setCurrentWidget(self.results_box)
        faces = project.get_table(f"{RESULT}/faces")
        self.face_table.fill(faces)
        self.iteration_table.fill(project.get_table(f"{RESULT}/iterations"))
        self._draw_convergence()
        if all(project.exists(f"{RESULT}/plan/{k}") for k in PLAN):
            clouds = {k: project.get(f"{RESULT}/plan/{k}") for k in PLAN}
            self.cloud_box.draw([str(n) for n in faces["face"]], clouds, faces.get("role"))
        else:
            self.cloud_box.clear()

    def _draw_convergence(self) -> None:
        project = self.project
        if (self._preview is not None or project is None
                or not project.exists(f"{RESULT}/iterations")):
            self.convergence.show_table(None, None, self.log_check.isChecked())
            return
        tol = project_run.stored_params(project).tol_deg
        self.convergence.show_table(project.get_table(f"{RESULT}/iterations"), tol,
                                    self.log_check.isChecked())

    # ------------------------------------------------------------------ slots
    def _on_segment(self) -> None:
        project, params = self.project, self.params()
        if project is None or params is None:
            return

        def task(progress, cancel):
            seg = project_run.segment_project(project, params, progress, cancel)
            return project, seg, segmentation_preview(seg, params.plan_points)

        self._enable(False)
        self._storing = None
        self.start_work(task, self._on_segmented, label="Segmentation")

    def _on_segmented(self, out) -> None:
        project, seg, preview = out
        if project is not self.project:  # another project was opened meanwhile
            return
        self.segmentation, self._preview = seg, preview
        self._show_preview()
        faces = self._preview[0]
        self.sig_status.emit(
            "Segmentation: " + ", ".join(
                f"{f} {a}/{b}" for f, a, b in zip(faces["face"], faces["points_laser"],
                                                  faces["points_mbes"], strict=True) if a or b)
            + " (laser/multibeam points)")

    def _on_run(self) -> None:
        project, params = self.project, self.params()
        if project is None or params is None:
            return
        self._start_storing_task(
            "Pool calibration", lambda progress, cancel: project_run.run(
                project, params, progress, cancel))

    def _on_iterate(self) -> None:
        project, params, seg = self.project, self.params(), self.segmentation
        if project is None or seg is None or params is None:
            return
        self._start_storing_task(
            "Pool calibration (iterate)", lambda progress, cancel: project_run.solve_and_store(
                project, seg, params, progress, cancel))

    def _start_storing_task(self, label: str, compute) -> None:
        """Run *compute(progress, cancel)*, which stores its results only when complete."""
        project = self.project
        stored = {"result": None}

        def task(progress, cancel):
            # Nothing is stored until the computation is complete, so a cancel before
            # that leaves the previous results untouched.
            stored["result"] = compute(progress, cancel)
            return stored["result"]

        self._enable(False)
        self._storing = (project, stored)
        self.start_work(task, self._on_run_finished, label=label)

    def _on_run_finished(self, result) -> None:
        extra = f"; {len(result.warnings)} warning(s)" if result.warnings else ""
        self.sig_status.emit(f"Pool calibration: {result.message}{extra}")

    def work_done(self) -> None:
        # Also after a late cancel: once run() returned, the stored results are complete.
        storing, self._storing = self._storing, None
        if storing is not None:
            project, stored = storing
            if stored["result"] is not None and project is self.project:
                self._preview = None
                self.refresh()
                self.sig_project_modified.emit()
        self.refresh_buttons()

    def refresh_buttons(self) -> None:
        project = self.project
        ok = project is not None and not self.spec.missing_inputs(project)
        self._enable(ok and not self.busy)

    def _on_apply(self) -> None:
        from PySide6.QtWidgets import QMessageBox

        from hydrosync_core.methods.pool_calibration.apply import apply_to_vessel

        project = self.project
        if project is None:
            return
        answer = QMessageBox.question(
            self, "Apply to vessel sheet",
            "Write the final boresight angles and lever arm into the vessel sheet's "
            "multibeam entry? The previous entry is kept in the project history.")
        if answer != QMessageBox.StandardButton.Yes:
            return
        try:
            message = apply_to_vessel(project)
        except InputError as exc:
            QMessageBox.warning(self, "Not applied", exc.message)
            return
        self.sig_project_modified.emit()
        self.sig_status.emit(f"Applied to the vessel sheet: {message}")
