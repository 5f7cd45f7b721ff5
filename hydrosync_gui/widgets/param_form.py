"""A form editing a flat dict of parameters, for the plugin panels.

Example
-------
>>> form = ParamForm([
...     ParamField("max_lag", "Max lag", 1.0, unit="s", minimum=0.01, maximum=10, decimals=3),
...     ParamField("window", "Window", 60, unit="s", minimum=1, maximum=3600),
...     ParamField("detrend", "Detrend heights", True),
...     ParamField("method", "Method", "xcorr", choices=("xcorr", "lsq")),
... ])
>>> form.values()
{'max_lag': 1.0, 'window': 60, 'detrend': True, 'method': 'xcorr'}

The editor follows the type of the default (float → spin box with *decimals*, int →
integer spin box, bool → check box, str → line edit, or a combo box if *choices* given).
Values are in the units shown to the user (degrees, seconds, metres); convert to radians
inside the core, not here. :attr:`ParamForm.sig_changed` fires after any edit.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from PySide6.QtCore import Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QLineEdit,
    QSpinBox,
    QWidget,
)


@dataclass(frozen=True)
class ParamField:
    """One parameter: key in the params dict, label, default and editor hints."""

    name: str
    label: str
    default: Any
    unit: str = ""
    minimum: float | None = None
    maximum: float | None = None
    decimals: int = 3
    step: float | None = None
    choices: tuple[str, ...] = ()
    tooltip: str = ""


class ParamForm(QWidget):
    """Editors for a list of :class:`ParamField`; :meth:`values` returns the dict."""

    sig_changed = Signal()

    def __init__(self, fields: Iterable[ParamField], parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.fields = {f.name: f for f in fields}
        self.editors: dict[str, QWidget] = {}
        layout = QFormLayout(self)
        layout.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
        for f in self.fields.values():
            editor = self._make_editor(f)
            editor.setToolTip(f.tooltip)
            editor.setObjectName(f"param_{f.name}")
            self.editors[f.name] = editor
            label = "" if isinstance(editor, QCheckBox) else f"{f.label}:"
            layout.addRow(label, editor)

    @classmethod
    def from_defaults(cls, defaults: Mapping[str, Any], parent: QWidget | None = None):
        """A form for a plugin's ``default_params`` (labels from the keys)."""
        fields = [ParamField(k, k.replace("_", " ").capitalize(), v) for k, v in defaults.items()]
        return cls(fields, parent)

    def _make_editor(self, f: ParamField) -> QWidget:
        value = f.default
        if f.choices:
            box = QComboBox()
            box.addItems(list(f.choices))
            box.setCurrentText(str(value))
            box.currentTextChanged.connect(self.sig_changed)
            return box
        if isinstance(value, bool):
            check = QCheckBox(f.label)
            check.setChecked(value)
            check.toggled.connect(self.sig_changed)
            return check
        if isinstance(value, int):
            spin = QSpinBox()
            spin.setRange(int(f.minimum if f.minimum is not None else -2**31),
                          int(f.maximum if f.maximum is not None else 2**31 - 1))
            spin.setValue(value)
            if f.step:
                spin.setSingleStep(int(f.step))
            if f.unit:
                spin.setSuffix(f" {f.unit}")
            spin.valueChanged.connect(self.sig_changed)
            return spin
        if isinstance(value, float):
            dspin = QDoubleSpinBox()
            dspin.setDecimals(f.decimals)
            dspin.setRange(f.minimum if f.minimum is not None else -1e12,
                           f.maximum if f.maximum is not None else 1e12)
            dspin.setValue(value)
            dspin.setSingleStep(f.step or 10 ** -max(f.decimals - 1, 0))
            if f.unit:
                dspin.setSuffix(f" {f.unit}")
            dspin.valueChanged.connect(self.sig_changed)
            return dspin
        line = QLineEdit(str(value))
        line.textChanged.connect(self.sig_changed)
        return line

    def values(self) -> dict[str, Any]:
        """The current values, typed like the defaults."""
        out: dict[str, Any] = {}
        for name, editor in self.editors.items():
            if isinstance(editor, QComboBox):
                out[name] = editor.currentText()
            elif isinstance(editor, QCheckBox):
                out[name] = editor.isChecked()
            elif isinstance(editor, QSpinBox | QDoubleSpinBox):
                out[name] = editor.value()
            else:
                assert isinstance(editor, QLineEdit)
                out[name] = editor.text()
        return out

    def set_values(self, values: Mapping[str, Any]) -> None:
        """Set the editors named in *values* (unknown keys are ignored)."""
        for name, value in values.items():
            editor = self.editors.get(name)
            if isinstance(editor, QComboBox):
                editor.setCurrentText(str(value))
            elif isinstance(editor, QCheckBox):
                editor.setChecked(bool(value))
            elif isinstance(editor, QSpinBox):
                editor.setValue(int(value))
            elif isinstance(editor, QDoubleSpinBox):
                editor.setValue(float(value))
            elif isinstance(editor, QLineEdit):
                editor.setText(str(value))
