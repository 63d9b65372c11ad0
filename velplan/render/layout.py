"""Placing things on the sheet: views on the free area, text in cells; labels that overlap.

Everything works on estimated boxes in sheet millimetres (see
:func:`~velplan.render.shapes.text_extent`); shapely does the geometry.
"""

from __future__ import annotations

import functools
import math
import re
from typing import Literal, Sequence

import numpy as np
import shapely
from shapely.geometry.base import BaseGeometry

from velplan.errors import ScaleError
from velplan.render.scene import Arrow, Bounds, Polygon, Polyline, Scene, Text
from velplan.render.shapes import DESCENDER_DEPTH, MIN_INDEX_MM, MIN_WIDTH_FACTOR, text_box, text_depth, text_extent
from velplan.render.style import ESKD_TEXT_HEIGHTS

__all__ = ["text_extent", "label_box", "overlapping_labels", "place_views",
           "fit_text", "LINE_PITCH"]

#: Distance between the baselines of wrapped lines, as a multiple of the text height.
LINE_PITCH = 1.5
_EPS = 1e-6


def label_box(text: Text) -> shapely.Polygon:
    """Estimated box of `text` as a shapely polygon, mm (rotated with the text)."""
    try:
        return _box_of(text)
    except TypeError:  # a lettering that cannot be hashed
        return shapely.Polygon(text_box(text))


@functools.lru_cache(maxsize=8192)
def _box_of(text: Text) -> shapely.Polygon:
    """`label_box`, remembered: a sheet asks for the same text's box many times, and a
    polygon costs more to make than a text to hash (shapely's geometries are immutable)."""
    return shapely.polygons(text_box(text))  # the same ring as shapely.Polygon's, made from the array at once


def overlapping_labels(scene: Scene, *, layers: Sequence[str] | None = None,
                       min_area: float = 0.0) -> list[tuple[Text, Text]]:
    """Pairs of texts whose estimated boxes overlap.

    Parameters
    ----------
    scene : Scene
        The scene to check.
    layers : sequence of str, optional
        Only texts on these layers; all texts if omitted.
    min_area : float
        Overlap area, mm², a pair must exceed; boxes that only touch never count.

    Returns
    -------
    list of (Text, Text)
        Each pair once, earlier text first, in drawing order.
    """
    texts = [t for t in scene.of_kind(Text) if layers is None or t.layer in layers]
    boxes = [label_box(t) for t in texts]
    tree = shapely.STRtree(boxes)
    pairs = []
    for i, box in enumerate(boxes):
        for j in sorted(int(k) for k in tree.query(box, predicate="intersects")):
            if j > i and box.intersection(boxes[j]).area > min_area:
                pairs.append((texts[i], texts[j]))
    return pairs


def crossed_letters(primitives, *, through_mm: float = 1.0) -> list[Text]:
    """The texts among `primitives` that a drawn line, outline or vector runs through over
    `through_mm` mm (inside the text's box), a text's own leader (a two-point thin line ending
    at its box) excepted: a letter read through a line."""
    lines, leaders = [], []
    for p in primitives:
        if isinstance(p, Polyline) and len(p.points) > 1:
            lines.append(shapely.LineString(p.points))
            leaders.append(p.line == "thin" and len(p.points) == 2)
        elif isinstance(p, Arrow) and p.length > 0:
            lines.append(shapely.LineString([p.start, p.end]))
            leaders.append(False)
        elif isinstance(p, Polygon):
            lines.append(shapely.LinearRing(p.points))
            leaders.append(False)
    if not lines:
        return []
    tree, out = shapely.STRtree(lines), []
    for t in (p for p in primitives if isinstance(p, Text)):
        box = label_box(t)
        own_end = box.buffer(0.6)
        if any(not (leaders[j] and own_end.contains(shapely.Point(lines[j].coords[-1])))
               and lines[j].intersection(box).length > through_mm
               for j in tree.query(box, predicate="intersects")):
            out.append(t)
    return out


def place_views(sizes: Sequence[tuple[float, float]], area: BaseGeometry, *,
                gap_mm: float = 10.0) -> tuple[Bounds, ...]:
    """Place rectangular views, in order, top-left first, without overlap.

    A bottom-left style packer: each view goes to the highest, then leftmost, corner
    formed by the area's top-left and the views already placed, where it lies inside
    `area` and at least `gap_mm` from every other view. Works on L-shaped areas (the
    frame minus the title block).

    Parameters
    ----------
    sizes : sequence of (width, height)
        View sizes, mm.
    area : shapely geometry
        Free drawing area, mm.
    gap_mm : float
        Least clearance between views, mm.

    Returns
    -------
    tuple of (xmin, ymin, xmax, ymax)
        One box per view, mm.

    Raises
    ------
    ScaleError
        If a view does not fit; the message names it and its size.
    """
    region = area.buffer(_EPS)
    left, _, _, top = area.bounds
    placed: list[Bounds] = []
    for index, (width, height) in enumerate(sizes):
        box = _first_fit(width, height, region, left, top, placed, gap_mm)
        if box is None:
            raise ScaleError(f"view {index + 1} ({width:.1f} × {height:.1f} mm) does not fit "
                             f"the free drawing area; choose a smaller scale or a larger "
                             f"sheet")
        placed.append(box)
    return tuple(placed)


def _first_fit(width, height, region, left, top, placed, gap) -> Bounds | None:
    xs = sorted({left, *(b[2] + gap for b in placed)})
    tops = sorted({top, *(b[1] - gap for b in placed)}, reverse=True)
    for y_top in tops:
        for x in xs:
            box = (x, y_top - height, x + width, y_top)
            if region.contains(shapely.box(*box)) and all(
                    _clear(box, other, gap) for other in placed):
                return box
    return None


def _clear(a: Bounds, b: Bounds, gap: float) -> bool:
    dx = max(b[0] - a[2], a[0] - b[2])
    dy = max(b[1] - a[3], a[1] - b[3])
    return dx >= gap - _EPS or dy >= gap - _EPS


def fit_text(text: str, cell: Bounds, *, layer: str, size_mm: float = 3.5,
             anchor: Literal["start", "middle"] = "middle",
             padding_mm: float = 1.0, least_mm: float = MIN_INDEX_MM) -> tuple[Text, ...]:
    """Write `text` inside a rectangular cell, shrinking, narrowing or wrapping it to fit.

    The largest standard height from `least_mm` (the ESKD 2.5 mm) to `size_mm` is used at
    which the text fits the cell on one line, else wrapped on word boundaries onto as many
    lines as the cell height allows; if nothing fits, the least height with its letters
    narrowed (the widest of 0.95, 0.9 … :data:`MIN_WIDTH_FACTOR` that fits); in a cell too
    low for that, the least height on one line, narrowed as its width needs (at least to
    :data:`MIN_WIDTH_FACTOR`).

    Parameters
    ----------
    text : str
        What to write; empty gives no primitives.
    cell : (xmin, ymin, xmax, ymax)
        The cell, mm.
    layer : str
        Layer of the texts.
    size_mm : float
        Preferred (largest) text height, mm.
    anchor : {"start", "middle"}
        Left-aligned after `padding_mm`, or centred.
    padding_mm : float
        Clearance to the cell's sides, mm.
    least_mm : float
        The least text height, mm: the text is narrowed rather than set smaller.

    Returns
    -------
    tuple of Text
        One Text per line, vertically centred in the cell.
    """
    if not text.strip():
        return ()
    room_w = cell[2] - cell[0] - 2 * padding_mm
    room_h = cell[3] - cell[1] - 2 * padding_mm
    sizes = [h for h in sorted(ESKD_TEXT_HEIGHTS, reverse=True) if least_mm - _EPS <= h <= size_mm + _EPS]
    sizes = sizes or [least_mm]
    for size in sizes:
        lines = _lines_in(text, room_w, room_h, size)
        if lines is not None:
            return _cell_lines(lines, cell, layer, size, anchor, padding_mm)
    size = sizes[-1]
    for factor in _NARROWER:
        lines = _lines_in(text, room_w / factor, room_h, size)
        if lines is not None:
            return _cell_lines(lines, cell, layer, size, anchor, padding_mm, factor)
    # too long or the cell too low for any wrapping: one line, as narrow as its width needs
    need = _CELL_MARGIN * text_extent(text, size)[0] / max(room_w, _EPS)
    factor = min(1.0, max(MIN_WIDTH_FACTOR, math.floor(100.0 / need) / 100.0 if need > 1.0 else 1.0))
    return _cell_lines([text], cell, layer, size, anchor, padding_mm, factor)


#: The widths `fit_text` tries, narrowest last.
_NARROWER = tuple(np.round(np.arange(0.95, MIN_WIDTH_FACTOR - _EPS, -0.05), 2))


def _lines_in(text: str, room_w: float, room_h: float, size: float) -> list[str] | None:
    """`text` wrapped to `room_w` mm at `size` mm onto the lines that `room_h` mm holds; None
    when it does not fit."""
    first = (1.0 + DESCENDER_DEPTH) * size  # one line, capitals plus descenders
    if first > room_h + _EPS:
        return None
    most = int((room_h - first + _EPS) // (LINE_PITCH * size)) + 1
    lines = _wrap(text, room_w, size, most)
    if lines is not None and first + sum(line_pitches(lines, size)) > room_h + _EPS:
        return None  # a raised index took a line's room
    return lines


def line_pitches(lines: list[str], size: float, pitch: float = 0.0) -> list[float]:
    """The baseline-to-baseline distance of each line after the first, mm: `pitch` (by default
    :data:`LINE_PITCH`) of the height, more where a raised index ("aᵗ") or a descending
    subscript would come nearer the line beside it (`text_depth`): the gap between them kept as
    plain lines keep it."""
    pitch = pitch or LINE_PITCH
    gap = (pitch - 1.0 - DESCENDER_DEPTH) * size
    return [max(pitch * size, text_depth(a, size)[0] + text_depth(b, size)[1] + gap)
            for a, b in zip(lines, lines[1:])]


#: Rendered Latin and Cyrillic run up to ~10 % wider than `text_extent`'s estimate: a cell
#: keeps that margin.
_CELL_MARGIN = 1.15


def _wrap(text: str, width: float, size: float, count: int) -> list[str] | None:
    """Greedy word wrap onto at most `count` lines no wider than `width`; None if not."""
    width = width / _CELL_MARGIN
    words = glued_words(text)
    lines: list[str] = []
    for word in words:
        trial = f"{lines[-1]} {word}" if lines else word
        if lines and text_extent(trial, size)[0] <= width:
            lines[-1] = trial
        else:
            lines.append(word)
    if len(lines) > count or any(text_extent(line, size)[0] > width for line in lines):
        return None
    return [line.replace("\u00a0", " ") for line in lines]


#: A unit after a number (mm, м/с, Н·м, rad/s², %, …, in the four languages): never the first
#: word of a line.
_UNIT = re.compile(r"^\(?(mm|m|s|N|kg|rad|мм|м|с|Н|кг|рад|毫米|米|秒|牛|%|°)([/·][^\s]*)?[²³]?\)?[,.;:)]*$")


def glued_words(text: str) -> list[str]:
    """The words of `text` for wrapping, a unit kept with the number before it ("63,9 мм")."""
    words: list[str] = []
    for word in text.split():
        if words and words[-1][-1:].isdigit() and _UNIT.match(word):
            words[-1] = f"{words[-1]}\u00a0{word}"
        else:
            words.append(word)
    return words


def _cell_lines(lines, cell, layer, size, anchor, padding, width_factor=1.0) -> tuple[Text, ...]:
    x = cell[0] + padding if anchor == "start" else (cell[0] + cell[2]) / 2
    centre = (cell[1] + cell[3]) / 2
    down = np.concatenate([[0.0], np.cumsum(line_pitches(list(lines), size))])
    offsets = down - down[-1] / 2
    return tuple(Text((x, centre - dy), line, layer, size, anchor, "middle", 0.0, float(width_factor))
                 for line, dy in zip(lines, offsets))
