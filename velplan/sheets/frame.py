"""Sheet formats, the drawing frame and the title block.

ESKD (GOST 2.301, 2.104): the frame runs 20 mm from the left edge (binding margin) and
5 mm from the others; the main title block, form 1, is 185 × 55 mm in the lower-right
corner of the frame. ``frame_style="iso"`` gives the same frame with a simpler 180 × 36 mm
block whose cells carry small captions (as ISO 7200 and Chinese course sheets do).

Examples
--------
>>> frame_bounds("A3")
(20.0, 5.0, 415.0, 292.0)
>>> title_block_bounds("A3")
(230.0, 5.0, 415.0, 60.0)
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal, Mapping

import shapely

from velplan.errors import VelplanError
from velplan.options import Language
from velplan.render.i18n import check_language, label
from velplan.render.layout import fit_text
from velplan.render.scene import Bounds, Polygon, Polyline, Primitive, Scene, Text
from velplan.render.style import LineType

FormatName = Literal["A1", "A2", "A3", "A4"]
FrameStyle = Literal["eskd", "iso"]

#: Frame offset from the left (binding) edge, mm.
FRAME_LEFT_MM = 20.0
#: Frame offset from the top, right and bottom edges, mm.
FRAME_MARGIN_MM = 5.0


@dataclass(frozen=True, slots=True)
class SheetFormat:
    """A sheet size, mm (width along x, height along y)."""

    name: str
    width_mm: float
    height_mm: float


SHEET_FORMATS: Mapping[str, SheetFormat] = MappingProxyType({
    "A1": SheetFormat("A1", 841.0, 594.0),
    "A2": SheetFormat("A2", 594.0, 420.0),
    "A3": SheetFormat("A3", 420.0, 297.0),
    "A4": SheetFormat("A4", 210.0, 297.0),  # portrait, as ESKD uses it
})

TITLE_BLOCK_SIZE: Mapping[str, tuple[float, float]] = MappingProxyType(
    {"eskd": (185.0, 55.0), "iso": (180.0, 36.0)})


@dataclass(frozen=True, slots=True)
class TitleInfo:
    """What the title block says. All fields are text given by the caller.

    Parameters
    ----------
    title : str
        Name of the drawing (ESKD graph 1), e.g. "Kinematic analysis of the shaper".
    designation : str
        Document designation (graph 2), e.g. "ТММ.КП.02.00.000".
    scale : str
        Scale text (graph 6), e.g. "1:2".
    sheet, sheets : int
        This sheet's number and the total (graphs 7, 8).
    author, checker, approved : str
        Surnames (graph 11).
    organisation : str
        University and group (graph 9).
    date : str
        Date as the caller wants it written; velplan never reads the clock.
    material, mass, literal : str
        Graphs 3, 5 and 4; usually empty on course sheets.
    """

    title: str = ""
    designation: str = ""
    scale: str = ""
    sheet: int = 1
    sheets: int = 1
    author: str = ""
    checker: str = ""
    approved: str = ""
    organisation: str = ""
    date: str = ""
    material: str = ""
    mass: str = ""
    literal: str = ""

    def __post_init__(self) -> None:
        if not (isinstance(self.sheet, int) and isinstance(self.sheets, int)
                and 1 <= self.sheet <= self.sheets):
            raise VelplanError(f"TitleInfo needs 1 <= sheet <= sheets, got sheet="
                               f"{self.sheet!r}, sheets={self.sheets!r}")


def sheet_format(name: FormatName | SheetFormat) -> SheetFormat:
    """Look up a sheet format by name (a :class:`SheetFormat` passes through).

    Raises
    ------
    VelplanError
        For an unknown name; the message lists the known formats.
    """
    if isinstance(name, SheetFormat):
        return name
    try:
        return SHEET_FORMATS[name]
    except KeyError:
        raise VelplanError(f"unknown sheet format {name!r}; known formats: "
                           f"{', '.join(SHEET_FORMATS)}") from None


def _check_frame_style(frame_style: str) -> str:
    if frame_style not in TITLE_BLOCK_SIZE:
        raise VelplanError(f"unknown frame style {frame_style!r}; known styles: "
                           f"{', '.join(TITLE_BLOCK_SIZE)}")
    return frame_style


def frame_bounds(fmt: FormatName | SheetFormat = "A1") -> Bounds:
    """(xmin, ymin, xmax, ymax) of the drawing frame, mm from the sheet's lower-left."""
    f = sheet_format(fmt)
    return (FRAME_LEFT_MM, FRAME_MARGIN_MM,
            f.width_mm - FRAME_MARGIN_MM, f.height_mm - FRAME_MARGIN_MM)


def title_block_bounds(fmt: FormatName | SheetFormat = "A1",
                       frame_style: FrameStyle = "eskd") -> Bounds:
    """(xmin, ymin, xmax, ymax) of the title block: the frame's lower-right corner, mm."""
    width, height = TITLE_BLOCK_SIZE[_check_frame_style(frame_style)]
    _, y0, x1, _ = frame_bounds(fmt)
    return (x1 - width, y0, x1, y0 + height)


def free_area(fmt: FormatName | SheetFormat = "A1", *, frame_style: FrameStyle = "eskd",
              margin_mm: float = 0.0) -> shapely.Polygon:
    """The area views may use: inside the frame, outside the title block, mm.

    Parameters
    ----------
    fmt : {"A1", "A2", "A3", "A4"} or SheetFormat
        Sheet format.
    frame_style : {"eskd", "iso"}
        Which title block is cut out.
    margin_mm : float
        Clearance kept from the frame and the title block, mm.

    Returns
    -------
    shapely.Polygon
        An L-shaped polygon.
    """
    area = shapely.box(*frame_bounds(fmt)).difference(
        shapely.box(*title_block_bounds(fmt, frame_style)))
    if margin_mm:
        area = area.buffer(-margin_mm, join_style="mitre")
    return area


def _rect(bounds: Bounds, layer: str, line: LineType) -> Polygon:
    x0, y0, x1, y1 = bounds
    return Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], layer, line)


def frame(fmt: FormatName | SheetFormat = "A1") -> tuple[Primitive, ...]:
    """The sheet's trim line (thin) and the drawing frame (thick), layer ``"frame"``."""
    f = sheet_format(fmt)
    return (_rect((0.0, 0.0, f.width_mm, f.height_mm), "frame", "thin"),
            _rect(frame_bounds(f), "frame", "thick"))


# -- ESKD form 1 -------------------------------------------------------------------------
# Local coordinates: x from the block's left edge (0…185), y from its bottom (0…55).
# Lines: (x0, y0, x1, y1, line type).
_ESKD_LINES: tuple[tuple[float, float, float, float, LineType], ...] = (
    # columns of the left part: Изм. 7 | Лист 10 | № докум. 23 | Подп. 15 | Дата 10
    (7, 30, 7, 55, "thick"), (17, 0, 17, 55, "thick"), (40, 0, 40, 55, "thick"),
    (55, 0, 55, 55, "thick"), (65, 0, 65, 55, "thick"),
    # rows of the left part: changes and signatures thin, the header row framed thick
    *((0, y, 65, y, "thin") for y in (5, 10, 15, 20, 25, 40, 45, 50)),
    (0, 30, 65, 30, "thick"), (0, 35, 65, 35, "thick"),
    # right part: designation | name, Лит./Масса/Масштаб, Лист/Листов | material, org.
    (65, 40, 185, 40, "thick"), (135, 0, 135, 40, "thick"),
    (135, 35, 185, 35, "thick"), (135, 20, 185, 20, "thick"), (65, 15, 185, 15, "thick"),
    (150, 20, 150, 40, "thick"), (167, 20, 167, 40, "thick"), (155, 15, 155, 20, "thick"),
    (140, 20, 140, 35, "thin"), (145, 20, 145, 35, "thin"),
)

# Caption cells: (label key, (x0, y0, x1, y1)).
_ESKD_CAPTIONS: tuple[tuple[str, Bounds], ...] = (
    ("change", (0, 30, 7, 35)), ("sheet_short", (7, 30, 17, 35)),
    ("document_no", (17, 30, 40, 35)), ("signature", (40, 30, 55, 35)),
    ("date", (55, 30, 65, 35)),
    ("designed", (0, 25, 17, 30)), ("checked", (0, 20, 17, 25)),
    ("tech_control", (0, 15, 17, 20)), ("norm_control", (0, 5, 17, 10)),
    ("approved", (0, 0, 17, 5)),
    ("literal", (135, 35, 150, 40)), ("mass", (150, 35, 167, 40)),
    ("scale", (167, 35, 185, 40)),
)


def _eskd_values(info: TitleInfo, lang: Language) -> tuple[tuple[str, Bounds, float, str], ...]:
    """(text, local cell, preferred height mm, anchor) of the filled-in graphs."""
    return (
        (info.designation, (65, 40, 185, 55), 7.0, "middle"),
        (info.title, (65, 15, 135, 40), 5.0, "middle"),
        (info.material, (65, 0, 135, 15), 3.5, "middle"),
        (info.organisation, (135, 0, 185, 15), 3.5, "middle"),
        (info.literal, (135, 20, 150, 35), 3.5, "middle"),
        (info.mass, (150, 20, 167, 35), 3.5, "middle"),
        (info.scale, (167, 20, 185, 35), 5.0, "middle"),
        (f"{label('sheet', lang)} {info.sheet}", (135, 15, 155, 20), 2.5, "start"),
        (f"{label('sheets', lang)} {info.sheets}", (155, 15, 185, 20), 2.5, "start"),
        (info.author, (17, 25, 40, 30), 2.5, "start"),
        (info.date, (55, 25, 65, 30), 2.5, "middle"),
        (info.checker, (17, 20, 40, 25), 2.5, "start"),
        (info.approved, (17, 0, 40, 5), 2.5, "start"),
    )


def _shift(cell: Bounds, origin: tuple[float, float]) -> Bounds:
    x, y = origin
    return (cell[0] + x, cell[1] + y, cell[2] + x, cell[3] + y)


def _eskd_block(info: TitleInfo, origin: tuple[float, float], lang: Language):
    x, y = origin
    items: list[Primitive] = [_rect((x, y, x + 185.0, y + 55.0), "title", "thick")]
    items += [Polyline([(x + x0, y + y0), (x + x1, y + y1)], "title", line)
              for x0, y0, x1, y1, line in _ESKD_LINES]
    for key, cell in _ESKD_CAPTIONS:
        anchor = "start" if cell[0] == 0 and cell[1] < 30 else "middle"
        items += fit_text(label(key, lang), _shift(cell, origin), layer="title",
                          size_mm=2.5, anchor=anchor, padding_mm=0.7)
    for text, cell, size, anchor in _eskd_values(info, lang):
        items += fit_text(text, _shift(cell, origin), layer="title", size_mm=size,
                          anchor=anchor, padding_mm=0.7)
    return items


# -- ISO-style block ---------------------------------------------------------------------
# (caption key, local cell, preferred value height mm, TitleInfo field or None).
_ISO_CELLS: tuple[tuple[str, Bounds, float, str], ...] = (
    ("organisation", (0, 24, 80, 36), 3.5, "organisation"),
    ("designed", (0, 12, 50, 24), 3.5, "author"),
    ("date", (50, 12, 80, 24), 3.5, "date"),
    ("checked", (0, 0, 50, 12), 3.5, "checker"),
    ("scale", (50, 0, 80, 12), 3.5, "scale"),
    ("title", (80, 12, 180, 36), 7.0, "title"),
    ("designation", (80, 0, 150, 12), 5.0, "designation"),
    ("sheet", (150, 0, 180, 12), 3.5, ""),
)
_ISO_CAPTION_MM = 2.5  # the ESKD least height


def _iso_block(info: TitleInfo, origin: tuple[float, float], lang: Language):
    x, y = origin
    items: list[Primitive] = []
    for key, cell, size, field in _ISO_CELLS:
        x0, y0, x1, y1 = _shift(cell, origin)
        items.append(_rect((x0, y0, x1, y1), "title", "thin"))
        items.append(Text((x0 + 1.0, y1 - 1.0), label(key, lang), "title",
                          _ISO_CAPTION_MM, "start", "top"))
        value = getattr(info, field) if field else f"{info.sheet} / {info.sheets}"
        items += fit_text(value, (x0, y0, x1, y1 - _ISO_CAPTION_MM - 1.0), layer="title",
                          size_mm=size, anchor="middle", padding_mm=1.0)
    items.append(_rect((x, y, x + 180.0, y + 36.0), "title", "thick"))
    return items


def title_block(info: TitleInfo, fmt: FormatName | SheetFormat = "A1", *,
                frame_style: FrameStyle = "eskd", lang: Language = "ru") -> tuple[Primitive, ...]:
    """The title block's lines and texts, layer ``"title"``, in the frame's corner.

    Parameters
    ----------
    info : TitleInfo
        What to write.
    fmt : {"A1", "A2", "A3", "A4"} or SheetFormat
        Sheet format.
    frame_style : {"eskd", "iso"}
        ESKD form 1 (185 × 55 mm) or the simpler captioned block (180 × 36 mm).
    lang : {"en", "ru", "uk", "zh"}
        Language of the captions.

    Returns
    -------
    tuple of Primitive
    """
    check_language(lang)
    x0, y0, _, _ = title_block_bounds(fmt, frame_style)
    build = _eskd_block if frame_style == "eskd" else _iso_block
    return tuple(build(info, (x0, y0), lang))


def sheet_scene(info: TitleInfo, fmt: FormatName | SheetFormat = "A1", *,
                frame_style: FrameStyle = "eskd", lang: Language = "ru") -> Scene:
    """A blank sheet: trim line, frame and filled title block, ready to :meth:`Scene.extend`."""
    f = sheet_format(fmt)
    return Scene(frame(f) + title_block(info, f, frame_style=frame_style, lang=lang),
                 f.width_mm, f.height_mm)
