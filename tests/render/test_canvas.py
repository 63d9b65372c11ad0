from velplan.render.canvas import RecordingCanvas, render
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text


def _scene():
    return Scene((
        Polyline([(0, 0), (50, 0)], "mechanism", "thick"),
        Polygon([(0, 0), (10, 0), (10, 5)], "mechanism", "thin", "hatch"),
        Circle((50, 0), 1.5, "mechanism", fill="white"),
        Arrow((100, 100), (140, 130), "plan-v-1", "thick"),
        Arrow((140, 130), (150, 100), "plan-v-1"),
        Text((100, 95), "p", "labels"),
        Arrow((0, 0), (1, 0), "plan-a-1"),
    ), 420, 297)


def test_recording_canvas_gets_exactly_the_scene():
    scene = _scene()
    canvas = RecordingCanvas()
    result = render(scene, canvas)
    assert result == scene.primitives
    assert canvas.primitives == scene.primitives
    assert canvas.size_mm == (420, 297)
    assert canvas.finished


def test_recording_canvas_selectors():
    canvas = RecordingCanvas()
    render(_scene(), canvas)
    plan = canvas.arrows(layer="plan-v-1")
    assert [a.end for a in plan] == [(140.0, 130.0), (150.0, 100.0)]
    assert len(canvas.arrows()) == 3
    assert [t.text for t in canvas.texts()] == ["p"]
    assert canvas.circles()[0].fill == "white"
    assert len(canvas.polylines("mechanism")) == 1
    assert canvas.polygons()[0].fill == "hatch"


def test_render_restarts_a_used_canvas():
    canvas = RecordingCanvas()
    render(_scene(), canvas)
    render(Scene((Text((0, 0), "x", "labels"),)), canvas)
    assert len(canvas.primitives) == 1
