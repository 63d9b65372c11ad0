"""Shape computations shared by every canvas: arrowheads, hatching, text boxes, strokes.

Backends only translate what these functions return into their own calls, so an SVG sheet
and a matplotlib figure of the same scene show the same geometry. All lengths are sheet
millimetres, origin at the bottom-left corner, y up; angles are degrees, counter-clockwise.
"""

from __future__ import annotations

import functools
import math
import unicodedata
from typing import TYPE_CHECKING, NamedTuple, Protocol

import numpy as np
import shapely

from velplan.notation import MARKED_INDEX, plain_text, unicode_text  # noqa: F401  (plain_text, unicode_text: named here too)
from velplan.render.sans_widths import WIDTHS as _SANS_WIDTHS

if TYPE_CHECKING:
    from velplan.render.style import LineType, SheetStyle

#: Estimated advance of a Latin/Cyrillic character the drawing fonts' table
#: (:mod:`velplan.render.sans_widths`) lacks, as a fraction of the text height.
NARROW_CHAR_WIDTH = 0.7
#: Em size of the sheet fonts over their capital height: SVG sizes text by the em, and a text
#: of height h is set at h/0.72 (:class:`velplan.render.style.SheetStyle`, Latin faces).
EM_PER_CAP = 1 / 0.72
#: Estimated advance of a CJK (full-width) character, as a fraction of the text height.
WIDE_CHAR_WIDTH = 1.0
#: Depth of descenders below the baseline, as a fraction of the text height.
DESCENDER_DEPTH = 0.25
#: Size of an index (sub- or superscript) drawn as a shifted character, relative to the text.
SCRIPT_SCALE = 0.7
#: The smallest index drawn, mm: the ESKD minimum text height (letters of 3.5 mm take indices of
#: 2.5 mm); an index of a letter smaller than this is drawn at the letter's own size.
MIN_INDEX_MM = 2.5
#: The narrowest lettering printed, as a fraction of the normal width at the same height:
#: ESKD type A letters (GOST 2.304, 5/14·h wide) are about 0.6 of type B's (6/10·h). A text
#: that must fit a fixed cell keeps its height and is narrowed, down to this.
MIN_WIDTH_FACTOR = 0.6


def script_size(size_mm: float) -> float:
    """The height of an index of a text `size_mm` high, mm: :data:`SCRIPT_SCALE` of it, but
    never below :data:`MIN_INDEX_MM` (nor above the letter).

    >>> script_size(5.0), script_size(3.5), script_size(2.0)
    (3.5, 2.5, 2.0)
    """
    return max(SCRIPT_SCALE * size_mm, min(size_mm, MIN_INDEX_MM))
#: How far an index's baseline is moved from the text's, as a fraction of the text height:
#: down for a subscript (its digits stay above the descender line), up for a superscript.
SUBSCRIPT_DROP = 0.25
SUPERSCRIPT_RISE = 0.45
# Head length over full head width: an opening angle of 2·atan(1/6) ≈ 19°.
_HEAD_LENGTH_PER_WIDTH = 3.0


class Lettering(Protocol):
    """What the text functions read of a line of text (the scene's ``Text`` primitive): the
    scene builds on these shapes, so they name no scene type."""

    position: tuple[float, float]  # anchor point, mm
    text: str
    size_mm: float  # capital letter height, mm
    anchor: str  # "start", "middle" or "end"
    baseline: str  # "baseline", "middle" or "top"
    rotation_deg: float  # direction of the baseline, degrees counter-clockwise
    width_factor: float  # letters' width over their normal width at this height


class ArrowShape(NamedTuple):
    """An arrow split into what a backend draws.

    Attributes
    ----------
    shaft : ndarray of shape (2, 2) or None
        Start and end of the stroked shaft, mm; None when the head takes the whole arrow.
    head : ndarray of shape (3, 2) or None
        Filled triangle tip, left corner, right corner, mm; None for a zero-length arrow.
    """

    shaft: np.ndarray | None
    head: np.ndarray | None


class Stroke(NamedTuple):
    """How a line is stroked.

    Attributes
    ----------
    width : float
        Stroke width, mm.
    dash : tuple of float
        Dash pattern, mm (dash, gap, …); empty for a solid line.
    colour : str
        SVG colour name.
    cap : {"round", "butt"}
        Line ends: round for solid lines (links meet cleanly at joints), butt for dashed
        ones so that dashes keep their drawn length.
    """

    width: float
    dash: tuple[float, ...]
    colour: str
    cap: str


def stroke_for(line: LineType, layer: str, style: SheetStyle) -> Stroke:
    """Return the stroke of line type `line` on `layer` under `style`."""
    dash = style.dash(line)
    return Stroke(style.width(line), dash, style.stroke_colour(layer),
                  "butt" if dash else "round")


def hatch_stroke(layer: str, style: SheetStyle) -> Stroke:
    """Stroke of hatch lines: thin and solid, whatever the outline's line type."""
    return stroke_for("thin", layer, style)


def arrow_size(head_length: float | None, head_width: float | None,
               style: SheetStyle, stroke_width: float) -> tuple[float, float]:
    """Arrowhead length and width, mm.

    Sizes given on the arrow are used as they are. Defaults come from the style, widened
    to 2.5 stroke widths so that a thick shaft never looks wider than its head, and
    lengthened to keep the head's opening angle near 20° (GOST 2.307).
    """
    width = head_width if head_width is not None else max(style.arrow_width_mm,
                                                          2.5 * stroke_width)
    if head_length is not None:
        return head_length, width
    return max(style.arrow_length_mm, width * _HEAD_LENGTH_PER_WIDTH), width


def arrowhead(start, end, length: float, width: float) -> np.ndarray | None:
    """Triangle of an arrowhead whose tip is at `end`, pointing from `start` to `end`.

    Parameters
    ----------
    start, end : array_like of shape (2,)
        Tail and tip of the vector, mm.
    length, width : float
        Head length along the vector and full width across it, mm. A head longer than
        the vector is shrunk to the vector's length, keeping its proportions.

    Returns
    -------
    ndarray of shape (3, 2) or None
        Tip, left base corner, right base corner, mm; None for a zero-length vector.
    """
    start, end = np.asarray(start, float), np.asarray(end, float)
    span = float(np.hypot(*(end - start)))
    if span == 0.0:
        return None
    along = (end - start) / span
    across = np.array([-along[1], along[0]])
    scale = min(1.0, span / length)
    base = end - along * length * scale
    half = across * width * scale / 2.0
    return np.array([end, base + half, base - half])


def arrow_shape(start, end, head_length: float, head_width: float) -> ArrowShape:
    """Split an arrow into a shaft ending at the base of its head, and the head.

    The shaft stops at the head's base so that a butt- or round-capped stroke never
    pokes past the tip; the round cap stays inside the triangle.
    """
    head = arrowhead(start, end, head_length, head_width)
    if head is None:
        return ArrowShape(None, None)
    base = (head[1] + head[2]) / 2.0
    start = np.asarray(start, float)
    if np.allclose(base, start):
        return ArrowShape(None, head)
    return ArrowShape(np.array([start, base]), head)


def circle_outline(centre, radius: float, *, segments: int = 72) -> np.ndarray:
    """Closed polygon approximating a circle, shape (segments, 2), mm."""
    t = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    return np.asarray(centre, float) + radius * np.column_stack([np.cos(t), np.sin(t)])


def hatch_segments(outline, spacing: float, angle_deg: float = 45.0) -> np.ndarray:
    """Hatch lines filling a polygon, clipped to it.

    Lines are laid at multiples of `spacing` from the sheet origin, so neighbouring
    hatched areas line up as on a hand drawing.

    Parameters
    ----------
    outline : array_like of shape (n, 2)
        Polygon vertices, mm (closing edge implied).
    spacing : float
        Distance between neighbouring lines, mm.
    angle_deg : float
        Direction of the lines, degrees from the x axis.

    Returns
    -------
    ndarray of shape (m, 2, 2)
        Segments (start, end), mm, sorted by their offset across the hatch.
    """
    area = shapely.Polygon(np.asarray(outline, float))
    if area.is_empty or area.area == 0.0:
        return np.empty((0, 2, 2))
    a = math.radians(angle_deg)
    along = np.array([math.cos(a), math.sin(a)])
    normal = np.array([-along[1], along[0]])
    corners = np.asarray(area.exterior.coords)
    offsets = corners @ normal
    reach = float(np.max(np.abs(corners @ along))) + 1.0
    first, last = math.ceil(offsets.min() / spacing), math.floor(offsets.max() / spacing)
    if last < first:
        return np.empty((0, 2, 2))
    centres = (normal * np.arange(first, last + 1, dtype=float)[:, None]) * spacing  # as normal * k * spacing
    ends = np.stack([centres - along * reach, centres + along * reach], axis=1)
    # every line clipped in one call (the same intersections, line by line), then the ends of
    # each straight piece of what is left, in order
    parts = shapely.get_parts(shapely.intersection(area, shapely.linestrings(ends)))
    parts = parts[(shapely.get_type_id(parts) == 1) & ~shapely.is_empty(parts) & (shapely.length(parts) > 1e-9)]
    return np.stack([shapely.get_coordinates(shapely.get_point(parts, 0)),
                     shapely.get_coordinates(shapely.get_point(parts, -1))], axis=1).reshape(-1, 2, 2)


def is_wide_char(char: str) -> bool:
    """True for a full-width (CJK) character, which is about as wide as it is tall."""
    return unicodedata.east_asian_width(char) in ("W", "F")


class TextRun(NamedTuple):
    """A piece of a text drawn at one size and baseline.

    Attributes
    ----------
    text : str
        The characters, indices already turned into the plain ones ("₅" → "5").
    script : {"", "sub", "super"}
        "" for the text's own size and baseline, else an index drawn at
        :func:`script_size` of the size, moved by :data:`SUBSCRIPT_DROP` or
        :data:`SUPERSCRIPT_RISE`.
    """

    text: str
    script: str


@functools.lru_cache(maxsize=4096)
def script_of(char: str) -> tuple[str, str]:
    """The plain character and script ("sub", "super" or "") of one character.

    Unicode subscripts ("₅", "ₐ") and the superscripts outside Latin-1 ("ⁿ", "ᵏ", "ʳ") are
    drawn as shifted plain characters: CJK fonts lack most of them. "²", "³" and the
    ordinals are in every font and stay as they are.
    """
    kind, _, code = unicodedata.decomposition(char).partition(" ")
    if " " in code or not code:
        return char, ""
    if kind == "<sub>":
        return chr(int(code, 16)), "sub"
    if kind == "<super>" and ord(char) > 0xFF:
        return chr(int(code, 16)), "super"
    return char, ""


def _characters(text: str):
    """(plain character, script) of every drawn character of `text`, marked indices as "sub"
    or "super"."""
    at = 0
    for m in MARKED_INDEX.finditer(text):
        yield from _unmarked(text[at:m.start()])
        script = "sub" if m.group(1) == "_" else "super"
        yield from ((script_of(c)[0], script) for c in m.group(2))
        at = m.end()
    yield from _unmarked(text[at:])


def _unmarked(text: str) -> list[tuple[str, str]]:
    """(plain character, script) of each character of `text` (no marked index): a run of
    superscripts with one drawn shifted (``⁻¹⁴``: "⁴" and "⁻" are) is drawn shifted whole, so
    that "¹" does not keep the font's own smaller glyph beside them."""
    out = [script_of(c) for c in text]
    run: list[int] = []
    for i, c in enumerate(text + " "):
        if i < len(text) and unicodedata.decomposition(c).startswith("<super>"):
            run.append(i)
            continue
        if any(out[j][1] == "super" for j in run):
            for j in run:  # every superscript's plain form is its compatibility form ("¹" → "1", "⁻" → "−")
                out[j] = (unicodedata.normalize("NFKC", text[j]), "super")
        run = []
    return out


@functools.lru_cache(maxsize=4096)  # a sheet writes the same few labels over and over
def text_runs(text: str) -> tuple[TextRun, ...]:
    """Split `text` into runs of one script each; a text without indices is one run.

    Examples
    --------
    >>> text_runs("ω₂")
    (TextRun(text='ω', script=''), TextRun(text='2', script='sub'))
    >>> [run.text for run in text_runs("aⁿ_A4O3 = 2 м/с²")]
    ['a', 'n', '_A4O3 = 2 м/с²']
    >>> text_runs("v_{K3} =")
    (TextRun(text='v', script=''), TextRun(text='K3', script='sub'), TextRun(text=' =', script=''))
    """
    runs: list[TextRun] = []
    for plain, script in _characters(text):
        if runs and runs[-1].script == script:
            runs[-1] = TextRun(runs[-1].text + plain, script)
        else:
            runs.append(TextRun(plain, script))
    return tuple(runs)


@functools.lru_cache(maxsize=4096)  # a view measures the same few labels over and over
def text_extent(text: str, size_mm: float) -> tuple[float, float]:
    """Estimated width and height of a one-line text, mm.

    Parameters
    ----------
    text : str
        The text (one line).
    size_mm : float
        Text height (capital letter height), mm.

    Returns
    -------
    (float, float)
        Width: each Latin/Greek/Cyrillic character's advance in the drawing fonts
        (:mod:`velplan.render.sans_widths`, the em set at :data:`EM_PER_CAP`·h: "5" 0.79·h,
        "G" 0.97·h, "Ж" 1.35·h), 0.7·h for one they lack, 1.0·h per CJK character, an index
        ("₅", "ⁿ") counted at its :func:`script_size`, as backends draw it;
        height from the descender line to the capital line, 1.25·h.
    """
    return _extent(text, float(size_mm))


@functools.lru_cache(maxsize=8192)
def _extent(text: str, size_mm: float) -> tuple[float, float]:
    """`text_extent`, remembered: a sheet measures the same labels in many trials."""
    units, index = 0.0, script_size(size_mm) / size_mm if size_mm > 0 else SCRIPT_SCALE
    for plain, script in _characters(text):
        width = WIDE_CHAR_WIDTH if is_wide_char(plain) else _char_width(plain)
        units += width * (index if script else 1.0)
    return units * size_mm, (1.0 + DESCENDER_DEPTH) * size_mm


def _char_width(char: str) -> float:
    """Advance of a narrow character as a fraction of the text height: the drawing fonts'
    (:mod:`velplan.render.sans_widths`), else :data:`NARROW_CHAR_WIDTH`."""
    em = _SANS_WIDTHS.get(char)
    return NARROW_CHAR_WIDTH if em is None else em * EM_PER_CAP


#: Letters that reach below the baseline (Latin, Cyrillic, Greek): a subscript holding one reaches
#: its own descender line, one without stays on its baseline.
DESCENDING = frozenset("gjpqyдруфцщзДЦЩβγζημξρφχψ,;()")


@functools.lru_cache(maxsize=8192)
def text_depth(text: str, size_mm: float) -> tuple[float, float]:
    """How far a one-line text reaches below and above its baseline, mm, as drawn: from the
    descender line (:data:`DESCENDER_DEPTH` of the height) to the capital line, and farther
    where a subscript, dropped :data:`SUBSCRIPT_DROP` of the height, has a descending letter:
    it reaches its own descender line ("M_{Fg}": its g; "M_{д}"); and where a superscript,
    raised :data:`SUPERSCRIPT_RISE`, reaches its own capital line (its x-height for a short
    lowercase letter: "aⁿ").

    >>> text_depth("G₅", 2.5), text_depth("M_{Fg}", 2.5), text_depth("10⁻⁵", 2.5)
    ((0.625, 2.5), (1.25, 2.5), (0.625, 3.625))
    """
    below, above = DESCENDER_DEPTH * size_mm, size_mm
    for plain, script in _characters(text):
        if script == "sub" and plain in DESCENDING:
            below = max(below, SUBSCRIPT_DROP * size_mm + DESCENDER_DEPTH * script_size(size_mm))
        elif script == "super":
            low = plain in SHORT  # a raised "n" reaches its x-height, a raised "1" its capital line
            above = max(above, SUPERSCRIPT_RISE * size_mm + (X_HEIGHT if low else 1.0) * script_size(size_mm))
    return below, above


#: Lowercase letters that reach no higher than the x-height (:data:`X_HEIGHT` of the capitals'):
#: a raised one ("aⁿ") reaches less high than a raised digit or capital.
SHORT = frozenset("acemnorsuvwxzταεικνοπστυωабвгежзиклмнопрстухцчшщъыьэюя")
#: The x-height of the drawing fonts as a share of their capital height (DejaVu Sans: 0.75).
X_HEIGHT = 0.75


def text_origin(text: Lettering) -> np.ndarray:
    """Point on the alphabetic baseline where a backend anchors `text`, mm.

    ``baseline="middle"`` centres the capitals on `text.position`, ``"top"`` hangs them
    from it; the shift is taken across the text's own direction, so rotated text moves
    the same way relative to its letters.
    """
    drop = {"baseline": 0.0, "middle": 0.5, "top": 1.0}[text.baseline] * text.size_mm
    a = math.radians(text.rotation_deg)
    return np.asarray(text.position, float) - drop * np.array([-math.sin(a), math.cos(a)])


def text_box(text: Lettering) -> np.ndarray:
    """Corners of the estimated box of `text`, shape (4, 2), mm, counter-clockwise: its width
    (`text_extent`) by its reach below and above the baseline (`text_depth`)."""
    width = text_extent(text.text, text.size_mm)[0] * text.width_factor
    x0 = -width * {"start": 0.0, "middle": 0.5, "end": 1.0}[text.anchor]
    below, top = text_depth(text.text, text.size_mm)
    y0 = -below
    if text.rotation_deg == 0.0:  # upright: the same numbers in plain arithmetic, without arrays
        ox = float(text.position[0])
        oy = float(text.position[1]) - {"baseline": 0.0, "middle": 0.5, "top": 1.0}[text.baseline] * text.size_mm
        x1 = x0 + width
        return np.array([[ox + x0, oy + y0], [ox + x1, oy + y0], [ox + x1, oy + top],
                         [ox + x0, oy + top]])
    local = np.array([[x0, y0], [x0 + width, y0],
                      [x0 + width, top], [x0, top]])
    return text_origin(text) + rotate(local, text.rotation_deg)


def rotate(points, angle_deg: float, about=(0.0, 0.0)) -> np.ndarray:
    """Rotate points (..., 2) by `angle_deg` counter-clockwise about `about`, mm."""
    about = np.asarray(about, float)
    if angle_deg == 0.0:  # the turn by 0 (x·1 + y·0) leaves every coordinate as it is
        return (np.asarray(points, float) - about) + about
    a = math.radians(angle_deg)
    turn = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return (np.asarray(points, float) - about) @ turn.T + about


def upright_angle(direction_deg: float) -> float:
    """The text angle along `direction_deg` that reads left-to-right, in (-90, 90] degrees."""
    a = (direction_deg + 180.0) % 360.0 - 180.0
    if a > 90.0:
        return a - 180.0
    if a <= -90.0:
        return a + 180.0
    return a
