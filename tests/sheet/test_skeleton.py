"""The sheets' skeleton and layout solver: one request check, one bottom band, one title block
for the three sheets; a trial drawing made once; the largest drawing that fits is found."""

import collections
import functools

import pytest

import velplan
from velplan.errors import VelplanError
from velplan.render.scene import Polyline
from velplan.sheets import dynamics, forces, kinematic
from velplan.sheets.skeleton import ComposedSheet, check_plan_positions, sheet_request
from velplan.sheets.solver import Trials, largest_fitting, widest_first
from velplan.views.base import make_view


def _box(width: float, height: float):
    return make_view("box", [Polyline([(0.0, 0.0), (width, height)], "l")], pad_mm=0.0)


def test_trials_draw_each_key_once():
    calls = []

    def draw(side):
        calls.append(side)
        return _box(side, side / 2)

    trials = Trials(draw)
    assert trials(40.0) is trials(40.0) and trials(20.0).width_mm == 20.0
    assert calls == [40.0, 20.0] and trials.drawn == 2


def test_largest_fitting_takes_the_first_that_fits_and_draws_no_skipped_trial():
    drawn = []

    def draw(side):
        drawn.append(side)
        return _box(side, side)

    found = largest_fitting(draw, (200.0, 150.0, 90.0, 80.0, 50.0), 100.0, 85.0,
                            skip=lambda side: side > 160.0)
    assert found[0] == 80.0 and found[1].height_mm == 80.0
    assert drawn == [150.0, 90.0, 80.0]  # 200 skipped, nothing after the first fit
    assert largest_fitting(draw, (300.0, 200.0), 100.0, 100.0) is None


def test_widest_first_gives_the_last_view_when_none_is_narrow_enough():
    size, view = widest_first(lambda s: _box(100.0 * s, 10.0), (3.5, 2.5, 1.8), 200.0)
    assert size == 1.8 and view.width_mm == pytest.approx(180.0)
    size, view = widest_first(lambda s: _box(100.0 * s, 10.0), (3.5, 2.5), 200.0)
    assert size is None and view.width_mm == pytest.approx(250.0)


@pytest.mark.parametrize("options, message", [
    ({"fmt": "A0"}, r"^unknown sheet format 'A0'; known formats: A1, A2, A3$"),
    ({"lang": "de"}, r"known languages"),
    ({"frame_style": "gb"}, r"^unknown frame style 'gb'; known styles: eskd, iso$"),
    ({"n": 2}, r"^a sheet needs at least 3 positions, not 2$"),
])
def test_one_request_check_for_every_sheet(options, message):
    for build in (kinematic.build_sheet, forces.build_force_sheet):
        with pytest.raises(VelplanError, match=message):
            build("shaper", **options)
    if "n" not in options:
        with pytest.raises(VelplanError, match=message):
            dynamics.build_dynamics_sheet(velplan.Study("shaper", delta=0.05), **options)


def test_request_defaults_and_positions():
    req = sheet_request("four-bar", fmt="A2", lang="uk")
    assert (req.frame_style, req.gap, req.mechanism.name) == ("eskd", 8.0, "four-bar")
    assert req.area[2] - req.area[0] == req.width == pytest.approx(594 - 25 - 8)
    assert check_plan_positions([2, 7], 12) == (2, 7)
    with pytest.raises(VelplanError, match=r"^--plans: give at least one position$"):
        check_plan_positions((), 12)


def test_the_three_sheets_share_the_skeleton():
    assert all(issubclass(cls, ComposedSheet) for cls in
               (kinematic.Sheet, forces.ForceSheet, dynamics.DynamicsSheet))
    titles = [kinematic.default_title(velplan.load("shaper"), "en", "A1", "1:2", "iso"),
              forces.default_force_title(velplan.load("shaper"), "en", "1:2"),
              dynamics.default_dynamics_title(velplan.load("shaper"), "en", "1:2")]
    assert [t.designation for t in titles] == ["TMM 01.00.000", "TMM 02.00.000", "TMM 03.00.000"]
    assert {t.scale for t in titles} == {"1:2"}


def _key(values) -> tuple:
    """Values as a key: numbers and text as they are, anything else by its identity."""
    return tuple(v if isinstance(v, (int, float, str)) else id(v) for v in values)


def _counting(monkeypatch, module, names):
    """Wrap `names` of `module` so that each call is counted by its arguments."""
    counts = collections.Counter()
    for name in names:
        original = getattr(module, name)

        @functools.wraps(original)
        def counted(*args, _original=original, _name=name, **kwargs):
            counts[_name, _key(args), tuple((k, *_key([v])) for k, v in sorted(kwargs.items()))] += 1
            return _original(*args, **kwargs)
        monkeypatch.setattr(module, name, counted)
    return counts


@pytest.mark.parametrize("fmt", ["A1", "A3"])
def test_no_trial_view_is_drawn_twice(monkeypatch, fmt):
    """However many arrangements a sheet compares, each view is drawn once per scale."""
    study = velplan.Study("shaper")
    counts = _counting(monkeypatch, forces, ("group_view", "polygon_view", "lever_view"))
    forces.build_force_sheet(study, fmt=fmt)
    assert counts and max(counts.values()) == 1, counts.most_common(3)
    counts = _counting(monkeypatch, kinematic, ("mechanism_view", "diagram_view"))
    kinematic.build_sheet(study, fmt=fmt)
    assert counts and max(counts.values()) == 1, counts.most_common(3)
