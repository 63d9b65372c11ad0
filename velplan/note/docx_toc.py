"""The contents of the note's .docx written out: each heading of levels 1–2 with its number, a
dot leader and its page, the page a PAGEREF field to a bookmark in the heading. An office
program computes the field as it lays the pages out (LibreOffice on every layout, Word on
opening: ``w:updateFields``), so the printed number is the page the heading lands on; the
field's stored result, shown by a viewer that computes no fields, is the page estimated here.

Not one TOC field: LibreOffice reads a TOC field's result as fixed text and leaves the
PAGEREF fields inside it as they were written.

The stored pages are estimated (`velplan.note.docx_pages.estimate_pages`).
"""

from __future__ import annotations

from dataclasses import dataclass

from docx.oxml import OxmlElement
from docx.oxml.ns import qn

from velplan.note.docx_layout import LOOKS, TEXT_WIDTH_TWIPS
from velplan.note.docx_pages import estimate_pages


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


def entries(doc, lang: str, depth: int = 2) -> list[Entry]:
    """The headings of levels 1..``depth`` with their numbers, anchors and estimated pages;
    each such heading gets a hidden bookmark ``_Toc<n>`` round its text, the anchor."""
    body = doc.element.body
    pages = estimate_pages(doc)
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
