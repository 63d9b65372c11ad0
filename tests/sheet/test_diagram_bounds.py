"""The kinematic diagrams' least row width (`least_row_width`, no curves drawn) never exceeds
the row drawn, and the sheet that skips the φ axes it rules out is the sheet drawn without it."""

import pytest

from velplan.sheets import kinematic
from velplan.study import Study
from tests.sheet.helpers import calls_with_and_without
from velplan.views.diagram import DiagramSizes, diagram_view, least_row_width

MECHS = ("shaper", "four-bar", "press", "whitworth", "crank-slider", "triad-press")


@pytest.mark.parametrize("name", MECHS)
def test_least_row_width_never_exceeds_the_drawing(name):
    study = Study(name, n=12)
    for omega in (study.mechanism.crank.omega, 0.0):  # read in time, and as analogues
        for length in (60.0, 144.0, 240.0):
            for height in (20.0, 60.0):
                for lang, sizes in (("ru", DiagramSizes(3.5, 2.5)), ("zh", DiagramSizes(2.5, 1.8))):
                    kw = dict(length_mm=length, height_mm=height, lang=lang, sizes=sizes, omega=omega)
                    view = diagram_view(study.diagrams, arrangement="row", **kw)
                    w = least_row_width(study.diagrams, **kw)
                    assert 3 * length < w <= view.width_mm * (1 + 1e-12)


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "ru"), ("press", "A2", "en"),
                                           ("four-bar", "A3", "zh"), ("whitworth", "A1", "uk")])
def test_sheet_is_the_same_without_the_least_width(name, fmt, lang, monkeypatch):
    bounded, every = calls_with_and_without(
        monkeypatch, lambda: kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang), "diagram_view",
        [(kinematic._Drawings, "least_width", lambda self, *a: None)])
    assert bounded <= every
    if (name, fmt) == ("shaper", "A1"):  # the row at a 144 mm axis is wider than the band
        assert bounded < every
