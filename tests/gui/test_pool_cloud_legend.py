"""The pool panel's cloud legend (#26): by face kind, one short line for 49 faces; each
face's name in the legend's tool tip and on hover; the face table's swatches the colours
of the cloud."""

from __future__ import annotations

import numpy as np
from PySide6.QtGui import QTextDocument

from plugins.pool_calibration.cloud_box import VIEW_MIN_HEIGHT, CloudBox
from plugins.pool_calibration.cloud_views import KIND_SHADES, face_colour, face_kind


def _demo_faces():
    """The demo target's 49 faces and roles (a wall, 6 blocks a side, 4 faces each pair)."""
    names, roles = ["wall"], ["wall"]
    for block in ("N1", "N2", "N3", "S1", "S2", "S3"):
        for side in ("up", "dn"):
            for face, role in (("perpendicular", "perpendicular"), ("oblique", "oblique"),
                               ("top", "horizontal"), ("bottom", "horizontal")):
                names.append(f"{block}_{side}_{face}")
                roles.append(role)
    return names, np.array(roles)


def test_face_kinds_from_role_and_from_name():
    assert face_kind("N1_up_top", "horizontal") == "top"
    assert face_kind("N1_up_bottom", "horizontal") == "underside"
    assert face_kind("anything", "oblique") == "oblique side"
    assert face_kind("pool floor", None) == "floor"
    assert face_kind("east wall", None) == "wall"
    assert face_kind("plinth 3", None) == "other"


def test_legend_is_one_line_per_kind_with_every_name_on_hover(qtbot):
    names, roles = _demo_faces()
    rng = np.random.default_rng(0)
    drawn = np.arange(0, len(names), 2)  # only the faces that have points are listed
    face = np.repeat(drawn, 20)
    clouds = {"laser_xyz": rng.normal(size=(face.size, 3)), "laser_face": face,
              "mbes_before_xyz": rng.normal(size=(30, 3)), "mbes_after_xyz": None,
              "mbes_face": np.r_[np.full(10, -1), np.full(20, 1)]}
    box = CloudBox()
    qtbot.addWidget(box)
    box.resize(700, 420)
    box.show()
    box.draw(names, clouds, roles)
    doc = QTextDocument()
    doc.setHtml(box.legend.text())
    legend = doc.toPlainText()
    shown = sorted({face_kind(names[k], str(roles[k])) for k in np.union1d(drawn, [1])})
    assert all(kind in legend for kind in shown) and "(12)" in legend
    assert not any(name in legend for name in names[1:])  # no 40-entry list
    assert all(names[k] in box.legend.toolTip() for k in drawn)
    # Colours: the kind's hue, one shade per neighbour; the face table reads the same.
    assert face_colour(0) == KIND_SHADES["wall"][0]
    assert face_colour(1) == KIND_SHADES["perpendicular side"][0]
    assert face_colour(5) == KIND_SHADES["perpendicular side"][1]
    assert face_colour(-1) != face_colour(0)
    assert box.stack.minimumHeight() == VIEW_MIN_HEIGHT
    qtbot.wait(50)  # the layout takes the new text on the next pass
    assert box.legend.heightForWidth(box.legend.width()) <= box.legend.height()


def test_legend_kinds_follow_the_language(qtbot, settings):
    from hydrosync_gui import i18n

    names, roles = _demo_faces()
    face = np.arange(len(names))
    clouds = {"laser_xyz": np.zeros((face.size, 3)), "laser_face": face,
              "mbes_before_xyz": np.zeros((0, 3)), "mbes_after_xyz": None,
              "mbes_face": np.zeros(0, int)}
    box = CloudBox()
    qtbot.addWidget(box)
    i18n.set_language("zh_CN", settings)
    try:
        box.draw(names, clouds, roles)
        box.show()
        qtbot.wait(20)
        text = box.legend.text()
        assert "斜侧面" in text and "顶面" in text and "底面" in text
        assert "三角形" in text  # the note after the kinds, by the shell's relabelling
    finally:
        i18n.set_language("en", settings)
