"""Issue 32 on the force and dynamics sheets: a φ axis's position numbers stand by their ticks,
clear of every line drawn over the axis (the M_b diagram's mean line too), a curve's name is led
to it without crossing a number, and the constant moment of the dynamics is named by what it
does (M_д where it drives a machine, M_с where it resists an engine's gas forces)."""

import math

import numpy as np
import pytest
import shapely

import velplan
from velplan.forces.curve import MomentCurve, turn_mean
from velplan.render.i18n import label
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Polyline, Text
from velplan.views.base import NUMBER_REACH, axis_numbers_clear
from velplan.views.dynamics import constant_moment
from velplan.views.forces.diagram import moment_diagram_view


def _numbers(items):
    return [t for t in items if isinstance(t, Text) and t.text.isdigit()]


def _lines(items):
    return [(p, shapely.LineString(p.points if isinstance(p, Polyline) else [p.start, p.end]))
            for p in items if isinstance(p, (Polyline, Arrow))]


def _crossed(t, lines) -> list:
    """The lines that cross the box of `t`, but its own leader (a thin segment ending at it)."""
    box = label_box(t)
    own = box.buffer(0.6)
    return [p for p, ln in lines if ln.intersects(box)
            and not (isinstance(p, Polyline) and p.line == "thin" and len(p.points) == 2
                     and own.contains(shapely.Point(p.points[-1])))]


@pytest.mark.parametrize("mean_mm", [-2.2, 2.2, 3.0])
@pytest.mark.parametrize("length", [144.0, 240.0])
def test_moment_diagram_numbers_clear_the_mean_line(mean_mm, length):
    """A curve that dips under the axis at most positions and a mean line just over or under
    it: the numbers mirrored above the axis, or moved a little below, used to land on the mean
    line (double-slider, sieve-shaker, yoke-punch-press: 5 numbers)."""
    turn = np.linspace(0.0, 2 * math.pi, 721)
    moment = -8.0 * np.sin(3 * turn) ** 2 + 10.0 * np.sin(turn) ** 8  # N·m, μM = 1 at height 20
    moment = moment - turn_mean(moment) + mean_mm  # its mean `mean_mm` N·m (mm at μM = 1)
    at = np.interp(np.arange(12) * 2 * math.pi / 12, turn, moment)
    view = moment_diagram_view(MomentCurve(turn, moment, at, turn_mean(moment)), length_mm=length,
                               height_mm=20.0, lang="en")
    assert view.meta["mu_m"] == 1.0
    items = view.primitives
    lines = _lines(items)
    for t in _numbers(items):
        assert not _crossed(t, lines), (t.text, t.position)


def _tick_distance(t, tick_x: float, origin) -> float:
    return label_box(t).distance(shapely.LineString([(tick_x, origin[1] - 1.0), (tick_x, origin[1] + 1.0)]))


def test_a_crossed_number_stays_by_its_tick():
    """Compressor's moments panel: under tick 4 the curve, 4.1 mm over the axis the dashed M_р:
    the number went 5.5 mm above the axis, over the dashed line; now it stands beside its
    tick, within `NUMBER_REACH` of its height, clear of both lines."""
    size = 2.5
    number = Text((40.0, -1.8), "4", "labels", size, "middle", "top")
    curve = np.array([(30.0, 0.5), (38.0, -1.0), (42.0, -4.0), (50.0, -12.0)])
    dashed = np.array([(0.0, 4.1), (100.0, 4.1)])
    out = axis_numbers_clear([number], [curve, dashed])
    (moved,) = _numbers(out)
    box = label_box(moved)
    assert not box.intersects(shapely.LineString(curve)) and not box.intersects(shapely.LineString(dashed))
    assert _tick_distance(moved, 40.0, (0.0, 0.0)) <= NUMBER_REACH * size
    assert not box.intersects(shapely.LineString([(0.0, 0.0), (100.0, 0.0)]))  # off the axis
    assert not box.intersects(shapely.LineString([(40.0, -1.0), (40.0, 1.0)]))  # off its tick


@pytest.fixture(scope="module")
def yoke_a3():
    from velplan.sheets.dynamics import build_dynamics_sheet

    return build_dynamics_sheet(velplan.Study("yoke-punch-press"), lang="ru", fmt="A3")


def test_curve_names_leaders_cross_no_number(yoke_a3):
    """yoke-punch-press A3: M_G's leader ran through the φ axis's number 6."""
    for name, placed in yoke_a3.views.items():
        if "curves" not in placed.view.meta:
            continue
        texts = [t for t in placed.view.primitives if isinstance(t, Text)]
        leaders = [p for p in placed.view.primitives if isinstance(p, Polyline) and p.line == "thin"
                   and len(p.points) == 2 and p.layer == "dynamics-labels"]
        for leader in leaders:
            line = shapely.LineString(leader.points)
            crossed = [t.text for t in texts if line.intersects(label_box(t))
                       and not label_box(t).buffer(0.6).contains(shapely.Point(leader.points[-1]))]
            assert not crossed, (name, crossed)


def test_every_panel_number_stands_by_its_tick(yoke_a3):
    for name, placed in yoke_a3.views.items():
        if "curves" not in placed.view.meta:
            continue
        prims, (ox, oy) = placed.view.primitives, placed.view.origin
        ticks = sorted({p.points[0][0] for p in prims if isinstance(p, Polyline) and p.line == "thin"
                        and len(p.points) == 2 and abs(p.points[0][0] - p.points[1][0]) < 1e-9
                        and abs(p.points[0][1] - (oy - 1.0)) < 1e-9 and abs(p.points[1][1] - (oy + 1.0)) < 1e-9})
        assert len(ticks) >= 12, name
        for t in _numbers(prims):
            if t.anchor == "end" and t.position[0] < ox:  # an ordinate's number
                continue
            near = min(ticks, key=lambda x: label_box(t).distance(shapely.Point(x, oy)))
            assert _tick_distance(t, near, (ox, oy)) <= NUMBER_REACH * t.size_mm + 1e-9, (name, t.text)


@pytest.mark.parametrize("name, role", [("engine-two-stroke", "resisting_moment"),
                                        ("compressor", "driving_moment"), ("v-compressor", "driving_moment"),
                                        ("piston-pump", "driving_moment")])
def test_the_constant_moment_is_named_by_what_it_does(name, role):
    """An engine's gas forces drive and its constant moment resists (M_с against M_д); a machine
    a motor drives at a constant moment has M_д against its loads' M_с."""
    d = velplan.Study(name).dynamics
    assert (d.driving < 0) == (role == "resisting_moment")
    key, own, loads = constant_moment(d, "ru")
    assert key == role
    assert (own, loads) == (("с", "д") if role == "resisting_moment" else ("д", "с"))
    assert constant_moment(d, "uk")[1:] == (("о", "р") if role == "resisting_moment" else ("р", "о"))


def test_the_engine_sheet_names_its_resisting_moment():
    from velplan.sheets.dynamics import build_dynamics_sheet

    sheet = build_dynamics_sheet(velplan.Study("engine-two-stroke"), lang="ru", fmt="A3")
    texts = [t.text for t in sheet.scene.of_kind(Text)]
    assert any(t.startswith("M_{с} = −30,4") for t in texts)  # the dashed constant, as drawn
    assert any(t.startswith("M_{д}") for t in texts)  # the gas forces' reduced moment
    assert not any(t.startswith("M_{д} = ") for t in texts)
    assert {"A_{д}", "A_{с}"} <= set(texts)
    assert label("resisting_moment", "ru") + " M_{с}" in texts  # the results' row
