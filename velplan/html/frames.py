"""The page's data: the scheme and both plans at every position, as records, read off a study.

Nothing is solved or constructed here: the positions, the exact plans (at one scale for the
whole turn, so that the slider moves them smoothly about a fixed pole) and the drafted plans
all come from a `velplan.study.Study`; the views draw them (`scheme_steps`, `plan_steps`,
`letters_to_place`) and `velplan.html.records` turns their primitives into compact records.

Records the scheme shares between positions (guides, supports that do not move) are stored
once in ``shared`` and referred to by their index.
"""

from __future__ import annotations

import math
import re

import numpy as np

from velplan.analysis.numbering import position_index, position_number
from velplan.options import Language
from velplan.plans.drafting import Drafting
from velplan.plans.engine import PlanResult
from velplan.plans.steps import Intersect, LayOff, Similar
from velplan.plans.text import label_of
from velplan.render.scene import Polyline
from velplan.render.style import SheetStyle
from velplan.study import Study
from velplan.html.letters import capsules, place_letters
from velplan.html.records import UNITS_PER_MM, encode, extent, round_sig
from velplan.html.scheme import draw_together
from velplan.html.text import templates
from velplan.views.base import eskd_scales, scale_mark, scale_text, subscript, unit
from velplan.views.mechanism import extent_m, scheme_steps, trajectory_points
from velplan.views.plan import letters_to_place, plan_steps
from velplan.views.steps import readable as _readable

#: The scheme is drawn at the largest ESKD scale that keeps it within this size, mm.
SCHEME_MM = 170.0
#: Positions, besides the drawn one, that the scheme view looks at to place its supports and
#: labels (the same for every drawn position, so they do not jump as the crank turns).
REFERENCE_POSITIONS = 24
#: A plan is shown in a frame about its own images at each position, no smaller than this
#: each way, mm: a small plan keeps the size a sheet gives it, centred (near a dead point a
#: plan shrinks to its pole), a large one is fitted to the panel.
SMALLEST_FRAME_MM = 110.0
#: Decimals of the crank angle, degrees.
PHI_DECIMALS = 2


def readable(sentence: str) -> str:
    """`velplan.views.steps.readable` for the page: whole indices keep the sheets' marks
    (``v_{A4A}``), which the page's script sets as ``<sub>`` (``v<sub>A4A</sub>``), as the
    sheets set them below the line."""
    return _readable(sentence)


def _centre_marks(study: Study, i: int, view, mu_l: float) -> list:
    """The instant centres of position ``i`` found by Kennedy lines (`Study.centres`), on the
    scheme ``view``."""
    from velplan.views.centres import centre_marks

    return centre_marks(study.centres(position_number(i), mu_l=mu_l), view.at(0.0, 0.0), top_mm=2.0)


def scheme_scale(study: Study) -> float:
    """μl of the scheme, m/mm: the largest ESKD scale that keeps it within `SCHEME_MM`."""
    fine = study.turn.take(slice(None, None, 3))
    wx, wy = extent_m(study.mechanism, study.kinematics, fine)
    return next((m for m in eskd_scales() if max(wx, wy) / m <= SCHEME_MM), eskd_scales()[-1])


def scheme_records(study: Study, positions: list[int], lang: Language, style: SheetStyle, *,
                   centres: bool = False) -> dict[int, list[list]]:
    """The scheme's records at each of the `positions` (numbers 1…n of the study's, where it
    assembles), by position number: each position's drawing (the scheme's own, `scheme_steps`,
    at `scheme_scale`), the letters of all placed together. A position's records do not depend
    on the others drawn with it."""
    mech, kin = study.mechanism, study.kinematics
    fine = study.turn.take(slice(None, None, 3))
    mu_l = scheme_scale(study)
    n = len(kin)
    reference = sorted({int(round(k * n / REFERENCE_POSITIONS)) % n for k in range(REFERENCE_POSITIONS)})
    indices = [position_index(p, n) for p in positions]
    steps = []
    for i in indices:
        idx = sorted(set(reference) | {i})
        steps.append(scheme_steps(mech, kin=kin.take(idx), fine=fine, mu_l=mu_l, n=len(idx),
                                  thick=position_number(idx.index(i)), lang=lang, single=True, title=False))
    out = {}
    known: dict = {}  # (primitive, origin) → its records: what every position draws alike is encoded once
    for i, view in zip(indices, draw_together(steps)):
        drawn = view.primitives + (tuple(_centre_marks(study, i, view, mu_l)) if centres else ())
        out[position_number(i)] = [r for p in drawn
                  for r in (known.get((p, view.origin)) or known.setdefault((p, view.origin),
                                                                          encode(p, style, view.origin)))]
    return out


def scheme_frames(study: Study, lang: Language, style: SheetStyle, *, centres: bool = False,
                  drawn: dict[int, list[list]] | None = None) -> dict:
    """The scheme at every position: ``under`` (trajectories, drawn first), ``shared`` records,
    ``frames`` (per position: shared indices and own records), ``box`` and ``mu_l``; with
    ``centres``, each position's instant centres found by Kennedy lines marked on it. The
    positions in `drawn` (`scheme_records` of them, by position number 1…n) are taken as
    drawn there."""
    mech, kin = study.mechanism, study.kinematics
    fine = study.turn.take(slice(None, None, 3))
    mu_l = scheme_scale(study)
    under = []
    for name in trajectory_points(mech):
        path = fine.position(name)
        path = path[np.all(np.isfinite(path), axis=1)]
        if len(path) >= 2 and np.ptp(path, axis=0).max() / mu_l > 0.5:
            under += encode(Polyline(path / mu_l, "trajectory", "thin"), style)
    n = len(kin)
    given = drawn or {}
    per_position: list[list[list] | None] = [None] * n
    numbers = [position_number(i) for i in range(n) if kin.valid[i]]
    here = scheme_records(study, [p for p in numbers if p not in given], lang, style, centres=centres)
    for number, own in (*given.items(), *here.items()):
        per_position[position_index(number, n)] = own
    # a record drawn at two positions or more is stored once (a record is a flat list of scalars)
    keys = [[tuple(r) for r in recs or ()] for recs in per_position]
    count: dict[tuple, int] = {}
    for frame_keys in keys:
        for key in set(frame_keys):
            count[key] = count.get(key, 0) + 1
    shared: list[list] = []
    where: dict[tuple, int] = {}
    frames = []
    for recs, frame_keys in zip(per_position, keys):
        frame = []
        for r, key in zip(recs or (), frame_keys):
            if count[key] > 1:
                if key not in where:
                    where[key] = len(shared)
                    shared.append(r)
                frame.append(where[key])
            else:
                frame.append(r)
        frames.append(frame)
    box = extent(under + shared + [r for recs in per_position for r in recs or ()])
    return {"mu_l": mu_l, "scale": scale_text("μl", mu_l, "m/mm", lang) +
            f"  ({scale_mark(mu_l, lang)})",
            "under": under, "shared": shared, "frames": frames, "box": _padded(box)}


def _padded(box, pad_mm: float = 4.0) -> list[int]:
    """A record-units box as an SVG viewBox [x, y, width, height], with a margin."""
    p = int(pad_mm * 100)
    x0, y0, x1, y1 = box
    return [x0 - p, y0 - p, x1 - x0 + 2 * p, y1 - y0 + 2 * p]


def _at_least(box, size: int) -> tuple[int, int, int, int]:
    """`box` (record units) widened about its centre to at least `size` each way."""
    x0, y0, x1, y1 = box
    gx, gy = max(0, size - (x1 - x0)) // 2, max(0, size - (y1 - y0)) // 2
    return (x0 - gx, y0 - gy, x1 + gx, y1 + gy)


# -- plans --------------------------------------------------------------------------------------


def _rows(res: PlanResult) -> list[list[tuple[str, str, str]]]:
    """Per construction step of `res`: the rows of values it fixes, ``(symbol, what, name)``
    with ``what`` "component" (a named component) or "point" (a point's absolute vector)."""
    k = res.kind[0]
    sym = "V" if k == "v" else "a"
    steps = [s for s in res.steps if s.target.startswith(k + ":")]
    points: dict[str, list[str]] = {}
    for p, t in res.plan.images[k].items():
        points.setdefault(t, []).append(p)
    out = []
    for s in steps:
        rows: list[tuple[str, str, str]] = []
        if isinstance(s, (LayOff, Intersect)):
            rows += [(name, "component", name) for name, (_, _, target) in res.ctx.components.items()
                     if target == s.target]
        if isinstance(s, (Intersect, Similar)):
            names = {r[0] for r in rows}
            rows += [(f"{sym}_{p}", "point", p) for p in points.get(s.target, ())
                     if f"{sym}_{p}" not in names and p in res.kin.point_index]
        out.append(rows)
    return out


def _magnitude(res: PlanResult, what: str, name: str, i: int) -> float:
    if what == "component":
        return float(res.components[name][1][i])
    return float(np.hypot(*res.vectors[name][i]))


def _analytic(res: PlanResult, what: str, name: str, i: int) -> float:
    """The solver's |V| or |a| of a point (a component named after a point's absolute vector
    too); other components as the exact construction computes them, from the solver's ω and
    positions."""
    kin = res.kin
    ref = kin.velocities if res.kind == "velocity" else kin.accelerations
    point = name if what == "point" else re.fullmatch(r"[Va]_(\w+)", name)
    if point is not None:
        p = point if isinstance(point, str) else point.group(1)
        if p in kin.point_index:
            return float(np.hypot(*ref[res.index[i], kin.point_index[p]]))
    return _magnitude(res, what, name, i)


def _quantized(x: float, quantum: float, digits: int) -> float | None:
    """`x` to `digits` significant figures and to a multiple of `quantum` (None if not finite)."""
    if not math.isfinite(x):
        return None
    return round_sig(round(x / quantum) * quantum, digits)


def plan_frames(study: Study, kind: str, lang: Language, style: SheetStyle, *, scale_v: float,
                scale_a: float, drafting: Drafting) -> dict:
    """One plan at every position, drawn at μv = `scale_v` ((m/s)/mm) and μa = `scale_a`
    ((m/s²)/mm): its records (each tagged with the construction step that draws it), the
    worked-solution sentences as templates, and per step the analytic values and the
    drafting errors of what the step fixes (the drafted plan drawn at `drafting` precision)."""
    k = kind[0]
    exact = study.plan(kind, scale_v=scale_v, scale_a=scale_a)
    drafted = study.plan(kind, drafting=drafting, scale_v=scale_v, scale_a=scale_a if k == "a" else None)
    kin = study.kinematics
    rows = _rows(exact)
    steps, n = len(rows), len(kin)
    largest = kin.largest(kind, slice(None))
    # values below a millionth of the largest are round-off: written as 0
    quantum = 10.0 ** (math.floor(math.log10(largest)) - 6) if largest > 0 else 1.0
    items: list[list | None] = []
    sentences: list[list[str | None]] = [[] for _ in rows]
    values: list[list | None] = []
    drawn = _plan_records([i for i in range(n) if kin.valid[i]], exact, lang, style)
    for i in range(n):
        if not kin.valid[i]:
            items.append(None)
            values.append(None)
            for col in sentences:
                col.append(None)
            continue
        recs, said = drawn[i]
        items.append(recs)
        for col, sentence in zip(sentences, said):
            col.append(sentence)
        vals = []
        for _, what, name in (row for step_rows in rows for row in step_rows):
            a = _analytic(exact, what, name, i)
            d = _magnitude(drafted, what, name, i)
            vals += [_quantized(a, quantum, 5), _quantized(d - a, quantum, 3)]
        values.append(vals)
    tpl, per_step = zip(*(templates(col) for col in sentences)) if steps else ((), ())
    pole = [[2, 0, 0, 0, 0, 0]]  # the pole at (0, 0) is in every frame
    box = extent([r[1:] for recs in items for r in recs or ()] + pole)
    least = int(SMALLEST_FRAME_MM * UNITS_PER_MM)
    frames = [None if recs is None else _padded(_at_least(extent([r[1:] for r in recs] + pole), least))
              for recs in items]
    unit_key = "m/s" if k == "v" else "m/s²"
    symbol, scale_unit = ("μv", "(m/s)/mm") if k == "v" else ("μa", "(m/s²)/mm")
    return {
        "kind": k, "steps": steps, "mu": exact.scale,
        "scale": scale_text(symbol, exact.scale, scale_unit, lang),
        "unit": unit(unit_key, lang),
        "rows": [[readable(sym) for sym, _, _ in r] for r in rows],
        "items": items, "tpl": list(tpl),
        # per position: per step [template, numbers…]
        "sentences": [[per_step[j][i] for j in range(steps)] for i in range(n)],
        "values": values, "box": _padded(box), "frames": frames,
        # below this analytic value a relative error means nothing
        "floor": round_sig(1e-3 * largest, 3),
    }


def _plan_records(positions: list[int], res: PlanResult, lang: Language,
                  style: SheetStyle) -> dict[int, tuple[list, list[str]]]:
    """The plan at each of the position indices `positions`: records ``[step, *record]``
    (letters with the step that fixes their first image) and the sentence of each step,
    written as by hand. The letters of all positions are placed together (`place_letters`)."""
    work = []
    for i in positions:
        drawings = plan_steps(res, position_number(i), lang=lang)
        first: dict[str, int] = {}
        recs: list[list] = []
        for j, d in enumerate(drawings, 1):
            for t in d.images:
                first.setdefault(subscript(label_of(t)), j)
            recs += [[j, *r] for p in d.items for r in encode(p, style)]
        texts, _, lines, circles = letters_to_place(res, position_number(i), drawings)
        work.append((drawings, first, recs, texts, capsules(lines, circles)))
    letters = place_letters([(texts, caps) for *_, texts, caps in work])
    out = {}
    for i, (drawings, first, recs, _, _), placed in zip(positions, work, letters):
        last = len(drawings)
        for t in placed:
            j = min((first.get(name, last) for name in t.text.split(", ")), default=last)
            recs += [[j, *r] for r in encode(t, style)]
        out[i] = (recs, [readable(d.sentence) for d in drawings])
    return out


def rates(study: Study) -> dict:
    """ω (rad/s) and ε (rad/s²) of every link at every position, read off the exact plans."""
    rv = study.plan("velocity")
    ra = study.plan("acceleration")
    out = {}
    crank = study.mechanism.crank.link
    for key, values in (("omega", rv.omegas), ("epsilon", ra.epsilons)):
        # links that do not turn (a slider) are left out; the crank is always there
        names = [m for m in values if m == crank or np.nanmax(np.abs(values[m]), initial=0.0) > 0]
        largest = max([float(np.nanmax(np.abs(values[m]), initial=0.0)) for m in names] + [0.0])
        quantum = 10.0 ** (math.floor(math.log10(largest)) - 6) if largest > 0 else 1.0
        out[key] = {"links": names,
                    "values": [[_quantized(float(values[m][i]), quantum, 5) for m in names]
                               for i in range(len(rv.index))]}
    return out


def phi_degrees(study: Study) -> list[float]:
    """Crank angles of the positions, degrees in [0, 360), to `PHI_DECIMALS`."""
    return [round(float(x) % 360.0, PHI_DECIMALS) % 360.0 + 0.0 for x in np.degrees(study.phi)]
