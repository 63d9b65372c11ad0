"""A scheme's least size (`least_scheme_size`: its positions' lines, margin and title, no
letters) never exceeds its drawing; the plans' tighter score bound (their construction and
title alone, `_drawn_vector_bound`) is never below the score fitted; and the kinematic sheet
that passes over a scheme that cannot be chosen, undrawn, is the sheet that draws it."""

import functools

import pytest

from velplan.sheets import kinematic
from velplan.study import Study
from velplan.views.base import eskd_scales
from velplan.views.mechanism import MechanismSizes, extent_m, least_scheme_size, mechanism_view

MECHS = ("shaper", "four-bar", "press", "whitworth", "triad-press", "jaw-crusher")


@pytest.mark.parametrize("name", MECHS)
def test_least_scheme_size_never_exceeds_the_drawing(name):
    study = Study(name, n=12)
    fine = study.turn.take(slice(None, None, 3))
    span = max(extent_m(study.mechanism, study.kinematics, fine))
    for size, thick, lang, sizes in ((400.0, 1, "ru", MechanismSizes()),
                                     (250.0, 4, "en", MechanismSizes(3.5, 2.5, 2.5)),
                                     (160.0, 10, "zh", MechanismSizes(7.0, 5.0, 3.5))):
        mu = next(m for m in eskd_scales() if span / m <= size)  # the largest drawing at most `size` mm
        view = mechanism_view(study.mechanism, kin=study.kinematics, fine=fine, mu_l=mu, n=study.n,
                              thick=thick, lang=lang, sizes=sizes, bold=(thick,), plans=(thick,))
        w, h = least_scheme_size(study.mechanism, study.kinematics, mu_l=mu, thick=thick, sizes=sizes)
        assert 0.5 * view.width_mm < w <= view.width_mm
        assert 0.5 * view.height_mm < h <= view.height_mm


@pytest.mark.parametrize("name,fmt", [("shaper", "A1"), ("whitworth", "A2"), ("slider-press", "A3"),
                                      ("four-bar", "A1"), ("triad-press", "A1")])
def test_drawn_vector_bound_is_never_below_the_fitted_score(name, fmt):
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
            bound = kinematic._score_bound(req.study, chosen, kinds, region, req.gap, tight)
            assert bound <= kinematic._score_bound(req.study, chosen, kinds, region, req.gap)
            try:
                score, _ = kinematic._fit_plans(req, draw, chosen, kinds, region)
            except ScaleError:
                continue
            assert score <= bound
            checked += 1
    assert checked


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "ru"), ("whitworth", "A1", "en"),
                                           ("four-bar", "A2", "uk"), ("slider-press", "A1", "en"),
                                           ("jaw-crusher", "A3", "zh"), ("triad-press", "A3", "en")])
def test_sheet_is_the_same_with_every_scheme_drawn(name, fmt, lang, monkeypatch):
    drawn = []
    real = kinematic.mechanism_view
    monkeypatch.setattr(kinematic, "mechanism_view", lambda *a, **kw: drawn.append(kw["mu_l"]) or real(*a, **kw))
    passing_over = kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang).svg()
    fewer = len(drawn)
    monkeypatch.setattr(kinematic, "_past_a_hopeless_scheme", lambda *a: None)
    monkeypatch.setattr(kinematic._Drawings, "least_scheme", lambda self, mu: (0.0, 0.0))
    drawn.clear()
    assert kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang).svg() == passing_over
    assert fewer <= len(drawn)


def test_the_shaper_sheet_draws_one_scheme(monkeypatch):
    """The shaper's A1 sheet passes over the 1:2 scheme, whose plans cannot be good beside it,
    undrawn: its plans are good beside the 1:2.5 scheme, drawn alone."""
    drawn = []
    real = kinematic.mechanism_view
    monkeypatch.setattr(kinematic, "mechanism_view", lambda *a, **kw: drawn.append(kw["mu_l"]) or real(*a, **kw))
    sheet = kinematic.build_sheet(Study("shaper", n=12), fmt="A1", lang="en")
    assert drawn == [0.0025] == [sheet.scales["mu_l"]]
