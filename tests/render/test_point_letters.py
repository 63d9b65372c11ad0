"""Point letters kept by their points (`velplan.views.letters.place_letters`): each letter by
its own point, nearer it than any other point, within reach; beyond a crowd, with a leader."""

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.render.layout import label_box
from velplan.render.scene import Polyline, Text
from velplan.views.letters import place_letters


def _distances(text, points):
    box = label_box(text)
    return np.array([box.distance(shapely.Point(p)) for p in points])


def test_two_close_points_each_letter_on_its_own_side():
    points = [(0.0, 0.0), (5.0, 0.0)]
    texts = [Text((2.5, 0.0), "A", "t", 3.5), Text((2.5, 0.0), "B", "t", 3.5)]
    placed, leaders = place_letters(texts, points, points)
    assert not leaders
    for k, t in enumerate(placed):
        d = _distances(t, points)
        assert d[k] < d[1 - k] and d[k] <= 6.0
    assert not label_box(placed[0]).intersects(label_box(placed[1]))


def test_a_letter_keeps_off_the_lines_and_takes_the_free_side():
    # lines leave the point right, up and up-right, where the letter is wanted: it goes to a
    # free side, by the point
    lines = [shapely.LineString([(0, 0), (20 * np.cos(a), 20 * np.sin(a))]).buffer(0.6)
             for a in np.radians([0.0, 30.0, 60.0, 90.0])]
    placed, leaders = place_letters([Text((3.0, 3.0), "O₁", "t", 3.5)], [(0.0, 0.0)], [(0.0, 0.0)], lines)
    box = label_box(placed[0])
    assert not leaders
    assert not any(box.intersects(g) for g in lines)
    assert box.distance(shapely.Point(0, 0)) < 3.0
    assert box.centroid.x < 0 or box.centroid.y < 0


def test_a_crowded_point_gets_its_letter_farther_out_with_a_leader():
    # a ring of lines 4 mm round the point leaves no room for a letter within reach
    ring = shapely.Point(0, 0).buffer(6.5).difference(shapely.Point(0, 0).buffer(1.6))
    placed, leaders = place_letters([Text((2.0, 2.0), "C", "t", 3.5)], [(0.0, 0.0)], [(0.0, 0.0)], [ring])
    box = label_box(placed[0])
    assert not box.intersects(ring)
    (leader,) = leaders
    assert isinstance(leader, Polyline) and leader.line == "thin"
    assert np.allclose(leader.points[0], (0.0, 0.0))
    assert box.buffer(0.6).contains(shapely.Point(leader.points[1]))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 40), st.floats(0, 40)), min_size=2, max_size=7))
def test_every_letter_nearest_its_own_point_or_led(raw):
    points = []
    for p in raw:  # points at least 4 mm apart, as a scheme's joints are
        if all(np.hypot(p[0] - q[0], p[1] - q[1]) >= 4.0 for q in points):
            points.append(p)
    texts = [Text((x + 2.0, y + 2.0), chr(ord("A") + k), "t", 3.5) for k, (x, y) in enumerate(points)]
    placed, leaders = place_letters(texts, points, points)
    led = {tuple(np.round(line.points[0], 9)) for line in leaders}
    boxes = [label_box(t) for t in placed]
    for k, t in enumerate(placed):
        if tuple(np.round(points[k], 9)) in led:
            continue
        d = _distances(t, points)
        assert d[k] <= 6.0
        assert all(d[k] < d[j] for j in range(len(points)) if j != k)
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            assert boxes[i].intersection(boxes[j]).area < 1e-9
