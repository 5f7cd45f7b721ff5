"""Guard against a Qt binding that corrupts reference counts (seen with PySide6 6.12.0).

On Python 3.11 (``None``/``True``/``False`` not yet immortal) shiboken6 6.12.0 returns
``None`` from every void method without a new reference, and ``Signal.emit`` returns
``True`` the same way: after a few thousand calls the interpreter aborts ("Fatal Python error:
none_dealloc" / "bool_dealloc"), typically at exit or in a long session. PySide6 6.11.3
does not. On Python >= 3.12 the counts never move, so this test passes trivially.
"""

from __future__ import annotations

import sys

from PySide6.QtCore import QObject, Signal
from PySide6.QtWidgets import QLabel

CALLS = 200
_COMPENSATION: list = []  # references given back so this test cannot abort the run itself


class _Emitter(QObject):
    sig = Signal(bool)


def _drift(obj, fn) -> int:
    before = sys.getrefcount(obj)
    for _ in range(CALLS):
        fn()
    drift = sys.getrefcount(obj) - before
    _COMPENSATION.extend([obj] * max(0, -drift))
    return drift


def test_void_methods_keep_the_reference_count_of_none(qtbot):
    label = QLabel()
    qtbot.addWidget(label)
    assert abs(_drift(None, lambda: label.setText("x"))) < CALLS // 2


def test_signal_emit_keeps_the_reference_count_of_true(qtbot):
    emitter = _Emitter()
    assert abs(_drift(True, lambda: emitter.sig.emit(False))) < CALLS // 2
