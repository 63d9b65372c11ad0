"""Where the analytic solver spends its time at 10⁶ positions, and what would make it faster.

Nothing in velplan/ is changed: the experiments below re-run the solver's loop (a copy of the
baseline commit's, on the group functions of ``velplan.analysis.groups``) with one change at a
time, check that the results are the same as ``velplan.solve``'s, and time them end to end
(round-robin, median and minimum of 5 at 10⁶ positions).

    python benchmarks/profile_solver.py        # prints the markdown section

`bench_solver.py` appends this section to ``results/solver.md`` under "Profile".
"""

from __future__ import annotations

import cProfile
import io
import os
import pstats
import time
from concurrent.futures import ThreadPoolExecutor
from types import SimpleNamespace

import numpy as np

from _common import grid, median_time, table

import velplan
from velplan.analysis import groups as G
from velplan.analysis.solvers import solve_group
from velplan.analysis import solver as S
from velplan.mechanism.model import GROUND, Crank, LinkPoint
from velplan.mechanism.structure import schedule

N = int(os.environ.get("PROFILE_N", 1_000_000))  # smaller for a smoke test only
EXAMPLES = ("four-bar", "shaper")
TARGET_US = {"four-bar": 0.1, "shaper": 0.2}
ROUNDS = 5


def ms(t: float) -> str:
    return f"{t * 1e3:.0f}"


BASELINE = "db37b34"
"""The commit whose `velplan.solve` was profiled. `solver.py` is being optimised while these
benchmarks are written, so the baseline is re-run here from a verbatim copy of its loop and
`_pack` (`baseline_solve`), built on the unchanged group functions of `velplan.analysis.groups`;
the current `velplan.solve` is timed alongside."""


# --- 1. the baseline solver, phase by phase -------------------------------------------------------

def _unit(theta: np.ndarray) -> np.ndarray:
    """e^{iθ} by cos and sin written into a complex array (no complex temporary 1j·θ)."""
    u = np.empty(theta.shape, dtype=complex)
    f = u.view(np.float64)
    np.cos(theta, out=f[0::2])
    np.sin(theta, out=f[1::2])
    return u


def _solve_block(mech, phi, w1, e1, *, crank_cs: bool = False, unit_cache: bool = False, lap=None):
    """The baseline's loop (its `solve` up to `_pack`) on a block of angles, with the changes B
    switchable; returns (State, conditions, valid, {link: e^{iθ}})."""
    lap = lap or (lambda name: None)
    n = phi.shape[0]
    st = G.State(n)
    zeros = np.zeros(n, dtype=complex)
    for name, (x, y) in mech.ground:
        st.points[name] = G.Motion(np.full(n, complex(x, y)), zeros, zeros)
    zr = np.zeros(n)
    st.links[GROUND] = G.LinkMotion(mech.ground[0][0], zr, zr, zr)
    scale = S.length_scale(mech)
    conditions, units = {}, {}
    lap("set-up (ground points, zeros)")
    with np.errstate(all="ignore"):
        for item in schedule(mech):
            if isinstance(item, Crank):
                u = _unit(phi) if crank_cs else np.exp(1j * phi)
                if crank_cs:
                    units[item.link] = u
                r = item.length * u
                O = st.points[item.pivot]
                st.points[item.tip] = G.Motion(O.p + r, 1j * w1 * r, (1j * e1 - w1 * w1) * r)
                st.links[item.link] = G.LinkMotion(item.pivot, phi.copy(), np.full(n, w1), np.full(n, e1))
                lap("crank: `np.exp(1j*phi)`, V, a")
            elif isinstance(item, LinkPoint):
                link = st.links[item.link]
                origin = st.points[link.origin]
                if unit_cache:
                    if item.link not in units:
                        units[item.link] = _unit(link.theta)
                    e = units[item.link]
                else:
                    e = np.exp(1j * link.theta)
                x = origin.p + (item.along + 1j * item.offset) * e
                st.points[item.name] = G.Motion(x, *G.carry(origin.p, origin.v, origin.a, link.omega, link.epsilon, x))
                lap(f"point {item.name}: `np.exp(1j*theta)` + `carry`")
            else:
                res = solve_group(item, st, scale)
                st.points.update(res.points)
                st.links.update(res.links)
                st.slides.update(res.slides)
                conditions[item.name] = np.where(res.closed, res.condition, np.nan)
                lap(f"group {item.name} ({item.kind})")
    valid = np.ones(n, dtype=bool)
    for c in conditions.values():
        valid &= np.isfinite(c) & (c > 0)
    return st, conditions, valid, units


def _stack(values, n):
    if not values:
        return np.zeros((n, 0, 2))
    z = np.stack(values, axis=1)
    return np.stack([z.real, z.imag], axis=-1)


def _baseline_pack(st, conditions, valid, n, lap=None):
    """The baseline's `_pack`, verbatim but for the final `Kinematics(...)` (a namespace here)."""
    lap = lap or (lambda name: None)
    names = list(st.points)
    pos = _stack([st.points[k].p for k in names], n)
    vel = _stack([st.points[k].v for k in names], n)
    acc = _stack([st.points[k].a for k in names], n)
    lap("`_pack`: 3 × `_stack` of points (complex stack, then real/imag stack)")
    links = [k for k in st.links if k != GROUND]
    ang = np.stack([st.links[k].theta for k in links], axis=1)
    om = np.stack([st.links[k].omega for k in links], axis=1)
    ep = np.stack([st.links[k].epsilon for k in links], axis=1)
    slides = list(st.slides)
    sl = (np.stack([np.stack([st.slides[k].p, st.slides[k].v, st.slides[k].a], -1) for k in slides], 1).real
          if slides else np.zeros((n, 0, 3)))
    cond = np.stack(list(conditions.values()), axis=1) if conditions else np.zeros((n, 0))
    lap("`_pack`: stack links, slides, conditions")
    finite = np.isfinite(pos).all(axis=(1, 2)) & np.isfinite(vel).all(axis=(1, 2))
    finite &= np.isfinite(acc).all(axis=(1, 2)) & np.isfinite(om).all(axis=1)
    lap("`_pack`: `isfinite(...).all(axis=(1, 2))` × 3")
    ang = np.angle(np.exp(1j * ang))
    lap("`_pack`: `np.angle(np.exp(1j*ang))` wrap of all link angles")
    return SimpleNamespace(positions=pos, velocities=vel, accelerations=acc, angles=ang, omegas=om, epsilons=ep,
                           slides=sl, condition=cond, valid=valid & finite,
                           point_index={k: i for i, k in enumerate(names)})


def baseline_solve(mech, phi):
    """`velplan.solve` as of the baseline commit (ε1 = 0)."""
    st, conditions, valid, _ = _solve_block(mech, phi, mech.crank.omega, 0.0)
    return _baseline_pack(st, conditions, valid, phi.shape[0])


def cprofile_top(mech, phi, k: int = 8) -> list[list[str]]:
    baseline_solve(mech, phi[:16])
    pr = cProfile.Profile()
    pr.enable()
    baseline_solve(mech, phi)
    pr.disable()
    st = pstats.Stats(pr, stream=io.StringIO())
    rows = []
    for (file, line, func), (cc, nc, tt, ct, _) in sorted(st.stats.items(), key=lambda kv: -kv[1][2])[:k]:
        if func == "baseline_solve" or file.endswith("profile_solver.py") and func in ("_solve_block",):
            pass
        where = f"{file.split('/')[-1]}:{line}" if line else "builtin"
        rows.append([f"`{func}` ({where})", str(nc), ms(tt), ms(ct)])
    return rows


def phase_times(mech, phi) -> list[tuple[str, float]]:
    """The baseline solve with a clock between its phases."""
    out: list[tuple[str, float]] = []
    clock = [time.perf_counter()]

    def lap(name):
        t = time.perf_counter()
        out.append((name, t - clock[0]))
        clock[0] = t

    st, conditions, valid, _ = _solve_block(mech, phi, mech.crank.omega, 0.0, lap=lap)
    _baseline_pack(st, conditions, valid, phi.shape[0], lap=lap)
    return out


# --- 2. the suggested changes, one at a time ---------------------------------------------------------

class _Buffers:
    """Outputs laid out point-major: (P, n) complex per quantity, exposed as (n, P, 2) views."""

    def __init__(self, st, conditions, n):
        self.names = list(st.points)
        self.links = [k for k in st.links if k != GROUND]
        self.slides = list(st.slides)
        self.groups = list(conditions)
        P, L = len(self.names), len(self.links)
        self.p, self.v, self.a = (np.empty((P, n), dtype=complex) for _ in range(3))
        self.th, self.om, self.ep = (np.empty((L, n)) for _ in range(3))
        self.sl = np.empty((len(self.slides), 3, n))
        self.cond = np.empty((len(self.groups), n))
        self.valid = np.empty(n, dtype=bool)
        self.crank_u = np.empty(n, dtype=complex)

    def fill(self, s: slice, st, conditions, valid, units, crank_link):
        for j, k in enumerate(self.names):
            m = st.points[k]
            self.p[j, s], self.v[j, s], self.a[j, s] = m.p, m.v, m.a
        for j, k in enumerate(self.links):
            m = st.links[k]
            self.th[j, s], self.om[j, s], self.ep[j, s] = m.theta, m.omega, m.epsilon
        for j, k in enumerate(self.slides):
            m = st.slides[k]
            self.sl[j, 0, s], self.sl[j, 1, s], self.sl[j, 2, s] = m.p.real, m.v.real, m.a.real
        for j, k in enumerate(self.groups):
            self.cond[j, s] = conditions[k]
        self.valid[s] = valid
        if crank_link in units:
            self.crank_u[s] = units[crank_link]

    def pack(self, mech, n, have_crank_u: bool):
        P = len(self.names)

        def xy(z):  # (P, n) complex → (n, P, 2) float view, no copy
            return z.view(np.float64).reshape(P, n, 2).transpose(1, 0, 2)

        # NaN/inf anywhere in a column of a point makes the column sum non-finite
        finite = np.isfinite(self.p.sum(axis=0)) & np.isfinite(self.v.sum(axis=0))
        finite &= np.isfinite(self.a.sum(axis=0)) & np.isfinite(self.om.sum(axis=0))
        for j, k in enumerate(self.links):  # wrap only the rows that are not already in (−π, π]
            row = self.th[j]
            if k == mech.crank.link and have_crank_u:
                self.th[j] = np.angle(self.crank_u)
            elif row.min() < -np.pi or row.max() > np.pi:
                self.th[j] = np.angle(np.exp(1j * row))
        return SimpleNamespace(positions=xy(self.p), velocities=xy(self.v), accelerations=xy(self.a),
                               angles=self.th.T, omegas=self.om.T, epsilons=self.ep.T,
                               slides=self.sl.transpose(2, 0, 1), condition=self.cond.T,
                               valid=self.valid & finite, point_index={k: i for i, k in enumerate(self.names)})


def solve_variant(mech, phi, *, pack_views=False, crank_cs=False, unit_cache=False, chunk=None,
                  threads=1):
    """The baseline solve with the suggested changes switched on one by one (ε1 = 0)."""
    n = phi.shape[0]
    w1, e1 = mech.crank.omega, 0.0
    if not pack_views:
        st, conditions, valid, _ = _solve_block(mech, phi, w1, e1, crank_cs=crank_cs, unit_cache=unit_cache)
        return _baseline_pack(st, conditions, valid, n)
    chunk = chunk or n
    blocks = [slice(i, min(i + chunk, n)) for i in range(0, n, chunk)]
    first = _solve_block(mech, phi[blocks[0]], w1, e1, crank_cs=crank_cs, unit_cache=unit_cache)
    buf = _Buffers(first[0], first[1], n)
    buf.fill(blocks[0], *first, mech.crank.link)

    def job(s):
        buf.fill(s, *_solve_block(mech, phi[s], w1, e1, crank_cs=crank_cs, unit_cache=unit_cache),
                 mech.crank.link)

    if threads > 1 and len(blocks) > 1:
        with ThreadPoolExecutor(threads) as ex:
            list(ex.map(job, blocks[1:]))
    else:
        for s in blocks[1:]:
            job(s)
    return buf.pack(mech, n, have_crank_u=crank_cs)


def max_diff(a, b) -> float:
    """Largest absolute difference over positions, velocities, accelerations, ω, ε and the
    wrapped angles (taken modulo 2π), points matched by name; inf if `valid` differs."""
    j = [b.point_index[k] for k in a.point_index]
    d = [np.max(np.abs(x - y[:, j])) for x, y in ((a.positions, b.positions), (a.velocities, b.velocities),
                                                  (a.accelerations, b.accelerations))]
    d += [np.max(np.abs(a.omegas - b.omegas)), np.max(np.abs(a.epsilons - b.epsilons)),
          float(np.abs(np.angle(np.exp(1j * (a.angles - b.angles)))).max())]
    if not np.array_equal(a.valid, b.valid):
        return float("inf")
    return float(max(d))


VARIANTS = [
    (f"baseline: `velplan.solve` as of {BASELINE}", {}),
    ("A. `_pack`: stack along axis 0 into (P, n) complex, return (n, P, 2) transposed views; "
     "finite check on column sums; wrap only angle rows outside (−π, π]", dict(pack_views=True)),
    ("B. + crank and link-point unit vectors by cos/sin into a complex array, one per link "
     "(instead of `np.exp(1j*θ)` per point); crank angle wrapped by `np.angle(u)`",
     dict(pack_views=True, crank_cs=True, unit_cache=True)),
    ("C. + solve in blocks of 16384 angles written into the preallocated outputs",
     dict(pack_views=True, crank_cs=True, unit_cache=True, chunk=16384)),
    ("D. + the blocks on 2 threads (numpy releases the GIL)",
     dict(pack_views=True, crank_cs=True, unit_cache=True, chunk=16384, threads=2)),
    ("`velplan.solve` in the working tree now", None),
]


def _round_robin(fns: list, rounds: int) -> list[float]:
    """Median time of each of ``fns``, timed in turn within each round (so that load from other
    processes falls on all of them alike); garbage collector off while timing."""
    import gc

    for f in fns:
        f()
    times = [[] for _ in fns]
    gc.collect()
    gc.disable()
    try:
        for _ in range(rounds):
            for k, f in enumerate(fns):
                t = time.perf_counter()
                f()
                times[k].append(time.perf_counter() - t)
    finally:
        gc.enable()
    return [(float(np.median(t)), float(np.min(t))) for t in times]


def variants(mech, phi):
    small = grid(12)
    ref = velplan.solve(mech, phi, epsilon1=0.0)
    ref12 = velplan.solve(mech, small, epsilon1=0.0)
    big, tiny, diffs = [], [], []
    for label, kw in VARIANTS:
        if kw is None:
            fn = lambda p: velplan.solve(mech, p, epsilon1=0.0)  # noqa: E731
        else:
            fn = lambda p, kw=kw: solve_variant(mech, p, **kw)  # noqa: E731
        diffs.append(max(max_diff(fn(phi), ref), max_diff(fn(small), ref12)))
        big.append(lambda fn=fn: fn(phi))
        tiny.append(lambda fn=fn: fn(small))
    del ref
    t_big = _round_robin(big, ROUNDS)
    t_small = _round_robin(tiny, 300)
    rows = []
    (m0, n0), (s0, _) = t_big[0], t_small[0]
    for (label, _), (t, tmin), (t12, _), d in zip(VARIANTS, t_big, t_small, diffs):
        rows.append([label, f"{t / N * 1e6:.3f}", f"{tmin / N * 1e6:.3f}", f"{m0 / t:.2f}×", f"{n0 / tmin:.2f}×",
                     f"{t12 * 1e3:.3f}", f"{s0 / t12:.2f}×", f"{d:.1e}"])
    return rows, [(t / N * 1e6, tmin / N * 1e6) for t, tmin in t_big]


# --- 4. floors ------------------------------------------------------------------------------------

def output_floor(mech, phi) -> tuple[float, float, int]:
    """Time to allocate and write once the arrays `Kinematics` holds, fresh and reused (s), and
    their size in bytes."""
    kin = velplan.solve(mech, phi[:8])
    P, L = len(kin.point_index), len(kin.link_index)
    S_, Gn = kin.slides.shape[1], kin.condition.shape[1]
    n = phi.shape[0]
    floats = n * (3 * P * 2 + 3 * L + 3 * S_ + Gn)
    nbytes = floats * 8 + n

    def fresh():
        a = np.empty(floats)
        a.fill(1.0)
        return a

    buf = np.empty(floats)
    t_fresh, _ = median_time(fresh, N, repeats=5)
    t_warm, _ = median_time(lambda: buf.fill(1.0), N, repeats=5)
    return t_fresh, t_warm, nbytes


def fused_fourbar(phi, chunk=8192, threads=1):
    """A hand-fused numpy four-bar (same outputs as velplan: 6 points' P, V, A and 3 links'
    θ, ω, ε), blocks of ``chunk`` angles written into point-major buffers: what numpy can reach."""
    l, D, l1, l2, w, br = 0.10, 0.30 + 0j, 0.25, 0.20, 10.0, 1
    n = phi.shape[0]
    P, V, A = (np.empty((6, n), dtype=complex) for _ in range(3))
    TH, OM, EP = (np.empty((3, n)) for _ in range(3))

    def block(s):
        ph = phi[s]
        a_ = l * _unit(ph)
        va, aa = 1j * w * a_, (-w * w) * a_
        d = D - a_
        L2 = d.real**2 + d.imag**2
        L = np.sqrt(L2)
        a = (l1 * l1 - l2 * l2 + L2) / (2 * L)
        h = np.sqrt(l1 * l1 - a * a)
        c = a_ + (a + 1j * br * h) * (d / L)
        r1, r2 = c - a_, c - D
        den = r2.real * r1.imag - r1.real * r2.imag
        w1 = (va.real * r2.real + va.imag * r2.imag) / den  # Cramer on V_A + iω1·r1 = iω2·r2
        w2 = (va.real * r1.real + va.imag * r1.imag) / den
        q = aa - w1 * w1 * r1 + w2 * w2 * r2
        e1 = (q.imag * r2.imag + q.real * r2.real) / den
        e2 = (q.imag * r1.imag + q.real * r1.real) / den
        P[0, s], P[1, s], P[2, s], P[3, s] = 0, D, a_, c
        V[0:2, s], A[0:2, s] = 0, 0
        V[2, s], A[2, s] = va, aa
        V[3, s], A[3, s] = va + 1j * w1 * r1, aa + (1j * e1 - w1 * w1) * r1
        k = 0.125 / l1
        P[4, s], V[4, s], A[4, s] = a_ + k * r1, va + 1j * w1 * (k * r1), aa + (1j * e1 - w1 * w1) * (k * r1)
        k = 0.10 / l2
        P[5, s], V[5, s], A[5, s] = D + k * r2, 1j * w2 * (k * r2), (1j * e2 - w2 * w2) * (k * r2)
        TH[0, s], TH[1, s], TH[2, s] = ph, np.arctan2(r1.imag, r1.real), np.arctan2(r2.imag, r2.real)
        OM[0, s], OM[1, s], OM[2, s] = w, w1, w2
        EP[0, s], EP[1, s], EP[2, s] = 0, e1, e2

    blocks = [slice(i, min(i + chunk, n)) for i in range(0, n, chunk)]
    if threads > 1:
        with ThreadPoolExecutor(threads) as ex:
            list(ex.map(block, blocks))
    else:
        for s in blocks:
            block(s)
    return P, V, A, TH, OM, EP


def run() -> str:
    phi = grid(N)
    out = ["## Profile", "",
           f"`benchmarks/profile_solver.py`, n = {N:g} positions, ε1 = 0, same machine. velplan/ is not "
           f"modified by it. The baseline is `velplan.solve` as of commit {BASELINE}, re-run from a verbatim "
           "copy of its loop and `_pack` on the unchanged group functions of `velplan.analysis.groups` "
           "(solver.py is being optimised while this is written; the working tree's `velplan.solve` is "
           "the last row of each table). Each change is checked against the working tree's "
           "`velplan.solve` (max |Δ| column) and timed: the variants are timed in turn, round after round "
           f"({ROUNDS} rounds at 10⁶, 300 at n = 12), and the median (and, at 10⁶, the minimum) of each is "
           "reported, so that load from other sessions on this shared machine falls on all of them "
           "alike. Differences of 1 ulp in link angles come from the baseline's round trip "
           "`np.angle(np.exp(1j*θ))`, which perturbs angles that were already in (−π, π].", ""]
    summary = {}
    for name in EXAMPLES:
        mech = velplan.load(name)
        out += [f"### {name}", "", "cProfile of the baseline, top functions by own time (ms):", ""]
        out += [table(["function", "calls", "own", "cumulative"], cprofile_top(mech, phi)), ""]
        ph = [phase_times(mech, phi) for _ in range(3)]
        tot = [sum(t for _, t in p) for p in ph]
        mid = ph[int(np.argsort(tot)[1])]
        total = sum(t for _, t in mid)
        out += ["Phases of the baseline (a clock between its phases; the median of 3 runs):", ""]
        out += [table(["phase", "ms", "share"], [[k, ms(t), f"{t / total:.0%}"] for k, t in mid]
                      + [["**total**", ms(total), "100%"]]), ""]
        rows, us_pos = variants(mech, phi)
        out += ["Suggested changes, cumulative (A, then A+B, …), speed-ups against the baseline:", ""]
        out += [table(["variant", "µs/pos at 10⁶, median", "min", "speed-up (medians)", "(minima)",
                       "ms per call at n=12, median", "speed-up", "max |Δ| vs solve"], rows), ""]
        tf, tw, nb = output_floor(mech, phi)
        out += [f"Floor: writing the {nb / 1e6:.0f} MB that `Kinematics` holds at 10⁶ positions takes "
                f"{ms(tf)} ms into fresh memory (page faults included) and {ms(tw)} ms into memory "
                f"already mapped, i.e. {tf / N * 1e6:.3f} µs/position before any arithmetic "
                f"(target {TARGET_US[name]} µs).", ""]
        summary[name] = (us_pos, tf / N * 1e6)
    kin = velplan.solve(velplan.load("four-bar"), phi[:1000], epsilon1=0.0)
    P, V, A, TH, OM, EP = fused_fourbar(phi[:1000], chunk=256)
    chk = max(np.abs(P.T - (kin.positions[..., 0] + 1j * kin.positions[..., 1])).max(),
              np.abs(V.T - (kin.velocities[..., 0] + 1j * kin.velocities[..., 1])).max() / 10.0,
              np.abs(A.T - (kin.accelerations[..., 0] + 1j * kin.accelerations[..., 1])).max() / 10.0**2,
              np.abs(np.angle(np.exp(1j * (TH.T - kin.angles)))).max())
    (t1, t1min), (t2, t2min) = _round_robin([lambda: fused_fourbar(phi, 8192, 1),
                                              lambda: fused_fourbar(phi, 16384, 2)], ROUNDS)
    out += ["### What numpy can reach on the four-bar", "",
            "A hand-fused numpy four-bar (`fused_fourbar`: the same outputs, real Cramer's rule, blocks "
            f"written into point-major buffers; max scaled |Δ| vs `velplan.solve` {chk:.1e}): "
            f"**{t1 / N * 1e6:.3f} µs/position** on one thread (blocks of 8192; min {t1min / N * 1e6:.3f}), "
            f"**{t2 / N * 1e6:.3f} µs/position** on two (blocks of 16384; min {t2min / N * 1e6:.3f}).", ""]
    out += ["### Conclusions", ""]
    for name, (u, floor) in summary.items():
        (b, bmin), (c, cmin), (d, dmin), (w, wmin) = u[0], u[3], u[4], u[5]
        out.append(f"- **{name}**: the baseline takes {b:.2f} µs/position (median; min {bmin:.2f}) against a "
                   f"target of {TARGET_US[name]} µs ({b / TARGET_US[name]:.0f}× over). Changes A–C, all inside "
                   f"`solver.py`, bring it to {c:.2f} µs (min {cmin:.2f}; {b / c:.1f}× by medians, "
                   f"{bmin / cmin:.1f}× by minima), still {cmin / TARGET_US[name]:.1f}× over at best; D (two "
                   f"threads) gives {d:.2f} µs (min {dmin:.2f}); the working tree's `velplan.solve` now "
                   f"takes {w:.2f} µs (min {wmin:.2f}). Merely writing the arrays `Kinematics` holds costs "
                   f"{floor:.3f} µs/position.")
    d_helps = all(u[4][1] < 0.85 * u[3][1] for u, _ in summary.values())
    out += ["- Where the baseline's time goes: `_pack` (≈ 60 %: the complex `np.stack` of every point followed "
            "by a second stack of real and imaginary parts, `isfinite(...).all(axis=(1, 2))` on the "
            "(n, P, 2) arrays, and the `np.angle(np.exp(1j*θ))` round trip on every link angle), then "
            "`np.exp(1j*θ)` for the crank and for every link point (~50–80 ms each at 10⁶), then the "
            "group arithmetic itself (~20–25 %).",
            "- Apply in this order: **A** (`_pack` returning transposed views of point-major (P, n) "
            "complex arrays — the (n, P, 2) shape and every index stay the same, `kin.position(name)` "
            "becomes a contiguous slice; only `reshape` of the whole array would copy), **B** (carry "
            "e^{iθ} per link: the crank's from cos/sin, a link point reuses its link's; RRR and RRP "
            "already have it as r/l), **C** (an inner loop over blocks of ~16k angles writing into "
            "preallocated outputs: temporaries stay in L2 instead of streaming 16 MB arrays). "
            + ("**D** (two threads over the blocks) helped here by minima; it needs the blocks to be "
               "independent, which they are." if d_helps else
               "**D** (two threads over the blocks) gave no consistent gain while other sessions loaded "
               "this 2-core machine; re-measure on a quiet one before adopting it."),
            f"- The targets (0.1 µs four-bar, 0.2 µs shaper at 10⁶, everything materialised) are out of "
            f"reach of numpy on this machine: the hand-fused four-bar reaches {min(t1min, t2min) / N * 1e6:.2f} µs "
            "at best, and the output bytes alone take most of the budget. Reaching them needs one of: "
            "computing only what is asked (e.g. `solve(..., points=[...])`, or velocities/accelerations "
            "on first access), a compiled kernel (an optional numba path, as pylinkage does), or "
            "targets restated at what A–C reach here: "
            + ", ".join(f"{k} ≈ {u[3][0]:.2f} µs (median)" for k, (u, _) in summary.items()) + ".", ""]
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    print(run())
