"""The symbols in the cells of the note's tables typeset as in its text: a symbol's index as a
subscript (``VA₄`` → V with "A4" below the line, ``ω2``, ``O2``, ``Mд``, ``JI``, ``ΔTII``),
written in pandoc Markdown's ``~…~`` (a subscript run in Word, ``<sub>`` in HTML)."""

from __future__ import annotations

import re

from velplan.notation import plain_digits

_WORD = re.compile(r"[A-Za-zА-Яа-яЁёΔΦωεφψ0-9₀-₉]+(?P<mark>τ(?![\w]))?")
"""A word of a cell; a force's tangential component carries τ after its index (R₄₅τ)."""
SYMBOL = re.compile(r"^(?P<delta>Δ?)(?P<head>[A-Za-zΦωεφψ])(?P<index>[A-Za-zА-Яа-яΦ0-9₀-₉]+)$")
"""A symbol and its index, one word: a Latin or Greek letter, then what is written below it."""
LOWER_HEADS = frozenset("avlm")
"""Lowercase letters that head a symbol (a, v, l, m: accelerations, velocities, lengths, masses)."""
WORD_INDICES = frozenset({"c", "d", "m", "max", "min", "ср"})
"""Lowercase Latin indices of the course's symbols (Mc, Md, ωm, ωmax)."""


def split_symbol(word: str) -> tuple[str, str] | None:
    """(the symbol with its marks, its index) of a word the tables write as a symbol, else None.

    >>> split_symbol("VA₄"), split_symbol("ω2"), split_symbol("Mд"), split_symbol("ΔTII")
    (('V', 'A4'), ('ω', '2'), ('M', 'д'), ('ΔT', 'II'))
    >>> split_symbol("Value"), split_symbol("II"), split_symbol("at"), split_symbol("0,25"), split_symbol("RPR")
    (None, None, None, None, None)
    """
    m = SYMBOL.match(word)
    if not m or re.fullmatch(r"[IVX]+|[RP]{3}", word):  # a Roman numeral, a dyad's kind (RPR)
        return None
    head, index = m.group("head"), m.group("index")
    if head.islower() and head.isascii() and head not in LOWER_HEADS:
        return None
    digits = any(c.isdigit() for c in index)
    cyrillic = bool(re.fullmatch(r"[А-Яа-яЁё]{1,3}", index))
    capitals = plain_digits(index).strip("0123456789").isupper() or index.strip("Φ") == ""
    if not (digits or cyrillic or capitals or index in WORD_INDICES):
        return None
    if head.isascii() and head.islower() and not (digits or capitals):
        return None
    return m.group("delta") + head, plain_digits(index)


def cell_markdown(cell: str, escape) -> str:
    """``cell`` in pandoc Markdown, each symbol's index as a subscript ``~…~`` and a force's
    τ as a superscript ``^…^``; ``escape`` makes plain text safe in Markdown.

    >>> cell_markdown("R₄₅τ", str), cell_markdown("R₀₄", str), cell_markdown("VA₄", str)
    ('R~45~^τ^', 'R~04~', 'V~A4~')
    """
    out, at = [], 0
    for m in _WORD.finditer(cell):
        mark = m.group("mark") or ""
        found = split_symbol(m.group(0)[:len(m.group(0)) - len(mark)])
        if found is None or (mark and not found[1].isdigit()):
            continue
        out.append(escape(cell[at:m.start()]) + escape(found[0]) + "~" + escape(found[1]) + "~"
                   + (f"^{escape(mark)}^" if mark else ""))
        at = m.end()
    out.append(escape(cell[at:]))
    return "".join(out)
