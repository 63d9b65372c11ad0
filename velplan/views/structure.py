"""The structural analysis drawn as a course draws it: the initial mechanism (the frame and the
crank, class I) and each Assur group drawn apart, in solving order, at one scale; the outer
pairs of each group marked with a dashed ring; its class, order and kind written under it; the
mobility and the formula of structure under the title.

The view takes the mechanism as drawn (`velplan.mechanism.drawn_write.drawn_tables`: every joint
with its links, each sliding pair with its guide's direction), so it never solves.
"""

from __future__ import annotations

import math
from typing import Mapping, NamedTuple, Sequence

import numpy as np
import shapely

from velplan.mechanism.model import GROUND, Mechanism
from velplan.mechanism.structure import structure
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Circle, Polygon, Polyline, Scene, Text
from velplan.render.shapes import DESCENDER_DEPTH, text_extent
from velplan.render.symbols import JOINT_RADIUS_MM, fixed_pivot, link, revolute_joint, slider_block, straight_guide
from velplan.notation import subscript
from velplan.views.letters import step_aside

PANEL_MM = 70.0
"""Width the widest panel is drawn at, mm."""
GAP_MM = 18.0
"""Gap between the panels of a figure drawn at `PANEL_MM`, mm (in proportion at other widths)."""
MARGIN_MM = 12.0
TEXT_MM = 3.5
"""Height of its letters, mm."""
TITLE_MM = 5.0
"""Height of its heading, mm."""
BLOCK_MM = (10.0, 6.0)
RING_MM = 3.2
"""Radius of the dashed ring that marks an outer pair, mm."""
_LETTERS = {"ru": {"R": "В", "P": "П"}, "uk": {"R": "О", "P": "П"}}
_ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV"}


def kind_in(kind: str, lang: str) -> str:
    """A group's kind in the letters of ``lang`` (ВПВ for RPR in Russian)."""
    if kind == "triad":
        return {"ru": "триада", "uk": "тріада", "zh": "三杆组"}.get(lang, "triad")
    return "".join(_LETTERS.get(lang, {}).get(c, c) for c in kind)


class _Panel:
    """One part of the figure: its links, and what it draws in metres, before placing."""

    def __init__(self, links: set[str], known: set[str], caption: tuple[str, ...], text_mm: float = TEXT_MM):
        self.links, self.known, self.caption, self.text_mm = links, known, caption, text_mm
        self.vertices: dict[str, list[np.ndarray]] = {k: [] for k in sorted(links)}  # a fixed order
        self.joints: list[tuple[str, np.ndarray, bool]] = []  # name, at, outer?
        self.blocks: list[tuple[np.ndarray, float, bool]] = []  # at, angle, outer?
        self.marks: list[tuple[str, np.ndarray]] = []  # a named point of a link, not a joint
        self.guides: list[tuple[np.ndarray, float, bool]] = []  # at, angle, on the frame?
        self.pivots: list[np.ndarray] = []
        self.centre = 0.0  # mm, where its captions are centred

    def points(self) -> np.ndarray:
        pts = [v for vs in self.vertices.values() for v in vs] + [p for _, p, _ in self.joints]
        pts += [p for p, _, _ in self.blocks] + self.pivots
        return np.array(pts) if pts else np.zeros((1, 2))


def _panels(mech: Mechanism, joints: Sequence[Mapping], lang: str, text_mm: float) -> list[_Panel]:
    st = structure(mech)
    first = _Panel({mech.crank.link}, {GROUND}, (label("initial_mechanism", lang), f"I(0, {mech.crank.link})"),
                   text_mm)
    panels, known = [first], {GROUND, mech.crank.link}
    for (name, kind, cls, order, links) in st.groups:
        caption = (label("group_class", lang).format(cls=_ROMAN.get(cls, str(cls)), order=order),
                   f"{kind_in(kind, lang)}: {', '.join(links)}")
        panels.append(_Panel(set(links), set(known), caption, text_mm))
        known |= set(links)
    for panel in panels:
        for j in joints:
            _add_joint(panel, j)
    return panels


def _add_joint(panel: _Panel, j: Mapping) -> None:
    """What joint ``j`` adds to ``panel``: points of its links, a joint, a block, a guide."""
    at, kind = np.array(j["at"], float), j.get("kind", "R")
    links = [str(k) for k in j["links"]]
    slide = None
    if kind == "R":
        hinge = links
    elif kind == "RP":  # the pins turn in a block that slides on links[0]
        hinge, slide = links[1:] + [str(j["block"])], (links[0], str(j["block"]))
    else:  # P: the point is the slider's, which slides on links[0]
        hinge, slide = [links[1]], (links[0], links[1])
    on = [k for k in hinge if k in panel.links]
    for k in on:
        panel.vertices[k].append(at)
    if slide is not None:
        slot, slider = slide
        if slot in panel.links:
            panel.vertices[slot].append(at)
        if slider in panel.links:
            outer = slot not in panel.links
            panel.blocks.append((at, float(j["angle_deg"]), outer))
            if outer:
                panel.guides.append((at, float(j["angle_deg"]), slot == GROUND))
    if not on:
        return
    initial = panel.known == {GROUND}
    if initial and GROUND in hinge:
        panel.pivots.append(at)
    if len(hinge) >= 2:
        outer = not initial and any(k in panel.known for k in hinge)
        panel.joints.append((subscript(str(j["name"])), at, outer))
    elif kind == "R":
        panel.marks.append((subscript(str(j["name"])), at))


def structure_view(mech: Mechanism, joints: Sequence[Mapping], *, lang: str = "en", title: bool = True,
                   panel_mm: float = PANEL_MM, text_mm: float = TEXT_MM, title_mm: float = TITLE_MM) -> Scene:
    """The figure of the structural analysis (mm, y up) from the drawn joints of ``mech``;
    ``title``: with its heading, W and the formula of structure above it; ``panel_mm``: the
    width of its widest panel, mm; ``text_mm``, ``title_mm``: its letters' and heading's
    height, mm."""
    return figure_layout(mech, joints, lang=lang, title=title, panel_mm=panel_mm, text_mm=text_mm,
                         title_mm=title_mm).scene()


class FigureLayout(NamedTuple):
    """`structure_view`'s figure before its panels are drawn in place: each panel's map from
    metres to the figure's mm (``places``), and the texts and the legend round them, placed."""

    panels: list
    places: list
    texts: list  # the captions, the heading and the formula, to be lifted with the drawings
    lift: float  # mm, the whole figure moved up so that its lowest text stands on the margin
    legend: list  # the outer pairs' key, lifted
    height_mm: float

    def scene(self) -> Scene:
        """The figure: every panel drawn at its place, then the texts and the legend."""
        items = [p for panel, place in zip(self.panels, self.places) for p in _draw(panel, place)] + self.texts
        items = [_moved(p, self.lift) for p in items] + self.legend
        return Scene(tuple(items), width_mm=max(_bounds(items)[2] + MARGIN_MM, 120.0), height_mm=self.height_mm)

    def text_extent(self) -> tuple[float, float]:
        """Width and height (mm) of the box of the texts and the legend alone: a lower bound of
        the figure's box, known before its panels are drawn in place."""
        x0, y0, x1, y1 = _bounds([_moved(p, self.lift) for p in self.texts] + self.legend)
        return x1 - x0, y1 - y0


def figure_layout(mech: Mechanism, joints: Sequence[Mapping], *, lang: str = "en", title: bool = True,
                  panel_mm: float = PANEL_MM, text_mm: float = TEXT_MM, title_mm: float = TITLE_MM) -> FigureLayout:
    """`structure_view`'s layout (the same arguments): each panel drawn once where it is first
    put, for its box; the panels side by side by their boxes, the texts and legend round them."""
    panels = _panels(mech, joints, lang, text_mm)
    spans = [np.ptp(p.points(), axis=0) for p in panels]
    mu = _scale(spans, panel_mm)
    gap, line = GAP_MM * panel_mm / PANEL_MM, text_mm * 1.6
    heights = [float(s[1]) * mu for s in spans]
    tallest = max(heights)
    base = MARGIN_MM + 4 * line + 8.0
    low, high = base, base
    sized = []  # per panel: its shift, drawn box, half its drawing's and its captions' widths
    for panel, span in zip(panels, spans):
        lo = panel.points().min(axis=0)
        shift = np.array([0.0, base + (tallest - float(span[1]) * mu) / 2]) - lo * mu
        box = _bounds(_draw(panel, lambda p, shift=shift: np.asarray(p, float) * mu + shift))
        captions = max(text_extent(c, text_mm)[0] for c in panel.caption)
        sized.append((shift, box, (box[2] - box[0]) / 2, captions / 2))
    places = []
    for i, (panel, (shift, box, half, caption)) in enumerate(zip(panels, sized)):
        if i:  # drawings `gap` apart, captions two letters apart, whichever needs more
            before = sized[i - 1]
            x += max(before[2] + half + gap, before[3] + caption + 2 * text_mm)
        else:
            x = MARGIN_MM + max(half, caption)
        shift = shift + (x - (box[0] + box[2]) / 2, 0.0)
        places.append(lambda p, shift=shift: np.asarray(p, float) * mu + shift)
        panel.centre, low, high = x, min(low, box[1]), max(high, box[3])
        right = x + max(half, caption)
    x = right + gap
    below = 1.7 * text_mm  # from the lowest drawing to the first caption's middle
    texts = [Text((panel.centre, low - below - k * line), text, "labels", text_mm, "middle", "middle")
             for panel in panels for k, text in enumerate(panel.caption)]
    width = x - gap + MARGIN_MM
    st = structure(mech)
    top = high + 1.7 * text_mm
    ring = RING_MM * text_mm / TEXT_MM
    key = label("outer_pairs", lang)
    key_w = 2 * ring + 0.6 * text_mm + text_extent(key, text_mm)[0]
    lowest = low - below - (len(panels[0].caption) - 1) * line - 0.7 * text_mm  # the captions' foot
    legend = np.array([MARGIN_MM + ring, lowest - 0.6 * line - ring])  # under the captions
    if title:
        heading = label("structural_analysis", lang)
        formula = (f"{st.formula()};  {label('structure_formula', lang)}: "
                   f"{st.structure_formula(mech.crank.link)}")
        texts += [Text((MARGIN_MM, top + 1.3 * title_mm), heading, "labels", title_mm),
                  Text((MARGIN_MM, top), formula, "labels", text_mm)]
        right = max(width - MARGIN_MM, MARGIN_MM + text_extent(formula, text_mm)[0]) - text_mm  # slack for wide fonts
        if MARGIN_MM + text_extent(heading, title_mm)[0] + 2 * text_mm + key_w <= right:
            legend = np.array([right - key_w + ring, top + 1.3 * title_mm + title_mm / 2])  # beside the heading
        top += 1.3 * title_mm + title_mm
    shift_up = MARGIN_MM - min(lowest, legend[1] - ring)
    legend = legend + (0.0, shift_up)
    return FigureLayout(panels, places, texts, shift_up,
                        [Circle(legend, ring, "labels", "hidden"),
                         Text(legend + (ring + 0.6 * text_mm, 0.0), key, "labels", text_mm, "start", "middle")],
                        top + shift_up + MARGIN_MM)


def least_extent(mech: Mechanism, joints: Sequence[Mapping], *, lang: str = "en", title: bool = True,
                 panel_mm: float = PANEL_MM, text_mm: float = TEXT_MM,
                 title_mm: float = TITLE_MM) -> tuple[float, float]:
    """A lower bound of the width and height (mm) of the box of everything `structure_view`
    draws with these arguments, found without drawing: the panels side by side at least their
    points' spans and `GAP_MM` apart, their captions two letters apart, the heading and the
    formula as wide as their text; the tallest panel's points, the caption lines under it and
    the heading's lines above it. (A sheet skips a size whose bound fits no free space.)"""
    panels = _panels(mech, joints, lang, text_mm)
    spans = [np.ptp(p.points(), axis=0) for p in panels]
    mu = _scale(spans, panel_mm)
    gap, line = GAP_MM * panel_mm / PANEL_MM, text_mm * 1.6
    drawings = sum(float(s[0]) * mu for s in spans) + gap * (len(panels) - 1)
    captions = sum(max(text_extent(c, text_mm)[0] for c in p.caption) for p in panels)
    width = max(drawings, captions + 2 * text_mm * (len(panels) - 1))
    height = (_least_drawing_height(panels, spans, mu) + (2.2 + DESCENDER_DEPTH) * text_mm  # to the captions' foot
              + max(len(p.caption) - 1 for p in panels) * line)
    if title:
        st = structure(mech)
        formula = (f"{st.formula()};  {label('structure_formula', lang)}: "
                   f"{st.structure_formula(mech.crank.link)}")
        width = max(width, text_extent(formula, text_mm)[0],
                    text_extent(label("structural_analysis", lang), title_mm)[0])
        height += 1.7 * text_mm + 2.3 * title_mm  # to the heading's top
    return width, height


def _least_drawing_height(panels: list[_Panel], spans, mu: float) -> float:
    """A lower bound of the height (mm) from the lowest to the highest drawn box of the panels,
    each centred on the tallest one's points as `structure_view` draws them: their points,
    and round them what `_draw` surely draws — a joint's circle and an outer pair's ring, a
    block's corners and an outer block's ring, a guide's ends."""
    tallest = max(float(s[1]) * mu for s in spans)
    top, bottom = -math.inf, math.inf
    for panel, span in zip(panels, spans):
        pts = panel.points()
        shift = (tallest - float(span[1]) * mu) / 2 - float(pts[:, 1].min()) * mu  # from the common base
        reach = [(float(y), 0.0) for y in pts[:, 1]]
        reach += [(float(at[1]), RING_MM if outer else JOINT_RADIUS_MM) for _, at, outer in panel.joints]
        for at, angle, outer in panel.blocks:
            a = math.radians(angle)
            corner = (BLOCK_MM[0] * abs(math.sin(a)) + BLOCK_MM[1] * abs(math.cos(a))) / 2
            reach.append((float(at[1]), max(corner, 0.75 * BLOCK_MM[0]) if outer else corner))
        reach += [(float(at[1]), BLOCK_MM[0] * 1.8 * abs(math.sin(math.radians(angle))))
                  for at, angle, _ in panel.guides]
        for y, r in reach:
            r = max(r - 1e-9, 0.0)  # round-off: never above what is drawn
            top, bottom = max(top, y * mu + shift + r), min(bottom, y * mu + shift - r)
    return max(top - bottom, tallest)


def _scale(spans, panel_mm: float) -> float:
    """mm per m at which the widest of the panels' ``spans`` (m) is ``panel_mm`` mm."""
    return panel_mm / (max(max(float(s[0]), float(s[1])) for s in spans) or 1.0)


def figure_scale(mech: Mechanism, joints: Sequence[Mapping], panel_mm: float = PANEL_MM) -> float:
    """mm per m of the figure `structure_view` draws with its widest panel ``panel_mm`` wide."""
    return _scale([np.ptp(p.points(), axis=0) for p in _panels(mech, joints, "en", TEXT_MM)], panel_mm)


def _draw(panel: _Panel, place) -> list:
    out: list = []
    for at, angle, frame in panel.guides:
        u = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))]) * BLOCK_MM[0] * 1.8
        c = place(at)
        if frame:
            out += straight_guide(c - u, c + u, side="right")
        else:
            out.append(Polyline([c - u, c + u], "mechanism", "thick"))
    shapes = {k: [place(v) for v in verts] for k, verts in panel.vertices.items()}
    for pts in shapes.values():
        out += _link_shape(pts)
    for at, angle, outer in panel.blocks:
        out += slider_block(place(at), angle, length_mm=BLOCK_MM[0], width_mm=BLOCK_MM[1])
        if outer:
            out.append(Circle(place(at), 0.75 * BLOCK_MM[0], "labels", "hidden"))
    sides = {}  # a pivot's side for its letter: across its support, away from its links
    for at in panel.pivots:
        c = place(at)
        away = _away(c, shapes)
        out += fixed_pivot(c, direction_deg=math.degrees(math.atan2(away[1], away[0])))
        across = np.array([-away[1], away[0]])
        sides[tuple(c)] = across if across[0] >= 0 else -across
    blocks = {tuple(place(at)): (angle, outer) for at, angle, outer in panel.blocks}
    letters = []  # (joint, name, the side it is best written on), placed last, clear of the rest
    for name, at, outer in panel.joints:
        c = place(at)
        out += revolute_joint(c)
        if outer:
            out.append(Circle(c, RING_MM, "labels", "hidden"))
        if tuple(c) in blocks:  # beside the block, across its guide
            angle, ringed = blocks[tuple(c)]
            left = np.array([-math.sin(math.radians(angle)), math.cos(math.radians(angle))])
            reach = (0.75 * BLOCK_MM[0] if ringed else BLOCK_MM[1] / 2) + 3.5
            out.append(Text(c + left * reach, name, "labels", panel.text_mm, "middle", "middle"))
        else:
            letters.append((c, name, sides.get(tuple(c), _away(c, shapes))))
    letters += [(place(at), name, _away(place(at), shapes)) for name, at in panel.marks]
    centre = np.mean([p for pts in shapes.values() for p in pts], axis=0)
    numbers = [_link_number(k, pts, centre, panel, place) for k, pts in shapes.items() if pts and k != GROUND]
    # a number a line crosses (another link's outline past a block) steps aside, off the ink
    ink = [g.buffer(0.3) for g in map(_outline, out) if g is not None]
    out += step_aside(numbers, ink, taken=[label_box(t).buffer(0.4) for t in out if isinstance(t, Text)])
    return out + _clear_letters(out, letters, panel.text_mm)


def _clear_letters(drawn: list, letters: list, size_mm: float) -> list[Text]:
    """Each joint's letter on its best side, or else turned by 45° steps to the first side
    where it crosses no line, ring or letter already drawn (its best side when none is)."""
    lines = [_outline(p) for p in drawn if not isinstance(p, Text)]
    ink = shapely.union_all([g for g in lines if g is not None])
    boxes = [label_box(t) for t in drawn if isinstance(t, Text)]
    out: list[Text] = []
    for c, name, away in letters:
        choice = None
        for turn in (0, 45, -45, 90, -90, 135, -135, 180):
            a = math.radians(turn)
            side = np.array([away[0] * math.cos(a) - away[1] * math.sin(a), away[0] * math.sin(a) + away[1] * math.cos(a)])
            text = _label(c, name, side, size_mm)
            box = label_box(text)
            if not box.intersects(ink) and not any(box.intersects(b) for b in boxes):
                choice = text
                break
        choice = choice or _label(c, name, away, size_mm)
        out.append(choice)
        boxes.append(label_box(choice))
    return out


def _outline(p):
    """The ink of a drawn primitive as a shapely line (a circle by its rim), or None."""
    if isinstance(p, Circle):
        return shapely.Point(p.centre).buffer(p.radius, quad_segs=8).boundary
    if isinstance(p, Polygon):
        return shapely.LinearRing(p.points)
    if isinstance(p, Polyline):
        return shapely.LineString(p.points)
    return None


def _bounds(items: list) -> tuple[float, float, float, float]:
    boxes = np.array([p.bounds for p in items])
    return (float(boxes[:, 0].min()), float(boxes[:, 1].min()), float(boxes[:, 2].max()), float(boxes[:, 3].max()))


def _moved(p, dy: float):
    """A primitive moved up by ``dy`` mm."""
    from dataclasses import replace

    if isinstance(p, Text):
        return replace(p, position=(p.position[0], p.position[1] + dy))
    if isinstance(p, Circle):
        return replace(p, centre=(p.centre[0], p.centre[1] + dy))
    return replace(p, points=[(x, y + dy) for x, y in p.points])


def _away(c: np.ndarray, shapes: Mapping[str, list], pivot=None) -> np.ndarray:
    """The unit direction from ``c`` away from the links drawn through it."""
    total = np.zeros(2)
    for pts in shapes.values():
        if any(np.hypot(*(p - c)) < 1e-6 for p in pts):
            for p in pts:
                d = p - c
                n = float(np.hypot(*d))
                if n > 1e-6:
                    total -= d / n
    n = float(np.hypot(*total))
    return total / n if n > 1e-9 else np.array([0.7071, 0.7071])


def _label(c: np.ndarray, name: str, away: np.ndarray, size_mm: float) -> Text:
    """A joint's letter ``size_mm`` high beside it, out along ``away``."""
    at = c + away * (RING_MM + 2.0)
    anchor = "start" if away[0] > 0.3 else "end" if away[0] < -0.3 else "middle"
    return Text(at, name, "labels", size_mm, anchor, "middle")


def _link_number(k: str, pts: list, centre: np.ndarray, panel: _Panel, place) -> Text:
    """The link's number beside its longest piece, on the side away from the panel's middle."""
    if len(pts) == 1:  # a block: its number across the guide from its joint's letter
        for at, angle, ringed in panel.blocks:
            if np.hypot(*(place(at) - pts[0])) < 1e-6:
                left = np.array([-math.sin(math.radians(angle)), math.cos(math.radians(angle))])
                reach = (0.75 * BLOCK_MM[0] if ringed else BLOCK_MM[1] / 2) + 3.5
                return Text(pts[0] - left * reach, k, "labels", panel.text_mm, "middle", "middle")
        return Text(pts[0] + (0.0, -3.0), k, "labels", panel.text_mm, "middle", "top")
    a, b = max(((p, q) for i, p in enumerate(pts) for q in pts[i + 1:]), key=lambda pq: np.hypot(*(pq[0] - pq[1])))
    mid, d = (a + b) / 2, b - a
    normal = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-9)
    if len(pts) >= 3 and not _collinear(pts):  # a plate: its number inside
        return Text(np.mean(pts, axis=0), k, "labels", panel.text_mm, "middle", "middle")
    for at, angle, frame in panel.guides:  # a link along a fixed guide: its number off the hatching
        g = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        if frame and abs(g[0] * d[1] - g[1] * d[0]) < 0.05 * float(np.hypot(*d)):
            ends = [p + (q - p) / max(float(np.hypot(*(q - p))), 1e-9) * _ring_at(p, panel, place)
                    for p, q in ((a, b), (b, a))]  # the part clear of a block's ring
            return Text((ends[0] + ends[1]) / 2 + np.array([-g[1], g[0]]) * (0.9 * panel.text_mm), k,
                        "labels", panel.text_mm, "middle", "middle")
    if normal @ (mid - centre) < 0:
        normal = -normal
    return Text(mid + normal * (0.9 * panel.text_mm), k, "labels", panel.text_mm, "middle", "middle")


def _ring_at(c: np.ndarray, panel: _Panel, place) -> float:
    """Radius (mm) of the ring drawn round a block at ``c``, 0 where there is none."""
    return next((0.75 * BLOCK_MM[0] for at, _, ringed in panel.blocks
                 if ringed and np.hypot(*(place(at) - c)) < 1e-6), 0.0)


def _collinear(pts: list) -> bool:
    hull = shapely.MultiPoint(pts).convex_hull
    return hull.geom_type != "Polygon" or hull.area < 0.02 * hull.length ** 2 / 4


def _link_shape(pts: list[np.ndarray]) -> list:
    """A link through its points: a line when they are (nearly) on one, else its outline."""
    unique = []
    for p in pts:
        if all(np.hypot(*(p - q)) > 1e-6 for q in unique):
            unique.append(p)
    if len(unique) < 2:
        return []
    if len(unique) == 2:
        return list(link(*unique, trim_a_mm=JOINT_RADIUS_MM, trim_b_mm=JOINT_RADIUS_MM))
    if _collinear(unique):
        arr = np.array(unique)
        d = arr - arr.mean(axis=0)
        axis = np.linalg.svd(d)[2][0]
        t = d @ axis
        return list(link(arr[np.argmin(t)], arr[np.argmax(t)]))
    ring = np.array(shapely.MultiPoint(unique).convex_hull.exterior.coords)[:-1]
    return [Polygon(ring, "mechanism", "thick", "white")]
