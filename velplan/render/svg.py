"""SVG backend: writes the SVG text itself (no SVG library to import).

The output is deterministic — numbers with a fixed precision, group ids derived from layer
names, no timestamps — so golden files compare byte for byte. Arrowheads are filled
polygons and hatching is explicit lines (no markers, no patterns), so cairosvg, browsers
and Inkscape render them alike. The sheet is sized in millimetres with a matching viewBox;
y is flipped here, the scene keeps y up. Attributes are written in name order, an element
without content as ``<name ... />``.

Examples
--------
>>> from velplan.render.scene import Scene, Polyline
>>> svg = to_svg(Scene((Polyline([(0, 0), (10, 5)], "mechanism", "thick"),), 420, 297))
>>> 'width="420mm"' in svg and 'points="0,297 10,292"' in svg
True
"""

from __future__ import annotations

import re

from velplan.render.canvas import render
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.shapes import (
    SUBSCRIPT_DROP, SUPERSCRIPT_RISE, Stroke, arrow_shape, arrow_size,
    circle_outline, hatch_segments, hatch_stroke, script_size, stroke_for, text_origin, text_runs)
from velplan.render.style import SheetStyle

_NAMESPACES = {"xmlns": "http://www.w3.org/2000/svg", "xmlns:ev": "http://www.w3.org/2001/xml-events",
               "xmlns:inkscape": "http://www.inkscape.org/namespaces/inkscape",
               "xmlns:xlink": "http://www.w3.org/1999/xlink"}
_PAPER = "white"
# Characters XML 1.0 forbids (C0 controls but tab, LF, CR) become U+FFFD.
_FORBIDDEN = {code: "\ufffd" for code in range(0x20) if chr(code) not in "\t\n\r"}
_TEXT_ESCAPES = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", **_FORBIDDEN})
#: A character `_ATTRIBUTE_ESCAPES` changes (most values, numbers and names, have none).
_ESCAPED = re.compile(r'[&<>"\x00-\x1f]')
_ATTRIBUTE_ESCAPES = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;",
                                    "\r": "&#13;", "\n": "&#10;", "\t": "&#09;", **_FORBIDDEN})


def element(name: str, attributes: dict[str, str], content: str = "") -> str:
    """One SVG element as text: attributes in name order (empty values left out) and escaped;
    `content` is already XML (escaped text, child elements).

    >>> element("text", {"x": "1", "aria-label": 'a"b'}, escape_text("R<2"))
    '<text aria-label="a&quot;b" x="1">R&lt;2</text>'
    """
    marks = "".join(f' {key}="{value.translate(_ATTRIBUTE_ESCAPES) if _ESCAPED.search(value) else value}"'
                    for key, value in sorted(attributes.items()) if value)
    return f"<{name}{marks}>{content}</{name}>" if content else f"<{name}{marks} />"


def escape_text(text: str) -> str:
    """`text` as XML character data."""
    return text.translate(_TEXT_ESCAPES)


class SvgCanvas:
    """Draws a scene as an SVG document.

    Parameters
    ----------
    style : SheetStyle, optional
        Line widths, dashes, fonts and arrow sizes; the default ESKD style if omitted.
    precision : int
        Decimals kept in every coordinate and length (mm).

    Notes
    -----
    Each run of consecutive primitives on one layer becomes an Inkscape layer group
    ``<g id="layer-NAME" class="layer NAME" inkscape:groupmode="layer">``; a layer that
    comes back later in the scene gets ``id="layer-NAME-2"`` and so on, so drawing order
    is kept exactly.
    """

    def __init__(self, style: SheetStyle | None = None, *, precision: int = 3) -> None:
        self.style = style if style is not None else SheetStyle()
        self.precision = precision
        self._spec = f".{precision}f"
        self._root: dict[str, str] = {}
        self._height = 0.0
        self._groups: list[tuple[dict[str, str], list[str]]] = []
        self._group_layer: str | None = None
        self._layer_runs: dict[str, int] = {}

    # -- number and coordinate formatting -------------------------------------------

    def _num(self, value: float) -> str:
        text = format(value, self._spec).rstrip("0").rstrip(".")
        return "0" if text in ("-0", "") else text

    def _xy(self, point) -> tuple[str, str]:
        return self._num(float(point[0])), self._num(self._height - float(point[1]))

    def _points(self, points) -> str:
        # `_xy` of each point, inlined: a sheet writes tens of thousands of coordinates
        spec, height, parts = self._spec, self._height, []
        for p in points:
            x = format(float(p[0]), spec).rstrip("0").rstrip(".")
            y = format(height - float(p[1]), spec).rstrip("0").rstrip(".")
            parts.append(f"{'0' if x in ('-0', '') else x},{'0' if y in ('-0', '') else y}")
        return " ".join(parts)

    def _path(self, segments) -> str:
        return " ".join("M{},{} L{},{}".format(*self._xy(a), *self._xy(b))
                        for a, b in segments)

    # -- canvas protocol --------------------------------------------------------------

    def begin(self, width_mm: float, height_mm: float) -> None:
        w, h = self._num(width_mm), self._num(height_mm)
        self._root = {"baseProfile": "full", "height": f"{h}mm", "version": "1.1",
                      "viewBox": f"0 0 {w} {h}", "width": f"{w}mm", **_NAMESPACES}
        self._height = float(height_mm)
        self._groups, self._group_layer, self._layer_runs = [], None, {}

    def draw_polyline(self, item: Polyline) -> None:
        stroke = stroke_for(item.line, item.layer, self.style)
        self._add(item.layer, element("polyline", {
            "points": self._points(item.points), "fill": "none", **self._stroke(stroke)}))

    def draw_polygon(self, item: Polygon) -> None:
        self._hatch(item.points, item.fill, item.layer)
        stroke = stroke_for(item.line, item.layer, self.style)
        self._add(item.layer, element("polygon", {
            "points": self._points(item.points), "fill": self._fill(item.fill, stroke),
            **self._stroke(stroke)}))

    def draw_circle(self, item: Circle) -> None:
        if item.fill == "hatch":  # the outline only for its hatching
            self._hatch(circle_outline(item.centre, item.radius), item.fill, item.layer)
        stroke = stroke_for(item.line, item.layer, self.style)
        cx, cy = self._xy(item.centre)
        self._add(item.layer, element("circle", {
            "cx": cx, "cy": cy, "r": self._num(item.radius),
            "fill": self._fill(item.fill, stroke), **self._stroke(stroke)}))

    def draw_arrow(self, item: Arrow) -> None:
        stroke = stroke_for(item.line, item.layer, self.style)
        length, width = arrow_size(item.head_length, item.head_width, self.style,
                                   stroke.width)
        shape = arrow_shape(item.start, item.end, length, width)
        if shape.shaft is not None:
            (x1, y1), (x2, y2) = (self._xy(p) for p in shape.shaft)
            self._add(item.layer, element("line", {
                "x1": x1, "y1": y1, "x2": x2, "y2": y2, **self._stroke(stroke)}))
        if shape.head is not None:
            self._add(item.layer, element("polygon", {
                "points": self._points(shape.head), "fill": stroke.colour, "stroke": "none"}))

    def draw_text(self, item: Text) -> None:
        x, y = self._xy(text_origin(item))
        attributes = {
            "x": x, "y": y,
            "font-size": self._num(self.style.font_size_em(item.size_mm)),
            "font-family": self.style.font_css,
            "text-anchor": item.anchor,
            "fill": self.style.stroke_colour(item.layer),
        }
        if self.style.italic:
            attributes["font-style"] = "italic"
        transforms = []
        if item.rotation_deg:
            transforms.append(f"rotate({self._num(-item.rotation_deg)} {x} {y})")
        if item.width_factor != 1.0:
            # narrowed letters: scaled along the baseline about the anchor (cairosvg and
            # browsers both follow a transform; a condensed font may not be installed)
            transforms.append(f"translate({x} 0) scale({self._num(item.width_factor)} 1) "
                              f"translate({self._num(-text_origin(item)[0])} 0)")
        if transforms:
            attributes["transform"] = " ".join(transforms)
        runs = text_runs(item.text)
        first = runs[0].text if runs and not runs[0].script else ""
        content = escape_text(first)
        if len(runs) > 1 or first != item.text:
            # Indices are drawn as shifted plain characters ("R24"): the label keeps its
            # meaning ("R₂₄") for screen readers and for whoever searches the file.
            attributes["aria-label"] = item.text
            content += "".join(self._index_tspans(runs[1:] if first else runs, item.size_mm))
        self._add(item.layer, element("text", attributes, content))

    def _index_tspans(self, runs, size_mm: float) -> list[str]:
        """Tspans for the runs after a text's first plain one: indices smaller and moved off
        the baseline by ``dy`` (which cairosvg, browsers and Inkscape all follow), the text
        after an index moved back."""
        tspans, shift = [], 0.0
        for run in runs:
            target = {"sub": SUBSCRIPT_DROP, "super": -SUPERSCRIPT_RISE, "": 0.0}[run.script]
            attributes = {}
            if target != shift:
                attributes["dy"] = self._num((target - shift) * size_mm)
            if run.script:
                attributes["font-size"] = self._num(
                    self.style.font_size_em(script_size(size_mm)))
            tspans.append(element("tspan", attributes, escape_text(run.text)))
            shift = target
        return tspans

    def finish(self) -> str:
        """Return the SVG document as a string (UTF-8 XML with declaration)."""
        groups = "".join(element("g", attributes, "".join(children))
                         for attributes, children in self._groups)
        body = element("svg", self._root, "<defs />" + groups)
        return f'<?xml version="1.0" encoding="utf-8" ?>\n{body}\n'

    # -- helpers ----------------------------------------------------------------------

    def _stroke(self, stroke: Stroke) -> dict[str, str]:
        attributes = {"stroke": stroke.colour, "stroke-width": self._num(stroke.width),
                      "stroke-linecap": stroke.cap, "stroke-linejoin": "round"}
        if stroke.dash:
            attributes["stroke-dasharray"] = ",".join(self._num(d) for d in stroke.dash)
        return attributes

    @staticmethod
    def _fill(fill: str | None, stroke: Stroke) -> str:
        return {"solid": stroke.colour, "white": _PAPER}.get(fill, "none")

    def _hatch(self, outline, fill: str | None, layer: str) -> None:
        if fill != "hatch":
            return
        segments = hatch_segments(outline, self.style.hatch_spacing_mm,
                                  self.style.hatch_angle_deg)
        if len(segments):
            self._add(layer, element("path", {
                "d": self._path(segments), "fill": "none",
                **self._stroke(hatch_stroke(layer, self.style))}))

    def _add(self, layer: str, text: str) -> None:
        if layer != self._group_layer:
            run = self._layer_runs.get(layer, 0) + 1
            self._layer_runs[layer] = run
            group_id = f"layer-{layer}" if run == 1 else f"layer-{layer}-{run}"
            self._groups.append(({"id": group_id, "class": f"layer {layer}",
                                  "inkscape:groupmode": "layer", "inkscape:label": layer}, []))
            self._group_layer = layer
        self._groups[-1][1].append(text)


def to_svg(scene: Scene, style: SheetStyle | None = None, *, precision: int = 3) -> str:
    """Render `scene` to an SVG string; same scene and style give identical text."""
    return render(scene, SvgCanvas(style, precision=precision))
