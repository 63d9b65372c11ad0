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
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Mapping, Sequence

import numpy as np

from velplan.analysis.numbering import position_index, position_number
from velplan.errors import ScaleError, VelplanError
from velplan.forces.agreement import ForceAnalysis
from velplan.mechanism.model import Mechanism
from velplan.options import Format, FrameStyle, Language
from velplan.plans import standard_scale
from velplan.render.i18n import label
from velplan.render.scene import Text
from velplan.render.style import SheetStyle
from velplan.sheets.frame import TitleInfo
from velplan.sheets.layout import MIN_CRANK_MM, MIN_DIAGRAM_MM
from velplan.sheets.skeleton import (
    ComposedSheet, Request, check_plan_positions, compose, fill_bottom_band, fit_table,
    sheet_request, sheet_text, title_with_scale)
from velplan.sheets.solver import ShrinkingRows, Trials, largest_fitting, widest_first
from velplan.study import Study
from velplan.views.base import PlacedView, View, eskd_scales, fixed, make_view, ratio_text
from velplan.views.forces import (
    ForceSizes, group_extent_m, group_view, lever_extent, lever_view,
    moment_diagram_view, moments_table_view, polygon_extent, polygon_view, slug)
from velplan.views.forces.group import group_body_size
from velplan.views.forces.lever import lever_body_size

#: Text heights and the conventional force-arrow length of the force views, per format.
FORCE_SIZES: Mapping[str, ForceSizes] = MappingProxyType({
    "A1": ForceSizes(5.0, 3.5, 16.0),
    "A2": ForceSizes(3.5, 2.5, 13.0, wrap_balance=True),
    "A3": ForceSizes(3.5, 2.5, 10.0, wrap_balance=True),
})
#: Smallest drawing (mm, its larger side) of a group, a polygon or the lever, per format.
MIN_TARGET_MM: Mapping[str, float] = MappingProxyType({"A1": 40.0, "A2": 35.0, "A3": 30.0})
#: Smallest larger side of Zhukovsky's lever (its velocity plan turned), mm, per format: the
#: lever carries every force of the mechanism at its image points, a smaller one piles their
#: arrows and labels on one another. The other drawings shrink first; a sheet that cannot
#: give the lever this much refuses (ScaleError).
MIN_LEVER_MM: Mapping[str, float] = MappingProxyType({"A1": 70.0, "A2": 60.0, "A3": 50.0})


@dataclass(frozen=True)
class ForceSheet(ComposedSheet):
    """A composed force-analysis sheet (the attributes of `ComposedSheet`, and these).

    Attributes
    ----------
    views : Mapping[str, PlacedView]
        ``"group-K-G"``, ``"polygon-K-G"`` (G a group's name, or ``crank``), ``"lever-K"``,
        ``"heading-K"``, ``"table"``, ``"mb-diagram"``.
    scales : Mapping[str, float]
        ``"mu_l"`` (m/mm) of the groups, μF (N/mm) of each polygon and μv ((m/s)/mm) of each
        lever by view name, ``"mu_m"`` (N·m/mm) of the diagram.
    analysis : ForceAnalysis
        The force analysis at the n positions.
    positions : tuple of int
        Positions (1-based) drawn.
    n : int
    """

    analysis: object
    positions: tuple[int, ...]
    n: int


def has_forces(mech: Mechanism) -> bool:
    """Whether `mech` declares masses or loads (something for a force sheet to show)."""
    return bool(mech.masses) or bool(mech.loads)


def default_force_positions(fa: ForceAnalysis) -> tuple[int, ...]:
    """The position of the largest |M_b|; when the useful load does not act there, first the
    position of the largest |M_b| under the load (a working-stroke position)."""
    mb = np.abs(np.asarray(fa.kinetostatics.balancing_moment, float))
    mb = np.where(np.isfinite(mb), mb, -1.0)
    best = int(np.argmax(mb))
    loads = [f for f in fa.actions.forces if f.source == "load"]
    if not loads:
        return (position_number(best),)
    acting = np.zeros(len(mb), bool)
    for f in loads:
        acting |= np.abs(np.asarray(f.vector)) > 0
    if acting[best] or not acting.any():
        return (position_number(best),)
    working = int(np.argmax(np.where(acting, mb, -1.0)))
    return (position_number(working), position_number(best))


def default_force_title(mech: Mechanism, lang: Language, scale: str) -> TitleInfo:
    """Title block of the force sheet: the second document of the course work."""
    from velplan.sheets.documents import default_title_of

    return default_title_of("forces", mech, lang, scale)


def solving_order(mech: Mechanism) -> tuple[str, ...]:
    """Groups in the order the kinetostatics solves them, the initial link last."""
    return tuple(g.name for g in reversed(mech.groups)) + ("crank",)


def build_force_sheet(mech: Study | Mechanism | str | Path, *, n: int = 12, plans: Sequence[int] | None = None,
                      fmt: Format = "A1", lang: Language = "ru", frame_style: FrameStyle | None = None,
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
    req = sheet_request(mech, n=n, fmt=fmt, lang=lang, frame_style=frame_style, style=style)
    study, mech = req.study, req.mechanism
    if not has_forces(mech):
        raise VelplanError(f"{mech.name} declares no masses and no loads: there are no forces "
                           f"to draw; add [link.N] masses or [[load]] tables")
    fa = study.forces()
    chosen = check_plan_positions(default_force_positions(fa) if plans is None else plans, study.n)
    _check_regular(fa, chosen)
    draw = _ForceDrawings(fa, lang, FORCE_SIZES[fmt])
    views, scales, (chosen, placed, top_scales) = _fit_sheet(req, fa, draw, chosen, plans,
                                                             table=table, diagrams=diagrams)
    views.update(placed)
    scales.update(top_scales)
    info = title_with_scale(info, lambda s: default_force_title(mech, lang, s),
                            ratio_text(scales["mu_l"], lang))
    order = [k for k in views if k not in ("mb-diagram", "table")] + [
        k for k in ("mb-diagram", "table") if k in views]
    return ForceSheet(mech, compose(req, views, order, info), MappingProxyType(dict(views)),
                      MappingProxyType(scales), fmt, lang, req.frame_style, req.style, info, fa,
                      chosen, study.n)


#: The least share of the drawing area's height the diagram M_b(φ) is given, in turn: the
#: drawings above take the room of a lower one where they need it.
DIAGRAM_SHARES = (0.26, 0.2)
#: The arrangements of the drawings above the band (`_fit_top`), in turn: each tried with
#: every diagram share before the next.
ARRANGEMENTS = (("row", "stack"), ("fit",))


def _fit_sheet(req: Request, fa, draw, chosen, plans, *, table: bool, diagrams: bool | None):
    """(bottom views, their scales, (positions, placed views, scales) above the band): the
    first arrangement of `ARRANGEMENTS` that fits with the tallest diagram of
    `DIAGRAM_SHARES`; the last ScaleError where none does."""
    failure: ScaleError | None = None
    bands: dict[float, tuple[dict, dict, float]] = {}  # each share's band made once for every arrangement
    diagram = _diagram_trials(req)
    for modes in ARRANGEMENTS:
        for share in DIAGRAM_SHARES:  # a lower diagram where the drawings above need the room
            if share not in bands:
                made: tuple[dict, dict] = ({}, {})
                top = _bottom_band(req, fa, *made, table=table, diagrams=diagrams, share=share, diagram=diagram)
                bands[share] = (*made, top)
            views: dict[str, PlacedView] = dict(bands[share][0])
            scales: dict[str, float] = dict(bands[share][1])
            band_top = bands[share][2]
            try:
                return views, scales, _top_views(draw, chosen, band_top, req, plans, modes)
            except ScaleError as exc:
                failure = exc
                if "mb-diagram" not in views:
                    break  # no diagram: the share changes nothing
    raise failure or ScaleError(f"the force views do not fit {req.fmt}")


def _top_views(draw, chosen, band_top: float, req: Request, plans, modes=ARRANGEMENTS[0]):
    """(positions, placed views, scales) of the groups, polygons and lever above the band:
    the default pair of positions, or the largest |M_b| alone where the pair does not fit."""
    fx0, _, fx1, fy1 = req.area
    top = (fx0, band_top + req.gap, fx1, fy1)
    try:
        return (chosen, *_fit_top(draw, chosen, top, req, modes))
    except ScaleError:
        if plans is not None or len(chosen) == 1:
            raise
        chosen = (chosen[-1],)  # the default pair does not fit: the largest |M_b| alone
        return (chosen, *_fit_top(draw, chosen, top, req, modes))


def _check_regular(fa: ForceAnalysis, chosen) -> None:
    """Refuse a chosen position where a group has no unique reactions."""
    for k in chosen:
        for name, poly in fa.kinetostatics.polygons.items():
            if not np.all(np.isfinite(poly.vertices()[position_index(k, len(fa.kinematics))])):
                raise VelplanError(f"position {k} is singular for the force analysis (group "
                                   f"{name} has no unique reactions there); choose another "
                                   f"with --plans")


def _bottom_band(req: Request, fa, views: dict, scales: dict, *, table: bool,
                 diagrams: bool | None, share: float = DIAGRAM_SHARES[0], diagram: Trials | None = None) -> float:
    """The table of the balancing moments above the title block, the diagram M_b(φ) to their
    left (`share` of the height, at least; `diagram`: its trial drawings, `_diagram_trials`);
    the band's top, mm."""
    tview = None
    if table:
        tview = fit_table(lambda size, width: moments_table_view(fa, lang=req.lang, size_mm=size,
                                                                 title_mm=req.sizes.table_title, width_factor=width),
                          req, what=f"table of balancing moments ({len(fa.kinematics)} positions)")
    band_top, dview = fill_bottom_band(
        views, req, table_view=tview,
        fit_diagram=None if diagrams is False else (lambda region: _fit_diagram(req, region, diagram)),
        diagram_share=share, required=bool(diagrams), diagram_name="mb-diagram")
    if dview is not None:
        scales["mu_m"] = dview.meta["mu_m"]
    return band_top


def _diagram_trials(req: Request) -> Trials:
    """The diagram M_b(φ) drawn at (φ axis length, ordinate height) mm, each drawn once
    whichever region tries it."""
    sizes = req.sizes.diagram
    return Trials(lambda length, height: moment_diagram_view(
        req.study.moment_curve, length_mm=length, height_mm=height, lang=req.lang, label_mm=sizes.label_mm,
        title_mm=sizes.title_mm))


def _fit_diagram(req: Request, region, draw: Trials | None = None) -> View:
    """The diagram M_b(φ) in `region`: the longest φ axis that fits, then the tallest
    ordinates (at most half the axis); `draw`: its trial drawings (`_diagram_trials`)."""
    x0, y0, x1, y1 = region
    w, h = x1 - x0, y1 - y0
    draw = _diagram_trials(req) if draw is None else draw
    lengths = [L for L in (360.0, 240.0, 180.0, 144.0, 120.0, 90.0, 72.0, 60.0) if L >= MIN_DIAGRAM_MM]
    length = widest_first(lambda L: draw(L, 10.0), lengths, w)[0]
    if length is not None:
        heights = [ht for ht in (120.0, 100.0, 80.0, 60.0, 50.0, 40.0, 30.0, 25.0, 20.0)
                   if ht <= 0.5 * length]
        found = largest_fitting(lambda ht: draw(length, ht), heights, w, h)
        if found is not None:
            return found[1]
    raise ScaleError(f"the balancing moment diagram does not fit {req.fmt} ({w:.0f} × {h:.0f} mm "
                     f"free beside the title block) with a φ axis of at least "
                     f"{MIN_DIAGRAM_MM:.0f} mm; use a larger --format")


class _ForceDrawings:
    """The trial drawings of a force sheet, each drawn once whichever arrangement tries it:
    ``view(kind, position, group, μ)`` of a group (μl, m/mm), a polygon (μF, N/mm) or a lever
    (μv, (m/s)/mm; group None)."""

    def __init__(self, fa: ForceAnalysis, lang: Language, fsizes: ForceSizes):
        self.fa, self.lang, self.fsizes = fa, lang, fsizes
        self.view = Trials(self._draw)
        self.least = Trials(self._least)

    def _least(self, kind: str, k: int, grp: str | None, mu: float) -> tuple[float, float]:
        """A lower bound of the size (mm) of the view `_draw` draws, found without drawing its
        forces and labels: the group's links, the lever's bars; (0, 0) for a polygon."""
        if kind == "group" and grp is not None:
            return group_body_size(self.fa, grp, k, mu_l=mu, sizes=self.fsizes)
        if kind == "poly":
            return 0.0, 0.0
        return lever_body_size(self.fa, k, mu_v=mu, lang=self.lang, sizes=self.fsizes)

    def _draw(self, kind: str, k: int, grp: str | None, mu: float) -> View:
        fa, lang, sizes = self.fa, self.lang, self.fsizes
        if kind == "group" and grp is not None:
            return group_view(fa, grp, k, mu_l=mu, lang=lang, sizes=sizes)
        if kind == "poly" and grp is not None:
            return polygon_view(fa, grp, k, mu_f=mu, lang=lang, sizes=sizes)
        return lever_view(fa, k, mu_v=mu, lang=lang, sizes=sizes)


def _fit_top(draw: _ForceDrawings, chosen, region, req: Request, modes=("row", "stack")):
    """Groups, polygons and levers of the chosen positions, a row per position under its
    heading: each group with its polygon beside it or under it (whichever of `modes`, the
    arrangements of `_Rows`, leaves the larger drawings), then the lever. (placed views,
    scales)."""
    best, failure = None, None
    for mode in modes:
        rows = _Rows(draw, chosen, region, req, mode=mode)
        try:
            # a layout's score only falls as it shrinks: one that falls to the best is dropped
            if not rows.solve(floor=None if best is None else best.score() + 1e-9):
                continue
        except ScaleError as exc:
            failure = failure or exc
            continue
        if best is None or rows.score() > best.score() + 1e-9:
            best = rows
    if best is None:
        raise failure if failure is not None else ScaleError(f"the force views do not fit {req.fmt}")
    return best.place()


class _Rows(ShrinkingRows):
    """One arrangement of :func:`_fit_top` (``mode``: a group's polygon beside it, "row",
    under it, "stack", or under it where the two fit a row's height so, "fit"), shrunk by
    `velplan.sheets.solver.ShrinkingRows`: each drawing starts at the largest standard scale
    that fits the row's height; the groups together share μl (an ESKD scale), each polygon
    and each lever has its own standard scale, the lever's no smaller than `MIN_LEVER_MM`."""

    def __init__(self, draw: _ForceDrawings, chosen, region, req: Request, *, mode: str):
        fa = draw.fa
        self.draw, self.chosen, self.fmt = draw, chosen, req.fmt
        self.least = MIN_TARGET_MM[req.fmt]
        self.least_lever = max(MIN_LEVER_MM[req.fmt], self.least)
        self.mech = fa.kinetostatics.mechanism
        x0, y0, x1, y1 = region
        count = len(chosen)
        self.head_h = 1.6 * draw.fsizes.title_mm + 2.0
        row_h = (y1 - y0 - req.gap * (count - 1)) / count - self.head_h - req.gap / 2
        order = solving_order(self.mech)
        layout = [[[("group", k, grp), ("poly", k, grp)] for grp in order] + [[("lever", k, None)]]
                  for k in chosen]
        span, scale = _spans_and_scales(fa, chosen, order, row_h)
        self.partner = {k: crank_partner(fa, k) for k in chosen}
        super().__init__(layout, region, req.gap, row_h, mode, span, scale)

    def fail(self, why: str) -> ScaleError:
        x0, y0, x1, y1 = self.region
        count = len(self.chosen)
        return ScaleError(
            f"the groups, force polygons and lever of position{'s' if count > 1 else ''} "
            f"{', '.join(map(str, self.chosen))} do not fit {self.fmt} at any standard scale with "
            f"drawings of at least {self.least:.0f} mm ({x1 - x0:.0f} × {y1 - y0:.0f} mm free, "
            f"Zhukovsky's lever at least {self.least_lever:.0f} mm across, {why}); use fewer "
            f"--plans or a larger --format")

    def solve(self, floor: float | None = None) -> bool:
        """`ShrinkingRows.solve`, refused at once where a lever is below its least size at
        the scale it starts at (the row is too low for it)."""
        for k in self.chosen:
            size = self.span[("lever", k)] / self.scale[("lever", k)]
            if size < self.least_lever - 1e-9:
                raise self.fail(f"lever-{k} {size:.0f} mm in rows of {max(self.row_h, 0):.0f} mm")
        return super().solve(floor)

    def records(self, ref) -> bool:
        """The polygons' and levers' scales are recorded by view; the groups' is μl."""
        return ref[0] != "group"

    def entity(self, ref):
        """What a drawing's scale belongs to: all the groups, one polygon (the initial link's
        shares the μF of the group that loads it, `crank_partner`), one lever."""
        kind, k, grp = ref
        if kind == "group":
            return "groups"
        if kind == "poly":
            return (kind, k, self.partner[k] if grp == "crank" else grp)
        return (kind, k)

    def view(self, ref) -> View:
        return self.draw.view(*ref, self.scale[self.entity(ref)])

    def least_height(self, ref) -> float:
        """A group's links alone, a lever's bars alone (`_ForceDrawings.least`); a polygon, quick
        to draw: 0."""
        return 0.0 if ref[0] == "poly" else self.draw.least(*ref, self.scale[self.entity(ref)])[1]

    def smaller(self, entity) -> float | None:
        """The next smaller drawing of `entity`, or None below the legible size."""
        mu = self.scale[entity]
        if entity != "groups":
            nxt = standard_scale(mu * 1.0001)
            least = self.least_lever if entity[0] == "lever" else self.least
            return nxt if self.span[entity] / nxt >= least else None
        eskd = eskd_scales()
        j = eskd.index(mu) + 1
        if j >= len(eskd):
            return None
        nxt = eskd[j]
        if self.span["groups"] / nxt < self.least or self.mech.crank.length / nxt < MIN_CRANK_MM:
            return None
        return nxt

    def place(self):
        """(placed views, scales): the rows from the top, the spare height shared out between
        them, each row's spare width between its units."""
        x0, _, x1, y1 = self.region
        gap, count = self.gap, len(self.chosen)
        heights = [max(self.unit_size(u)[1] for u in units) for units in self.layout]
        spare = max(self.region[3] - self.region[1] - sum(h + self.head_h for h in heights)
                    - gap * (count - 1), 0.0) / count
        placed: dict[str, PlacedView] = {}
        scales: dict[str, float] = {"mu_l": self.scale["groups"]}
        y = y1
        for k, units, height in zip(self.chosen, self.layout, heights):
            heading = _heading(self.draw.fa, k, self.draw.lang, self.draw.fsizes)
            placed[heading.name] = heading.at(x0, y - heading.height_mm)
            y -= self.head_h
            extra = max(x1 - x0 - self.row_width(units), 0.0) / len(units)
            x = x0 + extra / 2
            for unit in units:
                self.place_unit(unit, x, y, placed, scales)
                x += self.unit_size(unit)[0] + gap + extra
            y -= height + gap + spare
        return placed, scales


def crank_partner(fa: ForceAnalysis, k: int) -> str:
    """The group whose polygon the initial link's polygon shares μF with: of the groups joined
    to the crank's tip (the reaction R₂₁ = −R₁₂ is a side of both polygons, so the student
    carries it over with dividers), the one with the larger polygon at position `k`."""
    mech = fa.kinetostatics.mechanism
    joined = [g.name for g in mech.groups if mech.crank.tip in g.joints_in()] or [mech.groups[0].name]
    return max(joined, key=lambda grp: max(polygon_extent(fa.kinetostatics.polygons[grp], k)))


def _spans_and_scales(fa: ForceAnalysis, chosen, order, row_h: float) -> tuple[dict, dict]:
    """The drawings' spans (m, N, m/s: the larger side) and their starting scales, each
    drawing as tall as a row (the groups: the largest ESKD scale)."""
    ks = fa.kinetostatics
    eskd = eskd_scales()
    group_span = max(max(group_extent_m(fa, grp, k)) for k in chosen for grp in order)
    span: dict = {"groups": group_span}
    for k in chosen:
        for grp in order:
            span[("poly", k, grp)] = max(max(polygon_extent(ks.polygons[grp], k)), 1e-9)
        span[("lever", k)] = max(max(lever_extent(fa, k)), 1e-12)
    scale: dict = {"groups": next((mu for mu in eskd if group_span / mu <= row_h), eskd[-1])}
    for e, value in span.items():
        if e != "groups":
            scale[e] = standard_scale(value / row_h)
    return span, scale


def _heading(fa: ForceAnalysis, k: int, lang: Language, fsizes: ForceSizes) -> View:
    """The row's heading: the position, its crank angle, and that forces are not to scale."""
    deg = math.degrees(float(fa.kinematics.phi[position_index(k, len(fa.kinematics))])) % 360.0
    text = (f"{label('position', lang)} {k}: φ = {fixed(deg, lang, 1)}°; "
            f"{label('forces_not_to_scale', lang)}")
    return make_view(f"heading-{k}", [Text((0.0, 0.0), text, "fheading", fsizes.title_mm)],
                     pad_mm=1.0, meta={"number": k})


force_sheet_text = sheet_text
"""Every text of the force sheet, one per line."""

__all__ = ["ForceSheet", "build_force_sheet", "default_force_positions", "default_force_title",
           "force_sheet_text", "has_forces", "solving_order", "slug"]
