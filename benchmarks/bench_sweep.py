"""Sweeps over designs (issue 27): figures of merit of many shaper variants at once, and the
streamed output of ``velplan analyze``.

* figures of merit (H, K, θ, extremes, γ_min, peak |v|, |a|, peak M_b) of V tolerance variants
  of the shaper × 360 angles, numpy engine: scaling in variants, in angles and in processes;
* the same work as a Python loop over variants (`Study` per variant: stroke + a solve of
  360 angles), per variant;
* what the dynamic figures cost: the kinematic figures alone (the file's loads and masses
  taken out), with the peak balancing moment, with the flywheel's J_I for δ = 0.05; and the
  same by a loop over variants (force analysis + dynamics per variant);
* a mechanism with a class III group (triad-press): variants × angles in one `solve_design`
  against a loop of `solve` per variant;
* ``velplan analyze four-bar --positions 1000000 --format csv|jsonl`` in a fresh process:
  wall time and peak memory (max RSS).

    python benchmarks/bench_sweep.py          # ~2 min on 2 cores

Writes ``benchmarks/results/sweep.md``.
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import replace

import numpy as np

from _common import RESULTS, load_average, machine_md, median_time, table, write

from velplan.analysis.design import solve_design, variant
from velplan.analysis.solver import solve
from velplan.dynamics import dynamics_analysis
from velplan.forces import force_analysis_at
from velplan.mechanism.loader import load
from velplan.study import Study
from velplan.sweep.merit import grid_angles
from velplan.sweep.run import monte_carlo, run_sweep, tolerances

MECH = load("shaper")


def draws(V: int) -> dict:
    return monte_carlo(MECH, tolerances(MECH, 1e-4, 0.05), V, "bench")


def sweep_time(V: int, positions: int = 360, jobs: int = 1, repeats: int = 3, engine: str = "numpy") -> float:
    values = draws(V)
    return median_time(lambda: run_sweep(MECH, values, positions=positions, jobs=jobs, engine=engine),
                       V, repeats=repeats, warmup=False)[0]


def loop_time(V: int = 40) -> float:
    """Seconds per variant of the same figures by a loop over studies."""
    values = draws(V)
    t = time.perf_counter()
    for v in range(V):
        study = Study(variant(MECH, {k: float(a[v]) for k, a in values.items()}), angles=grid_angles(360))
        st = study.stroke
        kin = study.kinematics
        _ = (st.H, st.K, kin.condition.min(), np.hypot(*kin.velocity("F").T).max(),
             np.hypot(*kin.acceleration("F").T).max())
    return (time.perf_counter() - t) / V


def dynamic_rows(V: int = 1000) -> tuple[list[list[str]], float]:
    """Rows (figures, s per V variants, ms per variant) for the kinematic figures alone, with
    Mb_max, with Mb_max and J_I; and the ms per variant of the loop over studies."""
    values = draws(V)
    bare = replace(MECH, loads=(), masses=())
    rows = []
    for label, mech, delta in (("H, K, θ, γ_min, peak v, a (loads and masses taken out)", bare, None),
                               ("+ Mb_max", MECH, None), ("+ Mb_max, J_I for δ = 0.05", MECH, 0.05)):
        dt = median_time(lambda: run_sweep(mech, values, delta=delta), V, repeats=3, warmup=False)[0]
        rows.append([label, f"{dt:.2f}", f"{dt / V * 1e3:.3f}"])
        print(label, dt, file=sys.stderr)
    few = draws(20)
    t = time.perf_counter()
    for v in range(20):
        m = variant(MECH, {k: float(a[v]) for k, a in few.items()})
        np.abs(force_analysis_at(m, grid_angles(360)).kinetostatics.balancing_moment).max()
        dynamics_analysis(m, delta=0.05).flywheel.exact
    return rows, (time.perf_counter() - t) / 20 * 1e3


def triad_rows(V: int = 256) -> list[list[str]]:
    """Seconds for V triad-press variants × 360 angles: one `solve_design`, a loop of `solve`."""
    mech = load("triad-press")
    values = monte_carlo(mech, tolerances(mech, 1e-4, 0.05), V, "bench")
    phi = grid_angles(360)
    one = median_time(lambda: solve_design(mech, values, phi), V, repeats=1, warmup=False)[0]
    loop = median_time(lambda: [solve(variant(mech, {k: float(a[v]) for k, a in values.items()}), phi)
                                for v in range(V)], V, repeats=1, warmup=False)[0]
    print("triad", one, loop, file=sys.stderr)
    return [["one `solve_design` (branches followed in all variants together)", f"{one:.2f}", f"{one / V * 1e3:.1f}"],
            ["a loop of `solve` per variant", f"{loop:.2f}", f"{loop / V * 1e3:.1f}"]]


def analyze(fmt: str, n: int = 1_000_000) -> tuple[float, float, int]:
    """(wall s, peak RSS MB, bytes) of ``velplan analyze four-bar --positions n --format fmt``."""
    exe = shutil.which("velplan")
    cmd = ([exe] if exe else [sys.executable, "-m", "velplan"]) + [
        "analyze", "four-bar", "--positions", str(n), "--format", fmt]
    timer = shutil.which("time") or "/usr/bin/time"
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, f"out.{fmt}")
        rss = os.path.join(tmp, "rss")
        wrap = [timer, "-f", "%M", "-o", rss] if os.path.exists(timer) else []
        t = time.perf_counter()
        proc = subprocess.run(wrap + cmd + ["-o", out], capture_output=True, text=True)
        dt = time.perf_counter() - t
        if proc.returncode:
            raise SystemExit(proc.stderr)
        if wrap:  # GNU time: this run's max RSS in KiB
            peak = float(open(rss).read().split()[-1])
        else:  # the largest of this process's children so far
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        return dt, peak / 1024, os.path.getsize(out)


def per_call() -> list[list[str]]:
    """Median µs per `solve` call of the four-bar at 1 and 100 angles, by engine."""
    from velplan.analysis.solver import solve

    four = load("four-bar")
    rows = []
    for engine in ("numpy", "compiled"):
        for n in (1, 100):
            phi = np.linspace(0.1, 6.0, n)
            dt = median_time(lambda: solve(four, phi, engine=engine), n, repeats=300)[0]
            rows.append([engine, f"{n}", f"{dt * 1e6:.0f}"])
    return rows


def main() -> None:
    load = load_average()
    rows_v = []
    cores = os.cpu_count() or 1
    runs = [(V, 360, 1, "numpy") for V in (1000, 3000, 10_000)] + [(1000, n, 1, "numpy") for n in (90, 1440)]
    runs += [(10_000, 360, cores, "numpy")] if cores > 1 else []
    calls = []
    try:
        import numba  # noqa: F401

        run_sweep(MECH, draws(4), engine="compiled")  # load (or compile) the kernel first
        runs += [(V, 360, 1, "compiled") for V in (1000, 10_000)]
        calls = per_call()
    except ImportError:
        pass
    times = {}
    for V, n, jobs, engine in runs:
        dt = sweep_time(V, positions=n, jobs=jobs, engine=engine, repeats=3 if V < 10_000 else 1)
        times[V, n, jobs, engine] = dt
        threads = f"{cores} threads" if engine == "compiled" else f"{jobs} process(es)"
        rows_v.append([f"{V}", f"{n}", engine, threads, f"{dt:.2f}", f"{dt / V * 1e3:.3f}"])
        print(V, n, jobs, engine, dt, file=sys.stderr)
    per_loop = loop_time()
    rows_d, per_dynamic_loop = dynamic_rows()
    rows_t = triad_rows()
    per_sweep = times[10_000, 360, 1, "numpy"] / 10_000
    rows_a = []
    for fmt in ("csv", "jsonl"):
        dt, mb, size = analyze(fmt)
        rows_a.append([fmt, f"{dt:.1f}", f"{mb:.0f}", f"{size / 1e6:.0f}"])
        print(fmt, dt, mb, file=sys.stderr)
    try:
        import numba  # noqa: F401
        fmt_note = "numba installed: the number text is written by the compiled loops of `velplan.cli.numfmt`."
    except ImportError:
        fmt_note = "numba not installed: the number text is written by Python's own formatting."
    text = "\n".join([
        "# Sweeps over designs (issue 27)",
        "",
        machine_md(),
        f"Load average at the start: {load}; at the end: {load_average()} (other sessions share the machine).",
        "",
        "## Figures of merit of many variants",
        "",
        "Tolerance Monte Carlo of the shaper (every length and coordinate ±0.1 mm, the guide's angle ±0.05°, "
        "normal with σ = T/3): H, K, θ, the extreme positions (to round-off: grid, then 6 Newton steps), "
        "γ_min with where it occurs, peak |v| and |a| of the ram, and the peak balancing moment (the file's cutting "
        "force, gravity and inertia). Chunks of 256 variants (numpy) or 1024 "
        "(compiled: one kernel call per chunk and Newton step, a parameter set per variant); median of 3 runs "
        "(1 at 10⁴ variants).",
        "",
        table(["variants", "angles", "engine", "workers", "seconds", "ms per variant"], rows_v),
        "",
        f"The same figures by a Python loop over studies (`Study(variant, angles=360)`: its stroke and "
        f"kinematics): {per_loop * 1e3:.1f} ms per variant, {per_loop / per_sweep:.0f}× the sweep's "
        f"{per_sweep * 1e3:.2f} ms.",
        "",
        "## What the dynamic figures cost",
        "",
        "The same 1000 shaper variants × 360 angles, numpy engine, one process, median of 3 runs: the kinematic "
        "figures alone (the file's loads and masses taken out), with the peak balancing moment (loads, gravity and "
        "inertia by the power balance, at the 360 angles), and with the flywheel's J_I for δ = 0.05 (64 panels of "
        "16 nodes cut at each variant's breakpoints, the cutting force's on and off angles found by Newton's steps "
        "on all variants together).",
        "",
        table(["figures", "seconds", "ms per variant"], rows_d),
        "",
        f"The same two figures by a loop over variants (`force_analysis_at` at 360 angles and "
        f"`dynamics_analysis(delta=0.05)` per variant): {per_dynamic_loop:.0f} ms per variant.",
        "",
        "## A class III group",
        "",
        "256 tolerance variants of triad-press × 360 angles (one run each): each variant's branch is followed over "
        "the turn (720 steps) in all variants together, a Newton correction per step for all of them.",
        "",
        table(["how", "seconds", "ms per variant"], rows_t),
        "",
        "## The compiled engine's fixed cost per call",
        "",
        "`velplan.solve(four_bar, phi, engine=…)`, median of 300 calls in one process: the compiled engine "
        "memoises each mechanism's program and output layout, and runs calls of up to 4096 angles on the "
        "calling thread alone (waking the other threads cost milliseconds on this busy machine).",
        "",
        table(["engine", "angles", "µs per call"], calls) if calls else "numba is not installed.",
        "",
        "## Streamed output of `velplan analyze`",
        "",
        "`velplan analyze four-bar --positions 1000000 --format FMT -o FILE` in a fresh process: solved and "
        f"written 16 384 positions at a time. {fmt_note}",
        "",
        table(["format", "seconds", "peak memory, MB (max RSS)", "file, MB"], rows_a),
        "",
        "Targets (issue 27): 10⁴ shaper variants × 360 positions in ≤ 5 s on 2 cores (compiled engine; "
        "numpy within 3×); `analyze` at 10⁶ positions in ≤ 10 s and ≤ 1 GB.",
        "",
    ])
    write(RESULTS / "sweep.md", text)


if __name__ == "__main__":
    main()
