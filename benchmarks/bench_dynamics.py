"""Machine dynamics (issue 23): run time against error.

* speed, warm, in process: the shaper's steady state with its flywheel by the three methods
  (`dynamics_analysis(shaper, delta=0.05)`), and a Kloss run of the slider-press, each the median of many
  calls (wall and CPU time);
* the Kloss run against a bare DOP853 integration of the same reduction at the same tolerance
  (scipy's ``solve_ivp`` on the same J, J′, M in plain floats, one piece, no events, no dense
  output), alternated in one process, the ratio taken pair by pair;
* the error of the driving moment, J_I, ω_max, ω_min and the period (and a run's time) against
  a converged reference (2048 panels, ODE rtol 1e-13), against the panels (and rtol), on
  bundled and catalogue mechanisms with table, parabola, Fourier and indicator loads; the
  defaults (64 panels, doubled while the estimate exceeds 1e-12; rtol 1e-11) are chosen from it.

    python benchmarks/bench_dynamics.py                 # ~1 min
    python benchmarks/bench_dynamics.py --before DIR    # also an older package, e.g. unpacked by
                                                        # git archive HEAD | tar -x -C DIR

Writes ``benchmarks/results/dynamics.md``. Targets (issue 23): steady state with the flywheel
≤ 20 ms warm; the Kloss run ≤ 2× the bare DOP853 integration.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from _common import RESULTS, ROOT, load_average, machine_md

EX = ROOT / "velplan"
STEPPED = """
[[load]]
kind = "table"
name = "Fc"
over = "output"
stroke = "working"
direction = "against-motion"
x = {x}
values = [0.0, 0.0, 1400.0, 1400.0, 900.0, 900.0, 0.0, 0.0]
[dynamics]
delta = 0.05
[[dynamics.inertia]]
name = "motor rotor"
inertia = 0.2
rpm = 960.0
"""
PRESS_TABLE = """
[[load]]
kind = "table"
name = "P"
over = "output"
stroke = "working"
direction = "against-motion"
x = {x}
values = [0.0, 0.0, 8000.0, 30000.0, 0.0, 0.0]
"""
KLOSS_RUN = """
[dynamics.motor]
kind = "kloss"
critical_torque = 120.0
synchronous_rpm = 1000.0
critical_rpm = 800.0
ratio = 12.0
efficiency = 0.9
[dynamics.run]
omega = -8.0
travel_deg = 720.0
"""
SLIDER_KLOSS = """
[dynamics]
[[dynamics.inertia]]
name = "flywheel"
inertia = 40.0
ratio = 1.0
[dynamics.motor]
kind = "kloss"
critical_torque = 120.0
synchronous_rpm = 1500.0
critical_rpm = 1200.0
ratio = 24.0
efficiency = 0.9
[dynamics.run]
omega = 6.2
travel_deg = 360.0
"""
JUMPS = {"shaper": "[0.0, 0.03, 0.03, 0.30, 0.30, 0.57, 0.57, 0.5998]",
         "press": "[0.0, 0.09, 0.105, 0.119, 0.119, 0.1231]"}
RAMPS = {"shaper": "[0.0, 0.03, 0.0301, 0.30, 0.3001, 0.57, 0.5701, 0.5998]",  # steps as 0.1 mm ramps
         "press": "[0.0, 0.09, 0.105, 0.119, 0.1191, 0.1231]"}
PANELS = (16, 32, 64, 128, 256, None)
"""None: the default (64, doubled while the error estimate exceeds 1e-12)."""
RTOLS = (1e-8, 1e-9, 1e-10, 1e-11, 1e-12)


def _strip_loads(text: str) -> str:
    import re

    return re.sub(r"\[\[load\]\][^\[]*", "", text)


def cases(folder: Path, jumps: bool) -> dict[str, Path]:
    """Mechanism files of the accuracy cases (``jumps`` False: steps written as steep ramps,
    which an older package accepts)."""
    x = JUMPS if jumps else RAMPS
    shaper = _strip_loads((EX / "examples/shaper.toml").read_text())
    press = _strip_loads((EX / "catalogue/stamping-press.toml").read_text())
    i = press.index("[dynamics]")
    slider = (EX / "examples/slider-press.toml").read_text()
    steady = "\n[dynamics]\ndelta = 0.05\n"
    fourier = slider.replace("\nb2 = 0.005\n", "\nb2 = 0.005\nharmonics = 8\n")
    press_table = press[:i] + PRESS_TABLE.format(x=x["press"]) + "\n" + press[i:]
    texts = {
        "shaper, stepped cutting table": shaper + STEPPED.format(x=x["shaper"]),
        "shaper, cutting force (seed 002)": (EX / "examples/shaper.toml").read_text() + steady,
        "stamping press, table load": press_table,
        "slider-press, parabola": slider + steady,
        "slider-press, Fourier 8": fourier + steady,
        "compressor, indicator diagram": (EX / "catalogue/compressor.toml").read_text(),
        "stamping press, table load, Kloss run": press_table + KLOSS_RUN,
    }
    out = {}
    for k, (name, text) in enumerate(texts.items()):
        out[name] = folder / f"case{k}.toml"
        out[name].write_text(text)
    return out


WORKER = r'''
import json, math, statistics, sys, time
import numpy as np
import velplan
from velplan.dynamics import dynamics_analysis
mode, arg = sys.argv[1], json.loads(sys.argv[2])


def values(d):
    out = {"driving moment": d.driving}
    if d.flywheel is not None:
        out["J_I exact"] = d.flywheel.exact
        out["J_I Mertsalov"] = d.flywheel.mertsalov
    st = d.steady or d.periodic
    if st is not None:
        out.update({"omega max": st.omega_max, "omega min": st.omega_min, "period": st.period})
    if d.run is not None:
        out.update({"run time": d.run.time, "omega end": d.run.omega_end})
    return out


def timed(f, n):
    f()
    wall, cpu = [], []
    for _ in range(n):
        a, b = time.perf_counter(), time.process_time()
        f()
        wall.append(time.perf_counter() - a), cpu.append(time.process_time() - b)
    return statistics.median(wall), statistics.median(cpu)


if mode == "speed":
    from velplan.forces.parse import parse_loads

    shaper = velplan.load("shaper")
    loads = parse_loads(shaper)
    slider = velplan.load(arg["slider"])
    print(json.dumps({"steady": timed(lambda: dynamics_analysis(shaper, delta=0.05), 31),
                      "steady_study": timed(lambda: dynamics_analysis(shaper, loads, delta=0.05), 31),
                      "kloss": timed(lambda: dynamics_analysis(slider), 11)}))
elif mode == "values":
    out = {}
    for name, path in arg["cases"].items():
        m = velplan.load(path)
        rows = {}
        for p in arg["panels"]:
            kw = {} if p is None else {"panels": p}  # None: the package's default
            t = timed(lambda: dynamics_analysis(m, **kw), 3)[1]
            rows[p] = {"cpu": t, **values(dynamics_analysis(m, **kw))}
        out[name] = rows
    print(json.dumps(out))
'''


def worker(pythonpath: Path, mode: str, arg: dict) -> dict:
    env = dict(os.environ, PYTHONPATH=str(pythonpath))
    out = subprocess.run([sys.executable, "-c", WORKER, mode, json.dumps(arg)], capture_output=True, text=True,
                         env=env, cwd=tempfile.gettempdir())
    if out.returncode:
        raise SystemExit(out.stderr)
    return json.loads(out.stdout)


def reference(paths: dict[str, Path]) -> dict[str, dict]:
    """Converged values: 2048 panels and, for a run, rtol 1e-13 (current package)."""
    import math

    import velplan
    from velplan.dynamics import dynamics_analysis
    from velplan.dynamics.run import simulate

    out = {}
    for name, path in paths.items():
        d = dynamics_analysis(velplan.load(str(path)), panels=2048)
        v = {"driving moment": d.driving}
        if d.flywheel is not None:
            v.update({"J_I exact": d.flywheel.exact, "J_I Mertsalov": d.flywheel.mertsalov})
        if d.steady is not None:
            v.update({"omega max": d.steady.omega_max, "omega min": d.steady.omega_min, "period": d.steady.period})
        if d.run is not None:
            r = simulate(d.profile, d.inertia, d.motor.moment, d.run.omega_start, travel=d.run.travel, rtol=1e-13)
            v.update({"run time": r.time, "omega end": r.omega_end})
        out[name] = v
        assert all(math.isfinite(x) for x in v.values())
    return out


def kloss_against_dop853(path: Path, pairs: int = 11) -> tuple[float, float, float, int, int]:
    """(ours s, bare DOP853 s, median ratio, ours RHS calls, bare RHS calls), medians of
    alternated pairs."""
    import math
    import statistics
    import time

    from scipy.integrate import solve_ivp

    import velplan
    from velplan.dynamics import dynamics_analysis
    from velplan.dynamics.run import RTOL, _Series, simulate

    d = dynamics_analysis(velplan.load(str(path)))
    prof, inertia, mom, w0, travel = d.profile, d.inertia, d.motor.scalar(), d.run.omega_start, d.run.travel
    calls = [0, 0]

    def ours():
        return simulate(prof, inertia, d.motor.moment, w0, travel=travel, scalar=mom)

    def bare():
        s = _Series(prof)

        def f(t, y):
            calls[1] += 1
            j, dj, m = s.at(y[0])
            return [y[1], (m + mom(y[1]) - 0.5 * dj * y[1] * y[1]) / (inertia + j)]

        end = lambda t, y: y[0] - travel  # noqa: E731
        end.terminal = True
        return solve_ivp(f, (0.0, 60.0), [0.0, w0], method="DOP853", rtol=RTOL,
                         atol=[1e-13 * 2 * math.pi, 1e-12 * max(w0, 1.0)], events=[end])

    ours(), bare()
    a, b, r = [], [], []
    for _ in range(pairs):
        t0 = time.process_time()
        ours()
        t1 = time.process_time()
        calls[1] = 0
        bare()
        t2 = time.process_time()
        a.append(t1 - t0), b.append(t2 - t1), r.append((t1 - t0) / (t2 - t1))
    return statistics.median(a), statistics.median(b), statistics.median(r), 0, calls[1]


def error_table(values: dict, ref: dict, panels) -> list[str]:
    head = [f"{p} panels" if p else "default" for p in panels]
    lines = ["| case | " + " | ".join(head) + " |", "|---|" + "---:|" * len(panels)]
    for name, rows in values.items():
        cells = []
        for p in panels:
            row = rows["null" if p is None else str(p)]
            err = max(abs(row[k] - ref[name][k]) / abs(ref[name][k]) for k in ref[name] if k in row)
            cells.append(f"{err:.1e} ({1e3 * row['cpu']:.1f} ms)")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return lines


def rtol_table(path: Path, ref: dict) -> list[str]:
    import statistics
    import time

    import velplan
    from velplan.dynamics import dynamics_analysis
    from velplan.dynamics.run import simulate

    d = dynamics_analysis(velplan.load(str(path)))
    lines = ["| rtol | run time, s | relative error | estimated error | CPU, ms |", "|---:|---:|---:|---:|---:|"]
    for rtol in RTOLS:
        ts, r = [], None
        for _ in range(3):
            t = time.process_time()
            r = simulate(d.profile, d.inertia, d.motor.moment, d.run.omega_start, travel=d.run.travel, rtol=rtol,
                         scalar=d.motor.scalar())
            ts.append(time.process_time() - t)
        err = abs(r.time - ref["run time"]) / ref["run time"]
        lines.append(f"| {rtol:.0e} | {r.time:.15g} | {err:.1e} | {r.errors['time'] / r.time:.1e} | "
                     f"{1e3 * statistics.median(ts):.1f} |")
    return lines


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", type=Path, help="an older package's root (its velplan/ inside) to time beside")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "new").mkdir(), (tmp / "old").mkdir()
        paths = cases(tmp / "new", jumps=True)
        slider = tmp / "slider-kloss.toml"
        slider.write_text((EX / "examples/slider-press.toml").read_text() + SLIDER_KLOSS)
        ref = reference(paths)
        now = worker(ROOT, "speed", {"slider": str(slider)})
        vals = worker(ROOT, "values", {"cases": {k: str(v) for k, v in paths.items()}, "panels": PANELS})
        before = old_vals = old_ref = None
        if args.before:
            before = worker(args.before, "speed", {"slider": str(slider)})
            old_paths = cases(tmp / "old", jumps=False)
            old_ref = reference(old_paths)  # the ramps are cut at both ends: converged as well
            old_vals = worker(args.before, "values", {"cases": {k: str(v) for k, v in old_paths.items()},
                                                      "panels": PANELS})
            new_on_old = worker(ROOT, "values", {"cases": {k: str(v) for k, v in old_paths.items()},
                                                 "panels": (None,)})
        ours, bare, ratio, _, nfev = kloss_against_dop853(paths["stamping press, table load, Kloss run"])
        ours2, bare2, ratio2, _, nfev2 = kloss_against_dop853(slider)
        rt = rtol_table(paths["stamping press, table load, Kloss run"], ref["stamping press, table load, Kloss run"])
    lines = ["# Machine dynamics: run time against error (issue 23)", "", machine_md(),
             f"- **load average** (other sessions share the machine): {load_average()}", "",
             "## Speed, warm, in process (median)", "",
             "| case | wall, ms | CPU, ms |" + (" before: wall, ms | before: CPU, ms |" if before else ""),
             "|---|---:|---:|" + ("---:|---:|" if before else "")]
    for key, label in (("steady", "shaper: steady state + flywheel by 3 methods (δ = 0.05), `dynamics_analysis(mech)`"),
                       ("steady_study", "the same with its loads parsed once (as `Study.dynamics` calls it)"),
                       ("kloss", "slider-press: Kloss run, one turn (whole `analyse`)")):
        row = f"| {label} | {1e3 * now[key][0]:.1f} | {1e3 * now[key][1]:.1f} |"
        if before and key in before:
            row += f" {1e3 * before[key][0]:.1f} | {1e3 * before[key][1]:.1f} |"
        lines.append(row)
    lines += ["", "Medians of 31 calls (11 for the run) after one warm-up. Target: the shaper's steady state "
              "with the flywheel ≤ 20 ms warm. Parsing the loads (the cutting force's on/off angles, by a "
              "root search on the solver) takes about 3 ms of the first line.", "",
              "## Kloss run against a bare DOP853 integration of the same reduction (CPU, median of 11 "
              "alternated pairs)", "",
              "| case | ours (events, restarts at jumps, dense output), ms | bare DOP853, ms | ratio | bare RHS calls |",
              "|---|---:|---:|---:|---:|",
              f"| slider-press, one turn | {1e3 * ours2:.1f} | {1e3 * bare2:.1f} | {ratio2:.2f} | {nfev2} |",
              f"| stamping press with a table load, two turns | {1e3 * ours:.1f} | {1e3 * bare:.1f} | {ratio:.2f} | {nfev} |",
              "", "Target: ratio ≤ 2. The bare run integrates across the loads' jumps in one piece (its own "
              "error is then larger).", "",
              "## Error against panels (largest relative error over the driving moment, J_I exact and "
              "Mertsalov, ω_max, ω_min, period, run time, ω at its end; CPU of one `analyse`)", "",
              "Reference: 2048 panels, rtol 1e-13. Default: 64 panels (doubled while the error estimate "
              "exceeds 1e-12 relative; none of these needs it): 64 are as converged as 256 everywhere, 16 "
              "already within 3e-13.", ""]
    lines += error_table(vals, ref, PANELS)
    if old_vals:
        lines += ["", "Before (the package given by --before) on the same loads with their steps written as "
                  "0.1 mm ramps, since it refuses a repeated x; reference: the current package at 2048 panels "
                  "on the same ramps:", ""]
        lines += error_table(old_vals, old_ref, PANELS)
        lines += ["", "The current package on those ramps (it cuts the panels at both ends of each):", ""]
        lines += error_table(new_on_old, old_ref, (None,))
    lines += ["", "## Run time against the ODE tolerance (stamping press, table load, Kloss run, default panels)", ""]
    lines += rt
    lines += ["", "Default rtol 1e-11: the run's error stays below 1e-10 relative at about the cost of "
              "1e-10; the estimate (10·rtol·t plus the profile's part) bounds the error.", ""]
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "dynamics.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
