"""Construction steps of a velocity or acceleration plan: one frozen value per textbook step.

A step names its inputs by image (``"v:a"``: the image a on the velocity plan, ``"a:c"``:
the image c on the acceleration plan) and by mechanism point, and evaluates on whole arrays
of positions. Plan coordinates are complex numbers in mm with the pole at 0.
"""

from __future__ import annotations

import math

from dataclasses import dataclass

import numpy as np

from velplan.analysis.groups import cis
from velplan.mechanism.model import GROUND, Guide
from velplan.options import Language
from velplan.plans.context import Context, Figure
from velplan.plans import text as T


# -- known vectors ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Rotation:
    """V = ω1 × (P − C): velocity of the crank tip P about its pivot C, m/s (ω1 given)."""

    link: str
    point: str
    centre: str
    plan: str = "v"

    inputs = ()

    def value(self, ctx: Context, vals) -> np.ndarray:
        return 1j * ctx.omega1 * (ctx.pos(self.point) - ctx.pos(self.centre))

    def symbol(self) -> str:
        return f"V_{self.point}"

    def direction_text(self, lang: Language) -> str:
        return T.phrase("perp", lang, T.pts(T.seg(self.centre, self.point))) + T.phrase("sense_of", lang,
                                                                                         T.rate("ω", self.link))


@dataclass(frozen=True)
class Normal:
    """aⁿ = −ω²·(P − C): normal acceleration of P about C on a link, m/s², directed from P
    towards C; ω from the velocity plan (``figure``), or ω1 for the crank (``figure=None``)."""

    link: str
    point: str
    centre: str
    figure: Figure | None = None
    plan: str = "a"
    name: str | None = None
    """The point's name in the component's symbol (the bar's A4 where the position is A's)."""

    @property
    def inputs(self) -> tuple[str, ...]:
        return self.figure.inputs if self.figure else ()

    def value(self, ctx: Context, vals) -> np.ndarray:
        w = ctx.omega1 if self.figure is None else ctx.omega_of(self.figure, vals)
        return -(w**2) * (ctx.pos(self.point) - ctx.pos(self.centre))

    def symbol(self) -> str:
        return f"aⁿ_{self.name or self.point}{self.centre}"

    def direction_text(self, lang: Language) -> str:
        return T.phrase("along_to", lang, T.pts(T.seg(self.point, self.centre)), T.pts(self.point),
                        T.pts(self.centre))


@dataclass(frozen=True)
class Tangential:
    """aᵗ = ε1 × (P − C): tangential acceleration of the crank tip, m/s² (ε1 given)."""

    link: str
    point: str
    centre: str
    plan: str = "a"

    inputs = ()

    def value(self, ctx: Context, vals) -> np.ndarray:
        return 1j * ctx.epsilon1 * (ctx.pos(self.point) - ctx.pos(self.centre))

    def symbol(self) -> str:
        return f"aᵗ_{self.point}{self.centre}"

    def direction_text(self, lang: Language) -> str:
        return T.phrase("perp", lang, T.pts(T.seg(self.centre, self.point))) + T.phrase("sense_of", lang,
                                                                                         T.rate("ε", self.link))


@dataclass(frozen=True)
class Coriolis:
    """aᵏ = 2·ω × V_rel: Coriolis acceleration of a point moving at V_rel (m/s, read off the
    velocity plan as the segment ``rel_from → rel_to``) along a link turning at ω (``frame``)."""

    frame: Figure
    rel_from: str
    rel_to: str
    name: str
    plan: str = "a"

    @property
    def inputs(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(self.frame.inputs + (self.rel_from, self.rel_to)))

    def value(self, ctx: Context, vals) -> np.ndarray:
        w = ctx.omega_of(self.frame, vals)
        v_rel = (vals[self.rel_to] - vals[self.rel_from]) * ctx.mu["v"]
        return 2j * w * v_rel

    def symbol(self) -> str:
        return f"aᵏ_{self.name}"

    def direction_text(self, lang: Language) -> str:
        return T.phrase("coriolis_dir", lang, T.rate("ω", self.frame.link), T.vector(T.phrase("v_rel", lang)))


# -- directions of construction lines -------------------------------------------------------------


@dataclass(frozen=True)
class Perpendicular:
    """The direction ⊥ the segment AB of the mechanism (as drawn in the position)."""

    a: str
    b: str

    def unit(self, ctx: Context) -> np.ndarray:
        return ctx.memo(self, lambda: self._unit(ctx))

    def _unit(self, ctx: Context) -> np.ndarray:
        d = ctx.pos(self.b) - ctx.pos(self.a)
        with np.errstate(invalid="ignore", divide="ignore"):
            d *= 1.0 / np.abs(d)
        return d * 1j

    def text(self, lang: Language) -> str:
        return T.phrase("perp", lang, T.pts(T.seg(self.a, self.b)))


@dataclass(frozen=True)
class Parallel:
    """The direction ∥ a guide: the reference direction of ``link`` turned by ``angle`` (rad);
    ``along`` names the guide for the sentence (e.g. ``"O3B"`` or ``"x"``)."""

    link: str
    angle: float
    along: str

    def unit(self, ctx: Context) -> np.ndarray:
        if self.link == GROUND:  # a guide of the frame keeps its direction
            return np.full(ctx.n, cis(self.angle))
        return ctx.memo(self, lambda: cis(ctx.theta(self.link) + self.angle))

    def text(self, lang: Language) -> str:
        along: T.Sentence | T.Sym
        if self.along == "slot":
            along = T.phrase("slot", lang)
        elif self.along.startswith("guide:"):
            along = T.phrase("guide", lang, self.along[6:])
        else:
            along = T.pts(self.along)
        return T.phrase("parallel", lang, along)


# -- steps ----------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Pole:
    """The pole (p on the velocity plan, π on the acceleration plan): the image of every fixed
    point and the origin of every absolute vector."""

    target: str
    label: str
    points: tuple[str, ...]

    inputs = ()

    def evaluate(self, ctx: Context, vals) -> np.ndarray:
        return np.zeros(ctx.n, dtype=complex)

    def describe(self, ctx, vals, i, lang) -> str:
        return T.phrase("pole", lang, T.pts(self.label), T.joined(", ", map(T.pts, self.points)))


@dataclass(frozen=True)
class LayOff:
    """Lay off a known vector (``vector``, physical units) from the image ``origin`` at the plan's
    scale: ``target = origin + vector / μ`` (mm)."""

    target: str
    label: str
    origin: str
    vector: Rotation | Normal | Tangential | Coriolis

    @property
    def inputs(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys((self.origin,) + tuple(self.vector.inputs)))

    def evaluate(self, ctx: Context, vals) -> np.ndarray:
        z = ctx.drafting.vector(self.vector.value(ctx, vals) / ctx.mu[self.vector.plan])
        ctx.record_segment(self, T.label_of(self.origin) + self.label, lambda: np.abs(z), self.vector.symbol())
        return vals[self.origin] + z

    def describe(self, ctx, vals, i, lang) -> str:
        z = vals[self.target][i] - vals[self.origin][i]
        value = abs(z) * ctx.mu[self.vector.plan]
        return T.phrase(
            "lay_off", lang, T.pts(T.label_of(self.origin)), T.pts(T.label_of(self.origin) + self.label),
            T.mm(abs(z), lang), self.vector.direction_text(lang), T.vector(self.vector.symbol()), T.num(value, lang),
            T.unit(self.vector.plan, lang),
        )


@dataclass(frozen=True)
class Line:
    """A construction line through the image ``through`` in the direction ``direction``; the
    segment it carries from ``through`` to the next intersection is the component ``component``."""

    target: str
    through: str
    direction: Perpendicular | Parallel
    component: str

    @property
    def inputs(self) -> tuple[str, ...]:
        return (self.through,)

    def evaluate(self, ctx: Context, vals) -> tuple[np.ndarray, np.ndarray]:
        return vals[self.through], ctx.drafting.direction(self.direction.unit(ctx))

    def describe(self, ctx, vals, i, lang) -> str:
        return T.phrase("line", lang, T.pts(T.label_of(self.through)), self.direction.text(lang),
                        T.vector(self.component))


@dataclass(frozen=True)
class Intersect:
    """The image ``target`` where two construction lines cross.

    Its condition estimate is |sin| of the angle between the lines; positions where it falls
    below the context's refusal threshold are refused (NaN and a mask) rather than returned.
    """

    target: str
    label: str
    lines: tuple[str, str]

    @property
    def inputs(self) -> tuple[str, ...]:
        return self.lines

    def evaluate(self, ctx: Context, vals) -> np.ndarray:
        (p1, u1), (p2, u2) = vals[self.lines[0]], vals[self.lines[1]]
        cross = u1.real * u2.imag - u1.imag * u2.real
        d = p2 - p1
        with np.errstate(divide="ignore", invalid="ignore"):  # parallel lines: refused below
            t = (d.real * u2.imag - d.imag * u2.real) / cross
            x = p1 + t * u1
        ctx.record_intersection(self, np.abs(cross), x, (p1, p2))
        for line, p in zip(self.lines, (p1, p2)):
            step = ctx.plan_steps[line]
            ctx.record_segment(self, T.label_of(step.through) + self.label, lambda p=p: np.abs(x - p), step.component)
        refused = ctx.refused_mask(self.target)
        return np.where(refused, np.nan + 0j, x) if refused.any() else x

    def describe(self, ctx, vals, i, lang) -> str:
        cond = ctx.conditions[self.target][i]
        segs = []
        for line in self.lines:
            step = ctx.plan_steps[line]
            length = abs(vals[self.target][i] - vals[step.through][i])
            segs.append(T.text(T.pts(T.label_of(step.through) + self.label), f" = {T.mm(length, lang)}"))
        return T.phrase("intersect", lang, T.pts(self.label), T.joined("; ", segs), T.num(cond, lang, 3))


@dataclass(frozen=True)
class Similar:
    """Place the image of ``point`` by the similarity theorem: the images of a link's points
    form a figure similar to the link (turned by 90° in the sense of ω on the velocity plan).

    ``x = anchor_image + (image2 − image1)·(P − A)/(P2 − P1)`` where (P1, P2) is a pair of the
    link's points (or of a link turning with it) with known images. ``base = None`` means
    the link does not turn (it translates): every point has the anchor's image.
    """

    target: str
    label: str
    link: str
    point: str
    anchor: str
    anchor_image: str
    base: Figure | None
    rigid: bool = False
    """All four points are fixed to their links: the ratio is the same at every position."""

    @property
    def inputs(self) -> tuple[str, ...]:
        extra = self.base.inputs if self.base else ()
        return tuple(dict.fromkeys((self.anchor_image,) + extra))

    def evaluate(self, ctx: Context, vals) -> np.ndarray:
        a = vals[self.anchor_image]
        if self.base is None:
            return a
        f = self.base
        if self.rigid:
            ratio = ctx.constant_ratio(self.point, self.anchor, f.p1, f.p2)
        else:
            ratio = ctx.memo(("ratio", self.point, self.anchor, f.p1, f.p2), lambda: self._ratio(ctx))
        z = ctx.drafting.vector((vals[f.img2] - vals[f.img1]) * ratio)
        ctx.record_segment(self, T.label_of(self.anchor_image) + self.label, lambda: np.abs(z), "")
        return a + z

    def _ratio(self, ctx: Context) -> np.ndarray:
        f = self.base
        with np.errstate(divide="ignore", invalid="ignore"):  # NaN at positions already masked
            return (ctx.pos(self.point) - ctx.pos(self.anchor)) / (ctx.pos(f.p2) - ctx.pos(f.p1))

    def describe(self, ctx, vals, i, lang) -> str:
        if self.base is None:
            return T.phrase("same_image", lang, T.pts(self.label), self.link, T.pts(T.label_of(self.anchor_image)))
        f = self.base
        length = abs(vals[self.target][i] - vals[self.anchor_image][i])
        ratio = abs(ctx.pos(self.point)[i] - ctx.pos(self.anchor)[i]) / abs(ctx.pos(f.p2)[i] - ctx.pos(f.p1)[i])
        return T.phrase(
            "similar", lang, T.pts(self.label), self.link, T.pts(T.label_of(self.anchor_image) + self.label),
            T.mm(length, lang), T.pts(T.label_of(f.img1) + T.label_of(f.img2)),
            T.text(T.pts(T.seg(self.anchor, self.point)), "/", T.pts(T.seg(f.p1, f.p2))),
            T.num(ratio, lang, 4),
        )


Step = Pole | LayOff | Line | Intersect | Similar


def guide_text(guide: Guide, link: str) -> str:
    """How a plan names the direction of ``guide`` (on ``link``): x–x, y–y or guide:<link>."""
    if link == GROUND:
        deg = math.degrees(guide.angle) % 180
        if abs(deg) < 1e-9 or abs(deg - 180) < 1e-9:
            return "x–x"
        if abs(deg - 90) < 1e-9:
            return "y–y"
    return f"guide:{link}"
