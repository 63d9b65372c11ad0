"""`free_spot` against its definition, point by point: every corner of the 5 mm grid whose box
keeps `gap` from every taken box is free; of those, the one whose upper left corner is nearest."""

import math

from hypothesis import given, settings, strategies as st

from velplan.sheets.layout import free_spot


def reference(w, h, taken, region, gap, near):
    x0, y0, x1, y1 = region
    if w > x1 - x0 or h > y1 - y0:
        return None
    best = None
    ny, nx = int((y1 - h - y0 + 1e-9) // 5.0) + 1, int((x1 - w - x0 + 1e-9) // 5.0) + 1
    for j in range(ny):
        for i in range(nx):
            x, y = x0 + 5.0 * i, y0 + 5.0 * j
            if all(math.hypot(max(bx0 - (x + w), x - bx1, 0.0), max(by0 - (y + h), y - by1, 0.0)) > gap
                   for bx0, by0, bx1, by1 in taken):
                d = math.hypot(x - near[0], y + h - near[1])
                if best is None or d < best[0]:
                    best = (d, (x, y))
    return None if best is None else best[1]


box = st.tuples(st.floats(-20, 200), st.floats(-20, 150), st.floats(1, 120), st.floats(1, 90)).map(
    lambda b: (b[0], b[1], b[0] + b[2], b[1] + b[3]))


@settings(max_examples=150, deadline=None)
@given(st.lists(box, max_size=5), st.integers(1, 30), st.integers(1, 20), st.sampled_from([0.0, 5.0, 10.0]),
       st.tuples(st.floats(0, 200), st.floats(0, 150)), st.booleans())
def test_free_spot_is_the_nearest_free_grid_corner(taken, wi, hi, gap, near, snapped):
    region = (3.0, 2.0, 203.0, 152.0)
    w, h = (5.0 * wi, 5.0 * hi) if snapped else (4.3 * wi, 3.7 * hi)
    got, want = free_spot(w, h, taken, region, gap, near), reference(w, h, taken, region, gap, near)
    assert (got is None) == (want is None)
    if got is not None:  # a free corner, the same or one exactly as near (a tie broken either way)
        x, y = got
        assert all(math.hypot(max(bx0 - (x + w), x - bx1, 0.0), max(by0 - (y + h), y - by1, 0.0)) > gap
                   for bx0, by0, bx1, by1 in taken)
        assert math.hypot(got[0] - near[0], got[1] + h - near[1]) == math.hypot(want[0] - near[0], want[1] + h - near[1])


def test_a_box_of_no_known_place_leaves_no_spot():
    # its distance is NaN at every corner, so no corner is farther than the gap from it
    assert free_spot(50.0, 40.0, [(float("nan"), 10.0, 100.0, 100.0)], (0.0, 0.0, 400.0, 300.0), 5.0, (0.0, 300.0)) is None
    assert free_spot(50.0, 40.0, [(-math.inf, 10.0, 100.0, math.inf)], (0.0, 0.0, 400.0, 300.0), 5.0,
                     (0.0, 300.0)) == (110.0, 260.0)
