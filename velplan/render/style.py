"""The drafting standard as one validated value: line widths, dashes, fonts, arrows.

ESKD (GOST 2.303, 2.304) fixes the line types and text heights a course-work sheet uses;
:class:`SheetStyle` holds them so that no drawing code carries loose constants. Meaning is
carried by line width and dash pattern, never by colour alone: everything is black unless
the caller asks for a colour on plan vectors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal, Mapping

from velplan.errors import VelplanError
from velplan.render.fonts import BUNDLED_FAMILY
from velplan.options import LANGUAGES, Language

LineType = Literal["thick", "thin", "construction", "axis", "hidden"]

#: Line types, in the order of GOST 2.303's table (used in error messages).
LINE_TYPES: tuple[str, ...] = ("thick", "thin", "construction", "axis", "hidden")

#: Standard text heights (capital letter height, mm) of GOST 2.304 / ISO 3098.
ESKD_TEXT_HEIGHTS: tuple[float, ...] = (1.8, 2.5, 3.5, 5.0, 7.0, 10.0, 14.0, 20.0)

#: Smallest text height ESKD allows, mm.
MIN_TEXT_HEIGHT_MM = 1.8

# Narrow faces first: ESKD letters are about 0.6·h wide; the layout measures each character
# at the wider of DejaVu Sans Condensed's and Velplan Sans's advances (render/sans_widths.py),
# and a normal-width sans runs ~10 % wider than that.
_LATIN_FONTS = ("DejaVu Sans Condensed", "Liberation Sans Narrow", "Arial Narrow",
                "DejaVu Sans", "Arial", "sans-serif")
# An installed CJK face first, else the bundled Velplan Sans (which PNG and PDF sheets and
# matplotlib always have, velplan.render.fonts), before any Latin face: cairosvg draws a
# text with one font, and a sheet should not mix them. Browsers walk the list the same way.
_CJK_FONTS = ("Noto Sans CJK SC", "Source Han Sans SC", "WenQuanYi Micro Hei",
              "Microsoft YaHei", "SimHei", "PingFang SC", BUNDLED_FAMILY,
              "DejaVu Sans Condensed", "DejaVu Sans", "sans-serif")

DEFAULT_FONT_FAMILIES: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"en": _LATIN_FONTS, "ru": _LATIN_FONTS, "uk": _LATIN_FONTS, "zh": _CJK_FONTS})

# Capital (resp. ideograph) height as a fraction of the em size, for the default fonts:
# ESKD text height is the capital height, while SVG and matplotlib size fonts by the em.
_CAP_HEIGHT_RATIO: Mapping[str, float] = MappingProxyType(
    {"en": 0.72, "ru": 0.72, "uk": 0.72, "zh": 0.86})


@dataclass(frozen=True, slots=True)
class SheetStyle:
    """Drafting conventions of one sheet.

    Parameters
    ----------
    language : {"en", "ru", "uk", "zh"}
        Language of the labels; also picks the default font families.
    thick_mm, thin_mm, construction_mm, axis_mm, hidden_mm : float
        Stroke width of each line type, mm. ESKD: thick (main) S = 0.5…1.4 mm,
        thin lines S/3…S/2.
    axis_dash, hidden_dash, construction_dash : tuple of float
        Dash patterns, mm, alternating dash and gap; empty for a solid line.
        ESKD dash-dot axis: dashes 5…30 mm, gaps 3…5 mm; dashed: dashes 2…8, gaps 1…2 mm.
    text_height_mm : float
        Default text height (capital letter height), mm; one of
        :data:`ESKD_TEXT_HEIGHTS`, at least 1.8 mm.
    font_family : tuple of str or None
        Font families in order of preference; None picks the default for `language`.
    italic : bool
        Slanted text, as the ESKD type B font is usually drawn.
    arrow_length_mm, arrow_width_mm : float
        Default arrowhead length along the vector and full width across it, mm.
    hatch_spacing_mm, hatch_angle_deg : float
        Distance between hatch lines, mm, and their angle to the x axis, degrees.
    colour : str
        Colour of every stroke, fill and text (an SVG colour).
    plan_vector_colour : str or None
        Optional colour for primitives on layers named ``plan-…``; width and arrowheads
        still carry the meaning, so the sheet reads the same printed in black.
    """

    language: Language = "ru"
    thick_mm: float = 0.7
    thin_mm: float = 0.35
    construction_mm: float = 0.25
    axis_mm: float = 0.35
    hidden_mm: float = 0.35
    axis_dash: tuple[float, ...] = (12.0, 3.0, 1.0, 3.0)
    hidden_dash: tuple[float, ...] = (4.0, 1.5)
    construction_dash: tuple[float, ...] = ()
    text_height_mm: float = 3.5
    font_family: tuple[str, ...] | None = None
    italic: bool = False
    arrow_length_mm: float = 4.5
    arrow_width_mm: float = 1.5
    hatch_spacing_mm: float = 2.0
    hatch_angle_deg: float = 45.0
    colour: str = "black"
    plan_vector_colour: str | None = None

    def __post_init__(self) -> None:
        if self.language not in LANGUAGES:
            raise VelplanError(f"SheetStyle.language {self.language!r} is unknown; "
                               f"known languages: {', '.join(LANGUAGES)}")
        for name in ("thick_mm", "thin_mm", "construction_mm", "axis_mm", "hidden_mm",
                     "arrow_length_mm", "arrow_width_mm", "hatch_spacing_mm"):
            _check_positive(name, getattr(self, name))
        for name in ("axis_dash", "hidden_dash", "construction_dash"):
            _check_dash(name, getattr(self, name))
        _check_text_height(self.text_height_mm)
        if self.font_family is not None and (
                not self.font_family or not all(isinstance(f, str) and f.strip()
                                                for f in self.font_family)):
            raise VelplanError("SheetStyle.font_family must be None or a non-empty tuple "
                               f"of font names, got {self.font_family!r}")
        if not math.isfinite(self.hatch_angle_deg):
            raise VelplanError(f"SheetStyle.hatch_angle_deg must be finite, "
                               f"got {self.hatch_angle_deg!r}")
        if not self.colour or (self.plan_vector_colour is not None
                               and not self.plan_vector_colour):
            raise VelplanError("SheetStyle colours must be non-empty SVG colour names")

    def width(self, line: LineType) -> float:
        """Stroke width of line type `line`, mm."""
        return getattr(self, f"{_checked_line(line)}_mm")

    def dash(self, line: LineType) -> tuple[float, ...]:
        """Dash pattern of line type `line`, mm; empty for a solid line."""
        _checked_line(line)
        return getattr(self, f"{line}_dash", ())

    @property
    def font_families(self) -> tuple[str, ...]:
        """Font families in order of preference, resolved for the language."""
        if self.font_family is not None:
            return self.font_family
        return DEFAULT_FONT_FAMILIES[self.language]

    @property
    def font_css(self) -> str:
        """The font families as a CSS ``font-family`` value (names with spaces quoted)."""
        return ", ".join(f"'{f}'" if " " in f else f for f in self.font_families)

    def font_size_em(self, text_height_mm: float) -> float:
        """Em size, mm, that gives capitals of height `text_height_mm`, mm."""
        return text_height_mm / _CAP_HEIGHT_RATIO[self.language]

    def stroke_colour(self, layer: str) -> str:
        """Colour for the primitives of `layer` (plan layers may have their own)."""
        if self.plan_vector_colour is not None and layer.startswith("plan-"):
            return self.plan_vector_colour
        return self.colour


def _checked_line(line: str) -> str:
    if line not in LINE_TYPES:
        raise VelplanError(f"unknown line type {line!r}; known line types: "
                           f"{', '.join(LINE_TYPES)}")
    return line


def _check_positive(name: str, value: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise VelplanError(f"SheetStyle.{name} must be a positive length in mm, "
                           f"got {value!r}")


def _check_dash(name: str, dash: tuple[float, ...]) -> None:
    if len(dash) % 2 or not all(math.isfinite(d) and d > 0 for d in dash):
        raise VelplanError(f"SheetStyle.{name} must be an even number of positive lengths "
                           f"in mm (dash, gap, …), got {dash!r}")


def _check_text_height(height: float) -> None:
    if not (math.isfinite(height) and height >= MIN_TEXT_HEIGHT_MM):
        raise VelplanError(f"SheetStyle.text_height_mm must be at least "
                           f"{MIN_TEXT_HEIGHT_MM} mm (ESKD), got {height!r}")
    if not any(math.isclose(height, h) for h in ESKD_TEXT_HEIGHTS):
        raise VelplanError(f"SheetStyle.text_height_mm {height!r} is not a standard height; "
                           f"use one of {', '.join(f'{h:g}' for h in ESKD_TEXT_HEIGHTS)} mm")
