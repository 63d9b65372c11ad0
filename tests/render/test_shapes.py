import math

import numpy as np
import pytest
import shapely

from velplan.render.scene import Text
from velplan.render.shapes import (
    arrow_shape, arrow_size, arrowhead, hatch_segments, text_box, text_extent, text_origin,
    upright_angle)
from velplan.render.style import SheetStyle


def test_arrowhead_tip_is_at_end_and_points_along_the_arrow():
    start, end = np.array([10.0, 20.0]), np.array([40.0, 60.0])   # length 50, direction (0.6, 0.8)
    head = arrowhead(start, end, 5.0, 2.0)
    assert head[0] == pytest.approx(end)
    base_mid = (head[1] + head[2]) / 2
    assert base_mid == pytest.approx(end - 5.0 * np.array([0.6, 0.8]))
    assert np.linalg.norm(head[1] - head[2]) == pytest.approx(2.0)
    # the base is perpendicular to the arrow
    assert np.dot(head[1] - head[2], end - start) == pytest.approx(0.0, abs=1e-12)


def test_arrow_shaft_stops_at_head_base():
    shape = arrow_shape((0, 0), (20, 0), 4.0, 1.5)
    assert shape.shaft.tolist() == [[0.0, 0.0], [16.0, 0.0]]
    assert shape.head.tolist() == [[20.0, 0.0], [16.0, 0.75], [16.0, -0.75]]


def test_short_arrow_head_shrinks_and_zero_arrow_has_nothing():
    shape = arrow_shape((0, 0), (2, 0), 4.0, 1.2)
    assert shape.shaft is None
    assert shape.head.tolist() == [[2.0, 0.0], [0.0, 0.3], [0.0, -0.3]]   # halved with the length
    assert arrow_shape((3, 3), (3, 3), 4.0, 1.2) == (None, None)


def test_default_arrow_size_grows_with_thick_lines():
    style = SheetStyle()
    assert arrow_size(None, None, style, 0.35) == (4.5, 1.5)
    length, width = arrow_size(None, None, style, 0.7)
    assert width == pytest.approx(1.75) and length == pytest.approx(5.25)
    assert arrow_size(3.0, 1.0, style, 0.7) == (3.0, 1.0)


def test_hatch_segments_stay_inside_and_are_spaced():
    square = [(0, 0), (10, 0), (10, 10), (0, 10)]
    segments = hatch_segments(square, 2.0, 45.0)
    area = shapely.box(0, 0, 10, 10).buffer(1e-9)
    # offsets k·2 mm across the lines, |k·2| <= 10/√2: k = -3…3
    assert len(segments) == 7
    for a, b in segments:
        assert area.contains(shapely.LineString([a, b]))
        assert (b - a)[1] / (b - a)[0] == pytest.approx(1.0)
    # neighbouring lines are `spacing` apart, measured across them
    normal = np.array([-1.0, 1.0]) / math.sqrt(2)
    offsets = sorted(float(seg[0] @ normal) for seg in segments)
    assert np.diff(offsets) == pytest.approx([2.0] * 6)


def test_text_extent_latin_and_cjk():
    # the fonts' advances in ems (DejaVu Sans Condensed), the em h/0.72
    assert text_extent("ab", 5.0) == pytest.approx(((0.563 + 0.618) * 5.0 / 0.72, 6.25), abs=0.01)
    assert text_extent("速度", 5.0)[0] == pytest.approx(10.0)
    assert text_extent("План", 2.5)[0] == pytest.approx((0.721 + 0.593 + 0.629 + 0.563) * 2.5 / 0.72, abs=0.01)


def test_text_origin_and_box_for_baselines_and_rotation():
    middle = Text((10, 10), "AB", "labels", 4.0, "start", "middle")
    assert text_origin(middle) == pytest.approx([10.0, 8.0])
    turned = Text((10, 10), "AB", "labels", 4.0, "start", "top", 90.0)
    assert text_origin(turned) == pytest.approx([14.0, 10.0])
    box = text_box(Text((0, 0), "AB", "labels", 4.0, "middle"))
    half = (0.615 + 0.657) * 4.0 / 0.72 / 2  # "AB": 0.615 + 0.657 em, the em 4/0.72 mm
    assert box[:, 0].min() == pytest.approx(-half, abs=0.01) and box[:, 0].max() == pytest.approx(half, abs=0.01)
    assert box[:, 1].min() == pytest.approx(-1.0) and box[:, 1].max() == pytest.approx(4.0)


@pytest.mark.parametrize("direction, expected", [
    (0, 0), (45, 45), (90, 90), (135, -45), (180, 0), (-90, 90), (270, 90), (-135, 45)])
def test_upright_angle_reads_left_to_right(direction, expected):
    assert upright_angle(direction) == pytest.approx(expected)
