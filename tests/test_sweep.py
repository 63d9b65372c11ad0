"""Sweeps over designs: the design axis against single-variant solves of files built the
batch's way (TOML overrides), class III groups included; the figures of merit against `stroke`,
the peak balancing moment against the kinetostatics and J_I against the dynamics' flywheel of
each variant; tolerance Monte Carlo (0 tolerance = nominal, a seed = the same bytes) and the
CLI's errors."""

import json
import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from velplan.analysis.design import design_keys, solve_design
from velplan.analysis.extremes import stroke
from velplan.analysis.solver import solve
from velplan.batch import apply_overrides, base_text
from velplan.cli import main
from velplan.dynamics import dynamics_analysis
from velplan.forces import force_analysis_at
from velplan.mechanism.loader import from_dict, load
from velplan.sweep.merit import figures, grid_angles
from velplan.sweep.run import grid, monte_carlo, run_sweep, sensitivities, tolerances


def _built(base: str, overrides: dict):
    """The variant the way `velplan batch` builds it: overrides into the TOML, then loaded."""
    name, text = base_text(base)
    mech, _ = apply_overrides(from_dict(tomllib.loads(text), name=name), overrides)
    return mech


CASES = {
    "shaper": {"crank.length": [0.15, 0.1605, 0.17], "group.5-6.guide.offset": [0.64, 0.67],
               "ground.O2.1": [0.36, 0.38]},
    "four-bar": {"crank.length": [0.09, 0.1, 0.11], "group.2-3.lengths.1": [0.19, 0.21],
                 "ground.D.0": [0.29, 0.31]},
    "crank-slider": {"group.2-3.length": [0.28, 0.3, 0.33], "group.2-3.guide.offset": [0.0, 0.02]},
    "press": {"crank.length": [0.9 * load("press").crank.length, 1.05 * load("press").crank.length],
              "point.E.along": None, "group.3-4.guide.offset": [-0.1, -0.09]},
    # class III groups: each variant's branch followed in all variants together
    "triad-rocker": {"crank.length": None, "ground.E.0": None},
    "triad-press": {"crank.length": None, "ground.O1.1": None},
    "triad-eight-link": {"crank.length": None, "ground.O3.0": None},
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


def _assert_same(ref, got):
    assert np.array_equal(ref.valid, got.valid)
    for field in ("positions", "velocities", "accelerations", "omegas", "epsilons", "slides", "condition"):
        a, b = getattr(ref, field), getattr(got, field)
        assert np.array_equal(np.isfinite(a), np.isfinite(b)), field
        if a.size:
            np.testing.assert_allclose(b[np.isfinite(a)], a[np.isfinite(a)], rtol=0, atol=1e-12 * np.nanmax(np.abs(a)))


def test_a_triad_that_cannot_be_assembled_is_masked_and_the_others_solved():
    mech = load("triad-rocker")
    phi = grid_angles(72)
    dk = solve_design(mech, {"ground.E.1": [0.011, -0.139]}, phi)
    assert dk.failures() == ["", f"group '3-2-4-5' does not close at φ = {np.degrees(phi[0]):.6g}°"]
    _assert_same(solve(mech, phi), dk.variant(0))


def test_a_variant_whose_branch_is_not_clear_is_tracked_alone(monkeypatch):
    """With no step taken as unambiguous, every variant falls back to its own `track`."""
    from velplan.analysis import design, triad

    design._tracks_of.cache_clear()
    mech = load("triad-press")
    values = {"crank.length": design_keys(mech)["crank.length"] * np.array([0.98, 1.02])}
    phi = grid_angles(72)
    monkeypatch.setattr(triad, "QUICK_MOVE", 0.0)
    dk = solve_design(mech, values, phi)
    for v in range(2):
        _assert_same(solve(_built("triad-press", {"crank.length": float(values["crank.length"][v])}), phi),
                     dk.variant(v))


def test_variants_that_choose_different_special_point_leads_get_each_their_own():
    """`Tracks.pair` gives a pair per position when the variants' branches choose differently;
    the special point of each position is then that of its own pair."""
    from velplan.analysis import triad

    g = next(x for x in load("triad-rocker").groups if isinstance(x, triad.Triad))
    trk = triad.Track(0.0, np.zeros(0), np.zeros(0, complex), np.zeros(0), False, (0, 1), 1.0)
    pair = triad.Tracks((trk, replace(trk, pair=(1, 2))), 3).pair
    assert pair.tolist() == [[0, 1]] * 3 + [[1, 2]] * 3
    rng = np.random.default_rng(5)
    z = lambda: rng.normal(size=6) + 1j * rng.normal(size=6)  # noqa: E731
    leads = [triad.Lead3(True, 1.0, z()) for _ in g.leads]
    joints = [z() for _ in g.leads]
    K = triad._special_point(leads, joints, pair)
    np.testing.assert_array_equal(K[:3], triad._special_point(leads, joints, (0, 1))[:3])
    np.testing.assert_array_equal(K[3:], triad._special_point(leads, joints, (1, 2))[3:])


DYNAMIC = {"shaper": {"crank.length": [0.15, 0.17], "group.5-6.guide.offset": [0.64, 0.67]},
           "slider-press": {"crank.length": None},  # a press load: resolved per variant
           "compressor": {"crank.length": None},  # an indicator diagram
           "beam-pump": {"crank.length": None},  # a table over the output's return stroke
           "jaw-crusher": {"crank.length": None},  # a table over the crank's turn, a rocker output
           "triad-press": {"crank.length": None}}  # a press load on a class III group's block


@pytest.mark.parametrize("name", list(DYNAMIC))
def test_balancing_moment_and_flywheel_equal_the_study_of_each_variant(name):
    """Mb_max against the kinetostatics (reactions, group by group) of each variant at the
    sweep's angles; J_I against the dynamics' flywheel sized for the same δ."""
    mech = load(name)
    keys = design_keys(mech)
    values = grid(mech, {k: np.array(v if v else [keys[k] * 0.97, keys[k] * 1.03]) for k, v in DYNAMIC[name].items()})
    figs, failures, _ = figures(mech, values, 120, delta=0.04)
    for v in range(len(failures)):
        m = _built(name, {k: float(a[v]) for k, a in values.items()})
        assert failures[v] == ""
        mb = force_analysis_at(m, grid_angles(120)).kinetostatics.balancing_moment
        assert figs["Mb_max"][v] == pytest.approx(np.max(np.abs(mb)), rel=1e-11)
        assert figs["J_I"][v] == pytest.approx(dynamics_analysis(m, delta=0.04).flywheel.exact, rel=1e-11)


def test_a_press_load_given_by_its_fourier_series_is_resolved_per_variant():
    name, text = base_text("slider-press")
    data = tomllib.loads(text)
    data["load"][0]["harmonics"] = 12
    mech = from_dict(data, name=name)
    lengths = mech.crank.length * np.array([0.98, 1.02])
    figs, failures, _ = figures(mech, {"crank.length": lengths}, 90, delta=0.05)
    for v, length in enumerate(lengths):
        data["crank"]["length"] = float(length)
        m = from_dict(data, name=name)
        mb = force_analysis_at(m, grid_angles(90)).kinetostatics.balancing_moment
        assert figs["Mb_max"][v] == pytest.approx(np.max(np.abs(mb)), rel=1e-11)
        assert figs["J_I"][v] == pytest.approx(dynamics_analysis(m, delta=0.05).flywheel.exact, rel=1e-11)


def test_no_flywheel_without_loads_or_masses(tmp_path, capsys):
    assert "Mb_max" not in figures(load("four-bar"), {}, 90)[0]
    assert main(["sweep", "four-bar", "--vary", "crank.length=0.09:0.11:3", "--delta", "0.05"]) == 2
    err = capsys.readouterr().err
    assert err == "velplan: error: --delta: 'four-bar' has no loads or masses: no flywheel to size\n"


def test_require_a_peak_balancing_moment():
    from velplan.sweep.require import check, parse_require

    figs, _, _ = figures(load("shaper"), {"crank.length": [0.15, 0.17]}, 90)
    out = check(figs, parse_require("Mb_max<=1200"))
    assert out[0] == "" and out[1].startswith("Mb_max<=1200 (it is 15")


def test_zero_tolerance_monte_carlo_reproduces_the_nominal_exactly():
    mech = load("shaper")
    values = monte_carlo(mech, tolerances(mech, 0.0, 0.0), 50, 3)
    assert all(np.array_equal(a, np.full(50, design_keys(mech)[k])) for k, a in values.items())
    res = run_sweep(mech, values, mode="monte-carlo", positions=180, chunk=16, delta=0.05)
    assert {"Mb_max", "J_I"} <= set(res.figures)
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
    (["--vary", "crank.lenth=1:2:3"], "unknown key 'crank.lenth'"),
    (["--vary", "crank.length=-1:0.1:3"], "crank.length = -1 must be a length ≥ 1e-09 m (variant 1)"),
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
