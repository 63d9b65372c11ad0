"""What a sheet's layout search decides without drawing: a size of the structural analysis is
skipped only where its least extent (`least_extent`) exceeds what it draws never, and a plan's
"≈ 0" list finds its corner by distances exactly where shapely's buffer would."""

import math

import pytest
import shapely
from hypothesis import given, settings, strategies as st

import velplan
from velplan.sheets.structure import FIGURE_SIZES, _joints
from velplan.study import Study
from velplan.views.base import bounds_of
from velplan.views.plan import _Clearance
from velplan.views.structure import least_extent, structure_view

MECHS = (*velplan.example_names(), "whitworth", "triad-press", "stephenson-six-bar", "jaw-crusher")


@pytest.mark.parametrize("name", MECHS)
def test_least_extent_never_exceeds_the_drawing(name):
    study = Study(name, n=12)
    joints = _joints(study)
    for lang in ("en", "ru", "zh"):
        for panel_mm, text_mm, title_mm in FIGURE_SIZES[::3] + FIGURE_SIZES[-1:]:
            for title in (True, False):
                kw = dict(lang=lang, title=title, panel_mm=panel_mm, text_mm=text_mm, title_mm=title_mm)
                x0, y0, x1, y1 = bounds_of(structure_view(study.mechanism, joints, **kw).primitives)
                w, h = least_extent(study.mechanism, joints, **kw)
                assert 0.5 * (x1 - x0) < w <= (x1 - x0) * (1 + 1e-12)
                assert 0.3 * (y1 - y0) < h <= (y1 - y0) * (1 + 1e-12)


def test_least_extent_is_the_heading_width_where_the_formula_is_widest():
    study = Study("shaper", n=12)
    joints = _joints(study)
    w, _ = least_extent(study.mechanism, joints, lang="en", panel_mm=35.0, text_mm=3.5, title_mm=5.0)
    drawn = structure_view(study.mechanism, joints, lang="en", panel_mm=35.0, text_mm=3.5, title_mm=5.0)
    x0, _, x1, _ = bounds_of(drawn.primitives)
    assert w == pytest.approx(x1 - x0, rel=1e-9)  # the formula sets the width: the bound is tight


SHAPES = [shapely.LineString([(0, 0), (20, 0), (20, 15)]), shapely.Point(5, 5).buffer(2.0),
          shapely.box(30, -4, 38, 2)]


@settings(max_examples=300, deadline=None)
@given(st.floats(-12, 50), st.floats(-12, 25), st.floats(0.1, 8), st.floats(0.1, 4),
       st.sampled_from([0.5, 1.0, 2.0]))
def test_clearance_agrees_with_the_buffer(x, y, w, h, gap):
    box = shapely.box(x, y, x + w, y + h)
    taken = shapely.union_all(SHAPES).buffer(gap)
    assert _Clearance(SHAPES, gap).meets(box) == box.intersects(taken)


def test_clearance_near_the_gap_asks_the_buffer():
    # a box whose distance to the corner's arc lies between the buffer's chord and the arc
    gap = 1.0
    c = _Clearance([shapely.Point(0.0, 0.0)], gap)
    a = math.pi / 64  # halfway between two of the buffer's vertices (16 per quarter)
    d = 0.9995 * gap
    box = shapely.box(d * math.cos(a), d * math.sin(a), d * math.cos(a) + 1, d * math.sin(a) + 1)
    assert shapely.distance(box, shapely.Point(0, 0)) < gap  # by distance alone it would meet
    assert not box.intersects(shapely.Point(0, 0).buffer(gap))  # the drawn buffer's chord misses it
    assert not c.meets(box)
    assert not _Clearance([], gap).meets(box)


FORCE_MECHS = ("shaper", "slider-press", "press", "whitworth", "jaw-crusher")


@pytest.mark.parametrize("name", FORCE_MECHS)
def test_force_views_are_never_smaller_than_their_bodies(name):
    from velplan.sheets.forces import FORCE_SIZES, solving_order
    from velplan.views.forces import group_view, lever_view
    from velplan.views.forces.group import group_body_size
    from velplan.views.forces.lever import lever_body_size

    fa = Study(name, n=12).forces()
    order = solving_order(fa.kinetostatics.mechanism)
    for fmt, sizes in FORCE_SIZES.items():
        for k in (2, 7):
            for mu in (0.002, 0.005):
                for grp in order:
                    view = group_view(fa, grp, k, mu_l=mu, lang="en", sizes=sizes)
                    w, h = group_body_size(fa, grp, k, mu_l=mu, sizes=sizes)
                    assert 0.0 < w <= view.width_mm + 1e-9 and 0.0 < h <= view.height_mm + 1e-9
            for mu_v in (0.01, 0.03):
                view = lever_view(fa, k, mu_v=mu_v, lang="ru", sizes=sizes)
                w, h = lever_body_size(fa, k, mu_v=mu_v, lang="ru", sizes=sizes)
                assert 0.0 < w <= view.width_mm + 1e-9 and 0.0 < h <= view.height_mm + 1e-9


@pytest.mark.parametrize("name,fmt", [("shaper", "A1"), ("slider-press", "A3"), ("whitworth", "A2")])
def test_force_sheet_is_the_same_without_the_bounds(name, fmt, monkeypatch):
    """The rows shrink the same way whether a drawing's least height is known or not."""
    from velplan.sheets import forces

    study = Study(name, n=12)
    with_bounds = forces.build_force_sheet(study, fmt=fmt, lang="en").svg()
    monkeypatch.setattr(forces._Rows, "least_height", lambda self, ref: 0.0)
    assert forces.build_force_sheet(Study(name, n=12), fmt=fmt, lang="en").svg() == with_bounds
