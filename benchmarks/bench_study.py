"""What one command computes: calls of the solver and of the plan construction per CLI command,
and the time of each, with one `Study` per command (issue 9).

Every call of ``velplan.solve`` (wherever it is imported) and of ``Plan.evaluate`` is counted
while the command runs in this process; the solver's calls are also split by who made them.
A second table times each command cold (a fresh process, median of 5) — compare it with the
figures in ``results/cli.md`` and with an older checkout (``--vs DIR``: the same commands run
from that tree, paired).

    python benchmarks/bench_study.py                 # ~40 s
    python benchmarks/bench_study.py --vs /tmp/old   # also time an older checkout

Writes ``benchmarks/results/study.md``. Targets: one sheet ≤ 12 solves and ≤ 4 evaluations;
cold ``velplan sheet shaper`` at least 30 % faster than before the study.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time
import traceback
from pathlib import Path

from _common import RESULTS, ROOT, load_average, machine_md, table, write

COMMANDS = [
    ["sheet", "shaper"],
    ["sheet", "shaper", "--kind", "forces"],
    ["sheet", "press"],
    ["info", "shaper"],
    ["analyze", "shaper"],
    ["plan", "press", "--position", "2", "--scale-v", "0.0007"],
    ["compare", "four-bar"],
    ["forces", "shaper"],
    ["diagrams", "press"],
    ["steps", "shaper", "--position", "3"],
]
RUNS = 5


def counted(argv: list[str]) -> tuple[int, int, collections.Counter, float]:
    """(solves, evaluations, solves by caller, seconds) of one command run in this process."""
    import velplan.analysis.solver as solver
    import velplan.plans.engine as engine

    solve, evaluate = solver.solve, engine.Plan.evaluate
    calls = {"solve": 0, "evaluate": 0}
    callers: collections.Counter = collections.Counter()

    def counting_solve(*a, **k):
        if not k.get("_inner"):
            calls["solve"] += 1
            frames = [f for f in traceback.extract_stack()[:-1] if "velplan" in f.filename]
            callers[f"{Path(frames[-1].filename).stem}.{frames[-1].name}" if frames else "?"] += 1
        k.pop("_inner", None)
        return solve(*a, **k)

    def counting_evaluate(self, *a, **k):
        calls["evaluate"] += 1
        return evaluate(self, *a, **k)

    patched = [m for m in list(sys.modules.values())
               if getattr(m, "__name__", "").startswith("velplan") and getattr(m, "solve", None) is solve]
    for m in patched:
        m.solve = counting_solve
    engine.Plan.evaluate = counting_evaluate
    from velplan.cli import main

    try:
        with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()):
            out = ["-o", os.path.join(tmp, "out")] if argv[0] in ("sheet", "diagrams", "steps") else []
            t = time.perf_counter()
            main(argv + out)
            dt = time.perf_counter() - t
    finally:
        for m in patched:
            m.solve = solve
        engine.Plan.evaluate = evaluate
    return calls["solve"], calls["evaluate"], callers, dt


def _import_everything() -> None:
    """Import every velplan module first, so that each binds ``solve`` before it is patched."""
    import pkgutil

    import velplan

    for info in pkgutil.walk_packages(velplan.__path__, "velplan."):
        if not info.name.startswith(("velplan.analysis.compiled", "velplan.__main__")):
            __import__(info.name)


def cold(argv: list[str], cwd: Path, cache: str) -> float:
    """Median wall time of a fresh process running ``velplan ARGV`` from the tree ``cwd``, with
    Python's bytecode written to (and read from) ``cache`` — an installed package has its .pyc
    files — whatever PYTHONDONTWRITEBYTECODE says."""
    env = {**os.environ, "PYTHONPATH": str(cwd), "PYTHONPYCACHEPREFIX": cache}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    with tempfile.TemporaryDirectory() as tmp:
        out = ["-o", os.path.join(tmp, "out")] if argv[0] in ("sheet", "diagrams", "steps") else []
        cmd = [sys.executable, "-m", "velplan", *argv, *out]
        subprocess.run(cmd, env=env, capture_output=True, check=True, cwd=tmp)
        times = []
        for _ in range(RUNS):
            t = time.perf_counter()
            subprocess.run(cmd, env=env, capture_output=True, check=True, cwd=tmp)
            times.append(time.perf_counter() - t)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vs", type=Path, help="an older checkout to time the same commands from")
    args = parser.parse_args()
    _import_everything()
    rows, callers_rows = [], []
    for argv in COMMANDS:
        n_solve, n_eval, callers, dt = counted(argv)
        rows.append([f"`velplan {' '.join(argv)}`", str(n_solve), str(n_eval), f"{dt:.2f}"])
        callers_rows.append([f"`{' '.join(argv)}`", ", ".join(f"{k} {v}" for k, v in callers.most_common())])
        print(rows[-1])
    timing = []
    with tempfile.TemporaryDirectory() as cache_new, tempfile.TemporaryDirectory() as cache_old:
        for argv in COMMANDS[:3]:
            new = cold(argv, ROOT, cache_new)
            line = [f"`velplan {' '.join(argv)}`", f"{new:.3f}"]
            if args.vs:
                old = cold(argv, args.vs, cache_old)
                line += [f"{old:.3f}", f"{new / old:.2f}"]
            timing.append(line)
            print(line)
    head = ["command", "cold s (this tree)"] + (["cold s (--vs)", "ratio"] if args.vs else [])
    text = "\n\n".join([
        "# One study per command: solves, plan constructions and time",
        machine_md() + f"\nLoad average at the start: {load_average()}.",
        "## Calls per command (in process, after imports)",
        table(["command", "solve calls", "Plan.evaluate calls", "seconds"], rows),
        "## Who calls the solver",
        table(["command", "caller → calls"], callers_rows),
        f"## Cold processes (median of {RUNS}; bytecode cached, as an installed package has it)",
        table(head, timing),
    ])
    write(RESULTS / "study.md", text + "\n")


if __name__ == "__main__":
    main()
