"""Extreme (dead-centre) positions found to round-off, the stroke H and the coefficient K.

An extreme of a link angle θ(φ) or of a slide s(φ) is a root of its velocity analogue
(ω/ω1 or ṡ/ω1). Roots are bracketed on a grid and refined by Newton steps on the analytic
derivative (the acceleration analogue at ε1 = 0), safeguarded by bisection.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from velplan.analysis.roots import newton_bisection
from velplan.analysis.solver import Kinematics, solve
from velplan.errors import MechanismError
from velplan.mechanism.model import Mechanism

GRID = 1440


@dataclass(frozen=True)
class Extreme:
    """One extreme position: crank angle ``phi`` (rad, in [0, 2π)), the value of the quantity
    there (rad or m), and whether it is a ``"max"`` or ``"min"``."""

    phi: float
    value: float
    kind: str


@dataclass(frozen=True)
class Stroke:
    """Stroke of the output between its two extreme positions.

    Attributes
    ----------
    quantity : str
        ``"point F"`` (displacement along its guide, m) or ``"link 5"`` (angle, rad).
    H : float
        Stroke, m (or the swing angle, rad, for a link).
    start, end : Extreme
        Extremes at the start and end of the slow (working) stroke.
    theta : float
        Angle of overlap θ (rad): the crank turns π + θ in the slow stroke, π − θ in the return.
    reversals : int
        Extreme positions of the output per turn: 2 for a plain back-and-forth stroke; more
        (a dwell mechanism, an output that doubles back) make H the overall travel between the
        highest and lowest extremes and θ, K refer to those two only.
    """

    quantity: str
    H: float
    start: Extreme
    end: Extreme
    theta: float
    reversals: int = 2

    @property
    def K(self) -> float:
        """Time-ratio coefficient K = (180° + θ)/(180° − θ)."""
        return (math.pi + self.theta) / (math.pi - self.theta)


def _quantities(mech: Mechanism, kin: Kinematics) -> dict[str, tuple[str, int, int]]:
    """Name → (kind "link"/"slide", index, component) for every quantity whose extremes matter."""
    out = {f"link {k}": ("link", i, 0) for k, i in kin.link_index.items() if k != mech.crank.link}
    out.update({f"slide {k}": ("slide", i, 0) for k, i in kin.slide_index.items()})
    return out


def _values(kin: Kinematics, kind: str, i: int):
    if kind == "link":
        return np.unwrap(kin.angles[:, i]), kin.omegas[:, i], kin.epsilons[:, i]
    return kin.slides[:, i, 0], kin.slides[:, i, 1], kin.slides[:, i, 2]


def find_roots(mech: Mechanism, kind: str, i: int, *, grid: int = GRID) -> list[Extreme]:
    """Crank angles in [0, 2π) where the rate of quantity (kind, i) vanishes, to round-off."""
    # The grid is shifted off round angles so that no sample lands on a root exactly.
    phi = (np.arange(grid + 1) + 0.3819660112501051) * (2 * np.pi / grid)
    kin = solve(mech, phi, omega1=1.0, epsilon1=0.0)
    _, rate, _ = _values(kin, kind, i)
    sign = np.sign(rate)
    brackets = np.flatnonzero(sign[:-1] * sign[1:] < 0)
    lo, hi = phi[brackets], phi[brackets + 1]
    flo, fhi = rate[brackets], rate[brackets + 1]

    def at(x):
        return _values(solve(mech, x, omega1=1.0, epsilon1=0.0), kind, i)

    def rate_of(x):
        _, f, df = at(x)
        return f, df

    # Newton's steps on the analytic derivative from the secant point of the grid's bracket
    # (two or three reach round-off), a bisection where a step would leave the bracket
    with np.errstate(divide="ignore", invalid="ignore"):
        x = lo - flo * (hi - lo) / (fhi - flo)
    x = np.where((x > lo) & (x < hi), x, 0.5 * (lo + hi))
    if x.size == 0:
        return []
    x = newton_bisection(rate_of, lo, hi, flo, x, ulps=4, closed=False)
    val, _, df = at(x)
    roots = x % (2 * np.pi)
    order = np.argsort(roots)
    return [Extreme(float(roots[j]), float(val[j]), "max" if df[j] < 0 else "min") for j in order]


def extremes(mech: Mechanism) -> dict[str, list[Extreme]]:
    """Extreme positions of every link angle (but the crank's) and every prismatic slide."""
    kin = solve(mech, np.zeros(1), order=0)
    return {name: find_roots(mech, kind, i) for name, (kind, i, _) in _quantities(mech, kin).items()}


def output_quantity(mech: Mechanism, kin: Kinematics | None = None) -> tuple[str, str, int] | None:
    """(label, kind, index) of the mechanism's output quantity, or None without an output;
    ``kin``, any solution of ``mech``, gives the indices (solved at one angle when omitted)."""
    out = mech.output
    if out is None:
        return None
    if kin is None:
        kin = solve(mech, np.zeros(1), order=0)
    if out.link is not None:
        return f"link {out.link}", "link", kin.link_index[out.link]
    for g in mech.groups:
        slide = g.output_slides().get(out.point)
        if slide is not None:
            return f"point {out.point}", "slide", kin.slide_index[slide[1]]
    raise MechanismError(
        f"output point {out.point!r} is not a slider on a guide; give output = {{link = ...}} for a rocker"
    )


@functools.lru_cache(maxsize=256)
def stroke(mech: Mechanism) -> Stroke | None:
    """Stroke H, extremes and K of the mechanism's output (None without an output).

    The slow stroke (the crank turns through π + θ) is taken as the working stroke. Cached
    by the mechanism (a hashable value): the extremes are found once however many results
    need them (the study's positions, the loads' strokes).
    """
    return _stroke(mech)


def _stroke(mech: Mechanism) -> Stroke | None:
    q = output_quantity(mech)
    if q is None:
        return None
    label, kind, i = q
    roots = find_roots(mech, kind, i)
    if len(roots) < 2:
        raise MechanismError(f"output {label} has no extreme positions (it turns or slides without reversing)")
    hi = max(roots, key=lambda e: e.value)
    lo = min(roots, key=lambda e: e.value)
    sense = mech.crank.sense
    span_lo_hi = (sense * (hi.phi - lo.phi)) % (2 * np.pi)
    if abs(span_lo_hi - np.pi) < 1e-9:
        # K = 1: both strokes take half a turn. The working stroke starts at the given
        # reference position when that is an extreme, else where the output starts to rise.
        ref = None if mech.reference_deg is None else math.radians(mech.reference_deg) % (2 * np.pi)
        near = lambda e: ref is not None and abs((e.phi - ref + np.pi) % (2 * np.pi) - np.pi) < 1e-6
        first = hi if near(hi) and not near(lo) else lo
        start, end = (lo, hi) if first is lo else (hi, lo)
        span = span_lo_hi if first is lo else 2 * np.pi - span_lo_hi
    elif span_lo_hi > np.pi:
        start, end, span = lo, hi, span_lo_hi
    else:
        start, end, span = hi, lo, 2 * np.pi - span_lo_hi
    return Stroke(label, abs(hi.value - lo.value), start, end, float(span - np.pi), len(roots))


def reference_angle(mech: Mechanism) -> float:
    """Crank angle of position 1, rad: ``reference_deg`` if given, else the start of the slow
    stroke of the output, else 0."""
    if mech.reference_deg is not None:
        return math.radians(mech.reference_deg)
    s = stroke(mech)
    return 0.0 if s is None else s.start.phi


def positions(mech: Mechanism, n: int = 12) -> np.ndarray:
    """``n`` crank angles (rad) evenly spaced from the reference position in the sense of ω1."""
    if n < 1:
        raise MechanismError(f"number of positions must be ≥ 1, not {n}")
    sense = mech.crank.sense
    return reference_angle(mech) + sense * np.arange(n) * (2 * np.pi / n)
