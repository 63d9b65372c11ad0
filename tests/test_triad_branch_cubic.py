"""The class III triad's branch read between its nodes by Hermite's cubic (`Track.pieces`): close
enough to the exact assemblies that one Newton step settles them, and the link points on the
triad's links placed from the unit vectors the group hands on (no sine of their angles)."""

import numpy as np
import pytest

import velplan
from velplan.analysis import prepared, solver, triad, triad_settle

EXAMPLES = ("triad-rocker", "triad-press")


def _branch(name):
    mech = velplan.load(name)
    prep = prepared.prepared(mech)
    g = next(x for x in prep.items if isinstance(x, triad.Triad))
    return prep, g, prep.tracks(solver.solve)[g.name]


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_cubic_lies_on_the_exact_assemblies(name):
    """At angles between the nodes the cubic is within 1e-9 of the group's size of the exact
    assembly (the nearest of all roots of the closure polynomial, found independently), a
    thousand times nearer than the chords."""
    prep, g, trk = _branch(name)
    assert trk.pieces is not None and trk.pieces.shape == (4, trk.t.size - 1, 3)
    phi = np.random.default_rng(7).uniform(0, 2 * np.pi, 400)
    leads = triad.leads_at(triad.upstream(prep.local, g), g, phi, velplan.solve)
    xs, ths, ok = triad._Closure(g, leads).candidates()
    for cubic, most in ((True, 1e-9), (False, None)):
        x, th, inside = trk.reference(phi, cubic=cubic)
        assert inside.all()
        d = triad._distance(xs, ths, x[:, None], th[:, None], trk.size)
        near = np.min(np.where(ok, d, np.inf), axis=1)
        if most is not None:
            assert near.max() <= most
            best = near.max()
        else:
            assert near.max() >= 1e3 * best  # the chords: ≈ 1e-6 off


@pytest.mark.parametrize("name", EXAMPLES)
def test_one_newton_step_settles_every_angle(name, monkeypatch):
    """From the cubic, Newton's first correction is already below `SETTLED`: with one step
    allowed every angle counts as settled, and the result is the exact assembly."""
    prep, g, trk = _branch(name)
    phi = np.linspace(0, 2 * np.pi, 1000, endpoint=False)
    leads = triad.leads_at(triad.upstream(prep.local, g), g, phi, velplan.solve)
    cl = triad._Closure(g, leads)
    monkeypatch.setattr(triad_settle, "STEPS", 1)
    xr, thr, _ = trk.reference(phi)
    x, th, ok, e = triad._settled(cl, xr, thr)
    assert ok.all()
    np.testing.assert_allclose(e, np.exp(1j * th), rtol=0, atol=4e-15)
    f, _ = cl._equations((x - cl.origin)[:, None], th[:, None])
    assert max(float(np.abs(r).max()) for r in f) <= 1e-14 * trk.size


@pytest.mark.parametrize("name", EXAMPLES)
def test_points_on_the_triads_links_from_their_angles(name):
    """Each link point equals its link's origin plus (along + i·offset)·(cos θ + i·sin θ) of the
    link's own solved angle, and its velocity and acceleration follow the link's ω, ε."""
    mech = velplan.load(name)
    phi = np.linspace(0, 2 * np.pi, 73)
    kin = velplan.solve(mech, phi, engine="numpy")
    z = lambda arr, n: arr[:, kin.point_index[n]] @ np.array([1, 1j])  # noqa: E731
    for pt in mech.points:
        origin = kin.link_origins[pt.link]
        th, w, e = kin.angle(pt.link), kin.omega(pt.link), kin.epsilon(pt.link)
        r = (pt.along + 1j * pt.offset) * np.exp(1j * th)
        np.testing.assert_allclose(z(kin.positions, pt.name), z(kin.positions, origin) + r, rtol=0, atol=1e-14)
        np.testing.assert_allclose(z(kin.velocities, pt.name), z(kin.velocities, origin) + 1j * w * r,
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(z(kin.accelerations, pt.name),
                                   z(kin.accelerations, origin) + (1j * e - w * w) * r, rtol=0, atol=1e-10)
