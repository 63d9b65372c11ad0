"""Bad input: one-line errors naming the key and value, exit 2 on the command line; and the
JSON contract of ``velplan dynamics``."""

import json
import subprocess
import sys

import pytest

import velplan
from velplan.cli import main
from velplan.dynamics import dynamics_analysis, parse_dynamics
from velplan.errors import MechanismError

from .conftest import DATA

BAD = [
    ("[dynamics]\ndelta = 0.0\n", r"\[dynamics\] delta must be between 0 and 1 \(exclusive\), not 0"),
    ("[dynamics]\ndelta = 1.0\n", r"\[dynamics\] delta must be between 0 and 1 \(exclusive\), not 1"),
    ("[dynamics]\ndelta = -0.1\n", r"delta must be between 0 and 1 \(exclusive\), not -0.1"),
    ("[dynamics]\ndelta = nan\n", r"\[dynamics\] delta must be a finite number, not nan"),
    ("[dynamics]\nspeed = 1\n", r"\[dynamics\]: unknown key 'speed'"),
    ("[dynamics.flywheel]\nratio = 0.0\n", r"\[dynamics.flywheel\] ratio must be > 0, not 0"),
    ("[dynamics.flywheel]\nshape = \"cube\"\n", r"shape must be 'disc' or 'rim', not 'cube'"),
    ("[[dynamics.inertia]]\nname = \"g\"\ninertia = 1.0\nratio = -2.0\n",
     r"\[\[dynamics.inertia\]\] 'g' ratio must be > 0, not -2"),
    ("[dynamics.motor]\nkind = \"steam\"\n", r"kind must be one of constant, kloss, table, not 'steam'"),
    ("[dynamics.motor]\nkind = \"kloss\"\ncritical_torque = 5.0\nsynchronous_rpm = 1000.0\ncritical_rpm = 1200.0\n",
     r"critical_rpm must be < synchronous_rpm \(1000\), not 1200"),
    ("[dynamics.motor]\nkind = \"table\"\nrpm = [0.0, 900.0, 800.0]\ntorque = [1.0, 2.0, 3.0]\n",
     r"rpm must be increasing; rpm\[2\] = 800 ≤ 900"),
    ("[dynamics.motor]\nefficiency = 1.2\n", r"\[dynamics.motor\] efficiency must be in \(0, 1\], not 1.2"),
    ("[dynamics.motor]\nratio = 0\n", r"\[dynamics.motor\] ratio must be > 0, not 0"),
    ("[dynamics.run]\nomega = 5.0\n", r"\[dynamics.run\]: give travel_deg or time"),
    ("[dynamics.run]\nomega = -5.0\ntravel_deg = 10.0\n", r"against the sense of \[crank\]"),
]


@pytest.mark.parametrize("text, message", BAD)
def test_bad_dynamics_sections(with_dynamics, text, message, capsys):
    path = with_dynamics("shaper", text)
    with pytest.raises(MechanismError, match=message):
        parse_dynamics(velplan.load(path))
    assert main(["dynamics", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("velplan: error: ")


def test_cli_delta_option_is_checked(capsys):
    assert main(["dynamics", "shaper", "--delta", "1.5"]) == 2
    assert "--delta must be between 0 and 1" in capsys.readouterr().err


def test_cli_json_contract_steady(capsys, tmp_path):
    assert main(["dynamics", str(DATA / "slider-dyn.toml"), "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("driving_moment", "omega_mean", "delta", "flywheel", "flywheel_added", "flywheel_on_shaft",
                "omega_max", "omega_min", "phi_omega_max_deg", "phi_omega_min_deg", "positions"):
        assert key in doc
    assert set(doc["flywheel"]) >= {"exact", "mertsalov", "wittenbauer"}
    assert doc["omega_mean"] == pytest.approx(-300 * 3.141592653589793 / 30, rel=1e-12)  # signed like ω
    assert doc["delta"] == pytest.approx(0.04, rel=1e-10)
    assert len(doc["positions"]) == 12
    assert set(doc["positions"][0]) >= {"phi_deg", "omega", "epsilon", "t", "J_red", "M_red"}
    out = tmp_path / "d.json"
    png = tmp_path / "d.png"
    assert main(["dynamics", str(DATA / "slider-dyn.toml"), "--format", "json", "-o", str(out),
                 "--plot", str(png), "--positions", "6"]) == 0
    assert len(json.loads(out.read_text())["positions"]) == 6 and png.stat().st_size > 1000


def test_cli_json_contract_run(with_dynamics, capsys):
    from .test_motor_run import KLOSS, RUN

    path = with_dynamics("slider-press", KLOSS.format(J=40.0, MK=120.0) + RUN)
    assert main(["dynamics", str(path), "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert {"time", "omega_end", "omega_min", "positions"} <= set(doc)
    assert len(doc["positions"]) == 13


def test_no_dynamics_section_gives_the_steady_state_without_flywheel(capsys):
    assert main(["dynamics", "slider-press", "--delta", "0.05", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["delta"] == pytest.approx(0.05, rel=1e-10)
    # the bare shaper (no flywheel, J = 0 at its dead centre) cannot keep its mean speed
    assert main(["dynamics", "shaper"]) == 2
    assert "the crank would stop" in capsys.readouterr().err
