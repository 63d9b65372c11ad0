"""Reduced inertia, its derivative and reduced moments against an independent closed form
written out in mpmath (50 digits), and the kinetic-energy identity J = 2T/ω² (hypothesis)."""

from dataclasses import replace

import mpmath as mp
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import velplan
from velplan.dynamics.reduction import profile, reducer
from velplan.forces.power import kinetic_energy
from velplan.mechanism.model import LinkMass

from .conftest import DATA

mp.mp.dps = 50
R, L, E, A1, A2 = mp.mpf("0.05"), mp.mpf("0.20"), mp.mpf("0.02"), mp.mpf("0.02"), mp.mpf("0.07")
M1, J1, M2, J2, M3 = 4, mp.mpf("0.002"), 3, mp.mpf("0.011"), 6


def _closed(phi):
    """Offset crank-slider by hand: S1, S2, B and the rod angle β as functions of φ."""
    ax, ay = R * mp.cos(phi), R * mp.sin(phi)
    bx = ax + mp.sqrt(L**2 - (E - ay) ** 2)
    beta = mp.atan2(E - ay, bx - ax)
    s2x, s2y = ax + A2 * mp.cos(beta), ay + A2 * mp.sin(beta)
    return s2x, s2y, bx, beta


def _J(phi):
    d = lambda f: mp.diff(f, phi)  # noqa: E731
    s2x, s2y = d(lambda p: _closed(p)[0]), d(lambda p: _closed(p)[1])
    bx, beta = d(lambda p: _closed(p)[2]), d(lambda p: _closed(p)[3])
    return M1 * A1**2 + J1 + M2 * (s2x**2 + s2y**2) + J2 * beta**2 + M3 * bx**2


def _variable_J(phi):
    return _J(phi) - (M1 * A1**2 + J1)


def test_reduced_inertia_and_derivative_match_mpmath_to_1e12():
    mech = velplan.load(DATA / "slider-dyn.toml")
    red = reducer(mech)
    theta = np.array([0.1, 0.7, 1.9, 2.6, 3.3, 4.4, 5.5, 6.1])
    got = red(theta)
    assert red.sense == -1.0  # clockwise: dJ/dθ = −dJ/dφ
    assert abs(red.crank_inertia - float(M1 * A1**2 + J1)) < 1e-15
    for i, th in enumerate(theta):
        phi = mp.mpf(float(got.phi[i]))
        j = _variable_J(phi)
        dj = mp.diff(_variable_J, phi)
        assert abs(got.J[i] - float(j)) <= 1e-12 * float(j)
        assert abs(got.dJ[i] - float(-dj)) <= 1e-12 * float(mp.fabs(dj)) + 1e-15
        # constant force −500 N along x on B: M = F·dB/dθ = F·(−dB/dφ)
        m = -500 * -mp.diff(lambda p: _closed(p)[2], phi)
        assert abs(got.moments["F"][i] - float(m)) <= 1e-12 * 500 * 0.05


def test_profile_interpolates_the_solver_to_round_off():
    for name in ("shaper", "slider-press"):
        red = reducer(velplan.load(name))
        prof = profile(red)
        theta = np.random.default_rng(3).uniform(0, 2 * np.pi, 300)
        ex, v = red(theta), prof.values(theta)
        scale_m = max(np.abs(r).max() for r in ex.moments.values())
        assert np.max(np.abs(v[0] - ex.J)) <= 1e-12 * ex.J.max()
        assert np.max(np.abs(v[1] - ex.dJ)) <= 1e-12 * np.abs(ex.dJ).max()
        for i, k in enumerate(prof.labels):
            assert np.max(np.abs(v[2 + i] - ex.moments[k])) <= 1e-12 * scale_m


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(0.1, 50.0), min_size=4, max_size=4), st.lists(st.floats(0.0, 0.5), min_size=2, max_size=2),
       st.floats(-40.0, 40.0).filter(lambda w: abs(w) > 0.1), st.floats(0.0, 2 * np.pi))
def test_reduced_inertia_is_twice_the_kinetic_energy_over_omega_squared(m, j, omega, phi):
    base = velplan.load(DATA / "slider-dyn.toml")
    mech = replace(base, masses=(LinkMass("1", m[0], "S1", j[0]), LinkMass("2", m[1], "S2", j[1]),
                                 LinkMass("3", m[2], "B", None)))
    red = reducer(mech, ())
    got = red(np.array([red.sense * (phi - red.phi1)]))
    kin = velplan.solve(mech, np.array([phi]), omega1=omega, epsilon1=0.0)
    T = kinetic_energy(mech, kin)[0]
    J = red.crank_inertia + got.J[0]
    assert abs(J - 2 * T / omega**2) <= 1e-12 * J
