"""The GNSS/INS Smoother panel: parameters, outage controls, Run, map and time series.

Plots (pyqtgraph): the trajectory map (GNSS fixes, forward, smoothed; local east/north),
position/velocity/attitude against time, their standard deviations, and the errors against
the reference when one is stored.
"""

from __future__ import annotations

import json

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QDoubleSpinBox,
    QFormLayout,
    QPushButton,
)

from hydrosync_core.methods.gins_smoother.params import RAN, GinsParams
from hydrosync_core.methods.gins_smoother.project_run import GNSS, OUTAGES, RESULT
from hydrosync_core.params import stored
from hydrosync_gui.analysis_panel import AnalysisPanel, plot_widget

COLOURS = {"forward": (200, 60, 40), "smoothed": (30, 90, 200), "gnss": (90, 90, 90)}
MAX_POINTS = 4000


def _plot(ylabel: str, xlabel: str = "time from start [s]") -> pg.PlotWidget:
    return plot_widget(ylabel, xlabel)


def _thin(n: int) -> np.ndarray:
    return np.arange(0, n, max(1, n // MAX_POINTS))


class GinsPanel(AnalysisPanel):
    """GNSS/INS integration with RTS smoothing (Wang et al.)."""

    def __init__(self, spec=None, parent=None) -> None:
        if spec is None:
            from plugins.gins_smoother import SPEC

            spec = SPEC
        super().__init__(spec, GinsParams, parent)
        self.outage_len = QDoubleSpinBox(minimum=0.0, maximum=600.0, value=30.0, suffix=" s")
        self.outage_every = QDoubleSpinBox(minimum=1.0, maximum=3600.0, value=120.0, suffix=" s")
        self.outage_button = QPushButton("Set outages")
        self.outage_button.setToolTip("remove GNSS for the given length every given interval "
                                      "(length 0 clears the outages); applied at the next Run")
        self.outage_button.clicked.connect(self._on_outages)
        outage_box = QFormLayout()
        outage_box.addRow("Outage length", self.outage_len)
        outage_box.addRow("Every", self.outage_every)
        outage_box.addRow(self.outage_button)
        self.map = _plot("north [m]", "east [m]")
        self.map.setAspectLocked(True)
        self.series = {k: _plot(lab) for k, lab in (("height", "height [m]"),
                                                    ("speed", "speed [m/s]"),
                                                    ("yaw", "yaw [°]"))}
        self.sigma = {k: _plot(lab) for k, lab in (("sd_n", "σ north [m]"),
                                                   ("sd_d", "σ down [m]"),
                                                   ("sd_yaw", "σ yaw [°]"))}
        self.errors = {c: _plot(f"{c} error [{u}]") for cs, u in
                       ((("north", "east", "down"), "m"), (("vn", "ve", "vd"), "m/s"),
                        (("roll", "pitch", "yaw"), "°")) for c in cs}
        self.add_tab("Map", self.map)
        self.add_tab("Position / velocity / attitude", *self.series.values())
        self.add_tab("Standard deviations", *self.sigma.values())
        # One tab per kind, three plots stacked at full width: nine side by side in one tab
        # left each a ~117-px data area on a 1366-px screen, legends cut.
        errors = list(self.errors.values())
        for k, kind in enumerate(("Position", "Velocity", "Attitude")):
            self.add_tab(f"{kind} errors (±σ)", *errors[3 * k:3 * k + 3])
        self.build(before_run=[outage_box])

    def _all_plots(self):
        return [self.map, *self.errors.values(), *self.series.values(), *self.sigma.values()]

    def redraw(self) -> None:
        project = self.project
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        self.outage_button.setEnabled(project is not None and not self.busy)
        for w in self._all_plots():
            w.clear()
        if project is None or not project.exists(f"{RESULT}/forward"):
            self.summary.setText("Needs " + ", ".join(missing) + " (File → Import: --gins-imu, "
                                 "--gins-gnss, --gins-config)." if missing else "Press Run.")
            return
        self.form.set_params(stored(GinsParams, project, RESULT))
        attrs = project.attrs(RESULT)
        counts = json.loads(attrs["counts"])
        ev = json.loads(attrs["evaluation"])
        text = (f"Ran: {counts.get('ran', RAN[True])}; {counts['imu_epochs']} IMU epochs, "
                f"{counts['gnss_used']} of {counts['gnss_epochs']} GNSS fixes used, "
                f"{counts['states']} states; alignment: "
                f"{json.loads(attrs['alignment']).get('method')}.")
        model = json.loads(attrs.get("gnss_model", "{}"))
        if model.get("summary"):
            text += "\nσ from: " + model["summary"]
        for name, e in ev.items():
            a = e.get("gnss_on", e["all"])
            text += (f"\n{name}: horizontal RMS {100 * a['horizontal']['rms']:.2f} cm, yaw RMS "
                     f"{a['yaw']['rms']:.4f}°")
            o = e.get("outage")
            if o and o.get("max_horizontal_m") is not None:
                text += f", outage drift max {o['max_horizontal_m']:.3f} m"
            c = e.get("coverage", {}).get("all", {})
            if c.get("north") and c.get("east") and c.get("down"):
                text += (", within 1.96σ N/E/D " + "/".join(
                    f"{100 * c[k]['within_95']:.0f}" for k in ("north", "east", "down")) + " %")
            off = e.get("constant_offset")
            if off and off.get("yaw") is not None:
                text += ("; constant offset from the reference (not independent; its own "
                         "axes and point) roll/pitch/yaw " + "/".join(
                             f"{off[k]:+.2f}" for k in ("roll", "pitch", "yaw")) + "°")
        self.summary.setText(text)
        tabs = {"forward": project.get_table(f"{RESULT}/forward")}
        if project.exists(f"{RESULT}/smoothed"):
            tabs["smoothed"] = project.get_table(f"{RESULT}/smoothed")
        f = tabs["forward"]
        lat0, lon0, t0 = float(f["lat"][0]), float(f["lon"][0]), float(f["time"][0])
        ke = 111320.0 * np.cos(np.radians(lat0))
        g = project.get_table(GNSS)
        self.map.plot((g["lon"] - lon0) * ke, (g["lat"] - lat0) * 110540.0, pen=None,
                      symbol="o", symbolSize=4, symbolBrush=COLOURS["gnss"], name="GNSS")
        for name, tab in tabs.items():
            i = _thin(tab["time"].size)
            pen = pg.mkPen(COLOURS[name], width=1)
            t = tab["time"][i] - t0
            self.map.plot((tab["lon"][i] - lon0) * ke, (tab["lat"][i] - lat0) * 110540.0,
                          pen=pen, name=name)
            self.series["height"].plot(t, tab["height"][i], pen=pen, name=name)
            self.series["speed"].plot(t, np.hypot(tab["vn"][i], tab["ve"][i]), pen=pen, name=name)
            self.series["yaw"].plot(t, tab["yaw"][i], pen=pen, name=name)
            for k, w in self.sigma.items():
                w.plot(t, tab[k][i], pen=pen, name=name)
        from hydrosync_core.methods.gins_smoother.project_run import stored_errors

        for name, e in stored_errors(project).items():
            i = _thin(e["time"].size)
            x = e["time"][i] - t0
            pen = pg.mkPen(COLOURS[name], width=1)
            dash = pg.mkPen(COLOURS[name], width=1, style=Qt.PenStyle.DashLine)
            for comp, w in self.errors.items():
                w.plot(x, e[comp][i], pen=pen, name=name)
                sd = e.get(f"sd_{comp}")
                if sd is not None:
                    w.plot(x, sd[i], pen=dash)
                    w.plot(x, -sd[i], pen=dash)

    def _on_outages(self) -> None:
        project = self.project
        if project is None or not project.exists("raw/gins/gnss"):
            return
        from hydrosync_core.methods.gins_smoother.evaluate import outage_windows

        g = project.get_table("raw/gins/gnss")
        length = float(self.outage_len.value())
        windows = [] if length <= 0 else outage_windows(
            float(g["time"][0]), float(g["time"][-1]), length, float(self.outage_every.value()))
        project.put_json(OUTAGES, {"windows": [list(w) for w in windows]})
        self.sig_project_modified.emit()
        self.summary.setText(f"{len(windows)} GNSS outages of {length:g} s set; press Run.")

