"""The symbols in the cells of the note's tables typeset as in its text: a symbol's index as a
subscript (``VA₄`` → V with "A4" below the line, ``ω2``, ``O2``, ``Mд``, ``JI``, ``ΔTII``),
written in pandoc Markdown's ``~…~`` (a subscript run in Word, ``<sub>`` in HTML)."""

from __future__ import annotations

import re

from velplan.notation import split_symbol  # noqa: F401  (named here too: the note's readers)

_WORD = re.compile(r"[A-Za-zА-Яа-яЁёΔΦωεφψ0-9₀-₉]+(?P<mark>τ(?![\w]))?")
"""A word of a cell; a force's tangential component carries τ after its index (R₄₅τ)."""
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
