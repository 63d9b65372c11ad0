"""Assembly check over a whole crank revolution, with the limits found exactly.

A group stops closing where its two construction circles or lines become tangent: there its
condition estimate c (the sine of the angle between them) falls to 0, and c² — the
discriminant of the closure, up to a positive factor — is smooth and changes sign. The turn
is sampled every 0.1°; every range that fails at a sample is bracketed and its ends found by
bisection, and every local minimum of c² between samples that still close is searched
(Brent's method on c²) for a gap narrower than the sampling, so that a mechanism that jams
for a hundredth of a degree is not taken for a full-turn crank.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.errors import AssemblyError
from velplan.mechanism.model import Mechanism

SAMPLES = 3600
"""Crank angles sampled by `check_full_rotation` (0.1° apart)."""
SUSPECT = 0.3
"""A local minimum of the condition estimate below this is searched for a gap between samples:
a gap under 0.1° leaves c ≈ √(slope·0.1°) at the samples beside it, far below 0.3."""
EDGE_TOL_DEG = 1e-9
"""Accuracy of the limits of a failing range, deg."""


def failing_ranges(mask: np.ndarray, phi_deg: np.ndarray) -> list[tuple[float, float]]:
    """Contiguous ranges (deg) of ``phi_deg`` where ``mask`` is True, wrapping at 360°."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    step = phi_deg[1] - phi_deg[0]
    breaks = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate([[idx[0]], idx[breaks + 1]])
    ends = np.concatenate([idx[breaks], [idx[-1]]])
    ranges = [(float(phi_deg[s]), float(phi_deg[e])) for s, e in zip(starts, ends)]
    if len(ranges) > 1 and ranges[0][0] == phi_deg[0] and ranges[-1][1] >= phi_deg[-1] - step / 2:
        ranges = [(ranges[-1][0] - 360.0, ranges[0][1])] + ranges[1:-1]
    return ranges


def _closure(mech: Mechanism, column: int):
    """c² of the group in ``column`` at one crank angle (deg), or −1 where it does not close."""
    from velplan.analysis.solver import solve

    def f(deg: float) -> float:
        c = float(solve(mech, [math.radians(deg)], order=0).condition[0, column])
        return c * c if math.isfinite(c) else -1.0

    return f


def _edge(f, closed: float, open_: float) -> float:
    """The limit between a closing angle and a failing one (deg), by bisection."""
    while abs(open_ - closed) > EDGE_TOL_DEG:
        mid = 0.5 * (closed + open_)
        if f(mid) < 0:
            open_ = mid
        else:
            closed = mid
    return 0.5 * (closed + open_)


def _hidden_gap(f, lo: float, hi: float) -> float | None:
    """An angle in (lo, hi) (deg) where the group does not close, searched around the minimum
    of c², or None."""
    from scipy.optimize import minimize_scalar

    found: list[float] = []

    def g(x: float) -> float:
        v = f(x)
        if v < 0:
            found.append(x)
            return -1.0
        return v

    minimize_scalar(g, bounds=(lo, hi), method="bounded", options={"xatol": 1e-10, "maxiter": 60})
    return found[0] if found else None


def limits(mech: Mechanism) -> dict[str, list[tuple[float, float]]]:
    """Group name → the ranges of crank angles (deg, in [0, 360) or wrapping below 0) where it
    cannot be assembled, with ends to `EDGE_TOL_DEG`."""
    from velplan.analysis.solver import solve

    phi_deg = np.arange(SAMPLES) * (360.0 / SAMPLES)
    step = 360.0 / SAMPLES
    kin = solve(mech, np.radians(phi_deg), order=0)
    out: dict[str, list[tuple[float, float]]] = {}
    for g in mech.groups:
        column = kin.group_index[g.name]
        c = kin.condition[:, column]
        bad = ~np.isfinite(c)
        f = _closure(mech, column)
        ranges = []
        if bad.all():
            out[g.name] = [(0.0, 360.0)]
            continue
        for a, b in failing_ranges(bad, phi_deg):
            ranges.append((_edge(f, a - step, a), _edge(f, b + step, b)))
        # a gap between two closing samples shows as a local minimum of c² there
        c2 = np.where(bad, np.inf, c * c)
        prev, nxt = np.roll(c2, 1), np.roll(c2, -1)
        minima = np.flatnonzero((c2 <= prev) & (c2 <= nxt) & ((c2 < prev) | (c2 < nxt)) & np.isfinite(prev)
                                & np.isfinite(nxt) & (c2 < SUSPECT ** 2))
        for k in minima:
            hit = _hidden_gap(f, phi_deg[k] - step, phi_deg[k] + step)
            if hit is not None:
                ranges.append((_edge(f, phi_deg[k] - step, hit), _edge(f, phi_deg[k] + step, hit)))
        if ranges:
            out[g.name] = sorted(ranges)
    return out


def _deg(x: float, width: float) -> str:
    digits = 1 if width >= 1.0 else max(1, min(9, 1 - math.floor(math.log10(max(width, 1e-12)))))
    return f"{x % 360.0 if x >= 360.0 else x:.{digits}f}°"


def check_full_rotation(mech: Mechanism) -> None:
    """Raise `AssemblyError` if some group cannot be closed at some crank angle.

    The message names the first group that fails and every range of crank angles (deg) where
    it cannot be assembled, its ends found to `EDGE_TOL_DEG` (written to 0.1°, or to as many
    decimals as a narrow range needs).
    """
    from velplan.analysis.solver import group_point

    found = limits(mech)
    for g in mech.groups:
        ranges = found.get(g.name)
        if not ranges:
            continue
        text = ", ".join(f"{_deg(a, b - a)}…{_deg(b, b - a)}" for a, b in ranges)
        first = ranges[0]
        raise AssemblyError(
            f"group {g.name!r} ({g.kind}) cannot be assembled for crank angles {text}: "
            f"point {group_point(g)!r} has no position there",
            group=g.name,
            point=group_point(g),
            phi_deg=float(0.5 * (first[0] + first[1]) % 360.0),
        )
