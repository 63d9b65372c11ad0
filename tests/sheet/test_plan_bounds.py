"""A plan's least size (`least_plan_size`: its construction and title, no letters) never
exceeds its drawing, and the kinematic sheet that skips the trial plans it rules out is the
sheet drawn without the bound."""

import pytest

from velplan.sheets import kinematic
from velplan.study import Study
from tests.sheet.helpers import calls_with_and_without
from velplan.views.plan import PlanSizes, least_plan_size, plan_steps, plan_view

MECHS = ("shaper", "four-bar", "press", "whitworth", "triad-press")


@pytest.mark.parametrize("name", MECHS)
def test_least_plan_size_never_exceeds_the_drawing(name):
    study = Study(name, n=12)
    for kind in ("velocity", "acceleration"):
        res0 = study.plan(kind)
        for k in (1, 4, 10):
            for factor, lang, sizes in ((1.0, "ru", PlanSizes(5.0, 3.5)), (0.5, "en", PlanSizes(3.5, 2.5)),
                                        (2.0, "zh", PlanSizes(3.5, 3.5))):
                res = res0.at_scale(res0.scale * factor)
                steps = plan_steps(res, k, lang=lang)
                view = plan_view(res, k, lang=lang, sizes=sizes, steps=steps)
                w, h = least_plan_size(res, k, steps, lang=lang, sizes=sizes)
                assert 0.3 * view.width_mm < w <= view.width_mm * (1 + 1e-12)
                assert 0.3 * view.height_mm < h <= view.height_mm * (1 + 1e-12)
                # the view drawn from shared steps is the view drawn from scratch
                assert plan_view(res, k, lang=lang, sizes=sizes) == view


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "ru"), ("press", "A2", "en"),
                                           ("whitworth", "A3", "zh"), ("four-bar", "A1", "en")])
def test_sheet_is_the_same_without_the_bound(name, fmt, lang, monkeypatch):
    bounded, every = calls_with_and_without(
        monkeypatch, lambda: kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang), "plan_view",
        [(kinematic._Drawings, "plan_fits", lambda self, *a: True)])
    assert bounded <= every


def test_the_bound_spares_a_shaper_plan(monkeypatch):
    """The shaper's A3 sheet tries plans whose construction and title alone exceed their
    cells: they are not drawn."""
    drawn = []
    real = kinematic.plan_view
    monkeypatch.setattr(kinematic, "plan_view", lambda *a, **kw: drawn.append(a[0].scale) or real(*a, **kw))
    kinematic.build_sheet(Study("shaper", n=12), fmt="A3", lang="ru")
    with_bound = len(drawn)
    monkeypatch.setattr(kinematic._Drawings, "plan_fits", lambda self, *a: True)
    drawn.clear()
    kinematic.build_sheet(Study("shaper", n=12), fmt="A3", lang="ru")
    assert with_bound < len(drawn)


@pytest.mark.parametrize("name,fmt", [("shaper", "A1"), ("whitworth", "A2"), ("slider-press", "A3"),
                                      ("four-bar", "A1"), ("triad-press", "A1")])
def test_score_bound_is_never_below_the_fitted_score(name, fmt):
    """Both bounds: the plans' least sizes (`_score_bound`) and the tighter one of their
    construction and title alone (`_drawn_vector_bound`), never below the score fitted."""
    import functools

    from velplan.errors import ScaleError
    from velplan.sheets.layout import MIN_PLAN_MM
    from velplan.sheets.skeleton import sheet_request

    req = sheet_request(Study(name, n=12), n=12, fmt=fmt, lang="en", frame_style=None, style=None)
    chosen = kinematic.default_plan_positions(req.study.plan("velocity"))
    draw = kinematic._Drawings(req, chosen)
    kinds = ("velocity", "acceleration")
    tight = functools.partial(kinematic._drawn_vector_bound, draw, MIN_PLAN_MM[fmt])
    fx0, fy0, fx1, fy1 = req.area
    checked = 0
    for left in (0.3, 0.45, 0.6):
        for bottom in (0.2, 0.5, 0.7):
            region = (fx0 + left * (fx1 - fx0), fy0 + bottom * (fy1 - fy0), fx1, fy1)
            bound = kinematic._score_bound(req.study, chosen, kinds, region, req.gap)
            tighter = kinematic._score_bound(req.study, chosen, kinds, region, req.gap, tight)
            assert tighter <= bound
            try:
                score, _ = kinematic._fit_plans(req, draw, chosen, kinds, region)
            except ScaleError:
                continue
            assert score <= tighter
            checked += 1
    assert checked


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "ru"), ("whitworth", "A1", "en"),
                                           ("four-bar", "A2", "uk"), ("slider-press", "A1", "en")])
def test_sheet_is_the_same_without_the_score_bound(name, fmt, lang, monkeypatch):
    bounded, every = calls_with_and_without(
        monkeypatch, lambda: kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang), "_fit_plans",
        [(kinematic, "_cannot_change", lambda *a: False)])
    assert bounded <= every
