"""Backend-neutral rendering: scenes of primitives in sheet millimetres, drawn on canvases.

The primitives, canvases, styles, symbols and label layout know nothing of mechanisms or
plans: they draw plain geometry. The views (`velplan.views`) sit on top of them and turn
results into shapes; the sheets (`velplan.sheets`) arrange views in a frame. Backends:
:class:`~velplan.render.svg.SvgCanvas` (SVG text), :class:`~velplan.render.mpl.MplCanvas`
(matplotlib, imported lazily) and :class:`~velplan.render.canvas.RecordingCanvas` (tests).
"""

from velplan.render.canvas import Canvas, RecordingCanvas, render
from velplan.render.i18n import LANGUAGES, label
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.style import SheetStyle
from velplan.render.svg import SvgCanvas, to_svg

__all__ = [
    "Arrow", "Canvas", "Circle", "LANGUAGES", "Polygon", "Polyline", "RecordingCanvas",
    "Scene", "SheetStyle", "SvgCanvas", "Text", "label", "render", "to_svg",
]
