"""Unsteady runs and the periodic regime with a motor characteristic.

Run (in time): dθ/dt = w, dw/dt = (M(θ, w) − ½·J′(θ)·w²)/J(θ), from position 1, integrated by
DOP853 piece by piece between the loads' breakpoints (restarted at each jump or kink), with events: the
travel reached, the time reached, the crank stopping (w falls to 0: a `VelplanError`).

Periodic regime (in travel): u = w², du/dθ = 2(M(θ, √u) − ½·J′·u)/J, dt/dθ = 1/√u over a
cycle; the speed at position 1 that returns after a cycle is found by the secant method
(shooting).

J, J′ and M(θ) come from the `Profile`: piecewise Legendre series through exact solver values,
equal to the solver to ~1e-14 relative (tests check it), so no step calls the solver; the
right-hand side evaluates them in plain floats (`_Series`). Each result carries ``errors``:
10·rtol of the time and speeds plus what the profile's estimated errors can move them
(benchmarks/results/dynamics.md: the true error stays below this at every rtol tried).
"""


from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from operator import mul
from typing import Callable

import numpy as np

from velplan.dynamics.reduction import Profile
from velplan.errors import VelplanError

RTOL = 1e-11
"""Relative tolerance of the ODE (benchmarks/results/dynamics.md: ~5e-12 relative on a run's
time, at ~1.3× the cost of 1e-9)."""


@dataclass(frozen=True, eq=False)
class Piece:
    """One integrated piece: independent variable from x0 to x1, dense solution ``sol``; for a
    run in time, the travels at its ends ``th0``, ``th1``."""

    x0: float
    x1: float
    sol: object
    th0: float = 0.0
    th1: float = 0.0


class _Series:
    """J, J′ and the total moment of the loads and gravity of a profile at one travel, in plain
    floats: the panel's own Legendre series (cached as lists) by the three-term recurrence —
    what the ODE's right-hand side calls, some thousands of times per run."""

    def __init__(self, prof: Profile):
        pn, f = prof.panels, prof.fields
        self.edges, self.half = pn.edges.tolist(), pn.half.tolist()
        self.rows = [tuple(f[:, p, :].tolist()) for p in range(pn.count)]
        self.rec = [((2 * k + 1) / (k + 1), k / (k + 1)) for k in range(1, f.shape[-1] - 1)]
        self.cycle, self.last = pn.cycle, pn.count - 1

    def __call__(self, t: float, lo: int = 0, hi: int | None = None) -> tuple[float, float, float]:
        """(J, J′, M) at travel ``t`` (rad, within the cycle), on the panels ``lo``…``hi`` only
        (a piece between jumps takes its own side of them); NaN for a NaN travel."""
        p = bisect.bisect_right(self.edges, t) - 1
        p = min(max(p, lo), self.last if hi is None else hi)
        # held within [−2, 2]: beyond its panel a series is only met by wild trial steps
        x = min(max(float(t - self.edges[p]) / self.half[p] - 1.0, -2.0), 2.0)
        basis = [1.0, x]
        p0, p1 = 1.0, x
        for a, b in self.rec:
            p0, p1 = p1, a * x * p1 - b * p0
            basis.append(p1)
        cj, cd, cm = self.rows[p]
        return sum(map(mul, cj, basis)), sum(map(mul, cd, basis)), sum(map(mul, cm, basis))

    def at(self, theta: float) -> tuple[float, float, float]:
        """(J, J′, M) at any travel (taken within the cycle)."""
        return self(theta % self.cycle)


def _segments(prof: Profile):
    """[(θa, θb, first panel, last panel)] between the breaks of one cycle."""
    pn = prof.panels
    out = []
    for a, b in zip(pn.breaks[:-1], pn.breaks[1:]):
        lo = int(np.searchsorted(pn.edges, a - 1e-12 * pn.cycle))
        hi = int(np.searchsorted(pn.edges, b - 1e-12 * pn.cycle)) - 1
        out.append((float(a), float(b), lo, max(lo, hi)))
    return out


def _local(series: _Series, lo: int, hi: int, base: float):
    return lambda theta: series(theta - base, lo, hi)


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

    errors: dict = field(default_factory=dict)

    def at_travel(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t s, w rad/s, dw/dt rad/s²) at travels ``theta`` (0 ≤ θ ≤ travel): the time by
        Newton's method on the dense solution (dθ/dt = w), bisection where w is 0."""
        out = []
        starts = [pc.th0 for pc in self.pieces]
        for th in np.atleast_1d(np.asarray(theta, dtype=float)).tolist():
            pc = self.pieces[max(0, min(bisect.bisect_right(starts, th) - 1, len(self.pieces) - 1))]
            t = _time_at(pc, th)
            y = pc.sol(t)
            out.append((t, y[1], self.rhs(y[0], y[1])))
        a = np.array(out).reshape(-1, 3)
        return a[:, 0], a[:, 1], a[:, 2]


def _time_at(pc: Piece, th: float) -> float:
    """The time within ``pc`` at which the travel is ``th`` (clamped to the piece)."""
    if th <= pc.th0:
        return pc.x0
    if th >= pc.th1:
        return pc.x1
    lo, hi = pc.x0, pc.x1
    t = lo + (hi - lo) * (th - pc.th0) / (pc.th1 - pc.th0)
    for _ in range(100):
        y = pc.sol(t)
        f = y[0] - th
        if f > 0:
            hi = t
        elif f < 0:
            lo = t
        else:
            return t
        step = t - f / y[1] if y[1] > 0 else math.nan
        new = step if lo <= step <= hi else 0.5 * (lo + hi)
        if abs(new - t) <= 4e-16 * max(abs(t), 1e-300) or hi - lo <= 4e-16 * max(abs(hi), 1e-300):
            return new
        t = new
    return t


def simulate(prof: Profile, inertia: float, moment: Callable, w0: float, *, travel: float | None = None,
             time: float | None = None, time_limit: float = 60.0, rtol: float = RTOL,
             scalar: Callable | None = None) -> Run:
    """Integrate a run from position 1 at speed ``w0`` (rad/s, ≥ 0) with the constant inertia
    ``inertia`` (kg·m²) and the driving moment ``moment(w)`` (N·m on the crank; ``scalar``, the
    same for one float, is what the right-hand side calls), until the travel ``travel`` (rad)
    or the time ``time`` (s). The result's ``errors`` estimate the error of its time (or
    travel) and speeds from the tolerance and the profile's errors.

    Raises
    ------
    VelplanError
        The crank stops (naming the travel, the crank angle and the time), or the travel is not
        reached within ``time_limit`` s.
    """
    from scipy.integrate import solve_ivp

    _check_inertia(prof, inertia)
    series = _Series(prof)
    mom = scalar or (lambda w: float(moment(w)))
    segs = _segments(prof)
    cyc = prof.cycle
    t_end = time if time is not None else time_limit
    t, th, w = 0.0, 0.0, float(w0)
    pieces, w_min, th_min, w_max = [], w, 0.0, w
    k, base = 0, 0.0
    atol = [1e-13 * cyc, 1e-12 * max(w0, 1.0)]
    while t < t_end:
        a, b, lo, hi = segs[k]

        def f(_t, y, lo=lo, hi=hi, base=base):
            j, dj, m = series(y[0] - base, lo, hi)
            return [y[1], (m + mom(y[1]) - 0.5 * dj * y[1] * y[1]) / (inertia + j)]

        target = base + b if travel is None else min(base + b, travel)
        reach = lambda _t, y, target=target: y[0] - target  # noqa: E731
        reach.terminal, reach.direction = True, 1
        stop = lambda _t, y: y[1]  # noqa: E731
        stop.terminal, stop.direction = True, -1
        turn = lambda _t, y, f=f: f(_t, y)[1]  # noqa: E731
        sol = solve_ivp(f, (t, t_end), [th, w], method="DOP853", rtol=rtol, atol=atol,
                        events=[reach, stop, turn], dense_output=True)
        if sol.status == -1:
            raise VelplanError(f"dynamics run: the integration failed at t = {t:.6g} s: {sol.message}")
        for yy in [sol.y[:, -1]] + list(sol.y_events[2]):
            if yy[1] < w_min:
                w_min, th_min = float(yy[1]), float(yy[0])
            w_max = max(w_max, float(yy[1]))
        if sol.t_events[1].size:
            ts, ys = float(sol.t_events[1][0]), sol.y_events[1][0]
            raise VelplanError(f"dynamics run: the crank stops after a travel of {_deg(float(ys[0]))} from position 1 "
                               f"at t = {ts:.6g} s; the driving moment cannot overcome the load")
        th_start = th
        if sol.t_events[0].size:
            t, w, th = float(sol.t_events[0][0]), float(sol.y_events[0][0][1]), target
        else:
            t, th, w = float(sol.t[-1]), float(sol.y[0, -1]), float(sol.y[1, -1])
        pieces.append(Piece(float(sol.t[0]), t, sol.sol, th_start, th))
        if not sol.t_events[0].size:
            if time is not None:
                break
            raise VelplanError(f"dynamics run: the crank turned only {_deg(th)} of travel_deg = "
                               f"{_deg(travel)} within time_limit = {time_limit:g} s")
        if travel is not None and target >= travel:
            break
        k += 1
        if k == len(segs):
            k, base = 0, base + cyc
    w_min = min(w_min, w)
    w_max = max(w_max, w)
    accel = _accel_error(prof, inertia, w_max)
    mean = th / t if t > 0 else max(w_max, 1e-300)
    e_w = 10 * rtol * w_max + accel * t
    errors = {"omega": e_w, "time": 0.0 if time is not None else 10 * rtol * t + t * e_w / mean,
              "travel": 10 * rtol * th + e_w * t if time is not None else 0.0}
    return Run(t, th, float(w0), float(w), w_min, w_max, th_min, tuple(pieces),
               lambda th_, w_: _rhs_at(series, mom, inertia, th_, w_), errors)


def _check_inertia(prof: Profile, inertia: float) -> None:
    """A `VelplanError` where the total reduced inertia vanishes (no finite acceleration)."""
    J = prof.values(prof.panels.nodes.ravel())[0] + inertia
    if not J.min() > 1e-12 * max(float(J.max()), 0.0):
        raise VelplanError(f"dynamics: the reduced inertia falls to {float(J.min()):.3g} kg·m² with the constant "
                           f"inertia {inertia:.6g} kg·m²; give masses or constant inertias (a flywheel)")


def _accel_error(prof: Profile, inertia: float, w: float) -> float:
    """Bound on the error of dw/dt (rad/s²) from the profile's errors at speeds up to ``w``."""
    e = prof.errors
    J = prof.values(prof.panels.nodes.ravel())[0] + inertia
    return (e["M"] + 0.5 * e["dJ"] * w * w) / float(J.min()) * (1.0 + e["J"] / float(J.min()))


def _rhs_at(series: _Series, mom: Callable, inertia: float, th: float, w: float) -> float:
    j, dj, m = series.at(th)
    return (m + mom(w) - 0.5 * dj * w * w) / (inertia + j)


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
    errors: dict = field(default_factory=dict)

    def at_travel(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t s, w rad/s, dw/dt rad/s²) at travels ``theta`` within the cycle."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        out = np.empty((th.size, 3))
        starts = [p.x0 for p in self.pieces]
        for i, x in enumerate(th.tolist()):
            pc = self.pieces[max(0, min(bisect.bisect_right(starts, x) - 1, len(self.pieces) - 1))]
            u, t = pc.sol(min(max(x, pc.x0), pc.x1))
            w = math.sqrt(max(u, 0.0))
            out[i] = (t, w, self.rhs(x, w))
        return out[:, 0], out[:, 1], out[:, 2]


def _cycle(series, segs, inertia, mom, w0, rtol, dense):
    from scipy.integrate import solve_ivp

    y = [w0 * w0, 0.0]
    pieces, ext = [], []
    for a, b, lo, hi in segs:

        def f(x, yy, lo=lo, hi=hi):
            j, dj, m = series(x, lo, hi)
            u = yy[0]
            w = math.sqrt(u) if u > 0 else 0.0
            # dt/dθ = 1/w: held finite where a trial step reaches w = 0 (the stop event ends it)
            return [2.0 * (m + mom(w) - 0.5 * dj * u) / (inertia + j), 1.0 / w if w > 1e-150 else 1e150]

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
             tol: float = 1e-10, scalar: Callable | None = None) -> Periodic:
    """The periodic regime with the driving moment ``moment(w)`` (N·m on the crank; ``scalar``
    the same for one float): the speed at position 1 that returns after a cycle, by the secant
    method from ``w_guess``. Its ``errors`` estimate those of the speeds and the period."""
    _check_inertia(prof, inertia)
    series = _Series(prof)
    mom = scalar or (lambda w: float(moment(w)))
    segs = _segments(prof)
    F = lambda w: _cycle(series, segs, inertia, mom, w, rtol, False)[0] - w  # noqa: E731
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
    w_end, period, pieces, ext = _cycle(series, segs, inertia, mom, x1, rtol, True)
    ths = np.array([e[0] for e in ext])
    ws = np.sqrt(np.maximum([e[1] for e in ext], 0.0))
    imax, imin = int(np.argmax(ws)), int(np.argmin(ws))
    wmax, wmin = float(ws[imax]), float(ws[imin])
    wm = 0.5 * (wmax + wmin)
    rhs = lambda th, w: _rhs_at(series, mom, inertia, th, w)  # noqa: E731
    e_w = 10 * rtol * wmax + abs(w_end - x1) + _accel_error(prof, inertia, wmax) * period
    errors = {"omega": e_w, "delta": 2.0 * e_w / wm * (1.0 + (wmax - wmin) / wm),
              "period": 10 * rtol * period + period * e_w / wmin}
    return Periodic(x1, wmax, wmin, wm, float(ths[imax]), float(ths[imin]), (wmax - wmin) / wm, period,
                    abs(w_end - x1), tuple(pieces), rhs, moment, errors)
