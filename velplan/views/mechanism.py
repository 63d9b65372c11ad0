"""The kinematic scheme in its positions: one position thick, the others thin and numbered,
with the trajectories of the characteristic points, at a standard scale μl (m/mm).

GOST 2.770 symbols: fixed pivots on hatched ground, revolute joints as small circles,
sliders as blocks on hatched guides (or in the slot of a moving link), links as thick lines.
Positions are numbered 1…n at the crank tip and at the output point, in the sense of ω1
from the reference position.

Layers: ``"trajectory"`` (thin paths), ``"positions"`` (the thin positions),
``"mechanism"`` (the thick position with its symbols), ``"labels"`` (letters, numbers,
the title and the scale).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Generator, NamedTuple, Sequence

import numpy as np
import shapely

from velplan.analysis.numbering import position_index, position_number
from velplan.analysis.solver import Kinematics
from velplan.mechanism.model import GROUND, PRP, RPP, RPR, RRP, RRR, Mechanism, Triad, kind_entry
from velplan.mechanism.structure import pairs, point_owners
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.shapes import text_box
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.render.symbols import (
    JOINT_RADIUS_MM, centre_of_mass_sign, fixed_pivot, link, revolute_joint, rotation_arrow,
    slider_block, straight_guide)
from velplan.views.base import (
    View, _moved, bounds_of, digits_down, free_direction, grown_once, make_view, place_labels, scale_mark, scale_text,
    subscript)
from velplan.views.letters import place_letters

#: Slider block length and width, mm.
BLOCK_MM = (12.0, 7.0)
_HATCH_MM = 3.0


@dataclass(frozen=True)
class Segment:
    """A straight piece of a link between two points of the mechanism at one position, m."""

    link: str
    a: np.ndarray
    b: np.ndarray
    joints: tuple[bool, bool]  # is there a revolute joint at a, at b (trim the line there)


@dataclass(frozen=True)
class Block:
    """A slider block at `centre` (m) with its long side along `angle` (rad)."""

    link: str
    centre: np.ndarray
    angle: float


@dataclass(frozen=True)
class GuideTrack:
    """A fixed straight guide: the line through `base` (m) along `angle`, travelled over the
    range [lo, hi] (m along the line) by the block of `link`."""

    link: str
    base: np.ndarray
    angle: float
    lo: float
    hi: float
    point: str = ""


def _unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


#: The link lines of the positions drawn so far, by `_Geometry.row_key` (the mechanism kept
#: with them, so that a reused id is not mistaken for it); cleared when full.
_SEGMENTS: dict[tuple, tuple] = {}
#: Per mechanism (by id, kept with it): its points' links, its hinges and its fixed pivots.
_FACTS: dict[int, tuple] = {}
_FACTS_KEPT = 64
_ROWS_KEPT = 20000


class _Geometry:
    """Where every link, block and guide is, at the positions of a `Kinematics`, m."""

    def __init__(self, mech: Mechanism, kin: Kinematics):
        self.mech, self.kin = mech, kin
        hit = _FACTS.get(id(mech))
        if hit is None or hit[0] is not mech:  # worked out once per mechanism (read only)
            if len(_FACTS) >= _FACTS_KEPT:
                _FACTS.clear()
            hinges = [p for p in pairs(mech) if p.kind == "R"]
            hit = _FACTS[id(mech)] = (mech, point_owners(mech), {p.point for p in hinges},
                                      [p.point for p in hinges if GROUND in p.links])
        self.owner, self.revolute, self.ground_pivots = hit[1:]

    def p(self, i: int, name: str) -> np.ndarray:
        return self.kin.positions[i, self.kin.point_index[name]]

    def theta(self, i: int, link_name: str) -> float:
        return 0.0 if link_name == GROUND else float(self.kin.angles[i, self.kin.link_index[link_name]])

    def _seg(self, link_name, a, b, i, joint_a=None, joint_b=None) -> Segment:
        pa = self.p(i, a) if isinstance(a, str) else a
        pb = self.p(i, b) if isinstance(b, str) else b
        ja = joint_a if joint_a is not None else (isinstance(a, str) and a in self.revolute)
        jb = joint_b if joint_b is not None else (isinstance(b, str) and b in self.revolute)
        return Segment(link_name, pa, pb, (ja, jb))

    def main_points(self) -> dict[str, tuple[str, str]]:
        """Link → two named points its main line runs between (links that are lines)."""
        c = self.mech.crank
        out = {c.link: (c.pivot, c.tip)}
        for g in self.mech.groups:
            out.update(g.link_lines())
        return out

    def plates(self, i: int) -> list[tuple[str, np.ndarray]]:
        """The ternary base links of the triads: (link, its joints B, C, D at position i, m)."""
        return [(link, np.array([self.p(i, j) for j in joints]))
                for g in self.mech.groups for link, joints in g.plates()]

    def row_key(self, i: int) -> tuple:
        """What the drawing of position i depends on: the mechanism, its points and its links'
        angles there (the same key in every view of that position: a frame, a trial)."""
        return id(self.mech), self.kin.positions[i].tobytes(), self.kin.angles[i].tobytes()

    def segments(self, i: int) -> list[Segment]:
        """Lines of every link at position i (worked out once per position and mechanism)."""
        key = self.row_key(i)
        hit = _SEGMENTS.get(key)
        if hit is None or hit[0] is not self.mech:
            if len(_SEGMENTS) >= _ROWS_KEPT:
                _SEGMENTS.clear()
            hit = _SEGMENTS[key] = (self.mech, tuple(self._segments(i)))
        return list(hit[1])

    def _segments(self, i: int) -> list[Segment]:
        segs: list[Segment] = []
        c = self.mech.crank
        segs.append(self._seg(c.link, c.pivot, c.tip, i))
        for g in self.mech.groups:
            segs.extend(drawing_of(g).segments(self, g, i))
        segs.extend(self._point_arms(i))
        return segs

    def _triad(self, g: Triad, i: int) -> list[Segment]:
        """The base link's three sides, each rod lead, and each moving guide of a block lead."""
        b, c, d = g.joints
        segs = [self._seg(g.base, b, c, i), self._seg(g.base, c, d, i),
                self._seg(g.base, d, b, i)]
        for lead, joint in zip(g.leads, g.joints):
            if not lead.slider:
                segs.append(self._seg(lead.link, lead.joint, joint, i))
            elif lead.guide.link != GROUND:
                segs.extend(self._moving_guide(lead.guide, self.p(i, joint), i))
        return segs

    def _bar(self, g: RPR, i: int) -> list[Segment]:
        bar = g.links[1]
        o, a = self.p(i, g.pivot), self.p(i, g.joint)
        direction = _unit(self.theta(i, bar))
        foot = o + g.offset * np.array([-direction[1], direction[0]])
        names = [n for n, owner in self.owner.items() if owner == bar]
        reach = [float((self.p(i, n) - foot) @ direction) for n in names]
        reach.append(float((a - foot) @ direction))
        far = foot + direction * (max(reach) + (0.0 if names else 0.15 * max(reach)))
        segs = []
        if g.offset:
            segs.append(Segment(bar, o, foot, (g.pivot in self.revolute, False)))
        end_joint = any(float(np.hypot(*(self.p(i, n) - far))) < 1e-9 and n in self.revolute
                        for n in names)
        segs.append(Segment(bar, foot, far, (not g.offset and g.pivot in self.revolute,
                                             end_joint)))
        return segs

    def _moving_guide(self, guide, at: np.ndarray, i: int) -> list[Segment]:
        direction = _unit(self.theta(i, guide.link) + guide.angle)
        through = self.p(i, guide.through)
        base = through + guide.offset * np.array([-direction[1], direction[0]])
        t = float((at - base) @ direction)
        lo, hi = min(0.0, t), max(0.0, t)
        span = max(hi - lo, 1e-6)
        return [Segment(guide.link, base + direction * (lo - 0.2 * span),
                        base + direction * (hi + 0.2 * span), (False, False))]

    def _point_arms(self, i: int) -> list[Segment]:
        """Lines to link points off a link's main line (triangular links, extensions)."""
        main = self.main_points()
        plates = dict(self.plates(i))
        out = []
        for lp in self.mech.points:
            ends = main.get(lp.link)
            if ends is None or lp.name in ends:
                continue
            p = self.p(i, lp.name)
            if lp.link in plates:
                out.extend(self._plate_arms(lp, plates[lp.link], p))
                continue
            a, b = self.p(i, ends[0]), self.p(i, ends[1])
            d = b - a
            length = float(np.hypot(*d))
            if length == 0:
                continue
            t = float((p - a) @ d) / length**2
            off = abs(float(d[0] * (p - a)[1] - d[1] * (p - a)[0])) / length
            joint = lp.name in self.revolute
            if off > 1e-6 * length:
                out.append(Segment(lp.link, a, p, (ends[0] in self.revolute, joint)))
                out.append(Segment(lp.link, b, p, (ends[1] in self.revolute, joint)))
            elif t > 1 + 1e-9:
                out.append(Segment(lp.link, b, p, (False, joint)))
            elif t < -1e-9:
                out.append(Segment(lp.link, a, p, (False, joint)))
        return out

    def _plate_arms(self, lp, corners: np.ndarray, p: np.ndarray) -> list[Segment]:
        """A point of a ternary link: none inside the plate (a centre of mass), else arms
        from the two nearest joints."""
        if shapely.Polygon(corners).buffer(1e-9).contains(shapely.Point(p)):
            return []
        near = np.argsort(np.hypot(*(corners - p).T))[:2]
        joint = lp.name in self.revolute
        return [Segment(lp.link, corners[k], p, (True, joint)) for k in near]

    def blocks(self, i: int) -> list[Block]:
        return [b for g in self.mech.groups for b in drawing_of(g).blocks(self, g, i)]

    def tracks(self, fine: Kinematics) -> list[GuideTrack]:
        """Fixed guides with the range their blocks travel over a whole turn."""
        out = []
        for g in self.mech.groups:
            for lk, gd, point in drawing_of(g).tracks(g):
                direction = _unit(gd.angle)
                through = np.asarray(self.mech.ground_points[gd.through], float)
                base = through + gd.offset * np.array([-direction[1], direction[0]])
                travel = (fine.position(point) - base) @ direction
                travel = travel[np.isfinite(travel)]
                out.append(GuideTrack(lk, base, gd.angle, float(travel.min()),
                                      float(travel.max()), point))
        return out


# ---- each group kind drawn: its lines, blocks, fixed guides --------------------------------


class Drawing(NamedTuple):
    """How a group kind is drawn: ``segments(geo, g, i)`` and ``blocks(geo, g, i)`` at position
    i, ``tracks(g)`` its blocks on fixed guides (link, guide, the point that travels), and
    ``lead_blocks(g)`` the joints of its block leads (their letters go beside the guide)."""

    segments: Callable[[_Geometry, Any, int], list[Segment]]
    blocks: Callable[[_Geometry, Any, int], list[Block]]
    tracks: Callable[[Any], list[tuple]] = lambda g: []
    lead_blocks: Callable[[Any], tuple[str, ...]] = lambda g: ()


def _rrr_segments(geo: _Geometry, g: RRR, i: int) -> list[Segment]:
    return [geo._seg(g.links[0], g.joints[0], g.point, i), geo._seg(g.links[1], g.joints[1], g.point, i)]


def _rrp_segments(geo: _Geometry, g: RRP, i: int) -> list[Segment]:
    segs = [geo._seg(g.links[0], g.joint, g.point, i)]
    if g.guide.link != GROUND:
        segs.extend(geo._moving_guide(g.guide, geo.p(i, g.point), i))
    return segs


def _prp_segments(geo: _Geometry, g: PRP, i: int) -> list[Segment]:
    return [s for guide in g.guides if guide.link != GROUND for s in geo._moving_guide(guide, geo.p(i, g.point), i)]


def _rpp_segments(geo: _Geometry, g: RPP, i: int) -> list[Segment]:
    k = geo.p(i, g.origin_name)
    b = geo.p(i, g.joint)
    direction = b - k
    length = float(np.hypot(*direction))
    if length > 0:
        far = b + direction / length * 0.25 * max(length, 1e-9)
        return [Segment(g.links[1], k, far, (False, False))]
    return []


def _rpp_blocks(geo: _Geometry, g: RPP, i: int) -> list[Block]:
    guide_angle = geo.theta(i, g.guide.link) + g.guide.angle
    return [Block(g.links[1], geo.p(i, g.origin_name), guide_angle),
            Block(g.links[0], geo.p(i, g.joint), guide_angle + g.slot_angle)]


def _triad_blocks(geo: _Geometry, g: Triad, i: int) -> list[Block]:
    return [Block(ld.link, geo.p(i, j), geo.theta(i, ld.guide.link) + ld.guide.angle)
            for ld, j in zip(g.leads, g.joints) if ld.slider]


#: The drawing's one lookup by group kind (`drawing_of`).
DRAWINGS: dict[type, Drawing] = {
    RRR: Drawing(_rrr_segments, lambda geo, g, i: []),
    RRP: Drawing(_rrp_segments,
                 lambda geo, g, i: [Block(g.links[1], geo.p(i, g.point), geo.theta(i, g.guide.link) + g.guide.angle)],
                 lambda g: [(g.links[1], g.guide, g.point)] if g.guide.link == GROUND else []),
    RPR: Drawing(lambda geo, g, i: geo._bar(g, i),
                 lambda geo, g, i: [Block(g.links[0], geo.p(i, g.joint), geo.theta(i, g.links[1]))]),
    PRP: Drawing(_prp_segments,
                 lambda geo, g, i: [Block(g.links[0], geo.p(i, g.point),
                                          geo.theta(i, g.guides[0].link) + g.guides[0].angle)],
                 lambda g: [(lk, gd, g.point) for lk, gd in zip(g.links, g.guides) if gd.link == GROUND]),
    RPP: Drawing(_rpp_segments, _rpp_blocks,
                 lambda g: [(g.links[1], g.guide, g.origin_name)] if g.guide.link == GROUND else []),
    Triad: Drawing(lambda geo, g, i: geo._triad(g, i), _triad_blocks,
                   lambda g: [(ld.link, ld.guide, j) for ld, j in zip(g.leads, g.joints)
                              if ld.slider and ld.guide.link == GROUND],
                   lambda g: tuple(j for ld, j in zip(g.leads, g.joints) if ld.slider)),
}


def drawing_of(g) -> Drawing:
    """How ``g``'s kind is drawn; a `MechanismError` naming a kind with no drawing."""
    return kind_entry(DRAWINGS, g, "velplan.views.mechanism.DRAWINGS")


def special_points(mech: Mechanism) -> set[str]:
    """Assur's special points of the triads: construction points of their base links, drawn
    only where the plan's construction is shown (they may lie far off, or at infinity)."""
    return {p for g in mech.groups for p in g.special_points()}


def _drawn_xy(kin: Kinematics) -> np.ndarray:
    """Positions (m) of the points the scheme draws, every position, finite ones only."""
    skip = special_points(kin.mechanism)
    keep = [k for name, k in kin.point_index.items() if name not in skip]
    xy = kin.positions[:, keep].reshape(-1, 2)
    return xy[np.all(np.isfinite(xy), axis=1)]


def _centroid(kin: Kinematics) -> np.ndarray:
    return _drawn_xy(kin).mean(axis=0)


def output_point(mech: Mechanism) -> str | None:
    """The point whose positions are numbered besides the crank's: the output slider, or the
    moving joint of the output link."""
    out = mech.output
    if out is None:
        return None
    if out.point:
        for g in mech.groups:
            if g.track_point(out.point) != out.point:
                return g.track_point(out.point)  # an RPP runner's positions are read on its guide
        return out.point
    for g in mech.groups:
        if g.output_joint(out.link) is not None:
            return g.output_joint(out.link)
    return None


def trajectory_points(mech: Mechanism) -> list[str]:
    """Characteristic points whose paths are drawn: the crank tip, every joint a group
    solves for and every named point on a moving link, without coincident duplicates."""
    owner = point_owners(mech)
    ground = set(mech.ground_points)
    names = [mech.crank.tip]
    for g in mech.groups:
        names += list(g.inner_joints())
    names += [p.name for p in mech.points]
    return [n for n in dict.fromkeys(names) if n not in ground and n in owner]


@dataclass(frozen=True)
class MechanismSizes:
    """Text heights of the view, mm."""

    title_mm: float = 5.0
    label_mm: float = 3.5
    number_mm: float = 2.5


def mechanism_view(mech: Mechanism, *, kin: Kinematics, fine: Kinematics, mu_l: float, n: int = 12,
                   thick: int = 1, lang: Language = "ru", sizes: MechanismSizes = MechanismSizes(),
                   title: bool = True, single: bool = False,
                   extreme: Kinematics | None = None, special: bool | Sequence[int] = False,
                   bold: Sequence[int] = (), plans: Sequence[int] = ()) -> View:
    """The kinematic scheme of `mech` in `n` positions at the scale `mu_l` (m/mm).

    Parameters
    ----------
    mu_l : float
        Length scale, m of the mechanism per mm of the drawing (0.002 is 1:2).
    n : int
        Number of positions, evenly spaced from the reference position in the sense of ω1.
    thick : int
        Position drawn thick, 1-based.
    lang : {"en", "ru", "uk", "zh"}
    kin, fine : Kinematics
        The mechanism solved at the n positions and on a fine grid over a turn (trajectories):
        a `velplan.study.Study`'s ``kinematics`` and ``turn``.
    title : bool
        Write the view's title and scale above it.
    single : bool
        Draw the thick position alone: no other positions, trajectories or numbers (the
        step-by-step figures).
    extreme : Kinematics, optional
        The other extreme position of the output (one position), drawn bold and marked
        ``1′`` at the output point (`velplan.study.Study.other_extreme`).
    bold : sequence of int
        Positions (1-based) drawn bold rather than thin: the extreme ones among the n, and
        those of the plans on the sheet.
    plans : sequence of int
        Positions (1-based) whose plans are drawn, named after the scale ("the plans'
        positions (thick lines): 4, 10").
    special : bool or sequence of int
        Draw each triad's Assur special point in the thick position (True) or in these
        positions (1-based; the plans' positions of a sheet): the lines of the two
        leads that cross there (thin, dash-dotted) and the point, lettered (the figures of a
        plan's construction); it is left out where it falls far off the scheme.

    Returns
    -------
    View
        ``mu`` is μl; ``to_view`` maps metres to the view's mm. ``meta["positions"]`` holds
        the crank angles (rad), ``meta["thick"]`` the thick position.
    """
    return run_scheme(scheme_steps(mech, kin=kin, fine=fine, mu_l=mu_l, n=n, thick=thick, lang=lang,
                                   sizes=sizes, title=title, single=single, extreme=extreme,
                                   special=special, bold=bold, plans=plans))


class LetterRequest(NamedTuple):
    """The arguments of one `place_letters` call a scheme's drawing waits on (`scheme_steps`)."""

    args: tuple
    kwargs: dict


def run_scheme(steps: Generator[LetterRequest, tuple, View]) -> View:
    """The view `scheme_steps` draws, each of its letter requests answered by `place_letters`."""
    try:
        request = next(steps)
        while True:
            request = steps.send(place_letters(*request.args, **request.kwargs))
    except StopIteration as done:
        return done.value


def scheme_steps(mech: Mechanism, *, kin: Kinematics, fine: Kinematics, mu_l: float, n: int = 12,
                 thick: int = 1, lang: Language = "ru", sizes: MechanismSizes = MechanismSizes(),
                 title: bool = True, single: bool = False,
                 extreme: Kinematics | None = None, special: bool | Sequence[int] = False,
                 bold: Sequence[int] = (), plans: Sequence[int] = ()) -> Generator[LetterRequest, tuple, View]:
    """`mechanism_view` as a generator: it yields each `place_letters` call it needs as a
    `LetterRequest`, is sent that call's result, and returns the view (so that the drawings of
    many positions can have their letters placed together, `velplan.html.scheme`). The same
    parameters (`thick`, `bold`, `plans`: positions 1-based)."""
    t = position_index(thick, n)
    geo = _Geometry(mech, kin)
    mm = lambda xy: np.asarray(xy, float) / mu_l  # noqa: E731 - content mm: model / μl
    items: list[Primitive] = []
    obstacles: list = []
    if not single:
        _other_positions(items, obstacles, geo, fine, t, mm, mu_l, extreme, bold)
    specials = ([t] if special is True else
                [position_index(k, n) for k in special] if special else [])
    drawn = _thick_position(items, obstacles, geo, fine, t, mm, mu_l, sizes.label_mm, specials)
    letters, labels, links, anchors = _scheme_labels(items, geo, drawn, t, mm, sizes, single, extreme, obstacles)
    # no letter over a point of the thick position: next to another point it would name that one
    points = [mm(geo.p(t, name)) for name in kin.point_index if name not in special_points(mech)]
    obstacles += list(shapely.buffer(shapely.points(np.array([p for p in points if np.all(np.isfinite(p))],
                                                             float).reshape(-1, 2)), POINT_CLEAR_MM, quad_segs=16))
    named = [mm(geo.p(t, name)) for name in kin.point_index] + [at for _, at in letters]
    thin = _lines([p.points for p in items if isinstance(p, Polyline) and p.line == "thin"])
    # the letters keep off the places the output's position numbers want, where they can
    wanted = [label_box(x) for x in labels if x.text.isdigit()]
    placed_letters, leaders = yield LetterRequest(
        ([x for x, _ in letters], [at for _, at in letters], named, obstacles), {"thin": thin + wanted, "soft_mm": SCHEME_SOFT_MM})
    if not single:  # the crank's numbers, each nearer its own position of the tip than any other
        tips = mm(kin.position(mech.crank.tip))
        numbers, number_leaders = yield LetterRequest(
            (_crank_numbers(mech, kin, mm, sizes.number_mm), tips, tips, obstacles),
            {"thin": thin, "taken": [label_box(x).buffer(0.4) for x in placed_letters], "soft_mm": SCHEME_SOFT_MM})
        placed_letters, leaders = placed_letters + numbers, leaders + number_leaders
    placed = place_labels(labels, obstacles, rings=8, taken=placed_letters)
    out = output_point(mech)
    marks = (list(shapely.buffer(shapely.points(_finite_rows(mm(kin.position(out)))), POINT_CLEAR_MM / 2))
             if out is not None and not single else [])  # no number over another position's point
    placed, moved, moved_leaders = _labels_off_the_lines(labels, placed, anchors, obstacles + marks, thin,
                                                         placed_letters)
    leaders += moved_leaders
    # the links' numbers, each nearer its own link's point than another link's
    numbers, number_leaders = yield LetterRequest(
        ([x for x, _ in links], [at for _, at in links], [at for _, at in links], obstacles + marks),
        {"thin": thin, "taken": _grown([*placed_letters, *placed], 1.5),  # not read as one with a letter
         "soft_mm": SCHEME_SOFT_MM})
    items += placed_letters + leaders + list(placed) + numbers + number_leaders
    if not single and out is not None and out != mech.crank.tip:
        # the output's numbers, the first len(kin) labels (`_scheme_labels`); a moved one has its leader already
        kept = [k for k in range(len(kin)) if k not in moved]
        items += _number_leaders([placed[k] for k in kept], mm(kin.position(out)))
    items = _broken_under_texts(items)
    if title:
        items += _title(items, thick, single, mu_l, lang, sizes, plans)
    return make_view("mechanism", items, pad_mm=SCHEME_PAD_MM, mu=mu_l, origin=(0.0, 0.0),
                     meta={"positions": kin.phi, "thick": thick, "n": n})


#: Margin of a scheme's view round what it draws, mm.
SCHEME_PAD_MM = 2.0


def least_scheme_size(mech: Mechanism, kin: Kinematics, *, mu_l: float, thick: int = 1,
                      sizes: MechanismSizes = MechanismSizes(), title: bool = True) -> tuple[float, float]:
    """A lower bound of the width and height (mm) of the box of `mechanism_view` (not
    ``single``) with these arguments (``thick``: the bold position's number, 1…n), found
    without drawing: the lines of the positions other than the thick one (a line is broken only within `BREAK_MM` of a text's box, and the box
    counts), the view's margin, and the title's lines above everything. A sheet passes over a
    scale whose bound fits nowhere, or leaves the plans no chance, undrawn."""
    t = position_index(thick, len(kin))
    geo = _Geometry(mech, kin)
    ends = [(s.a, s.b) for i in range(len(kin)) if i != t and kin.valid[i] for s in geo.segments(i)]
    xy = np.array([e for a, b in ends if np.any(a != b) for e in (a, b)], float).reshape(-1, 2) / mu_l
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    above = 4.0 + 2.6 * sizes.title_mm if title else 0.0  # the title's capital line over the top
    if not len(xy):
        return 2 * SCHEME_PAD_MM, 2 * SCHEME_PAD_MM + above
    span = np.maximum(np.ptp(xy, axis=0) - 2 * BREAK_MM, 0.0)
    return float(span[0]) + 2 * SCHEME_PAD_MM - 1e-6, float(span[1]) + 2 * SCHEME_PAD_MM + above - 1e-6


#: The thin lines a scheme's text interrupts (ESKD: a line is broken where a text must stand
#: on it): the other positions and the trajectories, never a leader or an axis.
_BROKEN_LAYERS = ("positions", "trajectory")
#: The gap a broken line keeps round a text's box, mm.
BREAK_MM = 0.4


def _broken_under_texts(items: list) -> list:
    """`items` with each thin line of the other positions or a trajectory broken where a text
    stands on it (the letters went to the spots clear of them where their points have one):
    the parts outside the texts' boxes (:data:`BREAK_MM` round), in the line's place."""
    texts = [p for p in items if isinstance(p, Text)]
    thin = [k for k, p in enumerate(items)
            if isinstance(p, Polyline) and p.line == "thin" and p.layer in _BROKEN_LAYERS]
    if not texts or not thin:
        return items
    holes = _grown(texts, BREAK_MM)
    lines = np.array(_lines([items[k].points for k in thin]), dtype=object)
    crossed, hole = shapely.STRtree(holes).query(lines, predicate="intersects")  # by line, in one call
    if not len(crossed):
        return items
    starts = np.flatnonzero(np.r_[True, crossed[1:] != crossed[:-1]])
    hit = crossed[starts]
    rests = shapely.difference(lines[hit], [shapely.union_all([holes[j] for j in group])
                                            for group in np.split(hole, starts[1:])])
    pieces = dict(zip((thin[i] for i in hit.tolist()), _kept_parts(rests)))
    out: list = []
    for k, p in enumerate(items):
        if k in pieces:
            out += [_moved(p, points=run) for run in pieces[k]]
        else:
            out.append(p)
    return out


def _kept_parts(lines) -> list[list]:
    """Per geometry of `lines` (what is left of each broken line), the point runs of its parts
    longer than 0.2 mm, as tuples of (x, y) mm."""
    parts, of = shapely.get_parts(lines, return_index=True)
    keep = ~shapely.is_empty(parts) & (shapely.length(parts) > 0.2)
    parts, of = parts[keep], of[keep]
    xy, at = shapely.get_coordinates(parts, return_index=True)
    runs = np.split(xy, np.flatnonzero(np.diff(at)) + 1) if len(xy) else []
    out: list[list] = [[] for _ in lines]
    for i, run in zip(of.tolist(), runs):
        out[i].append(tuple(map(tuple, run.tolist())))
    return out


def _finite_rows(xy) -> np.ndarray:
    """The rows of the points `xy` (n, 2) with finite coordinates."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    return xy[np.all(np.isfinite(xy), axis=1)]


def _grown(texts: list[Text], by_mm: float) -> list:
    """Each text's `label_box` grown by `by_mm` (as ``label_box(t).buffer(by_mm)``), in one call."""
    if not texts:
        return []
    return list(shapely.buffer(shapely.polygons([text_box(t) for t in texts]), by_mm, quad_segs=16))


def _lines(runs: list) -> list:
    """Shapely lines through each run of points (mm), made in one call."""
    if not runs:
        return []
    xy = np.array([q for run in runs for q in run], float).reshape(-1, 2)
    return list(shapely.linestrings(xy, indices=np.repeat(np.arange(len(runs)), [len(r) for r in runs])))


#: Millimetres of gap a thin line (another position, a trajectory) across a scheme's letter or
#: number is worth: more than any clear spot round its point costs (`letters.GAPS_MM` and the
#: turn), so a letter crosses a thin line only where every spot within reach of its point does.
SCHEME_SOFT_MM = 10.0
#: The letters keep this far off every point of the thick position (its own included), mm.
POINT_CLEAR_MM = 1.5


def _other_positions(items: list, obstacles: list, geo: _Geometry, fine: Kinematics, t: int, mm,
                     mu_l: float, extreme: Kinematics | None, bold: Sequence[int]) -> None:
    """Add the trajectories, the positions other than the thick one `t` (thin, or bold when
    1-based in `bold`) and the other extreme position to `items` (bold lines to `obstacles`)."""
    kin = geo.kin
    for name in trajectory_points(geo.mech):  # under everything
        path = fine.position(name)
        path = path[np.all(np.isfinite(path), axis=1)]
        if len(path) >= 2 and np.ptp(path, axis=0).max() / mu_l > 0.5:
            items.append(Polyline(mm(path), "trajectory", "thin"))
    for i in range(len(kin)):
        if i == t or not kin.valid[i]:
            continue
        weight = "thick" if position_number(i) in bold else "thin"
        for s in geo.segments(i):
            items += link(mm(s.a), mm(s.b), trim_a_mm=0.0, trim_b_mm=0.0, layer="positions",
                          line=weight)
            if weight == "thick":  # letters keep off the bold lines too
                obstacles.append(shapely.LineString([mm(s.a), mm(s.b)]).buffer(0.6))
    if extreme is not None and extreme.valid[0]:
        for sg in _Geometry(geo.mech, extreme).segments(0):
            items.append(Polyline([mm(sg.a), mm(sg.b)], "positions", "thick"))
            obstacles.append(shapely.LineString([mm(sg.a), mm(sg.b)]).buffer(0.6))


@dataclass(frozen=True)
class _Thick:
    """What the labels of the thick position need to know of its drawing."""

    centre: np.ndarray
    tracks: list
    segments: list
    blocks: list
    guide_sides: dict
    special_letters: list


def _thick_position(items: list, obstacles: list, geo: _Geometry, fine: Kinematics, t: int, mm,
                    mu_l: float, label_mm: float, specials: Sequence[int] = ()) -> _Thick:
    """Add the thick position `t` to `items`: guides, pivots, (special point), links, blocks,
    joints; their outlines to `obstacles`."""
    centre = mm(_centroid(geo.kin))
    tracks = geo.tracks(fine)
    thick_segments = geo.segments(t)
    guide_sides = {}
    for tr in tracks:
        side = _guide_side(tr, mu_l, centre, mm(geo.p(t, tr.point)), thick_segments, mm)
        guide_sides[tr.point] = side
        guide, outline = _drawn_once(("guide", tr.base.tobytes(), tr.angle, tr.lo, tr.hi, mu_l, side.tobytes()),
                                     lambda: _guide_and_outline(tr, mu_l, side))
        items += guide
        obstacles += outline
    for name in geo.ground_pivots:
        at, towards = mm(geo.p(t, name)), _ground_side(geo, name, t, mm)
        support, outline = _drawn_once(("pivot", at.tobytes(), towards), lambda: _support_and_outline(at, towards))
        items += support
        obstacles += outline
    special_letters = [x for i in specials  # positions other than the thick one say theirs
                       for x in _add_special(items, obstacles, geo, i, mm, label_mm,
                                             "" if i == t else f" ({position_number(i)})")]
    for _, corners in geo.plates(t):
        strokes = plate_corners(mm(corners))
        items += strokes
        obstacles += _corner_hulls(mm(corners), strokes)  # no letter on a plate's hatched corner
    ends = []
    for s in thick_segments:
        a, b = mm(s.a), mm(s.b)
        items += link(a, b, trim_a_mm=JOINT_RADIUS_MM if s.joints[0] else 0.0,
                      trim_b_mm=JOINT_RADIUS_MM if s.joints[1] else 0.0, layer="mechanism")
        ends.append((a, b))
    obstacles += _capsules(ends, 0.6)
    blocks = geo.blocks(t)
    for bl in blocks:
        body = slider_block(mm(bl.centre), math.degrees(bl.angle), length_mm=BLOCK_MM[0],
                            width_mm=BLOCK_MM[1], layer="mechanism")
        items += body
        obstacles.append(shapely.Polygon(body[0].points).buffer(0.5))
    joints = [p for p in geo.revolute if p not in geo.ground_pivots]
    for name in sorted(joints, key=lambda p: list(geo.kin.point_index).index(p)):
        items += revolute_joint(mm(geo.p(t, name)), layer="mechanism")
    _mass_signs(items, obstacles, geo, t, mm)
    return _Thick(centre, tracks, thick_segments, blocks, guide_sides, special_letters)


def _capsules(ends: list, radius: float) -> list:
    """Each segment (a, b) (mm) grown by `radius`, as ``LineString([a, b]).buffer(radius)``,
    made in one call."""
    if not ends:
        return []
    return list(shapely.buffer(shapely.linestrings(np.array(ends, float).reshape(-1, 2, 2)), radius, quad_segs=16))


#: Guides and supports drawn so far, by all they depend on (cleared when full): a page's frames
#: and a sheet's trials draw the same ones again and again.
_DRAWN: dict[tuple, tuple[tuple, tuple]] = {}
_DRAWN_KEPT = 512


def _drawn_once(key: tuple, draw: Callable[[], tuple[list, list]]) -> tuple[tuple, tuple]:
    """The primitives and outlines `draw` makes, drawn once per `key` (both immutable)."""
    hit = _DRAWN.get(key)
    if hit is None:
        if len(_DRAWN) >= _DRAWN_KEPT:
            _DRAWN.clear()
        primitives, outlines = draw()
        hit = _DRAWN[key] = (tuple(primitives), tuple(outlines))
    return hit


def _guide_and_outline(tr: GuideTrack, mu_l: float, side: np.ndarray) -> tuple[list, list]:
    """A fixed guide (`_guide`) and its outline the letters keep off: its points' hull (an
    inclined guide's bounding box would cover half the scheme), 0.3 mm round."""
    guide = _guide(tr, mu_l, side)
    hull = shapely.multipoints(np.array([q for g in guide for q in g.points], float)).convex_hull
    return guide, [hull.buffer(0.3)]


def _support_and_outline(at: np.ndarray, towards: float) -> tuple[list, list]:
    """A fixed pivot's support at `at` (mm) on ground towards `towards` (deg), and its outlines:
    the triangle and the hatching, 0.5 mm round (a letter may stand beside the pivot's circle)."""
    support = fixed_pivot(at, direction_deg=towards, layer="mechanism")
    return support, [shapely.Polygon(support[0].points).buffer(0.5), shapely.box(*bounds_of(support[1:-1])).buffer(0.5)]


def _mass_signs(items: list, obstacles: list, geo: _Geometry, t: int, mm) -> None:
    """The centre-of-mass sign at every centre of mass of position t (the mass table's
    centres, or the points named S2, S3…) that no joint already marks."""
    centres = {m.centre for m in geo.mech.masses} | {
        p for p in geo.kin.point_index if p[:1] == "S" and p[1:].isdigit()}
    joints = [mm(geo.p(t, q)) for q in geo.revolute]
    for name in sorted(c for c in centres if c in geo.kin.point_index):
        p = mm(geo.p(t, name))
        if np.all(np.isfinite(p)) and all(np.hypot(*(p - q)) > JOINT_RADIUS_MM for q in joints):
            items += centre_of_mass_sign(p, layer="mechanism")
            obstacles.append(shapely.Point(p).buffer(2.0))


def _output_on_track(mech: Mechanism, out: str) -> bool:
    """Whether the output point slides on a guide (its numbers go beside the guide)."""
    return any(out in g.output_slides() for g in mech.groups)


def _scheme_labels(items: list, geo: _Geometry, drawn: _Thick, t: int, mm, sizes: MechanismSizes,
                   single: bool, extreme: Kinematics | None, obstacles: list | None = None
                   ) -> tuple[list, list[Text], list, list]:
    """The labels to place: the letters of the points of the thick position (and of the special
    points), each with its point (mm); the position numbers of the output, ω1 (its arrow added
    to `items`, and to `obstacles`: no letter is written over it), the numbers inside plates;
    the other links' numbers, each with its point on the link (mm); and for each of the
    second, the point it names and the points it must stand nearer to than to any other
    (the output's positions; ω1's arc), or None (a number inside its plate)."""
    mech, kin = geo.mech, geo.kin
    letters = list(drawn.special_letters)
    letters += _point_labels(geo, t, mm, sizes.label_mm, drawn.segments, drawn.blocks,
                             {pt: side for pt, side in drawn.guide_sides.items() if pt in _lead_blocks(mech)})
    labels: list[Text] = []
    anchors: list = []
    out = output_point(mech)
    if out is not None and out != mech.crank.tip and not single:
        labels += _output_numbers(kin, out, mm, sizes.number_mm,
                                  _output_on_track(mech, out) and bool(drawn.tracks),
                                  drawn.centre, drawn.guide_sides.get(out))
        anchors += [(p, mm(kin.position(out))) for p in mm(kin.position(out))]
    if extreme is not None and not single and extreme.valid[0] and out is not None:
        at = mm(extreme.position(out)[0])
        labels.append(Text((at[0] + 1.5, at[1] + 1.5), "1′", "labels", sizes.number_mm))
        anchors.append((at, [at]))
    omega = _omega_arrow(mech, geo, t, mm, sizes.label_mm)
    items += omega[:-1]
    labels.append(omega[-1])
    arc = np.asarray(omega[0].points)  # ω1 names its arc: the arc's point nearest its wanted place
    on_arc = arc[int(np.argmin(np.hypot(*(arc - np.asarray(omega[-1].position)).T)))]
    anchors.append((on_arc, [on_arc]))
    if obstacles is not None:
        obstacles += [shapely.LineString(p.points if isinstance(p, Polyline) else [p.start, p.end]).buffer(0.6)
                      for p in omega[:-1] if isinstance(p, (Polyline, Arrow))]
    away_from_guides = [(mm(geo.p(t, pt)), -side) for pt, side in drawn.guide_sides.items()]
    numbers = _link_numbers(mech, geo, t, mm, sizes.label_mm, drawn.segments, drawn.blocks,
                            drawn.centre, away_from_guides)
    labels += [x for x, at in numbers if at is None]
    anchors += [None for _, at in numbers if at is None]
    return letters, labels, [(x, at) for x, at in numbers if at is not None], anchors


def _labels_off_the_lines(wanted: list[Text], placed, anchors: list, obstacles: list, thin: list,
                          letters: list[Text]) -> tuple[tuple[Text, ...], set[int], list[Polyline]]:
    """The scheme's labels (`placed` by `place_labels` from their `wanted` places) with each one
    that `place_labels` had to leave over a line or a symbol (`obstacles`), or over a `thin`
    line, placed again by `place_letters` round its point (`anchors`: the point and the points
    it must stand nearer to than to any other, as `_scheme_labels` gives them): the nearest
    free spot that reads as its point's, else one beyond the crowd with a thin leader; one
    that was only over thin lines moves where it crosses fewer. Returns the labels, the
    indices of those placed again and their leaders."""
    shapes = [g for g in obstacles if not g.is_empty]
    if not shapes:
        return tuple(placed), set(), []
    tree = shapely.STRtree(shapes)
    lines = [g for g in thin if not g.is_empty]
    soft = shapely.STRtree(lines) if lines else None
    out: list[Text] = list(placed)
    moved: set[int] = set()
    leaders: list[Polyline] = []
    letter_boxes = shapely.polygons([text_box(x) for x in letters]) if letters else []
    grown: dict = {}  # id of a text → (the text, its box grown by 0.4 mm)
    for k, (text, where) in enumerate(zip(placed, anchors)):
        if where is None or not np.all(np.isfinite(where[0])):
            continue
        hard = bool(len(tree.query(label_box(text), predicate="intersects")))
        crossing = _thin_crossings(soft, lines, text)
        blocked = _leader_blocked(text, where[0], letter_boxes)
        if not hard and not crossing and not blocked:
            continue
        taken = [grown_once(x, grown) for x in (*letters, *out[:k], *out[k + 1:])]
        (again,), led = place_letters([wanted[k]], [where[0]], where[1], shapes, taken=taken, thin=thin,
                                      soft_mm=SCHEME_SOFT_MM)
        if len(tree.query(label_box(again), predicate="intersects")):
            continue  # crowded all round: where place_labels left it
        now = _thin_crossings(soft, lines, again)
        still = (_through(led[0], letter_boxes) if led else _leader_blocked(again, where[0], letter_boxes))
        if not hard and (now > crossing or (now == crossing and not (blocked and not still))):
            continue  # no spot crosses fewer thin lines (as many, where its leader would cross a letter)
        out[k], leaders = again, leaders + led
        moved.add(k)
    return tuple(out), moved, leaders


def _through(leader: Polyline, boxes) -> bool:
    """Whether `leader` runs through one of `boxes` (over 0.5 mm)."""
    return bool(len(boxes)) and bool(
        (shapely.length(shapely.intersection(shapely.LineString(leader.points), boxes)) > 0.5).any())


def _leader_blocked(text: Text, point, letter_boxes) -> bool:
    """Whether `text`, standing farther than :data:`NUMBER_LEADER_MM` from its `point` (mm),
    would have its leader (`_number_leaders`) run through one of the letters (their boxes)."""
    box = label_box(text)
    if not len(letter_boxes) or box.distance(shapely.Point(point)) <= NUMBER_LEADER_MM:
        return False
    leader = shapely.shortest_line(box.buffer(0.4), shapely.Point(point))
    return _through(Polyline(tuple(leader.coords), "labels", "thin"), letter_boxes)


def _thin_crossings(soft, lines: list, text: Text) -> int:
    """How many of the thin `lines` (in the tree `soft`) cross the box of `text` over more
    than 1 mm (what a reader sees as a line through it)."""
    if soft is None:
        return 0
    box = label_box(text)
    return sum(lines[j].intersection(box).length > 1.0 for j in soft.query(box, predicate="intersects"))


def _title(items: list, thick: int, single: bool, mu_l: float, lang: Language,
           sizes: MechanismSizes, plans: Sequence[int] = ()) -> list[Text]:
    """The view's title and scale (and the positions of the plans), above `items`."""
    x0, _, _, y1 = bounds_of(items)
    which = (f";  {label('plan_positions_bold', lang)}: {', '.join(map(str, plans))}"
             if plans and not single else "")
    return [Text((x0, y1 + 4.0 + 1.6 * sizes.title_mm),
                 f"{label('position', lang)} {thick}" if single else label("mechanism_positions", lang),
                 "labels", sizes.title_mm),
            Text((x0, y1 + 4.0), scale_text("μl", mu_l, "m/mm", lang) + f"  ({scale_mark(mu_l, lang)})"
                 + which, "labels", sizes.label_mm)]


def extent_m(mech: Mechanism, kin: Kinematics, fine: Kinematics) -> tuple[float, float]:
    """Width and height of the scheme, m (positions and trajectories, no symbols)."""
    xy = np.concatenate([_drawn_xy(kin), _drawn_xy(fine)])
    span = np.ptp(xy, axis=0)
    return float(span[0]), float(span[1])


def _guide_side(tr: GuideTrack, mu_l: float, centre_mm, slider_mm, segs, mm) -> np.ndarray:
    """Unit normal of the guide pointing to the side its hatched line is drawn on: away
    from the rod that drives the slider in the thick position (so the rod never crosses
    the ground), or away from the mechanism's centre when the rod lies along the guide."""
    d = _unit(tr.angle)
    n = np.array([-d[1], d[0]])
    pull = np.zeros(2)
    for here, other in _ends_at(_segment_ends(segs, mm), slider_mm):
        v = other - here
        pull += v / max(np.hypot(*v), 1e-9)
    if abs(float(pull @ n)) > 0.05:
        return -n if float(pull @ n) > 0 else n
    return -n if float((centre_mm - tr.base / mu_l) @ n) > 0 else n


def _guide(tr: GuideTrack, mu_l: float, n: np.ndarray) -> list[Primitive]:
    """A hatched guide line along the block's travel, on the side `n`, so the block rides
    on it."""
    d = _unit(tr.angle)
    base = tr.base / mu_l
    lo = tr.lo / mu_l - BLOCK_MM[0] / 2 - 6.0
    hi = tr.hi / mu_l + BLOCK_MM[0] / 2 + 6.0
    off = n * BLOCK_MM[1] / 2
    a, b = base + d * lo + off, base + d * hi + off
    # hatch on the outer side: `side` is relative to the direction a → b
    side = "left" if float(d[0] * n[1] - d[1] * n[0]) > 0 else "right"
    return list(straight_guide(a, b, side=side, depth_mm=_HATCH_MM, layer="mechanism"))


def _ground_side(geo: _Geometry, name: str, t: int, mm) -> float:
    """Direction (deg) from a fixed pivot to its ground: away from the links at it (over all
    positions, so the same for every ``t``; computed once per view geometry)."""
    cache = geo.__dict__.setdefault("_ground_sides", {})
    if name not in cache:
        cache[name] = _ground_direction(geo, name)
    return cache[name]


def _ground_direction(geo: _Geometry, name: str) -> float:
    dirs = [d for i in range(len(geo.kin)) for d in _directions_at(geo, name, i)]
    if not dirs:
        return -90.0
    mean = np.mean(dirs, axis=0)
    if np.hypot(*mean) < 0.3:  # a crank turning all round: the ground below, by custom
        return -90.0
    a = math.degrees(math.atan2(-mean[1], -mean[0]))
    return float(90.0 * round(a / 90.0))  # supports stand square to the sheet


def _directions_at(geo: _Geometry, name: str, i: int) -> tuple:
    """Unit directions (m) of the link lines leaving point `name` at position i (worked out
    once per position and mechanism)."""
    key = (name, *geo.row_key(i))
    hit = _DIRECTIONS.get(key)
    if hit is not None and hit[0] is geo.mech:
        return hit[1]
    dirs = []
    qx, qy = (float(c) for c in geo.p(i, name))
    tx, ty = 1e-9 + 1e-5 * abs(qx), 1e-9 + 1e-5 * abs(qy)  # np.allclose(here, q, atol=1e-9)
    for s in geo.segments(i):
        for here, other in ((s.a, s.b), (s.b, s.a)):
            if abs(float(here[0]) - qx) <= tx and abs(float(here[1]) - qy) <= ty:
                d = other - here
                if np.hypot(*d) > 0:
                    dirs.append(d / np.hypot(*d))
    if len(_DIRECTIONS) >= _ROWS_KEPT:
        _DIRECTIONS.clear()
    _DIRECTIONS[key] = (geo.mech, tuple(dirs))
    return _DIRECTIONS[key][1]


_DIRECTIONS: dict[tuple, tuple] = {}


def _lead_blocks(mech: Mechanism) -> set[str]:
    """Inner joints of the triads' block leads."""
    return {j for g in mech.groups for j in drawing_of(g).lead_blocks(g)}


def _segment_ends(segs, mm) -> np.ndarray:
    """The ends of the segments `segs` on the drawing (``mm`` of each end), shape (n, 2, 2)."""
    return mm(np.array([(s.a, s.b) for s in segs], float).reshape(-1, 2, 2))


def _ends_at(ends: np.ndarray, p: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The segments' ends (`_segment_ends`) within 0.5 mm of `p` (mm), each with the other end
    of its segment: (end, other), in the order of the segments, an end before its other."""
    here = ends.reshape(-1, 2)
    other = ends[:, ::-1].reshape(-1, 2)
    near = np.hypot(here[:, 0] - p[0], here[:, 1] - p[1]) < 0.5
    return [(here[k], other[k]) for k in np.flatnonzero(near)]


def _point_labels(geo: _Geometry, t: int, mm, size: float, segs, blocks,
                  guide_sides=None) -> list[tuple[Text, np.ndarray]]:
    """Letters of the points at position t, each with its point (mm), off the lines that meet
    at each (and off the hatched side of the guide, for the points in `guide_sides`: point →
    its hatch normal)."""
    kin = geo.kin
    placed: list[np.ndarray] = []
    out = []
    ends = _segment_ends(segs, mm)
    for name in kin.point_index:
        if name.startswith("K") and name not in geo.revolute and name != output_point(geo.mech):
            continue  # the runner's origin is a construction point, not lettered
        p = mm(geo.p(t, name))
        if not np.all(np.isfinite(p)) or any(np.hypot(*(p - q)) < 1.0 for q in placed):
            continue  # a coincident point (A4 at A) takes the letter already written
        placed.append(p)
        away = np.zeros(2)
        for here, other in _ends_at(ends, p):
            d = other - here
            away -= d / max(np.hypot(*d), 1e-9)
        if name in geo.ground_pivots:
            g = math.radians(_ground_side(geo, name, t, mm))
            away -= 1.5 * np.array([math.cos(g), math.sin(g)])
        if guide_sides and name in guide_sides:
            away -= 3.0 * guide_sides[name]
        if np.hypot(*away) < 0.2:
            away = np.array([1.0, 1.0])
        away /= np.hypot(*away)
        # point labels sit diagonally off the joint, clear of the lines meeting there
        anchor = "start" if away[0] > 0.35 else ("end" if away[0] < -0.35 else "middle")
        reach = JOINT_RADIUS_MM + 1.5 + 0.5 * size
        if any(np.hypot(*(mm(b.centre) - p)) < 0.5 for b in blocks):
            reach = 0.5 * math.hypot(*BLOCK_MM) + 1.0  # clear of the slider's corners
        pos = p + away * reach
        out.append((Text(pos, subscript(name), "labels", size, anchor, "middle"), p))
    return out


def _crank_numbers(mech: Mechanism, kin: Kinematics, mm, size: float) -> list[Text]:
    pivot = mm(kin.position(mech.crank.pivot)[0])
    tips = mm(kin.position(mech.crank.tip))
    out = []
    for i, tip in enumerate(tips):
        d = tip - pivot
        d = d / max(np.hypot(*d), 1e-9)
        out.append(Text(tip + d * (1.0 + 0.9 * size), str(position_number(i)), "labels", size, "middle",
                        "middle"))
    return out


def _output_numbers(kin: Kinematics, point: str, mm, size: float, on_track: bool,
                    centre, guide_side=None) -> list[Text]:
    """Numbers of the positions of the output point, one label each, beside its point and off
    the path; where points crowd (an extreme position), a number that would touch one already
    written steps further out along the path's normal, so none overlaps another."""
    from velplan.render.layout import label_box

    xy = mm(kin.position(point))
    n = len(xy)
    _, _, vt = np.linalg.svd(xy - xy.mean(axis=0))
    out: list[Text] = []
    boxes: list = []
    for i in range(n):
        p = xy[i]
        tangent = xy[(i + 1) % n] - xy[(i - 1) % n]
        if np.hypot(*tangent) < 0.2 * size:
            tangent = vt[0]  # an extreme position: its neighbours nearly coincide
        normal = np.array([-tangent[1], tangent[0]]) / np.hypot(*tangent)
        if guide_side is not None:
            if float(guide_side @ normal) < 0:
                normal = -normal  # beyond the hatching of the guide
        elif float((p - centre) @ normal) < 0:
            normal = -normal
        anchor = "start" if normal[0] > 0.35 else ("end" if normal[0] < -0.35 else "middle")
        gap = (BLOCK_MM[1] / 2 + _HATCH_MM + 1.0) if on_track else 2.0
        if anchor == "middle":
            gap += 0.6 * size  # half the text's height, above or below the path
        for row in range(4 * n):
            text = Text(p + normal * (gap + 0.5 * size * row), str(position_number(i)), "labels", size,
                        anchor, "middle")
            box = label_box(text).buffer(0.3 * size)
            if not any(box.intersects(b) for b in boxes):
                break
        boxes.append(box)
        out.append(text)
    return out


#: A position number of the output point farther than this from its point gets a leader, mm.
NUMBER_LEADER_MM = 4.0


def _number_leaders(placed: list[Text], points) -> list[Polyline]:
    """Thin leaders from the output point's positions (`points`, mm, one a position) to their
    numbers (`placed`, the output's only) that stand more than `NUMBER_LEADER_MM` off: the
    numbers stepped out of a crowd (an extreme position, where the points nearly coincide),
    however far the crowd pushed them."""
    from velplan.render.layout import label_box

    out = []
    grown: list = []  # the numbers' boxes grown by 0.4 mm, made at the first leader
    for text in placed:
        p = points[int(text.text) - 1]
        if not np.all(np.isfinite(p)):
            continue
        box = label_box(text)
        if box.distance(shapely.Point(p)) > NUMBER_LEADER_MM:
            near = shapely.shortest_line(box.buffer(0.4), shapely.Point(p)).coords[0]
            if not grown:
                grown = [(x, label_box(x).buffer(0.4)) for x in placed if x.text.rstrip("′").isdigit()]
            leader = _past_the_others(shapely.LineString([p, near]), text, grown)
            if leader is not None:
                out.append(Polyline(leader, "labels", "thin"))
    return out


def _past_the_others(leader, text: Text, grown: list) -> tuple | None:
    """The piece of a number's `leader` (from its point to its box) that runs on from the last
    other number it passes (a number stepped out of a crowd stands beyond its neighbours' in
    line with its point: its leader starts past them, not through them; the other extreme
    position's "1′" too), or None where nothing of it is left. `grown`: (number, its box grown
    by 0.4 mm) of the placed numbers."""
    others = [b for x, b in grown if x is not text]
    hit = [b for b in others if b.intersects(leader)]
    if not hit:
        return tuple(leader.coords)
    end = shapely.Point(leader.coords[-1])
    rest = leader.difference(shapely.union_all(hit))
    parts = [g for g in getattr(rest, "geoms", [rest]) if not g.is_empty and g.distance(end) < 1e-6]
    return tuple(parts[0].coords) if parts and parts[0].length > 0.5 else None


def _omega_arrow(mech: Mechanism, geo: _Geometry, t: int, mm, size: float) -> list:
    """ω1's curved arrow about the crank pivot, in the widest gap between the lines that
    meet there and the pivot's ground support."""
    c = mech.crank
    kin = geo.kin
    pivot = mm(kin.position(c.pivot)[t])
    length = np.hypot(*(mm(kin.position(c.tip)[t]) - pivot))
    radius = float(np.clip(0.5 * length, 6.0, 16.0))
    busy = [_ground_side(geo, c.pivot, t, mm)]
    for s in geo.segments(t):
        a, b = mm(s.a), mm(s.b)
        ends = [(here, other) for here, other in ((a, b), (b, a)) if np.hypot(*(here - pivot)) < 0.5]
        for here, other in ends:  # a line from the pivot blocks its own direction
            d = other - pivot
            busy.append(math.degrees(math.atan2(d[1], d[0])))
        if ends:
            continue
        # a line passing near the pivot (a guide bar) blocks both ways; a line that ends at
        # the pivot was taken above (deciding that by round-off made the arrow flip)
        d = b - a
        L = np.hypot(*d)
        if L > 0 and abs(d[0] * (pivot - a)[1] - d[1] * (pivot - a)[0]) / L < radius and 0 < (pivot - a) @ d < L * L:
            ang = math.degrees(math.atan2(d[1], d[0]))
            busy += [ang, ang + 180.0]
    best = free_direction(busy, 0.0)
    sweep = 70.0 * c.sense
    start = best - sweep / 2
    arrow = rotation_arrow(pivot, radius, start, sweep, layer="mechanism")
    mid = math.radians(best)
    where = pivot + (radius + 1.0 + 0.8 * size) * np.array([math.cos(mid), math.sin(mid)])
    return [*arrow, Text(where, "ω" + digits_down(c.link), "labels", size, "middle", "middle")]


def _link_numbers(mech: Mechanism, geo: _Geometry, t: int, mm, size: float, segs, blocks,
                  centre, away_from_guides=()) -> list[tuple[Text, np.ndarray | None]]:
    """Link numbers beside the middle of each link, or beside its block, on the side of the
    mechanism's centre (away from guides and the numbers of positions), each with its point
    on the link (mm), or None for a number inside its plate."""
    out = []
    done = set()
    for link_name, corners in geo.plates(t):
        lettered = [mm(geo.p(t, lp.name)) for lp in mech.points if lp.link == link_name]
        inside = _plate_number_at(mm(corners), size, lettered)
        if inside is not None:
            done.add(link_name)
            out.append((Text(inside, link_name, "labels", size, "middle", "middle"), None))
    for s in segs:
        if s.link in done:
            continue
        a, b = mm(s.a), mm(s.b)
        d = b - a
        length = np.hypot(*d)
        if length < 4 * size and s.link != mech.crank.link:  # a short crank keeps its number
            continue
        done.add(s.link)
        normal = np.array([-d[1], d[0]]) / length
        if float((centre - (a + 0.42 * d)) @ normal) < 0:
            normal = -normal
        where = a + 0.42 * d + normal * (0.9 * size)
        out.append((Text(where, s.link, "labels", size, "middle", "middle"), a + 0.42 * d))
    for bl in blocks:
        if bl.link in done:
            continue
        done.add(bl.link)
        u = _unit(bl.angle)
        normal = np.array([-u[1], u[0]])
        free = [side for where, side in away_from_guides if np.hypot(*(where - mm(bl.centre))) < 0.5]
        if free:
            if float(free[0] @ normal) < 0:
                normal = -normal  # the side of the block away from its guide
        elif float((centre - mm(bl.centre)) @ normal) < 0:
            normal = -normal
        where = mm(bl.centre) + normal * (BLOCK_MM[1] / 2 + 0.9 * size) - u * (BLOCK_MM[0] / 2)
        out.append((Text(where, bl.link, "labels", size, "middle", "middle"), mm(bl.centre)))
    return out


#: Reach of the hatching in each corner of a ternary link along its sides, mm.
PLATE_CORNER_MM = 7.0


def plate_corners(corners, *, reach_mm: float = PLATE_CORNER_MM, spacing_mm: float = 1.0,
                  layer: str = "mechanism") -> list[Primitive]:
    """The hatched corners of a ternary link (GOST 2.770: the rods of one rigid link, their
    joints hatched in the angle): thin strokes inside each corner of the triangle `corners`
    (mm) out to `reach_mm` along its sides (less on a small triangle)."""
    corners = np.asarray(corners, float)
    sides = [float(np.hypot(*(corners[k] - corners[k - 1]))) for k in range(3)]
    reach = min(reach_mm, 0.4 * min(sides))
    out: list[Primitive] = []
    if reach <= JOINT_RADIUS_MM + 0.5:
        return out
    for k in range(3):
        v, u, w = corners[k], corners[k - 1], corners[(k + 1) % 3]
        eu, ew = (u - v) / np.hypot(*(u - v)), (w - v) / np.hypot(*(w - v))
        # strokes across the corner, square to its bisector, from the joint's circle out
        half = 0.5 * math.acos(float(np.clip(eu @ ew, -1.0, 1.0)))
        first = (JOINT_RADIUS_MM + 0.4) * math.cos(half)
        last = reach * math.cos(half)
        for d in np.arange(first, last + 1e-9, spacing_mm):
            out.append(Polyline([v + eu * d / math.cos(half), v + ew * d / math.cos(half)],
                                layer, "thin"))
    return out


def _corner_hulls(corners, strokes: list) -> list:
    """The hull of the strokes (`plate_corners`) in each corner of the triangle `corners` (mm)."""
    ends = np.array([p.points for p in strokes], float).reshape(-1, 2, 2)
    if not len(ends):
        return []
    mid = ends.mean(axis=1)
    nearest = np.argmin(np.hypot(*(mid[:, None, :] - np.asarray(corners, float)[None, :, :]).transpose(2, 0, 1)), axis=1)
    return [shapely.multipoints(ends[nearest == k].reshape(-1, 2)).convex_hull.buffer(0.3)
            for k in range(len(corners)) if (nearest == k).any()]


def _plate_number_at(corners, size: float, points=()):
    """Where a ternary link's number goes (mm): inside its triangle, at the incentre or on the
    way from it to the middle of a side or to a corner, whichever lies farthest from the link's lettered
    `points` (its centre of mass is often at the incentre); None when the inscribed circle
    cannot hold the number clear of the hatched corners."""
    a, b, c = (float(np.hypot(*(corners[(k + 2) % 3] - corners[(k + 1) % 3]))) for k in range(3))
    perimeter = a + b + c
    if perimeter == 0:
        return None
    area = 0.5 * abs(float((corners[1] - corners[0])[0] * (corners[2] - corners[0])[1]
                           - (corners[1] - corners[0])[1] * (corners[2] - corners[0])[0]))
    radius = 2 * area / perimeter
    if radius < 1.2 * size:
        return None
    incentre = (a * corners[0] + b * corners[1] + c * corners[2]) / perimeter
    spots = [incentre] + [incentre + 0.6 * (0.5 * (corners[k] + corners[k - 1]) - incentre)
                          for k in range(3)] + [incentre + 0.4 * (c - incentre) for c in corners]
    if not len(points):
        return incentre
    return max(spots, key=lambda q: min(float(np.hypot(*(q - p))) for p in points))


def _add_special(items: list, obstacles: list, geo: _Geometry, t: int, mm, size: float,
                 suffix: str = "") -> list[Text]:
    """Append the special points' construction to `items` (under the links and joints that
    come after) and its lines to `obstacles`; returns the letters, to be placed, each with
    its point (mm)."""
    letters, at = [], None
    for p in _special_construction(geo, t, mm, size, suffix):
        if isinstance(p, Text):
            letters.append((p, at))
        else:
            at = p.centre if isinstance(p, Circle) else at
            items.append(p)
            obstacles.append(shapely.box(*p.bounds).buffer(0.5) if isinstance(p, Circle)
                             else shapely.LineString(p.points).buffer(0.5))
    return letters


def _special_construction(geo: _Geometry, t: int, mm, size: float, suffix: str = "") -> list[Primitive]:
    """Each triad's special point in position t: the two lead lines through it (dash-dotted,
    from the outer joint, or the inner joint of a block, on to the point and a little past
    it), the point
    and its letter; nothing when it lies over three scheme-widths away."""
    out: list[Primitive] = []
    span = max(np.ptp(_drawn_xy(geo.kin), axis=0).max(), 1e-9)
    for g in geo.mech.groups:
        special = g.special_points()
        if not special or special[0] not in geo.kin.point_index:
            continue
        k = geo.p(t, special[0])
        centre = _drawn_xy(geo.kin.take([t])).mean(axis=0)
        if not np.all(np.isfinite(k)) or np.hypot(*(k - centre)) > 3 * span:
            continue
        lines = []
        for lead, joint in zip(g.leads, g.joints):
            j = geo.p(t, joint)
            if lead.slider:  # the normal to the guide through the inner joint
                u = _unit(geo.theta(t, lead.guide.link) + lead.guide.angle)
                u = np.array([-u[1], u[0]])
                start = j
            else:
                start = geo.p(t, lead.joint)
                u = (j - start) / max(np.hypot(*(j - start)), 1e-12)
            off = abs(float(u[0] * (k - start)[1] - u[1] * (k - start)[0]))
            lines.append((off, start, j))
        tie = 1e-9 * span  # leads through the point to round-off keep their order, whichever engine solved
        lines.sort(key=lambda x: x[0] if x[0] > tie else 0.0)
        for _, start, j in lines[:2]:
            ends = [mm(start), mm(j), mm(k)]
            direction = ends[2] - ends[0]
            if np.hypot(*direction) < 1e-9:
                direction = ends[1] - ends[0]
            u = direction / max(np.hypot(*direction), 1e-9)
            along = [float((e - ends[0]) @ u) for e in ends]
            lo, hi = min(along), max(along)
            lo, hi = (lo - 4.0, hi) if along[2] == lo else (lo, hi + 4.0)  # on past the point
            out.append(Polyline([ends[0] + u * lo, ends[0] + u * hi], "mechanism", "axis"))
        at = mm(k)
        out.append(Circle(at, 0.6, "mechanism", "thin", "solid"))
        out.append(Text(at + np.array([1.2, 1.2]), subscript(special[0]) + suffix, "labels", size,
                        "start", "baseline"))
    return out
