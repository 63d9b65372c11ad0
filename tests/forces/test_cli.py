"""``velplan forces``: JSON schema, table, errors, output file and plots."""

import json
import math

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.cli import main


def _run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_json_schema(capsys):
    code, out, err = _run(capsys, "forces", "shaper", "--positions", "6", "--format", "json")
    assert code == 0 and err == ""
    doc = json.loads(out)
    assert doc["mechanism"] == "shaper" and doc["loads"] == ["Fc"]
    assert doc["omega1"] == pytest.approx(80 * math.pi / 30)
    assert [p["position"] for p in doc["positions"]] == [1, 2, 3, 4, 5, 6]
    mech = velplan.load("shaper")
    phi = velplan.positions(mech, 6)
    res = vf.force_analysis_at(mech, phi)
    pair_names = [p.name for p in velplan.mechanism.structure.pairs(mech)]
    for i, p in enumerate(doc["positions"]):
        assert set(p) >= {"phi_deg", "balancing_moment", "reactions"}
        assert p["phi_deg"] == pytest.approx(math.degrees(phi[i]) % 360)
        assert set(p["balancing_moment"]) == {"kinetostatics", "lever", "power"}
        for method, value in p["balancing_moment"].items():
            assert value == pytest.approx(res.balancing_moments[method][i], rel=1e-12, abs=1e-9)
        assert list(p["reactions"]) == pair_names
        for name, r in p["reactions"].items():
            f = res.kinetostatics.reactions[name].force[i]
            assert (r["x"], r["y"]) == pytest.approx((f.real, f.imag), rel=1e-12, abs=1e-9)
            assert ("moment" in r) == name.startswith("P:")


def test_single_position_and_table(capsys):
    code, out, _ = _run(capsys, "forces", "slider-press", "--position", "5")
    assert code == 0
    lines = out.splitlines()
    assert lines[0].startswith("slider-press: ω1 = +6.28319 rad/s; loads: P")
    assert lines[1].split() == ["quantity", "5"]
    assert any(line.strip().startswith("kinetostatics") for line in lines)
    assert any(line.strip().startswith("P:3/0 (3←0)") for line in lines)


def test_output_file_and_plot(tmp_path, capsys):
    target = tmp_path / "press.json"
    plot = tmp_path / "mb.svg"
    code, out, _ = _run(capsys, "forces", "press", "--positions", "3", "--format", "json", "-o", str(target),
                        "--plot", str(plot))
    assert code == 0 and out == ""
    doc = json.loads(target.read_text("utf-8"))
    assert len(doc["positions"]) == 3 and doc["loads"] == []
    assert plot.read_text("utf-8").lstrip().startswith("<?xml")


@pytest.mark.parametrize("argv, message", [
    (["forces", "shaper", "--position", "13"], "velplan: error: --position 13: must be between 1 and 12\n"),
    (["forces", "nosuch"], None),
    (["forces", "shaper", "--plot", "x.pdf"], "velplan: error: cannot plot to x.pdf: the file must end in .png or .svg, not .pdf\n"),
])
def test_errors_are_one_line(argv, message, capsys):
    code, out, err = _run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("velplan: error: ")
    if message:
        assert err == message


def test_position_and_positions_are_exclusive(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["forces", "shaper", "--position", "1", "--positions", "3"])
    assert exc.value.code == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_plot_functions_return_their_data(tmp_path):
    pytest.importorskip("matplotlib")
    from velplan.forces.plot import plot_balancing_moment, plot_press_load

    mech = velplan.load("slider-press")
    study = velplan.Study(mech)
    data = plot_balancing_moment(study.turn_forces(), tmp_path / "mb.png", sense=study.sense)
    assert data["turn_deg"][0] == 0 and data["turn_deg"][-1] == pytest.approx(360)
    assert (tmp_path / "mb.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    np.testing.assert_allclose(data["lever"], data["kinetostatics"], atol=1e-9)
    (p,) = vf.parse_loads(mech)
    d = plot_press_load(p, tmp_path / "p.svg")
    assert [k for k in d if k.startswith("N=")] == [f"N={k}" for k in range(1, 11)]
    assert np.all(np.diff(d["rms_error"]) < 0)
    assert "<svg" in (tmp_path / "p.svg").read_text("utf-8")
