"""Backend-neutral rendering: scenes of primitives in sheet millimetres, drawn on canvases.

The primitives, canvases, styles, symbols and the sheet frame know nothing of mechanisms or
plans: they draw plain geometry. The view builders (`mechanism_view`, `plan_view`,
`steps_view`, `table_view`, `diagram_view`) sit on top of them and turn a solved mechanism
and its plans into scenes; nothing below this package imports it. Backends:
:class:`~velplan.render.svg.SvgCanvas` (svgwrite), :class:`~velplan.render.mpl.MplCanvas`
(matplotlib, imported lazily) and :class:`~velplan.render.canvas.RecordingCanvas` (tests).
"""

from velplan.render.canvas import Canvas, RecordingCanvas, render
from velplan.render.i18n import LANGUAGES, label
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.sheet import TitleInfo, free_area, sheet_scene, title_block
from velplan.render.style import SheetStyle
from velplan.render.svg import SvgCanvas, to_svg

__all__ = [
    "Arrow", "Canvas", "Circle", "LANGUAGES", "Polygon", "Polyline", "RecordingCanvas",
    "Scene", "SheetStyle", "SvgCanvas", "Text", "TitleInfo", "free_area", "label", "render",
    "sheet_scene", "title_block", "to_svg",
]
