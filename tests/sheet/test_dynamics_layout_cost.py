"""The dynamics sheet's cheaper layout search gives what the plain one gave (issue 34): a
curve's distances to the other lines from the segments near it are shapely's whole-line
distances; a panel drawn at the μ a height gives is the panel drawn for that height; the
named pass skips only heights whose unnamed panels do not fit; the sheet is the same with the
memos emptied before every drawing."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import velplan
from velplan.sheets import dynamics as sd
from velplan.views import dynamics as vd
from velplan.views.dynamics import DynamicsSizes, Series, curve_panel, ordinate_scale


def _whole_line(xy, others, cap):
    """The reference: shapely's distance of every point to every whole line, capped."""
    pts = shapely.points(xy)
    out = np.full(len(xy), cap)
    for ln in others:
        out = np.minimum(out, shapely.distance(pts, ln))
    return out


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(3, 400), sorted_x=st.booleans(), lines=st.integers(1, 3))
def test_distances_to_the_other_lines_are_shapelys_to_the_last_bit(seed, n, sorted_x, lines):
    rng = np.random.default_rng(seed)
    x = rng.uniform(0.0, 120.0, n)
    xy = np.column_stack([np.sort(x) if sorted_x else x, rng.normal(0.0, 3.0, n).cumsum()])
    others = []
    for k in range(lines):
        m = int(rng.integers(2, 300))
        xs = rng.uniform(0.0, 120.0, m)
        if k % 2 == 0:  # a curve over the travel (x never decreasing), repeated x included
            xs = np.sort(np.round(xs, 0))
        others.append(shapely.LineString(np.column_stack([xs, rng.normal(0.0, 2.0, m).cumsum()])))
    assert np.array_equal(vd._apart(xy, others, 8.0), _whole_line(xy, others, 8.0))


def test_distances_on_crossing_and_touching_curves_and_the_axis():
    x = np.linspace(0.0, 180.0, 721)
    xy = np.column_stack([x, 20.0 * np.sin(x / 15.0)])
    others = [shapely.LineString(np.column_stack([x, 20.0 * np.cos(x / 15.0)])),  # crosses it
              shapely.LineString(np.column_stack([x, 20.0 * np.sin(x / 15.0) + 1.0])),  # 1 mm above
              shapely.LineString([(0.0, 0.0), (188.0, 0.0)])]  # the φ axis
    got = vd._apart(xy, others, 8.0)
    assert np.array_equal(got, _whole_line(xy, others, 8.0))
    assert got.max() <= 1.0 + 1e-12 and got.min() == 0.0


TRAVEL = np.linspace(0.0, 2 * math.pi, 361)
ARGS = dict(cycle=2 * math.pi, positions=12, length_mm=180.0, title="M", ordinate="M", unit_text="N·m",
            lang="en", mu_symbol="μ_{M}")


@pytest.mark.parametrize("names", [False, True])
@pytest.mark.parametrize("height", [15.0, 25.0, 40.0, 100.0])
def test_a_panel_at_its_heights_mu_is_the_panel_of_that_height(names, height):
    series = [Series(-80.0 * np.maximum(np.sin(TRAVEL), 0.0), "thin", "M_{F}"),
              Series(30.0 * np.cos(2 * TRAVEL) - 20.0, "thick", "M_{r}")]
    plain = curve_panel("moments", TRAVEL, series, height_mm=height, names=names, **ARGS)
    mu = ordinate_scale(series, 0.0, height)
    at_mu = curve_panel("moments", TRAVEL, series, height_mm=1.0, mu=mu, names=names, **ARGS)
    assert plain.primitives == at_mu.primitives and plain.meta["mu"] == mu
    assert (plain.width_mm, plain.height_mm) == (at_mu.width_mm, at_mu.height_mm)


def test_a_named_panel_is_never_smaller_than_its_unnamed_drawing():
    """What lets the named pass skip the heights whose unnamed panels do not fit."""
    series = [Series(50.0 * np.sin(TRAVEL), "thin", "M_{F}"), Series(60.0 * np.sin(TRAVEL) + 5.0, "thick", "M_{r}"),
              Series(np.full_like(TRAVEL, 12.0), "hidden", "M_{d}")]
    for height in (15.0, 30.0, 60.0):
        bare = curve_panel("moments", TRAVEL, series, height_mm=height, names=False, **ARGS)
        named = curve_panel("moments", TRAVEL, series, height_mm=height, names=True, **ARGS)
        assert named.width_mm >= bare.width_mm and named.height_mm >= bare.height_mm


@pytest.mark.parametrize("name, fmt", [("shaper-lever-rod", "A3"), ("jaw-crusher", "A3"), ("compressor", "A1")])
def test_the_sheet_is_the_same_without_the_memos(monkeypatch, name, fmt):
    """Every panel and energy–mass diagram drawn afresh where it was taken from a memo: the
    same SVG."""
    study = velplan.Study(name)
    fast = sd.build_dynamics_sheet(study, fmt=fmt, lang="ru").svg()
    panels, fit_wittenbauer = sd._panels, sd._fit_wittenbauer
    monkeypatch.setattr(sd, "_panels", lambda *a, **k: panels(*a[:9]))  # no memo
    monkeypatch.setattr(sd, "_fit_wittenbauer", lambda *a: fit_wittenbauer(*a[:7]))  # no memo
    bare = sd.build_dynamics_sheet(study, fmt=fmt, lang="ru").svg()
    assert fast == bare


@pytest.mark.parametrize("height", [15.0, 40.0])
def test_a_measured_panel_has_the_drawings_size_and_meta(height):
    """A trial only measured (its curves as their boxes' diagonals) is as large as the drawing."""
    series = [Series(50.0 * np.sin(TRAVEL) - 7.0, "thin", "M_{F}"), Series(60.0 * np.cos(TRAVEL), "thick", "M_{r}")]
    drawn = curve_panel("moments", TRAVEL, series, height_mm=height, names=False, **ARGS)
    measured = curve_panel("moments", TRAVEL, series, height_mm=height, names=False, measured=True, **ARGS)
    assert (measured.width_mm, measured.height_mm) == (drawn.width_mm, drawn.height_mm)
    for key in ("mu", "mu_phi", "span_mm"):
        assert measured.meta[key] == drawn.meta[key]
    assert max(len(p.points) for p in measured.primitives if hasattr(p, "points")) == 2
