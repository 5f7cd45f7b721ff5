"""Column widths that fit what the columns hold.

A section asks for column widths as fractions of the page; the words it then puts in
them did not always fit: a header broke mid-word ("Patent metho/d") and a plain-text cell
("N1_up_perpendicular") ran into its neighbour. :func:`fit_widths` keeps the asked-for
widths where they are wide enough and moves room from columns with slack to the ones
that need it; when the page cannot hold every column's need, :func:`shrink_factor`
tells the table by how much to reduce its font.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from reportlab.pdfbase.pdfmetrics import stringWidth
from reportlab.platypus import Flowable, Paragraph


def cell_need(cell, font: str, size: float) -> float:
    """The narrowest width (points, padding excluded) *cell* can be drawn in unbroken.

    A plain string is drawn on one line by the table (its full width, the widest line
    if it holds new-lines); a Paragraph wraps at spaces (its longest word); other
    flowables are left to their own wrapping (0).
    """
    if isinstance(cell, Paragraph):
        return float(cell.minWidth())
    if isinstance(cell, Flowable):
        return 0.0
    text = str(cell)
    return max((stringWidth(line, font, size) for line in text.split("\n")), default=0.0)


def fit_widths(widths: Sequence[float], needs: Sequence[float]) -> list[float]:
    """Widths of the same total where each column gets at least its need, if possible.

    Parameters
    ----------
    widths : sequence of float
        The asked-for widths (points).
    needs : sequence of float
        The smallest width each column's content fits in (points, padding included).

    Returns
    -------
    list of float
        Unchanged when every column fits. Otherwise columns short of their need grow to it
        and the others give up room in proportion to their slack (never below their own
        need). If the needs exceed the total, every column gets the total shared in
        proportion to its need (the caller shrinks the font, :func:`shrink_factor`).
    """
    w = np.asarray(widths, float)
    need = np.minimum(np.asarray(needs, float), np.inf)
    total = float(w.sum())
    short = np.clip(need - w, 0.0, None)
    if not short.any():
        return w.tolist()
    if need.sum() >= total:
        return (need / need.sum() * total).tolist()
    slack = np.clip(w - need, 0.0, None)
    out = np.maximum(w, need)
    out -= slack / slack.sum() * short.sum()
    return out.tolist()


def shrink_factor(total: float, needs: Sequence[float], floor: float = 0.75) -> float:
    """By how much to reduce the font so that *needs* fit *total* (1.0: they fit).

    Never below *floor* (a smaller font than 3/4 of the section's is not readable in
    print); the few words still too long then break.
    """
    need = float(np.sum(needs))
    if need <= total or need <= 0:
        return 1.0
    return max(floor, total / need)
