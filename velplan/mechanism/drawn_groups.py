"""The explicit tables of a drawn file's Assur groups (`explicit`): each
group's lengths, offsets and guide angles from the joints' coordinates, its branch or assembly
from the drawn pose, and the frame (origin, angle) of each link it brings, so that the points
and guides of later groups can be placed on it."""

from __future__ import annotations

import cmath
import math
from typing import Any

from velplan.errors import MechanismError
from velplan.mechanism.drawn import (CRANK_KEYS, TOLERANCE, Chain, GroupPair, Joint, check_held, check_joints, decompose,
                                     drawing_size, group_pairs, links_text, parse_joints)
from velplan.mechanism.fields import degrees_of, no_unknown
from velplan.mechanism.model import GROUND


class Builder:
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
        return {"link": link, "through": ref, "angle_deg": degrees_of(cmath.phase(u) - angle), "offset": offset}

    def snap(self, length: float) -> float:
        """A drawn length, 0 where it is round-off of the drawing's size."""
        return 0.0 if abs(length) < 1e-12 * self.scale else length

    def frame(self, link: str, origin: complex, toward: complex | float) -> None:
        angle = toward if isinstance(toward, float) else cmath.phase(toward - origin)
        self.frames[link] = (origin, angle)


def _sign(x: float, what: str) -> int:
    """The sign (±1) of ``x``, read off the drawing; a one-line error naming ``what`` at 0."""
    if x == 0:
        raise MechanismError(f"{what} is drawn exactly at a dead point: the branch cannot be read from the drawing")
    return 1 if x > 0 else -1


def crank_table(build: Builder, link: str, t: dict) -> dict:
    """The explicit ``[crank]`` of the drawn crank ``link`` (``t``: its table): its tip its
    other joint, its length (m) the tip's distance from the pivot."""
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


def group_tables(build: Builder, group: frozenset) -> None:
    """The explicit ``[[group]]`` table of the dyad or triad ``group`` (its links) added to
    ``build``, lengths (m) and branch read from the drawn pose."""
    known = frozenset(build.frames)
    pairs = group_pairs(build.chain, group, known)
    inner = [p for p in pairs if p.inner]
    names = sorted(group, key=build.chain.links.index)
    if len(group) == 4:
        return _triad(build, names, pairs)
    outer = {k: [p for p in pairs if not p.inner and p.link == k] for k in names}
    if len(inner) != 1 or any(len(v) != 1 for v in outer.values()):
        raise MechanismError(f"links {links_text(names)} are joined by {len(inner)} pairs and held by "
                             f"{sum(len(v) for v in outer.values())}: not a dyad (a locked sub-chain)")
    (mid,) = inner
    (oa,), (ob,) = outer[names[0]], outer[names[1]]
    pattern = oa.kind + mid.kind + ob.kind
    if pattern in ("PRR", "PPR"):
        oa, ob = ob, oa
        pattern = pattern[::-1]
    if pattern == "PPP":
        raise MechanismError(f"links {links_text(names)} form a PPP dyad (three sliding pairs): it does not fix them")
    handler = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}[pattern]
    build.groups.append(handler(build, oa, mid, ob))


def _rrr(build: Builder, oa: GroupPair, mid: GroupPair, ob: GroupPair) -> dict:
    """The RRR dyad (outer pairs ``oa``, ``ob``, inner ``mid``): its lengths (m) and branch,
    from the drawing."""
    a, b = oa.link, ob.link
    A, D, C = oa.at, ob.at, mid.at
    if abs(D - A) <= TOLERANCE * build.scale:
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


def _rrp(build: Builder, oa: GroupPair, mid: GroupPair, ob: GroupPair) -> dict:
    """The RRP dyad (``ob``: its slider on a known link's guide): the rod's length (m), the
    guide through the slider's pin and the branch, from the drawing."""
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


def _rpr(build: Builder, oa: GroupPair, mid: GroupPair, ob: GroupPair) -> dict:
    """The RPR dyad (``mid``: its block sliding on its bar): the bar line's offset (m) from
    its pivot and the branch, from the drawing."""
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


def _prp(build: Builder, oa: GroupPair, mid: GroupPair, ob: GroupPair) -> dict:
    """The PRP dyad (two outer slides on known guides, ``mid`` the pin between its links):
    the guides through the pin, from the drawing."""
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


def _rpp(build: Builder, oa: GroupPair, mid: GroupPair, ob: GroupPair) -> dict:
    """The RPP dyad (``oa``: the block's pin on a known link, ``mid``: the block in the
    runner's slot, ``ob``: the runner on a known guide): the guide through K, where the slot's
    line meets it, and the slot's angle to the guide (deg), from the drawing."""
    block, runner = oa.link, ob.link
    B, v, u = oa.at, mid.slide.u, ob.slide.u
    # K: the slot's line through B crosses the guide's line through the runner's P joint
    den = (u.conjugate() * v).imag
    if abs(den) < 1e-12:
        raise MechanismError(f"links {block}, {runner}: the slot is parallel to the guide; the group cannot move")
    t = ((ob.slide.at - B).conjugate() * u).imag / (v.conjugate() * u).imag
    k_at = B + t * v
    out = {"kind": "RPP", "links": [block, runner], "joint": build.known_point(oa.name, oa.outer),
           "guide": build.guide(ob.outer, k_at, u), "slot_angle_deg": degrees_of(cmath.phase(v / u))}
    if mid.slide.coincident and mid.slide.slot == runner:
        out["coincident"] = mid.slide.coincident
    mark = ob.slide.name
    if mark in build.chain.marks and abs(build.chain.position[mark] - k_at) <= TOLERANCE * build.scale:
        out["origin"] = mark
    build.frame(block, B, cmath.phase(v))
    build.frame(runner, k_at, cmath.phase(u))
    build.mark(oa.name, block)
    build.mark(out.get("origin", f"K{runner}"), runner, at=k_at)
    return out


def _triad(build: Builder, names: list[str], pairs: list[GroupPair]) -> None:
    """The class III triad of links ``names`` added to ``build``: its base, inner joints,
    sides (m), leads and the drawn pose as its assembly; a one-line error for another group."""
    inner = [p for p in pairs if p.inner]
    count = {k: sum(1 for p in inner if k in (p.link, p.other)) for k in names}
    bases = [k for k in names if count[k] == 3]
    if len(inner) != 3 or len(bases) != 1 or any(p.kind != "R" for p in inner):
        kind = "a class IV group (a closed contour of four links)" if len(inner) == 4 else \
            "a group of four links that is not a triad with revolute inner joints"
        raise MechanismError(f"links {links_text(names)} form {kind}; velplan solves the dyads of class II "
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


def leftover_points(build: Builder, joints: tuple[Joint, ...]) -> None:
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


def drawn_points(build: Builder, points: Any) -> list:
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
                                     f"{links_text(sorted(set(build.frames) - {GROUND}))}")
            origin, angle = build.frames[link]
            local = (complex(*at) - origin) * cmath.rect(1.0, -angle)
            t = {k: v for k, v in t.items() if k != "at"} | {"along": local.real, "offset": local.imag}
        out.append(t)
    return out


def special(build: Builder, t: Any) -> None:
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


# -- the explicit tables --------------------------------------------------------------------


def explicit(data: dict, name: str = "mechanism") -> dict:
    """The explicit tables (``[ground]``, ``[crank]``, ``[[group]]``, ``[[point]]``) of a drawn
    file's parsed TOML ``data``; the other keys are passed through to the loader."""
    if "ground" in data or "group" in data:
        raise MechanismError("a drawn file gives [[joint]] tables instead of [ground] and [[group]], not both")
    joints = parse_joints(data.get("joint"))
    crank_t = data.get("crank")
    if not isinstance(crank_t, dict):
        raise MechanismError("missing [crank] section: link, pivot (a joint) and omega or rpm")
    no_unknown(crank_t, CRANK_KEYS, "[crank]")
    chain = Chain(joints)
    crank = str(crank_t.get("link", ""))
    if crank not in chain.links:
        raise MechanismError(f"[crank] link {crank_t.get('link')!r} is not a moving link of the joints; "
                             f"links: {links_text(chain.links)}")
    check_joints(chain)
    w = chain.mobility()
    if w != 1:
        check_held(chain, crank)
        raise MechanismError(f"the joints give W = {w} (3·{len(chain.links)} − 2·{chain.p5}), not 1, for links "
                             f"{links_text(chain.links)}: velplan drives a mechanism of one crank")
    groups = decompose(chain, crank)
    build = Builder(chain, crank_t, drawing_size(chain))
    tables = dict(data)
    del tables["joint"]
    tables["crank"] = crank_table(build, crank, crank_t)
    for g in groups:
        group_tables(build, g)
    leftover_points(build, joints)
    tables["ground"] = build.ground
    tables["group"] = build.groups
    tables["point"] = build.points + drawn_points(build, data.get("point", []))
    special(build, data.get("special"))
    tables.pop("special", None)
    return tables
