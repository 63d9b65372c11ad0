"""Stress: extreme sizes and speeds, crank angles a hair from dead centres and toggles.

Every result must be correct to its stated bound, or flagged/masked, or a clear error:
never NaN without a mask, never a silent branch flip, never a hang.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import velplan
from velplan.analysis import compiled
from velplan.plans import Plan
from tests.strategies import mechanisms

log_scale = st.floats(-6, 3).map(lambda e: 10.0**e)
log_omega = st.tuples(st.floats(-3, 4), st.sampled_from([1, -1])).map(lambda t: t[1] * 10.0 ** t[0])
DELTAS = [1e-3, 1e-6, 1e-9, 1e-12]
ENGINES = ["numpy", "compiled"] if compiled.available() else ["numpy"]


def _scaled(mech, k):
    """The same mechanism with every length multiplied by ``k``."""
    from dataclasses import replace

    data = {
        "ground": tuple((n, (x * k, y * k)) for n, (x, y) in mech.ground),
        "crank": replace(mech.crank, length=mech.crank.length * k),
        "points": tuple(replace(p, along=p.along * k, offset=p.offset * k) for p in mech.points),
    }
    groups = []
    for g in mech.groups:
        changes = {}
        for key in ("length", "offset"):
            if hasattr(g, key):
                changes[key] = getattr(g, key) * k
        if hasattr(g, "lengths"):
            changes["lengths"] = tuple(x * k for x in g.lengths)
        if hasattr(g, "guide"):
            changes["guide"] = replace(g.guide, offset=g.guide.offset * k)
        if hasattr(g, "guides"):
            changes["guides"] = tuple(replace(x, offset=x.offset * k) for x in g.guides)
        groups.append(replace(g, **changes))
    return replace(mech, groups=tuple(groups), **data)


@settings(max_examples=60, deadline=None)
@given(mechanisms(scale=log_scale, omega=log_omega), st.lists(st.floats(0, 2 * math.pi), min_size=1, max_size=8),
       st.sampled_from(ENGINES))
def test_random_sizes_and_speeds_mask_every_nan_and_match_the_plan(mech, phi, engine):
    kin = velplan.solve(mech, phi, engine=engine)
    bad = ~np.isfinite(kin.positions).all(axis=(1, 2)) | ~np.isfinite(kin.velocities).all(axis=(1, 2))
    bad |= ~np.isfinite(kin.accelerations).all(axis=(1, 2))
    assert not (bad & kin.valid).any(), "NaN or inf without a mask"
    res = Plan.of(mech).evaluate(kin, kind="acceleration")
    ref = kin.accelerations
    size = np.nanmax(np.hypot(ref[..., 0], ref[..., 1]), axis=1)
    ok = kin.valid & ~res.flagged
    for p, v in res.vectors.items():
        err = np.hypot(*(v - ref[:, kin.point_index[p]]).T) / size
        assert (err[ok] <= np.maximum(1e-9, kin.error_bound("acceleration")[ok])).all()
    _refusals_hold_nan(res)  # random draws seldom refuse: the toggle test below makes them


def _refusals_hold_nan(res) -> int:
    """A refused plan position says so and holds NaN where the refused intersection's point
    would be (and only the points found from it); returns the number of refused positions."""
    for i in np.flatnonzero(res.refused):
        missing = [p for p, v in res.vectors.items() if np.isnan(v[i]).any()]
        assert missing and res.flagged[i], (i, missing)
        assert not np.isnan(res.vectors[res.kin.mechanism.crank.tip][i]).any()
    return int(res.refused.sum())


@settings(max_examples=30, deadline=None)
@given(mechanisms(), st.floats(-6, 3), st.floats(0, 2 * math.pi))
def test_results_scale_exactly_with_the_size_of_the_mechanism(mech, e, phi):
    k = 10.0**e
    a = velplan.solve(mech, [phi])
    b = velplan.solve(_scaled(mech, k), [phi])
    if not a.valid[0] or a.min_condition()[0] < 1e-4:
        return
    tol = 1e-10 / a.min_condition()[0]
    assert np.allclose(b.positions, k * a.positions, rtol=tol, atol=tol * k * np.abs(a.positions).max())
    assert np.allclose(b.velocities, k * a.velocities, rtol=tol, atol=tol * k * np.abs(a.velocities).max())
    assert np.allclose(b.omegas, a.omegas, rtol=tol, atol=tol * abs(mech.crank.omega))


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("name", velplan.example_names())
def test_a_hair_from_every_dead_centre(name, engine):
    """At φ_e ± δ (δ down to 1e-12 rad) of every extreme of every link and slide: assembled,
    continuous with the extreme itself (no branch flip), the rate ≈ its slope × δ."""
    mech = velplan.load(name)
    for q, roots in velplan.extremes(mech).items():
        for e in roots:
            phi = np.array([e.phi] + [e.phi + s * d for d in DELTAS for s in (-1, 1)])
            kin = velplan.solve(mech, phi, omega1=1.0, epsilon1=0.0, engine=engine)
            assert kin.valid.all(), (name, q)
            vmax = np.abs(kin.velocities).max()
            step = np.abs(kin.positions[1:] - kin.positions[0]).max(axis=(1, 2))
            assert (step <= 1.01 * vmax * np.repeat(DELTAS, 2) + 1e-15).all(), (name, q)
            if q.startswith("link"):
                rate, slope = kin.omegas[:, kin.link_index[q[5:]]], kin.epsilons[0, kin.link_index[q[5:]]]
            else:
                rate, slope = kin.slides[:, kin.slide_index[q[6:]], 1], kin.slides[0, kin.slide_index[q[6:]], 2]
            expect = slope * (phi - e.phi)
            assert np.allclose(rate[1:], expect[1:], rtol=1e-2, atol=1e-13 * max(1.0, vmax)), (name, q)


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("delta", DELTAS)
def test_a_hair_from_a_group_toggle_is_bounded_or_masked(delta, engine):
    from tests.plans.test_plan_features import _toggle_slider

    mech = _toggle_slider()
    phi = np.array([math.pi / 2 - delta, math.pi / 2 + delta])
    kin = velplan.solve(mech, phi, engine=engine)
    res = Plan.of(mech).evaluate(kin, kind="velocity")
    for i in range(2):
        if kin.valid[i]:
            # no branch flip: B stays on the +x side of A's foot, within its stated bound
            A, B = kin.position("A")[i], kin.position("B")[i]
            assert B[0] - A[0] >= -kin.error_bound("position")[i] * 0.12
            assert np.isfinite(kin.error_bound("velocity")[i])
        elif kin.singular[i]:  # closed, but refused: velocities there would exceed the bound
            from velplan.analysis.solver import SINGULAR_BOUND

            assert kin.error_bound("velocity")[i] > SINGULAR_BOUND
        else:
            assert np.isnan(kin.positions[i]).any() or not np.isfinite(kin.condition[i]).all() or kin.condition[i, 0] == 0
        assert res.flagged[i]
    # within 1e-9 rad of the toggle the intersection for B is refused: NaN, said so
    assert _refusals_hold_nan(res) == (2 if delta <= 1e-9 else 0)
    if delta <= 1e-9:
        assert np.isnan(res.vector("B")).all() and not np.isnan(res.vector("A")).any()


def test_extremes_search_terminates_and_counts_right():
    mech = velplan.load("four-bar")
    kin = velplan.solve(mech, [0.0])
    find = velplan.analysis.extremes.find_roots
    # the crank turns at constant ω: no extremes; the rocker and the coupler swing: two each
    assert find(mech, "link", kin.link_index["1"]) == []
    rocker = find(mech, "link", kin.link_index["3"])
    assert [e.kind for e in sorted(rocker, key=lambda e: e.value)] == ["min", "max"]
    assert len(find(mech, "link", kin.link_index["2"])) == 2
    # the rocker's swing from the closed form: cosine rule at the two crank–coupler alignments
    r, a, b, d = 0.10, 0.25, 0.20, 0.30
    lo, hi = min(e.value for e in rocker), max(e.value for e in rocker)
    ang = []
    for s in (a + r, a - r):
        # angle ODB with |OB| = s
        ang.append(math.acos((d * d + b * b - s * s) / (2 * d * b)))
    assert hi - lo == pytest.approx(abs(ang[0] - ang[1]), abs=1e-12)
