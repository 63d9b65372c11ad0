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

from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from velplan.errors import ScaleError
from velplan.mechanism.model import Mechanism
from velplan.options import Format, FrameStyle, Language
from velplan.render.i18n import label
from velplan.render.style import SheetStyle
from velplan.sheets.frame import TitleInfo
from velplan.sheets.layout import MIN_DIAGRAM_MM
from velplan.sheets.skeleton import (
    ComposedSheet, Request, compose, fit_table, sheet_request, title_with_scale)
from velplan.sheets.solver import fits, largest_fitting
from velplan.study import Study
from velplan.views.base import PlacedView, View, eskd_scales, indexed, number, ratio_text, scale_mark, unit
from velplan.views.diagram import standard_up
from velplan.views.dynamics import (
    DynamicsSizes, Series, constant_moment, curve_panel, flywheel_view, moment_scale, ordinate_scale,
    results_rows, results_view, wittenbauer_view)

PANELS = ("moments", "works", "inertia", "omega")
"""The curve panels, top to bottom."""


@dataclass(frozen=True)
class DynamicsSheet(ComposedSheet):
    """A composed dynamics sheet (the attributes of `ComposedSheet`, and these).

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

    dynamics: object
    wittenbauer: object


def default_dynamics_title(mech: Mechanism, lang: Language, scale: str) -> TitleInfo:
    """Title block of the dynamics sheet: the third document of the course work."""
    from velplan.sheets.documents import default_title_of

    return default_title_of("dynamics", mech, lang, scale)


def _panels(d, c, lang: Language, length: float, height: float, sizes: DynamicsSizes, positions: int,
            mus: dict[str, float] | None = None, names: bool = True, memo: dict | None = None) -> dict[str, View]:
    """The four curve panels of ``d`` from its curves ``c`` (`Dynamics.curves`); ``mus``: the
    panels drawn at a given ordinate scale, only those when given; `names`: with the curves'
    names (`curve_panel`; unnamed, a trial only measured: its curves stand as their boxes);
    `memo`: the panels already drawn by (panel, φ axis length, μ, names)
    — a panel's drawing depends on `height` only through its μ — taken from it, and added."""
    travel = np.radians(c["travel_deg"])
    cycle = float(travel[-1])
    kw: dict[str, Any] = dict(cycle=cycle, positions=positions, length_mm=length, height_mm=height, lang=lang,
                              sizes=sizes, names=names)
    wanted = PANELS if mus is None else tuple(mus)
    memo = {} if memo is None else memo

    def panel(name: str, series: list[Series], **args) -> View:
        mu = mus[name] if mus is not None else ordinate_scale(series, args.get("base", 0.0), height)
        key = (name, length, mu, names)
        if key not in memo:
            memo[key] = curve_panel(name, travel, series, mu=mu, measured=not names, **kw, **args)
        return memo[key]

    nm, joule = unit("N·m", lang), unit("J", lang)
    _, drv, res = constant_moment(d, lang)  # an engine's constant moment resists: M_с, its loads' M_д
    views: dict[str, View] = {}
    if "moments" in wanted:
        loads = [Series(c[f"M_{k}"], "thin", indexed("M", k if k != "gravity" else "G")) for k in d.profile.labels]
        m_drv, m_res = indexed("M", drv), indexed("M", res)
        driving = number(d.driving, lang, 5, scale=moment_scale(c["M_red"]))
        drive = f"{m_drv} = {driving} {nm}" if d.run is None and d.periodic is None else m_drv
        moments = [Series(c["M_red"], "thick", m_res), Series(c["M_drive"], "hidden", drive)]
        views["moments"] = panel("moments", (loads if len(loads) > 1 else []) + moments,
                                 title=label("reduced_moments", lang), ordinate="M", unit_text=nm,
                                 mu_symbol=indexed("μ", "M"))
    if "works" in wanted:
        works = [Series(c["A_resist"], "thin", indexed("A", res)), Series(c["A_sum"], "thick", "ΔT")]
        if np.all(np.isfinite(c["A_drive"])):
            works.insert(0, Series(c["A_drive"], "hidden", indexed("A", drv)))
        views["works"] = panel("works", works, title=label("works_energy", lang), ordinate="A, ΔT",
                               unit_text=joule, mu_symbol=indexed("μ", "A"))
    if "inertia" in wanted:
        views["inertia"] = panel(
            "inertia", [Series(c["J_red"] - d.declared, "thick", indexed("J", "II"))],
            title=label("reduced_inertia", lang), ordinate=indexed("J", "II"), unit_text=unit("kg·m²", lang),
            notes=[f"{indexed('J', 'I')} = {_n(d.inertia, lang)} {unit('kg·m²', lang)}"], mu_symbol=indexed("μ", "J"))
    if "omega" in wanted:
        views["omega"] = panel("omega", **_omega_panel(d, c, lang))
    return views


def _omega_panel(d, c, lang: Language) -> dict[str, Any]:
    """The crank's speed over the cycle about ω_m (the run's over its travel about its least):
    the series and the arguments of its `curve_panel`."""
    w = np.abs(c["omega"])
    st = d.steady or d.periodic
    if st is not None:
        base = st.omega_mean
        marks = [(st.theta_max, st.omega_max, indexed("ω", "max")), (st.theta_min, st.omega_min, indexed("ω", "min"))]
        notes = [f"{indexed('ω', 'm')} = {_n(st.omega_mean, lang)} {unit('rad/s', lang)};  δ = {_n(st.delta, lang)}"]
        base_label = indexed("ω", "m")
    else:
        base, marks, base_label = float(np.nanmin(w)), [], ""
        notes = [f"t = {_n(d.run.time, lang)} {unit('s', lang)}"]
    return dict(series=[Series(w, "thick", "")], title=label("crank_speed", lang), ordinate="ω",
                unit_text=unit("rad/s", lang), base=base, marks=marks, notes=notes, base_label=base_label,
                mu_symbol=indexed("μ", "ω"))


def _n(x: float, lang: Language) -> str:
    return number(x, lang, 5)


def build_dynamics_sheet(mech: Study | Mechanism | str | Path, *, n: int = 12, fmt: Format = "A1",
                         lang: Language = "ru", frame_style: FrameStyle | None = None, info: TitleInfo | None = None,
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
    req = sheet_request(mech, n=n, fmt=fmt, lang=lang, frame_style=frame_style, style=style,
                        assembled=False)
    d = req.study.dynamics
    views: dict[str, PlacedView] = {}
    # the curves over the cycle (or the run), read once for every panel and the energy–mass diagram
    curves = d.curves(720 * d.spec.cycle_turns if d.run is None else 720)
    scales = _left_column(req, curves, views)
    right_x0 = req.area[0] + max(views[name].view.width_mm for name in PANELS) + req.gap
    wit = _right_column(req, curves, views, scales, right_x0)
    scale = ratio_text(scales["flywheel"], lang) if "flywheel" in scales else ""
    info = title_with_scale(info, lambda s: default_dynamics_title(req.mechanism, lang, s), scale)
    return DynamicsSheet(req.mechanism, compose(req, views, list(views), info), MappingProxyType(dict(views)),
                         MappingProxyType(scales), fmt, lang, req.frame_style, req.style, info, d, wit)


def _left_column(req: Request, curves, views: dict) -> dict[str, float]:
    """The four panels on one φ axis down the left, the longest axis and then the tallest
    ordinates that fit; their scales."""
    d = req.study.dynamics
    fx0, _, fx1, fy1 = req.area
    share = 0.56 if d.flywheel is not None else 0.75
    tx0, _, _, ty1 = req.title_block
    left = _fit_panels(d, curves, req.lang, _sizes(req), req.study.n, share * (fx1 - fx0),
                       fy1 - req.area[1], req.gap, req.fmt, beside=(tx0 - fx0, ty1 + req.gap - req.area[1]))
    scales: dict[str, float] = {}
    y = fy1
    for name in PANELS:
        v = left[name]
        y -= v.height_mm
        views[name] = v.at(fx0, y)
        y -= req.gap
        scales[name] = v.meta["mu"]
    scales["mu_phi"] = left["moments"].meta["mu_phi"]
    return scales


def _sizes(req: Request) -> DynamicsSizes:
    return DynamicsSizes(req.sizes.diagram.title_mm, req.sizes.diagram.label_mm)


def _right_column(req: Request, curves, views: dict, scales: dict, right_x0: float):
    """The results above the title block, the flywheel beside them, Wittenbauer on top;
    the Wittenbauer diagram as drawn (None without a flywheel)."""
    d, lang, g = req.study.dynamics, req.lang, req.gap
    fx0, fy0, fx1, fy1 = req.area
    tx0, _, _, ty1 = req.title_block
    wit = d.wittenbauer() if d.flywheel is not None else None
    table = fit_table(lambda size, width: results_view(results_rows(d, wit, lang, marked=True), lang=lang,
                                                       size_mm=size, title_mm=req.sizes.table_title,
                                                       width_factor=width),
                      req, what="table of results", max_width=fx1 - right_x0, advice="")
    views["results"] = table.at(fx1 - table.width_mm, ty1 + g)
    if d.flywheel is None:
        return wit
    band_top = ty1 + g + table.height_mm
    beside_table = (right_x0, fy0, min(tx0, fx1 - table.width_mm) - g, band_top)
    placed, wit = _flywheel_and_wittenbauer(req, curves, beside_table, band_top)
    for name, view in placed.items():
        views[name] = view
    if "flywheel" in placed:
        scales["flywheel"] = placed["flywheel"].view.meta["scale"]
    scales["mu_J"], scales["mu_T"] = wit.mu_J, wit.mu_T
    # the table reads the segment off this drawing
    table = results_view(results_rows(d, wit, lang, marked=True), lang=lang, size_mm=table.meta["size_mm"],
                         title_mm=req.sizes.table_title, width_factor=table.meta["width_factor"])
    views["results"] = table.at(fx1 - table.width_mm, ty1 + g)
    return wit


READABLE_DELTA_T_MM = 40.0
"""The ΔT range of Wittenbauer's diagram, mm, past which a larger flywheel drawing is preferred."""
LEAST_DELTA_T_MM = 29.5
"""The least ΔT range of Wittenbauer's diagram (30 mm, as every diagram's ordinates, to the
drawing's half millimetre): a band that leaves the diagram less loses to one that does not."""
FLYWHEEL_BANDS = (0.3, 0.2, 0.14, 0.12, 0.1)
"""The heights, as shares of the drawing area, of the band above the table that the flywheel
may take when it does not fit beside the table: the largest first."""


def _flywheel_and_wittenbauer(req: Request, curves, beside_table, band_top: float):
    """The flywheel's section (beside the table or in a band above it) and Wittenbauer's
    diagram above: of the bands of :data:`FLYWHEEL_BANDS`, the first giving the diagram a ΔT
    range of :data:`READABLE_DELTA_T_MM`, else, of those leaving it :data:`LEAST_DELTA_T_MM` if
    any do, the one with the larger of the least of the ΔT range and twice the flywheel's drawn
    diameter (the energy–mass diagram is the sheet's
    construction, the flywheel a sketch of its result); the placed views and the diagram."""
    d, g = req.study.dynamics, req.gap
    fx0, fy0, fx1, fy1 = req.area
    assert d.flywheel is not None  # drawn only when there is one to size
    dims = d.flywheel.dimensions
    sized = dims is not None
    best = None
    drawn: dict = {}  # the energy–mass diagrams drawn, by scales: the same in every band
    for share in FLYWHEEL_BANDS if sized else (0.0,):
        placed: dict[str, PlacedView] = {}
        top = band_top
        try:
            if sized:
                top = _place_flywheel(req, placed, beside_table, share)
            region = (beside_table[0], top + g, fx1, fy1)
            wv, wit = _fit_wittenbauer(d, curves, req.lang, _sizes(req), region, req.fmt, req.study.n, drawn)
        except ScaleError:
            if best is None and share == FLYWHEEL_BANDS[-1]:
                raise
            continue
        placed["wittenbauer"] = wv.at(0.5 * (region[0] + region[2] - wv.width_mm), region[3] - wv.height_mm)
        rise = wv.meta["delta_T_mm"]
        # the flywheel stays a readable sketch: twice its drawn diameter weighs against ΔT
        disc = 2.0 * dims.outer / placed["flywheel"].view.meta["scale"] if dims is not None else np.inf
        ok = rise >= LEAST_DELTA_T_MM
        if best is None or (ok and not best[3]) or (ok == best[3] and min(rise, disc) > best[0] + 1.0):
            best = (min(rise, disc), placed, wit, ok)
        if rise >= READABLE_DELTA_T_MM or top == band_top:  # readable, or the flywheel beside the table
            break
    assert best is not None  # the last band raises when nothing fits
    return best[1], best[2]


def _place_flywheel(req: Request, views: dict, region, share: float) -> float:
    """The flywheel's section beside the table (or, without room there, above it in a band
    ``share`` of the drawing area's height); the top of the bottom band, mm."""
    flywheel = req.study.dynamics.flywheel
    assert flywheel is not None  # placed only when there is one to size
    dims = flywheel.dimensions
    band_top = region[3]
    fw = _fit_flywheel(dims, req.lang, _sizes(req), region)
    if fw is None:  # beside the table there is no room: above it
        H = req.area[3] - req.area[1]
        region = (region[0], band_top + req.gap, req.area[2], band_top + req.gap + share * H)
        fw = _fit_flywheel(dims, req.lang, _sizes(req), region)
    if fw is None:
        raise ScaleError(f"the flywheel's section does not fit {req.fmt} at any ESKD scale; use a larger --format")
    views["flywheel"] = fw.at(region[0], region[1])
    return max(band_top, region[1] + fw.height_mm)


def _fit_panels(d, c, lang, sizes, n, width, height, gap, fmt, beside=(np.inf, 0.0)) -> dict[str, View]:
    """The four panels at the longest φ axis, then the tallest ordinates, that fit `width` ×
    `height` mm; ``beside`` = (width, height) mm of the column's bottom part that the title
    block leaves: a column wider than that ends above it. A shorter axis is taken where the
    longest leaves a panel's ordinates under :data:`LEAST_PANEL_MM` and the shorter does not."""
    fit = lambda vs: _column_fits(vs, width, height, gap, beside)  # noqa: E731
    memo: dict = {}  # every panel drawn once, whatever height gave its μ

    def draw(length: float, h: float, names: bool, mus: dict[str, float] | None = None) -> dict[str, View]:
        return _panels(d, c, lang, length, h, sizes, n, mus, names, memo)

    first = None
    lengths: tuple[float, ...] = AXIS_LENGTHS
    while (found := _fit_from(draw, width, fit, lengths)) is not None:
        length, views = found
        if min(v.meta["span_mm"] for v in views.values()) >= LEAST_PANEL_MM:
            return views
        first = first or views
        lengths = tuple(x for x in lengths if x < length)
    if first is not None:
        return first
    raise ScaleError(f"the dynamics diagrams do not fit {fmt} ({width:.0f} × {height:.0f} mm) with a φ axis "
                     f"of at least {MIN_DIAGRAM_MM:.0f} mm; use a larger --format")


def _fit_from(draw, width, fit, lengths) -> tuple[float, dict[str, View]] | None:
    """(φ axis length, the named panels) of the longest of `lengths`, then the tallest ordinates,
    that fit; None where none does."""
    # sought with the panels unnamed, then drawn named; named all along where the names take more room
    for names in (False, True):
        for length, h, views in _fitting(draw, width, fit, names, lengths):
            finer = _finer_panels(views, lambda mus: draw(length, h, names, mus), fit)
            # drawn named at the finer scales, else at the scales found (the names take a little more
            # room: the search named all along is the last resort, and the costliest)
            for found in ([finer, views] if not names else [finer]):
                if not names:
                    found = draw(length, h, True, {k: v.meta["mu"] for k, v in found.items()})
                if fit(list(found.values())):
                    return length, found
            break
    return None


#: The least ordinate range of a curve panel, mm, that a shorter φ axis is not traded for: the four
#: panels share one column, and each keeps at least this much.
LEAST_PANEL_MM = 20.0
#: The φ axis lengths tried, mm, the longest first.
AXIS_LENGTHS = (360.0, 300.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0)


def _fitting(draw, width, fit, names: bool, lengths=AXIS_LENGTHS):
    """(φ axis length, ordinate height, the panels) of the longest axis, then the tallest
    ordinates, whose column `fit`s; none where nothing does. `draw` (length, height, names):
    the panels. A named panel holds its unnamed drawing and more, so where the unnamed
    panels do not fit the named ones are not drawn."""
    heights = (120.0, 100.0, 80.0, 70.0, 60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0)
    for length in lengths:
        if length < MIN_DIAGRAM_MM:
            break
        if names and max(v.width_mm for v in draw(length, heights[-1], False).values()) > width:
            continue
        low = draw(length, heights[-1], names)
        if max(v.width_mm for v in low.values()) > width:
            continue
        for h in heights:
            if names and h != heights[-1] and not fit(list(draw(length, h, False).values())):
                continue
            views = low if h == heights[-1] else draw(length, h, names)
            if fit(list(views.values())):
                yield length, h, views
                return


def _finer_panels(views: dict[str, View], redraw, fit) -> dict[str, View]:
    """The panels with the shortest ordinate range drawn one standard scale finer, in turn, while
    the column still fits (the one height of :func:`_fit_panels` loses up to half of a panel's
    range to the series' steps: 5.1 N·m/mm → 10)."""
    stuck: set[str] = set()
    for _ in range(4 * len(views)):
        free = [k for k in views if k not in stuck]
        if not free:
            break
        name = min(free, key=lambda k: views[k].meta["span_mm"])
        mu = views[name].meta["mu"]
        finer = standard_up(mu * 0.999 / 2.5)
        while standard_up(finer * 1.001) < mu * 0.999:  # the next value of the series below μ
            finer = standard_up(finer * 1.001)
        trial = {**views, name: redraw({name: finer})[name]}
        if fit(list(trial.values())):
            views = trial
        else:
            stuck.add(name)
    return views


def _column_fits(views: list[View], width: float, height: float, gap: float, beside) -> bool:
    """Whether `views` stacked from the top fit `width` × `height` mm, each one that reaches
    down to the title block (the bottom ``beside[1]`` mm) no wider than ``beside[0]``."""
    top = height
    for v in views:
        top -= v.height_mm
        if top < -1e-9 or v.width_mm > (width if top >= beside[1] else min(width, beside[0])):
            return False
        top -= gap
    return True


def _fit_flywheel(dims, lang, sizes, region) -> View | None:
    """The flywheel's section at the largest ESKD scale that fits `region`, or None."""
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    if w < 40 or h < 30:
        return None
    found = largest_fitting(
        lambda mu: flywheel_view(dims, scale=mu, lang=lang, sizes=sizes, scale_text=scale_mark(mu, lang)),
        eskd_scales(), w, h, skip=lambda mu: dims.outer / mu > 0.8 * h)
    return None if found is None else found[1]


def _fit_wittenbauer(d, c, lang, sizes, region, fmt, n, drawn: dict | None = None):
    """Wittenbauer's diagram at the finest scales that fit `region`, and the diagram as drawn;
    `drawn`: the drawings already made, by (μJ, μT, numbers), taken from it and added."""
    drawn = {} if drawn is None else drawn
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
    def draw(mu_J, mu_T, numbers=False):  # sought with the numbers where first put, then placed
        if (mu_J, mu_T, numbers) not in drawn:
            wit = d.wittenbauer(mu_J=mu_J, mu_T=mu_T)
            drawn[mu_J, mu_T, numbers] = wittenbauer_view(
                wit, J, T, points, omega_mean=d.flywheel.omega_mean, delta=d.flywheel.delta, lang=lang, sizes=sizes,
                numbers=numbers), wit
        view, wit = drawn[mu_J, mu_T, numbers]
        if not numbers and fits(view, w, h):
            return draw(mu_J, mu_T, True)
        return view, wit

    for _ in range(12):
        view, wit = draw(mu_J, mu_T)
        if fits(view, w, h):
            # the first guess allowed for the texts round the curve; with their measured room,
            # the finest scales that may still fit
            finer = (nice_scale(max(float(J.max()), 1e-12) / max(w - (view.width_mm - view.meta["J_mm"]), 20.0)),
                     nice_scale(t_span / max(h - (view.height_mm - view.meta["delta_T_mm"]), 20.0)))
            if finer[0] <= mu_J and finer[1] <= mu_T and finer != (mu_J, mu_T):
                better = draw(*finer)
                if fits(better[0], w, h):
                    return better
            return view, wit
        if view.width_mm > w:
            mu_J = nice_scale(mu_J * 1.0001)
        if view.height_mm > h:
            mu_T = nice_scale(mu_T * 1.0001)
    raise ScaleError(f"the energy–mass diagram does not fit {fmt} ({w:.0f} × {h:.0f} mm free); "
                     f"use a larger --format")

