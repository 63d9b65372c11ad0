"""A class III triad with two block leads and one rod (issue 35, item 1): the catalogue's
triad-press with its rocker 4 replaced by a block sliding on a fixed horizontal guide through
the plate's joint C as drawn. Every assembly against a dense scan of the closure written out
here, the tracked branch against a 50-digit reference and against differences of its own
positions, the three balancing moments, and every command on the file."""

from __future__ import annotations

import cmath
import contextlib
import io
import json
import math
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from scipy.optimize import brentq

import velplan
from velplan.analysis import triad
from velplan.cli import main
from velplan.forces.agreement import mechanism_actions
from velplan.forces.kinetostatics import kinetostatics
from velplan.forces.lever import lever_balancing_moment
from velplan.forces.power import power_balancing_moment

from tests.test_triad import FD_TOL, central_difference, local_joints
from tests.test_triad_oracle import DPS, TOL, Reference

PRESS = (Path(velplan.__file__).parent / "catalogue" / "triad-press.toml").read_text(encoding="utf-8")
ROD_4 = '{ link = "4", joint = "E", length = 0.299 }'
BLOCK_4 = '{ link = "4", guide = { link = "0", through = "E", angle_deg = 0.0, offset = -0.277 } }'
TWO_BLOCKS = PRESS.replace(ROD_4, BLOCK_4).replace('name = "triad-press"', 'name = "triad-two-blocks"')
"""Leads: the rod AB, a block at C on the horizontal line y = 0.096 m, the ram at D."""


def two_blocks(pair: str = "[1, 3]"):
    return velplan.parse(TWO_BLOCKS.replace("pair = [1, 3]", f"pair = {pair}"))


def run_cli(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(list(argv)) == 0
    return out.getvalue()


def test_the_mutant_has_two_block_leads():
    assert BLOCK_4 in TWO_BLOCKS and ROD_4 not in TWO_BLOCKS
    g = two_blocks().groups[0]
    assert [lead.slider for lead in g.leads] == [False, True, True]


# ---- every assembly ---------------------------------------------------------------------------


def scan(g, known: dict, samples: int = 20000) -> list[tuple[complex, float]]:
    """All assemblies (B, θ): for each base-link angle θ the blocks' joints C = B + r_C, D = B + r_D
    lie on their guide lines, two linear equations for B; the rod's residual |B − A| − l_AB changes
    sign at each assembly, refined by Brent's method."""
    loc = local_joints(g)
    rod, blocks = g.leads[0], g.leads[1:]
    lines = []
    for lead in blocks:
        u = cmath.exp(1j * lead.guide.angle)
        lines.append((u, known[lead.guide.through] + 1j * u * lead.guide.offset))
    (u1, b1), (u2, b2) = lines
    A = known[rod.joint]

    def b_of(theta):  # cross(u_k, B + r_k − b_k) = 0, k = C, D
        c = cmath.exp(1j * theta)
        h1 = (u1.conjugate() * (b1 - loc[1] * c)).imag
        h2 = (u2.conjugate() * (b2 - loc[2] * c)).imag
        m = np.array([[-u1.imag, u1.real], [-u2.imag, u2.real]])
        x, y = np.linalg.solve(m, [h1, h2])
        return complex(x, y)

    def residual(theta):
        return abs(b_of(theta) - A) - rod.length

    grid = np.linspace(0.0, 2 * np.pi, samples + 1)
    vals = [residual(t) for t in grid]
    found = []
    for k in range(samples):
        if (vals[k] > 0) != (vals[k + 1] > 0):
            t = brentq(residual, grid[k], grid[k + 1], xtol=1e-14)
            found.append((b_of(t), t))
    return found


@pytest.mark.parametrize("phi_deg", [0.0, 90.0, 200.0, 300.0])
def test_candidates_are_every_real_assembly(phi_deg):
    mech = two_blocks()
    g = mech.groups[0]
    phi = np.radians([phi_deg])
    up = triad.upstream(mech, g)
    cl = triad._Closure(g, triad.leads_at(up, g, phi, velplan.solve))
    x, th, ok = cl.candidates()
    known = velplan.solve(up, phi, order=0)
    known = {n: complex(*known.positions[0, i]) for n, i in known.point_index.items()}
    ours = scan(g, known)
    assert len(ours) >= 2
    theirs = []
    for k in np.flatnonzero(ok[0]):  # the 16 columns hold each root more than once
        if all(abs(x[0, k] - b) + abs(cmath.exp(1j * th[0, k]) - cmath.exp(1j * t)) > 1e-7 for b, t in theirs):
            theirs.append((x[0, k], th[0, k]))
    assert len(theirs) == len(ours)
    size = max(g.sides)
    for b, t in ours:
        assert min(abs(b - b2) + size * abs(cmath.exp(1j * t) - cmath.exp(1j * t2)) for b2, t2 in theirs) < 1e-9


# ---- the branch: a 50-digit reference and the derivatives of its own positions ------------------


@pytest.mark.parametrize("pair", ["[1, 3]", "[2, 3]", "[1, 2]"])
def test_against_the_50_digit_reference(pair):
    mech = two_blocks(pair)
    angles = np.radians(np.arange(12) * 30.0 + 7.0)
    kin = velplan.solve(mech, angles)
    assert kin.valid.all()
    size = float(np.max(np.abs(kin.positions)))
    scales = (size, kin.largest("velocity"), kin.largest("acceleration"))
    worst = 0.0
    with mp.workdps(DPS):
        for i, phi in enumerate(angles):
            ref = Reference(mech, float(phi), kin, i)
            assert set(ref.P) == set(kin.point_index)
            for n, j in kin.point_index.items():
                for q, arr in enumerate((kin.positions, kin.velocities, kin.accelerations)):
                    worst = max(worst, abs(complex(*arr[i, j]) - complex(ref.P[n][q])) / scales[q])
            for n, j in kin.link_index.items():
                th, w, e = (float(v) for v in ref.L[n])
                worst = max(worst, abs(math.remainder(kin.angles[i, j] - th, 2 * math.pi)),
                            abs(kin.omegas[i, j] - w) / np.max(np.abs(kin.omegas)),
                            abs(kin.epsilons[i, j] - e) / np.max(np.abs(kin.epsilons)))
            for n, j in kin.slide_index.items():
                for q in range(3):
                    worst = max(worst, abs(kin.slides[i, j, q] - float(ref.slides[n][q])) / scales[q])
    assert 0 < worst <= TOL


def test_cli_derivatives_of_its_own_positions_over_the_turn():
    """The branch is followed continuously: 12th-order differences of 72 positions over the
    turn give the reported velocities and accelerations (the special point excepted)."""
    mech = two_blocks()
    n = 72
    phi = np.radians(np.arange(n) * 360.0 / n)
    kin = velplan.solve(mech, phi)
    assert kin.valid.all()
    h = float(phi[1] - phi[0])
    w1 = mech.crank.omega
    names = [k for k in kin.point_index if k != mech.groups[0].special_name]
    idx = [kin.point_index[k] for k in names]
    x, v, a = kin.positions[:, idx], kin.velocities[:, idx], kin.accelerations[:, idx]
    fold = lambda d: np.mod(d + np.pi, 2 * np.pi) - np.pi  # noqa: E731
    for fd, exact in ((w1 * central_difference(x, h), v), (w1 * central_difference(v, h), a),
                      (w1 * central_difference(kin.angles, h, wrap=fold), kin.omegas),
                      (w1 * central_difference(kin.omegas, h), kin.epsilons)):
        assert np.max(np.abs(fd - exact)) <= FD_TOL * np.max(np.abs(exact))


def test_the_block_c_slides_on_its_guide_and_the_plate_turns():
    kin = velplan.solve(two_blocks(), np.radians(np.arange(36) * 10.0))
    c = kin.positions[:, kin.point_index["C"]]
    assert np.max(np.abs(c[:, 1] - 0.096)) < 1e-12  # on y = 0.373 − 0.277
    assert np.ptp(c[:, 0]) > 0.05 and np.ptp(kin.angles[:, kin.link_index["3"]]) > 0.1
    assert np.all(kin.omegas[:, kin.link_index["4"]] == 0)  # a block on a fixed guide does not turn


# ---- forces and every command -----------------------------------------------------------------


@pytest.mark.parametrize("pair", ["[1, 3]", "[2, 3]"])
def test_three_balancing_moments_agree(pair):
    mech = two_blocks(pair)
    kin = velplan.solve(mech, velplan.positions(mech, 24))
    acts = mechanism_actions(mech, kin)
    mb = kinetostatics(mech, kin, acts).balancing_moment
    scale = np.abs(mb).max()
    assert scale > 1.0
    for other in (lever_balancing_moment(mech, kin, acts, mu_v=0.01), power_balancing_moment(kin, acts)):
        assert np.abs(other - mb).max() <= 1e-9 * scale


def test_every_command_runs(tmp_path):
    f = tmp_path / "two-blocks.toml"
    f.write_text(TWO_BLOCKS, encoding="utf-8")
    assert "class 3" in run_cli("info", str(f))
    doc = json.loads(run_cli("analyze", str(f), "--positions", "12", "--format", "json"))
    assert all(p["valid"] for p in doc["positions"])
    assert "P:4/0" in doc["positions"][0]["slides"]
    for kind in ("velocity", "acceleration"):
        run_cli("plan", str(f), "--position", "3", "--kind", kind, "-o", str(tmp_path / f"{kind}.svg"))
    run_cli("steps", str(f), "--position", "5", "-o", str(tmp_path / "steps"), "--kind", "both")
    assert list((tmp_path / "steps").glob("*.svg"))
    assert "P:4/0" in run_cli("forces", str(f), "--positions", "6")
    for kind in ("both", "forces"):
        out = tmp_path / f"sheet-{kind}.svg"
        run_cli("sheet", str(f), "--kind", kind, "-o", str(out))
        assert out.read_text(encoding="utf-8").lstrip().startswith("<")
