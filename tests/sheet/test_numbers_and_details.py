"""Issue 32: a position number of a φ axis that the fixed tries leave crossed (a steep curve
through its tick, both above and below the axis) goes round its tick, clear of the curves,
its own tick the nearest; a plan crowded round its pole gets an enlarged detail on A3 even
where the whole crowd is too large for one (the triad press) or the room is only there once
a plan slides in its column (the jaw crusher), every image inside the detail lettered inside
its circle, nearest its own image."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

import velplan
from tests.sheet import gallery_marks as gm
from velplan.plans.text import label_of
from velplan.render.layout import label_box
from velplan.render.scene import Circle, Polyline, Text
from velplan.sheets.kinematic import build_sheet
from velplan.views.base import axis_numbers_clear, subscript
from velplan.views.diagram import phi_axes
from velplan.views.plan_detail import CROWD_MM, crowd_near_pole

LENGTH, N = 60.0, 12  # ticks 5 mm apart, as on an A3 compact block


def axes():
    return phi_axes(LENGTH, 25.0, -25.0, N, "a", layer="diagram", text_layer="diagram-labels",
                    label_mm=3.5, tick_mm=2.5)


def crossing(x: float, slope: float, lean: float) -> list[np.ndarray]:
    """Two steep lines through the tick at x (a chord curve and the analytic one), 25 mm each way."""
    return [np.array([(x - 25.0 / slope, -25.0), (x + 25.0 / slope, 25.0)]),
            np.array([(x - 25.0 / lean, -25.0), (x + 25.0 / lean, 25.0)])]


def check_number_by_its_tick(out, k: int, curves) -> None:
    text = next(t for t in out if isinstance(t, Text) and t.text == str(k + 1))
    box = label_box(text)
    assert not any(box.intersects(shapely.LineString(c)) for c in curves), text
    own = (k * LENGTH / N, 0.0)
    ticks = [(j * LENGTH / N, 0.0) for j in range(N)]
    led = any(isinstance(p, Polyline) and np.allclose(p.points[0], own)
              and box.buffer(0.6).contains(shapely.Point(p.points[1])) for p in out)
    nearest = min(ticks, key=lambda q: box.distance(shapely.Point(q)))
    assert led or nearest == own, (text.position, nearest)


def test_a_number_a_steep_curve_crosses_above_and_below_goes_beside_its_tick():
    """The whitworth's case: chord and analytic curves both through tick 11, steep both ways."""
    curves = crossing(50.0, 6.0, 15.0)
    before = axes()
    out = axis_numbers_clear(before, curves)
    check_number_by_its_tick(out, 10, curves)
    # the numbers no curve crosses stay where they were
    assert [t.position for t in out if isinstance(t, Text) and t.text in ("3", "5", "7")] == [
        t.position for t in before if isinstance(t, Text) and t.text in ("3", "5", "7")]


@settings(max_examples=25, deadline=None)
@given(st.integers(1, N - 1), st.floats(3.0, 40.0), st.floats(3.0, 40.0), st.sampled_from([1.0, -1.0]))
def test_a_crossed_number_ends_clear_and_reads_as_its_ticks(k, slope, lean, sign):
    curves = crossing(k * LENGTH / N, sign * slope, sign * lean)
    check_number_by_its_tick(axis_numbers_clear(axes(), curves), k, curves)


def test_a_tighter_reach_gives_a_smaller_region_round_the_pole():
    images = {"p": 0j, "a": 120 + 0j, "b": 3 + 4j, "c": -5 + 2j, "d": 6 - 3j, "e": 12 + 13j, "f": -20 + 10j}
    whole, tight = crowd_near_pole(images, 200.0), crowd_near_pole(images, 200.0, CROWD_MM)
    assert whole is not None and tight is not None and tight[1] < whole[1]
    # the tight region holds the images within CROWD_MM, 3 mm in from its edge
    inside = [z for z in images.values() if 0.5 < abs(z) <= CROWD_MM]
    assert all(abs(z - tight[0]) <= tight[1] - 3.0 + 1e-9 for z in inside)


@pytest.fixture(scope="module", params=["triad-press", "jaw-crusher"])
def sheet(request):
    return build_sheet(velplan.Study(request.param), fmt="A3", lang=gm.lang_of(request.param))


def test_the_crowded_acceleration_plan_gets_its_detail_and_the_views_stay_apart(sheet):
    detail = sheet.views["detail-a-4"]
    assert detail.view.meta["factor"] >= 2.0
    boxes = [shapely.box(*v.bounds) for v in sheet.views.values()]
    assert all(a.intersection(b).area == 0 for i, a in enumerate(boxes) for b in boxes[i + 1:])


def test_every_image_in_the_detail_is_lettered_inside_its_circle_nearest_its_own_image(sheet):
    detail, plan = sheet.views["detail-a-4"], sheet.views["plan-a-4"]
    k = detail.view.meta["factor"]
    pole = np.asarray(detail.to_sheet((0.0, 0.0)))
    ring = next(c for c in detail.primitives if isinstance(c, Circle) and c.line == "thin" and c.radius > 5.0)
    window = shapely.Point(ring.centre).buffer(ring.radius)
    at = {}
    for target, z in plan.view.meta["images"].items():
        xy = pole + k * np.array([z.real, z.imag])
        if np.isfinite(z) and window.contains(shapely.Point(xy)):
            at.setdefault(subscript(label_of(target)), []).append(xy)
    letters = {part: t for t in detail.primitives if isinstance(t, Text) for part in t.text.split(", ") if part in at}
    assert set(letters) == set(at)
    points = [xy for xys in at.values() for xy in xys]
    for name, t in letters.items():
        box = label_box(t)
        assert window.contains(box), name
        own = min(box.distance(shapely.Point(xy)) for xy in at[name])
        others = [box.distance(shapely.Point(xy)) for xy in points if min(np.hypot(*(xy - o)) for o in at[name]) > 0.3]
        led = any(isinstance(p, Polyline) and p.line == "thin" and len(p.points) == 2
                  and min(np.hypot(*(np.asarray(p.points[0]) - o)) for o in at[name]) < 1e-6
                  and box.buffer(0.6).contains(shapely.Point(p.points[1])) for p in detail.primitives)
        assert led or not others or own < min(others), name
