"""The drawn form: a mechanism given as joints at one drawn pose, decomposed into Assur groups.

A drawn file gives ``[[joint]]`` tables instead of ``[ground]`` and ``[[group]]``: each joint's
name, its position ``at`` (m) in the drawn pose, its ``kind`` (``R`` revolute; ``P`` prismatic:
``links[1]`` slides without turning on a guide of ``links[0]``; ``RP`` pin in a slot: the pin of
``links[1:]`` turns in a block that slides on a guide of ``links[0]``) and the links it joins
(``"0"`` or ``"ground"`` is the frame). The ``[crank]`` names its link, its pivot joint and its
speed. velplan counts the mobility (Chebyshev), splits the chain into Assur groups in solving
order (the dyads RRR, RRP, RPR, PRP, RPP and the class III triad), reads each branch from the
drawn pose and every length from the joints' coordinates, and hands the loader the explicit
tables (`explicit`, built by `velplan.mechanism.drawn_groups`): a drawn file is an ordinary
`Mechanism`. `velplan.mechanism.drawn_write.drawn_tables` writes a mechanism back as joints.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from itertools import combinations
from typing import Any

from velplan.errors import MechanismError
from velplan.mechanism.fields import finite, fresh_name, no_unknown, optional_name
from velplan.mechanism.model import GROUND

FRAME_NAMES = (GROUND, "ground")
"""Names of the frame in a joint's ``links``."""
JOINT_KINDS = ("R", "P", "RP")
_JOINT_KEYS = {"name", "at", "kind", "links", "angle_deg", "block", "coincident", "color"}
CRANK_KEYS = {"link", "pivot", "omega", "rpm", "epsilon"}
TOLERANCE = 1e-9
"""Relative tolerance of the drawn geometry (a point on a line, coincident joints)."""


@dataclass(frozen=True)
class Joint:
    """A joint as drawn: ``at`` (x, y) in m; ``angle`` (rad, absolute) is the guide's direction
    of a P or RP joint; ``block`` names the RP joint's block link; ``coincident`` names the
    point of the guide's link (``links[0]``) at the joint; ``color`` is kept for PMKS."""

    name: str
    kind: str
    at: tuple[float, float]
    links: tuple[str, ...]
    angle: float = 0.0
    block: str | None = None
    coincident: str | None = None
    color: str | None = None


def parse_joints(tables: Any) -> tuple[Joint, ...]:
    """The ``[[joint]]`` tables as `Joint` values, each checked (one-line errors)."""
    if not isinstance(tables, list) or not tables:
        raise MechanismError("joint must be an array of tables ([[joint]]) with at least one joint")
    out, seen = [], set()
    for i, t in enumerate(tables):
        if not isinstance(t, dict):
            raise MechanismError(f"joint #{i + 1} must be a table, not {t!r}")
        name = str(t.get("name", "")).strip()
        if not name:
            raise MechanismError(f"joint #{i + 1}: missing name")
        where = f"joint {name!r}"
        no_unknown(t, _JOINT_KEYS, where)
        if name in seen:
            raise MechanismError(f"duplicate joint name {name!r}")
        seen.add(name)
        kind = str(t.get("kind", "R")).upper()
        if kind not in JOINT_KINDS:
            raise MechanismError(f"{where}: unknown joint kind {t.get('kind')!r}; known kinds: R, P, RP")
        at = t.get("at")
        if not (isinstance(at, list) and len(at) == 2):
            raise MechanismError(f"{where}: at must be [x, y] in m, not {at!r}")
        xy = (finite(at[0], f"{where} x"), finite(at[1], f"{where} y"))
        links = t.get("links")
        if not (isinstance(links, list) and links and all(isinstance(k, (str, int)) and str(k) for k in links)):
            raise MechanismError(f"{where}: links must be a list of link names, not {links!r}")
        links = tuple(GROUND if str(k) in FRAME_NAMES else str(k) for k in links)
        if len(set(links)) != len(links):
            raise MechanismError(f"{where}: a link is named twice in links {list(links)}")
        angle = 0.0
        if kind != "R":
            if len(links) < 2:
                raise MechanismError(f"{where}: a {kind} joint joins the guide's link and at least one more")
            if kind == "P" and len(links) != 2:
                raise MechanismError(f"{where}: a P joint joins two links (the guide's, the slider), not {len(links)}")
            if "angle_deg" not in t:
                raise MechanismError(f"{where}: a {kind} joint needs angle_deg, the guide's direction")
            angle = math.radians(finite(t["angle_deg"], f"{where} angle_deg"))
        elif "angle_deg" in t or "block" in t or "coincident" in t:
            raise MechanismError(f"{where}: angle_deg, block and coincident belong to P and RP joints")
        block = optional_name(t, "block")
        if block is not None and kind != "RP":
            raise MechanismError(f"{where}: block names the block of an RP joint")
        color = t.get("color")
        out.append(Joint(name, kind, xy, links, angle, block, optional_name(t, "coincident"),
                         None if color is None else str(color)))
    return tuple(out)


@dataclass(frozen=True)
class _Slide:
    """A prismatic pair: ``slider`` moves along ``u`` (unit, drawn pose) on ``slot``'s guide."""

    name: str
    slot: str
    slider: str
    u: complex
    at: complex
    coincident: str | None


class Chain:
    """The joints expanded into links and pairs: hinges (a point shared by two or more links
    turning about it; an RP joint's pin joins its block too) and slides (P pairs)."""

    def __init__(self, joints: tuple[Joint, ...]):
        self.joints = joints
        self.hinges: dict[str, tuple[complex, tuple[str, ...]]] = {}
        self.slides: list[_Slide] = []
        self.marks: dict[str, tuple[complex, str]] = {}  # P joints: a point of the slider
        self.blocks: dict[str, str] = {}  # block link → its RP joint
        names = {j.name for j in joints}
        used = {k for j in joints for k in j.links}
        order: list[str] = []
        for j in joints:
            at = complex(*j.at)
            for k in j.links:
                if k not in order:
                    order.append(k)
            if j.kind == "R":
                self.hinges[j.name] = (at, j.links)
            elif j.kind == "P":
                self.slides.append(_Slide(j.name, j.links[0], j.links[1], cmath.rect(1.0, j.angle), at, j.coincident))
                self.marks[j.name] = (at, j.links[1])
            else:
                block = j.block or fresh_name(f"b{j.name}", used | names)
                if block in self.blocks or block in j.links:
                    other = self.blocks.get(block, j.name)
                    raise MechanismError(f"joint {j.name!r}: block {block!r} is already the block of joint {other!r} "
                                         "or one of its links")
                if block not in order:
                    order.append(block)
                self.blocks[block] = j.name
                self.hinges[j.name] = (at, j.links[1:] + (block,))
                self.slides.append(_Slide(j.name, j.links[0], block, cmath.rect(1.0, j.angle), at, j.coincident))
        self.links = tuple(k for k in order if k != GROUND)
        self.position = {n: at for n, (at, _) in self.hinges.items()}
        self.position.update({n: at for n, (at, _) in self.marks.items()})

    @property
    def p5(self) -> int:
        """Lower pairs: a hinge of k links is k − 1 pairs, each slide one."""
        return sum(len(links) - 1 for _, links in self.hinges.values()) + len(self.slides)

    def mobility(self) -> int:
        """Chebyshev: W = 3·n − 2·p5 (no higher pairs)."""
        return 3 * len(self.links) - 2 * self.p5

    def pairs(self, group: frozenset, known: frozenset) -> int:
        """Pairs a set of unknown links adds over the known ones."""
        p = 0
        for _, links in self.hinges.values():
            inside = sum(1 for k in links if k in group)
            if inside:
                p += inside if any(k in known for k in links) else inside - 1
        for s in self.slides:
            ends = {s.slot, s.slider}
            if ends & group and ends <= group | known:
                p += 1
        return p

    def freedom(self, group: frozenset, known: frozenset) -> int:
        """W of ``group`` on the known links: 3·n − 2·p."""
        return 3 * len(group) - 2 * self.pairs(group, known)


def check_joints(chain: Chain) -> None:
    """One-line errors for revolute joints that cannot be a mechanism's: two joining the same
    links, two of one link drawn at one point (within `TOLERANCE` of the drawing's size)."""
    hinges = [(name, hinge) for name, hinge in chain.hinges.items() if len(hinge[1]) > 1]  # not points
    tol = TOLERANCE * drawing_size(chain)
    for i, (a, (at_a, links_a)) in enumerate(hinges):
        for b, (at_b, links_b) in hinges[i + 1:]:
            if set(links_a) == set(links_b):
                raise MechanismError(f"joints {a!r} and {b!r} both join links {links_text(links_a)}")
            shared = [k for k in links_a if k in links_b and k != GROUND]
            if shared and abs(at_a - at_b) <= tol:
                raise MechanismError(f"joints {a!r} and {b!r} of link {shared[0]} are drawn at one point "
                                     f"({at_a.real:g}, {at_a.imag:g}) m: a link's joints must be apart "
                                     "(links turning about one point share one joint)")


def check_held(chain: Chain, crank: str) -> None:
    """A one-line error naming the moving links but the ``crank`` that one pair alone holds
    (each adds a freedom: the usual cause of W ≠ 1 is a mistyped link in a joint)."""
    held: dict[str, list[str]] = {k: [] for k in chain.links}
    for name, (_, links) in chain.hinges.items():
        for k in links if len(links) > 1 else ():  # a point of one link is no pair
            held.setdefault(k, []).append(name)
    for s in chain.slides:
        for k in (s.slot, s.slider):
            held.setdefault(k, []).append(s.name)
    alone = [f"{k} (joint {held[k][0]!r})" for k in chain.links if len(held[k]) == 1 and k != crank]
    if alone:
        raise MechanismError(f"link{'s' if len(alone) > 1 else ''} held by one joint alone: {', '.join(alone)}; "
                             "every moving link but the crank needs two pairs at least (check the joints' links)")


def links_text(links) -> str:
    """Link names for a message: "1, 2, 3", or "(none)"."""
    return ", ".join(links) or "(none)"


# -- decomposition --------------------------------------------------------------------------


def decompose(chain: Chain, crank: str) -> list[frozenset]:
    """The Assur groups of ``chain`` on the frame and the crank, in solving order: each the
    smallest set of links (a dyad before a triad) of W = 0 on the links known before it.

    Raises `MechanismError` naming the links of a locked sub-chain, a class IV group or a
    group of higher class that velplan does not solve."""
    known = frozenset({GROUND, crank})
    left = [k for k in chain.links if k != crank]
    out: list[frozenset] = []
    while left:
        for k in left:
            if chain.freedom(frozenset({k}), known) < 0:
                held = [x for x in sorted(known - {GROUND})] + ["frame"]
                raise MechanismError(f"link {k} is held by more pairs than it can move in (a locked sub-chain "
                                     f"on links {links_text(held)})")
        group = _next_group(chain, left, known)
        if group is None:
            _refuse(chain, left, known)
        out.append(group)
        known = known | group
        left = [k for k in left if k not in group]
    return out


def _neighbours(chain: Chain, links: set[str]) -> dict[str, set[str]]:
    """Each of ``links`` → those of ``links`` it shares a joint with."""
    out: dict[str, set[str]] = {k: set() for k in links}
    groups = [ls for _, ls in chain.hinges.values()] + [(s.slot, s.slider) for s in chain.slides]
    for ls in groups:
        mine = [k for k in ls if k in links]
        for k in mine:
            out[k].update(x for x in mine if x != k)
    return out


def _next_group(chain: Chain, left: list[str], known: frozenset) -> frozenset | None:
    """The first dyad (in the order of the links), else the first triad (a base link and three
    of its neighbours) of W = 0 on the known links."""
    index = {k: i for i, k in enumerate(left)}
    near = _neighbours(chain, set(left))
    for i, a in enumerate(left):
        for b in sorted(near[a], key=index.__getitem__):
            if index[b] > i and _is_group(chain, (a, b), known):
                return frozenset((a, b))
    stars = sorted({tuple(sorted((base, *leads), key=index.__getitem__))
                    for base in left for leads in combinations(sorted(near[base], key=index.__getitem__), 3)},
                   key=lambda combo: [index[k] for k in combo])
    for combo in stars:
        if _is_group(chain, combo, known):
            return frozenset(combo)
    return None


def _is_group(chain: Chain, combo: tuple, known: frozenset) -> bool:
    """Whether the links ``combo`` are an Assur group on the known links: W = 0, no part W ≤ 0."""
    return chain.freedom(frozenset(combo), known) == 0 and not _smaller(chain, combo, known)


def _smaller(chain: Chain, combo: tuple, known: frozenset) -> bool:
    """Whether a proper part of ``combo`` has W ≤ 0 on the known links."""
    return any(chain.freedom(frozenset(part), known) <= 0
               for r in range(1, len(combo)) for part in combinations(combo, r))


SEARCH_LIMIT = 20000
"""Most connected sets of links a refusal looks through for the one to name."""


def _connected_sets(chain: Chain, left: list[str], most: int) -> list[tuple[str, ...]]:
    """Connected sets of 2…``most`` of the links ``left``, smallest first, in the links' order."""
    index = {k: i for i, k in enumerate(left)}
    near = _neighbours(chain, set(left))
    layer = {frozenset((k,)) for k in left}
    out: list[tuple[str, ...]] = []
    for _ in range(most - 1):
        layer = {s | {n} for s in layer for k in s for n in near[k] if n not in s}
        out += sorted((tuple(sorted(s, key=index.__getitem__)) for s in layer),
                      key=lambda c: [index[k] for k in c])
        if len(out) > SEARCH_LIMIT or not layer:
            break
    return out


def _refuse(chain: Chain, left: list[str], known: frozenset) -> None:
    """Raise the most telling error for links that form no dyad or triad."""
    sets = _connected_sets(chain, left, 8)
    for combo in sets:
        w = chain.freedom(frozenset(combo), known)
        if w < 0:
            raise MechanismError(f"links {links_text(combo)} form a locked sub-chain (W = {w} on the links before them)")
    for combo in sets:
        if len(combo) >= 4 and chain.freedom(frozenset(combo), known) == 0:
            inner = _inner_count(chain, frozenset(combo), known)
            kind = "a class IV group (a closed contour of four links)" if len(combo) == 4 and inner == 4 \
                else f"a group of {len(combo)} links of a class above III or an order above 3"
            raise MechanismError(f"links {links_text(combo)} form {kind}; velplan solves the dyads of "
                                 "class II and the class III triad")
    raise MechanismError(f"links {links_text(left)} cannot be split into Assur groups on links "
                         f"{links_text(sorted(known))}")


def _inner_count(chain: Chain, group: frozenset, known: frozenset) -> int:
    """Number of the inner pairs of ``group`` (pairs between two of its links)."""
    return sum(1 for p in group_pairs(chain, group, known) if p.inner)


@dataclass(frozen=True)
class GroupPair:
    """A pair of a group: ``link`` (and ``other``, inside the group, for an inner pair) at the
    joint ``name``; ``slide`` for a prismatic pair; ``outer`` names the known link."""

    kind: str
    link: str
    name: str
    at: complex
    other: str | None = None
    outer: str | None = None
    slide: _Slide | None = None

    @property
    def inner(self) -> bool:
        return self.other is not None


def group_pairs(chain: Chain, group: frozenset, known: frozenset) -> list[GroupPair]:
    """Every pair of ``group``: its outer pairs (to a known link, the frame last) and its inner
    ones, revolute then prismatic."""
    out = []
    for name, (at, links) in chain.hinges.items():
        mine = [k for k in links if k in group]
        outside = sorted((k for k in links if k in known), key=lambda k: k != GROUND)
        if not mine:
            continue
        if outside:
            out += [GroupPair("R", k, name, at, outer=outside[0]) for k in mine]
        else:
            out += [GroupPair("R", mine[0], name, at, other=k) for k in mine[1:]]
    for s in chain.slides:
        ends = {s.slot, s.slider}
        if not (ends & group and ends <= group | known):
            continue
        if ends <= group:
            out.append(GroupPair("P", s.slider, s.name, s.at, other=s.slot, slide=s))
        else:
            mine, other = (s.slider, s.slot) if s.slider in group else (s.slot, s.slider)
            out.append(GroupPair("P", mine, s.name, s.at, outer=other, slide=s))
    return out


def drawing_size(chain: Chain) -> float:
    """The drawing's size: the largest distance between two of its joints, m (1 for one point)."""
    xs = list(chain.position.values())
    return max((abs(a - b) for a in xs for b in xs), default=1.0) or 1.0
