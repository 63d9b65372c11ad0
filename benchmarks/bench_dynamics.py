"""Machine dynamics: the shaper's steady state (table at 3600 positions) and a Kloss
single-stroke press run, in process (cold = first call in a fresh process, warm = median of
later calls) and as CLI processes.

    python benchmarks/bench_dynamics.py        # ~30 s

Writes ``benchmarks/results/dynamics.md``. Target (issue 14): both under 1 s warm.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import RESULTS, ROOT, load_average, machine_md

SHAPER = """
[dynamics]
delta = 0.05
[[dynamics.inertia]]
name = "motor rotor"
inertia = 0.2
rpm = 960.0
[dynamics.flywheel]
ratio = 1.8333
shape = "rim"
"""
PRESS = """
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
CASES = {"shaper steady state, 3600 positions": ("shaper", SHAPER, 3600),
         "slider-press Kloss run, one stroke": ("slider-press", PRESS, 12)}
INPROC = """
import sys, time
t0 = time.perf_counter()
import velplan
from velplan.dynamics import analyse
m = velplan.load(sys.argv[1]); n = int(sys.argv[2])
t1 = time.perf_counter(); d = analyse(m); d.table(n); t2 = time.perf_counter()
ws = []
for _ in range(5):
    a = time.perf_counter(); analyse(m).table(n); ws.append(time.perf_counter() - a)
ws.sort()
print(t1 - t0, t2 - t1, ws[2])
"""


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, (example, text, n) in CASES.items():
            path = Path(tmp) / f"{example}.toml"
            path.write_text((ROOT / "velplan" / "examples" / f"{example}.toml").read_text() + text)
            out = subprocess.run([sys.executable, "-c", INPROC, str(path), str(n)], capture_output=True,
                                 text=True, check=True, cwd=ROOT).stdout.split()
            imp, cold, warm = (float(x) for x in out)
            cmd = [sys.executable, "-m", "velplan", "dynamics", str(path), "--positions", str(n), "--format", "json"]
            subprocess.run(cmd, capture_output=True, check=True, cwd=ROOT)
            walls = []
            for _ in range(5):
                t = time.perf_counter()
                subprocess.run(cmd, capture_output=True, check=True, cwd=ROOT)
                walls.append(time.perf_counter() - t)
            rows.append((label, imp, cold, warm, statistics.median(walls)))
    lines = ["# Machine dynamics benchmark", "", machine_md(), f"- **load average**: {load_average()}", "",
             "| case | import velplan, s | first analyse, s | warm analyse (median of 5), s | CLI process (median of 5), s |",
             "|---|---:|---:|---:|---:|"]
    lines += [f"| {a} | {b:.3f} | {c:.3f} | {d:.3f} | {e:.3f} |" for a, b, c, d, e in rows]
    lines += ["", "Target: under 1 s warm. The CLI process includes Python start-up, imports (numpy, scipy) "
              "and the JSON output."]
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "dynamics.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
