"""The chord method against closed forms, and the kinematic diagrams of the examples."""

import math
import re

import numpy as np
import pytest

import velplan
from velplan.analysis.chord import (
    chord_method, chord_ordinates_mm, closed_form_diagrams, kinematic_diagrams)
from velplan.views.diagram import choose_scales
from velplan.views.diagram import diagram_view
from velplan.render.scene import Text


def test_chord_slopes_sit_at_mid_intervals():
    h = 2 * math.pi / 12
    mid, slope = chord_method(np.sin(np.arange(12) * h), h)
    assert np.allclose(mid, (np.arange(12) + 0.5) * h)
    # exact: the chord slope of sin is cos(mid)·sin(h/2)/(h/2)
    assert np.allclose(slope, np.cos(mid) * math.sin(h / 2) / (h / 2))


@pytest.mark.parametrize("n", [12, 24, 48, 96])
def test_chord_error_of_sine_is_h2_over_24(n):
    d = closed_form_diagrams(np.sin, np.cos, lambda x: -np.sin(x), n)
    h = 2 * math.pi / n
    shrink = 1 - math.sin(h / 2) / (h / 2)
    assert d.error_v == pytest.approx(shrink * np.max(np.abs(np.cos(d.phi_mid))), rel=1e-9)
    assert d.error_v == pytest.approx(h * h / 24 * np.max(np.abs(np.cos(d.phi_mid))), rel=0.02)


def test_errors_fall_as_positions_increase():
    errs = [closed_form_diagrams(np.sin, np.cos, lambda x: -np.sin(x), n) for n in (12, 24, 48)]
    assert errs[0].error_v > errs[1].error_v > errs[2].error_v
    assert errs[0].error_a > errs[1].error_a > errs[2].error_a
    # second order: halving the step quarters the error
    assert errs[0].error_v / errs[1].error_v == pytest.approx(4, rel=0.05)
    shaper = [kinematic_diagrams(velplan.load("shaper"), n) for n in (12, 24, 48)]
    assert shaper[0].error_v > shaper[1].error_v > shaper[2].error_v


def test_drawn_ordinates_times_derived_scale_give_the_slope():
    d = kinematic_diagrams(velplan.load("crank-slider"), 12)
    sc = choose_scales(d, length_mm=180.0, height_mm=40.0)
    assert sc.mu_phi == pytest.approx(2 * math.pi / 180.0)
    assert sc.mu_v == pytest.approx(sc.mu_s / (sc.mu_phi * sc.H_v))
    assert sc.mu_a == pytest.approx(sc.mu_v / (sc.mu_phi * sc.H_a))
    y_mm = chord_ordinates_mm(d.s / sc.mu_s, d.step / sc.mu_phi, sc.H_v)
    assert np.allclose(y_mm * sc.mu_v, d.v_chord)
    assert np.max(np.abs(d.v_exact)) / sc.mu_v <= 40.0 + 1e-9


def test_displacement_starts_at_zero_and_matches_the_stroke():
    mech = velplan.load("shaper")
    d = kinematic_diagrams(mech, 12)
    assert d.s[0] == 0.0 and d.quantity == "point F"
    assert np.max(d.s_exact) == pytest.approx(velplan.stroke(mech).H, rel=1e-3)
    rocker = kinematic_diagrams(velplan.load("four-bar"), 12)
    assert rocker.angular and np.max(rocker.s_exact) == pytest.approx(
        velplan.stroke(velplan.load("four-bar")).H, rel=1e-3)


def test_diagram_view_writes_h_scales_and_error():
    d = kinematic_diagrams(velplan.load("press"), 12)
    view = diagram_view(d, lang="en", arrangement="column")
    texts = "\n".join(t.text for t in view.primitives if isinstance(t, Text))
    sc = view.meta["scales"]
    assert f"H = {sc.H_v:g} mm" in texts and f"H = {sc.H_a:g} mm" in texts
    assert "μv = μs/(μφ·H)" in texts and "μa = μv/(μφ·H)" in texts
    assert f"δ = {100 * d.error_v:.2g} %" in texts or f"δ = {100 * d.error_v:.3g} %" in texts


def test_diagrams_read_in_time_give_the_solver_speed():
    """With ω1 the velocity diagram is V = ω1·dS/dφ at μv = μs/(μt·H), μt = μφ/ω1: its analytic
    curve, read at the printed μv, is the ram's speed along its guide from the solver."""
    study = velplan.Study("shaper")
    w = abs(study.mechanism.crank.omega)
    view = diagram_view(study.diagrams, lang="en", arrangement="column", omega=w)
    sc = view.meta["scales"]
    texts = [t.text for t in view.primitives if isinstance(t, Text)]
    mu_v = sc.mu_v * w
    assert any(f"μv = μs/(μt·H) = {mu_v:.3g}" in t for t in texts)
    assert any(f"μt = μφ/ω1 = {sc.mu_phi / w:.3g} s/mm" in t for t in texts)
    d = study.diagrams
    turn = velplan.solve(study.mechanism, study.phi[0] + study.sense * d.phi_fine)
    vx = turn.velocity("F")[:, 0]  # the ram runs along x
    sign = np.sign(np.dot(vx, d.v_exact))
    assert np.allclose(sign * vx, w * d.v_exact, atol=1e-9 * np.abs(vx).max())


def test_sheet_carries_input_data_and_the_other_extreme():
    from velplan.sheets.kinematic import build_sheet, sheet_text

    study = velplan.Study("shaper")
    sheet = build_sheet(study, lang="en")
    st = study.stroke
    text = sheet_text(sheet)
    assert "Input data and results" in text
    assert f"H = {st.H:.4g} m; θ = {math.degrees(st.theta):.4g}°; K = {st.K:.4g}" in text
    assert "lO₂A = 0.1605 m" in text and "Fc = 1400 N" in text
    # the end of the working stroke is not one of the 12 positions: drawn bold, marked 1′
    assert study.other_extreme is not None
    bold = [p for p in sheet.views["mechanism"].view.primitives
            if getattr(p, "line", None) == "thick" and p.layer == "positions"]
    assert bold and "1′" in text
    end = study.other_extreme.position("F")[0]
    assert abs(end[0] - study.mechanism.ground[0][1][0]) >= 0  # solved at the extreme
    v = velplan.solve(study.mechanism, [st.end.phi]).velocity("F")[0]
    assert np.hypot(*v) < 1e-9 * abs(study.mechanism.crank.omega)


def test_step_captions_are_written_as_by_hand_and_the_series_has_one_page_size():
    from velplan.views.steps import readable, step_figures

    assert readable("Через точку a проводим прямую ∥ O3A (направление V_A4A).") == \
        "Через точку a проводим прямую ∥ O₃A (направление v_{A4A})."  # the whole index below v
    assert readable("отрезок ak1 = 37,1 мм по V_отн (aⁿ_A4O3 = 2,237 м/с²), шаг 3/14") == \
        "отрезок ak₁ = 37,1 мм по v_{отн} (aⁿ_{A4O3} = 2,237 м/с²), шаг 3/14"
    study = velplan.Study("shaper")
    figs = step_figures(study.mechanism, study.kinematics,
                        {k: study.plan(k) for k in ("velocity", "acceleration")}, 3, lang="ru")
    assert len({(f.scene.width_mm, f.scene.height_mm) for f in figs}) == 1
    for f in figs:
        text = " ".join(t.text for t in f.scene.primitives if isinstance(t, Text) and t.layer == "labels")
        assert "_" not in re.sub(r"_\{[^{}]*\}", "", text)  # only whole indices v_{BA}
