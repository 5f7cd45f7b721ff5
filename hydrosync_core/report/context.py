"""What a plugin's report section receives: styles, page width and flowable helpers.

A section is ``section(project, ctx: ReportContext) -> list[Flowable]``. It builds its
heading, paragraphs, tables and figures through *ctx* so every section looks the same
and tables split across pages with their header row repeated.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime

from reportlab.graphics.shapes import Drawing, Group
from reportlab.lib.enums import TA_RIGHT
from reportlab.lib.styles import ParagraphStyle
from reportlab.platypus import (
    Flowable,
    LongTable,
    Paragraph,
    Spacer,
    TableStyle,
)
from reportlab.platypus.flowables import HRFlowable

from hydrosync_core.i18n import language, tr
from hydrosync_core.report.charts import Chart
from hydrosync_core.report.colwidths import cell_need, fit_widths, shrink_factor
from hydrosync_core.report.styles import FONT, FONT_BOLD, RULE, stylesheet, table_style


class Figure(Flowable):
    """A drawing and its caption as one unsplittable flowable.

    Not a ``KeepTogether``: reportlab does not chain a heading's ``keepWithNext`` onto a
    container, which left headings alone at the foot of a page above their figure.
    """

    def __init__(self, drawing, caption: Paragraph, space_before: float = 4.0) -> None:
        super().__init__()
        self.drawing = drawing
        self.caption = caption
        self.space_before = space_before
        self._cap_h = 0.0

    def wrap(self, avail_width, avail_height):
        _, self._cap_h = self.caption.wrap(avail_width, avail_height)
        self.width = avail_width
        self.height = self.space_before + self.drawing.height + self._cap_h
        return self.width, self.height

    def getSpaceAfter(self) -> float:  # noqa: N802 (reportlab API)
        return self.caption.getSpaceAfter()

    def draw(self) -> None:
        self.caption.drawOn(self.canv, 0, 0)
        self.drawing.drawOn(self.canv, 0, self._cap_h)


def _translated_cell(cell):
    """A table cell in the report's language: text and Paragraphs through the catalogue
    (numbers have no entry and pass unchanged); other flowables as they are."""
    if isinstance(cell, Paragraph):
        source = getattr(cell, "text", None)
        if isinstance(source, str) and tr(source) != source:
            return Paragraph(tr(source), cell.style)
        return cell
    return cell if isinstance(cell, Flowable) else tr(str(cell))


class ReportTable(LongTable):
    """A long table that never leaves a single row alone at the top of the next page.

    reportlab splits at the last row that fits: a correlation table's last row ("lever_z")
    went over to the next page alone, under a repeated header. Here one more row goes
    with it when the first part keeps at least :attr:`MIN_ROWS` of its own.
    """

    MIN_ROWS = 2

    def split(self, availWidth, availHeight):  # noqa: N803 (reportlab API)
        parts = super().split(availWidth, availHeight)
        if len(parts) != 2:
            return parts
        first, rest = parts
        header = self.repeatRows if isinstance(self.repeatRows, int) else len(self.repeatRows)
        kept = len(first._cellvalues) - header
        if len(rest._cellvalues) - header >= self.MIN_ROWS or kept <= self.MIN_ROWS:
            return parts
        last = self._rowHeights[len(first._cellvalues) - 1]
        return super().split(availWidth, availHeight - last - 0.5)


def markup(text: str) -> str:
    """Give ``<sub>`` a small drop: reportlab's default (half the font size) makes the
    subscript touch the next line."""
    return str(text).replace("<sub>", '<sub rise="2" size="7">')


def esc(text) -> str:
    """Escape text for a reportlab Paragraph (which parses a small XML subset)."""
    return str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def fmt(value, decimals: int = 3, unit: str = "") -> str:
    """Fixed-decimal number with an optional unit; ``"—"`` for missing/non-finite values.

    The minus sign is ASCII so that text extracted from the PDF parses as a number.
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        return "\u2014"
    if not math.isfinite(number):
        return "\u2014"
    text = f"{number:.{decimals}f}"
    if text.strip("-0.") == "":
        text = text.lstrip("-")  # no "-0.000"
    return _with_unit(text, unit)


def _with_unit(text: str, unit: str) -> str:
    """Append *unit* after a space, except the degree sign which is written closed up."""
    if not unit:
        return text
    return f"{text}{unit}" if unit == "\u00b0" else f"{text} {unit}"


def utc_text(iso) -> str:
    """``"2026-11-22 04:40:23 UTC"`` from an ISO 8601 time stamp (as stored in the project)."""
    try:
        stamp = datetime.fromisoformat(str(iso))
    except ValueError:
        return str(iso or "?")
    if stamp.tzinfo is not None:
        stamp = stamp.astimezone(UTC)
    return stamp.strftime("%Y-%m-%d %H:%M:%S UTC")


def fmt_pm(value, sigma, decimals: int = 3, unit: str = "") -> str:
    """``value ± sigma unit`` (sigma omitted when missing)."""
    main = fmt(value, decimals)
    if fmt(sigma, decimals) != "\u2014":
        main += f" \u00b1 {fmt(sigma, decimals)}"
    return _with_unit(main, unit)


@dataclass
class ReportContext:
    """Shared state and helpers for building report sections.

    Attributes
    ----------
    width : float
        Usable frame width in points.
    styles : StyleSheet1
        Paragraph styles: ``Body``, ``Small``, ``Caption``, ``H1``, ``H2``, ``Cell``, ``Warning``.
    figure_count, table_count : int
        Running numbers for captions ("Figure 3", "Table 2").
    """

    width: float
    styles: object = field(default_factory=lambda: stylesheet(cjk=language() == "zh_CN"))
    figure_count: int = 0
    table_count: int = 0

    # ------------------------------------------------------------------ text
    def heading(self, text: str, level: int = 1) -> Paragraph:
        """A section (level 1) or sub-section (level 2) heading; appears in the outline."""
        return Paragraph(esc(tr(text)), self.styles["H1" if level == 1 else "H2"])

    def para(self, text: str, style: str = "Body") -> Paragraph:
        """A paragraph; *text* may use reportlab mark-up (``<b>``, ``<i>``, ``<sub>``)."""
        return Paragraph(markup(tr(text)), self.styles[style])

    def warning(self, text: str) -> Paragraph:
        return Paragraph(f"<b>{tr('Warning:')}</b> {esc(tr(text))}", self.styles["Warning"])

    def rule(self) -> HRFlowable:
        return HRFlowable(width="100%", thickness=0.5, color=RULE, spaceBefore=2, spaceAfter=6)

    # ------------------------------------------------------------------ tables
    def table(
        self,
        header: Sequence[str],
        rows: Sequence[Sequence],
        *,
        col_widths: Sequence[float] | None = None,
        numeric_from: int = 1,
        caption: str | None = None,
        highlight_rows: Sequence[int] = (),
        extra_style: Sequence[tuple] = (),
        zebra: bool = True,
        font_size: float = 8.5,
        left_columns: Sequence[int] = (),
    ) -> list[Flowable]:
        """A table whose header row repeats on each page, with an optional caption above.

        Parameters
        ----------
        header : sequence of str
            Column titles (units in brackets), reportlab mark-up allowed
            (``R<sub>max</sub>``); wrapped in Paragraphs so long titles break.
        rows : sequence of sequences
            Cell values: str (already formatted) or Flowable.
        col_widths : sequence of float, optional
            Fractions of the frame width (summing to <= 1) or None for equal widths.
        numeric_from : int
            Columns from this index on are right-aligned.
        highlight_rows : sequence of int
            Body row indices (0-based) printed in bold (e.g. the combined result).
        left_columns : sequence of int
            Text columns at or after *numeric_from* that stay left-aligned.
        """
        n_cols = len(header)
        fractions = col_widths or [1.0 / n_cols] * n_cols
        asked = [f * self.width for f in fractions]
        cells = [[_translated_cell(c if isinstance(c, Flowable) else str(c)) for c in r]
                 for r in rows]
        head, needs = self._head_and_needs(header, cells, font_size, numeric_from,
                                           left_columns, highlight_rows)
        factor = shrink_factor(sum(asked), needs)
        if factor < 1.0:  # too many words for the page: a smaller font, then fit again
            font_size = math.floor(font_size * factor * 4) / 4
            head, needs = self._head_and_needs(header, cells, font_size, numeric_from,
                                               left_columns, highlight_rows)
        widths = fit_widths(asked, needs)
        data = [head] + cells
        style = table_style(len(data), numeric_from=numeric_from, zebra=zebra,
                            font_size=font_size)
        style += [("ALIGN", (c, 0), (c, -1), "LEFT") for c in left_columns]
        for i in highlight_rows:
            style.append(("FONT", (0, i + 1), (-1, i + 1), FONT_BOLD, font_size))
        style.extend(extra_style)
        table = ReportTable(data, colWidths=widths, repeatRows=1, hAlign="LEFT")
        table.setStyle(TableStyle(style))
        out: list[Flowable] = []
        if caption:
            self.table_count += 1
            # TableCaption keeps with the table (at least its first rows).
            out.append(Paragraph(f"<b>{tr(f'Table {self.table_count}.')}</b> "
                                 f"{markup(tr(caption))}",
                                 self.styles["TableCaption"]))
        out.append(table)
        out.append(Spacer(1, 8))
        return out

    def _head_and_needs(self, header, cells, font_size, numeric_from, left_columns,
                        highlight_rows) -> tuple[list[Paragraph], list[float]]:
        """Header paragraphs at *font_size*, and the width each column needs (points,
        padding included) so that no header word breaks and no plain cell overflows."""
        head_style = self.styles["CellBold"]
        if font_size != head_style.fontSize:
            head_style = ParagraphStyle("CellBoldSmall", parent=head_style, fontSize=font_size,
                                        leading=font_size + 2)
        head_right = ParagraphStyle("CellBoldRight", parent=head_style, alignment=TA_RIGHT)
        head = [Paragraph(markup(tr(h)), head_right if i >= numeric_from and i not in left_columns
                          else head_style) for i, h in enumerate(header)]
        pad = 2 * (4 if font_size >= 8.5 else 2.5) + 1.0
        bold = set(highlight_rows)
        needs = []
        for c, title in enumerate(head):
            body = (cell_need(r[c], FONT_BOLD if i in bold else FONT, font_size)
                    for i, r in enumerate(cells) if c < len(r))
            needs.append(max(float(title.minWidth()), *body, 0.0) + pad)
        return head, needs

    def key_values(self, pairs: Sequence[tuple[str, str]], caption: str | None = None,
                   key_width: float = 0.38) -> list[Flowable]:
        """A two-column table of labelled values (no numeric alignment)."""
        rows = [[Paragraph(esc(tr(k)), self.styles["Cell"]),
                 Paragraph(esc(tr(v)), self.styles["Cell"])] for k, v in pairs]
        return self.table(["Item", "Value"], rows, col_widths=[key_width, 1 - key_width],
                          numeric_from=2, caption=caption)

    def params_table(self, params, caption: str,
                     blank: dict[str, str] | None = None) -> list[Flowable]:
        """Every processing parameter of *params* (a ``Params`` instance) with its unit.

        Labels, units and the meaning of "not set" come from the analysis's parameter
        schema, so the report lists exactly what the method was run with. A value that
        prints empty (an empty text parameter) shows ``blank[name]`` — what the analysis
        did instead — or "(empty)": a blank cell reads as a fault.
        """
        from hydrosync_core.params import describe

        blank = blank or {}
        rows = [[Paragraph(esc(tr(label)), self.styles["Cell"]),
                 Paragraph(esc(tr(value) if value.strip() else tr(blank.get(name, "(empty)"))),
                           self.styles["Cell"]),
                 Paragraph(f"<font face='Courier' size='7'>{esc(name)}</font>",
                           self.styles["Cell"])]
                for label, value, name in describe(type(params), params.to_dict())]
        return self.table(["Parameter", "Value", "Name (--param)"], rows,
                          col_widths=[0.42, 0.3, 0.28], numeric_from=3, caption=caption)

    # ------------------------------------------------------------------ figures
    def chart(self, height: float = 210.0, fraction: float = 1.0, **kwargs) -> Chart:
        """A :class:`Chart` *fraction* of the frame wide (points); call ``figure()`` with it."""
        return Chart(width=self.width * fraction, height=height, **kwargs)

    def figure(self, content, caption: str) -> Figure:
        """Figure + numbered caption kept on one page.

        *content* is a :class:`Chart`, a reportlab Drawing, or a list of Charts placed
        side by side (panels of one figure).
        """
        self.figure_count += 1
        if isinstance(content, list | tuple):
            drawing = Drawing(sum(c.width for c in content), max(c.height for c in content))
            x = 0.0
            for chart in content:
                panel = Group(*chart.drawing().contents)
                panel.translate(x, 0)
                drawing.add(panel)
                x += chart.width
        else:
            drawing = content.drawing() if isinstance(content, Chart) else content
        cap = Paragraph(f"<b>{tr(f'Figure {self.figure_count}.')}</b> {markup(tr(caption))}",
                        self.styles["Caption"])
        return Figure(drawing, cap)
