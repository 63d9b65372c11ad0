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
>>> sheet.scales["mu_l"], sorted(sheet.views)[:2]
(0.001, ['diagrams', 'mechanism'])
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Literal, Mapping, Sequence

import numpy as np
import shapely

from velplan.analysis.extremes import positions as crank_positions
from velplan.analysis.solver import solve
from velplan.errors import ScaleError, VelplanError
from velplan.io import write_atomic
from velplan.mechanism.loader import load
from velplan.mechanism.model import Mechanism
from velplan.plans import Plan, standard_scale
from velplan.plans.engine import PlanResult
from velplan.render.diagram_view import DiagramSizes, diagram_view
from velplan.render.i18n import check_language, label
from velplan.render.mechanism_view import MechanismSizes, extent_m, mechanism_view
from velplan.render.plan_view import PlanSizes, extent_mm, plan_view
from velplan.render.scene import Scene
from velplan.render.sheet import (
    TitleInfo, frame_bounds, free_area, sheet_scene, title_block_bounds)
from velplan.render.style import SheetStyle
from velplan.render.table_view import sheet_table, table_view
from velplan.render.view import PlacedView, View, eskd_scales, ratio_text

Kind = Literal["velocity", "acceleration", "both"]
Format = Literal["A1", "A2", "A3"]
FORMATS: tuple[str, ...] = ("A1", "A2", "A3")
KINDS: tuple[str, ...] = ("velocity", "acceleration", "both")

#: Shortest longest-vector a plan may have on the sheet, mm, per format: below it a plan is
#: unreadable.
MIN_PLAN_MM: Mapping[str, float] = MappingProxyType({"A1": 35.0, "A2": 30.0, "A3": 25.0})
#: Longest vector of the shortest plan that a sheet is content with, mm, per format.
GOOD_PLAN_MM: Mapping[str, float] = MappingProxyType({"A1": 90.0, "A2": 70.0, "A3": 50.0})
#: Shortest crank a scheme may show, mm.
MIN_CRANK_MM = 8.0
#: Shortest φ axis of a diagram, mm.
MIN_DIAGRAM_MM = 60.0


@dataclass(frozen=True)
class _Sizes:
    gap: float
    mechanism: MechanismSizes
    plan: PlanSizes
    table: tuple[float, ...]
    table_title: float
    diagram: DiagramSizes


_SIZES: Mapping[str, _Sizes] = MappingProxyType({
    "A1": _Sizes(10.0, MechanismSizes(5.0, 3.5, 2.5), PlanSizes(5.0, 3.5), (3.5, 2.5, 1.8), 5.0,
                 DiagramSizes(3.5, 2.5)),
    "A2": _Sizes(8.0, MechanismSizes(5.0, 3.5, 2.5), PlanSizes(3.5, 3.5), (2.5, 1.8), 3.5,
                 DiagramSizes(3.5, 2.5)),
    "A3": _Sizes(6.0, MechanismSizes(3.5, 2.5, 2.5), PlanSizes(3.5, 2.5), (1.8,), 2.5,
                 DiagramSizes(2.5, 1.8)),
})


class SheetOutput:
    """What every composed sheet offers: its SVG text and its files (needs ``scene`` and
    ``style`` attributes)."""

    def svg(self, *, precision: int = 3) -> str:
        """The sheet as an SVG document; the same sheet gives the same bytes."""
        from velplan.render.svg import to_svg

        return to_svg(self.scene, self.style, precision=precision)

    def write(self, path: str | os.PathLike, *, png: bool = False, pdf: bool = False,
              dpi: float = 150.0) -> list[Path]:
        """Write the SVG to `path` (and a PNG / PDF beside it), atomically; returns the files.

        Conversions run before anything is written, so a failure leaves no file behind.
        """
        return write_outputs(self.svg(), path, png=png, pdf=pdf, dpi=dpi)


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
        View name → the plan evaluated at its one position (index 0).
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
    positions: tuple[int, ...]
    n: int
    fmt: str
    lang: str
    frame_style: str
    style: SheetStyle
    info: TitleInfo



def write_outputs(svg: str, path: str | os.PathLike, *, png: bool = False, pdf: bool = False,
                  dpi: float = 150.0) -> list[Path]:
    """Write an SVG document to `path` and, when asked, its PNG and PDF beside it."""
    from velplan.render import export

    target = Path(path)
    if target.suffix.lower() in (".png", ".pdf"):
        png = png or target.suffix.lower() == ".png"
        pdf = pdf or target.suffix.lower() == ".pdf"
        target = target.with_suffix(".svg")
    if not target.parent.is_dir():
        raise VelplanError(f"cannot write {target}: directory {target.parent} does not exist")
    blobs: list[tuple[bytes, Path]] = []
    if png:
        blobs.append((export._convert("svg2png", svg, dpi=dpi, background_color="white"),
                      target.with_suffix(".png")))
    if pdf:
        blobs.append((export._convert("svg2pdf", svg), target.with_suffix(".pdf")))
    written = [export.write_svg(svg, target)]
    for data, where in blobs:
        written.append(write_atomic(where, data))
    return written


def default_plan_positions(mech: Mechanism, kin) -> tuple[int, ...]:
    """Two positions worth drawing plans for: one in each half of the turn (the working and
    the return stroke), each the one whose velocity plan shows the most distinct images with
    well-conditioned intersections, near a quarter of the half when that is a tie.

    Positions where the plan collapses (a rod translating for an instant, an extreme
    position) teach nothing and are avoided.
    """
    n = len(kin)
    if n < 4:
        return (min(2, n),)
    res = Plan.of(mech).evaluate(kin, kind="velocity")
    ground = set(mech.ground_points)
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
    return TitleInfo(title=f"{label('kinematic_analysis', lang)}: {mech.name}",
                     designation=f"{prefix}.{mech.name}.01", scale=scale)


def build_sheet(mech: Mechanism | str, *, n: int = 12, plans: Sequence[int] | None = None,
                kind: Kind = "both", fmt: Format = "A1", lang: str = "ru",
                frame_style: str | None = None, info: TitleInfo | None = None,
                diagrams: bool | None = None, table: bool = True,
                style: SheetStyle | None = None) -> Sheet:
    """Compose the kinematic-analysis sheet of `mech`.

    Parameters
    ----------
    mech : Mechanism or str
        The mechanism, or a bundled example name / TOML path.
    n : int
        Number of positions of the scheme, the table and the diagrams.
    plans : sequence of int, optional
        Positions (1-based) whose plans are drawn; two by default
        (:func:`default_plan_positions`). The first one is drawn thick in the scheme.
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
        or draw them when they fit and the mechanism names an output (None, the default:
        an A3 sheet has no room for them beside the table).
    table : bool
        Draw the table of transfer functions.

    Raises
    ------
    ScaleError
        A view cannot be drawn legibly at any standard scale in its part of the sheet.
    VelplanError
        Bad options (unknown format, kind or language, positions out of range).
    """
    if isinstance(mech, str):
        mech = load(mech)
    check_language(lang)
    if fmt not in FORMATS:
        raise VelplanError(f"unknown sheet format {fmt!r}; known formats: {', '.join(FORMATS)}")
    if kind not in KINDS:
        raise VelplanError(f"unknown plan kind {kind!r}; known kinds: {', '.join(KINDS)}")
    if n < 3:
        raise VelplanError(f"a sheet needs at least 3 positions, not {n}")
    kin = solve(mech, crank_positions(mech, n))
    bad = np.flatnonzero(~kin.valid)
    if bad.size:
        raise VelplanError(f"{mech.name} cannot be assembled at position {bad[0] + 1} "
                           f"(crank angle {math.degrees(kin.phi[bad[0]]):.6g}°)")
    chosen = tuple(default_plan_positions(mech, kin) if plans is None else plans)
    if not chosen:
        raise VelplanError("--plans: give at least one position")
    for k in chosen:
        if not (isinstance(k, (int, np.integer)) and 1 <= k <= n):
            raise VelplanError(f"--plans: position {k} is outside 1…{n}")
    if len(set(chosen)) != len(chosen):
        raise VelplanError(f"--plans: a position is repeated in {', '.join(map(str, chosen))}")
    frame_style = frame_style or ("eskd" if lang in ("ru", "uk") else "iso")
    style = style or SheetStyle(language=lang)
    sizes = _SIZES[fmt]
    g = sizes.gap

    sense = 1.0 if mech.crank.omega >= 0 else -1.0
    fine = solve(mech, kin.phi[0] + sense * np.linspace(0.0, 2 * np.pi, 241))

    fx0, fy0, fx1, fy1 = frame_bounds(fmt)
    tx0, ty0, tx1, ty1 = title_block_bounds(fmt, frame_style)
    m = 4.0  # clearance from the frame lines
    fx0, fy0, fx1, fy1 = fx0 + m, fy0 + m, fx1 - m, fy1 - m
    W, H = fx1 - fx0, fy1 - fy0
    views: dict[str, PlacedView] = {}

    # the bottom band: the table above the title block, the diagrams to their left
    right_w = tx1 - tx0
    band_top = ty1 + g
    tview = None
    if table:
        tview = _fit_table(mech, n, lang, sizes, max_width=0.62 * W, fmt=fmt)
        right_w = max(right_w, tview.width_mm)
        band_top = ty1 + g + tview.height_mm
        views["table"] = tview.at(fx1 - tview.width_mm, ty1 + g)
    if diagrams and mech.output is None:
        raise VelplanError(f"{mech.name} names no output, so it has no kinematic diagrams")
    if diagrams is not False and mech.output is not None:
        region = (fx0, fy0, fx1 - right_w - g, max(band_top, fy0 + 0.3 * H))
        try:
            dview = _fit_diagrams(mech, n, lang, sizes, region, fmt=fmt,
                                  start=float(kin.phi[0]))
        except ScaleError:
            if diagrams:
                raise
            dview = None
        if dview is not None:
            band_top = max(band_top, fy0 + dview.height_mm)
            views["diagrams"] = dview.at(fx0, fy0)

    # the top band: the scheme, then the plans to its right
    top = (fx0, band_top + g, fx1, fy1)
    thick = chosen[0]
    kinds = ("velocity", "acceleration") if kind == "both" else (kind,)
    # the largest scheme whose neighbours, the plans, still get vectors of a good length;
    # failing that, the scheme that leaves the plans the longest vectors
    best, failure = None, None
    for mview in _mechanism_candidates(mech, kin, fine, n, thick, lang, sizes, top, fmt=fmt):
        # the plans go to the right of the scheme, or below it across the sheet
        regions = [(fx0 + mview.width_mm + g, band_top + g, fx1, fy1),
                   (fx0, band_top + g, fx1, fy1 - mview.height_mm - g)]
        good = False
        for plan_region in regions:
            if plan_region[2] - plan_region[0] < 40 or plan_region[3] - plan_region[1] < 40:
                continue
            try:
                plan_views, results, score = _fit_plans(mech, kin, chosen, kinds, lang, sizes,
                                                        plan_region, g, fmt=fmt)
            except ScaleError as exc:
                failure = failure or exc
                continue
            if best is None or score > best[0]:
                best = (score, mview, plan_views, results)
            good = good or score >= GOOD_PLAN_MM[fmt]
        if good:
            break
    if best is None:
        raise failure
    _, mview, plan_views, results = best
    views["mechanism"] = mview.at(fx0, fy1 - mview.height_mm)
    views.update(plan_views)

    scales = {"mu_l": mview.mu}
    for name, res in results.items():
        scales[name] = res.scale
    if info is None:
        info = default_title(mech, lang, fmt, ratio_text(mview.mu), frame_style)
    elif not info.scale:
        from dataclasses import replace
        info = replace(info, scale=ratio_text(mview.mu))
    _check_layout(views, fmt, frame_style)
    scene = sheet_scene(info, fmt, frame_style=frame_style, lang=lang)
    order = ["mechanism"] + sorted(k for k in views if k.startswith("plan-")) + [
        k for k in ("diagrams", "table") if k in views]
    scene = scene.extend(*(views[k].primitives for k in order))
    return Sheet(mech, scene, MappingProxyType(dict(views)), MappingProxyType(scales),
                 MappingProxyType(results), chosen, n, fmt, lang, frame_style, style, info)


def _fits(view: View, w: float, h: float) -> bool:
    return view.width_mm <= w + 1e-6 and view.height_mm <= h + 1e-6


def _fit_table(mech, n, lang, sizes: _Sizes, *, max_width: float, fmt: str) -> View:
    data = sheet_table(mech, n)
    for size in sizes.table:
        view = table_view(data, mech, lang=lang, size_mm=size, title_mm=sizes.table_title)
        if view.width_mm <= max_width:
            return view
    raise ScaleError(f"the table of transfer functions ({n} positions) does not fit {fmt} "
                     f"even with 1.8 mm text ({view.width_mm:.0f} mm wide, "
                     f"{max_width:.0f} mm free); use fewer --positions or a larger --format")


def _fit_diagrams(mech, n, lang, sizes: _Sizes, region, *, fmt: str, start: float) -> View:
    from velplan.diagrams import kinematic_diagrams

    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    d = kinematic_diagrams(mech, n, start=start)
    best = None

    def build(length, height):
        return diagram_view(d, length_mm=length, height_mm=height, lang=lang,
                            arrangement="row", sizes=sizes.diagram)

    # the longest φ axis (μφ a round number of degrees per mm) that fits with the lowest
    # diagrams, then the highest diagrams that fit with it
    for length in (360.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0, 60.0):
        if build(length, 10.0).width_mm <= w:
            for height in (60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0, 12.0, 10.0):
                view = build(length, height)
                if _fits(view, w, h):
                    best = (length * height, view)
                    break
            break
    if best is None:
        raise ScaleError(f"the kinematic diagrams do not fit {fmt} ({w:.0f} × {h:.0f} mm free "
                         f"beside the title block) with a φ axis of at least "
                         f"{MIN_DIAGRAM_MM:.0f} mm; use a larger --format")
    return best[1]


def _mechanism_candidates(mech, kin, fine, n, thick, lang, sizes: _Sizes, region, *,
                          fmt: str, count: int = 3):
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
                              sizes=sizes.mechanism, kin=kin, fine=fine)
        if _fits(view, w, h):
            yield view
            found += 1
            if found >= count:
                return
    if found:
        return
    raise ScaleError(f"the scheme of {mech.name} does not fit {fmt} ({w:.0f} × {h:.0f} mm free) "
                     f"at any ESKD scale with a crank of at least {MIN_CRANK_MM:.0f} mm; "
                     f"use a larger --format")


def _fit_plans(mech, kin, chosen, kinds, lang, sizes: _Sizes, region, gap, *, fmt: str):
    """Plans in a grid of equal cells, each at its own standard scale (the largest drawing
    that fits its cell); of the grid shapes tried (a row per kind, a row per position, one
    row, one column) the one giving the longest shortest-plan wins."""
    x0, y0, x1, y1 = region
    W, H = x1 - x0, y1 - y0
    plan = Plan.of(mech)
    K, M = len(chosen), len(kinds)
    kind_major = [(kd, k) for kd in kinds for k in chosen]
    position_major = [(kd, k) for k in chosen for kd in kinds]
    shapes = [(M, K, kind_major), (K, M, position_major), (1, K * M, kind_major),
              (K * M, 1, kind_major)]
    best = None
    cache: dict = {}
    first = {(kd, k): plan.evaluate(kin, kind=kd, positions=[k - 1]) for kd, k in kind_major}

    def estimate(shape) -> float:
        """Longest shortest plan (mm) the grid shape promises from the images alone."""
        rows, cols, _ = shape
        cw, ch = (W - gap * (cols - 1)) / cols, (H - gap * (rows - 1)) / rows
        if cw <= 24 or ch <= 38:
            return 0.0
        worst = math.inf
        for (kd, k), res in first.items():
            ew, eh = extent_mm(res, 0)
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
                cache[key] = _fit_one(plan, kin, number, kind, lang, sizes, cw, ch,
                                      MIN_PLAN_MM[fmt])
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
    placed, results = {}, {}
    for j, (kind, number) in enumerate(order):
        res, view, _ = fitted[kind, number]
        results[view.name] = res
        r, c = divmod(j, cols)
        cx = x0 + c * (cw + gap) + (cw - view.width_mm) / 2
        cy = y1 - r * (ch + gap) - ch + (ch - view.height_mm) / 2
        placed[view.name] = view.at(cx, cy)
    return placed, results, score


def _standard_from(mu: float):
    """Standard scale values from the one at or above `mu`, increasing."""
    value = standard_scale(mu)
    while True:
        yield value
        value = standard_scale(value * 1.0001)


def _fit_one(plan, kin, number, kind, lang, sizes, cw, ch, least):
    """(result, view, longest vector mm) of one plan at the smallest standard μ that fits a
    cell of cw × ch mm, or None."""
    idx = [number - 1]
    res0 = plan.evaluate(kin, kind=kind, positions=idx)
    ew, eh = extent_mm(res0, 0)
    room_w, room_h = cw - 2 * 12.0, ch - 2 * 12.0 - 14.0
    if room_w <= 0 or room_h <= 0:
        return None
    # start a little below the estimate: labels rarely need the whole margin
    estimate = res0.scale * max(ew / room_w, eh / room_h, 1e-9)
    vec = kin.velocities if kind == "velocity" else kin.accelerations
    peak = float(np.nanmax(np.hypot(vec[idx, :, 0], vec[idx, :, 1])))
    key = "scale_v" if kind == "velocity" else "scale_a"
    tried = 0
    for mu in _standard_from(estimate / 1.6):
        if tried >= 10 or peak / mu < least:
            return None
        # the images alone must fit the cell (its margins are for the letters): a scale at
        # which they do not is skipped without drawing the view
        if ew * res0.scale / mu > cw or eh * res0.scale / mu > ch - 14.0:
            continue
        tried += 1
        res = plan.evaluate(kin, kind=kind, positions=idx, **{key: mu})
        view = plan_view(res, 0, number=number, lang=lang, sizes=sizes.plan)
        if _fits(view, cw, ch):
            return res, view, peak / mu
    return None


def _check_layout(views: Mapping[str, PlacedView], fmt: str, frame_style: str) -> None:
    """Every view inside the free area, no two views overlapping (a layout bug otherwise)."""
    area = free_area(fmt, frame_style=frame_style).buffer(1e-6)
    boxes = {k: shapely.box(*v.bounds) for k, v in views.items()}
    for k, box in boxes.items():
        if not area.contains(box):
            raise ScaleError(f"the {k} view ({box.bounds[2] - box.bounds[0]:.0f} × "
                             f"{box.bounds[3] - box.bounds[1]:.0f} mm) does not fit the free "
                             f"area of {fmt}; use a larger --format")
    names = sorted(boxes)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if boxes[a].intersection(boxes[b]).area > 1e-6:
                raise ScaleError(f"the {a} and {b} views overlap on {fmt}; use a larger "
                                 f"--format or fewer --plans")


def sheet_text(sheet: Sheet) -> str:
    """Every text of the sheet, one per line (for tests and search)."""
    from velplan.render.scene import Text

    return "\n".join(t.text for t in sheet.scene.of_kind(Text))
