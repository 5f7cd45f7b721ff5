"""Small reusable widgets for the shell and the plugin panels.

- :class:`ParamForm` — the form of an analysis's parameter schema
  (:mod:`hydrosync_core.params`), with labels, units, ranges, tooltips, optional values,
  groups and a collapsed "Advanced" section; ``params()`` returns the validated instance
  to pass to a core ``run``.
- :class:`ColumnsTable` — a read-only table view fed from a dict of equal-length 1-D
  arrays (a project table, ``Project.get_table``); cheap for millions of rows because
  cells are formatted on demand.
"""

from hydrosync_gui.widgets.columns_table import ColumnsTable, ColumnsTableModel
from hydrosync_gui.widgets.param_form import ParamForm

__all__ = ["ColumnsTable", "ColumnsTableModel", "ParamForm"]
