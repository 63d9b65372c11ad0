"""The instant centres drawn: the scheme in one position with every centre it reaches on the
drawing, the Kennedy lines each centre was found with, and the circle diagram (links on a
circle, a chord per centre: thick for the obvious ones, thin for those found by Kennedy
lines, dashed for those not reached). Pure functions from a `Construction` and a scale to
shapes.
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import MappingProxyType

import numpy as np
import shapely

from velplan.analysis.numbering import position_number
from velplan.analysis.solver import Kinematics
from velplan.options import Language
from velplan.plans.centres import Construction, CentreStep, centre_name
from velplan.render.i18n import centres_words as _t
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Primitive, Text
from velplan.views.base import View, bounds_of, digits_down, make_view, number, place_labels, scale_text, shift, subscript
from velplan.views.letters import LEADER_GAPS_MM, NEAR_MM, place_letters, step_aside
from velplan.views.mechanism import MechanismSizes, mechanism_view
from velplan.views.base import number as _number  # `number` is also the position argument

MARGIN_MM = 40.0
"""How far beyond the scheme (mm, at least; ¾ of its size when larger) centres and Kennedy lines
are still drawn."""
CIRCLE_MM = 28.0
"""Radius of the circle diagram, mm."""
LAYER = "centres"



def _name(pair: tuple[str, str]) -> str:
    """``P₁₃``: the centre's name with subscript link numbers."""
    return digits_down(centre_name(pair))


def _clip(a, b, box, line: str = "construction") -> list[Primitive]:
    """The segment a–b (view mm) clipped to the box, as a ``line`` (or nothing)."""
    cut = shapely.LineString([a, b]).intersection(box)
    if cut.is_empty or cut.geom_type != "LineString" or cut.length < 0.5:
        return []
    return [Polyline(list(cut.coords), LAYER, line)]


def _kennedy_lines(con: Construction, s: CentreStep, to_mm, box, line: str = "construction") -> list[Primitive]:
    """The two Kennedy lines of step ``s``, drawn through their centres to the found one."""
    out: list[Primitive] = []
    if s.infinite:
        return out
    x = to_mm(s.point)
    for ln in s.lines:
        ends = [to_mm(con.centre(*p).point) for p in ln.through if not con.centre(*p).infinite]
        u = np.array([ln.direction.real, ln.direction.imag])
        pts = ends + [x]
        t = [float(np.dot(p - x, u)) for p in pts]
        lo, hi = min(t) - 6.0, max(t) + 6.0
        out += _clip(x + lo * u, x + hi * u, box, line)
    return out


def infinity_note(direction: complex, lang: Language) -> str:
    """Where a centre at infinity lies, in words: vertically, horizontally, or along the line
    at an angle (0…180°, counter-clockwise from the horizontal) — the direction of the centre
    itself, not of the guide it is perpendicular to."""
    deg = math.degrees(math.atan2(direction.imag, direction.real)) % 180.0
    if min(deg, 180.0 - deg) < 0.05:
        return _t("horizontal", lang)
    if abs(deg - 90.0) < 0.05:
        return _t("vertical", lang)
    return _t("inclined", lang, number(deg, lang, 4))


def _at_infinity(con: Construction, s: CentreStep, to_mm, name: str, size: float) -> tuple[list, list]:
    """A slider's centre at infinity on the drawing: its direction line through the slider's
    joint, an arrowhead at each end, and its name with ∞ beyond one end (with that end: the
    point the name is placed by)."""
    joint = s.via[0] if s.how == "slider" and s.via else None
    if joint is None or joint not in con.kin.point_index:
        return [], []
    at = to_mm(complex(*con.kin.position(joint)[con.index]))
    u = np.array([s.direction.real, s.direction.imag])
    if u[1] < -1e-9 or (abs(u[1]) <= 1e-9 and u[0] < 0):
        u = -u  # the named end up (or to the right)
    reach = INFINITY_LINE_MM
    items = [Arrow(tuple(at), tuple(at + reach * u), LAYER, "thin", 2.5, 0.8),
             Arrow(tuple(at), tuple(at - reach * u), LAYER, "thin", 2.5, 0.8)]
    tip = at + (reach + 1.0 + 0.6 * size) * u
    return items, [(Text(tuple(tip), name + " → ∞", "labels", size, "middle", "middle"), at + reach * u)]


#: Gaps of a name with a leader beyond `velplan.views.letters.LEADER_GAPS_MM`, mm: the Kennedy
#: lines crowd a scheme more than its own lines do.
FAR_LEADER_GAPS_MM = (15.0, 18.0)
#: Half-length of the direction line of a centre at infinity through its slider's joint, mm.
INFINITY_LINE_MM = 9.0


def _markers(con: Construction, to_mm, box, size: float, lang: Language) -> tuple[list, list, list[str], dict]:
    """Centre marks, the names of the centres found by Kennedy lines (one merged name where
    marks coincide), each with the point it names (mm), the notes for centres at infinity or
    off the drawing, and the names of the centres at a lettered joint (joint → names: written
    with the joint's letter)."""
    items, labels, notes = [], [], []
    joints: dict[str, list[str]] = {}
    spots: list[tuple[np.ndarray, list[str]]] = []
    for s in con.steps:
        name = _name(s.pair)
        if s.how == "unreached":
            notes.append(f"{name}: {_t('not_reached', lang)}")
        elif s.infinite:
            notes.append(f"{name}: {infinity_note(s.direction, lang)}")
            marks, names = _at_infinity(con, s, to_mm, name, size)
            items += marks
            labels += names
        elif box.contains(shapely.Point(*to_mm(s.point))):
            at = to_mm(s.point)
            items.append(Circle(tuple(at), 0.9 if s.how == "kennedy" else 1.6, LAYER,
                                "thin", "solid" if s.how == "kennedy" else None))
            if s.how in ("joint", "hinge") and s.via:
                joints.setdefault(s.via[0], []).append(name)
                continue
            for where, names in spots:
                if np.hypot(*(where - at)) < COINCIDENT_MM:
                    names.append(name)
                    break
            else:
                spots.append((at, [name]))
        else:
            far = abs(s.point)  # a coordinate within round-off of the other's size is 0
            xy = (f"({number(s.point.real, lang, 4, scale=far)}; {number(s.point.imag, lang, 4, scale=far)}) "
                  f"{_t('metre', lang)}")
            notes.append(f"{name} = {xy}: {_t('off', lang)}")  # `number` writes the minus sign
    labels += [(Text((at[0] + 1.5, at[1] + 1.2), ", ".join(names), "labels", size), at) for at, names in spots]
    return items, labels, notes, joints


#: Centres closer than this on the drawing share one name ("P₂₄, P₂₆"), mm.
COINCIDENT_MM = 1.0


def circle_diagram(con: Construction, *, lang: Language = "en", radius_mm: float = CIRCLE_MM,
                   size_mm: float = 3.5, grow: bool = True) -> list[Primitive]:
    """The circle diagram around (0, 0) mm: links on a circle, a chord per centre — solid for
    the centres known at once, dashed and numbered in the order found for those found by
    Kennedy lines, dash-dotted for those not reached — and its title. Each number sits on or
    beside its own chord, as near its middle as no other chord, mark or number lets it, and
    nearer its own chord than any other; with ``grow``, the radius (``radius_mm`` at least)
    grows from ``radius_mm`` (scaled by the links beyond :data:`CIRCLE_LINKS`) by steps of
    :data:`CIRCLE_GROWTH` until every number finds such a spot."""
    links = con.links
    n = len(links)
    radius, numbers = radius_mm * (max(1.0, n / CIRCLE_LINKS) if grow else 1.0), None
    while numbers is None:
        at = {k: radius * np.array([math.cos(math.pi / 2 - 2 * math.pi * j / n),
                                    math.sin(math.pi / 2 - 2 * math.pi * j / n)]) for j, k in enumerate(links)}
        last = not grow or radius >= radius_mm * CIRCLE_MAX_GROWTH - 1e-9
        numbers = _chord_numbers(con, at, radius, forced=last)
        radius = radius if numbers is not None else radius * CIRCLE_GROWTH
    items: list[Primitive] = [Circle((0.0, 0.0), radius, LAYER, "thin")]
    in_order = iter(numbers)  # one a Kennedy step, in the steps' order
    for s in con.steps:
        line = {"joint": "thick", "hinge": "thick", "slider": "thick", "kennedy": "hidden"}.get(s.how, "axis")
        items += _broken_at(Polyline([tuple(at[s.pair[0]]), tuple(at[s.pair[1]])], LAYER, line),
                            next(in_order) if s.how == "kennedy" else None)
    items += numbers
    for k, p in at.items():
        items.append(Circle(tuple(p), VERTEX_MM, LAYER, "thin", "white"))
        out = p / radius * (radius + 3.5)
        items.append(Text((out[0], out[1]), k, "labels", size_mm, "middle", "middle"))
    found = sum(1 for s in con.steps if s.how != "unreached")
    total = len(con.links) * (len(con.links) - 1) // 2
    items.append(Text((0.0, -radius - 10.0), _t("found", lang, found, total), "labels", 2.5, "middle"))
    items.append(Text((0.0, radius + 9.0), _t("circle", lang), "labels", size_mm, "middle"))
    return items


def _broken_at(chord: Polyline, number: Text | None) -> list[Polyline]:
    """`chord` broken where its own `number` stands on it (ESKD: a line is broken for the text
    written on it), :data:`NUMBER_CLEAR_MM` round the number's box; whole where it stands beside."""
    if number is None:
        return [chord]
    line = shapely.LineString(chord.points)
    hole = label_box(number).buffer(NUMBER_CLEAR_MM)
    if not line.intersects(hole):
        return [chord]
    rest = line.difference(hole)
    return [replace(chord, points=tuple(part.coords)) for part in getattr(rest, "geoms", [rest])
            if not part.is_empty and part.length > 0.2]


#: The links a circle diagram of the standard radius holds; one of more links starts larger in proportion.
CIRCLE_LINKS = 6
#: The radius of the circle diagram grows by this factor a step while its numbers do not fit…
CIRCLE_GROWTH = 1.15
#: …up to this multiple of the radius asked for; beyond it the numbers take their least crossed spots.
CIRCLE_MAX_GROWTH = 2.5
#: Radius of a link's mark on the circle diagram, mm.
VERTEX_MM = 1.2
#: The clearance around a chord's number that other chords, marks and numbers keep, mm.
NUMBER_CLEAR_MM = 0.3
#: How far beside its chord a number may sit (its centre from the chord), mm.
NUMBER_ASIDE_MM = 2.4
#: How much nearer its own chord than any other a number's centre is, at least, mm.
NUMBER_NEAREST_MM = 1.5
#: The gap between two chords' numbers, mm (beyond their clearance).
NUMBER_GAP_MM = 1.5


def _number_spots(a: np.ndarray, b: np.ndarray) -> list[np.ndarray]:
    """Where a chord a–b's number may go: along the chord (12…88 % of it) and beside it on
    either side, nearest the chord's middle first (mm)."""
    d = b - a
    side = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-9)
    spots = [a + t * d + off * side for t in np.linspace(0.12, 0.88, 39)
             for off in (0.0, NUMBER_ASIDE_MM, -NUMBER_ASIDE_MM)]
    mid = (a + b) / 2
    return sorted(spots, key=lambda p: float(np.hypot(*(p - mid))))


def _chord_numbers(con: Construction, at: dict, radius: float, *, forced: bool) -> list[Text] | None:
    """The numbers (order found) of the chords of the centres found by Kennedy lines, each at
    the first spot of `_number_spots` whose box no other chord, the circle, a link's mark or an
    earlier number comes within :data:`NUMBER_CLEAR_MM` of and whose nearest chord is its own
    (by :data:`NUMBER_NEAREST_MM` at least), clear of its own chord where it can be;
    None where one has no such spot, unless `forced`: then it takes the spot crossing fewest."""
    chords = [shapely.LineString([at[s.pair[0]], at[s.pair[1]]]) for s in con.steps]
    fixed = [shapely.Point(0.0, 0.0).buffer(radius, 64).exterior]
    fixed += [shapely.Point(*p).buffer(VERTEX_MM) for p in at.values()]
    out: list[Text] = []
    for j, s in enumerate(con.steps):
        if s.how != "kennedy":
            continue
        others = np.array(chords[:j] + chords[j + 1:], dtype=object)
        taken = np.array(fixed + [label_box(t).buffer(NUMBER_GAP_MM) for t in out], dtype=object)
        best, fewest = None, None
        for spot in _number_spots(at[s.pair[0]], at[s.pair[1]]):
            text = Text(tuple(spot), str(len(out) + 1), "labels", 2.5, "middle", "middle")
            box = label_box(text)
            grown, centre = box.buffer(NUMBER_CLEAR_MM), box.centroid
            hits = int(shapely.intersects(grown, others).sum()) + int(shapely.intersects(grown, taken).sum())
            nearest_other = float(shapely.distance(centre, others).min()) if len(others) else math.inf
            hits += int(chords[j].distance(centre) + NUMBER_NEAREST_MM > nearest_other)
            # a spot clear of its own chord too reads better than one the dashes strike through
            score = (hits, bool(grown.intersects(chords[j])))
            if fewest is None or score < fewest:
                best, fewest = text, score
            if score == (0, False):
                break
        if fewest[0] and not forced:
            return None
        out.append(best)
    return out


def centres_view(con: Construction, *, fine: Kinematics, number: int | None = None, lang: Language = "en",
                 sizes: MechanismSizes = MechanismSizes(), emphasis: int | None = None,
                 circle_mm: float | None = None) -> View:
    """The scheme at the construction's position and scale with every centre, the Kennedy lines
    used, notes for the centres at infinity, off the drawing or not reached, and the circle
    diagram to the right.

    Parameters
    ----------
    con : Construction
        The centres by construction at one position (`velplan.plans.centres.construct_centres`).
    fine : Kinematics
        The mechanism over a fine turn (`velplan.study.Study.turn`): the guides' extents.
    number : int, optional
        The position's number (1-based) written in the title.
    emphasis : int, optional
        The step (1-based) whose centre and Kennedy lines are drawn thick.
    circle_mm : float, optional
        The circle diagram's radius, mm; by default the least from :data:`CIRCLE_MM` up at
        which its numbers fit (`circle_diagram`).

    Returns
    -------
    View
        ``mu`` is μl (m/mm); ``meta["centres"]`` counts the centres drawn on the scheme,
        ``meta["position"]`` is the position's number (1…n of the construction's kinematics),
        ``meta["circle_mm"]`` the circle diagram's radius, ``meta["anchors"]`` each name written
        (a point's letter, a centre's "P₁₃", "P₀₆ → ∞") → its points in the view, mm.
    """
    kin = con.kin
    scheme = mechanism_view(kin.mechanism, kin=kin, fine=fine, mu_l=con.mu_l, n=len(kin),
                            thick=position_number(con.index), lang=lang, sizes=sizes, title=False, single=True)
    to_mm = lambda z: scheme.to_view([z.real, z.imag])  # noqa: E731 - metres → the scheme's mm
    m = max(MARGIN_MM, 0.75 * max(scheme.width_mm, scheme.height_mm))
    box = shapely.box(-m, -m, scheme.width_mm + m, scheme.height_mm + m)
    items = list(scheme.primitives)
    for s in con.steps:
        if s.how == "kennedy":
            items += _kennedy_lines(con, s, to_mm, box, "thick" if s.number == emphasis else "construction")
    marks, labels, notes, joints = _markers(con, to_mm, box, sizes.number_mm + 0.5, lang)
    items += marks
    points = {subscript(q): np.asarray(to_mm(complex(*kin.position(q)[con.index]))) for q in kin.point_index}
    points = {k: xy for k, xy in points.items() if np.all(np.isfinite(xy))}
    at_joint = {j: np.asarray(to_mm(complex(*kin.position(j)[con.index]))) for j in joints}
    items, anchors = _names_placed(items, labels, joints, at_joint, points, sizes.number_mm + 0.5)
    x0, y0, x1, y1 = bounds_of(items)
    diagram = circle_diagram(con, lang=lang, **({} if circle_mm is None else {"radius_mm": circle_mm, "grow": False}))
    radius = next(p.radius for p in diagram if isinstance(p, Circle))
    cx, cy = x1 + radius + 20.0, (y0 + y1) / 2
    items += [shift(p, cx, cy) for p in diagram]
    for k, note in enumerate(notes):
        items.append(Text((x0, y0 - 6.0 - 4.0 * k), note, "labels", 2.5))
    title = _t("title", lang) + (f", {_t('position', lang)} {number}" if number is not None else "")
    title += f", φ = {_number(round(float(kin.phi_deg[con.index]) % 360.0, 1) % 360.0, lang, 4)}°"
    top = max(y1, cy + radius + 12.0)
    items.append(Text((x0, top + 4.0 + 1.6 * sizes.title_mm), title, "labels", sizes.title_mm))
    items.append(Text((x0, top + 4.0), scale_text("μl", con.mu_l, "m/mm", lang), "labels", sizes.label_mm))
    view = make_view("centres", items, pad_mm=2.0, mu=con.mu_l, origin=tuple(scheme.origin),
                     meta={"centres": len(marks), "position": position_number(con.index), "circle_mm": radius})
    d = np.asarray(view.origin) - np.asarray(scheme.origin)  # content mm → the view's mm
    anchors = {k: tuple((float(x + d[0]), float(y + d[1])) for x, y in v) for k, v in anchors.items()}
    return replace(view, meta=MappingProxyType({**view.meta, "anchors": anchors}))


def _names_placed(items: list, labels: list, joints: dict, at_joint: dict, points: dict,
                  size: float) -> tuple[list, dict]:
    """`items` with every letter placed anew, the scheme's with the centres' names (`labels`:
    (text, its point)): none over another, none on a line; a joint that is a centre carries its
    name ("A (P₁₂)"; `joints`: joint → names, `at_joint`: joint → mm), a joint without a letter
    of its own its names alone. With each name written → its points (`points`: the scheme's
    letters → mm, and the centres'), mm."""
    anchors: dict[str, list] = {k: [xy] for k, xy in points.items()}
    for j, names in joints.items():
        for name in names:
            anchors.setdefault(name, []).append(at_joint[j])
    for t, at in labels:
        for name in t.text.split(", "):
            anchors.setdefault(name, []).append(at)
    letters = {subscript(j): j for j in joints}
    texts = [p for p in items if isinstance(p, Text)]
    items = [p for p in items if not isinstance(p, Text)]
    texts = [replace(t, text=f"{t.text} ({', '.join(joints.pop(letters[t.text]))})")
             if t.text in letters and letters[t.text] in joints else t for t in texts]
    labels = list(labels)
    for j, names in joints.items():  # a joint without a letter of its own
        at = at_joint[j]
        labels.append((Text((at[0] + 1.5, at[1] + 1.2), ", ".join(names), "labels", size), at))
    # the scheme's letters and the centres' names placed anew, each by its own point (the old
    # leaders dropped), clear of every line drawn and of the rest (link numbers, ω: by their links)
    items = [p for p in items if not (isinstance(p, Polyline) and p.layer == "labels" and p.line == "thin"
                                      and len(p.points) == 2
                                      and any(np.allclose(p.points[0], q) for q in points.values()))]
    obstacles = [shapely.LineString(p.points).buffer(0.4) for p in items if isinstance(p, Polyline)]
    obstacles += [shapely.LineString([p.start, p.end]).buffer(0.4) for p in items if isinstance(p, Arrow)]
    obstacles += [shapely.box(*p.bounds).buffer(0.3) for p in items if isinstance(p, Circle)]
    obstacles += [shapely.Polygon(p.points).buffer(0.4) for p in items if isinstance(p, Polygon)]  # blocks, ground
    own = [t for t in texts if t.text.split(" (")[0] in points]
    spots = [points[t.text.split(" (")[0]] for t in own] + [np.asarray(at, float) for _, at in labels]
    named = list(points.values()) + [np.asarray(at, float) for _, at in labels]
    others = [t for t in texts if t not in own]
    rest = step_aside(place_labels(others, obstacles, rings=8), obstacles)  # none left on a line
    items = _leaders_followed(items, others, rest)
    # the names at infinity first: each has one place, the end of its direction line
    texts_of = [*own, *(t for t, _ in labels)]
    order = sorted(range(len(texts_of)), key=lambda k: not texts_of[k].text.endswith("∞"))
    placed, leaders = place_letters([texts_of[k] for k in order], [spots[k] for k in order], named, obstacles,
                                    taken=[label_box(t).buffer(0.4) for t in rest], near_mm=NEAR_MM,
                                    leader_gaps=(*LEADER_GAPS_MM, *FAR_LEADER_GAPS_MM))
    items += [*rest, *placed, *leaders]
    return _broken_under_texts(items), {k: [tuple(map(float, xy)) for xy in v] for k, v in anchors.items() if v}


def _broken_under_texts(items: list) -> list:
    """`items` with each thin construction line (a Kennedy line) broken where a text had to
    stand on it (a link's number in a web of lines; ESKD: a line is broken for a text), 0.4 mm
    round the text's box: the parts outside, in the line's place."""
    holes = [label_box(t).buffer(0.4) for t in items if isinstance(t, Text)]
    if not holes:
        return items
    tree = shapely.STRtree(holes)
    out: list = []
    for p in items:
        hit = (tree.query(line := shapely.LineString(p.points), predicate="intersects")
               if isinstance(p, Polyline) and p.layer == LAYER and p.line == "construction" else ())
        if not len(hit):
            out.append(p)
            continue
        rest = line.difference(shapely.union_all([holes[j] for j in hit]))
        out += [replace(p, points=tuple(part.coords)) for part in getattr(rest, "geoms", [rest])
                if not part.is_empty and part.length > 0.2]
    return out


def _leaders_followed(items: list, texts: list, moved: list) -> list:
    """`items` with the thin leader of each of `texts` (the scheme's own: from its point to the
    text's box) drawn to where the text was moved (`moved`, in the same order)."""
    boxes = [(label_box(t).buffer(0.6), label_box(m).buffer(0.4)) for t, m in zip(texts, moved) if t != m]
    out = []
    for p in items:
        if isinstance(p, Polyline) and p.layer == "labels" and p.line == "thin" and len(p.points) == 2:
            end = shapely.Point(p.points[1])
            to = next((new for old, new in boxes if old.contains(end)), None)
            if to is not None:
                near = shapely.shortest_line(to, shapely.Point(p.points[0])).coords[0]
                p = replace(p, points=(tuple(p.points[0]), (near[0], near[1])))
        out.append(p)
    return out


def centre_step_figures(con: Construction, *, fine: Kinematics, number: int, lang: Language = "en",
                        margin_mm: float = 10.0, sentence_mm: float = 26.0) -> list:
    """One figure per step of the construction (`velplan.views.steps.StepFigure`, kind "c"):
    the centres found so far, the step's centre and Kennedy lines drawn thick, the circle
    diagram as it stands, and the step's sentence under the drawing; every page the same size
    with the scheme in the same place."""
    from dataclasses import replace

    from velplan.render.i18n import label
    from velplan.render.layout import fit_text
    from velplan.render.scene import Scene
    from velplan.views.steps import StepFigure, readable

    full = centres_view(con, fine=fine, number=number, lang=lang)
    width = max(297.0, full.width_mm + 2 * margin_mm)
    height = max(210.0, full.height_mm + 2 * margin_mm + sentence_mm)
    sentences = con.describe(lang)
    figures = []
    for k in range(1, len(con.steps) + 1):
        done = con.steps[:k]
        part = replace(con, steps=done, centres={s.pair: s for s in done if s.how != "unreached"})
        view = centres_view(part, fine=fine, number=number, lang=lang, emphasis=k, circle_mm=full.meta["circle_mm"])
        x = margin_mm + full.origin[0] - view.origin[0]
        y = height - margin_mm - full.height_mm + full.origin[1] - view.origin[1]
        items = list(view.at(x, y).primitives)
        text = f"{label('step', lang)} {k}/{len(con.steps)}. {readable(sentences[k - 1])}"
        items += fit_text(text, (margin_mm, margin_mm, width - margin_mm, margin_mm + sentence_mm - 4.0),
                          layer="labels", size_mm=5.0, anchor="start")
        items.append(Polygon([(0, 0), (width, 0), (width, height), (0, height)], "frame", "thin"))
        figures.append(StepFigure(k, "c", sentences[k - 1], Scene(tuple(items), width, height)))
    return figures


def centre_marks(con: Construction, placed, *, tag: str = "", size_mm: float = 2.5,
                 top_mm: float = 16.0) -> list[Primitive]:
    """Marks of the centres found by Kennedy lines (the joints are drawn already) that fall on a
    placed scheme (`velplan.views.base.PlacedView` of `mechanism_view` at the construction's
    position): a dot and the centre's name with ``tag`` (e.g. the position number), on the
    layer "centres", in sheet mm; none within ``top_mm`` of the top (the scheme's title)."""
    x0, y0, x1, y1 = placed.bounds
    out: list[Primitive] = []
    for s in con.steps:
        if s.how != "kennedy" or s.infinite:
            continue
        x, y = placed.to_sheet([s.point.real, s.point.imag])
        if x0 + 2.0 <= x <= x1 - 12.0 and y0 + 2.0 <= y <= y1 - top_mm:
            out.append(Circle((float(x), float(y)), 0.7, LAYER, "thin", "solid"))
            out.append(Text((float(x) + 1.0, float(y) + 0.8), _name(s.pair) + tag, LAYER, size_mm))
    return out
