"""Shared helpers of the benchmark scripts: the machine, timing, errors, markdown."""

from __future__ import annotations

import gc
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
RESULTS = HERE / "results"
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

SIZES = (12, 360, 10_000, 100_000, 1_000_000)
REPEATS = {12: 200, 360: 100, 10_000: 30, 100_000: 7, 1_000_000: 3}
"""Timed repeats per size (the median is reported); fewer at 10⁶."""


def repeats_for(n: int) -> int:
    if n in REPEATS:
        return REPEATS[n]
    return 200 if n <= 100 else 100 if n <= 1000 else 30 if n <= 10_000 else 7 if n < 1_000_000 else 3


def load_average() -> str:
    """The 1-, 5- and 15-minute load averages (other sessions may share the machine)."""
    try:
        return " ".join(Path("/proc/loadavg").read_text().split()[:3])
    except OSError:
        return "?"


def machine() -> dict[str, str]:
    """CPU model, cores, memory, OS, Python and library versions."""
    info: dict[str, str] = {}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        fields = dict(re.findall(r"^([^:\n]+):\s*(.*)$", out, flags=re.M))
        info["cpu"] = fields.get("Model name", platform.processor())
        info["cores"] = (f"{os.cpu_count()} logical CPU(s); {fields.get('Core(s) per socket', '?')} core(s)/socket, "
                         f"{fields.get('Thread(s) per core', '?')} thread(s)/core"
                         + (f", {fields['Hypervisor vendor']} guest" if "Hypervisor vendor" in fields else ""))
        caches = [f"{k.split()[0]} {fields[k]}" for k in ("L1d cache", "L2 cache", "L3 cache") if k in fields]
        if caches:
            info["caches"] = ", ".join(caches)
    except (OSError, subprocess.CalledProcessError):
        info["cpu"] = platform.processor() or "?"
        info["cores"] = str(os.cpu_count())
    try:
        kb = int(re.search(r"MemTotal:\s+(\d+)", Path("/proc/meminfo").read_text()).group(1))
        info["memory"] = f"{kb / 2**20:.1f} GiB"
    except (OSError, AttributeError):
        pass
    info["os"] = f"{platform.system()} {platform.release()}"
    info["python"] = platform.python_version()
    info["numpy"] = np.__version__
    for mod in ("mpmath", "matplotlib"):
        try:
            info[mod] = __import__(mod).__version__
        except ImportError:
            pass
    return info


def machine_md() -> str:
    m = machine()
    return "\n".join(f"- **{k}**: {v}" for k, v in m.items())


def median_time(fn, n: int, *, repeats: int | None = None, warmup: bool = True) -> tuple[float, int]:
    """Median wall time (s) of ``fn()`` over ``repeats`` runs, the garbage collector off while
    timing (one collection before); one untimed warm-up run first. Returns (median, repeats)."""
    r = repeats or repeats_for(n)
    if warmup:
        fn()
    times = []
    gc.collect()  # once: a full collection per repeat costs ~70 ms once numba is imported
    gc.disable()
    try:
        for _ in range(r):
            t = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t)
    finally:
        gc.enable()
    return float(np.median(times)), r


def grid(n: int) -> np.ndarray:
    """n crank angles evenly spaced over one turn, rad."""
    return np.arange(n) * (2 * np.pi / n)


def us(seconds_per_position: float) -> str:
    """Format a time per position in µs with three significant digits."""
    x = seconds_per_position * 1e6
    return f"{x:.3g}"


def sci(x: float) -> str:
    if x is None or not np.isfinite(x):
        return "–"
    return f"{x:.1e}"


def table(header: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def scales(mech) -> tuple[float, float, float]:
    """Length (m), velocity (m/s) and acceleration (m/s²) scales: L, |ω1|·L, ω1²·L."""
    from velplan.analysis.solver import length_scale

    L = length_scale(mech)
    w = abs(mech.crank.omega)
    return L, w * L, w * w * L


def dd_error(x: np.ndarray, ref_hi: np.ndarray, ref_lo: np.ndarray) -> np.ndarray:
    """|x − ref| per point (norm over the trailing xy axis), ref given as hi + lo."""
    d = (x - ref_hi) - ref_lo
    return np.hypot(d[..., 0], d[..., 1])


def point_errors(ref, names, pos=None, vel=None, acc=None, *, mech, rows=slice(None)) -> dict[str, float]:
    """Worst scaled errors of (n, P, 2) arrays whose point axis follows ``names``, against the
    reference at angle rows ``rows``. Keys: pos, vel, acc."""
    L, V, A = scales(mech)
    j = [ref.point(k) for k in names]
    out = {}
    for key, arr, ra, s in (("pos", pos, ref.pos, L), ("vel", vel, ref.vel, V), ("acc", acc, ref.acc, A)):
        if arr is None:
            continue
        e = dd_error(arr, ra[0][rows][:, j], ra[1][rows][:, j])
        out[key] = float(np.nanmax(e) / s) if np.isfinite(e).all() else float("inf")
    return out


def write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)
    print(f"wrote {path.relative_to(ROOT)}")
