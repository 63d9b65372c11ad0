"""A mechanism prepared once for solving: what every call of `velplan.analysis.solver.solve` on
one mechanism (and one ``points=``) would otherwise redo — the mechanism moved about its crank's
pivot and the shift back, the solving schedule, the length scale, each class III group's branch
over the turn, the compiled engine's program, and the numpy engine's output layout.

Preparations are kept per mechanism object (looked up by identity, a few hundred nanoseconds) and,
for an equal mechanism loaded again, by content (the latest `KEEP`).
"""

from __future__ import annotations

import dataclasses
import threading
import weakref

import numpy as np

from velplan.analysis.blocks import about_pivot, needed_items
from velplan.analysis.kinematics import length_scale
from velplan.mechanism.model import Mechanism
from velplan.mechanism.structure import schedule

KEEP = 64
"""Preparations kept by content (mechanisms, ``points=``); the oldest goes first."""


class Prepared:
    """``mech`` prepared for solving ``points`` (None: all).

    Attributes
    ----------
    local : Mechanism
        ``mech`` moved so that its crank's pivot is at the origin (``mech`` itself when it is).
    shift : complex
        Where the pivot is (m): added to the positions solved about it.
    items : tuple
        The solving schedule, cut to what ``points`` need.
    scale : float
        `velplan.analysis.kinematics.length_scale` of ``mech``, m.
    class_iii : bool
        Whether ``items`` hold a class III group.
    """

    __slots__ = ("local", "shift", "items", "scale", "points", "class_iii", "_tracks", "_layout", "outputs")

    def __init__(self, mech: Mechanism, points: tuple | None):
        self.points = points
        self.local, pivot = about_pivot(mech)
        if self.local is mech:  # held by the caches: an equal copy, so that `mech` may be collected
            self.local = dataclasses.replace(mech)
        self.shift = complex(pivot[0], pivot[1])
        self.items = schedule(self.local) if points is None else needed_items(self.local, points)
        self.scale = length_scale(self.local)
        self.class_iii = any(getattr(g, "tracked", False) for g in self.items)
        """Whether a group whose branch is tracked (class III) is solved: its branch is tracked
        before the first solve."""
        self._tracks: dict | None = None
        self._layout = None
        self.outputs: dict | None = None
        """Where the numpy engine's results sit (`velplan.analysis.blocks.output_index`), set by
        its first solve."""

    def tracks(self, solve) -> dict:
        """Each class III group's branch over the turn (`velplan.analysis.triad.track`, solving
        what comes before it with ``solve``), found once."""
        if self._tracks is None:
            triads = [g for g in self.items if getattr(g, "tracked", False)]
            found = {}
            if triads:
                from velplan.analysis import triad

                found = {g.name: triad.track(triad.upstream(self.local, g), g, solve) for g in triads}
            self._tracks = found
        return self._tracks

    def layout(self, tracks: dict | None = None):
        """The compiled engine's `velplan.analysis.compiled.Layout` of the moved mechanism (its
        class III groups solved from ``tracks``, `tracks`; without them the layout hands them to numpy)."""
        if self._layout is None:
            from velplan.analysis import compiled

            self._layout = compiled.layout(self.local, self.points, tracks)
        return self._layout


_BY_ID: dict[int, tuple] = {}
"""id(mechanism) → (weak reference to it, {points: Prepared})."""
_BY_CONTENT: dict = {}
_LOCK = threading.Lock()


def prepared(mech: Mechanism, points=None) -> Prepared:
    """``mech`` prepared for solving ``points`` (an iterable of point names, or None for all)."""
    key = None if points is None else tuple(points)
    entry = _BY_ID.get(id(mech))
    if entry is not None and entry[0]() is mech:
        hit = entry[1].get(key)
        if hit is not None:
            return hit
    hit = _by_content(mech, key)
    with _LOCK:
        entry = _BY_ID.get(id(mech))
        if entry is None or entry[0]() is not mech:
            entry = (_weak(mech), {})
            _BY_ID[id(mech)] = entry
        entry[1][key] = hit
    return hit


def _weak(mech: Mechanism):
    """A weak reference to ``mech`` that forgets its preparations when it is collected."""
    ident = id(mech)

    def forget(ref, table=_BY_ID):  # no lock: the collector may call this while this thread holds it
        if table.get(ident, (None,))[0] is ref:
            table.pop(ident, None)

    return weakref.ref(mech, forget)


def _by_content(mech: Mechanism, key) -> Prepared:
    """The preparation of a mechanism whose kinematics equals ``mech``'s (the same ground, crank,
    groups and points), made once."""
    content = (mech.ground, mech.crank, mech.groups, mech.points, key)
    try:
        hit = _BY_CONTENT.get(content)
    except TypeError:  # built by hand with a list somewhere: not kept
        return Prepared(mech, key)
    if hit is not None:
        return hit
    hit = Prepared(mech, key)
    with _LOCK:
        if len(_BY_CONTENT) >= KEEP:
            _BY_CONTENT.pop(next(iter(_BY_CONTENT)), None)
        _BY_CONTENT[content] = hit
    return hit


def shifted(z: np.ndarray, shift: complex) -> None:
    """Add ``shift`` (m) to the complex positions ``z`` (…, n) in place."""
    if shift:
        z += shift
