"""A mechanism written as it is drawn: its joints in one solved pose (the drawn file of
`velplan.mechanism.drawn`; `velplan convert` writes it)."""

from __future__ import annotations

from typing import Mapping

from velplan.mechanism.fields import degrees_of, fresh_name
from velplan.mechanism.model import GROUND, PRP, RPP, RPR, RRP, RRR, Triad, kind_entry


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
    """A point (m, as x + iy) as [x, y] for a table."""
    return [float(z.real), float(z.imag)]


class _Slides:
    """Collects the RP joints (a block's pin, as ``rp``) and P joints (``extra``) that show
    the sliding pairs of a group in the pose: ``theta`` the links' frame angles (rad), ``at``
    the points (m)."""

    def __init__(self, theta, at, rp: dict, extra: list, taken: set):
        self.theta, self.at, self.rp, self.extra, self.taken = theta, at, rp, extra, taken

    def rp_at(self, name: str, slot: str, block: str, angle: float, co: str | None) -> None:
        self.rp[name] = {"links": [slot], "block": block, "angle_deg": degrees_of(angle)} | (
            {"coincident": co} if co else {})

    def p_at(self, name: str, point: str, links: list[str], angle: float, co: str | None = None) -> None:
        self.extra.append({"name": name, "at": _xy(self.at[point]), "kind": "P", "links": links,
                           "angle_deg": degrees_of(angle)} | ({"coincident": co} if co else {}))

    def guide_angle(self, guide) -> float:
        return self.theta[guide.link] + guide.angle


def _rrp(g, s: _Slides) -> None:
    """The RRP dyad's slide: its block on the guide, at its point."""
    s.rp_at(g.point, g.guide.link, g.links[1], s.guide_angle(g.guide), g.coincident)


def _rpr(g, s: _Slides) -> None:
    """The RPR dyad's slide: the block on the bar, at its pin."""
    s.rp_at(g.joint, g.links[1], g.links[0], s.theta[g.links[1]], g.coincident)


def _prp(g, s: _Slides) -> None:
    """The PRP dyad's two slides, each on its guide."""
    a, b = g.links
    name = fresh_name(f"{g.point}_{a}", s.taken)
    s.taken.add(name)
    s.p_at(name, g.point, [g.guides[0].link, a], s.guide_angle(g.guides[0]), g.coincident[0])
    s.rp_at(g.point, g.guides[1].link, b, s.guide_angle(g.guides[1]), g.coincident[1])


def _rpp(g, s: _Slides) -> None:
    """The RPP dyad's slides: the slot on the pin's block, the runner on its guide."""
    block, runner = g.links
    s.rp_at(g.joint, runner, block, s.guide_angle(g.guide) + g.slot_angle, g.coincident)
    s.p_at(g.origin_name, g.origin_name, [g.guide.link, runner], s.guide_angle(g.guide))


def _triad(g, s: _Slides) -> None:
    """A triad's sliding leads, each a block on its guide."""
    for j, lead in zip(g.joints, g.leads):
        if lead.slider:
            s.rp_at(j, lead.guide.link, lead.link, s.guide_angle(lead.guide), lead.coincident)


SLIDES = {RRR: lambda g, s: None, RRP: _rrp, RPR: _rpr, PRP: _prp, RPP: _rpp, Triad: _triad}
"""Group kind → how its sliding pairs are drawn as joints (the drawn form's lookup)."""


def _slides_of(g, theta, at, rp: dict, extra: list, taken: set) -> None:
    """The RP joints (a block's pin) and P joints that show the sliding pairs of ``g``."""
    kind_entry(SLIDES, g, "velplan.mechanism.drawn_write.SLIDES")(g, _Slides(theta, at, rp, extra, taken))
