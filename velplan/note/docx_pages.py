"""The pages of the note's .docx, estimated as an office program lays them out: the page on
which each body element starts (`estimate_pages`), the stored result of the contents' page
fields.

The model, measured against LibreOffice's layout (Liberation Serif for Times New Roman):
a line of a paragraph is 1.149 of its font size (ascent, descent and line gap) times its line
spacing; the spacing between paragraphs the larger of the one's after and the next's before,
none at the top of a page the text ran onto; a paragraph splits between lines, a heading, an
equation, a picture and a table row do not; "keep with next" carries a heading, a caption or a
picture (and every row of a table but its last) to the next page with what follows; a table
row is its tallest cell's lines and its rules; a picture its height on a line of its
paragraph; a displayed equation a line of its paragraph and what its fractions, scripts and
accents add (`_MATH_MM`).
"""

from __future__ import annotations

import copy
import unicodedata
from dataclasses import dataclass

from docx.oxml.ns import qn

from velplan.note.docx_layout import CELL_PAD_TWIPS, TEXT_WIDTH_TWIPS
from velplan.note.docx_tables import em
from velplan.note.serif_widths import WIDTHS

PAGE_PT = 257 / 25.4 * 72
"""Height of the text on an A4 page with margins of 20 mm at top and bottom, points."""
LINE = 1.149
"""Height of a single line, font sizes (Times New Roman's ascent 0.891, descent 0.216 and
line gap 0.042 of an em)."""
CJK_LINE = 1.175
"""The same for a line holding Chinese characters (the fallback font is taller)."""
RULE_PT = 0.55
"""What a table row's rules add to its lines, points."""
_MATH_MM = {"plain": 0.1, "script": 0.4, "nested": 0.4, "sup": 0.6, "accent": 0.5,
            "fraction": 5.1, "fraction_scripts": 6.4, "fraction_nested": 0.7}
"""What a formula adds to a line of its paragraph, mm (LibreOffice's formula objects): plain
symbols; a sub- or superscript, scripts on scripts, a superscript, an accent (each adds);
a fraction, a fraction with scripts inside, and scripts on scripts in it."""
_M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"
_W = "{http://schemas.openxmlformats.org/wordprocessingml/2006/main}"
_WP = "{http://schemas.openxmlformats.org/drawingml/2006/wordprocessingDrawing}"
_PT_PER_MM = 72 / 25.4


@dataclass
class Para:
    """Spacing and layout of a paragraph style (or of a paragraph), points and flags."""

    before: float = 0.0
    after: float = 10.0
    line: float = 1.0
    size: float = 12.0
    keep_next: bool = False
    indent: float = 0.0
    """Left plus right indent, twips."""
    first: float = 0.0
    """First-line indent, twips."""


def _apply(para: Para, ppr, rpr) -> None:
    """Overlay the properties ``ppr`` / ``rpr`` (either None) on ``para``."""
    if ppr is not None:
        sp = ppr.find(f"{_W}spacing")
        if sp is not None:
            for attr, name in (("before", "before"), ("after", "after")):
                if sp.get(_W + attr) is not None:
                    setattr(para, name, int(sp.get(_W + attr)) / 20)
            if sp.get(f"{_W}line") is not None and sp.get(f"{_W}lineRule", "auto") == "auto":
                para.line = int(sp.get(f"{_W}line")) / 240
        keep = ppr.find(f"{_W}keepNext")
        if keep is not None:
            para.keep_next = keep.get(f"{_W}val", "true") not in ("0", "false")
        ind = ppr.find(f"{_W}ind")
        if ind is not None:
            side = sum(int(ind.get(_W + k, 0)) for k in ("left", "right"))
            para.indent = side if (ind.get(f"{_W}left") or ind.get(f"{_W}right")) else para.indent
            if ind.get(f"{_W}firstLine") is not None:
                para.first = int(ind.get(f"{_W}firstLine"))
    if rpr is not None:
        sz = rpr.find(f"{_W}sz")
        if sz is not None:
            para.size = int(sz.get(f"{_W}val")) / 2


def styles(doc) -> dict[str, Para]:
    """Each paragraph style of ``doc`` resolved through the styles it is based on."""
    root = doc.styles.element
    base = Para()
    defaults = root.find(f"{_W}docDefaults")
    if defaults is not None:
        _apply(base, defaults.find(f"{qn('w:pPrDefault')}/{qn('w:pPr')}"),
               defaults.find(f"{qn('w:rPrDefault')}/{qn('w:rPr')}"))
    raw = {s.get(f"{_W}styleId"): s for s in root.findall(f"{_W}style") if s.get(f"{_W}type") == "paragraph"}
    done: dict[str, Para] = {}

    def resolve(sid: str, depth: int = 0) -> Para:
        if sid in done:
            return done[sid]
        style = raw.get(sid)
        parent = style.find(f"{_W}basedOn") if style is not None else None
        para = Para(**vars(resolve(parent.get(f"{_W}val"), depth + 1) if parent is not None and depth < 20
                           else base))
        if style is not None:
            _apply(para, style.find(f"{_W}pPr"), style.find(f"{_W}rPr"))
        done[sid] = para
        return para

    default = next((k for k, s in raw.items() if s.get(f"{_W}default") in ("1", "true")), "Normal")
    done[""] = resolve(default)
    for sid in raw:
        resolve(sid)
    return done


def _para(p, known: dict[str, Para]) -> Para:
    """The properties of paragraph ``p``: its style's, with its own over them (not to be
    changed: a paragraph of its style's alone shares them)."""
    ppr = p.find(f"{_W}pPr")
    sid = ppr.find(f"{_W}pStyle") if ppr is not None else None
    style = known.get(sid.get(f"{_W}val") if sid is not None else "", known[""])
    if ppr is None or len(ppr) == (sid is not None):
        return style
    para = copy.copy(style)
    _apply(para, ppr, None)
    return para


def _char(c: str) -> float:
    w = WIDTHS.get(c)
    return w if w is not None else em(c)


def _math_width(formula, size: float) -> float:
    """Width of an inline formula at ``size`` points, twips: its symbols, scripts at 0.6 of the
    size, a little room each side of a relation or an operation."""
    ems = 0.0
    for t in formula.iter(f"{_M}t"):
        scale = 0.6 if any(a.tag in (f"{_M}sub", f"{_M}sup") for a in t.iterancestors()) else 1.0
        ems += sum(_char(c) + (0.3 if c in "=+−±×≈<>≤≥" else 0.0) for c in t.text or "") * scale
    return ems * size * 20


def _words(p, size: float) -> list[tuple[float, float]]:
    """The words of paragraph ``p`` (what lies between its breakable spaces, an inline formula
    part of its word; a Chinese character a word of its own): the space before each and its
    width, twips."""
    words, word, gap, twips = [], 0.0, 0.0, size * 20
    for el in p.iter(f"{_W}t", f"{_W}tab", f"{_M}oMath"):
        if el.tag == f"{_M}oMath":
            word += _math_width(el, size) / twips
            continue
        for c in " " if el.tag == f"{_W}tab" else (el.text or ""):
            ems, wide = _EMS.get(c) or _ems(c)
            if c == " " or wide:
                if word:
                    words.append((gap, word * twips))
                    gap = 0.0
                word = 0.0
                if wide:
                    words.append((gap, ems * twips))
                gap = _EMS[" "][0] * twips if c == " " else 0.0
            else:
                word += ems
    return words + [(gap, word * twips)] if word else words


_EMS: dict[str, tuple[float, bool]] = {}


def _ems(c: str) -> tuple[float, bool]:
    """The advance width of ``c`` (ems) and whether it is a Chinese (wide) character, kept."""
    _EMS[c] = (_char(c), unicodedata.east_asian_width(c) in "WF")
    return _EMS[c]


def _lines(words: list[tuple[float, float]], width: float, first: float) -> int:
    """Lines the words (the space before each, its width; twips) take, broken greedily."""
    lines, used, room = 1, 0.0, width - first
    for gap, w in words:
        if used and used + gap + w > room:
            lines, used, room = lines + 1, 0.0, width
            gap = 0.0
        used += (gap if used else 0.0) + w
    return lines


def _cjk(p) -> bool:
    return any(unicodedata.east_asian_width(c) in "WF" for t in p.iter(f"{_W}t") for c in t.text or "")


def line_pt(para: Para, cjk: bool = False) -> float:
    """Height of one line of ``para``, points."""
    return para.size * (CJK_LINE if cjk else LINE) * para.line


def _math_extra(el) -> float:
    """What the formula ``el`` adds to a line of its paragraph, points."""
    kinds = (f"{_M}sSub", f"{_M}sSup", f"{_M}sSubSup")
    scripts = list(el.iter(*kinds))
    nested = any(inner is not s for s in scripts for inner in s.iter(*kinds))
    sup = any(True for _ in el.iter(f"{_M}sSup", f"{_M}sSubSup"))
    fractions = list(el.iter(f"{_M}f"))
    if fractions:
        inner = any(True for f in fractions for _ in f.iter(*kinds, f"{_M}acc"))
        mm = _MATH_MM["fraction_scripts" if inner else "fraction"]
        mm += (_MATH_MM["fraction_nested"] if nested else 0.0) + (_MATH_MM["sup"] if sup else 0.0)
    else:
        mm = _MATH_MM["script" if scripts else "plain"] + (_MATH_MM["nested"] if nested else 0.0)
        mm += (_MATH_MM["sup"] if sup else 0.0) + (_MATH_MM["accent"] if el.find(f".//{_M}acc") is not None else 0.0)
    return mm * _PT_PER_MM


def _display(formula, para: Para) -> float:
    """Height of a displayed formula on its line of ``para``, points: a long one is a matrix
    whose rows stand one under another, each a font's height and what its symbols add."""
    rows = formula.findall(f".//{_M}mr")
    if not rows:
        return line_pt(para) + _math_extra(formula)
    return line_pt(para) - para.size * LINE + sum(para.size * LINE + _math_extra(r) for r in rows)


@dataclass
class Block:
    """A body element as the paginator sees it: its pieces (lines, rows; one piece if it does
    not split), points."""

    pieces: list[float]
    before: float = 0.0
    after: float = 0.0
    keep_next: bool = False
    splits: bool = False
    header: float = 0.0
    """A table's first row, repeated on each page it runs onto."""
    breaks: bool = False
    """A page break: the next element starts a page."""
    slack: float = 0.0
    """What a line's spacing adds beyond the font's height: the last line of a page may hang
    that far below the text (LibreOffice)."""


def _table(tbl, known: dict[str, Para]) -> Block:
    grid = [int(c.get(f"{_W}w")) for c in tbl.find(f"{_W}tblGrid")] or [TEXT_WIDTH_TWIPS]
    rows = []
    for tr in tbl.findall(f"{_W}tr"):
        tallest = 0.0
        for tc, width in zip(tr.findall(f"{_W}tc"), grid):
            height = 0.0
            for p in tc.iter(f"{_W}p"):
                para = copy.copy(_para(p, known))
                sizes = [int(s.get(f"{_W}val")) / 2 for s in p.iter(f"{_W}sz")]
                para.size = min(sizes) if sizes else para.size
                lines = _lines(_words(p, para.size), width - CELL_PAD_TWIPS - para.indent, 0)
                height += lines * line_pt(para, _cjk(p)) + para.before + para.after
            tallest = max(tallest, height)
        rows.append(tallest + RULE_PT)
    return Block(rows, header=rows[0] if rows else 0.0, splits=True)


def _paragraph(p, known: dict[str, Para]) -> Block:
    para = _para(p, known)
    if any(b.get(f"{_W}type") == "page" for b in p.iter(f"{_W}br")):
        return Block([], breaks=True)
    font_line = para.size * LINE
    spacing = {"before": para.before, "after": para.after, "keep_next": para.keep_next,
               "slack": line_pt(para) - font_line}
    extents = list(p.iter(f"{_WP}extent"))
    if extents:
        height = sum(int(e.get("cy")) for e in extents) / 12700
        return Block([height + line_pt(para) - font_line], **spacing)
    display = p.find(f"{_M}oMathPara")
    if display is not None:
        lines = display.findall(f"{_M}oMath") or [display]
        return Block([sum(_display(m, para) for m in lines)], **spacing)
    lines = _lines(_words(p, para.size), TEXT_WIDTH_TWIPS - para.indent, para.first)
    line = line_pt(para, _cjk(p))
    pieces = [line] * lines
    tallest = max((_math_extra(m) for m in p.iter(f"{_M}oMath")), default=0.0)
    if tallest > _MATH_MM["plain"] * _PT_PER_MM:  # the line that holds it, half of it on each other line
        pieces = [line + tallest] + [line + tallest / 2] * (lines - 1)
    style = p.find(f"{_W}pPr/{_W}pStyle")
    heading = style is not None and style.get(f"{_W}val", "").startswith("Heading")
    return Block(pieces if not heading else [sum(pieces)], splits=not heading, **spacing)


def blocks(doc) -> list[Block | None]:
    """The paginator's view of each element of the body (None: it takes no room)."""
    known = styles(doc)
    out: list[Block | None] = []
    for el in doc.element.body:
        if el.tag == f"{_W}tbl":
            out.append(_table(el, known))
        elif el.tag == f"{_W}p":
            out.append(_paragraph(el, known))
        else:
            out.append(None)
    return out


def _first(block: Block) -> float:
    """What of ``block`` must go on the page of a block kept with it, points: a table whole
    (its header and first row if it is longer than a page), a paragraph's first line."""
    if block.header:
        total = sum(block.pieces)
        return total if total <= PAGE_PT else sum(block.pieces[:2])
    return block.pieces[0] if block.splits and block.pieces else sum(block.pieces)


def estimate_pages(doc, start: int = 1) -> list[int]:
    """The estimated page (from ``start``) on which each element of the body starts."""
    return [page for page, _ in place(blocks(doc), start)]


def place(items: list[Block | None], start: int = 1) -> list[tuple[int, float]]:
    """The page and height on it (points from the top of the text) at which each block starts."""
    page, y, after, hard = start, 0.0, 0.0, True
    pages: list[tuple[int, float]] = []
    for k, block in enumerate(items):
        if block is None or block.breaks:
            pages.append((page, y))
            if block is not None:
                page, y, after, hard = page + 1, 0.0, 0.0, True
            continue
        gap = max(after, block.before) if y > 0 else (block.before if hard else 0.0)
        need = _chain(items, k) + _first(block) - (0.0 if _chain(items, k) else block.slack)
        if y > 0 and (y + gap + need > PAGE_PT and need <= PAGE_PT
                      or not _fit(block, block.pieces, PAGE_PT - y - gap)):
            page, y, gap, hard = page + 1, 0.0, 0.0, False
        pages.append((page, y + gap))
        pieces = block.pieces
        while pieces:
            fit = _fit(block, pieces, PAGE_PT - y - gap) if y > 0 else max(1, _fit(block, pieces, PAGE_PT))
            y += gap + sum(pieces[:fit])
            pieces, gap = pieces[fit:], 0.0
            if pieces:
                page, y, hard = page + 1, block.header, False
        after = block.after
    return pages


def _fit(block: Block, pieces: list[float], room: float) -> int:
    """How many of the pieces left of ``block`` go into ``room`` points: lines of a paragraph
    with two at least on each page (widow and orphan control), rows of a table."""
    n, used = 0, 0.0
    while n < len(pieces) and used + pieces[n] - block.slack <= room:
        used, n = used + pieces[n], n + 1
    if n == len(pieces) or block.header or not block.splits:
        return n
    n = min(n, len(pieces) - 2)
    return n if n >= 2 else 0


def _chain(items: list[Block | None], k: int) -> float:
    """Height of what block ``k`` keeps with it beyond itself (the blocks it is kept with, up
    to what must go with them of the last), points."""
    total, j = 0.0, k
    while items[j] is not None and items[j].keep_next:
        nxt = next((i for i in range(j + 1, len(items)) if items[i] is not None), None)
        if nxt is None or items[nxt].breaks:
            break
        b = items[nxt]
        total += max(items[j].after, b.before) + (_first(b) if not b.keep_next else sum(b.pieces))
        j = nxt
    return total
