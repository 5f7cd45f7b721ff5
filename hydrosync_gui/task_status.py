"""The status-bar task indicator: progress of the running task and its Cancel button.

Tasks are keyed by whoever runs them (a plugin panel, or the shell for save / open /
import / report). The most recently started task is the *active* one: its progress is
shown and Cancel cancels it. When every task has ended the indicator hides.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from dataclasses import dataclass

from PySide6.QtCore import Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QPushButton, QWidget


@dataclass
class _Task:
    label: str
    cancel: Callable[[], None] | None
    fraction: float = 0.0
    message: str = ""


class TaskStatus(QWidget):
    """``[message] [progress bar] [Cancel]`` for the status bar."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.label = QLabel()
        self.label.setMinimumWidth(160)
        self.bar = QProgressBar()
        self.bar.setRange(0, 1000)
        self.bar.setFixedWidth(180)
        self.bar.setFormat("%p%")
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setToolTip("Cancel the running task")
        self.cancel_button.clicked.connect(self._on_cancel)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.label)
        layout.addWidget(self.bar)
        layout.addWidget(self.cancel_button)
        self._tasks: dict[Hashable, _Task] = {}
        self._show()

    # ---------------------------------------------------------------- public
    @property
    def busy(self) -> bool:
        return bool(self._tasks)

    def active(self) -> Hashable | None:
        """Key of the task whose progress is shown (the last started), or None."""
        return next(reversed(self._tasks), None)

    def begin(self, key: Hashable, label: str, cancel: Callable[[], None] | None = None) -> None:
        """A task started; *cancel* (if given) is what the Cancel button calls."""
        self._tasks.pop(key, None)
        self._tasks[key] = _Task(label, cancel)
        self._show()

    def update(self, key: Hashable, fraction: float, message: str = "") -> None:
        task = self._tasks.get(key)
        if task is None:
            return
        task.fraction = min(1.0, max(0.0, fraction))
        task.message = message
        if key == self.active():
            self._show()

    def end(self, key: Hashable) -> None:
        self._tasks.pop(key, None)
        self._show()

    # --------------------------------------------------------------- private
    def _show(self) -> None:
        key = self.active()
        self.setVisible(key is not None)
        if key is None:
            return
        task = self._tasks[key]
        text = f"{task.label}: {task.message}" if task.message else task.label
        self.label.setText(text)
        self.label.setToolTip(text)
        self.bar.setValue(round(task.fraction * 1000))
        self.cancel_button.setEnabled(task.cancel is not None)

    @Slot()
    def _on_cancel(self) -> None:
        key = self.active()
        if key is None:
            return
        task = self._tasks[key]
        if task.cancel is not None:
            task.message = "cancelling…"
            self.cancel_button.setEnabled(False)
            self.label.setText(f"{task.label}: cancelling…")
            task.cancel()
