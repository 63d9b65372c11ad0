"""Kloss's formula, runs (time ODE with events) and the periodic regime with a motor."""

import math

import numpy as np
import pytest

import velplan
from velplan.dynamics import dynamics_analysis
from velplan.dynamics.motor import Motor, kloss, kloss_from_rating
from velplan.dynamics.run import simulate
from velplan.dynamics.spec import MotorSpec
from velplan.errors import VelplanError

KLOSS = """
[dynamics]
[[dynamics.inertia]]
name = "flywheel"
inertia = {J}
ratio = 1.0

[dynamics.motor]
kind = "kloss"
critical_torque = {MK}
synchronous_rpm = 1500.0
critical_rpm = 1200.0
ratio = 24.0
efficiency = 0.9
"""
RUN = """
[dynamics.run]
omega = 6.2
travel_deg = 360.0
"""


def test_kloss_zero_at_synchronism_and_critical_at_critical_slip():
    assert kloss(0.0, 0.2, 5240.0) == 0.0
    assert abs(kloss(0.2, 0.2, 5240.0) - 5240.0) < 1e-12
    assert kloss(-0.1, 0.2, 5240.0) < 0  # a brake above synchronism
    m = Motor(MotorSpec("kloss", critical_torque=5240.0, synchronous_rpm=1002.0, critical_rpm=738.0, ratio=18.6))
    assert float(m.shaft_torque(1002.0)) == 0.0
    assert abs(float(m.shaft_torque(738.0)) - 5240.0) < 1e-9
    # reduced to the crank: u·η·M at the crank speed n/u
    assert abs(float(m.moment(738.0 / 18.6 * math.pi / 30)) - 5240.0 * 18.6) < 1e-6
    mk, nk = kloss_from_rating(11.0, 1447.0, 1500.0, 2.2)
    s_n = 1 - 1447 / 1500
    assert abs(kloss(s_n, 1 - nk / 1500, mk) - 9550 * 11 / 1447) < 1e-9


def test_run_from_the_steady_state_returns_to_it_after_a_cycle():
    # the steady ω(φ) of the energy equation is a solution of the time ODE too
    d = dynamics_analysis(velplan.load("shaper"), delta=0.05)
    st = d.steady
    run = simulate(d.profile, d.inertia, lambda w: d.driving, st.omega(0.0), travel=2 * math.pi)
    assert abs(run.omega_end - st.omega(0.0)) <= 1e-9 * st.omega(0.0)
    assert abs(run.time - st.period) <= 1e-9 * st.period
    t, w, e = run.at_travel(np.array([1.0, 3.0, 5.0]))
    assert np.max(np.abs(w - st.omega(np.array([1.0, 3.0, 5.0])))) <= 1e-9 * st.omega_max
    assert np.max(np.abs(t - st.time(np.array([1.0, 3.0, 5.0])))) <= 1e-9


def test_press_run_with_kloss_and_periodic_regime(with_dynamics):
    d = dynamics_analysis(velplan.load(with_dynamics("slider-press", KLOSS.format(J=40.0, MK=120.0) + RUN)))
    assert d.run.travel == pytest.approx(2 * math.pi, abs=1e-12)
    assert 4.0 < d.run.omega_min < 6.3 and d.run.time > 0.9
    p = dynamics_analysis(velplan.load(with_dynamics("slider-press", KLOSS.format(J=40.0, MK=120.0)))).periodic
    assert p.residual < 1e-8
    # a run started at the periodic speed stays periodic
    dd = dynamics_analysis(velplan.load(with_dynamics("slider-press", KLOSS.format(J=40.0, MK=120.0))))
    run = simulate(dd.profile, dd.inertia, dd.motor.moment, p.omega_start, travel=2 * math.pi)
    assert abs(run.omega_end - p.omega_start) < 1e-8 * p.omega_start
    assert abs(run.time - p.period) < 1e-8


def test_too_weak_motor_stops_the_crank(with_dynamics):
    path = with_dynamics("slider-press", KLOSS.format(J=0.5, MK=10.0) + RUN)
    with pytest.raises(VelplanError, match=r"the crank stops after a travel of .* at t = "):
        dynamics_analysis(velplan.load(path))


def test_run_that_never_reaches_its_travel(with_dynamics):
    text = KLOSS.format(J=40.0, MK=120.0) + RUN.replace("travel_deg = 360.0", "travel_deg = 3600.0\ntime_limit = 0.5")
    with pytest.raises(VelplanError, match=r"turned only .* of travel_deg = 3600° within time_limit = 0.5 s"):
        dynamics_analysis(velplan.load(with_dynamics("slider-press", text)))


def test_time_limited_run_with_constant_torque(with_dynamics):
    text = """
[dynamics]
[[dynamics.inertia]]
name = "flywheel"
inertia = 40.0
ratio = 1.0
[dynamics.motor]
kind = "constant"
torque = 4.0
ratio = 24.0
[dynamics.run]
omega = 6.0
time = 0.5
"""
    d = dynamics_analysis(velplan.load(with_dynamics("slider-press", text)))
    assert d.run.time == pytest.approx(0.5, abs=1e-12)
    assert d.run.travel > 2.5
