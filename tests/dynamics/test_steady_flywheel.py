"""Steady state and flywheel: the energy equation against Lagrange's equation integrated by an
independent ODE solver on exact solver values, zero cycle work, periodicity, and the three
flywheel methods on published textbook examples."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import velplan
from velplan.dynamics import dynamics_analysis
from velplan.dynamics.flywheel import dimensions, exact_inertia, mertsalov_inertia, size_flywheel, wittenbauer
from velplan.dynamics.spec import FlywheelSpec
from velplan.dynamics.steady import EnergyCurve, steady_state


@pytest.fixture(scope="module")
def shaper():
    return dynamics_analysis(velplan.load("shaper"), delta=0.05)


def test_energy_equation_agrees_with_lagrange_integrated_to_1e9(shaper):
    d = shaper
    red, J_I, Md = d.reducer, d.inertia, d.driving
    st = d.steady

    def f(theta, y):  # Lagrange in travel: J·w·dw/dθ + ½J′w² = M, values solved exactly per call
        r = red(np.array([theta]))
        w = y[0]
        return [(Md + r.resisting[0] - 0.5 * r.dJ[0] * w * w) / ((J_I + r.J[0]) * w)]

    breaks = np.unique(np.concatenate(([0.0, 2 * np.pi], red.breakpoints())))
    check = np.arange(12) * (2 * np.pi / 12)
    w = [float(st.omega(0.0))]
    got, want = [], []
    for a, b in zip(breaks[:-1], breaks[1:]):
        inside = check[(check > a) & (check < b)]
        sol = solve_ivp(f, (a, b), w, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=np.append(inside, b))
        got += list(sol.y[0, :-1])
        want += list(st.omega(inside))
        w = [sol.y[0, -1]]
    got, want = np.array(got), np.array(want)
    assert np.max(np.abs(got - want) / want) < 1e-9
    # after the cycle: periodic
    assert abs(w[0] - st.omega(0.0)) / st.omega(0.0) < 1e-9


def test_zero_cycle_work_periodicity_and_delta(shaper):
    d = shaper
    st = d.steady
    works = sum(d.profile.cycle_work().values())
    assert abs(d.driving * 2 * np.pi + works) <= 1e-12 * abs(works)
    assert abs(st.omega(2 * np.pi) - st.omega(0.0)) <= 1e-12 * st.omega(0.0)
    assert abs(st.delta - 0.05) < 1e-12
    assert abs(st.omega_mean - 80 * math.pi / 30) < 1e-12
    # the extremes are stationary points of ω (or a kink of A): no grid value beyond them
    th = np.linspace(0, 2 * np.pi, 20001)
    w = st.omega(th)
    assert w.max() <= st.omega_max * (1 + 1e-14) and w.min() >= st.omega_min * (1 - 1e-14)
    # ε from Lagrange equals dω/dt = w·dw/dθ by differences
    h = 1e-6
    t0 = 1.0
    num = st.omega(t0) * (st.omega(t0 + h) - st.omega(t0 - h)) / (2 * h)
    assert abs(num - st.epsilon(t0)) < 1e-6
    # t(θ): the period equals ∫dθ/w by a fine midpoint rule
    mid = (th[:-1] + th[1:]) / 2
    assert abs(np.sum(np.diff(th) / st.omega(mid)) - st.period) < 1e-8


def test_three_flywheel_methods_side_by_side(shaper):
    f = shaper.flywheel
    assert abs(f.wittenbauer - f.exact) <= 1e-12 * f.exact  # the same tangents, computed
    assert abs(f.diagram.inertia_drawn - f.exact) <= f.diagram.mu_T * 0.25 / (f.omega_mean**2 * f.delta) * 1.000001
    assert 0.02 < f.mertsalov_difference < 0.06  # Mertsalov over-estimates by ≈ 4.2 % here
    dm = f.dimensions
    assert dm.inertia >= f.on_shaft and dm.inertia < f.on_shaft * 1.02


def _constant_inertia_curve(breaks, moments):
    """J_II ≡ 0 and a piecewise constant moment (a turning-moment diagram)."""
    breaks = np.asarray(breaks, float)
    moments = np.asarray(moments, float)
    edge_A = np.concatenate(([0.0], np.cumsum(np.diff(breaks) * moments)))
    idx = lambda t: np.clip(np.searchsorted(breaks, t, side="right") - 1, 0, len(moments) - 1)  # noqa: E731
    A = lambda t: edge_A[idx(t)] + moments[idx(t)] * (np.asarray(t) - breaks[idx(t)])  # noqa: E731
    M = lambda t: moments[idx(t)]  # noqa: E731
    zero = lambda t: np.zeros(np.shape(t))  # noqa: E731
    grid = np.unique(np.concatenate((breaks, np.linspace(breaks[0], breaks[-1], 721))))
    return EnergyCurve(grid, A, M, zero, zero)


def test_textbook_flywheel_6_5_t_radius_of_gyration_1_8_m():
    # Khurmi & Gupta, Theory of Machines, flywheel of 6.5 t, k = 1.8 m, ΔE = 56 kN·m at
    # 120 rpm: N_max = 121.01 rpm, N_min = 118.99 rpm (printed).
    J = 6500 * 1.8**2
    wm = 120 * math.pi / 30
    dE = 56e3
    curve = _constant_inertia_curve([0, math.pi, 2 * math.pi], [dE / math.pi, -dE / math.pi])
    delta = dE / (J * wm**2)
    for method in (exact_inertia, mertsalov_inertia):
        assert abs(method(curve, wm, delta) - J) <= 1e-10 * J
    assert abs(wittenbauer(curve, wm, delta).inertia - J) <= 1e-10 * J
    st = steady_state(curve, wm, J, 0.0, 2 * math.pi)
    assert f"{st.omega_max * 30 / math.pi:.2f}" == "121.01"
    assert f"{st.omega_min * 30 / math.pi:.2f}" == "118.99"


def test_textbook_turning_moment_diagram_petrol_engine():
    # Khurmi & Gupta: turning-moment diagram at 1 mm = 5 N·m and 1 mm = 1°, areas above and
    # below the mean line 295, −685, 40, −340, 960, −270 mm² (per half turn), rotating parts
    # 36 kg at k = 150 mm, 1800 rpm: coefficient of fluctuation of speed 0.003 (printed).
    mm2 = 5 * math.pi / 180
    areas = np.array([295, -685, 40, -340, 960, -270]) * mm2
    widths = np.full(6, math.pi / 6)
    breaks = np.concatenate(([0.0], np.cumsum(widths)))
    curve = _constant_inertia_curve(breaks, areas / widths)
    J, wm = 36 * 0.15**2, 1800 * math.pi / 30
    st = steady_state(curve, wm, J, 0.0, math.pi)
    assert f"{st.delta:.3f}" == "0.003"
    # and back: the flywheel for that δ is the given one, by all three methods
    for value in (exact_inertia(curve, wm, st.delta), mertsalov_inertia(curve, wm, st.delta),
                  wittenbauer(curve, wm, st.delta).inertia):
        assert abs(value - J) <= 1e-9 * J


def test_disc_and_rim_dimensions_recomputed():
    disc = dimensions(21060.0, FlywheelSpec(shape="disc", density=7800.0, width_ratio=0.2))
    assert disc.inertia >= 21060.0 and abs(disc.inertia - disc.mass * disc.diameter**2 / 8) < 1e-9 * disc.inertia
    rim = dimensions(100.0, FlywheelSpec(shape="rim", width_ratio=0.2, thickness_ratio=0.1))
    assert rim.inertia >= 100.0 and rim.inertia < 103.0
    assert abs(rim.inertia - rim.mass * (rim.outer**2 + rim.inner**2) / 8) < 1e-9 * rim.inertia


def test_flywheel_on_a_geared_shaft_after_declared_inertias(with_dynamics):
    path = with_dynamics("shaper", """
[dynamics]
delta = 0.05

[[dynamics.inertia]]
name = "motor rotor"
inertia = 0.2
rpm = 960.0

[dynamics.flywheel]
ratio = 1.8333
shape = "rim"
density = 7200.0
""")
    d = dynamics_analysis(velplan.load(path))
    f = d.flywheel
    assert abs(d.declared - 0.2 * (960 / 80) ** 2) < 1e-12
    assert abs(f.added - (f.exact - d.declared)) < 1e-12 * f.exact
    assert abs(f.on_shaft - f.added / 1.8333**2) < 1e-12 * f.exact
    assert abs(f.exact - 216.68764928629) < 1e-6  # unchanged by the declared inertias
    assert f.dimensions.shape == "rim"


def test_a_4pi_cycle_of_loads_that_repeat_every_turn_is_two_equal_turns(with_dynamics):
    """cycle_turns = 2 (a four-stroke engine's 4π) on loads that repeat every turn: the same
    driving moment, δ and flywheel as the 2π cycle, and ω(φ) repeats after one turn."""
    one = dynamics_analysis(velplan.load(with_dynamics("shaper", "[dynamics]\ndelta = 0.05\n")))
    two = dynamics_analysis(velplan.load(with_dynamics("shaper", "[dynamics]\ndelta = 0.05\ncycle_turns = 2\n")))
    assert two.spec.cycle == pytest.approx(4 * math.pi)
    assert two.driving == pytest.approx(one.driving, rel=1e-12)
    assert two.flywheel.exact == pytest.approx(one.flywheel.exact, rel=1e-9)
    assert two.steady.delta == pytest.approx(one.steady.delta, rel=1e-9)
    assert two.steady.period == pytest.approx(2 * one.steady.period, rel=1e-9)
    theta = np.linspace(0.0, 2 * math.pi, 50)
    w2 = two.speed_at_travel(theta)[1]
    assert np.allclose(two.speed_at_travel(theta + 2 * math.pi)[1], w2, rtol=1e-9)
    assert np.allclose(one.speed_at_travel(theta)[1], w2, rtol=1e-9)
