import math

import numpy as np
import pytest
import shapely

from velplan.render.scene import Arrow, Circle, Polygon, Text
from velplan.render.symbols import (
    dimension_line, fixed_pivot, ground_hatch, link, point_label, pole_marker,
    revolute_joint, rotation_arrow, slider_block, straight_guide)


def _band(start, end, normal, depth):
    start, end, normal = map(np.asarray, (start, end, normal))
    return shapely.Polygon([start, end, end + depth * normal, start + depth * normal])


@pytest.mark.parametrize("side, normal", [("right", (0.0, -1.0)), ("left", (0.0, 1.0))])
def test_guide_hatch_stays_in_band_on_its_side(side, normal):
    guide = straight_guide((100, 50), (160, 50), side=side, depth_mm=3.0)
    line, *strokes = guide
    assert line.line == "thick" and line.points == ((100.0, 50.0), (160.0, 50.0))
    # 2 mm apart across the strokes is 2·√2 mm along the guide: 60 / 2.83 ≈ 21
    assert 20 <= len(strokes) <= 22
    band = _band((100, 50), (160, 50), normal, 3.0).buffer(1e-9)
    for stroke in strokes:
        assert stroke.line == "thin"
        assert band.contains(shapely.LineString(stroke.points))
        (x0, y0), (x1, y1) = stroke.points
        assert abs((y1 - y0) / (x1 - x0)) == pytest.approx(1.0)  # 45° to the guide


def test_inclined_guide_hatch_stays_in_band():
    start, end = (0.0, 0.0), (30.0, 40.0)
    _, *strokes = ground_hatch(start, end, side="right", depth_mm=4.0)
    band = _band(start, end, (0.8, -0.6), 4.0).buffer(1e-9)
    assert strokes and all(band.contains(shapely.LineString(s.points)) for s in strokes)


def test_revolute_joint_is_white_circle():
    joint, = revolute_joint((10, 20))
    assert joint == Circle((10, 20), 1.5, "mechanism", "thin", "white")


def test_fixed_pivot_support_ground_and_joint_on_top():
    items = fixed_pivot((50, 50), height_mm=7.0, width_mm=8.0)
    legs = items[0]
    assert legs.points == ((54.0, 43.0), (50.0, 50.0), (46.0, 43.0))
    assert isinstance(items[-1], Circle) and items[-1].fill == "white"
    ground = items[1]
    assert ground.points[0][1] == pytest.approx(43.0) and ground.points[1][1] == pytest.approx(43.0)
    for stroke in items[2:-1]:
        assert all(y <= 43.0 + 1e-9 for _, y in stroke.points)  # hatching below the ground


def test_slider_block_rotated_about_its_centre():
    block, = slider_block((100, 100), 90.0, length_mm=10.0, width_mm=6.0)
    assert isinstance(block, Polygon) and block.fill == "white" and block.line == "thick"
    x0, y0, x1, y1 = block.bounds
    assert (x0, y0, x1, y1) == pytest.approx((97.0, 95.0, 103.0, 105.0))


def test_link_is_trimmed_at_joint_circles():
    bar, = link((0, 0), (30, 40))
    assert bar.line == "thick"
    assert bar.points[0] == pytest.approx((0.9, 1.2))
    assert bar.points[1] == pytest.approx((29.1, 38.8))
    assert link((0, 0), (2, 0)) == ()


def test_dimension_line_arrows_reach_the_extension_lines():
    items = dimension_line((0, 0), (100, 0), "100", offset_mm=-10.0)
    ext_a, ext_b, arrow_a, arrow_b, text = items
    assert isinstance(arrow_a, Arrow) and arrow_a.end == (0.0, -10.0)
    assert arrow_b.end == (100.0, -10.0) and arrow_a.start == (50.0, -10.0)
    assert ext_a.points == ((0.0, -1.0), (0.0, -12.0))
    assert isinstance(text, Text) and text.text == "100" and text.rotation_deg == 0.0
    assert text.position == (50.0, -9.0)


def test_dimension_text_stays_upright_on_leftward_line():
    *_, text = dimension_line((100, 0), (0, 0), "100")
    assert text.rotation_deg == pytest.approx(0.0)


def test_pole_marker_and_label():
    dot, name = pole_marker((10, 10), "p")
    assert dot.fill == "solid" and dot.centre == (10.0, 10.0)
    assert name.text == "p" and name.anchor == "end"
    label, = point_label((5, 5), "a")
    assert label.position == (6.2, 6.2)


def test_rotation_arrow_head_at_end_of_arc():
    arc, head = rotation_arrow((0, 0), 10.0, 0.0, 90.0)
    assert head.end == pytest.approx((0.0, 10.0), abs=1e-12)
    assert math.dist(head.start, head.end) == pytest.approx(2 * 10 * math.sin(0.15), rel=1e-9)
    assert arc.points[-1] == pytest.approx(head.start)
    assert arc.points[0] == pytest.approx((10.0, 0.0))
