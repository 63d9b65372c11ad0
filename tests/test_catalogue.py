"""The catalogue of course mechanisms: every one closes over the turn, its exact plans equal the
solver's values, the force analysis's three methods agree, and a few draw their A1 sheet."""

import math
import re
import tomllib
from importlib import resources

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.mechanism.loader import catalogue_names, example_names
from velplan.sheets.kinematic import build_sheet

NAMES = catalogue_names()
SHEETS = ("shaper-lever-ram", "whitworth", "jaw-crusher")
"""Catalogue mechanisms whose A1 sheet is built here (the gallery draws them all)."""


def _text(name):
    return resources.files("velplan.catalogue").joinpath(f"{name}.toml").read_text("utf-8")


def test_catalogue_is_a_course_worth_of_mechanisms():
    assert len(NAMES) >= 20
    assert not set(NAMES) & set(example_names())
    kinds = {g.kind for name in NAMES for g in velplan.load(name).groups}
    assert kinds == {"RRR", "RRP", "RPR", "PRP", "RPP", "triad"}
    indicators = [n for n in NAMES if any(ld.get("kind") == "indicator" for ld in tomllib.loads(_text(n)).get("load", []))]
    assert len(indicators) >= 4


@pytest.mark.parametrize("name", NAMES)
def test_catalogue_mechanism(name):
    text = _text(name)
    assert text.startswith("# ")  # the numbers and their source are stated at the top
    data = tomllib.loads(text)
    mech = velplan.load(name)
    assert mech.name == name and mech.title and mech.description
    assert mech.masses and data.get("load"), "masses and loads"
    dyn = data["dynamics"]
    assert 0 < dyn["delta"] < 1
    for item in dyn.get("inertia", []):
        assert item["name"] and item["inertia"] > 0 and (item.get("rpm", 0) != 0 or item.get("ratio", 0) > 0)

    study = velplan.Study(name)  # checks the assembly over a whole turn (every 0.1°)
    assert study.stroke is not None and study.stroke.H > 0 and study.stroke.K >= 1 - 1e-12
    for kind in ("velocity", "acceleration"):
        res = study.plan(kind)
        kin = res.kin
        ref = kin.velocities if kind == "velocity" else kin.accelerations
        size = np.nanmax(np.hypot(ref[..., 0], ref[..., 1]), axis=1)
        assert len(size) == 12 and np.all(size > 0)
        for p, v in res.vectors.items():
            err = np.hypot(*(v - ref[:, kin.point_index[p]]).T) / size
            assert np.all(err < 1e-12), (kind, p, err.max())
        for link, w in res.omegas.items():
            assert np.allclose(w, kin.omega(link), rtol=1e-12, atol=1e-12 * abs(kin.omega1))
    forces = study.forces()
    assert forces.max_relative_difference() < 1e-9
    mb = forces.balancing_moments["kinetostatics"]
    assert np.all(np.isfinite(mb)) and np.max(np.abs(mb)) > 0


@pytest.mark.parametrize("name", SHEETS)
def test_catalogue_sheet_builds_at_a1(name):
    study = velplan.Study(name)
    svg = build_sheet(study, fmt="A1", lang="en").svg()
    # the title block names the mechanism in the sheet's language, never by its file key
    # (the title block may break the name over lines)
    words = " ".join(" ".join(re.findall(r">([^<>]+)<", svg)).split())
    assert svg.startswith("<?xml") and study.mechanism.name_in("en") in words


def test_strokes_against_closed_forms():
    # a slotted lever with its slot through the pivot swings ±asin(r/d): θ = 2·asin(r/d)
    st = velplan.Study("shaper-lever-ram").stroke
    theta = 2 * math.asin(0.10 / 0.30)
    assert st.H == pytest.approx(2 * 0.52 * math.tan(theta / 2), rel=1e-9)
    assert st.K == pytest.approx((math.pi + theta) / (math.pi - theta), rel=1e-9)
    assert velplan.Study("scotch-yoke-pump").stroke.H == pytest.approx(0.12, rel=1e-12)
    assert velplan.Study("feed-inclined-yoke").stroke.H == pytest.approx(0.08 / math.sin(math.radians(60)), rel=1e-9)
    assert velplan.Study("compressor").stroke.H == pytest.approx(0.10, rel=1e-12)


def test_load_finds_catalogue_names_and_examples_lists_them(capsys):
    assert velplan.load("whitworth").title.startswith("Whitworth")
    assert main(["examples"]) == 0
    plain = capsys.readouterr().out
    assert "whitworth" not in plain and "shaper" in plain
    assert main(["examples", "--all"]) == 0
    listed = capsys.readouterr().out
    assert all(f"\n{n} " in listed for n in NAMES)


def test_unknown_name_mentions_the_catalogue():
    with pytest.raises(velplan.MechanismError, match="catalogue"):
        velplan.load("no-such-mechanism")


def test_compound_hinge_keeps_both_reactions():
    # B joins rod 2, rocker 3 and rod 4: two pairs there, each with its own reaction
    fa = velplan.Study("stamping-press").forces()
    reactions = fa.kinetostatics.reactions
    labels = [rc.label for rc in reactions.values()]
    assert len(set(reactions)) == len(velplan.mechanism.structure.pairs(fa.kinetostatics.mechanism)) == 7
    assert "R24" in labels and "R32" in labels
    r24 = reactions["B:4/2"].force
    # link 4's balance: the reaction from 2 at B, from 5 at D, and link 4's own forces sum to 0
    group = fa.kinetostatics.polygons["4-5"]
    total = sum(v for _, v in group.vectors) + sum(v for _, v in group.closing_vectors)
    assert np.nanmax(np.abs(total)) < 1e-9 * np.nanmax(np.abs(r24))


@pytest.mark.parametrize("name, pair", [("stamping-press", ("R₂₄", "R₄₂")), ("v-compressor", ("R₁₄", "R₄₁"))])
def test_force_sheet_with_a_compound_hinge(name, pair):
    from velplan.sheets.forces import build_force_sheet

    svg = build_force_sheet(velplan.Study(name), fmt="A1", lang="en").svg()
    assert all(label in svg for label in pair)
