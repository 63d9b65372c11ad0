"""Laziness, scales, drafting, conditioning, sentences and the table check."""

import math

import numpy as np
import pytest

import velplan
from velplan.errors import ScaleError, SingularPositionError, TableError, VelplanError
from velplan.plans import Drafting, Plan, standard_scale
from velplan.plans.check import check_table
from velplan.plans.table import transfer_table


def test_one_point_evaluates_strictly_fewer_steps_than_the_whole_plan():
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, [0.4, 1.3])
    plan = Plan.of(mech)
    whole = plan.evaluate(kin, kind="velocity")
    a4 = plan.evaluate(kin, kind="velocity", only=["A4"])
    # pole, pa, two lines, the intersection: exactly the five steps a4 depends on
    assert a4.evaluated_steps == 5 < whole.evaluated_steps == 11
    assert set(a4.vectors) == {"O3", "O2", "A", "A4"}
    assert np.array_equal(a4.image("A4"), whole.image("A4"))
    # ω of link 5 needs B and F but not the centres of mass S4, S5
    w5 = plan.evaluate(kin, kind="velocity", only=["5"])
    assert w5.evaluated_steps == 9 and "S4" not in w5.vectors
    # an acceleration of one point builds only the velocity steps it needs
    acc_all = plan.evaluate(kin, kind="acceleration")
    acc_a4 = plan.evaluate(kin, kind="acceleration", only=["A4"])
    assert acc_a4.evaluated_steps == 12 < acc_all.evaluated_steps == 23  # 14 a-steps + 9 v-steps it needs
    assert not any(s.target in ("v:b", "v:f", "v:s4") for s in acc_a4.steps)


def test_only_the_requested_positions_are_evaluated():
    mech = velplan.load("press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    res = Plan.of(mech).evaluate(kin, kind="velocity", positions=[4, 8], scale_v=0.001)
    assert res.image("C").shape == (2, 2)
    full = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.001)
    assert np.allclose(res.image("C"), full.image("C")[[3, 7]], rtol=0, atol=1e-12)


@pytest.mark.parametrize("raw, mu", [(0.00063, 0.001), (0.0007, 0.001), (0.0021, 0.0025), (0.0039, 0.004),
                                     (0.0041, 0.005), (0.0051, 0.01), (1.0, 1.0), (3.3e5, 4e5)])
def test_standard_scale_series(raw, mu):
    assert standard_scale(raw) == pytest.approx(mu)


def test_auto_scale_fits_the_longest_vector_in_100_mm():
    mech = velplan.load("press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    res = Plan.of(mech).evaluate(kin, kind="velocity", positions=[2])
    assert res.scale == 0.0005  # V_A = 0.05 m/s → 0.05/100 = 0.0005 (m/s)/mm
    assert max(np.hypot(*v[0]) for v in res.images.values()) <= 100.0
    seg = res.segments["pa"][0]
    assert seg == pytest.approx(100.0)


def test_seed_000_scale_gives_pa_71_4_mm():
    mech = velplan.load("press")
    kin = velplan.solve(mech, [0.0])
    res = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.0007)
    assert res.segments["pa"][0] == pytest.approx(0.05 / 0.0007)
    assert "pa = 71.4 mm ⊥ O1A in the sense of ω1 (V_A = 0.05 m/s)" in res.describe(lang="en")[1]


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_scale_is_a_one_line_error(bad):
    mech = velplan.load("press")
    kin = velplan.solve(mech, [0.0])
    with pytest.raises(ScaleError, match=r"^scale μv must be a positive number of units per mm, not "):
        Plan.of(mech).evaluate(kin, scale_v=bad)


def test_drafting_rounds_lengths_and_its_error_is_bounded():
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    plan = Plan.of(mech)
    exact = plan.evaluate(kin, kind="velocity", scale_v=0.02)
    draft = plan.evaluate(kin, kind="velocity", scale_v=0.02, drafting=Drafting(0.5, 0.5))
    pa = draft.segments["pa"]
    assert np.allclose(pa / 0.5, np.round(pa / 0.5))  # laid off to 0.5 mm
    for p, v in draft.vectors.items():
        dev_mm = np.hypot(*(v - exact.vectors[p]).T) / 0.02
        # a few lengths and directions, each off by at most half its step, and the lines'
        # intersections amplify by 1/sin: stay within the bound the flags state
        bound = 4 * 0.5 + np.radians(0.5) * 150
        assert (dev_mm <= bound).all(), (p, dev_mm.max())
    assert max(np.nanmax(np.hypot(*(draft.vectors[p] - exact.vectors[p]).T)) for p in exact.vectors) > 0


def test_monte_carlo_drafting_is_reproducible_and_spreads():
    mech = velplan.load("four-bar")
    kin = velplan.solve(mech, np.full(500, 1.0))
    plan = Plan.of(mech)
    a = plan.evaluate(kin, drafting=Drafting(0.5, 0.5, rng=np.random.default_rng(1))).vector("B")
    b = plan.evaluate(kin, drafting=Drafting(0.5, 0.5, rng=np.random.default_rng(1))).vector("B")
    assert np.array_equal(a, b)
    spread_mm = np.std(np.hypot(*a.T)) / plan.evaluate(kin).scale
    assert 0.1 < spread_mm < 2.0


def _toggle_slider():
    """Offset crank-slider with l = r + e: at φ = 90° the rod stands ⊥ the guide (a toggle)."""
    return velplan.parse("""
[ground]
O = [0.0, 0.0]
[crank]
link = "1"
pivot = "O"
tip = "A"
length = 0.05
omega = 10.0
[[group]]
kind = "RRP"
links = ["2", "3"]
joint = "A"
point = "B"
length = 0.07
guide = { link = "0", through = "O", angle_deg = 0.0, offset = -0.02 }
""")


@pytest.mark.parametrize("delta", [1e-3, 1e-5, 1e-7, 1e-9, 1e-12])
def test_near_a_toggle_the_plan_is_correct_to_its_bound_or_refused(delta):
    mech = _toggle_slider()
    phi = math.pi / 2 - delta
    kin = velplan.solve(mech, [phi])
    cond = kin.condition[0, 0]
    res = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=1.0)
    if cond == 0:
        # closer to the toggle than float64 positions resolve (h² below round-off of l²):
        # the solver masks the position and the plan refuses it
        assert not kin.valid[0] and res.refused[0] and np.isnan(res.vector("B")).all()
        return
    assert 0 < cond < 1e-1
    flags = [f for f in res.flags if f.image == "b"]
    assert flags and flags[0].condition == pytest.approx(res.conditions["b"][0])
    got, ref = res.vector("B")[0], kin.velocity("B")[0]
    if flags[0].refused:
        assert np.isnan(got).all()
        with pytest.raises(SingularPositionError, match=r"the lines meeting at b are nearly parallel at crank angle"):
            Plan.of(mech).evaluate(kin, kind="velocity", scale_v=1.0, on_failure="raise")
    else:
        assert np.hypot(*(got - ref)) <= flags[0].bound_mm * res.scale
    # the solver's own condition estimate is the same sine
    assert res.conditions["b"][0] == pytest.approx(cond, rel=1e-6)


def test_sentences_in_every_language():
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, [1.0])
    res = Plan.of(mech).evaluate(kin, kind="acceleration", scale_v=0.02, scale_a=0.2)
    en, ru, uk, zh = (res.describe(lang=lang) for lang in ("en", "ru", "uk", "zh"))
    assert len(en) == len(ru) == len(uk) == len(zh) == 14
    assert en[2].startswith("From a lay off ak1 = ") and "aᵏ_A4A" in en[2]
    assert ru[2].startswith("Из точки a откладываем отрезок ak1 = ") and "," in ru[2]
    assert uk[0].startswith("Обираємо полюс π")
    assert zh[0].startswith("选取极点 π")
    with pytest.raises(VelplanError, match=r"^unknown language 'de'; known languages: en, ru, uk, zh$"):
        res.describe(lang="de")


def test_transfer_table_layout_matches_seed_000():
    mech = velplan.load("press")
    table = transfer_table(velplan.Study(mech).plan("velocity", scale_v=0.0007))
    text = table.text().splitlines()
    assert text[0].split()[1:] == [str(i) for i in range(1, 13)] + ["1"]
    assert set(table.rows) >= {"V_A", "V_B2", "V_C", "V_E", "V_B4", "w_2", "w_5"}
    assert np.allclose(table.rows["V_A"], 0.05)
    # ω2/ω1 at position 1 is l1/l2 = 0.05/0.6 (crank and rod in line), seed: 0.083
    assert abs(table.rows["w_2"][0]) == pytest.approx(0.05 / 0.6, rel=1e-12)


def test_check_of_seed_000_table_2():
    mech = velplan.load("press")
    from importlib import resources

    path = resources.files("velplan.examples").joinpath("press-table2.csv")
    report = check_table(mech, path, scale_v=0.0007)
    assert len(report.entries) == 84
    flagged = {(e.quantity, e.position) for e in report.flagged}
    # the columns of positions 2 and 8 hold values of the rocker that belong elsewhere
    assert {("VC/ω1", 2), ("VE/ω1", 2), ("ω5/ω1", 2), ("VC/ω1", 8), ("VE/ω1", 8), ("ω5/ω1", 8)} <= flagged
    by = {(e.quantity, e.position): e for e in report.entries}
    assert by[("VC/ω1", 2)].cause.startswith("equals the exact value at position 8 (210°)")
    assert by[("VE/ω1", 8)].cause.startswith("equals the exact value at position 2 (30°)")
    assert "mis-measured segment" in by[("VC/ω1", 6)].cause
    # the rest agree within tolerance: every V_A entry and the dead-centre zeros
    assert not any(e.flagged for e in report.entries if e.quantity == "VA/ω1" or e.position in (1, 4, 7, 10))
    assert 15 <= len(flagged) <= 30
    for e in report.flagged:
        assert e.cause


def test_check_table_errors(tmp_path):
    mech = velplan.load("press")
    bad = tmp_path / "t.csv"
    bad.write_text("quantity,1,2\nVZ/ω1,0.1,0.2\n")
    with pytest.raises(TableError, match=r"^unknown quantity 'VZ/ω1'; use v<point>/ω1 with a point of "):
        check_table(mech, bad)
    bad.write_text("quantity,1,2\nVC/ω1,0.1,x\n")
    with pytest.raises(TableError, match=r"row 'VC/ω1': 'x' is not a number$"):
        check_table(mech, bad)
    bad.write_text("quantity,2,3\nVC/ω1,0.1,0.1\n")
    with pytest.raises(TableError, match=r"position headers must be 1…2 in order, not \[2, 3\]$"):
        check_table(mech, bad)


@pytest.mark.parametrize("name", ["shaper", "press"])
def test_acceleration_plan_on_a_velocity_plan_already_drawn(name):
    """velocity= reuses the drawn velocity plan: the same acceleration plan, the velocity steps
    not drawn again, and a velocity plan from other positions is refused."""
    mech = velplan.load(name)
    plan = Plan.of(mech)
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    rv = plan.evaluate(kin, kind="velocity")
    fresh = plan.evaluate(kin, kind="acceleration")
    reused = plan.evaluate(kin, kind="acceleration", velocity=rv)
    for p, v in fresh.vectors.items():
        np.testing.assert_array_equal(reused.vectors[p], v)
    assert reused.scales == fresh.scales and reused.flags == fresh.flags
    assert set(fresh.components) <= set(reused.components)  # and the velocity plan's own
    # random drafting: the acceleration plan is drawn on the very velocity images given
    rng_plan = plan.evaluate(kin, kind="velocity", drafting=Drafting(rng=np.random.default_rng(1)))
    acc = plan.evaluate(kin, kind="acceleration", drafting=rng_plan.drafting, velocity=rng_plan)
    for t, z in rng_plan.values.items():
        assert acc.values[t] is z
    with pytest.raises(ValueError, match="same kinematics, positions"):
        plan.evaluate(kin, kind="acceleration", positions=[1, 2], velocity=rv)
    with pytest.raises(ValueError, match="takes a velocity plan"):
        plan.evaluate(kin, kind="acceleration", velocity=fresh)
