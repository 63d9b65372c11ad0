"""Structural analysis: solving order, kinematic pairs, point owners, mobility (Chebyshev).

Everything here is derived from a `Mechanism` value; nothing is solved numerically.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Union

from velplan.errors import MechanismError, deprecated
from velplan.mechanism.model import (
    GROUND,
    FACTS,
    AssurGroup,
    Crank,
    Group,
    Guide,
    LinkPoint,
    Mechanism,
    Pair,
)

Item = Union[Crank, Group, LinkPoint]


def facts(group) -> AssurGroup:
    """``group`` itself, checked to be an Assur group kind that states its structure (an
    `AssurGroup`); a `MechanismError` naming the kind otherwise."""
    if not isinstance(group, AssurGroup):
        raise MechanismError(f"group {getattr(group, 'name', '?')!r}: kind {type(group).__name__} is not an Assur "
                             f"group kind (velplan.mechanism.model.AssurGroup): its structure is unknown")
    missing = [f for f in FACTS if not hasattr(group, f)]
    if missing:
        raise MechanismError(f"group {group.name!r}: kind {type(group).__name__} does not state its "
                             f"{', '.join(missing)}")
    return group


def joints_in(group: Group) -> tuple[str, ...]:
    """Known points a group attaches to (its outer joints and its guides' points)."""
    return facts(group).joints_in()


def guides_of(group: Group) -> tuple[Guide, ...]:
    """The guides a group slides on (empty for RRR and RPR)."""
    return facts(group).guide_lines()


def points_out(group: Group) -> dict[str, str]:
    """Points a group determines → the link that owns each of them."""
    return facts(group).points_out()


def revolute_joints(group: Group) -> dict[str, tuple[str, ...]]:
    """Revolute joint centres of a group → the group's links they are a point of.

    A joint centre is a material point of every link it joins, so a guide or a later group
    may refer to it on either link.
    """
    return facts(group).revolute_joints()


def schedule(mech: Mechanism) -> tuple[Item, ...]:
    """Solving order: crank, then each group followed by the points on its links.

    Raises
    ------
    MechanismError
        A group or point refers to a point or link that is not known before it.
    """
    owner: dict[str, str] = {name: GROUND for name, _ in mech.ground}
    on: dict[str, set[str]] = {name: {GROUND} for name in owner}
    links = {GROUND}
    order: list[Item] = [mech.crank]
    if mech.crank.pivot not in owner:
        raise MechanismError(
            f"crank pivot {mech.crank.pivot!r} is not a ground point; ground points: {_names(owner)}"
        )
    owner[mech.crank.tip] = mech.crank.link
    on[mech.crank.tip] = {mech.crank.link}
    on[mech.crank.pivot].add(mech.crank.link)
    links.add(mech.crank.link)
    pending = list(mech.points)

    def attach_points() -> None:
        for p in list(pending):
            if p.link in links:
                owner[p.name] = p.link
                on[p.name] = {p.link}
                order.append(p)
                pending.remove(p)

    attach_points()
    for g in mech.groups:
        for name in joints_in(g):
            if name not in owner:
                _unknown_point(mech, g, name, pending, owner)
        for guide in guides_of(g):
            if guide.link not in links:
                raise MechanismError(
                    f"group {g.name!r}: guide link {guide.link!r} is not known before it; "
                    f"known links: {_names(links)}"
                )
            if guide.link not in on[guide.through]:
                raise MechanismError(
                    f"group {g.name!r}: guide point {guide.through!r} is on link(s) "
                    f"{_names(on[guide.through])}, not on the guide's link {guide.link!r}"
                )
        order.append(g)
        links.update(g.links)
        for name, link in points_out(g).items():
            owner[name] = link
            on[name] = {link}
        for name, on_links in revolute_joints(g).items():
            on.setdefault(name, set()).update(on_links)
        attach_points()
    if pending:
        known = _names(links - {GROUND})
        p = pending[0]
        raise MechanismError(f"point {p.name!r} is on unknown link {p.link!r}; known links: {known}")
    return tuple(order)


def _unknown_point(mech: Mechanism, g: Group, name: str, pending, owner) -> None:
    """Raise the most telling error for a group that uses a point not known before it."""
    all_links = set(mech.links) | {GROUND}
    for p in pending:
        if p.name == name and p.link not in all_links:
            raise MechanismError(f"point {p.name!r} is on unknown link {p.link!r}; "
                                 f"known links: {_names(all_links - {GROUND})}")
        if p.name == name:
            raise MechanismError(f"group {g.name!r} uses point {name!r} of link {p.link!r}, "
                                 f"which is solved after the group; reorder the groups")
    raise MechanismError(
        f"group {g.name!r} uses point {name!r}, which is not solved before it; known points: {_names(owner)}"
    )


def point_owners(mech: Mechanism) -> dict[str, str]:
    """Every named point → the link it is fixed to (``"0"`` for the frame)."""
    owner = {name: GROUND for name, _ in mech.ground}
    for item in schedule(mech):
        if isinstance(item, Crank):
            owner[item.tip] = item.link
        elif isinstance(item, LinkPoint):
            owner[item.name] = item.link
        else:
            owner.update(points_out(item))
    return owner


def coincident_points(mech: Mechanism) -> dict[str, str]:
    """Coincident point name → the guide's link it belongs to (the point of that link that is at
    the slider's joint now: a different material point at each position)."""
    out = {}
    for g in mech.groups:
        owners = points_out(g)
        out.update({n: owners[n] for n in facts(g).coincident_names()})
    return out


def material_points(mech: Mechanism) -> dict[str, tuple[str, ...]]:
    """Moving link → the named points that are, at the current instant, points of that link.

    A point is: fixed to the link (`point_owners`, coincident points included), a revolute
    joint centre of the link (`revolute_joints`), or the crank's pivot for the crank.
    """
    out: dict[str, list[str]] = {k: [] for k in mech.links}

    def add(link: str, name: str) -> None:
        if link in out and name not in out[link]:
            out[link].append(name)

    add(mech.crank.link, mech.crank.pivot)
    for name, link in point_owners(mech).items():
        add(link, name)
    for g in mech.groups:
        for name, links in revolute_joints(g).items():
            for link in links:
                add(link, name)
    return {k: tuple(v) for k, v in out.items()}


def pairs(mech: Mechanism) -> tuple[Pair, ...]:
    """All lower pairs, named after their point (``"P:<slider link>/<guide link>"`` for sliders).

    A compound hinge (three or more links on one point) has one pair per added link; the
    second and later pairs there are named ``"<point>:<link>/<link>"`` so that every name is
    unique."""
    owner = point_owners(mech)
    c = mech.crank
    out = [Pair(c.pivot, "R", (c.link, GROUND), c.pivot, "crank")]
    for g in mech.groups:
        out += facts(g).pairs(owner)
    seen: set[str] = set()
    for k, p in enumerate(out):
        if p.name in seen:
            out[k] = replace(p, name=f"{p.name}:{p.links[0]}/{p.links[1]}")
        seen.add(out[k].name)
    return tuple(out)


def group_class(g: Group) -> tuple[int, int]:
    """Assur's class and order of a group: (2, 2) for a dyad, (3, 3) for a triad."""
    return facts(g).group_class


@dataclass(frozen=True)
class Structure:
    """Result of the structural analysis.

    ``mobility`` W = 3·n − 2·p5 − p4 (Chebyshev), n moving links, p5 lower pairs, p4 higher.
    ``groups`` lists (name, kind, class, order, links) for every Assur group.
    """

    n_links: int
    p5: int
    p4: int
    groups: tuple[tuple[str, str, int, int, tuple[str, ...]], ...]

    @property
    def mobility(self) -> int:
        return 3 * self.n_links - 2 * self.p5 - self.p4

    @property
    def mechanism_class(self) -> int:
        """The mechanism's class: the highest class of its groups (1 for a crank alone)."""
        return max((c for _, _, c, _, _ in self.groups), default=1)

    def structure_formula(self, crank_link: str = "1") -> str:
        """Formula of structure: I(0, 1) → II(2, 3) → III(4, 5, 6, 7) …"""
        roman = {1: "I", 2: "II", 3: "III"}
        parts = [f"I(0, {crank_link})"]
        parts += [f"{roman.get(c, str(c))}({', '.join(links)})" for _, _, c, _, links in self.groups]
        return " → ".join(parts)

    def formula(self) -> str:
        """The Chebyshev formula with numbers, e.g. ``W = 3·5 − 2·7 − 0 = 1``."""
        return f"W = 3·{self.n_links} − 2·{self.p5} − {self.p4} = {self.mobility}"


def structure(mech: Mechanism) -> Structure:
    """Structural analysis of ``mech``: link and pair counts and the Assur groups with their class
    and order (dyads: class II, order 2; triads: class III, order 3).

    >>> import velplan
    >>> structure(velplan.load("shaper")).formula()
    'W = 3·5 − 2·7 − 0 = 1'
    """
    ps = pairs(mech)
    groups = tuple((g.name, g.kind, *group_class(g), g.links) for g in mech.groups)
    return Structure(n_links=len(mech.links), p5=len(ps), p4=0, groups=groups)


analyse = deprecated(structure, "velplan.mechanism.structure.analyse")


def _names(names) -> str:
    return ", ".join(sorted(names)) or "(none)"
