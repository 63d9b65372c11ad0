"""Kinetostatics of a class III group (Assur's triad) the way the course draws it.

Each outer reaction (on a lead from the known link it is jointed to) is split into the
component along the lead's line, Rⁿ, and the one across it, Rᵗ:

* a rod lead P → J: Rᵗ from the moment equation of the rod about its inner joint J
  (Rⁿ passes through J);
* a block lead on a guide: the guide pushes along its normal only (no friction), so Rᵗ = 0
  and the lead's line is the guide's normal through J; the block's moment equation about J
  gives the couple of the prismatic pair (the offset of N along the guide).

The moment of the whole group about Assur's special point S — where the lines of two leads
(the solver's ``special_pair``) meet, so that their Rⁿ have no moment about it — gives the
third lead's Rⁿ. The force polygon of the group is then laid out: the Rᵗ, the third Rⁿ and
all the known forces on the four links, closed by the two remaining Rⁿ along their known
directions. Each inner reaction follows from the equilibrium of its lead. Everything here is
computed from the moment and force equations alone, independently of the 12 × 12 system of
`velplan.forces.kinetostatics`, and agrees with it to round-off.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.analysis.solver import special_pair
from velplan.forces.common import cross, point
from velplan.forces.reactions import ForcePolygon, Reaction
from velplan.mechanism.model import Mechanism, Pair, Triad

Known = Mapping[str, list]
"""Link → known forces (label, vector (n,) complex N, point (n,) complex m), or → moments."""


def _unit(z: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", invalid="ignore"):
        return z / np.abs(z)


def _resultant(forces: Known, moments: Known, link: str, ref: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Σ F (complex, N) and Σ M about ``ref`` (N·m) of the known actions on ``link``."""
    f = np.zeros(ref.shape, complex)
    m = np.zeros(ref.shape)
    for _, v, at in forces.get(link, ()):
        f = f + v
        m = m + cross(at - ref, v)
    for mm in moments.get(link, ()):
        m = m + mm
    return f, m


@dataclass(frozen=True)
class LeadForces:
    """The outer reaction of one lead split as the course draws it, over n positions.

    Attributes
    ----------
    label : str
        The outer reaction's label (``"R12"``: on lead 2 from link 1).
    rod : bool
        True for a rod lead, False for a block on a guide.
    line_point : ndarray (n,) complex
        A point of the lead's line, m: the rod's outer joint, or the block's joint J.
    along : ndarray (n,) complex
        Unit direction of the lead's line: P → J along the rod, or the guide's normal i·u.
    tangential : ndarray (n,) complex
        Rᵗ, N (zero for a block: no friction).
    couple : ndarray (n,)
        The prismatic pair's couple on the block about J, N·m (zero for a rod).
    """

    label: str
    rod: bool
    line_point: np.ndarray
    along: np.ndarray
    tangential: np.ndarray
    couple: np.ndarray


def lead_forces(g: Triad, gp: list[Pair], reactions: Mapping[str, Reaction], forces: Known, moments: Known,
                kin: Kinematics) -> list[LeadForces]:
    """Rᵗ (rods) and the pair couple (blocks) of each lead from its moment equation about its
    inner joint J: cross(P − J, Rᵗ) + ΣM_J(known) = 0, or M + ΣM_J(known) = 0."""
    out = []
    for i, lead in enumerate(g.leads):
        outer = reactions[gp[2 * i].name]
        j = point(kin, g.joints[i])
        _, m = _resultant(forces, moments, lead.link, j)
        if lead.slider:
            e = 1j * outer.direction
            zero = np.zeros(j.shape, complex)
            out.append(LeadForces(outer.label, False, j, e, zero, -m))
        else:
            p = outer.reference
            e = _unit(j - p)
            t = 1j * e
            with np.errstate(divide="ignore", invalid="ignore"):
                rt = -m / cross(p - j, t)
            out.append(LeadForces(outer.label, True, p, e, rt * t, np.zeros(j.shape)))
    return out


def special_point(a: LeadForces, b: LeadForces) -> np.ndarray:
    """S, the crossing of the lines of leads ``a`` and ``b``, m (inf/NaN where parallel)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        s = cross(b.line_point - a.line_point, b.along) / cross(a.along, b.along)
    return a.line_point + s * a.along


@dataclass(frozen=True)
class TriadForcePolygon(ForcePolygon):
    """`ForcePolygon` of a triad with its construction.

    Attributes
    ----------
    pair : (int, int)
        The leads whose lines meet at S (their Rⁿ close the polygon).
    third : int
        The lead whose Rⁿ comes from the moment of the group about S.
    special : ndarray (n,) complex
        S, m.
    leads : tuple of LeadForces
    normal : ndarray (n,)
        The third lead's Rⁿ (signed along its ``along``), N.
    outer : Mapping[str, ndarray]
        Outer pair name → the reaction on the lead from its known link as the polygon gives
        it (Rᵗ + Rⁿ), N.
    inner : Mapping[str, ndarray]
        Inner pair name (the joint B, C, D) → the reaction on the lead from the base link, N,
        from each lead's ΣF = 0 with its outer reaction from the polygon.
    """

    pair: tuple[int, int] = (0, 1)
    third: int = 2
    special: np.ndarray = field(default=None, repr=False)
    leads: tuple[LeadForces, ...] = field(default=(), repr=False)
    normal: np.ndarray = field(default=None, repr=False)
    outer: Mapping[str, np.ndarray] = field(default=None, repr=False)
    inner: Mapping[str, np.ndarray] = field(default=None, repr=False)


def _third_normal(g: Triad, leads: list[LeadForces], third: int, s: np.ndarray, forces: Known,
                  moments: Known) -> np.ndarray:
    """Rⁿ of lead ``third`` from ΣM_S = 0 over the whole group (the other two Rⁿ pass through S)."""
    total = np.zeros(s.shape)
    for link in g.links:
        total = total + _resultant(forces, moments, link, s)[1]
    for lf in leads:
        total = total + cross(lf.line_point - s, lf.tangential) + lf.couple
    lf = leads[third]
    with np.errstate(divide="ignore", invalid="ignore"):
        return -total / cross(lf.line_point - s, lf.along)


def triad_polygon(mech: Mechanism, g: Triad, gp: list[Pair], reactions: Mapping[str, Reaction], forces: Known,
                  moments: Known, kin: Kinematics) -> TriadForcePolygon:
    """The triad's force polygon by Assur's special point.

    Parameters
    ----------
    mech : Mechanism
    g : Triad
    gp : list of Pair
        The group's six pairs (outer, inner per lead, as `velplan.mechanism.structure.pairs`).
    reactions : Mapping[str, Reaction]
        Used only for the pairs' reference points, guide directions and labels.
    forces, moments : Mapping
        Known forces and moments on the group's links (loads, gravity, inertia and the
        reactions of later groups).
    kin : Kinematics

    Returns
    -------
    TriadForcePolygon
        ``vectors``: every Rᵗ of a rod lead, the third lead's Rⁿ, then the known forces link
        by link; ``closing``: the directions of the special pair's Rⁿ.
    """
    pair = tuple(special_pair(mech, g))
    third = ({0, 1, 2} - set(pair)).pop()
    leads = lead_forces(g, gp, reactions, forces, moments, kin)
    s = special_point(leads[pair[0]], leads[pair[1]])
    rn = _third_normal(g, leads, third, s, forces, moments)
    vectors = [(lf.label + "τ", lf.tangential) for lf in leads if lf.rod]
    lt = leads[third]
    vectors.append((lt.label + "n" if lt.rod else lt.label, rn * lt.along))
    vectors += [(lab, v) for link in g.links for lab, v, _ in forces.get(link, ())]
    end = np.sum([v for _, v in vectors], axis=0)
    (la, lb) = (leads[pair[0]], leads[pair[1]])
    d1, d2 = la.along, lb.along
    with np.errstate(divide="ignore", invalid="ignore"):
        den = cross(d1, d2)
        alpha = cross(-end, d2) / den
        beta = cross(d1, -end) / den
    names = [lf.label + "n" if lf.rod else lf.label for lf in (la, lb)]
    closing = ((names[0], d1), (names[1], d2))
    closing_vectors = ((names[0], alpha * d1), (names[1], beta * d2))
    outer = {third: lt.tangential + rn * lt.along, pair[0]: la.tangential + alpha * d1,
             pair[1]: lb.tangential + beta * d2}
    inner = {gp[2 * i + 1].name: -(outer[i] + _resultant(forces, moments, lead.link, s)[0])
             for i, lead in enumerate(g.leads)}
    return TriadForcePolygon(g.name, g.kind, tuple(vectors), closing, closing_vectors, pair=pair, third=third,
                             special=s, leads=tuple(leads), normal=rn,
                             outer={gp[2 * i].name: outer[i] for i in range(3)}, inner=inner)

