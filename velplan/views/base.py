"""Views: a block of primitives in its own millimetres, placed on a sheet by translation.

A view builder (the kinematic scheme, a plan, a table, a diagram) draws in *content*
coordinates — model units divided by the view's scale, or plain mm — and :func:`make_view`
moves the result so that its box starts at (0, 0). Placing a view on the sheet is one more
translation; scale and placement stay out of the geometry, as DESIGN.md asks.

Also here: label formatting shared by the views (scale labels and units in the sheet's
language); the notation itself (subscript digits, the minus sign, numbers to significant
figures) is `velplan.notation`'s, named here too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import chain
from types import MappingProxyType
from typing import Iterable, Mapping

import numpy as np

from velplan.notation import (  # noqa: F401  (named here too for the views that import them from here)
    MINUS, POWER_BELOW, POWER_FROM, ROUND_OFF, decimal, digits_down, fixed, indexed, number, power_of_ten, subscript)
from velplan.options import Language
from velplan.render.scene import Arrow, Bounds, Circle, Polygon, Polyline, Primitive


#: Per primitive class, (name, slot descriptor) of each of its fields (made once).
_SLOTS: dict[type, tuple] = {}


def _moved(item: Primitive, **fields) -> Primitive:
    # A validated primitive moved by finite amounts stays valid: copy it field by field
    # instead of re-validating every point (sheets move thousands of them).
    cls = type(item)
    slots = _SLOTS.get(cls)
    if slots is None:
        slots = _SLOTS[cls] = tuple((name, getattr(cls, name)) for name in cls.__slots__)
    new = object.__new__(cls)
    for name, slot in slots:
        slot.__set__(new, fields[name] if name in fields else slot.__get__(item, cls))
    return new


def shift(item: Primitive, dx: float, dy: float) -> Primitive:
    """The primitive moved by (dx, dy) mm."""
    dx, dy = float(dx), float(dy)
    if not (math.isfinite(dx) and math.isfinite(dy)):
        raise ValueError(f"cannot move a primitive by ({dx}, {dy}) mm")
    if isinstance(item, (Polyline, Polygon)):
        return _moved(item, points=tuple([(x + dx, y + dy) for x, y in item.points]))
    if isinstance(item, Circle):
        return _moved(item, centre=(item.centre[0] + dx, item.centre[1] + dy))
    if isinstance(item, Arrow):
        return _moved(item, start=(item.start[0] + dx, item.start[1] + dy),
                      end=(item.end[0] + dx, item.end[1] + dy))
    return _moved(item, position=(item.position[0] + dx, item.position[1] + dy))


def bounds_of(items: Iterable[Primitive]) -> Bounds:
    """(xmin, ymin, xmax, ymax) of primitives (text by its estimated box), mm."""
    boxes, points = [], []
    for p in items:
        if isinstance(p, (Polyline, Polygon)):
            points.extend(p.points)  # every line's points, reduced once below
        else:
            boxes.append(p.bounds)
    if points:
        xy = np.fromiter(chain.from_iterable(points), float, 2 * len(points)).reshape(-1, 2)  # ≈ 2× asarray's speed
        boxes.append((*xy.min(axis=0), *xy.max(axis=0)))
    if not boxes:
        raise ValueError("no primitives to take the bounds of")
    b = np.asarray(boxes, float)
    return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))


@dataclass(frozen=True)
class View:
    """A drawing block in its own mm, its box from (0, 0) to (width_mm, height_mm).

    Attributes
    ----------
    name : str
        What it is (``"mechanism"``, ``"plan-v-4"``, ``"table"``, ``"diagrams"``).
    primitives : tuple of Primitive
        In the view's mm.
    width_mm, height_mm : float
        Size of the box, mm.
    mu : float or None
        Model units per mm of the drawing (μl, μv, μa); None for tables.
    origin : (float, float)
        Where the model origin (the pole of a plan) lies in the view's mm.
    meta : Mapping
        Anything the builder wants to tell the sheet or the tests (scales, positions).
    """

    name: str
    primitives: tuple[Primitive, ...]
    width_mm: float
    height_mm: float
    mu: float | None = None
    origin: tuple[float, float] = (0.0, 0.0)
    meta: Mapping = field(default_factory=lambda: MappingProxyType({}))

    def to_view(self, xy) -> np.ndarray:
        """Model coordinates (m, or mm of a plan at its scale) → the view's mm."""
        xy = np.asarray(xy, float)
        scale = 1.0 if self.mu is None else 1.0 / self.mu
        return np.asarray(self.origin) + xy * scale

    def at(self, x: float, y: float) -> "PlacedView":
        """This view with its lower-left corner at (x, y) on the sheet, mm."""
        return PlacedView(self, float(x), float(y))


@dataclass(frozen=True)
class PlacedView:
    """A view placed on the sheet."""

    view: View
    x: float
    y: float

    @property
    def bounds(self) -> Bounds:
        """The view's box on the sheet, mm."""
        return (self.x, self.y, self.x + self.view.width_mm, self.y + self.view.height_mm)

    @property
    def primitives(self) -> tuple[Primitive, ...]:
        return tuple(shift(p, self.x, self.y) for p in self.view.primitives)

    def to_sheet(self, xy) -> np.ndarray:
        """Model coordinates → sheet mm."""
        return self.view.to_view(xy) + np.array([self.x, self.y])


def make_view(name: str, items: Iterable[Primitive], *, pad_mm: float = 2.0,
              mu: float | None = None, origin=(0.0, 0.0), meta: Mapping | None = None,
              min_size: tuple[float, float] = (0.0, 0.0)) -> View:
    """Wrap primitives drawn in content mm into a view whose box starts at (0, 0).

    Parameters
    ----------
    items : iterable of Primitive
        Drawn in content mm; `origin` is where the model origin lies in those mm.
    pad_mm : float
        Margin kept around everything, mm.
    """
    items = tuple(items)
    x0, y0, x1, y1 = bounds_of(items)
    dx, dy = pad_mm - x0, pad_mm - y0
    width = max(x1 - x0 + 2 * pad_mm, min_size[0])
    height = max(y1 - y0 + 2 * pad_mm, min_size[1])
    return View(name, tuple(shift(p, dx, dy) for p in items), width, height, mu,
                (origin[0] + dx, origin[1] + dy), MappingProxyType(dict(meta or {})))


# -- text helpers ---------------------------------------------------------------------------


def row_decimals(values, digits: int = 3) -> int:
    """Decimals that give the largest magnitude of `values` `digits` significant figures (every
    entry of a table's row to the same absolute precision, as read off one plan); 0 for a row
    of zeros."""
    a = np.abs(np.asarray(values, float))
    a = a[np.isfinite(a)]
    top = float(a.max()) if a.size else 0.0
    if top == 0.0:
        return 0
    return max(0, digits - 1 - math.floor(math.log10(float(f"{top:.{digits}g}"))))


_UNITS: Mapping[str, Mapping[str, str]] = MappingProxyType({
    "m/mm": MappingProxyType({"en": "m/mm", "ru": "м/мм", "uk": "м/мм", "zh": "m/mm"}),
    "(m/s)/mm": MappingProxyType({"en": "(m/s)/mm", "ru": "(м/с)/мм", "uk": "(м/с)/мм",
                                  "zh": "(m/s)/mm"}),
    "(m/s²)/mm": MappingProxyType({"en": "(m/s²)/mm", "ru": "(м/с²)/мм", "uk": "(м/с²)/мм",
                                   "zh": "(m/s²)/mm"}),
    "rad/mm": MappingProxyType({"en": "rad/mm", "ru": "рад/мм", "uk": "рад/мм", "zh": "rad/mm"}),
    "1/mm": MappingProxyType({"en": "1/mm", "ru": "1/мм", "uk": "1/мм", "zh": "1/mm"}),
    "mm": MappingProxyType({"en": "mm", "ru": "мм", "uk": "мм", "zh": "mm"}),
    "m": MappingProxyType({"en": "m", "ru": "м", "uk": "м", "zh": "m"}),
    "rad": MappingProxyType({"en": "rad", "ru": "рад", "uk": "рад", "zh": "rad"}),
    "deg": MappingProxyType({"en": "°", "ru": "°", "uk": "°", "zh": "°"}),
    "J": MappingProxyType({"en": "J", "ru": "Дж", "uk": "Дж", "zh": "J"}),
    "N": MappingProxyType({"en": "N", "ru": "Н", "uk": "Н", "zh": "N"}),
    "N·m": MappingProxyType({"en": "N·m", "ru": "Н·м", "uk": "Н·м", "zh": "N·m"}),
    "kg·m²": MappingProxyType({"en": "kg·m²", "ru": "кг·м²", "uk": "кг·м²", "zh": "kg·m²"}),
    "kg": MappingProxyType({"en": "kg", "ru": "кг", "uk": "кг", "zh": "kg"}),
    "kg/m³": MappingProxyType({"en": "kg/m³", "ru": "кг/м³", "uk": "кг/м³", "zh": "kg/m³"}),
    "rad/s": MappingProxyType({"en": "rad/s", "ru": "рад/с", "uk": "рад/с", "zh": "rad/s"}),
    "s": MappingProxyType({"en": "s", "ru": "с", "uk": "с", "zh": "s"}),
    "s/mm": MappingProxyType({"en": "s/mm", "ru": "с/мм", "uk": "с/мм", "zh": "s/mm"}),
    "m/s": MappingProxyType({"en": "m/s", "ru": "м/с", "uk": "м/с", "zh": "m/s"}),
    "m/s²": MappingProxyType({"en": "m/s²", "ru": "м/с²", "uk": "м/с²", "zh": "m/s²"}),
    "rad/s²": MappingProxyType({"en": "rad/s²", "ru": "рад/с²", "uk": "рад/с²", "zh": "rad/s²"}),
    "(rad/s)/mm": MappingProxyType({"en": "(rad/s)/mm", "ru": "(рад/с)/мм", "uk": "(рад/с)/мм",
                                    "zh": "(rad/s)/mm"}),
    "(rad/s²)/mm": MappingProxyType({"en": "(rad/s²)/mm", "ru": "(рад/с²)/мм", "uk": "(рад/с²)/мм",
                                     "zh": "(rad/s²)/mm"}),
})


def unit(key: str, lang: Language) -> str:
    """A unit written in the sheet's language (``"(m/s)/mm"`` → ``"(м/с)/мм"`` in ru)."""
    return _UNITS[key][lang]


def scale_text(symbol: str, value: float, unit_key: str, lang: Language) -> str:
    """A scale label as course sheets write it: ``"μv = 0,02 (м/с)/мм"``."""
    return f"{symbol} = {number(value, lang)} {unit(unit_key, lang)}"


#: ESKD reduction and enlargement scales as "1:k" → μl in m/mm (1:1 is 0.001 m/mm).
ESKD_RATIOS: tuple[tuple[float, float], ...] = (
    (10, 1), (5, 1), (4, 1), (2.5, 1), (2, 1), (1, 1), (1, 2), (1, 2.5), (1, 4), (1, 5),
    (1, 10), (1, 15), (1, 20), (1, 25), (1, 40), (1, 50), (1, 75), (1, 100))


def eskd_scales() -> tuple[float, ...]:
    """μl of the ESKD scales, m/mm, from the largest drawing (10:1) to the smallest (1:100)."""
    return tuple(0.001 * b / a for a, b in ESKD_RATIOS)


def ratio_text(mu_l: float, lang: Language = "ru") -> str:
    """The ESKD scale of μl (m/mm) as written in the title block: ``0.0025`` → ``"1:2,5"``
    (a decimal comma in ru and uk, a point otherwise)."""
    for a, b in ESKD_RATIOS:
        if math.isclose(0.001 * b / a, mu_l, rel_tol=1e-9):
            return decimal(f"{a:g}:{b:g}", lang)
    return decimal(f"1:{1000 * mu_l:g}", lang)


def scale_mark(mu_l: float, lang: Language) -> str:
    """The scale as a drawing writes it: ``"М 1:2,5"`` (Cyrillic М in ru, uk), ``"M 1:2.5"``."""
    return f"{'М' if lang in ('ru', 'uk') else 'M'} {ratio_text(mu_l, lang)}"


#: A position number moved off a curve stays within this many of its heights of its tick (the
#: box's distance from the tick's segment): farther it floats, and it is placed round its tick
#: with every text and line of the view instead (`_numbers_by_their_ticks`).
NUMBER_REACH = 1.2


def axis_numbers_clear(items: list, curves) -> list:
    """Position numbers hung under a φ axis (``baseline="top"``) kept clear: the one under the
    origin moves beside the ordinate axis, and one that a curve crosses moves to the nearest
    spot by its tick that no curve crosses (`_number_tries`: above the axis, mirrored; beside
    its tick, under or over the axis; a little farther below or above; narrowed,
    `MIN_WIDTH_FACTOR`), within :data:`NUMBER_REACH` of its height of the tick; one that no such
    spot clears goes to the nearest spot round its tick clear of the curves, the axes and the
    other texts where its own tick stays the nearest (`_numbers_by_their_ticks`). ``curves``
    are polylines' points in the same mm. Other primitives pass unchanged."""
    import shapely

    from velplan.render.layout import label_box
    from velplan.render.scene import Text

    lines = [shapely.LineString(c) for c in curves if len(c) >= 2]
    if not lines:
        return items
    field = shapely.STRtree(lines)
    texts = None  # the other texts' boxes, as written (a tree), and those of the numbers moved
    ticks = shapely.points([(q.position[0], 0.0) for q in items if isinstance(q, Text) and q.baseline == "top"
                            and q.text.isdigit() and q.position[1] < 0])
    out = []
    for p in items:
        if isinstance(p, Text) and p.baseline == "top" and p.text.isdigit() and p.position[1] < 0:
            item = p
            tick = shapely.LineString([(p.position[0], -1.0), (p.position[0], 1.0)])
            if abs(p.position[0]) < 1e-9:  # under the origin: beside the ordinate axis instead
                p = _moved(p, position=(0.8, p.position[1]), anchor="start")
            if len(field.query(label_box(p), predicate="intersects")):
                if texts is None:
                    written = [q for q in items if isinstance(q, Text)]
                    texts = (written, shapely.STRtree([label_box(q) for q in written]), [])
                p = next((q for q, box in _number_tries(p, tick, label_box)
                          if not len(field.query(box, predicate="intersects"))
                          and not any(texts[0][j] is not item for j in texts[1].query(box, predicate="intersects"))
                          and not any(box.intersects(b) for b in texts[2])
                          and _own_tick_nearest(box, item.position[0], ticks)), p)
                texts[2].append(label_box(p))
        out.append(p)
    numbers = [k for k, p in enumerate(items)
               if isinstance(p, Text) and p.baseline == "top" and p.text.isdigit() and p.position[1] < 0]
    crossed = [k for k in numbers if len(field.query(label_box(out[k]), predicate="intersects"))]
    return _numbers_by_their_ticks(out, crossed, numbers, items, lines) if crossed else out


def _own_tick_nearest(box, x: float, ticks) -> bool:
    """Whether the tick at `x` on the φ axis is nearer to a number's `box` than any other of the
    `ticks` (points): a number two digits wide beside its tick may reach over the next one."""
    import shapely

    d = shapely.distance(box, ticks)
    own = np.abs(shapely.get_x(ticks) - x) < 1e-9
    return not own.any() or d[own].min() < d[~own].min(initial=np.inf)


def _number_tries(p, tick, box_of) -> list:
    """(text, its box by `box_of`) of the spots a position number `p` hung under the φ axis
    tries when a curve crosses it, nearest its `tick` (a segment across the axis) first and
    none farther than :data:`NUMBER_REACH` of its height: mirrored above the axis; beside the
    tick (a number under its tick only), just under or over the axis; a little farther below or
    above; narrowed (`MIN_WIDTH_FACTOR`, a number of two digits), below or above, then a text
    height farther."""
    from velplan.render.shapes import DESCENDER_DEPTH, MIN_WIDTH_FACTOR

    x, y = p.position
    h = p.size_mm
    up = _moved(p, position=(x, -y), baseline="baseline")
    steps = [0.5 * h * k for k in (1, 2, 3)]
    # narrowed: a number of two digits only (one narrowed digit reads as a misprint beside the others)
    narrow = [_moved(q, width_factor=MIN_WIDTH_FACTOR) for q in (p, up)] if len(p.text) > 1 else []
    tries = ([up] + [_moved(p, position=(x, y - d)) for d in steps]
             + [_moved(up, position=(x, -y + d)) for d in steps] + narrow
             + [_moved(q, position=(q.position[0], q.position[1] + s * h)) for q, s in zip(narrow, (-1.0, 1.0))])
    if p.anchor == "middle":  # clear of the tick by 0.6 mm and of the axis by 0.4 mm
        tries += [_moved(p, position=(x + side * 0.6, -0.4), anchor=anchor)
                  for side, anchor in ((-1.0, "end"), (1.0, "start"))]
        tries += [_moved(up, position=(x + side * 0.6, 0.4 + DESCENDER_DEPTH * h), anchor=anchor)
                  for side, anchor in ((-1.0, "end"), (1.0, "start"))]
    reach = NUMBER_REACH * h
    boxes = [box_of(q) for q in tries]
    near = [(box.distance(tick), k) for k, box in enumerate(boxes)]
    return [(tries[k], boxes[k]) for d, k in sorted(near) if d <= reach]


def grown_once(text, grown: dict):
    """``label_box(text).buffer(0.4)`` (a placed text's keep-off area), made once per text for
    the calls sharing `grown` (id of a text → (the text, its area))."""
    from velplan.render.layout import label_box

    kept = grown.get(id(text))
    if kept is None or kept[0] is not text:
        kept = grown[id(text)] = (text, label_box(text).buffer(0.4))
    return kept[1]


def _numbers_by_their_ticks(out: list, crossed: list[int], numbers: list[int], items: list, lines: list) -> list:
    """`out` with its position numbers at the indices `crossed` (texts a curve of `lines`
    crosses) placed by `place_letters` round their ticks on the φ axis (the tick of a number
    of `items`, at the indices `numbers`, is on the axis under its wanted place): clear of the
    curves, the axes, ticks and rays, and every other text, its own tick nearer to it than
    any other, else beyond them with a thin leader."""
    import shapely

    from velplan.render.scene import Text
    from velplan.views.letters import place_letters

    ticks = [(items[k].position[0], 0.0) for k in numbers]
    drawn = [shapely.LineString([p.start, p.end]) for p in out if isinstance(p, Arrow)]
    drawn += [shapely.LineString(p.points) for p in out if isinstance(p, Polyline)]
    out = list(out)
    grown: dict = {}  # id of a text → (the text, its box grown by 0.4 mm), made once
    for k in crossed:
        taken = []
        for j, p in enumerate(out):
            if isinstance(p, Text) and j != k:
                taken.append(grown_once(p, grown))
        tick = (items[k].position[0], 0.0)
        (placed,), leaders = place_letters([items[k]], [tick], ticks, [*lines, *drawn], taken=taken,
                                           leader_layer=items[k].layer)
        out[k] = placed
        out += leaders
    return out


def _farther(text, x0, y0, x1, y1, step, rings, placed):
    """The first spot of rings `rings` + 1 … 2·`rings` around an upright `text` whose box
    (offsets x0…x1, y0…y1 from the spot, mm) meets none of the `placed` boxes:
    (0, spot, box), or (0, None, None)."""
    import shapely

    if not placed:
        return 0, None, None
    x, y = text.position
    others = np.array(placed)
    for ring in range(rings + 1, 2 * rings + 1):
        for k in range(8):
            sx = x + ring * step * math.cos(math.pi / 4 * k)
            sy = y + ring * step * math.sin(math.pi / 4 * k)
            box = shapely.box(sx + x0 - 0.4, sy + y0 - 0.4, sx + x1 + 0.4, sy + y1 + 0.4)
            if not shapely.intersects(box, others).any():
                return 0, (sx, sy), box
    return 0, None, None


#: Spots a label tries at once, in order: the wanted one, the first ring, the next two rings,
#: then the rest. Most labels find room near their point and the first free spot wins, so the
#: outer rings are seldom examined.
_LABEL_STAGES = (1, 9, 25)
#: cos and sin of the eight directions of a ring, counter-clockwise from +x.
_RING_DIRECTIONS = np.array([(math.cos(math.pi / 4 * k), math.sin(math.pi / 4 * k)) for k in range(8)])


class _PlacedLabels:
    """The padded boxes of the labels placed so far. Two upright boxes meet exactly when their
    bounds overlap (closed intervals), so only a pair with a rotated box asks shapely."""

    def __init__(self) -> None:
        self.boxes: list = []
        self._bounds = np.empty((0, 4))
        self._upright = np.empty(0, dtype=bool)

    def add(self, box, bounds, upright: bool) -> None:
        self.boxes.append(box)
        self._bounds = np.vstack([self._bounds, bounds])
        self._upright = np.append(self._upright, upright)

    def meet(self, boxes, bounds, upright: bool) -> np.ndarray:
        """Whether each of `boxes` (bounds (n, 4): xmin, ymin, xmax, ymax, mm) meets a placed box."""
        import shapely

        b = self._bounds
        meets = ((bounds[:, None, 0] <= b[:, 2]) & (b[:, 0] <= bounds[:, None, 2])
                 & (bounds[:, None, 1] <= b[:, 3]) & (b[:, 1] <= bounds[:, None, 3]))
        rows, cols = np.nonzero(meets & ~(self._upright & upright))
        if len(rows):
            meets[rows, cols] = shapely.intersects(boxes[rows], np.array(self.boxes)[cols])
        return meets.any(axis=1)


def _spots(position, step: float, rings: int) -> np.ndarray:
    """The wanted spot, then `rings` rings of eight directions around it, `step` apart, mm,
    shape (1 + 8·rings, 2)."""
    if rings not in _RINGS:
        _RINGS[rings] = (np.repeat(np.arange(1, rings + 1), 8)[:, None], np.tile(_RING_DIRECTIONS, (rings, 1)))
    ring, directions = _RINGS[rings]
    return np.vstack([position, position + (ring * step) * directions])


#: Per number of rings: each spot's ring (1, 1, …, 2, …) and direction, made once.
_RINGS: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _enlarged_box(text) -> np.ndarray:
    """Corners of the estimated box of `text`, 1.25 times wider and 1.1 times taller about its
    anchor, mm: rendered glyphs run wider than the layout's estimate."""
    from velplan.render.shapes import text_box

    position = np.asarray(text.position)
    return position + (text_box(text) - position) * (1.25, 1.1)


def _spot_boxes(text, spots):
    """The padded box of `text` at each of `spots` (0.4 mm round its enlarged box), their bounds
    (n, 4), mm, and the box's offsets (x0, y0, x1, y1) from its spot. An upright text's boxes
    are made from their bounds when needed: None, with its offsets; a rotated text has no
    offsets (None)."""
    import shapely

    if text.rotation_deg != 0.0:
        boxes = np.array([shapely.Polygon(_enlarged_box(
            text if j == 0 else _moved(text, position=tuple(spot)))).buffer(0.4)
            for j, spot in enumerate(spots.tolist())])
        return boxes, shapely.bounds(boxes), None
    # an upright label's box only moves with it: all spots' boxes at once
    x, y = text.position
    scaled = _enlarged_box(text)
    (x0, y0), (x1, y1) = scaled.min(axis=0) - (x, y), scaled.max(axis=0) - (x, y)
    bounds = np.column_stack([spots[:, 0] + x0 - 0.4, spots[:, 1] + y0 - 0.4,
                              spots[:, 0] + x1 + 0.4, spots[:, 1] + y1 + 0.4])
    return None, bounds, (x0, y0, x1, y1)


def _survey(boxes, bounds, field, placed: _PlacedLabels):
    """Per spot: clear of the obstacles, how many obstacles its box meets, apart from the placed
    labels. Spots are examined by `_LABEL_STAGES` up to the first stage with a free one; the
    spots left unexamined read clear and apart, behind a free spot that is taken first."""
    import shapely

    n = len(bounds)
    clear, apart, crossings = np.ones(n, dtype=bool), np.ones(n, dtype=bool), np.zeros(n, dtype=int)
    start = 0
    for stop in [s for s in _LABEL_STAGES if s < n] + [n]:
        part = slice(start, stop)
        some = shapely.box(*bounds[part].T) if boxes is None else boxes[part]
        if field is not None:
            hits = field.query(some, predicate="intersects")[0]
            clear[start + hits] = False
            crossings[part] = np.bincount(hits, minlength=stop - start)
        apart[part] = ~placed.meet(some, bounds[part], boxes is None)
        if (clear[part] & apart[part]).any():
            break
        start = stop
    return clear, crossings, apart


def place_labels(texts: Iterable, obstacles: Iterable = (), *, step_mm: float | None = None,
                 rings: int = 8, taken: Iterable = ()) -> tuple:
    """Move labels, in order, clear of `obstacles` and of the labels placed before them.

    Each label that collides is tried in rings of eight directions around its wanted spot,
    with a tree of the obstacles and the spots examined
    ring by ring, so a view with many lines places its letters quickly. A label with no free
    spot takes the spot clear of the other labels that meets the fewest obstacles (the first of
    those), looking twice as far out if it must, or keeps its place. `taken`: labels placed
    already (upright), which the labels keep off as they keep off each other.
    """
    import shapely

    # a box meets the obstacles' union exactly when it meets one of them: a tree finds which
    shapes = [g for g in obstacles if not g.is_empty]
    field = shapely.STRtree(shapes) if shapes else None
    placed = _PlacedLabels()
    for text in taken:
        _, bounds, _ = _spot_boxes(text, np.array([text.position], float))
        placed.add(shapely.box(*bounds[0]), bounds[0], True)
    out = []
    for text in texts:
        step = step_mm or 0.5 * text.size_mm
        spots = _spots(text.position, step, rings)
        upright = text.rotation_deg == 0.0
        boxes, bounds, offsets = _spot_boxes(text, spots)
        clear, crossings, apart = _survey(boxes, bounds, field, placed)
        free = clear & apart
        # no free spot: at least off the other labels (a line under a letter still reads)
        j = int(np.argmax(free)) if free.any() else (
            int(np.argmin(np.where(apart, crossings, np.iinfo(int).max))) if apart.any() else -1)
        if j < 0 and not upright:
            j = 0
        if j < 0:  # crowded all round: off the other labels further out, else where it was
            j, spot, box = _farther(text, *offsets, step, rings, placed.boxes)
            if spot is not None:
                spots, bounds = np.vstack([spots, spot]), np.vstack([bounds, shapely.bounds(box)])
                j = len(spots) - 1
        chosen = text if j == 0 else _moved(text, position=tuple(spots[j].tolist()))
        placed.add(shapely.box(*bounds[j]) if boxes is None else boxes[j], bounds[j], upright)
        out.append(chosen)
    return tuple(out)


def free_direction(busy: list[float], default: float = 45.0) -> float:
    """The direction (deg, a multiple of 5) farthest from every busy direction (deg);
    ``default`` when nothing is busy."""
    if not busy:
        return default
    # every candidate's gap at once (numpy's float remainder is Python's %), then the same scan
    cand = 5.0 * np.arange(72)
    gaps = np.abs((cand[:, None] - np.asarray(busy, float)[None, :] + 180.0) % 360.0 - 180.0).min(axis=1)
    best, gap = default, -1.0
    for c, g in zip(cand.tolist(), gaps.tolist()):
        if g > gap + 1e-9:
            best, gap = c, g
    return best


def spots_of(texts: list, rings: int) -> np.ndarray:
    """`_spots` of every text, a step of half its size, shape (n, 1 + 8·rings, 2): the same sums,
    all at once."""
    _spots((0.0, 0.0), 1.0, rings)  # makes the rings' table
    ring, directions = _RINGS[rings]
    at = np.array([t.position for t in texts], float).reshape(-1, 2)
    step = np.array([0.5 * t.size_mm for t in texts], float)
    around = at[:, None, :] + (ring[None, :, :] * step[:, None, None]) * directions[None, :, :]
    return np.concatenate([at[:, None, :], around], axis=1)


_SHARE = {"start": 0.0, "middle": 0.5, "end": 1.0}
_DROP = {"baseline": 0.0, "middle": 0.5, "top": 1.0}


def upright_offsets(texts: list) -> np.ndarray:
    """The offsets (x0, y0, x1, y1) of `_spot_boxes` for upright texts, shape (n, 4): the box of
    `text_box` enlarged as `_enlarged_box` enlarges it, the same operations in the same order
    on all at once (``text_origin`` and the turn by 0 of `rotate` written out)."""
    from velplan.render.shapes import text_depth, text_extent

    size = np.array([t.size_mm for t in texts], float)
    width = np.array([text_extent(t.text, t.size_mm)[0] for t in texts], float)
    below, above = np.array([text_depth(t.text, t.size_mm) for t in texts], float).reshape(-1, 2).T
    x, y = np.array([t.position for t in texts], float).reshape(-1, 2).T
    drop = np.array([_DROP[t.baseline] for t in texts], float) * size
    lx0 = -width * np.array([_SHARE[t.anchor] for t in texts], float)
    ly0 = -below
    ox, oy = x - drop * -0.0, y - drop * 1.0  # x − drop·(−sin 0), y − drop·cos 0
    sx = [x + ((ox + ((c - 0.0) + 0.0)) - x) * 1.25 for c in (lx0, lx0 + width)]
    sy = [y + ((oy + ((c - 0.0) + 0.0)) - y) * 1.1 for c in (ly0, above)]
    return np.column_stack([np.minimum(*sx) - x, np.minimum(*sy) - y, np.maximum(*sx) - x, np.maximum(*sy) - y])
