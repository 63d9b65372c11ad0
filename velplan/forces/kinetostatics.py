"""Kinetostatics (d'Alembert): pair reactions group by group, from the last group back to
the crank, and the balancing moment on the crank — vectorised over positions.

Conventions
-----------
A pair joins ``links = (k0, k1)`` (`velplan.mechanism.structure.pairs`; k0 is always the link
of the group that brings the pair). Its reaction is the force **on k0 from k1**, N; k1 feels
the opposite. A revolute pair's reaction acts at the joint. A prismatic pair's reaction is
perpendicular to its guide (no friction): a force N·n through a reference point of the guide
line plus a couple M (N·m), which is the same as the force N·n acting at the point
reference + (M/N)·u along the guide (u the guide's direction, n = i·u). The balancing moment
M_b is the moment the drive applies to the crank, counter-clockwise positive.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.forces.actions import Actions
from velplan.forces.common import cross, dot, point
from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Group, Mechanism, Pair, Triad, kind_entry
from velplan.mechanism.structure import pairs
from velplan.forces.reactions import ForcePolygon, Reaction, reaction_label  # noqa: F401  (re-exported)


@dataclass(frozen=True)
class Kinetostatics:
    """Result of `kinetostatics`.

    Attributes
    ----------
    phi : ndarray, shape (n,)
        Crank angles, rad.
    reactions : Mapping[str, Reaction]
        Pair name → reaction, in the order of `pairs`.
    balancing_moment : ndarray, shape (n,)
        M_b on the crank, N·m, counter-clockwise positive.
    polygons : Mapping[str, ForcePolygon]
        Group name (and ``"crank"``) → force polygon.
    condition : Mapping[str, ndarray]
        Group name → 1/cond of its system (6×6 for a dyad, 12×12 for a triad; 0 = singular,
        e.g. a toggle position, or a triad's three lead lines through one point).
    """

    mechanism: Mechanism = field(repr=False)
    phi: np.ndarray
    reactions: Mapping[str, Reaction]
    balancing_moment: np.ndarray
    polygons: Mapping[str, ForcePolygon]
    condition: Mapping[str, np.ndarray]

    def reaction(self, pair: str) -> Reaction:
        """The `Reaction` of pair ``pair``."""
        try:
            return self.reactions[pair]
        except KeyError:
            from velplan.errors import MechanismError

            raise MechanismError(f"unknown pair {pair!r}; known pairs: {', '.join(self.reactions)}") from None


# -- the solver -----------------------------------------------------------------------------


def _reference(g: Group, p: Pair, kin: Kinematics) -> np.ndarray:
    line = g.line_point(p.links[0]) if p.kind == "P" else None
    return point(kin, line or p.point)  # an RPP runner's guide line passes through K


class _Known:
    """Known forces (labelled, at points) and moments on each link, accumulated as groups are
    solved."""

    def __init__(self, kin: Kinematics, actions: Actions):
        self.forces: dict[str, list[tuple[str, np.ndarray, np.ndarray]]] = {}
        self.moments: dict[str, list[np.ndarray]] = {}
        for f in actions.forces:
            self.add_force(f.link, f.label, f.vector, point(kin, f.point))
        for m in actions.moments:
            self.add_moment(m.link, m.moment)

    def add_force(self, link: str, label: str, vector: np.ndarray, at: np.ndarray) -> None:
        self.forces.setdefault(link, []).append((label, vector, at))

    def add_moment(self, link: str, moment: np.ndarray) -> None:
        self.moments.setdefault(link, []).append(moment)

    def resultant(self, link: str, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Σ F (complex, N) and Σ M about ``ref`` (N·m) of the known actions on ``link``."""
        f = np.zeros(ref.shape, complex)
        m = np.zeros(ref.shape)
        for _, v, at in self.forces.get(link, ()):
            f = f + v
            m = m + cross(at - ref, v)
        for mm in self.moments.get(link, ()):
            m = m + mm
        return f, m


def _solve(a: np.ndarray, b: np.ndarray, ok: np.ndarray) -> np.ndarray:
    """x of a·x = b per position (k×k systems, stacked over n positions); NaN where not ``ok``
    or singular."""
    eye = np.broadcast_to(np.eye(a.shape[-1]), a.shape)
    a = np.where(ok[:, None, None], a, eye)
    b = np.where(ok[:, None], b, 0.0)
    try:
        x = np.linalg.solve(a, b[..., None])[..., 0]
    except np.linalg.LinAlgError:
        x = np.full(b.shape, np.nan)
        for i in range(a.shape[0]):
            try:
                x[i] = np.linalg.solve(a[i], b[i])
            except np.linalg.LinAlgError:
                pass
    x[~ok] = np.nan
    return x


def group_system(g: Group, gp: list[Pair], refs: list[np.ndarray], dirs: list[np.ndarray],
                 known: _Known) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The equilibrium equations of a group's links in its pairs' unknowns.

    Parameters
    ----------
    g : Group
        A dyad (2 links, 3 pairs) or a triad (4 links, 6 pairs).
    gp : list of Pair
        The group's pairs in the order of `pairs`.
    refs, dirs : list of ndarray (n,) complex
        Each pair's reference point (m) and, for a prismatic pair, the guide's unit direction.
    known : _Known
        The known forces and moments on the links.

    Returns
    -------
    a : ndarray, shape (n, 3·links, 2·pairs)
        Rows ΣFx, ΣFy, ΣM (about ``refs[1]``) per link in the order of ``g.links``; columns
        Rx, Ry of a revolute pair, N and the couple M of a prismatic pair, in the order of ``gp``.
    b : ndarray, shape (n, 3·links)
        Minus the known actions' resultants (N, N·m).
    origin : ndarray, shape (n,) complex
        The moment centre, m.
    """
    n = refs[0].shape[0]
    origin = refs[1]
    a = np.zeros((n, 3 * len(g.links), 2 * len(gp)))
    b = np.zeros((n, 3 * len(g.links)))
    for row, link in enumerate(g.links):
        r0 = 3 * row
        for j, p in enumerate(gp):
            if link not in p.links:
                continue
            s = 1.0 if p.links[0] == link else -1.0
            r = refs[j] - origin
            if p.kind == "R":
                a[:, r0, 2 * j] += s
                a[:, r0 + 1, 2 * j + 1] += s
                a[:, r0 + 2, 2 * j] += -s * r.imag
                a[:, r0 + 2, 2 * j + 1] += s * r.real
            else:
                nrm = 1j * dirs[j]
                a[:, r0, 2 * j] += s * nrm.real
                a[:, r0 + 1, 2 * j] += s * nrm.imag
                a[:, r0 + 2, 2 * j] += s * cross(r, nrm)
                a[:, r0 + 2, 2 * j + 1] += s
        f, m = known.resultant(link, origin)
        b[:, r0], b[:, r0 + 1], b[:, r0 + 2] = -f.real, -f.imag, -m
    return a, b, origin


def kinetostatics(mech: Mechanism, kin: Kinematics, actions: Actions) -> Kinetostatics:
    """Pair reactions and the balancing moment by d'Alembert's principle.

    Parameters
    ----------
    mech : Mechanism
    kin : Kinematics
        Positions of ``mech`` (only positions and link angles are used).
    actions : Actions
        Loads, gravity and inertia forces/moments at the positions of ``kin``.

    Returns
    -------
    Kinetostatics

    Notes
    -----
    Each Assur group is statically determinate: its pairs bring two unknowns each (Rx, Ry of a
    revolute pair; N and the couple M of a prismatic pair) and its links give three equations
    each, ΣF = 0 (two) and ΣM = 0 about a common point — 6 × 6 for a class-II dyad, 12 × 12 for
    a class-III triad, every reaction component of the group solved together (`group_system`).
    The groups are solved from the last to the first, each passing its reactions (reversed) to
    the links it is attached to; the crank then gives R01 = −ΣF and M_b = −ΣM_O1 (moments about
    its pivot).
    """
    n = len(kin)
    known = _Known(kin, actions)
    all_pairs = pairs(mech)
    reactions: dict[str, Reaction] = {}
    polygons: dict[str, ForcePolygon] = {}
    condition: dict[str, np.ndarray] = {}
    finite = kin.valid.copy()
    for g in reversed(mech.groups):
        polygon = kind_entry(POLYGONS, g, "velplan.forces.kinetostatics.POLYGONS")
        gp = [p for p in all_pairs if p.group == g.name]
        refs = [_reference(g, p, kin) for p in gp]
        dirs = [np.exp(1j * kin.angle(p.links[0])) if p.kind == "P" else np.full(n, np.nan + 0j) for p in gp]
        a, b, _ = group_system(g, gp, refs, dirs, known)
        ok = finite & np.isfinite(a).all(axis=(1, 2)) & np.isfinite(b).all(axis=1)
        x = _solve(a, b, ok)
        with np.errstate(invalid="ignore"):
            eye = np.eye(a.shape[-1])
            cond = np.where(ok, 1.0 / np.linalg.cond(np.where(ok[:, None, None], a, eye)), np.nan)
        condition[g.name] = cond
        group_known = {k: list(known.forces.get(k, ())) for k in g.links}
        group_moments = {k: list(known.moments.get(k, ())) for k in g.links}
        for j, p in enumerate(gp):
            if p.kind == "R":
                force, moment = x[:, 2 * j] + 1j * x[:, 2 * j + 1], np.zeros(n)
            else:
                force, moment = x[:, 2 * j] * 1j * dirs[j], x[:, 2 * j + 1]
            rc = Reaction(p, force, moment, refs[j], dirs[j])
            reactions[p.name] = rc
            if p.links[1] not in g.links:
                known.add_force(p.links[1], reaction_label(p.links[0], p.links[1]), -force, refs[j])
                if p.kind == "P":
                    known.add_moment(p.links[1], -moment)
        polygons[g.name] = polygon(mech, g, gp, reactions, group_known, group_moments, kin)
    # The crank: R01 and M_b.
    c = mech.crank
    pivot = point(kin, c.pivot)
    f, m = known.resultant(c.link, pivot)
    crank_pair = next(p for p in all_pairs if p.group == "crank")
    r01 = -f
    reactions[crank_pair.name] = Reaction(crank_pair, r01, np.zeros(n), pivot, np.full(n, np.nan + 0j))
    label = reaction_label(crank_pair.links[1], crank_pair.links[0])
    polygons["crank"] = ForcePolygon(
        "crank", "crank", tuple((lab, v) for lab, v, _ in known.forces.get(c.link, ())), (), ((label, r01),))
    ordered = {p.name: reactions[p.name] for p in all_pairs}
    return Kinetostatics(mech, kin.phi, ordered, -m, polygons, condition)


# -- force polygons ---------------------------------------------------------------------------


def _component(v: np.ndarray, e: np.ndarray) -> np.ndarray:
    return dot(v, e) * e


def _unit(z):
    with np.errstate(divide="ignore", invalid="ignore"):
        return z / np.abs(z)


def _rrr(g: RRR, r: list[Reaction], lab: list[str], kin: Kinematics):
    c = point(kin, g.point)
    ea, ed = _unit(c - r[0].reference), _unit(c - r[2].reference)
    first = [(lab[0] + "τ", _component(r[0].force, 1j * ea))]
    last = [(lab[2] + "τ", _component(r[2].force, 1j * ed))]
    return first, last, ((lab[0] + "n", ea), (lab[2] + "n", ed))


def _rrp(g: RRP, r: list[Reaction], lab: list[str], kin: Kinematics):
    ea = _unit(point(kin, g.point) - r[0].reference)
    first = [(lab[0] + "τ", _component(r[0].force, 1j * ea))]
    return first, [], ((lab[0] + "n", ea), (lab[2], 1j * r[2].direction))


def _rpr(g: RPR, r: list[Reaction], lab: list[str], kin: Kinematics):
    u = r[1].direction
    eo = _unit(r[0].reference - r[2].reference)
    first = [(lab[0] + "∥", _component(r[0].force, u))]
    last = [(lab[2] + "τ", _component(r[2].force, 1j * eo))]
    return first, last, ((lab[0] + "⊥", 1j * u), (lab[2] + "n", eo))


def _prp(g: PRP, r: list[Reaction], lab: list[str], kin: Kinematics):
    return [], [], ((lab[0], 1j * r[0].direction), (lab[2], 1j * r[2].direction))


def _rpp(g: RPP, r: list[Reaction], lab: list[str], kin: Kinematics):
    v = r[1].direction
    first = [(lab[0] + "∥", _component(r[0].force, v))]
    return first, [], ((lab[0] + "⊥", 1j * v), (lab[2], 1j * r[2].direction))


def _polygon(g: Group, gp: list[Pair], reactions: dict[str, Reaction],
             known: dict[str, list[tuple[str, np.ndarray, np.ndarray]]], kin: Kinematics) -> ForcePolygon:
    """Decompose the group's outer reactions as the graphical method does and close the polygon
    by intersecting the two unknown directions."""
    a, b = g.links
    loads = [(lab, v) for k in (a, b) for lab, v, _ in known.get(k, ())]
    r = [reactions[p.name] for p in gp]
    lab = [x.label for x in r]
    first, last, closing = _DYADS[type(g)](g, r, lab, kin)
    vectors = tuple(first + loads + last)
    n = len(kin)
    end = np.sum([vv for _, vv in vectors], axis=0) if vectors else np.zeros(n, complex)
    (l1, d1), (l2, d2) = closing
    with np.errstate(divide="ignore", invalid="ignore"):
        den = cross(d1, d2)
        alpha = cross(-end, d2) / den
        beta = cross(d1, -end) / den
    return ForcePolygon(g.name, g.kind, vectors, closing, ((l1, alpha * d1), (l2, beta * d2)))


def _dyad_polygon(mech, g, gp, reactions, known, moments, kin) -> ForcePolygon:
    return _polygon(g, gp, reactions, known, kin)


def _triad_polygon(mech, g, gp, reactions, known, moments, kin):
    from velplan.forces.triad import triad_polygon

    return triad_polygon(mech, g, gp, reactions, known, moments, kin)


#: How a dyad kind decomposes its outer reactions: (first, last, the two closing directions).
_DYADS = {RRR: _rrr, RRP: _rrp, RPR: _rpr, PRP: _prp, RPP: _rpp}

#: The kinetostatics' one lookup by group kind: kind → its force polygon
#: (mech, g, its pairs, reactions, known forces and moments by link, kin).
POLYGONS = {**dict.fromkeys(_DYADS, _dyad_polygon), Triad: _triad_polygon}
