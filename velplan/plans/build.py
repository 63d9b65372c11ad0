"""The construction of each group kind, written once: which lines to draw, through which images,
in which directions, for the velocity plan and for the acceleration plan.

`build_plan` walks the mechanism in solving order and emits the steps. For every link it keeps
an *anchor* (one of its points with a known image) and a *rotor* (a `Figure`: two points of the
link, or of a link turning with it, with known images; ``None`` for a link that does not turn),
from which any other point of the link is placed by similarity and its ω (ε) read off.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from velplan.mechanism.model import GROUND, PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Mechanism, Triad, kind_entry
from velplan.mechanism.structure import coincident_points, material_points, schedule
from velplan.plans.context import Figure
from velplan.plans.steps import (
    Coriolis,
    Intersect,
    LayOff,
    Line,
    Normal,
    Parallel,
    Perpendicular,
    Pole,
    Rotation,
    Similar,
    Step,
    Tangential,
    guide_text,
)

POLE = {"v": "p", "a": "π"}


@dataclass
class _Sheet:
    """Book-keeping of one plan (velocity "v" or acceleration "a") while it is being built."""

    kind: str
    images: dict[str, str] = field(default_factory=dict)
    anchor: dict[str, tuple[str, str]] = field(default_factory=dict)
    rotor: dict[str, Figure | None] = field(default_factory=dict)

    @property
    def pole(self) -> str:
        return f"{self.kind}:{POLE[self.kind]}"


class _Builder:
    def __init__(self, mech: Mechanism, tangential: bool):
        self.mech = mech
        self.tangential = tangential
        self.steps: dict[str, list[Step]] = {"v": [], "a": []}
        self.v, self.a = _Sheet("v"), _Sheet("a")
        self.counters = {"n": 0, "k": 0, "line": 0}
        self.labels = _labels(mech)
        self.fixed = _fixed_points(mech)

    # -- helpers ---------------------------------------------------------------------------------

    def add(self, sheet: _Sheet, step: Step) -> str:
        self.steps[sheet.kind].append(step)
        return step.target

    def target(self, sheet: _Sheet, point: str) -> str:
        return f"{sheet.kind}:{self.labels.get(point, point.lower())}"

    def line(self, sheet: _Sheet, through: str, direction, component: str) -> str:
        self.counters["line"] += 1
        return self.add(sheet, Line(f"{sheet.kind}:ℓ{self.counters['line']}", through, direction, component))

    def aux(self, prefix: str) -> str:
        self.counters[prefix] += 1
        return f"{prefix}{self.counters[prefix]}"

    def image_on(self, sheet: _Sheet, link: str, point: str, name: str | None) -> str:
        """Image of the point of ``link`` that is at ``point`` now (by similarity if needed)."""
        if link == GROUND:
            return sheet.pole
        anchor, anchor_img = sheet.anchor[link]
        if anchor == point and name is None:
            return anchor_img
        target = self.target(sheet, name or f"{point}{link}")
        if target not in sheet.images.values():
            base = sheet.rotor[link]
            self.add(sheet, Similar(target, target.split(":")[1], link, point, anchor, anchor_img, base))
        if name:
            sheet.images[name] = target
        return target

    def set_link(self, link: str, anchor: tuple[str, str, str], rotor_v: Figure | None, rotor_a: Figure | None) -> None:
        point, img_v, img_a = anchor
        self.v.anchor[link], self.a.anchor[link] = (point, img_v), (point, img_a)
        self.v.rotor[link], self.a.rotor[link] = rotor_v, rotor_a

    def figure(self, link, p1, p2, point_img=None) -> tuple[Figure, Figure]:
        """(velocity, acceleration) figures of ``link`` on its points p1, p2."""
        iv = point_img or {}
        rigid = {p1, p2} <= self.fixed.get(link, set())
        return tuple(
            Figure(link, p1, iv.get((k, p1), s.images.get(p1)), p2, iv.get((k, p2), s.images.get(p2)), rigid)
            for k, s in (("v", self.v), ("a", self.a))
        )

    def coriolis_line(self, link_of_guide: str, origin_a: str, rel: tuple[str, str], direction, component: str,
                      name: str) -> str:
        """Line ∥ a guide for the relative acceleration, after the Coriolis component when the
        guide's link turns (``rel`` = velocity images (from, to) of the relative velocity)."""
        frame = self.v.rotor.get(link_of_guide) if link_of_guide != GROUND else None
        start = origin_a
        if frame is not None:
            k = self.aux("k")
            start = self.add(self.a, LayOff(f"a:{k}", k, origin_a, Coriolis(frame, rel[0], rel[1], name)))
        return self.line(self.a, start, direction, component)

    def normal_line(self, link: str, point: str, centre: str, centre_img_a: str, name: str | None = None) -> str:
        """Normal component laid off from the centre's image, then the tangential line ⊥ the link
        (``name``: the point's name in the symbols, when it differs from the position's)."""
        n = self.aux("n")
        self.add(self.a, LayOff(f"a:{n}", n, centre_img_a, Normal(link, point, centre, self.v.rotor[link], name=name)))
        return self.line(self.a, f"a:{n}", Perpendicular(point, centre), f"aᵗ_{name or point}{centre}")

    # -- items -----------------------------------------------------------------------------------

    def crank(self, c: Crank) -> None:
        ground = tuple(n for n, _ in self.mech.ground)
        for s in (self.v, self.a):
            self.add(s, Pole(s.pole, POLE[s.kind], ground))
            s.images.update({g: s.pole for g in ground})
        tip_v, tip_a = self.target(self.v, c.tip), self.target(self.a, c.tip)
        self.add(self.v, LayOff(tip_v, tip_v[2:], self.v.pole, Rotation(c.link, c.tip, c.pivot)))
        if self.tangential:
            n = self.aux("n")
            self.add(self.a, LayOff(f"a:{n}", n, self.a.pole, Normal(c.link, c.tip, c.pivot)))
            self.add(self.a, LayOff(tip_a, tip_a[2:], f"a:{n}", Tangential(c.link, c.tip, c.pivot)))
        else:
            self.add(self.a, LayOff(tip_a, tip_a[2:], self.a.pole, Normal(c.link, c.tip, c.pivot)))
        self.v.images[c.tip], self.a.images[c.tip] = tip_v, tip_a
        fv, fa = self.figure(c.link, c.pivot, c.tip)
        self.set_link(c.link, (c.pivot, self.v.pole, self.a.pole), fv, fa)

    def point(self, p: LinkPoint) -> None:
        for s in (self.v, self.a):
            anchor, anchor_img = s.anchor[p.link]
            target = self.target(s, p.name)
            self.add(s, Similar(target, target[2:], p.link, p.name, anchor, anchor_img, s.rotor[p.link]))
            s.images[p.name] = target

    def rrr(self, g: RRR) -> None:
        (A, D), C = g.joints, g.point
        l1, l2 = g.links
        c_v, c_a = self.target(self.v, C), self.target(self.a, C)
        ia, id_ = self.v.images[A], self.v.images[D]
        L1 = self.line(self.v, ia, Perpendicular(C, A), f"V_{C}{A}")
        L2 = self.line(self.v, id_, Perpendicular(C, D), f"V_{C}{D}" if id_ != self.v.pole else f"V_{C}")
        self.add(self.v, Intersect(c_v, c_v[2:], (L1, L2)))
        self.v.images[C] = c_v
        self.v.rotor[l1], self.v.rotor[l2] = self.figure(l1, A, C)[0], self.figure(l2, D, C)[0]
        M1 = self.normal_line(l1, C, A, self.a.images[A])
        M2 = self.normal_line(l2, C, D, self.a.images[D])
        self.add(self.a, Intersect(c_a, c_a[2:], (M1, M2)))
        self.a.images[C] = c_a
        for link, base in ((l1, A), (l2, D)):
            fv, fa = self.figure(link, base, C)
            self.set_link(link, (base, self.v.images[base], self.a.images[base]), fv, fa)

    def rrp(self, g: RRP) -> None:
        A, C, k = g.joint, g.point, g.guide.link
        rod, slider = g.links
        along = guide_text(g.guide, k)
        cg_v = self.image_on(self.v, k, C, g.coincident)
        c_v, c_a = self.target(self.v, C), self.target(self.a, C)
        L1 = self.line(self.v, self.v.images[A], Perpendicular(C, A), f"V_{C}{A}")
        L2 = self.line(self.v, cg_v, Parallel(k, g.guide.angle, along), _rel("V", C, cg_v, self.v.pole))
        self.add(self.v, Intersect(c_v, c_v[2:], (L1, L2)))
        self.v.images[C] = c_v
        self.v.rotor[rod] = self.figure(rod, A, C)[0]
        M1 = self.normal_line(rod, C, A, self.a.images[A])
        cg_a = self.image_on(self.a, k, C, g.coincident)
        M2 = self.coriolis_line(k, cg_a, (cg_v, c_v), Parallel(k, g.guide.angle, along), f"aʳ_{C}", f"{C}")
        self.add(self.a, Intersect(c_a, c_a[2:], (M1, M2)))
        self.a.images[C] = c_a
        fv, fa = self.figure(rod, A, C)
        self.set_link(rod, (A, self.v.images[A], self.a.images[A]), fv, fa)
        self.set_link(slider, (C, c_v, c_a), self.v.rotor[k] if k != GROUND else None,
                      self.a.rotor[k] if k != GROUND else None)

    def rpr(self, g: RPR) -> None:
        A, O = g.joint, g.pivot
        block, bar = g.links
        name = g.coincident or f"{A}{bar}"
        a4_v, a4_a = self.target(self.v, name), self.target(self.a, name)
        guide = Parallel(bar, 0.0, f"{O}{A}")
        L1 = self.line(self.v, self.v.images[A], guide, f"V_{name}{A}")
        L2 = self.line(self.v, self.v.images[O], Perpendicular(A, O), _rel("V", name, self.v.images[O], self.v.pole, O))
        self.add(self.v, Intersect(a4_v, a4_v[2:], (L1, L2)))
        self.v.images[name] = a4_v
        fv = Figure(bar, O, self.v.images[O], A, a4_v)
        self.v.rotor[bar] = fv
        M1 = self.coriolis_line(bar, self.a.images[A], (self.v.images[A], a4_v), guide, f"aʳ_{name}{A}", f"{name}{A}")
        M2 = self.normal_line(bar, A, O, self.a.images[O], name=name)
        self.add(self.a, Intersect(a4_a, a4_a[2:], (M1, M2)))
        self.a.images[name] = a4_a
        fa = Figure(bar, O, self.a.images[O], A, a4_a)
        self.set_link(bar, (O, self.v.images[O], self.a.images[O]), fv, fa)
        self.set_link(block, (A, self.v.images[A], self.a.images[A]), fv, fa)

    def prp(self, g: PRP) -> None:
        C = g.point
        c_v, c_a = self.target(self.v, C), self.target(self.a, C)
        imgs_v, lines = [], []
        for guide, name in zip(g.guides, g.coincident):
            iv = self.image_on(self.v, guide.link, C, name)
            imgs_v.append(iv)
            lines.append(self.line(self.v, iv, Parallel(guide.link, guide.angle, guide_text(guide, guide.link)),
                                   _rel("V", C, iv, self.v.pole)))
        self.add(self.v, Intersect(c_v, c_v[2:], tuple(lines)))
        self.v.images[C] = c_v
        lines = []
        for guide, name, iv in zip(g.guides, g.coincident, imgs_v):
            ia = self.image_on(self.a, guide.link, C, name)
            direction = Parallel(guide.link, guide.angle, guide_text(guide, guide.link))
            lines.append(self.coriolis_line(guide.link, ia, (iv, c_v), direction, f"aʳ_{C}", C))
        self.add(self.a, Intersect(c_a, c_a[2:], tuple(lines)))
        self.a.images[C] = c_a
        for link, guide in zip(g.links, g.guides):
            k = guide.link
            self.set_link(link, (C, c_v, c_a), self.v.rotor.get(k) if k != GROUND else None,
                          self.a.rotor.get(k) if k != GROUND else None)

    def rpp(self, g: RPP) -> None:
        B, k = g.joint, g.guide.link
        block, runner = g.links
        name = g.coincident or f"{B}{runner}"
        b4_v, b4_a = self.target(self.v, name), self.target(self.a, name)
        slot = Parallel(runner, g.slot_angle, "slot")
        guide = Parallel(k, g.guide.angle, guide_text(g.guide, k))
        bk_v = self.image_on(self.v, k, B, None)
        L1 = self.line(self.v, self.v.images[B], slot, f"V_{name}{B}")
        L2 = self.line(self.v, bk_v, guide, _rel("V", name, bk_v, self.v.pole))
        self.add(self.v, Intersect(b4_v, b4_v[2:], (L1, L2)))
        self.v.images[name] = b4_v
        rot_v = self.v.rotor.get(k) if k != GROUND else None
        rot_a = self.a.rotor.get(k) if k != GROUND else None
        M1 = self.coriolis_line(k, self.a.images[B], (self.v.images[B], b4_v), slot, f"aʳ_{name}{B}", f"{name}{B}")
        bk_a = self.image_on(self.a, k, B, None)
        M2 = self.coriolis_line(k, bk_a, (bk_v, b4_v), guide, f"aʳ_{name}", name)
        self.add(self.a, Intersect(b4_a, b4_a[2:], (M1, M2)))
        self.a.images[name] = b4_a
        self.set_link(block, (B, self.v.images[B], self.a.images[B]), rot_v, rot_a)
        self.set_link(runner, (B, b4_v, b4_a), rot_v, rot_a)
        origin = LinkPoint(g.origin_name, runner, 0.0)
        for s in (self.v, self.a):
            anchor, anchor_img = s.anchor[runner]
            target = self.target(s, origin.name)
            self.add(s, Similar(target, target[2:], runner, origin.name, anchor, anchor_img, s.rotor[runner]))
            s.images[origin.name] = target


def _rel(prefix: str, point: str, through: str, pole: str, other: str | None = None) -> str:
    """Name of the velocity component a line carries: absolute from the pole, else relative."""
    return f"{prefix}_{point}" if through == pole else f"{prefix}_{point}{other or ''}".rstrip("_")


def _labels(mech: Mechanism) -> dict[str, str]:
    """Point name → lower-case image letter; the name itself where lower-casing would collide."""
    from velplan.mechanism.structure import point_owners

    names = list(point_owners(mech))
    lower = [n.lower() for n in names] + list(POLE.values())  # a point P must not take the pole's p
    return {n: (n.lower() if lower.count(n.lower()) == 1 else n) for n in names}


def construct(mech: Mechanism, *, tangential: bool | None = None) -> tuple[tuple[Step, ...], dict, dict]:
    """Steps of the velocity plan then the acceleration plan of ``mech``, with the image map
    ({"v"|"a": {point: target}}) and the link figures ({"v"|"a": {link: Figure | None}})."""
    b = _Builder(mech, mech.crank.epsilon != 0 if tangential is None else tangential)
    for item in schedule(mech):
        if isinstance(item, Crank):
            b.crank(item)
        elif isinstance(item, LinkPoint):
            b.point(item)
        else:
            kind_entry(BUILDERS, item, "velplan.plans.build.BUILDERS")(b, item)
    for steps in b.steps.values():  # similarity whose ratio stays constant: points fixed to their links
        steps[:] = [replace(x, rigid=_rigid(x, b.fixed)) if isinstance(x, Similar) else x for x in steps]
    images = {"v": dict(b.v.images), "a": dict(b.a.images)}
    figures = {"v": dict(b.v.rotor), "a": dict(b.a.rotor)}
    return tuple(b.steps["v"] + b.steps["a"]), images, figures


def build_triad(b, g) -> None:
    """The class III group's steps (`velplan.plans.triad`, imported by the mechanisms that have one)."""
    from velplan.plans.triad import build_triad as build

    build(b, g)


#: The plans' one lookup by group kind: kind → its steps, builder(b, g).
BUILDERS = {RRR: _Builder.rrr, RRP: _Builder.rrp, RPR: _Builder.rpr, PRP: _Builder.prp, RPP: _Builder.rpp,
            Triad: build_triad}


def _fixed_points(mech: Mechanism) -> dict[str, set[str]]:
    """Link → the named points that are one and the same material point of it at every position
    (coincident points, a different one each time, left out)."""
    moving = coincident_points(mech)
    return {link: {p for p in names if p not in moving} for link, names in material_points(mech).items()}


def _rigid(step: Similar, fixed: dict[str, set[str]]) -> bool:
    """Whether the similarity ratio (P − anchor)/(P2 − P1) of ``step`` is the same at every
    position: all four points fixed to their links, which turn together."""
    f = step.base
    return f is not None and f.rigid and {step.point, step.anchor} <= fixed.get(step.link, set())
