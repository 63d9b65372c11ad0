"""One velocity or acceleration plan at one position, drawn from a `PlanResult`.

Every construction step becomes what a draughtsman draws for it (Pole: the pole's dot;
LayOff: the known vector with its arrowhead; Line: a thin construction line through an
image, clipped to the plan's area; Intersect: the two vectors the lines carry, and the
absolute vector from the pole; Similar: the similarity figure's side and the absolute
vector), then every image gets its lower-case letter (digits as subscripts: a₄, n₁), the
pole its p or π, and the plan its title and scale ("μv = 0,02 (м/с)/мм").

The plan keeps the orientation of the mechanism: a line ⊥ CA on the plan is ⊥ the link CA
as drawn in the scheme. Coordinates are the plan's own mm (the pole at the origin); the
view's ``to_view`` maps image mm to the view.

Layers: ``plan-v-K`` (vectors), ``plan-v-K-lines`` (construction lines) and
``plan-v-K-labels`` (letters, title, scale) for the velocity plan of position K;
``plan-a-K…`` for the acceleration plan.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import shapely

from velplan.options import Language
from velplan.plans.steps import Intersect, LayOff, Line, Pole, Similar
from velplan.plans.text import label_of
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.views.base import View, make_view, number, place_labels, scale_text, subscript, unit
from velplan.views.letters import place_letters

#: Construction lines run this far past the images they join, mm.
LINE_OVERRUN_MM = 10.0
#: Clearance of the plan's area around its images, mm.
AREA_MARGIN_MM = 12.0
#: Images closer than this share one label ("p, f"), mm.
COINCIDENT_MM = 0.8
#: Shortest labelled vector a plan draws as a readable length, mm; a shorter one is listed
#: under the plan as "≈ 0" with its value (DRAWING.md: the smallest labelled vector reads).
MIN_VECTOR_MM = 3.0


@dataclass(frozen=True)
class StepDrawing:
    """What one construction step adds to the plan, in the plan's mm (pole at 0).

    Attributes
    ----------
    step : Step
        The construction step.
    items : tuple of Primitive
        Its vectors and lines.
    images : tuple of str
        Targets (``"v:c"``) of the images this step fixes (lettered with it).
    sentence : str
        The step's sentence of the worked solution.
    """

    step: object
    items: tuple[Primitive, ...]
    images: tuple[str, ...]
    sentence: str


@dataclass(frozen=True)
class PlanSizes:
    """Text heights of a plan view, mm."""

    title_mm: float = 5.0
    label_mm: float = 3.5


def _xy(z: complex) -> tuple[float, float]:
    return (float(z.real), float(z.imag))


def _kind(res) -> str:
    return res.kind[0]


def layer_names(kind: str, number: int) -> tuple[str, str, str]:
    """(vectors, construction lines, labels) layer names of a plan."""
    base = f"plan-{kind}-{number}"
    return base, f"{base}-lines", f"{base}-labels"


def _image(res, target: str, i: int) -> complex:
    return complex(res.values[target][i])


def plan_steps(res, position: int, *, lang: Language = "ru") -> list[StepDrawing]:
    """The plan of `res` at position `position`, step by step, in the plan's mm.

    Parameters
    ----------
    res : PlanResult
        A velocity or acceleration plan.
    position : int
        Position number (1…n of the result's kinematics; one the result was evaluated at),
        also written in the layer names.
    lang : str
        Language of the sentences.
    """
    i = res.index_of(position)
    k = _kind(res)
    vec_layer, line_layer, _ = layer_names(k, position)
    pole = f"{k}:{'p' if k == 'v' else 'π'}"
    steps = [s for s in res.steps if s.target.startswith(k + ":")]
    sentences = res.describe(position, lang)
    area = plan_area(res, position)
    # which intersection each line serves, to run the line past it
    meets: dict[str, str] = {}
    for s in steps:
        if isinstance(s, Intersect):
            for line in s.lines:
                meets[line] = s.target
    out = []
    from_pole: set[str] = set()
    figures = _figures(res, k)
    fixed: set[str] = set()
    for s, sentence in zip(steps, sentences):
        items: list[Primitive] = []
        images: tuple[str, ...] = ()
        if isinstance(s, Pole):
            items.append(Circle((0.0, 0.0), 0.8, vec_layer, "thin", "solid"))
            images = (s.target,)
        elif isinstance(s, LayOff):
            a, b = _image(res, s.origin, i), _image(res, s.target, i)
            line = "thick" if s.origin == pole else "thin"
            if s.origin == pole:
                from_pole.add(s.target)
            items.append(Arrow(_xy(a), _xy(b), vec_layer, line))
            images = (s.target,)
        elif isinstance(s, Line):
            through, direction = res.values[s.target]
            p, u = complex(through[i]), complex(direction[i])
            ends = [0.0]
            if s.target in meets:
                x = _image(res, meets[s.target], i)
                if np.isfinite(x):
                    ends.append(((x - p) * u.conjugate()).real)
            seg = shapely.LineString([_xy(p + u * (min(ends) - LINE_OVERRUN_MM)),
                                      _xy(p + u * (max(ends) + LINE_OVERRUN_MM))])
            clipped = seg.intersection(area)
            if not clipped.is_empty and clipped.length > 0:
                items.append(Polyline(np.asarray(clipped.coords), line_layer, "thin"))
        elif isinstance(s, Intersect):
            x = _image(res, s.target, i)
            for name in s.lines:
                through = res.plan.by_target[name].through
                a = _image(res, through, i)
                items.append(Arrow(_xy(a), _xy(x), vec_layer,
                                   "thick" if through == pole else "thin"))
                if through == pole:
                    from_pole.add(s.target)
            if s.target not in from_pole:
                items.append(Arrow((0.0, 0.0), _xy(x), vec_layer, "thick"))
                from_pole.add(s.target)
            images = (s.target,)
        elif isinstance(s, Similar):
            a, x = _image(res, s.anchor_image, i), _image(res, s.target, i)
            if s.anchor_image != pole and abs(x - a) > 1e-9:
                items.append(Polyline([_xy(a), _xy(x)], vec_layer, "thin"))
            items.append(Arrow((0.0, 0.0), _xy(x), vec_layer, "thick"))
            from_pole.add(s.target)
            images = (s.target,)
        fixed.update(images)
        items += _marks(res, images, i, pole, vec_layer)
        items += _figure_sides(res, figures, images, fixed, i, vec_layer)
        items = [p for p in items if _finite(p)]
        out.append(StepDrawing(s, tuple(items), images, sentence))
    return out


#: Radius of the dot that marks an image point on a plan, mm.
IMAGE_DOT_MM = 0.45


def _marks(res, images, i: int, pole: str, layer: str) -> list[Primitive]:
    """A dot at each image a step fixes (every image is a point of the plan, marked as one,
    not only by the arrowhead of its vector); the pole has its own larger dot."""
    out = []
    for t in images:
        z = _image(res, t, i)
        if t != pole and np.isfinite(z) and abs(z) > 1e-9:
            out.append(Circle(_xy(z), IMAGE_DOT_MM, layer, "thin", "solid"))
    return out


def _figures(res, k: str) -> list[tuple[str, ...]]:
    """Targets of the images of each class III group's base link (b, c, d): drawn as the
    figure similar to the link (the similarity theorem) once the plan has all three."""
    images = res.plan.images[k]
    return [tuple(images[j] for j in g.joints) for g in res.plan.mechanism.groups
            if getattr(g, "kind", "") == "triad" and all(j in images for j in g.joints)]


def _figure_sides(res, figures, images, fixed: set, i: int, layer: str) -> list[Primitive]:
    """The closed figure of a base link's images, drawn by the step that fixes its last one."""
    out = []
    for fig in figures:
        if set(images) & set(fig) and set(fig) <= fixed:
            pts = [_xy(_image(res, t, i)) for t in fig]
            out.append(Polyline(pts + pts[:1], layer, "thin"))
    return out


def _finite(p: Primitive) -> bool:
    coords = {Arrow: lambda a: [a.start, a.end], Circle: lambda c: [c.centre]}.get(
        type(p), lambda q: list(q.points))(p)
    return all(math.isfinite(x) and math.isfinite(y) for x, y in coords)  # pairs of floats


def plan_area(res, position: int) -> shapely.Polygon:
    """The plan's drawing area at position number `position`: its images' box with a margin,
    mm (pole at 0)."""
    pts = [z for z in _images(res, position) if np.isfinite(z)]
    xs, ys = [z.real for z in pts], [z.imag for z in pts]
    return shapely.box(min(xs) - AREA_MARGIN_MM, min(ys) - AREA_MARGIN_MM,
                       max(xs) + AREA_MARGIN_MM, max(ys) + AREA_MARGIN_MM)


def letters_to_place(res, position: int, drawings: list[StepDrawing], *, size_mm: float = 3.5,
                     upto: int | None = None) -> tuple[list[Text], list, np.ndarray, list[Circle]]:
    """What `image_letters` places at position number `position` (1…n): the letters at their
    wanted spots (off the lines that meet at each image), each letter's image (mm), the segments
    the letters keep off, shape (n, 2, 2): start and end (mm; each vector twice), and the dots
    they keep off."""
    i = res.index_of(position)
    _, _, text_layer = layer_names(_kind(res), position)
    upto = len(drawings) if upto is None else upto
    shown = [t for d in drawings[:upto] for t in d.images]
    image = {t: _image(res, t, i) for t in shown}
    groups: list[list[str]] = []
    for t in shown:
        z = image[t]
        if not np.isfinite(z):
            continue
        for g in groups:
            if abs(image[g[0]] - z) < COINCIDENT_MM:
                g.append(t)
                break
        else:
            groups.append([t])
    shown_items = [p for d in drawings[:upto] for p in d.items]
    pairs: list = []  # every straight piece drawn: (start, end), mm
    for p in shown_items:
        if isinstance(p, Arrow):
            pairs.append((p.start, p.end))
        elif isinstance(p, Polyline):
            pairs += zip(p.points[:-1], p.points[1:])
    segments = np.array(pairs, float).reshape(-1, 2, 2)
    # where every spot is crossed, a thin line under a letter reads better than a vector: each
    # vector counts twice; the outlines are buffered all at once (the same as one by one)
    step = segments[:, 1] - segments[:, 0]
    arrows = [(p.start, p.end) for p in shown_items if isinstance(p, Arrow) and p.length > 1e-9]
    lines = np.concatenate([segments[np.hypot(step[:, 0], step[:, 1]) > 1e-9],
                            np.array(arrows, float).reshape(-1, 2, 2)])
    circles = [p for p in shown_items if isinstance(p, Circle)]
    texts = []
    # each segment's ends and the unit vectors out of them along it, in the order (a, b), (b, a)
    ends = segments.reshape(-1, 2)
    along = (segments[:, ::-1] - segments).reshape(-1, 2)
    span = np.hypot(along[:, 0], along[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        unit_along = along / span[:, None]
    # per image, the units out of the ends at it summed one after the other (a running sum, the
    # others adding 0), as a loop over them would
    heres = np.array([_xy(image[g[0]]) for g in groups], float).reshape(-1, 2)
    off = ends[None, :, :] - heres[:, None, :]
    at = (np.hypot(off[..., 0], off[..., 1]) < COINCIDENT_MM) & (span > 1e-9)[None, :]
    sums = np.cumsum(np.where(at[..., None], unit_along[None, :, :], 0.0), axis=1)
    aways = -sums[:, -1] if len(ends) else np.zeros((len(groups), 2))
    for g, here, away in zip(groups, heres, aways):
        if np.hypot(*away) < 0.3:
            away = here / np.hypot(*here) if np.hypot(*here) > 1 else np.array([-0.7, -0.7])
        away = away / np.hypot(*away)
        text = ", ".join(subscript(label_of(t)) for t in g)
        anchor = "start" if away[0] > 0.35 else ("end" if away[0] < -0.35 else "middle")
        pos = here + away * (1.2 + 0.45 * size_mm)
        texts.append(Text(pos, text, text_layer, size_mm, anchor, "middle"))
    anchors = [_xy(image[g[0]]) for g in groups]
    return texts, anchors, lines, circles


def image_letters(res, position: int, drawings: list[StepDrawing], *, size_mm: float = 3.5,
                  upto: int | None = None, leaders: bool = False, avoid: Sequence = (),
                  near_mm: float | None = None) -> list:
    """Letters of the images fixed by the first `upto` steps of the plan at position number
    `position`, clear of the vectors. With `leaders`, each letter goes to the nearest free
    spot where its own image is the nearest image to it, within `LEADER_MM` (never where a
    line crosses it), else farther out, joined to its image by a thin leader (the leaders
    follow the letters in the list).
    `avoid`: shapes (plan mm) the letters keep off besides the vectors, e.g. the title's texts;
    `near_mm`: with `leaders`, how far from its image a letter without a leader may stand, mm."""
    texts, anchors, lines, circles = letters_to_place(res, position, drawings, size_mm=size_mm, upto=upto)
    obstacles = list(shapely.buffer(shapely.linestrings(np.array(lines, float).reshape(-1, 2, 2)), 0.5,
                                     quad_segs=16))
    obstacles += list(shapely.buffer(shapely.points(np.array([p.centre for p in circles], float).reshape(-1, 2)),
                                     np.array([p.radius + 0.3 for p in circles], float), quad_segs=16))
    obstacles += list(avoid)
    if not leaders:
        return list(place_labels(texts, obstacles, rings=8))
    # each letter by its own image, nearer it than any other image; beyond the crowd, a leader
    named = anchors + [_xy(z) for z in _images(res, position) if np.isfinite(z)]
    placed, leader_lines = place_letters(texts, anchors, named, obstacles,
                                         leader_layer=layer_names(_kind(res), position)[1],
                                         gaps=LETTER_GAPS_MM, leader_gaps=LEADER_GAPS_MM, near_mm=near_mm)
    return placed + leader_lines


#: A letter farther than this from its image gets a leader, mm.
LEADER_MM = 3.0
#: The gaps between an image and its letter's box tried without a leader, then with one, mm.
LETTER_GAPS_MM = (1.0, 1.6, 2.3, LEADER_MM)
LEADER_GAPS_MM = (4.5, 6.0, 7.5, 9.0, 11.0, 13.0)


def labelled_vectors(res, position: int) -> dict[str, tuple[str, float]]:
    """Image target → (the image its vector starts from, the vector's length, mm) of every
    image of the plan at position number `position` (1…n): a laid-off vector (a normal, a Coriolis
    component, n₁, k) from its origin, any other image from the pole."""
    k, i = _kind(res), res.index_of(position)
    pole = f"{k}:{'p' if k == 'v' else 'π'}"
    origin = {s.target: s.origin for s in res.steps
              if isinstance(s, LayOff) and s.target.startswith(k + ":")}
    out = {}
    for t in _image_targets(res, position):
        if t == pole:
            continue
        start = origin.get(t, pole)
        z = _image(res, t, i) - _image(res, start, i)
        if np.isfinite(z):
            out[t] = (start, float(abs(z)))
    return out


def near_zero(res, position: int, lang: str) -> list[str]:
    """The labelled vectors shorter than `MIN_VECTOR_MM` at the plan's scale at position
    number `position` (1…n), as the course lists them: ``"πs₄ ≈ 0 (0,092 м/с²)"`` (its
    value is |vector| · μ); the vectors that vanish (under 10⁻⁶ mm) together:
    ``"pa₄, pb = 0"``."""
    u = unit("m/s" if _kind(res) == "v" else "m/s²", lang)
    out, zero = [], []
    for t, (start, length) in labelled_vectors(res, position).items():
        if length < MIN_VECTOR_MM:
            name = subscript(label_of(start)) + subscript(label_of(t))
            if length < 1e-6:
                zero.append(name)
            else:
                out.append(f"{name} ≈ 0 ({number(length * res.scale, lang, 2)} {u})")
    return ([", ".join(zero) + " = 0"] if zero else []) + out


def _image_targets(res, position: int) -> list[str]:
    """Targets of the images drawn on the plan at position number `position` (1…n; finite
    values only)."""
    k, i = _kind(res), res.index_of(position)
    return [t for t, z in res.values.items() if t.startswith(k + ":") and not isinstance(z, tuple)
            and np.isfinite(complex(z[i]))]


def plan_title(res, number: int, lang: Language) -> tuple[str, str]:
    """(title, scale) lines: ``"План скоростей (пол. 4)"``, ``"μv = 0,02 (м/с)/мм"``."""
    k = _kind(res)
    name = label("velocity_plan" if k == "v" else "acceleration_plan", lang)
    symbol, unit_key = ("μv", "(m/s)/mm") if k == "v" else ("μa", "(m/s²)/mm")
    return (f"{name} ({label('position_short', lang)} {number})",
            scale_text(symbol, res.scale, unit_key, lang))


def plan_view(res, position: int, *, lang: Language = "ru", sizes: PlanSizes = PlanSizes(),
              title: bool = True, steps: list[StepDrawing] | None = None) -> View:
    """The plan of `res` at position number `position` as a view.

    Parameters
    ----------
    res : PlanResult
    position : int
        Position number (1…n of the result's kinematics; one the result was evaluated at),
        written in the title and the layer names.
    lang : {"en", "ru", "uk", "zh"}
    sizes : PlanSizes
    title : bool
        Write the title and the scale above the plan.
    steps : list of StepDrawing, optional
        ``plan_steps(res, position, lang=lang)`` where already made (a layout's trial).

    Returns
    -------
    View
        ``to_view`` maps plan mm (pole at 0) to the view's mm; ``meta`` holds ``kind``,
        ``number``, ``scale`` and ``images`` (target → plan mm).
    """
    drawings = plan_steps(res, position, lang=lang) if steps is None else steps
    items: list[Primitive] = [p for d in drawings for p in d.items]
    items += image_letters(res, position, drawings, size_mm=sizes.label_mm, leaders=True)
    if title:
        items += _title_lines(res, position, lang, sizes, items)
        items += _near_zero_lines(res, position, lang, items, sizes.label_mm, items[:-2])
    k, i = _kind(res), res.index_of(position)
    images = {t: _image(res, t, i) for d in drawings for t in d.images}
    return make_view(f"plan-{k}-{position}", items, pad_mm=_PAD_MM, mu=None,
                     meta={"kind": k, "number": position, "scale": res.scale, "images": images})


_PAD_MM = 2.0
"""Margin of a plan view around its drawing, mm."""


def _title_lines(res, position: int, lang: Language, sizes: PlanSizes, items) -> list[Text]:
    """The title and the scale lines, above the upper left corner of the box of `items`."""
    _, _, text_layer = layer_names(_kind(res), position)
    x0, _, _, y1 = _bounds(items)
    head, scale = plan_title(res, position, lang)
    return [Text((x0, y1 + 3.0 + 1.5 * sizes.label_mm), head, text_layer, sizes.title_mm),
            Text((x0, y1 + 3.0), scale, text_layer, sizes.label_mm)]


def least_plan_size(res, position: int, steps: list[StepDrawing], *, lang: Language = "ru",
                    sizes: PlanSizes = PlanSizes()) -> tuple[float, float]:
    """A lower bound of the width and height (mm) of ``plan_view(res, position, lang=lang,
    sizes=sizes, steps=steps)`` at position number `position` (1…n), without placing its
    letters: the box of the construction
    `steps` and of the title above it, padded as the view is. The letters and the ≈ 0 list
    only widen the box, and the title, set above the box's upper left corner, only moves
    up and left with it, so the view is at least this large."""
    items: list[Primitive] = [p for d in steps for p in d.items]
    x0, y0, x1, y1 = _bounds(items + _title_lines(res, position, lang, sizes, items))
    return x1 - x0 + 2 * _PAD_MM, y1 - y0 + 2 * _PAD_MM


def _near_zero_lines(res, position: int, lang: str, items, size: float, body) -> list[Text]:
    """The ≈ 0 list, two entries a line or one: in a corner of the box of the plan's `body`
    (its drawing without the title) where no line or letter is, so that the plan keeps its
    size, else under the plan."""
    listed = near_zero(res, position, lang)
    if not listed:
        return []
    _, _, text_layer = layer_names(_kind(res), position)
    x0, y0, x1, y1 = _bounds(body)
    taken = _Clearance([_outline(p) for p in items], 1.0)
    step = 1.5 * size
    for per in (2, 1):
        lines = ["; ".join(listed[j:j + per]) for j in range(0, len(listed), per)]
        for x, top, anchor in ((x0, y0 + step * len(lines) + 0.5 * size, "start"),
                               (x1, y0 + step * len(lines) + 0.5 * size, "end"),
                               (x1, y1, "end")):
            texts = [Text((x, top - step * (j + 1)), line, text_layer, size, anchor)
                     for j, line in enumerate(lines)]
            if not any(taken.meets(label_box(t)) for t in texts):
                return texts
    lines = ["; ".join(listed[j:j + 2]) for j in range(0, len(listed), 2)]
    return [Text((x0, y0 - 2.0 - step * (j + 1)), line, text_layer, size)
            for j, line in enumerate(lines)]


class _Clearance:
    """Whether a shape meets the union of `shapes` buffered by `gap` mm (shapely's polygonal
    buffer, as drawn), decided by the distance to the shapes: the buffer, slow to build, is
    built only for a shape whose distance lies within `BAND` of `gap`, where the buffer's
    chords (≤ 0.2 % of `gap`) and its input simplification (≤ 1 %) could decide otherwise."""

    BAND = 0.05

    def __init__(self, shapes, gap: float):
        self.shapes, self.gap, self._buffer = shapes, gap, None

    def meets(self, shape) -> bool:
        d = float(shapely.distance(shape, self.shapes).min()) if self.shapes else math.inf
        if abs(d - self.gap) > self.BAND * self.gap:
            return d < self.gap
        if self._buffer is None:
            self._buffer = shapely.union_all(self.shapes).buffer(self.gap)
        return shape.intersects(self._buffer)


def _outline(p: Primitive):
    """The shape a primitive covers on the plan, mm."""
    if isinstance(p, Text):
        return label_box(p)
    if isinstance(p, Arrow):
        return shapely.LineString([p.start, p.end])
    if isinstance(p, Circle):
        return shapely.Point(p.centre).buffer(p.radius)
    return shapely.LineString(p.points)


def _bounds(items):
    from velplan.views.base import bounds_of
    return bounds_of(items)


def extent_mm(res, position: int) -> tuple[float, float]:
    """Width and height of the plan's images at position number `position`, at its scale, mm."""
    pts = np.array([z for z in _images(res, position) if np.isfinite(z)])
    return float(np.ptp(pts.real)), float(np.ptp(pts.imag))


def _images(res, position: int) -> list[complex]:
    """The pole and the images of the plan at position number `position`, plan mm."""
    k, i = _kind(res), res.index_of(position)
    return [0j] + [complex(z[i]) for t, z in res.values.items()
                   if t.startswith(k + ":") and not isinstance(z, tuple)]


__all__ = ["StepDrawing", "PlanSizes", "MIN_VECTOR_MM", "labelled_vectors", "near_zero", "plan_steps", "plan_view", "plan_area", "image_letters",
           "letters_to_place", "plan_title", "layer_names", "extent_mm", "label_box"]
