"""What the force views share: text sizes, layer names, force labels and units, small vector
helpers and the title and note lines written above and under a view."""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Text
from velplan.render.layout import line_pitches
from velplan.render.shapes import text_depth
from velplan.views.base import bounds_of
from velplan.notation import force_text, number as _num  # noqa: F401  (force_text: named here too)


@dataclass(frozen=True)
class ForceSizes:
    """Text heights and the conventional length of a force arrow, mm; ``wrap_balance``: write
    the lever's balance on two lines where it is wider than the lever (small formats)."""

    title_mm: float = 5.0
    label_mm: float = 3.5
    arrow_mm: float = 16.0
    wrap_balance: bool = False


@dataclass
class Sketch:
    """What a view has drawn so far, mm: its primitives, the shapes that arrows and labels
    keep clear of (None: nothing to avoid), and the straight lines drawn, as (start, end)."""

    items: list = field(default_factory=list)
    obstacles: list = field(default_factory=list)
    lines: list = field(default_factory=list)

    def clear_of(self) -> list:
        """The obstacles, the Nones left out."""
        return [o for o in self.obstacles if o is not None]


# -- names -------------------------------------------------------------------------------


def slug(name: str) -> str:
    """A group's name as it appears in layer and view names (``"3-4"`` → ``"3-4"``)."""
    return re.sub(r"[^a-z0-9-]+", "-", name.lower()).strip("-") or "g"


def group_layers(number: int, group: str) -> tuple[str, str, str]:
    """(links, forces, labels) layers of a group drawn at position `number`."""
    base = f"fgroup-{number}-{slug(group)}"
    return base, f"{base}-forces", f"{base}-labels"


def polygon_layers(number: int, group: str) -> tuple[str, str, str]:
    """(vectors, construction lines, labels) layers of a group's force polygon."""
    base = f"fpoly-{number}-{slug(group)}"
    return base, f"{base}-lines", f"{base}-labels"


def lever_layers(number: int) -> tuple[str, str, str]:
    """(lever, forces, labels) layers of Zhukovsky's lever at position `number`."""
    base = f"lever-{number}"
    return base, f"{base}-forces", f"{base}-labels"


def newton(lang: Language) -> str:
    """The unit N as written in `lang`."""
    return label("unit_newton", lang)


def newton_metre(lang: Language) -> str:
    """The unit N·m as written in `lang`."""
    return label("unit_newton_metre", lang)


def number_text(x: float, lang: Language) -> str:
    """A scale value as written (``0.25`` → ``"0,25"`` in ru)."""
    return _num(x, lang)


# -- vectors -----------------------------------------------------------------------------


def xy(z: complex) -> np.ndarray:
    """A complex number as (x, y)."""
    return np.array([float(np.real(z)), float(np.imag(z))])


def unit_vector(v) -> np.ndarray:
    """`v` (x, y) scaled to length 1."""
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def anchor_of(u) -> str:
    """Horizontal anchor of a text written beyond a point in the direction `u`."""
    return "start" if u[0] > 0.35 else ("end" if u[0] < -0.35 else "middle")


def away_from_lines(p, lines) -> np.ndarray:
    """The sum of the unit vectors from `p` away along every drawn line that starts at `p`
    (within 0.8 mm): where a letter of the point goes is opposite it."""
    away = np.zeros(2)
    for a, b in lines:
        for here, other in ((a, b), (b, a)):
            if np.hypot(*(here - p)) < 0.8 and np.hypot(*(other - here)) > 1e-9:
                away -= unit_vector(other - here)
    return away


# -- lines of text -----------------------------------------------------------------------


def title_lines(items, lines: list[tuple[str, float]], layer: str) -> list[Text]:
    """Title lines (text, height mm) stacked above everything in `items`, first on top."""
    x0, _, _, y1 = bounds_of(items)
    out = []
    y = y1 + 3.0
    for text, size in reversed(lines):
        out.append(Text((x0, y), text, layer, size))
        y += 1.6 * size
    return out


#: Baseline-to-baseline distance of the lines under a force drawing, in text heights.
NOTE_PITCH = 1.6


def note_lines(items, lines: list[str], size: float, layer: str) -> list[Text]:
    """Lines `size` mm high written under everything in `items`, `NOTE_PITCH` heights apart,
    farther where a raised index (R_{12}^{τ}) or a descending subscript would come nearer the
    line beside it (`line_pitches`)."""
    if not lines:
        return []
    x0, y0, _, _ = bounds_of(items)
    y = y0 - 2.0 - text_depth(lines[0], size)[1]  # the first line's capitals 2 mm under them
    out = [Text((x0, y), lines[0], layer, size)]
    for text, step in zip(lines[1:], line_pitches(lines, size, NOTE_PITCH)):
        y -= step
        out.append(Text((x0, y), text, layer, size))
    return out
