"""The contents of the note's .docx written out: each heading of levels 1–2 with its number, a
dot leader and its page, the page a PAGEREF field to a bookmark in the heading. An office
program computes the field as it lays the pages out (LibreOffice on every layout, Word on
opening: ``w:updateFields``), so the printed number is the page the heading lands on; the
field's stored result, shown by a viewer that computes no fields, is the page estimated here.

Not one TOC field: LibreOffice reads a TOC field's result as fixed text and leaves the
PAGEREF fields inside it as they were written.

The pages are estimated, not measured: the body is walked once with the heights of its lines,
equations, tables and pictures on an A4 page of the note's margins (`estimate_pages`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from docx.oxml import OxmlElement
from docx.oxml.ns import qn

from velplan.note.docx_layout import LOOKS, TEXT_WIDTH_TWIPS
from velplan.note.docx_tables import cell_text, text_twips

PAGE_TWIPS = round(257 / 25.4 * 1440)
"""Height of the text on an A4 page with margins of 20 mm at top and bottom, twips."""
EMU_PER_TWIP = 635
FILL = {"ru": 0.88, "uk": 0.88, "en": 1.0, "zh": 1.0}
"""Heights are estimated per line spacing; these factors, measured against LibreOffice's
pagination of the shaper (ru), triad press (en) and V compressor (zh) notes, bring them to
what a page holds (the estimate within 1–2 pages of LibreOffice's over 25–30 pages)."""
_M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"


@dataclass(frozen=True)
class Entry:
    level: int
    text: str
    anchor: str
    page: int


def _text(p) -> str:
    return "".join(t.text or "" for t in p.iter(qn("w:t")))


def _style(p) -> str:
    s = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
    return s.get(qn("w:val")) if s is not None else ""


def _height(el, look) -> tuple[float, bool]:
    """Height of a body element, twips, and whether it breaks the page before itself."""
    line = look.body * 10 * look.line / 240 * 1.17
    if el.tag == qn("w:tbl"):
        rows = [[cell_text(tc) for tc in tr.findall(qn("w:tc"))] for tr in el.findall(qn("w:tr"))]
        cols = max(1, max(len(r) for r in rows))
        per = TEXT_WIDTH_TWIPS / cols
        tline = look.table * 10 * 1.17
        return sum(max(1, max(math.ceil(text_twips(" ".join(c), look.table) / per) for c in r)) * tline + 40
                   for r in rows) + 120, False
    if el.tag != qn("w:p"):
        return 0.0, False
    if any(b.get(qn("w:type")) == "page" for b in el.iter(qn("w:br"))):
        return 0.0, True
    extents = list(el.iter("{http://schemas.openxmlformats.org/drawingml/2006/wordprocessingDrawing}extent"))
    if extents:
        return sum(int(e.get("cy")) for e in extents) / EMU_PER_TWIP + 120, False
    if el.find(f"{_M}oMathPara") is not None:
        tall = el.find(f".//{_M}f") is not None
        return line * (2.2 if tall else 1.3), False
    style = _style(el)
    size = look.headings[min(int(style[7:]), 3) - 1] if style[7:].isdigit() else look.body
    lines = max(1, math.ceil(text_twips(_text(el), size) / (TEXT_WIDTH_TWIPS - look.indent)))
    extra = 480 if style.startswith("Heading") else (180 if "Caption" in style else 0)
    return lines * line * size / look.body + extra, False


def estimate_pages(body, lang: str, start: int = 1) -> list[int]:
    """The estimated page (from ``start``) of each element of ``body``, in order."""
    look = LOOKS.get(lang, LOOKS["en"])
    page, used, pages = start, 0.0, []
    for el in body:
        h, breaks = _height(el, look)
        h *= FILL.get(lang, 1.0)
        if breaks:
            pages.append(page)
            page, used = page + 1, 0.0
            continue
        if used + h > PAGE_TWIPS and used > 0 and (el.tag != qn("w:p") or h < PAGE_TWIPS / 3):
            page, used = page + 1, 0.0
        elif used + h > PAGE_TWIPS:  # a long table or paragraph runs on
            page, used = page + int((used + h) // PAGE_TWIPS), (used + h) % PAGE_TWIPS
            pages.append(page)
            continue
        pages.append(page)
        used += h
    return pages


def entries(doc, lang: str, depth: int = 2) -> list[Entry]:
    """The headings of levels 1..``depth`` with their numbers, anchors and estimated pages;
    each such heading gets a hidden bookmark ``_Toc<n>`` round its text, the anchor."""
    body = doc.element.body
    pages = estimate_pages(body, lang)
    ids = [int(b.get(qn("w:id"))) for b in body.iter(qn("w:bookmarkStart")) if (b.get(qn("w:id")) or "").isdigit()]
    free = max(ids, default=0) + 1
    out = []
    for k, el in enumerate(body):
        if el.tag != qn("w:p"):
            continue
        style = _style(el)
        if style.startswith("Heading") and style[7:].isdigit() and int(style[7:]) <= depth:
            anchor = _bookmark(el, free)
            free += 1
            out.append(Entry(int(style[7:]), " ".join(_text(el).split()), anchor, pages[k]))
    return out


def _bookmark(p, number: int) -> str:
    """A bookmark ``_Toc<number>`` round the runs of paragraph ``p``; returns its name (a
    bookmark between paragraphs, as pandoc writes them, LibreOffice loses after a table)."""
    name = f"_Toc{number}"
    start, end = OxmlElement("w:bookmarkStart"), OxmlElement("w:bookmarkEnd")
    start.set(qn("w:id"), str(number))
    start.set(qn("w:name"), name)
    end.set(qn("w:id"), str(number))
    ppr = p.find(qn("w:pPr"))
    (ppr.addnext if ppr is not None else lambda e: p.insert(0, e))(start)
    p.append(end)
    return name


def _run(text: str | None = None, *, tab: bool = False, fld: str | None = None, instr: str | None = None):
    r = OxmlElement("w:r")
    if tab:
        r.append(OxmlElement("w:tab"))
    if fld:
        f = OxmlElement("w:fldChar")
        f.set(qn("w:fldCharType"), fld)
        r.append(f)
    for tag, value in (("w:t", text), ("w:instrText", instr)):
        if value is not None:
            t = OxmlElement(tag)
            t.set("{http://www.w3.org/XML/1998/namespace}space", "preserve")
            t.text = value
            r.append(t)
    return r


def _entry_paragraph(e: Entry, look):
    p = OxmlElement("w:p")
    ppr = OxmlElement("w:pPr")
    style = OxmlElement("w:pStyle")
    style.set(qn("w:val"), f"TOC{e.level}")
    tabs, tab = OxmlElement("w:tabs"), OxmlElement("w:tab")
    for k, v in (("val", "right"), ("leader", "dot"), ("pos", str(TEXT_WIDTH_TWIPS))):
        tab.set(qn(f"w:{k}"), v)
    tabs.append(tab)
    spacing, ind = OxmlElement("w:spacing"), OxmlElement("w:ind")
    for k, v in (("before", "0"), ("after", "0"), ("line", str(look.line)), ("lineRule", "auto")):
        spacing.set(qn(f"w:{k}"), v)
    ind.set(qn("w:left"), str(280 * (e.level - 1)))
    ind.set(qn("w:right"), "567")
    ind.set(qn("w:firstLine"), "0")
    for el in (style, tabs, spacing, ind):
        ppr.append(el)
    p.append(ppr)
    link = OxmlElement("w:hyperlink")
    if e.anchor:
        link.set(qn("w:anchor"), e.anchor)
    link.set(qn("w:history"), "1")
    field = [_run(fld="begin"), _run(instr=f" PAGEREF {e.anchor} \\h "), _run(fld="separate"),
             _run(str(e.page)), _run(fld="end")] if e.anchor else [_run(str(e.page))]
    for r in [_run(e.text), _run(tab=True)] + field:
        link.append(r)
    p.append(link)
    return p


def fill_contents(doc, lang: str) -> int:
    """Replace the contents' placeholder (the TOC field the Markdown writes) by its entries;
    returns the number of entries."""
    body = doc.element.body
    field = next((p for p in body.iter(qn("w:p"))
                  if any((t.text or "").lstrip().startswith("TOC") for t in p.iter(qn("w:instrText")))), None)
    if field is None:
        return 0
    items = entries(doc, lang)
    look = LOOKS.get(lang, LOOKS["en"])
    anchor = field
    for p in [_entry_paragraph(e, look) for e in items]:
        anchor.addnext(p)
        anchor = p
    body.remove(field)
    return len(items)
