"""Formulas of each construction step of a plan, with the plan's own numbers substituted.

Every number is formatted by the functions that write the step sentences and the sheets
(`velplan.plans.text.num`, `velplan.plans.text.mm`, `velplan.views.base.number`), so the note
says what the sheet and the worked solution say, digit for digit.
"""

from __future__ import annotations

import numpy as np

from velplan.note.formulas import chain, name, seg, symbol, txt, vec
from velplan.options import Language
from velplan.plans import text as T
from velplan.plans.steps import Coriolis, Intersect, LayOff, Line, Normal, Perpendicular, Pole, Rotation, Similar
from velplan.notation import number


def num(x: float, lang: Language) -> str:
    return txt(T.num(float(x), lang))


def mm(x: float, lang: Language) -> str:
    """A length on the plan, 0.1 mm, without its unit (as in the step sentences)."""
    return txt(T.mm(float(x), lang).rsplit(" ", 1)[0])


def mu_tex(plan: str) -> str:
    return r"\mu_{" + plan + "}"


def letter(plan: str) -> str:
    return "V" if plan == "v" else "a"


def step_equations(res, step, i: int, lang: Language) -> list[str]:
    """TeX equations of ``step`` of the plan ``res`` at its position index ``i``."""
    for kind, fn in ((Pole, _pole), (LayOff, _lay_off), (Line, _line), (Intersect, _intersect),
                     (Similar, _similar)):
        if isinstance(step, kind):
            return fn(res, step, i, lang)
    return []


def _pole(res, step, i, lang):
    k = res.kind[0]
    return [" = ".join(f"{letter(k)}_{{{name(pt)}}}" for pt in step.points) + " = 0"]


def _length(ctx, a: str, b: str, i: int) -> float:
    return float(abs(ctx.pos(a)[i] - ctx.pos(b)[i]))


def _lay_off(res, step, i, lang):
    ctx, vals, v = res.ctx, res.values, step.vector
    z = vals[step.target][i] - vals[step.origin][i]
    value, length = abs(z) * ctx.mu[v.plan], abs(z)
    sym, unit = symbol(v.symbol()), txt(T.unit(v.plan, lang))
    if isinstance(v, Coriolis):
        w = ctx.omega_of(v.frame, vals)[i]
        rel = abs(vals[v.rel_to][i] - vals[v.rel_from][i]) * ctx.mu["v"]
        head = (rf"{sym} = 2\,\omega_{{{v.frame.link}}}\cdot V_{{{chain(v.name)}}} = 2\cdot{num(abs(w), lang)}"
                rf"\cdot{num(rel, lang)}")
    else:
        l_tex, l = r"l_{" + chain(v.centre + v.point) + "}", _length(ctx, v.point, v.centre, i)
        if isinstance(v, Rotation):
            head = rf"{sym} = \omega_{{{v.link}}}\cdot {l_tex} = {num(abs(ctx.omega1[i] if np.ndim(ctx.omega1) else ctx.omega1), lang)}\cdot{num(l, lang)}"
        elif isinstance(v, Normal):
            w = ctx.omega1 if v.figure is None else ctx.omega_of(v.figure, vals)
            w = w[i] if np.ndim(w) else w
            head = rf"{sym} = \omega_{{{v.link}}}^{{2}}\cdot {l_tex} = {num(abs(w), lang)}^{{2}}\cdot{num(l, lang)}"
        else:
            e = ctx.epsilon1[i] if np.ndim(ctx.epsilon1) else ctx.epsilon1
            head = rf"{sym} = \varepsilon_{{{v.link}}}\cdot {l_tex} = {num(abs(e), lang)}\cdot{num(l, lang)}"
    first = rf"{head} = {num(value, lang)}\ {unit}"
    origin = T.label_of(step.origin)
    second = (rf"{seg(origin, step.label)} = \frac{{{sym}}}{{{mu_tex(v.plan)}}} = "
              rf"\frac{{{num(value, lang)}}}{{{txt(number(ctx.mu[v.plan], lang))}}} = {mm(length, lang)}\ "
              rf"{txt(T.unit('mm', lang))}")
    return [first, second]


def _direction(d, lang: str = "en") -> str:
    if isinstance(d, Perpendicular):
        return r"\perp " + chain(d.a + d.b)
    if d.along.startswith("guide:"):  # a link's guide, in words as the step's sentence says it
        return r"\parallel " + txt(T.phrase("guide", lang, d.along.split(":", 1)[1]))
    from velplan.note.prose import sym_tex

    return r"\parallel " + sym_tex(T.pts(d.along))  # as the step's sentence sets it (x–x, O3B)


def _line(res, step, i, lang):
    return [vec(step.component) + " " + _direction(step.direction, lang)]


def _point_of(res, target: str) -> str | None:
    inverse = {t: p for p, t in res.plan.images[target[0]].items()}
    return inverse.get(target)


def absolute(res, target: str) -> list[str]:
    """The vectors (TeX) whose sum goes from the pole to the image ``target``."""
    step = res.plan.by_target[target]
    if isinstance(step, Pole):
        return []
    point = _point_of(res, target)
    if point is not None:
        return [vec(f"{letter(target[0])}_{point}")]
    if isinstance(step, LayOff):
        return absolute(res, step.origin) + [vec(step.vector.symbol())]
    return [seg("p" if target[0] == "v" else "π", T.label_of(target))]


def _reading(res, comp: str, i: int, lang: Language) -> str:
    """A component read off the plan: its segment times μ."""
    label, value = res.components[comp]
    plan = res.ctx.segment_plans[label]
    length = float(res.drafting.length(res.ctx.segments[label])[i])
    return (rf"{symbol(comp)} = \overline{{{_label_tex(label)}}}\cdot{mu_tex(plan)} = "
            rf"{mm(length, lang)}\cdot{txt(number(res.scales[plan], lang))} = "
            rf"{num(value[i], lang)}\ {txt(T.unit(plan, lang))}")


def _label_tex(label: str) -> str:
    """A segment label of the plan (``pa4``, ``k1a4``, ``πn1``) in TeX."""
    import re

    return " ".join(name(p) for p in re.findall(r"[^\d]\d*", label))


def _point_value(res, point: str, target: str, i: int, lang: Language) -> str:
    k = target[0]
    z = res.values[target][i]
    length = abs(z)
    value = float(np.hypot(*res.vector(point)[i]))
    pole = "p" if k == "v" else "π"
    return (rf"{letter(k)}_{{{name(point)}}} = {seg(pole, T.label_of(target))}\cdot{mu_tex(k)} = "
            rf"{mm(length, lang)}\cdot{txt(number(res.scale, lang))} = {num(value, lang)}\ {txt(T.unit(k, lang))}")


def _intersect(res, step, i, lang):
    point = _point_of(res, step.target)
    sides, reads, through_pole = [], [], False
    for line in step.lines:
        ln = res.plan.by_target[line]
        terms = absolute(res, ln.through) + [vec(ln.component)]
        through_pole |= isinstance(res.plan.by_target[ln.through], Pole)
        sides.append(" + ".join(terms))
        if ln.component in res.components:
            reads.append(_reading(res, ln.component, i, lang))
    lhs = vec(f"{letter(step.target[0])}_{point}") if point else ""
    sides = [side for side in sides if side != lhs] or sides
    head = (lhs + " = " if lhs else "") + " = ".join(sides)
    out = [head] + reads
    if point and not through_pole:
        out.append(_point_value(res, point, step.target, i, lang))
    return out


def _similar(res, step, i, lang):
    point = _point_of(res, step.target)
    if step.base is None:
        k = step.target[0]
        return [f"{vec(letter(k) + '_' + point)} = {vec(letter(k) + '_' + step.anchor)}"] if point else []
    ctx, vals, f = res.ctx, res.values, step.base
    ratio = _length(ctx, step.point, step.anchor, i) / _length(ctx, f.p2, f.p1, i)
    base = abs(vals[f.img2][i] - vals[f.img1][i])
    length = abs(vals[step.target][i] - vals[step.anchor_image][i])
    out = [rf"{seg(T.label_of(step.anchor_image), step.label)} = {seg(T.label_of(f.img1), T.label_of(f.img2))}"
           rf"\cdot\frac{{l_{{{chain(step.anchor + step.point)}}}}}{{l_{{{chain(f.p1 + f.p2)}}}}} = "
           rf"{mm(base, lang)}\cdot{txt(T.num(ratio, lang, 4))} = {mm(length, lang)}\ {txt(T.unit('mm', lang))}"]
    if point:
        out.append(_point_value(res, point, step.target, i, lang))
    return out


def _image_point(image: str, point: str) -> str:
    """The point whose image ``image`` is (``v:a4`` → ``A4``); the pole stands for ``point``."""
    label = T.label_of(image)
    return point if label in ("p", "π") else label[:1].upper() + label[1:]


def rate_equation(res, link: str, i: int, lang: Language) -> str | None:
    """ω (velocity plan) or ε (acceleration plan) of ``link`` with its numbers, TeX."""
    k = res.kind[0]
    fig = res.plan.figures[k].get(link)
    rates = res.omegas if k == "v" else res.epsilons
    if link not in rates:
        return None
    value = float(rates[link][i])
    sym = (r"\omega_{" if k == "v" else r"\varepsilon_{") + link + "}"
    unit = txt(("рад/с" if lang in ("ru", "uk") else "rad/s") + ("" if k == "v" else "²"))
    if link == res.plan.mechanism.crank.link or fig is None:
        return rf"{sym} = {num(abs(value), lang)}\ {unit}"
    l = _length(res.ctx, fig.p1, fig.p2, i)
    points = _image_point(fig.img2, fig.p2) + _image_point(fig.img1, fig.p1)  # A4O3: the point the plan found
    if k == "v":
        rel = abs(res.values[fig.img2][i] - res.values[fig.img1][i]) * res.ctx.mu["v"]
        top = rf"V_{{{chain(points)}}}"
    else:
        rel = abs(value) * l
        top = rf"a^{{t}}_{{{chain(points)}}}"
    return (rf"{sym} = \frac{{{top}}}{{l_{{{chain(fig.p1 + fig.p2)}}}}} = \frac{{{num(rel, lang)}}}"
            rf"{{{num(l, lang)}}} = {num(abs(value), lang)}\ {unit}")
