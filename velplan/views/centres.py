"""The instant centres drawn: the scheme in one position with every centre it reaches on the
drawing, the Kennedy lines each centre was found with, and the circle diagram (links on a
circle, a chord per centre: thick for the obvious ones, thin for those found by Kennedy
lines, dashed for those not reached). Pure functions from a `Construction` and a scale to
shapes.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from velplan.analysis.numbering import position_number
from velplan.analysis.solver import Kinematics
from velplan.options import Language
from velplan.plans.centres import Construction, CentreStep, centre_name
from velplan.render.scene import Circle, Polyline, Primitive, Text
from velplan.views.base import View, bounds_of, digits_down, make_view, number, place_labels, scale_text, shift
from velplan.views.mechanism import MechanismSizes, mechanism_view

MARGIN_MM = 40.0
"""How far beyond the scheme (mm, at least; ¾ of its size when larger) centres and Kennedy lines
are still drawn."""
CIRCLE_MM = 28.0
"""Radius of the circle diagram, mm."""
LAYER = "centres"

_LABELS = {
    "title": {"en": "Instant centres of velocity", "ru": "Мгновенные центры скоростей",
              "uk": "Миттєві центри швидкостей", "zh": "速度瞬心"},
    "position": {"en": "position", "ru": "положение", "uk": "положення", "zh": "位置"},
    "circle": {"en": "Circle diagram", "ru": "Круговая диаграмма", "uk": "Кругова діаграма", "zh": "瞬心多边形"},
    "found": {"en": "found {0} of {1}", "ru": "найдено {0} из {1}", "uk": "знайдено {0} з {1}",
              "zh": "已求得 {0}/{1}"},
    "off": {"en": "off the drawing", "ru": "вне чертежа", "uk": "поза кресленням", "zh": "在图外"},
    "infinity": {"en": "at infinity ⊥ {0}°", "ru": "в бесконечности ⊥ {0}°", "uk": "у нескінченності ⊥ {0}°",
                 "zh": "在无穷远处 ⊥ {0}°"},
    "unreached": {"en": "not reached", "ru": "не найден", "uk": "не знайдено", "zh": "未求得"},
}


def _t(key: str, lang: Language, *args) -> str:
    return _LABELS[key][lang].format(*args)


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


def _markers(con: Construction, to_mm, box, size: float, lang: Language) -> tuple[list, list, list[str]]:
    """Centre marks with their names, and notes for centres at infinity or off the drawing."""
    items, labels, notes = [], [], []
    for s in con.steps:
        name = _name(s.pair)
        if s.how == "unreached":
            notes.append(f"{name}: {_t('unreached', lang)}")
        elif s.infinite:
            deg = round(math.degrees(math.atan2(s.direction.imag, s.direction.real)), 6) + 0.0  # no 1e-15°
            notes.append(f"{name}: {_t('infinity', lang, number(deg, lang, 4))}")
        elif box.contains(shapely.Point(*to_mm(s.point))):
            at = to_mm(s.point)
            items.append(Circle(tuple(at), 0.9 if s.how == "kennedy" else 1.6, LAYER,
                                "thin", "solid" if s.how == "kennedy" else None))
            labels.append(Text((at[0] + 1.5, at[1] + 1.2), name, "labels", size))
        else:
            xy = f"({number(s.point.real, lang, 4)}; {number(s.point.imag, lang, 4)}) m"
            notes.append(f"{name} = {xy}: {_t('off', lang)}")
    return items, labels, notes


def circle_diagram(con: Construction, *, lang: Language = "en", radius_mm: float = CIRCLE_MM,
                   size_mm: float = 3.5) -> list[Primitive]:
    """The circle diagram around (0, 0) mm: links on a circle, a chord per centre (thick:
    obvious, thin: by Kennedy lines, dashed: not reached), and its title."""
    links = con.links
    n = len(links)
    at = {k: radius_mm * np.array([math.cos(math.pi / 2 - 2 * math.pi * j / n),
                                   math.sin(math.pi / 2 - 2 * math.pi * j / n)]) for j, k in enumerate(links)}
    items: list[Primitive] = [Circle((0.0, 0.0), radius_mm, LAYER, "axis")]
    for s in con.steps:
        line = {"joint": "thick", "hinge": "thick", "slider": "thick", "kennedy": "thin"}.get(s.how, "hidden")
        items.append(Polyline([tuple(at[s.pair[0]]), tuple(at[s.pair[1]])], LAYER, line))
    for k, p in at.items():
        items.append(Circle(tuple(p), 1.2, LAYER, "thin", "white"))
        out = p / radius_mm * (radius_mm + 3.5)
        items.append(Text((out[0], out[1]), k, "labels", size_mm, "middle", "middle"))
    found = sum(1 for s in con.steps if s.how != "unreached")
    total = len(con.links) * (len(con.links) - 1) // 2
    items.append(Text((0.0, -radius_mm - 10.0), _t("found", lang, found, total), "labels", 2.5, "middle"))
    items.append(Text((0.0, radius_mm + 9.0), _t("circle", lang), "labels", size_mm, "middle"))
    return items


def centres_view(con: Construction, *, fine: Kinematics, number: int | None = None, lang: Language = "en",
                 sizes: MechanismSizes = MechanismSizes(), emphasis: int | None = None) -> View:
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

    Returns
    -------
    View
        ``mu`` is μl (m/mm); ``meta["centres"]`` counts the centres drawn on the scheme,
        ``meta["position"]`` is the position's number (1…n of the construction's kinematics).
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
    marks, labels, notes = _markers(con, to_mm, box, sizes.number_mm + 0.5, lang)
    items += marks
    obstacles = [shapely.LineString(p.points).buffer(0.4) for p in items if isinstance(p, Polyline)]
    obstacles += [shapely.box(*p.bounds).buffer(0.3) for p in items if isinstance(p, (Text, Circle))]
    items += place_labels(labels, obstacles, rings=6)
    x0, y0, x1, y1 = bounds_of(items)
    diagram = circle_diagram(con, lang=lang)
    cx, cy = x1 + CIRCLE_MM + 20.0, (y0 + y1) / 2
    items += [shift(p, cx, cy) for p in diagram]
    for k, note in enumerate(notes):
        items.append(Text((x0, y0 - 6.0 - 4.0 * k), note, "labels", 2.5))
    title = _t("title", lang) + (f", {_t('position', lang)} {number}" if number is not None else "")
    title += f", φ = {kin.phi_deg[con.index]:.1f}°"
    top = max(y1, cy + CIRCLE_MM + 12.0)
    items.append(Text((x0, top + 4.0 + 1.6 * sizes.title_mm), title, "labels", sizes.title_mm))
    items.append(Text((x0, top + 4.0), scale_text("μl", con.mu_l, "m/mm", lang), "labels", sizes.label_mm))
    return make_view("centres", items, pad_mm=2.0, mu=con.mu_l, origin=tuple(scheme.origin),
                     meta={"centres": len(marks), "position": position_number(con.index)})


def centre_step_figures(con: Construction, *, fine: Kinematics, number: int, lang: Language = "en",
                        margin_mm: float = 10.0, sentence_mm: float = 26.0) -> list:
    """One figure per step of the construction (`velplan.views.steps.StepFigure`, kind "c"):
    the centres found so far, the step's centre and Kennedy lines drawn thick, the circle
    diagram as it stands, and the step's sentence under the drawing; every page the same size
    with the scheme in the same place."""
    from dataclasses import replace

    from velplan.render.i18n import label
    from velplan.render.layout import fit_text
    from velplan.render.scene import Polygon, Scene
    from velplan.views.steps import StepFigure, readable

    full = centres_view(con, fine=fine, number=number, lang=lang)
    width = max(297.0, full.width_mm + 2 * margin_mm)
    height = max(210.0, full.height_mm + 2 * margin_mm + sentence_mm)
    sentences = con.describe(lang)
    figures = []
    for k in range(1, len(con.steps) + 1):
        done = con.steps[:k]
        part = replace(con, steps=done, centres={s.pair: s for s in done if s.how != "unreached"})
        view = centres_view(part, fine=fine, number=number, lang=lang, emphasis=k)
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
