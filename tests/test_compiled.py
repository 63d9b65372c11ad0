"""The compiled engine (numba) against the numpy engine: the same closed forms, so the same
values to round-off, the same masks, the same errors, on every example and on random
mechanisms of every group kind."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import velplan
from tests.strategies import mechanisms
from tests.test_errors import four_bar
from velplan.analysis import compiled
from velplan.analysis.solver import length_scale

pytestmark = pytest.mark.skipif(not compiled.available(), reason="numba is not installed")

FIELDS = ("positions", "velocities", "accelerations", "omegas", "epsilons", "slides", "condition")


def assert_same(a, b, mech, tol=1e-12):
    """Both engines agree: names, masks, and every value to ``tol`` of its scale, relaxed by the
    solver's own error bound near toggles."""
    assert a.point_index == b.point_index and a.link_index == b.link_index
    assert a.slide_index == b.slide_index and a.group_index == b.group_index
    assert a.link_origins == b.link_origins
    np.testing.assert_array_equal(a.valid, b.valid)
    ok = a.valid
    L, w = length_scale(mech), abs(a.omega1)
    relax = np.maximum(1.0, b.error_bound("acceleration")[ok] / 1e-13)
    scales = {"positions": L, "velocities": w * L, "accelerations": w * w * L, "omegas": w, "epsilons": w * w,
              "slides": w * w * L + w * L + L, "condition": 1.0}
    for f in FIELDS:
        x, y = getattr(a, f)[ok], getattr(b, f)[ok]
        err = np.abs(x - y).reshape(len(x), -1).max(axis=1, initial=0.0)
        assert (err <= tol * scales[f] * relax).all(), (f, err.max(initial=0.0))
    # angles agree modulo 2π (a wrap at ±π may land on either side)
    d = np.angle(np.exp(1j * (a.angles[ok] - b.angles[ok])))
    assert (np.abs(d) <= 1e-12 * relax[:, None]).all()
    assert ((a.angles[ok] > -np.pi) & (a.angles[ok] <= np.pi)).all()


@pytest.mark.parametrize("name", velplan.example_names())
def test_examples_agree_over_several_turns(name):
    mech = velplan.load(name)
    phi = np.linspace(-7.0, 7.0, 2 * compiled.SERIAL + 1)  # shared among threads
    a = velplan.solve(mech, phi, engine="compiled", epsilon1=0.3)
    b = velplan.solve(mech, phi, engine="numpy", epsilon1=0.3)
    assert a.valid.any()
    assert_same(a, b, mech)


@settings(max_examples=40, deadline=None)
@given(mechanisms(), st.lists(st.floats(-10, 10), min_size=1, max_size=40).map(np.array))
def test_random_mechanisms_agree(mech, phi):
    assert_same(velplan.solve(mech, phi, engine="compiled"), velplan.solve(mech, phi, engine="numpy"), mech)


def test_positions_that_do_not_close_are_masked_alike():
    # the crank-rocker of the error tests with a coupler too short: B has no position over part of the turn
    mech = velplan.parse(four_bar(coupler=0.12))
    phi = np.linspace(0, 2 * math.pi, 721)
    a = velplan.solve(mech, phi, engine="compiled")
    b = velplan.solve(mech, phi, engine="numpy")
    assert 0 < a.valid.sum() < len(phi)
    assert np.isnan(a.positions[~a.valid]).any(axis=(1, 2)).all()  # never NaN without the mask
    assert_same(a, b, mech)
    with pytest.raises(velplan.AssemblyError, match=r"group '2-3' \(RRR\) cannot be assembled: point 'B'"):
        velplan.solve(mech, phi, engine="compiled", on_failure="raise")


def test_auto_engine_and_bad_engine_name(monkeypatch):
    from velplan.analysis import solver

    mech = velplan.load("four-bar")
    calls = []
    real = solver._solve_compiled
    monkeypatch.setattr(solver, "_solve_compiled", lambda *a: calls.append(len(a[1])) or real(*a))
    monkeypatch.setattr(compiled, "loaded", lambda: False)
    monkeypatch.setattr(solver, "_AUTO_ON", [False])
    monkeypatch.setattr(solver, "_NUMPY_SECONDS", [0.0])  # this process has not solved much yet
    velplan.solve(mech, np.linspace(0, 1, 5), engine="auto")  # few angles, kernel not loaded: numpy
    assert calls == []
    monkeypatch.setattr(compiled, "loaded", lambda: True)
    kin = velplan.solve(mech, np.linspace(0, 1, 5), engine="auto")  # loaded: compiled
    assert calls == [5] and kin.valid.all()
    with pytest.raises(ValueError, match="engine must be"):
        velplan.solve(mech, 0.0, engine="fortran")


def test_empty_and_scalar_input():
    mech = velplan.load("shaper")
    assert len(velplan.solve(mech, np.array([]), engine="compiled")) == 0
    a, b = velplan.solve(mech, 1.0, engine="compiled"), velplan.solve(mech, 1.0)
    assert_same(a, b, mech)


def test_cli_engines_print_the_same_table(capsys):
    from velplan.cli import main

    outs = []
    for engine in ("numpy", "compiled"):
        assert main(["analyze", "shaper", "--positions", "12", "--engine", engine]) == 0
        outs.append(capsys.readouterr().out)
    assert "φ, deg" in outs[0]
    # the same table: the same words, and every number the same to one unit of its last
    # printed digit (the engines agree to round-off, which may round a digit either way)
    import re

    number = re.compile(r"[-+]?\d+(?:\.(\d+))?(?:e[-+]?\d+)?")
    assert number.sub("#", outs[0]) == number.sub("#", outs[1])
    for x, y in zip(number.finditer(outs[0]), number.finditer(outs[1])):
        digits = len(x.group(1) or "")
        exponent = int(x.group(0).split("e")[1]) if "e" in x.group(0) else 0
        assert abs(float(x.group(0)) - float(y.group(0))) <= 1.01 * 10.0 ** (exponent - digits), (x, y)


def assert_close(x, y, what, tol=1e-13):
    """Arrays equal to ``tol`` of their largest value (NaN where the other is NaN)."""
    np.testing.assert_allclose(x, y, rtol=0, atol=tol * np.nanmax(np.abs(y), initial=1.0), err_msg=what)


@pytest.mark.parametrize("name, points", [("shaper", None), ("shaper", ["B"]), ("press", None), ("press", ["A"])])
@pytest.mark.parametrize("order", [0, 1, 2])
def test_points_and_order_subsets_are_slices_of_the_full_result(name, points, order):
    # points= and order= reach the kernel: it writes only the points of the groups they need and
    # no derivative above the order; what it writes equals the full result's slice, and the
    # numpy engine's result with the same arguments
    mech = velplan.load(name)
    phi = np.linspace(-4.0, 4.0, 301)
    full = velplan.solve(mech, phi, engine="compiled")
    part = velplan.solve(mech, phi, engine="compiled", points=points, order=order)
    assert part.order == order
    assert (part.velocities is None) == (order < 1) and (part.epsilons is None) == (order < 2)
    if points is not None:
        assert set(points) <= set(part.point_index) < set(full.point_index)
    for fields, index, full_index in (
            (("positions", "velocities", "accelerations"), part.point_index, full.point_index),
            (("angles", "omegas", "epsilons"), part.link_index, full.link_index)):
        rows = [full_index[k] for k in index]
        for field in fields[:order + 1]:
            assert_close(getattr(part, field), getattr(full, field)[:, rows], field)
    slides = full.slides[:, [full.slide_index[k] for k in part.slide_index], :order + 1]
    assert_close(part.slides, slides, "slides")
    assert_close(part.condition, full.condition[:, [full.group_index[k] for k in part.group_index]], "condition")
    # with velocities solved, a position is refused where they are singular, as in the full result
    np.testing.assert_array_equal(part.valid, full.valid if order else np.isfinite(part.positions).all(axis=(1, 2)))
    ref = velplan.solve(mech, phi, points=points, order=order)
    np.testing.assert_array_equal(part.valid, ref.valid)
    for field in ("positions", "velocities", "accelerations")[:order + 1]:
        assert_close(getattr(part, field)[part.valid], getattr(ref, field)[ref.valid], field, tol=1e-12)


def test_a_class_iii_group_runs_compiled_and_points_stop_before_it():
    mech = velplan.load("triad-rocker")
    phi = np.radians(np.arange(0.0, 360.0, 30.0))
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no fallback warning: the kernel solves the triad
        kin = velplan.solve(mech, phi, engine="compiled")
        crank_tip = mech.crank.tip  # solved before the triad
        part = velplan.solve(mech, phi, engine="compiled", points=[crank_tip])
    ref = velplan.solve(mech, phi, engine="numpy")
    assert_close(kin.positions, ref.positions, "positions", tol=1e-12)
    assert crank_tip in part.point_index and len(part.group_index) == 0
    np.testing.assert_allclose(part.position(crank_tip), kin.position(crank_tip), rtol=0, atol=1e-15)


def test_a_fresh_process_loads_the_cached_kernel_without_numbas_compiler():
    # the first call here compiles or loads the kernel (and fills the disk cache); a new process
    # then loads its machine code without initialising numba's compiler (and its numpy library)
    import subprocess
    import sys

    mech = velplan.load("four-bar")
    velplan.solve(mech, np.zeros(1), engine="compiled")
    code = ("import sys, numpy as np, velplan\n"
            "kin = velplan.solve(velplan.load('four-bar'), np.array([0.5]), engine='compiled')\n"
            "print(kin.valid.all(), 'numba.np.arraymath' in sys.modules, float(kin.positions[0, 3, 1]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out[:2] == ["True", "False"]
    y_b = velplan.solve(mech, np.array([0.5])).positions[0, 3, 1]
    assert abs(float(out[2]) - y_b) <= 1e-14
