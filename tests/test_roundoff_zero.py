"""A value zero to round-off prints as 0 (issue 32): the oscillating cylinder's loads do no work
over a cycle, so its driving moment is 0 — computed as ~10⁻¹⁶ N·m beside moments of several N·m —
and the sheet, its results table and the note print 0, not "7.97·10⁻¹⁶"; a real driving moment
keeps its value."""

from __future__ import annotations

import numpy as np
import pytest

import velplan
from velplan.render.scene import Text
from velplan.sheets.dynamics import build_dynamics_sheet
from velplan.views.base import ROUND_OFF, number
from velplan.views.dynamics import moment_scale, results_rows


@pytest.mark.parametrize("x, scale, text", [(7.97e-16, 8.5, "0"), (-3e-13, 40.0, "0"), (7.97e-16, None, "7,97·10⁻¹⁶"),
                                            (2e-8, 8.5, "2·10⁻⁸"), (0.25, 8.5, "0,25")])
def test_a_value_within_round_off_of_its_scale_prints_as_zero(x, scale, text):
    assert number(x, "ru", 5, scale=scale) == text


def test_the_bound_is_relative():
    assert number(0.9 * ROUND_OFF * 1e6, "en", scale=1e6) == "0"
    assert number(2 * ROUND_OFF * 1e6, "en", scale=1e6) != "0"


@pytest.fixture(scope="module")
def cylinder():
    study = velplan.Study("oscillating-cylinder", delta=0.05)
    return study, build_dynamics_sheet(study, lang="ru")


def test_the_cylinder_driving_moment_is_zero_to_round_off(cylinder):
    study, sheet = cylinder
    d = study.dynamics
    scale = moment_scale(d.curves(72)["M_red"])
    assert scale > 1.0 and abs(d.driving) < 1e-12 * scale  # the loads do no work over the cycle


def test_sheet_and_table_print_zero(cylinder):
    study, sheet = cylinder
    row = next(r for r in results_rows(study.dynamics, None, "ru") if "Mд" in r[0])
    assert row[1] == "0"
    texts = [t.text for v in sheet.views.values() for t in v.primitives if isinstance(t, Text)]
    drive = [t for t in texts if t.startswith("M_{д} =")]
    assert drive == ["M_{д} = 0 Н·м"]
    assert not any("10⁻¹" in t for t in texts if not t.startswith("±") and "±" not in t)


def test_a_real_driving_moment_keeps_its_value():
    d = velplan.Study("shaper", delta=0.05).dynamics
    work = sum(d.profile.cycle_work().values())
    expected = -work / d.profile.cycle
    row = next(r for r in results_rows(d, None, "en") if r[0].startswith("Driving moment"))
    assert float(row[1]) == pytest.approx(expected, rel=1e-4)
    assert abs(expected) > 1.0
