"""Every documented error: its exact one-line message, and the CLI's exit status 2."""

import math
import subprocess
import sys

import numpy as np
import pytest

import velplan
from velplan.errors import AssemblyError, MechanismError
from velplan.cli import main

FOUR_BAR = """
[ground]
O = [0.0, 0.0]
D = [0.30, 0.0]
[crank]
link = "1"
pivot = "O"
tip = "A"
length = {crank}
omega = 10.0
[[group]]
kind = "RRR"
links = ["2", "3"]
joints = ["A", "{joint}"]
point = "B"
lengths = [{coupler}, 0.20]
"""


def four_bar(crank=0.10, joint="D", coupler=0.25):
    return FOUR_BAR.format(crank=crank, joint=joint, coupler=coupler)


@pytest.mark.parametrize("value, message", [
    ("0.0", "crank length must be > 0 m, not 0.0"),
    ("-0.1", "crank length must be > 0 m, not -0.1"),
    ("nan", "crank length must be finite, not nan"),
    ("inf", "crank length must be finite, not inf"),
])
def test_bad_lengths(value, message):
    with pytest.raises(MechanismError, match=f"^{message}$"):
        velplan.parse(four_bar(crank=value))


def test_zero_link_length_in_a_group():
    with pytest.raises(MechanismError, match=r"^group '2-3' length of link 2 must be > 0 m, not 0.0$"):
        velplan.parse(four_bar(coupler="0.0"))


def test_unknown_point_lists_the_known_ones():
    with pytest.raises(MechanismError, match=r"^group '2-3' uses point 'X', which is not solved before it; "
                                             r"known points: A, D, O$"):
        velplan.parse(four_bar(joint="X"))


def test_group_that_cannot_be_assembled_names_the_ranges():
    text = four_bar(crank=0.2)
    mech = velplan.parse(text)  # loading checks the structure; the study checks the assembly
    with pytest.raises(AssemblyError) as info:
        velplan.Study(mech)
    msg = str(info.value)
    assert msg.startswith("group '2-3' (RRR) cannot be assembled for crank angles ")
    assert msg.endswith(": point 'B' has no position there")
    # |AD| > 0.45 for 2 cos φ... closed form of the failing range: |A − D| > l2 + l3 = 0.45
    lim = math.degrees(math.acos((0.2**2 + 0.3**2 - 0.45**2) / (2 * 0.2 * 0.3)))
    assert f"{360 - lim + 0.05:.1f}"[:3] in msg or f"{lim:.1f}"[:3] in msg
    assert info.value.group == "2-3" and info.value.point == "B"


def test_strict_path_raises_with_group_point_and_angle():
    mech = velplan.parse(four_bar(crank=0.2))
    with pytest.raises(AssemblyError, match=r"^group '2-3' \(RRR\) cannot be assembled: point 'B' has no position at crank angle 180°$"):
        velplan.solve(mech, np.radians([0.0, 180.0]), on_failure="raise")
    kin = velplan.solve(mech, np.radians([0.0, 180.0]))
    assert kin.valid.tolist() == [True, False]
    assert np.isnan(kin.position("B")[1]).all()


def test_duplicate_names():
    text = four_bar() + '[[point]]\nname = "A"\nlink = "2"\nalong = 0.1\n'
    with pytest.raises(MechanismError, match=r"^duplicate name 'A': used for the crank tip and for point on link 2$"):
        velplan.parse(text)


def test_unknown_link_of_a_point():
    text = four_bar() + '[[point]]\nname = "E"\nlink = "9"\nalong = 0.1\n'
    with pytest.raises(MechanismError, match=r"^point 'E' is on unknown link '9'; known links: 1, 2, 3$"):
        velplan.parse(text)


def test_point_on_an_unknown_link_used_by_a_group():
    text = four_bar() + """
[[point]]
name = "E"
link = "9"
along = 0.1
[[group]]
kind = "RRP"
links = ["4", "5"]
joint = "E"
point = "F"
length = 0.3
guide = { link = "0", through = "O", angle_deg = 0.0, offset = 0.0 }
"""
    with pytest.raises(MechanismError, match=r"^point 'E' is on unknown link '9'; known links: 1, 2, 3, 4, 5$"):
        velplan.parse(text)
    later = text.replace('link = "9"', 'link = "5"')
    with pytest.raises(MechanismError, match=r"^group '4-5' uses point 'E' of link '5', which is solved after the group; "
                                             r"reorder the groups$"):
        velplan.parse(later)


def test_malformed_toml():
    with pytest.raises(MechanismError, match=r"^malformed TOML in mechanism: "):
        velplan.parse("[ground\nO = 1")


def test_unknown_key_and_kind():
    with pytest.raises(MechanismError, match=r"^\[crank\]: unknown key 'lenght'; allowed: "):
        velplan.parse(four_bar().replace("length =", "lenght ="))
    with pytest.raises(MechanismError, match=r"^group #1: unknown kind 'RRX'; known kinds: RRR, RRP, RPR, PRP, RPP, triad$"):
        velplan.parse(four_bar().replace('"RRR"', '"RRX"'))


def test_unknown_example_or_file():
    with pytest.raises(MechanismError, match=r"^unknown mechanism 'nope': not a bundled example \(crank-slider, "):
        velplan.load("nope")


def test_unknown_point_in_a_query():
    kin = velplan.solve(velplan.load("four-bar"), [0.0])
    with pytest.raises(MechanismError, match=r"^unknown point 'Z'; known points: O, D, A, B, S2, S3$"):
        kin.position("Z")


def test_cli_error_is_one_line_exit_2_no_traceback(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(four_bar(crank="-1"))
    out = tmp_path / "out.json"
    assert main(["analyze", str(bad), "--format", "json", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err == "velplan: error: crank length must be > 0 m, not -1.0\n"
    assert not out.exists() and list(tmp_path.iterdir()) == [bad]


def test_cli_subprocess_exit_status_and_stderr():
    r = subprocess.run([sys.executable, "-m", "velplan", "analyze", "no-such-mechanism"], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "Traceback" not in r.stderr
    r = subprocess.run([sys.executable, "-m", "velplan", "analyze", "shaper", "--positions", "0"], capture_output=True, text=True)
    assert r.returncode == 2 and "must be ≥ 1, not 0" in r.stderr and r.stderr.count("\n") == 1


def test_cli_output_directory_missing(tmp_path, capsys):
    assert main(["analyze", "shaper", "-o", str(tmp_path / "no" / "x.txt")]) == 2
    assert "directory" in capsys.readouterr().err
