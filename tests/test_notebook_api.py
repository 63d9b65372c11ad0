"""The notebook layer: SvgDrawing, the drawing functions and the crank slider."""

from __future__ import annotations

import math
import subprocess
import sys
import types

import numpy as np
import pytest

import velplan
from velplan.errors import VelplanError
from velplan.notebook import (
    SvgDrawing, crank_slider, draw_diagrams, draw_mechanism, draw_plan, draw_sheet, draw_steps,
    side_by_side)
from velplan.views.plan import plan_view
from velplan.render.scene import Arrow, Circle, Polyline, Text


@pytest.fixture(scope="module")
def press():
    study = velplan.Study("press")
    res = study.plan("velocity", positions=[3], scale_v=0.0007)    # position 3 alone
    return study.mechanism, study.kinematics, res


@pytest.fixture(scope="module")
def shaper_acc():
    return velplan.Study("shaper").plan("acceleration", positions=[3], scale_v=0.02, scale_a=0.1)


def _arrows(d: SvgDrawing) -> list[Arrow]:
    return [p for p in d.scene.primitives if isinstance(p, Arrow)]


def _pole(d: SvgDrawing) -> np.ndarray:
    dots = [p for p in d.scene.primitives if isinstance(p, Circle)]
    return np.array(max(dots, key=lambda c: c.radius).centre)  # the pole's dot: the images' are smaller


# -- SvgDrawing ---------------------------------------------------------------------------------

def test_svg_drawing_shows_and_saves(tmp_path, press):
    d = draw_plan(press[2])
    assert d._repr_svg_() == d.svg and d.svg.startswith("<?xml") and "<svg" in d.svg
    assert 'width="' in d.svg and 'mm"' in d.svg     # sized in millimetres
    svg = d.save(tmp_path / "plan.svg")
    assert svg.read_text("utf-8") == d.svg
    assert d.save(tmp_path / "plan.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert d.save(tmp_path / "plan.pdf").read_bytes()[:4] == b"%PDF"
    assert d.png()[:4] == b"\x89PNG"
    again = SvgDrawing.from_file(svg)
    assert again.svg == d.svg and again.scene is None and again.size_mm is None
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plan.pdf", "plan.png", "plan.svg"]


def test_svg_drawing_errors(tmp_path, press):
    d = draw_plan(press[2])
    with pytest.raises(VelplanError, match="use .svg, .png or .pdf"):
        d.save(tmp_path / "plan.txt")
    with pytest.raises(VelplanError, match="does not exist"):
        d.save(tmp_path / "missing" / "plan.svg")
    with pytest.raises(VelplanError, match="cannot read drawing"):
        SvgDrawing.from_file(tmp_path / "nothing.svg")
    assert list(tmp_path.iterdir()) == []


# -- the mechanism --------------------------------------------------------------------------------

def test_draw_mechanism(press):
    mech, kin, _ = press
    d = draw_mechanism(mech, kin, position=3)
    layers = d.scene.layers
    assert {"mechanism", "positions", "labels"} <= set(layers)
    texts = [t.text for t in d.scene.of_kind(Text)]
    assert any("μl = 0.005 m/mm" in t for t in texts)   # English, decimal point
    alone = draw_mechanism(mech, kin, position=3, single=True)
    assert "positions" not in alone.scene.layers and "trajectory" not in alone.scene.layers
    assert any(t.text == "Position 3" for t in alone.scene.of_kind(Text))
    default = draw_mechanism(mech)                       # 12 positions, position 1 thick
    assert default.scene.layers == draw_mechanism(mech, kin, position=1).scene.layers


def test_draw_mechanism_errors(press):
    mech, kin, _ = press
    for bad in (0, 13):
        with pytest.raises(VelplanError, match=rf"^position {bad} is outside 1…12 "):
            draw_mechanism(mech, kin, position=bad)
    with pytest.raises(TypeError):       # a former index, passed positionally, is refused
        draw_mechanism(mech, kin, 2)


# -- the plan and its steps ---------------------------------------------------------------------

def test_draw_plan_is_the_plan_view(press):
    res = press[2]
    d = draw_plan(res)
    view = plan_view(res, 3, lang="en")
    assert d.scene.primitives == draw_plan(res, position=3).scene.primitives
    assert d.scene.primitives == view.primitives
    assert d.size_mm == (view.width_mm, view.height_mm)
    assert any(t.text == "Velocity plan (pos. 3)" for t in d.scene.of_kind(Text))


def test_draw_plan_upto_draws_the_first_steps(press):
    res = press[2]
    full = draw_plan(res)
    counts = [len(_arrows(draw_plan(res, upto=k))) for k in range(1, 16)]
    assert counts == sorted(counts) and counts[0] == 0
    assert counts[-1] == len(_arrows(full))
    first = draw_plan(res, upto=2)          # the pole and pa
    assert first.size_mm == full.size_mm    # every step in the full plan's frame
    (pa,) = _arrows(first)
    assert pa.line == "thick"
    assert math.isclose(pa.length, res.segments["pa"][0], rel_tol=1e-9)       # 71.43 mm
    assert np.allclose(pa.start, _pole(first))
    assert np.allclose(np.subtract(pa.end, pa.start), res.images["A"][0])
    letters = {t.text for t in first.scene.of_kind(Text)}
    assert {"p", "a"} <= letters and "c" not in letters
    with pytest.raises(VelplanError, match=r"upto=16: this plan has steps 1…15"):
        draw_plan(res, upto=16)
    with pytest.raises(VelplanError, match=r"upto=0"):
        draw_plan(res, upto=0)
    with pytest.raises(VelplanError, match=r"^position 2 is not in this plan \(its positions: 3\)$"):
        draw_plan(res, position=2)
    with pytest.raises(VelplanError, match=r"^position 0 is outside 1…12 "):
        draw_plan(res, position=0)


def test_draw_steps_pairs_each_sentence_with_its_drawing(press):
    res = press[2]
    steps = list(draw_steps(res, position=3))
    assert [s for s, _ in steps] == res.describe(lang="en")
    assert [s for s, _ in draw_steps(res, lang="ru")] == res.describe(lang="ru")
    # step 5, "The two lines meet at c": the vectors ac and pc are new (thick) and end at c
    sentence, d = steps[4]
    assert sentence.startswith("The two lines meet at c")
    pole = _pole(d)
    c = pole + res.images["C"][0]
    thick = [a for a in _arrows(d) if a.line == "thick"]
    assert len(thick) == 2 and all(np.allclose(a.end, c) for a in thick)
    assert sorted(round(a.length, 6) for a in thick) == sorted(
        round(float(res.segments[s][0]), 6) for s in ("ac", "pc"))
    # the earlier vector pa is thin now
    assert [a.line for a in _arrows(d) if np.allclose(a.end, pole + res.images["A"][0])] == ["thin"]
    # a line step adds a thin construction line and no arrow
    sentence, d = steps[2]
    assert sentence.startswith("Through a draw a line ⊥ CA")
    assert len(_arrows(d)) == 1
    assert [p.line for p in d.scene.primitives if isinstance(p, Polyline)] == ["thick"]


def test_coriolis_step_is_drawn_along_v_rel_turned(shaper_acc):
    res = shaper_acc
    steps = list(draw_steps(res))
    k = next(j for j, (s, _) in enumerate(steps) if "turned 90°" in s)
    sentence, d = steps[k]
    pole = _pole(d)
    (new,) = [a for a in _arrows(d) if a.line == "thick"]
    assert np.allclose(new.start, pole + res.images["A"][0])
    assert np.allclose(new.end, pole + res.images["k1"][0])
    assert math.isclose(new.length * res.scale, res.components["aᵏ_A4A"][1][0], rel_tol=1e-9)


# -- side by side, the slider ------------------------------------------------------------------

def test_side_by_side(press):
    a, b = draw_plan(press[2]), draw_mechanism(press[0], press[1], position=3, single=True)
    row = side_by_side(a, b, gap_mm=5.0)
    assert row.size_mm == pytest.approx((a.size_mm[0] + 5.0 + b.size_mm[0], max(a.size_mm[1], b.size_mm[1])))
    assert len(row.scene) == len(a.scene) + len(b.scene)
    with pytest.raises(VelplanError, match="needs drawings made by velplan.notebook"):
        side_by_side(a, SvgDrawing("<svg/>"))
    with pytest.raises(VelplanError, match="at least one"):
        side_by_side()


def test_crank_slider_static_fallback(press):
    mech = press[0]
    row = crank_slider(mech, interactive=False, fallback=4)
    titles = [t.text for t in row.scene.of_kind(Text) if t.text.startswith("Position")]
    assert titles == ["Position 1", "Position 4", "Position 7", "Position 10"]
    seen = []

    def callback(kin):
        seen.append(float(kin.phi[0]))
        return draw_mechanism(mech, kin, single=True)

    crank_slider(mech, callback, interactive=False, n=12, fallback=3)
    phi = velplan.positions(mech, 12)
    assert np.allclose(seen, phi[[0, 4, 8]])


def test_crank_slider_without_ipywidgets(monkeypatch, press):
    monkeypatch.setitem(sys.modules, "ipywidgets", None)   # import fails
    assert isinstance(crank_slider(press[0], fallback=2), SvgDrawing)
    with pytest.raises(VelplanError, match="needs ipywidgets"):
        crank_slider(press[0], interactive=True)


def test_crank_slider_with_ipywidgets(monkeypatch, press):
    made = {}
    fake = types.ModuleType("ipywidgets")

    class FloatSlider:
        def __init__(self, **kw):
            made["slider"] = kw

    def interactive(f, **kw):
        made["function"], made["controls"] = f, kw
        return "widget"

    fake.FloatSlider, fake.interactive = FloatSlider, interactive
    monkeypatch.setitem(sys.modules, "ipywidgets", fake)
    shown = []
    import IPython.display

    monkeypatch.setattr(IPython.display, "display", shown.append)
    angles = []

    def callback(kin):
        angles.append(float(kin.phi[0]))
        return "drawing"

    mech = press[0]
    assert crank_slider(mech, callback, n=12) == "widget"
    assert made["slider"]["min"] == 0.0 and made["slider"]["max"] == 330.0
    assert made["slider"]["step"] == 30.0
    made["function"](90.0)
    assert shown == ["drawing"]
    assert math.isclose(angles[0], velplan.positions(mech, 12)[3])


def test_crank_slider_errors(press):
    with pytest.raises(VelplanError, match="n ≥ 1 and fallback ≥ 1"):
        crank_slider(press[0], n=0)


# -- sheet and diagrams ---------------------------------------------------------------------------

def test_draw_sheet_and_diagrams():
    sheet = draw_sheet("crank-slider", fmt="A3", lang="en")
    assert sheet.size_mm == (420.0, 297.0) and "<svg" in sheet.svg
    diagrams = draw_diagrams(velplan.load("crank-slider"), 12)
    assert "diagram" in diagrams.scene.layers


def test_importing_the_notebook_layer_is_cheap():
    code = ("import sys, velplan.notebook; "
            "print(any(m.startswith(('velplan.render', 'svgwrite', 'matplotlib', 'IPython')) "
            "for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
