"""The drawing sheet of a force analysis: for one or two positions the structural groups cut
free with their forces, each group's force polygon and Zhukovsky's lever; along the bottom
the diagram of the balancing moment over a revolution and the table of the three balancing
moments (kinetostatics, lever, power), above the title block.

Every view is drawn at a standard scale: the groups at one ESKD μl, each polygon at its own
μF (N/mm) from the series (1, 2, 2.5, 4, 5)·10ⁿ, the lever at a standard μv. The top band is
filled row by row — a group and its polygon side by side, in the order the groups are
solved (the last group first, the initial link last), then the lever; each position starts
a new row — at the largest drawing for which everything fits. A sheet that cannot show them
legibly raises :class:`~velplan.errors.ScaleError` with a one-line message.

Examples
--------
>>> sheet = build_force_sheet("slider-press", fmt="A1", lang="en")
>>> sheet.positions
(6,)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Mapping, Sequence

import numpy as np

from velplan.errors import ScaleError, VelplanError
from velplan.mechanism.model import Mechanism
from velplan.plans import standard_scale
from velplan.views.forces import (
    ForceSizes, MomentCurve, group_extent_m, group_view, lever_extent, lever_view,
    moment_diagram_view, moments_table_view, polygon_extent, polygon_view, slug)
from velplan.render.i18n import check_language, label
from velplan.render.scene import Scene
from velplan.sheets.frame import TitleInfo, sheet_scene
from velplan.render.style import SheetStyle
from velplan.views.base import PlacedView, View, eskd_scales, ratio_text
from velplan.sheets.layout import (
    FORMATS, MIN_CRANK_MM, MIN_DIAGRAM_MM, SIZES, SheetOutput, check_layout, drawing_area, fill_bottom_band,
    fits)
from velplan.study import Study

#: Text heights and the conventional force-arrow length of the force views, per format.
FORCE_SIZES: Mapping[str, ForceSizes] = MappingProxyType({
    "A1": ForceSizes(5.0, 3.5, 16.0),
    "A2": ForceSizes(3.5, 2.5, 13.0, wrap_balance=True),
    "A3": ForceSizes(3.5, 2.5, 10.0, wrap_balance=True),
})
#: Smallest drawing (mm, its larger side) of a group, a polygon or the lever, per format.
MIN_TARGET_MM: Mapping[str, float] = MappingProxyType({"A1": 40.0, "A2": 35.0, "A3": 30.0})


@dataclass(frozen=True)
class ForceSheet(SheetOutput):
    """A composed force-analysis sheet.

    Attributes
    ----------
    mechanism : Mechanism
    scene : Scene
        Everything drawn, in sheet mm.
    views : Mapping[str, PlacedView]
        ``"group-K-G"``, ``"polygon-K-G"`` (G a group's name, or ``crank``), ``"lever-K"``,
        ``"table"``, ``"mb-diagram"``.
    scales : Mapping[str, float]
        ``"mu_l"`` (m/mm) of the groups, μF (N/mm) of each polygon and μv ((m/s)/mm) of each
        lever by view name, ``"mu_m"`` (N·m/mm) of the diagram.
    analysis : ForceAnalysis
        The force analysis at the n positions.
    positions : tuple of int
        Positions (1-based) drawn.
    n : int
    fmt, lang, frame_style : str
    style : SheetStyle
    info : TitleInfo
    """

    mechanism: Mechanism
    scene: Scene
    views: Mapping[str, PlacedView]
    scales: Mapping[str, float]
    analysis: object
    positions: tuple[int, ...]
    n: int
    fmt: str
    lang: str
    frame_style: str
    style: SheetStyle
    info: TitleInfo


def has_forces(mech: Mechanism) -> bool:
    """Whether `mech` declares masses or loads (something for a force sheet to show)."""
    return bool(mech.masses) or bool(mech.loads)


def default_force_positions(fa) -> tuple[int, ...]:
    """The position of the largest |M_b|; when the useful load does not act there, first the
    position of the largest |M_b| under the load (a working-stroke position)."""
    mb = np.abs(np.asarray(fa.kinetostatics.balancing_moment, float))
    mb = np.where(np.isfinite(mb), mb, -1.0)
    best = int(np.argmax(mb))
    loads = [f for f in fa.actions.forces if f.source == "load"]
    if not loads:
        return (best + 1,)
    acting = np.zeros(len(mb), bool)
    for f in loads:
        acting |= np.abs(np.asarray(f.vector)) > 0
    if acting[best] or not acting.any():
        return (best + 1,)
    working = int(np.argmax(np.where(acting, mb, -1.0)))
    return (working + 1, best + 1)


def default_force_title(mech: Mechanism, lang: str, scale: str) -> TitleInfo:
    """Title block of the force sheet: the second document of the course work."""
    prefix = "ТММ" if lang in ("ru", "uk") else "TMM"
    return TitleInfo(title=f"{label('force_analysis', lang)}: {mech.name_in(lang)}",
                     designation=f"{prefix}.{mech.name}.02", scale=scale)


def solving_order(mech: Mechanism) -> tuple[str, ...]:
    """Groups in the order the kinetostatics solves them, the initial link last."""
    return tuple(g.name for g in reversed(mech.groups)) + ("crank",)


def build_force_sheet(mech: Study | Mechanism | str, *, n: int = 12, plans: Sequence[int] | None = None,
                      fmt: str = "A1", lang: str = "ru", frame_style: str | None = None,
                      info: TitleInfo | None = None, diagrams: bool | None = None,
                      table: bool = True, style: SheetStyle | None = None) -> ForceSheet:
    """Compose the force-analysis sheet of `mech`.

    Parameters
    ----------
    mech : Study, Mechanism or str
        The study to draw, or a mechanism / bundled example name / TOML path to study; it
        must declare masses or loads.
    n : int
        Number of positions of the table and of the marks on the diagram.
    plans : sequence of int, optional
        Positions (1-based) whose groups, polygons and lever are drawn; by default
        :func:`default_force_positions` (the last of them alone when both do not fit).
    fmt : {"A1", "A2", "A3"}
    lang : {"en", "ru", "uk", "zh"}
    frame_style : {"eskd", "iso"}, optional
    info : TitleInfo, optional
        Title block fields; the scale field is filled with the groups' scale when empty.
    diagrams : bool or None
        Draw the diagram M_b(φ) (True: or raise ScaleError), leave it out (False), or draw
        it when it fits (None).
    table : bool
        Draw the table of the balancing moments.

    Raises
    ------
    ScaleError
        A view cannot be drawn legibly at any standard scale in its part of the sheet.
    VelplanError
        Bad options, or a mechanism with no masses and no loads.
    """
    study = mech if isinstance(mech, Study) else Study(mech, n=n)
    mech, n = study.mechanism, study.n
    check_language(lang)
    if fmt not in FORMATS:
        raise VelplanError(f"unknown sheet format {fmt!r}; known formats: {', '.join(FORMATS)}")
    if n < 3:
        raise VelplanError(f"a sheet needs at least 3 positions, not {n}")
    if not has_forces(mech):
        raise VelplanError(f"{mech.name} declares no masses and no loads: there are no forces "
                           f"to draw; add [link.N] masses or [[load]] tables")
    kin = study.kinematics
    bad = np.flatnonzero(~kin.valid)
    if bad.size:
        raise VelplanError(f"{mech.name} cannot be assembled at position {bad[0] + 1} "
                           f"(crank angle {math.degrees(kin.phi[bad[0]]):.6g}°)")
    fa = study.forces()
    chosen = tuple(default_force_positions(fa) if plans is None else plans)
    if not chosen:
        raise VelplanError("--plans: give at least one position")
    for k in chosen:
        if not (isinstance(k, (int, np.integer)) and 1 <= k <= n):
            raise VelplanError(f"--plans: position {k} is outside 1…{n}")
    if len(set(chosen)) != len(chosen):
        raise VelplanError(f"--plans: a position is repeated in {', '.join(map(str, chosen))}")
    for k in chosen:
        for name, poly in fa.kinetostatics.polygons.items():
            if not np.all(np.isfinite(poly.vertices()[k - 1])):
                raise VelplanError(f"position {k} is singular for the force analysis (group "
                                   f"{name} has no unique reactions there); choose another "
                                   f"with --plans")
    frame_style = frame_style or ("eskd" if lang in ("ru", "uk") else "iso")
    style = style or SheetStyle(language=lang)
    sizes = SIZES[fmt]
    fsizes = FORCE_SIZES[fmt]
    g = sizes.gap

    (fx0, fy0, fx1, fy1), (tx0, ty0, tx1, ty1) = drawing_area(fmt, frame_style)
    W, H = fx1 - fx0, fy1 - fy0
    views: dict[str, PlacedView] = {}
    scales: dict[str, float] = {}

    # the bottom band: the table above the title block, the diagram to their left
    tview = _fit_table(fa, lang, sizes, max_width=0.62 * W, fmt=fmt) if table else None
    band_top, dview = fill_bottom_band(
        views, (fx0, fy0, fx1, fy1), (tx0, ty0, tx1, ty1), g, table_view=tview,
        fit_diagram=None if diagrams is False else (lambda r: _fit_diagram(study, lang, sizes, r, fmt=fmt)),
        diagram_share=0.26, required=bool(diagrams), diagram_name="mb-diagram")
    if dview is not None:
        scales["mu_m"] = dview.meta["mu_m"]

    # the top band: a row per position of groups with their polygons, then the lever
    top = (fx0, band_top + g, fx1, fy1)
    try:
        placed, top_scales = _fit_top(fa, chosen, lang, fsizes, top, g, fmt=fmt)
    except ScaleError:
        if plans is not None or len(chosen) == 1:
            raise
        # the default pair does not fit: the position of the largest |M_b| alone
        chosen = (chosen[-1],)
        placed, top_scales = _fit_top(fa, chosen, lang, fsizes, top, g, fmt=fmt)
    views.update(placed)
    scales.update(top_scales)

    if info is None:
        info = default_force_title(mech, lang, ratio_text(scales["mu_l"], lang))
    elif not info.scale:
        info = replace(info, scale=ratio_text(scales["mu_l"], lang))
    check_layout(views, fmt, frame_style)
    scene = sheet_scene(info, fmt, frame_style=frame_style, lang=lang)
    order = [k for k in views if k not in ("mb-diagram", "table")] + [
        k for k in ("mb-diagram", "table") if k in views]
    scene = scene.extend(*(views[k].primitives for k in order))
    return ForceSheet(mech, scene, MappingProxyType(dict(views)), MappingProxyType(scales), fa,
                      chosen, n, fmt, lang, frame_style, style, info)


def _fit_table(fa, lang, sizes, *, max_width: float, fmt: str) -> View:
    for size in sizes.table:
        view = moments_table_view(fa, lang=lang, size_mm=size, title_mm=sizes.table_title)
        if view.width_mm <= max_width:
            return view
    n = len(fa.kinematics)
    raise ScaleError(f"the table of balancing moments ({n} positions) does not fit {fmt} even "
                     f"with 1.8 mm text ({view.width_mm:.0f} mm wide, {max_width:.0f} mm "
                     f"free); use fewer --positions or a larger --format")


def moment_curve(study: Study) -> MomentCurve:
    """M_b by kinetostatics over a revolution from position 1, on the study's fine turn."""
    turn = study.turn_forces()
    rot = study.sense * (turn.kinematics.phi - turn.kinematics.phi[0])
    return MomentCurve(rot, np.asarray(turn.balancing_moments["kinetostatics"], float),
                       np.asarray(study.forces().kinetostatics.balancing_moment, float))


def _fit_diagram(study: Study, lang, sizes, region, *, fmt: str) -> View:
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    curve = moment_curve(study)

    def build(length, height):
        return moment_diagram_view(curve, length_mm=length, height_mm=height, lang=lang,
                                   label_mm=sizes.diagram.label_mm,
                                   title_mm=sizes.diagram.title_mm)

    for length in (360.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0, 60.0):
        if length < MIN_DIAGRAM_MM or build(length, 10.0).width_mm > w:
            continue
        for height in (120.0, 100.0, 80.0, 60.0, 50.0, 40.0, 30.0, 25.0, 20.0):
            if height > 0.5 * length:
                continue
            view = build(length, height)
            if fits(view, w, h):
                return view
        break
    raise ScaleError(f"the balancing moment diagram does not fit {fmt} ({w:.0f} × {h:.0f} mm "
                     f"free beside the title block) with a φ axis of at least "
                     f"{MIN_DIAGRAM_MM:.0f} mm; use a larger --format")


def _fit_top(fa, chosen, lang, fsizes: ForceSizes, region, gap, *, fmt: str):
    """Groups, polygons and levers of the chosen positions, a row per position under its
    heading: each group with its polygon beside it or under it (whichever arrangement
    leaves the larger drawings), then the lever."""
    best = None
    failure = None
    for mode in ("row", "stack"):
        try:
            found = _fit_rows(fa, chosen, lang, fsizes, region, gap, fmt=fmt, mode=mode)
        except ScaleError as exc:
            failure = failure or exc
            continue
        if best is None or found[2] > best[2] + 1e-9:
            best = found
    if best is None:
        raise failure
    return best[0], best[1]


def _fit_rows(fa, chosen, lang, fsizes: ForceSizes, region, gap, *, fmt: str, mode: str):
    """One arrangement of :func:`_fit_top`: (placed views, scales, score). Each drawing
    starts at the largest standard scale that fits the row's height; while a row is too
    wide, the drawing that makes it so (the groups together, which share μl, or one
    polygon, or the lever; the widest view first) goes one standard scale smaller. The
    score is the sum over the views of the logarithm of their drawings' sizes."""
    mech = fa.kinetostatics.mechanism
    ks = fa.kinetostatics
    x0, y0, x1, y1 = region
    W, H = x1 - x0, y1 - y0
    order = solving_order(mech)
    count = len(chosen)
    head_h = 1.6 * fsizes.title_mm + 2.0
    row_h = (H - gap * (count - 1)) / count - head_h - gap / 2
    least = MIN_TARGET_MM[fmt]

    def fail(why: str) -> ScaleError:
        return ScaleError(
            f"the groups, force polygons and lever of position{'s' if count > 1 else ''} "
            f"{', '.join(map(str, chosen))} do not fit {fmt} at any standard scale with "
            f"drawings of at least {least:.0f} mm ({W:.0f} × {H:.0f} mm free, {why}); use "
            f"fewer --plans or a larger --format")

    if row_h < least:
        raise fail(f"rows of {max(row_h, 0):.0f} mm")
    eskd = eskd_scales()
    group_span = max(max(group_extent_m(fa, grp, k - 1)) for k in chosen for grp in order)
    span: dict = {"groups": group_span}
    for k in chosen:
        for grp in order:
            span[("poly", k, grp)] = max(max(polygon_extent(ks.polygons[grp], k - 1)), 1e-9)
        span[("lever", k)] = max(max(lever_extent(fa, k - 1)), 1e-12)
    # the starting scales: each drawing as tall as a row
    scale: dict = {"groups": next((mu for mu in eskd if group_span / mu <= row_h), eskd[-1])}
    for e, value in span.items():
        if e != "groups":
            scale[e] = standard_scale(value / row_h)
    cache: dict = {}

    def entity_of(ref):
        kind, k, grp = ref
        return "groups" if kind == "group" else ((kind, k, grp) if kind == "poly" else (kind, k))

    def build(ref) -> View:
        kind, k, grp = ref
        mu = scale[entity_of(ref)]
        ck = (ref, round(mu, 12))
        if ck not in cache:
            i = k - 1
            if kind == "group":
                cache[ck] = group_view(fa, grp, i, mu_l=mu, number=k, lang=lang, sizes=fsizes)
            elif kind == "poly":
                cache[ck] = polygon_view(fa, grp, i, mu_f=mu, number=k, lang=lang, sizes=fsizes)
            else:
                cache[ck] = lever_view(fa, i, mu_v=mu, number=k, lang=lang, sizes=fsizes)
        return cache[ck]

    layout = [[[("group", k, grp), ("poly", k, grp)] for grp in order] + [[("lever", k, None)]]
              for k in chosen]

    def unit_size(unit) -> tuple[float, float]:
        vs = [build(r) for r in unit]
        if mode == "stack" or len(vs) == 1:
            return max(v.width_mm for v in vs), sum(v.height_mm for v in vs) + gap * (len(vs) - 1)
        return sum(v.width_mm for v in vs) + gap * (len(vs) - 1), max(v.height_mm for v in vs)

    def smaller(entity) -> float | None:
        """The next smaller drawing of `entity`, or None below the legible size."""
        mu = scale[entity]
        if entity == "groups":
            j = eskd.index(mu) + 1
            if j >= len(eskd):
                return None
            nxt = eskd[j]
            if group_span / nxt < least or mech.crank.length / nxt < MIN_CRANK_MM:
                return None
            return nxt
        nxt = standard_scale(mu * 1.0001)
        return nxt if span[entity] / nxt >= least else None

    stuck: set = set()
    for _ in range(400):
        tall = None
        for units in layout:
            for unit in units:
                if unit_size(unit)[1] > row_h + 1e-6:
                    tall = max(unit, key=lambda r: build(r).height_mm)
                    break
            if tall:
                break
        if tall is not None:
            # the tallest drawing of the unit goes smaller; one at its least, the next tallest
            unit = next(u for units in layout for u in units if tall in u)
            shrink = [r for r in sorted(unit, key=lambda r: -build(r).height_mm)
                      if smaller(entity_of(r)) is not None]
            if not shrink:
                raise fail(f"{build(tall).name} is {build(tall).height_mm:.0f} mm tall")
            scale[entity_of(shrink[0])] = smaller(entity_of(shrink[0]))
            continue
        widths = [sum(unit_size(u)[0] for u in units) + gap * (len(units) - 1)
                  for units in layout]
        worst = int(np.argmax(widths))
        if widths[worst] <= W + 1e-6:
            break
        share: dict = {}
        for unit in layout[worst]:
            vs = [build(r) for r in unit]
            for r, v in zip(unit, vs):
                if mode == "row" or v.width_mm >= max(w.width_mm for w in vs) - 1e-9:
                    share[entity_of(r)] = max(share.get(entity_of(r), 0.0), v.width_mm)
        candidates = sorted((e for e in share if e not in stuck and smaller(e) is not None),
                            key=lambda e: (-share[e], str(e)))
        if not candidates:
            raise fail(f"a row {widths[worst]:.0f} mm wide")
        entity = candidates[0]
        old = scale[entity]
        scale[entity] = smaller(entity)
        after = sum(unit_size(u)[0] for u in layout[worst]) + gap * (len(layout[worst]) - 1)
        if after > widths[worst] - 0.5:
            scale[entity] = old  # its width is its text's: a smaller drawing gains nothing
            stuck.add(entity)
    else:
        raise fail("no layout found")

    # place the rows from the top, the spare height shared out between them
    heights = [max(unit_size(u)[1] for u in units) for units in layout]
    spare = max(H - sum(h + head_h for h in heights) - gap * (count - 1), 0.0) / count
    placed: dict[str, PlacedView] = {}
    scales: dict[str, float] = {"mu_l": scale["groups"]}
    y = y1
    for k, units, height in zip(chosen, layout, heights):
        heading = _heading(fa, k, lang, fsizes)
        placed[heading.name] = heading.at(x0, y - heading.height_mm)
        y -= head_h
        sizes = [unit_size(u) for u in units]
        total = sum(w for w, _ in sizes) + gap * (len(units) - 1)
        extra = max(W - total, 0.0) / len(units)
        x = x0 + extra / 2
        for unit, (uw, _) in zip(units, sizes):
            cx, cy = x, y
            for ref in unit:
                v = build(ref)
                placed[v.name] = v.at(cx, cy - v.height_mm)
                if ref[0] != "group":
                    scales[v.name] = scale[entity_of(ref)]
                if mode == "stack":
                    cy -= v.height_mm + gap
                else:
                    cx += v.width_mm + gap
            x += uw + gap + extra
        y -= height + gap + spare
    score = sum(math.log(span[entity_of(r)] / scale[entity_of(r)])
                for units in layout for unit in units for r in unit)
    return placed, scales, score


def _heading(fa, k: int, lang: str, fsizes: ForceSizes) -> View:
    """The row's heading: the position, its crank angle, and that forces are not to scale."""
    from velplan.render.scene import Text
    from velplan.views.base import fixed, make_view

    deg = math.degrees(float(fa.kinematics.phi[k - 1])) % 360.0
    text = (f"{label('position', lang)} {k}: φ = {fixed(deg, lang, 1)}°; "
            f"{label('forces_not_to_scale', lang)}")
    return make_view(f"heading-{k}", [Text((0.0, 0.0), text, "fheading", fsizes.title_mm)],
                     pad_mm=1.0, meta={"number": k})


def force_sheet_text(sheet: ForceSheet) -> str:
    """Every text of the sheet, one per line."""
    from velplan.render.scene import Text

    return "\n".join(t.text for t in sheet.scene.of_kind(Text))


__all__ = ["ForceSheet", "build_force_sheet", "default_force_positions", "default_force_title",
           "force_sheet_text", "has_forces", "moment_curve", "solving_order", "slug"]
