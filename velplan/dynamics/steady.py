"""Steady state with a constant driving moment: the driving moment from zero cycle work, the
works, ω(θ) by the energy equation, ε from Lagrange's equation, t(θ), δ and the extremes.

Travel θ, speed w = |ω| and moments positive when they drive (see `velplan.dynamics.reduction`):
energy ½·J(θ)·w² = T0 + A(θ), A = ∫₀^θ M dθ; Lagrange J·dw/dt + ½·J′·w² = M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable, Sequence

import numpy as np

from velplan.analysis.roots import newton_bisection
from velplan.dynamics.reduction import Profile
from velplan.errors import VelplanError


@dataclass(frozen=True, eq=False)
class EnergyCurve:
    """Total work A(θ), its moment M(θ) = dA/dθ, the variable inertia J(θ) and J′(θ), over a
    cycle; the candidates ``grid`` (sorted travels, rad, including 0 and the cycle) bracket
    every extreme of A − k·J between two neighbours.

    Each callable takes an array of travels and returns an array; ``local`` returns the six
    arrays (A, M, M′, J, J′, J″) at once. ``errors`` are the estimated errors of a value of A
    (``"A"``, J) and of J (``"J"``, kg·m²) (see `velplan.dynamics.reduction.Profile.errors`).
    """

    grid: np.ndarray
    A: Callable
    M: Callable
    J: Callable
    dJ: Callable
    local: Callable | None = None
    errors: dict = field(default_factory=lambda: {"A": 0.0, "J": 0.0})

    @cached_property
    def on_grid(self) -> tuple[np.ndarray, np.ndarray]:
        """(A, J) on the grid."""
        return self.A(self.grid), self.J(self.grid)

    def evaluate(self, t: np.ndarray) -> tuple:
        """(A, M, M′, J, J′, J″) at travels ``t``; without ``local``, M′ and J″ are NaN (the
        extremes are then found by bisection)."""
        if self.local is not None:
            return self.local(t)
        nan = np.full(np.shape(t), np.nan)
        return self.A(t), self.M(t), nan, self.J(t), self.dJ(t), nan


def curve_of(prof: Profile, driving: float) -> EnergyCurve:
    """The `EnergyCurve` of a profile plus a constant driving moment ``driving`` (N·m)."""
    grid = np.unique(np.concatenate((prof.panels.edges, prof.panels.nodes.ravel())))

    def A(t):
        return driving * np.asarray(t) + prof.works(t).sum(axis=0)

    def M(t):
        return driving + prof.values(t)[2:].sum(axis=0)

    def local(t):
        W, v, d = prof.energy(t)
        return driving * np.asarray(t) + W, driving + v[2], d[2], v[0], v[1], d[1]

    e = prof.errors
    # A = driving·θ + works, driving = −(cycle work)/cycle: each term errs by at most e["work"]
    return EnergyCurve(grid, A, M, lambda t: prof.values(t)[0], lambda t: prof.values(t)[1], local,
                       {"A": 2.0 * e["work"], "J": e["J"]})


@dataclass(frozen=True)
class Target:
    """An extreme to find: of F(θ) = (e0 + A − k·J)/(e1 + e2·J) (with e2 = 0 or k = 0), whose
    derivative has the sign of g = M·(e1 + e2·J) − J′·(k·e1 + e2·(e0 + A)).

    ``values`` are F on the curve's grid; ``kind`` "max" or "min". A − k·J + e0 is (e1, e2) =
    (1, 0); (T0 + A)/(J_I + J) is (e0, k, e1, e2) = (T0, 0, J_I, 1).
    """

    values: np.ndarray
    kind: str
    e0: float = 0.0
    k: float = 0.0
    e1: float = 1.0
    e2: float = 0.0


def _g(t: Target | np.ndarray, A, M, dM, J, dJ, d2J):
    """(g, g′) of `Target` parameters (arrays (4, m): e0, k, e1, e2) at the six local arrays."""
    e0, k, e1, e2 = t
    a = e1 + e2 * J
    b = k * e1 + e2 * (e0 + A)
    return M * a - dJ * b, dM * a - d2J * b  # b′ = e2·M cancels M·a′ = M·e2·J′


def extremes(c: EnergyCurve, targets: list[Target], guess: Sequence[float] | None = None) -> list[tuple[float, float]]:
    """(θ*, F(θ*)) of each target's largest (or least) value: its best grid value, refined by
    the root of F′ in a neighbouring grid interval where F′ changes sign (safeguarded Newton
    on the panel's own series, every candidate at once); at a kink of F (a jump of M), the
    kink itself. ``guess`` (a travel per target, rad) starts Newton's steps there when it lies
    in the bracket (a previous root)."""
    grid = c.grid
    best, lo, hi, owner = [], [], [], []
    for n, t in enumerate(targets):
        sgn = 1.0 if t.kind == "max" else -1.0
        i = int(np.argmax(sgn * t.values))
        best.append([float(grid[i]), float(t.values[i])])
        for a, b in ((i - 1, i), (i, i + 1)):
            if 0 <= a and b < grid.size:
                lo.append(grid[a]), hi.append(grid[b]), owner.append(n)
    if not owner:
        return [tuple(b) for b in best]
    lo, hi, owner = np.array(lo), np.array(hi), np.array(owner)
    par = np.array([[t.e0, t.k, t.e1, t.e2] for t in targets]).T[:, owner]
    sgn = np.array([1.0 if t.kind == "max" else -1.0 for t in targets])[owner]
    nudge = 1e-9 * (hi - lo)
    ends = c.evaluate(np.concatenate((lo + nudge, hi - nudge)))
    g_ends, _ = _g(np.concatenate((par, par), axis=1), *ends)
    m = owner.size
    keep = (sgn * g_ends[:m] > 0) & (sgn * g_ends[m:] < 0)
    if np.any(keep):
        start = 0.5 * (lo[keep] + hi[keep])
        if guess is not None:
            g = np.asarray(guess, dtype=float)[owner[keep]]
            start = np.where((g > lo[keep]) & (g < hi[keep]), g, start)
        # the roots of g to 8 ulp, a Newton step onto a bracket's end accepted
        roots = newton_bisection(lambda x: _g(par[:, keep], *c.evaluate(x)), lo[keep], hi[keep],
                                 g_ends[:m][keep], start, ulps=8, closed=True)
        A, _, _, J, _, _ = c.evaluate(roots)
        e0, k, e1, e2 = par[:, keep]
        F = (e0 + A - k * J) / (e1 + e2 * J)
        for n, r, v in zip(owner[keep], roots, F):
            s = 1.0 if targets[n].kind == "max" else -1.0
            if s * v > s * best[n][1]:
                best[n] = [float(r), float(v)]
    return [tuple(b) for b in best]


@dataclass(frozen=True, eq=False)
class SteadyState:
    """The steady motion over one cycle.

    Attributes
    ----------
    omega_mean : float
        ω_m = (w_max + w_min)/2, rad/s (magnitude).
    driving : float
        Constant driving moment, N·m (positive when it drives).
    inertia : float
        The constant inertia J_I the motion uses (reduced to the crank), kg·m².
    T0 : float
        Kinetic energy at position 1, J.
    omega_max, omega_min : float
        Extreme speeds w, rad/s.
    theta_max, theta_min : float
        Travels from position 1 where they occur, rad.
    delta : float
        (w_max − w_min)/ω_m.
    period : float
        Time of one cycle, s.
    errors : dict
        Estimated errors: ``"omega"`` of w_max, w_min and ω_m (rad/s), ``"delta"``, and
        ``"period"`` (s), from the profile's (`EnergyCurve.errors`) and the quadrature's.
    """

    curve: EnergyCurve = field(repr=False)
    omega_mean: float
    driving: float
    inertia: float
    T0: float
    omega_max: float
    omega_min: float
    theta_max: float
    theta_min: float
    delta: float
    cycle: float
    _time: tuple = field(repr=False, default=())
    errors: dict = field(default_factory=dict)

    def omega(self, theta) -> np.ndarray:
        """w(θ) = √(2(T0 + A)/(J_I + J)), rad/s."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        c = self.curve
        w = np.sqrt(2.0 * (self.T0 + c.A(th)) / (self.inertia + c.J(th)))
        return w if np.ndim(theta) else float(w[0])

    def epsilon(self, theta) -> np.ndarray:
        """dw/dt = (M − ½·J′·w²)/(J_I + J), rad/s² (Lagrange)."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        c = self.curve
        w = self.omega(th)
        e = (c.M(th) - 0.5 * c.dJ(th) * w * w) / (self.inertia + c.J(th))
        return e if np.ndim(theta) else float(e[0])

    def time(self, theta) -> np.ndarray:
        """t(θ) = ∫₀^θ dθ/w from position 1, s (0 ≤ θ ≤ cycle)."""
        panels, coef, edges, icoef = self._time
        r = panels.integrate_to(coef, edges, np.atleast_1d(np.asarray(theta, dtype=float)), icoef=icoef)[0]
        return r if np.ndim(theta) else float(r[0])

    @property
    def period(self) -> float:
        return float(self._time[2][0, -1])


def _speed_extremes(c: EnergyCurve, inertia: float, T0: float, guess=None):
    """((θ, F), (θ, F)) of the largest and least F = w²/2 = (T0 + A)/(J_I + J)."""
    A, J = c.on_grid
    vals = (T0 + A) / (inertia + J)
    return extremes(c, [Target(vals, "max", T0, 0.0, inertia, 1.0), Target(vals, "min", T0, 0.0, inertia, 1.0)],
                    guess)


def steady_state(c: EnergyCurve, omega_mean: float, inertia: float, driving: float, cycle: float,
                 prof: Profile | None = None) -> SteadyState:
    """The steady motion with the constant inertia ``inertia`` (kg·m²) whose mean speed
    (w_max + w_min)/2 is ``omega_mean`` (rad/s, > 0): T0 by Brent's method, the extremes
    refined by a root of d(w²)/dθ ∝ M − J′·w²/2 (or at a kink of A)."""
    if not omega_mean > 0:
        raise VelplanError(f"dynamics: the mean crank speed must be > 0 rad/s, not {omega_mean:g}")
    A, J = c.on_grid
    Jt = inertia + J
    stop = (f"dynamics: the crank would stop: with the constant inertia {inertia:.6g} kg·m² the "
            f"speed cannot average {omega_mean:.6g} rad/s over the cycle; add inertia (a flywheel: [dynamics] "
            "delta or --delta sizes one)")
    if not Jt.max() > 0:
        raise VelplanError("dynamics: the reduced inertia is 0 over the whole cycle; give masses or constant inertias")
    if Jt.min() <= 1e-12 * Jt.max():  # 0 at a dead centre: no finite speed passes it
        raise VelplanError(stop)
    lo = -float(A.min())

    def mean_speed(T0, pA=None, pJ=None):
        w2 = 2.0 * (T0 + A) / Jt
        w = np.sqrt(np.maximum(w2, 0.0))
        wmax, wmin = w.max(), w.min()
        if pA is not None:
            wp = np.sqrt(np.maximum(2.0 * (T0 + pA) / (inertia + pJ), 0.0))
            wmax, wmin = max(wmax, wp.max()), min(wmin, wp.min())
        return 0.5 * (wmax + wmin)

    if mean_speed(lo) >= omega_mean:
        raise VelplanError(stop)
    from scipy.optimize import brentq  # ≈ 0.3 s to import: not for a motion refused above

    hi = lo + 0.5 * float(Jt.max()) * omega_mean**2 + 1.0
    while mean_speed(hi) < omega_mean:
        hi = lo + 2.0 * (hi - lo)
    T0 = brentq(lambda T: mean_speed(T) - omega_mean, lo, hi, xtol=1e-12 * hi, rtol=1e-12)
    pts = None
    for _ in range(8):
        (tmax, fmax), (tmin, fmin) = _speed_extremes(c, inertia, T0, pts)
        new = [tmax, tmin]
        # the mean speed is that of the two extremes (no grid value lies beyond them)
        (a0, a1), (j0, j1) = c.A(np.array(new)).tolist(), (inertia + c.J(np.array(new))).tolist()

        def two(T):
            w0, w1 = math.sqrt(max(2.0 * (T + a0) / j0, 0.0)), math.sqrt(max(2.0 * (T + a1) / j1, 0.0))
            return 0.5 * (w0 + w1) - omega_mean

        T0_new = brentq(two, -min(a0, a1), hi, xtol=1e-15 * hi, rtol=1e-15)
        done = abs(T0_new - T0) <= 1e-15 * abs(T0_new) and new == pts
        T0, pts = T0_new, new
        if done:
            break
    (tmax, fmax), (tmin, fmin) = _speed_extremes(c, inertia, T0, pts)
    wmax, wmin = float(np.sqrt(2 * fmax)), float(np.sqrt(2 * fmin))
    wm = 0.5 * (wmax + wmin)
    # error of w: a perturbation δA of A and δJ of J moves w by w·(δA/(2E) − δJ/(2J)), E = T0 + A,
    # and T0 by as much again to keep the mean speed
    e_w = wmax * (c.errors["A"] / float((T0 + A).min()) + c.errors["J"] / float(Jt.min()))
    errors = {"omega": e_w, "delta": 2.0 * e_w / wm * (1.0 + (wmax - wmin) / wm)}
    st = SteadyState(c, wm, driving, inertia, T0, wmax, wmin, tmax, tmin, (wmax - wmin) / wm, cycle,
                     errors=errors)
    if prof is not None:
        pn = prof.panels
        inv = 1.0 / st.omega(pn.nodes.ravel()).reshape(pn.nodes.shape)
        coef = pn.coefficients(inv[None])
        edges = pn.integral(inv[None])
        object.__setattr__(st, "_time", (pn, coef, edges, pn.antiderivative(coef)))
        period = float(edges[0, -1])
        errors["period"] = period * e_w / wmin + float(np.sum(2.0 * pn.half * pn.tail(coef)[0])) \
            + 64 * np.finfo(float).eps * period
    return st
