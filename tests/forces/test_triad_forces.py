"""Kinetostatics of class III groups (triads): the 12 × 12 reactions against link-by-link
equilibrium and an independently built system, the force polygon by Assur's special point,
the three balancing moments, and the dynamic reduction."""

import dataclasses
import json
from importlib import resources

import numpy as np
import pytest

import velplan
from velplan.analysis.solver import solve
from velplan.cli import main
from velplan.forces.agreement import mechanism_actions
from velplan.forces.common import as_complex, cross, point
from velplan.forces.kinetostatics import kinetostatics
from velplan.forces.lever import lever_balancing_moment
from velplan.forces.power import power_balancing_moment
from velplan.forces.inertia import inertia_of
from velplan.mechanism.loader import parse as load_text
from velplan.mechanism.model import Triad
from velplan.mechanism.structure import pairs

# The catalogue's triad-rocker with its rocker 5 replaced by a block on a fixed guide through H
# (the tangent of D's arc at the assembly), a force and a mass on the block, a couple on 4.
BLOCK = """
name = "triad-block-test"
[ground]
O1 = [0.0, 0.0]
E = [0.574, 0.011]
H = [0.373, 0.124]
[crank]
link = "1"
pivot = "O1"
tip = "A"
length = 0.078
rpm = 90.0
[[group]]
kind = "triad"
name = "3-2-4-5"
base = "3"
joints = ["B", "C", "D"]
sides = [0.241, 0.205, 0.311]
side = -1
leads = [
  { link = "2", joint = "A", length = 0.347 },
  { link = "4", joint = "E", length = 0.347 },
  { link = "5", guide = { link = "0", through = "H", angle_deg = 123.0 } },
]
assembly = { phi_deg = 90, B = [0.185, 0.372], C = [0.421, 0.323], D = [0.373, 0.124] }
[[point]]
name = "S2"
link = "2"
along = 0.1735
[[point]]
name = "S3"
link = "3"
along = 0.1583
offset = -0.0683
[[point]]
name = "S4"
link = "4"
along = 0.1735
[[point]]
name = "G5"
link = "5"
along = 0.03
offset = 0.01
[link.2]
mass = 2.4
inertia = 0.024
centre = "S2"
[link.3]
mass = 4.5
inertia = 0.030
centre = "S3"
[link.4]
mass = 2.4
inertia = 0.024
centre = "S4"
[link.5]
mass = 1.5
inertia = 0.004
centre = "G5"
[[load]]
kind = "force"
name = "Q"
point = "G5"
link = "5"
fx = -120.0
fy = 60.0
[[load]]
kind = "moment"
name = "M4"
link = "4"
moment = 7.5
"""


def _catalogue_triads() -> list[str]:
    files = resources.files("velplan.catalogue")
    names = sorted(f.name[:-5] for f in files.iterdir() if f.name.endswith(".toml")
                   and 'kind = "triad"' in f.read_text(encoding="utf-8"))
    assert "triad-rocker" in names
    return names


def _with_pair(mech, pair):
    groups = tuple(dataclasses.replace(g, pair=pair) if isinstance(g, Triad) else g for g in mech.groups)
    return dataclasses.replace(mech, groups=groups, name=f"{mech.name}@{pair}")


def _mechanisms():
    out = {name: velplan.load(name) for name in _catalogue_triads()}
    block = load_text(BLOCK, name="triad-block-test")
    out["triad-block-test"] = block
    for pair in ((0, 1), (0, 2), (1, 2)):  # every lead in turn gives its Rⁿ by ΣM_S
        out[f"triad-block-test@{pair}"] = _with_pair(block, pair)
        out[f"triad-rocker@{pair}"] = _with_pair(velplan.load("triad-rocker"), pair)
    return out


MECHS = _mechanisms()
_CACHE = {}


def _analysis(key):
    if key not in _CACHE:
        mech = MECHS[key]
        kin = solve(mech, velplan.positions(mech, 72))
        assert kin.valid.all(), f"{key} does not close over the turn"
        acts = mechanism_actions(mech, kin)
        _CACHE[key] = (mech, kin, acts, kinetostatics(mech, kin, acts))
    return _CACHE[key]


def _force_scale(acts, ks) -> float:
    big = [np.abs(f.vector).max() for f in acts.forces] + [np.nanmax(r.magnitude) for r in ks.reactions.values()]
    return float(max(big))


def _triads(mech):
    return [g for g in mech.groups if isinstance(g, Triad)]


@pytest.mark.parametrize("key", sorted(MECHS))
def test_three_methods_agree(key):
    mech, kin, acts, ks = _analysis(key)
    mb = ks.balancing_moment
    scale = np.abs(mb).max()
    assert scale > 0.1
    for other in (lever_balancing_moment(mech, kin, acts, mu_v=0.01), power_balancing_moment(kin, acts)):
        assert np.abs(other - mb).max() <= 1e-9 * scale


@pytest.mark.parametrize("key", sorted(MECHS))
def test_every_link_in_equilibrium(key):
    """ΣF and ΣM of the loads, gravity, inertia and every pair reaction (and M_b on the crank)
    on each moving link, summed here from the reactions as reported."""
    mech, kin, acts, ks = _analysis(key)
    f_big = _force_scale(acts, ks)
    size = float(np.abs(as_complex(kin.positions)).max())
    for link in mech.links:
        ref = point(kin, mech.crank.pivot) + 0.3 + 0.2j  # any point will do
        f = np.zeros(len(kin), complex)
        m = np.zeros(len(kin))
        for a in acts.forces:
            if a.link == link:
                f, m = f + a.vector, m + cross(point(kin, a.point) - ref, a.vector)
        m = m + sum((a.moment for a in acts.moments if a.link == link), np.zeros(len(kin)))
        for r in ks.reactions.values():
            if link in r.pair.links:
                s = 1.0 if r.pair.links[0] == link else -1.0
                f, m = f + s * r.force, m + s * (cross(r.reference - ref, r.force) + r.moment)
        if link == mech.crank.link:
            m = m + ks.balancing_moment
        assert np.abs(f).max() <= 1e-9 * f_big, link
        assert np.abs(m).max() <= 1e-9 * f_big * size, link


def _independent(mech, kin, acts, ks, g):
    """The group's reactions from a system built here: rows per link in reverse order (ΣM about
    the link's own joint, ΣFy, ΣFx), unknowns inner pairs first then outer, (Ry, Rx) of a
    revolute pair and (moment about the world origin, N) of a prismatic one."""
    gp = [p for p in pairs(mech) if p.group == g.name]
    inner = [p for p in gp if p.point in g.joints and p.kind == "R"]
    order = inner + [p for p in gp if p not in inner]
    assert len(order) == 6 and {p.name for p in order} == {p.name for p in gp}
    links = list(reversed(g.links))
    centre = {g.base: g.joints[1]} | {lead.link: j for lead, j in zip(g.leads, g.joints)}
    n = len(kin)
    a = np.zeros((n, 12, 12))
    b = np.zeros((n, 12))
    for row, link in enumerate(links):
        c = point(kin, centre[link])
        for col, p in enumerate(order):
            if link not in p.links:
                continue
            s = 1.0 if p.links[0] == link else -1.0
            if p.kind == "R":
                r = point(kin, p.point) - c
                a[:, 3 * row, 2 * col] += s * r.real  # Ry
                a[:, 3 * row, 2 * col + 1] -= s * r.imag  # Rx
                a[:, 3 * row + 1, 2 * col] += s
                a[:, 3 * row + 2, 2 * col + 1] += s
            else:
                nrm = 1j * np.exp(1j * kin.angle(p.links[0]))
                a[:, 3 * row, 2 * col] += s  # the P reaction's moment about the origin
                a[:, 3 * row, 2 * col + 1] -= s * cross(c, nrm)
                a[:, 3 * row + 1, 2 * col + 1] += s * nrm.imag
                a[:, 3 * row + 2, 2 * col + 1] += s * nrm.real
        known_f, known_m = np.zeros(n, complex), np.zeros(n)
        for f in acts.forces:
            if f.link == link:
                known_f, known_m = known_f + f.vector, known_m + cross(point(kin, f.point) - c, f.vector)
        known_m = known_m + sum((m.moment for m in acts.moments if m.link == link), np.zeros(n))
        for r in ks.reactions.values():  # later groups pushing on this one
            if r.pair.group != g.name and link == r.pair.links[1]:
                known_f, known_m = known_f - r.force, known_m - cross(r.reference - c, r.force) - r.moment
        b[:, 3 * row], b[:, 3 * row + 1], b[:, 3 * row + 2] = -known_m, -known_f.imag, -known_f.real
    x = np.linalg.solve(a, b[..., None])[..., 0]
    out = {}
    for col, p in enumerate(order):
        if p.kind == "R":
            out[p.name] = (x[:, 2 * col + 1] + 1j * x[:, 2 * col], np.zeros(n))
        else:
            nrm = 1j * np.exp(1j * kin.angle(p.links[0]))
            force = x[:, 2 * col + 1] * nrm
            out[p.name] = (force, x[:, 2 * col] - cross(point(kin, p.point), force))  # couple about J
    return out


@pytest.mark.parametrize("key", sorted(MECHS))
def test_reactions_by_an_independent_system(key):
    mech, kin, acts, ks = _analysis(key)
    f_big = _force_scale(acts, ks)
    for g in _triads(mech):
        assert ks.condition[g.name].min() > 1e-3
        for name, (force, couple) in _independent(mech, kin, acts, ks, g).items():
            r = ks.reactions[name]
            assert np.abs(force - r.force).max() <= 1e-9 * f_big, name
            assert np.abs(couple - r.moment).max() <= 1e-9 * f_big, name


@pytest.mark.parametrize("key", sorted(MECHS))
def test_force_polygon_by_special_point(key):
    """The polygon closes, and the reactions it gives (Rᵗ from each lead's moment about its
    inner joint, the third Rⁿ from ΣM_S, the two others by closing it, the inner ones from
    each lead's ΣF) are the solver's."""
    mech, kin, acts, ks = _analysis(key)
    f_big = _force_scale(acts, ks)
    for g in _triads(mech):
        poly = ks.polygons[g.name]
        assert poly.kind == "triad" and len(poly.closing) == 2
        assert poly.misclosure().max() <= 1e-9 * f_big
        assert np.abs(poly.special - point(kin, g.special_name)).max() <= 1e-9
        for i, lf in enumerate(poly.leads):
            name = [p.name for p in pairs(mech) if p.group == g.name][2 * i]
            r = ks.reactions[name]
            assert np.abs(poly.outer[name] - r.force).max() <= 1e-9 * f_big
            if lf.rod:  # Rᵗ ⊥ the rod, Rⁿ along it
                assert np.abs(cross(lf.along, lf.tangential) - cross(lf.along, r.force)).max() <= 1e-9 * f_big
            else:  # no friction: the guide pushes along its normal; the couple from ΣM_J of the block
                assert np.abs(cross(lf.along, r.force)).max() <= 1e-9 * f_big
                assert np.abs(lf.couple - r.moment).max() <= 1e-9 * f_big
        for name, v in poly.inner.items():
            assert np.abs(v - ks.reactions[name].force).max() <= 1e-9 * f_big
        labels = [lab for lab, _ in poly.vectors]
        assert len(labels) == len(set(labels))
        closing = dict(poly.closing_vectors)
        for (lab, d), (lab2, v) in zip(poly.closing, poly.closing_vectors):
            assert lab == lab2 and np.abs(cross(d, v)).max() <= 1e-9 * f_big
        assert set(closing) | set(labels) >= {lf.label + ("n" if lf.rod else "") for lf in poly.leads}


def test_block_lead_polygon_labels():
    mech, kin, acts, ks = _analysis("triad-block-test@(0, 1)")
    poly = ks.polygons["3-2-4-5"]
    assert poly.pair == (0, 1) and poly.third == 2
    assert [lab for lab, _ in poly.vectors][:3] == ["R12τ", "R04τ", "R05"]
    assert [lab for lab, _ in poly.closing] == ["R12n", "R04n"]


def _forces_cli_available() -> bool:
    from velplan.plans import Plan

    try:
        Plan.of(velplan.load("triad-rocker"))
    except (KeyError, NotImplementedError):
        return False
    return True


@pytest.mark.skipif(not _forces_cli_available(), reason="the triad's velocity plan is not constructed yet")
@pytest.mark.parametrize("name", _catalogue_triads())
def test_cli_forces_agree(capsys, name):
    assert main(["forces", name, "--positions", "72", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    mb = np.array([[p["balancing_moment"][k] for k in ("kinetostatics", "lever", "power")] for p in doc["positions"]])
    scale = np.abs(mb[:, 0]).max()
    assert np.abs(mb[:, 1:] - mb[:, :1]).max() <= 1e-9 * scale


def _derivative(f, phi, h=1e-3):
    """Five-point central difference of f(φ) (arrays over φ, unwrapped angles allowed)."""
    return (-f(phi + 2 * h) + 8 * f(phi + h) - 8 * f(phi - h) + f(phi - 2 * h)) / (12 * h)


@pytest.mark.parametrize("name", _catalogue_triads())
def test_reduced_inertia_by_differences(name):
    """J_red of the dynamics = Σ (m·v_S² + J_S·ω²)/ω1² with v_S/ω1, ω/ω1 from differences of
    the positions alone."""
    from velplan.dynamics.reduction import reducer

    mech = velplan.load(name)
    theta = np.linspace(0.0, 2 * np.pi, 25)[:-1]
    red = reducer(mech)(theta)
    masses = [m for m in mech.masses if m.link != mech.crank.link]
    assert all(set(g.links) <= {m.link for m in masses} for g in _triads(mech))

    def state(phi):
        kin = solve(mech, phi, omega1=1.0, epsilon1=0.0, order=0)
        z = as_complex(kin.positions)
        return np.stack([z[:, kin.point_index[m.centre]] for m in masses]
                        + [np.exp(1j * kin.angle(m.link)) for m in masses])

    def angles_and_points(phi):
        s = state(phi)
        k = len(masses)
        return s[:k], np.unwrap(np.angle(s[k:]) - np.angle(state(red.phi)[k:]), axis=1)

    v = _derivative(lambda p: angles_and_points(p)[0], red.phi)
    w = _derivative(lambda p: angles_and_points(p)[1], red.phi)
    j = sum(m.mass * np.abs(v[i]) ** 2 + inertia_of(mech, m) * w[i].real ** 2 for i, m in enumerate(masses))
    assert np.abs(red.J - j).max() <= 1e-8 * j.max()
    assert j.min() > 0


def test_dynamics_cli_runs(capsys):
    assert main(["dynamics", "triad-rocker", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["flywheel"]["exact"] > 0 and np.isfinite(doc["omega_min"])
    mech = velplan.load("triad-rocker")
    for p in doc["positions"]:
        kin = solve(mech, np.radians([p["phi_deg"]]), omega1=1.0, epsilon1=0.0)
        j = sum(m.mass * float(np.sum(kin.velocity(m.centre)[0] ** 2))
                + inertia_of(mech, m) * float(kin.omega(m.link)[0]) ** 2
                for m in mech.masses if m.link != mech.crank.link)
        assert p["J_red"] - doc["J_declared"] == pytest.approx(j, rel=1e-9)
