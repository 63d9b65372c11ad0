"""Steady state with a constant driving moment: the driving moment from zero cycle work, the
works, ω(θ) by the energy equation, ε from Lagrange's equation, t(θ), δ and the extremes.

Travel θ, speed w = |ω| and moments positive when they drive (see `velplan.dynamics.reduction`):
energy ½·J(θ)·w² = T0 + A(θ), A = ∫₀^θ M dθ; Lagrange J·dw/dt + ½·J′·w² = M.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

import numpy as np

from velplan.dynamics.reduction import Profile
from velplan.errors import VelplanError


@dataclass(frozen=True, eq=False)
class EnergyCurve:
    """Total work A(θ), its moment M(θ) = dA/dθ, the variable inertia J(θ) and J′(θ), over a
    cycle; the candidates ``grid`` (sorted travels, rad, including 0 and the cycle) bracket
    every extreme of A − k·J between two neighbours.

    Each callable takes an array of travels and returns an array.
    """

    grid: np.ndarray
    A: Callable
    M: Callable
    J: Callable
    dJ: Callable

    @cached_property
    def on_grid(self) -> tuple[np.ndarray, np.ndarray]:
        """(A, J) on the grid."""
        return self.A(self.grid), self.J(self.grid)


def curve_of(prof: Profile, driving: float) -> EnergyCurve:
    """The `EnergyCurve` of a profile plus a constant driving moment ``driving`` (N·m)."""
    grid = np.unique(np.concatenate((prof.panels.edges, prof.panels.nodes.ravel())))

    def A(t):
        return driving * np.asarray(t) + prof.works(t).sum(axis=0)

    def M(t):
        return driving + prof.values(t)[2:].sum(axis=0)

    return EnergyCurve(grid, A, M, lambda t: prof.values(t)[0], lambda t: prof.values(t)[1])


def extreme(grid: np.ndarray, values: np.ndarray, f: Callable, df: Callable, kind: str = "max") -> tuple[float, float]:
    """(θ*, f(θ*)) of the largest (``kind="max"``) or least value of f, refined from its best
    grid value by a root of f′ between the neighbours (Brent's method); at a jump of f′ (a
    kink of f) the root is the kink itself."""
    from scipy.optimize import brentq

    sign = 1.0 if kind == "max" else -1.0
    i = int(np.argmax(sign * values))
    best_t, best_v = float(grid[i]), float(values[i])
    for lo, hi in ((i - 1, i), (i, i + 1)):
        if lo < 0 or hi >= grid.size:
            continue
        a, b = float(grid[lo]), float(grid[hi])
        ga, gb = float(df(np.array([a]))[0]), float(df(np.array([b]))[0])
        if sign * ga > 0 > sign * gb:
            r = brentq(lambda t: float(df(np.array([t]))[0]), a, b, xtol=1e-15, rtol=1e-15, maxiter=200)
            v = float(f(np.array([r]))[0])
            if sign * v > sign * best_v:
                best_t, best_v = r, v
    return best_t, best_v


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
        panels, coef, edges = self._time
        r = panels.integrate_to(coef, edges, np.atleast_1d(np.asarray(theta, dtype=float)))[0]
        return r if np.ndim(theta) else float(r[0])

    @property
    def period(self) -> float:
        return float(self._time[2][0, -1])


def _speed_extremes(c: EnergyCurve, inertia: float, T0: float, extra=()):
    def f(t):
        return (T0 + c.A(t)) / (inertia + c.J(t))

    def df(t):  # d/dθ of (T0 + A)/J ∝ M − J′·(T0 + A)/J
        return c.M(t) - c.dJ(t) * f(t)

    grid = c.grid if not extra else np.unique(np.concatenate((c.grid, extra)))
    A, J = (c.on_grid if not extra else (c.A(grid), c.J(grid)))
    vals = (T0 + A) / (inertia + J)
    return extreme(grid, vals, f, df, "max"), extreme(grid, vals, f, df, "min")


def steady_state(c: EnergyCurve, omega_mean: float, inertia: float, driving: float, cycle: float,
                 prof: Profile | None = None) -> SteadyState:
    """The steady motion with the constant inertia ``inertia`` (kg·m²) whose mean speed
    (w_max + w_min)/2 is ``omega_mean`` (rad/s, > 0): T0 by Brent's method, the extremes
    refined by a root of d(w²)/dθ ∝ M − J′·w²/2 (or at a kink of A)."""
    from scipy.optimize import brentq

    if not omega_mean > 0:
        raise VelplanError(f"dynamics: the mean crank speed must be > 0 rad/s, not {omega_mean:g}")
    A, J = c.on_grid
    Jt = inertia + J
    if np.any(Jt <= 0):
        raise VelplanError("dynamics: the reduced inertia is 0 somewhere; give masses or constant inertias")
    lo = -float(A.min())

    def mean_speed(T0, pts=None):
        if pts is None:
            w2 = 2.0 * (T0 + A) / Jt
        else:
            w2 = np.concatenate((2.0 * (T0 + A) / Jt, 2.0 * (T0 + c.A(pts)) / (inertia + c.J(pts))))
        w = np.sqrt(np.maximum(w2, 0.0))
        return 0.5 * (w.max() + w.min())

    if mean_speed(lo) >= omega_mean:
        raise VelplanError(
            f"dynamics: the crank would stop: with the constant inertia {inertia:.6g} kg·m² the "
            f"speed cannot average {omega_mean:.6g} rad/s over the cycle; add inertia (a flywheel: [dynamics] delta or --delta sizes one)")
    hi = lo + 0.5 * float(Jt.max()) * omega_mean**2 + 1.0
    while mean_speed(hi) < omega_mean:
        hi = lo + 2.0 * (hi - lo)
    T0 = brentq(lambda T: mean_speed(T) - omega_mean, lo, hi, xtol=1e-14 * hi, rtol=1e-15)
    pts = np.empty(0)
    for _ in range(3):
        (tmax, fmax), (tmin, fmin) = _speed_extremes(c, inertia, T0)
        new = np.array([tmax, tmin])
        T0_new = brentq(lambda T: mean_speed(T, new) - omega_mean, lo, hi, xtol=1e-15 * hi, rtol=1e-15)
        done = abs(T0_new - T0) <= 1e-15 * abs(T0_new) and np.array_equal(new, pts)
        T0, pts = T0_new, new
        if done:
            break
    (tmax, fmax), (tmin, fmin) = _speed_extremes(c, inertia, T0)
    wmax, wmin = float(np.sqrt(2 * fmax)), float(np.sqrt(2 * fmin))
    wm = 0.5 * (wmax + wmin)
    st = SteadyState(c, wm, driving, inertia, T0, wmax, wmin, tmax, tmin, (wmax - wmin) / wm, cycle)
    if prof is not None:
        pn = prof.panels
        inv = 1.0 / st.omega(pn.nodes.ravel()).reshape(pn.nodes.shape)
        object.__setattr__(st, "_time", (pn, pn.coefficients(inv[None]), pn.integral(inv[None])))
    return st
