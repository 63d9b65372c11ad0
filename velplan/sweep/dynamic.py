"""Dynamic figures of merit of many variants: the peak balancing moment M_b on the crank and
the flywheel's constant reduced inertia J_I for a coefficient of speed fluctuation δ.

Both come from the balance of powers over variants × angles in whole arrays. The file's loads
are resolved for every variant from the output's extremes that `velplan.sweep.merit` finds
(the crank angles where a load starts or stops by Newton's steps on all variants together),
gravity and the inertia forces join them, and

* M_b·ω1 = −Σ (F·V + M·ω) over loads, gravity and inertia (`velplan.forces.power`) at the
  sweep's angles — equal to the kinetostatic and lever results to round-off; ``Mb_max`` is
  its largest |M_b| there;
* J(θ) = Σ m·|r′_S|² + J_S·φ′² and M(θ) = Σ F·r′ + M·φ′ at the 16 Gauss–Legendre nodes of 64
  panels cut at every variant's breakpoints (`velplan.dynamics.panels`), their Legendre series,
  and J_I by the energy–mass envelope of `velplan.dynamics.flywheel`, its extremes refined by
  Newton's steps on the series of all variants together.

A press load given by its Fourier series (``harmonics``) is resolved per variant by
`parse_load` on the variant (a loop); every other load in whole arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.polynomial import legendre as L

from velplan.analysis.design import DesignKinematics, _speed, solve_design, variant
from velplan.analysis.extremes import output_quantity
from velplan.analysis.roots import newton_bisection
from velplan.dynamics.panels import legendre_basis, panels_over
from velplan.dynamics.reduction import PANELS
from velplan.dynamics.spec import parse_dynamics
from velplan.errors import MechanismError, VelplanError
from velplan.forces.actions import Actions, AppliedForce
from velplan.forces.common import dot, link_motion, point
from velplan.forces.inertia import inertia_of
from velplan.forces.loads import CuttingForce, IndicatorForce, PressLoad, TableForce, gravity_actions, load_actions
from velplan.forces.parse import parse_load, parse_loads
from velplan.forces.power import powers
from velplan.mechanism.model import Mechanism

TWO_PI = 2.0 * math.pi
SPEED_KEYS = ("crank.omega", "crank.rpm")


def has_dynamics(mech: Mechanism) -> bool:
    """True when ``mech`` has loads or masses: a balancing moment to find."""
    return bool(mech.loads) or any(m.mass > 0 or m.inertia for m in mech.masses)


@dataclass(frozen=True)
class Ends:
    """The output's working stroke per variant (arrays of shape (V,)).

    Attributes
    ----------
    start_phi, end_phi : ndarray
        Crank angles at its start and end extremes, rad.
    s_start, s_end : ndarray
        The output's slide there, m.
    span : ndarray
        Crank turn of the working stroke, π + θ, rad.
    sense : ndarray
        +1 where the crank turns counter-clockwise, −1 otherwise.
    reference : ndarray
        Crank angle of position 1, rad (`velplan.analysis.extremes.reference_angle`).
    """

    start_phi: np.ndarray
    end_phi: np.ndarray
    s_start: np.ndarray
    s_end: np.ndarray
    span: np.ndarray
    sense: np.ndarray
    reference: np.ndarray


# ---- loads over variants --------------------------------------------------------------------


@dataclass(frozen=True)
class _EachVariant:
    """A load resolved variant by variant (a press load's Fourier series): ``loads`` one per
    variant, None where the variant has no stroke to resolve it on."""

    name: str
    loads: tuple

    def actions(self, kin) -> Actions:
        """The force of each variant's load at its own n positions of ``kin`` (V·n, variant-major)."""
        n = len(kin) // len(self.loads)
        vectors, head = [], None
        for v, ld in enumerate(self.loads):
            if ld is None:
                vectors.append(np.full(n, np.nan + 0j))
                continue
            head = ld.actions(kin.take(slice(v * n, (v + 1) * n))).forces[0]
            vectors.append(head.vector)
        if head is None:
            return Actions()
        return Actions((AppliedForce(head.label, head.link, head.point, np.concatenate(vectors), head.source),))

    def breakpoints(self) -> np.ndarray:
        """(V, 2) crank angles where the load starts and stops (NaN for the exact parabola's
        series, and where the variant has none), rad."""
        rows = [(ld.breakpoints() if ld is not None else ()) for ld in self.loads]
        return np.array([r + (math.nan,) * (2 - len(r)) for r in rows])


def variant_loads(mech: Mechanism, values: dict, ends: Ends, engine: str) -> tuple:
    """The file's loads over the variants of ``values``: a press load with its angles and sense
    per variant (`press_arrays`), or resolved on every variant when it is a Fourier series."""
    loads = parse_loads(mech)
    V = ends.sense.shape[0]
    out = []
    for i, ld in enumerate(loads):
        if isinstance(ld, PressLoad) and ld.harmonics is not None:
            ld = _EachVariant(ld.name, tuple(_press(mech, values, v, i) for v in range(V)))
        elif isinstance(ld, PressLoad):
            ld = press_arrays(mech, values, ld, mech.loads[i].get("extreme", "lower"), ends, engine)
        out.append(ld)
    return tuple(out)


@dataclass(frozen=True)
class _PressArrays(PressLoad):
    """A press load whose angles, sense and direction are arrays (per variant or element)."""

    @property
    def width(self) -> np.ndarray:
        """Δ = crank turn from φ_start to φ_end, rad."""
        return np.mod(self.track.sense * (self.phi_end - self.phi_start), TWO_PI)


def press_arrays(mech: Mechanism, values: dict, ld: PressLoad, extreme: str, ends: Ends, engine: str) -> PressLoad:
    """``ld`` (the exact parabola) with φ_start, φ_end and its sense per variant (V,), as
    `velplan.forces.loads.press_load` resolves them on one mechanism: where the output, on its
    approach to the ``extreme`` ("lower", "start" or "end"), is b1 + b2 and b2 from it; NaN
    where the variant's stroke is shorter than b1 + b2."""
    if extreme == "lower":
        dk = solve_design(mech, values, np.column_stack([ends.start_phi, ends.end_phi]), order=0, engine=engine)
        y = dk.per_variant(dk.flat.positions[:, dk.flat.point_index[ld.point], 1])
        to_end = y[:, 1] < y[:, 0]
    else:
        to_end = np.full(ends.sense.shape, extreme == "end")
    s_far, s_near = np.where(to_end, ends.s_start, ends.s_end), np.where(to_end, ends.s_end, ends.s_start)
    toward = np.sign(s_near - s_far)
    target = np.column_stack([s_near - toward * (ld.b1 + ld.b2), s_near - toward * ld.b2])
    target[np.abs(s_near - s_far) < ld.b1 + ld.b2] = np.nan
    phi = np.full(target.shape, np.nan)
    for working in (True, False):
        if np.any(to_end == working):
            phi = np.where((to_end == working)[:, None], crossings(mech, values, ends, target, working, engine), phi)
    if ld.b2 == 0.0:  # ends at the extreme itself
        phi[:, 1] = np.mod(np.where(to_end, ends.end_phi, ends.start_phi), TWO_PI)
    fields = {f: getattr(ld, f) for f in ld.__dataclass_fields__}
    return _PressArrays(**{**fields, "track": replace(ld.track, sense=ends.sense), "phi_start": phi[:, 0],
                           "phi_end": phi[:, 1], "away": -toward})


def _press(mech: Mechanism, values: dict, v: int, i: int):
    try:
        return parse_load(variant(mech, {k: float(a[v]) for k, a in values.items()}), mech.loads[i], i)
    except MechanismError:  # the variant does not close or has no stroke: masked by its failure
        return None


def element_loads(loads: tuple, ends: Ends, n: int) -> tuple:
    """``loads`` for V variants at n angles each: every number resolved on the output's stroke
    an array over the V·n elements (variant-major)."""
    rep = lambda a: np.repeat(a, n)  # noqa: E731
    out = []
    for ld in loads:
        track = getattr(ld, "track", None)
        if track is not None:
            track = replace(track, start_phi=rep(ends.start_phi), end_phi=rep(ends.end_phi), sense=rep(ends.sense),
                            s_start=rep(ends.s_start), s_end=rep(ends.s_end), span=rep(ends.span))
        if isinstance(ld, TableForce):
            ld = replace(ld, track=track, ref_phi=rep(ends.reference), sense=rep(ends.sense))
        elif isinstance(ld, PressLoad):
            ld = replace(ld, track=track, phi_start=rep(ld.phi_start), phi_end=rep(ld.phi_end), away=rep(ld.away))
        elif isinstance(ld, (CuttingForce, IndicatorForce)):
            ld = replace(ld, track=track)
        out.append(ld)
    return tuple(out)


def _travel_targets(ends: Ends, travel, head: str) -> np.ndarray:
    """(V, k) slides at ``travel`` (m) from the extreme ``head`` strictly inside each stroke
    (NaN outside it)."""
    s0, s1 = (ends.s_start, ends.s_end) if head == "start" else (ends.s_end, ends.s_start)
    H = np.abs(s1 - s0)[:, None]
    d = np.unique(np.asarray(travel, dtype=float))[None, :]
    inside = (d > 1e-12 * H) & (d < H * (1 - 1e-12))
    return np.where(inside, s0[:, None] + d * np.sign(s1 - s0)[:, None], np.nan)


def breakpoints(mech: Mechanism, values: dict, loads: tuple, ends: Ends, engine: str) -> np.ndarray:
    """(V, B) crank angles where a load jumps or has a kink, per variant (NaN: none), rad —
    what `Load.breakpoints` gives for each variant."""
    V = ends.start_phi.shape[0]
    extremes = np.column_stack([ends.start_phi, ends.end_phi])
    cols = [np.zeros((V, 0))]
    for ld in loads:
        if isinstance(ld, _EachVariant):
            cols.append(ld.breakpoints())
        elif isinstance(ld, PressLoad):
            cols.append(np.column_stack([ld.phi_start, ld.phi_end]))
        elif isinstance(ld, CuttingForce):
            f = np.array([ld.start, ld.end])[None, :]
            cols.append(crossings(mech, values, ends, ends.s_start[:, None] + f * (ends.s_end - ends.s_start)[:, None],
                                  True, engine))
        elif isinstance(ld, TableForce):
            if ld.over == "crank":
                cols.append(ends.reference[:, None] + ends.sense[:, None] * np.radians(np.asarray(ld.x))[None, :])
            if ld.track is not None:
                cols.append(extremes)
            if ld.over == "output":
                target = _travel_targets(ends, ld.x, "start")
                if ld.stroke != "return":
                    cols.append(crossings(mech, values, ends, target, True, engine))
                if ld.stroke != "working":
                    cols.append(crossings(mech, values, ends, target, False, engine))
        elif isinstance(ld, IndicatorForce):
            target = _travel_targets(ends, ld.travel, ld.head)
            cols += [extremes, crossings(mech, values, ends, target, True, engine),
                     crossings(mech, values, ends, target, False, engine)]
    return np.concatenate(cols, axis=1)


def crossings(mech: Mechanism, values: dict, ends: Ends, target: np.ndarray, working: bool, engine: str) -> np.ndarray:
    """(V, k) crank angles (rad) where the output's slide is ``target`` (V, k; m; NaN: none) on
    the working (or the return) stroke, to a few ulp: a grid of 65 turns brackets every target,
    then safeguarded Newton steps on the exact analogue solve all of them together."""
    _, _, j = output_quantity(mech)
    V = target.shape[0]
    lo = np.zeros(V) if working else ends.span
    hi = ends.span if working else np.full(V, TWO_PI)

    def slide(psi):
        dk = solve_design(mech, values, ends.start_phi[:, None] + ends.sense[:, None] * psi, order=1, engine=engine)
        sl = dk.per_variant(dk.flat.slides[:, j])
        w = dk.per_variant(dk.flat.crank_rate("omega"))
        return sl[..., 0], ends.sense[:, None] * sl[..., 1] / w

    grid = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, 65)[None, :]
    s, _ = slide(grid)
    up = np.sign(s[:, -1] - s[:, 0])[:, None]
    k = np.clip(np.sum(up[:, :, None] * s[:, None, :] < (up * target)[:, :, None], axis=2), 1, grid.shape[1] - 1)
    pick = lambda a, i: np.take_along_axis(a, i, axis=1)  # noqa: E731
    a, b = pick(grid, k - 1), pick(grid, k)
    f_a, f_b = pick(s, k - 1) - target, pick(s, k) - target
    live = np.isfinite(f_a) & np.isfinite(f_b)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = a - f_a * (b - a) / (f_b - f_a)
    x = np.where((x >= a) & (x <= b), x, 0.5 * (a + b))

    def f(x):
        sx, ds = slide(x)
        return np.where(live, sx - target, 0.0), np.where(live, ds, 1.0)

    x = newton_bisection(f, a, b, f_a, x, ulps=4, closed=False)
    return np.where(live, np.mod(ends.start_phi[:, None] + ends.sense[:, None] * x, TWO_PI), np.nan)


# ---- inertia and the balancing moment -------------------------------------------------------


def centre_inertias(mech: Mechanism, dk: DesignKinematics) -> list[tuple]:
    """(LinkMass, J_S per variant (V,) kg·m²) of every link with a mass: the given inertia, or
    m·l²/K with the variant's own link length (`velplan.forces.inertia.inertia_of`) — 0 for a
    link that never turns in ``dk`` (a slider on a fixed guide), where J_S does no work."""
    V = dk.shape[0]
    out = []
    for m in mech.masses:
        w = dk.flat.omega(m.link)
        if m.inertia is not None or not np.any(w[np.isfinite(w)] != 0):
            j = np.full(V, float(m.inertia or 0.0))
        else:
            j = np.array([inertia_of(variant(mech, {k: float(a[v]) for k, a in dk.values.items()}), m)
                          for v in range(V)])
        out.append((m, j))
    return out


def _inertia_terms(mech: Mechanism, kin, inertia: list, n: int, *, crank: bool = True):
    """(Σ m·|V_S|² + J_S·ω², Σ m·a_S·V_S + J_S·ε·ω) over the elements of ``kin`` (V·n): twice
    the kinetic energy and its rate, of the crank's masses too unless ``crank`` is False."""
    two_t = np.zeros(len(kin))
    rate = np.zeros(len(kin))
    for m, j in inertia:
        if not crank and m.link == mech.crank.link:
            continue
        v, a = link_motion(kin, m.link, point(kin, m.centre))
        w, e = kin.omega(m.link), kin.epsilon(m.link)
        jn = np.repeat(j, n)
        two_t = two_t + m.mass * np.abs(v) ** 2 + jn * w * w
        rate = rate + m.mass * dot(a, v) + jn * e * w
    return two_t, rate


def _external_power(mech: Mechanism, kin, loads_e: tuple) -> np.ndarray:
    """Σ F·V + M·ω of the loads and gravity over the elements of ``kin``, W."""
    acts = load_actions(loads_e, kin) + gravity_actions(mech, kin)
    return sum(powers(kin, acts).values(), np.zeros(len(kin)))


def balancing_peak(mech: Mechanism, dk: DesignKinematics, loads: tuple, ends: Ends, inertia: list) -> np.ndarray:
    """(V,) the largest |M_b| over the angles of ``dk``, N·m, with M_b·ω1 = dT/dt − Σ P_loads
    (the power method: the inertia forces' power is −dT/dt)."""
    kin = dk.flat
    n = dk.shape[1]
    _, rate = _inertia_terms(mech, kin, inertia, n)
    with np.errstate(invalid="ignore", divide="ignore"):
        mb = (rate - _external_power(mech, kin, element_loads(loads, ends, n))) / kin.crank_rate("omega")
    mb = np.abs(dk.per_variant(mb))
    return np.max(np.where(np.isnan(mb), -np.inf, mb), axis=1)


# ---- the flywheel ---------------------------------------------------------------------------


@dataclass(frozen=True)
class _Series:
    """The total work A(θ) and the variable inertia J(θ) of V variants as piecewise Legendre
    series on their panels (`velplan.dynamics.panels`: 16 nodes a panel).

    Attributes
    ----------
    edges, work : ndarray, shape (V, P + 1)
        Panel edges (rad of travel) and A there (J).
    cA : ndarray, shape (V, P, 17)
        A − A(edge) from each panel's start.
    cM, cJ, cdJ : ndarray, shape (V, P, 16)
        M_Σ = dA/dθ (N·m), J (kg·m²) and J′ = dJ/dθ (kg·m²/rad).
    """

    edges: np.ndarray
    work: np.ndarray
    cA: np.ndarray
    cM: np.ndarray
    cJ: np.ndarray
    cdJ: np.ndarray

    @staticmethod
    def of(pns: list, M: np.ndarray, J: np.ndarray, dJ: np.ndarray) -> "_Series":
        """From the node values (V, P·16) of the total moment, J and J′ on each variant's panels."""
        V, P = len(pns), pns[0].count
        edges = np.stack([p.edges for p in pns])
        half = 0.5 * np.diff(edges, axis=1)
        coef = lambda a: pns[0].coefficients(a.reshape(V, P, -1))  # noqa: E731  (the same on every panel)
        cM = coef(M)
        per = np.sum(M.reshape(V, P, -1) * np.stack([p.weights for p in pns]), axis=2)
        work = np.concatenate([np.zeros((V, 1)), np.cumsum(per, axis=1)], axis=1)
        cA = L.legint(cM, lbnd=-1.0, axis=-1) * half[:, :, None]
        return _Series(edges, work, cA, cM, coef(J), coef(dJ))

    def at(self, theta: np.ndarray):
        """(A, M_Σ, M_Σ′, J, J′, J″), each (V, m), at travels ``theta`` (V, m) within the cycle."""
        V, m = theta.shape
        P, n = self.cM.shape[1:]
        rows = np.arange(V)[:, None]
        p = np.clip(np.sum(self.edges[:, None, :] <= theta[:, :, None], axis=2) - 1, 0, P - 1)
        lo, half = self.edges[rows, p], 0.5 * (self.edges[rows, p + 1] - self.edges[rows, p])
        B, dB = legendre_basis(((theta - lo) / half - 1.0).ravel(), n + 1, True)
        B, dB = B.reshape(V, m, n + 1), dB.reshape(V, m, n + 1)
        ev = lambda c, basis: np.einsum("vmk,vmk->vm", c[rows, p], basis[..., :c.shape[-1]])  # noqa: E731
        return (self.work[rows, p] + ev(self.cA, B), ev(self.cM, B), ev(self.cM, dB) / half,
                ev(self.cJ, B), ev(self.cdJ, B), ev(self.cdJ, dB) / half)

    def grid(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(θ, A, J), each (V, P·17 + 1): every edge and node of the panels, in order."""
        V, P, n = self.cM.shape
        x, _ = L.leggauss(n)
        Bn, _ = legendre_basis(x, n + 1)
        sign = (-1.0) ** np.arange(n)
        half = 0.5 * np.diff(self.edges, axis=1)
        theta = np.concatenate([self.edges[:, :-1, None], self.edges[:, :-1, None] + half[:, :, None] * (x + 1.0)],
                               axis=2)
        A = np.concatenate([self.work[:, :-1, None], self.work[:, :-1, None] + self.cA @ Bn.T], axis=2)
        J = np.concatenate([(self.cJ @ sign)[:, :, None], self.cJ @ Bn[:, :n].T], axis=2)
        last = lambda a, end: np.concatenate([a.reshape(V, -1), end[:, None]], axis=1)  # noqa: E731
        return last(theta, self.edges[:, -1]), last(A, self.work[:, -1]), last(J, self.cJ[:, 0] @ sign)


def _extreme(c: _Series, theta: np.ndarray, F: np.ndarray, k: np.ndarray, sgn: float) -> np.ndarray:
    """(V,) the largest (``sgn`` +1) or least (−1) F = A − k·J: its best value on the grid
    ``theta``, refined by the root of F′ = M_Σ − k·J′ in a neighbouring grid interval where F′
    changes sign (as `velplan.dynamics.steady.extremes`)."""
    V, G = theta.shape
    rows = np.arange(V)
    i = np.argmax(sgn * F, axis=1)
    best = F[rows, i]
    kk = k[:, None]

    def g(x):
        _, M, dM, _, dJ, d2J = c.at(x[:, None])
        return (M - kk * dJ)[:, 0], (dM - kk * d2J)[:, 0]

    for a in (i - 1, i):
        ok = (a >= 0) & (a + 1 < G)
        lo, hi = theta[rows, np.clip(a, 0, G - 1)], theta[rows, np.clip(a + 1, 0, G - 1)]
        nudge = 1e-9 * (hi - lo)
        g_lo, g_hi = g(lo + nudge)[0], g(hi - nudge)[0]
        keep = ok & (sgn * g_lo > 0) & (sgn * g_hi < 0)

        def f(x):
            gx, dg = g(x)
            return np.where(keep, gx, 0.0), np.where(keep, dg, 1.0)

        x = newton_bisection(f, lo, hi, g_lo, 0.5 * (lo + hi))
        A, _, _, J, _, _ = c.at(x[:, None])
        Fx = (A - kk * J)[:, 0]
        best = np.where(keep & (sgn * Fx > sgn * best), Fx, best)
    return best


def flywheel_inertia(mech: Mechanism, values: dict, loads: tuple, ends: Ends, inertia: list, delta: float,
                     engine: str) -> np.ndarray:
    """(V,) J_I for the coefficient of speed fluctuation ``delta`` at the crank's speed as the
    mean ω_m (kg·m², reduced to the crank; NaN where a variant does not close): the
    energy–mass envelope J_I = (max(A − k₊J) − min(A − k₋J))/(k₊ − k₋), k± = ½ω_m²(1 ± δ/2)²,
    as `velplan.dynamics.dynamics_analysis` sizes it on 64 panels."""
    if not 0 < delta < 1:
        raise VelplanError(f"--delta must be between 0 and 1 (exclusive), not {delta:g}")
    if parse_dynamics(mech).cycle_turns != 1:
        raise VelplanError(f"sweep: J_I of {mech.name!r} needs a cycle of one turn; its [dynamics] cycle is 4π")
    V = ends.sense.shape[0]
    travel = np.mod(ends.sense[:, None] * (breakpoints(mech, values, loads, ends, engine) - ends.reference[:, None]),
                    TWO_PI)
    pns = [panels_over(TWO_PI, t[np.isfinite(t)], PANELS) for t in travel]
    if len({p.count for p in pns}) > 1:
        raise VelplanError(f"sweep: J_I of {mech.name!r}: more pieces between the loads' breakpoints "
                           f"than {PANELS} panels")
    nodes = np.stack([p.nodes.ravel() for p in pns])  # (V, P·16) travel, rad
    # unit speed in the sense of rotation: V = s·r′, a = r″, so Σ m·V·a = ½ dJ/dθ
    unit = replace(mech, crank=replace(mech.crank, epsilon=0.0)) if mech.crank.epsilon else mech
    at_unit_speed = {**{k: a for k, a in values.items() if k not in SPEED_KEYS}, "crank.omega": ends.sense}
    dk = solve_design(unit, at_unit_speed, ends.reference[:, None] + ends.sense[:, None] * nodes, engine=engine)
    n = nodes.shape[1]
    J, rate = (dk.per_variant(x) for x in _inertia_terms(mech, dk.flat, inertia, n, crank=False))
    M = dk.per_variant(_external_power(mech, dk.flat, element_loads(loads, ends, n)))
    weights = np.stack([p.weights.ravel() for p in pns])
    driving = -np.sum(M * weights, axis=1) / TWO_PI  # zero work over the cycle
    c = _Series.of(pns, M + driving[:, None], J, 2.0 * rate)
    theta, A, Jg = c.grid()
    wm = np.abs(np.broadcast_to(_speed(mech, values), (V,)))
    kp, km = 0.5 * wm**2 * (1 + delta / 2) ** 2, 0.5 * wm**2 * (1 - delta / 2) ** 2
    with np.errstate(invalid="ignore", divide="ignore"):
        top = _extreme(c, theta, A - kp[:, None] * Jg, kp, 1.0)
        bottom = _extreme(c, theta, A - km[:, None] * Jg, km, -1.0)
        out = (top - bottom) / (kp - km)
    return np.where(dk.valid.all(axis=1) & (wm > 0), out, np.nan)
