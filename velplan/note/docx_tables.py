"""Tables of the note's .docx: ruled, the header row repeated on each page the table runs
onto, its rows kept together (a table no longer than a page is not broken), and each column as wide as its contents need (a number or a word is never broken
across lines; what is left of the text width goes to the columns that wrap)."""

from __future__ import annotations

import unicodedata

from docx.oxml import OxmlElement
from docx.oxml.ns import qn

from velplan.notation import SUBSCRIPT_DIGITS
from velplan.note.docx_layout import CELL_PAD_TWIPS, LOOKS, TEXT_WIDTH_TWIPS

SMALLEST = 16
"""The smallest table text, half-points (8 pt), used only where a table cannot fit otherwise."""
SAFETY = 1.06
"""Widths are estimated from Times' advance widths; the margin covers a wider substitute."""


def em(c: str) -> float:
    """Advance width of ``c`` in Times New Roman (Liberation Serif), ems."""
    if c.isdigit() and c.isascii():
        return 0.5
    if c == " ":
        return 0.25
    if c in ",.;:'!|":
        return 0.28
    if c in "()[]/-":
        return 0.34
    if c in "−–—=+<>±×":
        return 0.69
    if unicodedata.east_asian_width(c) in "WF":
        return 1.0
    if c in SUBSCRIPT_DIGITS or c in "ⁿᵗ²³":
        return 0.35
    if c.isupper():
        return 0.72
    return 0.53


def text_twips(s: str, half_points: int) -> float:
    """Width of ``s`` set at ``half_points``, twips."""
    return SAFETY * sum(em(c) for c in s) * half_points * 10


def cell_text(tc) -> list[str]:
    """The lines (paragraphs) of a table cell."""
    return ["".join(t.text or "" for t in p.iter(qn("w:t"))) for p in tc.iter(qn("w:p"))]


def column_widths(rows: list[list[list[str]]], size: int, width: int = TEXT_WIDTH_TWIPS) -> list[int] | None:
    """Widths (twips) of the columns of ``rows`` (cells as lists of lines) at ``size``
    half-points: at least the longest word of each column, the rest of ``width`` shared by
    what the columns need beyond it; None if the longest words alone do not fit."""
    cols = max(len(r) for r in rows)
    least, natural = [0.0] * cols, [0.0] * cols
    for row in rows:
        for c, lines in enumerate(row):
            for line in lines:
                natural[c] = max(natural[c], text_twips(line, size))
                for word in line.split():
                    least[c] = max(least[c], text_twips(word, size))
    least = [w + CELL_PAD_TWIPS for w in least]
    natural = [w + CELL_PAD_TWIPS for w in natural]
    if sum(least) > width:
        return None
    if sum(natural) <= width:
        spare = width - sum(natural)
        return [int(n + spare * n / sum(natural)) for n in natural]
    spare, wants = width - sum(least), [n - m for n, m in zip(natural, least)]
    return [int(m + spare * w / sum(wants)) for m, w in zip(least, wants)]


def layout_tables(doc, lang: str) -> int:
    """Rule, size and head every table of ``doc``; returns the number of tables."""
    size0 = LOOKS.get(lang, LOOKS["en"]).table
    tables = list(doc.element.body.iter(qn("w:tbl")))
    for tbl in tables:
        rows = [[cell_text(tc) for tc in tr.findall(qn("w:tc"))] for tr in tbl.findall(qn("w:tr"))]
        size, widths = size0, None
        while widths is None and size >= SMALLEST:
            widths = column_widths(rows, size)
            size = size if widths is not None else size - 2
        if widths is None:  # even 8 pt does not fit: the widest words, the page decides
            size, widths = SMALLEST, column_widths(rows, SMALLEST, 10 ** 6)
        _grid(tbl, widths or [])
        _rules(tbl)
        _head(tbl)
        _kept_together(tbl)
        if size != size0:
            _text_size(tbl, size)
    return len(tables)


_TBLPR_ORDER = ("w:tblStyle", "w:tblpPr", "w:tblOverlap", "w:bidiVisual", "w:tblStyleRowBandSize",
                "w:tblStyleColBandSize", "w:tblW", "w:jc", "w:tblCellSpacing", "w:tblInd", "w:tblBorders",
                "w:shd", "w:tblLayout", "w:tblCellMar", "w:tblLook", "w:tblCaption", "w:tblDescription")


def put(tblpr, el) -> None:
    """Put ``el`` into the table properties in the schema's order, replacing its namesake."""
    order = [qn(t) for t in _TBLPR_ORDER]
    old = tblpr.find(el.tag)
    if old is not None:
        tblpr.remove(old)
    rank = order.index(el.tag)
    for k, child in enumerate(tblpr):
        if child.tag in order and order.index(child.tag) > rank:
            tblpr.insert(k, el)
            return
    tblpr.append(el)


def _grid(tbl, widths: list[int]) -> None:
    tblpr = tbl.find(qn("w:tblPr"))
    tblw = OxmlElement("w:tblW")
    tblw.set(qn("w:w"), str(sum(widths)))
    tblw.set(qn("w:type"), "dxa")
    layout = OxmlElement("w:tblLayout")
    layout.set(qn("w:type"), "fixed")
    put(tblpr, tblw)
    put(tblpr, layout)
    grid = tbl.find(qn("w:tblGrid"))
    for col in list(grid):
        grid.remove(col)
    for w in widths:
        col = OxmlElement("w:gridCol")
        col.set(qn("w:w"), str(w))
        grid.append(col)
    for tr in tbl.findall(qn("w:tr")):
        for tc, w in zip(tr.findall(qn("w:tc")), widths):
            tcpr = tc.find(qn("w:tcPr"))
            if tcpr is None:
                tcpr = OxmlElement("w:tcPr")
                tc.insert(0, tcpr)
            tcw = tcpr.find(qn("w:tcW"))
            if tcw is None:
                tcw = OxmlElement("w:tcW")
                tcpr.insert(0, tcw)
            tcw.set(qn("w:w"), str(w))
            tcw.set(qn("w:type"), "dxa")


def _rules(tbl) -> None:
    """Single thin lines round every cell (a ruled table of ГОСТ 2.105)."""
    borders = OxmlElement("w:tblBorders")
    for side in ("top", "left", "bottom", "right", "insideH", "insideV"):
        b = OxmlElement(f"w:{side}")
        for k, v in (("val", "single"), ("sz", "4"), ("space", "0"), ("color", "000000")):
            b.set(qn(f"w:{k}"), v)
        borders.append(b)
    put(tbl.find(qn("w:tblPr")), borders)
    for tr in tbl.findall(qn("w:tr")):  # pandoc's own header border would double the top rule
        for tc in tr.findall(qn("w:tc")):
            tcpr = tc.find(qn("w:tcPr"))
            if tcpr is not None and tcpr.find(qn("w:tcBorders")) is not None:
                tcpr.remove(tcpr.find(qn("w:tcBorders")))


def _head(tbl) -> None:
    """The first row repeats on every page; no row is split across pages."""
    for k, tr in enumerate(tbl.findall(qn("w:tr"))):
        trpr = tr.find(qn("w:trPr"))
        if trpr is None:
            trpr = OxmlElement("w:trPr")
            tblpr_ex = tr.find(qn("w:tblPrEx"))
            (tblpr_ex.addnext if tblpr_ex is not None else lambda e: tr.insert(0, e))(trpr)
        for el in list(trpr):
            if el.tag in (qn("w:cantSplit"), qn("w:tblHeader")):
                trpr.remove(el)
        trpr.append(OxmlElement("w:cantSplit"))
        if k == 0:
            trpr.append(OxmlElement("w:tblHeader"))


def _kept_together(tbl) -> None:
    """Every row kept with the next (each paragraph of every row but the last "keep with next",
    as Word and LibreOffice read it): a table of a page or less (a part of
    `velplan.note.model.ROWS_PER_PAGE` rows of a longer one) goes whole to the next page with
    its caption rather than leaving a row or two there under a repeated header without
    "Продолжение таблицы N"."""
    from velplan.note.docx_layout import put_ordered

    for tr in tbl.findall(qn("w:tr"))[:-1]:
        for p in tr.iter(qn("w:p")):
            ppr = p.find(qn("w:pPr"))
            if ppr is None:
                ppr = OxmlElement("w:pPr")
                p.insert(0, ppr)
            if ppr.find(qn("w:keepNext")) is None:
                put_ordered(ppr, OxmlElement("w:keepNext"))


def _text_size(tbl, half_points: int) -> None:
    from velplan.note.docx_layout import put_ordered

    for r in tbl.iter(qn("w:r")):
        rpr = r.find(qn("w:rPr"))
        if rpr is None:
            rpr = OxmlElement("w:rPr")
            r.insert(0, rpr)
        for tag in ("w:sz", "w:szCs"):
            el = rpr.find(qn(tag))
            if el is None:
                el = put_ordered(rpr, OxmlElement(tag))
            el.set(qn("w:val"), str(half_points))
