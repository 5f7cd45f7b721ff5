"""Small reusable widgets for the shell and the plugin panels.

- :class:`ParamForm` — a form editing a flat ``dict`` of parameters (float / int / bool /
  str / choice), with labels, units, ranges and tooltips; ``values()`` returns the dict to
  pass to a core ``run``.
- :class:`ColumnsTable` — a read-only table view fed from a dict of equal-length 1-D
  arrays (a project table, ``Project.get_table``); cheap for millions of rows because
  cells are formatted on demand.
"""

from hydrosync_gui.widgets.columns_table import ColumnsTable, ColumnsTableModel
from hydrosync_gui.widgets.param_form import ParamField, ParamForm

__all__ = ["ColumnsTable", "ColumnsTableModel", "ParamField", "ParamForm"]
