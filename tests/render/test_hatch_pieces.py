"""`shapes.hatch_segments` against the hatch clipped line by line: each hatch line through a
random polygon (concave ones, which cut a line into several pieces, included) is clipped on its
own with shapely, and the ends of every straight piece left, in order, are the segments."""

import math

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.render.shapes import hatch_segments


def _clipped_one_by_one(outline, spacing, angle_deg):
    area = shapely.Polygon(outline)
    a = math.radians(angle_deg)
    along, normal = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
    corners = np.asarray(area.exterior.coords)
    reach = float(np.max(np.abs(corners @ along))) + 1.0
    offsets = corners @ normal
    out = []
    for k in range(math.ceil(offsets.min() / spacing), math.floor(offsets.max() / spacing) + 1):
        c = normal * k * spacing
        piece = area.intersection(shapely.LineString([c - along * reach, c + along * reach]))
        for p in getattr(piece, "geoms", [piece]):
            if p.geom_type == "LineString" and not p.is_empty and p.length > 1e-9:
                out.append([p.coords[0], p.coords[-1]])
    return np.array(out, float).reshape(-1, 2, 2)


@settings(max_examples=60, deadline=None)
@given(st.integers(3, 9), st.integers(0, 10_000), st.floats(0.5, 4.0), st.floats(-180.0, 180.0))
def test_the_hatch_is_each_line_clipped_on_its_own(n, seed, spacing, angle):
    rng = np.random.default_rng(seed)
    turn = np.sort(rng.uniform(0.0, 2 * np.pi, n))
    radius = rng.uniform(2.0, 30.0, n)  # a star-shaped polygon: concave where the radii differ
    outline = np.column_stack([radius * np.cos(turn), radius * np.sin(turn)]) + rng.uniform(-50, 50, 2)
    if not shapely.Polygon(outline).is_valid:
        return
    got = hatch_segments(outline, spacing, angle)
    want = _clipped_one_by_one(outline, spacing, angle)
    assert got.shape == want.shape
    assert np.array_equal(got, want)


def test_a_band_thinner_than_the_spacing_may_have_no_line_and_a_flat_one_none():
    assert hatch_segments([(0.1, 0.1), (0.2, 0.1), (0.2, 0.2), (0.1, 0.2)], 5.0, 0.0).shape == (0, 2, 2)
    assert hatch_segments([(0, 0), (10, 0), (20, 0)], 1.0).shape == (0, 2, 2)
    band = hatch_segments([(0, 0), (10, 0), (10, 3), (0, 3)], 1.0, 0.0)
    assert band.shape == (4, 2, 2) and np.allclose(band[:, :, 1], [[0, 0], [1, 1], [2, 2], [3, 3]])
