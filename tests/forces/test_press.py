"""Seed 000's static moment (table 3) on the press, and seed 004's parabolic press load with
its Fourier series on the slider press."""

import math

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.forces.common import as_complex

# Seed 000, table 3: angles (°) between G2 (and G3) and V_B2, and between G5 and V_E.
TABLE3_G2 = [180, 128, 104, 90, 77, 52, 0, 46, 69.5, 90, 110, 132]
TABLE3_G5 = [np.nan, 79, 84.5, 90, 98.5, 102, np.nan, 78, 82, 90, 97, 101]


@pytest.fixture(scope="module")
def press():
    mech = velplan.load("press")
    q = vf.table_force(mech, [0.0, 0.1], [1000.0, 1000.0], over="output", stroke="working",
                       direction="against-motion", name="Q")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    return mech, q, kin


def test_press_masses_are_declared(press):
    mech, _, _ = press
    assert {m.link: (m.mass, m.centre) for m in mech.masses} == {
        "2": (6.0, "S2"), "3": (1.0, "S3"), "4": (20.0, "S4"), "5": (3.0, "S5")}
    kin = velplan.solve(mech, [0.4, 2.0])
    for s, p in {"S2": "B2", "S3": "B2", "S4": "K4", "S5": "E"}.items():  # where seed 000 applies G2…G5
        np.testing.assert_allclose(kin.position(s), kin.position(p), atol=1e-12)


def test_static_moment_reproduces_table_3_angles(press):
    mech, q, kin = press
    st = vf.static_moment(kin, vf.gravity_actions(mech, kin) + q.actions(kin))
    assert st.labels == ("G2", "G3", "G4", "G5", "Q")
    ang = dict(zip(st.labels, st.angle_deg.T))
    np.testing.assert_allclose(ang["G2"], TABLE3_G2, atol=3.0)  # read off drawn plans to a few degrees
    np.testing.assert_allclose(ang["G3"], ang["G2"])
    np.testing.assert_allclose(ang["G5"], TABLE3_G5, atol=3.0)  # NaN where V_E = 0 (positions 1, 7)
    np.testing.assert_allclose(ang["G4"][np.isfinite(ang["G4"])], 90.0, atol=1e-9)  # punch moves horizontally
    # Q acts on the pressing stroke only, always against V_B4. K = 1 for this press, so the
    # working stroke is the one that starts at the reference position 1 (φ = 0°): 2–6 here.
    pressing = np.isfinite(ang["Q"])
    assert list(np.flatnonzero(pressing) + 1) == [2, 3, 4, 5, 6]
    np.testing.assert_allclose(ang["Q"][pressing], 180.0)
    # M_st = −Σ F·(V/ω1)·cos: the Q term is +Q·V_B4/ω1 during pressing
    vb4 = np.abs(as_complex(kin.velocity("B4"))) / kin.omega1
    np.testing.assert_allclose(st.terms[:, -1], np.where(pressing, -1000.0 * vb4, 0.0), atol=1e-12)


def test_static_moment_is_the_power_method_without_inertia(press):
    mech, q, kin = press
    acts = vf.gravity_actions(mech, kin) + q.actions(kin)
    st = vf.static_moment(kin, acts)
    np.testing.assert_allclose(st.moment, vf.power_balancing_moment(kin, acts), rtol=1e-12, atol=1e-12)
    res = vf.force_analysis_at(mech, kin.phi, loads=[q], inertia=False)
    np.testing.assert_allclose(st.moment, res.kinetostatics.balancing_moment, rtol=1e-9, atol=1e-12)
    with pytest.raises(velplan.MechanismError, match="^the static moment takes gravity and loads only, not inertia forces$"):
        vf.static_moment(kin, vf.inertia_actions(mech, kin))


@pytest.fixture(scope="module")
def parabola():
    mech = velplan.load("slider-press")
    (load,) = vf.parse_loads(mech)
    return mech, load


def test_start_and_end_from_the_distances_to_the_lower_extreme(parabola):
    mech, p = parabola
    assert (p.name, p.p_max, p.b1, p.b2, p.harmonics) == ("P", 40000.0, 0.02, 0.005, None)
    st = velplan.stroke(mech)
    kin = velplan.solve(mech, [st.start.phi, st.end.phi, p.phi_start, p.phi_end])
    y = as_complex(kin.position("B")).imag
    lower = min(y[0], y[1])
    np.testing.assert_allclose(y[2:] - lower, [0.025, 0.005], atol=1e-12)
    assert np.all(as_complex(kin.velocity("B")).imag[2:] < 0)  # approaching the lower extreme
    # crank 0.05 m, rod 0.20 m, slider on the vertical through O: y_B = −(r·sin… ) closed form
    for phi, d in ((p.phi_start, 0.025), (p.phi_end, 0.005)):
        yb = 0.05 * math.sin(phi) - math.sqrt(0.2**2 - (0.05 * math.cos(phi)) ** 2)
        assert yb == pytest.approx(-0.25 + d, abs=1e-12)


def test_parabola_through_the_three_points_of_seed_004(parabola):
    _, p = parabola
    a, b, c = p.parabola
    fs = p.phi_start
    fe = p.phi_start + p.width
    for phi, value in ((fs, 0.0), (fe, 40000.0), (2 * fe - fs, 0.0)):
        assert a * phi**2 + b * phi + c == pytest.approx(value, abs=1e-6)
    assert p.exact(np.array([p.phi_end]))[0] == pytest.approx(40000.0)
    assert p.exact(np.array([p.phi_end + 1e-9, p.phi_start - 1e-9])).tolist() == [0.0, 0.0]
    mid = p.phi_start + 0.5 * p.width
    assert p.exact(np.array([mid]))[0] == pytest.approx(30000.0)  # ψ = Δ/2: P_max·(1 − 1/4)


def test_fourier_coefficients_match_quadrature(parabola):
    _, p = parabola
    series = p.fourier(10)
    x, w = np.polynomial.legendre.leggauss(40)
    phi = p.phi_start + 0.5 * p.width * (x + 1)
    w = 0.5 * p.width * w
    vals = p.exact(phi)
    for k in range(11):
        ak = np.sum(w * vals * np.cos(k * phi)) / math.pi
        bk = np.sum(w * vals * np.sin(k * phi)) / math.pi
        assert series.a[k] == pytest.approx(ak, abs=1e-8)
        assert series.b[k] == pytest.approx(bk, abs=1e-8)
    assert series.a[0] / 2 == pytest.approx(40000 * (2 / 3) * p.width / (2 * math.pi))


def test_fourier_error_decreases_with_the_number_of_harmonics(parabola):
    _, p = parabola
    errors = [p.approximation_error(n) for n in range(1, 11)]
    rms = [e[1] for e in errors]
    assert all(b < a for a, b in zip(rms, rms[1:]))
    assert rms[0] == pytest.approx(7619.19, rel=1e-5) and rms[-1] == pytest.approx(2786.20, rel=1e-5)
    # Parseval against a dense sample
    phi = np.linspace(0, 2 * math.pi, 1 << 16, endpoint=False)
    sampled = math.sqrt(np.mean((p.fourier(10)(phi) - p.exact(phi)) ** 2))
    assert sampled == pytest.approx(rms[-1], rel=1e-3)
    # the load jumps from P_max to 0 at φ_end, so the largest error never drops below P_max/2 (Gibbs)
    assert all(e[0] >= 20000.0 for e in errors)


def test_series_as_the_load(parabola):
    mech, p = parabola
    text = "\n".join(["[[load]]", 'kind = "press"', "p_max = 40000.0", "b1 = 0.02", "b2 = 0.005", "harmonics = 5"])
    from tests.forces.mechs import example_text

    m2 = velplan.parse(example_text("slider-press").split("[[load]]")[0] + text)
    (s,) = vf.parse_loads(m2)
    assert s.harmonics == 5 and s.name == "#1"
    kin = velplan.solve(m2, np.linspace(0, 6, 7))
    np.testing.assert_allclose(s.actions(kin).forces[0].vector.imag, p.fourier(5)(kin.phi), rtol=1e-12)


def test_mean_balancing_moment_is_the_press_work(parabola):
    mech, p = parabola
    x, w = np.polynomial.legendre.leggauss(60)
    phi = p.phi_start + 0.5 * p.width * (x + 1)
    kin = velplan.solve(mech, phi)
    work = np.sum(0.5 * p.width * w * p.exact(phi) * np.abs(as_complex(kin.velocity("B"))) / kin.omega1)
    assert vf.mean_balancing_moment(mech, n=3600) == pytest.approx(work / (2 * math.pi), rel=1e-9)
