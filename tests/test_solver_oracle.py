"""The analytic solver against an independent 50-digit reference (tests/oracle.py)."""

import math

import numpy as np
import pytest

import velplan
from tests import oracle
from tests.strategies import fixed_points

EXAMPLES = velplan.example_names()
ANGLES = [0.0, 0.7, 1.9, 3.3, 4.4, 5.8]


def _rel(a, b, scale):
    return abs(float(a) - float(b)) / scale


@pytest.mark.parametrize("name", EXAMPLES)
def test_velocities_and_accelerations_match_mpmath(name):
    mech = velplan.load(name)
    w1 = mech.crank.omega
    kin = velplan.solve(mech, ANGLES, epsilon1=0.0)
    vscale = abs(w1) * velplan.analysis.solver.length_scale(mech)
    ascale = w1**2 * velplan.analysis.solver.length_scale(mech)
    for i, phi in enumerate(ANGLES):
        pts, links = oracle.derivatives(mech, phi, w1)
        for pname, (x, y, vx, vy, ax, ay) in pts.items():
            j = kin.point_index[pname]
            assert _rel(kin.positions[i, j, 0], x, 1) < 1e-13
            assert _rel(kin.positions[i, j, 1], y, 1) < 1e-13
            for got, ref in zip(kin.velocities[i, j], (vx, vy)):
                assert _rel(got, ref, vscale) < 1e-9, (name, phi, pname)
            for got, ref in zip(kin.accelerations[i, j], (ax, ay)):
                assert _rel(got, ref, ascale) < 1e-9, (name, phi, pname)
        for lname, (_, w, e) in links.items():
            j = kin.link_index[lname]
            assert _rel(kin.omegas[i, j], w, abs(w1)) < 1e-9, (name, phi, lname)
            assert _rel(kin.epsilons[i, j], e, w1**2) < 1e-9, (name, phi, lname)


@pytest.mark.parametrize("name", EXAMPLES)
def test_loop_closures_hold_over_a_revolution(name):
    mech = velplan.load(name)
    phi = np.linspace(0, 2 * np.pi, 3601)
    kin = velplan.solve(mech, phi)
    assert kin.valid.all()
    P = kin.position
    for g in mech.groups:
        if g.kind == "RRR":
            (a, d), (l1, l2) = g.joints, g.lengths
            assert np.abs(np.hypot(*(P(g.point) - P(a)).T) - l1).max() < 1e-12
            assert np.abs(np.hypot(*(P(g.point) - P(d)).T) - l2).max() < 1e-12
        if g.kind == "RRP":
            assert np.abs(np.hypot(*(P(g.point) - P(g.joint)).T) - g.length).max() < 1e-12
    # rigid links: every pair of points fixed to one link keeps its distance
    for link, names in fixed_points(mech).items():
        for a in names:
            for b in names:
                d = np.hypot(*(P(a) - P(b)).T)
                assert np.ptp(d) < 1e-12, (name, link, a, b)


def test_shaper_stroke_and_K_match_closed_form():
    mech = velplan.load("shaper")
    s = velplan.stroke(mech)
    L1, L3, L6 = 0.1605, 0.6914, 0.370
    assert s.H == pytest.approx(2 * L3 * L1 / L6, rel=1e-14)
    psi = math.asin(L1 / L6)
    assert s.K == pytest.approx((math.pi + 2 * psi) / (math.pi - 2 * psi), rel=1e-13)
    # the extremes are where the crank is perpendicular to the bar
    assert math.degrees(s.start.phi) == pytest.approx(360 - math.degrees(psi), abs=1e-9)
    assert math.degrees(s.end.phi) == pytest.approx(180 + math.degrees(psi), abs=1e-9)
    assert velplan.reference_angle(mech) == pytest.approx(s.start.phi, abs=1e-15)


def test_extremes_are_roots_to_round_off():
    for name in EXAMPLES:
        mech = velplan.load(name)
        for q, roots in velplan.extremes(mech).items():
            kin = velplan.solve(mech, [e.phi for e in roots], omega1=1.0)
            for i, e in enumerate(roots):
                rate = kin.omegas[i, kin.link_index[q[5:]]] if q.startswith("link") else kin.slides[i, kin.slide_index[q[6:]], 1]
                assert abs(rate) < 1e-12, (name, q, e)


def test_press_rocker_extremes_at_0_and_180_degrees():
    s = velplan.stroke(velplan.load("press"))
    # K = 1: the working stroke starts at the given reference position (0°)
    assert math.degrees(s.start.phi) % 360 == pytest.approx(0.0, abs=1e-7) or \
        math.degrees(s.start.phi) % 360 == pytest.approx(360.0, abs=1e-7)
    assert math.degrees(s.end.phi) == pytest.approx(180.0, abs=1e-7)
    assert s.K == pytest.approx(1.0, abs=1e-12)
    assert s.H == pytest.approx(0.10, abs=1e-12)


def test_seed_002_mobility():
    st = velplan.structure(velplan.load("shaper"))
    assert (st.n_links, st.p5, st.mobility) == (5, 7, 1)
    assert st.formula() == "W = 3·5 − 2·7 − 0 = 1"
    assert [g[1] for g in st.groups] == ["RPR", "RRP"]


@pytest.mark.parametrize("delta", [1e-2, 1e-3, 1e-4, 1e-5, 1e-6])
def test_error_near_a_toggle_stays_within_the_stated_bound(delta):
    """Offset crank-slider with l = r + e: the rod stands ⊥ its guide at φ = 90°."""
    from tests.plans.test_plan_features import _toggle_slider

    mech = _toggle_slider()
    phi = math.pi / 2 - delta
    kin = velplan.solve(mech, [phi])
    pts, _ = oracle.derivatives(mech, phi, mech.crank.omega)
    L, w = velplan.analysis.solver.length_scale(mech), mech.crank.omega
    x, y, vx, vy, ax, ay = (float(v) for v in pts["B"])
    j = kin.point_index["B"]
    assert abs(kin.positions[0, j, 0] - x) / L <= kin.error_bound("position")[0]
    assert abs(kin.velocities[0, j, 0] - vx) / (w * L) <= kin.error_bound("velocity")[0]
    assert abs(kin.accelerations[0, j, 0] - ax) / (w * w * L) <= kin.error_bound("acceleration")[0]
    # and the condition estimate is the sine of the rod's angle to the guide's normal, ∝ δ
    assert kin.condition[0, 0] == pytest.approx(0.845 * delta, rel=2e-2)
