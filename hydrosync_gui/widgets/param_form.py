"""A form editing an analysis's parameters, built from its parameter schema.

Example
-------
>>> form = ParamForm(LatencyParams)          # one editor per field, defaults shown
>>> form.params()                            # a validated LatencyParams
>>> form.set_params(stored_params)           # e.g. the parameters of the stored result

Everything the user sees comes from the schema (:mod:`hydrosync_core.params`): labels,
units (as spin-box suffixes), ranges, help (tooltips) and defaults. The editor follows the
field's type: float → spin box with the declared decimals, int → integer spin box, bool →
check box, str → combo box of its choices (line edit without), tuple → one spin box per
element. An optional field (``… | None``) gets a check box in front: unticked means
"not set", whose meaning (``none_label``, e.g. "vessel sheet") is shown beside it.
Fields of a named ``group`` go into a group box, ``advanced`` ones into a collapsed
"Advanced" section, so panels stay short on a laptop screen. Values are in the units
shown to the user (degrees, seconds, metres); the core converts to radians.
:attr:`ParamForm.sig_changed` fires after any edit.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from PySide6.QtCore import QSize, Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QSpinBox,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.params import FieldInfo, Params


def _tooltip(info: FieldInfo) -> str:
    text = info.meta.help or info.meta.label
    return f"{text}\n\nDefault: {info.describe_value(info.default)}  (--param {info.name})"


class _Editor(QWidget):
    """The editor of one field: get/set a typed value, None for an unset optional."""

    sig_changed = Signal()

    def __init__(self, info: FieldInfo, choice_labels: Mapping[str, str] | None = None) -> None:
        super().__init__()
        self.info = info
        self.choice_labels = dict(choice_labels or {})
        layout = QHBoxLayout()
        layout.setContentsMargins(0, 0, 0, 0)
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.setSpacing(2)
        outer.addLayout(layout)
        self.enable: QCheckBox | None = None
        if info.optional:
            self.enable = QCheckBox()
            self.enable.setToolTip(f"tick to set; unticked: {info.meta.none_label or 'not set'}")
            self.enable.toggled.connect(self._on_enable)
            layout.addWidget(self.enable)
        self.parts = self._make_parts(info)
        for part in self.parts:
            layout.addWidget(part, 1)
        self.unset_label: QLabel | None = None
        if info.optional:
            self.unset_label = QLabel(info.meta.none_label or "not set")
            self.unset_label.setStyleSheet("color: palette(mid);")
            # Wrapped, so that a long note ("vessel sheet (gnss − motion)") does not set the
            # form's minimum width: the panel's plots and tables need that room. Under the
            # boxes of a tuple (beside three of them it wrapped into a narrow column).
            self.unset_label.setWordWrap(True)
            if info.kind == "tuple":
                outer.addWidget(self.unset_label)
            else:
                layout.addWidget(self.unset_label, 1)
        self.setToolTip(_tooltip(info))
        self.set_value(info.default)

    def _spin(self, kind: str) -> QWidget:
        m = self.info.meta
        if kind == "int":
            spin = QSpinBox()
            spin.setRange(int(m.minimum if m.minimum is not None else -(2**31)),
                          int(m.maximum if m.maximum is not None else 2**31 - 1))
            if m.step:
                spin.setSingleStep(int(m.step))
            spin.valueChanged.connect(self.sig_changed)
        else:
            spin = QDoubleSpinBox()
            spin.setDecimals(m.decimals)
            tick = 10.0 ** -m.decimals
            low = m.minimum if m.minimum is not None else -1e12
            high = m.maximum if m.maximum is not None else 1e12
            spin.setRange(low + (tick if m.min_exclusive else 0.0),
                          high - (tick if m.max_exclusive else 0.0))
            spin.setSingleStep(m.step or 10.0 ** -max(m.decimals - 1, 0))
            spin.valueChanged.connect(self.sig_changed)
        if m.unit:
            spin.setSuffix(f" {m.unit}")
        # An unbounded range sizes the box for "-1000000000000.000": three of them (a
        # tuple) pushed the form wider than its column and forced a horizontal scroll bar.
        sample = "−000." + "0" * m.decimals if kind == "float" else "−00000"
        digits = spin.fontMetrics().horizontalAdvance(sample)
        spin.setMinimumWidth(min(spin.minimumSizeHint().width(), digits + 20))
        return spin

    def _make_parts(self, info: FieldInfo) -> list[QWidget]:
        if info.kind == "tuple":
            return [self._spin("float") for _ in range(info.length)]
        if info.kind in ("float", "int"):
            return [self._spin(info.kind)]
        if info.kind == "bool":
            check = QCheckBox(info.meta.label)
            check.toggled.connect(self.sig_changed)
            return [check]
        if info.meta.choices:
            box = QComboBox()
            # The surveyor reads the label ("least squares"); the value stays the key.
            for choice in info.meta.choices:
                box.addItem(self.choice_labels.get(choice, choice), choice)
            box.currentIndexChanged.connect(self.sig_changed)
            return [box]
        line = QLineEdit()
        line.textChanged.connect(self.sig_changed)
        return [line]

    def _on_enable(self, on: bool) -> None:
        for part in self.parts:
            part.setEnabled(on)
        if self.unset_label is not None:
            self.unset_label.setVisible(not on)
        self.sig_changed.emit()

    def value(self) -> Any:
        if self.enable is not None and not self.enable.isChecked():
            return None
        values = []
        for part in self.parts:
            if isinstance(part, QComboBox):
                data = part.currentData()
                values.append(data if data is not None else part.currentText())
            elif isinstance(part, QCheckBox):
                values.append(part.isChecked())
            elif isinstance(part, QSpinBox | QDoubleSpinBox):
                values.append(part.value())
            else:
                values.append(part.text())
        return tuple(values) if self.info.kind == "tuple" else values[0]

    def set_shown(self, value: Any) -> None:
        """Show *value* in the editors without changing whether the field is set."""
        if value is None:
            return
        values = list(value) if self.info.kind == "tuple" else [value]
        for part, v in zip(self.parts, values, strict=False):
            if isinstance(part, QComboBox):
                index = part.findData(str(v))
                if index >= 0:
                    part.setCurrentIndex(index)
                else:
                    part.setCurrentText(str(v))
            elif isinstance(part, QCheckBox):
                part.setChecked(bool(v))
            elif isinstance(part, QSpinBox):
                part.setValue(int(v))
            elif isinstance(part, QDoubleSpinBox):
                part.setValue(float(v))
            else:
                part.setText(str(v))

    def set_value(self, value: Any) -> None:
        self.set_shown(value)
        if self.enable is not None:
            self.enable.setChecked(value is not None)
            self._on_enable(value is not None)


def _form(parent: QWidget | None = None) -> QFormLayout:
    """A form layout; :class:`ParamForm` decides whether its rows wrap (all or none)."""
    form = QFormLayout(parent)
    form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
    form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.DontWrapRows)
    return form


def _row_widths(form: QFormLayout) -> tuple[list[int], list[int]]:
    labels, fields = [0], [0]
    for row in range(form.rowCount()):
        label = form.itemAt(row, QFormLayout.ItemRole.LabelRole)
        field = form.itemAt(row, QFormLayout.ItemRole.FieldRole)
        if label is not None and label.widget() is not None and label.widget().text():
            labels.append(label.widget().sizeHint().width())
        if field is not None and field.widget() is not None:
            fields.append(field.widget().minimumSizeHint().width())
    return labels, fields


def stacked_width(form: QFormLayout) -> int:
    """Pixels *form* needs with every field under its label (margins included)."""
    labels, fields = _row_widths(form)
    margins = form.contentsMargins()
    return max(max(labels), max(fields)) + margins.left() + margins.right()


def side_by_side_width(form: QFormLayout) -> int:
    """Pixels *form* needs to put every field beside its label (margins included)."""
    labels, fields = _row_widths(form)
    margins = form.contentsMargins()
    spacing = max(form.horizontalSpacing(), 0) if max(labels) else 0
    return max(labels) + spacing + max(fields) + margins.left() + margins.right()


class ParamForm(QWidget):
    """Editors for every field of a :class:`~hydrosync_core.params.Params` schema.

    *choice_labels* ``{field: {value: label}}``: what a choice box shows for each value
    (the words of the panel and PDF, "least squares" for ``lsq``); the value is still
    what :meth:`values` returns.
    """

    sig_changed = Signal()

    def __init__(self, schema: type[Params], parent: QWidget | None = None,
                 choice_labels: Mapping[str, Mapping[str, str]] | None = None) -> None:
        super().__init__(parent)
        self.schema = schema
        choice_labels = choice_labels or {}
        self.editors: dict[str, _Editor] = {}
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        main = _form()
        outer.addLayout(main)
        groups: dict[str, QFormLayout] = {}
        advanced = QWidget()
        advanced_layout = QVBoxLayout(advanced)
        advanced_layout.setContentsMargins(0, 0, 0, 0)
        advanced_form = _form()
        advanced_layout.addLayout(advanced_form)
        for info in schema.schema():
            editor = _Editor(info, choice_labels.get(info.name))
            editor.setObjectName(f"param_{info.name}")
            editor.sig_changed.connect(self.sig_changed)
            self.editors[info.name] = editor
            label = "" if info.kind == "bool" else f"{info.meta.label}:"
            if info.meta.advanced:
                advanced_form.addRow(label, editor)
            elif info.meta.group:
                if info.meta.group not in groups:
                    box = QGroupBox(info.meta.group)
                    groups[info.meta.group] = _form(box)
                    outer.addWidget(box)
                groups[info.meta.group].addRow(label, editor)
            else:
                main.addRow(label, editor)
        self.forms = [main, *groups.values(), advanced_form]
        self.wrapped = False
        self.advanced = advanced
        self.advanced_button = QToolButton()
        self.advanced_button.setObjectName("advanced_toggle")
        self.advanced_button.setText("Advanced")
        self.advanced_button.setCheckable(True)
        self.advanced_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.advanced_button.setArrowType(Qt.ArrowType.RightArrow)
        self.advanced_button.toggled.connect(self._on_advanced)
        if advanced_form.rowCount():
            outer.addWidget(self.advanced_button)
            outer.addWidget(advanced)
        else:
            self.advanced_button.hide()
        advanced.setVisible(False)

    def minimumSizeHint(self) -> QSize:  # noqa: N802 - Qt override
        """As narrow as the form is with every field under its label, so that the column
        holding it may be narrower than label + field side by side: the form then wraps
        its rows (:meth:`fit_rows`) instead of pushing a horizontal scroll bar."""
        hint = super().minimumSizeHint()
        narrow = 0
        for form in self.forms:
            laid_out = form.geometry().width()
            extra = max(self.width() - laid_out, 0) if laid_out > 0 else 0
            narrow = max(narrow, stacked_width(form) + extra)
        return QSize(min(hint.width(), narrow) if narrow else hint.width(), hint.height())

    def resizeEvent(self, event) -> None:  # noqa: N802 - Qt override
        """Wrap all rows (field under label) or none: row by row, a narrow column mixed
        fields beside and under their labels, which reads as a misaligned form."""
        super().resizeEvent(event)
        self.fit_rows(event.size().width())

    def showEvent(self, event) -> None:  # noqa: N802 - Qt override
        # Before the first show the labels are not polished and measure narrower.
        super().showEvent(event)
        self.fit_rows(self.width())

    def fit_rows(self, width: int) -> bool:
        """Put every field under its label if any row does not fit *width* pixels beside
        its label, else every field beside it; return whether the rows are wrapped."""
        need = 0
        for form in self.forms:
            # A group box's frame and margins come on top of its form's own need.
            laid_out = form.geometry().width()
            extra = self.width() - laid_out if laid_out > 0 else 0
            need = max(need, side_by_side_width(form) + max(extra, 0))
        wrap = need > width
        if wrap != self.wrapped:
            self.wrapped = wrap
            policy = (QFormLayout.RowWrapPolicy.WrapAllRows if wrap
                      else QFormLayout.RowWrapPolicy.DontWrapRows)
            for form in self.forms:
                form.setRowWrapPolicy(policy)
        return wrap

    def _on_advanced(self, shown: bool) -> None:
        self.advanced.setVisible(shown)
        self.advanced_button.setArrowType(Qt.ArrowType.DownArrow if shown
                                          else Qt.ArrowType.RightArrow)

    def values(self) -> dict[str, Any]:
        """The current values, typed like the schema's fields (None = not set)."""
        return {name: editor.value() for name, editor in self.editors.items()}

    def params(self) -> Params:
        """The current values as a validated schema instance (raises ``InputError``)."""
        return self.schema.from_dict(self.values())

    def set_params(self, values: Params | Mapping[str, Any]) -> None:
        """Show *values* (an instance or a dict; unknown keys are ignored)."""
        if isinstance(values, Params):
            values = values.to_dict()
        for name, value in values.items():
            if name in self.editors:
                self.editors[name].set_value(value)

    def show_unset(self, name: str, value: Any) -> None:
        """For an optional field that is not set, show the value that will be used."""
        editor = self.editors[name]
        if editor.value() is None:
            editor.set_shown(value)
