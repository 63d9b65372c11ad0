"""The class III triad from outside the solver: the CLI's derivatives against finite differences
of its own positions, Assur's special point, every assembly against a dense scan of the
closure, the assembly limits and singular positions, loader errors, the catalogue and the
compiled engine's fallback. (The 50-digit reference is in test_triad_oracle.py.)"""

from __future__ import annotations

import cmath
import contextlib
import io
import json
import math
import re
import warnings
from math import factorial
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import velplan
import velplan.analysis.solver
from velplan.analysis import triad
from velplan.analysis.assembly import check_full_rotation, limits
from velplan.cli import main
from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND

from tests.test_triad_oracle import Reference, triad_mechanisms

ROCKER = (Path(velplan.__file__).parent / "catalogue" / "triad-rocker.toml").read_text(encoding="utf-8")


def run_cli(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(list(argv)) == 0
    return out.getvalue()


def local_joints(g):
    """B, C, D in the base link's frame, from the sides (law of cosines), complex."""
    bc, cd, db = g.sides
    along = (bc * bc + db * db - cd * cd) / (2 * bc)
    return [0j, complex(bc, 0), complex(along, g.side * math.sqrt(db * db - along * along))]


# ---- derivatives of the CLI's own output ---------------------------------------------------------


def central_difference(f: np.ndarray, h: float, m: int = 6, wrap=None) -> np.ndarray:
    """df/dφ of periodic samples (axis 0, step h rad) by the central difference of order 2m;
    ``wrap`` folds differences (angles: into (−π, π])."""
    out = np.zeros_like(f)
    for k in range(1, m + 1):
        w = (-1) ** (k + 1) * factorial(m) ** 2 / (k * factorial(m - k) * factorial(m + k))
        ahead, behind = np.roll(f, -k, axis=0) - f, f - np.roll(f, k, axis=0)
        if wrap is not None:
            ahead, behind = wrap(ahead), wrap(behind)
        out = out + w * (ahead + behind)
    return out / h


FD_TOL = 1e-7
"""Relative error allowed to the 12th-order differences at h = 5°: their truncation error,
measured against the 8th and 10th orders on the three catalogue triads, is below 3e-9."""


@pytest.mark.parametrize("name", triad_mechanisms())
def test_cli_velocities_and_accelerations_are_derivatives(name):
    doc = json.loads(run_cli("analyze", name, "--positions", "72", "--format", "json"))
    pos, w1 = doc["positions"], doc["omega1"]
    assert len(pos) == 72 and all(p["valid"] for p in pos)
    phi = np.unwrap(np.radians([p["phi_deg"] for p in pos]))
    steps = np.diff(phi)
    assert np.allclose(steps, steps[0], rtol=1e-9, atol=0) and abs(abs(steps[0]) * 72 - 2 * math.pi) < 1e-9
    h = float(steps[0])  # negative for a crank turning clockwise: positions follow the crank
    # the special point is where two lead lines cross: not a fixed point of the base link, so
    # its velocity (that of the base link's point there) is not the derivative of its position
    special = {g.special_name for g in velplan.load(name).groups if g.kind == "triad"}
    names = [n for n in pos[0]["points"] if n not in special]
    get = lambda keys: np.array([[[p["points"][n][q] for q in keys] for n in names] for p in pos])  # noqa: E731
    x, v, a = get(("x", "y")), get(("vx", "vy")), get(("ax", "ay"))
    links = list(pos[0]["links"])
    lget = lambda key: np.array([[p["links"][k][key] for k in links] for p in pos])  # noqa: E731
    th, w, e = lget("angle"), lget("omega"), lget("epsilon")
    fold = lambda d: np.mod(d + np.pi, 2 * np.pi) - np.pi  # noqa: E731
    pairs = [(w1 * central_difference(x, h), v), (w1 * central_difference(v, h), a),
             (w1 * central_difference(th, h, wrap=fold), w), (w1 * central_difference(w, h), e)]
    slides = list(pos[0]["slides"])
    if slides:
        s = np.array([[p["slides"][k][q] for k in slides for q in ("s", "v", "a")] for p in pos]).reshape(72, -1, 3)
        pairs += [(w1 * central_difference(s[..., 0], h), s[..., 1]),
                  (w1 * central_difference(s[..., 1], h), s[..., 2])]
    for fd, exact in pairs:
        assert np.max(np.abs(fd - exact)) <= FD_TOL * np.max(np.abs(exact))


# ---- Assur's special point ---------------------------------------------------------------------


@pytest.mark.parametrize("name", triad_mechanisms())
def test_special_point_lies_on_both_chosen_lead_lines(name):
    mech = velplan.load(name)
    kin = velplan.solve(mech, np.radians(np.arange(12) * 30.0))
    for g in (g for g in mech.groups if g.kind == "triad"):
        size = max(max(g.sides), max(lead.length for lead in g.leads))
        K = kin.positions[:, kin.point_index[g.special_name]] @ np.array([1, 1j])
        for i in velplan.analysis.solver.special_pair(mech, g):
            lead = g.leads[i]
            J = kin.positions[:, kin.point_index[g.joints[i]]] @ np.array([1, 1j])
            if lead.slider:
                assert lead.guide.link == GROUND
                direction = 1j * np.exp(1j * lead.guide.angle) * np.ones_like(J)  # the guide's normal
            else:
                direction = J - kin.positions[:, kin.point_index[lead.joint]] @ np.array([1, 1j])
            off = (np.conj(direction) * (K - J)).imag / np.abs(direction)  # distance from the line
            assert np.max(np.abs(off)) <= 1e-12 * size * max(1.0, np.max(np.abs(K - J)) / size)


# ---- every assembly: a dense scan of the one-unknown closure ----------------------------------


def scan_assemblies(g, known: dict, samples: int = 20000) -> list[tuple[complex, float]]:
    """All real assemblies (B, θ) of ``g`` whose leads 1 and 2 are rods: for each base-link
    angle θ, B lies on the circle about lead 1's outer joint and on the circle about lead 2's
    outer joint moved back by the base link's offset of C; the third lead's residual (rod: its
    length; block: the distance of D from the guide) changes sign at each assembly; every sign
    change is refined by Brent's method. ``known``: point name → complex position (m)."""
    loc = local_joints(g)
    l1, l2 = g.leads[0], g.leads[1]
    assert not (l1.slider or l2.slider)
    A, E = known[l1.joint], known[l2.joint]
    third = g.leads[2]

    def branch(theta, sign):
        c = cmath.exp(1j * theta)
        e = E - loc[1] * c
        d = abs(e - A)
        a = (l1.length ** 2 - l2.length ** 2 + d * d) / (2 * d)
        h2 = l1.length ** 2 - a * a
        if h2 < 0:
            return None
        u = (e - A) / d
        b = A + a * u + sign * math.sqrt(h2) * 1j * u
        j = b + loc[2] * c
        if third.slider:
            ug = cmath.exp(1j * third.guide.angle)
            base = known[third.guide.through] + 1j * ug * third.guide.offset
            return b, (ug.conjugate() * (j - base)).imag
        return b, abs(j - known[third.joint]) - third.length

    found = []
    grid = np.linspace(0.0, 2 * np.pi, samples + 1)
    for sign in (1, -1):
        vals = [branch(t, sign) for t in grid]
        for k in range(samples):
            if vals[k] is None or vals[k + 1] is None or (vals[k][1] > 0) == (vals[k + 1][1] > 0):
                continue
            t = brentq(lambda x: branch(x, sign)[1], grid[k], grid[k + 1], xtol=1e-14)
            found.append((branch(t, sign)[0], t))
    return found


def _known(mech, g, phi):
    kin = velplan.solve(triad.upstream(mech, g), [phi], order=0)
    return {n: complex(*kin.positions[0, i]) for n, i in kin.point_index.items()}


def _distinct(roots, tol=1e-7):
    out = []
    for b, t in roots:
        if all(abs(b - b2) > tol or abs(cmath.exp(1j * t) - cmath.exp(1j * t2)) > tol for b2, t2 in out):
            out.append((b, t))
    return out


@pytest.mark.parametrize("name, phi_deg", [("triad-rocker", 0.0), ("triad-rocker", 117.0), ("triad-rocker", 250.0),
                                           ("triad-press", 40.0), ("triad-eight-link", 200.0)])
def test_candidates_are_every_real_assembly(name, phi_deg):
    mech = velplan.load(name)
    g = next(g for g in mech.groups if g.kind == "triad")
    phi = math.radians(phi_deg)
    up = triad.upstream(mech, g)
    x, th, ok = triad._Closure(g, triad.leads_at(up, g, np.array([phi]), velplan.solve)).candidates()
    ref = triad._Closure(g, triad.leads_at(up, g, np.array([phi]), velplan.solve)).ref
    loc = local_joints(g)
    theirs = _distinct([(x[0, k] - loc[ref] * cmath.exp(1j * th[0, k]), th[0, k]) for k in np.flatnonzero(ok[0])])
    ours = _distinct(scan_assemblies(g, _known(mech, g, phi)))
    assert len(ours) >= 2
    assert len(theirs) == len(ours)
    size = max(g.sides)
    for b, t in ours:  # the same assemblies, to the scan's refinement
        assert min(abs(b - b2) + size * abs(cmath.exp(1j * t) - cmath.exp(1j * t2)) for b2, t2 in theirs) < 1e-9


# ---- assembly limits and singular positions -------------------------------------------------


def long_crank_rocker():
    """triad-rocker with a 0.25 m crank: the triad cannot follow the crank over a whole turn."""
    return velplan.parse(ROCKER.replace("length = 0.078", "length = 0.25"))


def test_limits_of_a_triad_that_cannot_turn_fully():
    mech = long_crank_rocker()
    g = mech.groups[0]
    found = limits(mech)
    assert list(found) == [g.name] and len(found[g.name]) == 1
    lo, hi = found[g.name][0]
    assert 10.0 < hi - lo < 350.0
    for edge, inside in ((lo, -1.0), (hi, +1.0)):
        cond = []
        for delta in (1e-3, 1e-5):
            kin = velplan.solve(mech, [math.radians(edge + inside * delta)], order=1)
            cond.append(float(kin.condition[0, 0]))
            assert np.isfinite(kin.positions).all()
        # at a fold of the closure c² grows linearly with the distance from the limit
        assert cond[1] < 1e-3 and cond[0] / cond[1] == pytest.approx(10.0, rel=0.05)
        kin = velplan.solve(mech, [math.radians(edge - inside * 1e-3)], order=0)
        assert not np.isfinite(kin.positions).all()
        # independently: two real assemblies merge at the limit and vanish past it
        n_in = len(_distinct(scan_assemblies(g, _known(mech, g, math.radians(edge + inside * 1e-3)))))
        n_out = len(_distinct(scan_assemblies(g, _known(mech, g, math.radians(edge - inside * 1e-3)))))
        assert n_in == n_out + 2


NEAR_SINGULAR = "0.2437437"
"""A crank length just below 0.24374370371… m, where the triad-rocker's branch touches a
singular position (found by bisection on `limits`): the mechanism still turns fully, but near
φ = 186.168° its three lead lines nearly meet in one point (condition about 8e-5)."""


def test_near_singular_position_is_masked_with_a_reason(tmp_path):
    text = ROCKER.replace("length = 0.078", f"length = {NEAR_SINGULAR}")
    mech = velplan.parse(text)
    check_full_rotation(mech)
    cond = lambda deg: float(velplan.solve(mech, [math.radians(deg)], order=0).condition[0, 0])  # noqa: E731
    worst = float(minimize_scalar(cond, bounds=(185.0, 187.5), method="bounded", options={"xatol": 1e-10}).x)
    assert cond(worst) < 1e-4 and min(cond(worst - 1.0), cond(worst + 1.0)) > 5e-3
    path = tmp_path / "near.toml"
    path.write_text(text, encoding="utf-8")
    angles = f"{worst - 1.0!r},{worst!r},{worst + 1.0!r}"
    table = run_cli("analyze", str(path), "--angles", angles)
    assert re.search(r"\nsingular \(a group at a toggle, velocities undetermined\) at positions: 2 "
                     r"\(condition \d\.\de-05\)$", table)
    for line in table.splitlines():
        if line.startswith(("V_B", "a_B", "ω3, rad/s", "ε3")):
            cells = line.split()[-3:]
            assert cells[1] == "—" and all(math.isfinite(float(c)) for c in cells[::2]), line
    doc = json.loads(run_cli("analyze", str(path), "--angles", angles, "--format", "json"))
    assert [p["valid"] for p in doc["positions"]] == [True, False, True]
    # the unmasked positions beside it are right: against the 50-digit reference
    phi = np.radians([worst - 1.0, worst + 1.0])
    kin = velplan.solve(mech, phi)
    with mp.workdps(50):
        for i in range(2):
            ref = Reference(mech, float(phi[i]), kin, i)
            for n, j in kin.point_index.items():
                assert abs(complex(*kin.velocities[i, j]) - complex(ref.P[n][1])) <= 1e-9 * kin.largest("velocity")
                err = abs(complex(*kin.accelerations[i, j]) - complex(ref.P[n][2]))
                assert err <= 1e-8 * kin.largest("acceleration")
    # and the branch passes the near-singular position continuously, without jumping branches
    fine = velplan.solve(mech, np.radians(np.arange(worst - 0.5, worst + 0.5, 1e-3)), order=0)
    B = fine.position("B") @ np.array([1, 1j])
    assert np.isfinite(B).all() and np.max(np.abs(np.diff(B))) < 2e-4


# ---- loader errors -----------------------------------------------------------------------------


@pytest.mark.parametrize("old, new, message", [
    ("sides = [0.241, 0.205, 0.311]", "sides = [0.241, 0.05, 0.311]",
     "group '3-2-4-5': sides 0.241, 0.05, 0.311 m do not make a triangle (the longest exceeds the sum of the others)"),
    ("assembly = { phi_deg = 90, B = [0.185, 0.372], C = [0.421, 0.323], D = [0.373, 0.124] }\n", "",
     "group '3-2-4-5': missing assembly = {phi_deg = …, B = [x, y], …}: the approximate position of the inner "
     "joints as drawn, which picks the branch"),
    ("B = [0.185, 0.372], C = [0.421, 0.323], D = [0.373, 0.124]", "phi = 90",
     "group '3-2-4-5' assembly: unknown key 'phi'; allowed: B, C, D, phi_deg"),
    ("assembly = { phi_deg = 90, B = [0.185, 0.372], C = [0.421, 0.323], D = [0.373, 0.124] }",
     "assembly = { phi_deg = 90 }", "group '3-2-4-5': assembly names none of the joints B, C, D"),
    ("side = -1 ", "pair = [1, 1]\nside = -1 ",
     "group '3-2-4-5': pair must be two different lead numbers 1…3, not [1, 1]"),
    ("side = -1 ", "pair = [1, 4]\nside = -1 ",
     "group '3-2-4-5': pair must be two different lead numbers 1…3, not [1, 4]"),
    ("side = -1 ", "side = 0 ", "group '3-2-4-5': side must be +1 or -1, not 0"),
    ('joint = "E"', 'joint = "Z"',
     "group '3-2-4-5' uses point 'Z', which is not solved before it; known points: A, E, F, O1"),
    ('joints = ["B", "C", "D"]', 'joints = ["B", "C"]',
     "group #1: joints must be a list of three values, not ['B', 'C']"),
    ('joints = ["B", "C", "D"]', 'joints = ["B", "C", "A"]', None),
    ('{ link = "4", joint = "E", length = 0.347 }',
     '{ link = "4", joint = "E", length = 0.347, guide = { link = "0", through = "E" } }',
     "group '3-2-4-5' lead 2: a lead is a rod (joint, length) or a block on a guide, not both"),
    ('{ link = "5", joint = "F", length = 0.290 }', '{ link = "3", joint = "F", length = 0.290 }',
     "duplicate link name '3': each group brings new links (a dyad two, a triad four)"),
    ('  { link = "5", joint = "F", length = 0.290 },\n', "",
     "group #1: leads must be a list of three tables ({link, joint, length} or {link, guide}), not "
     "[{'link': '2', 'joint': 'A', 'length': 0.347}, {'link': '4', 'joint': 'E', 'length': 0.347}]"),
])
def test_loader_errors(old, new, message):
    assert old in ROCKER
    text = ROCKER.replace(old, new)
    if message is None:  # a joint named like the crank's tip
        text = text.replace("D = [0.373, 0.124]", "A = [0.373, 0.124]")
        message = "duplicate name 'A': used for the crank tip and for a point of group '3-2-4-5'"
    with pytest.raises(MechanismError) as err:
        velplan.parse(text)
    assert str(err.value) == message


def test_all_three_leads_blocks_is_refused():
    text = ROCKER
    for link, joint, length in (("2", "A", "0.347"), ("4", "E", "0.347"), ("5", "F", "0.290")):
        text = text.replace(f'{{ link = "{link}", joint = "{joint}", length = {length} }}',
                            f'{{ link = "{link}", guide = {{ link = "0", through = "{joint}" }} }}')
    with pytest.raises(MechanismError, match=r"^group '3-2-4-5': at least one lead must be a rod "
                                             r"\(all three are blocks on guides\)$"):
        velplan.parse(text)


def test_cli_loader_error_is_one_line_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(ROCKER.replace("sides = [0.241, 0.205, 0.311]", "sides = [0.241, 0.05, 0.311]"), encoding="utf-8")
    assert main(["info", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("velplan: error: group '3-2-4-5': sides") and "Traceback" not in err


# ---- the catalogue and the compiled engine --------------------------------------------------


def test_examples_list_three_class_three_mechanisms():
    listed = run_cli("examples", "--all")
    class3 = [n for n in triad_mechanisms() if n in listed]
    assert len(class3) >= 3
    for name in class3:
        info = run_cli("info", name)
        assert "mechanism of class 3" in info and "triad  class 3, order 3" in info


@pytest.mark.parametrize("name", triad_mechanisms())
def test_full_rotation_with_comfortable_condition(name):
    study = velplan.Study(name)  # checks the full rotation
    kin = velplan.solve(study.mechanism, np.radians(np.arange(0.0, 360.0, 0.5)))
    assert kin.valid.all() and float(np.min(kin.condition)) >= 0.1


def test_compiled_engine_solves_the_triad_as_numpy_does():
    mech = velplan.load("triad-rocker")
    phi = np.radians(np.arange(0.0, 360.0, 15.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fast = velplan.solve(mech, phi, engine="compiled")
    ref = velplan.solve(mech, phi, engine="numpy")
    np.testing.assert_array_equal(fast.valid, ref.valid)
    for arr in ("positions", "velocities", "accelerations", "angles", "omegas", "epsilons", "condition"):
        a, b = getattr(fast, arr), getattr(ref, arr)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.max(np.abs(b)))


# ---- the documentation ---------------------------------------------------------------------


def _doc_block(after: str) -> str:
    text = (Path(__file__).resolve().parent.parent / "docs" / "format.md").read_text("utf-8")
    return text.split(after, 1)[1].split("```toml", 1)[1].split("```", 1)[0]


def test_the_complete_class_three_file_of_the_docs_works():
    mech = velplan.parse(_doc_block("A complete class III file"), name="my-triad-press")
    study = velplan.Study(mech)  # turns fully
    g = mech.groups[0]
    assert g.kind == "triad" and g.pair == (0, 2) and velplan.analysis.solver.special_pair(mech, g) == (0, 2)
    assert "mechanism of class 3" in run_cli("info", "triad-press")
    # the same machine as the catalogue's triad-press, with the special point on leads 1 and 3
    ref = velplan.Study("triad-press")
    assert study.stroke.H == pytest.approx(ref.stroke.H, rel=1e-12)
    fa = study.forces()
    assert fa.max_relative_difference() < 1e-9
    np.testing.assert_allclose(fa.balancing_moments["kinetostatics"], ref.forces().balancing_moments["kinetostatics"],
                               rtol=1e-9, atol=1e-9)


def test_the_group_example_of_the_docs_is_a_triad_with_every_key():
    text = _doc_block("## Class III groups: the triad")
    head = ROCKER.split("[[group]]")[0].replace('E = [0.574, 0.011]', 'E = [0.576, 0.373]').replace(
        "length = 0.078", "length = 0.061")
    mech = velplan.parse(head + text)
    g = mech.groups[0]
    for key in ("base", "joints", "sides", "side", "leads", "assembly", "special", "pair"):
        assert f"\n{key} = " in text
    assert g.special_name == "K3" and g.pair == (0, 2) and g.leads[2].slider


def test_an_assembly_far_from_every_root_is_refused_not_replaced(tmp_path, capsys):
    """With a 0.26 m crank the drawn branch exists only from −149.9° to 162.1°: at 180° the
    joints as drawn are 0.47 m from the nearest assembly (another branch), which is refused."""
    text = ROCKER.replace("length = 0.078", "length = 0.26").replace("phi_deg = 90", "phi_deg = 180")
    mech = velplan.parse(text)
    with pytest.raises(MechanismError, match=r"^group '3-2-4-5' \(triad\): at its assembly angle 180° no "
                                             r"assembly lies near the joints given; the nearest is 0\.4\d+ m"):
        velplan.solve(mech, [0.0])
    path = tmp_path / "far.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["analyze", str(path), "--angles", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no assembly lies near the joints given" in err


def test_a_rod_lead_takes_no_coincident_point():
    text = ROCKER.replace('joint = "F", length = 0.290 }', 'joint = "F", length = 0.290, coincident = "X" }')
    with pytest.raises(MechanismError, match=r"^group '3-2-4-5' lead 3: coincident names a guide's point"):
        velplan.parse(text)
