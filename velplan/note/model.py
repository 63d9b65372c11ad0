"""The explanatory note as data: a flat list of blocks (`velplan.note.blocks`) that every writer
renders.

Text is plain Unicode (the sheets' own strings); formulas are TeX (`Math` inline,
`Equation` displayed), which pandoc turns into Word equations (OMML), MathML and Typst math.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field


from velplan.note.blocks import (  # noqa: F401  (the blocks, re-exported)
    Block, Contents, Equation, Figure, Heading, Math, PageBreak, Para, Table, TitlePage)
from velplan.note.cells import split_symbol
from velplan.options import Language


ROWS_PER_PAGE = 30
"""Rows of a table on one page of the note (A4, 11–12 pt): a longer table is split in parts."""


@dataclass
class Note:
    """The note: its language, title and blocks; `figure` and `table` number them."""

    lang: Language
    title: str
    blocks: list = field(default_factory=list)
    figures: int = 0
    tables: int = 0

    def add(self, *blocks) -> None:
        self.blocks.extend(blocks)

    def save(self, path):
        """Write the note to ``path`` in the format its suffix names (.docx, .pdf, .html, .md;
        `velplan.note.write_note`)."""
        from velplan.note.writers import write_note

        return write_note(self, path)

    def figure(self, caption: str, picture, width_mm: float) -> int:
        """Add a figure (a `velplan.note.figures.Picture`) with the next number; returns the
        number."""
        from velplan.note.text import p

        self.figures += 1
        self.add(Figure(f"{p('figure', self.lang)} {self.figures} — {caption}", picture, width_mm,
                        f"figure-{self.figures}"))
        return self.figures

    def table(self, caption: str, header, rows, key: str = "") -> int:
        """Add a table with the next number; returns the number. A table of more than
        `ROWS_PER_PAGE` rows goes in parts of that many, each after the first captioned
        "Продолжение таблицы N" (ГОСТ 2.105) over its header repeated."""
        from velplan.note.text import p

        self.tables += 1
        header = [capital_header(h) for h in header]
        rows = [tuple(r) for r in rows]
        parts = [rows[k:k + ROWS_PER_PAGE] for k in range(0, len(rows), ROWS_PER_PAGE)] or [[]]
        self.add(Table(f"{p('table', self.lang)} {self.tables} — {caption}", tuple(header), tuple(parts[0]), key))
        for j, part in enumerate(parts[1:], 2):
            self.add(Table(p("table_continued", self.lang, self.tables), tuple(header), tuple(part),
                           f"{key}-part-{j}" if key else ""))
        return self.tables

    @property
    def equations(self) -> int:
        """Displayed equations in the note."""
        return sum(isinstance(b, Equation) for b in self.blocks)


def capital_header(cell: str) -> str:
    """A table's column heading with a capital first letter where it starts with a word
    ("по плану" → "По плану", "segment, mm" → "Segment, mm"; ГОСТ 2.105); one that starts
    with a symbol ("h, мм", "ω3/ω2", "aA4") is left as it is.

    >>> [capital_header(c) for c in ("пол.", "read off the plan", "h, мм", "ω3/ω2", "aA4", "δ, %", "k²")]
    ['Пол.', 'Read off the plan', 'h, мм', 'ω3/ω2', 'aA4', 'δ, %', 'k²']
    """
    word = re.match(r"\w+", str(cell))
    letters = re.match(r"[^\W\d_²³]+", word.group(0)) if word else None
    if letters is None or len(letters.group(0)) < 2 or split_symbol(word.group(0)):
        return cell
    return cell[0].upper() + cell[1:]
