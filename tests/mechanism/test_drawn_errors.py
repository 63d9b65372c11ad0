"""Bad drawn files and bad PMKS expressions: each refused in one line naming the element and
the value (a `MechanismError`), on the command line with exit status 2, no traceback and no
output file."""

from __future__ import annotations

import pytest

from velplan.cli import main
from velplan.errors import MechanismError
from velplan.mechanism import pmks
from velplan.mechanism.loader import from_dict

from .test_drawn import FOUR_BAR, _file

GOOD = ("M[J[R, color[Green], P[0.0, 0.0], L[ground, L1]], J[R, P[0, 10], L[L1, L2]], "
        "J[R, P[30, 0], L[ground, L3]], J[R, P[13, 20], L[L2, L3]]]")


def _one_line(exc) -> str:
    text = str(exc.value)
    assert "\n" not in text
    return text


@pytest.mark.parametrize("joints, words", [
    # B joins link 9, which no other joint holds (a mistyped link): named with its joint
    (FOUR_BAR[:3] + [("B", [0.6, 0.0], ["3", "9"])], ["link held by one joint alone: 9 (joint 'B');"]),
    (FOUR_BAR[:2] + [("C", [0.5, 0.4], ["2", "7"]), ("D", [0.6, 0.0], ["3", "0"])],
     ["links held by one joint alone: 7 (joint 'C'), 3 (joint 'D');"]),
    # A and B of link 2 at one point: a link of no length
    (FOUR_BAR[:2] + [("B", [0.1, 0.1], ["2", "3"]), ("D", [0.6, 0.0], ["3", "0"])],
     ["joints 'A' and 'B' of link 2 are drawn at one point (0.1, 0.1) m"]),
    # the same pair twice
    (FOUR_BAR + [("D2", [0.6, 0.1], ["0", "3"])], ["joints 'D' and 'D2' both join links 3, 0"]),
    # a duplicated name
    (FOUR_BAR + [("A", [0.3, 0.3], ["2", "3"])], ["duplicate joint name 'A'"]),
])
def test_bad_joints_are_refused_in_one_line(joints, words):
    with pytest.raises(MechanismError) as exc:
        from_dict(_file(joints))
    text = _one_line(exc)
    for w in words:
        assert w in text, text


def test_points_of_a_link_may_lie_on_its_joints():
    # a single-link joint is a point of that link, not a pair: it may sit on a joint
    mech = from_dict(_file(FOUR_BAR + [("S", [0.1, 0.1], ["2"])]))
    (s,) = mech.points
    assert (s.name, s.link) == ("S", "2") and abs(s.along) < 1e-12 and abs(s.offset) < 1e-12


def test_an_empty_file_says_what_a_mechanism_file_gives():
    with pytest.raises(MechanismError) as exc:
        from_dict({})
    assert "missing [ground] section" in _one_line(exc) and "[[joint]]" in str(exc.value)


@pytest.mark.parametrize("text, words", [
    ("", ["expected 'M', found 'end of text'"]),
    ("M[J[R, P[0, 0], L[ground, L1]], J[R, P[0, 10], L[L1, L2]", ["expected ']', found 'end of text'"]),
    ("M[J[R, P[a, 0], L[ground, L1]]]", ["character 10", "expected a number, found 'a'"]),
    ("M[J[R, P[0, 0], L[ground, L1]], J[P, P[0, 10], L[L1, L2]]]", ["joint 1: a P joint needs A[deg]"]),
    ("M[J[RP, P[0, 0], L[ground, L1]]]", ["joint 0: a RP joint needs A[deg]"]),
    ("M[J[X, P[0, 0], L[ground, L1]]]", ["joint 0: unknown joint kind 'X'"]),
    ("M[]", ["holds no joint"]),
])
def test_bad_expressions_are_refused_in_one_line(text, words):
    with pytest.raises(MechanismError) as exc:
        pmks.parse(text)
    line = _one_line(exc)
    for w in words:
        assert w in line, line


@pytest.mark.parametrize("argv, words", [
    (["--input", "7,1"], ["--input 7,1: joints are numbered 0…3, not 7"]),
    (["--input", "B,D"], ["--input must be two joint numbers"]),
    (["--input", "0,3"], ["--input 0,3: joints P0 and P3 share 0 moving links"]),
    (["--input", "1,3"], ["--input 1,3: joint P1 is not an R joint of the frame"]),
])
def test_convert_refuses_a_bad_input_pair_in_one_line(tmp_path, capsys, argv, words):
    src, out = tmp_path / "x.pmks", tmp_path / "x.toml"
    src.write_text(GOOD, "utf-8")
    code = main(["convert", str(src), *argv, "-o", str(out)])
    _, err = capsys.readouterr()
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1
    for w in words:
        assert w in err, err
    assert not out.exists()


def test_convert_of_an_empty_pmks_file_is_one_line(tmp_path, capsys):
    src, out = tmp_path / "e.pmks", tmp_path / "e.toml"
    src.write_text("", "utf-8")
    code = main(["convert", str(src), "-o", str(out)])
    _, err = capsys.readouterr()
    assert code == 2 and len(err.strip().splitlines()) == 1 and "malformed expression" in err
    assert not out.exists()
