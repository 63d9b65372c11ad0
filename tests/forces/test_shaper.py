"""The shaper of seed 002 with its masses and cutting force: the mean balancing moment is the
cutting work per revolution over 2π."""

import math

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.forces.common import as_complex, dot


@pytest.fixture(scope="module")
def shaper():
    return velplan.load("shaper")


def test_seed_002_masses_and_gravity(shaper):
    masses = {m.link: (m.mass, m.inertia, m.centre) for m in shaper.masses}
    assert masses == {"4": (22.0, 0.9, "S4"), "5": (3.0, 0.015, "S5"), "6": (52.0, None, "F")}
    assert shaper.gravity == 9.81
    kin = velplan.solve(shaper, [1.0])
    g = {f.label: f.vector[0] for f in vf.gravity_actions(shaper, kin).forces}
    assert g == pytest.approx({"G4": -22 * 9.81j, "G5": -3 * 9.81j, "G6": -52 * 9.81j})
    # centres at mid-length: S4 halfway O3→B, S5 halfway B→F
    for s, (p, q) in {"S4": ("O3", "B"), "S5": ("B", "F")}.items():
        mid = 0.5 * (as_complex(kin.position(p)) + as_complex(kin.position(q)))
        np.testing.assert_allclose(as_complex(kin.position(s)), mid, atol=1e-12)


def test_cutting_force_over_5_to_95_percent_of_the_working_stroke(shaper):
    (fc,) = vf.parse_loads(shaper)
    assert (fc.name, fc.force, fc.start, fc.end, fc.link, fc.point) == ("Fc", 1400.0, 0.05, 0.95, "6", "F")
    st = velplan.stroke(shaper)
    assert fc.track.H == pytest.approx(st.H, rel=1e-12)
    kin = velplan.solve(shaper, [fc.phi_on, fc.phi_off])
    x = kin.slide(fc.track.pair)[:, 0]
    frac = (x - fc.track.s_start) / (fc.track.s_end - fc.track.s_start)
    np.testing.assert_allclose(frac, [0.05, 0.95], atol=1e-12)
    # active and against the ram's motion inside, zero just outside and on the return stroke
    d = 1e-6
    phi = np.array([fc.phi_on - d, fc.phi_on + d, 0.5 * (fc.phi_on + fc.phi_off), fc.phi_off - d, fc.phi_off + d,
                    st.end.phi + 1.0])
    kin = velplan.solve(shaper, phi)
    f = fc.actions(kin).forces[0].vector
    np.testing.assert_allclose(np.abs(f), [0, 1400, 1400, 1400, 0, 0])
    v = as_complex(kin.velocity("F"))
    assert np.all(dot(f, v)[[1, 2, 3]] < 0)
    assert fc.work == pytest.approx(1400 * 0.9 * st.H)


def test_mean_balancing_moment_is_the_cutting_work_over_two_pi(shaper):
    (fc,) = vf.parse_loads(shaper)
    # cutting work = ∫ Fc·|dx_F| over the cut, from the solver's displacement at its ends
    kin = velplan.solve(shaper, [fc.phi_on, fc.phi_off])
    work = 1400.0 * abs(np.diff(kin.slide(fc.track.pair)[:, 0])[0])
    expected = work / (2 * math.pi)
    assert expected == pytest.approx(120.2882925590, rel=1e-9)  # 1400 N · 0.9 · 0.59984 m / 2π
    mean = vf.mean_balancing_moment(shaper, n=3600)
    assert mean == pytest.approx(expected, rel=1e-6)
    # A plain uniform mean is only first-order accurate across the jumps of Fc (error ~ 1e-4 here).
    uniform = vf.mean_balancing_moment(shaper, n=3600, quadrature="uniform")
    assert uniform == pytest.approx(expected, rel=1e-3)


def test_the_energy_form_of_seed_002(shaper):
    """M_b·ω1 = dT/dt + Fc·|V_F| − P_gravity, the Matlab program's formula plus gravity."""
    phi = velplan.positions(shaper, 36)
    res = vf.force_analysis_at(shaper, phi)
    kin = res.kinematics
    (fc,) = vf.parse_loads(shaper)
    cut = np.where(fc.active(kin), 1400.0 * np.abs(as_complex(kin.velocity("F"))), 0.0)
    g = sum(vf.powers(kin, vf.gravity_actions(shaper, kin)).values())
    expected = (vf.kinetic_energy_rate(shaper, kin) + cut - g) / kin.omega1
    np.testing.assert_allclose(res.kinetostatics.balancing_moment, expected, rtol=1e-10, atol=1e-9)
