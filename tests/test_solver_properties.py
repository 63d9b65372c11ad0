"""Property tests of the analytic solver over random mechanisms of every group kind."""

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import velplan
import velplan.analysis.compiled
from tests.strategies import KINDS, fixed_points, mechanisms

angles = st.lists(st.floats(0, 2 * math.pi), min_size=1, max_size=6).map(np.array)
SETTINGS = settings(max_examples=40, deadline=None)


def _moved(mech, dx, dy, rot):
    """The same mechanism turned by ``rot`` about the origin and shifted by (dx, dy)."""
    c, s = math.cos(rot), math.sin(rot)
    ground = tuple((k, (c * x - s * y + dx, s * x + c * y + dy)) for k, (x, y) in mech.ground)

    def turn(g):
        return g if g.link != "0" else type(g)(g.link, g.through, g.angle + rot, g.offset)

    groups = []
    for g in mech.groups:
        from dataclasses import replace

        if hasattr(g, "guide"):
            g = replace(g, guide=turn(g.guide))
        if hasattr(g, "guides"):
            g = replace(g, guides=tuple(turn(x) for x in g.guides))
        groups.append(g)
    from dataclasses import replace

    return replace(mech, ground=ground, groups=tuple(groups))


def _rotate(v, rot):
    c, s = math.cos(rot), math.sin(rot)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


@SETTINGS
@given(mechanisms(), angles, st.floats(-10, 10), st.floats(-10, 10), st.floats(-math.pi, math.pi))
def test_invariant_under_moving_the_whole_mechanism(mech, phi, dx, dy, rot):
    a = velplan.solve(mech, phi)
    b = velplan.solve(_moved(mech, dx, dy, rot), phi + rot)
    ok = a.valid & b.valid & (a.min_condition() > 1e-3)
    assume(ok.any())  # a draw where nothing assembles well proves nothing: draw again
    L = velplan.analysis.solver.length_scale(mech) + abs(dx) + abs(dy)
    w = abs(mech.crank.omega)
    assert np.allclose(_rotate(a.positions[ok], rot) + [dx, dy], b.positions[ok], atol=1e-11 * L, rtol=0)
    scale_v = w * L / a.min_condition()[ok, None, None]
    assert (np.abs(_rotate(a.velocities[ok], rot) - b.velocities[ok]) <= 1e-9 * scale_v).all()
    assert np.allclose(a.omegas[ok], b.omegas[ok], atol=1e-9 * w / a.min_condition()[ok, None].clip(1e-3))


@SETTINGS
@given(mechanisms(), angles, st.floats(0.001, 1000.0))
def test_velocities_linear_and_accelerations_quadratic_in_omega1(mech, phi, k):
    w = mech.crank.omega
    a = velplan.solve(mech, phi, epsilon1=0.0)
    b = velplan.solve(mech, phi, omega1=k * w, epsilon1=0.0)
    ok = a.valid & (a.min_condition() > 1e-3)
    assume(ok.any())
    assert np.allclose(b.velocities[ok], k * a.velocities[ok], rtol=1e-10, atol=1e-10 * np.abs(a.velocities[ok]).max(initial=0) * k)
    assert np.allclose(b.accelerations[ok], k * k * a.accelerations[ok], rtol=1e-10,
                       atol=1e-10 * np.abs(a.accelerations[ok]).max(initial=0) * k * k)
    assert np.allclose(b.omegas[ok], k * a.omegas[ok], rtol=1e-10, atol=1e-12 * abs(k * w))


@SETTINGS
@given(mechanisms(), angles)
def test_relative_velocity_of_two_points_of_a_link_is_perpendicular_to_it(mech, phi):
    kin = velplan.solve(mech, phi)
    ok = kin.valid
    assume(ok.any())
    # an absolute floor: the mechanism's own velocity scale |ω1|·L (a link at rest for an
    # instant has a relative velocity of round-off size, whose direction means nothing)
    v_floor = abs(mech.crank.omega) * velplan.analysis.solver.length_scale(mech)
    for link, names in fixed_points(mech).items():
        j = kin.link_index[link]
        for a in names:
            for b in names:
                r = kin.position(a)[ok] - kin.position(b)[ok]
                dv = kin.velocity(a)[ok] - kin.velocity(b)[ok]
                # two points at the same place (E put on C): their relative velocity is round-off
                apart = np.hypot(*r.T) > 1e-9 * velplan.analysis.solver.length_scale(mech)
                r, dv = r[apart], dv[apart]
                scale = np.hypot(*r.T) * (np.hypot(*dv.T) + 1e-6 * v_floor)
                assert (np.abs((r * dv).sum(-1)) <= 1e-9 * scale).all()
                # and its size is |ω|·|r| (ω of the link, counter-clockwise positive)
                expect = kin.omegas[ok, j][apart][:, None] * np.stack([-r[:, 1], r[:, 0]], -1)
                assert np.allclose(dv, expect, rtol=1e-9, atol=1e-9 * max(np.abs(expect).max(initial=0), v_floor))


@settings(max_examples=12, deadline=None)
@given(st.sampled_from(KINDS), st.data())
def test_every_kind_generates_assemblable_mechanisms(kind, data):
    mech = data.draw(mechanisms(kind))
    kin = velplan.solve(mech, np.linspace(0, 2 * np.pi, 73))
    assert kin.valid.mean() > 0.5
    assert mech.groups[-1].kind == kind.split("-")[0]


def test_branch_continuity_through_a_revolution():
    for name in velplan.example_names():
        mech = velplan.load(name)
        phi = np.linspace(0, 2 * np.pi, 20001)
        kin = velplan.solve(mech, phi)
        step = np.abs(np.diff(kin.positions, axis=0)).max()
        vmax = np.abs(kin.velocities).max() / abs(mech.crank.omega)
        assert step <= 1.01 * vmax * (phi[1] - phi[0]), name
        assert np.allclose(kin.positions[0], kin.positions[-1], atol=1e-12)


def test_blocks_give_the_same_results_as_one_pass(monkeypatch):
    """Solving in cache-sized blocks must not change a single bit."""
    from velplan.analysis import blocks as engine

    mech = velplan.load("shaper")
    phi = np.linspace(0, 2 * np.pi, 1001)
    whole = velplan.solve(mech, phi)
    monkeypatch.setattr(engine, "BLOCK", 97)
    blocks = velplan.solve(mech, phi)
    for name in ("positions", "velocities", "accelerations", "angles", "omegas", "epsilons", "slides", "condition"):
        assert np.array_equal(getattr(whole, name), getattr(blocks, name), equal_nan=True), name
    assert np.array_equal(whole.valid, blocks.valid)


def test_angles_are_wrapped_into_the_half_open_interval():
    """(−π, π]: −π itself becomes π, values inside stay bit for bit, others move by whole turns."""
    from velplan.analysis.groups import wrap_angle

    edge = np.array([-np.pi, np.pi, np.nextafter(-np.pi, 0.0), np.nextafter(np.pi, 4.0), 3 * np.pi, -3 * np.pi])
    w = wrap_angle(edge)
    assert w[0] == np.pi and w[1] == np.pi and w[2] == edge[2] and w[4] == np.pi and w[5] == np.pi
    t = np.random.default_rng(0).uniform(-60, 60, 100_000)
    w = wrap_angle(t)
    assert ((w > -np.pi) & (w <= np.pi)).all()
    inside = (t > -np.pi) & (t <= np.pi)
    assert (w[inside] == t[inside]).all()
    turns = (t - w) / (2 * np.pi)
    assert np.abs(turns - np.round(turns)).max() < 1e-14
    # a rod pointing exactly along −x reads +π, not −π (found by hypothesis on the compiled engine)
    mech = velplan.parse("""
        [ground]
        O = [0.0, 0.0]
        [crank]
        link = "1"
        pivot = "O"
        tip = "A"
        length = 1.0
        omega = 1.0
        [[group]]
        kind = "RRP"
        links = ["2", "3"]
        joint = "A"
        point = "C"
        length = 1.1
        guide = { link = "0", through = "O" }
        branch = -1
    """)
    for engine in ("numpy", "compiled") if velplan.analysis.compiled.available() else ("numpy",):
        kin = velplan.solve(mech, [0.0], engine=engine)
        assert kin.angle("2")[0] == np.pi
