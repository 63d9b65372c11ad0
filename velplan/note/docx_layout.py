"""The layout of the note's .docx after pandoc: the plain style of a course note (ГОСТ 2.105
for ru/uk, its equivalent for en/zh), black numbered headings with a space after the number,
ruled tables whose columns fit their contents, header rows repeated on a new page, and
equations in the body size.

Everything here edits the WordprocessingML tree of a python-docx ``Document``.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

from docx.oxml import OxmlElement
from docx.oxml.ns import qn

TEXT_WIDTH_TWIPS = 9638
"""Width of the text on an A4 page with margins 25 and 15 mm (170 mm), twips."""
CELL_PAD_TWIPS = 2 * 108
"""Left and right margin of a table cell (Word's and LibreOffice's default), twips."""


@dataclass(frozen=True)
class Look:
    """Fonts and sizes of a note, half-points (Word's unit of ``w:sz``)."""

    font: str
    east_asia: str
    body: int
    table: int
    headings: tuple[int, int, int]
    line: int
    """Line spacing, 240ths of a line (360: one and a half)."""
    indent: int
    """First-line indent of a paragraph, twips."""


LOOKS = {
    "ru": Look("Times New Roman", "Times New Roman", 24, 22, (28, 26, 24), 360, 709),
    "uk": Look("Times New Roman", "Times New Roman", 24, 22, (28, 26, 24), 360, 709),
    "en": Look("Times New Roman", "Times New Roman", 24, 22, (28, 26, 24), 288, 0),
    "zh": Look("Times New Roman", "SimSun", 24, 21, (28, 26, 24), 288, 480),
}
"""ГОСТ 2.105 / 7.32 for ru/uk: Times 12 pt (the least the standard allows, and the size
LibreOffice sets a Word equation in, so formulas and text match in every viewer), 1.5 lines,
1.25 cm indent; en/zh: 12 pt, 1.2 lines."""

_BODY_STYLES = ("Normal", "BodyText", "FirstParagraph")
_INDENTED = ("BodyText", "FirstParagraph")


_ORDER = {
    "w:rPr": ("rStyle", "rFonts", "b", "bCs", "i", "iCs", "caps", "smallCaps", "strike", "dstrike", "outline",
              "shadow", "emboss", "imprint", "noProof", "snapToGrid", "vanish", "webHidden", "color", "spacing",
              "w", "kern", "position", "sz", "szCs", "highlight", "u", "effect", "bdr", "shd", "fitText",
              "vertAlign", "rtl", "cs", "em", "lang", "eastAsianLayout", "specVanish", "oMath"),
    "w:pPr": ("pStyle", "keepNext", "keepLines", "pageBreakBefore", "framePr", "widowControl", "numPr",
              "suppressLineNumbers", "pBdr", "shd", "tabs", "suppressAutoHyphens", "kinsoku", "wordWrap",
              "overflowPunct", "topLinePunct", "autoSpaceDE", "autoSpaceDN", "bidi", "adjustRightInd",
              "snapToGrid", "spacing", "ind", "contextualSpacing", "mirrorIndents", "suppressOverlap", "jc",
              "textDirection", "textAlignment", "textboxTightWrap", "outlineLvl", "divId", "cnfStyle", "rPr",
              "sectPr", "pPrChange"),
    "w:style": ("name", "aliases", "basedOn", "next", "link", "autoRedefine", "hidden", "uiPriority",
                "semiHidden", "unhideWhenUsed", "qFormat", "locked", "personal", "personalCompose",
                "personalReply", "rsid", "pPr", "rPr", "tblPr", "trPr", "tcPr", "tblStylePr"),
}
"""The schema's order of the children of run and paragraph properties and of a style (Word
refuses a file whose elements are out of it)."""


def put_ordered(parent, el):
    """Insert ``el`` into ``parent`` at its place in the schema's order; returns ``el``."""
    order = _ORDER.get(parent.tag.replace("{http://schemas.openxmlformats.org/wordprocessingml/2006/main}", "w:"))
    name = el.tag.rsplit("}", 1)[-1]
    if order and name in order:
        rank = order.index(name)
        for k, child in enumerate(parent):
            other = child.tag.rsplit("}", 1)[-1]
            if other in order and order.index(other) > rank:
                parent.insert(k, el)
                return el
    parent.append(el)
    return el


def _child(parent, tag: str):
    """The child ``tag`` of ``parent``, made in its place if missing."""
    el = parent.find(qn(tag))
    return el if el is not None else put_ordered(parent, OxmlElement(tag))


def _set(el, **attrs) -> None:
    for key, value in attrs.items():
        el.set(qn(f"w:{key}"), str(value))


def _fonts(rpr, look: Look) -> None:
    for tag in ("w:rFonts",):
        old = rpr.find(qn(tag))
        if old is not None:
            rpr.remove(old)
    fonts = OxmlElement("w:rFonts")
    _set(fonts, ascii=look.font, hAnsi=look.font, cs=look.font, eastAsia=look.east_asia)
    put_ordered(rpr, fonts)


def _size(rpr, half_points: int) -> None:
    for tag in ("w:sz", "w:szCs"):
        _set(_child(rpr, tag), val=half_points)


def _plain(rpr) -> None:
    """No colour, no italics, no theme font in a style's run properties."""
    for tag in ("w:color", "w:i", "w:iCs"):
        for el in rpr.findall(qn(tag)):
            rpr.remove(el)


def apply_look(doc, lang: str) -> None:
    """Fonts, sizes, spacing and colours of every style the note uses."""
    look = LOOKS.get(lang, LOOKS["en"])
    styles = doc.styles.element
    defaults = styles.find(qn("w:docDefaults"))
    rpr = _child(_child(defaults, "w:rPrDefault"), "w:rPr")
    _fonts(rpr, look)
    _size(rpr, look.body)
    for style in styles.findall(qn("w:style")):
        sid = style.get(qn("w:styleId"))
        rpr = _child(style, "w:rPr")
        if rpr.find(qn("w:rFonts")) is not None:
            _fonts(rpr, look)
        _plain(rpr)
        if sid in _BODY_STYLES:
            _size(rpr, look.body)
            ppr = _child(style, "w:pPr")
            _set(_child(ppr, "w:spacing"), before=0, after=0, line=look.line, lineRule="auto")
            if sid in _INDENTED:
                _set(_child(ppr, "w:ind"), firstLine=look.indent)
                _set(_child(ppr, "w:jc"), val="both")
        elif sid.startswith("Heading") and sid[7:].isdigit():
            level = int(sid[7:])
            _size(rpr, look.headings[min(level, 3) - 1])
            _child(rpr, "w:b")
            ppr = _child(style, "w:pPr")
            _set(_child(ppr, "w:spacing"), before=360 if level == 1 else 240, after=120)
            _set(_child(ppr, "w:ind"), firstLine=look.indent)
        elif sid in ("Compact", "TableCaption", "ImageCaption", "Caption"):
            _size(rpr, look.table if sid == "Compact" else look.body)
            ppr = _child(style, "w:pPr")
            _set(_child(ppr, "w:spacing"), before=120 if sid != "Compact" else 0,
                 after=60 if sid != "Compact" else 0, line=240, lineRule="auto")
            _set(_child(ppr, "w:ind"), firstLine=0, left=0)
            _set(_child(ppr, "w:jc"), val="center" if sid == "ImageCaption" else "left")
            if sid == "TableCaption":
                _child(ppr, "w:keepNext")
        elif sid in ("Title", "TOCHeading"):
            _size(rpr, look.headings[0])
            for tag in ("w:b", "w:bCs"):  # pandoc's TOC Heading says bold off
                _child(rpr, tag).attrib.pop(qn("w:val"), None)
            if sid == "TOCHeading":
                ppr = _child(style, "w:pPr")
                _set(_child(ppr, "w:ind"), firstLine=0)
                _set(_child(ppr, "w:jc"), val="center")


def heading_spaces(doc) -> int:
    """A space, not a tab, after each heading's number ("5.1.1 Группа"): a tab reaches the
    next default stop, which a long number has already passed. Returns the headings fixed."""
    fixed = 0
    for p in doc.element.body.iter(qn("w:p")):
        runs = p.findall(qn("w:r"))
        if len(runs) < 2 or not _is_section_number(runs[0]):
            continue
        tab = runs[1].find(qn("w:tab"))
        if tab is not None:
            runs[1].remove(tab)
            t = OxmlElement("w:t")
            t.set("{http://www.w3.org/XML/1998/namespace}space", "preserve")
            t.text = " "
            runs[1].append(t)
            fixed += 1
    return fixed


def centre_unnumbered(doc) -> int:
    """The headings of the note's parts that carry no number (introduction, conclusion,
    references) centred, with no indent, as "Содержание" is (ГОСТ 2.105: headings of the
    document's parts symmetric to the text). Returns the headings centred."""
    centred = 0
    for p in doc.element.body.iter(qn("w:p")):
        style = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
        if style is None or style.get(qn("w:val")) != "Heading1":
            continue
        if any(_is_section_number(r) for r in p.findall(qn("w:r"))):
            continue
        ppr = p.find(qn("w:pPr"))
        _set(_child(ppr, "w:ind"), firstLine=0)
        _set(_child(ppr, "w:jc"), val="center")
        centred += 1
    return centred


def keep_lead_ins(doc) -> int:
    """A paragraph of text that ends with a colon ("Формула строения:") kept with what it
    introduces, so a page break never parts them. Returns the paragraphs kept."""
    kept = 0
    for p in doc.element.body.iter(qn("w:p")):
        text = "".join(t.text or "" for t in p.iter(qn("w:t"))).rstrip()
        if not text.endswith(":") or p.getparent() is not doc.element.body:
            continue
        ppr = p.find(qn("w:pPr"))
        if ppr is None:
            ppr = OxmlElement("w:pPr")
            p.insert(0, ppr)
        _child(ppr, "w:keepNext")
        kept += 1
    return kept


def _is_section_number(run) -> bool:
    style = run.find(f"{qn('w:rPr')}/{qn('w:rStyle')}")
    return style is not None and style.get(qn("w:val")) == "SectionNumber"


def math_size(doc, lang: str) -> None:
    """Equations in the body size: each math run carries the body's ``w:sz``."""
    look = LOOKS.get(lang, LOOKS["en"])
    m_r = "{http://schemas.openxmlformats.org/officeDocument/2006/math}r"
    m_rpr = "{http://schemas.openxmlformats.org/officeDocument/2006/math}rPr"
    sized = OxmlElement("w:rPr")  # a bare run's properties: made once, copied to each
    _size(sized, look.body)
    w_rpr = qn("w:rPr")
    for run in doc.element.body.iter(m_r):
        rpr = run.find(w_rpr)
        if rpr is None:
            mr = run.find(m_rpr)
            run.insert(1 if mr is not None else 0, copy.deepcopy(sized))
        else:
            _size(rpr, look.body)
    for para in doc.element.body.iter(qn("w:p")):  # LibreOffice sizes a formula by its paragraph
        if para.find("{http://schemas.openxmlformats.org/officeDocument/2006/math}oMathPara") is not None:
            ppr = para.find(qn("w:pPr"))
            if ppr is None:
                ppr = OxmlElement("w:pPr")
                para.insert(0, ppr)
            _size(_child(ppr, "w:rPr"), look.body)


def page_numbers(doc) -> None:
    """The page number centred in the footer of every page but the title page."""
    for section in doc.sections:
        section.different_first_page_header_footer = True
        p = section.footer.paragraphs[0]
        p.alignment = 1
        field = OxmlElement("w:fldSimple")
        field.set(qn("w:instr"), "PAGE")
        run = OxmlElement("w:r")
        t = OxmlElement("w:t")
        t.text = "1"
        run.append(t)
        field.append(run)
        p._p.append(field)
