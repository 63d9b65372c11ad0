"""The study: each result computed once; a variable crank speed through solver, plans and
forces; the solver computing only what is asked."""

import math

import numpy as np
import pytest

import velplan
from velplan.analysis import solver as solver_module
from velplan.errors import MechanismError
from velplan.plans import Drafting
from velplan.plans.engine import Plan


@pytest.fixture
def counted(monkeypatch):
    """Count every call of the solver (wherever it was imported) and of Plan.evaluate."""
    import sys

    calls = {"solve": 0, "evaluate": 0}
    solve, evaluate = solver_module.solve, Plan.evaluate

    def counting_solve(*a, **k):
        calls["solve"] += 1
        return solve(*a, **k)

    def counting_evaluate(self, *a, **k):
        calls["evaluate"] += 1
        return evaluate(self, *a, **k)

    for module in list(sys.modules.values()):
        if getattr(module, "__name__", "").startswith("velplan") and getattr(module, "solve", None) is solve:
            monkeypatch.setattr(module, "solve", counting_solve)
    monkeypatch.setattr(Plan, "evaluate", counting_evaluate)
    return calls


def test_each_result_is_computed_once(counted):
    study = velplan.Study("shaper")
    study.phi  # the positions (their reference needs the extremes)
    start = counted["solve"]
    assert study.kinematics is study.kinematics
    assert counted["solve"] == start + 1
    v = study.plan("velocity")
    a = study.plan("acceleration")
    assert study.plan("velocity") is v and study.plan("acceleration") is a
    assert counted["evaluate"] == 2
    # another scale of an exact plan draws the same construction: nothing evaluated again
    v2 = study.plan("velocity", scale_v=v.scale * 4)
    assert counted["evaluate"] == 2 and v2.scale == v.scale * 4
    assert study.forces() is study.forces()
    assert counted["evaluate"] == 2  # the lever reads the velocity plan already drawn


def test_one_sheet_solves_at_most_12_times_and_constructs_at_most_4_plans(counted, tmp_path):
    from velplan.cli import main

    assert main(["sheet", "shaper", "-o", str(tmp_path / "s.svg")]) == 0
    assert counted["solve"] <= 12 and counted["evaluate"] <= 4, counted
    counted.update(solve=0, evaluate=0)
    assert main(["sheet", "shaper", "--kind", "forces", "-o", str(tmp_path / "f.svg")]) == 0
    assert counted["solve"] <= 24 and counted["evaluate"] <= 4, counted


def test_loading_parses_only(counted):
    velplan.load("shaper")
    velplan.load("slider-press")
    assert counted["solve"] == 0


# -- a crank speed per position ------------------------------------------------------------


@pytest.mark.parametrize("name", velplan.example_names())
def test_speed_per_position_equals_a_solve_at_each_speed(name):
    mech = velplan.load(name)
    phi = velplan.positions(mech, 12)
    w = mech.crank.omega * (1.0 + 0.3 * np.sin(phi))
    e = 2.0 * np.cos(phi) - 0.5
    kin = velplan.solve(mech, phi, omega1=w, epsilon1=e)
    assert isinstance(kin.omega1, np.ndarray) and kin.omega1.shape == (12,)
    scale_a = np.abs(kin.accelerations).max()
    for i in range(12):
        one = velplan.solve(mech, phi[i], omega1=w[i], epsilon1=e[i])
        assert np.allclose(kin.velocities[i], one.velocities[0], rtol=0, atol=1e-13 * np.abs(kin.velocities).max())
        assert np.allclose(kin.accelerations[i], one.accelerations[0], rtol=0, atol=1e-12 * scale_a)
        assert np.allclose(kin.omegas[i], one.omegas[0], rtol=0, atol=1e-12 * np.abs(kin.omegas).max())
        assert np.allclose(kin.slides[i], one.slides[0], rtol=0,
                           atol=1e-12 * max(np.abs(kin.slides).max(initial=0), 1.0))


def test_speed_per_position_against_time_differences_of_a_motion():
    """φ(t) = φ0 + a·t + b·t²: velocities and accelerations of every point are the time
    derivatives of its positions (central differences, h = 1e-4 s). Coincident points (A4,
    the point of the guide bar under the block) are a different material point at each
    instant, so they are left out."""
    from velplan.mechanism.structure import coincident_points

    mech = velplan.load("shaper")
    a, b, h = 7.0, 3.0, 1e-4
    t = np.linspace(0.0, 0.8, 9)

    def at(tt):
        return velplan.solve(mech, 0.3 + a * tt + b * tt * tt, order=0).positions

    kin = velplan.solve(mech, 0.3 + a * t + b * t * t, omega1=a + 2 * b * t, epsilon1=np.full(t.size, 2 * b))
    keep = [j for name, j in kin.point_index.items() if name not in coincident_points(mech)]
    p0, pp, pm = at(t)[:, keep], at(t + h)[:, keep], at(t - h)[:, keep]
    v_fd = (pp - pm) / (2 * h)
    a_fd = (pp - 2 * p0 + pm) / (h * h)
    V = np.abs(kin.velocities).max()
    A = np.abs(kin.accelerations).max()
    assert np.abs(kin.velocities[:, keep] - v_fd).max() <= 1e-6 * V
    assert np.abs(kin.accelerations[:, keep] - a_fd).max() <= 1e-4 * A


def test_plans_and_forces_at_a_speed_per_position_agree_with_the_solver():
    mech = velplan.load("shaper")
    phi = velplan.positions(mech, 12)
    w = mech.crank.omega * (1.0 + 0.2 * np.cos(phi))
    e = 3.0 * np.sin(phi)
    kin = velplan.solve(mech, phi, omega1=w, epsilon1=e)
    plan = Plan.of(mech, tangential=True)
    rv = plan.evaluate(kin)
    ra = plan.evaluate(kin, kind="acceleration", velocity=rv)
    for p in rv.vectors:
        assert np.allclose(rv.vector(p), kin.velocity(p), rtol=0, atol=1e-12 * np.abs(kin.velocities).max())
        assert np.allclose(ra.vector(p), kin.acceleration(p), rtol=0, atol=1e-11 * np.abs(kin.accelerations).max())
    crank = mech.crank.link
    assert np.allclose(rv.omegas[crank], w) and np.allclose(ra.epsilons[crank], e)
    from velplan.forces.agreement import force_analysis
    from velplan.forces.parse import parse_loads

    fa = force_analysis(kin, rv, parse_loads(mech))
    mb = fa.balancing_moments
    scale = np.abs(mb["kinetostatics"]).max()
    assert np.abs(mb["power"] - mb["kinetostatics"]).max() <= 1e-9 * scale
    assert np.abs(mb["lever"] - mb["kinetostatics"]).max() <= 1e-9 * scale


def test_at_speed_is_exact_from_the_unit_solution():
    mech = velplan.load("press")
    phi = velplan.positions(mech, 12)
    unit = velplan.solve(mech, phi, omega1=1.0, epsilon1=0.0)
    fast = unit.at_speed(-4.0, 0.0)
    ref = velplan.solve(mech, phi, omega1=-4.0, epsilon1=0.0)
    assert fast.omega1 == -4.0
    assert np.allclose(fast.accelerations, ref.accelerations, rtol=0, atol=1e-12 * np.abs(ref.accelerations).max())
    with pytest.raises(MechanismError, match="constant crank speed"):
        velplan.solve(mech, phi, omega1=np.ones(12)).at_speed(2.0)


def test_speed_arrays_must_match_the_angles():
    mech = velplan.load("four-bar")
    with pytest.raises(ValueError, match=r"omega1 must be a scalar or have one value per angle \(3\)"):
        velplan.solve(mech, [0.0, 1.0, 2.0], omega1=[1.0, 2.0])


# -- only what is asked --------------------------------------------------------------------


def test_points_solve_only_what_they_need():
    mech = velplan.load("shaper")
    phi = velplan.positions(mech, 12)
    whole = velplan.solve(mech, phi)
    a4 = velplan.solve(mech, phi, points=["A4"])
    assert set(a4.point_index) == {"O3", "O2", "A", "A4"} < set(whole.point_index)
    assert set(a4.group_index) == {mech.groups[0].name}
    assert np.array_equal(a4.velocity("A4"), whole.velocity("A4"))
    with pytest.raises(MechanismError, match="unknown point 'F'; known points: O3, O2, A, A4"):
        a4.position("F")
    with pytest.raises(MechanismError, match="unknown point 'Q'"):
        velplan.solve(mech, phi, points=["Q"])


@pytest.mark.parametrize("engine", ["numpy", "compiled"])
def test_order_keeps_only_the_derivatives_asked_for(engine):
    pytest.importorskip("numba") if engine == "compiled" else None
    mech = velplan.load("four-bar")
    phi = np.linspace(0, 2 * math.pi, 50)
    whole = velplan.solve(mech, phi, engine=engine)
    pos = velplan.solve(mech, phi, order=0, engine=engine)
    vel = velplan.solve(mech, phi, order=1, engine=engine)
    assert pos.velocities is None and pos.accelerations is None and pos.omegas is None
    assert vel.accelerations is None and vel.epsilons is None
    assert np.array_equal(pos.positions, whole.positions, equal_nan=True)
    assert np.array_equal(vel.velocities, whole.velocities, equal_nan=True)
    assert np.array_equal(pos.valid, whole.valid)
    with pytest.raises(MechanismError, match=r"velocities were not solved \(order=0\); solve with order=1"):
        pos.velocity("C")
    with pytest.raises(MechanismError, match=r"accelerations were not solved \(order=1\)"):
        vel.epsilon("3")


# -- exact plans at any scale --------------------------------------------------------------


@pytest.mark.parametrize("name", velplan.example_names())
def test_an_exact_plan_at_another_scale_is_the_plan_constructed_at_it(name):
    study = velplan.Study(name)
    for kind, key in (("velocity", "scale_v"), ("acceleration", "scale_a")):
        res = study.plan(kind)
        mu = res.scale * 2.5
        moved = res.at_scale(mu)
        kin = study.kinematics
        opts = {key: mu}
        if kind == "acceleration":
            opts["velocity"] = study.plan("velocity")
        fresh = study.construction.evaluate(kin, kind=kind, **opts)
        size = max(np.abs(fresh.values[t]).max() for t in fresh.values if t.startswith(kind[0])
                   and not isinstance(fresh.values[t], tuple))
        for t, z in fresh.values.items():
            if isinstance(z, tuple):
                assert np.allclose(moved.values[t][0], z[0], rtol=0, atol=1e-12 * size, equal_nan=True)
            else:
                assert np.allclose(moved.values[t], z, rtol=0, atol=1e-12 * size, equal_nan=True)
        assert moved.describe(3, "ru") == fresh.describe(3, "ru")
        for label, length in fresh.segments.items():
            assert np.allclose(moved.segments[label], length, rtol=1e-12, atol=1e-12 * size, equal_nan=True)


def test_a_drafted_plan_is_not_rescaled():
    study = velplan.Study("four-bar")
    res = study.plan("velocity", drafting=Drafting(0.5, 0.5), scale_v=0.02)
    with pytest.raises(MechanismError, match="drafted plan"):
        res.at_scale(0.05)


def test_study_of_given_angles_and_its_errors():
    study = velplan.Study("crank-slider", angles=np.radians([10.0, 200.0]))
    assert study.n == 2 and np.allclose(study.kinematics.phi_deg, [10.0, 200.0])
    with pytest.raises(velplan.VelplanError, match="unknown motion 'wobbly'; known motions: constant, dynamic"):
        velplan.Study("shaper", motion="wobbly")
    with pytest.raises(velplan.VelplanError, match="unknown plan kind 'jerk'"):
        study.plan("jerk")


# -- the computed motion through the engine ------------------------------------------------


KLOSS = """
[dynamics.motor]
kind = "kloss"
critical_torque = 60.0
synchronous_rpm = 1500.0
critical_rpm = 1200.0
ratio = 4.8
"""


@pytest.mark.parametrize("name", ["shaper", "slider-press", "tests/dynamics/data/slider-dyn.toml"])
def test_kinetostatics_at_the_computed_motion_balances_the_constant_driving_moment(name):
    """In the steady state with a constant driving moment M_d, the crank's balancing moment at
    the computed ω(φ), ε(φ) plus the moment J_I·ε of the constant inertias (flywheel, rotor:
    they are not links) is M_d at every position — the dynamics (energy equation on the
    reduced quantities) and the kinetostatics (link by link, at the variable speed) agree."""
    study = velplan.Study(name, motion="dynamic", n=24, delta=0.05)
    dyn = study.dynamics
    w, e = study.crank_motion
    assert isinstance(w, np.ndarray) and np.ptp(w) > 0 and np.ptp(e) > 0
    assert np.allclose(study.kinematics.omega1, w) and np.allclose(study.kinematics.epsilon1, e)
    mb = study.forces().balancing_moments
    own = dict(dyn.constants).get(f"crank {study.mechanism.crank.link}", 0.0)  # a link mass already
    balance = mb["kinetostatics"] + (dyn.inertia - own) * e
    scale = np.abs(mb["kinetostatics"]).max()
    assert np.abs(balance - study.sense * dyn.driving).max() <= 1e-10 * scale
    assert study.forces().max_relative_difference() < 1e-9  # lever and power agree there too


def test_forces_cli_at_the_computed_motion(capsys):
    import json

    from velplan.cli import main

    data = "tests/dynamics/data/slider-dyn.toml"
    assert main(["forces", data, "--motion", "dynamic", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    w = [p["omega1"] for p in doc["positions"]]
    assert len(set(w)) == 12 and all(x < 0 for x in w)  # clockwise crank, speed varies
    assert main(["forces", data, "--angles", "0,45", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [round(p["phi_deg"], 9) for p in doc["positions"]] == [0.0, 45.0]


def test_kinetostatics_at_a_motors_periodic_regime_balances_its_moment(tmp_path):
    """The same balance with a Kloss motor (clockwise crank, periodic regime): M_b + J_I·ε equals
    the motor's moment on the crank at the computed speed, position by position."""
    from pathlib import Path

    src = Path("tests/dynamics/data/slider-dyn.toml").read_text("utf-8")
    path = tmp_path / "slider-kloss.toml"
    path.write_text(src + KLOSS, "utf-8")
    study = velplan.Study(path, motion="dynamic", n=24)
    dyn = study.dynamics
    assert dyn.periodic is not None and study.sense < 0
    w, e = study.crank_motion
    mb = study.forces().balancing_moments["kinetostatics"]
    own = dict(dyn.constants).get(f"crank {study.mechanism.crank.link}", 0.0)
    drive = study.sense * dyn.motor.moment(np.abs(w))
    assert np.ptp(drive) > 0  # the motor's moment follows the speed
    assert np.abs(mb + (dyn.inertia - own) * e - drive).max() <= 1e-8 * np.abs(mb).max()
