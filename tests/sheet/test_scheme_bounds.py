"""A scheme's least size (`least_scheme_size`: its positions' lines, margin and title, no
letters) never exceeds its drawing (the plans' score bounds: test_plan_bounds.py); and the kinematic sheet
that passes over a scheme that cannot be chosen, undrawn, is the sheet that draws it."""

import pytest

from velplan.sheets import kinematic
from velplan.study import Study
from tests.sheet.helpers import calls_with_and_without
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


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "ru"), ("whitworth", "A1", "en"),
                                           ("four-bar", "A2", "uk"), ("slider-press", "A1", "en"),
                                           ("jaw-crusher", "A3", "zh"), ("triad-press", "A3", "en")])
def test_sheet_is_the_same_with_every_scheme_drawn(name, fmt, lang, monkeypatch):
    fewer, every = calls_with_and_without(
        monkeypatch, lambda: kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang), "mechanism_view",
        [(kinematic, "_past_a_hopeless_scheme", lambda *a: None),
         (kinematic._Drawings, "least_scheme", lambda self, mu: (0.0, 0.0))])
    assert fewer <= every


def test_the_shaper_sheet_draws_one_scheme(monkeypatch):
    """The shaper's A1 sheet passes over the 1:2 scheme, whose plans cannot be good beside it,
    undrawn: its plans are good beside the 1:2.5 scheme, drawn alone."""
    drawn = []
    real = kinematic.mechanism_view
    monkeypatch.setattr(kinematic, "mechanism_view", lambda *a, **kw: drawn.append(kw["mu_l"]) or real(*a, **kw))
    sheet = kinematic.build_sheet(Study("shaper", n=12), fmt="A1", lang="en")
    assert drawn == [0.0025] == [sheet.scales["mu_l"]]
