"""Sweeps over designs (issue 27): figures of merit of many shaper variants at once, and the
streamed output of ``velplan analyze``.

* figures of merit (H, K, θ, extremes, γ_min, peak |v|, |a|) of V tolerance variants of the
  shaper × 360 angles, numpy engine: scaling in variants, in angles and in processes;
* the same work as a Python loop over variants (`Study` per variant: stroke + a solve of
  360 angles), per variant;
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

import numpy as np

from _common import RESULTS, load_average, machine_md, median_time, table, write

from velplan.analysis.design import variant
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
        "γ_min with where it occurs, peak |v| and |a| of the ram. Chunks of 256 variants (numpy) or 1024 "
        "(compiled: one kernel call per chunk and Newton step, a parameter set per variant); median of 3 runs "
        "(1 at 10⁴ variants).",
        "",
        table(["variants", "angles", "engine", "workers", "seconds", "ms per variant"], rows_v),
        "",
        f"The same figures by a Python loop over studies (`Study(variant, angles=360)`: its stroke and "
        f"kinematics): {per_loop * 1e3:.1f} ms per variant, {per_loop / per_sweep:.0f}× the sweep's "
        f"{per_sweep * 1e3:.2f} ms.",
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
