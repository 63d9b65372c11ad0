"""The layout problem every sheet solves: draw a view at a trial scale, measure it, try the
next scale until it fits its region. A view's labels make its size known only once drawn, so
the trials are real drawings; `Trials` keeps each one, so that no view of a sheet is drawn
twice at the same scale, however many arrangements the sheet compares.

Examples
--------
>>> from velplan.views.base import make_view
>>> from velplan.render.scene import Polyline
>>> square = Trials(lambda side: make_view("square", [Polyline([(0, 0), (side, side)], "l")]))
>>> largest_fitting(square, (120.0, 90.0, 60.0), 100.0, 100.0)[0]
90.0
>>> square(90.0) is square(90.0), square.drawn
(True, 2)
"""

from __future__ import annotations

import math
from typing import Callable, Generic, Hashable, Iterable, TypeVar

import numpy as np

from velplan.views.base import View

EPS_MM = 1e-6
"""Tolerance of a fit, mm."""


def fits(view: View, w: float, h: float) -> bool:
    """Whether `view` fits a region of w × h mm."""
    return view.width_mm <= w + EPS_MM and view.height_mm <= h + EPS_MM


T = TypeVar("T")

class Trials(Generic[T]):
    """A view drawn at trial parameters, memoised: ``trials(*key)`` draws ``draw(*key)`` the
    first time and returns the same view afterwards. ``drawn`` counts the drawings made."""

    def __init__(self, draw: Callable[..., T]):
        self._draw = draw
        self._views: dict[Hashable, T] = {}

    def __call__(self, *key) -> T:
        if key not in self._views:
            self._views[key] = self._draw(*key)
        return self._views[key]

    @property
    def drawn(self) -> int:
        return len(self._views)


def largest_fitting(draw: Callable[..., View], trials: Iterable, w: float, h: float, *,
                    skip: Callable[..., bool] | None = None):
    """(trial, view) of the first of `trials` (scales or sizes, the largest drawing first)
    whose view ``draw(trial)`` fits w × h mm, or None. ``skip(trial)`` true marks a trial
    that cannot fit (its geometry alone exceeds the region): it is passed over undrawn."""
    for trial in trials:
        if skip is not None and skip(trial):
            continue
        view = draw(trial)
        if fits(view, w, h):
            return trial, view
    return None


def widest_first(draw: Callable[[float], View], scales: Iterable[float], w: float):
    """(scale, view) of the first of `scales` whose drawing is at most `w` mm wide (a table's
    text sizes, a diagram's φ axes), or (None, the last view drawn)."""
    view = None
    for scale in scales:
        view = draw(scale)
        if view.width_mm <= w:
            return scale, view
    return None, view


class ShrinkingRows:
    """Rows of drawings shrunk to fit a region, the one shrink-to-fit of a sheet's rows.

    ``layout`` holds the rows, each a list of units, each unit a list of drawings (``refs``):
    a unit's drawings side by side (``mode`` "row"), one under another ("stack"), or under
    one another where they are no taller than a row so, side by side otherwise ("fit"). Every
    drawing starts at the scale ``scale[entity(ref)]`` (drawings of one entity share it) and
    ``span[entity]`` is its size at scale 1. While a unit is taller than ``row_h``, its tallest
    drawing that can shrink goes one scale smaller; while a row is wider than the region, the
    entity of its widest drawing does (kept and marked stuck when that does not narrow the
    row). The score is the sum over the drawings of the logarithm of their sizes.

    A subclass says what a drawing is at its entity's scale (`view`), what its scale belongs
    to (`entity`), the next smaller scale of an entity or None below the legible size
    (`smaller`), which drawings' scales the sheet records (`records`) and the one-line error
    when no layout fits (`fail`); ``least`` is the least row height, mm.
    """

    least: float = 0.0

    def __init__(self, layout, region, gap: float, row_h: float, mode: str, span: dict, scale: dict):
        self.layout, self.region, self.gap, self.row_h, self.mode = layout, region, gap, row_h, mode
        self.span, self.scale = span, scale
        self.stuck: set = set()

    def view(self, ref) -> View:
        raise NotImplementedError

    def entity(self, ref):
        raise NotImplementedError

    def smaller(self, entity) -> float | None:
        raise NotImplementedError

    def fail(self, why: str) -> Exception:
        raise NotImplementedError

    def records(self, ref) -> bool:
        """Whether the sheet records the scale of the drawing ``ref`` by its view's name."""
        return True

    def least_height(self, ref) -> float:
        """A lower bound of the height of the drawing ``ref`` at its entity's scale, mm, found
        without drawing it (0: none known); a drawing that must be taller than a row is
        shrunk undrawn where it is the tallest of its unit."""
        return 0.0

    def stacks(self, unit) -> bool:
        """Whether the drawings of `unit` go one under another: always in mode "stack", never
        in mode "row"; in mode "fit", where so they are no taller than a row (they save width)."""
        if self.mode != "fit" or len(unit) == 1:
            return self.mode == "stack"
        heights = [self.view(r).height_mm for r in unit]
        return sum(heights) + self.gap * (len(heights) - 1) <= self.row_h + 1e-6

    def unit_size(self, unit) -> tuple[float, float]:
        vs = [self.view(r) for r in unit]
        if self.stacks(unit) or len(vs) == 1:
            return max(v.width_mm for v in vs), sum(v.height_mm for v in vs) + self.gap * (len(vs) - 1)
        return sum(v.width_mm for v in vs) + self.gap * (len(vs) - 1), max(v.height_mm for v in vs)

    def row_width(self, units) -> float:
        return sum(self.unit_size(u)[0] for u in units) + self.gap * (len(units) - 1)

    def score(self) -> float:
        return sum(math.log(self.span[self.entity(r)] / self.scale[self.entity(r)])
                   for units in self.layout for unit in units for r in unit)

    def solve(self, floor: float | None = None) -> bool:
        """Shrink until every row fits; False as soon as the score falls to `floor`."""
        if self.row_h < self.least:
            raise self.fail(f"rows of {max(self.row_h, 0):.0f} mm")
        for _ in range(400):
            if floor is not None and self.score() <= floor:
                return False
            if not (self.shrink_tall() or self.shrink_wide()):
                return True
        raise self.fail("no layout found")

    def shrink_tall(self) -> bool:
        """The tallest drawing of the first unit taller than a row one scale smaller (one at
        its least: the next tallest); False when no unit is too tall."""
        too_tall = self.row_h + 1e-6  # a unit is at least as tall as each of its drawings
        unit = next((u for units in self.layout for u in units
                     if max(self.least_height(r) for r in u) > too_tall or self.unit_size(u)[1] > too_tall), None)
        if unit is None:
            return False
        if self._shrink_undrawn(unit, too_tall):
            return True
        by_height = sorted(unit, key=lambda r: -self.view(r).height_mm)
        shrink = [r for r in by_height if self.smaller(self.entity(r)) is not None]
        if not shrink:
            tall = self.view(by_height[0])
            raise self.fail(f"{tall.name} is {tall.height_mm:.0f} mm tall")
        self.scale[self.entity(shrink[0])] = self.smaller(self.entity(shrink[0]))
        return True

    def _shrink_undrawn(self, unit, too_tall: float) -> bool:
        """`shrink_tall` for a unit whose drawing, by its `least_height` taller than a row and
        than every other drawing of the unit, can shrink: the same step, that drawing undrawn."""
        least = [self.least_height(r) for r in unit]
        j = int(np.argmax(least))
        ref = unit[j]
        if least[j] <= too_tall or self.smaller(self.entity(ref)) is None:
            return False
        if any(least[j] <= self.view(r).height_mm for k, r in enumerate(unit) if k != j):
            return False
        self.scale[self.entity(ref)] = self.smaller(self.entity(ref))
        return True

    def shrink_wide(self) -> bool:
        """The widest drawing of the widest row one scale smaller (kept, and marked stuck,
        when that does not narrow the row); False when every row fits."""
        widths = [self.row_width(units) for units in self.layout]
        worst = int(np.argmax(widths))
        if widths[worst] <= self.region[2] - self.region[0] + 1e-6:
            return False
        share: dict = {}
        for unit in self.layout[worst]:
            vs = [self.view(r) for r in unit]
            side_by_side = not self.stacks(unit)
            for r, v in zip(unit, vs):
                if side_by_side or v.width_mm >= max(w.width_mm for w in vs) - 1e-9:
                    share[self.entity(r)] = max(share.get(self.entity(r), 0.0), v.width_mm)
        candidates = sorted((e for e in share if e not in self.stuck and self.smaller(e) is not None),
                            key=lambda e: (-share[e], str(e)))
        if not candidates:
            raise self.fail(f"a row {widths[worst]:.0f} mm wide")
        entity = candidates[0]
        old = self.scale[entity]
        self.scale[entity] = self.smaller(entity)
        if self.row_width(self.layout[worst]) > widths[worst] - 0.5:
            self.scale[entity] = old  # its width is its text's: a smaller drawing gains nothing
            self.stuck.add(entity)
        return True

    def place_unit(self, unit, x: float, y: float, placed: dict, scales: dict) -> None:
        """A unit's views from its upper left corner (x, y): side by side, or stacked."""
        stacked = self.stacks(unit)
        for ref in unit:
            v = self.view(ref)
            placed[v.name] = v.at(x, y - v.height_mm)
            if self.records(ref):
                scales[v.name] = self.scale[self.entity(ref)]
            if stacked:
                y -= v.height_mm + self.gap
            else:
                x += v.width_mm + self.gap
