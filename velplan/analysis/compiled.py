"""The optional compiled engine: the closed forms of `velplan.analysis.groups`, run position by
position by numba (``pip install velplan[fast]``), on several threads, in one pass over the outputs.

The mechanism is encoded as a small program — one row per crank, group and link point, each
an opcode, register slots and real parameters — and a kernel interprets that program at every
crank angle. A class III group's row starts from its branch over the turn, tracked once by the
numpy engine and given per angle (``aux``, `triad_aux`); an angle it finds ambiguous is solved
again by numpy. Each kind of row (crank, link point, RRR, RRP, RPR, PRP, RPP, triad) has its own small
function, compiled and cached on disk by numba on its own; the interpreter links them (all
compiled in ≈ 10 s, once per machine). A new process loads the interpreter's machine code
without numba's start-up of its whole compiler (`_load_cached`: ≈ 0.05 s, against ≈ 0.4 s for
numba's own loading). The row functions call the very functions the numpy engine calls on whole
arrays (`groups.rrr`, `groups.rrp`, …), compiled for scalars, so the two engines share every
formula; only the bookkeeping differs. Derivatives above the ``order`` asked for are neither
allocated nor written.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
import threading
import types
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from velplan.analysis import groups as G
from velplan.analysis import triad_rows as T
from velplan.analysis import blocks
from velplan.analysis.kinematics import SINGULAR_BOUND, Kinematics, length_scale
from velplan.errors import VelplanError
from velplan.mechanism.model import GROUND, PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Mechanism, Triad, kind_entry
from velplan.mechanism.structure import schedule


CRANK, POINT, OP_RRR, OP_RRP, OP_RPR, OP_PRP, OP_RPP, OP_TRIAD = range(8)
KINDS = ("crank", "point", "rrr", "rrp", "rpr", "prp", "rpp", "triad")
"""The opcodes' names, in opcode order: the row function of kind ``x`` is ``_x_rows``."""
NI, NF = 26, 17
"""Integer slots and real parameters per program row (unused ones are −1 / 0)."""
CHUNK = 256
"""Crank angles one thread solves at a time (its slices of the outputs stay in the CPU's caches)."""
CORES = ("cross", "solve2", "cis", "direction", "wrap_angle", "carry", "crank_tip", "link_point", "guide_line",
         "sqrt_clamped", "rrr", "rrp", "rpr", "prp", "rpp")
TRIAD_CORES = ("tdot", "tcross", "cramer3", "condition3", "closure_row", "unit", "distance", "triad_newton",
               "lead_velocity_row", "lead_acceleration_rhs", "rod_link", "special_point", "triad_at")
"""The class III group's scalar formulas (`velplan.analysis.triad_rows`), compiled in this order."""
ROUND_OFF = 64 * float(np.finfo(float).eps)
"""The factor of `velplan.analysis.kinematics.velocity_bound`: 64·ε."""


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
        else:
            op, ints, reals = kind_entry(_ROWS, item, "velplan.analysis.compiled._ROWS")(item, P, L, S, Gi, opt, origin,
                                                                                   length_scale)
            row(op, ints, reals)
    return ops, pars


# Each group kind's program row: (opcode, register slots, reals); it records its links' origins.
def _row_rrr(item, P, L, S, Gi, opt, origin, scale):
    origin.update(zip(item.links, item.joints))
    return OP_RRR, [P[item.joints[0]], P[item.joints[1]], P[item.point], L[item.links[0]],
                    L[item.links[1]], Gi[item.name]], [*item.lengths, item.branch]


def _row_rrp(item, P, L, S, Gi, opt, origin, scale):
    rod, slider = item.links
    origin.update({rod: item.joint, slider: item.point})
    g = item.guide
    return OP_RRP, [P[item.joint], P[g.through], L[g.link], P[item.point], opt(item.coincident),
                    L[rod], L[slider], S[G.slide_name(slider, g.link)], Gi[item.name]], \
        [g.angle, g.offset, item.length, item.branch]


def _row_rpr(item, P, L, S, Gi, opt, origin, scale):
    block, bar = item.links
    origin.update({block: item.joint, bar: item.pivot})
    return OP_RPR, [P[item.joint], P[item.pivot], opt(item.coincident), L[block], L[bar],
                    S[G.slide_name(block, bar)], Gi[item.name]], [item.offset, item.branch, scale]


def _row_prp(item, P, L, S, Gi, opt, origin, scale):
    m1, m2 = item.links
    origin.update({m1: item.point, m2: item.point})
    g1, g2 = item.guides
    return OP_PRP, [P[g1.through], L[g1.link], P[g2.through], L[g2.link], P[item.point],
                    opt(item.coincident[0]), opt(item.coincident[1]), L[m1], L[m2],
                    S[G.slide_name(m1, g1.link)], S[G.slide_name(m2, g2.link)], Gi[item.name]], \
        [g1.angle, g1.offset, g2.angle, g2.offset]


def _row_rpp(item, P, L, S, Gi, opt, origin, scale):
    block, runner = item.links
    origin.update({block: item.joint, runner: item.origin_name})
    g = item.guide
    return OP_RPP, [P[item.joint], P[g.through], L[g.link], opt(item.coincident), P[item.origin_name],
                    L[block], L[runner], S[G.slide_name(block, runner)], S[G.slide_name(runner, g.link)],
                    Gi[item.name]], [g.angle, g.offset, item.slot_angle]


def _row_triad(item, P, L, S, Gi, opt, origin, scale):
    """A class III group: its leads' known points, guide links (−1: a rod), joints, links,
    coincident points, special point and slides; reals: the joints' offsets from the first rod
    lead's inner joint, the rods' lengths, the guides' angles and offsets, the group's size and
    the length scale. The special point's pair (slots 23, 24) is set by `_layout` from the track."""
    from velplan.analysis import triad

    origin[item.base] = item.joints[0]
    local = item.local()
    ref = next(i for i, lead in enumerate(item.leads) if not lead.slider)
    rel = [z - local[ref] for z in local]
    ints, guides, slides, coinc = [], [], [], []
    for lead in item.leads:
        ints.append(P[lead.guide.through] if lead.slider else P[lead.joint])
        guides.append(L[lead.guide.link] if lead.slider else -1)
        slides.append(S[G.slide_name(lead.link, lead.guide.link)] if lead.slider else -1)
        coinc.append(opt(lead.coincident) if lead.slider else -1)
    for lead, name in zip(item.leads, item.joints):
        origin[lead.link] = name if lead.slider else lead.joint
    reals = [c for z in rel for c in (z.real, z.imag)]
    reals += [0.0 if lead.slider else lead.length for lead in item.leads]
    reals += [lead.guide.angle if lead.slider else 0.0 for lead in item.leads]
    reals += [lead.guide.offset if lead.slider else 0.0 for lead in item.leads]
    return OP_TRIAD, [*ints, *guides, *(P[j] for j in item.joints), L[item.base], *(L[lead.link] for lead in item.leads),
                      *coinc, P[item.special_name], *slides, Gi[item.name], -1, -1, -1, ref], \
        [*reals, triad._size(item), scale]


#: The compiled engine's lookup by group kind (a `tracked` kind, the triad, needs its branch
#: over the turn: `_layout` sends it to the numpy engine when none is given).
_ROWS = {RRR: _row_rrr, RRP: _row_rrp, RPR: _row_rpr, PRP: _row_prp, RPP: _row_rpp, Triad: _row_triad}

# ---- the kernel ------------------------------------------------------------------------------
# Each kind of program row has its own function over the angles i0 … i0+m−1 of a chunk, all with
# the same arguments: the row's slots ``o`` and reals ``f``; the chunk (i0, m); the angles, the
# crank's ω and ε; the chunk's registers — points p, v, a (P, m) complex, links θ, ω, ε (L, m)
# (the frame, link L, reads as ``zero``) —, the slides S (S, k, n), the conditions cn (G, m)
# (NaN where a group does not close); and k, the derivatives kept (order + 1): above it the
# registers alias lower ones, so nothing above order k − 1 is written (positions never depend
# on velocities, nor velocities on accelerations). Their free names (put, rrr, crank_rows, …)
# are the compiled functions of `_env` and `kernel`.


def _put(p, v, a, x, t, k, c, cv, ca):
    """Point x at angle t of the chunk: its position, and its velocity and acceleration if kept."""
    p[x, t] = c
    if k > 1:
        v[x, t] = cv
    if k > 2:
        a[x, t] = ca


def _turn(th, om, ep, x, t, k, theta, w, e):
    """Link x at angle t of the chunk: its angle (rad), and ω, ε if kept."""
    th[x, t] = theta
    if k > 1:
        om[x, t] = w
    if k > 2:
        ep[x, t] = e


def _glide(S, x, i, k, s, sd, sdd):
    """Slide x at angle i: s (m), and ṡ, s̈ if kept."""
    S[x, 0, i] = s
    if k > 1:
        S[x, 1, i] = sd
    if k > 2:
        S[x, 2, i] = sdd


def _link(th, om, ep, lk, zero):
    """The chunk's rows θ, ω, ε of link lk; the frame (lk = L) reads as zeros."""
    if lk < th.shape[0]:
        return th[lk], om[lk], ep[lk]
    return zero, zero, zero


def _crank_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """The crank: its tip, and its link at the angle φ, ω1, ε1."""
    q, x, lk = o[1], o[2], o[3]
    for t in range(m):
        c, cv, ca = crank_tip(p[q, t], f[0], phi[i0 + t], w1, e1)
        put(p, v, a, x, t, k, c, cv, ca)
        turn(th, om, ep, lk, t, k, phi[i0 + t], w1, e1)


def _point_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """A point of a link, ``f[0]`` along its reference direction from its origin and ``f[1]`` to its left."""
    lk, q, x = o[1], o[2], o[3]
    lt, lw, le = link(th, om, ep, lk, zero)
    for t in range(m):
        c, cv, ca = link_point(p[q, t], v[q, t], a[q, t], lt[t], lw[t], le[t], f[0], f[1])
        put(p, v, a, x, t, k, c, cv, ca)


def _rrr_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """An RRR group on the joints o[1], o[2]: its middle joint and its two links."""
    A, D, x, l1, l2, g = o[1], o[2], o[3], o[4], o[5], o[6]
    for t in range(m):
        c, cv, ca, t1, w_1, e_1, t2, w_2, e_2, cond, closed = rrr(
            p[A, t], v[A, t], a[A, t], p[D, t], v[D, t], a[D, t], f[0], f[1], f[2])
        put(p, v, a, x, t, k, c, cv, ca)
        turn(th, om, ep, l1, t, k, t1, w_1, e_1)
        turn(th, om, ep, l2, t, k, t2, w_2, e_2)
        cn[g, t] = cond if closed else np.nan


def _rrp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """An RRP group: the slider on a guide of link o[3], the rod, the slide."""
    A, Q, gl, x, xc, rod, sld, s_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9]
    gt, gw, ge = link(th, om, ep, gl, zero)
    for t in range(m):
        c, cv, ca, gv, ga, tr, wr, er, s, sd, sdd, cond, closed = rrp(
            p[A, t], v[A, t], a[A, t], p[Q, t], v[Q, t], a[Q, t], gt[t], gw[t], ge[t], f[0], f[1], f[2], f[3])
        put(p, v, a, x, t, k, c, cv, ca)
        if xc >= 0:
            put(p, v, a, xc, t, k, c, gv, ga)
        turn(th, om, ep, rod, t, k, tr, wr, er)
        turn(th, om, ep, sld, t, k, gt[t] + f[0], gw[t], ge[t])
        glide(S, s_, i0 + t, k, s, sd, sdd)
        cn[g, t] = cond if closed else np.nan


def _rpr_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """An RPR group: the block on the bar through the pivot o[2], turning with it; the slide."""
    A, Q, xc, blk, bar, s_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7]
    for t in range(m):
        tt, w, e, s, sd, sdd, bv, ba, cond, closed = rpr(
            p[A, t], v[A, t], a[A, t], p[Q, t], v[Q, t], a[Q, t], f[0], f[1], f[2])
        if xc >= 0:
            put(p, v, a, xc, t, k, p[A, t], bv, ba)
        turn(th, om, ep, blk, t, k, tt, w, e)
        turn(th, om, ep, bar, t, k, tt, w, e)
        glide(S, s_, i0 + t, k, s, sd, sdd)
        cn[g, t] = cond if closed else np.nan


def _prp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """A PRP group: the joint on two guides (of links o[2], o[4]), both slides."""
    Q1, g1, Q2, g2, x, xc1, xc2 = o[1], o[2], o[3], o[4], o[5], o[6], o[7]
    m1, m2, s1_, s2_, g = o[8], o[9], o[10], o[11], o[12]
    t1, w_1, e_1 = link(th, om, ep, g1, zero)
    t2, w_2, e_2 = link(th, om, ep, g2, zero)
    for t in range(m):
        c, cv, ca, c1v, c1a, c2v, c2a, s1, sd1, sdd1, s2, sd2, sdd2, cond, closed = prp(
            p[Q1, t], v[Q1, t], a[Q1, t], t1[t], w_1[t], e_1[t], f[0], f[1],
            p[Q2, t], v[Q2, t], a[Q2, t], t2[t], w_2[t], e_2[t], f[2], f[3])
        put(p, v, a, x, t, k, c, cv, ca)
        if xc1 >= 0:
            put(p, v, a, xc1, t, k, c, c1v, c1a)
        if xc2 >= 0:
            put(p, v, a, xc2, t, k, c, c2v, c2a)
        turn(th, om, ep, m1, t, k, t1[t] + f[0], w_1[t], e_1[t])
        turn(th, om, ep, m2, t, k, t2[t] + f[2], w_2[t], e_2[t])
        glide(S, s1_, i0 + t, k, s1, sd1, sdd1)
        glide(S, s2_, i0 + t, k, s2, sd2, sdd2)
        cn[g, t] = cond if closed else np.nan


def _rpp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """An RPP group: the block in the runner's slot, the runner on a guide of link o[3]; both slides."""
    B, Q, gl, xc, xk, blk, run, sb_, sr_, g = o[1], o[2], o[3], o[4], o[5], o[6], o[7], o[8], o[9], o[10]
    gt, gw, ge = link(th, om, ep, gl, zero)
    sine = abs(np.sin(f[2]))
    for t in range(m):
        k_, kv, ka, bv, ba, s, sd, sdd, u, ud, udd, closed = rpp(
            p[B, t], v[B, t], a[B, t], p[Q, t], v[Q, t], a[Q, t], gt[t], gw[t], ge[t], f[0], f[1], f[2])
        if xc >= 0:
            put(p, v, a, xc, t, k, p[B, t], bv, ba)
        put(p, v, a, xk, t, k, k_, kv, ka)
        theta = gt[t] + f[0]
        turn(th, om, ep, blk, t, k, theta + f[2], gw[t], ge[t])
        turn(th, om, ep, run, t, k, theta, gw[t], ge[t])
        glide(S, sb_, i0 + t, k, u, ud, udd)
        glide(S, sr_, i0 + t, k, s, sd, sdd)
        cn[g, t] = sine if closed else np.nan


def _triad_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux):
    """A class III group (`velplan.analysis.triad_rows.triad_at`) from its branch over the turn,
    ``aux[g, 0:3]`` (J_r, θ at each angle; NaN off the branch); ``aux[g, 3]`` is set to 1 where
    the correction is ambiguous, for the numpy engine to solve that angle again."""
    g, ref, pa, pb = o[21], o[25], o[23], o[24]
    rods = np.array([o[4] < 0, o[5] < 0, o[6] < 0])
    lengths = np.array([f[6], f[7], f[8]])
    R = np.array([f[0] + 1j * f[1], f[2] + 1j * f[3], f[4] + 1j * f[5]])
    w_ = np.zeros((12, 3), np.complex128)  # the leads' known motions and the group's, lead by lead
    Q, QV, QA, U, BASE, J, VJ, AJ, D, GV, GA, COR = w_[0], w_[1], w_[2], w_[3], w_[4], w_[5], w_[6], w_[7], w_[8], \
        w_[9], w_[10], w_[11]
    r_ = np.zeros((4, 3))
    GT, GW, GE, SD = r_[0], r_[1], r_[2], r_[3]
    C, work = np.zeros(3, np.complex128), np.zeros((4, 3))
    nl = th.shape[0]
    for t in range(m):
        for i in range(3):
            q = o[1 + i]
            Q[i], QV[i], QA[i] = p[q, t], v[q, t], a[q, t]
            if not rods[i]:
                gt, gw, ge = link(th, om, ep, o[4 + i] if o[4 + i] < nl else nl, zero)
                GT[i], GW[i], GE[i] = gt[t], gw[t], ge[t]
                U[i] = cis(GT[i] + f[9 + i])
                BASE[i] = Q[i] + 1j * f[12 + i] * U[i]
        xr, thr = aux[g, 0, i0 + t] + 1j * aux[g, 1, i0 + t], aux[g, 2, i0 + t]
        theta, w, e, cond, closed, redo = triad_at(rods, ref, Q, QV, QA, GW, GE, U, BASE, R, lengths, xr, thr, f[15],
                                                   f[16], J, VJ, AJ, D, GV, GA, SD, COR, C, work)
        if redo:
            aux[g, 3, i0 + t] = 1.0
        for i in range(3):
            put(p, v, a, o[7 + i], t, k, J[i], VJ[i], AJ[i])
            if rods[i]:
                lt, lw, le = rod_link(J[i], VJ[i], AJ[i], Q[i], QV[i], QA[i])
                turn(th, om, ep, o[11 + i], t, k, lt, lw, le)
            else:
                turn(th, om, ep, o[11 + i], t, k, GT[i] + f[9 + i], GW[i], GE[i])
                sdd = tdot(AJ[i] - GA[i] - COR[i], U[i])
                glide(S, o[18 + i], i0 + t, k, tdot(J[i] - BASE[i], U[i]), SD[i], sdd)
                if o[14 + i] >= 0:
                    put(p, v, a, o[14 + i], t, k, J[i], GV[i], GA[i])
        turn(th, om, ep, o[10], t, k, theta, w, e)
        da = J[pa] - Q[pa] if rods[pa] else 1j * U[pa]
        db = J[pb] - Q[pb] if rods[pb] else 1j * U[pb]
        K = special_point(J[pa], da, J[pb], db)
        kv, ka = carry(J[0], VJ[0], AJ[0], w, e, K)
        put(p, v, a, o[17], t, k, K, kv, ka)
        cn[g, t] = cond if closed else np.nan


def _mark(p, v, a, th, om, ep, cn, valid, i0, m, k, limit):
    """valid[i0 + t]: every kept output finite, every group closed and, velocities kept, their
    relative round-off (`velplan.analysis.kinematics.velocity_bound`) within ``limit``; the angles wrapped into (−π, π]."""
    for t in range(m):
        ok = True
        for j in range(p.shape[0]):
            ok = ok and np.isfinite(p[j, t]) and (k < 2 or np.isfinite(v[j, t])) and (k < 3 or np.isfinite(a[j, t]))
        for j in range(th.shape[0]):
            th[j, t] = wrap_angle(th[j, t])
            ok = ok and (k < 2 or np.isfinite(om[j, t])) and (k < 3 or np.isfinite(ep[j, t]))
        s = 0.0
        for j in range(cn.shape[0]):
            ok = ok and cn[j, t] > 0
            s += abs(cn[j, t]) ** -2.0
        valid[i0 + t] = ok and (k < 2 or ROUND_OFF * (1.0 + s) <= limit)


def _chunks(u0, u1, ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid, zero, limit, aux):
    """Interpret the program over the chunks u0 … u1 − 1 of the angles ``phi``; write Z (k, P, n)
    positions, velocities, accelerations; R (k, L, n) angles, ω, ε; S (S, k, n) slides; C (G, n)
    conditions and ``valid`` (n,) (`_mark`); k = Z.shape[0] is the order + 1. ``aux`` (G, 4, n):
    the class III groups' branches in, their flags of ambiguous angles out (`_triad_rows`).

    The angles are V variants × ``nper`` angles (variant-major); variant v has the parameters
    ``par[v]`` (m, NF), ground points ``ground[v]`` and crank rates ``w1s[v]``, ``e1s[v]``. A
    chunk is up to `CHUNK` angles of one variant; its slices of the outputs are its registers.
    """
    k = Z.shape[0]
    per = (nper + CHUNK - 1) // CHUNK  # chunks per variant
    for unit in range(u0, u1):
        vi = unit // per
        i0 = vi * nper + (unit - vi * per) * CHUNK
        m = min(vi * nper + nper, i0 + CHUNK) - i0
        w1, e1 = w1s[vi], e1s[vi]
        p, v, a = Z[0, :, i0:i0 + m], Z[min(1, k - 1), :, i0:i0 + m], Z[k - 1, :, i0:i0 + m]
        th, om, ep = R[0, :, i0:i0 + m], R[min(1, k - 1), :, i0:i0 + m], R[k - 1, :, i0:i0 + m]
        cn = C[:, i0:i0 + m]
        for j in range(ground.shape[1]):
            for t in range(m):
                put(p, v, a, j, t, k, ground[vi, j], 0j, 0j)
        for r in range(ops.shape[0]):
            o, f = ops[r], par[vi, r]
            op = o[0]
            if op == CRANK:
                crank_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == POINT:
                point_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == OP_RRR:
                rrr_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == OP_RRP:
                rrp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == OP_RPR:
                rpr_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == OP_TRIAD:
                triad_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            elif op == OP_PRP:
                prp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
            else:
                rpp_rows(o, f, i0, m, phi, w1, e1, p, v, a, th, om, ep, S, cn, zero, k, aux)
        mark(p, v, a, th, om, ep, cn, valid, i0, m, k, limit)


# ---- compiling, loading and calling ----------------------------------------------------------

SERIAL = 4096
"""Up to this many angles a call runs on the calling thread alone: waking other threads costs
more than they save (milliseconds on a busy machine)."""
ZERO = np.zeros(CHUNK)
"""The frame's angle, ω and ε over a chunk (read only)."""


def _jit(f, env: dict, qualname: str, **kw):
    """``f``'s code compiled by numba with ``env`` as its globals (its names resolved to compiled
    functions); cached on disk under ``qualname`` when ``cache=True``."""
    import numba

    g = types.FunctionType(f.__code__, env, f.__name__)
    g.__qualname__ = qualname
    return numba.njit(error_model="numpy", **kw)(g)


@lru_cache(maxsize=1)
def _env() -> dict:
    """Globals of the row functions: the closed forms and the register helpers, compiled."""
    if not available():
        raise VelplanError("the compiled engine needs numba: pip install numba (in a checkout: pip install '.[fast]')")
    env = {"__name__": __name__, "np": np, "CHUNK": CHUNK, "ROUND_OFF": ROUND_OFF, "CRANK": CRANK, "POINT": POINT,
           "OP_RRR": OP_RRR, "OP_RRP": OP_RRP, "OP_RPR": OP_RPR, "OP_PRP": OP_PRP, "OP_TRIAD": OP_TRIAD}
    for name in CORES:
        env[name] = _jit(getattr(G, name), env, name)
    for name in TRIAD_CORES:  # inlined: a call per angle would pass (and count references to) a dozen arrays
        env[name] = _jit(getattr(T, name), env, name, inline="always")
    env.update({k: getattr(T, k) for k in ("NEWTON_STEPS", "SETTLED", "QUICK_MOVE", "QUICK_CONDITION")})
    for f in (_put, _turn, _glide, _link, _mark):
        env[f.__name__[1:]] = _jit(f, env, f.__name__)
    return env


@lru_cache(maxsize=None)
def _rows(op: int):
    """The row function of opcode ``op``, compiled once per machine and cached on its own."""
    f = globals()[f"_{KINDS[op]}_rows"]
    return _jit(f, _env(), f"{f.__name__}_{fingerprint()}", cache=True, nogil=True)


@lru_cache(maxsize=1)
def kernel():
    """`_chunks` compiled: the interpreter, cached on disk, linking the row functions (`_rows`)."""
    env = dict(_env())
    for op, kind in enumerate(KINDS):
        env[f"{kind}_rows"] = _rows(op)
    return _jit(_chunks, env, f"_chunks_{fingerprint()}", cache=True, nogil=True)


@lru_cache(maxsize=1)
def _pool(pid: int):
    """Threads of the process ``pid`` (a forked child makes its own) that run shares of a call's
    chunks beside the calling thread (the kernel releases the GIL): as many as numba may use,
    less one."""
    import numba
    from concurrent.futures import ThreadPoolExecutor

    return ThreadPoolExecutor(max(1, numba.config.NUMBA_NUM_THREADS - 1), thread_name_prefix="velplan-kernel")


def _load_cached(kernel, args: tuple) -> None:
    """Load ``kernel``'s machine code for ``args`` from numba's disk cache without first
    initialising numba's whole compiler (its registries of every numpy function, ≈ 0.3 s, which
    a compiled kernel does not use); on any failure (another numba, no cache yet) the kernel's
    own call compiles or loads it the usual way."""
    try:
        from numba.core.runtime import rtsys

        rtsys.initialize(kernel.targetctx)  # the allocator the machine code links to
        sig = tuple(kernel.typeof_pyval(x) for x in args)
        done = kernel._cache._load_overload(sig, kernel.targetctx)
        if done is not None:
            kernel.add_overload(done)
    except Exception:  # noqa: BLE001 - numba's private interface: fall back to its public one
        return


def _compiled_once(kernel, args: tuple) -> None:
    """Compile ``kernel`` for ``args`` (an empty range of units: no work) while holding a lock
    file beside numba's disk cache, so that processes starting together (test workers, a batch's
    pool) compile it once between them: the others wait, then load the machine code the first
    wrote (≈ 0.3 s against ≈ 12 s). Without the lock (no ``fcntl``, no cache directory) each
    compiles, as before."""
    try:
        import fcntl

        path = os.path.join(kernel._cache._cache_path, "velplan-kernel.lock")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        handle = open(path, "a")
    except Exception:  # noqa: BLE001 - numba's private interface, another platform: no lock
        return
    with handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            kernel(0, 0, *args)
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


NO_AUX = np.zeros((0, 4, 1))
"""``aux`` of a program without class III groups."""


def run(ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid, aux=None) -> None:
    """Run the program (`_chunks`' arguments from ``ops`` on) over every angle: on the calling
    thread up to `SERIAL` angles, else in ``numba.get_num_threads()`` equal shares of the chunks,
    one on the calling thread and the others on `_pool`'s. ``aux`` (G, 4, n): each class III
    group's branch at the angles (`triad_aux`). A read-only ``phi`` is copied: to numba it is
    another type, whose kernel would be compiled again (≈ 12 s) beside the writable one's."""
    import numba

    k = kernel()
    if not phi.flags.writeable:  # one machine code for every caller: a read-only array is another type
        phi = phi.copy()
    units = par.shape[0] * ((nper + CHUNK - 1) // CHUNK)
    args = (ops, par, ground, phi, w1s, e1s, nper, Z, R, S, C, valid, ZERO, SINGULAR_BOUND,
            NO_AUX if aux is None else aux)
    if not getattr(k, "overloads", True):  # a plain function under NUMBA_DISABLE_JIT
        _load_cached(k, (0, units, *args))
        if not k.overloads:  # no machine code on disk yet: one process compiles it
            _compiled_once(k, args)
    if phi.shape[0] <= SERIAL:
        k(0, units, *args)
        return
    threads = min(numba.get_num_threads(), units)
    bounds = [units * i // threads for i in range(threads + 1)]
    shares = [_pool(os.getpid()).submit(k, a, b, *args) for a, b in zip(bounds[1:-1], bounds[2:])]
    k(bounds[0], bounds[1], *args)
    for share in shares:
        share.result()


def loaded() -> bool:
    """True once the kernel is loaded (or compiled) in this process."""
    return kernel.cache_info().currsize > 0


@lru_cache(maxsize=1)
def fingerprint() -> str:
    """A digest of the source the kernels are compiled from (this module and the closed forms)
    and of the numba version: it names their cache files, so that a change makes new ones."""
    h = hashlib.sha256(_numba_version().encode())
    for module in (__file__, G.__file__, T.__file__):
        h.update(Path(module).read_bytes())
    return h.hexdigest()[:16]


def _numba_version() -> str:
    """The installed numba's version, read without importing it."""
    version = getattr(sys.modules.get("numba"), "__version__", None)
    if version:
        return version
    from importlib import metadata

    try:
        return metadata.version("numba")
    except metadata.PackageNotFoundError:  # e.g. vendored: ask numba itself
        from numba import __version__

        return __version__


LOAD_SECONDS = {"kernel": 0.05, "numba": 0.35, "compile": 10.0}
"""What loading the kernel costs (s, measured on a 2-core machine): numba imported already and the
kernel on disk; numba to import too; no kernel on disk for this source (compiled once per machine)."""


def load_cost() -> float:
    """Seconds that loading the kernel would cost this process now (`LOAD_SECONDS`); 0 once loaded."""
    if loaded():
        return 0.0
    if not _on_disk():
        return LOAD_SECONDS["compile"]
    return LOAD_SECONDS["kernel" if "numba" in sys.modules else "numba"]


@lru_cache(maxsize=1)
def _on_disk() -> bool:
    """Whether numba's disk cache holds the kernel of this source: beside this module, or under
    ``NUMBA_CACHE_DIR``."""
    pattern = f"{Path(__file__).stem}._chunks_{fingerprint()}-*.nbi"
    if any((Path(__file__).parent / "__pycache__").glob(pattern)):
        return True
    root = os.environ.get("NUMBA_CACHE_DIR")
    return bool(root) and any(Path(root).rglob(pattern))


# ---- solving one mechanism -------------------------------------------------------------------


@dataclass(frozen=True)
class Layout:
    """What every call of `solve` on one mechanism (and one ``points=``) reuses: the schedule,
    the outputs' names and order, and the program."""

    items: tuple
    triad: str | None
    ops: np.ndarray
    par: np.ndarray
    ground: np.ndarray
    names: dict
    sizes: tuple[int, int, int, int]
    """Points, links, slides, groups."""
    tracked: tuple = ()
    """The class III groups the kernel solves from their branches (`triad_aux`)."""


_LAYOUTS: dict = {}
"""Layouts by mechanism content and ``points`` (`layout`), the latest few."""
_LAYOUTS_LOCK = threading.Lock()


def layout(mech: Mechanism, points, tracks: dict | None = None) -> Layout:
    """The `Layout` of ``mech`` solving ``points`` (None: all), memoised by the mechanism's numbers
    and names; ``tracks``: each class III group's branch over the turn (`velplan.analysis.triad.track`),
    without which ``triad`` names the first one, which the kernel then does not cover."""
    key = (mech.ground, mech.crank, mech.groups, mech.points, None if points is None else tuple(points),
           tracks is not None)
    hit = _LAYOUTS.get(key)
    if hit is None:
        hit = _layout(mech, key[-2], tracks)
        with _LAYOUTS_LOCK:  # solves from several threads: evict and add one at a time
            if len(_LAYOUTS) >= 32:
                _LAYOUTS.pop(next(iter(_LAYOUTS)), None)
            _LAYOUTS[key] = hit
    return hit


def _layout(mech: Mechanism, points, tracks=None) -> Layout:
    items = schedule(mech) if points is None else blocks.needed_items(mech, points)
    triad = next((g.name for g in items if getattr(g, "tracked", False)), None)
    if triad is not None and (tracks is None or any(np.ndim(tracks[g.name].pair) != 1 for g in items
                                                    if getattr(g, "tracked", False))):
        return Layout(items, triad, None, None, None, {}, (0, 0, 0, 0))
    scale = length_scale(mech)
    # the numpy engine on one angle fixes the outputs' names, order and link origins
    st, conditions = blocks.solve_block(mech, np.zeros(1), 1.0, 0.0, scale, "nan", items, tracks)
    pts, links, slides = list(st.points), [k for k in st.links if k != GROUND], list(st.slides)
    ops, par, ground = encode(mech, pts, links, slides, list(conditions), scale, items)
    for r, item in enumerate(items):  # Assur's special point: the pair of lead lines the branch chose
        if getattr(item, "tracked", False):
            ops[r, 23:25] = tracks[item.name].pair
    names = {"point_index": {k: i for i, k in enumerate(pts)}, "link_index": {k: i for i, k in enumerate(links)},
             "link_origins": {k: st.links[k].origin for k in links},
             "slide_index": {k: i for i, k in enumerate(slides)},
             "group_index": {k: i for i, k in enumerate(conditions)}}
    sizes = (len(pts), len(links), len(slides), len(conditions))
    tracked = tuple(g.name for g in items if getattr(g, "tracked", False))
    return Layout(items, None, ops, par[None], ground[None], names, sizes, tracked)


CUBIC_FROM = 256
"""From this many angles the kernel starts Newton from the branch's cubic (one step settles it);
below, from its chords (two steps, cheaper there than the cubic's dozen numpy calls)."""


def triad_aux(lay: Layout, tracks: dict | None, phi: np.ndarray) -> np.ndarray | None:
    """The kernel's ``aux`` (G, 4, n): for each class III group (row = its group index) the
    tracked branch's J_r (real, imaginary) and θ at the angles ``phi``, NaN off the branch
    (`velplan.analysis.triad.Track.reference`); row 3 is the kernel's flag of an angle to solve
    again. None without class III groups."""
    if not lay.tracked:
        return None
    aux = np.zeros((lay.sizes[3], 4, phi.shape[0]))
    for name in lay.tracked:
        x, th, inside = tracks[name].reference(phi, cubic=phi.shape[0] >= CUBIC_FROM)
        row = aux[lay.names["group_index"][name]]
        row[0], row[1], row[2] = x.real, x.imag, np.where(inside, th, np.nan)
    return aux


def solve(lay: Layout, mech: Mechanism, phi: np.ndarray, w1: float, e1: float, order: int,
          shift: complex = 0j, tracks: dict | None = None, again=None) -> Kinematics:
    """`solver.solve` of ``mech`` (its `Layout` ``lay``) at the angles ``phi`` (rad) and one crank
    speed ``w1`` (rad/s) and acceleration ``e1`` (rad/s²), derivatives up to ``order``: the
    outputs are allocated for that order only, and the kernel writes nothing above it. ``shift``
    (m, x + iy) is added to the positions (``lay`` was made about the crank's pivot).
    ``tracks``: the class III groups' branches (`layout`); ``again(idx)`` solves the angles
    ``phi[idx]`` where a branch is ambiguous (near another assembly) with the numpy engine, whose
    `Kinematics` replaces the kernel's there."""
    n, k = phi.shape[0], order + 1
    P, L, S, G_ = lay.sizes
    z, rates, slides = np.empty((k, P, n), dtype=complex), np.empty((k, L, n)), np.empty((S, k, n))
    condition, valid = np.empty((G_, n)), np.empty(n, dtype=bool)
    phi = np.ascontiguousarray(phi)
    aux = triad_aux(lay, tracks, phi)
    run(lay.ops, lay.par, lay.ground, phi, np.array([float(w1)]), np.array([float(e1)]), n,
        z, rates, slides, condition, valid, aux)
    redo = np.zeros(0, dtype=np.intp) if aux is None else np.flatnonzero(aux[:, 3].any(axis=0))
    if shift:
        z[0] += shift
    xy = z.view(float).reshape(k, P, n, 2).transpose(0, 2, 1, 3)
    rates = rates.transpose(0, 2, 1)
    kin = Kinematics(
        mechanism=mech, phi=phi, omega1=w1, epsilon1=e1, positions=xy[0], velocities=xy[1] if k > 1 else None,
        accelerations=xy[2] if k > 2 else None, angles=rates[0], omegas=rates[1] if k > 1 else None,
        epsilons=rates[2] if k > 2 else None, slides=slides.transpose(2, 0, 1), condition=condition.T, valid=valid,
        order=order, **lay.names)
    if redo.size:
        _replace(kin, redo, again(redo))
    return kin


def _replace(kin: Kinematics, idx: np.ndarray, sub: Kinematics) -> None:
    """Write ``sub`` (the same outputs at the angles ``idx`` of ``kin``) into ``kin``, by name."""
    groups = (("point_index", ("positions", "velocities", "accelerations")),
              ("link_index", ("angles", "omegas", "epsilons")), ("slide_index", ("slides",)),
              ("group_index", ("condition",)))
    for index, fields in groups:
        cols = [getattr(sub, index)[name] for name in getattr(kin, index)]
        for field in fields:
            mine = getattr(kin, field)
            if mine is not None and len(cols):
                mine[idx] = getattr(sub, field)[:, cols]
    kin.valid[idx] = sub.valid
