"""The construction of one plan, step by step, for teaching: one figure per step.

Each figure shows the mechanism in the position (thick, alone) on the left and the plan as
far as it is built on the right, at the same scale and place in every figure, so that the
figures can be flipped through. What the step adds is drawn thick (its vectors and its
line); what earlier steps drew stays thin. Under the drawing the step's sentence of the
worked solution is written ("Через точку a проводим прямую ∥ O3A …").
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field, replace

from typing import Mapping

import numpy as np

from velplan.analysis.numbering import position_index
from velplan.analysis.solver import Kinematics
from velplan.errors import VelplanError
from velplan.mechanism.model import Mechanism
from velplan.options import Language
from velplan.plans.engine import POSITION_PLAN_MM, PlanResult
from velplan.render.i18n import label
from velplan.render.layout import fit_text, label_box
from velplan.views.letters import NEAR_MM
from velplan.views.mechanism import MechanismSizes, extent_m, mechanism_view
from velplan.views.plan import (
    image_letters, plan_steps, plan_title, plan_view)
from velplan.render.scene import Arrow, Polygon, Polyline, Scene, Text
from velplan.notation import digits_down, indexed, subscript
from velplan.plans.text import Sentence, Sym, label_of
from velplan.views.base import eskd_scales, shift

_MARGIN = 10.0
_SENTENCE_H = 26.0


@dataclass(frozen=True)
class StepFigure:
    """One step: its number (1-based), the plan kind ("v"/"a"), sentence and scene; `anchors`:
    each point's letter as written ("B₂", "b₂", "π") → where its points lie on the figure, mm
    (the scheme's points and the images the step has drawn)."""

    number: int
    kind: str
    sentence: str
    scene: Scene
    anchors: Mapping[str, tuple[tuple[float, float], ...]] = field(default_factory=dict)


def step_figures(mech: Mechanism, kin: Kinematics, plans: Mapping[str, PlanResult], position: int, *,
                 kind: str = "both", lang: Language = "ru", plan_mm: float = POSITION_PLAN_MM) -> list[StepFigure]:
    """Figures of every construction step of the plans at `position` (1-based).

    Parameters
    ----------
    kin : Kinematics
        The mechanism solved at its positions.
    plans : mapping
        ``"velocity"`` (and ``"acceleration"``) → the exact plan at those positions.
    kind : {"velocity", "acceleration", "both"}
        Which plans; "both" gives the velocity steps, then the acceleration steps.
    plan_mm : float
        Size the plan is drawn to (its scale is the standard one that keeps it within).
    """
    n = len(kin)
    i = position_index(position, n)
    kinds = {"velocity": ("velocity",), "acceleration": ("acceleration",),
             "both": ("velocity", "acceleration")}.get(kind)
    if kinds is None:
        raise VelplanError(f"unknown plan kind {kind!r}; known kinds: velocity, acceleration, "
                           "both")
    if not kin.valid[i]:
        raise VelplanError(f"{mech.name} cannot be assembled at position {position}")
    # the mechanism alone in the position, about 120 mm across
    wx, wy = extent_m(mech, kin, kin)
    mu_l = next((m for m in eskd_scales() if max(wx, wy) / m <= 170.0), eskd_scales()[-1])
    mview = mechanism_view(mech, mu_l=mu_l, n=n, thick=position, lang=lang, kin=kin, fine=kin,
                           sizes=MechanismSizes(3.5, 3.5, 2.5), single=True, special=True)
    figures: list[StepFigure] = []
    series = []
    for kd in kinds:
        res0 = plans[kd]
        res = res0.at_scale(res0.position_scale(position, plan_mm))
        series.append((kd, res, plan_view(res, position, lang=lang), plan_steps(res, position, lang=lang)))
    # one page size for the whole series, velocity and acceleration alike
    width = max([_MARGIN * 3 + mview.width_mm + full.width_mm for _, _, full, _ in series] + [297.0])
    height = max([_MARGIN * 2 + max(mview.height_mm, full.height_mm) + _SENTENCE_H
                  for _, _, full, _ in series] + [210.0])
    scheme = mview.at(_MARGIN, height - _MARGIN - mview.height_mm)
    points = [(subscript(q), scheme.to_sheet(kin.position(q)[i])) for q in kin.point_index]
    for kd, res, full, drawings in series:
        px = _MARGIN * 2 + mview.width_mm
        py = height - _MARGIN - full.height_mm
        total = len(drawings)
        for k in range(1, total + 1):
            items = list(scheme.primitives)
            items += [shift(p, px, py) for p in partial_plan(res, position, k, full=full, drawings=drawings,
                                                             lang=lang)]
            sentence = f"{label('step', lang)} {k}/{total}. {readable(drawings[k - 1].sentence)}"
            box = (_MARGIN, _MARGIN, width - _MARGIN, _MARGIN + _SENTENCE_H - 4.0)
            items += fit_text(sentence, box, layer="labels", size_mm=5.0, anchor="start")
            items.append(Polygon([(0, 0), (width, 0), (width, height), (0, height)], "frame",
                                 "thin"))
            images = [(subscript(label_of(t)), complex(res.values[t][res.index_of(position)])
                       + complex(px + full.origin[0], py + full.origin[1])) for d in drawings[:k] for t in d.images]
            figures.append(StepFigure(k, kd[0], drawings[k - 1].sentence, Scene(tuple(items), width, height),
                                      _anchors(points + [(n, (z.real, z.imag)) for n, z in images])))
    return figures


def _anchors(named) -> dict[str, tuple[tuple[float, float], ...]]:
    """(letter, (x, y)) pairs → letter → its finite points, mm."""
    out: dict[str, list] = {}
    for name, xy in named:
        if np.all(np.isfinite(xy)):
            out.setdefault(name, []).append((float(xy[0]), float(xy[1])))
    return {k: tuple(v) for k, v in out.items()}


_SYMBOL = re.compile(r"([VaRFωε])([ⁿᵗᵏʳ]?)_([A-Za-zА-Яа-яЁё0-9]+)")
_INDEX = re.compile(r"(?<=[A-Za-zωεπ])(\d+)")


def readable(sentence: str) -> str:
    """A worked-solution sentence as it is written by hand: ``V_A4A`` → ``v_{A4A}`` (v with
    the whole index "A4A" below), ``aⁿ_A4O3`` → ``aⁿ_{A4O3}``, ``O3A`` → ``O₃A``, ``ak1`` →
    ``ak₁`` (velocities in lowercase v; the digits of point, image and link names outside a
    symbol's index as subscripts). A `Sentence` sets exactly the symbols it marks (`written`);
    plain text has its symbols found by their look.

    >>> from velplan.plans.text import pts, rate, text, vector
    >>> readable(text(pts("K3"), " lies on it, so ", vector("V_K3"), " = ", vector("V_BA"), " + ", vector("V_K3B")))
    'K₃ lies on it, so v_{K3} = v_{BA} + v_{K3B}'
    """
    if isinstance(sentence, Sentence):
        return "".join(written(x) if isinstance(x, Sym) else x for x in sentence.parts)
    parts = _SYMBOL.split(sentence)  # text, (letter, mark, index), text, …
    out = [_INDEX.sub(lambda m: digits_down(m.group(1)), parts[0])]
    for k in range(1, len(parts), 4):
        letter, mark, index, rest = parts[k:k + 4]
        out.append(("v" if letter == "V" else letter) + mark + "_{" + index + "}")
        out.append(_INDEX.sub(lambda m: digits_down(m.group(1)), rest))
    return "".join(out)


def written(sym: Sym) -> str:
    """A symbol a sentence marks, as the drawings set it: a vector's letter (v for V) and mark
    with its whole index below, the digits of point names and of ω, ε as subscripts.

    >>> from velplan.plans.text import pts, rate, vector
    >>> written(vector("aⁿ_K3B")), written(vector("V_отн")), written(pts("O3A")), written(rate("ω", "1"))
    ('aⁿ_{K3B}', 'v_{отн}', 'O₃A', 'ω₁')
    """
    if sym.kind != "vector":
        return digits_down(sym.text)
    head, _, index = sym.text.partition("_")
    return indexed("v" + head[1:] if head.startswith("V") else head, index)


def partial_plan(res, position: int, k: int, *, full, drawings, lang: Language) -> list:
    """The plan at position number ``position`` as far as construction step ``k`` (1-based),
    in the coordinates of the full plan view ``full``: the step's own vectors and line thick,
    earlier ones thin, the image letters placed so far, and the plan's title. ``drawings`` are
    `plan_steps` of the plan."""
    ox, oy = full.origin
    items = [shift(_emphasis(p, j == k - 1), ox, oy) for j, d in enumerate(drawings[:k]) for p in d.items]
    heads = [p for p in full.primitives if isinstance(p, Text) and p.text in plan_title(res, position, lang)]
    avoid = [label_box(shift(t, -ox, -oy)) for t in heads]  # the letters keep off the title and μ
    items += [shift(t, ox, oy) for t in image_letters(res, position, drawings, upto=k, avoid=avoid, leaders=True,
                                                                 near_mm=NEAR_MM)]
    return items + heads


def _emphasis(p, new: bool):
    """The step's own vectors and lines thick; earlier ones thin."""
    if isinstance(p, (Arrow, Polyline)):
        if new:
            return replace(p, line="thick")
        return replace(p, line="thin") if p.line == "thick" else p
    return p
