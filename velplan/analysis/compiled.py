"""The optional compiled engine: the closed forms of `velplan.analysis.groups`, run position by
position by numba (``pip install velplan[fast]``), in parallel, in one pass over the outputs.

The mechanism is encoded as a small program — one row per crank, group and link point, each
an opcode, register slots and real parameters — and a single kernel interprets that program
at every crank angle. The kernel is compiled once per machine (≈ 20 s) and cached on disk by
numba; a new process loads it in well under a second. The kernel calls the very functions the numpy
engine calls on whole arrays (`groups.rrr`, `groups.rrp`, …), compiled for scalars, so the two
engines share every formula; only the bookkeeping differs.
"""

from __future__ import annotations

import hashlib
import importlib.util
import inspect
import types
from functools import lru_cache

import numpy as np

from velplan.analysis import groups as G
from velplan.errors import VelplanError
from velplan.mechanism.model import GROUND, PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Mechanism
from velplan.mechanism.structure import schedule


CRANK, POINT, OP_RRR, OP_RRP, OP_RPR, OP_PRP, OP_RPP = range(7)
NI, NF = 13, 4
"""Integer slots and real parameters per program row (unused ones are −1 / 0)."""
CHUNK = 256
"""Crank angles one thread solves at a time (its slices of the outputs stay in the CPU's caches)."""
CORES = ("cross", "solve2", "cis", "wrap_angle", "carry", "crank_tip", "link_point", "guide_line", "sqrt_clamped", "rrr", "rrp", "rpr", "prp", "rpp")


@lru_cache(maxsize=1)
def available() -> bool:
    """True when numba (an optional dependency, imported only when the engine runs) is installed."""
    try:
        return importlib.util.find_spec("numba") is not None
    except (ImportError, ValueError):  # e.g. blocked with sys.modules["numba"] = None
        return False


def encode(mech: Mechanism, points: list[str], links: list[str], slides: list[str], groups: list[str],
           length_scale: float, items: tuple | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The program of ``mech`` for the output order given: (ops (m, NI) int64, params (m, NF)
    float64, ground point coordinates (complex, in register order)).

    Link registers are the output links in order, then the frame; point registers follow
    ``points``, whose first entries are the ground points.
    """
    ops, pars = _program(mech, points, links, slides, groups, length_scale, items)
    ground = np.array([complex(x, y) for _, (x, y) in mech.ground])
    return np.array(ops, dtype=np.int64).reshape(-1, NI), np.array(pars, dtype=float).reshape(-1, NF), ground


def encode_design(mech: Mechanism, V: int, points: list[str], links: list[str], slides: list[str],
                  groups: list[str], length_scale, items: tuple | None = None):
    """`encode` for V variants: ``mech``'s numbers (and ``length_scale``) may be (V,) arrays
    (`velplan.analysis.design`). Returns ops (m, NI), params (V, m, NF), ground (V, Pg)."""
    ops, pars = _program(mech, points, links, slides, groups, length_scale, items)
    par = np.empty((V, len(pars), NF))
    for k, row in enumerate(pars):
        for j, x in enumerate(row):
            par[:, k, j] = x
    ground = np.empty((V, len(mech.ground)), dtype=complex)
    for j, (_, (x, y)) in enumerate(mech.ground):
        ground[:, j] = np.asarray(x, float) + 1j * np.asarray(y, float)
    return np.array(ops, dtype=np.int64).reshape(-1, NI), par, ground


def _program(mech, points, links, slides, groups, length_scale, items) -> tuple[list, list]:
    """Rows of the program: opcodes with register slots, and real parameters (floats, or
    arrays over variants)."""
    P = {k: i for i, k in enumerate(points)}
    L = {k: i for i, k in enumerate(links)}
    L[GROUND] = len(links)
    S = {k: i for i, k in enumerate(slides)}
    Gi = {k: i for i, k in enumerate(groups)}
    origin: dict[str, str] = {GROUND: mech.ground[0][0]}
    ops, pars = [], []

    def row(op, ints, reals=()):
        ops.append([op, *ints] + [-1] * (NI - 1 - len(ints)))
        pars.append([*reals] + [0.0] * (NF - len(reals)))

    def opt(name):
        return P[name] if name else -1

    for item in schedule(mech) if items is None else items:
        if isinstance(item, Crank):
            origin[item.link] = item.pivot
            row(CRANK, [P[item.pivot], P[item.tip], L[item.link]], [item.length])
        elif isinstance(item, LinkPoint):
            row(POINT, [L[item.link], P[origin[item.link]], P[item.name]], [item.along, item.offset])
        elif isinstance(item, RRR):
            origin.update(zip(item.links, item.joints))
            row(OP_RRR, [P[item.joints[0]], P[item.joints[1]], P[item.point], L[item.links[0]],
                         L[item.links[1]], Gi[item.name]], [*item.lengths, item.branch])
        elif isinstance(item, RRP):
            rod, slider = item.links
            origin.update({rod: item.joint, slider: item.point})
            g = item.guide
            row(OP_RRP, [P[item.joint], P[g.through], L[g.link], P[item.point], opt(item.coincident),
                         L[rod], L[slider], S[G.slide_name(slider, g.link)], Gi[item.name]],
                [g.angle, g.offset, item.length, item.branch])
        elif isinstance(item, RPR):
            block, bar = item.links
            origin.update({block: item.joint, bar: item.pivot})
            row(OP_RPR, [P[item.joint], P[item.pivot], opt(item.coincident), L[block], L[bar],
                         S[G.slide_name(block, bar)], Gi[item.name]], [item.offset, item.branch, length_scale])
        elif isinstance(item, PRP):
            m1, m2 = item.links
            origin.update({m1: item.point, m2: item.point})
            g1, g2 = item.guides
            row(OP_PRP, [P[g1.through], L[g1.link], P[g2.through], L[g2.link], P[item.point],
                         opt(item.coincident[0]), opt(item.coincident[1]), L[m1], L[m2],
                         S[G.slide_name(m1, g1.link)], S[G.slide_name(m2, g2.link)], Gi[item.name]],
                [g1.angle, g1.offset, g2.angle, g2.offset])
        elif isinstance(item, RPP):
            block, runner = item.links
            origin.update({block: item.joint, runner: item.origin_name})
            g = item.guide
            row(OP_RPP, [P[item.joint], P[g.through], L[g.link], opt(item.coincident), P[item.origin_name],
                         L[block], L[runner], S[G.slide_name(block, runner)], S[G.slide_name(runner, g.link)],
                         Gi[item.name]], [g.angle, g.offset, item.slot_angle])
        else:  # pragma: no cover - the model has no other kinds
            raise TypeError(f"no compiled form for {type(item).__name__}")
    return ops, pars


def _kernel(ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid):  # noqa: C901 - one switch
    """Interpret the program at every angle of ``phi``; write Z (3, P, n) positions, velocities,
    accelerations; R (3, L, n) angles, ω, ε; S (S, 3, n) slides; C (G, n) conditions (NaN where
    a group does not close) and ``valid`` (n,).

    The angles are V variants × ``nper`` angles (variant-major); variant v has the parameters
    ``par[v]`` (m, NF), ground points ``ground[v]`` and crank rates ``w1s[v]``, ``e1s[v]``.
    Each thread takes a chunk of one variant's angles and runs the program over it one row at
    a time; the chunk's slices of the outputs are its registers (the frame, link L, reads as
    zeros).
    """
    nP, nL, nS, nG = Z.shape[1], R.shape[1], S.shape[0], C.shape[0]
    per = (nper + CHUNK - 1) // CHUNK  # chunks per variant
    for unit in prange(par.shape[0] * per):
        vi = unit // per
        i0 = vi * nper + (unit - vi * per) * CHUNK
        i1 = min(vi * nper + nper, i0 + CHUNK)
        m = i1 - i0
        w1, e1 = w1s[vi], e1s[vi]
        zero = np.zeros(m)
        p, v, a = Z[0, :, i0:i1], Z[1, :, i0:i1], Z[2, :, i0:i1]
        th, om, ep = R[0, :, i0:i1], R[1, :, i0:i1], R[2, :, i0:i1]
        cn = C[:, i0:i1]
        for j in range(ground.shape[1]):
            for t in range(m):
                p[j, t], v[j, t], a[j, t] = ground[vi, j], 0.0, 0.0
        for k in range(ops.shape[0]):
            o = ops[k]
            f = par[vi, k]
            op = o[0]
            if op == CRANK:
                q, x, lk = o[1], o[2], o[3]
                for t in range(m):
                    p[x, t], v[x, t], a[x, t] = crank_tip(p[q, t], f[0], phi[i0 + t], w1, e1)
                    th[lk, t], om[lk, t], ep[lk, t] = phi[i0 + t], w1, e1
            elif op == POINT:
                lk, q, x = o[1], o[2], o[3]
                lt, lw, le = (th[lk], om[lk], ep[lk]) if lk < nL else (zero, zero, zero)
                for t in range(m):
                    p[x, t], v[x, t], a[x, t] = link_point(p[q, t], v[q, t], a[q, t], lt[t], lw[t], le[t], f[0], f[1])
            elif op == OP_RRR:
                A, D, x, l1, l2, g = o[1], o[2], o[3], o[4], o[5], o[6]
                for t in range(m):
                    c, cv, ca, t1, w_1, e_1, t2, w_2, e_2, cond, closed = rrr(
                        p[A, t], v[A, t], a[A, t], p[D, t], v[D, t], a[D, t], f[0], f[1], f[2])
                    p[x, t], v[x, t], a[x, t] = c, cv, ca
                    th[l1, t], om[l1, t], ep[l1, t] = t1, w_1, e_1
                    th[l2, t], om[l2, t], ep[l2, t] = t2, w_2, e_2
                    cn[g, t] = cond if closed else np.nan
            elif op == OP_RRP:
                A, Q, gl, x, xc, rod, sld, s_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9]
                gt, gw, ge = (th[gl], om[gl], ep[gl]) if gl < nL else (zero, zero, zero)
                for t in range(m):
                    c, cv, ca, gv, ga, tr, wr, er, s, sd, sdd, cond, closed = rrp(
                        p[A, t], v[A, t], a[A, t], p[Q, t], v[Q, t], a[Q, t], gt[t], gw[t], ge[t],
                        f[0], f[1], f[2], f[3])
                    p[x, t], v[x, t], a[x, t] = c, cv, ca
                    if xc >= 0:
                        p[xc, t], v[xc, t], a[xc, t] = c, gv, ga
                    th[rod, t], om[rod, t], ep[rod, t] = tr, wr, er
                    th[sld, t], om[sld, t], ep[sld, t] = gt[t] + f[0], gw[t], ge[t]
                    S[s_, 0, i0 + t], S[s_, 1, i0 + t], S[s_, 2, i0 + t] = s, sd, sdd
                    cn[g, t] = cond if closed else np.nan
            elif op == OP_RPR:
                A, Q, xc, blk, bar, s_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7]
                for t in range(m):
                    tt, w, e, s, sd, sdd, bv, ba, cond, closed = rpr(
                        p[A, t], v[A, t], a[A, t], p[Q, t], v[Q, t], a[Q, t], f[0], f[1], f[2])
                    if xc >= 0:
                        p[xc, t], v[xc, t], a[xc, t] = p[A, t], bv, ba
                    th[blk, t], om[blk, t], ep[blk, t] = tt, w, e
                    th[bar, t], om[bar, t], ep[bar, t] = tt, w, e
                    S[s_, 0, i0 + t], S[s_, 1, i0 + t], S[s_, 2, i0 + t] = s, sd, sdd
                    cn[g, t] = cond if closed else np.nan
            elif op == OP_PRP:
                Q1, g1, Q2, g2, x, xc1, xc2 = o[1], o[2], o[3], o[4], o[5], o[6], o[7]
                m1, m2, s1_, s2_, g = o[8], o[9], o[10], o[11], o[12]
                t1, w_1, e_1 = (th[g1], om[g1], ep[g1]) if g1 < nL else (zero, zero, zero)
                t2, w_2, e_2 = (th[g2], om[g2], ep[g2]) if g2 < nL else (zero, zero, zero)
                for t in range(m):
                    c, cv, ca, c1v, c1a, c2v, c2a, s1, sd1, sdd1, s2, sd2, sdd2, cond, closed = prp(
                        p[Q1, t], v[Q1, t], a[Q1, t], t1[t], w_1[t], e_1[t], f[0], f[1],
                        p[Q2, t], v[Q2, t], a[Q2, t], t2[t], w_2[t], e_2[t], f[2], f[3])
                    p[x, t], v[x, t], a[x, t] = c, cv, ca
                    if xc1 >= 0:
                        p[xc1, t], v[xc1, t], a[xc1, t] = c, c1v, c1a
                    if xc2 >= 0:
                        p[xc2, t], v[xc2, t], a[xc2, t] = c, c2v, c2a
                    th[m1, t], om[m1, t], ep[m1, t] = t1[t] + f[0], w_1[t], e_1[t]
                    th[m2, t], om[m2, t], ep[m2, t] = t2[t] + f[2], w_2[t], e_2[t]
                    S[s1_, 0, i0 + t], S[s1_, 1, i0 + t], S[s1_, 2, i0 + t] = s1, sd1, sdd1
                    S[s2_, 0, i0 + t], S[s2_, 1, i0 + t], S[s2_, 2, i0 + t] = s2, sd2, sdd2
                    cn[g, t] = cond if closed else np.nan
            else:  # OP_RPP
                B, Q, gl, xc, xk, blk, run, sb_, sr_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10]
                gt, gw, ge = (th[gl], om[gl], ep[gl]) if gl < nL else (zero, zero, zero)
                sine = abs(np.sin(f[2]))
                for t in range(m):
                    k_, kv, ka, bv, ba, s, sd, sdd, u, ud, udd, closed = rpp(
                        p[B, t], v[B, t], a[B, t], p[Q, t], v[Q, t], a[Q, t], gt[t], gw[t], ge[t],
                        f[0], f[1], f[2])
                    if xc >= 0:
                        p[xc, t], v[xc, t], a[xc, t] = p[B, t], bv, ba
                    p[xk, t], v[xk, t], a[xk, t] = k_, kv, ka
                    theta = gt[t] + f[0]
                    th[blk, t], om[blk, t], ep[blk, t] = theta + f[2], gw[t], ge[t]
                    th[run, t], om[run, t], ep[run, t] = theta, gw[t], ge[t]
                    S[sb_, 0, i0 + t], S[sb_, 1, i0 + t], S[sb_, 2, i0 + t] = u, ud, udd
                    S[sr_, 0, i0 + t], S[sr_, 1, i0 + t], S[sr_, 2, i0 + t] = s, sd, sdd
                    cn[g, t] = sine if closed else np.nan
        for t in range(m):
            ok = True
            for j in range(nP):
                ok = ok and np.isfinite(p[j, t]) and np.isfinite(v[j, t]) and np.isfinite(a[j, t])
            for j in range(nL):
                th[j, t] = wrap_angle(th[j, t])
                ok = ok and np.isfinite(om[j, t]) and np.isfinite(ep[j, t])
            for j in range(nG):
                ok = ok and cn[j, t] > 0
            valid[i0 + t] = ok


SERIAL = 4096
"""Up to this many angles a call runs on the calling thread alone: waking the other threads
costs more than they save (milliseconds on a busy machine)."""

_PREPARED: dict = {}
"""Programs by mechanism content (`prepared`), the latest few."""


def prepared(mech: Mechanism, items: tuple, length_scale: float, layout) -> tuple:
    """(state, conditions, ops, params (1, m, NF), ground (1, Pg)) of ``mech``: ``layout()``
    (the numpy engine on one angle: the outputs' names and order) and `encode`, memoised by
    the mechanism's numbers and names, so that a repeated call costs only its kernel."""
    key = (mech.ground, mech.crank, mech.groups, mech.points, items, length_scale)
    hit = _PREPARED.get(key)
    if hit is None:
        st, conditions = layout()
        names, links = list(st.points), [k for k in st.links if k != GROUND]
        ops, par, ground = encode(mech, names, links, list(st.slides), list(conditions), length_scale, items)
        hit = (st, conditions, ops, par[None], ground[None])
        if len(_PREPARED) >= 32:
            _PREPARED.pop(next(iter(_PREPARED)))
        _PREPARED[key] = hit
    return hit


def run(ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid) -> None:
    """Call the kernel (`_kernel`'s arguments): on one thread up to `SERIAL` angles."""
    k = kernel()
    if phi.shape[0] > SERIAL:
        k(ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid)
        return
    import numba

    before = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        k(ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid)
    finally:
        numba.set_num_threads(before)


def loaded() -> bool:
    """True once the kernel is loaded (or compiled) in this process."""
    return kernel.cache_info().currsize > 0


@lru_cache(maxsize=1)
def kernel():
    """The compiled kernel: loaded from numba's disk cache, or compiled on its first call."""
    if not available():
        raise VelplanError("the compiled engine needs numba: pip install numba (in a checkout: pip install '.[fast]')")
    import numba
    env = {"__name__": __name__, "np": np, "prange": numba.prange, "CHUNK": CHUNK, "CRANK": CRANK, "POINT": POINT,
           "OP_RRR": OP_RRR, "OP_RRP": OP_RRP, "OP_RPR": OP_RPR, "OP_PRP": OP_PRP}

    def jit(f, qualname=None, **kw):  # the same code object, its globals resolved to compiled functions
        g = types.FunctionType(f.__code__, env, f.__name__)
        g.__qualname__ = qualname or f.__qualname__
        return numba.njit(error_model="numpy", **kw)(g)

    for name in CORES:
        env[name] = jit(getattr(G, name))
    # compiled once per machine: numba caches the kernel on disk under a name that changes
    # whenever the source of the kernel or of any closed form (or numba) changes
    return jit(_kernel, f"_kernel_{fingerprint()}", parallel=True, nogil=True, cache=True)


def fingerprint() -> str:
    """A digest of the source the kernel is compiled from, and of the numba version."""
    from numba import __version__

    h = hashlib.sha256(__version__.encode())
    for f in [_kernel, *(getattr(G, name) for name in CORES)]:
        h.update(inspect.getsource(f).encode())
    return h.hexdigest()[:16]
