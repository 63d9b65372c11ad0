"""The blocks of an explanatory note, each a frozen value every writer renders.

Text is plain Unicode (the sheets' own strings); formulas are TeX (`Math` inline,
`Equation` displayed), which pandoc turns into Word equations (OMML), MathML and Typst math.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Math:
    """An inline formula, TeX."""

    tex: str


@dataclass(frozen=True)
class Para:
    """A paragraph: text pieces and inline formulas."""

    parts: tuple

    @classmethod
    def of(cls, *parts) -> "Para":
        return cls(tuple(parts))


@dataclass(frozen=True)
class Equation:
    """A displayed formula, TeX."""

    tex: str


@dataclass(frozen=True)
class Heading:
    text: str
    level: int = 1
    numbered: bool = True
    """False for the introduction, conclusion and references (unnumbered, ГОСТ 2.105)."""


@dataclass(frozen=True)
class Table:
    """A table with its numbered caption; cells are plain text, as the sheets print them."""

    caption: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    key: str = ""
    """What the table holds, for readers of the data (``"velocities-4"``); not printed."""


@dataclass(frozen=True)
class Figure:
    """A numbered figure: the sheets' drawings (a `velplan.note.figures.Picture`: SVG, and
    its PNG when a format needs pixels) and its size on the page."""

    caption: str
    picture: object = field(repr=False)
    width_mm: float
    name: str
    """The file's stem (``figure-3``): the writers add ``.png`` or ``.svg``."""

    @property
    def png(self) -> bytes:
        """The figure's PNG (made on first use)."""
        return self.picture.png()

    @property
    def svg(self) -> str:
        """The figure's SVG document, sized in mm."""
        return self.picture.svg


@dataclass(frozen=True)
class TitlePage:
    """The title page: the document's kind, the topic and the ESKD fields (label, value)."""

    organisation: str
    kind: str
    course: str
    topic: str
    designation: str
    fields: tuple[tuple[str, str], ...]
    place_year: str


@dataclass(frozen=True)
class Contents:
    title: str


@dataclass(frozen=True)
class PageBreak:
    pass


Block = Para | Equation | Heading | Table | Figure | TitlePage | Contents | PageBreak
