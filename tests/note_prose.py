"""Reading the prose of a note's .docx for the tests: the text of each paragraph outside its
equations, and the words of Latin script that are not symbols, units or formulas."""

from __future__ import annotations

import re

from docx.oxml.ns import qn

M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"
PROSE_STYLES = ("BodyText", "FirstParagraph", "Heading1", "Heading2", "Heading3", "TableCaption", "ImageCaption",
                "Compact")
LATIN_WORD = re.compile(r"[A-Za-z]+")
SYMBOL = re.compile(r"^(?:max|min|[A-Za-z]{1,2}|[A-Z][a-z]?[IV]*|JI{1,2}|TI{1,2})$")
"""A symbol written in plain text: one or two letters (V, VA, Fc, Fb, Mb, pa), JI, TII."""
UNITS = frozenset({"m", "mm", "s", "N", "kg", "rad", "min", "rpm", "kW", "W", "J", "r", "Hz"})
"""Units a zh note writes in Latin (ru/uk write theirs in Cyrillic)."""


def _style(p) -> str:
    s = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
    return s.get(qn("w:val")) if s is not None else ""


def prose(body) -> list[tuple[str, str]]:
    """(style, text outside equations) of each prose paragraph and table cell of ``body``."""
    out = []
    for p in body.iter(qn("w:p")):
        style = _style(p)
        if style not in PROSE_STYLES:
            continue
        text = "".join(t.text or "" for t in p.iter(qn("w:t"))
                       if not any(a.tag.startswith(M) for a in t.iterancestors()))
        out.append((style, text))
    return out


def latin_words(text: str, lang: str) -> list[str]:
    """Words of Latin script in ``text`` that are not a symbol or (zh) a unit."""
    return [w for w in LATIN_WORD.findall(text) if not SYMBOL.match(w) and not (lang == "zh" and w in UNITS)]


def ascii_subscripts(text: str) -> list[str]:
    """Programmer's notation in ``text``: an underscore, or a symbol letter followed by a
    plain digit (ω2, V_A4, O3A, pa4) where the course writes a subscript."""
    return re.findall(r"\w*_\w*|(?<![\w.])[A-Za-zωεφμ][A-Za-z]?\d+[A-Za-z]*", text)
