"""Issue 15's cases, one regression test each: a wrong answer with exit status 0 becomes a right
one, a flagged one, or a one-line refusal (exit 2, nothing written)."""

import math
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.cli import main

EXAMPLES = Path(velplan.__file__).parent / "examples"
ROD_EQUALS_CRANK = """
name = "cs"
output = "B"
[ground]
O = [0.0, 0.0]
[crank]
link = "1"
pivot = "O"
tip = "A"
length = 0.1
omega = 10.0
[[group]]
kind = "RRP"
name = "2-3"
links = ["2", "3"]
joint = "A"
point = "B"
length = 0.1
branch = 1
guide = { link = "0", through = "O", angle_deg = 0.0, offset = 0.0 }
"""


@pytest.fixture
def cs(tmp_path):
    path = tmp_path / "cs.toml"
    path.write_text(ROD_EQUALS_CRANK)
    return path


def _run(capsys, *argv):
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def test_a_singular_column_does_not_zero_a_row(cs, capsys):
    rc, out, _ = _run(capsys, "analyze", cs, "--angles", "45,90,180")
    assert rc == 0
    row = next(line for line in out.splitlines() if line.startswith("V_B/ω1"))
    assert row.split()[2:] == ["0.1414", "—", "0"]  # 2·l·sin 45° = 0.1414 m; 90° is a toggle
    assert "singular (a group at a toggle, velocities undetermined) at positions: 2" in out
    rc, out, _ = _run(capsys, "analyze", cs, "--angles", "45,90", "--format", "csv")
    second = out.splitlines()[2].split(",")
    assert second[:2] == ["2", "90"] and set(second[2:]) == {""}  # no inf, no nan


def test_a_toggle_is_refused_not_printed(cs, capsys):
    mech = velplan.load(cs)
    for off in (0.0, 1e-9, 1e-6):
        kin = velplan.solve(mech, np.radians([90.0 + off]), omega1=10.0)
        assert not kin.valid[0] and kin.singular[0]
    kin = velplan.solve(mech, np.radians([90.01]), omega1=10.0)
    assert kin.valid[0] and kin.error_bound("velocity")[0] <= 1e-6
    rc, out, err = _run(capsys, "compare", cs, "--positions", "4")
    assert rc == 0 and not err
    assert [line.split()[-1] for line in out.splitlines() if line.startswith("V_B ")][1::2] == ["singular"] * 2
    rc, _, err = _run(capsys, "plan", cs, "--position", "2", "--positions", "4")
    assert rc == 2 and err.count("\n") == 1 and "singular" in err


def _edited(tmp_path, example, old, new, name="edited.toml"):
    text = (EXAMPLES / f"{example}.toml").read_text()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new, 1))
    return path


@pytest.mark.parametrize("example, old, new, message", [
    ("press", 'origin = "K4"', 'origin = "B4"', "group '3-4': origin 'B4' is already its coincident"),
    ("press", "[[point]]", '[[point]]\nname = "Q"\nlink = "0"\nalong = 0.1\n\n[[point]]',
     "point 'Q': link '0' is the frame; a fixed point goes in [ground]"),
    ("crank-slider", "length = 0.05", "length = 1e300", "crank length = 1e+300 is out of range"),
    ("crank-slider", "length = 0.05", "length = 1e-12", "crank length = 1e-12 m is shorter than 1e-09 m"),
])
def test_bad_files_are_refused_at_load(tmp_path, capsys, example, old, new, message):
    path = _edited(tmp_path, example, old, new)
    rc, out, err = _run(capsys, "analyze", path)
    assert rc == 2 and not out and err.count("\n") == 1 and message in err


def test_a_coincident_point_of_a_fixed_guide_is_drawn(tmp_path, capsys):
    path = _edited(tmp_path, "shaper", "offset = 0.6572 }", 'offset = 0.6572 }\ncoincident = "F0"')
    for argv in (["sheet", path, "-o", tmp_path / "k.svg"], ["sheet", path, "--kind", "forces", "-o", tmp_path / "f.svg"],
                 ["forces", path], ["plan", path, "--position", "2"]):
        rc, _, err = _run(capsys, *argv)
        assert rc == 0 and not err, (argv, err)
    kin = velplan.Study(path).kinematics
    assert np.allclose(kin.velocity("F0"), 0.0) and np.allclose(kin.position("F0"), kin.position("F"))


def test_angles_are_reduced_in_degrees():
    from velplan.cli.common import parse_angles

    # 10¹⁷ = 280 (mod 360) exactly; reduced after conversion it came out 4.4° off
    assert 10**17 % 360 == 280
    assert math.degrees(parse_angles("1e17")[0]) == pytest.approx(280.0, abs=1e-12)
    assert math.degrees(parse_angles("-725")[0]) == pytest.approx(-5.0, abs=1e-12)


def test_absurd_scales_and_tables(tmp_path, capsys):
    rc, _, err = _run(capsys, "plan", "shaper", "--position", "3", "--mode", "drafting", "--scale-v", "1e30")
    assert rc == 2 and "under 5 mm" in err
    table = EXAMPLES / "press-table2.csv"
    for extra, message in ((["--scale-v", "0"], "--scale-v must be a positive number"),
                           (["--scale-v", "0.0007", "--precision", "1e9"], "at most 10")):
        rc, out, err = _run(capsys, "check", "press", "--table", table, *extra)
        assert rc == 2 and not out and message in err
    bad = tmp_path / "nan.csv"
    bad.write_text(table.read_text().replace("0.025", "nan", 1))
    rc, _, err = _run(capsys, "check", "press", "--table", bad, "--scale-v", "0.0007")
    assert rc == 2 and "'nan' is not a finite number" in err


def test_signed_omega_rows_are_compared_signed(tmp_path, capsys):
    mech = velplan.load("press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    ratio = kin.omega("5") / kin.omega1
    assert (ratio < 0).any() and (ratio > 0).any()
    head = "quantity," + ",".join(str(k) for k in range(1, 13))
    good = tmp_path / "signed.csv"
    good.write_text(head + "\nω5/ω1," + ",".join(f"{x:.4f}" for x in ratio) + "\n")
    flipped = tmp_path / "flipped.csv"
    flipped.write_text(head + "\nω5/ω1," + ",".join(f"{-x:.4f}" for x in ratio) + "\n")
    from velplan.plans.check import check_table

    assert not check_table(mech, good, scale_v=0.0007).flagged
    wrong = check_table(mech, flipped, scale_v=0.0007).flagged
    big = np.abs(ratio) > 0.05
    assert len(wrong) >= big.sum()  # every clearly turning position flips sign: flagged


@pytest.mark.parametrize("argv, message", [
    (["analyze", "shaper", "--angles", ""], "--angles: give at least one angle"),
    (["analyze", "shaper", "-o", ""], "-o/--output: give a file name"),
    (["sheet", "shaper", "--dpi", "0", "--png"], "--dpi must be between 10 and 2400"),
    (["diagrams", "press", "--dpi", "nan"], "--dpi must be between 10 and 2400"),
])
def test_small_cli_cases(capsys, tmp_path, monkeypatch, argv, message):
    monkeypatch.chdir(tmp_path)
    rc, out, err = _run(capsys, *argv)
    assert rc == 2 and not out and err.count("\n") == 1 and message in err
    assert not list(tmp_path.iterdir())


def test_steps_refuses_a_missing_parent(capsys, tmp_path):
    target = tmp_path / "missing" / "steps"
    rc, _, err = _run(capsys, "steps", "shaper", "--position", "3", "-o", target)
    assert rc == 2 and "does not exist" in err and not (tmp_path / "missing").exists()


def test_forces_table_is_clean(capsys):
    rc, out, _ = _run(capsys, "forces", "shaper", "--positions", "4")
    assert rc == 0
    assert "-0 " not in out and "e-1" not in out
    for line in out.splitlines()[1:]:
        label_end = line.rstrip().rfind("  ")
        assert label_end > 0 or not line.startswith(" ")
    percent = next(line for line in out.splitlines() if "lever − kinetost." in line)
    assert percent.split()[-4:] == ["—", "0", "0", "0"]  # position 1: M_b = 0 at the dead centre


def test_a_plain_stroke_has_two_reversals():
    assert velplan.Study("shaper").stroke.reversals == 2


def _jamming_four_bar(gap_deg: float, centre_deg: float) -> str:
    """A four-bar whose coupler and rocker, stretched out, just fail to reach across |AD| for
    ``gap_deg`` around the crank angle ``centre_deg`` (closed form: |AD| > l2 + l3)."""
    a, d, b = 0.1, 0.3, 0.2
    half = math.radians(gap_deg / 2)
    c = math.sqrt(a * a + d * d + 2 * a * d * math.cos(half)) - b
    rot = math.radians(centre_deg - 180.0)
    return f"""
name = "jam"
[ground]
O = [0.0, 0.0]
D = [{d * math.cos(rot)!r}, {d * math.sin(rot)!r}]
[crank]
link = "1"
pivot = "O"
tip = "A"
length = {a}
omega = 1.0
[[group]]
kind = "RRR"
name = "2-3"
links = ["2", "3"]
joints = ["A", "D"]
point = "B"
lengths = [{b}, {c!r}]
"""


@pytest.mark.parametrize("gap, centre", [(0.06, 180.05), (0.004, 123.4567), (2.0, 200.0)])
def test_assembly_limits_are_exact(gap, centre):
    from velplan.analysis.assembly import limits
    from velplan.errors import AssemblyError

    mech = velplan.parse(_jamming_four_bar(gap, centre))
    ((lo, hi),) = limits(mech)["2-3"]
    assert lo == pytest.approx(centre - gap / 2, abs=1e-6) and hi == pytest.approx(centre + gap / 2, abs=1e-6)
    with pytest.raises(AssemblyError, match="cannot be assembled for crank angles"):
        velplan.Study(mech)


def test_sizes_are_capped(tmp_path, capsys):
    rc, _, err = _run(capsys, "analyze", "shaper", "--positions", "400")
    assert rc == 2 and "at most 360" in err
    rc, out, _ = _run(capsys, "analyze", "crank-slider", "--positions", "400", "--format", "csv")
    assert rc == 0 and len(out.splitlines()) == 401
    text = (EXAMPLES / "shaper.toml").read_text() + "".join(
        f'\n[[point]]\nname = "Q{i}"\nlink = "4"\nalong = 0.1\n' for i in range(600))
    path = tmp_path / "many.toml"
    path.write_text(text)
    rc, _, err = _run(capsys, "analyze", path)
    assert rc == 2 and "[point]: 603 entries; a mechanism file holds at most 500" in err
