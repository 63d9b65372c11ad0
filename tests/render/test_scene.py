import pytest

from velplan.errors import VelplanError
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text


def test_points_are_stored_as_float_tuples():
    line = Polyline([[0, 0], [10, 5]], "mechanism", "thick")
    assert line.points == ((0.0, 0.0), (10.0, 5.0))
    assert line == Polyline(((0.0, 0.0), (10.0, 5.0)), "mechanism", "thick")


@pytest.mark.parametrize("make, message", [
    (lambda: Polyline([(0, 0)], "mechanism"), "at least 2 points"),
    (lambda: Polygon([(0, 0), (1, 1)], "mechanism"), "at least 3 points"),
    (lambda: Polyline([(0, 0), (1, float("nan"))], "mechanism"), "finite"),
    (lambda: Polyline([(0, 0), (1, 1)], "Bad Layer"), "not a valid layer name"),
    (lambda: Polyline([(0, 0), (1, 1)], "mechanism", "bold"), "known line types: thick"),
    (lambda: Polygon([(0, 0), (1, 0), (1, 1)], "mechanism", fill="red"), "fill 'red'"),
    (lambda: Circle((0, 0), -1, "mechanism"), "radius must be a positive length"),
    (lambda: Arrow((0, 0), (1, 1), "plan-v-1", head_length=0), "head_length"),
    (lambda: Text((0, 0), "a\nb", "labels"), "one-line"),
    (lambda: Text((0, 0), "a", "labels", anchor="left"), "allowed: 'start'"),
])
def test_invalid_primitives_raise(make, message):
    with pytest.raises(VelplanError, match=message):
        make()


def test_extend_returns_new_scene_and_keeps_order():
    empty = Scene(width_mm=420, height_mm=297)
    a = Polyline([(0, 0), (1, 0)], "mechanism")
    b = Circle((5, 5), 2, "mechanism", fill="white")
    c = Text((1, 1), "A", "labels")
    full = empty.extend(a, [b, c])
    assert len(empty) == 0
    assert full.primitives == (a, b, c)
    assert (full.width_mm, full.height_mm) == (420, 297)
    assert full.layers == ("mechanism", "labels")


def test_filter_by_layer_and_kind():
    a = Polyline([(0, 0), (1, 0)], "mechanism")
    b = Arrow((0, 0), (3, 4), "plan-v-1")
    c = Arrow((0, 0), (1, 1), "plan-v-2")
    scene = Scene((a, b, c))
    assert scene.on_layer("plan-v-1", "plan-v-2").primitives == (b, c)
    assert scene.of_kind(Arrow) == (b, c)
    assert b.length == pytest.approx(5.0)


def test_bounds_of_layer():
    scene = Scene((Polyline([(10, 20), (30, 5)], "mechanism"),
                   Circle((100, 100), 4, "positions"),
                   Circle((0, 50), 1, "mechanism")))
    assert scene.bounds_of("mechanism") == (-1.0, 5.0, 30.0, 51.0)
    assert scene.bounds_of("positions") == (96.0, 96.0, 104.0, 104.0)
    assert scene.bounds() == (-1.0, 5.0, 104.0, 104.0)


def test_bounds_of_missing_layer_lists_present_layers():
    scene = Scene((Circle((0, 0), 1, "mechanism"),))
    with pytest.raises(VelplanError, match="no primitives on layer.*diagram.*mechanism"):
        scene.bounds_of("diagram")


def test_text_bounds_follow_anchor():
    # "abc" at 5 mm: the fonts' advances (0.563 + 0.589 + 0.55 em, DejaVu Sans Condensed and
    # Velplan Sans at their widest), the em 5/0.72 mm: 11.74 mm wide.
    width = (0.563 + 0.618 + 0.51) * 5.0 / 0.72
    start = Text((100, 50), "abc", "labels", 5.0, "start")
    end = Text((100, 50), "abc", "labels", 5.0, "end")
    assert start.bounds[0] == pytest.approx(100.0) and start.bounds[2] == pytest.approx(100 + width, abs=0.01)
    assert end.bounds[0] == pytest.approx(100 - width, abs=0.01) and end.bounds[2] == pytest.approx(100.0)
    assert start.bounds[3] == pytest.approx(55.0)


def test_scene_rejects_non_primitives():
    with pytest.raises(VelplanError, match="only drawing primitives"):
        Scene(("not a primitive",))
