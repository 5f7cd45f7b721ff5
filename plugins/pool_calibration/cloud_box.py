"""The panel's cloud area: before/after toggle, the 3-D or 2-D view and a legend by face
kind (wall, block sides, tops…): one short line whatever the number of faces; each
face's name is on hover (2-D view), in the legend's tool tip and in the face table."""

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

from hydrosync_gui.i18n import tr
from plugins.pool_calibration.cloud_views import (
    KIND_SHADES,
    GLCloudView,
    ProjectionView,
    face_kind,
    gl_available,
    set_face_kinds,
)

VIEW_MIN_HEIGHT = 200
"""Pixels the cloud view keeps when the face table below it grows (at 1366×768 the
splitter would otherwise give the view a strip)."""


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
        self.stack.setMinimumHeight(VIEW_MIN_HEIGHT)
        self.stack.addWidget(self.placeholder)
        self.stack.addWidget(self.view)
        self.legend = QLabel()
        self.legend.setObjectName("face_kind_legend")
        self.legend.setWordWrap(True)
        self.legend.setTextFormat(Qt.TextFormat.RichText)
        # A wrapped label's height-for-width is not a minimum its layout honours: reserve
        # the two lines the legend takes at 1366 px, or a squeezed splitter lets the view
        # cover it.
        self.legend.setMinimumHeight(2 * self.legend.fontMetrics().lineSpacing() + 2)
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

    def draw(self, names: list[str], clouds: dict, roles=None) -> None:
        """Show *clouds* (plan-array layout, see :mod:`.cloud_views`) for faces *names*,
        coloured by kind (from *roles*, the faces table's ``role`` column, when given)."""
        kinds = [face_kind(str(n), None if roles is None else str(roles[i]))
                 for i, n in enumerate(names)]
        set_face_kinds(kinds)
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
        shown = [int(k) for k in np.union1d(clouds["laser_face"], clouds["mbes_face"]) if k >= 0]
        self._legend(names, kinds, shown)

    def _legend(self, names: list[str], kinds: list[str], shown: list[int]) -> None:
        by_kind: dict[str, list[str]] = {}
        for k in shown:
            by_kind.setdefault(kinds[k], []).append(str(names[k]))
        order = [kind for kind in KIND_SHADES if kind in by_kind]
        # Kind names in the workbench's language here: inside the rich text the shell's
        # relabelling cannot reach them (it translates the note after them).
        swatches = [f"<span style='color:{KIND_SHADES[kind][0]}'>■</span>&nbsp;{tr(kind)}"
                    + (f"&nbsp;({len(by_kind[kind])})" if len(by_kind[kind]) > 1 else "")
                    for kind in order]
        self.legend.setText(
            "&nbsp;&nbsp; ".join(swatches) + "&nbsp;&nbsp; <span style='color:#555'>"
            "faint discs: laser · triangles: multibeam · grey: on no face</span>")
        self.legend.setToolTip("<br>".join(
            f"<b>{kind}</b>: {', '.join(by_kind[kind])}" for kind in order)
            + "<br>Each face's name shows on hover and in the face table.")

    def _on_after_toggled(self, after: bool) -> None:
        self.view.set_after(after)
