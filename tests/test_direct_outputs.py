"""The numpy engine solving blocks straight into the preallocated outputs (`blocks.Sink`), and
the triad's cos θ, sin θ from the branch's nodes (`triad._unit`): the same values as the copying
path and as numpy's cosine and sine, to round-off."""

from __future__ import annotations

import math

import numpy as np
import pytest

import velplan
from velplan.analysis import blocks, solver, triad
from velplan.analysis.prepared import prepared

KINDS = ["four-bar", "shaper", "triad-rocker", "triad-press", "triad-eight-link", "double-slider",
         "feed-inclined-yoke", "oscillating-cylinder", "shaper-lever-ram", "yoke-punch-press"]
"""Every group kind (RRR, RRP, RPR, PRP, RPP, the triad with rods and with a block), link points."""


def _fields(kin):
    return {f: getattr(kin, f) for f in ("positions", "velocities", "accelerations", "angles", "omegas",
                                         "epsilons", "slides", "condition")}


@pytest.mark.parametrize("name", KINDS)
def test_solved_into_the_outputs_as_copied(name):
    """A call over 2 × 1500 + 70 angles in blocks of 1500 (each block solved into the outputs)
    against the same angles solved 500 at a time (each copied in one assignment per kind):
    the same values to round-off, the same validity and the same NaN."""
    mech = velplan.load(name)
    rng = np.random.default_rng(7)
    phi = np.sort(rng.uniform(-np.pi, 3 * np.pi, 3070))
    velplan.solve(mech, phi[:3], engine="numpy")  # the outputs' layout is known from here on
    old = blocks.BLOCK
    blocks.BLOCK = 1500
    try:
        direct = velplan.solve(mech, phi, engine="numpy")
    finally:
        blocks.BLOCK = old
    parts = [velplan.solve(mech, phi[a:a + 500], engine="numpy") for a in range(0, phi.size, 500)]
    np.testing.assert_array_equal(direct.valid, np.concatenate([k.valid for k in parts]))
    for key, arr in _fields(direct).items():
        ref = np.concatenate([_fields(k)[key] for k in parts])
        np.testing.assert_array_equal(np.isnan(arr), np.isnan(ref), err_msg=key)
        scale = max(np.nanmax(np.abs(ref), initial=0.0), 1.0)
        np.testing.assert_allclose(arr, ref, rtol=0, atol=1e-13 * scale, equal_nan=True, err_msg=key)


@pytest.mark.parametrize("name", ["triad-rocker", "triad-press", "triad-eight-link"])
def test_unit_vector_of_the_branch_is_numpys(name):
    """cos θ, sin θ of the branch's reference angle from its nodes and the turn's series: within
    4e-16 of numpy's cosine and sine of the same θ, at 20 000 random crank angles."""
    mech = velplan.load(name)
    prep = prepared(mech)
    for trk in prep.tracks(solver.solve).values():
        phi = np.random.default_rng(3).uniform(-10, 10, 20000)  # at least triad.UNIT_FROM
        x, th, inside, cs = trk.reference(phi, unit=True)
        assert cs is not None
        np.testing.assert_allclose(cs[0], np.cos(th), rtol=0, atol=4e-16)
        np.testing.assert_allclose(cs[1], np.sin(th), rtol=0, atol=4e-16)
        x2, th2, inside2 = trk.reference(phi)
        np.testing.assert_array_equal(th, th2)
        np.testing.assert_array_equal(x, x2)


@pytest.mark.parametrize("turn", [1e-6, 2e-3, 0.02, 0.1])
def test_series_to_round_off(turn):
    """The series `_series` sums for turns up to ``turn``: cos δ and sin δ within 2 units of the
    last place of `math`'s at 201 turns in [−turn, turn]; longer series for larger turns."""
    cos_terms, sin_terms, largest = triad._series(turn)
    assert largest == turn and len(cos_terms) == len(sin_terms) >= 2
    d = np.linspace(-turn, turn, 201)
    c = triad._horner(cos_terms, d * d)
    s = triad._horner(sin_terms, d * d) * d
    for di, ci, si in zip(d, c, s):
        assert abs(ci - math.cos(di)) <= 2 * math.ulp(1.0)
        assert abs(si - math.sin(di)) <= 2 * math.ulp(max(abs(di), 1e-300))
    assert len(triad._series(0.1)[0]) > len(triad._series(1e-3)[0])
