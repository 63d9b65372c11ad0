"""The vector equation each reaction of a group is read from, as written under its force
polygon: an outer reaction is the sum of its components found on the polygon
(R₁₂ = R₁₂τ + R₁₂n); an inner reaction (and the crank's frame reaction) follows from the
equilibrium of one of the pair's links, ΣF = 0 over that link (R₃₂ = −(R₁₂ + G₂ + Φ₂)).

>>> import velplan
>>> fa = velplan.Study("slider-press", n=4).forces()
>>> [(e.label, e.terms, e.negated) for e in reaction_equations(fa, "2-3", 2)]
[('R12', ('R12τ', 'R12n'), False), ('R32', ('R12', 'G2', 'Φ2'), True), ('R03', (), False)]
>>> e = reaction_equations(fa, "crank", 2)[0]
>>> e.label, e.terms, e.negated, e.link
('R01', ('R21', 'G1', 'Φ1'), True, '1')
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.analysis.numbering import position_index
from velplan.forces.agreement import ForceAnalysis
from velplan.forces.reactions import reaction_label

#: Suffixes of the components into which a polygon splits a reaction.
COMPONENTS = ("τ", "n", "∥", "⊥")


@dataclass(frozen=True)
class ReactionEquation:
    """``label = (−)(Σ terms)``, |label| = ``value`` N. ``link``: the link whose equilibrium
    gives it (None: read off the polygon as the sum of its components); no terms: the
    reaction is itself a vector of the polygon.

    >>> e = ReactionEquation("R32", ("R12", "G2", "Φ2"), True, 6295.0, "2")
    >>> e.negated, e.link
    (True, '2')
    """

    label: str
    terms: tuple[str, ...]
    negated: bool
    value: float
    link: str | None


def _forces_on(fa: ForceAnalysis, link: str, skip: str) -> list[str]:
    """Labels of every force on `link` other than those of pair `skip`: reactions of its
    other pairs (as forces on it), then its loads, gravity and inertia forces."""
    out = []
    for rc in fa.kinetostatics.reactions.values():
        p = rc.pair
        if p.name == skip or link not in p.links:
            continue
        out.append(rc.label if p.links[0] == link else reaction_label(p.links[0], p.links[1]))
    out += [f.label for f in fa.actions.forces if f.link == link]
    return out


def _inner_pairs(fa: ForceAnalysis, link: str, group: str) -> int:
    """How many pairs of `group` join `link` to another link of the group."""
    return sum(1 for rc in fa.kinetostatics.reactions.values()
               if rc.pair.group == group and link in rc.pair.links
               and _inner(fa, rc.pair, group))


def _inner(fa: ForceAnalysis, pair, group: str) -> bool:
    """Whether `pair` joins two links of `group` (or is the crank's pair with the frame)."""
    if group == "crank":
        return True
    links = next(g.links for g in fa.kinetostatics.mechanism.groups if g.name == group)
    return all(k in links for k in pair.links)


def reaction_equations(fa: ForceAnalysis, group: str, position: int) -> list[ReactionEquation]:
    """The equation of every reaction of `group` (or ``"crank"``) at position number
    ``position`` (1…n), in the order of the pairs.

    >>> import velplan
    >>> fa = velplan.Study("slider-press", n=4).forces()
    >>> [e.label for e in reaction_equations(fa, "2-3", 2)]
    ['R12', 'R32', 'R03']
    """
    i = position_index(position, len(fa.kinematics))
    ks = fa.kinetostatics
    names = [n for n, _ in ks.polygons[group].vectors] + [
        n for n, _ in ks.polygons[group].closing_vectors]
    out = []
    for rc in ks.reactions.values():
        p = rc.pair
        if p.group != group:
            continue
        value = float(np.abs(rc.force[i]))
        if not _inner(fa, p, group):
            parts = tuple(rc.label + s for s in COMPONENTS if rc.label + s in names)
            out.append(ReactionEquation(rc.label, parts if len(parts) > 1 else (), False, value,
                                        None))
            continue
        k0, k1 = p.links
        if (group != "crank" and _inner_pairs(fa, k0, group) > 1
                and _inner_pairs(fa, k1, group) == 1):
            # the other link closes alone: the reaction on it, from its equilibrium
            out.append(ReactionEquation(reaction_label(k0, k1), tuple(_forces_on(fa, k1, p.name)),
                                        True, value, k1))
            continue
        out.append(ReactionEquation(rc.label, tuple(_forces_on(fa, k0, p.name)), True, value, k0))
    return out
