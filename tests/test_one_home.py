"""One home for every result and every rule (issue 36): the study computes the instant
centres, the curve M_b(φ) and the table once, and the sheets, the page and the note read them;
one dispatch of the sheet kinds; saving by suffix; one parser of a finite number."""

import subprocess
import sys

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.analysis.numbering import position_numbers
from velplan.errors import TableError, VelplanError
from velplan.io import finite_number
from velplan.plans.centres import construct_centres


@pytest.fixture(scope="module")
def press():
    return velplan.Study("slider-press", n=6)


def test_the_study_constructs_the_centres_once_and_as_the_construction_does():
    study = velplan.Study("four-bar", n=6)
    con = study.centres(3, mu_l=0.002)
    assert study.centres(3, mu_l=0.002) is con  # cached
    again = construct_centres(study.kinematics, 3, mu_l=0.002)
    assert [s.pair for s in con.steps] == [s.pair for s in again.steps]
    for s, t in zip(con.steps, again.steps):
        assert (s.point is None) == (t.point is None)
        if s.point is not None and np.isfinite(s.point):
            assert s.point == pytest.approx(t.point, abs=1e-12)
    # P13 of a four-bar (Kennedy): where the line of P01, P03 (O, D) meets that of P12, P23 (A, B)
    kin = study.kinematics
    o, a, b, d = (complex(*kin.position(p)[2]) for p in ("O", "A", "B", "D"))
    cross = lambda p, q: (p.conjugate() * q).imag  # noqa: E731
    t = cross(a - o, b - a) / cross(d - o, b - a)
    assert con.centre("1", "3").point == pytest.approx(o + t * (d - o), abs=1e-9)
    with pytest.raises(VelplanError, match=r"^position 7 is outside 1…6"):
        study.centres(7)


def test_the_moment_curve_is_the_studys_and_agrees_with_the_positions(press):
    curve = press.moment_curve
    assert press.moment_curve is curve
    at = press.forces().kinetostatics.balancing_moment
    assert np.array_equal(curve.at_positions, at)
    assert curve.turn[0] == 0.0 and curve.turn[-1] == pytest.approx(2 * np.pi)
    assert curve.moment[0] == pytest.approx(at[0], rel=1e-9, abs=1e-9)  # the turn starts at position 1
    # the mean over the turn, by the trapezoid rule on 241 steps, against a fine independent sum
    assert curve.mean == pytest.approx(vf.mean_balancing_moment(press.mechanism, n=3600), rel=2e-2)


def test_the_sheet_and_the_note_print_the_studys_table():
    study = velplan.Study("four-bar", n=6)
    sheet = velplan.sheet(study, fmt="A2", lang="en", plans=[2])
    assert sheet.views["table"].view.meta["rows"] == tuple(study.table.rows)
    note = velplan.explanatory_note(study, parts=["kinematics"], lang="en", fmt="A2", plans=[2])
    table = next(b for b in note.blocks if getattr(b, "key", None) == "analogues")
    assert len(table.rows) == study.n


def test_one_dispatch_of_the_sheet_kinds_for_the_front_door_and_the_cli(press, tmp_path):
    out = tmp_path / "f.svg"
    run = subprocess.run([sys.executable, "-m", "velplan", "sheet", "slider-press", "--positions", "6", "--kind",
                          "forces", "--lang", "en", "-o", str(out)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert out.read_text("utf-8") == velplan.sheet(press, "forces", lang="en").svg()
    run = subprocess.run([sys.executable, "-m", "velplan", "sheet", "slider-press", "--kind", "dynamics",
                          "--plans", "2", "-o", str(tmp_path / "d.svg")], capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.strip().endswith(
        "--plans has no meaning for the dynamics sheet (it draws the whole cycle)")
    assert not (tmp_path / "d.svg").exists()


def test_a_sheet_saves_by_suffix(tmp_path):
    sheet = velplan.sheet("four-bar", fmt="A3", lang="en", plans=[2], n=6)
    written = sheet.save(tmp_path / "s.dxf")
    assert [p.name for p in written] == ["s.svg", "s.dxf"]
    assert written[1].read_text("utf-8").split(None, 2)[:2] == ["0", "SECTION"]
    assert written[0].read_text("utf-8") == sheet.svg()
    assert [p.name for p in sheet.save(tmp_path / "t.svg", dxf=True)] == ["t.svg", "t.dxf"]
    pytest.importorskip("cairosvg")
    assert [p.name for p in sheet.save(tmp_path / "u.png", dpi=10)] == ["u.svg", "u.png"]
    assert (tmp_path / "u.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_sheet_to_a_missing_directory_writes_nothing(tmp_path):
    sheet = velplan.sheet("four-bar", fmt="A3", lang="en", plans=[2], n=6)
    with pytest.raises(VelplanError, match=r"^cannot write .*s\.svg: directory .*nowhere does not exist$"):
        sheet.save(tmp_path / "nowhere" / "s.dxf")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("raw, value", [("2.5", 2.5), (" -1e3 ", -1000.0), (3, 3.0), (0.25, 0.25)])
def test_one_parser_of_a_finite_number(raw, value):
    assert finite_number(raw, "x") == value


@pytest.mark.parametrize("raw, message", [("abc", "x: 'abc' is not a number"), ("nan", "x: 'nan' is not a finite number"),
                                          (float("inf"), "x: inf is not a finite number"), (None, "x: None is not a number"),
                                          (False, "x: False is not a number")])
def test_the_parser_names_the_value(raw, message):
    with pytest.raises(TableError, match=f"^{message}$"):
        finite_number(raw, "x", error=TableError)


def test_the_cli_angles_and_a_checked_table_use_it(tmp_path):
    from velplan.cli.common import parse_angles
    from velplan.plans.check import check_table

    with pytest.raises(VelplanError, match=r"^--angles: 'inf' is not a finite number of degrees$"):
        parse_angles("10,inf")
    bad = tmp_path / "t.csv"
    bad.write_text("quantity,1,2\nVB/ω1,0.1,nan\n", "utf-8")
    with pytest.raises(TableError, match=r"row 'VB/ω1': 'nan' is not a finite number$"):
        check_table(velplan.load("four-bar"), bad)


def test_position_numbers_and_the_lever_take_numbers():
    assert position_numbers(range(4)).tolist() == [1, 2, 3, 4]
    mech = velplan.load("four-bar")
    kin = velplan.solve(mech, [0.0, 1.0])
    assert vf.positions_from_kinematics(kin, 2)["B"] == complex(*kin.position("B")[1])
    with pytest.raises(VelplanError, match=r"^position 3 is outside 1…2"):
        vf.images_from_kinematics(kin, 3, 0.01)
