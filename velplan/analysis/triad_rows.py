"""The class III triad at one crank angle, for the compiled engine: the formulas of
`velplan.analysis.triad` (Newton's correction from the tracked branch, the 3×3 systems of the
velocities and accelerations, the leads' links, slides and Assur's special point) written for
scalars, in the same order of operations, so that the kernel gives the numpy engine's numbers to
round-off. `velplan.analysis.compiled` compiles these functions with numba; run as plain Python
they give the same numbers (slowly).

A lead is given by its known point ``q`` (a rod's outer joint, or the guide link's point the
guide passes through) with its velocity and acceleration, and, for a block, the guide link's
angle, ω, ε and the guide's angle and offset on it (``rod`` False).
"""

from __future__ import annotations

import numpy as np

NEWTON_STEPS = 5
"""Newton's steps from the tracked branch at most (`velplan.analysis.triad._correct`)."""
SETTLED = 1e-9
QUICK_MOVE = 1e-3
QUICK_CONDITION = 0.05
"""As `velplan.analysis.triad` (a test checks they agree)."""


def tdot(a, b):
    """Scalar product of two complex-encoded vectors."""
    return a.real * b.real + a.imag * b.imag


def tcross(a, b):
    """z-component of the cross product of two complex-encoded vectors."""
    return (a.real * b.imag) - (a.imag * b.real)


def cramer3(a1, b1, c1, a2, b2, c2, a3, b3, c3, r1, r2, r3):
    """The 3×3 system with rows (a, b, c) and right side r, as `velplan.analysis.triad._cramer3`."""
    bc, ac, ab = b2 * c3 - b3 * c2, a2 * c3 - a3 * c2, a2 * b3 - a3 * b2
    rc, br, ar = r2 * c3 - r3 * c2, b2 * r3 - b3 * r2, a2 * r3 - a3 * r2
    det = a1 * bc - b1 * ac + c1 * ab
    return (r1 * bc - b1 * rc - c1 * br) / det, (a1 * rc - r1 * ac + c1 * ar) / det, (a1 * br - b1 * ar + r1 * ab) / det


def condition3(a1, b1, c1, a2, b2, c2, a3, b3, c3, scale):
    """Hadamard ratio of the 3×3 matrix, moment column over ``scale`` (`triad._condition`)."""
    c1, c2, c3 = c1 / scale, c2 / scale, c3 / scale
    det = a1 * (b2 * c3 - b3 * c2) - b1 * (a2 * c3 - a3 * c2) + c1 * (a2 * b3 - a3 * b2)
    norm = (a1 * a1 + b1 * b1 + c1 * c1) * (a2 * a2 + b2 * b2 + c2 * c2) * (a3 * a3 + b3 * b3 + c3 * c3)
    return abs(det) / np.sqrt(norm)  # one root for the three rows' norms


def closure_row(rod, c, u, length, y, r):
    """One lead's closure residual (m) and Jacobian row ∂/∂(Yx, Yy, θ) (`triad._Closure._equations`):
    ``c`` is the rod's outer joint or the guide's base point, relative to the first rod's outer joint."""
    w = y + r - c
    if rod:
        return (tdot(w, w) - length ** 2) / (2 * length), w.real / length, w.imag / length, tdot(w, 1j * r) / length
    return tcross(u, w), -u.imag, u.real, tcross(u, 1j * r)


def unit(t):
    """cos t + i·sin t."""
    return np.cos(t) + 1j * np.sin(t)


def distance(x, th, x0, th0, size):
    """`triad._distance` of two configurations (inf where not finite)."""
    turn = th - th0  # the angle of e^{i·turn} (np.angle would load numba's array library)
    if not abs(turn) < 3.0:
        turn = np.arctan2(np.sin(turn), np.cos(turn))
    d = abs(x - x0) / size + abs(turn)
    return d if np.isfinite(d) else np.inf


def triad_newton(c0, c1, c2, u0, u1, u2, rods, lengths, r0, r1, r2, xr, thr, origin, size):
    """Newton's correction of the tracked configuration (J_r ``xr``, θ ``thr``): (J_r, θ,
    unambiguous, cos θ + i·sin θ) as `velplan.analysis.triad._correct` at one position (the last
    step's dθ is below `SETTLED` where unambiguous: the unit vector is the last step's turned by
    it, e·(1 + i·dθ), to round-off, without a new sine). ``c``, ``u``: the leads'
    points and guide directions (relative to ``origin``, the first rod's outer joint); ``r``: the
    joints' offsets from J_r in the base link's frame."""
    y, th = xr - origin, thr
    moved, dt, e = np.nan, 0.0, 1.0 + 0j
    for _ in range(NEWTON_STEPS):
        e = unit(th)
        f0, a0, b0, k0 = closure_row(rods[0], c0, u0, lengths[0], y, r0 * e)
        f1, a1, b1, k1 = closure_row(rods[1], c1, u1, lengths[1], y, r1 * e)
        f2, a2, b2, k2 = closure_row(rods[2], c2, u2, lengths[2], y, r2 * e)
        dx, dy, dt = cramer3(a0, b0, k0, a1, b1, k1, a2, b2, k2, -f0, -f1, -f2)
        y, th = y + dx + 1j * dy, th + dt
        moved = abs(dx) + abs(dy) + abs(dt) * size
        if not moved > SETTLED * size:
            break
    cond = condition3(a0, b0, k0, a1, b1, k1, a2, b2, k2, size)  # the last step's rows
    x = y + origin
    ok = moved <= SETTLED * size and distance(x, th, xr, thr, size) <= QUICK_MOVE and cond >= QUICK_CONDITION
    return x, th, ok, e * (1.0 + 1j * dt)


def lead_velocity_row(rod, j, x, qp, qv, qa, u, gw, ge):
    """A lead's row of the velocity system and its right side (`triad._motion`): (normal d,
    moment, rhs, guide point's velocity, acceleration at j)."""
    rr = j - x
    if rod:
        d = j - qp
        return d, tdot(d, 1j * rr), tdot(d, qv), qv, qa
    d = 1j * u
    r = j - qp
    gv, ga = qv + 1j * gw * r, qa + (1j * ge - gw * gw) * r
    return d, tdot(d, 1j * rr), tdot(d, gv), gv, ga


def lead_acceleration_rhs(rod, d, j, x, vj, w, qv, qa, u, gw, gv, ga):
    """A lead's right side of the acceleration system; and, for a block, its slide speed and Coriolis term."""
    rr = j - x
    if rod:
        rel = vj - qv
        return tdot(d, qa) + w * w * tdot(d, rr) - tdot(rel, rel), 0.0, 0j
    sd = tdot(vj - gv, u)
    cor = 2j * gw * sd * u
    return tdot(d, ga + cor) + w * w * tdot(d, rr), sd, cor


def rod_link(j, vj, aj, qp, qv, qa):
    """A rod lead's angle, ω and ε (`triad._result`)."""
    d = j - qp
    d2 = tdot(d, d)
    wl = tcross(d, vj - qv) / d2
    el = tcross(d, aj - qa + wl * wl * d) / d2
    return np.arctan2(d.imag, d.real), wl, el


def special_point(ja, da, jb, db):
    """Where the line through ``ja`` along ``da`` crosses the one through ``jb`` along ``db``."""
    s = tcross(jb - ja, db) / tcross(da, db)  # real: inf/NaN for parallel lines, as numpy (no complex division)
    return ja + da * s


def triad_at(rods, ref, Q, QV, QA, GW, GE, U, BASE, R, lengths, xr, thr, size, scale, J, VJ, AJ, D, GV, GA, SD, COR,
             C, work):
    """The triad at one position from the tracked configuration (J_r ``xr``, θ ``thr``; NaN
    outside the branch): fills the joints J, VJ, AJ, the leads' normals D, the guides' motions
    at the joints GV, GA, the slide speeds SD and Coriolis terms COR (arrays of 3), and returns
    (θ, ω, ε, condition, closed, redo); ``C`` (3, complex) and ``work`` (4, 3) are scratch. Where Newton's correction is ambiguous or the
    position lies off the branch, the joints are NaN; ``redo`` where the position is on the branch
    but the correction ambiguous (`triad._branch` then searches all roots: the caller's numpy engine)."""
    origin = Q[ref]
    for i in range(3):
        C[i] = (Q[i] if rods[i] else BASE[i]) - origin
    x, theta, ok, e = triad_newton(C[0], C[1], C[2], U[0], U[1], U[2], rods, lengths, R[0], R[1], R[2],
                                   xr, thr, origin, size)
    closed = ok and np.isfinite(thr)
    if not closed:
        x, theta, e = complex(np.nan, np.nan), np.nan, complex(np.nan, np.nan)
    A3, B3, M3, H3 = work[0], work[1], work[2], work[3]
    for i in range(3):
        J[i] = x + R[i] * e
        D[i], M3[i], H3[i], GV[i], GA[i] = lead_velocity_row(rods[i], J[i], x, Q[i], QV[i], QA[i], U[i], GW[i], GE[i])
        A3[i], B3[i] = D[i].real, D[i].imag
    vx, vy, w = cramer3(A3[0], B3[0], M3[0], A3[1], B3[1], M3[1], A3[2], B3[2], M3[2], H3[0], H3[1], H3[2])
    vX = vx + 1j * vy
    for i in range(3):
        VJ[i] = vX + 1j * w * (J[i] - x)
        H3[i], SD[i], COR[i] = lead_acceleration_rhs(rods[i], D[i], J[i], x, VJ[i], w, QV[i], QA[i], U[i], GW[i],
                                                     GV[i], GA[i])
    ax, ay, eps = cramer3(A3[0], B3[0], M3[0], A3[1], B3[1], M3[1], A3[2], B3[2], M3[2], H3[0], H3[1], H3[2])
    aX = ax + 1j * ay
    for i in range(3):
        AJ[i] = aX + (1j * eps - w * w) * (J[i] - x)
    cond = condition3(A3[0], B3[0], M3[0], A3[1], B3[1], M3[1], A3[2], B3[2], M3[2], scale)
    return theta, w, eps, cond, closed, np.isfinite(thr) and not ok
