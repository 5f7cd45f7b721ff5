"""The Tilt Alignment panel: parameters, Run, the per-method table and the plots.

Plots (pyqtgraph): the swing (antenna path, plan and side views, with the tip per epoch),
J(ψ) with the gradient-descent iterates of each method (Li et al., fig. 11), the
Monte-Carlo heading-error histogram (fig. 4) and the tip-error scatter (figs. 6-9).
"""

from __future__ import annotations

import json

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt

from hydrosync_core.methods.tilt_alignment.params import TiltParams
from hydrosync_core.methods.tilt_alignment.present import (
    COLUMNS,
    LABELS,
    heading_text,
    imu_text,
    joint_text,
    method_rows,
    sigma_enu_text,
    tip_header,
    tip_text,
)
from hydrosync_core.methods.tilt_alignment.project_run import RESULT
from hydrosync_core.params import stored
from hydrosync_gui.analysis_panel import AnalysisPanel
from hydrosync_gui.analysis_panel import plot_widget as _plot
from hydrosync_gui.widgets import ColumnsTable

COLOURS = {"joint": (30, 90, 200), "mbgd": (200, 60, 40), "bgd": (230, 150, 30),
           "sgd": (150, 80, 180), "svd": (40, 150, 60), "closed_form": (90, 90, 90)}


class TiltAlignmentPanel(AnalysisPanel):
    """Heading alignment and tip of a tilt RTK pole."""

    def __init__(self, spec=None, parent=None) -> None:
        if spec is None:
            from plugins.tilt_alignment import SPEC

            spec = SPEC
        super().__init__(spec, TiltParams, parent)
        self.table = ColumnsTable()
        self.plan = _plot("north [m]", "east [m]", equal=True)
        self.side = _plot("up [m]", "east [m]", equal=True)
        self.jcurve = _plot("J(ψ)", "ψ [°]")
        # J(ψ) is drawn over ψ̂ ± 180°: high at both ends, its minimum in the middle, so
        # the legend goes top centre, where the curve is not.
        self.jcurve.plotItem.legend.anchor((0.5, 0), (0.5, 0), offset=(0, 2))
        self.hist = _plot("runs", "heading error [°]")
        self.scatter = _plot("tip error north [mm]", "tip error east [mm]", equal=True)
        self.add_tab("Swing", self.plan, self.side, horizontal=True)
        self.add_tab("J(ψ) and iterations", self.jcurve)
        self.add_tab("Heading errors (Monte Carlo)", self.hist)
        self.add_tab("Tip errors (Monte Carlo)", self.scatter)
        self.build(after_summary=[self.table])

    def _clear(self) -> None:
        for w in (self.plan, self.side, self.jcurve, self.hist, self.scatter):
            w.clear()
        self.table.set_columns({})

    def redraw(self) -> None:
        project = self.project
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        self._clear()
        if project is None or not project.exists(f"{RESULT}/epochs"):
            self.summary.setText("Needs " + ", ".join(missing) + " (File → Import: "
                                 "--tilt_imu, --tilt_gnss, --tilt_pole)." if missing
                                 else "Press Run.")
            return
        self.form.set_params(stored(TiltParams, project, RESULT))
        doc = json.loads(project.attrs(RESULT)["result"])
        chosen = doc["methods"][doc["method"]]
        if chosen["undetermined"]:
            text = f"{LABELS[doc['method']]}: undetermined — {chosen['undetermined']}"
        else:
            text = (f"{LABELS[doc['method']]}: tip {tip_text(chosen)} m (σ E/N/U "
                    f"{sigma_enu_text(chosen)} mm), heading misalignment "
                    f"{heading_text(chosen)}")
        warn = "".join(f" Warning — {w}." for w in doc.get("warnings", []))
        self.summary.setText(f"{text}. {imu_text(doc)}. {joint_text(doc)}. Vectors used "
                             f"{doc['vectors_used']}, rejected {doc['vectors_rejected']}; "
                             f"tilt up to {doc['tilt_deg']['max']:.1f}°.{warn}")
        rows = method_rows(doc)
        heads = {**COLUMNS, "tip": tip_header(doc)}
        self.table.set_columns({k: np.array([r[k] for r in rows], dtype=object)
                                for k in heads}, labels=heads,
                               tips={"heading": "C = Rz(ψ)·C′: the IMU's heading error at "
                                                "the first sample, ± 1σ",
                                     "sigma": "1σ of the tip east, north and up"})
        ep = project.get_table(f"{RESULT}/epochs")
        e0, n0, u0 = (float(np.mean(ep[k])) for k in ("e", "n", "u"))
        pen = pg.mkPen((30, 90, 200), width=1)
        self.plan.plot(ep["e"] - e0, ep["n"] - n0, name="antenna", pen=pen, symbol="o",
                       symbolSize=3)
        self.side.plot(ep["e"] - e0, ep["u"] - u0, name="antenna", pen=pen, symbol="o",
                       symbolSize=3)
        if "tip_e" in ep:
            for w, y in ((self.plan, ep["tip_n"] - n0), (self.side, ep["tip_u"] - u0)):
                w.plot(ep["tip_e"] - e0, y, name="tip per epoch", pen=None, symbol="x",
                       symbolSize=5, symbolBrush=(200, 60, 40), symbolPen=(200, 60, 40))
        jc = project.get_table(f"{RESULT}/j_curve")
        self.jcurve.plot(jc["psi_deg"], jc["J"], name="J(ψ)", pen=pg.mkPen("k", width=1))
        for name in ("bgd", "sgd", "mbgd"):
            d = project.get_table(f"{RESULT}/descent_{name}")
            if d["psi_deg"].size:
                c = COLOURS[name]
                self.jcurve.plot(d["psi_deg"], d["J"], name=name.upper(), pen=pg.mkPen(c),
                                 symbol="o", symbolSize=5, symbolBrush=c)
        has_mc = project.exists(f"{RESULT}/montecarlo")
        for w in (self.hist, self.scatter):
            w.setTitle(None if has_mc else "no Monte Carlo for this record (parameter "
                       "'Monte-Carlo runs'; benchmarks/bench_tilt.py runs the full study)")
        if has_mc:
            mc = project.get_table(f"{RESULT}/montecarlo")
            edges = np.linspace(-2.0, 2.0, 33)
            for name in ("joint", "mbgd", "svd", "closed_form"):
                v = mc[f"{name}_heading_err_deg"]
                counts, _ = np.histogram(v[np.isfinite(v)], bins=edges)
                self.hist.plot(edges, counts, stepMode="center", name=name,
                               pen=pg.mkPen(COLOURS[name], width=2))
            for name in ("mbgd", "svd", "joint"):
                c = COLOURS[name]
                self.scatter.plot(1000 * mc[f"{name}_tip_err_e"], 1000 * mc[f"{name}_tip_err_n"],
                                  name=name, pen=None, symbol="o", symbolSize=5,
                                  symbolBrush=c, symbolPen=None)
            t = np.linspace(0, 2 * np.pi, 90)
            for r in (10, 25):
                self.scatter.plot(r * np.cos(t), r * np.sin(t), pen=pg.mkPen((150, 150, 150),
                                                                             style=Qt.PenStyle.DashLine))

