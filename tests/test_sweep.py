"""Sweeps over designs: the design axis against single-variant solves of files built the
batch's way (TOML overrides), the figures of merit against `stroke`, tolerance Monte Carlo
(0 tolerance = nominal, a seed = the same bytes) and the CLI's errors."""

import json
import math
import tomllib

import numpy as np
import pytest

from velplan.analysis.design import design_keys, solve_design
from velplan.analysis.extremes import stroke
from velplan.analysis.solver import solve
from velplan.batch import apply_overrides, base_text
from velplan.cli import main
from velplan.mechanism.loader import from_dict, load
from velplan.sweep.merit import figures, grid_angles
from velplan.sweep.run import grid, monte_carlo, run_sweep, sensitivities, tolerances


def _built(base: str, overrides: dict):
    """The variant the way `velplan batch` builds it: overrides into the TOML, then loaded."""
    name, text = base_text(base)
    data, _ = apply_overrides(tomllib.loads(text), overrides)
    return from_dict(data, name=name)


CASES = {
    "shaper": {"crank.length": [0.15, 0.1605, 0.17], "group.5-6.guide.offset": [0.64, 0.67],
               "ground.O2.1": [0.36, 0.38]},
    "four-bar": {"crank.length": [0.09, 0.1, 0.11], "group.2-3.lengths.1": [0.19, 0.21],
                 "ground.D.0": [0.29, 0.31]},
    "crank-slider": {"group.2-3.length": [0.28, 0.3, 0.33], "group.2-3.guide.offset": [0.0, 0.02]},
    "press": {"crank.length": [0.9 * load("press").crank.length, 1.05 * load("press").crank.length],
              "point.E.along": None, "group.3-4.guide.offset": [-0.1, -0.09]},
}


def _axes(name):
    mech = load(name)
    keys = design_keys(mech)
    out = {}
    for k, v in CASES[name].items():
        if v is None:  # ± 2 % about the nominal
            v = [keys[k] * 0.98, keys[k] * 1.02]
        out[k] = np.array(v)
    return mech, out


@pytest.mark.parametrize("name", list(CASES))
def test_grid_sweep_equals_single_variant_solves(name):
    mech, axes = _axes(name)
    values = grid(mech, axes)
    phi = np.radians(np.arange(0.0, 360.0, 7.5) + 0.25)
    dk = solve_design(mech, values, phi)
    V = len(next(iter(values.values())))
    assert dk.shape == (V, phi.size)
    for v in range(V):
        ref = solve(_built(name, {k: float(a[v]) for k, a in values.items()}), phi)
        got = dk.variant(v)
        assert np.array_equal(ref.valid, got.valid)
        assert list(ref.point_index) == list(got.point_index)
        for field in ("positions", "velocities", "accelerations", "angles", "omegas", "epsilons", "slides", "condition"):
            a, b = getattr(ref, field), getattr(got, field)
            assert np.array_equal(np.isfinite(a), np.isfinite(b)), field
            scale = np.nanmax(np.abs(a)) if a.size else 1.0
            np.testing.assert_allclose(b[np.isfinite(a)], a[np.isfinite(a)], rtol=0, atol=1e-12 * scale, err_msg=field)


@pytest.mark.parametrize("name", ["shaper", "four-bar", "crank-slider"])
def test_figures_equal_stroke_of_each_variant(name):
    mech, axes = _axes(name)
    values = grid(mech, axes)
    figs, failures, _ = figures(mech, values, 180)
    for v in range(len(failures)):
        m = _built(name, {k: float(a[v]) for k, a in values.items()})
        s = stroke(m)
        assert failures[v] == ""
        assert figs["H"][v] == pytest.approx(s.H, rel=1e-11, abs=1e-13)
        assert figs["K"][v] == pytest.approx(s.K, rel=1e-11)
        start = (figs["phi_start_deg"][v] - math.degrees(s.start.phi) + 180) % 360 - 180
        assert abs(start) < 1e-7
        # peak |v| of the output against a fine independent solve
        fine = solve(m, grid_angles(180))
        q = mech.output
        peak = np.max(np.abs(fine.omega(q.link))) if q.link else np.max(np.hypot(*fine.velocity(q.point).T))
        assert figs["v_max"][v] == pytest.approx(peak, rel=1e-12)


def test_transmission_angle_of_a_four_bar_is_the_coupler_rocker_angle():
    mech = load("four-bar")
    figs, _, group = figures(mech, {}, 3600)
    kin = solve(mech, np.linspace(0, 2 * np.pi, 200_001))  # an independent, much finer grid
    mu = np.abs(kin.angle("2") - kin.angle("3"))  # angle between coupler and rocker
    gamma = np.degrees(np.arcsin(np.abs(np.sin(mu))))
    assert figs["gamma_min_deg"][0] == pytest.approx(gamma.min(), abs=1e-6)
    assert group == ["2-3"]


def test_a_variant_that_does_not_close_is_masked_with_its_reason():
    mech = load("four-bar")
    figs, failures, _ = figures(mech, {"crank.length": [0.1, 0.2]}, 90)
    assert failures[0] == "" and np.isfinite(figs["K"][0])
    assert failures[1].startswith("group '2-3' does not close at φ = ")
    assert all(np.isnan(figs[k][1]) for k in figs)


def test_a_triad_mechanism_is_solved_by_a_loop_over_variants():
    mech = load("triad-rocker")
    keys = design_keys(mech)
    phi = np.radians([10.0, 100.0, 250.0])
    dk = solve_design(mech, {"crank.length": keys["crank.length"] * np.array([0.99, 1.0])}, phi)
    ref = solve(mech, phi)
    np.testing.assert_array_equal(dk.variant(1).positions, ref.positions)


def test_zero_tolerance_monte_carlo_reproduces_the_nominal_exactly():
    mech = load("shaper")
    values = monte_carlo(mech, tolerances(mech, 0.0, 0.0), 50, 3)
    assert all(np.array_equal(a, np.full(50, design_keys(mech)[k])) for k, a in values.items())
    res = run_sweep(mech, values, mode="monte-carlo", positions=180, chunk=16)
    for name, arr in res.figures.items():
        assert np.array_equal(arr, np.full(50, res.nominal[name])), name
    assert res.nominal["K"] == pytest.approx(stroke(mech).K, rel=1e-12)


def test_sensitivity_names_the_key_that_moves_a_figure():
    mech = load("crank-slider")
    values = monte_carlo(mech, {"crank.length": 1e-3, "point.S2.along": 1e-3}, 200, "x")
    res = run_sweep(mech, values, mode="monte-carlo", positions=90)
    share = sensitivities(res)["H"]
    assert share["crank.length"] > 0.999 and share["point.S2.along"] < 1e-3


def _cli_bytes(tmp_path, name, *extra):
    out = tmp_path / name
    assert main(["sweep", "four-bar", "--tolerance", "0.2mm,0.1°", "--samples", "40", "--positions", "90",
                 "--format", "csv", "-o", str(out), *extra]) == 0
    return out.read_bytes()


def test_a_seed_gives_the_same_bytes(tmp_path):
    a = _cli_bytes(tmp_path, "a.csv", "--seed", "course 7")
    b = _cli_bytes(tmp_path, "b.csv", "--seed", "course 7")
    c = _cli_bytes(tmp_path, "c.csv", "--seed", "course 8")
    assert a == b and a != c
    head = a.decode().splitlines()[0].split(",")
    assert head[:2] == ["variant", "ground.O.0"] and "gamma_min_deg" in head


def test_sweep_json_and_plots(tmp_path, capsys):
    out = tmp_path / "s.json"
    assert main(["sweep", "four-bar", "--vary", "crank.length=0.09:0.11:5", "--positions", "90", "--format",
                 "json", "-o", str(out), "--plots", str(tmp_path)]) == 0
    doc = json.loads(out.read_text())
    assert doc["variants"] == 5 and doc["columns"]["crank.length"][-1] == pytest.approx(0.11)
    assert doc["sensitivities"]["H"]["crank.length"] == pytest.approx(1.0)
    for f in ("sweep-hist.svg", "sweep-scatter.svg"):
        assert (tmp_path / f).read_text().lstrip().startswith("<?xml")


@pytest.mark.parametrize("argv, words", [
    (["--vary", "crank.lenth=1:2:3"], "unknown design key 'crank.lenth'"),
    (["--vary", "crank.length=-1:0.1:3"], "crank.length must be a finite number > 0 m, not -1 (variant 1)"),
    (["--tolerance", "0.1 inch"], "is not a number with a unit"),
    ([], "give --vary"),
])
def test_sweep_errors_are_one_line_and_leave_no_file(tmp_path, capsys, argv, words):
    out = tmp_path / "x.csv"
    assert main(["sweep", "four-bar", *argv, "--format", "csv", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err
    assert not out.exists() and not list(tmp_path.iterdir())


@pytest.mark.parametrize("name", ["shaper", "press"])
def test_compiled_design_axis_equals_numpy(name):
    pytest.importorskip("numba")
    mech, axes = _axes(name)
    values = grid(mech, axes)
    phi = grid_angles(90)
    a, b = solve_design(mech, values, phi), solve_design(mech, values, phi, engine="compiled")
    np.testing.assert_array_equal(a.valid, b.valid)
    for field in ("positions", "velocities", "accelerations", "omegas", "epsilons", "slides", "condition"):
        x, y = getattr(a.flat, field), getattr(b.flat, field)
        scale = np.nanmax(np.abs(x))
        np.testing.assert_allclose(y, x, rtol=0, atol=1e-12 * scale, err_msg=field)
    fa, fb = figures(mech, values, 90)[0], figures(mech, values, 90, engine="compiled")[0]
    for k in fa:
        np.testing.assert_allclose(fb[k], fa[k], rtol=1e-10, atol=1e-9, err_msg=k)
