"""The canvas protocol, a recording canvas for tests, and :func:`render`.

A canvas receives the primitives of a scene one by one, in drawing order, between
``begin`` and ``finish``; what ``finish`` returns depends on the canvas (an SVG string, a
matplotlib Axes, the recorded primitives).

Examples
--------
>>> from velplan.render.scene import Scene, Arrow
>>> scene = Scene((Arrow((0, 0), (10, 0), "plan-v-1"),), 420, 297)
>>> canvas = RecordingCanvas()
>>> render(scene, canvas) == scene.primitives
True
>>> canvas.arrows(layer="plan-v-1")[0].end
(10.0, 0.0)
"""

from __future__ import annotations

from typing import Protocol, TypeVar

from velplan.errors import VelplanError
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Primitive, Scene, Text

Result = TypeVar("Result", covariant=True)


class Canvas(Protocol[Result]):
    """What a rendering backend implements; all coordinates are sheet mm, y up."""

    def begin(self, width_mm: float, height_mm: float) -> None:
        """Start a sheet of the given size, mm."""

    def draw_polyline(self, item: Polyline) -> None:
        """Stroke an open chain of segments."""

    def draw_polygon(self, item: Polygon) -> None:
        """Fill (if asked) and stroke a closed outline."""

    def draw_circle(self, item: Circle) -> None:
        """Fill (if asked) and stroke a circle."""

    def draw_arrow(self, item: Arrow) -> None:
        """Stroke a shaft and fill its arrowhead."""

    def draw_text(self, item: Text) -> None:
        """Write one line of text."""

    def finish(self) -> Result:
        """End the sheet and return the backend's result."""


_DRAW = {Polyline: "draw_polyline", Polygon: "draw_polygon", Circle: "draw_circle",
         Arrow: "draw_arrow", Text: "draw_text"}


def render(scene: Scene, canvas: Canvas[Result]) -> Result:
    """Draw every primitive of `scene` on `canvas`, in order, and return its result.

    Parameters
    ----------
    scene : Scene
        What to draw.
    canvas : Canvas
        Where to draw it; used once.

    Returns
    -------
    object
        Whatever ``canvas.finish()`` returns.
    """
    canvas.begin(scene.width_mm, scene.height_mm)
    for item in scene.primitives:
        method = _DRAW.get(type(item))
        if method is None:
            raise VelplanError(f"no canvas method draws a {type(item).__name__}")
        getattr(canvas, method)(item)
    return canvas.finish()


class RecordingCanvas:
    """A canvas that keeps what it is given, for tests and inspection.

    Attributes
    ----------
    size_mm : tuple of float or None
        Sheet size given to :meth:`begin`, mm.
    """

    def __init__(self) -> None:
        self._items: list[Primitive] = []
        self.size_mm: tuple[float, float] | None = None
        self.finished = False

    def begin(self, width_mm: float, height_mm: float) -> None:
        self._items.clear()
        self.size_mm = (width_mm, height_mm)
        self.finished = False

    def draw_polyline(self, item: Polyline) -> None:
        self._items.append(item)

    def draw_polygon(self, item: Polygon) -> None:
        self._items.append(item)

    def draw_circle(self, item: Circle) -> None:
        self._items.append(item)

    def draw_arrow(self, item: Arrow) -> None:
        self._items.append(item)

    def draw_text(self, item: Text) -> None:
        self._items.append(item)

    def finish(self) -> tuple[Primitive, ...]:
        self.finished = True
        return self.primitives

    @property
    def primitives(self) -> tuple[Primitive, ...]:
        """Everything drawn so far, in order."""
        return tuple(self._items)

    def _select(self, kind: type, layer: str | None) -> tuple:
        return tuple(p for p in self._items
                     if isinstance(p, kind) and (layer is None or p.layer == layer))

    def polylines(self, layer: str | None = None) -> tuple[Polyline, ...]:
        """Recorded polylines, optionally only those on `layer`."""
        return self._select(Polyline, layer)

    def polygons(self, layer: str | None = None) -> tuple[Polygon, ...]:
        """Recorded polygons, optionally only those on `layer`."""
        return self._select(Polygon, layer)

    def circles(self, layer: str | None = None) -> tuple[Circle, ...]:
        """Recorded circles, optionally only those on `layer`."""
        return self._select(Circle, layer)

    def arrows(self, layer: str | None = None) -> tuple[Arrow, ...]:
        """Recorded arrows, optionally only those on `layer`."""
        return self._select(Arrow, layer)

    def texts(self, layer: str | None = None) -> tuple[Text, ...]:
        """Recorded texts, optionally only those on `layer`."""
        return self._select(Text, layer)
