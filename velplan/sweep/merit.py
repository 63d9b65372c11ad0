"""Figures of merit of many variants at once, from one `solve_design` call per chunk.

Per variant: whether it closes (assembles, off every toggle) over the whole turn, the stroke
H and the time-ratio coefficient K of the output with its extreme positions found to
round-off (grid, then Newton steps on the exact derivatives, all variants together), the
minimum transmission angle γ_min with where it occurs, and the peak |v| and |a| of the output;
with loads or masses in the file, the peak balancing moment and, for a required δ, the
flywheel's J_I (`velplan.sweep.dynamic`).
"""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.design import DesignKinematics, solve_design, variant
from velplan.analysis.extremes import output_quantity, reference_angle
from velplan.mechanism.keys import resolve
from velplan.mechanism.model import RPR, Mechanism, turning_sense
from velplan.sweep import dynamic

FIGURES = {
    "H": "stroke of the output (m; rad for a rocker)",
    "K": "time-ratio coefficient K = (180° + θ)/(180° − θ)",
    "theta_deg": "angle of overlap θ, deg",
    "phi_start_deg": "crank angle at the start of the slow (working) stroke, deg",
    "phi_end_deg": "crank angle at its end, deg",
    "gamma_min_deg": "smallest transmission angle over the turn and the groups, deg",
    "gamma_phi_deg": "crank angle where it occurs, deg",
    "v_max": "peak |v| of the output point, m/s (|ω|, rad/s, of an output link)",
    "a_max": "peak |a| of the output point, m/s² (|ε|, rad/s², of an output link)",
    "Mb_max": "peak |M_b|, the balancing moment on the crank (loads, gravity, inertia), N·m",
    "J_I": "constant reduced inertia for the coefficient of speed fluctuation δ (flywheel), kg·m²",
}
"""Figures of merit: name → meaning and unit."""

NEWTON = 6
"""Newton steps on each extreme (quadratic convergence: round-off after 3 or 4 from a 1° grid)."""


def grid_angles(n: int) -> np.ndarray:
    """``n`` crank angles over the turn (rad), shifted off round angles so that no sample lands
    on an extreme exactly."""
    return (np.arange(n) + 0.3819660112501051) * (2 * np.pi / n)


def figures(mech: Mechanism, values: dict, n: int = 360, engine: str = "numpy",
            delta: float | None = None) -> tuple[dict[str, np.ndarray], list[str], list[str]]:
    """Figures of merit of the variants ``values`` (key → (V,) array) of ``mech`` at ``n`` crank
    angles over the turn, solved by ``engine`` ("numpy" or "compiled", `solve_design`);
    ``delta`` (0 < δ < 1) adds the flywheel's J_I when the file has loads or masses.

    Returns
    -------
    figures : dict of name → ndarray, shape (V,)
        See `FIGURES`; NaN for a variant that does not close (and H, K, θ for an output
        that does not reverse).
    failures : list of str, length V
        "" for a variant that closes over the turn, else why not.
    gamma_group : list of str, length V
        The group whose transmission angle is γ_min.
    """
    if values and not all(resolve(mech, k).array for k in values):
        return _each_variant(mech, values, n, engine, delta)
    phi = grid_angles(n)
    dk = solve_design(mech, values, phi, engine=engine)
    failures = dk.failures()
    ok = np.array([f == "" for f in failures])
    out: dict[str, np.ndarray] = {}
    gamma, where, group = transmission(dk)
    out["gamma_min_deg"], out["gamma_phi_deg"] = gamma, where
    q = output_quantity(mech, dk.flat)
    ends = None
    if q is not None:
        stroke, reason, ends = _strokes(mech, dk, q, engine)
        out.update(stroke)
        out["v_max"], out["a_max"] = _peaks(mech, dk, q)
        failures = [f or r for f, r in zip(failures, reason)]
    if dynamic.has_dynamics(mech):
        out.update(_dynamic(mech, dk, ends, delta, engine))
    for k, arr in out.items():
        out[k] = np.where(ok, arr, np.nan)
    return {k: out[k] for k in FIGURES if k in out}, failures, group


def _each_variant(mech: Mechanism, values: dict, n: int, engine: str, delta: float | None):
    """`figures` of variants that differ in a number the arrays do not carry (a triad's sides,
    a mass, a load …): each built as its file would be (`variant`) and studied alone."""
    cols = {k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in values.items()}
    V = max(len(c) for c in cols.values())
    rows = [figures(variant(mech, {k: float(c[v if len(c) > 1 else 0]) for k, c in cols.items()}), {}, n, engine,
                    delta) for v in range(V)]
    names = [k for k in FIGURES if any(k in r[0] for r in rows)]
    figs = {k: np.array([r[0][k][0] if k in r[0] else np.nan for r in rows]) for k in names}
    return figs, [r[1][0] for r in rows], [r[2][0] for r in rows]


def _dynamic(mech: Mechanism, dk: DesignKinematics, ends, delta: float | None, engine: str) -> dict[str, np.ndarray]:
    """Mb_max and, with ``delta``, J_I per variant (`velplan.sweep.dynamic`)."""
    V = dk.shape[0]
    if ends is None:  # no output: loads need none, and position 1 is φ = 0
        nan = np.full(V, np.nan)
        ends = dynamic.Ends(nan, nan, nan, nan, nan, np.full(V, mech.crank.sense), np.zeros(V))
    loads = dynamic.variant_loads(mech, dk.values, ends, engine)
    inertia = dynamic.centre_inertias(mech, dk)
    out = {"Mb_max": dynamic.balancing_peak(mech, dk, loads, ends, inertia)}
    if delta is not None:
        out["J_I"] = dynamic.flywheel_inertia(mech, dk.values, loads, ends, inertia, delta, engine)
    return out


def transmission(dk: DesignKinematics) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """(γ_min in deg, the crank angle in deg where it occurs, the group) per variant.

    The transmission angle of a group is the acute angle between the two lines whose
    crossing fixes it (its condition estimate is the sine of that angle): rod and rocker
    (RRR), rod and guide (RRP), the two guides (PRP), slot and guide (RPP); for a block on a
    bar (RPR), the angle whose sine is s/|OA| (90° when the bar passes through the pivot).
    """
    kin = dk.flat
    c = np.array(kin.condition, copy=True)  # (E, G)
    mech = dk.mechanism
    for g in mech.groups:
        if isinstance(g, RPR):
            j = kin.group_index[g.name]
            s = kin.slides[:, kin.slide_index[f"P:{g.links[0]}/{g.links[1]}"], 0]
            r = kin.positions[:, kin.point_index[g.joint]] - kin.positions[:, kin.point_index[g.pivot]]
            with np.errstate(invalid="ignore", divide="ignore"):
                c[:, j] = np.abs(s) / np.hypot(r[:, 0], r[:, 1])
    V, n = dk.shape
    names = list(kin.group_index)
    if not names:
        return np.full(V, 90.0), np.full(V, np.nan), [""] * V
    G = len(names)
    c = np.where(np.isfinite(c), np.clip(c, 0.0, 1.0), np.inf).reshape(V, n, G)
    at = np.argmin(c.reshape(V, n * G), axis=1)
    i, j = np.divmod(at, G)
    rows = np.arange(V)
    with np.errstate(invalid="ignore"):
        g = np.degrees(np.arcsin(c))  # inf (not closed) → NaN
    # a parabola through the grid's minimum and its two neighbours (the turn is periodic)
    g0, gm, gp = g[rows, i, j], g[rows, (i - 1) % n, j], g[rows, (i + 1) % n, j]
    curv = gm - 2 * g0 + gp
    with np.errstate(invalid="ignore", divide="ignore"):
        d = np.clip(np.where(curv > 0, 0.5 * (gm - gp) / curv, 0.0), -0.5, 0.5)
    d = np.where(np.isfinite(d), d, 0.0)
    gamma = g0 - 0.25 * (gm - gp) * d
    step = np.diff(dk.phi[:, :2], axis=1)[:, 0] if n > 1 else np.zeros(V)
    where = np.degrees(dk.phi[rows, i] + d * step) % 360.0
    return gamma, where, [names[k] for k in j]


def _rates(kin, kind: str, i: int):
    """Value, rate and acceleration of quantity (kind, i) over the elements of ``kin``."""
    if kind == "link":
        return kin.angles[:, i], kin.omegas[:, i], kin.epsilons[:, i]
    return kin.slides[:, i, 0], kin.slides[:, i, 1], kin.slides[:, i, 2]


def _analogues(dk: DesignKinematics, kind: str, i: int):
    """(V, n) value, first and second derivative by the crank angle (ω1 = 1, ε1 = 0)."""
    kin = dk.flat
    f, rate, acc = _rates(kin, kind, i)
    w = np.broadcast_to(np.asarray(kin.omega1, float), rate.shape)
    e = np.broadcast_to(np.asarray(kin.epsilon1, float), rate.shape)
    d1 = rate / w
    d2 = (acc - e * d1) / (w * w)
    return tuple(dk.per_variant(a) for a in (f, d1, d2))


def _strokes(mech: Mechanism, dk: DesignKinematics, q, engine: str
             ) -> tuple[dict[str, np.ndarray], list[str], dynamic.Ends]:
    """H, K, θ and the extremes per variant; the reason where the output does not reverse; the
    working stroke's extremes (NaN where it does not)."""
    _, kind, i = q
    f, d1, _ = _analogues(dk, kind, i)
    V, n = dk.shape
    if kind == "link":
        f = np.unwrap(f, axis=1)
    rows = np.arange(V)
    sign = np.sign(d1)
    reversals = np.sum(sign * np.roll(sign, -1, axis=1) < 0, axis=1)
    start = np.stack([dk.phi[rows, np.nanargmax(np.where(np.isnan(f), -np.inf, f), axis=1)],
                      dk.phi[rows, np.nanargmin(np.where(np.isnan(f), np.inf, f), axis=1)]], axis=1)
    x, val = _newton(mech, dk.values, start, kind, i, 2 * np.pi / n, engine)
    hi, lo = x[:, 0], x[:, 1]
    sense = mech.crank.sense
    if "crank.omega" in dk.values or "crank.rpm" in dk.values:
        sense = turning_sense(dk.flat.omega1[::n])
    span = (sense * (hi - lo)) % (2 * np.pi)
    theta = np.abs(span - np.pi)
    slow_lo = span > np.pi
    even = np.abs(span - np.pi) < 1e-9  # K = 1: as `stroke`, from the reference when it is an extreme
    if mech.reference_deg is not None and even.any():
        ref = math.radians(mech.reference_deg) % (2 * np.pi)
        near = lambda a: np.abs((a - ref + np.pi) % (2 * np.pi) - np.pi) < 1e-6  # noqa: E731
        slow_lo = np.where(even, ~(near(hi) & ~near(lo)), slow_lo)
    else:
        slow_lo = np.where(even, True, slow_lo)
    H = np.abs(val[:, 0] - val[:, 1])
    if kind == "link":
        H = np.abs((val[:, 0] - val[:, 1] + np.pi) % (2 * np.pi) - np.pi)
    bad = reversals < 2
    nan = lambda a: np.where(bad, np.nan, a)  # noqa: E731
    with np.errstate(divide="ignore", invalid="ignore"):
        K = (np.pi + theta) / (np.pi - theta)
    out = {"H": nan(H), "K": nan(K), "theta_deg": nan(np.degrees(theta)),
           "phi_start_deg": nan(np.degrees(np.where(slow_lo, lo, hi) % (2 * np.pi))),
           "phi_end_deg": nan(np.degrees(np.where(slow_lo, hi, lo) % (2 * np.pi)))}
    reason = ["output does not reverse (no stroke)" if b else "" for b in bad]
    start, end = nan(np.where(slow_lo, lo, hi)), nan(np.where(slow_lo, hi, lo))
    s_start, s_end = nan(np.where(slow_lo, val[:, 1], val[:, 0])), nan(np.where(slow_lo, val[:, 0], val[:, 1]))
    sense = np.broadcast_to(np.asarray(sense, float), (V,))
    reference = np.full(V, reference_angle(mech)) if mech.reference_deg is not None else np.where(bad, 0.0, start)
    return out, reason, dynamic.Ends(start, end, s_start, s_end, np.pi + theta, sense, reference)


def _newton(mech: Mechanism, values: dict, x: np.ndarray, kind: str, i: int, h: float, engine: str):
    """Refine the (V, 2) crank angles ``x`` of the output's max and min: Newton steps on the
    analogue's exact derivative, each step kept within one grid spacing ``h``."""
    val = np.full(x.shape, np.nan)
    for _ in range(NEWTON):
        dk = solve_design(mech, values, x, engine=engine)
        val, d1, d2 = _analogues(dk, kind, i)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.clip(-d1 / d2, -h, h)
        x = np.where(np.isfinite(step), x + step, x)
    return x, val


def _peaks(mech: Mechanism, dk: DesignKinematics, q) -> tuple[np.ndarray, np.ndarray]:
    """Peak |v|, |a| of the output point (|ω|, |ε| of an output link) over the grid."""
    _, kind, i = q
    kin = dk.flat
    if mech.output.link is not None:
        v, a = np.abs(kin.omegas[:, i]), np.abs(kin.epsilons[:, i])
    else:
        j = kin.point_index[mech.output.point]
        v = np.hypot(*kin.velocities[:, j].T)
        a = np.hypot(*kin.accelerations[:, j].T)
    v, a = dk.per_variant(v), dk.per_variant(a)
    return np.max(v, axis=1), np.max(a, axis=1)


def nominal_figures(mech: Mechanism, n: int = 360, delta: float | None = None) -> dict[str, float]:
    """The figures of merit of ``mech`` itself."""
    figs, fail, _ = figures(mech, {}, n, delta=delta)
    return {k: float(v[0]) for k, v in figs.items()}
