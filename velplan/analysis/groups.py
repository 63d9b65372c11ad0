"""Closed-form position, velocity and acceleration of each class-II group, vectorised.

Points are complex numbers z = x + i·y (m); velocities and accelerations likewise (m/s,
m/s²). For a point X of a link with origin O turning at ω, ε (rad/s, rad/s²):

    V_X = V_O + i·ω·(X − O),     a_X = a_O + (i·ε − ω²)·(X − O).

A slider moving at relative speed ṡ along a direction u on a link turning at ω adds
ṡ·u + s̈·u + 2·i·ω·ṡ·u (relative and Coriolis). Each group reduces its velocity and
acceleration equations to ``α·u + β·v = Q`` with unknown reals α, β, solved by `solve2`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Group, Guide


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


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of the cross product of two complex-encoded vectors."""
    return (a.real * b.imag) - (a.imag * b.real)


def solve2(u: np.ndarray, v: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Real α, β with α·u + β·v = q (complex u, v, q); inf/NaN where u ∥ v."""
    with np.errstate(divide="ignore", invalid="ignore"):
        d = cross(u, v)
        return cross(q, v) / d, cross(u, q) / d


def carried(m: Motion, link: LinkMotion, x: np.ndarray) -> Motion:
    """Motion of the point of ``link`` (whose origin moves as ``m``) that is at ``x`` now."""
    r = x - m.p
    return Motion(x, m.v + 1j * link.omega * r, m.a + (1j * link.epsilon - link.omega**2) * r)


class State:
    """Accumulates point and link motions while the mechanism is solved in order."""

    def __init__(self, n: int):
        self.n = n
        self.points: dict[str, Motion] = {}
        self.links: dict[str, LinkMotion] = {}
        self.slides: dict[str, Motion] = {}

    def guide(self, g: Guide) -> tuple[Motion, LinkMotion, np.ndarray, np.ndarray]:
        """The guide's point motion, its link's motion, its unit direction u and the base point
        of the guide line (complex arrays)."""
        m = self.points[g.through]
        link = self.links[g.link]
        u = np.exp(1j * (link.theta + g.angle))
        return m, link, u, m.p + 1j * g.offset * u


def _unit(theta: np.ndarray) -> np.ndarray:
    return np.exp(1j * theta)


def _sqrt_clamped(h2: np.ndarray, scale2: float) -> tuple[np.ndarray, np.ndarray]:
    """√h² where h² ≥ −tol (round-off at a toggle counts as 0), NaN where it is below."""
    closed = h2 >= -1e-14 * scale2
    with np.errstate(invalid="ignore"):
        return np.where(closed, np.sqrt(np.maximum(h2, 0.0)), np.nan), closed


def solve_rrr(g: RRR, st: State) -> GroupResult:
    """V_C = V_A + ω_AC × AC = V_D + ω_DC × DC (and the same with aⁿ + aᵗ) at the joint C."""
    A, D = (st.points[j] for j in g.joints)
    l1, l2 = g.lengths
    d = D.p - A.p
    L = np.abs(d)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (l1 * l1 - l2 * l2 + L * L) / (2 * L)
        h, closed = _sqrt_clamped(l1 * l1 - a * a, l1 * l1)
        c = A.p + (a + 1j * g.branch * h) * d / L
    r1, r2 = c - A.p, c - D.p
    w1, w2 = solve2(r1, -r2, -1j * (D.v - A.v))
    q = D.a - A.a + w1**2 * r1 - w2**2 * r2
    e1, e2 = solve2(r1, -r2, -1j * q)
    v = A.v + 1j * w1 * r1
    acc = A.a + (1j * e1 - w1**2) * r1
    cond = np.abs(cross(r1, r2)) / (l1 * l2)
    return GroupResult(
        points={g.point: Motion(c, v, acc)},
        links={
            g.links[0]: LinkMotion(g.joints[0], np.angle(r1), w1, e1),
            g.links[1]: LinkMotion(g.joints[1], np.angle(r2), w2, e2),
        },
        slides={},
        condition=cond,
        closed=closed,
    )


def solve_rrp(g: RRP, st: State) -> GroupResult:
    """V_C = V_A + ω × AC = V_C(guide) + V_rel (∥ guide); a_C adds aᵏ = 2·ω_guide × V_rel."""
    A = st.points[g.joint]
    G, link, u, base = st.guide(g.guide)
    w = (A.p - base) / u
    h, closed = _sqrt_clamped(g.length**2 - w.imag**2, g.length**2)
    s_along = w.real + g.branch * h
    c = base + s_along * u
    r = c - A.p
    cg = carried(G, link, c)
    sd, wr = solve2(u, -1j * r, A.v - cg.v)
    coriolis = 2j * link.omega * sd * u
    q = A.a - wr**2 * r - cg.a - coriolis
    sdd, er = solve2(u, -1j * r, q)
    slider, rod = g.links[1], g.links[0]
    points = {g.point: Motion(c, cg.v + sd * u, cg.a + coriolis + sdd * u)}
    if g.coincident:
        points[g.coincident] = cg
    return GroupResult(
        points=points,
        links={
            rod: LinkMotion(g.joint, np.angle(r), wr, er),
            slider: LinkMotion(g.point, link.theta + g.guide.angle, link.omega, link.epsilon),
        },
        slides={f"P:{slider}/{g.guide.link}": Motion(s_along, sd, sdd)},
        condition=np.abs(h) / g.length,
        closed=closed,
    )


def solve_rpr(g: RPR, st: State, length_scale: float) -> GroupResult:
    """V_A(block) = V_O + ω × OA + V_rel (∥ bar); a_A adds aᵏ = 2·ω × V_rel and aʳ ∥ bar."""
    A, O = st.points[g.joint], st.points[g.pivot]
    r = A.p - O.p
    dist = np.abs(r)
    s, closed = _sqrt_clamped(dist**2 - g.offset**2, dist**2 + length_scale**2)
    s = g.branch * s
    theta = np.angle(r) - np.angle(s + 1j * g.offset)
    u = _unit(theta)
    w, sd = solve2(1j * r, u, A.v - O.v)
    q = A.a - O.a + w**2 * r - 2j * w * sd * u
    e, sdd = solve2(1j * r, u, q)
    block, bar = g.links
    barm = LinkMotion(g.pivot, theta, w, e)
    points = {g.coincident: carried(O, barm, A.p)} if g.coincident else {}
    with np.errstate(divide="ignore", invalid="ignore"):
        cond = np.abs(s) / dist * np.minimum(1.0, dist / length_scale)
    return GroupResult(
        points=points,
        links={block: LinkMotion(g.joint, theta, w, e), bar: barm},
        slides={f"P:{block}/{bar}": Motion(s, sd, sdd)},
        condition=np.nan_to_num(cond),
        closed=closed,
    )


def solve_prp(g: PRP, st: State) -> GroupResult:
    """V_C = V_C(guide 1) + V_rel1 = V_C(guide 2) + V_rel2, each V_rel ∥ its guide."""
    (G1, k1, u1, b1), (G2, k2, u2, b2) = (st.guide(x) for x in g.guides)
    s1, s2 = solve2(u1, -u2, b2 - b1)
    c = b1 + s1 * u1
    c1, c2 = carried(G1, k1, c), carried(G2, k2, c)
    sd1, sd2 = solve2(u1, -u2, c2.v - c1.v)
    cor1, cor2 = 2j * k1.omega * sd1 * u1, 2j * k2.omega * sd2 * u2
    sdd1, sdd2 = solve2(u1, -u2, c2.a + cor2 - c1.a - cor1)
    m1, m2 = g.links
    points = {g.point: Motion(c, c1.v + sd1 * u1, c1.a + cor1 + sdd1 * u1)}
    for name, cm in zip(g.coincident, (c1, c2)):
        if name:
            points[name] = cm
    cond = np.abs(cross(u1, u2))
    return GroupResult(
        points=points,
        links={
            m1: LinkMotion(g.point, k1.theta + g.guides[0].angle, k1.omega, k1.epsilon),
            m2: LinkMotion(g.point, k2.theta + g.guides[1].angle, k2.omega, k2.epsilon),
        },
        slides={
            f"P:{m1}/{g.guides[0].link}": Motion(s1, sd1, sdd1),
            f"P:{m2}/{g.guides[1].link}": Motion(s2, sd2, sdd2),
        },
        condition=cond,
        closed=np.isfinite(s1) & (cond > 0),
    )


def solve_rpp(g: RPP, st: State) -> GroupResult:
    """V_B(block) = V_B(runner) + V_rel(∥ slot); V_B(runner) = V_B(guide link) + V_rel(∥ guide)."""
    B = st.points[g.joint]
    G, k, u, base = st.guide(g.guide)
    v = u * np.exp(1j * g.slot_angle)
    s, t = solve2(u, v, B.p - base)
    K = base + s * u
    bg = carried(G, k, B.p)
    sd, td = solve2(u, v, B.v - bg.v)
    cor_s, cor_t = 2j * k.omega * sd * u, 2j * k.omega * td * v
    sdd, tdd = solve2(u, v, B.a - bg.a - cor_s - cor_t)
    block, runner = g.links
    kmotion = carried(G, k, K)
    points = {}
    if g.coincident:
        points[g.coincident] = Motion(B.p, bg.v + sd * u, bg.a + cor_s + sdd * u)
    origin = g.origin_name
    points[origin] = Motion(K, kmotion.v + sd * u, kmotion.a + cor_s + sdd * u)
    cond = np.abs(np.sin(g.slot_angle)) * np.ones(st.n)
    theta = k.theta + g.guide.angle
    return GroupResult(
        points=points,
        links={
            block: LinkMotion(g.joint, theta + g.slot_angle, k.omega, k.epsilon),
            runner: LinkMotion(origin, theta, k.omega, k.epsilon),
        },
        slides={
            f"P:{block}/{runner}": Motion(t, td, tdd),
            f"P:{runner}/{g.guide.link}": Motion(s, sd, sdd),
        },
        condition=cond,
        closed=np.isfinite(s),
    )


SOLVERS: dict[type, Callable[..., GroupResult]] = {
    RRR: solve_rrr,
    RRP: solve_rrp,
    RPR: solve_rpr,
    PRP: solve_prp,
    RPP: solve_rpp,
}


def solve_group(g: Group, st: State, length_scale: float) -> GroupResult:
    """Dispatch to the closed-form solver of ``g``'s kind."""
    if isinstance(g, RPR):
        return solve_rpr(g, st, length_scale)
    return SOLVERS[type(g)](g, st)
