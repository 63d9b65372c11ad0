"""Drive selection (seed 003): useful power, motor, gear ratio, torques, and δ with the motor."""

import math

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.dynamics.drive import choose_motor, read_catalogue, select_drive
from velplan.errors import MechanismError, VelplanError


@pytest.fixture(scope="module")
def shaper_drive():
    study = velplan.Study("shaper", delta=0.05)
    return study, select_drive(study.dynamics)


def test_seed_003_chooses_the_air_132m4_and_a_ratio_of_4_1():
    # seed 003: N_max = 6330.8 W, η = 0.75 → 8441.07 W, × 1.1 → 9285.17 W; motor AIR 132M4
    # (11 kW, 1447 rpm); a crank at 352 rpm gives u = 1447/352 ≈ 4.1
    motors = read_catalogue()
    required = 6330.8 / 0.75 * 1.1
    assert required == pytest.approx(9285.17, abs=0.01)
    m = choose_motor(motors, required, None)
    assert (m.name, m.power_kw, m.nominal_rpm, m.synchronous_rpm) == ("AIR132M4", 11.0, 1447.0, 1500.0)
    assert m.nominal_rpm / 352 == pytest.approx(4.11, abs=0.005)
    assert choose_motor(motors, required, 1000.0).name == "AIR160S6"  # the preferred speed first


def test_useful_power_is_the_cutting_force_times_the_ram_speed(shaper_drive):
    """The shaper's useful resistance is 1400 N against the ram over 5…95 % of its working
    stroke: the useful power is 1400·|v_F| there, computed here from the solver directly."""
    study, drive = shaper_drive
    mech = study.mechanism
    st = study.stroke
    phi = st.start.phi + study.sense * np.linspace(0.0, math.pi + st.theta, 20001)
    kin = velplan.solve(mech, phi)
    s = kin.slide("P:6/0")[:, 0]
    done = np.abs(s - s[0]) / st.H
    cutting = (done >= 0.05) & (done <= 0.95)
    power = 1400.0 * np.hypot(*kin.velocity("F").T)
    assert drive.useful_max == pytest.approx(power[cutting].max(), rel=1e-6)
    # the mean is the work over the working stroke over its time: 1400·0.9·H / ((π + θ)/ω)
    mean = 1400.0 * 0.9 * st.H * abs(mech.crank.omega) / (math.pi + st.theta)
    assert drive.useful_mean == pytest.approx(mean, rel=1e-9)


def test_power_motor_ratio_and_torques_follow_the_rules(shaper_drive):
    study, d = shaper_drive
    assert d.spent == pytest.approx(d.useful_max / 0.75, rel=1e-15)
    assert d.required == pytest.approx(d.spent * 1.1, rel=1e-15)
    smaller = [m for m in read_catalogue() if m.synchronous_rpm == 1500 and m.power_kw < d.motor.power_kw]
    assert d.motor.power_kw * 1000 >= d.required and all(m.power_kw * 1000 < d.required for m in smaller)
    n_crank = abs(study.mechanism.crank.omega) * 30 / math.pi
    assert d.ratio == pytest.approx(d.motor.nominal_rpm / n_crank, rel=1e-15)
    assert d.torques["motor"] == pytest.approx(9550 * d.motor.power_kw / d.motor.nominal_rpm, rel=1e-15)
    assert d.torques["fast"] == pytest.approx(0.98 * d.torques["motor"], rel=1e-15)
    assert d.torques["slow"] == pytest.approx(0.97 * d.ratio * d.torques["fast"], rel=1e-15)


def test_the_dynamics_again_with_the_motor(shaper_drive):
    study, d = shaper_drive
    again = d.dynamics
    rotor = [j for name, j in again.constants if name.startswith("motor ")]
    assert rotor == [pytest.approx(d.motor.rotor_inertia * d.ratio**2, rel=1e-15)]
    assert again.periodic is not None and again.periodic.residual < 1e-6
    # the flywheel sized for δ = 0.05 at a constant driving moment keeps a Kloss motor's δ
    # below it (the motor's falling characteristic evens the speed)
    assert 0 < d.delta < 0.05
    assert again.periodic.omega_mean == pytest.approx(abs(study.mechanism.crank.omega), rel=0.05)


def test_catalogue_errors_name_the_row_and_column(tmp_path):
    bad = tmp_path / "m.csv"
    bad.write_text("name,power_kw,synchronous_rpm,nominal_rpm,rotor_inertia,critical_ratio,starting_ratio\n"
                   "X1,4,1500,1410,abc,2.2,2\n", "utf-8")
    with pytest.raises(MechanismError, match=r"^motor catalogue .*m\.csv, row 2: rotor_inertia 'abc' is not a number$"):
        read_catalogue(bad)
    bad.write_text("name,power\nX,1\n", "utf-8")
    with pytest.raises(MechanismError, match="the header must be name,power_kw,"):
        read_catalogue(bad)
    bad.write_text("name,power_kw,synchronous_rpm,nominal_rpm,rotor_inertia,critical_ratio,starting_ratio\n"
                   "X1,4,1500,1600,0.01,2.2,2\n", "utf-8")
    with pytest.raises(MechanismError, match=r"row 2 \(X1\): nominal_rpm 1600 must be below synchronous_rpm 1500"):
        read_catalogue(bad)
    with pytest.raises(VelplanError, match=r"no motor of the catalogue gives 1e\+03 kW \(the largest is AIR180M4, 30 kW\)"):
        choose_motor(read_catalogue(), 1e6, None)


def test_cli_drive(capsys):
    assert main(["dynamics", "shaper", "--delta", "0.05", "--drive", "--format", "json"]) == 0
    import json

    doc = json.loads(capsys.readouterr().out)
    assert doc["drive"]["motor"]["name"] == "AIR100L4" and doc["drive"]["gear_ratio"] > 1
