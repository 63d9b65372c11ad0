"""The drawing sheet of a kinematic analysis: frame and title block, the scheme in its
positions, velocity and acceleration plans, kinematic diagrams and the table of transfer
functions, each at a standard scale, placed without overlap.

The layout follows the Russian course sheet (METHOD.md §7): the scheme in the upper left,
the plans to its right in a grid (one row per kind, one column per chosen position, or the
transpose when that gives larger plans), the diagrams along the bottom and the table above
the title block. Each view takes the largest drawing (the smallest μ of the standard
series) that fits its region; a view that cannot be drawn legibly at any standard scale
raises :class:`~velplan.errors.ScaleError` with a one-line message.

Examples
--------
>>> sheet = build_sheet("crank-slider", fmt="A3", lang="en")
>>> sheet.scales["mu_l"], {"mechanism", "diagrams", "table"} <= set(sheet.views)
(0.002, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Literal, Mapping, Sequence

import numpy as np
import shapely

from velplan.errors import ScaleError, VelplanError
from velplan.mechanism.model import Mechanism
from velplan.plans import standard_scale
from velplan.plans.engine import PlanResult
from velplan.study import Study
from velplan.views.diagram import DiagramSizes, diagram_view
from velplan.render.i18n import check_language, label
from velplan.views.mechanism import MechanismSizes, extent_m, mechanism_view
from velplan.views.plan import PlanSizes, extent_mm, plan_view
from velplan.render.scene import Scene
from velplan.sheets.frame import TitleInfo, sheet_scene
from velplan.render.style import SheetStyle
from velplan.sheets.layout import (
    FORMATS, GOOD_PLAN_MM, MIN_CRANK_MM, MIN_DIAGRAM_MM, MIN_PLAN_MM, SIZES, SheetOutput, Sizes,
    check_layout, drawing_area, fill_bottom_band, fits, write_outputs)
from velplan.views.table import sheet_table, table_view
from velplan.views.base import PlacedView, View, eskd_scales, ratio_text

Kind = Literal["velocity", "acceleration", "both"]
Format = Literal["A1", "A2", "A3"]
KINDS: tuple[str, ...] = ("velocity", "acceleration", "both")


@dataclass(frozen=True)
class Sheet(SheetOutput):
    """A composed sheet.

    Attributes
    ----------
    mechanism : Mechanism
    scene : Scene
        Everything drawn, in sheet mm; render it with ``velplan.render.to_svg``.
    views : Mapping[str, PlacedView]
        ``"mechanism"``, ``"plan-v-K"``, ``"plan-a-K"``, ``"table"``, ``"diagrams"``.
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
    fmt, lang, frame_style : str
    style : SheetStyle
    """

    mechanism: Mechanism
    scene: Scene
    views: Mapping[str, PlacedView]
    scales: Mapping[str, float]
    plans: Mapping[str, PlanResult]
    plan_index: Mapping[str, int]
    positions: tuple[int, ...]
    n: int
    fmt: str
    lang: str
    frame_style: str
    style: SheetStyle
    info: TitleInfo
    zones: Mapping[str, tuple] = field(default_factory=lambda: MappingProxyType({}))
    """View name → the zone of the sheet it was fitted to (sheet mm): a plan's grid cell, the
    scheme's share of the top band."""



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
        picks.append(best + 1)
    return tuple(picks)


def default_title(mech: Mechanism, lang: str, fmt: str, scale: str,
                  frame_style: str) -> TitleInfo:
    """Title block filled with what velplan knows; no date (velplan never reads the clock)."""
    prefix = "ТММ" if lang in ("ru", "uk") else "TMM"
    return TitleInfo(title=f"{label('kinematic_analysis', lang)}: {mech.name_in(lang)}",
                     designation=f"{prefix}.{mech.name}.01", scale=scale)


def build_sheet(mech: Study | Mechanism | str, *, n: int = 12, plans: Sequence[int] | None = None,
                kind: Kind = "both", fmt: Format = "A1", lang: str = "ru",
                frame_style: str | None = None, info: TitleInfo | None = None,
                diagrams: bool | None = None, table: bool = True,
                style: SheetStyle | None = None, data: bool = True, centres: Sequence[int] = (),
                scale_per_plan: bool = False) -> Sheet:
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
        fit beside the scheme (a large scheme on A3). The first one is drawn thick in the
        scheme.
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
        Draw the kinematic diagrams (True: or raise ScaleError), leave them out (False),
        or draw them when they fit and the mechanism names an output (None, the default):
        beside the table, or else in the largest free corner left by the scheme and the
        plans, in a row or a column.
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
        Fit each plan to its cell at its own μ; by default all velocity plans of the sheet
        share one μv and all acceleration plans one μa (the largest of their fits), so that
        they compare by eye.

    Raises
    ------
    ScaleError
        A view cannot be drawn legibly at any standard scale in its part of the sheet.
    VelplanError
        Bad options (unknown format, kind or language, positions out of range).
    """
    study = mech if isinstance(mech, Study) else Study(mech, n=n)
    mech, n = study.mechanism, study.n
    check_language(lang)
    if fmt not in FORMATS:
        raise VelplanError(f"unknown sheet format {fmt!r}; known formats: {', '.join(FORMATS)}")
    if kind not in KINDS:
        raise VelplanError(f"unknown plan kind {kind!r}; known kinds: {', '.join(KINDS)}")
    if n < 3:
        raise VelplanError(f"a sheet needs at least 3 positions, not {n}")
    kin = study.kinematics
    bad = np.flatnonzero(~kin.valid)
    if bad.size:
        raise VelplanError(f"{mech.name} cannot be assembled at position {bad[0] + 1} "
                           f"(crank angle {math.degrees(kin.phi[bad[0]]):.6g}°)")
    chosen = tuple(default_plan_positions(study.plan("velocity")) if plans is None else plans)
    if not chosen:
        raise VelplanError("--plans: give at least one position")
    for k in chosen:
        if not (isinstance(k, (int, np.integer)) and 1 <= k <= n):
            raise VelplanError(f"--plans: position {k} is outside 1…{n}")
    if len(set(chosen)) != len(chosen):
        raise VelplanError(f"--plans: a position is repeated in {', '.join(map(str, chosen))}")
    frame_style = frame_style or ("eskd" if lang in ("ru", "uk") else "iso")
    style = style or SheetStyle(language=lang)
    sizes = SIZES[fmt]
    g = sizes.gap

    fine = study.turn.take(slice(None, None, 3))  # 240 steps: the scheme's trajectories

    (fx0, fy0, fx1, fy1), (tx0, ty0, tx1, ty1) = drawing_area(fmt, frame_style)
    W, H = fx1 - fx0, fy1 - fy0
    views: dict[str, PlacedView] = {}

    # the bottom band: the table above the title block, the diagrams to their left
    if diagrams and mech.output is None:
        raise VelplanError(f"{mech.name} names no output, so it has no kinematic diagrams")
    tview = _fit_table(study, lang, sizes, max_width=0.62 * W, fmt=fmt) if table else None
    band_top, _ = fill_bottom_band(
        views, (fx0, fy0, fx1, fy1), (tx0, ty0, tx1, ty1), g, table_view=tview,
        fit_diagram=(lambda r: _fit_diagrams(study, lang, sizes, r, fmt=fmt))
        if diagrams is not False and mech.output is not None else None,
        diagram_share=0.3, required=bool(diagrams), diagram_name="diagrams")

    # the top band: the scheme, then the plans to its right
    top = (fx0, band_top + g, fx1, fy1)
    thick = chosen[0]
    kinds = ("velocity", "acceleration") if kind == "both" else (kind,)
    # the largest scheme whose neighbours, the plans, still get vectors of a good length;
    # failing that, the scheme that leaves the plans the longest vectors
    best, failure = None, None
    drawn: dict = {}  # (kind, number, μ) → (result, view): a plan's view does not depend on its cell
    # the default positions' plans that fit no scheme: the first position's alone
    attempts = [chosen] + ([chosen[:1]] if plans is None and len(chosen) > 1 else [])
    bold = _extreme_positions(study)
    for mview, attempt in ((m, a) for a in attempts for m in _mechanism_candidates(
            mech, kin, fine, n, thick, lang, sizes, top, fmt=fmt, extreme=study.other_extreme,
            bold=bold)):
        if best is not None and attempt is not chosen:
            break
        # the plans go to the right of the scheme, or below it across the sheet
        regions = [(fx0 + mview.width_mm + g, band_top + g, fx1, fy1),
                   (fx0, band_top + g, fx1, fy1 - mview.height_mm - g)]
        good = False
        for plan_region in regions:
            if plan_region[2] - plan_region[0] < 40 or plan_region[3] - plan_region[1] < 40:
                continue
            try:
                plan_views, results, score, cells = _fit_plans(study, attempt, kinds, lang, sizes,
                                                               plan_region, g, fmt=fmt, drawn=drawn)
            except ScaleError as exc:
                failure = failure or exc
                continue
            if best is None or score > best[0]:
                best = (score, mview, plan_views, results, cells)
                chosen = attempt
            good = good or score >= GOOD_PLAN_MM[fmt]
        if good:
            break
    if best is None:
        raise failure
    _, mview, plan_views, results, cells = best
    if not scale_per_plan:
        plan_views, results = _one_scale_per_kind(plan_views, results, cells, lang, sizes, drawn)
    index = {name: int(name.rsplit("-", 1)[1]) - 1 for name in results}  # its position in the plan's
    views["mechanism"] = mview.at(fx0, fy1 - mview.height_mm)
    views.update(plan_views)
    if "diagrams" not in views and diagrams is not False and mech.output is not None:
        placed = _diagrams_in_free_corner(study, lang, sizes, views, (fx0, fy0, fx1, fy1),
                                          (tx0, ty0, tx1, ty1), g, fmt)
        if placed is not None:
            views["diagrams"] = placed
    if data:
        from velplan.views.data import data_view
        from velplan.views.readings import readings_view

        top_band = (fx0, band_top + g, fx1, fy1)
        placed = _free_spot(lambda s, t: data_view(study, lang=lang, size_mm=s, title_mm=t),
                            ((3.5, 5.0), (2.5, 3.5), (1.8, 2.5)), views, top_band, g)
        if placed is not None:
            views["data"] = placed
        on_sheet = {name: (res, index[name]) for name, res in results.items()}
        placed = _free_spot(lambda s, t: readings_view(on_sheet, lang=lang, size_mm=s, title_mm=t),
                            ((2.5, 3.5), (1.8, 2.5)), views, top_band, g)
        if placed is not None:
            views["readings"] = placed

    scales = {"mu_l": mview.mu}
    for name, res in results.items():
        scales[name] = res.scale
    if info is None:
        info = default_title(mech, lang, fmt, ratio_text(mview.mu, lang), frame_style)
    elif not info.scale:
        from dataclasses import replace
        info = replace(info, scale=ratio_text(mview.mu, lang))
    check_layout(views, fmt, frame_style)
    scene = sheet_scene(info, fmt, frame_style=frame_style, lang=lang)
    order = ["mechanism"] + sorted(k for k in views if k.startswith("plan-")) + [
        k for k in ("data", "readings", "diagrams", "table") if k in views]
    scene = scene.extend(*(views[k].primitives for k in order))
    if centres:  # the instant centres of the chosen positions, on the scheme
        from velplan.plans.centres import construct_centres
        from velplan.views.centres import centre_marks

        for k in centres:
            if not 1 <= k <= len(kin):
                raise VelplanError(f"--centres: position {k} is outside 1…{len(kin)}")
            con = construct_centres(kin, k - 1, mu_l=mview.mu) if kin.valid[k - 1] else None
            tag = f" ({k})" if len(centres) > 1 else ""
            scene = scene.extend(centre_marks(con, views["mechanism"], tag=tag) if con else ())
    zones = dict(cells)
    zones["mechanism"] = (top[0], top[1], top[0] + 0.62 * (top[2] - top[0]), top[3])
    return Sheet(mech, scene, MappingProxyType(dict(views)), MappingProxyType(scales),
                 MappingProxyType(results), MappingProxyType(index), chosen, n, fmt, lang,
                 frame_style, style, info, MappingProxyType(zones))


def _free_spot(build, sizes, views, region, gap):
    """``build(text size, title size)`` placed where no view is in ``region``, at the largest
    of ``sizes`` that fits: the free spot nearest the scheme's lower left corner; None when
    there is no room."""
    x0, y0, x1, y1 = region
    taken = np.array([shapely.box(*v.bounds).buffer(gap) for v in views.values()])
    corner = np.array([views["mechanism"].bounds[0], views["mechanism"].bounds[1]])
    for size, title in sizes:
        view = build(size, title)
        w, h = view.width_mm, view.height_mm
        if w > x1 - x0 or h > y1 - y0:
            continue
        xs, ys = np.meshgrid(np.arange(x0, x1 - w + 1e-9, 5.0), np.arange(y0, y1 - h + 1e-9, 5.0))
        xs, ys = xs.ravel(), ys.ravel()
        boxes = shapely.box(xs, ys, xs + w, ys + h)
        free = ~shapely.intersects(boxes[:, None], taken[None, :]).any(axis=1)
        if free.any():
            k = np.flatnonzero(free)
            best = k[np.argmin(np.hypot(xs[k] - corner[0], ys[k] + h - corner[1]))]
            return view.at(xs[best], ys[best])
    return None


def _fit_table(study: Study, lang, sizes: Sizes, *, max_width: float, fmt: str) -> View:
    mech, n = study.mechanism, study.n
    data = sheet_table(study.plan("velocity"))
    for size in sizes.table:
        view = table_view(data, mech, lang=lang, size_mm=size, title_mm=sizes.table_title)
        if view.width_mm <= max_width:
            return view
    raise ScaleError(f"the table of transfer functions ({n} positions) does not fit {fmt} "
                     f"even with 1.8 mm text ({view.width_mm:.0f} mm wide, "
                     f"{max_width:.0f} mm free); use fewer --positions or a larger --format")


def _fit_diagrams(study: Study, lang, sizes: Sizes, region, *, fmt: str,
                  arrangement: str = "row") -> View:
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    d = study.diagrams
    best = None

    def build(length, height):
        return diagram_view(d, length_mm=length, height_mm=height, lang=lang, omega=study.mechanism.crank.omega,
                            arrangement=arrangement, sizes=sizes.diagram)

    # the longest φ axis (μφ a round number of degrees per mm) that fits with the lowest
    # diagrams, then the highest diagrams that fit with it
    heights = (60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0, 12.0, 10.0)
    lengths = (360.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0, 60.0)
    # the width grows linearly with the φ axis: from the longest and the shortest axis, the
    # longest that may fit is tried first (the longer ones cannot)
    widths = {lengths[0]: build(lengths[0], heights[-1])}
    start = 0
    if widths[lengths[0]].width_mm > w:
        widths[lengths[-1]] = build(lengths[-1], heights[-1])
        w0, w1 = widths[lengths[0]].width_mm, widths[lengths[-1]].width_mm
        per_mm = (w0 - w1) / (lengths[0] - lengths[-1])
        start = next((j for j, L in enumerate(lengths) if w1 + per_mm * (L - lengths[-1]) <= w + 1.0),
                     len(lengths) - 1)
        while start > 0 and (widths.get(lengths[start - 1]) or build(lengths[start - 1], heights[-1])).width_mm <= w:
            start -= 1
    for length in lengths[start:]:
        low = widths.get(length) or build(length, heights[-1])
        if low.width_mm <= w:
            # the view grows with its diagrams' height: start from the tallest that the lowest
            # view's margins leave room for, and step down until one fits (or up while one does)
            room = h - (low.height_mm - heights[-1])
            k = next((j for j, ht in enumerate(heights) if ht <= room + 1e-6), len(heights) - 1)
            views = {len(heights) - 1: low}
            fitting = None
            for j in range(k, len(heights)):
                views[j] = views.get(j) or build(length, heights[j])
                if fits(views[j], w, h):
                    fitting = j
                    break
            while fitting is not None and fitting > 0:
                above = build(length, heights[fitting - 1])
                if not fits(above, w, h):
                    break
                fitting, views[fitting - 1] = fitting - 1, above
            if fitting is not None:
                best = (length * heights[fitting], views[fitting])
            break
    if best is None:
        raise ScaleError(f"the kinematic diagrams do not fit {fmt} ({w:.0f} × {h:.0f} mm free "
                         f"beside the title block) with a φ axis of at least "
                         f"{MIN_DIAGRAM_MM:.0f} mm; use a larger --format")
    return best[1]


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


def _one_scale_per_kind(plan_views, results, cells, lang, sizes: Sizes, drawn: dict):
    """The plans redrawn so that each kind has one μ, the largest of their fits (every plan
    then fits its cell), each centred in its cell again."""
    common: dict[str, float] = {}
    for res in results.values():
        common[res.kind] = max(common.get(res.kind, 0.0), res.scale)
    views, out = {}, {}
    for name, res in results.items():
        mu = common[res.kind]
        number = int(name.rsplit("-", 1)[1])
        if res.scale != mu:
            key = (res.kind, number, mu)
            if key not in drawn:
                at = res.at_scale(mu)
                drawn[key] = at, plan_view(at, number - 1, number=number, lang=lang,
                                           sizes=sizes.plan)
            res, view = drawn[key]
            x0, y0, x1, y1 = cells[name]
            views[name] = view.at(x0 + (x1 - x0 - view.width_mm) / 2,
                                  y0 + (y1 - y0 - view.height_mm) / 2)
        else:
            views[name] = plan_views[name]
        out[name] = res
    return views, out


def _diagrams_in_free_corner(study: Study, lang, sizes: Sizes, views, area, title_block, gap,
                             fmt):
    """The kinematic diagrams in the largest free rectangle at the lower left corner of the
    drawing area, in a row, a grid or a column; None where they fit nowhere."""
    fx0, fy0, fx1, _ = area
    boxes = [v.bounds for v in views.values()] + [title_block]
    best = None
    for right in sorted({b[0] for b in boxes if b[0] > fx0 + 60.0} | {fx1 + gap}):
        x1 = right - gap
        below = [b[1] for b in boxes if b[0] < x1 and b[2] > fx0]
        y1 = min(below, default=area[3] + gap) - gap
        if x1 - fx0 < MIN_DIAGRAM_MM or y1 - fy0 < 30.0:
            continue
        for arrangement in ("row", "grid", "column"):
            try:
                view = _fit_diagrams(study, lang, sizes, (fx0, fy0, x1, y1), fmt=fmt,
                                     arrangement=arrangement)
            except ScaleError:
                continue
            score = view.width_mm * view.height_mm
            if best is None or score > best[0]:
                best = (score, view.at(fx0, fy0))
    return None if best is None else best[1]


def _mechanism_candidates(mech, kin, fine, n, thick, lang, sizes: Sizes, region, *, extreme=None,
                          fmt: str, count: int = 3, bold=()):
    """Up to `count` schemes at successive ESKD scales, the largest that fits first."""
    x0, y0, x1, y1 = region
    w, h = 0.62 * (x1 - x0), y1 - y0
    wx, wy = extent_m(mech, kin, fine)
    found = 0
    for mu in eskd_scales():
        if wx / mu > w or wy / mu > h:
            continue
        if mech.crank.length / mu < MIN_CRANK_MM:
            break
        view = mechanism_view(mech, mu_l=mu, n=n, thick=thick, lang=lang,
                              sizes=sizes.mechanism, kin=kin, fine=fine, extreme=extreme,
                              bold=bold)
        if fits(view, w, h):
            yield view
            found += 1
            if found >= count:
                return
    if found:
        return
    raise ScaleError(f"the scheme of {mech.name} does not fit {fmt} ({w:.0f} × {h:.0f} mm free) "
                     f"at any ESKD scale with a crank of at least {MIN_CRANK_MM:.0f} mm; "
                     f"use a larger --format")


def _fit_plans(study: Study, chosen, kinds, lang, sizes: Sizes, region, gap, *, fmt: str,
               drawn: dict | None = None):
    """Plans in a grid of equal cells, each at its own standard scale (the largest drawing
    that fits its cell); of the grid shapes tried (a row per kind, a row per position, one
    row, one column) the one giving the longest shortest-plan wins."""
    x0, y0, x1, y1 = region
    W, H = x1 - x0, y1 - y0
    kin = study.kinematics
    K, M = len(chosen), len(kinds)
    kind_major = [(kd, k) for kd in kinds for k in chosen]
    position_major = [(kd, k) for k in chosen for kd in kinds]
    shapes = [(M, K, kind_major), (K, M, position_major), (1, K * M, kind_major),
              (K * M, 1, kind_major)]
    # many plans (all 12 of a course work): the grids between one row and one column too
    count = K * M
    shapes += [(r, math.ceil(count / r), kind_major) for r in range(2, count)
               if (r - 1) * math.ceil(count / r) < count]
    best = None
    cache: dict = {}
    drawn = {} if drawn is None else drawn
    first = {(kd, k): study.plan(kd) for kd, k in kind_major}

    def estimate(shape) -> float:
        """Longest shortest plan (mm) the grid shape promises from the images alone."""
        rows, cols, _ = shape
        cw, ch = (W - gap * (cols - 1)) / cols, (H - gap * (rows - 1)) / rows
        if cw <= 24 or ch <= 38:
            return 0.0
        worst = math.inf
        for (kd, k), res in first.items():
            ew, eh = extent_mm(res, k - 1)
            vec = kin.velocities if kd == "velocity" else kin.accelerations
            peak = float(np.nanmax(np.hypot(vec[k - 1, :, 0], vec[k - 1, :, 1])))
            mu = standard_scale(res.scale * max(ew / (cw - 24), eh / (ch - 38), 1e-9))
            worst = min(worst, peak / mu)
        return worst

    # the most promising grid shapes first; drawing stops at the first that fits
    candidates = sorted(dict.fromkeys((r, c, tuple(o)) for r, c, o in shapes), key=estimate, reverse=True)
    for rows, cols, order in candidates:
        if best is not None:
            break
        cw = (W - gap * (cols - 1)) / cols
        ch = (H - gap * (rows - 1)) / rows
        if cw <= 0 or ch <= 0:
            continue
        fitted = {}
        for kind, number in order:
            key = (kind, number, round(cw, 3), round(ch, 3))
            if key not in cache:
                cache[key] = _fit_one(study.plan(kind), number, lang, sizes, cw, ch,
                                      MIN_PLAN_MM[fmt], drawn)
            if cache[key] is None:
                break
            fitted[kind, number] = cache[key]
        else:
            score = min(f[2] for f in fitted.values())
            if best is None or score > best[0] + 1e-9:
                best = (score, cols, order, cw, ch, fitted)
    if best is None or best[0] < MIN_PLAN_MM[fmt]:
        what = " and ".join(kinds)
        raise ScaleError(f"the {what} plans of positions {', '.join(map(str, chosen))} do not "
                         f"fit {fmt} at any standard scale with vectors of at least "
                         f"{MIN_PLAN_MM[fmt]:.0f} mm ({W:.0f} × {H:.0f} mm free); use fewer "
                         f"--plans or a larger --format")
    score, cols, order, cw, ch, fitted = best
    placed, results, zones = {}, {}, {}
    for j, (kind, number) in enumerate(order):
        res, view, _ = fitted[kind, number]
        results[view.name] = res
        r, c = divmod(j, cols)
        cx = x0 + c * (cw + gap) + (cw - view.width_mm) / 2
        cy = y1 - r * (ch + gap) - ch + (ch - view.height_mm) / 2
        placed[view.name] = view.at(cx, cy)
        zones[view.name] = (x0 + c * (cw + gap), y1 - r * (ch + gap) - ch, x0 + c * (cw + gap) + cw, y1 - r * (ch + gap))
    return placed, results, score, zones


def _standard_from(mu: float):
    """Standard scale values from the one at or above `mu`, increasing."""
    value = standard_scale(mu)
    while True:
        yield value
        value = standard_scale(value * 1.0001)


def _fit_one(res0: PlanResult, number, lang, sizes, cw, ch, least, drawn: dict):
    """(result, view, longest vector mm) of the plan of position ``number`` at the smallest
    standard μ that fits a cell of cw × ch mm, or None."""
    i = number - 1
    kin, kind = res0.kin, res0.kind
    ew, eh = extent_mm(res0, i)
    room_w, room_h = cw - 2 * 12.0, ch - 2 * 12.0 - 14.0
    if room_w <= 0 or room_h <= 0:
        return None
    # start a little below the estimate: labels rarely need the whole margin
    estimate = res0.scale * max(ew / room_w, eh / room_h, 1e-9)
    vec = kin.velocities if kind == "velocity" else kin.accelerations
    peak = float(np.nanmax(np.hypot(vec[[i], :, 0], vec[[i], :, 1])))
    tried = 0
    for mu in _standard_from(estimate / 1.6):
        if tried >= 10 or peak / mu < least:
            return None
        # the images alone must fit the cell (its margins are for the letters): a scale at
        # which they do not is skipped without drawing the view
        if ew * res0.scale / mu > cw or eh * res0.scale / mu > ch - 14.0:
            continue
        tried += 1
        if (kind, number, mu) not in drawn:
            res = res0.at_scale(mu)
            drawn[kind, number, mu] = res, plan_view(res, i, number=number, lang=lang, sizes=sizes.plan)
        res, view = drawn[kind, number, mu]
        if fits(view, cw, ch):
            return res, view, peak / mu
    return None


def sheet_text(sheet: Sheet) -> str:
    """Every text of the sheet, one per line (for tests and search)."""
    from velplan.render.scene import Text

    return "\n".join(t.text for t in sheet.scene.of_kind(Text))
