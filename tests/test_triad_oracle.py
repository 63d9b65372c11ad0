"""Every class III (triad) catalogue mechanism against an independent 50-digit reference.

The reference shares no code with velplan's solver: the crank, the RRR dyads, the points on
links and the triad are written out here in mpmath. Positions: Newton's method on the closure
equations (|B − A| = l2, |C − E| = l4, |D − F| = l5 with B, C, D rigid on the base link, or
the block's line condition for a block lead), started from velplan's float answer so that the
branch is the same. Velocities and accelerations: the linear systems of the first and second
derivatives of those equations, solved in mpmath. Only the mechanism description is shared.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

import velplan
from velplan.analysis.solver import special_pair
from velplan.mechanism.loader import catalogue_names
from velplan.mechanism.model import GROUND, RRR, Triad

DPS = 50
ANGLES = np.radians(np.arange(12) * 30.0 + 7.0)
TOL = 1e-12


def _cis(t):
    """e^{i·t} for a real t (mpmath's expj raises ComplexResult on an mpf in some releases)."""
    return mp.mpc(mp.cos(t), mp.sin(t))


def triad_mechanisms() -> list[str]:
    """Catalogue names whose mechanism holds a ``kind = "triad"`` group."""
    return [n for n in catalogue_names() if any(g.kind == "triad" for g in velplan.load(n).groups)]


# ---- small mpmath vector algebra (points as mpc) ---------------------------------------------


def mpc(xy) -> mp.mpc:
    return mp.mpc(float(xy[0]), float(xy[1]))


def dot(a, b):
    return a.real * b.real + a.imag * b.imag


def cross(a, b):
    return a.real * b.imag - a.imag * b.real


def carried(origin, theta, w, e, p):
    """Velocity and acceleration of the point p of a link (origin motion, ω, ε)."""
    r = p - origin[0]
    return origin[1] + 1j * w * r, origin[2] + (1j * e - w * w) * r


def rod_motion(p, j):
    """Angle, ω, ε of a link whose frame runs from the point p to j (motions (x, v, a))."""
    d, dv, da = j[0] - p[0], j[1] - p[1], j[2] - p[2]
    d2 = dot(d, d)
    w = cross(d, dv) / d2
    e = cross(d, da) / d2 - 2 * dot(d, dv) * w / d2
    return mp.atan2(d.imag, d.real), w, e


# ---- the reference solution at one crank angle -------------------------------------------------


class Reference:
    """Points {name: (x, v, a)} (mpc) and links {name: (θ, ω, ε)} at one crank angle."""

    def __init__(self, mech, phi: float, start: velplan.Kinematics, i: int):
        self.mech, self.start, self.i = mech, start, i
        self.P = {n: (mpc(xy), mp.mpc(0), mp.mpc(0)) for n, xy in mech.ground}
        self.L = {GROUND: (mp.mpf(0), mp.mpf(0), mp.mpf(0))}
        self.origin = {GROUND: mech.ground[0][0]}
        self.slides = {}
        self._crank(mp.mpf(phi))
        done = set()
        for g in mech.groups:
            self._points(done)
            if isinstance(g, RRR):
                self._rrr(g)
            elif isinstance(g, Triad):
                self._triad(g)
            else:
                raise NotImplementedError(f"the oracle knows no {g.kind} group: extend it")
        self._points(done)

    def guess(self, name):
        return mpc(self.start.positions[self.i, self.start.point_index[name]])

    def _crank(self, phi):
        c = self.mech.crank
        w, e, r = mp.mpf(c.omega), mp.mpf(c.epsilon), c.length * _cis(phi)
        self.P[c.tip] = (self.P[c.pivot][0] + r, 1j * w * r, (1j * e - w * w) * r)
        self.L[c.link] = (phi, w, e)
        self.origin[c.link] = c.pivot

    def _points(self, done):
        for p in self.mech.points:
            if p.name in done or p.link not in self.L:
                continue
            o = self.P[self.origin[p.link]]
            th, w, e = self.L[p.link]
            x = o[0] + mp.mpc(p.along, p.offset) * _cis(th)
            self.P[p.name] = (x, *carried(o, th, w, e, x))
            done.add(p.name)

    def _rrr(self, g):
        a, d = (self.P[n] for n in g.joints)
        l1, l2 = g.lengths

        def f(x, y):
            c = mp.mpc(x, y)
            return [abs(c - a[0]) ** 2 - l1 ** 2, abs(c - d[0]) ** 2 - l2 ** 2]

        g0 = self.guess(g.point)
        x, y = mp.findroot(f, (g0.real, g0.imag), tol=mp.mpf(10) ** (8 - DPS))
        c = mp.mpc(x, y)
        m = mp.matrix([[(c - a[0]).real, (c - a[0]).imag], [(c - d[0]).real, (c - d[0]).imag]])
        v = mp.lu_solve(m, mp.matrix([dot(c - a[0], a[1]), dot(c - d[0], d[1])]))
        cv = mp.mpc(v[0], v[1])
        acc = mp.lu_solve(m, mp.matrix([dot(c - a[0], a[2]) - abs(cv - a[1]) ** 2,
                                        dot(c - d[0], d[2]) - abs(cv - d[1]) ** 2]))
        self.P[g.point] = (c, cv, mp.mpc(acc[0], acc[1]))
        for link, known in zip(g.links, (a, d)):
            self.L[link] = rod_motion(known, self.P[g.point])
        self.origin[g.links[0]], self.origin[g.links[1]] = g.joints

    def _triad(self, g):
        bc, cd, db = (mp.mpf(s) for s in g.sides)
        along = (bc * bc + db * db - cd * cd) / (2 * bc)
        local = [mp.mpc(0), mp.mpc(bc, 0), mp.mpc(along, g.side * mp.sqrt(db * db - along * along))]
        rows = []  # per lead: ("rod", outer motion, length) or ("block", u, base point)
        for lead in g.leads:
            if lead.slider:
                gd = lead.guide
                assert gd.link == GROUND, "the oracle knows blocks on frame guides only"
                u = _cis(mp.mpf(gd.angle))
                rows.append(("block", u, self.P[gd.through][0] + 1j * u * gd.offset))
            else:
                rows.append(("rod", self.P[lead.joint], mp.mpf(lead.length)))

        def f(x, y, th):
            out = []
            for (kind, a, b), r in zip(rows, local):
                j = mp.mpc(x, y) + r * _cis(th)
                out.append(abs(j - a[0]) ** 2 - b ** 2 if kind == "rod" else cross(a, j - b))
            return out

        b0 = self.guess(g.joints[0])
        th0 = self.start.angles[self.i, self.start.link_index[g.base]]
        x, y, th = mp.findroot(f, (b0.real, b0.imag, mp.mpf(th0)), tol=mp.mpf(10) ** (8 - DPS))
        X = mp.mpc(x, y)
        js = [X + r * _cis(th) for r in local]
        # first derivatives: unknowns (Vx, Vy, ω); J' = V + iω(J − X)
        m = mp.matrix(3, 3)
        rhs_v = mp.matrix(3, 1)
        for k, ((kind, a, b), j) in enumerate(zip(rows, js)):
            n = j - a[0] if kind == "rod" else 1j * a
            m[k, 0], m[k, 1], m[k, 2] = n.real, n.imag, dot(n, 1j * (j - X))
            rhs_v[k] = dot(n, a[1]) if kind == "rod" else 0
        s = mp.lu_solve(m, rhs_v)
        V, w = mp.mpc(s[0], s[1]), s[2]
        jv = [V + 1j * w * (j - X) for j in js]
        # second derivatives: J'' = A + iε(J − X) − ω²(J − X)
        rhs_a = mp.matrix(3, 1)
        for k, ((kind, a, b), j, v) in enumerate(zip(rows, js, jv)):
            n = j - a[0] if kind == "rod" else 1j * a
            known = w * w * dot(n, j - X)
            rhs_a[k] = known + (dot(n, a[2]) - abs(v - a[1]) ** 2 if kind == "rod" else 0)
        s = mp.lu_solve(m, rhs_a)
        A, e = mp.mpc(s[0], s[1]), s[2]
        ja = [A + (1j * e - w * w) * (j - X) for j in js]
        for name, j, v, a in zip(g.joints, js, jv, ja):
            self.P[name] = (j, v, a)
        self.L[g.base], self.origin[g.base] = (th, w, e), g.joints[0]
        for lead, (kind, a, b), name in zip(g.leads, rows, g.joints):
            if kind == "rod":
                self.L[lead.link], self.origin[lead.link] = rod_motion(a, self.P[name]), lead.joint
            else:
                self.L[lead.link], self.origin[lead.link] = (mp.mpf(lead.guide.angle), 0, 0), name
                self.slides[f"P:{lead.link}/{lead.guide.link}"] = (dot(self.P[name][0] - b, a),
                                                                   dot(self.P[name][1], a), dot(self.P[name][2], a))
                if lead.coincident:
                    self.P[lead.coincident] = (self.P[name][0], mp.mpc(0), mp.mpc(0))
        self._special(g, rows, X, th, w, e)

    def _special(self, g, rows, X, th, w, e):
        """Assur's special point: the crossing of the lines of the two chosen leads, a point of
        the base link."""
        lines = []
        for i in special_pair(self.mech, g):
            kind, a, _ = rows[i]
            j = self.P[g.joints[i]][0]
            lines.append((j, j - a[0] if kind == "rod" else 1j * a))
        (p1, d1), (p2, d2) = lines
        k = p1 + d1 * cross(p2 - p1, d2) / cross(d1, d2)
        self.P[g.special_name] = (k, *carried(self.P[g.joints[0]], th, w, e, k))


# ---- the comparison ----------------------------------------------------------------------------


def _scaled_errors(name):
    mech = velplan.load(name)
    kin = velplan.solve(mech, ANGLES)
    assert kin.valid.all()
    size = max(float(np.max(np.abs(kin.positions))), 1e-9)
    vmax, amax = kin.largest("velocity"), kin.largest("acceleration")
    wmax = float(np.max(np.abs(kin.omegas)))
    emax = float(np.max(np.abs(kin.epsilons)))
    worst = {}
    with mp.workdps(DPS):
        for i, phi in enumerate(ANGLES):
            ref = Reference(mech, float(phi), kin, i)
            assert set(ref.P) == set(kin.point_index), "the oracle solves every point velplan reports"
            assert set(ref.L) - {GROUND} == set(kin.link_index)
            for n, j in kin.point_index.items():
                for q, arr, scale in ((0, kin.positions, size), (1, kin.velocities, vmax),
                                      (2, kin.accelerations, amax)):
                    z = complex(ref.P[n][q])
                    err = abs(complex(*arr[i, j]) - z) / scale
                    worst[(n, q)] = max(worst.get((n, q), 0.0), err)
            for n, j in kin.link_index.items():
                th, w, e = (float(x) for x in ref.L[n])
                errs = (abs(math.remainder(kin.angles[i, j] - th, 2 * math.pi)),
                        abs(kin.omegas[i, j] - w) / wmax, abs(kin.epsilons[i, j] - e) / emax)
                for q, err in enumerate(errs):
                    worst[(f"link {n}", q)] = max(worst.get((f"link {n}", q), 0.0), err)
            for n, j in kin.slide_index.items():
                for q, scale in ((0, size), (1, vmax), (2, amax)):
                    err = abs(kin.slides[i, j, q] - float(ref.slides[n][q])) / scale
                    worst[(n, q)] = max(worst.get((n, q), 0.0), err)
    return worst


def test_catalogue_has_three_class_three_mechanisms():
    assert len(triad_mechanisms()) >= 3


@pytest.mark.parametrize("name", triad_mechanisms())
def test_triad_against_the_50_digit_reference(name):
    worst = _scaled_errors(name)
    bad = {k: v for k, v in worst.items() if not v <= TOL}
    assert not bad, f"{name}: scaled errors above {TOL:g}: {bad}"
    assert max(worst.values()) > 0  # a real comparison, not an empty one
