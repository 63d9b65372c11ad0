"""``velplan convert`` and .pmks files on every command: pyslvs's examples converted and
analysed; the refusals are one line on stderr, exit status 2, no traceback, no output file."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import velplan
from velplan.cli import main
from velplan.mechanism import pmks

EXAMPLES = json.loads((Path(__file__).parent.parent / "mechanism" / "data" / "pyslvs_examples.json").read_text("utf-8"))
NO_FULL_TURN = ("Parallel Linkage", "Ten Fold's levers")
"""A parallelogram that folds flat at φ = 0° and 180° (its change point), and a lever train whose
input link cannot turn through 52°…128°: velplan analyses a crank that turns fully."""
SINGLE_INPUT = sorted(k for k, v in EXAMPLES.items() if len(v["inputs"]) == 1 and len(set(v["inputs"][0])) == 2
                      and k != "Stephenson II" and k not in NO_FULL_TURN)


def _run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("name", SINGLE_INPUT)
def test_a_pyslvs_example_converts_and_analyses(name, tmp_path, capsys):
    ex = EXAMPLES[name]
    src = tmp_path / "x.pmks"
    src.write_text(ex["expression"], "utf-8")
    b, d = ex["inputs"][0]
    out = tmp_path / "x.toml"
    code, _, err = _run(capsys, "convert", src, "--input", f"{b},{d}", "--unit", "mm", "--omega", "10", "-o", out)
    assert code == 0 and err == ""
    joints, _ = pmks.parse(ex["expression"])
    pb, pd = (complex(*joints[i].at) for i in (b, d))
    drawn = math.degrees(math.atan2((pd - pb).imag, (pd - pb).real))
    code, text, err = _run(capsys, "analyze", out, f"--angles={drawn!r},{drawn + 1.0!r}", "--format", "json")
    assert code == 0 and err == ""
    doc = json.loads(text)
    assert doc["omega1"] == 10.0
    first = doc["positions"][0]
    assert first["valid"]
    for j in joints:  # the drawn pose is reproduced, joint by joint
        p = first["points"][j.name]
        assert (p["x"], p["y"]) == pytest.approx(j.at, abs=1e-12)
    # the crank's tip moves at ω·r, perpendicular to the crank
    tip = first["points"][joints[d].name]
    r = abs(pd - pb)
    assert math.hypot(tip["vx"], tip["vy"]) == pytest.approx(10.0 * r, rel=1e-12)


@pytest.mark.parametrize("name", NO_FULL_TURN)
def test_an_example_whose_input_does_not_turn_fully_converts_and_is_refused_by_analyze(name, tmp_path, capsys):
    src, out = tmp_path / "x.pmks", tmp_path / "x.toml"
    src.write_text(EXAMPLES[name]["expression"], "utf-8")
    b, d = EXAMPLES[name]["inputs"][0]
    assert _run(capsys, "convert", src, "--input", f"{b},{d}", "-o", out)[0] == 0
    code, text, err = _run(capsys, "analyze", out, "--angles=90", "--format", "json")
    assert code == 2 and "cannot be assembled for crank angles" in err and err.count("\n") == 1


def test_every_command_takes_a_pmks_file(tmp_path, capsys):
    src = tmp_path / "crank-rocker.pmks"
    src.write_text(EXAMPLES["Crank rocker"]["expression"], "utf-8")
    code, text, err = _run(capsys, "info", src)
    assert code == 0 and err == ""
    assert "W = 3·3 − 2·4 − 0 = 1" in text and "I(0, 1) → II(2, 3)" in text and "outer pairs P1, P4" in text
    code, text, err = _run(capsys, "analyze", src, "--angles", "0", "--format", "csv")
    assert code == 0 and text.startswith("position,phi_deg")


def test_convert_round_trip_through_the_three_forms(tmp_path, capsys):
    drawn, expr, back = tmp_path / "d.toml", tmp_path / "s.pmks", tmp_path / "b.toml"
    assert _run(capsys, "convert", "shaper", "-o", drawn)[0] == 0
    assert "[[joint]]" in drawn.read_text("utf-8")
    assert _run(capsys, "convert", drawn, "-o", expr)[0] == 0
    assert expr.read_text("utf-8").splitlines()[0] == "# velplan joints: O2 A O3 B F S4 S5"
    assert _run(capsys, "convert", expr, "--input", "0,1", "--rpm", "80", "-o", back)[0] == 0
    mech, again = velplan.load("shaper"), velplan.load(back)
    assert [g.kind for g in again.groups] == ["RPR", "RRP"] and again.crank.omega == pytest.approx(mech.crank.omega)
    k1, k2 = velplan.solve(mech, 0.3), velplan.solve(again, 0.3)
    for n in ("A", "B", "F"):
        assert k2.positions[0, k2.point_index[n]] == pytest.approx(k1.positions[0, k1.point_index[n]], abs=1e-12)


@pytest.mark.parametrize("argv, message", [
    (["convert", "{arm}", "--input", "0,1"], "W = 2 ("),
    (["convert", "{steph}", "--input", "0,1"], "form a class IV group (a closed contour of four links); velplan "
                                                "solves the dyads of class II and the class III triad; driven by "
                                                "link 3 (--input 5,4) it decomposes"),
    (["convert", "{bad}"], "malformed expression"),
    (["convert", "{kind}"], "unknown joint kind 'X'"),
    (["convert", "{rocker}", "--input", "0"], "--input must be two joint numbers B,D"),
    (["convert", "{rocker}", "--input", "1,1"], "B and D must be two different joints"),
    (["convert", "{rocker}", "--input", "0,7"], "joints are numbered 0…4, not 7"),
    (["convert", "{rocker}", "--input", "1,2"], "is not an R joint of the frame"),
    (["convert", "{rocker}", "--names", "A,B"], "--names gives 2 names for 5 joints"),
    (["convert", "{locked}"], "locked sub-chain"),
    (["convert", "shaper", "-o", "{out}.txt"], "is a .toml file"),
    (["info", "{arm}"], "W = 2 ("),
])
def test_a_refusal_is_one_line_exit_two_and_no_file(argv, message, tmp_path, capsys):
    files = {"arm": EXAMPLES["Arm"]["expression"], "steph": EXAMPLES["Stephenson II"]["expression"],
             "bad": "M[J[R, P[0, 0], L[ground, L1]]", "kind": "M[J[X, P[0, 0], L[ground, L1]]]",
             "rocker": EXAMPLES["Crank rocker"]["expression"]}
    paths = {}
    for key, text in files.items():
        paths[key] = tmp_path / f"{key}.pmks"
        paths[key].write_text(text, "utf-8")
    paths["locked"] = tmp_path / "locked.toml"
    paths["locked"].write_text("""[crank]
link = "1"
pivot = "O"
omega = 1.0
[[joint]]
name = "O"
at = [0.0, 0.0]
links = ["0", "1"]
[[joint]]
name = "A"
at = [0.0, 0.1]
links = ["1", "2"]
[[joint]]
name = "B"
at = [0.3, 0.2]
links = ["2", "0"]
[[joint]]
name = "C"
at = [0.1, 0.1]
links = ["2", "3"]
[[joint]]
name = "D"
at = [0.5, 0.0]
links = ["3", "4"]
[[joint]]
name = "E"
at = [0.6, 0.3]
links = ["4", "0"]
[[joint]]
name = "F"
at = [0.02, 0.05]
links = ["1", "5"]
""", "utf-8")
    paths["out"] = tmp_path / "out"
    out = tmp_path / "never.toml"
    argv = [a.format(**{k: str(v) for k, v in paths.items()}) for a in argv] + (["-o", str(out)] if "-o" not in argv
                                                                                 and argv[0] == "convert" else [])
    code, text, err = _run(capsys, *argv)
    assert code == 2 and text == ""
    assert err.startswith("velplan: error: ") and message in err and err.count("\n") == 1
    assert "Traceback" not in err and not out.exists()


def test_colours_and_names_survive_pmks_to_drawn_and_back(tmp_path, capsys):
    src, drawn, again = tmp_path / "j.pmks", tmp_path / "j.toml", tmp_path / "j2.pmks"
    src.write_text(EXAMPLES["Jansen's linkage (Single)"]["expression"], "utf-8")
    assert _run(capsys, "convert", src, "--form", "drawn", "--names", "O,A,B,C,D,E,F,G", "-o", drawn)[0] == 0
    assert _run(capsys, "convert", drawn, "-o", again)[0] == 0
    first, _ = pmks.parse(src.read_text("utf-8"), names=list("OABCDEFG"))
    second, _ = pmks.parse(again.read_text("utf-8"))
    assert [(j.name, j.color, j.links) for j in second] == [(j.name, j.color, j.links) for j in first]
    assert [j.color for j in second].count("Blue") == 1
    for a, b in zip(first, second):
        assert b.at == pytest.approx(a.at, rel=1e-15, abs=1e-18)


def test_stephenson_two_converts_when_driven_as_the_refusal_says(tmp_path, capsys):
    src, out = tmp_path / "s.pmks", tmp_path / "s.toml"
    src.write_text(EXAMPLES["Stephenson II"]["expression"], "utf-8")
    assert _run(capsys, "convert", src, "--input", "5,4", "--omega", "10", "-o", out)[0] == 0
    mech = velplan.load(out)
    assert [g.kind for g in mech.groups] == ["triad"]
    # its rocker does not turn fully, but the drawn pose solves, through every drawn joint
    joints, _ = pmks.parse(src.read_text("utf-8"))
    pivot, tip = complex(*joints[5].at), complex(*joints[4].at)
    k = velplan.solve(mech, math.atan2((tip - pivot).imag, (tip - pivot).real), order=0)
    for j in joints:
        assert tuple(k.positions[0, k.point_index[j.name]]) == pytest.approx(j.at, abs=1e-12)
