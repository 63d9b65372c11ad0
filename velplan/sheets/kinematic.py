"""The drawing sheet of a kinematic analysis: frame and title block, the scheme in its
positions, velocity and acceleration plans, kinematic diagrams and the table of transfer
functions, each at a standard scale, placed without overlap.

The layout follows the Russian course sheet (METHOD.md §7): the scheme in the upper left,
the plans to its right in a grid (one row per kind, one column per chosen position, or the
transpose when that gives larger plans), the diagrams along the bottom and the table above
the title block. A scheme too large for the top band at every legible scale (a jaw crusher
on A3) takes the whole height left of the table and the title block instead, the plans to
its right and the diagrams in a free corner if one is left. Each view takes the largest drawing (the smallest μ of the standard
series) that fits its region; a view that cannot be drawn legibly at any standard scale
raises :class:`~velplan.errors.ScaleError` with a one-line message.

Where the diagrams find no room at their full size (A3), their compact block
(`velplan.views.diagram_compact`, every curve 30 mm high at least) goes to a free spot, or
beside the plans fitted again smaller where they stay legible, or beside the first position's
plans alone, or under the scheme with the table moved back over the title block and the plans
fitted again right of the scheme above it (the triad press). A plan crowded round its pole gets an enlarged detail at a stated scale
(`velplan.views.plan_detail`) in the room left.

Examples
--------
>>> sheet = build_sheet("crank-slider", fmt="A3", lang="en")
>>> sheet.scales["mu_l"], {"mechanism", "table"} <= set(sheet.views)
(0.002, True)
"""

from __future__ import annotations

import math
from functools import partial
from itertools import islice
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Mapping, Sequence

import numpy as np

from velplan.analysis.numbering import position_index, position_number
from velplan.errors import ScaleError, VelplanError
from velplan.mechanism.model import Mechanism
from velplan.options import Format, FrameStyle, KINEMATIC_SHEET_KINDS, Language, PlanKind, SheetKind
from velplan.plans import standard_scale
from velplan.plans.engine import PlanResult
from velplan.render.layout import crossed_letters
from velplan.render.style import SheetStyle
from velplan.sheets.frame import TitleInfo
from velplan.sheets.layout import (
    GOOD_PLAN_MM, MIN_CRANK_MM, MIN_DIAGRAM_MM, MIN_ORDINATE_MM, MIN_PLAN_MM, free_spot, ink_boxes, write_outputs)
from velplan.sheets.skeleton import (
    NARROWER_TABLE, ComposedSheet, Request, check_plan_positions, compose, fill_bottom_band, fit_table,
    sheet_request, sheet_text, title_with_scale)
from velplan.sheets.solver import EPS_MM, Trials, fits, largest_fitting
from velplan.study import Study
from velplan.views.base import PlacedView, View, eskd_scales, ratio_text
from velplan.views.diagram import Arrangement, DiagramSizes, diagram_view, least_row_width
from velplan.views.mechanism import extent_m, least_scheme_size, mechanism_view
from velplan.views.plan import (
    MIN_VECTOR_MM, extent_mm, labelled_vectors, least_plan_size, plan_steps, plan_view)
from velplan.views.table import table_view

if TYPE_CHECKING:  # the compact block's module is loaded where a sheet draws one
    from velplan.views.diagram_compact import Form

KINDS: tuple[str, ...] = KINEMATIC_SHEET_KINDS
"""The plan kinds of the kinematic sheet."""


@dataclass(frozen=True)
class Sheet(ComposedSheet):
    """A composed kinematic sheet (the attributes of `ComposedSheet`, and these).

    Attributes
    ----------
    views : Mapping[str, PlacedView]
        ``"mechanism"``, ``"plan-v-K"``, ``"plan-a-K"``, ``"table"``, ``"diagrams"``,
        ``"data"``, ``"readings"``, ``"structure"``, and ``"detail-a-K"`` (an enlarged detail
        of a plan crowded round its pole, `velplan.views.plan_detail`) where there is room.
    scales : Mapping[str, float]
        ``"mu_l"`` (m/mm) of the scheme, and μ of each plan by view name (``"plan-v-4"``:
        (m/s)/mm, ``"plan-a-4"``: (m/s²)/mm), as drawn.
    plans : Mapping[str, PlanResult]
        View name → the plan it draws (at every position, at the view's scale).
    plan_index : Mapping[str, int]
        View name → the index of its position in that plan's positions.
    positions : tuple of int
        Positions (1-based) whose plans are drawn.
    n : int
        Number of positions of the scheme.
    zones : Mapping[str, tuple]
        View name → the zone of the sheet it was fitted to (sheet mm): a plan's grid cell,
        the scheme's share of the top band (or, for a scheme too tall for it, the whole
        height of the drawing area left of the table and the title block).
    """

    plans: Mapping[str, PlanResult]
    plan_index: Mapping[str, int]
    positions: tuple[int, ...]
    n: int
    zones: Mapping[str, tuple] = field(default_factory=lambda: MappingProxyType({}))


def default_plan_positions(res: PlanResult) -> tuple[int, ...]:
    """Two positions worth drawing plans for: one in each half of the turn (the working and
    the return stroke), each the one whose velocity plan shows the most distinct images with
    well-conditioned intersections, near a quarter of the half when that is a tie.

    Positions where the plan collapses (a rod translating for an instant, an extreme
    position) teach nothing and are avoided.
    """
    n = len(res.index)
    if n < 4:
        return (min(2, n),)
    ground = set(res.plan.mechanism.ground_points)
    names = [p for p in res.vectors if p not in ground]
    scores = []
    for i in range(n):
        z = np.array([complex(*res.image(p)[i]) for p in names])
        z = z[np.isfinite(z)]
        spread = max(float(np.max(np.abs(z))) if z.size else 0.0, 1e-12)
        distinct: list[complex] = [0j]
        for w in z:
            if all(abs(w - u) > 0.04 * spread for u in distinct):
                distinct.append(w)
        cond = min([float(c[i]) for c in res.conditions.values()] or [1.0])
        scores.append(len(distinct) + min(cond, 0.5))
    half = n // 2
    picks = []
    for lo, hi in ((0, half), (half, n)):
        quarter = (lo + hi) / 2.0
        best = max(range(lo, hi),
                   key=lambda i: (round(scores[i], 6), -abs(i - quarter), -i))
        picks.append(position_number(best))
    return tuple(picks)


def default_title(mech, lang: Language, fmt: str, scale: str, frame_style: str) -> TitleInfo:
    """Title block of the kinematic sheet: the first document of the course work."""
    from velplan.sheets.documents import default_title_of

    return default_title_of("both", mech, lang, scale)


class _Drawings:
    """The trial drawings of one kinematic sheet, each drawn once however many layouts try
    it: the scheme by μl, a plan by (kind, position, μ) → (result at μ, view) and its
    construction (``steps``, shared by the plan's view and its least size), the kinematic
    diagrams by (arrangement, φ axis mm, height mm)."""

    def __init__(self, req: Request, chosen: Sequence[int]):
        self.req, self.thick, self.chosen = req, chosen[0], tuple(chosen)
        study = req.study
        self.fine = study.turn.take(slice(None, None, 3))  # 240 steps: the scheme's trajectories
        # the extreme positions and the other positions whose plans are drawn: bold
        self.bold = tuple(dict.fromkeys(_extreme_positions(study) + tuple(chosen[1:])))
        self.scheme = Trials(self._scheme)
        self.plan = Trials(self._plan)
        self.steps = Trials(self._steps)
        self.least_plan = Trials(self._least_plan)  # a plan's construction and title alone, mm
        self.diagrams = Trials(self._diagrams)
        self.compact = Trials(self._compact)

    def _scheme(self, mu: float) -> View:
        study, req = self.req.study, self.req
        return mechanism_view(study.mechanism, mu_l=mu, n=study.n, thick=self.thick, lang=req.lang,
                              sizes=req.sizes.mechanism, kin=study.kinematics, fine=self.fine,
                              extreme=study.other_extreme, bold=self.bold, special=self.chosen, plans=self.chosen)

    def least_scheme(self, mu: float) -> tuple[float, float]:
        """A lower bound of the size of ``scheme(mu)``, mm (`least_scheme_size`), without drawing it."""
        study, req = self.req.study, self.req
        return least_scheme_size(study.mechanism, study.kinematics, mu_l=mu, thick=self.thick,
                                 sizes=req.sizes.mechanism)

    def _steps(self, kind: PlanKind, number: int, mu: float):
        res = self.req.study.plan(kind).at_scale(mu)
        return res, plan_steps(res, number, lang=self.req.lang)

    def _plan(self, kind: PlanKind, number: int, mu: float) -> tuple[PlanResult, View]:
        res, steps = self.steps(kind, number, mu)
        return res, plan_view(res, number, lang=self.req.lang, sizes=self.req.sizes.plan, steps=steps)

    def least_width(self, arrangement: Arrangement, length: float, height: float) -> float | None:
        """A lower bound of the width of ``diagrams(arrangement, length, height)``, mm, known
        without drawing for a row (`least_row_width`); None otherwise."""
        if arrangement != "row":
            return None
        study = self.req.study
        return least_row_width(study.diagrams, length_mm=length, height_mm=height, lang=self.req.lang,
                               omega=study.mechanism.crank.omega, sizes=self.req.sizes.diagram)

    def plan_fits(self, kind: PlanKind, number: int, mu: float, w: float, h: float) -> bool:
        """Whether the plan at μ may fit w × h mm: False where its construction and title
        alone (`least_plan_size`) exceed it, found without drawing its letters."""
        lw, lh = self.least_plan(kind, number, mu)
        return lw <= w + EPS_MM and lh <= h + EPS_MM

    def _least_plan(self, kind: PlanKind, number: int, mu: float) -> tuple[float, float]:
        res, steps = self.steps(kind, number, mu)
        return least_plan_size(res, number, steps, lang=self.req.lang, sizes=self.req.sizes.plan)

    def _diagrams(self, arrangement: Arrangement, length: float, height: float) -> View:
        study = self.req.study
        return diagram_view(study.diagrams, length_mm=length, height_mm=height, lang=self.req.lang,
                            omega=study.mechanism.crank.omega, arrangement=arrangement,
                            sizes=self.req.sizes.diagram)

    def _compact(self, form: Form, length: float) -> View:
        study, sizes = self.req.study, self.req.sizes.diagram
        # the compact block is drawn where the sheet is small: its text at the ESKD minimum at least
        sizes = DiagramSizes(max(sizes.title_mm, MIN_TEXT_MM), max(sizes.label_mm, MIN_TEXT_MM))
        from velplan.views.diagram_compact import compact_diagram_view

        return compact_diagram_view(study.diagrams, length_mm=length, min_range_mm=MIN_ORDINATE_MM,
                                    lang=self.req.lang, omega=study.mechanism.crank.omega, form=form,
                                    sizes=sizes)


def build_sheet(mech: Study | Mechanism | str | Path, *, n: int = 12, plans: Sequence[int] | None = None,
                kind: SheetKind = "both", fmt: Format = "A1", lang: Language = "ru",
                frame_style: FrameStyle | None = None, info: TitleInfo | None = None,
                diagrams: bool | None = None, table: bool = True,
                style: SheetStyle | None = None, data: bool = True, centres: Sequence[int] = (),
                scale_per_plan: bool = False, structure: bool | None = None) -> Sheet:
    """Compose the kinematic-analysis sheet of `mech`.

    Parameters
    ----------
    mech : Study, Mechanism or str
        The study to draw, or a mechanism / bundled example name / TOML path to study.
    n : int
        Number of positions of the scheme, the table and the diagrams (a study brings its own).
    plans : sequence of int, optional
        Positions (1-based) whose plans are drawn; two by default
        (:func:`default_plan_positions`), or the first of them alone where the two do not
        fit beside the scheme (a large scheme on A3) or leave the diagrams no room. The first
        one is drawn thick in the scheme.
    kind : {"velocity", "acceleration", "both"}
        Which plans.
    fmt : {"A1", "A2", "A3"}
        Sheet format (landscape).
    lang : {"en", "ru", "uk", "zh"}
        Language of every label.
    frame_style : {"eskd", "iso"}, optional
        Title block: ESKD form 1 (default for ru, uk) or the captioned block (en, zh).
    info : TitleInfo, optional
        Title block fields; the scale field is filled with the scheme's scale when empty.
    diagrams : bool or None
        Draw the kinematic diagrams where they fit and the mechanism names an output (None,
        the default): beside the table, or else in the largest free corner left by the
        scheme and the plans, in a row, a grid or a column, or else as a compact block
        (`velplan.views.diagram_compact`: a small sheet) in a free spot, beside the plans
        drawn smaller where they stay legible or under the scheme; the same but raise ScaleError
        where they fit nowhere (True); leave them out (False).
    table : bool
        Draw the table of transfer functions.
    data : bool
        Write the input data and the main results (H, θ, K, the extreme positions), and the
        values read off the drawn plans beside the analytic ones, where the top band has room
        for them (`velplan.views.data`, `velplan.views.readings`).
    centres : sequence of int
        Positions (1-based) whose instant centres found by Kennedy lines are marked on the
        scheme, where they fall on it (`velplan.views.centres.centre_marks`).
    scale_per_plan : bool
        Fit each plan to its cell at its own μ. By default the plans of a kind share one μ
        (the largest of their fits), so that they compare by eye, where every one of them
        stays legible at it (`legible_at`); otherwise each states its own.
    structure : bool or None
        Draw the structural analysis (`velplan.sheets.structure`) where free space is left
        for it legibly once the enlarged details of crowded plans have theirs (None, the
        default: legibility first); before the details, raising ScaleError where there is no
        room (True); leave it out (False).

    Raises
    ------
    ScaleError
        A view cannot be drawn legibly at any standard scale in its part of the sheet.
    VelplanError
        Bad options (unknown format, kind or language, positions out of range).
    """
    req = sheet_request(mech, n=n, fmt=fmt, lang=lang, frame_style=frame_style, style=style)
    study, mech = req.study, req.mechanism
    chosen = _check_options(study, plans, kind, diagrams, centres)
    draw = _Drawings(req, chosen)
    views: dict[str, PlacedView] = {}
    with_diagrams = diagrams is not False and mech.output is not None
    band_top = _bottom_band(req, draw, views, table=table, diagrams=with_diagrams)
    kinds = ("velocity", "acceleration") if kind == "both" else (kind,)
    mview, fitted, chosen, scheme_zone = _roomiest(req, draw, views, chosen, kinds, band_top, table=table,
                                                   fallback=plans is None)
    plan_views, results, cells = fitted
    mview = _without_dropped(draw, mview, chosen)
    if not scale_per_plan:
        plan_views, results = _one_scale_where_legible(req.fmt, draw, plan_views, results, cells)
    views["mechanism"] = mview.at(req.area[0], req.area[3] - mview.height_mm)
    views.update(plan_views)
    if "diagrams" not in views and with_diagrams:
        alone = None if plans is not None or len(chosen) < 2 else partial(
            build_sheet, study, plans=chosen[:1], kind=kind, fmt=fmt, lang=lang, frame_style=frame_style, info=info,
            diagrams=diagrams, table=table, style=style, data=data, centres=centres, scale_per_plan=scale_per_plan,
            structure=structure)
        found = _diagrams_anywhere(req, draw, views, (cells, chosen, kinds), scale_per_plan, alone, bool(diagrams))
        if isinstance(found, Sheet):
            return found
        plan_views, results, cells = found or (plan_views, results, cells)
    index = {name: int(name.rsplit("-", 1)[1]) - 1 for name in results}  # its position in the plan's
    if data:
        _place_notes(req, views, {name: (res, index[name] + 1) for name, res in results.items()}, band_top)
    if structure:  # asked for: before the details, which take the room left
        _place_structure(req, views, required=True)
    _place_details(req, views, results)
    if structure is None:  # by default legibility first: the figure where the details leave room
        _place_structure(req, views, required=False)
    info = title_with_scale(info, lambda s: default_title(mech, lang, fmt, s, req.frame_style),
                            ratio_text(mview.mu, lang))
    return _sheet(req, views, info, mview.mu, (results, index, chosen), dict(cells) | {"mechanism": scheme_zone},
                  centres)


def _sheet(req: Request, views: dict, info: TitleInfo, mu_l: float, plans, zones: dict, centres) -> Sheet:
    """The composed sheet of the placed `views`: ``plans`` are (results, their position indices,
    the positions drawn); the instant centres of `centres` marked on the scheme."""
    results, index, chosen = plans
    order = ["mechanism"] + sorted(k for k in views if k.startswith(("plan-", "detail-"))) + [
        k for k in ("data", "readings", "diagrams", "table", "structure") if k in views]
    scene = compose(req, views, order, info)
    if centres:
        scene = scene.extend(_centre_marks(req.study, centres, views["mechanism"], mu_l))
    return Sheet(req.mechanism, scene, MappingProxyType(dict(views)),
                 MappingProxyType({"mu_l": mu_l} | {k: r.scale for k, r in results.items()}),
                 req.fmt, req.lang, req.frame_style, req.style, info, MappingProxyType(results),
                 MappingProxyType(index), chosen, req.study.n, MappingProxyType(zones))


def _without_dropped(draw: _Drawings, mview, chosen):
    """The scheme with a position dropped from the plans (the first alone fitted) drawn thin
    again, where that keeps its box; else `mview` as it is."""
    extreme = _extreme_positions(draw.req.study)
    if not set(draw.bold) - set(chosen) - set(extreme) and tuple(chosen) == draw.chosen:
        return mview
    draw.bold, draw.chosen = extreme, tuple(chosen)
    redrawn = draw._scheme(mview.mu)
    return redrawn if fits(redrawn, mview.width_mm, mview.height_mm) else mview


def _check_options(study: Study, plans, kind: str, diagrams: bool | None, centres) -> tuple[int, ...]:
    """The positions whose plans are drawn, after checking the kinematic sheet's options."""
    mech = study.mechanism
    if kind not in KINDS:
        raise VelplanError(f"unknown plan kind {kind!r}; known kinds: {', '.join(KINDS)}")
    chosen = check_plan_positions(
        default_plan_positions(study.plan("velocity")) if plans is None else plans, study.n)
    for k in centres:
        try:
            position_index(k, study.n)
        except VelplanError as exc:
            raise VelplanError(f"--centres: {exc}") from None
    if diagrams and mech.output is None:
        raise VelplanError(f"{mech.name} names no output, so it has no kinematic diagrams")
    return chosen


def _bottom_band(req: Request, draw: _Drawings, views: dict, *, table: bool, diagrams: bool,
                 table_left: bool = False) -> float:
    """The table above the title block, the diagrams to their left where they fit (or, with
    `table_left` and no diagrams, the table left of the title block); the band's top, mm."""
    study = req.study
    tview = None
    if table:
        data = study.table
        tview = fit_table(lambda size, width: table_view(data, study.mechanism, lang=req.lang, size_mm=size,
                                                         title_mm=req.sizes.table_title, width_factor=width),
                          req, what=f"table of transfer functions ({study.n} positions)")
    band_top, _ = fill_bottom_band(
        views, req, table_view=tview,
        fit_diagram=(lambda region: _fit_diagrams(req, draw, region)) if diagrams else None,
        diagram_share=0.3, required=False, diagram_name="diagrams", table_left=table_left)
    return band_top


def _roomiest(req: Request, draw: _Drawings, views: dict, chosen, kinds, band_top: float, *, table: bool,
              fallback: bool):
    """`_scheme_and_plans` above the bottom band; where the band has no diagrams, also above
    the table moved left of the title block (a lower band): that one where the first fails, or
    where it draws the same plans with a larger scheme."""
    found, failure = None, ScaleError(f"the plans do not fit {req.fmt} beside the scheme")
    try:
        found = _scheme_and_plans(req, draw, views, chosen, kinds, band_top, fallback=fallback)
    except ScaleError as exc:
        failure = exc
    low: dict = {}
    if "diagrams" not in views and "table" in views:
        low_top = _bottom_band(req, draw, low, table=table, diagrams=False, table_left=True)
    if low.get("table") is None or low["table"].bounds == views["table"].bounds:
        if found is None:
            raise failure
        return found
    try:
        other = _scheme_and_plans(req, draw, low, chosen, kinds, low_top, fallback=fallback)
    except ScaleError:
        if found is None:
            raise failure from None
        return found
    if found is None or (tuple(other[2]) == tuple(found[2]) and other[0].mu < found[0].mu * (1 - 1e-9)):
        views.clear()
        views.update(low)
        return other
    return found


#: The scheme's share of the width of the top band.
SCHEME_WIDTH = 0.62
#: The share of its zone (along the fuller direction) a scheme fills, below which a smaller
#: scheme is drawn only where no scheme of that share leaves the plans room.
SCHEME_SHARE = 0.5


def _scheme_and_plans(req: Request, draw: _Drawings, views: dict, chosen, kinds, band_top: float, *,
                      fallback: bool):
    """(scheme view, (plan views, results, cells), positions drawn, the scheme's zone): the
    largest scheme whose neighbours, the plans, still get vectors of a good length; failing
    that, the scheme that leaves the plans the longest vectors. With `fallback`, the first
    position's plans alone when the positions' plans fit beside no scheme filling
    `SCHEME_SHARE` of its zone. Where nothing fits the top band, the scheme's zone takes the
    whole height left of the table and the title block (`_tall_zone`): the bottom band's
    diagrams give way to it, taken out of `views`."""
    attempts = [chosen] + ([chosen[:1]] if fallback and len(chosen) > 1 else [])
    fx0, _, fx1, fy1 = req.area
    zones = [(_scheme_zone((fx0, band_top + req.gap, fx1, fy1)), band_top), _tall_zone(req, views)]
    failure = None
    for tall, (zone, floor) in enumerate(zones):
        for least in (SCHEME_SHARE, 0.0):
            try:
                best, failure = _pairing(req, draw, attempts, kinds, zone, floor, least, failure)
            except ScaleError as exc:  # no scheme fits the zone
                failure = failure or exc
                break
            if best is not None:
                if tall:
                    views.pop("diagrams", None)
                return best[1:] + (zone,)
    raise failure or ScaleError(f"the plans do not fit {req.fmt} beside the scheme; use a larger --format")


def _tall_zone(req: Request, views: dict) -> tuple[tuple, float]:
    """(zone, the plans' floor) of a scheme as tall as the drawing area, left of the table
    and the title block, with the plans to its right above them (their floor: the top of
    the table or the title block, mm)."""
    fx0, fy0, _, fy1 = req.area
    right = [req.title_block] + ([views["table"].bounds] if "table" in views else [])
    return (fx0, fy0, min(b[0] for b in right) - req.gap, fy1), max(b[3] for b in right)


def _pairing(req: Request, draw: _Drawings, attempts, kinds, zone, floor: float, least: float, failure):
    """(the best (score, scheme, fitted plans, positions) or None, the first ScaleError) of
    the schemes in `zone` (at its upper left) filling at least `least` of it with the plans
    of the first of the `attempts` that fits, the plans above `floor` (mm)."""
    ahead = _past_a_hopeless_scheme(req, draw, attempts[0], kinds, zone, floor, least)
    if ahead is not None:
        return ahead, failure
    best = None
    for attempt in attempts:
        if best is not None:
            break
        for mview in _mechanism_candidates(req, draw, zone):
            if _zone_share(mview, zone) < least:
                continue
            best, good, failure = _plans_beside(req, draw, mview, attempt, kinds, floor, best, failure)
            if good:
                return best, failure
    return best, failure


def _plans_beside(req: Request, draw: _Drawings, mview: View, attempt, kinds, floor: float, best, failure):
    """(best, whether the plans of `attempt` beside the scheme `mview` are good, the first
    ScaleError): the plans fitted right of the scheme, or below it across the sheet, where
    they may beat `best` (score, scheme, fitted plans, positions) or make the scheme good."""
    good = False
    for region in _plan_regions(req, mview.width_mm, mview.height_mm, floor):
        if best is not None and _cannot_change(best[0], good, req, attempt, kinds, region):
            continue
        try:
            score, fitted = _fit_plans(req, draw, attempt, kinds, region)
        except ScaleError as exc:
            failure = failure or exc
            continue
        if best is None or score > best[0]:
            best = (score, mview, fitted, attempt)
        good = good or score >= GOOD_PLAN_MM[req.fmt]
    return best, good, failure


def _plan_regions(req: Request, width: float, height: float, floor: float) -> list[tuple]:
    """The plans' regions beside a scheme of width × height mm at the upper left, above
    `floor` (mm): right of it, and below it across the sheet, each at least 40 mm each way."""
    fx0, _, fx1, fy1 = req.area
    g = req.gap
    regions = [(fx0 + width + g, floor + g, fx1, fy1), (fx0, floor + g, fx1, fy1 - height - g)]
    return [r for r in regions if not (r[2] - r[0] < 40 or r[3] - r[1] < 40)]


def _past_a_hopeless_scheme(req: Request, draw: _Drawings, attempt, kinds, zone, floor: float, least: float):
    """`_pairing`'s best of `attempt` found without drawing the largest scheme that may fit
    `zone` where it cannot be chosen: at its least size (`least_scheme_size`) its plans can
    score no more than a bound (`_score_bound`) short of good, and the next scheme's plans are
    good and score more than that bound. None where that is not so (every scheme is tried)."""
    scales = _scheme_scales(req, draw, zone)
    first = next(scales, None)
    if first is None:
        return None
    vector_bound = partial(_drawn_vector_bound, draw, MIN_PLAN_MM[req.fmt])
    bound = max((_score_bound(req.study, attempt, kinds, region, req.gap, vector_bound)
                 for region in _plan_regions(req, *draw.least_scheme(first), floor)), default=0.0)
    if bound >= GOOD_PLAN_MM[req.fmt]:
        return None
    for mview in _fitting(draw, scales, zone):  # the next scheme that fits: the first chosen can be
        if _zone_share(mview, zone) < least:
            return None
        best, good, _ = _plans_beside(req, draw, mview, attempt, kinds, floor, None, None)
        return best if good and best[0] > bound else None
    return None


def _cannot_change(best: float, good: bool, req: Request, chosen, kinds, region) -> bool:
    """Whether the plans in `region` can neither beat the `best` score nor make the scheme
    `good` (`_score_bound`): they need not be fitted."""
    bound = _score_bound(req.study, chosen, kinds, region, req.gap)
    return bound <= best and (good or bound < GOOD_PLAN_MM[req.fmt])


def _scheme_zone(top) -> tuple[float, float, float, float]:
    """The scheme's zone: its share of the top band, at the left."""
    return (top[0], top[1], top[0] + SCHEME_WIDTH * (top[2] - top[0]), top[3])


def _zone_share(view: View, zone) -> float:
    """The share of its `zone` a scheme spans along the fuller direction."""
    x0, y0, x1, y1 = zone
    return max(view.width_mm / (x1 - x0), view.height_mm / (y1 - y0))


#: Radius of an enlarged detail of a plan as drawn, at most, mm, per format.
DETAIL_MM: Mapping[str, float] = MappingProxyType({"A1": 60.0, "A2": 48.0, "A3": 36.0})


def _place_details(req: Request, views: dict, results) -> None:
    """An enlarged detail of each plan whose images crowd round its pole
    (`velplan.views.plan_detail`), at the largest enlargement that finds a free spot, the
    region marked on the plan, its title above the circle or, where that finds no spot, beside
    it; where the crowd's region is too large for any enlargement or spot, the tighter crowd
    within `CROWD_MM` of the pole, then two thirds of it; none where no spot is free or the
    mark leaves the plan's room. A plan may slide up or down into the free room of its column
    to make the room (`_slid`). A plan that finds no spot so gets its detail in the empty room
    inside the plan of positions, clear of its lines and letters (`ink_boxes`), where there is one."""
    from velplan.views.plan_detail import CROWD_MM, NUMERALS, crowd_near_pole

    numerals = iter(NUMERALS)
    numeral = next(numerals)
    done: set[str] = set()
    inside = None
    for host in (None, "mechanism"):  # then, for a plan still without, in the scheme's empty room
        for reach in (None, CROWD_MM, 2.0 / 3.0 * CROWD_MM):  # every plan's whole crowd before a tighter one
            for name, res in sorted(results.items()):
                if name in done:
                    continue
                number = int(name.rsplit("-", 1)[1])
                region = crowd_near_pole(views[name].view.meta["images"], max(extent_mm(res, number)), reach)
                if region is None:
                    continue
                if host is not None and inside is None:  # the scheme's ink, once, where it is asked
                    inside = (host, ink_boxes(views[host]))
                if _detail_placed(req, views, name, res, region, numeral, inside):
                    numeral = next(numerals, numeral)
                    done.add(name)


def _detail_placed(req: Request, views: dict, name: str, res, region, numeral: str, inside) -> bool:
    """Whether the detail of the plan `name` (its `region`, numbered `numeral`) found a spot:
    then it is in `views`, the plan marked (and a plan slid in its column where that made the
    room); `inside`, a view's name and its `ink_boxes`, lends that view's empty room."""
    from velplan.views.plan_detail import FACTORS, detail_view, least_detail_size, marked

    placed, number = views[name], int(name.rsplit("-", 1)[1])
    if (mark := marked(placed.view, region, req.sizes.plan.label_mm, numeral)) is None:
        return False
    view, (dx, dy) = mark
    with_mark = views | {name: view.at(placed.x - dx, placed.y - dy)}
    if not _free_of(with_mark[name].bounds, {k: v for k, v in views.items() if k != name}, req):
        return False
    for factor, beside in ((f, b) for f in FACTORS if region[1] * f <= DETAIL_MM[req.fmt] for b in (False, True)):
        least = least_detail_size(res, number, region, factor, lang=req.lang, sizes=req.sizes.plan, numeral=numeral,
                                  beside=beside)
        if all(_spot_for(least, arranged, name, req, inside) is None for arranged in _slid(with_mark, req)):
            continue  # not drawn: its circle and titles alone find no spot
        detail = detail_view(res, number, region, factor, lang=req.lang, sizes=req.sizes.plan, numeral=numeral,
                             beside=beside)
        if crossed_letters(detail.primitives):
            continue  # its crowd read through its own lines: no clearer than the plan itself
        for arranged in _slid(with_mark, req):
            at = _spot_for((detail.width_mm, detail.height_mm), arranged, name, req, inside)
            if at is not None:
                views.update(arranged)
                if inside is not None:  # a guest of the view whose empty room it takes
                    detail = replace(detail, meta=MappingProxyType(dict(detail.meta) | {"inside": inside[0]}))
                views[detail.name] = detail.at(*at)
                return True
    return False


def _spot_for(size, views: dict, name: str, req: Request, inside=None):
    """A free spot for a w × h mm `size` (a detail of the plan `name`) among the `views`, nearest
    the plan's upper right corner, or None (`free_spot`); with `inside`, a view's name and its
    `ink_boxes`, within that view's empty room too."""
    key, ink = inside or (None, [])
    taken = [v.bounds for k, v in views.items() if k != key] + [req.title_block] + ink
    return free_spot(size[0], size[1], taken, req.area, req.gap, views[name].bounds[2:], square=bool(ink))


def _slid(views: dict, req: Request):
    """The `views` as they are, then with one plan slid to the top, or to the bottom, of the free
    room of its column (`req.gap` from the views above and below it, the drawing area and the
    title block), in turn."""
    yield views
    boxes = {k: v.bounds for k, v in views.items()} | {"title block": req.title_block}
    for k in sorted(c for c in views if c.startswith("plan-")):
        x0, y0, x1, y1 = boxes[k]
        column = [b for j, b in boxes.items() if j != k and b[0] < x1 + req.gap and x0 - req.gap < b[2]]
        low = max([b[3] + req.gap for b in column if b[3] <= y0 + 1e-6] + [req.area[1]])
        high = min([b[1] - req.gap for b in column if b[1] >= y1 - 1e-6] + [req.area[3]])
        for y in (high - (y1 - y0), low):
            moved = views[k].view.at(views[k].x, y)
            if abs(y - y0) > 1.0 and _free_of(moved.bounds, {j: v for j, v in views.items() if j != k}, req):
                yield views | {k: moved}


def _free_of(box, views: dict, req: Request) -> bool:
    """Whether `box` (sheet mm) lies in the drawing area clear of the title block and `views`."""
    x0, y0, x1, y1 = req.area
    inside = box[0] >= x0 - 1e-6 and box[1] >= y0 - 1e-6 and box[2] <= x1 + 1e-6 and box[3] <= y1 + 1e-6
    return inside and not any(b[0] < box[2] and box[0] < b[2] and b[1] < box[3] and box[1] < b[3]
                              for b in [v.bounds for v in views.values()] + [req.title_block])


def _place_notes(req: Request, views: dict, on_sheet, band_top: float) -> None:
    """The input data and the readings off the plans, each in a free spot of the top band; on
    A3 at the ESKD minimum of 2.5 mm at least (where no spot is left, the note is left out)."""
    from velplan.views.data import data_view
    from velplan.views.readings import readings_view

    top_band = (req.area[0], band_top + req.gap, req.area[2], req.area[3])
    study, lang = req.study, req.lang
    placed = _free_spot(lambda s, t, w: data_view(study, lang=lang, size_mm=s, title_mm=t, width_factor=w),
                        ((3.5, 5.0, 1.0), (2.5, 3.5, 1.0), (2.5, 3.5, 0.8), (2.5, 3.5, 0.6)),
                        views, top_band, req.gap)
    if placed is not None:
        views["data"] = placed
    placed = _free_spot(lambda s, t, w: readings_view(on_sheet, lang=lang, size_mm=s, title_mm=t, width_factor=w),
                        ((2.5, 3.5, 1.0),) + tuple((2.5, 3.5, w) for w in NARROWER_TABLE),
                        views, top_band, req.gap)
    if placed is not None:
        views["readings"] = placed


def _place_structure(req: Request, views: dict, *, required: bool) -> None:
    """The structural analysis in free space of the sheet, where it fits legibly."""
    from velplan.sheets.structure import place_structure

    placed = place_structure(req.study, req.lang, views, req.area, req.title_block, req.gap, required)
    if placed is not None:
        views["structure"] = placed


def _centre_marks(study: Study, centres, scheme: PlacedView, mu_l: float) -> list:
    """The instant centres of the chosen positions (`Study.centres`), on the scheme."""
    from velplan.views.centres import centre_marks

    valid = study.kinematics.valid
    items: list = []
    for k in centres:
        con = study.centres(k, mu_l=mu_l) if valid[position_index(k, study.n)] else None
        tag = f" ({k})" if len(centres) > 1 else ""
        items += centre_marks(con, scheme, tag=tag) if con else ()
    return items


def _free_spot(build, sizes, views, region, gap):
    """``build(text size, title size, width factor)`` placed where no view is in ``region``,
    at the first of ``sizes`` that fits: the free spot nearest the scheme's lower left corner;
    None when there is no room."""
    taken = [v.bounds for v in views.values()]
    corner = (views["mechanism"].bounds[0], views["mechanism"].bounds[1])
    for size, title, width in sizes:
        view = build(size, title, width)
        at = free_spot(view.width_mm, view.height_mm, taken, region, gap, corner)
        if at is not None:
            return view.at(*at)
    return None


#: φ axes (mm per turn: μφ a round number of degrees per mm) and heights of the diagrams, mm.
DIAGRAM_LENGTHS = (360.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0, 60.0)
DIAGRAM_HEIGHTS = (60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0, 12.0, 10.0)


def _fit_diagrams(req: Request, draw: _Drawings, region, arrangement: Arrangement = "row") -> View:
    """The kinematic diagrams in `region`: the longest φ axis that fits with the lowest
    diagrams, then the highest diagrams that fit with it, provided every diagram's ordinate
    range is at least `MIN_ORDINATE_MM` (diagrams squashed flatter are left out, not drawn)."""
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    low = DIAGRAM_HEIGHTS[-1]
    length = _longest_axis(lambda L: draw.diagrams(arrangement, L, low), w, arrangement,
                           least=lambda L: draw.least_width(arrangement, L, low))
    if length is not None:
        # the view grows with its diagrams' height: start from the tallest that the lowest
        # view's margins leave room for, and step down until one fits (or up while one does)
        room = h - (draw.diagrams(arrangement, length, low).height_mm - low)
        k = next((j for j, ht in enumerate(DIAGRAM_HEIGHTS) if ht <= room + 1e-6), len(DIAGRAM_HEIGHTS) - 1)
        found = largest_fitting(lambda ht: draw.diagrams(arrangement, length, ht), DIAGRAM_HEIGHTS[k:], w, h)
        if found is not None:
            j = DIAGRAM_HEIGHTS.index(found[0])
            while j > 0 and fits(draw.diagrams(arrangement, length, DIAGRAM_HEIGHTS[j - 1]), w, h):
                j -= 1
            view = draw.diagrams(arrangement, length, DIAGRAM_HEIGHTS[j])
            if min(view.meta["ranges"]) >= MIN_ORDINATE_MM - 1e-6:
                return view
    raise ScaleError(f"the kinematic diagrams do not fit {req.fmt} ({w:.0f} × {h:.0f} mm free "
                     f"beside the title block) with a φ axis of at least "
                     f"{MIN_DIAGRAM_MM:.0f} mm and ordinates of at least {MIN_ORDINATE_MM:.0f} mm; "
                     f"use a larger --format")


def _longest_axis(draw_low, w: float, arrangement: str, least=None) -> float | None:
    """The longest of `DIAGRAM_LENGTHS` whose lowest view ``draw_low(length)`` is at most w mm
    wide, or None. An axis at which the diagrams side by side alone (each as wide as its φ
    axis, 12 mm apart as `diagram_view` sets them), or the least width ``least(length)`` (mm)
    where known, are wider is passed over undrawn."""
    columns = {"row": 3, "grid": 2}.get(arrangement, 1)
    found = largest_fitting(draw_low, DIAGRAM_LENGTHS, w, math.inf,
                            skip=lambda length: columns * length + 12.0 * (columns - 1) > w or (
                                least is not None and (least(length) or 0.0) > w + EPS_MM))
    return None if found is None else found[0]


def _extreme_positions(study: Study) -> tuple[int, ...]:
    """Positions (1-based) among the study's n that are extreme positions of the output."""
    st = study.stroke
    if st is None:
        return ()
    out = []
    for phi in (st.start.phi, st.end.phi):
        gap = np.abs((study.phi - phi + np.pi) % (2 * np.pi) - np.pi)
        if gap.min() < np.radians(0.5):
            out.append(int(np.argmin(gap)) + 1)
    return tuple(dict.fromkeys(out))


def _one_scale_per_kind(draw: _Drawings, results, kinds) -> dict:
    """The plans of each of `kinds` at one μ, the largest of their fits (every plan then fits
    its cell), as results (no plan drawn): name → result."""
    common: dict[str, float] = {}
    for res in results.values():
        common[res.kind] = max(common.get(res.kind, 0.0), res.scale)
    return {name: res if res.scale == common[res.kind] else
            draw.steps(res.kind, int(name.rsplit("-", 1)[1]), common[res.kind])[0]
            for name, res in results.items() if res.kind in kinds}


#: Size (the larger side of its images' box) below which a plan drawn at the sheet's common
#: scale is too small to read, mm, per format (DRAWING.md: about 80–150 mm on A1), unless
#: its own scale draws it no larger.
LEGIBLE_PLAN_MM: Mapping[str, float] = MappingProxyType({"A1": 80.0, "A2": 60.0, "A3": 40.0})


def legible_at(common: PlanResult, own: PlanResult, number: int, fmt: str) -> bool:
    """Whether the plan of position number `number` (1…n) drawn at the scale of `common` stays as legible
    as the legibility rule asks, compared with `own`, the same plan at its own fit: every
    labelled vector at least `MIN_VECTOR_MM` long at its own scale stays so, and the plan
    spans `LEGIBLE_PLAN_MM` of the format (or as much as its own scale gives)."""
    at_own = labelled_vectors(own, number)
    at_common = labelled_vectors(common, number)
    if any(length >= MIN_VECTOR_MM and at_common[t][1] < MIN_VECTOR_MM
           for t, (_, length) in at_own.items() if t in at_common):
        return False
    size = max(extent_mm(common, number))
    return size >= min(LEGIBLE_PLAN_MM[fmt], max(extent_mm(own, number))) - 1e-6


def _one_scale_where_legible(fmt: str, draw: _Drawings, plan_views, results, cells):
    """The plans of each kind at one μ where every one of them stays legible at it
    (`legible_at`), else each plan of that kind at its own μ (its title states it); a plan
    is redrawn at the common μ only where that μ is kept, centred in its cell again."""
    views, out = dict(plan_views), dict(results)
    for kind in {res.kind for res in results.values()}:
        common = _one_scale_per_kind(draw, results, (kind,))
        if not all(legible_at(common[n], results[n], int(n.rsplit("-", 1)[1]), fmt) for n in common):
            continue
        mu = max(results[n].scale for n in common)
        for name, res in common.items():
            if res is results[name]:
                continue
            res, view = draw.plan(kind, int(name.rsplit("-", 1)[1]), mu)
            x0, y0, x1, y1 = cells[name]
            views[name] = view.at(x0 + (x1 - x0 - view.width_mm) / 2,
                                  y0 + (y1 - y0 - view.height_mm) / 2)
            out[name] = res
    return views, out


def _diagrams_if_room(req: Request, draw: _Drawings, views: dict, *, required: bool) -> None:
    """The kinematic diagrams in a free corner, or as their compact block in a free spot, where
    they fit; ScaleError where they do not and are ``required``."""
    placed = _diagrams_in_free_corner(req, draw, views)
    if placed is None:
        placed = _compact_diagrams(req, draw, views)
    if placed is None and required:
        raise ScaleError(f"the kinematic diagrams do not fit {req.fmt} beside the table, in a free "
                         f"corner nor beside the plans with a φ axis of at least {MIN_DIAGRAM_MM:.0f} mm and "
                         f"ordinates of at least {MIN_ORDINATE_MM:.0f} mm; "
                         f"use a larger --format or fewer --plans")
    if placed is not None:
        views["diagrams"] = placed


def _diagrams_in_free_corner(req: Request, draw: _Drawings, views):
    """The kinematic diagrams in the largest free rectangle at the lower left corner of the
    drawing area, in a row, a grid or a column; None where they fit nowhere."""
    fx0, fy0, fx1, fy1 = req.area
    gap = req.gap
    boxes = [v.bounds for v in views.values()] + [req.title_block]
    best = None
    for right in sorted({b[0] for b in boxes if b[0] > fx0 + 60.0} | {fx1 + gap}):
        x1 = right - gap
        below = [b[1] for b in boxes if b[0] < x1 and b[2] > fx0]
        y1 = min(below, default=fy1 + gap) - gap
        if x1 - fx0 < MIN_DIAGRAM_MM or y1 - fy0 < 30.0:
            continue
        for arrangement in ("row", "grid", "column"):
            try:
                view = _fit_diagrams(req, draw, (fx0, fy0, x1, y1), arrangement)
            except ScaleError:
                continue
            score = view.width_mm * view.height_mm
            if best is None or score > best[0]:
                best = (score, view.at(fx0, fy0))
    return None if best is None else best[1]


def _diagrams_anywhere(req: Request, draw: _Drawings, views: dict, plans, scale_per_plan: bool, alone,
                       required: bool):
    """Room for the kinematic diagrams, tried in turn: a free corner or spot (`_diagrams_if_room`);
    beside the plans fitted again smaller (`plans`: their cells, positions and kinds;
    `_diagrams_beside_plans`), which returns (plan views, results, cells); the sheet ``alone()``
    draws with the first position's plans alone, returned where it has them; under the scheme
    (`_diagrams_under_scheme`, the plans fitted again). None where none has room (ScaleError
    then if ``required``)."""
    _diagrams_if_room(req, draw, views, required=False)
    if "diagrams" in views:
        return None
    refit = _diagrams_beside_plans(req, draw, views, *plans)
    if refit is not None:
        return _refitted(req, draw, views, refit, scale_per_plan)
    if alone is not None and "diagrams" in (sheet := alone()).views:
        return sheet
    refit = _diagrams_under_scheme(req, draw, views, *plans)
    if refit is not None:
        return _refitted(req, draw, views, refit, scale_per_plan)
    _diagrams_if_room(req, draw, views, required=required)
    return None


def _refitted(req: Request, draw: _Drawings, views: dict, refit, scale_per_plan: bool):
    """The plans fitted again beside the diagrams (`refit`: plan views, results, cells), at one
    scale per kind where every plan stays legible, put into `views`; (plan views, results, cells)."""
    plan_views, results, cells = refit
    if not scale_per_plan:
        plan_views, results = _one_scale_where_legible(req.fmt, draw, plan_views, results, cells)
    views.update(plan_views)
    return plan_views, results, cells


def _diagrams_under_scheme(req: Request, draw: _Drawings, views: dict, cells, chosen, kinds):
    """(plan views, results, cells) of the plans fitted again right of the scheme above the
    table moved back over the title block, the compact diagrams' block (placed in `views`,
    its longest φ axis that fits) in the lower left corner under the scheme, left of the
    table and the title block; None where the plans do not lie right of the scheme, the
    table moved meets the scheme, or the block or the plans fit nowhere."""
    if not cells or "table" not in views or min(b[0] for b in cells.values()) < views["mechanism"].bounds[2]:
        return None
    g, (fx0, fy0, fx1, fy1) = req.gap, req.area
    scheme = views["mechanism"].bounds
    high: dict = {}
    top = _bottom_band(req, draw, high, table=True, diagrams=False)
    table = high["table"].bounds
    if table[0] < scheme[2] + g and table[3] > scheme[1] - g:  # the table moved meets the scheme
        return None
    w, h = min(table[0], req.title_block[0]) - g - fx0, scheme[1] - g - fy0
    # below the plans' floor where it reaches right of the scheme
    blocks = [b for b in (draw.compact(form, length) for length in COMPACT_LENGTHS for form in FORMS)
              if min(b.meta["drawn_ranges"]) >= MIN_ORDINATE_MM - 1e-6 and b.width_mm <= w and b.height_mm <= h
              and (fx0 + b.width_mm <= scheme[2] or fy0 + b.height_mm <= top)]
    if not blocks:
        return None
    try:
        _, fitted = _fit_plans(req, draw, chosen, kinds, (scheme[2] + g, top + g, fx1, fy1))
    except ScaleError:
        return None
    for name in [k for k in views if k.startswith("plan-")]:
        del views[name]
    views["table"], views["diagrams"] = high["table"], blocks[0].at(fx0, fy0)
    return fitted


def _diagrams_beside_plans(req: Request, draw: _Drawings, views: dict, cells, chosen, kinds):
    """(plan views, results, cells) of the plans fitted again into their region less the
    compact diagrams' block (placed in `views`) at one of its edges, the placing that leaves
    the plans the longest shortest vector (each plan legible as `_fit_plans` asks); None
    where the plans are legible beside the block nowhere."""
    if not cells:
        return None
    x0, y0 = min(b[0] for b in cells.values()), min(b[1] for b in cells.values())
    x1, y1 = max(b[2] for b in cells.values()), max(b[3] for b in cells.values())
    g = req.gap
    best = None
    for form in FORMS:
        block = draw.compact(form, COMPACT_LENGTHS[-1])
        w, h = block.width_mm, block.height_mm
        if min(block.meta["drawn_ranges"]) < MIN_ORDINATE_MM - 1e-6 or w > x1 - x0 or h > y1 - y0:
            continue
        for at, region in (((x0, y0), (x0, y0 + h + g, x1, y1)), ((x1 - w, y0), (x0, y0 + h + g, x1, y1)),
                           ((x1 - w, y0), (x0, y0, x1 - w - g, y1)), ((x0, y0), (x0 + w + g, y0, x1, y1))):
            if region[2] - region[0] < 40 or region[3] - region[1] < 40:
                continue
            try:
                score, fitted = _fit_plans(req, draw, chosen, kinds, region)
            except ScaleError:
                continue
            if best is None or score > best[0]:
                best = (score, block.at(*at), fitted)
    if best is None:
        return None
    for name in [k for k in views if k.startswith("plan-")]:
        del views[name]
    views["diagrams"] = best[1]
    return best[2]


#: φ axes of the compact diagrams (`velplan.views.diagram_compact`), mm, the longest first.
COMPACT_LENGTHS = (90.0, 72.0, 60.0)
#: Forms of the compact diagrams, in the order tried.
FORMS: tuple[Form, ...] = ("grid", "column")
#: The ESKD minimum height of printed text, mm (ГОСТ 2.304): the compact diagrams' text at least.
MIN_TEXT_MM = 2.5


def _compact_diagrams(req: Request, draw: _Drawings, views):
    """The kinematic diagrams in their compact block (s and v side by side over a, or the three
    in a column), each curve at least `MIN_ORDINATE_MM` high, in a free spot of the sheet
    nearest its lower left corner: the longest φ axis that finds one; None where none does."""
    fx0, fy0, _, _ = req.area
    taken = [v.bounds for v in views.values()] + [req.title_block]
    for length in COMPACT_LENGTHS:
        for form in FORMS:
            view = draw.compact(form, length)
            if min(view.meta["drawn_ranges"]) < MIN_ORDINATE_MM - 1e-6:
                continue
            at = free_spot(view.width_mm, view.height_mm, taken, req.area, req.gap, (fx0, fy0))
            if at is not None:
                return view.at(*at)
    return None


def _mechanism_candidates(req: Request, draw: _Drawings, zone, count: int = 3):
    """Up to `count` schemes at successive ESKD scales that fit `zone`, the largest first."""
    found = 0
    for view in _fitting(draw, _scheme_scales(req, draw, zone), zone):
        yield view
        found += 1
        if found >= count:
            return
    if found:
        return
    x0, y0, x1, y1 = zone
    raise ScaleError(f"the scheme of {req.mechanism.name} does not fit {req.fmt} ({x1 - x0:.0f} × {y1 - y0:.0f} mm "
                     f"free) at any ESKD scale with a crank of at least {MIN_CRANK_MM:.0f} mm; "
                     f"use a larger --format")


def _scheme_scales(req: Request, draw: _Drawings, zone):
    """The ESKD scales, the largest drawing first, whose scheme may fit `zone`: its extent and
    its least size (`least_scheme_size`) do, and its crank is at least `MIN_CRANK_MM` long."""
    study = req.study
    mech = study.mechanism
    x0, y0, x1, y1 = zone
    w, h = x1 - x0, y1 - y0
    wx, wy = extent_m(mech, study.kinematics, draw.fine)
    for mu in eskd_scales():
        if wx / mu > w or wy / mu > h:
            continue
        if mech.crank.length / mu < MIN_CRANK_MM:
            return
        lw, lh = draw.least_scheme(mu)
        if lw <= w + EPS_MM and lh <= h + EPS_MM:
            yield mu


def _fitting(draw: _Drawings, scales, zone):
    """The schemes drawn at `scales` (an iterator, consumed as they are drawn) that fit `zone`."""
    x0, y0, x1, y1 = zone
    for mu in scales:
        view = draw.scheme(mu)
        if fits(view, x1 - x0, y1 - y0):
            yield view


def _grid_shapes(chosen, kinds) -> list[tuple[int, int, tuple]]:
    """(rows, columns, plans in reading order) of the grids tried: a row per kind, a row per
    position, one row, one column, and for many plans the grids between."""
    K, M = len(chosen), len(kinds)
    kind_major = tuple((kd, k) for kd in kinds for k in chosen)
    position_major = tuple((kd, k) for k in chosen for kd in kinds)
    shapes = [(M, K, kind_major), (K, M, position_major), (1, K * M, kind_major),
              (K * M, 1, kind_major)]
    count = K * M
    shapes += [(r, math.ceil(count / r), kind_major) for r in range(2, count)
               if (r - 1) * math.ceil(count / r) < count]
    return list(dict.fromkeys(shapes))


def _promise(study: Study, shape, W: float, H: float, gap: float) -> float:
    """Longest shortest plan (mm) the grid shape promises from the images alone."""
    rows, cols, order = shape
    cw, ch = (W - gap * (cols - 1)) / cols, (H - gap * (rows - 1)) / rows
    if cw <= 24 or ch <= 38:
        return 0.0
    worst = math.inf
    for kd, k in order:
        res = study.plan(kd)
        ew, eh = extent_mm(res, k)
        mu = standard_scale(res.scale * max(ew / (cw - 24), eh / (ch - 38), 1e-9))
        worst = min(worst, _peak(res, position_index(k, len(res.kin))) / mu)
    return worst


def _score_bound(study: Study, chosen, kinds, region, gap: float, vector_bound=None) -> float:
    """An upper bound of `_fit_plans`' score in `region` (mm), found without drawing: for
    each grid shape, the least over its plans of the longest vector at the first scale
    `_fit_one` may try in its cell (`_vector_bound`); the largest of them over the shapes.
    With ``vector_bound(plan, number, cw, ch)``, a tighter bound of that vector, the shapes
    whose plain bound may raise the result are bounded by it instead."""
    bound = 0.0
    for shape in _grid_shapes(chosen, kinds):
        worst = _shape_bound(study, shape, region, gap, _vector_bound, bound)
        if vector_bound is not None and worst > bound:
            worst = _shape_bound(study, shape, region, gap, vector_bound, bound)
        bound = max(bound, worst)
    return bound


def _shape_bound(study: Study, shape, region, gap: float, vector_bound, floor: float) -> float:
    """The least ``vector_bound(plan, number, cw, ch)`` (mm) over the plans of the grid
    `shape` (rows, columns, plans) in `region`, or any value not above `floor` once it is
    known to fall there; 0 where the cells have no room."""
    rows, cols, order = shape
    x0, y0, x1, y1 = region
    cw, ch = (x1 - x0 - gap * (cols - 1)) / cols, (y1 - y0 - gap * (rows - 1)) / rows
    if cw <= 0 or ch <= 0:
        return 0.0
    worst = math.inf
    for kind, number in order:
        worst = min(worst, vector_bound(study.plan(kind), number, cw, ch))
        if worst <= floor:
            break
    return worst


def _vector_bound(res0: PlanResult, number: int, cw: float, ch: float) -> float:
    """The longest vector (mm) of the plan of position ``number`` at the first (largest
    drawing's) scale `_fit_one` tries in a cw × ch mm cell: no plan it fits there is longer;
    0 where it tries none."""
    ew, eh = extent_mm(res0, number)
    room_w, room_h = cw - 2 * 12.0, ch - 2 * 12.0 - 14.0
    if room_w <= 0 or room_h <= 0:
        return 0.0
    estimate = res0.scale * max(ew / room_w, eh / room_h, 1e-9)
    for mu in _standard_from(estimate / 1.6):  # ends: the images shrink as μ grows
        if ew * res0.scale / mu <= cw and eh * res0.scale / mu <= ch - 14.0:
            return _peak(res0, number - 1) / mu
    raise AssertionError("unreachable")


def _peak(res: PlanResult, i: int) -> float:
    """The longest vector of the plan at position index i, in its units."""
    vec = res.kin.velocities if res.kind == "velocity" else res.kin.accelerations
    return float(np.nanmax(np.hypot(vec[i, :, 0], vec[i, :, 1])))


def _fit_plans(req: Request, draw: _Drawings, chosen, kinds, region):
    """(score, (placed views, results, cells)): the plans in a grid of equal cells, each at
    its own standard scale (the largest drawing that fits its cell); of the grid shapes
    tried, the most promising first, the first that fits wins; its score is its shortest
    plan's longest vector, mm."""
    x0, y0, x1, y1 = region
    W, H = x1 - x0, y1 - y0
    gap, least = req.gap, MIN_PLAN_MM[req.fmt]
    shapes = sorted(_grid_shapes(chosen, kinds), key=lambda s: _promise(req.study, s, W, H, gap),
                    reverse=True)
    for rows, cols, order in shapes:
        cw, ch = (W - gap * (cols - 1)) / cols, (H - gap * (rows - 1)) / rows
        if cw <= 0 or ch <= 0:
            continue
        fitted = {}
        for kind, number in order:
            fitted[kind, number] = _fit_one(req.study.plan(kind), number, draw, cw, ch, least)
            if fitted[kind, number] is None:
                break
        else:
            score = min(f[2] for f in fitted.values())
            if score >= least:
                return score, _place_grid(fitted, order, cols, (x0, y1), cw, ch, gap)
            break
    raise ScaleError(f"the {' and '.join(kinds)} plans of positions {', '.join(map(str, chosen))} do "
                     f"not fit {req.fmt} at any standard scale with vectors of at least "
                     f"{least:.0f} mm ({W:.0f} × {H:.0f} mm free); use fewer --plans or a larger "
                     f"--format")


def _place_grid(fitted, order, cols: int, corner, cw: float, ch: float, gap: float):
    """(placed views, results, cells) of plans in a grid from the upper left `corner`, each
    centred in its cell."""
    x0, y1 = corner
    placed, results, cells = {}, {}, {}
    for j, (kind, number) in enumerate(order):
        res, view, _ = fitted[kind, number]
        results[view.name] = res
        r, c = divmod(j, cols)
        cx0, cy0 = x0 + c * (cw + gap), y1 - r * (ch + gap) - ch
        placed[view.name] = view.at(cx0 + (cw - view.width_mm) / 2, cy0 + (ch - view.height_mm) / 2)
        cells[view.name] = (cx0, cy0, cx0 + cw, cy0 + ch)
    return placed, results, cells


def _standard_from(mu: float):
    """Standard scale values from the one at or above `mu`, increasing."""
    value = standard_scale(mu)
    while True:
        yield value
        value = standard_scale(value * 1.0001)


def _fit_one(res0: PlanResult, number: int, draw: _Drawings, cw: float, ch: float, least: float):
    """(result, view, longest vector mm) of the plan of position ``number`` at the smallest
    standard μ that fits a cell of cw × ch mm, or None: ten scales at most are drawn, none
    whose longest vector is under `least` mm."""
    tried = _scales_tried(res0, number, cw, ch, least)
    if tried is None:
        return None
    peak, scales = tried
    found = largest_fitting(lambda mu: draw.plan(res0.kind, number, mu)[1], scales, cw, ch,
                            skip=lambda mu: not draw.plan_fits(res0.kind, number, mu, cw, ch))
    if found is None:
        return None
    mu, view = found
    return draw.plan(res0.kind, number, mu)[0], view, peak / mu


def _scales_tried(res0: PlanResult, number: int, cw: float, ch: float, least: float):
    """(the plan's longest vector in its units, the scales `_fit_one` tries in a cw × ch mm
    cell, the largest drawing first), or None where the cell leaves no room."""
    ew, eh = extent_mm(res0, number)
    room_w, room_h = cw - 2 * 12.0, ch - 2 * 12.0 - 14.0
    if room_w <= 0 or room_h <= 0:
        return None
    peak = _peak(res0, number - 1)
    # start a little below the estimate: labels rarely need the whole margin
    estimate = res0.scale * max(ew / room_w, eh / room_h, 1e-9)
    # the images alone must fit the cell (its margins are for the letters): a scale at
    # which they do not is passed over undrawn; ten scales are drawn at most
    return peak, islice((mu for mu in _legible(_standard_from(estimate / 1.6), peak, least)
                         if ew * res0.scale / mu <= cw and eh * res0.scale / mu <= ch - 14.0), 10)


def _drawn_vector_bound(draw: _Drawings, least: float, res0: PlanResult, number: int, cw: float,
                        ch: float) -> float:
    """The longest vector (mm) of the plan of position ``number`` at the first scale `_fit_one`
    tries in a cw × ch mm cell whose construction and title alone fit (`_Drawings.plan_fits`):
    no plan it fits there is longer; 0 where it fits none. Tighter than `_vector_bound`, and
    found without drawing a plan."""
    tried = _scales_tried(res0, number, cw, ch, least)
    if tried is None:
        return 0.0
    peak, scales = tried
    return next((peak / mu for mu in scales if draw.plan_fits(res0.kind, number, mu, cw, ch)), 0.0)


def _legible(scales, peak: float, least: float):
    """The `scales` while the longest vector stays at least `least` mm."""
    for mu in scales:
        if peak / mu < least:
            return
        yield mu


__all__ = ["KINDS", "Sheet", "build_sheet", "default_plan_positions", "default_title", "sheet_text",
           "write_outputs"]
