"""The structure figure's layout (`figure_layout`: each panel drawn once for its box, the texts
placed round them) draws the figure `structure_view` draws; the box of its texts alone
(`FigureLayout.text_extent`) never exceeds the figure's; and the kinematic sheet that passes
over a size whose texts alone find no free spot, its panels undrawn in place, is the sheet that
draws it."""

import pytest

import velplan.views.structure as vs
from velplan.sheets import kinematic
from velplan.sheets.structure import _joints
from velplan.study import Study
from velplan.views.base import bounds_of

MECHS = ("shaper", "four-bar", "whitworth", "triad-press", "jaw-crusher", "slider-press")


@pytest.mark.parametrize("name", MECHS)
def test_text_extent_never_exceeds_the_figure(name):
    study = Study(name, n=12)
    joints = _joints(study)
    for kw in (dict(lang="en"), dict(lang="ru", title=False), dict(lang="zh", panel_mm=45.0, text_mm=2.5, title_mm=3.5)):
        layout = vs.figure_layout(study.mechanism, joints, **kw)
        scene = layout.scene()
        assert scene == vs.structure_view(study.mechanism, joints, **kw)
        x0, y0, x1, y1 = bounds_of(scene.primitives)
        w, h = layout.text_extent()
        assert 0.3 * (x1 - x0) < w <= x1 - x0
        assert (0.5 * (y1 - y0) if kw.get("title", True) else 0.0) < h <= y1 - y0  # the heading over the captions


@pytest.mark.parametrize("name,fmt,lang", [("shaper", "A1", "en"), ("whitworth", "A2", "ru"),
                                           ("triad-press", "A1", "zh"), ("four-bar", "A3", "uk")])
def test_sheet_is_the_same_without_the_text_extent(name, fmt, lang, monkeypatch):
    drawn = []
    real = vs._draw
    monkeypatch.setattr(vs, "_draw", lambda *a: drawn.append(1) or real(*a))
    with_bound = kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang).svg()
    fewer = len(drawn)
    monkeypatch.setattr(vs.FigureLayout, "text_extent", lambda self: (0.0, 0.0))
    drawn.clear()
    assert kinematic.build_sheet(Study(name, n=12), fmt=fmt, lang=lang).svg() == with_bound
    assert fewer <= len(drawn)


def test_the_shaper_sheet_draws_the_rejected_figure_once(monkeypatch):
    """On the shaper's A1 sheet the structure figure at 55 mm panels (letters 2.5 mm) is too
    tall for the free space: its panels are drawn once, for their boxes, not again in place."""
    drawn = []
    real = vs._draw
    monkeypatch.setattr(vs, "_draw", lambda *a: drawn.append(1) or real(*a))
    sheet = kinematic.build_sheet(Study("shaper", n=12), fmt="A1", lang="en")
    assert "structure" in sheet.views
    assert len(drawn) == 9  # three panels: once for the figure left out, twice for the one drawn
