"""Backend-neutral rendering: scenes of primitives in sheet millimetres, drawn on canvases.

The primitives, canvases, styles, symbols and label layout know nothing of mechanisms or
plans: they draw plain geometry. The views (`velplan.views`) sit on top of them and turn
results into shapes; the sheets (`velplan.sheets`) arrange views in a frame. Backends:
:class:`~velplan.render.svg.SvgCanvas` (SVG text), :class:`~velplan.render.mpl.MplCanvas`
(matplotlib, imported lazily) and :class:`~velplan.render.canvas.RecordingCanvas` (tests).

A scene of every primitive, drawn on two canvases (any object with the `Canvas` methods):

>>> from velplan.render import Arrow, Canvas, Circle, Polygon, Polyline, RecordingCanvas, Scene, Text
>>> scene = Scene((Polyline(((0, 0), (40, 0)), "links", "thick"), Circle((0, 0), 2.0, "pairs"),
...                Arrow((0, 0), (0, 20), "forces"), Polygon(((10, 10), (20, 10), (15, 18)), "links"),
...                Text((5, 5), "A", "labels")), width_mm=50.0, height_mm=30.0)
>>> [type(p).__name__ for p in render(scene, RecordingCanvas())]
['Polyline', 'Circle', 'Arrow', 'Polygon', 'Text']
>>> svg = to_svg(scene, SheetStyle(language="en"))
>>> svg.startswith("<?xml"), 'width="50mm"' in svg
(True, True)
>>> render(scene, SvgCanvas(SheetStyle(language="en"))) == svg
True
>>> sorted(m for m in dir(Canvas) if m.startswith("draw_"))
['draw_arrow', 'draw_circle', 'draw_polygon', 'draw_polyline', 'draw_text']
>>> LANGUAGES, label("position", "ru")
(('en', 'ru', 'uk', 'zh'), 'Положение')
>>> label("position", "fr")
Traceback (most recent call last):
...
velplan.errors.VelplanError: unknown language 'fr'; known languages: en, ru, uk, zh
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
