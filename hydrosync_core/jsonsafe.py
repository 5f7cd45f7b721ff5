"""One conversion to plain JSON types for results, stored attributes and result.json."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def jsonable(obj: Any) -> Any:
    """A copy of *obj* made of JSON types only.

    numpy scalars and arrays become Python numbers and lists, tuples become lists, dict
    keys become strings, and NaN/±inf become ``None`` (JSON has no NaN; ``None`` reads
    back as "not determined").
    """
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple | np.ndarray):
        return [jsonable(v) for v in obj]
    if isinstance(obj, bool | np.bool_):
        return bool(obj)
    if isinstance(obj, int | np.integer):
        return int(obj)
    if isinstance(obj, float | np.floating):
        return float(obj) if math.isfinite(obj) else None
    return obj
