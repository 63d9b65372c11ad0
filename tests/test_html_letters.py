"""The page's plan letters placed for all positions at once: the same spots as one position at a
time (`velplan.html.letters.place_letters` against `image_letters`), and its capsule test against
shapely's distance from a segment to a box."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.html.letters import RINGS, _all_spots, capsules, meets, offsets_of, place_letters
from velplan.render.scene import Circle, Text
from velplan.study import Study
from velplan.views.base import _spot_boxes, _spots, place_labels
from velplan.views.plan import image_letters, letters_to_place, plan_steps


_coord = st.floats(-20, 20, allow_nan=False, allow_infinity=False).map(lambda v: round(v, 6))  # mm, to 1 nm


@settings(max_examples=300, deadline=None)
@given(st.tuples(_coord, _coord, st.floats(0.01, 8), st.floats(0.01, 8)),
       st.tuples(_coord, _coord, _coord, _coord, st.floats(0.05, 3)), st.booleans())
def test_a_box_meets_a_capsule_where_the_segment_comes_within_its_radius(box, capsule, dot):
    x0, y0, w, h = box
    ax, ay, bx, by, r = capsule
    if dot or (ax, ay) == (bx, by):
        bx, by, dot = ax, ay, True
    bounds = np.array([[x0, y0, x0 + w, y0 + h]])
    core = shapely.Point(ax, ay) if dot else shapely.LineString([(ax, ay), (bx, by)])
    gap = shapely.distance(shapely.box(*bounds[0]), core)
    if abs(gap - r) < 1e-9:
        return  # on the rim: either answer is a round-off
    assert bool(meets(bounds, np.array([[ax, ay, bx, by, r]]))[0]) == (gap <= r)


def test_capsules_are_the_lines_and_the_dots_with_their_clearances():
    caps = capsules(np.array([[[0.0, 0.0], [3.0, 4.0]]]), [Circle((1.0, 2.0), 0.45, "plan", "thin", "solid")])
    assert caps.tolist() == [[0.0, 0.0, 3.0, 4.0, 0.5], [1.0, 2.0, 1.0, 2.0, 0.75]]


@pytest.mark.parametrize("name", ["shaper", "four-bar", "triad-rocker", "press"])
@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_plan_letters_placed_together_are_those_of_image_letters(name, kind):
    study = Study(name, n=12)
    res = study.plan(kind)
    frames, alone = [], []
    for number in range(1, 13):
        if not study.kinematics.valid[number - 1]:
            continue
        drawings = plan_steps(res, number, lang="en")
        texts, anchors, lines, circles = letters_to_place(res, number, drawings)
        assert len(anchors) == len(texts) and lines.shape[1:] == (2, 2)
        frames.append((texts, capsules(lines, circles)))
        alone.append(image_letters(res, number, drawings))
    together = place_letters(frames)
    assert len(together) == len(alone) > 0
    for got, want in zip(together, alone):
        assert [t.text for t in got] == [t.text for t in want]
        for g, w in zip(got, want):
            assert g.position == pytest.approx(w.position, abs=1e-9), g.text


def test_a_crowded_letter_moves_farther_out_as_place_labels_moves_it():
    texts = [Text((1.0, 1.0), "ab", "plan-v-1-labels", 3.5, "middle", "middle") for _ in range(12)]
    big = np.array([[-40.0, 0.0, 40.0, 0.0, 60.0]])  # a capsule over every spot of the rings
    got = place_letters([(texts, big)])[0]
    want = place_labels(texts, [shapely.LineString([(-40, 0), (40, 0)]).buffer(60.0, quad_segs=16)])
    assert np.allclose([t.position for t in got], [t.position for t in want], rtol=0, atol=1e-9)
    assert len({t.position for t in got}) > 1


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(_coord, _coord, st.sampled_from([2.5, 3.5, 5.0]),
                          st.text("abcdπ₁₂₄, ", min_size=1, max_size=6),
                          st.sampled_from(["start", "middle", "end"]), st.sampled_from(["baseline", "middle", "top"])),
                min_size=1, max_size=12))
def test_boxes_and_spots_of_all_letters_are_those_of_each_bit_for_bit(specs):
    texts = [Text((x, y), s, "labels", size, anchor, baseline) for x, y, size, s, anchor, baseline in specs]
    want = np.array([_spot_boxes(t, np.array([t.position]))[2] for t in texts])
    assert offsets_of(texts).view(np.int64).tolist() == want.view(np.int64).tolist()
    spots = np.stack([_spots(t.position, 0.5 * t.size_mm, RINGS) for t in texts])
    assert _all_spots(texts).view(np.int64).tolist() == spots.view(np.int64).tolist()
