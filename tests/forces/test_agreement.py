"""Kinetostatics, Zhukovsky's lever and the power method agree to round-off in exact mode."""

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from tests.forces.mechs import four_bar_with_prp

TOL = 1e-9


def _mechanisms():
    out = [(name, velplan.load(name)) for name in velplan.example_names() if velplan.load(name).masses]
    out.append(("four-bar-prp", four_bar_with_prp()))
    return out


MECHS = _mechanisms()


def test_every_example_with_masses_is_checked():
    assert {n for n, _ in MECHS} >= {"press", "shaper", "slider-press", "four-bar-prp"}


@pytest.mark.parametrize("name, mech", MECHS, ids=[n for n, _ in MECHS])
def test_three_balancing_moments_agree(name, mech):
    phi = np.linspace(0.0, 2 * np.pi, 1440, endpoint=False) + 0.001
    res = vf.force_analysis_at(mech, phi)
    bm = res.balancing_moments
    ref = bm["kinetostatics"]
    assert np.isfinite(ref).all()
    scale = np.max(np.abs(ref))
    assert scale > 0
    big = np.abs(ref) > 1e-6 * scale
    for method in ("lever", "power"):
        diff = np.abs(bm[method] - ref)
        assert np.max(diff) <= TOL * scale, method
        assert np.max(diff[big] / np.abs(ref[big])) <= 1e-8, method  # per position, away from zeros
    assert res.max_relative_difference() <= TOL


@pytest.mark.parametrize("name, mech", MECHS, ids=[n for n, _ in MECHS])
def test_reactions_balance_every_link(name, mech):
    """Σ F = 0 on every moving link with the reactions, the actions and M_b."""
    phi = np.linspace(0.2, 2 * np.pi, 36, endpoint=False)
    res = vf.force_analysis_at(mech, phi)
    ks, acts = res.kinetostatics, res.actions
    scale = max(float(np.max(np.abs(r.force))) for r in ks.reactions.values())
    for link in mech.links:
        total = sum((f.vector for f in acts.on(link).forces), np.zeros(len(phi), complex))
        for r in ks.reactions.values():
            if r.pair.links[0] == link:
                total = total + r.force
            elif r.pair.links[1] == link:
                total = total - r.force
        assert np.max(np.abs(total)) <= 1e-10 * scale, link


def test_lever_is_independent_of_the_scale_and_takes_xy_images():
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    acts = vf.mechanism_actions(mech, kin)
    ref = vf.kinetostatics(mech, kin, acts).balancing_moment
    for i in range(12):
        for mu_v in (0.002, 0.01):
            images = {k: (v.real, v.imag) for k, v in vf.images_from_kinematics(kin, i + 1, mu_v).items()}
            lv = vf.zhukovsky_lever(mech, vf.positions_from_kinematics(kin, i + 1), images, mu_v, acts.at(i))
            assert lv.balancing_moment[0] == pytest.approx(ref[i], rel=1e-9, abs=1e-9)
            # M_b = F_b·l_OA with F_b ⊥ the crank at the tip image
            assert lv.balancing_force[0] * 0.1605 == pytest.approx(lv.balancing_moment[0], rel=1e-12, abs=1e-12)


def test_percent_difference_of_a_drafted_plan():
    """Images measured 1 % long (the crank tip's image laid off exactly) give M_b 1 % large;
    a uniform scale error of the whole plan cancels out."""
    mech = velplan.load("slider-press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    acts = vf.mechanism_actions(mech, kin, inertia=False)
    ref = vf.kinetostatics(mech, kin, acts).balancing_moment
    exact = vf.images_from_kinematics(kin, None, 0.005)
    pos = vf.positions_from_kinematics(kin, None)
    ok = np.abs(ref) > 1e-6
    images = {k: (v if k == "A" else 1.01 * v) for k, v in exact.items()}
    pct = vf.lever_difference_percent(vf.zhukovsky_lever(mech, pos, images, 0.005, acts).balancing_moment, ref)
    np.testing.assert_allclose(pct[ok], np.sign(ref[ok]), atol=1e-9)  # signed: M_b is 1 % larger in size
    images = {k: 1.01 * v for k, v in exact.items()}
    pct = vf.lever_difference_percent(vf.zhukovsky_lever(mech, pos, images, 0.005, acts).balancing_moment, ref)
    np.testing.assert_allclose(pct[ok], 0.0, atol=1e-9)
    assert np.all(np.isnan(vf.lever_difference_percent([0.0], [0.0])))
    assert vf.lever_difference_percent([103.0], [-100.0])[0] == pytest.approx(203.0)


def test_lever_needs_the_images_it_uses():
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, [1.0])
    acts = vf.mechanism_actions(mech, kin)
    images = vf.images_from_kinematics(kin, 1, 0.01)
    del images["S4"]
    with pytest.raises(velplan.VelplanError, match=r"^the velocity plan has no point 'S4' \(needed for force 'G4'\)$"):
        vf.zhukovsky_lever(mech, vf.positions_from_kinematics(kin, 1), images, 0.01, acts.at(0))
    with pytest.raises(velplan.VelplanError, match=r"^velocity scale μv must be > 0 \(m/s\)/mm, not 0$"):
        vf.images_from_kinematics(kin, 1, 0)
