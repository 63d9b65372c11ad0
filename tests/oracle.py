"""An independent high-precision reference: positions by Newton iteration on the loop-closure
equations in mpmath (50 digits), started from velplan's float64 positions so the branch is
the same, and velocities/accelerations by mpmath's numerical differentiation of them.

It shares no code with velplan's closed forms: only the mechanism description.
"""

from __future__ import annotations

import mpmath as mp

from velplan.analysis.solver import solve
from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Mechanism
from velplan.mechanism.structure import coincident_points, schedule

mp.mp.dps = 50


def _tol():
    """Newton tolerance at the working precision (mp.diff raises it while differencing)."""
    return mp.eps * 2**16


def _rot(theta):
    return mp.cos(theta), mp.sin(theta)


def positions(mech: Mechanism, phi, start) -> tuple[dict, dict]:
    """Points {name: (x, y)} and link angles {link: θ} at crank angle ``phi`` (mpf), by Newton
    iteration from ``start`` (a float64 `Kinematics` at the same angle, position 0)."""
    P = {k: (mp.mpf(x), mp.mpf(y)) for k, (x, y) in mech.ground}
    T = {"0": mp.mpf(0)}
    origin = {"0": mech.ground[0][0]}

    def guide(g):
        th = T[g.link] + g.angle
        ux, uy = _rot(th)
        gx, gy = P[g.through]
        return (gx - g.offset * uy, gy + g.offset * ux), (ux, uy)

    def f0(name):
        return [mp.mpf(float(v)) for v in start.positions[0, start.point_index[name]]]

    for item in schedule(mech):
        if isinstance(item, Crank):
            ox, oy = P[item.pivot]
            c, s = _rot(phi)
            P[item.tip] = (ox + item.length * c, oy + item.length * s)
            T[item.link], origin[item.link] = phi, item.pivot
        elif isinstance(item, LinkPoint):
            ox, oy = P[origin[item.link]]
            c, s = _rot(T[item.link])
            P[item.name] = (ox + item.along * c - item.offset * s, oy + item.along * s + item.offset * c)
        elif isinstance(item, RRR):
            (ax, ay), (dx, dy) = P[item.joints[0]], P[item.joints[1]]
            l1, l2 = item.lengths
            x, y = mp.findroot(
                lambda x, y: [(x - ax) ** 2 + (y - ay) ** 2 - l1**2, (x - dx) ** 2 + (y - dy) ** 2 - l2**2],
                f0(item.point), tol=_tol())
            P[item.point] = (x, y)
            T[item.links[0]], T[item.links[1]] = mp.atan2(y - ay, x - ax), mp.atan2(y - dy, x - dx)
            origin[item.links[0]], origin[item.links[1]] = item.joints
        elif isinstance(item, RRP):
            (ax, ay) = P[item.joint]
            (bx, by), (ux, uy) = guide(item.guide)
            x, y = mp.findroot(
                lambda x, y: [(x - ax) ** 2 + (y - ay) ** 2 - item.length**2, ux * (y - by) - uy * (x - bx)],
                f0(item.point), tol=_tol())
            P[item.point] = (x, y)
            T[item.links[0]], origin[item.links[0]] = mp.atan2(y - ay, x - ax), item.joint
            T[item.links[1]], origin[item.links[1]] = T[item.guide.link] + item.guide.angle, item.point
            if item.coincident:
                P[item.coincident] = (x, y)
        elif isinstance(item, RPR):
            (ax, ay), (ox, oy) = P[item.joint], P[item.pivot]
            th0 = mp.mpf(float(start.angles[0, start.link_index[item.links[1]]]))
            th = mp.findroot(lambda t: -mp.sin(t) * (ax - ox) + mp.cos(t) * (ay - oy) - item.offset, th0,
                             tol=_tol())
            T[item.links[0]] = T[item.links[1]] = th
            origin[item.links[0]], origin[item.links[1]] = item.joint, item.pivot
            if item.coincident:
                P[item.coincident] = (ax, ay)
        elif isinstance(item, PRP):
            (b1, u1), (b2, u2) = guide(item.guides[0]), guide(item.guides[1])
            s1, s2 = mp.lu_solve(mp.matrix([[u1[0], -u2[0]], [u1[1], -u2[1]]]),
                                 mp.matrix([b2[0] - b1[0], b2[1] - b1[1]]))
            P[item.point] = (b1[0] + s1 * u1[0], b1[1] + s1 * u1[1])
            for k, g in zip(item.links, item.guides):
                T[k], origin[k] = T[g.link] + g.angle, item.point
            for name in item.coincident:
                if name:
                    P[name] = P[item.point]
        elif isinstance(item, RPP):
            (bx, by), (ux, uy) = guide(item.guide)
            vx, vy = _rot(T[item.guide.link] + item.guide.angle + item.slot_angle)
            jx, jy = P[item.joint]
            s, t = mp.lu_solve(mp.matrix([[ux, vx], [uy, vy]]), mp.matrix([jx - bx, jy - by]))
            P[item.origin_name] = (bx + s * ux, by + s * uy)
            if item.coincident:
                P[item.coincident] = (jx, jy)
            T[item.links[0]], origin[item.links[0]] = T[item.guide.link] + item.guide.angle + item.slot_angle, item.joint
            T[item.links[1]], origin[item.links[1]] = T[item.guide.link] + item.guide.angle, item.origin_name
    return P, T, origin


def derivatives(mech: Mechanism, phi: float, omega1: float):
    """High-precision positions, velocities and accelerations at ``phi`` (rad), ε1 = 0.

    Returns ({point: (x, y, vx, vy, ax, ay)}, {link: (θ, ω, ε)}) as mpf values.
    """
    start = solve(mech, [phi])
    phi0 = mp.mpf(phi)
    memo: dict = {}

    def at(t):
        key = (t, mp.mp.prec)
        if key not in memo:
            memo[key] = positions(mech, t, start)
        return memo[key]

    P0, T0, origin = at(phi0)
    coincident = coincident_points(mech)

    def material(name):
        """Coordinates of the material point at ``name`` now: a coincident point is the point
        of its link that is there at phi0, carried along with the link."""
        if name not in coincident:
            return lambda t, k: at(t)[0][name][k]
        link = coincident[name]
        o = P0[origin[link]]
        c, s = _rot(-T0[link])
        dx, dy = P0[name][0] - o[0], P0[name][1] - o[1]
        lx, ly = c * dx - s * dy, s * dx + c * dy

        def f(t, k):
            Pt, Tt, _ = at(t)
            ot = Pt[origin[link]]
            ct, st = _rot(Tt[link])
            return (ot[0] + ct * lx - st * ly, ot[1] + st * lx + ct * ly)[k]

        return f

    pts = {}
    for name in P0:
        f = material(name)
        d = [[mp.diff(lambda t, k=k: f(t, k), phi0, n) for n in (1, 2)] for k in (0, 1)]
        pts[name] = (P0[name][0], P0[name][1], d[0][0] * omega1, d[1][0] * omega1,
                     d[0][1] * omega1**2, d[1][1] * omega1**2)
    links = {}
    for name in T0:
        if name == "0":
            continue
        d1, d2 = (mp.diff(lambda t: at(t)[1][name], phi0, n) for n in (1, 2))
        links[name] = (T0[name], d1 * omega1, d2 * omega1**2)
    return pts, links

