"""The compiled engine's class III group (`velplan.analysis.triad_rows`, the kernel's triad row):
the numpy engine's numbers to round-off on every catalogue triad, a triad with two block leads,
random mutants (branches that end, assemblies that come near each other) and the angles the
kernel hands back to numpy."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import velplan
from velplan.analysis import compiled, triad, triad_rows
from velplan.errors import VelplanError
from velplan.mechanism.loader import from_dict

from tests.test_fuzz_triad import BASES, mutant
from tests.test_triad_two_blocks import two_blocks

pytest.importorskip("numba")

FIELDS = ("positions", "velocities", "accelerations", "angles", "omegas", "epsilons", "slides", "condition")
TOL = 1e-12
"""Largest difference between the engines over the field's largest value."""


def assert_engines_agree(mech, phi, where: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no fallback warning
        fast = velplan.solve(mech, phi, engine="compiled", on_failure="nan")
    ref = velplan.solve(mech, phi, engine="numpy", on_failure="nan")
    np.testing.assert_array_equal(fast.valid, ref.valid, err_msg=where)
    for field in FIELDS:
        a, b = getattr(fast, field)[ref.valid], getattr(ref, field)[ref.valid]
        if b.size:
            scale = max(float(np.max(np.abs(b))), 1e-300)
            err = float(np.max(np.abs(a - b)))
            assert err <= TOL * scale, f"{where}: {field} differ by {err:.3g} (scale {scale:.3g})"


def turn(n: int) -> np.ndarray:
    """n angles over a turn and a half, from below zero (rad)."""
    return np.linspace(-1.0, 2 * np.pi + 2.0, n)


@pytest.mark.parametrize("name", ["triad-press", "triad-rocker", "triad-eight-link"])
def test_every_catalogue_triad_equals_numpy(name):
    mech = velplan.load(name)
    for n in (1, 12, 5000):
        assert_engines_agree(mech, turn(n), f"{name} at {n} angles")
    assert velplan.solve(mech, turn(12), engine="compiled").valid.all()  # full turns, every angle solved


@pytest.mark.parametrize("pair", ["[1, 3]", "[1, 2]"])
def test_a_triad_with_two_block_leads_equals_numpy(pair):
    mech = two_blocks(pair)
    assert sum(lead.slider for g in mech.groups if g.tracked for lead in g.leads) == 2
    assert_engines_agree(mech, turn(2000), f"two blocks, pair {pair}")


@pytest.mark.parametrize("name", sorted(BASES))
def test_random_mutants_equal_numpy(name):
    solved = 0
    for seed in range(12):
        data, done = mutant(name, seed)
        try:
            mech = from_dict(data, name=f"{name}-{seed}")
            velplan.solve(mech, np.zeros(1), engine="numpy")
        except VelplanError:
            continue
        assert_engines_agree(mech, np.linspace(0, 2 * np.pi, 361), f"{name} seed {seed} ({'; '.join(done)})")
        solved += 1
    assert solved >= 3


def test_ambiguous_angles_are_solved_again_by_numpy(monkeypatch):
    """Where Newton's step from the branch is not clearly the branch's, the kernel flags the
    angle and the numpy engine's answer (every root, the nearest taken) replaces its NaNs."""
    seen = []
    keep = compiled._replace
    monkeypatch.setattr(compiled, "_replace", lambda kin, idx, sub: (seen.append(idx.size), keep(kin, idx, sub)))
    flagged = 0
    for name in sorted(BASES):
        for seed in range(12):
            data, _ = mutant(name, seed)
            try:
                mech = from_dict(data, name=f"{name}-{seed}")
                velplan.solve(mech, np.zeros(1), engine="numpy")
            except VelplanError:
                continue
            seen.clear()
            assert_engines_agree(mech, np.linspace(0, 2 * np.pi, 361), f"{name} seed {seed}")
            flagged += sum(seen)
    assert flagged > 0  # the path was taken, and agreed


def test_the_kernel_uses_the_numpy_engines_thresholds():
    for name in ("SETTLED", "QUICK_MOVE", "QUICK_CONDITION"):
        assert getattr(triad_rows, name) == getattr(triad, name)


def test_the_scalar_formulas_match_the_array_ones():
    rng = np.random.default_rng(3)
    rows = [tuple(rng.normal(size=3)) for _ in range(3)]
    rhs = list(rng.normal(size=3))
    x = triad._cramer3([tuple(np.array([c]) for c in r) for r in rows], [np.array([c]) for c in rhs])
    y = triad_rows.cramer3(*rows[0], *rows[1], *rows[2], *rhs)
    np.testing.assert_allclose([float(c[0]) for c in x], y, rtol=1e-15)
    m = np.array(rows)
    np.testing.assert_allclose(np.linalg.solve(m, rhs), y, rtol=1e-12)
    cond = triad._condition([tuple(np.array([c]) for c in r) for r in rows], 2.0)[0]
    assert triad_rows.condition3(*rows[0], *rows[1], *rows[2], 2.0) == pytest.approx(cond, rel=1e-15)


def test_parallel_lead_lines_give_no_special_point_and_no_exception():
    """Where the pair's lines are parallel the special point is not finite (numpy's inf/NaN),
    not a ZeroDivisionError inside the kernel."""
    special = compiled._env()["special_point"]
    k = special(0j, 1 + 0j, 1j, 2 + 0j)
    assert not np.isfinite(k.real) or not np.isfinite(k.imag)
    assert special(0j, 1 + 0j, 1 + 1j, 1j) == pytest.approx(1 + 0j)
