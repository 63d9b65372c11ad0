"""The drawing sheet of the machine dynamics: the reduced moments, the works and ΔT, the
variable reduced inertia and the crank's ω over the cycle stacked on the left (one φ axis
length); Wittenbauer's energy–mass diagram with its tangents on the right; the flywheel's
section with its dimensions and the table of results above the title block.

A run (``[dynamics.run]``) has no flywheel to size: its sheet shows the curves over the
run's travel and the results. Each view takes the largest drawing that fits its region; a
sheet that cannot show them legibly raises :class:`~velplan.errors.ScaleError`.

Examples
--------
>>> sheet = build_dynamics_sheet("shaper-lever-rod", fmt="A1", lang="en")
>>> sorted(sheet.views)[:3]
['flywheel', 'inertia', 'moments']
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Mapping

import numpy as np

from velplan.errors import ScaleError, VelplanError
from velplan.mechanism.model import Mechanism
from velplan.render.i18n import check_language, label
from velplan.render.scene import Scene
from velplan.render.style import SheetStyle
from velplan.sheets.frame import TitleInfo, sheet_scene
from velplan.sheets.layout import FORMATS, MIN_DIAGRAM_MM, SIZES, SheetOutput, check_layout, drawing_area, fits
from velplan.study import Study
from velplan.views.base import PlacedView, View, eskd_scales, number, ratio_text, scale_mark, unit
from velplan.views.dynamics import (
    DynamicsSizes, Series, curve_panel, flywheel_view, results_rows, results_view, wittenbauer_view)

PANELS = ("moments", "works", "inertia", "omega")
"""The curve panels, top to bottom."""


@dataclass(frozen=True)
class DynamicsSheet(SheetOutput):
    """A composed dynamics sheet.

    Attributes
    ----------
    views : Mapping[str, PlacedView]
        ``"moments"``, ``"works"``, ``"inertia"``, ``"omega"``, ``"wittenbauer"``,
        ``"flywheel"``, ``"results"`` (the last three when there is a flywheel to size).
    scales : Mapping[str, float]
        μ of each panel's ordinate (its units per mm), ``"mu_phi"`` (rad/mm), ``"mu_J"``,
        ``"mu_T"`` of the Wittenbauer diagram, ``"flywheel"`` (m/mm).
    dynamics : Dynamics
    wittenbauer : Wittenbauer or None
        The diagram as drawn (its scales and the segment read off it).
    """

    mechanism: Mechanism
    scene: Scene
    views: Mapping[str, PlacedView]
    scales: Mapping[str, float]
    dynamics: object
    wittenbauer: object
    fmt: str
    lang: str
    frame_style: str
    style: SheetStyle
    info: TitleInfo


def default_dynamics_title(mech: Mechanism, lang: str, scale: str) -> TitleInfo:
    """Title block of the dynamics sheet: the third document of the course work."""
    prefix = "ТММ" if lang in ("ru", "uk") else "TMM"
    return TitleInfo(title=f"{label('dynamic_analysis', lang)}: {mech.name_in(lang)}",
                     designation=f"{prefix}.{mech.name}.03", scale=scale)


def _panels(d, c, lang: str, length: float, height: float, sizes: DynamicsSizes, positions: int) -> dict[str, View]:
    """The four curve panels of ``d`` from its curves ``c`` (`Dynamics.curves`)."""
    travel = np.radians(c["travel_deg"])
    cycle = float(travel[-1])
    kw = dict(cycle=cycle, positions=positions, length_mm=length, height_mm=height, lang=lang, sizes=sizes)
    nm, joule = unit("N·m", lang), unit("J", lang)
    drv, res = label("symbol_drive", lang), label("symbol_resist", lang)
    loads = [Series(c[f"M_{k}"], "thin", f"M {k}" if k != "gravity" else "M G") for k in d.profile.labels]
    drive = f"M{drv} = {_n(d.driving, lang)} {nm}" if d.run is None and d.periodic is None else f"M{drv}"
    moments = [Series(c["M_red"], "thick", f"M{res}"), Series(c["M_drive"], "hidden", drive)]
    views = {"moments": curve_panel("moments", travel, (loads if len(loads) > 1 else []) + moments,
                                    title=label("reduced_moments", lang), ordinate="M", unit_text=nm, **kw)}
    works = [Series(c["A_resist"], "thin", f"A{res}"), Series(c["A_sum"], "thick", "ΔT")]
    if np.all(np.isfinite(c["A_drive"])):
        works.insert(0, Series(c["A_drive"], "hidden", f"A{drv}"))
    views["works"] = curve_panel("works", travel, works, title=label("works_energy", lang), ordinate="A, ΔT",
                                 unit_text=joule, **kw)
    jii = c["J_red"] - d.declared
    views["inertia"] = curve_panel(
        "inertia", travel, [Series(jii, "thick", "JII")], title=label("reduced_inertia", lang), ordinate="JII",
        unit_text=unit("kg·m²", lang),
        notes=[f"JI = {_n(d.inertia, lang)} {unit('kg·m²', lang)}"], **kw)
    w = np.abs(c["omega"])
    st = d.steady or d.periodic
    if st is not None:
        base = st.omega_mean
        marks = [(st.theta_max, st.omega_max, "ωmax"), (st.theta_min, st.omega_min, "ωmin")]
        notes = [f"ωm = {_n(st.omega_mean, lang)} {unit('rad/s', lang)};  δ = {_n(st.delta, lang)}"]
    else:
        base, marks = float(np.nanmin(w)), []
        notes = [f"t = {_n(d.run.time, lang)} {unit('s', lang)}"]
    views["omega"] = curve_panel("omega", travel, [Series(w, "thick", "")], title=label("crank_speed", lang),
                                 ordinate="ω", unit_text=unit("rad/s", lang), base=base, marks=marks,
                                 notes=notes, **kw)
    return views


def _n(x: float, lang: str) -> str:
    return number(x, lang, 5)


def build_dynamics_sheet(mech: Study | Mechanism | str, *, n: int = 12, fmt: str = "A1", lang: str = "ru",
                         frame_style: str | None = None, info: TitleInfo | None = None,
                         style: SheetStyle | None = None) -> DynamicsSheet:
    """Compose the dynamics sheet of ``mech`` (its ``[dynamics]`` section).

    Parameters
    ----------
    mech : Study, Mechanism or str
    n : int
        Positions per turn numbered on the φ axes and on the Wittenbauer curve.
    fmt : {"A1", "A2", "A3"}
    lang : {"en", "ru", "uk", "zh"}
    frame_style : {"eskd", "iso"}, optional
    info : TitleInfo, optional

    Raises
    ------
    ScaleError
        A view cannot be drawn legibly in its part of the sheet.
    VelplanError
        Bad options, or dynamics that cannot be computed (one line naming the cause).
    """
    study = mech if isinstance(mech, Study) else Study(mech, n=n)
    mech, n = study.mechanism, study.n
    check_language(lang)
    if fmt not in FORMATS:
        raise VelplanError(f"unknown sheet format {fmt!r}; known formats: {', '.join(FORMATS)}")
    d = study.dynamics
    frame_style = frame_style or ("eskd" if lang in ("ru", "uk") else "iso")
    style = style or SheetStyle(language=lang)
    base = SIZES[fmt]
    sizes = DynamicsSizes(base.diagram.title_mm, base.diagram.label_mm)
    g = base.gap
    (fx0, fy0, fx1, fy1), (tx0, ty0, tx1, ty1) = drawing_area(fmt, frame_style)
    W, H = fx1 - fx0, fy1 - fy0
    views: dict[str, PlacedView] = {}
    scales: dict[str, float] = {}

    # the left column: four panels on one φ axis, the longest axis and then the tallest
    # ordinates that fit
    share = 0.56 if d.flywheel is not None else 0.75
    # the curves over the cycle (or the run), read once for every panel and the energy–mass diagram
    curves = d.curves(720 * d.spec.cycle_turns if d.run is None else 720)
    left = _fit_panels(d, curves, lang, sizes, n, share * W, H, g, fmt)
    y = fy1
    for name in PANELS:
        v = left[name]
        y -= v.height_mm
        views[name] = v.at(fx0, y)
        y -= g
        scales[name] = v.meta["mu"]
    scales["mu_phi"] = left["moments"].meta["mu_phi"]
    right_x0 = fx0 + max(v.width_mm for v in left.values()) + g

    # the results above the title block, the flywheel beside them, Wittenbauer on top
    wit = d.wittenbauer() if d.flywheel is not None else None
    table = _fit_results(d, wit, lang, base, max_width=fx1 - right_x0, fmt=fmt)
    views["results"] = table.at(fx1 - table.width_mm, ty1 + g)
    band_top = ty1 + g + table.height_mm
    if d.flywheel is not None and d.flywheel.dimensions is not None:
        region = (right_x0, fy0, min(tx0, fx1 - table.width_mm) - g, band_top)
        fw = _fit_flywheel(d.flywheel.dimensions, lang, sizes, region)
        if fw is None:  # beside the table there is no room: above it
            region = (right_x0, band_top + g, fx1, band_top + g + 0.3 * H)
            fw = _fit_flywheel(d.flywheel.dimensions, lang, sizes, region)
        if fw is None:
            raise ScaleError(f"the flywheel's section does not fit {fmt} at any ESKD scale; use a larger --format")
        views["flywheel"] = fw.at(region[0], region[1])
        scales["flywheel"] = fw.meta["scale"]
        band_top = max(band_top, region[1] + fw.height_mm)
    if d.flywheel is not None:
        region = (right_x0, band_top + g, fx1, fy1)
        wv, wit = _fit_wittenbauer(d, curves, lang, sizes, region, fmt, n)
        views["wittenbauer"] = wv.at(0.5 * (region[0] + region[2] - wv.width_mm), region[3] - wv.height_mm)
        scales["mu_J"], scales["mu_T"] = wit.mu_J, wit.mu_T
        # the table reads the segment off this drawing
        table = results_view(results_rows(d, wit, lang), lang=lang, size_mm=table.meta["size_mm"],
                             title_mm=base.table_title)
        views["results"] = table.at(fx1 - table.width_mm, ty1 + g)
    scale = ratio_text(scales["flywheel"], lang) if "flywheel" in scales else ""
    if info is None:
        info = default_dynamics_title(mech, lang, scale)
    elif not info.scale and scale:
        info = replace(info, scale=scale)
    check_layout(views, fmt, frame_style)
    scene = sheet_scene(info, fmt, frame_style=frame_style, lang=lang)
    scene = scene.extend(*(v.primitives for v in views.values()))
    return DynamicsSheet(mech, scene, MappingProxyType(dict(views)), MappingProxyType(scales), d, wit, fmt, lang,
                         frame_style, style, info)


def _fit_panels(d, c, lang, sizes, n, width, height, gap, fmt) -> dict[str, View]:
    """The four panels at the longest φ axis, then the tallest ordinates, that fit."""
    lengths = (360.0, 300.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0)
    heights = (120.0, 100.0, 80.0, 70.0, 60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0)
    for length in lengths:
        if length < MIN_DIAGRAM_MM:
            break
        low = _panels(d, c, lang, length, heights[-1], sizes, n)
        if max(v.width_mm for v in low.values()) > width:
            continue
        for h in heights:
            views = low if h == heights[-1] else _panels(d, c, lang, length, h, sizes, n)
            total = sum(v.height_mm for v in views.values()) + gap * (len(views) - 1)
            if total <= height and max(v.width_mm for v in views.values()) <= width:
                return views
    raise ScaleError(f"the dynamics diagrams do not fit {fmt} ({width:.0f} × {height:.0f} mm) with a φ axis "
                     f"of at least {MIN_DIAGRAM_MM:.0f} mm; use a larger --format")


def _fit_results(d, wit, lang, base, *, max_width, fmt) -> View:
    rows = results_rows(d, wit, lang)
    for size in base.table:
        view = results_view(rows, lang=lang, size_mm=size, title_mm=base.table_title)
        if view.width_mm <= max_width:
            return view
    raise ScaleError(f"the table of results does not fit {fmt} ({view.width_mm:.0f} mm wide, "
                     f"{max_width:.0f} mm free); use a larger --format")


def _fit_flywheel(dims, lang, sizes, region) -> View | None:
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    if w < 40 or h < 30:
        return None
    for mu in eskd_scales():
        if dims.outer / mu > 0.8 * h:
            continue
        view = flywheel_view(dims, scale=mu, lang=lang, sizes=sizes, scale_text=scale_mark(mu, lang))
        if fits(view, w, h):
            return view
    return None


def _fit_wittenbauer(d, c, lang, sizes, region, fmt, n):
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    J = c["J_red"] - d.declared
    T = c["A_sum"]
    per_turn = d.table(n, exact=False)
    points = list(zip(per_turn["J_red"] - d.declared, per_turn["A_sum"]))
    # each axis at its own scale: J across the region, ΔT (with the tangents' intercepts) up it
    from velplan.dynamics.flywheel import nice_scale

    cp, cm = d.flywheel.diagram.intercept_max, d.flywheel.diagram.intercept_min
    t_span = max(float(T.max()), cp, 0.0) - min(float(T.min()), cm, 0.0)
    mu_J = nice_scale(max(float(J.max()), 1e-12) / max(w - 60.0, 20.0))
    mu_T = nice_scale(max(t_span, 1e-12) / max(h - 50.0, 20.0))
    for _ in range(12):
        wit = d.wittenbauer(mu_J=mu_J, mu_T=mu_T)
        view = wittenbauer_view(wit, J, T, points, omega_mean=d.flywheel.omega_mean, delta=d.flywheel.delta,
                                lang=lang, sizes=sizes)
        if fits(view, w, h):
            return view, wit
        if view.width_mm > w:
            mu_J = nice_scale(mu_J * 1.0001)
        if view.height_mm > h:
            mu_T = nice_scale(mu_T * 1.0001)
    raise ScaleError(f"the energy–mass diagram does not fit {fmt} ({w:.0f} × {h:.0f} mm free); "
                     f"use a larger --format")

