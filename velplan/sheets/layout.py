"""What every sheet shares: formats, legibility limits, the sizes of text per format, the
files a sheet writes, and the check that views stay inside the frame without overlapping."""

from __future__ import annotations

import math

import os
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Mapping

import numpy as np
import shapely

from velplan.errors import ScaleError, VelplanError, deprecated
from velplan.sheets.frame import free_area, frame_bounds, title_block_bounds
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Text
from velplan.render.shapes import circle_outline, text_box
from velplan.views.base import PlacedView
from velplan.views.diagram import DiagramSizes
from velplan.views.mechanism import MechanismSizes
from velplan.views.plan import PlanSizes

FORMATS: tuple[str, ...] = ("A1", "A2", "A3")
#: Shortest longest-vector a plan may have on the sheet, mm, per format: below it a plan is
#: unreadable.
MIN_PLAN_MM: Mapping[str, float] = MappingProxyType({"A1": 35.0, "A2": 30.0, "A3": 25.0})
#: Longest vector of the shortest plan that a sheet is content with, mm, per format.
GOOD_PLAN_MM: Mapping[str, float] = MappingProxyType({"A1": 90.0, "A2": 70.0, "A3": 50.0})
#: Shortest crank a scheme may show, mm.
MIN_CRANK_MM = 8.0
#: Shortest φ axis of a diagram, mm.
MIN_DIAGRAM_MM = 60.0
#: Shortest ordinate range of a kinematic diagram, mm: a flatter curve cannot be read.
MIN_ORDINATE_MM = 30.0


CLEARANCE_MM = 4.0
"""Clearance kept between the views and the frame lines, mm."""


def drawing_area(fmt: str, frame_style: str) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float]]:
    """(the inside of the frame less `CLEARANCE_MM`, the title block), sheet mm."""
    fx0, fy0, fx1, fy1 = frame_bounds(fmt)
    m = CLEARANCE_MM
    return (fx0 + m, fy0 + m, fx1 - m, fy1 - m), title_block_bounds(fmt, frame_style)


@dataclass(frozen=True)
class Sizes:
    gap: float
    mechanism: MechanismSizes
    plan: PlanSizes
    table: tuple[float, ...]
    table_title: float
    diagram: DiagramSizes
    #: The width factor of the tables' letters to try first (`velplan.render.scene.Text`): A3
    #: tables start narrowed, as ESKD's type A lettering, and keep the least height, 2.5 mm.
    table_width: float = 1.0


SIZES: Mapping[str, Sizes] = MappingProxyType({
    "A1": Sizes(10.0, MechanismSizes(5.0, 3.5, 2.5), PlanSizes(5.0, 3.5), (3.5, 2.5), 5.0,
                 DiagramSizes(3.5, 2.5)),
    "A2": Sizes(8.0, MechanismSizes(5.0, 3.5, 2.5), PlanSizes(3.5, 3.5), (2.5,), 3.5,
                 DiagramSizes(3.5, 2.5)),
    "A3": Sizes(6.0, MechanismSizes(3.5, 2.5, 2.5), PlanSizes(3.5, 2.5), (2.5,), 2.5,
                 DiagramSizes(2.5, 2.5), table_width=0.75),
})


class SheetOutput:
    """What every composed sheet offers: its SVG text and its files (needs ``scene`` and
    ``style`` attributes)."""

    def svg(self, *, precision: int = 3) -> str:
        """The sheet as an SVG document; the same sheet gives the same bytes."""
        from velplan.render.svg import to_svg

        return to_svg(self.scene, self.style, precision=precision)

    def save(self, path: str | os.PathLike, *, png: bool = False, pdf: bool = False, dxf: bool = False,
             dpi: float = 150.0) -> list[Path]:
        """Save the sheet, the writer chosen by the suffix of `path`: the SVG (always), and the
        PNG, PDF or DXF of a ``.png``, ``.pdf`` or ``.dxf`` name (or asked for) beside it,
        atomically; returns the files written, the SVG first.

        Conversions run before anything is written, so a failure leaves no file behind.
        """
        from velplan.render.export import save_drawing

        return save_drawing(self.svg(), path, scene=self.scene, style=self.style, png=png, pdf=pdf,
                            dxf=dxf, dpi=dpi)

    write = deprecated(save, "SheetOutput.write", "SheetOutput.save")


def write_outputs(svg: str, path: str | os.PathLike, *, png: bool = False, pdf: bool = False,
                  dpi: float = 150.0) -> list[Path]:
    """Write an SVG document to `path` and, when asked, its PNG and PDF beside it
    (`velplan.render.export.save_drawing`)."""
    from velplan.render.export import save_drawing

    return save_drawing(svg, path, png=png, pdf=pdf, dpi=dpi)


def check_layout(views: Mapping[str, PlacedView], fmt: str, frame_style: str) -> None:
    """Every view inside the free area, no two views overlapping (a layout bug otherwise)."""
    area = free_area(fmt, frame_style=frame_style).buffer(1e-6)
    boxes = {k: shapely.box(*v.bounds) for k, v in views.items()}
    for k, box in boxes.items():
        if not area.contains(box):
            raise ScaleError(f"the {k} view ({box.bounds[2] - box.bounds[0]:.0f} × "
                             f"{box.bounds[3] - box.bounds[1]:.0f} mm) does not fit the free "
                             f"area of {fmt}; use a larger --format")
    names = sorted(boxes)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            guest, host = (a, b) if views[a].view.meta.get("inside") == b else (b, a)
            if views[guest].view.meta.get("inside") == host:  # in the host's empty room: clear of its ink
                if _on_ink(views[guest].bounds, ink_boxes(views[host])):
                    raise ScaleError(f"the {guest} view lies on the drawing of the {host} view on {fmt}; "
                                     f"use a larger --format")
                continue
            if boxes[a].intersection(boxes[b]).area > 1e-6:
                raise ScaleError(f"the {a} and {b} views overlap on {fmt}; use a larger "
                                 f"--format or fewer --plans")


def _grid_span(grid: np.ndarray, lo: float, hi: float) -> tuple[int, int]:
    """Index range [i0, i1) of the ascending `grid` values within [lo, hi], one more each way."""
    return (max(int(np.searchsorted(grid, lo, side="left")) - 1, 0),
            min(int(np.searchsorted(grid, hi, side="right")) + 1, len(grid)))


def _on_ink(box, ink) -> bool:
    """Whether the `box` (sheet mm) overlaps one of the boxes `ink`."""
    b = np.asarray(ink, float).reshape(-1, 4)
    return bool(np.any((b[:, 0] < box[2]) & (box[0] < b[:, 2]) & (b[:, 1] < box[3]) & (box[1] < b[:, 3])))


def free_spot(w: float, h: float, taken, region, gap: float, near, *,
              square: bool = False) -> tuple[float, float] | None:
    """The lower left corner (sheet mm) of a free w × h mm box in ``region`` (x0, y0, x1, y1),
    at least ``gap`` mm from every box of ``taken``, on a 5 mm grid: the one whose upper left
    corner is nearest the point ``near``; None when there is none. With ``square`` the gap is
    kept along x or along y (a box grown by it, its corners square): one pass over thousands of
    boxes (`ink_boxes`)."""
    x0, y0, x1, y1 = region
    if w > x1 - x0 or h > y1 - y0:
        return None
    gx, gy = np.arange(x0, x1 - w + 1e-9, 5.0), np.arange(y0, y1 - h + 1e-9, 5.0)
    if square:
        return _nearest(_free_square(gx, gy, w, h, taken, gap), gx, gy, h, near)
    free = np.ones((len(gy), len(gx)), bool)
    for bx0, by0, bx1, by1 in taken:  # free: farther than `gap` from the box
        # only corners within `gap` of the box along both axes can be too near: that block
        # of the grid is examined (a cell more each way), the rest is free of this box
        if math.isnan(bx0 + by0 + bx1 + by1):  # a box of no known place: every corner is asked
            i0, i1, j0, j1 = 0, len(gx), 0, len(gy)
        else:
            i0, i1 = _grid_span(gx, bx0 - w - gap, bx1 + gap)
            j0, j1 = _grid_span(gy, by0 - h - gap, by1 + gap)
        if i0 >= i1 or j0 >= j1:
            continue
        bx, by = gx[i0:i1], gy[j0:j1]
        dx = np.maximum(np.maximum(bx0 - (bx + w), bx - bx1), 0.0)
        dy = np.maximum(np.maximum(by0 - (by + h), by - by1), 0.0)
        free[j0:j1, i0:i1] &= np.hypot(dx[None, :], dy[:, None]) > gap
    return _nearest(free, gx, gy, h, near)


def _nearest(free: np.ndarray, gx: np.ndarray, gy: np.ndarray, h: float, near) -> tuple[float, float] | None:
    """The free grid corner (lower left) whose upper left corner is nearest ``near``, or None."""
    k = np.flatnonzero(free)
    if not k.size:
        return None
    xs, ys = gx[k % len(gx)], gy[k // len(gx)]
    best = int(np.argmin(np.hypot(xs - near[0], ys + h - near[1])))
    return float(xs[best]), float(ys[best])


def _free_square(gx: np.ndarray, gy: np.ndarray, w: float, h: float, taken, gap: float) -> np.ndarray:
    """Which lower left grid corners of a w × h box leave every box of ``taken`` grown by ``gap``
    unmet: each box blocks a block of corners, summed at once in a difference array."""
    b = np.asarray(taken, float).reshape(-1, 4)
    b = b[~np.isnan(b).any(axis=1)]
    i0 = np.searchsorted(gx, b[:, 0] - gap - w, side="right")  # the first corner x > x0 - gap - w
    i1 = np.searchsorted(gx, b[:, 2] + gap, side="left")  # the first corner x ≥ x1 + gap
    j0 = np.searchsorted(gy, b[:, 1] - gap - h, side="right")
    j1 = np.searchsorted(gy, b[:, 3] + gap, side="left")
    hit = (i0 < i1) & (j0 < j1)
    diff = np.zeros((len(gy) + 1, len(gx) + 1), np.int32)
    for rows, cols, sign in ((j0, i0, 1), (j0, i1, -1), (j1, i0, -1), (j1, i1, 1)):
        np.add.at(diff, (rows[hit], cols[hit]), sign)
    return diff.cumsum(axis=0).cumsum(axis=1)[:-1, :-1] == 0


#: Longest piece of a drawn line taken as one box when a view's empty room is looked into, mm.
INK_PIECE_MM = 4.0


def ink_boxes(placed: PlacedView, piece_mm: float = INK_PIECE_MM) -> list[tuple[float, float, float, float]]:
    """Boxes (sheet mm) that cover what `placed` draws: its lines, circles and vectors cut into
    pieces of at most `piece_mm`, its texts' boxes and its closed outlines' (a link's plate, a
    block) whole boxes; a box clear of them all lies in the view's empty room (the inside of a
    tall mechanism's plan of positions), not inside a part of it."""
    chains, boxes = [], []
    for p in placed.primitives:
        if isinstance(p, Text):
            x, y = text_box(p).T
            boxes.append((x.min(), y.min(), x.max(), y.max()))
        elif isinstance(p, Polygon):  # a plate, a block, a hatched ground: its whole box
            x, y = np.asarray(p.points, float).T
            boxes.append((x.min(), y.min(), x.max(), y.max()))
        elif isinstance(p, Polyline):
            chains.append(np.asarray(p.points, float))
        elif isinstance(p, Circle):
            chains.append(circle_outline(p.centre, p.radius, segments=36))
        elif isinstance(p, Arrow):
            chains.append(np.array([p.start, p.end], float))
    if chains:
        a = np.concatenate([c[:-1] for c in chains])
        b = np.concatenate([c[1:] for c in chains])
        n = np.maximum(np.ceil(np.hypot(*(b - a).T) / piece_mm), 1).astype(int)
        k = np.repeat(np.arange(len(a)), n)
        t = (np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)) / n[k]
        lo, hi = a[k] + (b - a)[k] * t[:, None], a[k] + (b - a)[k] * (t + 1.0 / n[k])[:, None]
        cut = np.hstack([np.minimum(lo, hi), np.maximum(lo, hi)])
        boxes += [tuple(r) for r in np.unique(np.round(cut, 1), axis=0)]
    return boxes
