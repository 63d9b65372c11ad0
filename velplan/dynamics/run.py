"""Unsteady runs and the periodic regime with a motor characteristic.

Run (in time): dθ/dt = w, dw/dt = (M(θ, w) − ½·J′(θ)·w²)/J(θ), from position 1, integrated by
DOP853 piece by piece between the loads' jumps (restarted at each one), with events: the
travel reached, the time reached, the crank stopping (w falls to 0: a `VelplanError`).

Periodic regime (in travel): u = w², du/dθ = 2(M(θ, √u) − ½·J′·u)/J, dt/dθ = 1/√u over a
cycle; the speed at position 1 that returns after a cycle is found by the secant method
(shooting).

J, J′ and M(θ) come from the `Profile`: piecewise Legendre series through exact solver values,
equal to the solver to ~1e-14 relative (tests check it), so no step calls the solver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from numpy.polynomial import legendre as L

from velplan.dynamics.reduction import Profile
from velplan.errors import VelplanError

RTOL = 1e-11


@dataclass(frozen=True, eq=False)
class Piece:
    """One integrated piece: independent variable from x0 to x1, dense solution ``sol``."""

    x0: float
    x1: float
    sol: object


def _fields(prof: Profile) -> np.ndarray:
    """(3, P, n) coefficients of J, J′ and the total load moment."""
    c = prof.coef
    return np.stack((c[0], c[1], c[2:].sum(axis=0))) if c.shape[0] > 2 else \
        np.stack((c[0], c[1], np.zeros_like(c[0])))


def _segments(prof: Profile):
    """[(θa, θb, first panel, last panel)] between the breaks of one cycle."""
    pn = prof.panels
    out = []
    for a, b in zip(pn.breaks[:-1], pn.breaks[1:]):
        lo = int(np.searchsorted(pn.edges, a - 1e-12 * pn.cycle))
        hi = int(np.searchsorted(pn.edges, b - 1e-12 * pn.cycle)) - 1
        out.append((float(a), float(b), lo, max(lo, hi)))
    return out


def _local(prof: Profile, coef: np.ndarray, lo: int, hi: int, base: float):
    pn = prof.panels
    edges, half = pn.edges, pn.half

    def values(theta: float):
        t = theta - base
        p = min(max(int(np.searchsorted(edges, t, side="right")) - 1, lo), hi)
        x = (t - edges[p]) / half[p] - 1.0
        return L.legval(x, coef[:, p, :].T)

    return values


def _deg(x: float) -> str:
    return f"{math.degrees(x):.4g}°"


@dataclass(frozen=True, eq=False)
class Run:
    """An unsteady run from position 1.

    Attributes
    ----------
    time : float
        Duration, s.
    travel : float
        Crank travel reached, rad.
    omega_start, omega_end, omega_min, omega_max : float
        Crank speeds w = |ω|, rad/s.
    theta_min : float
        Travel where the speed is least, rad.
    """

    time: float
    travel: float
    omega_start: float
    omega_end: float
    omega_min: float
    omega_max: float
    theta_min: float
    pieces: tuple = field(repr=False)
    rhs: Callable = field(repr=False)

    def at_travel(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t s, w rad/s, dw/dt rad/s²) at travels ``theta`` (0 ≤ θ ≤ travel)."""
        from scipy.optimize import brentq

        out = []
        for th in np.atleast_1d(np.asarray(theta, dtype=float)):
            for pc in self.pieces:
                y0, y1 = pc.sol(pc.x0), pc.sol(pc.x1)
                if y0[0] - 1e-12 <= th <= y1[0] + 1e-12:
                    break
            if th <= y0[0]:
                t = pc.x0
            elif th >= y1[0]:
                t = pc.x1
            else:
                t = brentq(lambda s: pc.sol(s)[0] - th, pc.x0, pc.x1, xtol=1e-15, rtol=1e-15)
            y = pc.sol(t)
            out.append((t, y[1], self.rhs(y[0], y[1])))
        a = np.array(out).reshape(-1, 3)
        return a[:, 0], a[:, 1], a[:, 2]


def simulate(prof: Profile, inertia: float, moment: Callable, w0: float, *, travel: float | None = None,
             time: float | None = None, time_limit: float = 60.0, rtol: float = RTOL) -> Run:
    """Integrate a run from position 1 at speed ``w0`` (rad/s, ≥ 0) with the constant inertia
    ``inertia`` (kg·m²) and the driving moment ``moment(w)`` (N·m on the crank), until the
    travel ``travel`` (rad) or the time ``time`` (s).

    Raises
    ------
    VelplanError
        The crank stops (naming the travel, the crank angle and the time), or the travel is not
        reached within ``time_limit`` s.
    """
    from scipy.integrate import solve_ivp

    coef = _fields(prof)
    segs = _segments(prof)
    cyc = prof.cycle
    t_end = time if time is not None else time_limit
    t, th, w = 0.0, 0.0, float(w0)
    pieces, w_min, th_min, w_max = [], w, 0.0, w
    rhs_any = None
    k, base = 0, 0.0
    while True:
        a, b, lo, hi = segs[k]
        values = _local(prof, coef, lo, hi, base)

        def f(_t, y, values=values):
            j, dj, m = values(y[0])
            return [y[1], (m + float(moment(y[1])) - 0.5 * dj * y[1] * y[1]) / (inertia + j)]

        if rhs_any is None:
            rhs_any = f
        target = base + b if travel is None else min(base + b, travel)
        reach = lambda _t, y, target=target: y[0] - target  # noqa: E731
        reach.terminal, reach.direction = True, 1
        stop = lambda _t, y: y[1]  # noqa: E731
        stop.terminal, stop.direction = True, -1
        turn = lambda _t, y, f=f: f(_t, y)[1]  # noqa: E731
        if t >= t_end:
            break
        sol = solve_ivp(f, (t, t_end), [th, w], method="DOP853", rtol=rtol, atol=[1e-13 * cyc, 1e-12 * max(w0, 1.0)],
                        events=[reach, stop, turn], dense_output=True)
        if sol.status == -1:
            raise VelplanError(f"dynamics run: the integration failed at t = {t:.6g} s: {sol.message}")
        ts = sol.t[-1]
        pieces.append(Piece(t, ts, sol.sol))
        for yy in [sol.y[:, -1]] + list(sol.y_events[2]):
            if yy[1] < w_min:
                w_min, th_min = float(yy[1]), float(yy[0])
            w_max = max(w_max, float(yy[1]))
        if sol.t_events[1].size:
            ts, ys = float(sol.t_events[1][0]), sol.y_events[1][0]
            phi_t = float(ys[0])
            raise VelplanError(f"dynamics run: the crank stops after a travel of {_deg(phi_t)} from position 1 "
                               f"at t = {ts:.6g} s; the driving moment cannot overcome the load")
        if sol.t_events[0].size:
            t, (th, w) = float(sol.t_events[0][0]), sol.y_events[0][0]
            th = target
            if travel is not None and target >= travel:
                break
            k += 1
            if k == len(segs):
                k, base = 0, base + cyc
            continue
        t, th, w = float(sol.t[-1]), float(sol.y[0, -1]), float(sol.y[1, -1])
        if time is not None:
            break
        raise VelplanError(f"dynamics run: the crank turned only {_deg(th)} of travel_deg = "
                           f"{_deg(travel)} within time_limit = {time_limit:g} s")
    w_min = min(w_min, w)
    return Run(t, th, float(w0), float(w), w_min, max(w_max, w), th_min, tuple(pieces),
               lambda th_, w_: (lambda r: r[1])(_rhs_at(prof, coef, inertia, moment, th_, w_)))


def _rhs_at(prof, coef, inertia, moment, th, w):
    v = prof.panels.evaluate(coef, np.array([th % prof.cycle]))[:, 0]
    return [w, (v[2] + float(moment(w)) - 0.5 * v[1] * w * w) / (inertia + v[0])]


@dataclass(frozen=True, eq=False)
class Periodic:
    """The periodic regime with a speed-dependent driving moment.

    Attributes
    ----------
    omega_start : float
        w at position 1 (and after a cycle), rad/s.
    omega_max, omega_min, omega_mean : float
        rad/s; ω_m = (max + min)/2.
    theta_max, theta_min : float
        Their travels, rad.
    delta : float
    period : float
        Time of a cycle, s.
    residual : float
        |w(cycle) − w(0)|, rad/s.
    """

    omega_start: float
    omega_max: float
    omega_min: float
    omega_mean: float
    theta_max: float
    theta_min: float
    delta: float
    period: float
    residual: float
    pieces: tuple = field(repr=False)
    rhs: Callable = field(repr=False)
    moment: Callable = field(repr=False)

    def at_travel(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t s, w rad/s, dw/dt rad/s²) at travels ``theta`` within the cycle."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        out = np.empty((th.size, 3))
        for i, x in enumerate(th):
            pc = next((p for p in self.pieces if p.x0 - 1e-12 <= x <= p.x1 + 1e-12), self.pieces[-1])
            u, t = pc.sol(min(max(x, pc.x0), pc.x1))
            w = math.sqrt(max(u, 0.0))
            out[i] = (t, w, self.rhs(x, w))
        return out[:, 0], out[:, 1], out[:, 2]


def _cycle(prof, coef, segs, inertia, moment, w0, rtol, dense):
    from scipy.integrate import solve_ivp

    y = [w0 * w0, 0.0]
    pieces, ext = [], []
    for a, b, lo, hi in segs:
        values = _local(prof, coef, lo, hi, 0.0)

        def f(x, yy, values=values):
            j, dj, m = values(x)
            u = max(yy[0], 0.0)
            w = math.sqrt(u)
            return [2.0 * (m + float(moment(w)) - 0.5 * dj * u) / (inertia + j), 1.0 / w if w > 0 else math.inf]

        stop = lambda x, yy: yy[0]  # noqa: E731
        stop.terminal, stop.direction = True, -1
        turn = lambda x, yy, f=f: f(x, yy)[0]  # noqa: E731
        sol = solve_ivp(f, (a, b), y, method="DOP853", rtol=rtol, atol=[1e-14 * w0 * w0, 1e-14],
                        events=[stop, turn] if dense else [stop], dense_output=dense)
        if sol.t_events[0].size:
            raise VelplanError(f"dynamics: the crank stops after a travel of {_deg(float(sol.t_events[0][0]))} "
                               "from position 1 in the periodic regime; the motor is too weak for the load")
        y = list(sol.y[:, -1])
        if dense:
            pieces.append(Piece(a, b, sol.sol))
            ext += [(a, sol.y[0, 0]), (b, sol.y[0, -1])] + [(e, ye[0]) for e, ye in zip(sol.t_events[1], sol.y_events[1])]
    return math.sqrt(max(y[0], 0.0)), y[1], pieces, ext


def periodic(prof: Profile, inertia: float, moment: Callable, w_guess: float, *, rtol: float = RTOL,
             tol: float = 1e-10) -> Periodic:
    """The periodic regime with the driving moment ``moment(w)`` (N·m on the crank): the
    speed at position 1 that returns after a cycle, by the secant method from ``w_guess``."""
    coef = _fields(prof)
    segs = _segments(prof)
    F = lambda w: _cycle(prof, coef, segs, inertia, moment, w, rtol, False)[0] - w  # noqa: E731
    x0, x1 = w_guess, w_guess * 1.01
    f0, f1 = F(x0), F(x1)
    for _ in range(60):
        if f1 == f0:
            break
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if not x2 > 0:
            x2 = 0.5 * x1
        x0, f0, x1 = x1, f1, x2
        f1 = F(x1)
        if abs(f1) <= tol * x1:
            break
    else:
        raise VelplanError(f"dynamics: no periodic regime found near {w_guess:.6g} rad/s (residual {f1:.3g} rad/s)")
    w_end, period, pieces, ext = _cycle(prof, coef, segs, inertia, moment, x1, rtol, True)
    ths = np.array([e[0] for e in ext])
    ws = np.sqrt(np.maximum([e[1] for e in ext], 0.0))
    imax, imin = int(np.argmax(ws)), int(np.argmin(ws))
    wmax, wmin = float(ws[imax]), float(ws[imin])
    wm = 0.5 * (wmax + wmin)
    rhs = lambda th, w: _rhs_at(prof, coef, inertia, moment, th, w)[1]  # noqa: E731
    return Periodic(x1, wmax, wmin, wm, float(ths[imax]), float(ths[imin]), (wmax - wmin) / wm, period,
                    abs(w_end - x1), tuple(pieces), rhs, moment)
