"""The scheme of a class III group (issue 21): the ternary base link drawn as a plate — its three
sides thick, its corners hatched (GOST 2.770), its number inside — the leads as rods or a
block on its guide, and Assur's special point kept off the scheme except where a plan's
construction is shown; the data block, the transfer-function table and the readings of a
triad."""

import numpy as np
import pytest
import shapely

import velplan
from velplan.render.layout import label_box
from velplan.render.scene import Circle, Polygon, Polyline, Text
from velplan.views.mechanism import mechanism_view, output_point, trajectory_points

MU = 0.004  # m/mm, 1:4


@pytest.fixture(scope="module")
def rocker():
    return velplan.Study("triad-rocker")


def _view(study, **kw):
    return mechanism_view(study.mechanism, kin=study.kinematics, fine=study.turn, mu_l=MU,
                          lang="en", thick=3, **kw)


def _at(view, study, name, i=2):
    """Where point `name` of position index `i` lies in the view, mm."""
    return view.to_view(study.kinematics.position(name)[i])


def test_the_base_link_is_a_plate_with_hatched_corners_and_its_number_inside(rocker):
    view = _view(rocker, single=True)
    b, c, d = (_at(view, rocker, p) for p in "BCD")
    thick = [np.asarray(p.points) for p in view.primitives
             if isinstance(p, Polyline) and p.line == "thick" and len(p.points) == 2]

    def drawn(p, q):  # a thick line from joint p to joint q, trimmed by the joints' circles
        u = (q - p) / np.hypot(*(q - p))
        return any(np.allclose(sorted(map(tuple, s)), sorted(map(tuple, (p + 1.5 * u, q - 1.5 * u))), atol=1e-6)
                   for s in thick)
    assert drawn(b, c) and drawn(c, d) and drawn(d, b)
    plate = shapely.Polygon([b, c, d])
    for corner in (b, c, d):  # thin strokes across each corner, inside the plate, near it
        strokes = [p for p in view.primitives if isinstance(p, Polyline) and p.line == "thin"
                   and plate.buffer(1e-6).contains(shapely.LineString(p.points))
                   and np.hypot(*(np.mean(p.points, axis=0) - corner)) < 8.0]
        assert len(strokes) >= 3
    (three,) = [t for t in view.primitives if isinstance(t, Text) and t.text == "3"]
    assert plate.contains(shapely.Point(three.position))
    # the leads: rods from A, E, F to B, C, D
    for outer, inner in (("A", "B"), ("E", "C"), ("F", "D")):
        assert drawn(_at(view, rocker, outer), _at(view, rocker, inner))


def test_the_special_point_only_where_the_construction_is_shown(rocker):
    plain = _view(rocker, single=True)
    assert not any(isinstance(t, Text) and t.text.startswith("K") for t in plain.primitives)
    shown = _view(rocker, single=True, special=True)
    (letter,) = [t for t in shown.primitives if isinstance(t, Text) and t.text == "K₃"]
    k = _at(shown, rocker, "K3")
    assert label_box(letter).distance(shapely.Point(k)) < 5.0
    assert any(isinstance(p, Circle) and p.fill == "solid" and np.allclose(p.centre, k) for p in shown.primitives)
    # two dash-dotted lead lines pass through it, each along a lead (E–C and F–D here)
    axes = [np.asarray(p.points) for p in shown.primitives if isinstance(p, Polyline) and p.line == "axis"]
    assert len(axes) == 2
    for a in axes:
        assert shapely.LineString(a).distance(shapely.Point(k)) < 1e-6
    # the scheme's extent ignores it (it may lie far off, or at infinity)
    assert "K3" not in trajectory_points(rocker.mechanism)


def test_the_output_of_a_triad_is_numbered_at_its_lead_joint(rocker):
    assert output_point(rocker.mechanism) == "D"  # output link 5 = the lead F–D
    view = _view(rocker)
    path = rocker.kinematics.position("D") / MU + np.asarray(view.origin)
    # by D's path (within 25 mm: the numbers of the crowded end stepped out), not by the crank's (80 mm off)
    near = [t.text for t in view.primitives if isinstance(t, Text) and t.size_mm == 2.5
            and np.min(np.hypot(*(path - t.position).T)) < 25.0 and t.text[0].isdigit()]
    assert sorted(int(k) for t in near for k in t.split(",")) == list(range(1, 13))


def test_a_block_lead_rides_on_its_hatched_guide():
    study = velplan.Study("triad-press")
    view = _view(study)
    d = study.kinematics.position("D")[2] / MU + np.asarray(view.origin)
    blocks = [p for p in view.primitives if isinstance(p, Polygon) and p.line == "thick" and p.fill == "white"]
    assert any(np.allclose(np.mean(p.points, axis=0), d, atol=1e-6) for p in blocks)
    # the guide: a thick vertical line beside the block's path, 0.272 m right of O1
    x = 0.272 / MU + view.origin[0]
    guides = [np.asarray(p.points) for p in view.primitives if isinstance(p, Polyline) and p.line == "thick"
              and abs(p.points[0][0] - p.points[1][0]) < 1e-6 and abs(abs(p.points[0][0] - x) - 3.5) < 1e-6]
    assert guides


def test_data_table_and_readings_of_a_triad(rocker):
    from velplan.views.data import data_lines
    from velplan.views.readings import readings

    text = "\n".join(data_lines(rocker, "en"))
    (g,) = rocker.mechanism.groups
    for symbol, value in (("l_{BC}", g.sides[0]), ("l_{CD}", g.sides[1]), ("l_{DB}", g.sides[2]),
                          ("l_{AB}", g.leads[0].length), ("l_{EC}", g.leads[1].length),
                          ("l_{FD}", g.leads[2].length)):
        assert f"{symbol} = {value:g} m" in text
    rows = rocker.table.rows
    assert {"V_B", "V_C", "V_D"} <= set(rows) and "V_K3" not in rows
    res = rocker.plan("velocity")
    assert "K3" in res.vectors  # constructed, but not read off as a result
    assert {p for p, *_ in readings(res, 1)} >= {"B", "C", "D"}
    assert "K3" not in {p for p, *_ in readings(res, 1)}
