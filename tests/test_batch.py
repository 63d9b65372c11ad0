"""``velplan batch``: variant tables → sheets and an answer key; random variants; grading."""

import json
from importlib import resources

import numpy as np
import pytest

import velplan
from velplan import batch
from velplan.cli import main
from velplan.errors import TableError, VelplanError
from velplan.plans.grade import grade_table


def _example(name):
    return resources.files("velplan.examples").joinpath(f"{name}.toml").read_text("utf-8")


def _shaper(crank=0.1605, rod=0.2074, ram=52.0, fc=1400.0):
    """The shaper with its numbers replaced in the text (independent of the batch's overrides)."""
    text = _example("shaper")
    for old, new in (("length = 0.1605", f"length = {crank}"), ("length = 0.2074", f"length = {rod}"),
                     ("mass = 52.0", f"mass = {ram}"), ("force = 1400.0", f"force = {fc}")):
        assert text.count(old) == 1
        text = text.replace(old, new)
    return velplan.parse(text, name="shaper-edited")


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    """Three variants (two good, one with a misspelt key), run by the CLI on all cores, A3."""
    d = tmp_path_factory.mktemp("batch")
    (d / "v.csv").write_text(
        "variant,base,crank.length,group.5-6.length,link.6.mass,load.Fc.force,crank.lenght,positions\n"
        "A,shaper,0.15,0.21,60,1500,,8\n"
        "B,press,0.06,,,,,\n"
        "C,shaper,0.15,,,,0.2,\n", "utf-8")
    return d, main(["batch", str(d / "v.csv"), "-o", str(d / "out"), "--format", "A3"])


def test_batch_writes_sheets_and_key_and_reports_the_bad_row(course, capfd):
    d, status = course
    assert status == 2  # one variant failed
    out = d / "out"
    assert sorted(p.name for p in out.iterdir()) == ["A.svg", "B.svg", "answers.csv", "answers.json"]
    key = json.loads((out / "answers.json").read_text("utf-8"))
    assert [a["variant"] for a in key["variants"]] == ["A", "B"]
    (fail,) = key["failures"]
    assert fail["variant"] == "C" and "row 4" in fail["where"] and "crank.lenght" in fail["error"]
    assert "\n" not in fail["error"]


def test_key_values_against_the_solver(course):
    d, _ = course
    key = {a["variant"]: a for a in json.loads((d / "out" / "answers.json").read_text("utf-8"))["variants"]}
    a = key["A"]
    mech = _shaper(crank=0.15, rod=0.21, ram=60.0, fc=1500.0)
    phi = velplan.positions(mech, 8)
    kin = velplan.solve(mech, phi)
    assert a["positions"] == 8
    assert np.allclose(a["phi_deg"], np.degrees(phi) % 360, atol=1e-9)
    w1 = abs(mech.crank.omega)
    for p in ("A", "B", "F"):
        assert np.allclose(a["V"][p], np.hypot(*kin.velocity(p).T) / w1, rtol=1e-9, atol=1e-12)
    assert np.allclose(a["omega"]["4"], kin.omega("4") / mech.crank.omega, rtol=1e-9, atol=1e-12)
    study = velplan.Study(mech, n=8)
    assert a["H"] == pytest.approx(study.stroke.H, rel=1e-12) and a["K"] == pytest.approx(study.stroke.K, rel=1e-12)
    mb = study.forces().balancing_moments
    assert np.allclose(a["M_b"], mb["power"], rtol=1e-9, atol=1e-9 * np.abs(mb["power"]).max())
    b = key["B"]
    assert b["V"]["A"] == pytest.approx([0.06] * 12, rel=1e-12)  # |V_A|/ω1 = OA
    csv = (d / "out" / "answers.csv").read_text("utf-8").splitlines()
    assert csv[0].startswith("variant,quantity,unit,1,2")
    assert any(line.startswith(f"A,vF/ω{mech.crank.link},m,0,") for line in csv)  # the sheet's name
    assert any(line.startswith("A,H,m,") for line in csv)


@pytest.mark.parametrize("cell, message", [
    ({"crank.length": "abc"}, "crank.length: 'abc' is not a number"),
    ({"group.9-9.length": "0.2"}, "no group named '9-9'; known: 3-4, 5-6"),
    ({"group.5-6.lengths.0": "0.2"}, "5-6 (RRP) has no 'lengths.0'"),
    ({"ground.O2.2": "0.3"}, "index 2 outside 0…1"),
    ({"link.2.mass": "3"}, "the base has no [link.2]"),
    ({"positions": "2.5"}, "positions: must be a whole number"),
    ({"crank.length": "0.5"}, "group '5-6' (RRP) cannot be assembled"),
])
def test_bad_cells_are_one_line_errors_naming_the_key(tmp_path, cell, message):
    v = batch.Variant("7", "shaper", cell, "row 8")
    res = batch.study_variant(v, batch.Options(str(tmp_path), sheets=False))
    assert isinstance(res, batch.Failure)
    assert message in res.message and res.line().startswith("variant 7 (row 8): ")
    assert "\n" not in res.line()


def test_toml_table_with_nested_keys(tmp_path):
    (tmp_path / "v.toml").write_text(
        'base = "four-bar"\n[[variant]]\nname = "1"\ncrank = { length = 0.08, omega = 12.0 }\n'
        '"group.2-3.lengths.1" = 0.22\n', "utf-8")
    (v,) = batch.read_variants(tmp_path / "v.toml")
    assert v.overrides == {"crank.length": 0.08, "crank.omega": 12.0, "group.2-3.lengths.1": 0.22}
    mech, n = batch.build_variant(v)
    assert mech.crank.length == 0.08 and mech.crank.omega == 12.0 and mech.groups[0].lengths == (0.25, 0.22)
    assert n == 12


def test_random_variants_are_reproducible_and_assemble():
    one, f1 = batch.random_variants("shaper", 3, "TMM-2026 work 1", spread=0.1)
    two, f2 = batch.random_variants("shaper", 3, "TMM-2026 work 1", spread=0.1)
    assert not f1 and not f2
    assert [v.overrides for v in one] == [v.overrides for v in two]
    other, _ = batch.random_variants("shaper", 1, "TMM-2026 work 2", spread=0.1)
    assert other[0].overrides != one[0].overrides
    assert len({tuple(v.overrides.values()) for v in one}) == 3
    base = velplan.load("shaper")
    for v in one:
        ratio = v.overrides["crank.length"] / base.crank.length
        assert 0.9 - 5e-3 <= ratio <= 1.1 + 5e-3
        assert float(f"{v.overrides['crank.length']:.3g}") == v.overrides["crank.length"]
        mech, _ = batch.build_variant(v)
        velplan.Study(mech)  # assembles over the whole turn
    rng = batch.generator("7", "work")
    assert rng.integers(0, 2**62) == batch.generator("7", "work").integers(0, 2**62)


def test_grading_against_the_key(course, tmp_path, capsys):
    d, _ = course
    key = d / "out" / "answers.json"
    a = json.loads(key.read_text("utf-8"))["variants"][0]
    vals_f = [f"{x:.3f}" for x in a["V"]["F"]]
    vals_f[2] = f"{a['V']['F'][2] * 1.3 + 0.01:.3f}"  # one wrong entry
    w4 = [f"{x:.3f}" for x in a["omega"]["4"]]
    table = tmp_path / "student.csv"
    table.write_text("quantity," + ",".join(str(i) for i in range(1, 9)) + ",1\n"
                     + "VF/ω1," + ",".join(vals_f + vals_f[:1]) + "\n"
                     + "ω4/ω1," + ",".join(w4 + w4[:1]) + "\n", "utf-8")
    report = grade_table(table, key, "A")
    assert len(report.entries) == 16 and report.right == 15
    (bad,) = [e for e in report.entries if not e.right]
    assert (bad.quantity, bad.position) == ("VF/ω1", 3)
    assert main(["check", "shaper", "--table", str(table), "--key", str(key), "--variant", "A"]) == 0
    assert "15 of 16 entries right" in capsys.readouterr().out
    assert main(["check", "press", "--table", str(table), "--key", str(key), "--variant", "A"]) == 2
    assert "is a variant of 'shaper', not of 'press'" in capsys.readouterr().err
    with pytest.raises(TableError, match="has no variant 'Z'; it has A, B"):
        grade_table(table, key, "Z")


def test_batch_needs_a_table_or_random(tmp_path, capsys):
    assert main(["batch", "-o", str(tmp_path / "x")]) == 2
    assert "give a variant table or --random N" in capsys.readouterr().err
    assert main(["batch", "--random", "2", "--base", "shaper", "-o", str(tmp_path / "x")]) == 2
    with pytest.raises(VelplanError, match="use a .csv, .xlsx or .toml file"):
        batch.read_variants(__file__)


def test_an_excel_workbook_reads_like_its_csv(tmp_path):
    openpyxl = pytest.importorskip("openpyxl")
    rows = [["variant", "base", "crank.length", "link.6.mass", "positions"],
            ["A-1", "shaper", 0.15, 50, 12],
            ["A-2", "shaper", 0.1605, None, 6],
            ["текст", "shaper", "0.17", 48.5, 12]]
    book = openpyxl.Workbook()
    sheet = book.active
    for r in rows:
        sheet.append(r)
    book.create_sheet("notes").append(["ignored"])  # only the first sheet is read
    xlsx = tmp_path / "variants.xlsx"
    book.save(xlsx)
    csv_path = tmp_path / "variants.csv"
    csv_path.write_text("variant,base,crank.length,link.6.mass,positions\n"
                        "A-1,shaper,0.15,50,12\nA-2,shaper,0.1605,,6\nтекст,shaper,0.17,48.5,12\n", "utf-8")
    got, want = batch.read_variants(xlsx), batch.read_variants(csv_path)
    assert [(v.name, v.base, v.overrides) for v in got] == [(v.name, v.base, v.overrides) for v in want]
    bad = tmp_path / "bad.xlsx"
    bad.write_text("not a workbook")
    with pytest.raises(VelplanError, match=r"^cannot read workbook .*bad\.xlsx"):
        batch.read_variants(bad)


def test_a_class_iii_base_with_keys_into_the_triad(tmp_path):
    """Dotted keys reach a triad's sides and leads; the key's V/ω1 of the inner joints are the
    solver's for the same numbers set on the model directly, Assur's special point (a
    construction point) is left out of the key, and each variant has its sheet."""
    from dataclasses import replace

    (tmp_path / "v.csv").write_text(
        "variant,crank.length,group.3-2-4-5.sides.0,group.3-2-4-5.leads.1.length\n"
        "1,0.075,0.245,0.350\n"
        "2,0.078,,\n"
        "3,,,\n", "utf-8")
    variants = batch.read_variants(tmp_path / "v.csv", base="triad-rocker")
    bad = batch.Variant("4", "triad-rocker", {"group.3-2-4-5.leads.3.length": "0.3"}, "row 5")
    assert [v.name for v in variants] == ["1", "2", "3"] and variants[2].overrides == {}
    out = tmp_path / "out"
    out.mkdir()
    report = batch.run_batch(variants[:2] + [bad], batch.Options(str(out), fmt="A3"), jobs=1)
    answers, failures = report.answers, report.failures
    assert sorted(p.name for p in out.iterdir()) == ["1.svg", "2.svg", "answers.csv", "answers.json"]
    (fail,) = failures
    assert "group.3-2-4-5.leads.3.length" in fail.message and "index 3 outside 0…2" in fail.message
    one = next(a for a in answers if a["variant"] == "1")
    base = velplan.load("triad-rocker")
    (g,) = base.groups
    leads = list(g.leads)
    leads[1] = replace(leads[1], length=0.350)
    mech = replace(base, crank=replace(base.crank, length=0.075),
                   groups=(replace(g, sides=(0.245,) + g.sides[1:], leads=tuple(leads)),))
    phi = velplan.positions(mech, 12)
    kin = velplan.solve(mech, phi)
    w1 = abs(mech.crank.omega)
    assert "K3" not in one["V"] and {"B", "C", "D"} <= set(one["V"])
    for p in ("A", "B", "C", "D"):
        assert np.allclose(one["V"][p], np.hypot(*kin.velocity(p).T) / w1, rtol=1e-9, atol=1e-12)
    assert np.allclose(one["omega"]["3"], kin.omega("3") / mech.crank.omega, rtol=1e-9, atol=1e-12)
    # random variants vary the triad too
    keys = batch._random_keys(__import__("tomllib").loads(batch.base_text("triad-rocker")[1]))
    assert {"group.3-2-4-5.sides.2", "group.3-2-4-5.leads.0.length", "group.3-2-4-5.leads.2.length"} <= set(keys)
