"""Zhukovsky's lever drawn from the plan engine's images, exactly and at drafting precision."""

import numpy as np
import pytest

import velplan
from velplan.forces.agreement import force_analysis_at, lever_difference_percent
from velplan.plans import Drafting


@pytest.mark.parametrize("name", ["shaper", "press", "slider-press"])
def test_exact_plan_lever_equals_kinetostatics(name):
    mech = velplan.load(name)
    res = force_analysis_at(mech, velplan.positions(mech, 24))
    bm = res.balancing_moments
    scale = np.abs(bm["kinetostatics"]).max()
    assert np.abs(bm["lever"] - bm["kinetostatics"]).max() <= 1e-9 * scale


def test_drafted_lever_differs_by_what_drafting_implies():
    mech = velplan.load("shaper")
    phi = velplan.positions(mech, 12)
    exact = force_analysis_at(mech, phi).balancing_moments
    drafted = force_analysis_at(mech, phi, drafting=Drafting(0.5, 0.5)).balancing_moments
    pct = lever_difference_percent(drafted["lever"], drafted["kinetostatics"])
    big = np.abs(exact["kinetostatics"]) > 0.2 * np.abs(exact["kinetostatics"]).max()
    # course works accept a few per cent; a 0.5 mm / 0.5° drafting gives well under that
    assert np.nanmax(np.abs(pct[big])) < 3.0
    assert np.nanmax(np.abs(pct[big])) > 0.0  # and it is not exact
    assert np.isnan(pct[0])  # position 1 is a dead centre: M_b = 0, no per cent
    # the drafted lever's error shrinks with the drafting precision
    fine = force_analysis_at(mech, phi, drafting=Drafting(0.05, 0.05)).balancing_moments
    pct_fine = lever_difference_percent(fine["lever"], fine["kinetostatics"])
    assert np.nanmax(np.abs(pct_fine[big])) < np.nanmax(np.abs(pct[big]))
