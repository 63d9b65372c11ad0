"""`views.letters._blocked` answers as the STRtree's "intersects" query it replaces: for random
obstacles (thick segments with round caps, polylines, rings, boxes sharing edges with the
candidates) and random candidate boxes, every box is blocked exactly where the tree's query
names it."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings, strategies as st

from velplan.views.letters import _blocked

coord = st.floats(-30.0, 30.0, allow_nan=False, allow_infinity=False)


def _reference(tree, boxes) -> np.ndarray:
    out = np.zeros(len(boxes), dtype=bool)
    out[tree.query(boxes, predicate="intersects")[0]] = True
    return out


@st.composite
def obstacle(draw):
    kind = draw(st.sampled_from(("capsule", "line", "ring", "box")))
    a, b = (draw(coord), draw(coord)), (draw(coord), draw(coord))
    if kind == "capsule":
        return shapely.LineString([a, b]).buffer(draw(st.floats(0.1, 3.0)))
    if kind == "line":
        return shapely.LineString([a, b, (draw(coord), draw(coord))])
    if kind == "ring":
        return shapely.Point(a).buffer(draw(st.floats(0.5, 8.0))).exterior
    x0, y0 = min(a[0], b[0]), min(a[1], b[1])
    return shapely.box(x0, y0, x0 + abs(a[0] - b[0]) + 0.5, y0 + abs(a[1] - b[1]) + 0.5)


@settings(max_examples=60, deadline=None)
@given(st.lists(obstacle(), min_size=1, max_size=25),
       st.lists(st.tuples(coord, coord, st.floats(0.5, 6.0), st.floats(0.5, 4.0)), min_size=1, max_size=40))
def test_blocked_matches_the_tree_query(obstacles, boxes):
    tree = shapely.STRtree(obstacles)
    cand = np.array([shapely.box(x, y, x + w, y + h) for x, y, w, h in boxes])
    assert np.array_equal(_blocked(tree, cand), _reference(tree, cand))


def test_touching_and_crowded_boxes():
    """Boxes touching an obstacle's edge or corner count as meeting it (as the tree's query
    says); a box among many envelopes but clear of every shape is free."""
    obstacles = [shapely.box(0, 0, 2, 2), shapely.LineString([(0, 10), (10, 0)]).buffer(0.5),
                 shapely.LineString([(-5, -5), (-5, 5)])]
    cand = np.array([shapely.box(2, 0, 3, 1), shapely.box(2, 2, 3, 3), shapely.box(2.01, 0, 3, 1),
                     shapely.box(1.0, 1.0, 1.5, 1.5), shapely.box(-5, 0, -4, 1), shapely.box(8.0, 8.0, 9.0, 9.0),
                     shapely.box(4.0, 4.0, 4.5, 4.5)])
    tree = shapely.STRtree(obstacles)
    got = _blocked(tree, cand)
    assert got.tolist() == [True, True, False, True, True, False, False]
    assert np.array_equal(got, _reference(tree, cand))


def test_no_candidates():
    tree = shapely.STRtree([shapely.box(0, 0, 1, 1)])
    assert _blocked(tree, np.array([shapely.box(5, 5, 6, 6)])).tolist() == [False]
