"""The circle diagram's numbers (the order the centres were found in, one on each chord found by
Kennedy lines): on the centres figure of every bundled and catalogue mechanism at a few
positions, no other chord crosses a number's box, and the chord nearest each number is its own
(issue 32, item 10)."""

import numpy as np
import pytest
import shapely

import velplan
from tests.sheet import gallery_marks as gm
from velplan.plans.centres import construct_centres
from velplan.render.layout import label_box
from velplan.render.scene import Circle, Polyline, Text
from velplan.views.centres import CIRCLE_MM, centres_view

POSITIONS = (1, 4, 9)


def _diagram(view, con):
    """The circle diagram's ring, its chords in step order and its numbers, from the figure (a
    chord broken where its number stands on it is drawn again whole from its pieces: each
    piece runs from a vertex on the ring along the chord)."""
    ring = max((p for p in view.primitives if isinstance(p, Circle) and p.layer == "centres"), key=lambda c: c.radius)
    centre = np.asarray(ring.centre)
    on_ring = lambda q: abs(np.hypot(*(np.asarray(q) - centre)) - ring.radius) < 1e-6  # noqa: E731
    chords, seen = [], set()
    for p in view.primitives:
        if not (isinstance(p, Polyline) and p.layer == "centres" and len(p.points) == 2 and any(map(on_ring, p.points))):
            continue
        a, b = (np.asarray(q, float) for q in (p.points if on_ring(p.points[0]) else p.points[::-1]))
        u = (b - a) / np.hypot(*(b - a))
        end = a - 2.0 * np.dot(a - centre, u) * u  # the chord's other end on the ring
        key = frozenset((tuple(np.round(a, 6)), tuple(np.round(end, 6))))
        if key not in seen:
            seen.add(key)
            chords.append(Polyline((tuple(a), tuple(end)), p.layer, p.line))
    assert len(chords) == len(con.steps)
    numbers = {t.text: t for t in view.primitives if isinstance(t, Text) and t.size_mm == 2.5 and t.text.isdigit()
               and np.hypot(*(np.asarray(t.position) - centre)) < ring.radius}
    return ring, chords, numbers


@pytest.mark.parametrize("name", gm.NAMES)
def test_each_number_is_clear_and_nearest_its_own_chord(name):
    study = velplan.Study(name)
    for position in POSITIONS:
        con = construct_centres(study.kinematics, position)
        view = centres_view(con, fine=study.turn, number=position, lang=gm.lang_of(name))
        ring, chords, numbers = _diagram(view, con)
        assert ring.radius >= CIRCLE_MM - 1e-9
        lines = [shapely.LineString(c.points) for c in chords]
        found = [j for j, s in enumerate(con.steps) if s.how == "kennedy"]
        assert sorted(numbers, key=int) == [str(k + 1) for k in range(len(found))]
        for k, j in enumerate(found):
            box = label_box(numbers[str(k + 1)])
            others = lines[:j] + lines[j + 1:]
            crossing = [i for i, line in enumerate(others) if line.intersects(box)]
            assert not crossing, (name, position, k + 1, crossing)
            mid = box.centroid
            assert lines[j].distance(mid) < min(line.distance(mid) for line in others), (name, position, k + 1)


def test_a_dense_diagram_grows_only_as_far_as_it_must():
    """triad-eight-link (8 links, 28 chords) gets a larger circle (at least 8/6 of the standard one); a four-bar's
    two numbers always fit the standard one."""
    study = velplan.Study("four-bar")
    for position in POSITIONS:
        view = centres_view(construct_centres(study.kinematics, position), fine=study.turn, number=position)
        assert view.meta["circle_mm"] == pytest.approx(CIRCLE_MM)
    study = velplan.Study("triad-eight-link")
    radii = [centres_view(construct_centres(study.kinematics, p), fine=study.turn, number=p).meta["circle_mm"]
             for p in POSITIONS]
    assert min(radii) >= 8 / 6 * CIRCLE_MM - 1e-9 and max(radii) <= 2.5 * CIRCLE_MM + 1e-9
