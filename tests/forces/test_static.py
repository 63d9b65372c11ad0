"""Closed-form static cases: the crank-slider with a single force on the slider, and the
inertia of single links."""

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.forces.common import as_complex, cross, dot

P = -500.0  # N, along x on the slider


@pytest.fixture(scope="module")
def crank_slider():
    mech = velplan.load("crank-slider")
    phi = np.linspace(0.0, 2 * np.pi, 73)
    kin = velplan.solve(mech, phi)
    acts = vf.load_actions([vf.constant_force(mech, "B", P, 0.0, link="3", name="P")], kin)
    return mech, kin, acts, vf.kinetostatics(mech, kin, acts)


def test_balancing_moment_is_p_times_velocity_ratio(crank_slider):
    mech, kin, acts, ks = crank_slider
    vb = as_complex(kin.velocity("B"))
    # M_b·ω1 = −P·V_B (the force resists when it opposes V_B).
    np.testing.assert_allclose(ks.balancing_moment, -P * vb.real / kin.omega1, rtol=1e-12, atol=1e-12)


def test_reactions_of_a_two_force_rod(crank_slider):
    mech, kin, acts, ks = crank_slider
    a, b, o = (as_complex(kin.position(k)) for k in ("A", "B", "O"))
    u = (b - a) / 0.20
    t = -P / u.real  # compression of the rod, N
    n = -t * u.imag  # guide's push on the slider, N (vertical)
    r = ks.reactions
    np.testing.assert_allclose(r["O"].force, t * u, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r["A"].force, t * u, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r["B"].force, -t * u, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r["P:3/0"].force, 1j * n, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r["P:3/0"].moment, 0.0, atol=1e-9)
    np.testing.assert_allclose(r["P:3/0"].at, b, atol=1e-12)  # every slider force passes through B
    np.testing.assert_allclose(ks.balancing_moment, t * cross(a - o, u), rtol=1e-12, atol=1e-9)


def test_the_three_methods_agree_on_the_static_case(crank_slider):
    mech, kin, acts, ks = crank_slider
    np.testing.assert_allclose(vf.power_balancing_moment(kin, acts), ks.balancing_moment, rtol=0, atol=1e-10)
    from velplan.forces.lever import lever_balancing_moment

    np.testing.assert_allclose(lever_balancing_moment(mech, kin, acts), ks.balancing_moment, rtol=0, atol=1e-10)


def test_inertia_force_and_moment_and_percussion_centre():
    mech = velplan.load("slider-press")
    kin = velplan.solve(mech, [0.3, 1.7, 4.0])
    rod = next(q for q in vf.inertias(mech, kin) if q.link == "2")
    np.testing.assert_allclose(rod.force, -12.0 * as_complex(kin.acceleration("S2")), rtol=1e-12)
    np.testing.assert_allclose(rod.moment, -0.045 * kin.epsilon("2"), rtol=1e-12)
    # The single resultant through the foot point X has moment M_Φ about S, its arm is h.
    x = rod.resultant_point
    np.testing.assert_allclose(cross(x - rod.at, rod.force), rod.moment, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(np.abs(x - rod.at), np.abs(rod.offset), rtol=1e-12)
    # The centre of percussion K on the rod's axis S→B: same moment, and K is on the axis.
    b = as_complex(kin.position("B"))
    k = rod.percussion_point(b)
    np.testing.assert_allclose(cross(k - rod.at, rod.force), rod.moment, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(cross(k - rod.at, b - rod.at), 0.0, atol=1e-12)
    # The slider translates: no inertia moment, Φ = −m·a_B.
    slider = next(q for q in vf.inertias(mech, kin) if q.link == "3")
    np.testing.assert_allclose(slider.moment, 0.0, atol=1e-12)
    np.testing.assert_allclose(slider.force, -30.0 * as_complex(kin.acceleration("B")), rtol=1e-12)


def test_estimated_inertia_uses_k():
    assert vf.estimated_inertia(6.0, 0.6) == pytest.approx(6.0 * 0.36 / 10)
    assert vf.estimated_inertia(6.0, 0.6, k=8) == pytest.approx(6.0 * 0.36 / 8)
    mech = velplan.load("slider-press")  # the crank has no inertia given: J = 8·0.05²/K
    kin = velplan.solve(mech, [1.0])
    crank = next(q for q in vf.inertias(mech, kin, k=8.0) if q.link == "1")
    assert crank.inertia == pytest.approx(8.0 * 0.05**2 / 8.0)
    with pytest.raises(velplan.MechanismError, match=r"^coefficient K of J_S ≈ m·l²/K must be > 0, not 0$"):
        vf.estimated_inertia(1.0, 1.0, k=0)


def test_inertia_power_is_minus_kinetic_energy_rate():
    mech = velplan.load("shaper")
    phi = np.linspace(0, 2 * np.pi, 50, endpoint=False)
    kin = velplan.solve(mech, phi)
    inertia_power = sum(vf.powers(kin, vf.inertia_actions(mech, kin)).values())
    np.testing.assert_allclose(inertia_power, -vf.kinetic_energy_rate(mech, kin), rtol=1e-10, atol=1e-9)
    # dT/dt against a central difference of T in time (ω1 constant).
    h = 1e-6
    tp = vf.kinetic_energy(mech, velplan.solve(mech, phi + h))
    tm = vf.kinetic_energy(mech, velplan.solve(mech, phi - h))
    fd = (tp - tm) / (2 * h) * kin.omega1
    np.testing.assert_allclose(vf.kinetic_energy_rate(mech, kin), fd, rtol=1e-6, atol=1e-4)


def test_force_polygons_close_on_the_exact_reactions():
    """The closing vectors found by intersecting the two unknown directions equal the exact
    components of the reactions, for every group kind."""
    from tests.forces.mechs import four_bar_with_prp

    for mech in (velplan.load("shaper"), velplan.load("press"), velplan.load("slider-press"), four_bar_with_prp()):
        res = vf.force_analysis_at(mech, np.linspace(0.1, 2 * np.pi, 24, endpoint=False))
        ks = res.kinetostatics
        scale = max(float(np.nanmax(np.abs(r.force))) for r in ks.reactions.values())
        for g in mech.groups:
            poly = ks.polygons[g.name]
            assert np.nanmax(poly.misclosure()) <= 1e-9 * scale
            gp = [r for r in ks.reactions.values() if r.pair.group == g.name]
            (l1, d1), (l2, d2) = poly.closing
            v1, v2 = (v for _, v in poly.closing_vectors)
            # the first closing direction belongs to the first outer pair, the second to the last
            np.testing.assert_allclose(v1, dot(gp[0].force, d1) * d1, atol=1e-9 * scale)
            np.testing.assert_allclose(v2, dot(gp[2].force, d2) * d2, atol=1e-9 * scale)
        crank = ks.polygons["crank"]
        assert np.nanmax(crank.misclosure()) <= 1e-9 * scale
        verts = crank.vertices(mu_f=10.0)
        assert verts.shape[1] == len(crank.vectors) + 2


def test_positions_that_do_not_assemble_are_nan_not_errors():
    from tests.forces.mechs import example_text

    text = example_text("four-bar").replace("length = 0.10", "length = 0.20") + (
        '\n[link.2]\nmass = 2.0\ncentre = "S2"\n[[load]]\nkind = "moment"\nlink = "3"\nmoment = 5.0\n')
    mech = velplan.parse(text)
    phi = np.linspace(0, 2 * np.pi, 36, endpoint=False)
    res = vf.force_analysis_at(mech, phi)
    bad = ~res.kinematics.valid
    assert bad.any() and (~bad).any()
    for m in res.balancing_moments.values():
        assert np.isnan(m[bad]).all() and np.isfinite(m[~bad]).all()
    assert np.isnan(res.kinetostatics.reaction("B").force[bad]).all()
    assert res.max_relative_difference() < 1e-9
    with pytest.raises(velplan.MechanismError, match=r"^unknown pair 'Z'; known pairs: O, A, B, D$"):
        res.kinetostatics.reaction("Z")
    with pytest.raises(velplan.MechanismError, match=r"^load 'T': missing point$"):
        vf.table_force(mech, [0.0, 1.0], [1.0, 1.0], name="T")
