"""Conventional symbols of kinematic schemes (GOST 2.770), as primitives in sheet mm.

Each function returns a tuple of primitives in drawing order (what must cover what comes
last: a joint's white circle over the links that meet at it), ready for
:meth:`Scene.extend`.

Examples
--------
>>> from velplan.render.scene import Scene
>>> scene = Scene(width_mm=420, height_mm=297).extend(
...     fixed_pivot((100, 100)), link((100, 100), (130, 120)), revolute_joint((130, 120)))
>>> scene.layers
('mechanism',)
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np

from velplan.render.scene import (
    Arrow, Circle, Fill, Polygon, Polyline, Primitive, Text)
from velplan.render.shapes import hatch_segments, rotate, upright_angle
from velplan.render.style import LineType

Side = Literal["left", "right"]

#: Radius of a revolute joint's circle, mm.
JOINT_RADIUS_MM = 1.5
_MIN_STROKE_FRACTION = 0.4


def _unit(start, end) -> np.ndarray:
    d = np.asarray(end, float) - np.asarray(start, float)
    length = float(np.hypot(*d))
    return d / length if length else np.array([1.0, 0.0])


def _side_normal(start, end, side: Side) -> np.ndarray:
    """Unit normal to the left or the right of the direction start → end."""
    u = _unit(start, end)
    left = np.array([-u[1], u[0]])
    return left if side == "left" else -left


def revolute_joint(centre, *, radius_mm: float = JOINT_RADIUS_MM, layer: str = "mechanism",
                   line: LineType = "thin") -> tuple[Primitive, ...]:
    """A revolute pair: a small white-filled circle, mm."""
    return (Circle(centre, radius_mm, layer, line, "white"),)


def centre_of_mass_sign(centre, *, radius_mm: float = 1.8, layer: str = "mechanism",
                        line: LineType = "thin") -> tuple[Primitive, ...]:
    """The centre-of-mass sign: a small white circle with its first and third quarters
    filled, mm."""
    c = np.asarray(centre, float)
    items: list[Primitive] = [Circle(tuple(c), radius_mm, layer, line, "white")]
    cx, cy = float(c[0]), float(c[1])
    for start in (0.0, math.pi):
        arc = np.linspace(start, start + math.pi / 2, 7).tolist()
        corners = [(cx, cy)] + [(cx + radius_mm * math.cos(a), cy + radius_mm * math.sin(a)) for a in arc]
        items.append(Polygon(tuple(corners), layer, line, "solid"))
    return tuple(items)


def ground_hatch(start, end, *, side: Side = "right", depth_mm: float = 3.0,
                 spacing_mm: float = 2.0, layer: str = "mechanism",
                 line: LineType = "thick") -> tuple[Primitive, ...]:
    """A ground line from `start` to `end` with short slanted hatch strokes on one side.

    Parameters
    ----------
    start, end : array_like of shape (2,)
        Ends of the ground line, mm.
    side : {"left", "right"}
        Side of the hatching, looking from `start` to `end`.
    depth_mm, spacing_mm : float
        Width of the hatched band and distance between strokes, mm.
    layer, line
        Layer, and line type of the ground line (strokes are thin).

    Returns
    -------
    tuple of Primitive
        The ground line, then one thin Polyline per stroke, all inside the band
        ``start, end, end + depth·n, start + depth·n``.
    """
    start, end = np.asarray(start, float), np.asarray(end, float)
    key = (start.tobytes(), end.tobytes(), side, depth_mm, spacing_mm, layer, line)  # -0.0 is not 0.0
    if key not in _HATCHES:
        if len(_HATCHES) >= _HATCHES_KEPT:
            _HATCHES.clear()
        _HATCHES[key] = _ground_hatch(start, end, side, depth_mm, spacing_mm, layer, line)
    return _HATCHES[key]


#: Hatched ground lines drawn so far, by their exact inputs: a support or a guide that stays
#: put from frame to frame (an animation, a layout's trial views) is hatched once.
_HATCHES: dict[tuple, tuple[Primitive, ...]] = {}
_HATCHES_KEPT = 4096


def _ground_hatch(start: np.ndarray, end: np.ndarray, side: Side, depth_mm: float, spacing_mm: float,
                  layer: str, line: LineType) -> tuple[Primitive, ...]:
    n = _side_normal(start, end, side)
    band = np.array([start, end, end + depth_mm * n, start + depth_mm * n])
    along = math.degrees(math.atan2(*(end - start)[::-1]))
    strokes = hatch_segments(band, spacing_mm, along + 45.0)
    # Corner stubs of the clipped hatch read as specks; keep strokes of fair length.
    full = depth_mm * math.sqrt(2.0)
    strokes = [s for s in strokes if math.dist(*s) >= _MIN_STROKE_FRACTION * full]
    return (Polyline([start, end], layer, line),
            *(Polyline(s, layer, "thin") for s in strokes))


def straight_guide(start, end, *, side: Side = "right", depth_mm: float = 3.0,
                   spacing_mm: float = 2.0, layer: str = "mechanism") -> tuple[Primitive, ...]:
    """A fixed straight guide of a slider: a thick line hatched on the ground side."""
    return ground_hatch(start, end, side=side, depth_mm=depth_mm, spacing_mm=spacing_mm,
                        layer=layer, line="thick")


def fixed_pivot(centre, *, radius_mm: float = JOINT_RADIUS_MM, height_mm: float = 7.0,
                width_mm: float = 8.0, direction_deg: float = -90.0,
                layer: str = "mechanism") -> tuple[Primitive, ...]:
    """A revolute pair on the frame: triangle support on hatched ground, joint on top.

    Parameters
    ----------
    centre : array_like of shape (2,)
        The pivot, mm.
    radius_mm : float
        Joint circle radius, mm.
    height_mm, width_mm : float
        Height of the support triangle and width of its base, mm.
    direction_deg : float
        Direction from the pivot to the ground, degrees (-90: ground below).
    layer : str
        Layer name.
    """
    c = np.asarray(centre, float)
    a = math.radians(direction_deg)
    down = np.array([math.cos(a), math.sin(a)])
    across = np.array([-down[1], down[0]])
    base = c + down * height_mm
    left, right = base + across * width_mm / 2, base - across * width_mm / 2
    margin = across * 2.0
    return (Polyline([left, c, right], layer, "thin"),
            *ground_hatch(left + margin, right - margin, side="left", layer=layer,
                          line="thin"),
            *revolute_joint(c, radius_mm=radius_mm, layer=layer))


def slider_block(centre, angle_deg: float, *, length_mm: float = 10.0,
                 width_mm: float = 6.0, layer: str = "mechanism",
                 fill: Fill | None = "white") -> tuple[Primitive, ...]:
    """A slider: a rectangle centred at `centre`, its long side along `angle_deg`, mm."""
    half = np.array([[-length_mm, -width_mm], [length_mm, -width_mm],
                     [length_mm, width_mm], [-length_mm, width_mm]]) / 2
    corners = rotate(half, angle_deg) + np.asarray(centre, float)
    return (Polygon(corners, layer, "thick", fill),)


def link(a, b, *, trim_a_mm: float = JOINT_RADIUS_MM, trim_b_mm: float = JOINT_RADIUS_MM,
         layer: str = "mechanism", line: LineType = "thick") -> tuple[Primitive, ...]:
    """A link drawn from joint `a` to joint `b`, stopping at the joints' circles.

    Returns an empty tuple when the joints' circles overlap (nothing left to draw).
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    length = float(np.hypot(*(b - a)))
    if length <= trim_a_mm + trim_b_mm:
        return ()
    u = (b - a) / length
    return (Polyline([a + u * trim_a_mm, b - u * trim_b_mm], layer, line),)


def dimension_line(a, b, text: str, *, offset_mm: float = 8.0, size_mm: float = 3.5,
                   layer: str = "labels", gap_mm: float = 1.0,
                   overshoot_mm: float = 2.0) -> tuple[Primitive, ...]:
    """A linear dimension between `a` and `b`: extension lines, arrows, the value.

    Parameters
    ----------
    a, b : array_like of shape (2,)
        Measured points, mm.
    text : str
        The value written above the dimension line.
    offset_mm : float
        Distance of the dimension line from `a`–`b`, mm, to the left of a → b
        (negative: to the right).
    size_mm : float
        Text height, mm.
    layer : str
        Layer name.
    gap_mm, overshoot_mm : float
        Gap between the object and an extension line, and how far the extension line
        passes the dimension line, mm.
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    n = _side_normal(a, b, "left") * math.copysign(1.0, offset_mm)
    reach = abs(offset_mm)
    da, db = a + n * reach, b + n * reach
    middle = (da + db) / 2
    angle = upright_angle(math.degrees(math.atan2(*(b - a)[::-1])))
    up = np.array([-math.sin(math.radians(angle)), math.cos(math.radians(angle))])
    return (Polyline([a + n * gap_mm, a + n * (reach + overshoot_mm)], layer, "thin"),
            Polyline([b + n * gap_mm, b + n * (reach + overshoot_mm)], layer, "thin"),
            Arrow(middle, da, layer, "thin"), Arrow(middle, db, layer, "thin"),
            Text(middle + up * 1.0, text, layer, size_mm, "middle", "baseline", angle))


def pole_marker(position, name: str = "p", *, layer: str = "labels",
                radius_mm: float = 0.7, size_mm: float = 3.5) -> tuple[Primitive, ...]:
    """The pole of a plan: a solid dot with its letter below-left, mm."""
    x, y = np.asarray(position, float)
    return (Circle((x, y), radius_mm, layer, "thin", "solid"),
            Text((x - 1.2, y - 1.2), name, layer, size_mm, "end", "top"))


def point_label(position, text: str, *, offset_mm=(1.2, 1.2), size_mm: float = 3.5,
                layer: str = "labels") -> tuple[Primitive, ...]:
    """A point's letter, offset up-right from it by default, mm."""
    x, y = np.asarray(position, float) + np.asarray(offset_mm, float)
    return (Text((x, y), text, layer, size_mm),)


def rotation_arrow(centre, radius_mm: float, start_deg: float, sweep_deg: float, *,
                   layer: str = "labels", head_length_mm: float = 3.0,
                   head_width_mm: float = 1.0) -> tuple[Primitive, ...]:
    """A curved arrow showing a sense of rotation (ω, ε), mm and degrees.

    The arc runs from `start_deg` through `sweep_deg` (positive: counter-clockwise);
    the arrowhead sits at its end, tangent to it.
    """
    c = np.asarray(centre, float)
    back = math.copysign(math.degrees(head_length_mm / radius_mm), sweep_deg)
    tip, tail = start_deg + sweep_deg, start_deg + sweep_deg - back
    steps = max(8, int(abs(sweep_deg) / 5))
    t = np.radians(np.linspace(start_deg, tail, steps + 1))
    arc = c + radius_mm * np.column_stack([np.cos(t), np.sin(t)])
    tip_point = c + radius_mm * np.array([math.cos(math.radians(tip)),
                                          math.sin(math.radians(tip))])
    # The arc stops where the head begins, so its round cap never shows past the tip.
    return (Polyline(arc, layer, "thin"),
            Arrow(arc[-1], tip_point, layer, "thin", head_length_mm, head_width_mm))
