"""Exact plans against the analytic solver, on the examples and on random mechanisms."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import velplan
from velplan.plans import Plan
from tests.strategies import KINDS, fixed_points, mechanisms

EXAMPLES = velplan.example_names()
SETTINGS = settings(max_examples=40, deadline=None)


def _plan_errors(res):
    """|plan − analytic| / (largest vector of the plan at that position), per point."""
    kin = res.kin
    ref = kin.velocities if res.kind == "velocity" else kin.accelerations
    size = np.nanmax(np.hypot(ref[res.index, :, 0], ref[res.index, :, 1]), axis=1)
    return {p: np.hypot(*(v - ref[res.index, kin.point_index[p]]).T) / size for p, v in res.vectors.items()}


@pytest.mark.parametrize("name", EXAMPLES)
@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_exact_plan_equals_analytic_on_every_example(name, kind):
    mech = velplan.load(name)
    kin = velplan.solve(mech, np.linspace(0, 2 * np.pi, 721))
    res = Plan.of(mech).evaluate(kin, kind=kind)
    ok = ~res.flagged
    assert ok.sum() >= 700
    worst = max(float(np.nanmax(e[ok])) for e in _plan_errors(res).values())
    assert worst < 1e-12, worst
    for link, w in res.omegas.items():
        assert np.allclose(w[ok], kin.omega(link)[ok], rtol=1e-12, atol=1e-12 * abs(kin.omega1))
    if kind == "acceleration":
        for link, e in res.epsilons.items():
            assert np.allclose(e[ok], kin.epsilon(link)[ok], rtol=1e-10, atol=1e-10 * kin.omega1**2)


def test_coriolis_components_match_2_omega_v_rel():
    """Shaper guide bar (RPR) and press punch slot (RPP): aᵏ = 2·ω·V_rel by construction."""
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    res = Plan.of(mech).evaluate(kin, kind="acceleration")
    label, value = res.components["aᵏ_A4A"]
    expected = 2 * np.abs(kin.omega("4") * kin.slide("P:3/4")[:, 1])
    assert np.allclose(value, expected, rtol=1e-12, atol=1e-12 * expected.max())
    assert label == "ak1"
    # the press punch translates: no Coriolis component appears in its construction
    press = velplan.load("press")
    r = Plan.of(press).evaluate(velplan.solve(press, [0.3]), kind="acceleration")
    assert not [c for c in r.components if c.startswith("aᵏ")]


def test_coriolis_on_a_moving_guide_rrp():
    from hypothesis import find

    mech = find(mechanisms("RRP-moving"), lambda m: True)
    kin = velplan.solve(mech, np.linspace(0, 2 * np.pi, 37))
    res = Plan.of(mech).evaluate(kin, kind="acceleration")
    assert any(c.startswith("aᵏ") for c in res.components)
    ok = kin.valid & ~res.flagged
    assert max(float(np.nanmax(e[ok])) for e in _plan_errors(res).values()) < 1e-11


@SETTINGS
@given(mechanisms(), st.lists(st.floats(0, 2 * math.pi), min_size=1, max_size=5))
def test_exact_plan_equals_analytic_on_random_mechanisms(mech, phi):
    kin = velplan.solve(mech, phi)
    plan = Plan.of(mech)
    for kind in ("velocity", "acceleration"):
        res = plan.evaluate(kin, kind=kind)
        ok = kin.valid & ~res.flagged
        errs = _plan_errors(res)
        for p, e in errs.items():
            # bound from the condition estimate of the intersections involved
            assert (e[ok] < 1e-9).all(), (mech.groups[-1].kind, kind, p, e[ok])


@SETTINGS
@given(mechanisms(probes=True), st.floats(0, 2 * math.pi))
def test_relative_velocities_perpendicular_and_images_similar_turned_90(mech, phi):
    """Drawn only where the property applies (assembled, well-conditioned), with two probe
    points on every link: every draw compares at least one figure per link."""
    kin = velplan.solve(mech, [phi])
    assume(kin.valid[0])
    res = Plan.of(mech).evaluate(kin, kind="velocity")
    assume(not res.flagged[0])
    checked = set()
    for link, points in fixed_points(mech).items():
        pts = [p for p in points if p in res.vectors]
        w = res.omegas[link][0]
        for a in pts:
            for b in pts:
                if a == b:
                    continue
                R = complex(*(kin.position(b)[0] - kin.position(a)[0]))
                if abs(R) <= 1e-9 * velplan.analysis.solver.length_scale(mech):
                    continue  # the same place (a point put on a joint): no figure to compare
                img = complex(*(res.image(b)[0] - res.image(a)[0]))
                scale = abs(R) * abs(w) / res.scale
                # ab ⊥ AB, and ab = AB turned by +90° (ω > 0) or −90° (ω < 0), scaled by |ω|/μv
                assert abs((R.conjugate() * img).real) <= 1e-9 * abs(R) * (abs(img) + scale + 1e-300)
                assert abs(img - 1j * w * R / res.scale) <= 1e-9 * (scale + 1e-300)
                checked.add(link)
    assert checked == set(mech.links)


@SETTINGS
@given(mechanisms(probes=True), st.floats(0, 2 * math.pi))
def test_acceleration_images_similar_and_normal_components_point_to_the_centre(mech, phi):
    kin = velplan.solve(mech, [phi])
    assume(kin.valid[0])
    res = Plan.of(mech).evaluate(kin, kind="acceleration")
    assume(not res.flagged[0])
    # similarity: a rigid link's acceleration image is the link times (iε − ω²)/μa
    checked = set()
    for link, points in fixed_points(mech).items():
        pts = [p for p in points if p in res.vectors]
        w, e = kin.omega(link)[0], kin.epsilon(link)[0]
        for a in pts[:1]:
            for b in pts[1:]:
                R = complex(*(kin.position(b)[0] - kin.position(a)[0]))
                if abs(R) <= 1e-9 * velplan.analysis.solver.length_scale(mech):
                    continue
                img = complex(*(res.image(b)[0] - res.image(a)[0]))
                expect = (1j * e - w * w) * R / res.scale
                assert abs(img - expect) <= 1e-9 * (abs(expect) + abs(R) * w * w / res.scale + 1e-300)
                checked.add(link)
    assert checked == set(mech.links)
    # normal components: laid off from the centre's image towards the centre, length ω²·l/μa
    for step in res.steps:
        vec = getattr(step, "vector", None)
        if type(vec).__name__ != "Normal":
            continue
        z = res.values[step.target][0] - res.values[step.origin][0]
        P, C = (complex(*kin.position(x)[0]) for x in (vec.point, vec.centre))
        w = kin.omega(vec.link)[0]
        if abs(z) < 1e-9:
            continue
        assert abs(np.angle(z / (C - P))) < 1e-9
        assert abs(abs(z) - w * w * abs(C - P) / res.scale) <= 1e-9 * abs(z)


@pytest.mark.parametrize("kind", KINDS)
def test_every_group_kind_builds_both_plans(kind):
    from hypothesis import find

    mech = find(mechanisms(kind), lambda m: True)
    steps = Plan.of(mech).steps
    names = {type(s).__name__ for s in steps}
    assert {"Pole", "LayOff", "Line", "Intersect"} <= names


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_intersection_agrees_with_shapely(name):
    """An independent check of the numerical core: each image found by `Intersect` is where
    shapely finds the two construction lines (as long segments) crossing."""
    import shapely

    from velplan.plans.steps import Intersect

    mech = velplan.load(name)
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    for kind in ("velocity", "acceleration"):
        res = Plan.of(mech).evaluate(kin, kind=kind)
        size = max(np.abs(v).max() for v in res.images.values())
        for step in (s for s in res.steps if isinstance(s, Intersect)):
            (p1, u1), (p2, u2) = (res.values[t] for t in step.lines)
            for i in range(len(kin)):
                reach = 10 * size
                a = shapely.LineString([(z.real, z.imag) for z in (p1[i] - reach * u1[i], p1[i] + reach * u1[i])])
                b = shapely.LineString([(z.real, z.imag) for z in (p2[i] - reach * u2[i], p2[i] + reach * u2[i])])
                x = a.intersection(b)
                assert x.geom_type == "Point", (name, kind, step.label, i)
                got = res.values[step.target][i]
                assert abs(complex(x.x, x.y) - got) <= 1e-9 * size / res.conditions[step.label][i]
