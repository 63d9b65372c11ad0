"""pyslvs/PMKS expressions: the grammar (comments, colours, optional fields, trailing commas),
the joints they mean, the names and fields kept through a round trip, and the one-line errors."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import velplan
from velplan.errors import MechanismError
from velplan.mechanism import pmks
from velplan.mechanism.loader import from_dict

EXAMPLES = json.loads((Path(__file__).parent / "data" / "pyslvs_examples.json").read_text("utf-8"))
"""pyslvs's public example list: each expression (coordinates in mm) and its input pairs."""


def test_a_joint_reads_kind_angle_colour_position_and_links():
    text = """# a comment
    M[
      J[R, color[Green], P[0.0, 0.0], L[ground, L1]],   # the crank's pivot
      J[RP, A[30.0], color[(10, 20, 30)], P[-1.5e1, 2.], L[L2, L1,]],
      J[P, A[-45], P[.5, 0], L[ground, link_3]]
    ]"""
    joints, _ = pmks.parse(text, unit="m")
    assert [(j.name, j.kind, j.links, j.at, j.color) for j in joints] == [
        ("P0", "R", ("0", "1"), (0.0, 0.0), "Green"),
        ("P1", "RP", ("2", "1"), (-15.0, 2.0), "(10, 20, 30)"),
        ("P2", "P", ("0", "link_3"), (0.5, 0.0), None)]
    assert joints[1].angle == pytest.approx(math.radians(30.0), rel=1e-15)
    assert joints[2].angle == pytest.approx(math.radians(-45.0), rel=1e-15)


def test_coordinates_are_millimetres_by_default_and_names_can_be_given():
    joints, _ = pmks.parse("M[J[R, P[12.5, -4], L[ground, L1]], J[R, P[0, 10], L[L1]]]", names=["O", "A"])
    assert [(j.name, j.at) for j in joints] == [("O", (0.0125, -0.004)), ("A", (0.0, 0.01))]


def test_names_blocks_and_colours_come_back_through_a_round_trip():
    tables = [{"name": "O", "at": [0.0, 0.0], "links": ["0", "1"], "color": "Blue"},
              {"name": "A", "at": [0.01, 0.02], "links": ["1", "2"]},
              {"name": "C", "at": [0.2, 0.05], "links": ["0", "2"], "kind": "RP", "angle_deg": 180.0, "block": "3"}]
    text = pmks.dumps(tables)
    joints, _ = pmks.parse(text)
    assert [pmks.joint_table(j) for j in joints] == [
        {"name": "O", "at": [0.0, 0.0], "links": ["0", "1"], "color": "Blue"},
        {"name": "A", "at": [pytest.approx(0.01, rel=1e-15), pytest.approx(0.02, rel=1e-15)], "links": ["1", "2"],
         "color": "Green"},
        {"name": "C", "at": [pytest.approx(0.2, rel=1e-15), pytest.approx(0.05, rel=1e-15)], "links": ["0", "2"],
         "kind": "RP", "angle_deg": 180.0, "block": "3", "color": "Green"}]


@pytest.mark.parametrize("text, message", [
    ("M[J[R, P[0, 0], L[ground, L1]]", "malformed expression at the end: expected '\\]', found 'end of text'"),
    ("M[J[R, P[0 0], L[ground, L1]]]", "malformed expression at character 12: expected ',', found '0'"),
    ("M[J[Q, P[0, 0], L[ground, L1]]]", "joint 0: unknown joint kind 'Q'; known kinds: R, P, RP"),
    ("M[J[R, P[0, 0], L[]]]", "joint 0: L\\[\\] names no link"),
    ("M[]", "holds no joint"),
    ("M[J[R, P[0, 0], L[ground, L1]]] extra", "text after the closing"),
    ("J[R, P[0, 0], L[ground, L1]]", "expected 'M', found 'J'"),
    ("M[J[R, P[0, 0], L[ground, L1]], J[R, P[$, 0], L[L1]]]", "unexpected '\\$"),
])
def test_a_malformed_expression_is_refused_in_one_line(text, message):
    with pytest.raises(MechanismError, match=message) as err:
        pmks.parse(text)
    assert "\n" not in str(err.value)


def test_a_link_name_an_expression_cannot_hold_is_refused():
    with pytest.raises(MechanismError, match="link 'rod 2' cannot be written"):
        pmks.dumps([{"name": "O", "at": [0, 0], "links": ["0", "rod 2"]}])


SINGLE_INPUT = sorted(k for k, v in EXAMPLES.items() if len(v["inputs"]) == 1 and len(set(v["inputs"][0])) == 2
                      and k != "Stephenson II")


@pytest.mark.parametrize("name", SINGLE_INPUT)
def test_the_single_input_examples_of_pyslvs_solve_in_their_drawn_pose(name):
    ex = EXAMPLES[name]
    pair = tuple(ex["inputs"][0])
    mech = from_dict(pmks.drawn_data(ex["expression"], pair=pair, omega=10.0), name=name)
    joints, _ = pmks.parse(ex["expression"])
    b, d = (complex(*joints[i].at) for i in pair)
    phi = math.atan2((d - b).imag, (d - b).real)
    k = velplan.solve(mech, phi)
    assert k.valid[0]
    for j in joints:  # every joint where pyslvs draws it
        assert tuple(k.positions[0, k.point_index[j.name]]) == pytest.approx(j.at, abs=1e-12)


def test_stephenson_two_driven_as_pyslvs_drives_it_is_a_class_four_group():
    ex = EXAMPLES["Stephenson II"]
    with pytest.raises(MechanismError, match=r"links 2, 5, 4, 3 form a class IV group"):
        from_dict(pmks.drawn_data(ex["expression"], pair=(0, 1)))
    # driven by its ternary rocker instead, the rest is a triad
    mech = from_dict(pmks.drawn_data(ex["expression"], pair=(5, 6)), name="stephenson-ii")
    assert [g.kind for g in mech.groups] == ["triad"]


def test_the_two_input_arm_is_refused_naming_w():
    with pytest.raises(MechanismError, match=r"W = 2 \("):
        from_dict(pmks.drawn_data(EXAMPLES["Arm"]["expression"], pair=(0, 1)))


@pytest.mark.parametrize("pair, message", [
    ((0, 9), "joints are numbered 0…4, not 9"),
    ((0, 2), "joints P0 and P2 share 0 moving links"),
    ((1, 2), "joint P1 is not an R joint of the frame"),
])
def test_a_bad_input_pair_is_refused(pair, message):
    with pytest.raises(MechanismError, match=message):
        pmks.drawn_data(EXAMPLES["Crank rocker"]["expression"], pair=pair)


def test_the_default_input_is_the_first_frame_joints_single_moving_link():
    data = pmks.drawn_data(EXAMPLES["Crank rocker"]["expression"])
    assert data["crank"] == {"link": "1", "pivot": "P0", "omega": 1.0}
