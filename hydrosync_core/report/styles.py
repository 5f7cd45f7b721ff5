"""Fonts, paragraph styles, colours and table styling shared by every report section.

One look for the whole document: DejaVu Sans, dark-blue headings, tables with a shaded
header row that repeats on each page. The standard PDF font Helvetica has no glyph for
Δ, σ or →, which a viewer then draws as blanks; DejaVu Sans has them and ships with
matplotlib (a HydroSync dependency), so it is embedded (subset) from there. Helvetica is
the fallback if the font files cannot be found.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
from collections.abc import Iterator

from reportlab.lib import colors
from reportlab.lib.enums import TA_CENTER, TA_LEFT
from reportlab.lib.styles import ParagraphStyle, StyleSheet1
from reportlab.lib.units import mm
from reportlab.pdfbase import pdfmetrics
from reportlab.pdfbase.ttfonts import TTFont

log = logging.getLogger(__name__)

INK = colors.HexColor("#1b1b1b")
ACCENT = colors.HexColor("#1f4e79")
MUTED = colors.HexColor("#666666")
RULE = colors.HexColor("#9aa7b4")
GRID = colors.HexColor("#e3e3e3")
HEADER_FILL = colors.HexColor("#dde6ef")
ZEBRA_FILL = colors.HexColor("#f4f6f8")
WARN_FILL = colors.HexColor("#fff4d6")
BAD_TEXT = colors.HexColor("#a32020")

# Colour cycle for plot series: colour-blind-safe (Okabe-Ito), dark enough on white paper.
SERIES = [
    colors.HexColor(c)
    for c in ("#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000",
              "#f0e442")
]

PAGE_MARGIN = 18 * mm


def _register_fonts() -> tuple[str, str]:
    """Register DejaVu Sans (regular/bold/italic) with reportlab; return (regular, bold)."""
    try:
        import matplotlib

        folder = os.path.join(matplotlib.get_data_path(), "fonts", "ttf")
        faces = {"DejaVuSans": "DejaVuSans.ttf", "DejaVuSans-Bold": "DejaVuSans-Bold.ttf",
                 "DejaVuSans-Oblique": "DejaVuSans-Oblique.ttf",
                 "DejaVuSans-BoldOblique": "DejaVuSans-BoldOblique.ttf"}
        for name, file in faces.items():
            if name not in pdfmetrics.getRegisteredFontNames():
                pdfmetrics.registerFont(TTFont(name, os.path.join(folder, file)))
        pdfmetrics.registerFontFamily("DejaVuSans", normal="DejaVuSans", bold="DejaVuSans-Bold",
                                      italic="DejaVuSans-Oblique",
                                      boldItalic="DejaVuSans-BoldOblique")
        return "DejaVuSans", "DejaVuSans-Bold"
    except Exception as exc:  # missing or unreadable font files: still produce a report
        log.warning("DejaVu Sans not available (%s); using Helvetica", exc)
        return "Helvetica", "Helvetica-Bold"


FONT, FONT_BOLD = _register_fonts()

#: Where the CJK font may be (Debian's fonts-wqy-zenhei, fonts-noto-cjk); the first found
#: is used. ``HYDROSYNC_CJK_FONT`` names another TrueType file (.ttf/.ttc).
CJK_FONT_FILES = (
    "/usr/share/fonts/truetype/wqy/wqy-zenhei.ttc",
    "/usr/share/fonts/opentype/noto/NotoSansCJK-Regular.ttc",
    "/usr/share/fonts/truetype/noto/NotoSansCJK-Regular.ttc",
)
_FONT_SWAP = threading.Lock()


def cjk_font_file() -> str:
    """The TrueType file used for Chinese text.

    Raises
    ------
    hydrosync_core.errors.InputError
        No CJK font is installed (one line that says which package to install).
    """
    from hydrosync_core.errors import InputError

    wanted = os.environ.get("HYDROSYNC_CJK_FONT")
    for path in ((wanted,) if wanted else CJK_FONT_FILES):
        if path and os.path.isfile(path):
            return path
    raise InputError(wanted or CJK_FONT_FILES[0],
                     "no Chinese (CJK) font found for the zh_CN report: install the Debian "
                     "package fonts-wqy-zenhei (scripts/install-system-packages.sh) or set "
                     "HYDROSYNC_CJK_FONT to a .ttf/.ttc file")


def _cjk_font(name: str, mono: bool = False) -> TTFont:
    # Only TrueType outlines: reportlab embeds (subsets) them, unlike its built-in CID
    # fonts, which each viewer substitutes differently. WenQuanYi Zen Hei carries Latin,
    # Greek (σ, Δ) and the signs ± ° → as well, so one face serves the whole page.
    path = cjk_font_file()
    # WenQuanYi Zen Hei's collection holds the proportional face first, the mono second.
    index = 1 if mono and path.endswith("wqy-zenhei.ttc") else 0
    font = TTFont(name, path, subfontIndex=index)
    glyphs, widths = font.face.charToGlyph, font.face.charWidths
    for missing, stand_in in _STAND_INS.items():
        if missing not in glyphs and stand_in in glyphs:  # a look-alike, not a tofu box
            glyphs[missing], widths[missing] = glyphs[stand_in], widths[stand_in]
    return font


#: Signs the CJK face lacks, drawn with a look-alike it has: minus sign → hyphen-minus,
#: check mark → √ (the tick of Chinese forms).
_STAND_INS = {0x2212: ord("-"), 0x2713: 0x221A, 0x2717: 0x00D7}


@contextlib.contextmanager
def language_fonts(lang: str) -> Iterator[None]:
    """Draw the report's text in the face *lang* needs while the block runs.

    Every style, table and chart names :data:`FONT` / :data:`FONT_BOLD`; for Chinese those
    names are pointed at the CJK face for the duration of one build (under a lock, so two
    reports built at once cannot mix faces) and restored afterwards. English is untouched.
    """
    if lang == "en" or FONT == "Helvetica":
        yield
        return
    if lang != "zh_CN":
        raise ValueError(f"no report fonts for language '{lang}'")
    face = _cjk_font(FONT)  # one face for every style: the font has no bold or italic
    # Helvetica and Courier too: they have no Chinese glyphs and are not embedded, and a
    # section may name them directly (a bold cell, parameter names in Courier).
    faces = dict.fromkeys((FONT, FONT_BOLD, "DejaVuSans-Oblique", "DejaVuSans-BoldOblique",
                           "Helvetica", "Helvetica-Bold", "Helvetica-Oblique"), face)
    faces["Courier"] = _cjk_font("Courier", mono=True)
    with _FONT_SWAP:
        saved = {name: pdfmetrics._fonts.get(name) for name in faces}
        try:
            pdfmetrics._fonts.update(faces)
            yield
        finally:
            for name, font in saved.items():
                if font is None:
                    pdfmetrics._fonts.pop(name, None)
                else:
                    pdfmetrics._fonts[name] = font


def stylesheet(cjk: bool = False) -> StyleSheet1:
    """Return the report's paragraph styles (``Title``, ``H1``, ``H2``, ``Body``, …).

    *cjk*: break running text between any two Chinese characters (Chinese has no
    spaces); table cells still break at spaces and split only words wider than the column.
    """
    ss = StyleSheet1()
    base = ParagraphStyle("Body", fontName=FONT, fontSize=9.5, leading=12.5,
                          textColor=INK, spaceAfter=4, wordWrap="CJK" if cjk else None)
    ss.add(base)
    ss.add(ParagraphStyle("Small", parent=base, fontSize=8, leading=10, textColor=MUTED))
    ss.add(ParagraphStyle("Caption", parent=base, fontSize=8.5, leading=10.5,
                          textColor=MUTED, spaceBefore=2, spaceAfter=10))
    ss.add(ParagraphStyle("TableCaption", parent=ss["Caption"], spaceBefore=6, spaceAfter=3,
                          keepWithNext=1))
    ss.add(ParagraphStyle("Title", parent=base, fontName=FONT_BOLD, fontSize=24,
                          leading=29, textColor=ACCENT, spaceAfter=6))
    ss.add(ParagraphStyle("Subtitle", parent=base, fontSize=13, leading=17, textColor=MUTED,
                          spaceAfter=18))
    ss.add(ParagraphStyle("H1", parent=base, fontName=FONT_BOLD, fontSize=15,
                          leading=19, textColor=ACCENT, spaceBefore=4, spaceAfter=8,
                          keepWithNext=1))
    ss.add(ParagraphStyle("H2", parent=base, fontName=FONT_BOLD, fontSize=11.5,
                          leading=15, textColor=ACCENT, spaceBefore=10, spaceAfter=4,
                          keepWithNext=1))
    # Table cells keep breaking at spaces (reportlab splits a word only when it is longer
    # than the column): CJK breaking, good for running Chinese text, would also cut a
    # unit or a name in a narrow column ("RM|S [mm]").
    ss.add(ParagraphStyle("Cell", parent=base, fontSize=8.5, leading=10.5, spaceAfter=0,
                          wordWrap=None))
    ss.add(ParagraphStyle("CellBold", parent=ss["Cell"], fontName=FONT_BOLD))
    ss.add(ParagraphStyle("CellCenter", parent=ss["Cell"], alignment=TA_CENTER))
    ss.add(ParagraphStyle("Warning", parent=base, backColor=WARN_FILL, borderPadding=4,
                          spaceBefore=4, spaceAfter=8, alignment=TA_LEFT))
    # Like H2 but not entered in the outline (the contents does not list itself).
    ss.add(ParagraphStyle("ContentsTitle", parent=ss["H2"], spaceBefore=0))
    ss.add(ParagraphStyle("TOC1", parent=base, fontSize=10, leading=14))
    ss.add(ParagraphStyle("TOC2", parent=base, fontSize=9, leading=12, leftIndent=12))
    return ss


def table_style(n_rows: int, numeric_from: int = 1, zebra: bool = True,
                font_size: float = 8.5) -> list[tuple]:
    """Table style commands: shaded bold header row, rules, optional zebra rows.

    Parameters
    ----------
    n_rows : int
        Number of rows including the header.
    numeric_from : int
        Columns from this index on are right-aligned (numbers).
    zebra : bool
        Shade every other body row to guide the eye across wide tables.
    font_size : float
        Points; smaller for wide tables.
    """
    pad = 4 if font_size >= 8.5 else 2.5
    cmds: list[tuple] = [
        ("FONT", (0, 0), (-1, 0), FONT_BOLD, font_size),
        ("FONT", (0, 1), (-1, -1), FONT, font_size),
        ("TEXTCOLOR", (0, 0), (-1, -1), INK),
        ("BACKGROUND", (0, 0), (-1, 0), HEADER_FILL),
        ("LINEABOVE", (0, 0), (-1, 0), 0.8, ACCENT),
        ("LINEBELOW", (0, 0), (-1, 0), 0.6, ACCENT),
        ("LINEBELOW", (0, -1), (-1, -1), 0.8, ACCENT),
        ("VALIGN", (0, 0), (-1, -1), "MIDDLE"),
        ("ALIGN", (0, 0), (numeric_from - 1, -1), "LEFT"),
        ("ALIGN", (numeric_from, 0), (-1, -1), "RIGHT"),
        ("TOPPADDING", (0, 0), (-1, -1), 2.5),
        ("BOTTOMPADDING", (0, 0), (-1, -1), 2.5),
        ("LEFTPADDING", (0, 0), (-1, -1), pad),
        ("RIGHTPADDING", (0, 0), (-1, -1), pad),
    ]
    if zebra:
        for row in range(2, n_rows, 2):
            cmds.append(("BACKGROUND", (0, row), (-1, row), ZEBRA_FILL))
    return cmds
