"""The symbols in the cells of the note's tables typeset as in its text: a symbol's index as a
subscript (``VA₄`` → V with "A4" below the line, ``ω2``, ``O2``, ``Mд``, ``JI``, ``ΔTII``),
written in pandoc Markdown's ``~…~`` (a subscript run in Word, ``<sub>`` in HTML)."""

from __future__ import annotations

import re

from velplan.notation import split_symbol  # noqa: F401  (named here too: the note's readers)

_WORD = re.compile(r"[A-Za-zА-Яа-яЁёΔΦωεφψ0-9₀-₉]+(?P<mark>[τ⊥∥](?![\w]))?")
"""A word of a cell; a reaction's component carries its mark after its index (R₄₅τ, R₂₃⊥; R₁₄n,
whose n the word takes in: `cell_markdown` parts it)."""
def cell_markdown(cell: str, escape) -> str:
    """``cell`` in pandoc Markdown, each symbol's index as a subscript ``~…~`` and a reaction
    component's mark (τ, n, ⊥, ∥) as a superscript ``^…^``, as the sheets draw them; ``escape`` makes plain text safe in Markdown.

    >>> cell_markdown("R₄₅τ", str), cell_markdown("R₀₄", str), cell_markdown("VA₄", str)
    ('R~45~^τ^', 'R~04~', 'V~A4~')
    >>> cell_markdown("R₁₄n", str), cell_markdown("R₂₃⊥", str)
    ('R~14~^n^', 'R~23~^⊥^')
    """
    out, at = [], 0
    for m in _WORD.finditer(cell):
        mark = m.group("mark") or ""
        word = m.group(0)[:len(m.group(0)) - len(mark)]
        if not mark and re.search(r"[0-9₀-₉]n$", word):  # a normal component (R₁₄n), as the sheet raises it
            word, mark = word[:-1], "n"
        found = split_symbol(word)
        if found is None or (mark and not found[1].isdigit()):
            continue
        out.append(escape(cell[at:m.start()]) + escape(found[0]) + "~" + escape(found[1]) + "~"
                   + (f"^{escape(mark)}^" if mark else ""))
        at = m.end()
    out.append(escape(cell[at:]))
    return "".join(out)
