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
CHUNK = 2048
"""Crank angles one thread solves in a row (its registers stay in the L1 cache)."""
CORES = ("cross", "solve2", "cis", "carry", "guide_line", "sqrt_clamped", "rrr", "rrp", "rpr", "prp", "rpp")


@lru_cache(maxsize=1)
def available() -> bool:
    """True when numba (an optional dependency, imported only when the engine runs) is installed."""
    try:
        return importlib.util.find_spec("numba") is not None
    except (ImportError, ValueError):  # e.g. blocked with sys.modules["numba"] = None
        return False


def encode(mech: Mechanism, points: list[str], links: list[str], slides: list[str], groups: list[str],
           length_scale: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The program of ``mech`` for the output order given: (ops (m, NI) int64, params (m, NF)
    float64, ground point coordinates (complex, in register order)).

    Link registers are the output links in order, then the frame; point registers follow
    ``points``, whose first entries are the ground points.
    """
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

    for item in schedule(mech):
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
    ground = np.array([complex(x, y) for _, (x, y) in mech.ground])
    return np.array(ops, dtype=np.int64).reshape(-1, NI), np.array(pars, dtype=float).reshape(-1, NF), ground


def _wrap(t):
    """An angle in (−π, π] (left as it is when it already is)."""
    if -np.pi < t <= np.pi:
        return t
    return np.arctan2(np.sin(t), np.cos(t))


def _kernel(ops, par, ground, phi, w1, e1, Z, R, S, C, valid):  # noqa: C901 - one switch
    """Interpret the program at every angle of ``phi``; write Z (3, P, n) positions, velocities,
    accelerations; R (3, L, n) angles, ω, ε; S (S, 3, n) slides; C (G, n) conditions (NaN where
    a group does not close) and ``valid`` (n,)."""
    n = phi.shape[0]
    nP, nL, nS, nG = Z.shape[1], R.shape[1], S.shape[0], C.shape[0]
    for chunk in prange((n + CHUNK - 1) // CHUNK):
        p = np.zeros(nP, dtype=np.complex128)
        v = np.zeros(nP, dtype=np.complex128)
        a = np.zeros(nP, dtype=np.complex128)
        th = np.zeros(nL + 1)
        om = np.zeros(nL + 1)
        ep = np.zeros(nL + 1)
        sl = np.zeros((nS, 3))
        cn = np.zeros(nG)
        for i in range(chunk * CHUNK, min(n, (chunk + 1) * CHUNK)):
            for j in range(ground.shape[0]):
                p[j] = ground[j]
            for k in range(ops.shape[0]):
                o = ops[k]
                f = par[k]
                op = o[0]
                if op == CRANK:
                    r = f[0] * cis(phi[i])
                    p[o[2]] = p[o[1]] + r
                    v[o[2]] = 1j * w1 * r
                    a[o[2]] = (1j * e1 - w1 * w1) * r
                    th[o[3]], om[o[3]], ep[o[3]] = phi[i], w1, e1
                elif op == POINT:
                    q, x = o[2], o[3]
                    z = p[q] + (f[0] + 1j * f[1]) * cis(th[o[1]])
                    p[x] = z
                    v[x], a[x] = carry(p[q], v[q], a[q], om[o[1]], ep[o[1]], z)
                elif op == OP_RRR:
                    A, D = o[1], o[2]
                    c, cv, ca, t1, w_1, e_1, t2, w_2, e_2, cond, closed = rrr(
                        p[A], v[A], a[A], p[D], v[D], a[D], f[0], f[1], f[2])
                    p[o[3]], v[o[3]], a[o[3]] = c, cv, ca
                    th[o[4]], om[o[4]], ep[o[4]] = t1, w_1, e_1
                    th[o[5]], om[o[5]], ep[o[5]] = t2, w_2, e_2
                    cn[o[6]] = cond if closed else np.nan
                elif op == OP_RRP:
                    A, Q, gl = o[1], o[2], o[3]
                    c, cv, ca, gv, ga, tr, wr, er, s, sd, sdd, cond, closed = rrp(
                        p[A], v[A], a[A], p[Q], v[Q], a[Q], th[gl], om[gl], ep[gl], f[0], f[1], f[2], f[3])
                    p[o[4]], v[o[4]], a[o[4]] = c, cv, ca
                    if o[5] >= 0:
                        p[o[5]], v[o[5]], a[o[5]] = c, gv, ga
                    th[o[6]], om[o[6]], ep[o[6]] = tr, wr, er
                    th[o[7]], om[o[7]], ep[o[7]] = th[gl] + f[0], om[gl], ep[gl]
                    sl[o[8], 0], sl[o[8], 1], sl[o[8], 2] = s, sd, sdd
                    cn[o[9]] = cond if closed else np.nan
                elif op == OP_RPR:
                    A, Q = o[1], o[2]
                    t, w, e, s, sd, sdd, bv, ba, cond, closed = rpr(
                        p[A], v[A], a[A], p[Q], v[Q], a[Q], f[0], f[1], f[2])
                    if o[3] >= 0:
                        p[o[3]], v[o[3]], a[o[3]] = p[A], bv, ba
                    th[o[4]], om[o[4]], ep[o[4]] = t, w, e
                    th[o[5]], om[o[5]], ep[o[5]] = t, w, e
                    sl[o[6], 0], sl[o[6], 1], sl[o[6], 2] = s, sd, sdd
                    cn[o[7]] = cond if closed else np.nan
                elif op == OP_PRP:
                    Q1, l1, Q2, l2 = o[1], o[2], o[3], o[4]
                    c, cv, ca, c1v, c1a, c2v, c2a, s1, sd1, sdd1, s2, sd2, sdd2, cond, closed = prp(
                        p[Q1], v[Q1], a[Q1], th[l1], om[l1], ep[l1], f[0], f[1],
                        p[Q2], v[Q2], a[Q2], th[l2], om[l2], ep[l2], f[2], f[3])
                    p[o[5]], v[o[5]], a[o[5]] = c, cv, ca
                    if o[6] >= 0:
                        p[o[6]], v[o[6]], a[o[6]] = c, c1v, c1a
                    if o[7] >= 0:
                        p[o[7]], v[o[7]], a[o[7]] = c, c2v, c2a
                    th[o[8]], om[o[8]], ep[o[8]] = th[l1] + f[0], om[l1], ep[l1]
                    th[o[9]], om[o[9]], ep[o[9]] = th[l2] + f[2], om[l2], ep[l2]
                    sl[o[10], 0], sl[o[10], 1], sl[o[10], 2] = s1, sd1, sdd1
                    sl[o[11], 0], sl[o[11], 1], sl[o[11], 2] = s2, sd2, sdd2
                    cn[o[12]] = cond if closed else np.nan
                else:  # OP_RPP
                    B, Q, gl = o[1], o[2], o[3]
                    k_, kv, ka, bv, ba, s, sd, sdd, t, td, tdd, closed = rpp(
                        p[B], v[B], a[B], p[Q], v[Q], a[Q], th[gl], om[gl], ep[gl], f[0], f[1], f[2])
                    if o[4] >= 0:
                        p[o[4]], v[o[4]], a[o[4]] = p[B], bv, ba
                    p[o[5]], v[o[5]], a[o[5]] = k_, kv, ka
                    theta = th[gl] + f[0]
                    th[o[6]], om[o[6]], ep[o[6]] = theta + f[2], om[gl], ep[gl]
                    th[o[7]], om[o[7]], ep[o[7]] = theta, om[gl], ep[gl]
                    sl[o[8], 0], sl[o[8], 1], sl[o[8], 2] = t, td, tdd
                    sl[o[9], 0], sl[o[9], 1], sl[o[9], 2] = s, sd, sdd
                    cn[o[10]] = abs(np.sin(f[2])) if closed else np.nan
            ok = True
            for j in range(nP):
                Z[0, j, i], Z[1, j, i], Z[2, j, i] = p[j], v[j], a[j]
                ok = ok and np.isfinite(p[j]) and np.isfinite(v[j]) and np.isfinite(a[j])
            for j in range(nL):
                R[0, j, i], R[1, j, i], R[2, j, i] = _wrap(th[j]), om[j], ep[j]
                ok = ok and np.isfinite(om[j]) and np.isfinite(ep[j])
            for j in range(nS):
                S[j, 0, i], S[j, 1, i], S[j, 2, i] = sl[j, 0], sl[j, 1], sl[j, 2]
            for j in range(nG):
                C[j, i] = cn[j]
                ok = ok and cn[j] > 0
            valid[i] = ok


@lru_cache(maxsize=1)
def kernel():
    """The compiled kernel: loaded from numba's disk cache, or compiled on its first call."""
    if not available():
        raise VelplanError("the compiled engine needs numba: pip install 'velplan[fast]'")
    import numba
    env = {"__name__": __name__, "np": np, "prange": numba.prange, "CHUNK": CHUNK, "CRANK": CRANK, "POINT": POINT,
           "OP_RRR": OP_RRR, "OP_RRP": OP_RRP, "OP_RPR": OP_RPR, "OP_PRP": OP_PRP}

    def jit(f, qualname=None, **kw):  # the same code object, its globals resolved to compiled functions
        g = types.FunctionType(f.__code__, env, f.__name__)
        g.__qualname__ = qualname or f.__qualname__
        return numba.njit(error_model="numpy", **kw)(g)

    for name in CORES:
        env[name] = jit(getattr(G, name))
    env["_wrap"] = jit(_wrap)
    # compiled once per machine: numba caches the kernel on disk under a name that changes
    # whenever the source of the kernel or of any closed form (or numba) changes
    return jit(_kernel, f"_kernel_{fingerprint()}", parallel=True, nogil=True, cache=True)


def fingerprint() -> str:
    """A digest of the source the kernel is compiled from, and of the numba version."""
    from numba import __version__

    h = hashlib.sha256(__version__.encode())
    for f in [_kernel, _wrap, *(getattr(G, name) for name in CORES)]:
        h.update(inspect.getsource(f).encode())
    return h.hexdigest()[:16]
