"""What the step and centres figures ask of `velplan.views.letters.place_letters` besides
the sheets: a letter without a leader within `near_mm` of its point (a wide letter on a slant
stands farther off than its gap along the slant), and leaders that keep off the other letters
and pass by the other points."""

import numpy as np
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Text
from velplan.views.letters import LEADER_CLEAR_MM, NEAR_MM, place_letters

WIDE = "a, b₂, s₂, b₄, k₄, s₃"


def _quadrant_walls():
    """Lines out of (0, 0) right, up and left: the letter must go below, on the slant it wants."""
    return [shapely.LineString([(0, 0), (40 * np.cos(a), 40 * np.sin(a))]).buffer(0.5)
            for a in np.radians([0.0, 90.0, 180.0])]


def test_a_wide_letter_stands_within_reach_or_gets_a_leader():
    wanted = Text((6.0, -6.0), WIDE, "t", 3.5)
    free, free_leaders = place_letters([wanted], [(0.0, 0.0)], [(0.0, 0.0)], _quadrant_walls())
    near, near_leaders = place_letters([wanted], [(0.0, 0.0)], [(0.0, 0.0)], _quadrant_walls(), near_mm=NEAR_MM)
    d_free = label_box(free[0]).distance(shapely.Point(0, 0))
    d_near = label_box(near[0]).distance(shapely.Point(0, 0))
    assert not free_leaders and d_free > 6.0  # on the slant: its gap is along it, the box farther off
    assert (d_near <= NEAR_MM + 1e-9 and not near_leaders) or len(near_leaders) == 1
    assert not any(label_box(near[0]).intersects(w) for w in _quadrant_walls())


def test_a_leader_goes_round_a_letter_placed_before():
    # a ring of lines round the point asks for a leader; the letter wants to go right, where a
    # letter stands already across the way out: the leader takes another way, clear of it
    ring = shapely.Point(0, 0).buffer(6.5).difference(shapely.Point(0, 0).buffer(1.6))
    before = shapely.box(2.0, -1.0, 5.0, 1.0)
    placed, leaders = place_letters([Text((8.0, 0.0), "C", "t", 3.5)], [(0.0, 0.0)], [(0.0, 0.0)], [ring],
                                    taken=[before])
    (leader,) = leaders
    assert not shapely.LineString(leader.points).intersects(before)
    assert not label_box(placed[0]).intersects(ring) and not label_box(placed[0]).intersects(before)
    assert label_box(placed[0]).centroid.x > 0  # still on the side it wants


def test_leaders_keep_off_the_other_letters_and_points():
    # six images 2.5 mm from the middle of a star of lines, one between each two, in a ring of
    # lines: every letter stands beyond the ring with a leader, none through another letter or
    # by another image
    points = [(2.5 * np.cos(a), 2.5 * np.sin(a)) for a in np.radians(np.arange(30.0, 360.0, 60.0))]
    lines = [shapely.LineString([(-30 * np.cos(a), -30 * np.sin(a)), (30 * np.cos(a), 30 * np.sin(a))]).buffer(0.5)
             for a in np.radians([0.0, 60.0, 120.0])]
    lines.append(shapely.Point(0, 0).buffer(8.0).difference(shapely.Point(0, 0).buffer(5.0)))
    texts = [Text((x + 2.0, y + 2.0), f"s{k + 1}", "t", 3.5) for k, (x, y) in enumerate(points)]
    placed, leaders = place_letters(texts, points, points, lines, near_mm=NEAR_MM)
    assert len(leaders) == len(points)
    boxes = [label_box(t) for t in placed]
    for leader in leaders:
        seg = shapely.LineString(leader.points)
        own = next(k for k, p in enumerate(points) if np.allclose(leader.points[0], p))
        assert not any(seg.intersects(b) for k, b in enumerate(boxes) if k != own)
        assert all(seg.distance(shapely.Point(p)) > LEADER_CLEAR_MM for k, p in enumerate(points) if k != own)
    assert not any(b.intersects(g) for b in boxes for g in lines)
    assert all(not a.intersects(b) for k, a in enumerate(boxes) for b in boxes[k + 1:])
