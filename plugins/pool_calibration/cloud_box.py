"""The panel's cloud area: before/after toggle, the 3-D or 2-D view and a face legend."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QButtonGroup,
    QHBoxLayout,
    QLabel,
    QRadioButton,
    QStackedWidget,
    QVBoxLayout,
    QWidget,
)

from plugins.pool_calibration.cloud_views import (
    GLCloudView,
    ProjectionView,
    face_colour,
    gl_available,
)


class CloudBox(QWidget):
    """Clouds coloured by face; :attr:`view` is 3-D when OpenGL works, else 2-D.

    A placeholder text stands in for the view until :meth:`draw` is called; the
    multibeam "after" choice is only enabled when corrected soundings were given.
    """

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.before_radio = QRadioButton("Before (coarse setup)")
        self.after_radio = QRadioButton("After (final values)")
        self.before_radio.setChecked(True)
        group = QButtonGroup(self)
        group.addButton(self.before_radio)
        group.addButton(self.after_radio)
        self.after_radio.toggled.connect(self._on_after_toggled)
        self.view = GLCloudView() if gl_available() else ProjectionView()
        self.placeholder = QLabel("The laser and multibeam clouds are drawn here after "
                                  "<b>Segment</b> or <b>Run all</b>.")
        self.placeholder.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.placeholder.setStyleSheet("QLabel { background: white; color: #777; }")
        self.stack = QStackedWidget()
        self.stack.addWidget(self.placeholder)
        self.stack.addWidget(self.view)
        self.legend = QLabel()
        self.legend.setWordWrap(True)
        self.legend.setTextFormat(Qt.TextFormat.RichText)
        toggle = QHBoxLayout()
        toggle.addWidget(QLabel("Multibeam georeferenced:"))
        toggle.addWidget(self.before_radio)
        toggle.addWidget(self.after_radio)
        toggle.addStretch(1)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addLayout(toggle)
        lay.addWidget(self.stack, 1)
        lay.addWidget(self.legend)
        self.clear()

    def clear(self) -> None:
        self.view.clear()
        self.stack.setCurrentWidget(self.placeholder)
        self.legend.setText("")
        self.after_radio.setEnabled(False)

    def draw(self, names: list[str], clouds: dict) -> None:
        """Show *clouds* (plan-array layout, see :mod:`.cloud_views`) for faces *names*."""
        has_after = clouds.get("mbes_after_xyz") is not None
        newly_available = has_after and not self.after_radio.isEnabled()
        self.after_radio.setEnabled(has_after)
        if not has_after:
            self.before_radio.setChecked(True)
        elif newly_available:
            # Fresh results: show the corrected soundings first; the user toggles back.
            self.after_radio.setChecked(True)
        self.view.after = self.after_radio.isChecked()
        self.view.draw(names, clouds)
        self.stack.setCurrentWidget(self.view)
        shown = np.union1d(clouds["laser_face"], clouds["mbes_face"])
        swatches = [f"<span style='color:{face_colour(int(k))}'>■</span>&nbsp;{names[int(k)]}"
                    for k in shown if k >= 0]
        self.legend.setText(
            "&nbsp;&nbsp; ".join(swatches) + "<br><span style='color:#555'>faint discs: "
            "laser (reference) · triangles: multibeam · grey dots: soundings on no face"
            "</span>")

    def _on_after_toggled(self, after: bool) -> None:
        self.view.set_after(after)
