"""Shared checks of the drawn-form and PMKS tests: two mechanisms move alike."""

from __future__ import annotations

import numpy as np

from velplan.analysis.solver import solve

ANGLES = np.radians(np.arange(0.0, 360.0, 5.0))
"""72 crank angles, rad."""


def same_motion(first, second, *, skip=(), phis=ANGLES, tol=1e-12, special: bool = True) -> int:
    """Assert that the points both mechanisms name (but ``skip``, and with ``special=False``
    Assur's special points: a triad's K is where the lines of the two leads its labelling pairs
    meet, so two labellings of one group that name no pair name different points K) have the
    same positions, velocities and accelerations at ``phis`` to ``tol`` of each quantity's
    largest value; returns the number of points compared."""
    k1, k2 = solve(first, phis), solve(second, phis)
    assert np.array_equal(k1.valid, k2.valid)
    left_out = set(skip) | (set() if special else
                            {p for m in (first, second) for g in m.groups for p in g.special_points()})
    names = [n for n in k1.point_index if n in k2.point_index and n not in left_out]
    assert names
    i1 = [k1.point_index[n] for n in names]
    i2 = [k2.point_index[n] for n in names]
    for attr in ("positions", "velocities", "accelerations"):
        a, b = getattr(k1, attr)[k1.valid][:, i1], getattr(k2, attr)[k2.valid][:, i2]
        scale = max(np.max(np.abs(a)), 1e-300)
        assert np.max(np.abs(a - b)) <= tol * scale, (attr, np.max(np.abs(a - b)) / scale)
    return len(names)


def canonical(group) -> tuple:
    """A group as (kind, its links as a set, its branch or side written for its links in
    sorted order): two decompositions of one mechanism give the same."""
    links = tuple(group.links)
    if group.kind == "RRR":
        return "RRR", frozenset(links), group.branch * (1 if list(links) == sorted(links) else -1)
    if group.kind == "triad":
        return "triad", frozenset(links), group.base, group.side
    return group.kind, frozenset(links), getattr(group, "branch", 0)
