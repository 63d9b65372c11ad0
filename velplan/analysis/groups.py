"""Closed-form position, velocity and acceleration of each class-II group, vectorised.

Points are complex numbers z = x + i·y (m); velocities and accelerations likewise (m/s,
m/s²). For a point X of a link with origin O turning at ω, ε (rad/s, rad/s²):

    V_X = V_O + i·ω·(X − O),     a_X = a_O + (i·ε − ω²)·(X − O).

A slider moving at relative speed ṡ along a direction u on a link turning at ω adds
ṡ·u + s̈·u + 2·i·ω·ṡ·u (relative and Coriolis). Each group reduces its velocity and
acceleration equations to ``α·u + β·v = Q`` with unknown reals α, β, solved by `solve2`.

The closed forms themselves (`rrr`, `rrp`, `rpr`, `prp`, `rpp`) take and return plain complex
values; the `solve_*` wrappers below fit them to the named points and links of a `State`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import numpy as np

from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Guide


@dataclass
class Motion:
    """Position, velocity, acceleration arrays (complex, shape (n,)) of one point."""

    p: np.ndarray
    v: np.ndarray
    a: np.ndarray


@dataclass
class LinkMotion:
    """Angle, ω, ε (rad, rad/s, rad/s²; shape (n,)) and origin point name of one link."""

    origin: str
    theta: np.ndarray
    omega: np.ndarray
    epsilon: np.ndarray


@dataclass
class GroupResult:
    """What a group adds: points, links, prismatic slides (s, ṡ, s̈ in m, m/s, m/s²), the
    condition estimate in [0, 1] (0 = singular) and the mask of assembled positions."""

    points: dict[str, Motion]
    links: dict[str, LinkMotion]
    slides: dict[str, Motion]
    condition: np.ndarray
    closed: np.ndarray
    units: dict = field(default_factory=dict)
    """Unit vectors cos θ + i·sin θ of links' reference directions where the group knows them
    without a sine (link name → complex array), for the points on those links."""
    spins: dict = field(default_factory=dict)
    """Links' i·ω and i·ε − ω² (complex arrays, 1/s and 1/s²) where the group has them already
    (link name → the pair), for the points on those links (`velplan.analysis.groups.carry`)."""


# ---- closed forms on plain complex values --------------------------------------------------
# Each function below works on complex/real numpy arrays (vectorised over positions) and on
# scalars alike (the compiled engine runs the very same functions per position), so it uses
# arithmetic and ufuncs only: no np.where, no errstate, no containers.


def cross(a, b):
    """z-component of the cross product of two complex-encoded vectors."""
    return (a.real * b.imag) - (a.imag * b.real)


def solve2(u, v, q):
    """Real α, β with α·u + β·v = q (complex u, v, q); inf/NaN where u ∥ v."""
    k = 1.0 / cross(u, v)
    return cross(q, v) * k, cross(u, q) * k


def cis(t):
    """The unit vector at angle ``t`` (rad): cos t + i·sin t."""
    return np.cos(t) + 1j * np.sin(t)


def direction(z):
    """The direction of the complex-encoded vector ``z`` (rad, in (−π, π]): `numpy.angle`'s own
    formula, written out so that numba compiles it without its numpy-function library."""
    return np.arctan2(z.imag, z.real)


def wrap_angle(t):
    """``t`` (rad) brought into (−π, π]: unchanged, bit for bit, when it is there already (−π
    itself becomes π)."""
    turns = np.ceil((t - np.pi) / (2 * np.pi)) * ((t <= -np.pi) | (t > np.pi))  # 0 inside
    return t - 2 * np.pi * turns


def carry(p, v, a, omega, epsilon, x):
    """Velocity and acceleration of the point at ``x`` of a link whose point at ``p`` moves
    with ``v``, ``a`` while the link turns at ``omega``, ``epsilon``."""
    r = x - p
    return v + 1j * omega * r, a + (1j * epsilon - omega * omega) * r


def crank_tip(p, length, phi, omega, epsilon):
    """Tip of a crank of ``length`` turning about the fixed pivot ``p`` at angle ``phi``, ``omega``,
    ``epsilon``: its position, velocity and acceleration."""
    r = length * cis(phi)
    return p + r, 1j * omega * r, (1j * epsilon - omega * omega) * r


def link_point(p, v, a, theta, omega, epsilon, along, offset):
    """The point ``along`` (m) the reference direction of a link (at ``theta``, turning at
    ``omega``, ``epsilon``) from its origin at ``p`` and ``offset`` (m) to its left: x, V, a."""
    x = p + (along + 1j * offset) * cis(theta)
    return (x, *carry(p, v, a, omega, epsilon, x))


def guide_line(p, theta, angle, offset):
    """Unit direction u and base point of a guide through ``p`` on a link at angle ``theta``."""
    u = cis(theta + angle)
    return u, p + 1j * offset * u


def sqrt_clamped(h2, tol):
    """(√h², closed): h² ≥ −tol counts as assembled (round-off at a toggle is 0), NaN below."""
    closed = h2 >= -tol
    # the second term is 0 where closed and NaN where not (√ of a negative number)
    return np.sqrt(np.maximum(h2, 0.0)) + np.sqrt(np.minimum(h2 + tol, 0.0)), closed


def rrr(Ap, Av, Aa, Dp, Dv, Da, l1, l2, branch):
    """RRR closed form: joint C, its motion, the two links' ω, ε and the condition."""
    d = Dp - Ap
    L = np.abs(d)
    a = (l1 * l1 - l2 * l2 + L * L) / (2 * L)
    h, closed = sqrt_clamped(l1 * l1 - a * a, 1e-14 * l1 * l1)
    c = Ap + (a + 1j * branch * h) * (d * (1.0 / L))
    r1, r2 = c - Ap, c - Dp
    w1, w2 = solve2(r1, -r2, -1j * (Dv - Av))
    q = Da - Aa + w1 * w1 * r1 - w2 * w2 * r2
    e1, e2 = solve2(r1, -r2, -1j * q)
    v = Av + 1j * w1 * r1
    acc = Aa + (1j * e1 - w1 * w1) * r1
    cond = np.abs(cross(r1, r2)) / (l1 * l2)
    return c, v, acc, direction(r1), w1, e1, direction(r2), w2, e2, cond, closed


def rrp(Ap, Av, Aa, Gp, Gv, Ga, gtheta, gw, ge, angle, offset, length, branch):
    """RRP closed form on a guide through G (of a link at gtheta, gw, ge): slider point C and
    its motion, the guide link's point at C, the rod's angle, ω, ε, the slide s, ṡ, s̈."""
    u, base = guide_line(Gp, gtheta, angle, offset)
    w = (Ap - base) / u
    h, closed = sqrt_clamped(length * length - w.imag * w.imag, 1e-14 * length * length)
    s = w.real + branch * h
    c = base + s * u
    r = c - Ap
    gv, ga = carry(Gp, Gv, Ga, gw, ge, c)
    sd, wr = solve2(u, -1j * r, Av - gv)
    coriolis = 2j * gw * sd * u
    sdd, er = solve2(u, -1j * r, Aa - wr * wr * r - ga - coriolis)
    return (c, gv + sd * u, ga + coriolis + sdd * u, gv, ga, direction(r), wr, er, s, sd, sdd,
            np.abs(h) / length, closed)


def rpr(Ap, Av, Aa, Op, Ov, Oa, offset, branch, scale):
    """RPR closed form: the bar's angle, ω, ε (the block turns with it), the slide s, ṡ, s̈ of
    the block along the bar, the bar's point at A (velocity, acceleration), the condition."""
    r = Ap - Op
    dist = np.abs(r)
    s, closed = sqrt_clamped(dist * dist - offset * offset, 1e-14 * (dist * dist + scale * scale))
    s = branch * s
    theta = direction(r) - direction(s + 1j * offset)
    u = cis(theta)
    w, sd = solve2(1j * r, u, Av - Ov)
    e, sdd = solve2(1j * r, u, Aa - Oa + w * w * r - 2j * w * sd * u)
    bv, ba = carry(Op, Ov, Oa, w, e, Ap)
    # |s|/dist, reduced where the bar is shorter than the mechanism (0 when A is at O)
    cond = np.abs(s) * np.minimum(1.0 / dist, 1.0 / scale)
    return theta, w, e, s, sd, sdd, bv, ba, cond, closed


def prp(G1p, G1v, G1a, t1, w1, e1, angle1, offset1, G2p, G2v, G2a, t2, w2, e2, angle2, offset2):
    """PRP closed form: C on two guides, its motion, the guides' points at C, both slides."""
    u1, b1 = guide_line(G1p, t1, angle1, offset1)
    u2, b2 = guide_line(G2p, t2, angle2, offset2)
    s1, s2 = solve2(u1, -u2, b2 - b1)
    c = b1 + s1 * u1
    c1v, c1a = carry(G1p, G1v, G1a, w1, e1, c)
    c2v, c2a = carry(G2p, G2v, G2a, w2, e2, c)
    sd1, sd2 = solve2(u1, -u2, c2v - c1v)
    cor1, cor2 = 2j * w1 * sd1 * u1, 2j * w2 * sd2 * u2
    sdd1, sdd2 = solve2(u1, -u2, c2a + cor2 - c1a - cor1)
    cond = np.abs(cross(u1, u2))
    closed = np.isfinite(s1) & (cond > 0)
    return (c, c1v + sd1 * u1, c1a + cor1 + sdd1 * u1, c1v, c1a, c2v, c2a,
            s1, sd1, sdd1, s2, sd2, sdd2, cond, closed)


def rpp(Bp, Bv, Ba, Gp, Gv, Ga, gtheta, gw, ge, angle, offset, slot):
    """RPP closed form: K (slot × guide) and its motion, the runner's point at B, the slides
    t (block in the slot) and s (runner on the guide) with their rates."""
    u, base = guide_line(Gp, gtheta, angle, offset)
    v = u * cis(slot)
    s, t = solve2(u, v, Bp - base)
    k = base + s * u
    bv, ba = carry(Gp, Gv, Ga, gw, ge, Bp)
    sd, td = solve2(u, v, Bv - bv)
    cor_s, cor_t = 2j * gw * sd * u, 2j * gw * td * v
    sdd, tdd = solve2(u, v, Ba - ba - cor_s - cor_t)
    kv, ka = carry(Gp, Gv, Ga, gw, ge, k)
    return (k, kv + sd * u, ka + cor_s + sdd * u, bv + sd * u, ba + cor_s + sdd * u,
            s, sd, sdd, t, td, tdd, np.isfinite(s))


# ---- the same closed forms on the named points and links of a State ------------------------


def slide_name(slider: str, guide_link: str) -> str:
    """Name of the prismatic pair of ``slider`` on ``guide_link``."""
    return f"P:{slider}/{guide_link}"


class State:
    """Accumulates point and link motions while the mechanism is solved in order."""

    def __init__(self, n: int):
        self.n = n
        self.points: dict[str, Motion] = {}
        self.links: dict[str, LinkMotion] = {}
        self.slides: dict[str, Motion] = {}
        self.units: dict[str, np.ndarray] = {}
        """Unit vectors of links' reference directions (`GroupResult.units`), and those found for
        their points."""
        self.spins: dict[str, tuple] = {}
        """Links' i·ω and i·ε − ω² (`GroupResult.spins`), and those found for their points."""
        self.fixed: frozenset[str] = frozenset()
        """The ground points (velocity and acceleration 0), where the solver set them."""
        self.sink = None
        """The block's views into preallocated outputs (`velplan.analysis.blocks.Sink`), or None:
        what is put into the state is written there, and producers may compute straight into
        them (`out_point`, `out_link`)."""

    def out_point(self, name: str) -> Motion | None:
        """The output arrays (p, v, a) of point ``name`` to compute into, or None (no sink)."""
        return None if self.sink is None else self.sink.points.get(name)

    def out_link(self, name: str) -> LinkMotion | None:
        """The output arrays (θ, ω, ε) of link ``name`` to compute into, or None (no sink)."""
        return None if self.sink is None else self.sink.links.get(name)

    def put_point(self, name: str, m: Motion) -> None:
        """Point ``name`` solved: its arrays copied into the sink's (those not computed there)."""
        slot = self.out_point(name)
        if slot is not None:
            _into(slot, m)
            m = slot
        self.points[name] = m

    def put_link(self, name: str, m: LinkMotion) -> None:
        """Link ``name`` solved (see `put_point`)."""
        slot = self.out_link(name)
        if slot is not None:
            _into(slot, m)
            m = LinkMotion(m.origin, slot.theta, slot.omega, slot.epsilon)
        self.links[name] = m

    def put_slide(self, name: str, m: Motion) -> None:
        """Slide ``name`` solved: s, ṡ, s̈ (their real parts) copied into the sink's rows."""
        slot = None if self.sink is None else self.sink.slides.get(name)
        if slot is not None:
            for dst, src in zip(slot, (m.p, m.v, m.a)):
                np.copyto(dst, src.real if np.iscomplexobj(src) else src)
        self.slides[name] = m

    def guide(self, g: Guide) -> tuple:
        """Arguments of a closed form for guide ``g``: its point's p, v, a, its link's θ, ω, ε,
        the guide's angle and offset."""
        m, link = self.points[g.through], self.links[g.link]
        return m.p, m.v, m.a, link.theta, link.omega, link.epsilon, g.angle, g.offset


def _into(slot, m) -> None:
    """Copy the arrays of ``m`` (a `Motion` or `LinkMotion`) into ``slot``'s, skipping those that
    are ``slot``'s already (computed in place)."""
    for key in ("p", "v", "a") if isinstance(slot, Motion) else ("theta", "omega", "epsilon"):
        dst, src = getattr(slot, key), getattr(m, key)
        if src is not dst:
            np.copyto(dst, src)


def solve_rrr(g: RRR, st: State) -> GroupResult:
    """V_C = V_A + ω_AC × AC = V_D + ω_DC × DC (and the same with aⁿ + aᵗ) at the joint C."""
    A, D = (st.points[j] for j in g.joints)
    c, v, a, t1, w1, e1, t2, w2, e2, cond, closed = rrr(A.p, A.v, A.a, D.p, D.v, D.a, *g.lengths, g.branch)
    return GroupResult(
        points={g.point: Motion(c, v, a)},
        links={
            g.links[0]: LinkMotion(g.joints[0], t1, w1, e1),
            g.links[1]: LinkMotion(g.joints[1], t2, w2, e2),
        },
        slides={},
        condition=cond,
        closed=closed,
    )


def solve_rrp(g: RRP, st: State) -> GroupResult:
    """V_C = V_A + ω × AC = V_C(guide) + V_rel (∥ guide); a_C adds aᵏ = 2·ω_guide × V_rel."""
    A = st.points[g.joint]
    link = st.links[g.guide.link]
    c, v, a, gv, ga, tr, wr, er, s, sd, sdd, cond, closed = rrp(
        A.p, A.v, A.a, *st.guide(g.guide), g.length, g.branch)
    rod, slider = g.links
    points = {g.point: Motion(c, v, a)}
    if g.coincident:
        points[g.coincident] = Motion(c, gv, ga)
    return GroupResult(
        points=points,
        links={
            rod: LinkMotion(g.joint, tr, wr, er),
            slider: LinkMotion(g.point, link.theta + g.guide.angle, link.omega, link.epsilon),
        },
        slides={slide_name(slider, g.guide.link): Motion(s, sd, sdd)},
        condition=cond,
        closed=closed,
    )


def solve_rpr(g: RPR, st: State, length_scale: float) -> GroupResult:
    """V_A(block) = V_O + ω × OA + V_rel (∥ bar); a_A adds aᵏ = 2·ω × V_rel and aʳ ∥ bar."""
    A, O = st.points[g.joint], st.points[g.pivot]
    theta, w, e, s, sd, sdd, bv, ba, cond, closed = rpr(
        A.p, A.v, A.a, O.p, O.v, O.a, g.offset, g.branch, length_scale)
    block, bar = g.links
    return GroupResult(
        points={g.coincident: Motion(A.p, bv, ba)} if g.coincident else {},
        links={block: LinkMotion(g.joint, theta, w, e), bar: LinkMotion(g.pivot, theta, w, e)},
        slides={slide_name(block, bar): Motion(s, sd, sdd)},
        condition=cond,
        closed=closed,
    )


def solve_prp(g: PRP, st: State) -> GroupResult:
    """V_C = V_C(guide 1) + V_rel1 = V_C(guide 2) + V_rel2, each V_rel ∥ its guide."""
    (c, v, a, c1v, c1a, c2v, c2a, s1, sd1, sdd1, s2, sd2, sdd2, cond, closed) = prp(
        *st.guide(g.guides[0]), *st.guide(g.guides[1]))
    m1, m2 = g.links
    points = {g.point: Motion(c, v, a)}
    for name, cv, ca in zip(g.coincident, (c1v, c2v), (c1a, c2a)):
        if name:
            points[name] = Motion(c, cv, ca)
    k1, k2 = (st.links[x.link] for x in g.guides)
    return GroupResult(
        points=points,
        links={
            m1: LinkMotion(g.point, k1.theta + g.guides[0].angle, k1.omega, k1.epsilon),
            m2: LinkMotion(g.point, k2.theta + g.guides[1].angle, k2.omega, k2.epsilon),
        },
        slides={
            slide_name(m1, g.guides[0].link): Motion(s1, sd1, sdd1),
            slide_name(m2, g.guides[1].link): Motion(s2, sd2, sdd2),
        },
        condition=cond,
        closed=closed,
    )


def solve_rpp(g: RPP, st: State) -> GroupResult:
    """V_B(block) = V_B(runner) + V_rel(∥ slot); V_B(runner) = V_B(guide link) + V_rel(∥ guide)."""
    B = st.points[g.joint]
    k = st.links[g.guide.link]
    K, kv, ka, bv, ba, s, sd, sdd, t, td, tdd, closed = rpp(
        B.p, B.v, B.a, *st.guide(g.guide), g.slot_angle)
    block, runner = g.links
    points = {g.coincident: Motion(B.p, bv, ba)} if g.coincident else {}
    origin = g.origin_name
    points[origin] = Motion(K, kv, ka)
    theta = k.theta + g.guide.angle
    return GroupResult(
        points=points,
        links={
            block: LinkMotion(g.joint, theta + g.slot_angle, k.omega, k.epsilon),
            runner: LinkMotion(origin, theta, k.omega, k.epsilon),
        },
        slides={
            slide_name(block, runner): Motion(t, td, tdd),
            slide_name(runner, g.guide.link): Motion(s, sd, sdd),
        },
        condition=np.full(st.n, abs(np.sin(g.slot_angle))),
        closed=closed,
    )
