"""The backend-neutral scene: immutable drawing primitives in sheet millimetres.

Coordinates are millimetres on the sheet, origin at its bottom-left corner, y up (the SVG
canvas flips y). Every primitive names its layer — ``"frame"``, ``"title"``,
``"mechanism"``, ``"positions"``, ``"trajectory"``, ``"plan-v-1"``, ``"construction"``,
``"labels"``, ``"table"``, ``"diagram"``, … — and a line type from
:class:`~velplan.render.style.SheetStyle`; widths, dashes and fonts are applied by the
canvas, not stored here.

Examples
--------
>>> s = Scene(width_mm=420, height_mm=297)
>>> s = s.extend(Polyline([(0, 0), (10, 0)], "mechanism", "thick"))
>>> s.bounds_of("mechanism")
(0.0, 0.0, 10.0, 0.0)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Iterable, Iterator, Literal, Union, get_args

import numpy as np

from velplan.errors import VelplanError
from velplan.render.shapes import MIN_WIDTH_FACTOR, text_box, text_depth, text_extent
from velplan.render.style import LINE_TYPES, LineType

Point = tuple[float, float]
Fill = Literal["hatch", "solid", "white"]
Anchor = Literal["start", "middle", "end"]
Baseline = Literal["baseline", "middle", "top"]
Bounds = tuple[float, float, float, float]

#: Layers the sheet builders use; other names matching ``[a-z][a-z0-9-]*`` are allowed.
STANDARD_LAYERS: tuple[str, ...] = (
    "frame", "title", "mechanism", "positions", "trajectory", "construction",
    "labels", "table", "diagram")

_LAYER_NAME = re.compile(r"[a-z][a-z0-9-]*\Z")


def _points(value, owner: str, minimum: int) -> tuple[Point, ...]:
    xy = np.asarray(value, dtype=float)
    if xy.ndim != 2 or xy.shape[1] != 2 or len(xy) < minimum:
        raise VelplanError(f"{owner} needs at least {minimum} points of shape (n, 2) in mm, "
                           f"got an array of shape {xy.shape}")
    if not np.isfinite(xy).all():  # one check for the whole array; the message names the point
        for p in xy:
            _point(p, owner)
    return tuple(map(tuple, xy.tolist()))


_REALS = (float, int, np.floating, np.integer)


def _point(value, owner: str) -> Point:
    if type(value) in (tuple, list, np.ndarray) and len(value) == 2:  # the common case, without an array
        x, y = value[0], value[1]
        if isinstance(x, _REALS) and isinstance(y, _REALS) and math.isfinite(x) and math.isfinite(y):
            return (float(x), float(y))
    xy = np.asarray(value, dtype=float)
    if xy.shape != (2,) or not np.all(np.isfinite(xy)):
        raise VelplanError(f"{owner} needs finite (x, y) points in mm, got {value!r}")
    return (float(xy[0]), float(xy[1]))


_GOOD_LAYERS: set[str] = set()
"""Layer names already found valid (a drawing uses a few over and over)."""


def _check_common(owner: str, layer: str, line: str | None = None) -> None:
    if type(layer) is str and layer in _GOOD_LAYERS:
        pass
    elif not isinstance(layer, str) or not _LAYER_NAME.match(layer):
        raise VelplanError(f"{owner} layer {layer!r} is not a valid layer name "
                           "(lower-case letters, digits and '-', starting with a letter)")
    elif type(layer) is str and len(_GOOD_LAYERS) < 4096:
        _GOOD_LAYERS.add(layer)
    if line is not None and line not in LINE_TYPES:
        raise VelplanError(f"{owner} line type {line!r} is unknown; known line types: "
                           f"{', '.join(LINE_TYPES)}")
    if type(layer) is str and len(_GOOD_LAYERS) < 4096:
        _GOOD_LAYERS.add(layer)


def _check_choice(owner: str, name: str, value, allowed: tuple) -> None:
    if value not in allowed:
        raise VelplanError(f"{owner} {name} {value!r} is unknown; allowed: "
                           f"{', '.join(repr(a) for a in allowed)}")


def _check_length(owner: str, name: str, value, *, allow_none: bool = False) -> None:
    if value is None and allow_none:
        return
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise VelplanError(f"{owner} {name} must be a positive length in mm, got {value!r}")


def _box(points) -> Bounds:
    xy = np.asarray(points, float).reshape(-1, 2)
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))


_FILLS = (None,) + get_args(Fill)
_ANCHORS, _BASELINES = get_args(Anchor), get_args(Baseline)


@dataclass(frozen=True, slots=True)
class Polyline:
    """An open chain of straight segments.

    Parameters
    ----------
    points : array_like of shape (n, 2), n ≥ 2
        Vertices, mm; stored as a tuple of (x, y) tuples.
    layer : str
        Layer name.
    line : {"thick", "thin", "construction", "axis", "hidden"}
        Line type.
    """

    points: tuple[Point, ...]
    layer: str
    line: LineType = "thin"

    def __post_init__(self) -> None:
        object.__setattr__(self, "points", _points(self.points, "Polyline", 2))
        _check_common("Polyline", self.layer, self.line)

    @property
    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax), mm."""
        return _box(self.points)


@dataclass(frozen=True, slots=True)
class Polygon:
    """A closed outline, optionally filled.

    Parameters
    ----------
    points : array_like of shape (n, 2), n ≥ 3
        Vertices, mm; the closing edge is implied.
    layer : str
        Layer name.
    line : LineType
        Line type of the outline.
    fill : {None, "hatch", "solid", "white"}
        None: outline only; ``"hatch"``: thin hatch lines inside (a section, the ground);
        ``"solid"``: filled with the stroke colour; ``"white"``: opaque paper colour, to
        hide what lies beneath (a slider over its guide).
    """

    points: tuple[Point, ...]
    layer: str
    line: LineType = "thin"
    fill: Fill | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "points", _points(self.points, "Polygon", 3))
        _check_common("Polygon", self.layer, self.line)
        _check_choice("Polygon", "fill", self.fill, _FILLS)

    @property
    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax), mm."""
        return _box(self.points)


@dataclass(frozen=True, slots=True)
class Circle:
    """A circle, optionally filled (a revolute joint is a white-filled circle).

    Parameters
    ----------
    centre : array_like of shape (2,)
        Centre, mm.
    radius : float
        Radius, mm.
    layer, line, fill
        As for :class:`Polygon`.
    """

    centre: Point
    radius: float
    layer: str
    line: LineType = "thin"
    fill: Fill | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "centre", _point(self.centre, "Circle"))
        _check_length("Circle", "radius", self.radius)
        object.__setattr__(self, "radius", float(self.radius))
        _check_common("Circle", self.layer, self.line)
        _check_choice("Circle", "fill", self.fill, _FILLS)

    @property
    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax), mm."""
        (x, y), r = self.centre, self.radius
        return (x - r, y - r, x + r, y + r)


@dataclass(frozen=True, slots=True)
class Arrow:
    """A vector: a straight shaft from `start` with a filled arrowhead at `end`.

    Parameters
    ----------
    start, end : array_like of shape (2,)
        Tail and tip, mm. A zero-length arrow is allowed (a zero velocity) and draws
        nothing.
    layer, line
        Layer name and line type of the shaft.
    head_length, head_width : float or None
        Arrowhead length along the vector and full width across it, mm; None takes the
        style's default.
    """

    start: Point
    end: Point
    layer: str
    line: LineType = "thin"
    head_length: float | None = None
    head_width: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _point(self.start, "Arrow"))
        object.__setattr__(self, "end", _point(self.end, "Arrow"))
        _check_common("Arrow", self.layer, self.line)
        _check_length("Arrow", "head_length", self.head_length, allow_none=True)
        _check_length("Arrow", "head_width", self.head_width, allow_none=True)

    @property
    def length(self) -> float:
        """Length of the vector, mm."""
        return math.dist(self.start, self.end)

    @property
    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax) of the shaft, mm."""
        return _box([self.start, self.end])


@dataclass(frozen=True, slots=True)
class Text:
    """One line of text.

    Parameters
    ----------
    position : array_like of shape (2,)
        Anchor point, mm.
    text : str
        The text, one line.
    layer : str
        Layer name.
    size_mm : float
        Text height (capital letter height), mm.
    anchor : {"start", "middle", "end"}
        Which end of the line sits at `position`.
    baseline : {"baseline", "middle", "top"}
        Whether `position` is on the baseline, at mid-height of the capitals, or at
        their top.
    rotation_deg : float
        Direction of the baseline, degrees counter-clockwise from the x axis.
    width_factor : float
        Width of the letters over their normal width at `size_mm`, from
        :data:`~velplan.render.shapes.MIN_WIDTH_FACTOR` to 1: a text that must fit a fixed
        cell keeps its height and is narrowed (as ESKD's narrow type A lettering is).
    """

    position: Point
    text: str
    layer: str
    size_mm: float = 3.5
    anchor: Anchor = "start"
    baseline: Baseline = "baseline"
    rotation_deg: float = 0.0
    width_factor: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _point(self.position, "Text"))
        if not isinstance(self.text, str) or "\n" in self.text:
            raise VelplanError(f"Text must be a one-line string, got {self.text!r}")
        _check_common("Text", self.layer)
        _check_length("Text", "size_mm", self.size_mm)
        _check_choice("Text", "anchor", self.anchor, _ANCHORS)
        _check_choice("Text", "baseline", self.baseline, _BASELINES)
        if not math.isfinite(self.rotation_deg):
            raise VelplanError(f"Text rotation_deg must be finite, got {self.rotation_deg!r}")
        object.__setattr__(self, "rotation_deg", float(self.rotation_deg))
        if not (isinstance(self.width_factor, (int, float))
                and MIN_WIDTH_FACTOR - 1e-9 <= self.width_factor <= 1.0):
            raise VelplanError(f"Text width_factor must be from {MIN_WIDTH_FACTOR} to 1 "
                               f"(narrower letters are illegible), got {self.width_factor!r}")
        object.__setattr__(self, "width_factor", float(self.width_factor))

    @property
    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax) of the estimated text box, mm."""
        if self.rotation_deg == 0.0:
            # the upright box in plain arithmetic: the same numbers as text_box, without arrays
            width = text_extent(self.text, self.size_mm)[0] * self.width_factor
            lx = -width * _ANCHOR[self.anchor]
            y = self.position[1] - _DROP[self.baseline] * self.size_mm
            below, above = text_depth(self.text, self.size_mm)
            return (self.position[0] + lx, y + -below, self.position[0] + (lx + width), y + above)
        return _box(text_box(self))


_ANCHOR = {"start": 0.0, "middle": 0.5, "end": 1.0}
_DROP = {"baseline": 0.0, "middle": 0.5, "top": 1.0}

Primitive = Union[Polyline, Polygon, Circle, Arrow, Text]
PRIMITIVE_TYPES: tuple[type, ...] = (Polyline, Polygon, Circle, Arrow, Text)


@dataclass(frozen=True, slots=True)
class Scene:
    """An ordered, immutable collection of primitives on a sheet.

    Later primitives are drawn over earlier ones.

    Parameters
    ----------
    primitives : tuple of Primitive
        The primitives, in drawing order.
    width_mm, height_mm : float
        Sheet size, mm.
    """

    primitives: tuple[Primitive, ...] = field(default=())
    width_mm: float = 841.0
    height_mm: float = 594.0

    def __post_init__(self) -> None:
        items = tuple(self.primitives)
        for item in items:
            if not isinstance(item, PRIMITIVE_TYPES):
                raise VelplanError(f"Scene accepts only drawing primitives, got {item!r}")
        object.__setattr__(self, "primitives", items)
        _check_length("Scene", "width_mm", self.width_mm)
        _check_length("Scene", "height_mm", self.height_mm)

    def __len__(self) -> int:
        return len(self.primitives)

    def __iter__(self) -> Iterator[Primitive]:
        return iter(self.primitives)

    def extend(self, *items: Primitive | Iterable[Primitive]) -> Scene:
        """Return a new scene with `items` drawn after the existing primitives.

        Each item is a primitive or an iterable of primitives (a tuple returned by a
        symbol function, another scene).
        """
        added: list = []
        for item in items:
            added.extend([item] if isinstance(item, PRIMITIVE_TYPES) else item)
        return Scene(self.primitives + tuple(added), self.width_mm, self.height_mm)

    @property
    def layers(self) -> tuple[str, ...]:
        """Layer names in order of first appearance."""
        return tuple(dict.fromkeys(p.layer for p in self.primitives))

    def on_layer(self, *layers: str) -> Scene:
        """Return the scene restricted to the primitives on `layers`, order kept."""
        wanted = set(layers)
        return Scene(tuple(p for p in self.primitives if p.layer in wanted),
                     self.width_mm, self.height_mm)

    def of_kind(self, kind: type) -> tuple:
        """Return the primitives that are instances of `kind`, in drawing order."""
        return tuple(p for p in self.primitives if isinstance(p, kind))

    def bounds(self) -> Bounds:
        """(xmin, ymin, xmax, ymax) of every primitive, mm.

        Raises
        ------
        VelplanError
            If the scene is empty.
        """
        if not self.primitives:
            raise VelplanError("an empty scene has no bounds")
        boxes = np.array([p.bounds for p in self.primitives])
        return (float(boxes[:, 0].min()), float(boxes[:, 1].min()),
                float(boxes[:, 2].max()), float(boxes[:, 3].max()))

    def bounds_of(self, *layers: str) -> Bounds:
        """(xmin, ymin, xmax, ymax) of the primitives on `layers`, mm.

        Raises
        ------
        VelplanError
            If none of `layers` has primitives; the message lists the layers present.
        """
        part = self.on_layer(*layers)
        if not part.primitives:
            raise VelplanError(f"no primitives on layer(s) {', '.join(layers)}; layers in "
                               f"the scene: {', '.join(self.layers) or 'none'}")
        return part.bounds()
