"""Page layout: A4 portrait, a cover page, running header and "page N of M" footer.

"Page N of M" needs M before any page is final. :class:`NumberedCanvas` keeps each
page's drawing state and paints the footers at save time, when the page count is known
(the standard reportlab recipe); this avoids a second layout pass just for M.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from reportlab.lib.pagesizes import A4
from reportlab.lib.units import mm
from reportlab.pdfbase.pdfmetrics import stringWidth
from reportlab.pdfgen import canvas as rl_canvas
from reportlab.platypus import BaseDocTemplate, Frame, KeepTogether, PageTemplate, Paragraph, Table

from hydrosync_core.i18n import tr
from hydrosync_core.progress import check_cancel, report
from hydrosync_core.report.styles import ACCENT, FONT, MUTED, PAGE_MARGIN, RULE


def fit_text(text: str, width: float, font: str, size: float) -> str:
    """*text* cut at a word boundary with "…" so that it fits *width* points.

    A long project name was cut at a fixed number of characters, mid-word, in the running
    header and footer.
    """
    if stringWidth(text, font, size) <= width:
        return text
    words = text.split(" ")
    while len(words) > 1:
        words.pop()
        candidate = " ".join(words).rstrip(" \u2014-,;:") + " \u2026"
        if stringWidth(candidate, font, size) <= width:
            return candidate
    # One word longer than the line: cut it (rare: a path without spaces).
    cut = text
    while cut and stringWidth(cut + "\u2026", font, size) > width:
        cut = cut[:-1]
    return cut + "\u2026"


class NumberedCanvas(rl_canvas.Canvas):
    """A canvas that writes "page N of M" on every page once M is known.

    The document template sets :attr:`footer_left` and :attr:`header_text` on the canvas
    class before the build (they are the same for every page).
    """

    footer_left = ""
    header_text = ""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._saved_pages: list[dict] = []

    def showPage(self) -> None:  # noqa: N802 (reportlab API)
        self._saved_pages.append(dict(self.__dict__))
        self._startPage()

    def save(self) -> None:
        total = len(self._saved_pages)
        for state in self._saved_pages:
            self.__dict__.update(state)
            self._draw_running_text(total)
            super().showPage()
        super().save()

    def _draw_running_text(self, total: int) -> None:
        width, height = self._pagesize
        page = self._pageNumber
        self.saveState()
        self.setFont(FONT, 8)
        self.setFillColor(MUTED)
        number = tr(f"page {page} of {total}")
        self.drawRightString(width - PAGE_MARGIN, 10 * mm, number)
        room = width - 2 * PAGE_MARGIN
        left_room = room - stringWidth(number, FONT, 8) - 12
        self.drawString(PAGE_MARGIN, 10 * mm, fit_text(self.footer_left, left_room, FONT, 8))
        if page > 1:  # the cover carries its own title block
            self.drawString(PAGE_MARGIN, height - 11 * mm,
                            fit_text(self.header_text, room, FONT, 8))
            self.setStrokeColor(RULE)
            self.setLineWidth(0.5)
            self.line(PAGE_MARGIN, height - 12.5 * mm, width - PAGE_MARGIN, height - 12.5 * mm)
        self.setStrokeColor(RULE)
        self.setLineWidth(0.5)
        self.line(PAGE_MARGIN, 13.5 * mm, width - PAGE_MARGIN, 13.5 * mm)
        self.restoreState()


class KeepWithStart(KeepTogether):
    """Keep headings and captions with the *start* of a long table, not with all of it.

    reportlab groups a ``keepWithNext`` paragraph and the next flowable into a
    KeepTogether, which moves a long (splittable) table whole to the next page and leaves
    a gap. Here only the table's first rows count towards the height that must fit.
    """

    FIRST_ROWS = 4

    def split(self, aW, aH):  # noqa: N803 (reportlab API)
        if getattr(self, "_wrapInfo", None) != (aW, aH):
            self.wrap(aW, aH)
        last = self._content[-1] if self._content else None
        heights = getattr(last, "_rowHeights", None) if isinstance(last, Table) else None
        if heights and len(heights) > self.FIRST_ROWS:
            self._H -= sum(heights) - sum(heights[: self.FIRST_ROWS])
        return super().split(aW, aH)


@dataclass
class PageLayout:
    """How full each page of a built report is, and where its sections start.

    Attributes
    ----------
    fill : list of float
        Per page (index 0 = page 1): the fraction of the body frame's height used.
    section_starts : set of int
        Pages (1-based) on which a top-level (H1) heading is placed.
    """

    fill: list[float] = field(default_factory=list)
    section_starts: set[int] = field(default_factory=set)

    def sparse_pages(self, threshold: float = 0.4) -> list[int]:
        """Pages (1-based) filled below *threshold* that do not end a section (the page
        after them starts one, or they are the last page)."""
        last = len(self.fill)
        return [page for page, used in enumerate(self.fill, 1)
                if used < threshold and page != last and page + 1 not in self.section_starts]


class ReportDocTemplate(BaseDocTemplate):
    """A4 document with one body frame; headings H1/H2 become PDF outline entries."""

    def __init__(self, filename: str, *, title: str, author: str, subject: str,
                 progress=None, cancel=None) -> None:
        super().__init__(
            filename, pagesize=A4, title=title, author=author, subject=subject,
            creator="HydroSync", leftMargin=PAGE_MARGIN, rightMargin=PAGE_MARGIN,
            topMargin=PAGE_MARGIN, bottomMargin=PAGE_MARGIN + 2 * mm,
            keepTogetherClass=KeepWithStart,
        )
        frame = Frame(self.leftMargin, self.bottomMargin, self.width, self.height, id="body",
                      leftPadding=0, rightPadding=0, topPadding=0, bottomPadding=0)
        self.addPageTemplates([PageTemplate(id="body", frames=[frame])])
        self._outline_count = 0
        self._progress = progress
        self._cancel = cancel
        self.layout = PageLayout()

    def afterPage(self) -> None:  # noqa: N802 (reportlab API)
        """Note how full the page is; let a long layout be followed and cancelled page by
        page."""
        frame = self.frame
        # reportlab takes the last flowable's spaceAfter from the cursor after checking that
        # the flowable fits, so the cursor may sit up to that space below the frame: the
        # page is full then, not over-full.
        self.layout.fill.append(min((frame._y2 - frame._y) / frame._height, 1.0))
        check_cancel(self._cancel)
        report(self._progress, 0.8, f"laying out page {self.page}")

    def afterFlowable(self, flowable) -> None:  # noqa: N802 (reportlab API)
        """Register H1/H2 headings as bookmarks and table-of-contents entries."""
        if not isinstance(flowable, Paragraph):
            return
        style = flowable.style.name
        if style not in ("H1", "H2"):
            return
        level = 0 if style == "H1" else 1
        if level == 0:
            self.layout.section_starts.add(self.page)
        text = flowable.getPlainText()
        key = f"h{self._outline_count}"
        self._outline_count += 1
        self.canv.bookmarkPage(key)
        self.canv.addOutlineEntry(text, key, level=level, closed=level > 0)
        self.notify("TOCEntry", (level, text, self.page, key))

    def handle_documentBegin(self) -> None:  # noqa: N802 (reportlab API)
        self._outline_count = 0
        self.layout = PageLayout()  # each layout pass starts again
        super().handle_documentBegin()


__all__ = ["ACCENT", "NumberedCanvas", "PageLayout", "ReportDocTemplate"]
