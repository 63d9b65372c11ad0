"""The class III triad, solved exactly: every assembly of the group at each crank angle, the one
branch followed continuously over the turn, and its velocities and accelerations from the
linear systems of the derivatives.

Closure reduced to one unknown
------------------------------
Let J_r be the inner joint of the first rod lead (outer joint P_r, length l_r), θ the base
link's angle (B → C) and Y = J_r − P_r. Every other joint is J_i = J_r + r_i(θ), r_i the
joint's offset from J_r turned by θ. Each other lead gives one equation linear in Y:

* a rod from P_i (length l_i): |Y + r_i − Q_i|² − |Y|² = l_i² − l_r², Q_i = P_i − P_r;
* a block on a guide (base point b_i, direction u_i): cross(u_i, Y + r_i − (b_i − P_r)) = 0.

The two linear equations give Y = N(θ)/Δ(θ) (N, Δ trigonometric polynomials of degree 2) and
the rod r closes when G(θ) = |N|² − l_r²·Δ² = 0: a trigonometric polynomial of degree 4, so
at most 8 assemblies. Its coefficients come exactly from 16 samples by the FFT, its roots
from the eigenvalues of the companion matrix of z⁴·G(z) (z = e^{iθ}, roots on |z| = 1), and
every root is polished by Newton's method on the three closure equations to round-off.

Branch
------
The file's ``assembly`` (approximate joints at one crank angle) picks one root; `track`
follows it over the turn in steps of at most 0.5° (halved where the nearest root is not
clearly the nearest), finds where it ends (an assembly limit, by bisection) or checks that it
comes back to itself after a full turn. At any crank angle the solver takes the root nearest
to the tracked branch: Newton's correction from the branch's Hermite cubic between nodes (off
by ≈ 1e-11 of the group's size, so one step settles it to round-off), every root only where
that correction is ambiguous. The cubic also gives cos θ, sin θ there without a cosine or sine
per angle (`_unit`: the node's, turned by the Taylor series of the turn from it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache

import numpy as np

from velplan.analysis import triad_settle
from velplan.analysis.groups import GroupResult, LinkMotion, Motion, carry, cis, cross, guide_line, slide_name
from velplan.analysis.triad_settle import QUICK_CONDITION, QUICK_MOVE, SETTLED  # noqa: F401 (the triad's numbers)
from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND, Mechanism, Triad

TRACK_STEP = math.radians(0.5)
"""Largest step of the branch tracking, rad."""
MAX_HALVINGS = 14
"""Halvings of a tracking step before the branch is taken to end there (0.5°/2¹⁴ ≈ 3e-5°)."""
EDGE_TOL = 1e-12
"""Accuracy of an assembly limit of the tracked branch, rad."""
ASSEMBLY_FAR = 1 / 3
"""Largest RMS distance (over the group's size) between the joints given in ``assembly`` and
the assembly they pick."""
FAR = 0.25
"""Largest distance (configuration units: lengths / the group's size + radians) between the
tracked branch and a root still taken as its continuation."""


def _cis(t):
    """cos t + i·sin t (`velplan.analysis.groups.cis`, the same numbers) written into one complex
    array: no complex temporaries on the triad's many (n, 16) arrays."""
    t = np.asarray(t, dtype=float)
    out = np.empty(t.shape, dtype=complex)
    np.cos(t, out=out.real)
    np.sin(t, out=out.imag)
    return out


def dot(a, b):
    """Scalar product of two complex-encoded vectors (summed in place: one temporary fewer)."""
    out = a.real * b.real
    out += a.imag * b.imag
    return out


def _cross(a, b):
    """`velplan.analysis.groups.cross` (the same numbers), its difference taken in place."""
    out = a.real * b.imag
    out -= a.imag * b.real
    return out


# ---- inputs of one evaluation ----------------------------------------------------------------


@dataclass
class Lead3:
    """The known motion a lead rests on, arrays over positions: a rod's outer joint P (p, v, a),
    or a block's guide (the guide link's point, its θ, ω, ε, the guide's angle and offset).
    ``still``: the lead rests on the ground: a rod's outer joint is a ground point (v = a = 0: its
    terms are left out), a block's guide is on the ground link (its direction found once)."""

    rod: bool
    length: float
    p: np.ndarray = None
    v: np.ndarray = None
    a: np.ndarray = None
    theta: np.ndarray = None
    omega: np.ndarray = None
    epsilon: np.ndarray = None
    angle: float = 0.0
    offset: float = 0.0
    still: bool = False

    def take(self, idx) -> "Lead3":
        """The same lead at positions ``idx`` only."""
        pick = lambda a: a if a is None or np.ndim(a) == 0 else a[idx]  # noqa: E731
        return Lead3(self.rod, self.length, pick(self.p), pick(self.v), pick(self.a), pick(self.theta),
                     pick(self.omega), pick(self.epsilon), self.angle, self.offset, self.still)

    def line(self):
        """Guide: unit direction u and base point (arrays), found once."""
        return self._line

    @cached_property
    def _line(self):
        if self.still:  # a guide on the ground: one direction (the same numbers) for every position
            u = np.broadcast_to(cis(self.theta[:1] + self.angle), np.shape(self.p))
            return u, self.p + 1j * self.offset * u
        return guide_line(self.p, self.theta, self.angle, self.offset)

    def carried(self, x):
        """Velocity and acceleration of the guide link's point at ``x``."""
        return carry(self.p, self.v, self.a, self.omega, self.epsilon, x)


def inputs_from_state(g: Triad, st) -> list[Lead3]:
    """The three leads' known motions from a solver `State` (a rod on one of its ground points,
    `State.fixed`, is `Lead3.still`)."""
    out = []
    fixed = getattr(st, "fixed", ())
    for lead in g.leads:
        if lead.slider:
            m, link = st.points[lead.guide.through], st.links[lead.guide.link]
            out.append(Lead3(False, 0.0, m.p, m.v, m.a, link.theta, link.omega, link.epsilon,
                             lead.guide.angle, lead.guide.offset, lead.guide.link == GROUND))
        else:
            m = st.points[lead.joint]
            out.append(Lead3(True, lead.length, m.p, m.v, m.a, still=lead.joint in fixed))
    return out


def _size(g: Triad) -> float:
    return max(max(g.sides), max(lead.length for lead in g.leads))


# ---- all assemblies at each position -----------------------------------------------------------


class _Closure:
    """The closure of one triad at n positions, relative to the first rod's outer joint."""

    def __init__(self, g: Triad, leads: list[Lead3]):
        self.g, self.leads = g, leads
        self.ref = next(i for i, x in enumerate(leads) if x.rod)
        self.others = [i for i in range(3) if i != self.ref]
        local = g.local()
        self.local = [z - local[self.ref] for z in local]
        self.origin = leads[self.ref].p
        self.size = _size(g)

    def offsets(self, theta):
        """r_i(θ) for the three joints (arrays broadcast with θ)."""
        e = _cis(theta)
        return [z * e for z in self.local]

    def rows(self, theta):
        """The two linear equations a·Y = h of the other leads at θ (arrays shaped like θ)."""
        r = self.offsets(theta)
        out = []
        lr = self.leads[self.ref].length
        for i in self.others:
            lead = self.leads[i]
            o = self.origin[..., None] if np.ndim(theta) > np.ndim(self.origin) else self.origin
            if lead.rod:
                q = (lead.p[..., None] if np.ndim(theta) > np.ndim(lead.p) else lead.p) - o
                w = r[i] - q
                out.append((2 * w, lead.length ** 2 - lr * lr - dot(w, w)))
            else:
                u, base = lead.line()
                if np.ndim(theta) > np.ndim(u):
                    u, base = u[..., None], base[..., None]
                out.append((1j * u, cross(u, base - o - r[i])))
        return out

    def numerator(self, theta):
        """N(θ) and Δ(θ): Y·Δ = N."""
        (a1, h1), (a2, h2) = self.rows(theta)
        return 1j * (h2 * a1 - h1 * a2), cross(a1, a2)

    def candidates(self):
        """All assemblies: J_r (complex) and θ, shape (n, 16), with a mask of those that close."""
        n = self.origin.shape[0]
        t = np.arange(16) * (2 * np.pi / 16)
        theta = np.broadcast_to(t, (n, 16))
        num, den = self.numerator(theta)
        lr = self.leads[self.ref].length
        gval = (num.real ** 2 + num.imag ** 2) - (lr * den) ** 2
        c = np.fft.fft(gval, axis=1) / 16
        coeffs = np.stack([c[:, k % 16] for k in range(4, -5, -1)], axis=1)  # z⁸ … z⁰
        roots = _poly_roots(coeffs)
        near = np.abs(np.abs(roots) - 1.0) < 1e-3
        th = np.where(near, np.angle(roots), np.nan)
        th = np.concatenate([th, th], axis=1)
        y = self._first_guess(th)
        y, th = self._newton(y, th)
        ok = self._residual(y, th) <= 1e-9 * self.size
        return np.where(ok, y + self.origin[:, None], np.nan), np.where(ok, th, np.nan), ok

    def _first_guess(self, th):
        """Y at each candidate θ: N/Δ, or where the two lines are parallel the two crossings of
        one line with the rod's circle (first and second half of the columns)."""
        num, den = self.numerator(th)
        (a1, h1), (a2, _) = self.rows(th)
        with np.errstate(all="ignore"):
            y = num / den
            size2 = dot(a1, a1)
            flat = np.abs(den) <= 1e-9 * np.sqrt(size2 * dot(a2, a2))
            foot = a1 * h1 / size2
            lr = self.leads[self.ref].length
            along = np.sqrt(np.maximum(lr * lr - dot(foot, foot), 0.0)) * 1j * a1 / np.sqrt(size2)
        # with two block leads a1, a2 do not depend on θ: broadcast to the columns
        y, flat, foot, along = np.broadcast_arrays(y, flat, foot, along)
        m = th.shape[1] // 2
        y = np.where(flat, foot + along, y)
        y[:, m:] = np.where(flat[:, m:], (foot - along)[:, m:], np.nan)
        return y

    def _equations(self, y, th):
        """The three closure residuals (m) and their Jacobian rows ∂/∂(Yx, Yy, θ)."""
        r = self.offsets(th)
        f, rows = [], []
        for i, lead in enumerate(self.leads):
            if lead.rod:
                q = 0.0 if i == self.ref else lead.p[:, None] - self.origin[:, None]
                w = y + r[i] - q
                f.append((dot(w, w) - lead.length ** 2) / (2 * lead.length))
                rows.append((w.real / lead.length, w.imag / lead.length, dot(w, 1j * r[i]) / lead.length))
            else:
                u, base = lead.line()
                u, base = u[:, None], base[:, None]
                f.append(cross(u, y + r[i] - (base - self.origin[:, None])))
                rows.append((-u.imag, u.real + 0 * y.real, cross(u, 1j * r[i])))
        return f, rows

    def _newton(self, y, th, steps: int = 6):
        with np.errstate(all="ignore"):
            for _ in range(steps):
                f, rows = self._equations(y, th)
                dx, dy, dt = _cramer3(rows, [-x for x in f])
                y = y + dx + 1j * dy
                th = th + dt
        return y, th

    def _residual(self, y, th):
        f, _ = self._equations(y, th)
        with np.errstate(invalid="ignore"):
            res = np.maximum(np.maximum(np.abs(f[0]), np.abs(f[1])), np.abs(f[2]))
        return np.where(np.isfinite(res), res, np.inf)


def _poly_roots(coeffs: np.ndarray) -> np.ndarray:
    """(n, 8) roots of the polynomials (n, 9) (highest first) by the eigenvalues of their
    companion matrices. For three rods the terms z⁸ and z⁰ vanish (the triad has at most six
    assemblies): those rows are solved as sextics; with two block leads the guides do not
    turn with the base link and z⁸, z⁷, z¹, z⁰ vanish (at most four assemblies): quartics; a
    row with other missing terms is solved alone (np.roots). Missing roots are NaN."""
    n = coeffs.shape[0]
    scale = np.max(np.abs(coeffs), axis=1)
    tiny = 1e-11 * scale
    octic = np.abs(coeffs[:, 0]) > tiny
    sextic = ~octic & (np.abs(coeffs[:, 8]) <= tiny) & (np.abs(coeffs[:, 1]) > tiny)
    small = np.abs(coeffs) <= tiny[:, None]
    quartic = ~octic & ~sextic & small[:, [1, 7, 8]].all(axis=1) & ~small[:, 2]  # two block leads
    out = np.full((n, 8), np.nan + 0j)
    for rows, lo, hi in ((octic, 0, 9), (sextic, 1, 8), (quartic, 2, 7)):
        if rows.any():
            out[rows, :hi - lo - 1] = _companion_roots(coeffs[rows, lo:hi])
    for k in np.flatnonzero(~octic & ~sextic & ~quartic & (scale > 0) & np.isfinite(scale)):
        r = np.roots(np.where(np.abs(coeffs[k]) > 1e-13 * scale[k], coeffs[k], 0.0))
        out[k, :r.size] = r
    return out


def _companion_roots(coeffs: np.ndarray) -> np.ndarray:
    """(m, d) roots of the (m, d + 1) polynomials (highest first, leading term non-zero)."""
    d = coeffs.shape[1] - 1
    comp = np.zeros((coeffs.shape[0], d, d), complex)
    comp[:, 0, :] = -coeffs[:, 1:] / coeffs[:, :1]
    comp[:, np.arange(1, d), np.arange(d - 1)] = 1.0
    return np.linalg.eigvals(comp)


def _minors(rows):
    """The 2×2 minors of the last two rows that Cramer's rule uses, and the determinant (a first
    row's moment given as the number 0: the first rod's joint is J_r itself, its term left out)."""
    (a1, b1, c1), (a2, b2, c2), (a3, b3, c3) = rows
    bc, ac, ab = b2 * c3 - b3 * c2, a2 * c3 - a3 * c2, a2 * b3 - a3 * b2
    det = a1 * bc
    det -= b1 * ac
    if not _zero(c1):
        det += c1 * ab
    return bc, ac, ab, det


def _zero(c) -> bool:
    """Whether a row's moment is the number 0 (not an array)."""
    return np.ndim(c) == 0 and c == 0.0


def _cramer3(rows, rhs, minors=None, out=(None, None, None)):
    """Solve the 3×3 systems whose rows are (a, b, c) arrays: returns the three unknowns (each
    2×2 minor computed once; ``minors``: `_minors` of ``rows``, shared by systems with one matrix;
    ``out``: arrays to write the unknowns into, None each where new)."""
    (a1, b1, c1), (a2, b2, c2), (a3, b3, c3) = rows
    r1, r2, r3 = rhs
    bc, ac, ab, det = _minors(rows) if minors is None else minors
    if _zero(r1) or _zero(r2) or _zero(r3):  # a rod on a ground point: its right side is 0
        rc, br, ar = _sum((1, r2, c3), (-1, r3, c2)), _sum((1, b2, r3), (-1, b3, r2)), _sum((1, a2, r3), (-1, a3, r2))
        x = _sum((1, r1, bc), (-1, b1, rc), (-1, c1, br))
        y = _sum((1, a1, rc), (-1, r1, ac), (1, c1, ar))
        z = _sum((1, a1, br), (-1, b1, ar), (1, r1, ab))
        return np.divide(x, det, out=out[0]), np.divide(y, det, out=out[1]), np.divide(z, det, out=out[2])
    rc, br, ar = r2 * c3 - r3 * c2, b2 * r3 - b3 * r2, a2 * r3 - a3 * r2
    x = r1 * bc
    x -= b1 * rc
    y = a1 * rc
    y -= r1 * ac
    if not _zero(c1):  # the first rod's row: c1 = 0
        x -= c1 * br
        y += c1 * ar
    z = a1 * br
    z -= b1 * ar
    z += r1 * ab
    return np.divide(x, det, out=out[0]), np.divide(y, det, out=out[1]), np.divide(z, det, out=out[2])


def _sum(*terms):
    """Σ ±p·q over the terms (sign, p, q), in their order, those with a factor the number 0 left
    out (`_zero`): the numbers of the whole sum where its factors are finite; the number 0.0
    when every term is left out."""
    out = None
    for sign, p, q in terms:
        if _zero(p) or _zero(q):
            continue
        t = p * q
        if out is None:
            out = t if sign > 0 else np.negative(t, out=t)
        elif sign > 0:
            out += t
        else:
            out -= t
    return 0.0 if out is None else out


# ---- the tracked branch -----------------------------------------------------------------------


@dataclass(frozen=True)
class Track:
    """The branch of a triad followed over the crank's turn.

    ``t`` (rad, increasing) are crank angles relative to the assembly angle ``phi0``, with the
    first rod's inner joint ``x`` (complex, m) and the base link's angle ``theta`` (rad) at
    each; the branch exists on [t[0], t[-1]] (``full``: the whole turn, t from 0 to 2π).
    ``pair`` are the two leads whose lines give Assur's special point. ``pieces`` (4, K, 3): on
    each of the K intervals between nodes, the coefficients of u⁰ … u³ (u = t − t_k, rad) of the
    cubic through (x.real, x.imag, θ unwrapped): Hermite's from the nodes' slopes where that was
    found nearer the branch than the chord (`_pieces`), else the chord; None: chords throughout.
    """

    phi0: float
    t: np.ndarray
    x: np.ndarray
    theta: np.ndarray
    full: bool
    pair: tuple[int, int]
    size: float
    pieces: np.ndarray | None = None

    @cached_property
    def unwrapped(self) -> np.ndarray:
        """``theta`` without jumps of 2π (rad), for interpolating between nodes."""
        return np.unwrap(self.theta)

    def reference(self, phi: np.ndarray, cubic: bool = True, unit: bool = False):
        """(x, θ, inside) of the branch at crank angles ``phi`` (`pieces` between nodes; with
        ``cubic`` False the chords: fewer calls, for a few angles whose Newton steps are cheap);
        with ``unit``, and (cos θ, sin θ) where the cubic gives them (`_unit`), else None."""
        if self.t.size == 0:
            nan = np.full(phi.shape, np.nan)
            return (nan + 0j, nan, np.zeros(phi.shape, bool)) + ((None,) if unit else ())
        t = phi - self.phi0
        # `np.mod`'s numbers within two turns (7 ns an angle against 1): t in [0, 2π], or off it by
        # round-off where the turn's floor is off by one at a whole turn (the same angle)
        t -= (2 * np.pi) * np.floor(t * (1 / (2 * np.pi)))
        if self.full:  # t in [0, 2π] = [t[0], t[-1]]: every angle on the branch
            inside, tc = np.ones(t.shape, bool), t
        else:
            t = np.where(t > self.t[-1] + EDGE_TOL, t - 2 * np.pi, t)
            inside = (t >= self.t[0] - EDGE_TOL) & (t <= self.t[-1] + EDGE_TOL)
            tc = np.clip(t, self.t[0], self.t[-1])
        if self.pieces is not None and cubic:
            x, th, cs = self._cubic(tc)
            return (x, th, inside, cs) if unit else (x, th, inside)
        x = np.interp(tc, self.t, self.x.real) + 1j * np.interp(tc, self.t, self.x.imag)
        th = np.interp(tc, self.t, self.unwrapped)
        return (x, th, inside, None) if unit else (x, th, inside)

    @cached_property
    def _spacing(self) -> float:
        """The nodes' step where they are evenly spaced (rad), else 0."""
        h = np.diff(self.t)
        return float(h[0]) if h.size and np.ptp(h) <= 1e-9 * h[0] else 0.0

    def _cubic(self, tc: np.ndarray):
        """x, θ of the `pieces` at the turns ``tc`` (within [t[0], t[-1]]), and cos θ, sin θ
        (`_unit`; None below `UNIT_FROM` angles)."""
        last = self.pieces.shape[1] - 1
        if self._spacing:
            k = ((tc - self.t[0]) * (1.0 / self._spacing)).astype(np.intp)
        else:
            k = np.searchsorted(self.t, tc, side="right") - 1
        np.clip(k, 0, last, out=k)
        u = tc - self.t.take(k)
        out = []
        for c0, c1, c2, c3 in self._columns:
            v = c3.take(k)
            v *= u
            v += c2.take(k)
            v *= u
            v += c1.take(k)
            v *= u
            out.append(v)  # from the interval's first node
        x = np.empty(tc.shape, complex)
        np.add(out[0], self._columns[0][0].take(k), out=x.real)
        np.add(out[1], self._columns[1][0].take(k), out=x.imag)
        turn = out[2]
        th = turn + self._columns[2][0].take(k)
        return x, th, _unit(self._node_units, k, turn, th) if tc.size >= UNIT_FROM else None

    @cached_property
    def _node_units(self) -> tuple:
        """cos, sin of θ at each interval's first node (the cubic's constant term), and the
        series `_unit` sums for the largest turn on an interval."""
        th0, c1, c2, c3 = self._columns[2]
        h = np.diff(self.t)
        turn = float(np.max(np.abs(c1) * h + np.abs(c2) * h * h + np.abs(c3) * h ** 3, initial=0.0))
        return np.cos(th0), np.sin(th0), _series(min(turn * (1 + 1e-6), UNIT_TURN))

    @cached_property
    def _columns(self) -> list:
        """`pieces` as contiguous columns: per quantity, its four coefficients over the intervals."""
        return [[np.ascontiguousarray(self.pieces[j, :, q]) for j in range(4)] for q in range(3)]


UNIT_FROM = 256
"""From this many angles `Track.reference` gives cos θ, sin θ by `_unit` (a dozen numpy calls);
below, numpy's cosine and sine cost less."""
UNIT_TURN = 0.1
"""Largest turn (rad) from an interval's node for which `_unit` sums the series."""
SERIES_TAIL = 1e-18
"""The first term left out of `_unit`'s series is below this (round-off is ≈ 1e-16)."""


def _series(turn: float) -> tuple:
    """The Taylor coefficients of cos δ and sin δ / δ in δ² (ascending) whose first term left out
    is below `SERIES_TAIL` for |δ| up to ``turn`` (rad), and ``turn``."""
    m = 2
    while turn ** (2 * m) / math.factorial(2 * m) > SERIES_TAIL:
        m += 1
    return (tuple((-1) ** j / math.factorial(2 * j) for j in range(m)),
            tuple((-1) ** j / math.factorial(2 * j + 1) for j in range(m)), turn)


def _unit(node, k, turn, theta):
    """cos θ, sin θ of θ = θ_k + ``turn`` (interval ``k``; ``node``: cos θ_k, sin θ_k and the
    `_series` for the track's largest turn) by the sum of the angles, the turn's cosine and sine
    from their Taylor series (to round-off); where a turn is larger than the series is made for,
    from ``theta`` by numpy's cosine and sine."""
    cos_terms, sin_terms, largest = node[2]
    t2 = turn * turn
    sn = _horner(sin_terms, t2)
    sn *= turn
    cn = _horner(cos_terms, t2)
    c0, s0 = node[0].take(k), node[1].take(k)
    c = c0 * cn
    c -= s0 * sn
    s = s0 * cn
    s += c0 * sn
    if not np.max(np.abs(turn), initial=0.0) <= largest:  # NaN included
        far = np.flatnonzero(~(np.abs(turn) <= largest))
        c[far], s[far] = np.cos(theta[far]), np.sin(theta[far])
    return c, s


def _horner(coeffs, x):
    """Σ coeffs[j]·x^j by Horner's rule (x an array; at least two coefficients)."""
    v = x * coeffs[-1]
    for a in coeffs[-2:0:-1]:
        v += a
        v *= x
    v += coeffs[0]
    return v


def _distance(x, th, x0, th0, size):
    d = np.abs(x - x0) / size + np.abs(np.angle(np.exp(1j * (th - th0))))
    return np.where(np.isfinite(d), d, np.inf)


def upstream(mech: Mechanism, g: Triad) -> Mechanism:
    """``mech`` cut before ``g``: ground, crank, earlier groups and the points on their links."""
    k = mech.groups.index(g)
    groups = mech.groups[:k]
    links = {mech.crank.link} | {x for grp in groups for x in grp.links}
    points = tuple(p for p in mech.points if p.link in links)
    return Mechanism(name=mech.name, ground=mech.ground, crank=replace(mech.crank, omega=1.0, epsilon=0.0),
                     groups=groups, points=points)


def leads_at(up: Mechanism, g: Triad, phi: np.ndarray, solve) -> list[Lead3]:
    """The leads' known motions at crank angles ``phi`` (unit crank speed), by ``solve`` (the
    solver's `velplan.solve`, passed in: this module sits below it) on ``up``, the mechanism
    cut before ``g`` (`upstream`)."""
    names = [lead.guide.through if lead.slider else lead.joint for lead in g.leads]
    kin = solve(up, phi, order=2)
    zc = lambda arr, name: arr[:, kin.point_index[name]] @ np.array([1, 1j])  # noqa: E731
    out = []
    for lead, name in zip(g.leads, names):
        p, v, a = zc(kin.positions, name), zc(kin.velocities, name), zc(kin.accelerations, name)
        if lead.slider:
            k = lead.guide.link
            zero = np.zeros(phi.shape)
            th, w, e = (zero, zero, zero) if k == GROUND else (kin.angle(k), kin.omega(k), kin.epsilon(k))
            out.append(Lead3(False, 0.0, p, v, a, th, w, e, lead.guide.angle, lead.guide.offset))
        else:
            out.append(Lead3(True, lead.length, p, v, a))
    return out


def _roots_at(mech, g, phi, solve):
    cl = _Closure(g, leads_at(mech, g, np.atleast_1d(phi), solve))
    x, th, ok = cl.candidates()
    local = g.local()
    return x, th, ok, cl, local


@lru_cache(maxsize=64)
def track(mech: Mechanism, g: Triad, solve) -> Track:
    """The branch of ``g`` picked by its ``assembly``, followed over the crank's turn (cached
    per geometry; ``mech`` holds what comes before ``g``, `upstream`, solved by ``solve``)."""
    size = _size(g)
    phi0 = g.assembly_phi
    x0, th0, ok0, cl, local = _roots_at(mech, g, np.array([phi0]), solve)
    start = _start(g, x0[0], th0[0], ok0[0], cl.ref, local, size)
    return _finish(mech, g, start, _walk(mech, g, phi0, start, +1, size, solve), solve)


def _start(g: Triad, x0, th0, ok0, ref: int, local, size: float) -> tuple:
    """(J_r, θ) of the assembly nearest to the joints as drawn, among the roots ``x0``, ``th0``
    (mask ``ok0``) at the assembly angle, and no farther than a third of the group's size."""
    where = f"group {g.name!r} (triad): at its assembly angle {math.degrees(g.assembly_phi):g}°"
    if not ok0.any():
        raise MechanismError(f"{where} the group cannot be assembled; give the angle of a position as drawn")
    cost = np.zeros(x0.shape[0])
    for name, (px, py) in g.assembly:
        j = g.joints.index(name)
        pos = x0 + (local[j] - local[ref]) * np.exp(1j * th0)
        cost = cost + np.abs(pos - complex(px, py)) ** 2
    cost = np.sqrt(np.where(ok0, cost, np.inf) / len(g.assembly))
    k = int(np.argmin(cost))
    if not cost[k] <= ASSEMBLY_FAR * size:
        raise MechanismError(f"{where} no assembly lies near the joints given; the nearest is {cost[k]:.3g} m "
                             f"from them (the group is {size:.3g} m across): check assembly")
    return x0[k], th0[k]


def _finish(mech: Mechanism, g: Triad, start: tuple, fwd: list, solve) -> Track:
    """The `Track` from the nodes ``fwd`` walked forward from ``start``: checked to come back to
    itself after a full turn, or completed backwards to where the branch ends."""
    size, phi0 = _size(g), g.assembly_phi
    full = fwd[-1][0] >= 2 * np.pi - EDGE_TOL
    if full:
        if _distance(fwd[-1][1], fwd[-1][2], start[0], start[1], size) > 1e-6:
            raise MechanismError(
                f"group {g.name!r} (triad): after one crank turn from {math.degrees(phi0):g}° it comes back in "
                "another assembly; the mechanism does not repeat its motion each turn")
        nodes = fwd
    else:
        bwd = _walk(mech, g, phi0, start, -1, size, solve)
        nodes = [(-t, x, th) for t, x, th in reversed(bwd[1:])] + fwd
    t = np.array([n[0] for n in nodes])
    x = np.array([n[1] for n in nodes])
    th = np.array([n[2] for n in nodes])
    return Track(phi0, t, x, th, bool(full), _pair(g, (mech, x, th, t), solve), size,
                 _pieces(mech, g, t, x, np.unwrap(th), solve))


def _pieces(mech: Mechanism, g: Triad, t, x, th, solve) -> np.ndarray | None:
    """`Track.pieces` of the nodes (t, x, θ unwrapped): on each interval Hermite's cubic from the
    slopes dx/dφ, dθ/dφ at its ends (the velocities at unit crank speed), where at the interval's
    middle it lies nearer the branch (Newton's correction from the chord) than the chord does;
    elsewhere (near a limit of the branch, where the slopes grow without bound) the chord."""
    m = t.size
    if m < 2:
        return None
    size, h = _size(g), np.diff(t)
    mid = t[:-1] + 0.5 * h
    leads = leads_at(mech, g, g.assembly_phi + np.concatenate([t, mid]), solve)
    at_nodes = _Closure(g, [lead.take(slice(0, m)) for lead in leads])
    at_mid = _Closure(g, [lead.take(slice(m, None)) for lead in leads])
    y = np.stack([x.real, x.imag, th], axis=1)
    with np.errstate(all="ignore"):  # a branch's last node may repeat the one before (h = 0)
        vx, w = _slopes(at_nodes, x, th)
        slope = np.stack([vx.real, vx.imag, w], axis=1)
        chord = np.where((h > 0)[:, None], (y[1:] - y[:-1]) / h[:, None], 0.0)
        hermite = [y[:-1], slope[:-1], (3 * chord - 2 * slope[:-1] - slope[1:]) / h[:, None],
                   (slope[:-1] + slope[1:] - 2 * chord) / (h * h)[:, None]]
        lin = 0.5 * (y[:-1] + y[1:])
        her = lin + (h / 8)[:, None] * (slope[:-1] - slope[1:])
        xm, thm, ok = _correct(at_mid, lin[:, 0] + 1j * lin[:, 1], lin[:, 2], size)
        near = lambda p: _distance(p[:, 0] + 1j * p[:, 1], p[:, 2], xm, thm, size)  # noqa: E731
        use = ok & (h > 0) & np.isfinite(slope[:-1]).all(axis=1) & np.isfinite(slope[1:]).all(axis=1) \
            & (near(her) < near(lin))
    linear = [y[:-1], chord, np.zeros_like(chord), np.zeros_like(chord)]
    return np.stack([np.where(use[:, None], a, b) for a, b in zip(hermite, linear)])


def _slopes(cl: _Closure, x, th):
    """dJ_r/dφ and dθ/dφ of the assemblies (J_r ``x``, θ ``th``) of ``cl``'s positions, its leads'
    motions at unit crank speed: the velocity system of `_motion`."""
    joints = [x + r for r in cl.offsets(th)]
    rows, rhs = [], []
    for lead, j in zip(cl.leads, joints):
        d = j - lead.p if lead.rod else 1j * lead.line()[0]
        rhs.append(dot(d, lead.v if lead.rod else lead.carried(j)[0]))
        rows.append((d.real, d.imag, dot(d, 1j * (j - x))))
    vx, vy, w = _cramer3(rows, rhs)
    return vx + 1j * vy, w


def tracks(ups: list[Mechanism], gs: list[Triad], solve) -> list[Track | None]:
    """The branches of one triad in V variants (``gs[v]`` with ``ups[v]`` before it, `upstream`;
    the triads differ in where they sit, not in their shape), followed over the turn in all
    variants together: from the assembly `track` would pick and its first step, each step of
    the same grid is Newton's correction of the configuration predicted from the last two,
    taken where it is unambiguous (as `QUICK_MOVE`, `QUICK_CONDITION` in `_branch`). A variant
    where a step is not is tracked alone (`track`); None where its triad cannot be assembled
    at its assembly angle."""
    g = gs[0]
    size, phi0 = _size(g), g.assembly_phi
    grid = _track_grid()
    leads = _joined([leads_at(up, gv, phi0 + grid, solve) for up, gv in zip(ups, gs)])
    m = grid.size
    at0 = _Closure(g, [lead.take(slice(0, None, m)) for lead in leads])
    xs, ths, oks = at0.candidates()
    local = g.local()
    starts = []
    for v, gv in enumerate(gs):
        try:
            starts.append(_start(gv, xs[v], ths[v], oks[v], at0.ref, local, size))
        except MechanismError:
            starts.append((np.nan + 0j, np.nan))
    x, th = np.array([s[0] for s in starts]), np.array([s[1] for s in starts])
    alive = np.isfinite(th)
    walked = [(x, th)]
    prev, cur = None, (0.0, x, th)
    for k in range(1, m):
        cl = _Closure(g, [lead.take(slice(k, None, m)) for lead in leads])
        if prev is None:  # no slope to predict with: the nearest of all roots, as `track` steps
            xs, ths, _ = cl.candidates()
            x, th, ok = _pick_rows(xs, ths, (x, th), size)
        else:
            x, th, ok = _correct(cl, *_predict(cur, prev, grid[k]), size)
        alive &= ok
        prev, cur = cur, (grid[k], x, th)
        walked.append((x, th))
    X, TH = np.array([w[0] for w in walked]), np.array([w[1] for w in walked])
    out = []
    for v, (up, gv) in enumerate(zip(ups, gs)):
        if alive[v]:
            out.append(_finish(up, gv, starts[v], list(zip(grid, X[:, v], TH[:, v])), solve))
        elif np.isfinite(starts[v][1]):
            out.append(track(up, gv, solve))
        else:
            out.append(None)
    return out


def _correct(cl: _Closure, xr: np.ndarray, thr: np.ndarray, size: float):
    """Newton's correction of the configurations (J_r ``xr``, θ ``thr``) of ``cl``'s positions:
    (J_r, θ, whether it is unambiguous: converged, moved less than `QUICK_MOVE`, well
    conditioned), by `velplan.analysis.triad_settle.settle`."""
    return _settled(cl, xr, thr)[:3]


def _settled(cl: _Closure, xr: np.ndarray, thr: np.ndarray, out=(None, None), cs=None):
    """`_correct`, and cos θ + i·sin θ at the result (J_r, θ written into ``out`` where given;
    ``cs``: cos, sin of ``thr`` where known)."""
    y0 = xr - cl.origin
    yx, yy = y0.real.copy(), y0.imag.copy()
    th = np.array(thr, dtype=float) if out[1] is None else out[1]
    if out[1] is not None:
        np.copyto(th, thr)
    c, s, ok = triad_settle.settle(triad_settle.Closure(cl), yx, yy, th, y0, thr, QUICK_MOVE, cs)
    x = np.empty(th.shape, complex) if out[0] is None else out[0]
    np.add(yx, cl.origin.real, out=x.real)
    np.add(yy, cl.origin.imag, out=x.imag)
    e = np.empty(th.shape, complex)
    e.real, e.imag = c, s
    return x, th, ok, e


def _track_grid() -> np.ndarray:
    """Crank turns (rad) of the tracking steps over a turn, 0 and 2π included."""
    steps = int(round(2 * np.pi / TRACK_STEP))
    return np.arange(steps + 1) * (2 * np.pi / steps)


def _joined(per_variant: list[list[Lead3]]) -> list[Lead3]:
    """The three leads of V variants (each at its own positions) as leads over all positions."""
    out = []
    for leads in zip(*per_variant):
        cat = lambda name: (None if getattr(leads[0], name) is None  # noqa: E731
                            else np.concatenate([getattr(ld, name) for ld in leads]))
        out.append(replace(leads[0], **{f: cat(f) for f in ("p", "v", "a", "theta", "omega", "epsilon")}))
    return out


@dataclass(frozen=True)
class Tracks:
    """The branches of one triad in consecutive variants, ``n`` crank angles each (positions
    variant-major), read as one `Track` by `solve_triad`; a variant without one (None) never
    closes."""

    tracks: tuple
    n: int

    @property
    def size(self) -> float:
        return next((t.size for t in self.tracks if t is not None), 1.0)

    @property
    def pair(self) -> tuple[int, int] | np.ndarray:
        """The leads of Assur's special point: one pair, or (V·n, 2) a pair per position where
        the variants choose differently."""
        pairs = [(0, 1) if t is None else t.pair for t in self.tracks]
        if len(set(pairs)) == 1:
            return pairs[0]
        return np.repeat(np.array(pairs), self.n, axis=0)

    def reference(self, phi: np.ndarray, cubic: bool = True, unit: bool = False):
        """(x, θ, inside) of each variant's branch at its crank angles ``phi`` (`Track.reference`;
        with ``unit``, and None: no cos θ, sin θ)."""
        n = self.n
        empty = Track(0.0, np.zeros(0), np.zeros(0, complex), np.zeros(0), False, (0, 1), 1.0)
        parts = [(t or empty).reference(phi[v * n:(v + 1) * n], cubic) for v, t in enumerate(self.tracks)]
        out = tuple(np.concatenate(a) for a in zip(*parts))
        return out + (None,) if unit else out


def _walk(mech, g, phi0, start, sense, size, solve):
    """Nodes (t ≥ 0, x, θ) of the branch from ``start`` in the crank's ``sense`` (±1) up to a
    full turn or to the limit where the branch ends."""
    t_grid = _track_grid()
    xs, ths, oks, _, _ = _roots_at(mech, g, phi0 + sense * t_grid, solve)
    nodes = [(0.0, start[0], start[1])]
    prev = None
    for k in range(1, t_grid.size):
        cur = nodes[-1]
        pred = _predict(cur, prev, t_grid[k])
        pick = _pick(xs[k], ths[k], pred, size)
        if pick is None:
            sub = _refine(mech, g, phi0, sense, cur, prev, t_grid[k], size, solve)
            if sub is None or sub[-1][0] < t_grid[k]:
                return nodes + (sub or [])
            nodes += sub[:-1]
            prev, cur = nodes[-1], sub[-1]
            nodes.append(cur)
            continue
        prev = cur
        nodes.append((t_grid[k], *pick))
    return nodes


def _predict(cur, prev, t):
    if prev is None or cur[0] == prev[0]:
        return cur[1], cur[2]
    s = (t - cur[0]) / (cur[0] - prev[0])
    return cur[1] + s * (cur[1] - prev[1]), cur[2] + s * (cur[2] - prev[2])


def _pick(xs, ths, pred, size):
    """The root clearly nearest to ``pred``, or None (none near, or two about as near)."""
    x, th, ok = _pick_rows(xs[None], ths[None], (np.atleast_1d(pred[0]), np.atleast_1d(pred[1])), size)
    return (x[0], th[0]) if ok[0] else None


def _pick_rows(xs, ths, pred, size):
    """Per row of the roots ``xs``, ``ths`` (V, m): the root nearest to ``pred`` (x, θ of shape
    (V,)), and whether it is clearly the nearest (within `FAR`, and no other root — the same
    root found twice, a complex pair polished onto one real root, is not another — as near
    as twice its distance)."""
    d = _distance(xs, ths, pred[0][:, None], pred[1][:, None], size)
    rows = np.arange(xs.shape[0])
    j = np.argmin(d, axis=1)
    d1, x, th = d[rows, j], xs[rows, j], ths[rows, j]
    twin = _distance(xs, ths, x[:, None], th[:, None], size) <= 1e-7
    rival = np.min(np.where(twin, np.inf, d), axis=1)
    return x, th, (d1 <= FAR) & ~((rival < 2.0 * d1) & (d1 > 1e-9))


def _refine(mech, g, phi0, sense, cur, prev, t_end, size, solve):
    """Nodes from ``cur`` towards ``t_end`` in halved steps; ends at the branch's limit (found
    by bisection) when no step, however short, continues it."""
    nodes = []
    step = (t_end - cur[0]) / 2
    halvings = 1
    while cur[0] < t_end - EDGE_TOL:
        t = min(cur[0] + step, t_end)
        xs, ths, _, _, _ = _roots_at(mech, g, np.array([phi0 + sense * t]), solve)
        pick = _pick(xs[0], ths[0], _predict(cur, prev, t), size)
        if pick is None:
            if halvings >= MAX_HALVINGS:
                return nodes + [_limit(mech, g, phi0, sense, cur, t, size, solve)]
            step /= 2
            halvings += 1
            continue
        prev, cur = cur, (t, *pick)
        nodes.append(cur)
    return nodes


def _limit(mech, g, phi0, sense, cur, t_out, size, solve):
    """The last node of a branch that ends between ``cur`` (closes) and ``t_out`` (does not)."""
    lo, hi, best = cur[0], t_out, cur
    while hi - lo > EDGE_TOL:
        mid = 0.5 * (lo + hi)
        xs, ths, ok, _, _ = _roots_at(mech, g, np.array([phi0 + sense * mid]), solve)
        d = _distance(xs[0], ths[0], best[1], best[2], size)
        j = int(np.argmin(d))
        if d[j] <= FAR:
            lo, best = mid, (mid, xs[0, j], ths[0, j])
        else:
            hi = mid
    return best


def _pair(g: Triad, sampled, solve) -> tuple[int, int]:
    """The leads whose lines give the special point: the file's, else the pair whose lines
    cross at the largest smallest angle over the tracked branch."""
    if g.pair is not None:
        return g.pair
    if sampled is None:
        return (0, 1)
    mech, x, th, t = sampled
    leads = leads_at(mech, g, g.assembly_phi + t, solve)
    cl = _Closure(g, leads)
    joints = [x + r for r in cl.offsets(th)]
    dirs = [_lead_direction(lead, j) for lead, j in zip(leads, joints)]
    best, score = (0, 1), -1.0
    for a, b in ((0, 1), (0, 2), (1, 2)):
        with np.errstate(all="ignore"):
            s = np.abs(cross(dirs[a], dirs[b])) / (np.abs(dirs[a]) * np.abs(dirs[b]))
        low = float(np.nanmin(s)) if np.isfinite(s).any() else 0.0
        if low > score + 1e-12:
            best, score = (a, b), low
    return best


def _lead_direction(lead: Lead3, joint):
    """Direction of a lead's line: along the rod (P → J), or the guide's normal at the block."""
    if lead.rod:
        return joint - lead.p
    return 1j * lead.line()[0]


# ---- the solution at the requested angles -------------------------------------------------


def solve_triad(g: Triad, st, phi: np.ndarray, trk: Track, scale: float) -> GroupResult:
    """Positions of the branch, then V and a of the base link from the 3×3 systems

        d_i·(V_X + i·ω3·r_i) = d_i·V_P            (rod: V_J − V_P ⊥ P J)
        n_i·(V_X + i·ω3·r_i) = n_i·V_J(guide)     (block: V_J − V_J(guide) ∥ guide)

    and the same rows for a_X, ε3 with the known normal, Coriolis terms on the right."""
    leads = inputs_from_state(g, st)
    cl = _Closure(g, leads)
    slots = _Slots(g, st)
    x, theta, closed, e = _branch(cl, trk, phi, (slots.p[cl.ref], slots.base[0]))
    offsets = [None if z == 0 else z * e for z in cl.local]
    joints = [x if r is None else np.add(x, r, out=p) for r, p in zip(offsets, slots.p)]
    return _motion(g, leads, x, theta, joints, closed, scale, trk.pair, offsets, slots, e)


class _Slots:
    """The outputs a triad's results are computed into (`velplan.analysis.groups.State.out_point`,
    `out_link`): the joints' p, v, a, the base link's θ, ω, ε, the leads' links and the special
    point; None each where the state has none (what is not computed in place is copied)."""

    def __init__(self, g: Triad, st):
        if getattr(st, "sink", None) is None:
            self.p = self.v = self.a = [None] * len(g.joints)
            self.base, self.links, self.special = (None, None, None), dict.fromkeys(x.link for x in g.leads), None
            return
        pts = [st.out_point(name) for name in g.joints]
        self.p, self.v, self.a = ([None if m is None else getattr(m, k) for m in pts] for k in "pva")
        base = st.out_link(g.base)
        self.base = (None, None, None) if base is None else (base.theta, base.omega, base.epsilon)
        self.links = {spec.link: st.out_link(spec.link) for spec in g.leads}
        self.special = st.out_point(g.special_name)


def _branch(cl: _Closure, trk: Track, phi: np.ndarray, out=(None, None)):
    """The tracked branch's assembly at each crank angle: Newton from the tracked configuration
    where that is unambiguous (well conditioned, a small correction), else every assembly
    found and the nearest to the branch taken. Returns J_r, θ, the mask of closed positions and
    cos θ + i·sin θ (J_r and θ in the arrays ``out`` where given, unless masked)."""
    xr, thr, inside, cs = trk.reference(phi, unit=True)
    x, th, quick, e = _settled(cl, xr, thr, out, cs)
    good = inside & quick
    rest = np.flatnonzero(inside & ~good)
    if rest.size:
        sub = _Closure(cl.g, [lead.take(rest) for lead in cl.leads])
        xs, ths, ok = sub.candidates()
        d = _distance(xs, ths, xr[rest, None], thr[rest, None], trk.size)
        k = np.argmin(d, axis=1)
        row = np.arange(rest.size)
        hit = ok[row, k] & (d[row, k] <= FAR)
        x[rest] = np.where(hit, xs[row, k], np.nan)
        th[rest] = np.where(hit, ths[row, k], np.nan)
        good[rest] = hit
        e[rest] = cis(th[rest])
    closed = inside & good
    if closed.all():
        return x, th, closed, e
    return np.where(closed, x, np.nan), np.where(closed, th, np.nan), closed, e


def _motion(g, leads, x, theta, joints, closed, scale, pair, offsets=None, slots=None, unit=None):
    """The velocities and accelerations of the assemblies (J_r ``x``, θ, the joints ``joints``,
    their ``offsets`` from J_r: None where J_r itself): one matrix, its minors found once, for
    both right sides; computed into ``slots`` (`_Slots`) where given; ``unit``: cos θ + i·sin θ
    where known."""
    if offsets is None:
        offsets = [j - x for j in joints]
    rows, rhs_v, normals, guides = [], [], [], []
    for lead, j, r in zip(leads, joints, offsets):
        if lead.rod:  # J − P as two contiguous real arrays
            d, gm = _Parts(np.subtract(j.real, lead.p.real), np.subtract(j.imag, lead.p.imag)), None
            rhs_v.append(0.0 if lead.still else dot(d, lead.v))
        else:
            d, gm = 1j * lead.line()[0], lead.carried(j)
            rhs_v.append(dot(d, gm[0]))
        normals.append(d)
        guides.append(gm)
        rows.append((np.ascontiguousarray(d.real), np.ascontiguousarray(d.imag),
                     0.0 if r is None else _cross(r, d)))  # d·(i·r)
    minors = _minors(rows)  # one matrix for the velocities and the accelerations
    w2, vj = _joints_at(rows, rhs_v, minors, offsets, None, None if slots is None else (slots.v, slots.base[1]))
    w = w2[1]
    rhs_a, slides, spins = [], [], []
    for lead, spec, j, v, d, r, gm in zip(leads, g.leads, joints, vj, normals, offsets, guides):
        turn = 0.0 if r is None else w2[0] * dot(d, r)
        if lead.rod:
            out = slots and slots.links[spec.link]
            # the rod's ω: |d| = its length
            wl = np.multiply(_cross(d, v if lead.still else v - lead.v), 1.0 / lead.length ** 2, out=out and out.omega)
            spins.append(wl)
            # |V_J − V_P|² = (ω·l)²: the relative velocity is across the rod
            rhs_a.append((turn if lead.still else dot(d, lead.a) + turn) - wl * wl * lead.length ** 2)
        else:
            u, base = lead.line()
            gv, ga = gm
            sd = dot(v - gv, u)
            cor = 2j * lead.omega * sd * u
            rhs_a.append(dot(d, ga + cor) + turn)
            slides.append((dot(j - base, u), sd, u, gv, ga, cor))
    e2, aj = _joints_at(rows, rhs_a, minors, offsets, w2[0], None if slots is None else (slots.a, slots.base[2]))
    return _result(g, leads, theta, (w, e2[1], w2[2], e2[2]), joints, vj, aj, (normals, [r[2] for r in rows]), offsets,
                   (slides, spins), (minors[3], closed), scale, pair, slots, unit)


def _joints_at(rows, rhs, minors, offsets, w2=None, out=None):
    """The system's solution (X's rate, ω or ε) for the right sides ``rhs``: (w², ω, i·ω) or
    (i·ε − ω², ε, i·ε − ω²), and the joints' rates X' + (i·ω)·r (or X'' + (i·ε − ω²)·r); ``out``:
    the joints' arrays and the rate's to write them into (None each where new)."""
    joints_out, rate_out = (None,) * len(offsets), None
    if out is not None:
        joints_out, rate_out = out
    ref = next(i for i, r in enumerate(offsets) if r is None)
    X = joints_out[ref]
    if X is None:
        X = np.empty(rows[0][0].shape, complex)
    ux, uy, rate = _cramer3(rows, rhs, minors, (X.real, X.imag, rate_out))
    k = np.empty(rate.shape, complex)
    k.imag = rate
    if w2 is None:
        k.real = 0.0
        first = rate * rate
    else:
        np.negative(w2, out=k.real)
        first = k
    return (first, rate, k), [X if r is None else np.add(X, k * r, out=o) for r, o in zip(offsets, joints_out)]


def _result(g, leads, theta, rates, joints, vj, aj, normals, offsets, slides, det_closed, scale, pair, slots=None,
            unit=None):
    """The group's points (joints, special point, coincident points), links and slides; the
    base link's unit vector and the rods' (their reference directions: the link points on them
    need no sine); the rods' motions and the special point's computed into ``slots`` where given."""
    w, e, iw, iea = rates
    det, closed = det_closed
    normals, moments = normals
    slides, spins = slides
    wi = iter(spins)
    B = joints[0]
    points = {name: Motion(j, v, a) for name, j, v, a in zip(g.joints, joints, vj, aj)}
    links = {g.base: LinkMotion(g.joints[0], theta, w, e)}
    slide_out, units = {}, {}
    si = iter(slides)
    norm = 1.0 / scale ** 2
    squares = []  # the rows' squared norms (|d| = l or 1)
    for lead, spec, name, j, v, a, d, r, c in zip(leads, g.leads, g.joints, joints, vj, aj, normals, offsets, moments):
        moment = 0.0 if r is None else c * c * norm
        squares.append((moment + lead.length ** 2) if lead.rod else (moment + 1.0))
        if lead.rod:
            k = 1.0 / lead.length ** 2  # |d| = the rod's length: the assembly closes
            wl = next(wi)
            out = (slots and slots.links[spec.link]) or LinkMotion(spec.joint, None, None, None)
            # d × (a_J − a_P + ω²·d): the last term is d × d = 0
            el = np.multiply(_cross(d, a if lead.still else a - lead.a), k, out=out.epsilon)
            links[spec.link] = LinkMotion(spec.joint, np.arctan2(d.imag, d.real, out=out.theta), wl, el)
        else:
            s, sd, u, gv, ga, cor = next(si)
            sdd = dot(a - ga - cor, u)
            links[spec.link] = LinkMotion(name, lead.theta + lead.angle, lead.omega, lead.epsilon)
            slide_out[slide_name(spec.link, spec.guide.link)] = Motion(s + 0j, sd + 0j, sdd + 0j)
            if spec.coincident:
                points[spec.coincident] = Motion(j, gv, ga)
            units[spec.link] = u  # cis(θ_guide + angle), as the link's angle
    out = (slots and slots.special) or Motion(None, None, None)
    K = _special_point(leads, joints, pair, normals, out.p)
    rK = K - B
    t = iw * rK
    kv = np.add(vj[0], t, out=out.v)
    np.multiply(iea, rK, out=t)
    ka = np.add(aj[0], t, out=out.a)
    points[g.special_name] = Motion(K, kv, ka)
    # the Hadamard ratio of `_condition`, its determinant and row norms known: |d| = l or 1
    norms = squares[0] * squares[1] * squares[2]
    cond = np.abs(det) / scale / np.sqrt(norms)
    # the base link's frame runs B → C: its unit vector is cos θ + i·sin θ (as (C − B)/BC)
    units[g.base] = (joints[1] - B) * (1.0 / g.sides[0]) if unit is None else unit
    units.update({spec.link: _times(d, 1.0 / lead.length)
                  for lead, spec, d in zip(leads, g.leads, normals) if lead.rod})
    return GroupResult(points=points, links=links, slides=slide_out,
                       condition=cond if closed.all() else np.where(closed, cond, np.nan), closed=closed, units=units,
                       spins={g.base: (iw, iea)})


def _special_point(leads, joints, pair, normals=None, out=None):
    """Assur's special point: where the lines of the two leads ``pair`` cross (a pair, or one
    per position, (n, 2)); ``normals``: the leads' velocity-system normals, a rod's its line's
    direction; ``out``: the array to write it into, or None."""
    if np.ndim(pair) == 2:
        K = np.full(joints[0].shape, np.nan + 0j)
        for p in {tuple(int(i) for i in row) for row in pair}:
            K = np.where(np.all(pair == p, axis=1), _special_point(leads, joints, p, normals), K)
        return K
    a_, b_ = ((joints[i], _lead_direction(leads[i], joints[i]) if normals is None else normals[i]) for i in pair)
    with np.errstate(all="ignore"):
        return np.add(a_[0], _times(a_[1], _cross(b_[0] - a_[0], b_[1]) / _cross(a_[1], b_[1])), out=out)


class _Parts:
    """A complex-encoded vector held as its two real parts (contiguous arrays), for `dot`,
    `cross` and `_times` (a rod's J − P: its rows need no copies)."""

    __slots__ = ("real", "imag")

    def __init__(self, real: np.ndarray, imag: np.ndarray):
        self.real, self.imag = real, imag


def _times(v, k):
    """The complex array of the vector ``v`` (complex or `_Parts`) times the real ``k`` (a number or
    an array): the numbers of ``v * k``."""
    if not isinstance(v, _Parts):
        return v * k
    out = np.empty(np.broadcast(v.real, k).shape, complex)
    np.multiply(v.real, k, out=out.real)
    np.multiply(v.imag, k, out=out.imag)
    return out


def _condition(rows, scale):
    """Hadamard ratio |det M| / Π‖row‖ of the velocity system (moment column over ``scale``):
    1 for three lead lines at right angles through well-spread points, 0 when they meet in
    one point or are parallel (the group's singular position)."""
    m = [(a, b, c / scale) for a, b, c in rows]
    (a1, b1, c1), (a2, b2, c2), (a3, b3, c3) = m
    det = a1 * (b2 * c3 - b3 * c2) - b1 * (a2 * c3 - a3 * c2) + c1 * (a2 * b3 - a3 * b2)
    norm = np.ones_like(det)
    for a, b, c in m:
        norm = norm * np.sqrt(a * a + b * b + c * c)
    with np.errstate(all="ignore"):
        return np.abs(det) / norm
