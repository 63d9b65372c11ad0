"""A mechanism written as it is drawn: its joints in one solved pose (the drawn file of
`velplan.mechanism.drawn`; `velplan convert` writes it)."""

from __future__ import annotations

from typing import Mapping

from velplan.mechanism.drawn import fresh_name
from velplan.mechanism.drawn_groups import degrees_of
from velplan.mechanism.model import GROUND

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
        rp[name] = {"links": [slot], "block": block, "angle_deg": degrees_of(angle)} | ({"coincident": co} if co else {})

    def guide_angle(guide) -> float:
        return theta[guide.link] + guide.angle

    if g.kind == "RRP":
        rp_at(g.point, g.guide.link, g.links[1], guide_angle(g.guide), g.coincident)
    elif g.kind == "RPR":
        rp_at(g.joint, g.links[1], g.links[0], theta[g.links[1]], g.coincident)
    elif g.kind == "PRP":
        a, b = g.links
        name = fresh_name(f"{g.point}_{a}", taken)
        taken.add(name)
        extra.append({"name": name, "at": _xy(at[g.point]), "kind": "P", "links": [g.guides[0].link, a],
                      "angle_deg": degrees_of(guide_angle(g.guides[0]))} |
                     ({"coincident": g.coincident[0]} if g.coincident[0] else {}))
        rp_at(g.point, g.guides[1].link, b, guide_angle(g.guides[1]), g.coincident[1])
    elif g.kind == "RPP":
        block, runner = g.links
        rp_at(g.joint, runner, block, guide_angle(g.guide) + g.slot_angle, g.coincident)
        extra.append({"name": g.origin_name, "at": _xy(at[g.origin_name]), "kind": "P",
                      "links": [g.guide.link, runner], "angle_deg": degrees_of(guide_angle(g.guide))})
    elif g.kind == "triad":
        for j, lead in zip(g.joints, g.leads):
            if lead.slider:
                rp_at(j, lead.guide.link, lead.link, guide_angle(lead.guide), lead.coincident)
