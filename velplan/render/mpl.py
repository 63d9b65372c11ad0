"""matplotlib backend: draws a scene on an Axes whose data units are sheet millimetres.

matplotlib is imported only when a canvas is used, never when velplan is imported. Line
widths, dashes and text sizes are converted from millimetres to points with the Axes' own
data-to-display scale, so a figure made by :class:`MplCanvas` at the sheet's size prints
at 1:1.

Examples
--------
>>> from velplan.render.scene import Scene, Arrow
>>> ax = render(Scene((Arrow((0, 0), (50, 20), "plan-v-1"),), 420, 297), MplCanvas())
>>> tuple(float(x) for x in ax.get_xlim())
(0.0, 420.0)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from velplan.notation import unicode_text
from velplan.render.canvas import render
from velplan.render.fonts import GENERIC_FAMILIES, candidate_families, register_with_matplotlib
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Text
from velplan.render.shapes import (
    Stroke, arrow_shape, arrow_size, circle_outline, hatch_segments, hatch_stroke,
    stroke_for, text_origin)
from velplan.render.style import SheetStyle

if TYPE_CHECKING:
    from matplotlib.axes import Axes

_MM_PER_INCH = 25.4
_POINTS_PER_INCH = 72.0
__all__ = ["MplCanvas", "render"]


def _installed_families(families: tuple[str, ...]) -> list[str]:
    """The families matplotlib can find, in order, with the bundled Velplan Sans among them
    as in PNG and PDF sheets (:func:`velplan.render.fonts.candidate_families`); skipping the
    rest avoids matplotlib's warnings. matplotlib falls back glyph by glyph along the list."""
    from matplotlib import font_manager

    register_with_matplotlib()
    known = {f.name for f in font_manager.fontManager.ttflist}
    return [f for f in candidate_families(list(families))
            if f in known or f.lower() in GENERIC_FAMILIES]


class MplCanvas:
    """Draws a scene on a matplotlib Axes.

    Parameters
    ----------
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; if omitted, a figure of the sheet's size (1:1) is made.
    style : SheetStyle, optional
        Drafting style; the default ESKD style if omitted.

    Notes
    -----
    Drawing order is kept with increasing ``zorder``. :meth:`finish` returns the Axes.
    """

    def __init__(self, ax: Axes | None = None, style: SheetStyle | None = None) -> None:
        self.ax = ax
        self.style = style if style is not None else SheetStyle()
        self._z = 0
        self._pt_per_mm = 1.0

    def begin(self, width_mm: float, height_mm: float) -> None:
        if self.ax is None:
            from matplotlib.figure import Figure

            figure = Figure(figsize=(width_mm / _MM_PER_INCH, height_mm / _MM_PER_INCH))
            self.ax = figure.add_axes((0.0, 0.0, 1.0, 1.0))
        self.ax.set_xlim(0.0, width_mm)
        self.ax.set_ylim(0.0, height_mm)
        self.ax.set_aspect("equal")
        self.ax.set_axis_off()
        self._pt_per_mm = self._points_per_mm()
        self._z = 0

    def _points_per_mm(self) -> float:
        ax = self.ax
        ax.apply_aspect()
        width_in = ax.get_position().width * ax.figure.get_figwidth()
        return width_in * _POINTS_PER_INCH / abs(ax.get_xlim()[1] - ax.get_xlim()[0])

    def _zorder(self) -> int:
        self._z += 1
        return self._z

    def _line_kwargs(self, stroke: Stroke) -> dict:
        width_pt = stroke.width * self._pt_per_mm
        kwargs = {"color": stroke.colour, "linewidth": width_pt,
                  "solid_capstyle": "round", "solid_joinstyle": "round"}
        if stroke.dash:
            # matplotlib scales dash lengths by the line width; undo that to keep mm.
            dash_pt = [d * self._pt_per_mm / width_pt for d in stroke.dash]
            kwargs.update(linestyle=(0, dash_pt), dash_capstyle="butt")
        return kwargs

    def _stroke_path(self, xy, stroke: Stroke) -> None:
        xs, ys = zip(*xy)
        self.ax.plot(xs, ys, zorder=self._zorder(), **self._line_kwargs(stroke))

    def _outline(self, xy, fill: str | None, stroke: Stroke, layer: str) -> None:
        from matplotlib.patches import Polygon as MplPolygon

        if fill == "hatch":
            for segment in hatch_segments(xy, self.style.hatch_spacing_mm,
                                          self.style.hatch_angle_deg):
                self._stroke_path(segment, hatch_stroke(layer, self.style))
        face = {"solid": stroke.colour, "white": "white"}.get(fill, "none")
        kwargs = self._line_kwargs(stroke)
        patch = MplPolygon(xy, closed=True, facecolor=face, edgecolor=kwargs["color"],
                           linewidth=kwargs["linewidth"],
                           linestyle=kwargs.get("linestyle", "solid"),
                           joinstyle="round", zorder=self._zorder())
        self.ax.add_patch(patch)

    def draw_polyline(self, item: Polyline) -> None:
        self._stroke_path(item.points, stroke_for(item.line, item.layer, self.style))

    def draw_polygon(self, item: Polygon) -> None:
        self._outline(item.points, item.fill, stroke_for(item.line, item.layer, self.style),
                      item.layer)

    def draw_circle(self, item: Circle) -> None:
        self._outline(circle_outline(item.centre, item.radius), item.fill,
                      stroke_for(item.line, item.layer, self.style), item.layer)

    def draw_arrow(self, item: Arrow) -> None:
        from matplotlib.patches import Polygon as MplPolygon

        stroke = stroke_for(item.line, item.layer, self.style)
        length, width = arrow_size(item.head_length, item.head_width, self.style,
                                   stroke.width)
        shape = arrow_shape(item.start, item.end, length, width)
        if shape.shaft is not None:
            self._stroke_path(shape.shaft, stroke)
        if shape.head is not None:
            self.ax.add_patch(MplPolygon(shape.head, closed=True, facecolor=stroke.colour,
                                         edgecolor="none", zorder=self._zorder()))

    def draw_text(self, item: Text) -> None:
        x, y = text_origin(item)
        if item.width_factor != 1.0:
            self._narrow_text(item, x, y)
            return
        size_pt = self.style.font_size_em(item.size_mm) * self._pt_per_mm
        self.ax.text(x, y, unicode_text(item.text), fontsize=size_pt,
                     family=_installed_families(self.style.font_families),
                     style="italic" if self.style.italic else "normal",
                     color=self.style.stroke_colour(item.layer),
                     ha={"start": "left", "middle": "center", "end": "right"}[item.anchor],
                     va="baseline", rotation=item.rotation_deg, rotation_mode="anchor",
                     zorder=self._zorder())

    def _narrow_text(self, item: Text, x: float, y: float) -> None:
        """Narrowed letters as the text's outline (matplotlib text has no width scale): the
        glyphs at the em size in mm, scaled along the baseline about the anchor."""
        from matplotlib.font_manager import FontProperties
        from matplotlib.patches import PathPatch
        from matplotlib.textpath import TextPath
        from matplotlib.transforms import Affine2D

        prop = FontProperties(family=_installed_families(self.style.font_families),
                              style="italic" if self.style.italic else "normal")
        path = TextPath((0.0, 0.0), unicode_text(item.text),
                        size=self.style.font_size_em(item.size_mm), prop=prop)
        width = path.get_extents().x1 if len(path.vertices) else 0.0
        shift = {"start": 0.0, "middle": 0.5, "end": 1.0}[item.anchor] * width
        place = (Affine2D().translate(-shift, 0.0).scale(item.width_factor, 1.0)
                 .rotate_deg(item.rotation_deg).translate(x, y))
        colour = self.style.stroke_colour(item.layer)
        self.ax.add_patch(PathPatch(path, transform=place + self.ax.transData, facecolor=colour,
                                    edgecolor="none", zorder=self._zorder()))

    def finish(self) -> Axes:
        """Return the Axes drawn on."""
        return self.ax
