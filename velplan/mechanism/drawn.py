"""The drawn form: a mechanism given as joints at one drawn pose, decomposed into Assur groups.

A drawn file gives ``[[joint]]`` tables instead of ``[ground]`` and ``[[group]]``: each joint's
name, its position ``at`` (m) in the drawn pose, its ``kind`` (``R`` revolute; ``P`` prismatic:
``links[1]`` slides without turning on a guide of ``links[0]``; ``RP`` pin in a slot: the pin of
``links[1:]`` turns in a block that slides on a guide of ``links[0]``) and the links it joins
(``"0"`` or ``"ground"`` is the frame). The ``[crank]`` names its link, its pivot joint and its
speed. velplan counts the mobility (Chebyshev), splits the chain into Assur groups in solving
order (the dyads RRR, RRP, RPR, PRP, RPP and the class III triad), reads each branch from the
drawn pose and every length from the joints' coordinates, and hands the loader the explicit
tables (`explicit`): a drawn file is an ordinary `Mechanism`. `drawn_tables` writes a
mechanism back as joints, from the positions of a solved pose.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from itertools import combinations
from typing import Any, Mapping

from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND

FRAME_NAMES = (GROUND, "ground")
"""Names of the frame in a joint's ``links``."""
JOINT_KINDS = ("R", "P", "RP")
_JOINT_KEYS = {"name", "at", "kind", "links", "angle_deg", "block", "coincident", "color"}
_CRANK_KEYS = {"link", "pivot", "omega", "rpm", "epsilon"}
_TOL = 1e-9
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
    from velplan.mechanism.loader import _finite, _no_unknown, _opt_name

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
        _no_unknown(t, _JOINT_KEYS, where)
        if name in seen:
            raise MechanismError(f"duplicate joint name {name!r}")
        seen.add(name)
        kind = str(t.get("kind", "R")).upper()
        if kind not in JOINT_KINDS:
            raise MechanismError(f"{where}: unknown joint kind {t.get('kind')!r}; known kinds: R, P, RP")
        at = t.get("at")
        if not (isinstance(at, list) and len(at) == 2):
            raise MechanismError(f"{where}: at must be [x, y] in m, not {at!r}")
        xy = (_finite(at[0], f"{where} x"), _finite(at[1], f"{where} y"))
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
            angle = math.radians(_finite(t["angle_deg"], f"{where} angle_deg"))
        elif "angle_deg" in t or "block" in t or "coincident" in t:
            raise MechanismError(f"{where}: angle_deg, block and coincident belong to P and RP joints")
        block = _opt_name(t, "block")
        if block is not None and kind != "RP":
            raise MechanismError(f"{where}: block names the block of an RP joint")
        color = t.get("color")
        out.append(Joint(name, kind, xy, links, angle, block, _opt_name(t, "coincident"),
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
                block = j.block or _fresh(f"b{j.name}", used | names)
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


def _fresh(stem: str, taken: set[str]) -> str:
    name, k = stem, 1
    while name in taken:
        k += 1
        name = f"{stem}{k}"
    return name


def _links_text(links) -> str:
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
                                     f"on links {_links_text(held)})")
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
            raise MechanismError(f"links {_links_text(combo)} form a locked sub-chain (W = {w} on the links before them)")
    for combo in sets:
        if len(combo) >= 4 and chain.freedom(frozenset(combo), known) == 0:
            inner = _inner_count(chain, frozenset(combo), known)
            kind = "a class IV group (a closed contour of four links)" if len(combo) == 4 and inner == 4 \
                else f"a group of {len(combo)} links of a class above III or an order above 3"
            raise MechanismError(f"links {_links_text(combo)} form {kind}; velplan solves the dyads of "
                                 "class II and the class III triad")
    raise MechanismError(f"links {_links_text(left)} cannot be split into Assur groups on links "
                         f"{_links_text(sorted(known))}")


def _inner_count(chain: Chain, group: frozenset, known: frozenset) -> int:
    return sum(1 for p in _pairs_of(chain, group, known) if p.inner)


@dataclass(frozen=True)
class _Pair:
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


def _pairs_of(chain: Chain, group: frozenset, known: frozenset) -> list[_Pair]:
    out = []
    for name, (at, links) in chain.hinges.items():
        mine = [k for k in links if k in group]
        outside = sorted((k for k in links if k in known), key=lambda k: k != GROUND)
        if not mine:
            continue
        if outside:
            out += [_Pair("R", k, name, at, outer=outside[0]) for k in mine]
        else:
            out += [_Pair("R", mine[0], name, at, other=k) for k in mine[1:]]
    for s in chain.slides:
        ends = {s.slot, s.slider}
        if not (ends & group and ends <= group | known):
            continue
        if ends <= group:
            out.append(_Pair("P", s.slider, s.name, s.at, other=s.slot, slide=s))
        else:
            mine, other = (s.slider, s.slot) if s.slider in group else (s.slot, s.slider)
            out.append(_Pair("P", mine, s.name, s.at, outer=other, slide=s))
    return out


# -- the explicit tables --------------------------------------------------------------------


class _Builder:
    """Turns the decomposition into the loader's explicit tables, tracking each known link's
    frame (origin, angle) in the drawn pose and the named points velplan knows on it."""

    def __init__(self, chain: Chain, crank: dict, scale: float):
        self.chain = chain
        self.scale = scale
        self.frames: dict[str, tuple[complex, float]] = {GROUND: (0j, 0.0)}
        self.on: dict[str, list[str]] = {GROUND: []}
        self.ground: dict[str, list[float]] = {}
        self.points: list[dict] = []
        self.defined: set[str] = set()
        self.at: dict[str, complex] = {}
        self.phi = 0.0  # the drawn crank angle, rad
        self.groups: list[dict] = []
        self.crank = crank

    # points ------------------------------------------------------------------------------
    def mark(self, name: str, *links: str, at: complex | None = None) -> None:
        self.defined.add(name)
        if at is not None or name not in self.at:
            self.at[name] = self.chain.position[name] if at is None else at
        for k in links:
            self.on.setdefault(k, [])
            if name not in self.on[k]:
                self.on[k].append(name)

    def known_point(self, name: str, link: str) -> str:
        """``name`` as a point velplan knows on ``link`` (a ground point or a link point)."""
        if name not in self.defined:
            self.add_point(name, link, self.chain.position[name])
        else:
            self.mark(name, link)
        return name

    def add_point(self, name: str, link: str, at: complex) -> None:
        if link == GROUND:
            self.ground[name] = [at.real, at.imag]
        else:
            origin, angle = self.frames[link]
            local = (at - origin) * cmath.rect(1.0, -angle)
            self.points.append({"name": name, "link": link, "along": local.real, "offset": self.snap(local.imag)})
        self.mark(name, link, at=at)

    def guide(self, link: str, through: complex, u: complex) -> dict:
        """A guide of ``link`` along ``u`` through the drawn point ``through``."""
        names = self.on.get(link) or []
        if not names:
            raise MechanismError(f"link {link} carries a guide but has no joint to place it by")
        ref = names[0]
        origin, angle = self.frames[link]
        offset = self.snap(((through - self.at[ref]) / u).imag)
        return {"link": link, "through": ref, "angle_deg": _deg(cmath.phase(u) - angle), "offset": offset}

    def snap(self, length: float) -> float:
        """A drawn length, 0 where it is round-off of the drawing's size."""
        return 0.0 if abs(length) < 1e-12 * self.scale else length

    def frame(self, link: str, origin: complex, toward: complex | float) -> None:
        angle = toward if isinstance(toward, float) else cmath.phase(toward - origin)
        self.frames[link] = (origin, angle)


def _deg(angle: float) -> float:
    """An angle in degrees in (−180, 180]."""
    d = math.degrees(math.remainder(angle, 2 * math.pi))
    return 180.0 if d == -180.0 else d


def _sign(x: float, what: str) -> int:
    if x == 0:
        raise MechanismError(f"{what} is drawn exactly at a dead point: the branch cannot be read from the drawing")
    return 1 if x > 0 else -1


def explicit(data: dict, name: str = "mechanism") -> dict:
    """The explicit tables (``[ground]``, ``[crank]``, ``[[group]]``, ``[[point]]``) of a drawn
    file's parsed TOML ``data``; the other keys are passed through to the loader."""
    from velplan.mechanism.loader import _no_unknown

    if "ground" in data or "group" in data:
        raise MechanismError("a drawn file gives [[joint]] tables instead of [ground] and [[group]], not both")
    joints = parse_joints(data.get("joint"))
    crank_t = data.get("crank")
    if not isinstance(crank_t, dict):
        raise MechanismError("missing [crank] section: link, pivot (a joint) and omega or rpm")
    _no_unknown(crank_t, _CRANK_KEYS, "[crank]")
    chain = Chain(joints)
    crank = str(crank_t.get("link", ""))
    if crank not in chain.links:
        raise MechanismError(f"[crank] link {crank_t.get('link')!r} is not a moving link of the joints; "
                             f"links: {_links_text(chain.links)}")
    w = chain.mobility()
    if w != 1:
        raise MechanismError(f"the joints give W = {w} (3·{len(chain.links)} − 2·{chain.p5}), not 1, for links "
                             f"{_links_text(chain.links)}: velplan drives a mechanism of one crank")
    groups = decompose(chain, crank)
    build = _Builder(chain, crank_t, _scale(chain))
    tables = dict(data)
    del tables["joint"]
    tables["crank"] = _crank(build, crank, crank_t)
    for g in groups:
        _group(build, g)
    _leftover_points(build, joints)
    tables["ground"] = build.ground
    tables["group"] = build.groups
    tables["point"] = build.points + _drawn_points(build, data.get("point", []))
    _special(build, data.get("special"))
    tables.pop("special", None)
    return tables


def _scale(chain: Chain) -> float:
    xs = list(chain.position.values())
    return max((abs(a - b) for a in xs for b in xs), default=1.0) or 1.0


def _crank(build: _Builder, link: str, t: dict) -> dict:
    chain = build.chain
    pivot = str(t.get("pivot", ""))
    if pivot not in chain.hinges or not {GROUND, link} <= set(chain.hinges[pivot][1]):
        raise MechanismError(f"[crank] pivot {t.get('pivot')!r} must be an R joint of the frame and link {link}")
    tip = next((n for n, (_, links) in chain.hinges.items() if link in links and n != pivot), None)
    if tip is None:
        raise MechanismError(f"[crank] link {link} has no joint besides its pivot {pivot}")
    p, a = chain.hinges[pivot][0], chain.hinges[tip][0]
    build.add_point(pivot, GROUND, p)
    build.frame(link, p, a)
    build.mark(pivot, link)
    build.mark(tip, link)
    build.phi = cmath.phase(a - p)
    out = {"link": link, "pivot": pivot, "tip": tip, "length": abs(a - p)}
    out.update({k: t[k] for k in ("omega", "rpm", "epsilon") if k in t})
    return out


def _group(build: _Builder, group: frozenset) -> None:
    known = frozenset(build.frames)
    pairs = _pairs_of(build.chain, group, known)
    inner = [p for p in pairs if p.inner]
    names = sorted(group, key=build.chain.links.index)
    if len(group) == 4:
        return _triad(build, names, pairs)
    outer = {k: [p for p in pairs if not p.inner and p.link == k] for k in names}
    if len(inner) != 1 or any(len(v) != 1 for v in outer.values()):
        raise MechanismError(f"links {_links_text(names)} are joined by {len(inner)} pairs and held by "
                             f"{sum(len(v) for v in outer.values())}: not a dyad (a locked sub-chain)")
    (mid,) = inner
    (oa,), (ob,) = outer[names[0]], outer[names[1]]
    pattern = oa.kind + mid.kind + ob.kind
    if pattern in ("PRR", "PPR"):
        oa, ob = ob, oa
        pattern = pattern[::-1]
    if pattern == "PPP":
        raise MechanismError(f"links {_links_text(names)} form a PPP dyad (three sliding pairs): it does not fix them")
    handler = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}[pattern]
    build.groups.append(handler(build, oa, mid, ob))


def _rrr(build: _Builder, oa: _Pair, mid: _Pair, ob: _Pair) -> dict:
    a, b = oa.link, ob.link
    A, D, C = oa.at, ob.at, mid.at
    if abs(D - A) <= _TOL * build.scale:
        raise MechanismError(f"links {a}, {b}: both outer joints are at one point ({oa.name}, {ob.name}): a locked pair")
    side = ((C - A) / (D - A)).imag
    out = {"kind": "RRR", "links": [a, b], "joints": [build.known_point(oa.name, oa.outer),
                                                        build.known_point(ob.name, ob.outer)],
           "point": mid.name, "lengths": [abs(C - A), abs(C - D)],
           "branch": _sign(side, f"joint {mid.name} (links {a}, {b})")}
    build.frame(a, A, C)
    build.frame(b, D, C)
    build.mark(oa.name, a)
    build.mark(ob.name, b)
    build.mark(mid.name, a, b)
    return out


def _rrp(build: _Builder, oa: _Pair, mid: _Pair, ob: _Pair) -> dict:
    rod, slider = oa.link, ob.link
    A, C, u = oa.at, mid.at, ob.slide.u
    out = {"kind": "RRP", "links": [rod, slider], "joint": build.known_point(oa.name, oa.outer),
           "point": mid.name, "length": abs(C - A), "guide": build.guide(ob.outer, C, u),
           "branch": _sign(((C - A) / u).real, f"joint {mid.name} (links {rod}, {slider})")}
    if ob.slide.coincident and ob.slide.slot == ob.outer:
        out["coincident"] = ob.slide.coincident
    build.frame(rod, A, C)
    build.frame(slider, C, cmath.phase(u))
    build.mark(oa.name, rod)
    build.mark(mid.name, rod, slider)
    return out


def _rpr(build: _Builder, oa: _Pair, mid: _Pair, ob: _Pair) -> dict:
    s = mid.slide
    block, bar = (oa, ob) if s.slot == ob.link else (ob, oa)
    A, O, u = block.at, bar.at, s.u
    w = (A - O) / u
    out = {"kind": "RPR", "links": [block.link, bar.link], "joint": build.known_point(block.name, block.outer),
           "pivot": build.known_point(bar.name, bar.outer), "offset": build.snap(w.imag),
           "branch": _sign(w.real, f"joint {block.name} (links {block.link}, {bar.link})")}
    if s.coincident and s.slot == bar.link:
        out["coincident"] = s.coincident
    theta = cmath.phase(u)
    build.frame(block.link, A, theta)
    build.frame(bar.link, O, theta)
    build.mark(block.name, block.link)
    build.mark(bar.name, bar.link)
    return out


def _prp(build: _Builder, oa: _Pair, mid: _Pair, ob: _Pair) -> dict:
    if build.chain.slides.index(oa.slide) > build.chain.slides.index(ob.slide):
        oa, ob = ob, oa
    C = mid.at
    out = {"kind": "PRP", "links": [oa.link, ob.link], "point": mid.name,
           "guides": [build.guide(oa.outer, C, oa.slide.u), build.guide(ob.outer, C, ob.slide.u)]}
    co = [p.slide.coincident if p.slide.coincident and p.slide.slot == p.outer else "" for p in (oa, ob)]
    if any(co):
        out["coincident"] = co
    build.frame(oa.link, C, cmath.phase(oa.slide.u))
    build.frame(ob.link, C, cmath.phase(ob.slide.u))
    build.mark(mid.name, oa.link, ob.link)
    return out


def _rpp(build: _Builder, oa: _Pair, mid: _Pair, ob: _Pair) -> dict:
    block, runner = oa.link, ob.link
    B, v, u = oa.at, mid.slide.u, ob.slide.u
    # K: the slot's line through B crosses the guide's line through the runner's P joint
    den = (u.conjugate() * v).imag
    if abs(den) < 1e-12:
        raise MechanismError(f"links {block}, {runner}: the slot is parallel to the guide; the group cannot move")
    t = ((ob.slide.at - B).conjugate() * u).imag / (v.conjugate() * u).imag
    k_at = B + t * v
    out = {"kind": "RPP", "links": [block, runner], "joint": build.known_point(oa.name, oa.outer),
           "guide": build.guide(ob.outer, k_at, u), "slot_angle_deg": _deg(cmath.phase(v / u))}
    if mid.slide.coincident and mid.slide.slot == runner:
        out["coincident"] = mid.slide.coincident
    mark = ob.slide.name
    if mark in build.chain.marks and abs(build.chain.position[mark] - k_at) <= _TOL * build.scale:
        out["origin"] = mark
    build.frame(block, B, cmath.phase(v))
    build.frame(runner, k_at, cmath.phase(u))
    build.mark(oa.name, block)
    build.mark(out.get("origin", f"K{runner}"), runner, at=k_at)
    return out


def _triad(build: _Builder, names: list[str], pairs: list[_Pair]) -> None:
    inner = [p for p in pairs if p.inner]
    count = {k: sum(1 for p in inner if k in (p.link, p.other)) for k in names}
    bases = [k for k in names if count[k] == 3]
    if len(inner) != 3 or len(bases) != 1 or any(p.kind != "R" for p in inner):
        kind = "a class IV group (a closed contour of four links)" if len(inner) == 4 else \
            "a group of four links that is not a triad with revolute inner joints"
        raise MechanismError(f"links {_links_text(names)} form {kind}; velplan solves the dyads of class II "
                             "and the class III triad")
    base = bases[0]
    order = list(build.chain.hinges)
    inner.sort(key=lambda p: order.index(p.name))
    joints, leads = [], []
    for p in inner:
        lead = p.other if p.link == base else p.link
        (o,) = [q for q in pairs if not q.inner and q.link == lead]
        joints.append(p.name)
        if o.kind == "R":
            leads.append({"link": lead, "joint": build.known_point(o.name, o.outer), "length": abs(p.at - o.at)})
            build.frame(lead, o.at, p.at)
            build.mark(o.name, lead)
        else:
            t = {"link": lead, "guide": build.guide(o.outer, p.at, o.slide.u)}
            if o.slide.coincident and o.slide.slot == o.outer:
                t["coincident"] = o.slide.coincident
            leads.append(t)
            build.frame(lead, p.at, cmath.phase(o.slide.u))
        build.mark(p.name, base, lead)
    B, C, D = (build.chain.position[j] for j in joints)
    side = _sign(((D - B) / (C - B)).imag, f"the triad's joints {', '.join(joints)}")
    asm = {"phi_deg": math.degrees(build.phi)}
    asm.update({j: [build.chain.position[j].real, build.chain.position[j].imag] for j in joints})
    build.frame(base, B, C)
    build.groups.append({"kind": "triad", "base": base, "joints": joints,
                         "sides": [abs(C - B), abs(D - C), abs(B - D)], "side": side,
                         "leads": leads, "assembly": asm})


def _leftover_points(build: _Builder, joints: tuple[Joint, ...]) -> None:
    """Joints no group placed (a coupler point, a P joint's point on its slider) as points."""
    chain = build.chain
    for j in joints:
        if j.name in build.defined:
            continue
        if j.kind == "P":
            build.add_point(j.name, j.links[1], complex(*j.at))
            continue
        links = chain.hinges[j.name][1]
        moving = [k for k in links if k != GROUND]
        build.add_point(j.name, GROUND if GROUND in links or not moving else moving[0], complex(*j.at))


def _drawn_points(build: _Builder, points: Any) -> list:
    """``[[point]]`` tables: ``at = [x, y]`` (drawn) becomes along/offset in the link's frame."""
    if not isinstance(points, list):
        return points
    out = []
    for t in points:
        if isinstance(t, dict) and "at" in t:
            if "along" in t or "offset" in t:
                raise MechanismError(f"point {t.get('name')!r}: give at (drawn) or along/offset, not both")
            at, link = t.get("at"), str(t.get("link", ""))
            if not (isinstance(at, list) and len(at) == 2 and all(isinstance(v, (int, float)) for v in at)):
                raise MechanismError(f"point {t.get('name')!r}: at must be [x, y] in m, not {at!r}")
            if link not in build.frames or link == GROUND:
                raise MechanismError(f"point {t.get('name')!r}: unknown link {link!r}; known links: "
                                     f"{_links_text(sorted(set(build.frames) - {GROUND}))}")
            origin, angle = build.frames[link]
            local = (complex(*at) - origin) * cmath.rect(1.0, -angle)
            t = {k: v for k, v in t.items() if k != "at"} | {"along": local.real, "offset": local.imag}
        out.append(t)
    return out


def _special(build: _Builder, t: Any) -> None:
    """``[[special]]``: a triad's special point (``base``, ``name``, ``leads`` = two lead links)."""
    if t is None:
        return
    if not isinstance(t, list):
        raise MechanismError("special must be an array of tables ([[special]]) {base, name, leads}")
    for s in t:
        base = str(s.get("base", "")) if isinstance(s, dict) else ""
        group = next((g for g in build.groups if g["kind"] == "triad" and g["base"] == base), None)
        if group is None:
            raise MechanismError(f"[[special]]: {base!r} is not the base link of a triad")
        if s.get("name"):
            group["special"] = str(s["name"])
        if "leads" in s:
            links = [lead["link"] for lead in group["leads"]]
            pair = [str(k) for k in s["leads"]] if isinstance(s["leads"], list) else []
            if len(pair) != 2 or not set(pair) <= set(links) or pair[0] == pair[1]:
                raise MechanismError(f"[[special]] of triad {base}: leads must be two of its lead links "
                                     f"{', '.join(links)}, not {s['leads']!r}")
            group["pair"] = [links.index(k) + 1 for k in pair]


# -- writing a mechanism as drawn -----------------------------------------------------------


def drawn_tables(mech, at: Mapping[str, complex], angles: Mapping[str, float]) -> dict:
    """The drawn file of ``mech`` in a pose: ``at`` holds every named point's position (m) and
    ``angles`` every moving link's frame angle (rad) there, as the solver gives them."""
    from velplan.mechanism.structure import point_owners, revolute_joints
    from velplan.mechanism.tables import crank_table, meta_tables

    theta = dict(angles) | {GROUND: 0.0}
    owners = point_owners(mech)
    hinges: dict[str, list[str]] = {}

    def hinge(name: str, *links: str) -> None:
        row = hinges.setdefault(name, [owners.get(name, links[0])])
        row += [k for k in links if k not in row]

    c = mech.crank
    hinge(c.pivot, GROUND, c.link)
    hinge(c.tip, c.link)
    for n, _ in mech.ground:
        hinge(n, GROUND)
    for g in mech.groups:
        for n, links in revolute_joints(g).items():
            hinge(n, *links)
    for p in mech.points:  # a link point that a group joins at is a joint
        if p.name in hinges:
            hinge(p.name, p.link)
    rp: dict[str, dict] = {}
    extra: list[dict] = []
    taken = set(owners) | set(hinges)
    for g in mech.groups:
        _slides_of(g, theta, at, rp, extra, taken)
    joints = []
    for n, links in hinges.items():
        t = {"name": n, "at": _xy(at[n])}
        if n in rp:
            slide = rp[n]
            pins = [k for k in links if k not in (slide["block"], slide["links"][0])]
            t |= {"kind": "RP", "links": slide["links"][:1] + pins} | {k: v for k, v in slide.items() if k != "links"}
        else:
            t["links"] = links
        joints.append(t)
    joints += extra
    out = meta_tables(mech)
    crank = crank_table(mech)
    out["crank"] = {"link": c.link, "pivot": c.pivot, "omega": crank["omega"]} | (
        {"epsilon": c.epsilon} if c.epsilon else {})
    out["joint"] = joints
    points = [{"name": p.name, "link": p.link, "at": _xy(at[p.name])} for p in mech.points if p.name not in hinges]
    if points:
        out["point"] = points
    special = [{"base": g.base} | ({"name": g.special} if g.special else {}) |
               ({"leads": [g.leads[g.pair[0]].link, g.leads[g.pair[1]].link]} if g.pair else {})
               for g in mech.groups if g.kind == "triad" and (g.special or g.pair)]
    if special:
        out["special"] = special
    return out


def _xy(z) -> list[float]:
    return [float(z.real), float(z.imag)]


def _slides_of(g, theta, at, rp: dict, extra: list, taken: set) -> None:
    """The RP joints (a block's pin) and P joints that show the sliding pairs of ``g``."""
    def rp_at(name: str, slot: str, block: str, angle: float, co: str | None) -> None:
        rp[name] = {"links": [slot], "block": block, "angle_deg": _deg(angle)} | ({"coincident": co} if co else {})

    def guide_angle(guide) -> float:
        return theta[guide.link] + guide.angle

    if g.kind == "RRP":
        rp_at(g.point, g.guide.link, g.links[1], guide_angle(g.guide), g.coincident)
    elif g.kind == "RPR":
        rp_at(g.joint, g.links[1], g.links[0], theta[g.links[1]], g.coincident)
    elif g.kind == "PRP":
        a, b = g.links
        name = _fresh(f"{g.point}_{a}", taken)
        taken.add(name)
        extra.append({"name": name, "at": _xy(at[g.point]), "kind": "P", "links": [g.guides[0].link, a],
                      "angle_deg": _deg(guide_angle(g.guides[0]))} |
                     ({"coincident": g.coincident[0]} if g.coincident[0] else {}))
        rp_at(g.point, g.guides[1].link, b, guide_angle(g.guides[1]), g.coincident[1])
    elif g.kind == "RPP":
        block, runner = g.links
        rp_at(g.joint, runner, block, guide_angle(g.guide) + g.slot_angle, g.coincident)
        extra.append({"name": g.origin_name, "at": _xy(at[g.origin_name]), "kind": "P",
                      "links": [g.guide.link, runner], "angle_deg": _deg(guide_angle(g.guide))})
    elif g.kind == "triad":
        for j, lead in zip(g.joints, g.leads):
            if lead.slider:
                rp_at(j, lead.guide.link, lead.link, guide_angle(lead.guide), lead.coincident)
