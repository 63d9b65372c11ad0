"""DXF backend: the only module that imports ezdxf (lazily, on the first drawing).

A scene becomes a DXF R2013 drawing at 1:1 in millimetres (``$INSUNITS = 4``) that AutoCAD,
KOMPAS-3D and other CAD programs import cleanly:

* **Layers are GOST 2.303 line types**, not the scene's layers: ``THICK`` (solid main line,
  the style's S snapped to a standard DXF lineweight, 0.70 mm by default), ``THIN``,
  ``CONSTRUCTION``, ``AXIS`` (linetype ``CENTER``, dash-dot) and ``HIDDEN`` (linetype
  ``DASHED``), thin ones at S/3 rounded up to a standard lineweight (0.25 mm by default),
  plus ``TEXT`` and ``FILL`` (arrowheads and dots, thin). Every entity is ByLayer, so a CAD
  user restyles a whole line type at one place. The linetypes are defined in the file from
  the style's dash patterns, in mm.
* **Entity types are LINE, CIRCLE, LWPOLYLINE and TEXT only** (ARC is allowed but the scene
  has no arcs): no HATCH, SOLID, MTEXT or blocks. A hatched area is its hatch lines as LINEs;
  a filled arrowhead is its triangle as a closed LWPOLYLINE plus a tapered LWPOLYLINE segment
  (width W at the base, 0 at the tip) that fills it exactly; a filled dot is its CIRCLE plus
  a "donut" LWPOLYLINE (two half-circle bulges, width r). A program that ignores polyline
  widths still shows every outline. A ``"white"`` fill (a joint or slider hiding what lies
  beneath) has no counterpart without WIPEOUT and is drawn as its outline.
* **Text** is TEXT in UTF-8 (DXF R2007 and later store Unicode as is), height = the scene's
  capital height, rotation as in the scene, narrowed letters as TEXT's width factor, and the
  DXF alignment that matches the scene's anchor (left/centre/right × baseline/middle/top), so
  the anchor point stays put when a CAD program substitutes its own font. Font: Arial (Chinese: SimHei), slanted 15° when the
  style is italic.

The scene is already y up with its origin at the sheet's bottom-left corner, exactly like
DXF world coordinates, so points are written unchanged (the SVG backend is the one that flips
y). The same scene and style give the same text: ezdxf's time stamps and GUIDs are fixed.

Examples
--------
>>> from velplan.render.scene import Scene, Polyline
>>> dxf = to_dxf(Scene((Polyline([(0, 0), (10, 5)], "mechanism", "thick"),), 420, 297))
>>> "AC1027" in dxf and "THICK" in dxf
True
"""

from __future__ import annotations

import importlib
import io
import math
import unicodedata
from contextlib import contextmanager
from functools import lru_cache
from types import MappingProxyType
from typing import Mapping

import numpy as np

from velplan.errors import VelplanError
from velplan.notation import unicode_text
from velplan.render.canvas import render
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.shapes import (
    arrow_shape, arrow_size, circle_outline, hatch_segments, stroke_for)
from velplan.render.style import LINE_TYPES, SheetStyle

#: DXF version written: AutoCAD R2013 (AC1027).
DXF_VERSION = "R2013"
#: ``$INSUNITS`` code of millimetres.
MILLIMETRES = 4

#: DXF layer of each scene line type.
LAYER_OF_LINE: Mapping[str, str] = MappingProxyType(
    {"thick": "THICK", "thin": "THIN", "construction": "CONSTRUCTION", "axis": "AXIS",
     "hidden": "HIDDEN"})
#: Layer of every TEXT entity.
TEXT_LAYER = "TEXT"
#: Layer of filled areas: arrowheads, dots, solid polygons.
FILL_LAYER = "FILL"
#: Every layer the backend defines, in the order of the layer table.
LAYERS: tuple[str, ...] = tuple(LAYER_OF_LINE.values()) + (TEXT_LAYER, FILL_LAYER)

#: DXF linetype of each dashed scene line type (solid ones are ``Continuous``).
LINETYPE_OF_LINE: Mapping[str, str] = MappingProxyType(
    {"axis": "CENTER", "hidden": "DASHED", "construction": "CONSTRUCTION"})

_DESCRIPTIONS: Mapping[str, str] = MappingProxyType({
    "thick": "GOST 2.303 solid thick main line (frame, links, plan vectors)",
    "thin": "GOST 2.303 solid thin line (positions, lines of the plans, hatching, tables)",
    "construction": "Construction lines, thin",
    "axis": "GOST 2.303 dash-dot thin line (axes, centre lines)",
    "hidden": "GOST 2.303 dashed thin line (second curves of the diagrams)",
    TEXT_LAYER: "Labels and title block text",
    FILL_LAYER: "Filled arrowheads, dots and solid areas",
})

#: Text font per language: TrueType files that Windows CAD installations have.
FONT_FILES: Mapping[str, str] = MappingProxyType(
    {"en": "arial.ttf", "ru": "arial.ttf", "uk": "arial.ttf", "zh": "simhei.ttf"})
#: Name of the text style every TEXT uses.
TEXT_STYLE = "VELPLAN"
#: Oblique angle of italic text, degrees (ESKD type B letters lean at 75°).
ITALIC_OBLIQUE_DEG = 15.0

_ALIGNMENT = {  # (anchor, baseline) → name of ezdxf's TextEntityAlignment
    ("start", "baseline"): "LEFT", ("middle", "baseline"): "CENTER",
    ("end", "baseline"): "RIGHT",
    ("start", "middle"): "MIDDLE_LEFT", ("middle", "middle"): "MIDDLE_CENTER",
    ("end", "middle"): "MIDDLE_RIGHT",
    ("start", "top"): "TOP_LEFT", ("middle", "top"): "TOP_CENTER", ("end", "top"): "TOP_RIGHT",
}
# LWPOLYLINE flag: the linetype pattern runs on across vertices (as an SVG dash array does)
# instead of restarting at each one, so a dashed curve of short segments stays dashed.
_PLINEGEN = 128
_BLACK = frozenset({"black", "#000", "#000000", "rgb(0,0,0)"})
_INSTALL_HINT = "pip install ezdxf"


def _ezdxf():
    """The ezdxf package, or a one-line VelplanError saying how to install it."""
    try:
        return importlib.import_module("ezdxf")
    except ImportError as exc:
        raise VelplanError(f"DXF export needs ezdxf ({exc}); install it with "
                           f"`{_INSTALL_HINT}`") from None


# -- lineweights and linetypes ---------------------------------------------------------------

def _standard_lineweights() -> tuple[int, ...]:
    """Lineweights DXF allows, hundredths of a mm, 0 excluded."""
    _ezdxf()
    from ezdxf.lldxf.const import VALID_DXF_LINEWEIGHTS

    return tuple(w for w in VALID_DXF_LINEWEIGHTS if w > 0)


def nearest_lineweight(width_mm: float) -> int:
    """The standard DXF lineweight nearest to `width_mm` (mm), in hundredths of a mm."""
    return min(_standard_lineweights(), key=lambda w: abs(w / 100.0 - width_mm))


def thin_lineweight(thick_mm: float) -> int:
    """Lineweight of thin lines for a main line `thick_mm` (mm): the smallest standard DXF
    lineweight of at least S/3 (GOST 2.303: S/3…S/2), in hundredths of a mm."""
    weights = _standard_lineweights()
    return next((w for w in weights if w / 100.0 >= thick_mm / 3.0 - 1e-9), weights[-1])


def layer_lineweights(style: SheetStyle) -> dict[str, int]:
    """Lineweight of every layer under `style`, hundredths of a mm: THICK from S, the rest S/3
    rounded up (with the default S = 0.7 mm: 70 and 25)."""
    thin = thin_lineweight(style.thick_mm)
    weights = {layer: thin for layer in LAYERS}
    weights[LAYER_OF_LINE["thick"]] = nearest_lineweight(style.thick_mm)
    return weights


def linetype_pattern(dash: tuple[float, ...]) -> list[float]:
    """ezdxf's simple linetype pattern of a dash pattern (dash, gap, …, mm): the total
    length, then dashes positive and gaps negative, mm."""
    elements = [d if i % 2 == 0 else -d for i, d in enumerate(dash)]
    return [float(sum(dash))] + [float(e) for e in elements]


def _linetype_description(dash: tuple[float, ...]) -> str:
    """A plain-ASCII picture of a dash pattern, as CAD programs show in their linetype lists."""
    marks = ["_" * max(1, round(d / 2)) if i % 2 == 0 else " " for i, d in enumerate(dash)]
    return ("".join(marks) * 3).strip()


def layer_linetypes(style: SheetStyle) -> dict[str, str]:
    """DXF linetype of each line-type layer under `style` (``Continuous`` for solid lines)."""
    return {LAYER_OF_LINE[line]: (LINETYPE_OF_LINE[line] if style.dash(line) else "Continuous")
            for line in LINE_TYPES}


# -- the canvas ------------------------------------------------------------------------------

class DxfCanvas:
    """Draws a scene as a DXF R2013 document in millimetres.

    Parameters
    ----------
    style : SheetStyle, optional
        Line widths (for the lineweights), dashes (for the linetypes), arrow sizes, hatching,
        language (for the font) and colours; the default ESKD style if omitted.

    Notes
    -----
    :meth:`finish` returns the document as a string; write it with
    :func:`velplan.render.export.write_dxf`, which encodes it as UTF-8.
    """

    def __init__(self, style: SheetStyle | None = None) -> None:
        self.style = style if style is not None else SheetStyle()
        self._doc = None
        self._msp = None

    # -- canvas protocol --------------------------------------------------------------------

    def begin(self, width_mm: float, height_mm: float) -> None:
        """Start a drawing of a sheet `width_mm` × `height_mm` (mm): header, tables, view."""
        ezdxf = _ezdxf()
        with _fixed_metadata(ezdxf):
            self._doc = ezdxf.new(DXF_VERSION, setup=False, units=MILLIMETRES)
        self._msp = self._doc.modelspace()
        self._set_header(width_mm, height_mm)
        self._add_linetypes()
        self._add_layers()
        self._doc.styles.add(TEXT_STYLE, font=FONT_FILES[self.style.language])
        self._doc.header["$TEXTSTYLE"] = TEXT_STYLE

    def draw_polyline(self, item: Polyline) -> None:
        """A two-point polyline as a LINE, a longer one as an open LWPOLYLINE."""
        attributes = self._attributes(LAYER_OF_LINE[item.line], item.layer)
        if len(item.points) == 2:
            self._msp.add_line(item.points[0], item.points[1], dxfattribs=attributes)
        else:
            attributes["flags"] = _PLINEGEN
            self._msp.add_lwpolyline(item.points, format="xy", dxfattribs=attributes)

    def draw_polygon(self, item: Polygon) -> None:
        """Fill lines (hatch or solid), then the outline as a closed LWPOLYLINE."""
        self._fill_area(item.points, item.fill, item.layer)
        attributes = self._attributes(LAYER_OF_LINE[item.line], item.layer)
        attributes["flags"] = _PLINEGEN
        self._msp.add_lwpolyline(item.points, format="xy", close=True, dxfattribs=attributes)

    def draw_circle(self, item: Circle) -> None:
        """Hatch lines or a solid donut, then the CIRCLE."""
        if item.fill == "solid":
            self._donut(item.centre, item.radius, item.layer)
        elif item.fill == "hatch":
            self._fill_area(circle_outline(item.centre, item.radius), "hatch", item.layer)
        self._msp.add_circle(item.centre, item.radius,
                             dxfattribs=self._attributes(LAYER_OF_LINE[item.line], item.layer))

    def draw_arrow(self, item: Arrow) -> None:
        """The shaft as a LINE up to the head's base, the head as a filled triangle."""
        stroke = stroke_for(item.line, item.layer, self.style)
        length, width = arrow_size(item.head_length, item.head_width, self.style, stroke.width)
        shape = arrow_shape(item.start, item.end, length, width)
        if shape.shaft is not None:
            self._msp.add_line(*_xy(shape.shaft),
                               dxfattribs=self._attributes(LAYER_OF_LINE[item.line],
                                                           item.layer))
        if shape.head is not None:
            self._filled_triangle(shape.head, item.layer)

    def draw_text(self, item: Text) -> None:
        """One TEXT entity anchored like the scene's text; blank texts are left out."""
        content = dxf_text_content(item.text)
        if not content.strip():
            return
        attributes = self._attributes(TEXT_LAYER, item.layer)
        attributes["style"] = TEXT_STYLE
        if self.style.italic:
            attributes["oblique"] = ITALIC_OBLIQUE_DEG
        if item.width_factor != 1.0:
            attributes["width"] = item.width_factor  # TEXT's relative x scale (group 41)
        entity = self._msp.add_text(content, height=item.size_mm, rotation=item.rotation_deg,
                                    dxfattribs=attributes)
        from ezdxf.enums import TextEntityAlignment

        align = TextEntityAlignment[_ALIGNMENT[(item.anchor, item.baseline)]]
        entity.set_placement(item.position, align=align)

    def finish(self) -> str:
        """Return the DXF document as a string (R2013: UTF-8 text once encoded)."""
        stream = io.StringIO()
        with _fixed_metadata(_ezdxf()):
            self._doc.write(stream)
        return stream.getvalue()

    # -- document set-up ----------------------------------------------------------------------

    def _set_header(self, width_mm: float, height_mm: float) -> None:
        """Units, lineweight display, linetype scale, limits, extents and the initial view."""
        header = self._doc.header
        header["$INSUNITS"] = MILLIMETRES
        header["$MEASUREMENT"] = 1          # metric
        header["$LUNITS"] = 2               # decimal
        header["$LWDISPLAY"] = 1            # show lineweights
        header["$LTSCALE"] = 1.0            # dash lengths are mm on the sheet
        header["$CELTSCALE"] = 1.0
        header["$PSLTSCALE"] = 1
        header["$ENDCAPS"] = 1              # round, as the SVG strokes solid lines
        header["$JOINSTYLE"] = 1
        corner, far = (0.0, 0.0), (float(width_mm), float(height_mm))
        self._msp.dxf.limmin, self._msp.dxf.limmax = corner, far
        self._msp.dxf.extmin = header["$EXTMIN"] = (*corner, 0.0)
        self._msp.dxf.extmax = header["$EXTMAX"] = (*far, 0.0)
        header["$LIMMIN"], header["$LIMMAX"] = corner, far
        self._doc.set_modelspace_vport(height=1.05 * float(height_mm),
                                       center=(far[0] / 2.0, far[1] / 2.0))

    def _add_linetypes(self) -> None:
        """Define CENTER, DASHED (and CONSTRUCTION if dashed) from the style's patterns, mm."""
        for line, name in LINETYPE_OF_LINE.items():
            dash = self.style.dash(line)
            if dash and name not in self._doc.linetypes:
                self._doc.linetypes.add(name, pattern=linetype_pattern(dash),
                                        description=_linetype_description(dash))

    def _add_layers(self) -> None:
        """One layer per line type, plus TEXT and FILL, each with its lineweight (colour 7)."""
        weights = layer_lineweights(self.style)
        linetypes = layer_linetypes(self.style)
        keys = {v: k for k, v in LAYER_OF_LINE.items()}
        for name in LAYERS:
            layer = self._doc.layers.add(name, color=7, lineweight=weights[name],
                                         linetype=linetypes.get(name, "Continuous"))
            layer.description = _DESCRIPTIONS[keys.get(name, name)]

    # -- fills --------------------------------------------------------------------------------

    def _fill_area(self, outline, fill: str | None, scene_layer: str) -> None:
        """Hatch lines (THIN) or close solid-fill lines (FILL) inside a polygon, mm."""
        if fill == "hatch":
            layer, spacing = LAYER_OF_LINE["thin"], self.style.hatch_spacing_mm
        elif fill == "solid":
            layer = FILL_LAYER
            spacing = layer_lineweights(self.style)[FILL_LAYER] / 100.0
        else:
            return
        attributes = self._attributes(layer, scene_layer)
        for a, b in hatch_segments(outline, spacing, self.style.hatch_angle_deg):
            self._msp.add_line(tuple(a), tuple(b), dxfattribs=attributes)

    def _filled_triangle(self, head: np.ndarray, scene_layer: str) -> None:
        """An arrowhead (tip, left, right; mm): its closed outline and a tapered segment from
        the middle of its base (full width) to its tip (zero width) that fills it."""
        tip, left, right = (tuple(map(float, p)) for p in head)
        base = ((left[0] + right[0]) / 2.0, (left[1] + right[1]) / 2.0)
        width = math.dist(left, right)
        attributes = self._attributes(FILL_LAYER, scene_layer)
        self._msp.add_lwpolyline([tip, left, right], format="xy", close=True,
                                 dxfattribs=attributes)
        self._msp.add_lwpolyline([(*base, width, 0.0), (*tip, 0.0, 0.0)], format="xyse",
                                 dxfattribs=attributes)

    def _donut(self, centre, radius: float, scene_layer: str) -> None:
        """A filled disc of `radius` (mm): a closed LWPOLYLINE of two half circles of radius
        r/2 drawn r wide, as AutoCAD's DONUT makes it."""
        x, y = centre
        half = radius / 2.0
        attributes = self._attributes(FILL_LAYER, scene_layer)
        attributes["const_width"] = radius
        self._msp.add_lwpolyline([(x - half, y, 1.0), (x + half, y, 1.0)], format="xyb",
                                 close=True, dxfattribs=attributes)

    # -- attributes ---------------------------------------------------------------------------

    def _attributes(self, dxf_layer: str, scene_layer: str) -> dict:
        """DXF attributes of an entity: its layer, and a true colour if the style gives
        `scene_layer` a colour other than black (everything else is ByLayer)."""
        attributes: dict = {"layer": dxf_layer}
        colour = self.style.stroke_colour(scene_layer)
        if colour.strip().lower().replace(" ", "") not in _BLACK:
            attributes["true_color"] = _true_colour(colour)
        return attributes


@contextmanager
def _fixed_metadata(ezdxf):
    """Within the block, ezdxf writes no time stamps and constant GUIDs (its option for
    comparable files), so that the same drawing gives the same bytes."""
    options = ezdxf.options
    before = options.write_fixed_meta_data_for_testing
    options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        options.write_fixed_meta_data_for_testing = before


@lru_cache(maxsize=32)
def _true_colour(colour: str) -> int:
    """DXF true colour (0xRRGGBB) of an SVG colour name or hex code."""
    from matplotlib.colors import to_rgb

    try:
        r, g, b = to_rgb(colour)
    except ValueError:
        raise VelplanError(f"colour {colour!r} is not an SVG colour name or #rrggbb code") \
            from None
    return (round(r * 255) << 16) | (round(g * 255) << 8) | round(b * 255)


def _xy(points) -> list[tuple[float, float]]:
    """Points of an (n, 2) array as (x, y) tuples of floats, mm."""
    return [(float(x), float(y)) for x, y in np.asarray(points, float)]


def dxf_text_content(text: str) -> str:
    """The string a TEXT entity stores for `text`: control characters become spaces, and
    ``%`` is escaped wherever ``%%`` would start an AutoCAD control code."""
    clean = "".join(" " if unicodedata.category(c) == "Cc" else c for c in unicode_text(text))
    return clean.replace("%", "%%%") if "%%" in clean else clean


def to_dxf(scene: Scene, style: SheetStyle | None = None) -> str:
    """Render `scene` to a DXF R2013 document (mm) as a string; the same scene and style give
    identical text.

    Raises
    ------
    VelplanError
        If ezdxf is missing or a colour of the style is unknown.
    """
    if style is not None and not isinstance(style, SheetStyle):
        raise VelplanError(f"to_dxf needs a SheetStyle or None, got {type(style).__name__}")
    return render(scene, DxfCanvas(style))


__all__ = ["DxfCanvas", "FILL_LAYER", "LAYERS", "LAYER_OF_LINE", "LINETYPE_OF_LINE",
           "TEXT_LAYER", "dxf_text_content", "layer_lineweights", "layer_linetypes",
           "linetype_pattern", "nearest_lineweight", "thin_lineweight", "to_dxf"]
