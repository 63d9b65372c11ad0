"""A course of variants with ``velplan batch``: 30 random variants of the shaper × 10 positions,
each with its A1 kinematic sheet (SVG), and the answer key, on every core.

* the whole command in a fresh process (``velplan batch --random 30 …``), wall time, with all
  cores and with one (``--jobs 1``), and with PNGs too;
* the per-variant time (study + sheet) in process.

    python benchmarks/bench_batch.py        # ~1 min

Writes ``benchmarks/results/batch.md``. Target (issue 17): a course of 30 × 10 in minutes.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

from _common import RESULTS, load_average, machine_md, table, write

N, POSITIONS = 30, 10
ARGS = ["batch", "--random", str(N), "--seed", "TMM course work 2026", "--base", "shaper", "--spread", "10%",
        "--positions", str(POSITIONS), "--quiet"]


def command() -> list[str]:
    exe = shutil.which("velplan")
    return [exe] if exe else [sys.executable, "-m", "velplan"]


def run(extra: list[str]) -> tuple[float, int]:
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "course")
        t = time.perf_counter()
        proc = subprocess.run(command() + ARGS + ["-o", out] + extra, capture_output=True, text=True)
        dt = time.perf_counter() - t
        if proc.returncode != 0:
            raise SystemExit(f"velplan batch failed: {proc.stderr.strip()}")
        files = len(os.listdir(out))
    return dt, files


def main() -> None:
    load = load_average()
    cores = os.cpu_count() or 1
    rows = []
    for label, extra in ((f"all cores ({cores})", []), ("one process (--jobs 1)", ["--jobs", "1"]),
                         (f"all cores, with PNG", ["--png"]), ("answer key only (--no-sheets)", ["--no-sheets"])):
        dt, files = run(extra)
        rows.append([label, f"{dt:.1f}", f"{dt / N:.2f}", str(files)])
        print(label, f"{dt:.2f} s", file=sys.stderr)
    text = "\n".join([
        "# A course of variants: `velplan batch`",
        "",
        machine_md(),
        f"Load average at the start: {load}.",
        "",
        f"`velplan {shlex.join(ARGS)} -o DIR`: {N} random variants of the shaper (±10 %), {POSITIONS} positions "
        "each, an A1 kinematic sheet (SVG) per variant, `answers.json` + `answers.csv` and `variants.csv`; "
        "wall time of the whole command in a fresh process.",
        "",
        table(["run", "seconds", "seconds per variant", "files written"], rows),
        "",
        "Target (issue 17): a course of 30 variants × 10 positions, sheets included, in minutes.",
        "",
    ])
    write(RESULTS / "batch.md", text)


if __name__ == "__main__":
    main()
