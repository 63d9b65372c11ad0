"""Zhukovsky's lever as drawn reads the force analysis: the numbers written and the arrows
drawn are `ForceAnalysis.lever`'s, and the drawn lever is in balance about its pole."""

import ast
import math
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.plans import standard_scale
from velplan.render.scene import Arrow
from velplan.study import Study
from velplan.views.base import number
from velplan.views.forces import lever_layers, lever_view

#: Mechanisms with loads, inertia, a couple on a rocking link and a class III group.
NAMES = ("shaper", "press", "slider-press", "triad-press", "whitworth")


def _cross(p, f) -> float:
    return float(p[0] * f.imag - p[1] * f.real)


@pytest.fixture(scope="module", params=NAMES)
def case(request):
    """(force analysis, position index, lever view) at the largest |M_b|, drawn at a μv that
    is not the analysis' own, so that reading the lever at the drawing's scale is exercised."""
    fa = Study(velplan.load(request.param), n=12).forces()
    i = int(np.nanargmax(np.abs(fa.kinetostatics.balancing_moment)))
    mu_v = standard_scale(fa.lever.scale * 1.0001)  # the next standard scale
    return fa, i, lever_view(fa, i + 1, mu_v=mu_v, lang="en")


def test_the_numbers_written_are_the_force_analysis(case):
    fa, i, view = case
    mb = float(fa.lever.balancing_moment[i])
    fb = float(fa.lever.balancing_force[i])
    assert view.meta["mb_lever"] == pytest.approx(mb, rel=1e-12)
    assert view.meta["mb_kinetostatics"] == pytest.approx(float(fa.kinetostatics.balancing_moment[i]),
                                                          rel=1e-12)
    assert view.meta["balancing_force"] == pytest.approx(fb, rel=1e-12)
    assert view.meta["percent"] == pytest.approx(float(fa.lever_difference_percent[i]), abs=1e-9)
    texts = " ".join(p.text for p in view.primitives if hasattr(p, "text"))
    assert f"F_{{b}} = {number(abs(fb), 'en')} N" in texts  # indices set below the line
    assert f"M_{{b}} = {number(mb, 'en')} N·m (lever)" in texts


def test_the_forces_drawn_are_the_lever_forces_at_the_drawing_scale(case):
    fa, i, view = case
    r = fa.lever.scale / view.meta["mu_v"]
    expected = {f.label: (complex(f.image[i]) * r, complex(f.vector[i])) for f in fa.lever.forces}
    drawn = view.meta["forces"]
    assert drawn
    for name, image, force in drawn:
        want_image, want_force = expected[name]
        assert complex(*image) == pytest.approx(want_image, rel=1e-12, abs=1e-9)
        assert force == pytest.approx(want_force, rel=1e-12, abs=1e-9)


def test_the_drawn_lever_balances_about_its_pole(case):
    """Σ of the moments of the drawn forces about the pole plus that of F_b at the crank tip's
    image is nil, with F_b ⊥ OA computed here from the positions."""
    fa, i, view = case
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    o, a = (complex(*kin.position(p)[i]) for p in (mech.crank.pivot, mech.crank.tip))
    e = 1j * (a - o) / abs(a - o)
    r = fa.lever.scale / view.meta["mu_v"]
    tip = 1j * complex(*kin.velocity(mech.crank.tip)[i]) / view.meta["mu_v"]  # turned image, mm
    fb = view.meta["balancing_force"]
    total = sum(_cross(p, f) for _, p, f in view.meta["forces"])
    scale = sum(abs(_cross(p, f)) for _, p, f in view.meta["forces"])
    assert total + _cross((tip.real, tip.imag), fb * e) == pytest.approx(0.0, abs=1e-9 * scale)
    assert fb * abs(a - o) == pytest.approx(view.meta["mb_lever"], rel=1e-9)
    assert abs(complex(fa.lever.tip_image[i]) * r - tip) < 1e-9 * abs(tip)
    # the thick arrow is F_b, drawn along ±e in the sense of its sign
    _, force_layer, _ = lever_layers(i + 1)
    thick = [p for p in view.primitives if isinstance(p, Arrow) and p.layer == force_layer
             and p.line == "thick"]
    assert len(thick) == 1
    d = np.asarray(thick[0].end) - np.asarray(thick[0].start)
    assert complex(*d) / abs(complex(*d)) == pytest.approx(e * math.copysign(1.0, fb), abs=1e-9)


def test_the_lever_at_another_scale_keeps_its_balance():
    fa = Study(velplan.load("shaper"), n=12).forces()
    lever = fa.lever.at_scale(fa.lever.scale / 2.5)
    assert lever.scale == pytest.approx(fa.lever.scale / 2.5)
    np.testing.assert_allclose(lever.tip_image, 2.5 * fa.lever.tip_image, rtol=1e-12)
    for f, g in zip(lever.forces, fa.lever.forces):
        np.testing.assert_allclose(f.moment, 2.5 * g.moment, rtol=1e-12, atol=1e-12)
        np.testing.assert_array_equal(f.vector, g.vector)
    np.testing.assert_array_equal(lever.balancing_force, fa.lever.balancing_force)
    assert fa.lever.at_scale(fa.lever.scale) is fa.lever


def test_the_lever_direction_is_perpendicular_to_the_crank():
    fa = Study(velplan.load("press"), n=12).forces()
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    crank = (kin.position(mech.crank.tip) - kin.position(mech.crank.pivot)) @ np.array([1, 1j])
    np.testing.assert_allclose(np.abs(fa.lever.direction), 1.0, rtol=1e-12)
    np.testing.assert_allclose((fa.lever.direction / crank).real, 0.0, atol=1e-12)
    np.testing.assert_allclose((fa.lever.direction / crank).imag, 1.0 / np.abs(crank), rtol=1e-12)


def test_the_force_views_solve_nothing():
    """The force views import no solver: the lever, the kinetostatics, the kinematics and the
    per-cent difference are read from the force analysis."""
    package = Path(velplan.__file__).parent / "views" / "forces"
    solvers = {"zhukovsky_lever", "kinetostatics", "solve", "lever_difference_percent",
               "force_analysis", "force_analysis_at", "images_from_plan"}
    for path in package.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text("utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("velplan."):
                names = {a.name for a in node.names}
                assert not names & solvers, f"{path.name} imports {names & solvers}"
