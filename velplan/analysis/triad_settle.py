"""Newton's correction of a class III triad from its tracked branch, over whole arrays of crank
angles in few passes (`velplan.analysis.triad._branch`; the compiled engine's
`velplan.analysis.triad_rows.triad_newton` does the same per angle).

The unknowns are Y = J_r − P_r (the first rod's inner joint from its outer joint) and the base
link's angle θ. Each lead gives one closure equation; a rod's is kept multiplied by its length,
``(|w|² − l²)/2 = 0`` with w = J − P, so that its Jacobian row is (w_x, w_y, w·(i·r)) without a
division. The first rod's row has no θ term (its joint is J_r itself), and the 3×3 systems are
solved by Cramer's rule with that zero used.

A position stops once its correction is below `SETTLED` (over the group's size): the error left is
about its square. The tracked branch predicts well enough (`velplan.analysis.triad.Track`) that
most positions stop after one step; the others take further steps on their own.
"""

from __future__ import annotations

import numpy as np

SETTLED = 1e-9
"""Newton from the tracked branch stops once its largest correction is below this (over the
group's size), and a position counts as converged where its last correction is: the error left
is about its square, below round-off (`QUICK_CONDITION` bounds the closure's curvature)."""
QUICK_MOVE = 1e-3
"""Newton from the tracked branch is taken as it is when it moves the configuration less than
this (the branch's nodes are 0.5° apart: it moves ≈ 1e-5) and the closure is well conditioned."""
QUICK_CONDITION = 0.05
STEPS = 5
"""Newton's steps at most."""


def _turned(L: complex, c, s):
    """The real and imaginary parts of L·(c + i·s) (L a constant)."""
    if L.imag == 0.0:
        return c * L.real, s * L.real
    rx = c * L.real
    rx -= s * L.imag
    ry = s * L.real
    ry += c * L.imag
    return rx, ry


class Closure:
    """The closure equations of a triad at n positions, relative to the first rod's outer joint
    (``cl``: a `velplan.analysis.triad._Closure`): each lead's constants as contiguous real arrays,
    the first rod first."""

    def __init__(self, cl):
        self.size = cl.size
        self.terms = []
        for i in [cl.ref] + cl.others:
            lead, L = cl.leads[i], complex(cl.local[i])
            if lead.rod:
                q = None if i == cl.ref else lead.p - cl.origin
                self.terms.append((True, L, lead.length ** 2, *(() if q is None else _parts(q))))
            else:
                u, base = lead.line()
                ux, uy = _parts(np.broadcast_to(u, cl.origin.shape))
                self.terms.append((False, L, 0.0, ux, uy, *_parts(base - cl.origin)))

    def take(self, idx) -> "Closure":
        """The same equations at the positions ``idx`` only."""
        out = object.__new__(Closure)
        out.size = self.size
        out.terms = [(t[0], t[1], t[2], *(a[idx] for a in t[3:])) for t in self.terms]
        return out

    def step(self, yx, yy, c, s):
        """Newton's step at (Y, θ) with (c, s) = (cos θ, sin θ): the corrections (dx, dy, dθ) and
        whether the closure is well conditioned there (Hadamard ratio of its rows, the θ column
        over the size, at least `QUICK_CONDITION`)."""
        rows = []
        for rod, L, l2, *k in self.terms:
            rx, ry = (None, None) if L == 0 else _turned(L, c, s)
            if rod:
                wx, wy = (yx, yy) if rx is None else (yx + rx - k[0], yy + ry - k[1])
                h = wx * wx
                h += wy * wy
                np.subtract(l2, h, out=h)
                h *= 0.5
                m = None
                if rx is not None:
                    m = wy * rx
                    m -= wx * ry
                rows.append((wx, wy, m, h))
            else:
                ux, uy, bx, by = k
                m = ux * rx
                m += uy * ry
                f = uy * (yx + rx - bx)
                f -= ux * (yy + ry - by)  # −cross(u, Y + r − base)
                rows.append((-uy, ux, m, f))
        return _solve(rows, self.size)


def _parts(z):
    """Contiguous real and imaginary parts of a complex array."""
    return np.ascontiguousarray(z.real), np.ascontiguousarray(z.imag)


def _minor(p, q, r, s):
    """p·q − r·s, elementwise, in one new array (no temporaries beyond it)."""
    out = p * q
    out -= r * s
    return out


def _solve(rows, size: float):
    """Cramer's rule for rows (a, b, c | r) whose first c is zero (None); and the condition test."""
    (a1, b1, _, r1), (a2, b2, c2, r2), (a3, b3, c3, r3) = rows
    bc, ac, rc = _minor(b2, c3, b3, c2), _minor(a2, c3, a3, c2), _minor(r2, c3, r3, c2)
    det = _minor(a1, bc, b1, ac)
    dx = _minor(r1, bc, b1, rc)
    dx /= det
    dy = _minor(a1, rc, r1, ac)
    dy /= det
    ab, br, ar = _minor(a2, b3, a3, b2), _minor(b2, r3, b3, r2), _minor(a2, r3, a3, r2)
    dt = _minor(a1, br, b1, ar)
    dt += r1 * ab
    dt /= det
    # |det|/size ≥ Q·Π‖row‖ (rows with the θ column over size), squared: no roots
    k = 1.0 / (size * size)
    norm = a1 * a1
    norm += b1 * b1
    for a, b, c in ((a2, b2, c2), (a3, b3, c3)):
        n2 = c * c
        n2 *= k
        n2 += a * a
        n2 += b * b
        norm *= n2
    det *= det
    det *= k
    norm *= QUICK_CONDITION ** 2
    return dx, dy, dt, det >= norm


def settle(eqs: Closure, yx, yy, th, x0, th0, quick_move: float = QUICK_MOVE, cs=None):
    """Newton's correction of (Y, θ) (arrays, updated in place) by `Closure.step`, each position
    until its correction is below `SETTLED` (at most `STEPS` steps). Returns cos θ, sin θ at the
    result and whether each position is unambiguous: converged, well conditioned at its last
    step, and moved no more than ``quick_move`` from the start (``x0`` its J_r relative to the
    origin, ``th0``). The last step's |dθ| ≤ `SETTLED`, so cos, sin at the result come from
    those at its start without a new sine: cos(θ + dθ) = cos θ − dθ·sin θ to round-off. A
    position settled in one step moved at most `SETTLED`: only those that took more are measured.
    ``cs``: cos θ, sin θ at the start where known (else numpy's)."""
    size = eqs.size
    c_out, s_out = np.empty_like(th), np.empty_like(th)
    ok = np.zeros(th.shape, bool)
    idx, cur, later = None, eqs, []
    for step in range(STEPS):
        X, Y, T = (yx, yy, th) if idx is None else (yx[idx], yy[idx], th[idx])
        c, s = cs if step == 0 and cs is not None else (np.cos(T), np.sin(T))
        dx, dy, dt, good = cur.step(X, Y, c, s)
        X += dx
        Y += dy
        T += dt
        moved = np.abs(dx)
        moved += np.abs(dy)
        moved += np.abs(dt) * size
        settled = moved <= SETTLED * size
        c_new = c - s * dt
        s += c * dt
        good &= settled
        if idx is None:
            c_out, s_out, ok = c_new, s, good
        else:
            yx[idx], yy[idx], th[idx] = X, Y, T
            c_out[idx], s_out[idx], ok[idx] = c_new, s, good
        rest = np.flatnonzero(~settled & np.isfinite(moved))
        if not rest.size or step == STEPS - 1:
            break
        if idx is None and 4 * rest.size > th.shape[0]:  # most go on: all of them, without copies
            later.append(np.arange(th.shape[0]))
            continue
        idx = rest if idx is None else idx[rest]
        cur = eqs.take(idx)
        later.append(idx)
    if quick_move < SETTLED:
        later.append(np.arange(th.shape[0]))
    if later:  # moved over several steps: how far, as `velplan.analysis.triad._distance`
        far = np.unique(np.concatenate(later))
        turn = np.angle(np.exp(1j * (th[far] - th0[far])))
        d = np.hypot(yx[far] - x0.real[far], yy[far] - x0.imag[far]) / size + np.abs(turn)
        ok[far] &= d <= quick_move
    return c_out, s_out, ok
