"""The course's sizes (issue 34): ``velplan.solve`` per call at 1 … 10⁴ positions (and 10⁶ once)
against pylinkage + numba, and the first answer of each command against a bare interpreter.

Per call (positions, velocities, accelerations), on the four-bar and the shaper: velplan's numpy
engine, its compiled engine, and the default (``engine="auto"``) against pylinkage's
``step_fast_with_kinematics`` (its numba kernels compiled before timing), all in this process.
Each round times every contender in turn — the order rotated round by round — for about
``--budget`` seconds each and takes the mean per call; the table gives each one's median over the
rounds and the median of its per-round ratio to the peer with the lowest and highest of them.

The shaper in pylinkage: the crank, the bar's point B as a `FixedDyad` on the line O3 → A (the
guide bar through the block), the ram F as an `RRPDyad` on y = 0.6572 m. pylinkage picks the
solution nearest its last position: at 12 positions it jumps to the wrong branch of the ram at
φ = 270° (column "peer right?"); velplan's closed form has no such failure.

Cold commands: whole processes in alternating pairs with the floor ``python -c "import numpy,
shapely"``, the ratio pair by pair (median, lowest, highest).

    python benchmarks/bench_small.py                # ≈ 3 min on 2 cores
    python benchmarks/bench_small.py --quick        # fewer rounds, no 10⁶, no cold commands
    python benchmarks/bench_small.py --triad-only --clock cpu   # the class III triad at 10⁵ only
    python benchmarks/bench_small.py --triad-only --clock cpu --print   # the same, printed (nothing written)
    python benchmarks/bench_small.py --triad-before /tmp/old --pairs 5   # the triad, old tree against this one
    git archive OLD | tar -x -C /tmp/old && python benchmarks/bench_small.py --before /tmp/old --clock cpu
    python benchmarks/bench_small.py --cold-only --pairs 5   # the cold table alone, printed
    python benchmarks/bench_small.py --cold-only --cold-match note   # only the rows naming "note"

Writes ``benchmarks/results/small.md``.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from _common import RESULTS, ROOT, grid, load_average, machine_md, table, write

SIZES = (1, 12, 72, 360, 10_000)
HUGE = 1_000_000
MECHS = ("four-bar", "shaper")
ENGINES = ("numpy", "compiled", "auto")
COLD = {
    "velplan sheet shaper": ("sheet", "shaper", "-o", "s.svg"),
    "velplan sheet shaper --kind forces": ("sheet", "shaper", "--kind", "forces", "-o", "f.svg"),
    "velplan html shaper": ("html", "shaper", "-o", "s.html"),
    "velplan note shaper --lang ru -o n.docx": ("note", "shaper", "--lang", "ru", "-o", "n.docx"),
}
"""Cold commands: the table's label → the arguments after ``python -m velplan``."""


def pylinkage_shaper(n: int):
    """The shaper of ``velplan/examples/shaper.toml`` as a pylinkage Linkage recording the crank
    angles 0, Δ, … (Δ = 2π/n): (linkage, names of its components in output order)."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRPDyad
    from pylinkage.simulation import Linkage

    d = 2 * math.pi / n
    O3, O2 = Ground(0.0, 0.0, name="O3"), Ground(0.0, 0.370, name="O2")
    crank = Crank(anchor=O2, radius=0.1605, angular_velocity=d, initial_angle=-d, name="A")
    B = FixedDyad(O3, crank.output, distance=0.6914, angle=0.0, name="B")
    L1, L2 = Ground(0.0, 0.6572, name="L1"), Ground(1.0, 0.6572, name="L2")
    F = RRPDyad(B, L1, L2, distance=0.2074, x=0.3, y=0.6572, name="F")
    comps = [O3, O2, L1, L2, crank, B, F]
    link = Linkage(comps, name="shaper")
    link.set_input_velocity(crank, omega=80 * 2 * math.pi / 60, alpha=0.0)
    return link, [c.name for c in comps]


def peer(mech: str, n: int):
    """pylinkage's call at ``n`` positions (compiled), and its points {name: column}."""
    from bench_peers import pylinkage_model

    if mech == "four-bar":
        link, ia, ib = pylinkage_model("four-bar", n)
        cols = {"A": ia, "B": ib}
    else:
        link, names = pylinkage_shaper(n)
        cols = {k: names.index(k) for k in ("A", "B", "F")}
    link.compile()
    link.step_fast_with_kinematics(iterations=n)  # numba compiles its kernels here
    return (lambda: link.step_fast_with_kinematics(iterations=n)), link, cols


def peer_right(mech: str, n: int, tol: float = 1e-6) -> bool:
    """Whether pylinkage's first turn gives velplan's positions at every angle (m, to ``tol``)."""
    import velplan

    _, link, cols = peer(mech, n)  # a fresh linkage: one warm-up turn, then the turn compared
    pos = link.step_fast_with_kinematics(iterations=n)[0]
    kin = velplan.solve(velplan.load(mech), grid(n))
    return all(np.nanmax(np.abs(pos[:, j] - kin.position(k))) < tol for k, j in cols.items())


def contenders(mech_name: str, n: int) -> dict:
    import velplan

    mech = velplan.load(mech_name)
    phi = grid(n)
    calls = {e: (lambda e=e: velplan.solve(mech, phi, engine=e)) for e in ENGINES}
    calls["auto"] = lambda: velplan.solve(mech, phi)
    calls["peer"] = peer(mech_name, n)[0]
    for f in calls.values():
        f()
    return calls


CLOCK = {"wall": time.perf_counter, "cpu": time.process_time}
"""``--clock``: wall time, or this process's CPU time (all its threads: steadier on a shared
machine; the compiled engine runs on one thread up to 4096 angles, pylinkage always)."""
_clock = CLOCK["wall"]
_clock_name = "wall"


def per_call(fn, budget: float) -> float:
    """Mean seconds per call of ``fn`` over at least ``budget`` seconds (at least one call)."""
    calls, t0 = 0, _clock()
    while True:
        fn()
        calls += 1
        t = _clock() - t0
        if t >= budget:
            return t / calls


def rounds(calls: dict, count: int, budget: float) -> dict[str, list[float]]:
    """Per-call times of every contender over ``count`` rounds, the order rotated each round."""
    names = list(calls)
    out: dict[str, list[float]] = {k: [] for k in names}
    for r in range(count):
        for k in names[r % len(names):] + names[:r % len(names)]:
            out[k].append(per_call(calls[k], budget))
    return out


def _ratio_cell(mine: list[float], theirs: list[float]) -> str:
    r = [a / b for a, b in zip(mine, theirs)]
    return f"{statistics.median(r):.2f} ({min(r):.2f}–{max(r):.2f})"


def solve_table(sizes, count: int, budget: float) -> str:
    rows = []
    for mech in MECHS:
        for n in sizes:
            t = rounds(contenders(mech, n), count if n < HUGE else 1, budget if n < HUGE else 0.0)
            med = {k: statistics.median(v) * 1e6 for k, v in t.items()}
            right = "yes" if n == 1 or peer_right(mech, n) else "**no**"
            rows.append([mech, f"{n:,}", *(f"{med[k]:.3g}" for k in (*ENGINES, "peer")),
                         *(_ratio_cell(t[k], t["peer"]) for k in ENGINES), right, load_average()])
            print(rows[-1], flush=True)
    head = ["mechanism", "positions", "numpy µs", "compiled µs", "auto (default) µs", "pylinkage+numba µs",
            "numpy / peer", "compiled / peer", "auto / peer", "peer right?", "load"]
    return table(head, rows)


SWITCH = """
import time, numpy as np, velplan
from velplan.analysis import solver
mech, phi = velplan.load("{mech}"), np.arange({n}) * (2 * np.pi / {n})
calls, t0 = 0, time.perf_counter()
while not solver._AUTO_ON[0] and calls < 10**6:
    velplan.solve(mech, phi)
    calls += 1
print(calls, time.perf_counter() - t0)
"""


def switch_point(mech: str = "four-bar", n: int = 12) -> str:
    """When a fresh process's default engine moves to the compiled kernel: after how many calls
    at ``n`` positions and how many seconds (numba not imported before)."""
    out = subprocess.run([sys.executable, "-c", SWITCH.format(mech=mech, n=n)], capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH=str(ROOT)), check=True).stdout.split()
    return (f"In a fresh process (numba not imported), the default engine solved the {mech} at {n} positions "
            f"{int(out[0])} times with numpy before it loaded the compiled kernel ({float(out[1]):.2f} s in all, the load "
            f"included; machine load {load_average()}).")


LARGE = """
import json, time, numpy as np, velplan
out = {}
for name in ("four-bar", "shaper"):
    mech = velplan.load(name)
    for n, reps in ((10_000, 30), (100_000, 7), (1_000_000, 3)):
        phi = np.arange(n) * (2 * np.pi / n)
        velplan.solve(mech, phi, engine="numpy")
        ts = []
        for _ in range(reps):
            t0 = time.process_time()
            velplan.solve(mech, phi, engine="numpy")
            ts.append(time.process_time() - t0)
        out[f"{name} {n}"] = float(np.median(ts)) / n * 1e9
print(json.dumps(out))
"""


def large_table(before: str, pairs: int) -> str:
    """The numpy engine at 10⁴–10⁶ positions (ns per position, CPU time, median of repeats in
    one process), this tree against ``before``, in alternating processes."""
    import json

    runs: dict[str, list[dict]] = {"before": [], "after": []}
    for _ in range(pairs):
        for key, tree in (("before", before), ("after", str(ROOT))):
            out = subprocess.run([sys.executable, "-c", LARGE], capture_output=True, text=True, check=True,
                                 env=dict(os.environ, PYTHONPATH=tree)).stdout
            runs[key].append(json.loads(out))
    rows = []
    for case in runs["after"][0]:
        b, a = [r[case] for r in runs["before"]], [r[case] for r in runs["after"]]
        ratio = [y / x for x, y in zip(b, a)]
        rows.append([case, f"{statistics.median(b):.0f}", f"{statistics.median(a):.0f}",
                     f"{statistics.median(ratio):.2f} ({min(ratio):.2f}–{max(ratio):.2f})"])
    return table(["mechanism, positions", "before ns/position", "after ns/position", "after ÷ before, pair by pair"],
                 rows) + f"\n\nLoad at the end: {load_average()}."


TRIADS = ("triad-rocker", "triad-press")
TRIAD_N = 100_000
TRIAD_HEADING = "## The class III triad per position against the four-bar"


def triad_rows(count: int) -> list[list[str]]:
    """Per position at `TRIAD_N` angles: the four-bar and the triads, numpy and compiled, every
    contender in turn each round (one call each, the order rotated); each triad's median per-round
    ratio to the four-bar on the same engine, and its compiled time over the four-bar's numpy time."""
    import velplan

    phi = grid(TRIAD_N)
    calls = {}
    for name in ("four-bar", *TRIADS):
        mech = velplan.load(name)
        for engine in ("numpy", "compiled"):
            calls[(name, engine)] = lambda m=mech, e=engine: velplan.solve(m, phi, engine=e)
            calls[(name, engine)]()
    t = rounds(calls, count, 0.0)
    rows = []
    for name in ("four-bar", *TRIADS):
        cells = [name]
        for engine in ("numpy", "compiled"):
            cells += [f"{statistics.median(t[(name, engine)]) / TRIAD_N * 1e6:.3g}",
                      _ratio_cell(t[(name, engine)], t[("four-bar", engine)])]
        cells += [_ratio_cell(t[(name, "compiled")], t[("four-bar", "numpy")]), load_average()]
        rows.append(cells)
        print(rows[-1], flush=True)
    return rows


def triad_table(count: int) -> str:
    head = ["mechanism", "numpy µs/position", "÷ four-bar (numpy)", "compiled µs/position", "÷ four-bar (compiled)",
            "compiled ÷ four-bar numpy", "load"]
    start = load_average()
    body = table(head, triad_rows(count))
    return f"""{TRIAD_HEADING}

{TRIAD_N:,} positions (positions, velocities, accelerations), {_clock_name} clock, the median of {count}
alternating rounds in one process (one call per contender per round, the order rotated); ratios:
the median of the per-round ratios (lowest–highest). Load {start} at the start.

{body}
"""


TRIAD_CALLS = """
import json, statistics, time, numpy as np, velplan
out = {}
for name in ("four-bar", "triad-rocker", "triad-press"):
    mech = velplan.load(name)
    for engine in ("numpy", "compiled"):
        for n, reps in ((12, 300), (100_000, 5)):
            phi = np.arange(n) * (2 * np.pi / n)
            velplan.solve(mech, phi, engine=engine)
            ts = []
            for _ in range(reps):
                t0 = time.process_time()
                velplan.solve(mech, phi, engine=engine)
                ts.append(time.process_time() - t0)
            out[f"{name}, {engine}, {n:,}"] = statistics.median(ts) * 1e6
print(json.dumps(out))
"""


def triad_before_table(before: str, pairs: int) -> str:
    """µs per call (CPU time, median of repeats in one process) of the four-bar and the triads at
    12 and 10⁵ positions, both engines, ``before`` (an older tree) against this one in alternating
    processes; and each triad's ratio to the four-bar in the same process, before and after."""
    import json

    runs: dict[str, list[dict]] = {"before": [], "after": []}
    for _ in range(pairs):
        for key, tree in (("before", before), ("after", str(ROOT))):
            out = subprocess.run([sys.executable, "-c", TRIAD_CALLS], capture_output=True, text=True, check=True,
                                 env=dict(os.environ, PYTHONPATH=tree)).stdout
            runs[key].append(json.loads(out.strip().splitlines()[-1]))
            print(key, runs[key][-1], flush=True)
    rows = []
    for case in runs["after"][0]:
        b, a = [r[case] for r in runs["before"]], [r[case] for r in runs["after"]]
        ratio = [y / x for x, y in zip(b, a)]
        four = case.replace(case.split(",")[0], "four-bar")
        per_four = lambda key: statistics.median(r[case] / r[four] for r in runs[key])  # noqa: E731
        rows.append([case, f"{statistics.median(b):.4g}", f"{statistics.median(a):.4g}",
                     f"{statistics.median(ratio):.2f} ({min(ratio):.2f}–{max(ratio):.2f})",
                     f"{per_four('before'):.2f}", f"{per_four('after'):.2f}"])
    head = ["mechanism, engine, positions", "before µs/call", "after µs/call", "after ÷ before, pair by pair",
            "÷ four-bar before", "÷ four-bar after"]
    return table(head, rows) + f"\n\nLoad at the end: {load_average()}."


def splice_triad(text: str) -> None:
    """Put the triad table ``text`` into ``small.md`` in place of its section (or at its end)."""
    path = RESULTS / "small.md"
    old = path.read_text("utf-8") if path.exists() else ""
    if TRIAD_HEADING in old:
        head, rest = old.split(TRIAD_HEADING, 1)
        tail = rest[rest.index("\n## "):] if "\n## " in rest else ""
        new = head + text.rstrip("\n") + "\n" + tail
    else:
        new = old.rstrip("\n") + "\n\n" + text
    write(path, new)


def _cold(args, cwd: str) -> float:
    """Wall seconds of one whole process, its bytecode cached outside the tree (as an installed
    package's is)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=os.path.join(cwd, "pyc"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *args], cwd=cwd, env=env, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def cold_table(pairs: int, match: str = "") -> str:
    """The cold commands whose label contains ``match`` (all by default) against the floor."""
    floor = ("-c", "import numpy, shapely")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, args in COLD.items():
            if match not in label:
                continue
            cmd = ("-m", "velplan", *args)
            _cold(floor, tmp), _cold(cmd, tmp)  # untimed: bytecode and OS caches
            f, c = [], []
            for _ in range(pairs):
                f.append(_cold(floor, tmp))
                c.append(_cold(cmd, tmp))
            r = [b / a for a, b in zip(f, c)]
            rows.append([label, f"{statistics.median(c):.2f}", f"{statistics.median(f):.2f}",
                         f"{statistics.median(r):.1f} ({min(r):.1f}–{max(r):.1f})", load_average()])
            print(rows[-1], flush=True)
    return table(["command", "wall s (median)", "floor s (median)", "÷ floor, pair by pair", "load"], rows)


def _versions() -> str:
    """The compiled engine's and the peer's versions, as markdown items."""
    from importlib import metadata

    return "\n".join(f"- **{pkg}**: {metadata.version(pkg)}" for pkg in ("numba", "pylinkage"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--budget", type=float, default=0.02, help="seconds per contender per round")
    ap.add_argument("--pairs", type=int, default=5, help="cold runs per command")
    ap.add_argument("--clock", choices=tuple(CLOCK), default="wall", help="what a call's time is")
    ap.add_argument("--no-cold", action="store_true", help="leave out the cold commands")
    ap.add_argument("--triad-only", action="store_true",
                    help="only the class III triad against the four-bar, put into small.md in place")
    ap.add_argument("--cold-only", action="store_true",
                    help="time the cold commands alone and print their table (nothing written)")
    ap.add_argument("--print", action="store_true", help="with --triad-only: print the table, write nothing")
    ap.add_argument("--triad-before", metavar="TREE",
                    help="the triad and the four-bar at 12 and 10⁵ positions, an older tree against this one (printed)")
    ap.add_argument("--cold-match", "--only", dest="cold_match", metavar="TEXT", default="",
                    help="with --cold-only: only the commands whose label contains TEXT")
    ap.add_argument("--before", metavar="TREE", help="an older tree: its numpy engine at 10⁴–10⁶ against this one")
    ap.add_argument("--before-label", metavar="TEXT", help="what the older tree is (default: its path)")
    a = ap.parse_args()
    global _clock, _clock_name
    _clock, _clock_name = CLOCK[a.clock], a.clock
    if a.cold_only:
        start = load_average()
        cold = cold_table(a.pairs, a.cold_match)
        print(f"load {start} at the start, {load_average()} at the end\n\n{cold}")
        return
    count = 5 if a.quick else a.rounds
    if a.triad_before:
        start = load_average()
        print(f"load {start} at the start\n\n{triad_before_table(a.triad_before, a.pairs)}")
        return
    if a.triad_only:
        text = triad_table(count)
        print(text) if a.print else splice_triad(text)
        return
    sizes = SIZES if a.quick else (*SIZES, HUGE)
    start = f"load {load_average()} at the start"
    switch = switch_point()
    solved = solve_table(sizes, count, a.budget)
    cold = "" if a.quick or a.no_cold else cold_table(a.pairs)
    text = f"""# Small sizes and cold commands (issue 34)

Written by `benchmarks/bench_small.py`{' --quick' if a.quick else ''}; {start}, load {load_average()} at the end
(the 1-, 5- and 15-minute load averages; each row gives the load when it was taken).

{machine_md()}
{_versions()}

## ``velplan.solve`` per call against pylinkage + numba

Positions, velocities and accelerations; µs per call ({a.clock} clock), the median of {count}
rounds of about {a.budget} s per contender (one call at 10⁶) in one process, the contenders alternating; ratios: the median of the per-round ratios to the
peer (lowest–highest). "auto" is the default engine, in a process that has been solving (the
compiled kernel is loaded once the numpy engine's time reaches the kernel's load cost). {switch}

{solved}
"""
    if a.before:
        text += f"""
## The numpy engine at 10⁴–10⁶ positions, before and after

CPU time per position (medians of 30, 7, 3 repeats), {a.before_label or a.before} against this tree in {a.pairs}
alternating pairs of processes (the default engine's first call in a process is the numpy one; later
calls are the compiled kernel's, faster still).

{large_table(a.before, a.pairs)}
"""
    text += "\n" + triad_table(count)
    if cold:
        text += f"""
## Cold commands against the floor `python -c "import numpy, shapely"`

Whole processes, {a.pairs} alternating pairs after one untimed run of each.

{cold}
"""
    write(RESULTS / "small.md", text)


if __name__ == "__main__":
    main()
