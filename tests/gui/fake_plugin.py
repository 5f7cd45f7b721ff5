"""Fake plugins for the GUI tests (registered as module ``hydrosync_test_fake_plugin``).

``FakePanel`` runs a slow job with progress and cancel; ``SecondPanel`` only counts its
instances (lazy-creation test); ``BrokenPanel`` fails in its constructor.
"""

from __future__ import annotations

import time

import numpy as np
from PySide6.QtWidgets import QLabel, QVBoxLayout

from hydrosync_core.plugins.spec import PluginSpec
from hydrosync_core.progress import check_cancel, report
from hydrosync_gui.plugin_panel import PluginPanel

MODULE = "hydrosync_test_fake_plugin"


def fake_run(project, params, progress=None, cancel=None):
    steps = int(params.get("steps", 100))
    for i in range(steps):
        check_cancel(cancel)
        time.sleep(float(params.get("dt", 0.01)))
        report(progress, (i + 1) / steps, f"step {i + 1} of {steps}")
    return {"steps": steps}


class FakePanel(PluginPanel):
    instances = 0

    def __init__(self) -> None:
        super().__init__()
        type(self).instances += 1
        self.label = QLabel("fake panel")
        QVBoxLayout(self).addWidget(self.label)
        self.refreshes = 0
        self.finished_with = None

    def refresh(self) -> None:
        self.refreshes += 1
        count = len(self.project.children("raw")) if self.project is not None else 0
        self.label.setText(f"raw groups: {count}")

    def run_job(self, steps: int = 100, dt: float = 0.01):
        def work(progress, cancel):
            return fake_run(self.project, {"steps": steps, "dt": dt}, progress, cancel)

        def finished(result) -> None:
            self.finished_with = result
            self.project.put_table("results/fake/out", {"step": np.arange(result["steps"])})
            self.sig_project_modified.emit()

        return self.start_work(work, finished, label="Fake job")


class SecondPanel(FakePanel):
    instances = 0


class BrokenPanel(PluginPanel):
    def __init__(self) -> None:
        raise RuntimeError("panel exploded on purpose")


def spec(id_: str, name: str, panel: str, order: int) -> PluginSpec:
    return PluginSpec(id=id_, name=name, run=f"{MODULE}:fake_run", panel=f"{MODULE}:{panel}",
                      description=f"{name} for tests", order=order)


FAKE = spec("fake", "Fake analysis", "FakePanel", 1)
SECOND = spec("second", "Second analysis", "SecondPanel", 2)
BROKEN_PANEL = spec("broken_panel", "Broken panel", "BrokenPanel", 3)
