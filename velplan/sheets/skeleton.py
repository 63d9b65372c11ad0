"""The skeleton every sheet shares: the request (study, format, language, frame style, the
positions drawn), the drawing area, the bottom band (a table above the title block, a
diagram to their left), the title block and the scene. A sheet module supplies only its
zones and views (`velplan.sheets.kinematic`, `forces`, `dynamics`).

Examples
--------
>>> req = sheet_request("crank-slider", fmt="A3", lang="en")
>>> req.frame_style, req.gap, req.area
('iso', 6.0, (24.0, 9.0, 411.0, 288.0))
>>> check_plan_positions((3, 9), 12)
(3, 9)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable, Iterable, Mapping, Sequence

from velplan.analysis.numbering import position_index
from velplan.errors import ScaleError, VelplanError
from velplan.mechanism.model import Mechanism
from velplan.options import Format, FrameStyle, Language
from velplan.render.i18n import check_language, label
from velplan.notation import unicode_text
from velplan.render.scene import Bounds, Scene, Text
from velplan.render.style import SheetStyle
from velplan.sheets.frame import TitleInfo, sheet_scene
from velplan.sheets.layout import FORMATS, SIZES, SheetOutput, Sizes, check_layout, drawing_area
from velplan.sheets.solver import widest_first
from velplan.study import Study
from velplan.views.base import PlacedView, View


@dataclass(frozen=True)
class ComposedSheet(SheetOutput):
    """What every sheet holds.

    Attributes
    ----------
    mechanism : Mechanism
    scene : Scene
        Everything drawn, in sheet mm; render it with ``velplan.render.to_svg``.
    views : Mapping[str, PlacedView]
        View name → the view as placed on the sheet.
    scales : Mapping[str, float]
        The scales the views are drawn at, by name.
    fmt, lang, frame_style : str
    style : SheetStyle
    info : TitleInfo
        What the title block says.
    """

    mechanism: Mechanism
    scene: Scene
    views: Mapping[str, PlacedView]
    scales: Mapping[str, float]
    fmt: str
    lang: Language
    frame_style: str
    style: SheetStyle
    info: TitleInfo


@dataclass(frozen=True)
class Request:
    """A checked request for a sheet: what to draw, on which format, in which language, and
    where (``area``: the inside of the frame less the clearance; ``title_block``; sheet mm)."""

    study: Study
    fmt: str
    lang: Language
    frame_style: str
    style: SheetStyle
    sizes: Sizes
    area: Bounds
    title_block: Bounds

    @property
    def mechanism(self) -> Mechanism:
        return self.study.mechanism

    @property
    def gap(self) -> float:
        """The gap between views, mm."""
        return self.sizes.gap

    @property
    def width(self) -> float:
        """Width of the drawing area, mm."""
        return self.area[2] - self.area[0]


def sheet_request(mech: Study | Mechanism | str | Path, *, n: int = 12, fmt: Format = "A1",
                  lang: Language = "ru", frame_style: FrameStyle | None = None,
                  style: SheetStyle | None = None, assembled: bool = True) -> Request:
    """Check a sheet's options and study `mech` (a study passes through).

    ``assembled``: the sheet draws the n positions, so it needs at least 3 of them and the
    mechanism assembled at each. The frame style defaults to ESKD for ru and uk, the
    captioned block otherwise.

    Raises
    ------
    VelplanError
        An unknown language, format or frame style, fewer than 3 positions, or a position
        where the mechanism cannot be assembled (one line each).
    """
    study = mech if isinstance(mech, Study) else Study(mech, n=n)
    check_language(lang)
    if fmt not in FORMATS:
        raise VelplanError(f"unknown sheet format {fmt!r}; known formats: {', '.join(FORMATS)}")
    if assembled:
        _check_assembled(study)
    frame_style = frame_style or ("eskd" if lang in ("ru", "uk") else "iso")
    area, block = drawing_area(fmt, frame_style)
    return Request(study, fmt, lang, frame_style, style or SheetStyle(language=lang), SIZES[fmt],
                   area, block)


def _check_assembled(study: Study) -> None:
    if study.n < 3:
        raise VelplanError(f"a sheet needs at least 3 positions, not {study.n}")
    study.require_assembled()


def check_plan_positions(chosen: Sequence[int], n: int) -> tuple[int, ...]:
    """The positions (1-based) whose views a sheet draws (``--plans``), checked: at least one,
    each within 1…n, none repeated."""
    chosen = tuple(chosen)
    if not chosen:
        raise VelplanError("--plans: give at least one position")
    for k in chosen:
        try:
            position_index(k, n)
        except VelplanError as exc:
            raise VelplanError(f"--plans: {exc}") from None
    chosen = tuple(int(k) for k in chosen)
    if len(set(chosen)) != len(chosen):
        raise VelplanError(f"--plans: a position is repeated in {', '.join(map(str, chosen))}")
    return chosen


#: The share of the drawing area's width a table of positions may take in the bottom band.
TABLE_WIDTH = 0.62
#: The widths a table's letters are narrowed to, in turn, where it is too wide at the format's
#: least text size (type A lettering is about 0.6 of type B's width: `MIN_WIDTH_FACTOR`).
NARROWER_TABLE = (0.9, 0.8, 0.7, 0.6)


def fit_table(build: Callable[[float, float], View], req: Request, *, what: str, max_width: float | None = None,
              advice: str = "fewer --positions or ") -> View:
    """The table ``build(text size, width factor)`` at the largest of the format's text sizes
    that leaves it at most `max_width` mm wide (`TABLE_WIDTH` of the area by default: a table
    of positions), its letters at the format's width (`Sizes.table_width`), else at the least
    size with its letters narrowed further (`NARROWER_TABLE`);
    `what` names it in the error, `advice` precedes "a larger --format" there."""
    max_width = TABLE_WIDTH * req.width if max_width is None else max_width
    least, first = req.sizes.table[-1], req.sizes.table_width
    tries = [(size, first) for size in req.sizes.table] + [(least, f) for f in NARROWER_TABLE if f < first]
    size, view = widest_first(lambda sw: build(*sw), tries, max_width)
    if size is None:
        raise ScaleError(f"the {what} does not fit {req.fmt} even with {least:g} mm text narrowed "
                         f"to {NARROWER_TABLE[-1]:g} ({view.width_mm:.0f} mm wide, {max_width:.0f} mm "
                         f"free); use {advice}a larger --format")
    return view


def fill_bottom_band(views: dict, req: Request, *, table_view: View | None, fit_diagram,
                     diagram_share: float, required: bool, diagram_name: str, table_left: bool = False):
    """The bottom band: ``table_view`` right-aligned above the title block, the diagram that
    ``fit_diagram(region)`` draws to their left (at least ``diagram_share`` of the height
    tall). Places them in ``views``; returns (the band's top, the diagram's view or None —
    when it does not fit and is not ``required``). With ``table_left`` and no diagram, the
    table stands left of the title block instead, where it fits there: the band is as low
    as they are."""
    fx0, fy0, fx1, fy1 = req.area
    tx0, _, tx1, ty1 = req.title_block
    gap = req.gap
    right_w, band_top = tx1 - tx0, ty1 + gap
    if table_view is not None:
        right_w = max(right_w, table_view.width_mm)
        band_top = ty1 + gap + table_view.height_mm
        views["table"] = table_view.at(fx1 - table_view.width_mm, ty1 + gap)
    dview = None
    if fit_diagram is not None:
        region = (fx0, fy0, fx1 - right_w - gap, max(band_top, fy0 + diagram_share * (fy1 - fy0)))
        try:
            dview = fit_diagram(region)
        except ScaleError:
            if required:
                raise
    if dview is not None:
        views[diagram_name] = dview.at(fx0, fy0)
        return max(band_top, fy0 + dview.height_mm), dview
    if table_left and table_view is not None and table_view.width_mm <= tx0 - gap - fx0:
        views["table"] = table_view.at(fx0, fy0)
        return max(ty1 + gap, fy0 + table_view.height_mm), None
    return band_top, None


def course_title(mech: Mechanism, lang: Language, what: str, number: int, scale: str) -> TitleInfo:
    """The title block of document `number` of a course work: `what` (a label key) of the
    mechanism, its designation and scale; no date (velplan never reads the clock). The
    designation is a code, ``"ТММ 01.00.000"`` (Cyrillic in ru and uk, ``"TMM 01.00.000"``
    otherwise): the document's number, no file name (ГОСТ 2.201)."""
    prefix = "ТММ" if lang in ("ru", "uk") else "TMM"
    return TitleInfo(title=f"{label(what, lang)}: {mech.name_in(lang)}",
                     designation=f"{prefix} {number:02d}.00.000", scale=scale)


def title_with_scale(info: TitleInfo | None, default: Callable[[str], TitleInfo],
                     scale: str) -> TitleInfo:
    """The caller's title block with its scale filled in when empty, or ``default(scale)``."""
    if info is None:
        return default(scale)
    if not info.scale and scale:
        return replace(info, scale=scale)
    return info


def compose(req: Request, views: Mapping[str, PlacedView], order: Iterable[str],
            info: TitleInfo) -> Scene:
    """The sheet's scene: frame, title block and the views in `order` (later on top), after
    checking that every view lies in the free area and none overlaps another."""
    check_layout(views, req.fmt, req.frame_style)
    scene = sheet_scene(info, req.fmt, frame_style=req.frame_style, lang=req.lang)
    return scene.extend(*(views[k].primitives for k in order))


def sheet_text(sheet: SheetOutput) -> str:
    """Every text of the sheet, one per line (for tests and search), as one reads it on a line:
    marked indices in Unicode where it has them (``l_{O2A}`` → ``lO₂A``, ``M_{ур}`` → ``Mур``)."""
    return "\n".join(unicode_text(t.text) for t in sheet.scene.of_kind(Text))
