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

from typing import Callable, Generic, Hashable, Iterable, TypeVar

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
