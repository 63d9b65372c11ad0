"""Sweeps: a parameter grid or a tolerance Monte Carlo over a mechanism's design keys, their
figures of merit (`velplan.sweep.merit`), quantiles and sensitivities.

Monte Carlo draws (`monte_carlo`): the generator is ``numpy.random.default_rng(seed)`` for a
whole-number seed, else seeded by the first 16 bytes (big-endian) of the SHA-256 of the seed's
text; for each toleranced key in the file's order it draws all samples at once, normal with
σ = T/3 (``T`` the ± tolerance, the ±3σ band) or uniform in ±T. The same seed gives the same
variants, figures and output bytes on any machine.
"""

from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, field
from typing import Callable, Iterator, Mapping

import numpy as np

from velplan.analysis.design import design_keys, nominal
from velplan.analysis.extremes import output_quantity
from velplan.errors import VelplanError
from velplan.mechanism.keys import resolve
from velplan.mechanism.model import Mechanism
from velplan.sweep.merit import FIGURES, figures

CHUNK = {"numpy": 256, "compiled": 1024}
"""Variants solved at a time by each engine (× 360 angles: tens of MB; the compiled kernel
prefers fewer, larger calls)."""

QUANTILES = (0.0, 0.01, 0.05, 0.5, 0.95, 0.99, 1.0)


@dataclass
class SweepResult:
    """Variants of a sweep and their figures of merit.

    Attributes
    ----------
    mechanism : str
    mode : {"grid", "monte-carlo"}
    values : dict of key → ndarray, shape (V,)
        The varied keys' values per variant (m, deg, rpm or rad/s).
    figures : dict of name → ndarray, shape (V,)
        See `velplan.sweep.merit.FIGURES`; NaN where a variant fails.
    failures : list of str
        "" for a variant that closes over the turn, else why not.
    gamma_group : list of str
        The group where each variant's γ_min occurs.
    nominal : dict of name → float
        The figures of the nominal mechanism.
    meta : dict
        Seed, tolerances, distribution, positions …
    """

    mechanism: str
    mode: str
    values: dict
    figures: dict
    failures: list
    gamma_group: list
    nominal: dict
    meta: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.failures)

    @property
    def ok(self) -> np.ndarray:
        """(V,) variants that close over the turn (and whose output reverses)."""
        return np.array([f == "" for f in self.failures], dtype=bool)


# ---- what to vary ---------------------------------------------------------------------------


def parse_vary(text: str) -> tuple[str, np.ndarray]:
    """``"crank.length=0.09:0.11:21"`` (from:to:count) or ``"key=a,b,c"`` → (key, values)."""
    key, eq, spec = text.partition("=")
    key = key.strip()
    if not eq or not key:
        raise VelplanError(f"--vary {text!r}: give KEY=FROM:TO:COUNT or KEY=A,B,…")
    try:
        if ":" in spec:
            lo, hi, count = spec.split(":")
            ends, n = [float(lo), float(hi)], int(count)
            if n < 1:
                raise ValueError
        else:
            ends, n = [float(x) for x in spec.split(",")], 0
    except ValueError:
        raise VelplanError(f"--vary {text!r}: {spec!r} is not FROM:TO:COUNT or a list of numbers") from None
    if not all(math.isfinite(x) for x in ends):
        raise VelplanError(f"--vary {text!r}: values must be finite")
    if n > MAX_AXIS:
        raise VelplanError(f"--vary {text!r}: {n} values on one axis is more than a sweep takes (at most {MAX_AXIS})")
    return key, (np.linspace(ends[0], ends[1], n) if n else np.array(ends))


MAX_AXIS = 10_000_000
"""Most values of one ``--vary`` axis."""


def parse_axes(texts: list[str]) -> dict[str, np.ndarray]:
    """Every ``--vary`` text (`parse_vary`) → key → values; a key given twice is refused."""
    axes: dict[str, np.ndarray] = {}
    for text in texts:
        key, vals = parse_vary(text)
        if key in axes:
            raise VelplanError(f"--vary {key} is given twice: give its values once (KEY=A,B,C)")
        axes[key] = vals
    return axes


def grid(mech: Mechanism, axes: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The full grid of ``axes`` (key → values), the first key varying slowest."""
    for key in axes:
        nominal(mech, key)  # an unknown key: one line naming it
    mesh = np.meshgrid(*axes.values(), indexing="ij")
    return {k: m.reshape(-1).copy() for k, m in zip(axes, mesh)}


_UNITS = {"mm": 1e-3, "m": 1.0, "um": 1e-6, "µm": 1e-6, "°": 1.0, "deg": 1.0}


def parse_tolerance(text: str) -> tuple[float, float, dict[str, float]]:
    """``"0.1mm,0.05°"`` (and ``KEY=0.02mm`` for one key) → (length ± m, angle ± deg, per key)."""
    length, angle, per = 0.0, 0.0, {}
    for item in (t.strip() for t in text.split(",")):
        if not item:
            continue
        key, _, spec = item.rpartition("=")
        m = re.fullmatch(r"([0-9.eE+-]+)\s*(mm|m|um|µm|°|deg)", spec.strip())
        if not m:
            raise VelplanError(f"--tolerance: {item!r} is not a number with a unit (0.1mm, 0.05°)")
        try:
            value = float(m.group(1)) * _UNITS[m.group(2)]
        except ValueError:
            raise VelplanError(f"--tolerance: {item!r} is not a number with a unit (0.1mm, 0.05°)") from None
        if not (math.isfinite(value) and value >= 0):
            raise VelplanError(f"--tolerance: {item!r} must be ≥ 0")
        angular = m.group(2) in ("°", "deg")
        if key:
            if angular != key.strip().endswith("_deg"):
                raise VelplanError(f"--tolerance: {item!r}: {key.strip()} takes {'an angle' if not angular else 'a length'}")
            per[key.strip()] = value
        elif angular:
            angle = value
        else:
            length = value
    return length, angle, per


def tolerances(mech: Mechanism, length: float, angle: float, per: Mapping[str, float] | None = None) -> dict[str, float]:
    """± tolerance of every geometric key of ``mech`` (m, or deg for ``*_deg`` keys)."""
    keys = design_keys(mech)
    for k in per or {}:
        if k not in keys:
            resolve(mech, k)  # any key of the file may be toleranced by name; unknown: one line
    out = {k: (angle if k.endswith("_deg") else length) for k in keys}
    out.update(per or {})
    return out


def generator(seed: str | int) -> np.random.Generator:
    """numpy's generator for ``seed``: the number itself, or the SHA-256 of its text."""
    text = str(seed).strip()
    if text.isdigit():
        return np.random.default_rng(int(text))
    digest = hashlib.sha256(text.encode("utf-8")).digest()
    return np.random.default_rng(int.from_bytes(digest[:16], "big"))


def monte_carlo(mech: Mechanism, tol: Mapping[str, float], samples: int, seed: str | int,
                distribution: str = "normal") -> dict[str, np.ndarray]:
    """``samples`` variants: every key of ``tol`` at its nominal value plus a random deviation
    (normal with σ = T/3, or uniform in ±T); a key with T = 0 stays at its nominal value."""
    if distribution not in ("normal", "uniform"):
        raise VelplanError(f"--distribution must be normal or uniform, not {distribution!r}")
    rng = generator(seed)
    out = {}
    for key, t in tol.items():
        base = nominal(mech, key)
        dev = rng.normal(0.0, t / 3.0, samples) if distribution == "normal" else rng.uniform(-t, t, samples)
        out[key] = base + dev * (t > 0)
    return out


# ---- running --------------------------------------------------------------------------------


def chunks(values: Mapping[str, np.ndarray], size: int) -> list[dict[str, np.ndarray]]:
    """``values`` cut into consecutive chunks of ``size`` variants."""
    V = len(next(iter(values.values()))) if values else 1
    return [{k: v[a:a + size] for k, v in values.items()} for a in range(0, V, size)]


def chunk_size(engine: str, positions: int) -> int:
    """Variants solved at a time: `CHUNK` at up to 360 angles, fewer at more angles, so that a
    chunk holds at most ``CHUNK[engine]·360`` variant-angles (bounded memory)."""
    return max(1, min(CHUNK[engine], CHUNK[engine] * 360 // max(positions, 1)))


def chunk_figures(mech: Mechanism, values: dict, positions: int, engine: str = "numpy", delta: float | None = None):
    """Figures of one chunk (a picklable task for a process pool or a Dask worker)."""
    return figures(mech, values, positions, engine, delta)


def run_sweep(mech: Mechanism, values: Mapping[str, np.ndarray], *, mode: str = "grid", positions: int = 360,
              chunk: int | None = None, progress: Callable | None = None, scheduler=None, jobs: int = 1,
              engine: str = "numpy", delta: float | None = None, meta: dict | None = None) -> SweepResult:
    """Figures of merit of every variant of ``values`` (key → (V,) array).

    The variants are solved ``chunk`` at a time (`CHUNK` by default; ``positions`` angles each): in this
    process, on ``jobs`` processes, or on a Dask cluster when ``scheduler`` is a
    `dask.distributed.Client` or a scheduler address (``tcp://host:port``,
    `velplan.sweep.cluster`). Every way runs the same function on the same chunks: the same
    figures, bit for bit. ``engine`` "compiled" solves each chunk with the compiled kernel on
    every core (numba), equal to the numpy engine's to round-off. With loads or masses in the
    file the figures include the peak balancing moment ``Mb_max``, and with ``delta`` (the
    coefficient of speed fluctuation, 0 < δ < 1) the flywheel's ``J_I``.
    """
    results = [r for _, r in sweep_chunks(mech, values, positions=positions, chunk=chunk, progress=progress,
                                          scheduler=scheduler, jobs=jobs, engine=engine, delta=delta)]
    return assemble(mech, values, results, mode=mode, positions=positions, engine=engine, delta=delta, meta=meta)


def sweep_chunks(mech: Mechanism, values: Mapping[str, np.ndarray], *, positions: int = 360,
                 chunk: int | None = None, progress: Callable | None = None, scheduler=None, jobs: int = 1,
                 engine: str = "numpy", delta: float | None = None) -> Iterator[tuple[dict, tuple]]:
    """(values, `chunk_figures`) of each chunk of variants in order, each as soon as it and those
    before it are computed (`run_sweep`'s work, for output written as it is computed)."""
    parts = chunks(values, chunk or chunk_size(engine, positions))
    if scheduler is not None:
        from velplan.sweep.cluster import map_chunks

        done = map_chunks(scheduler, chunk_figures, mech, parts, positions, progress, engine, delta)
    else:
        done = _map_local(mech, parts, positions, jobs, progress, engine, delta)
    yield from zip(parts, done)


def assemble(mech: Mechanism, values: Mapping[str, np.ndarray], results: list, *, mode: str, positions: int,
             engine: str, delta: float | None = None, meta: dict | None = None) -> SweepResult:
    """The `SweepResult` of the chunks' ``results`` (`chunk_figures`, in order) and the nominal figures."""
    figs = {k: np.concatenate([r[0][k] for r in results]) for k in results[0][0]}
    failures = [f for r in results for f in r[1]]
    group = [g for r in results for g in r[2]]
    nom, _, _ = figures(mech, {}, positions, engine, delta)
    q = output_quantity(mech)
    info = {"positions": positions, "engine": engine, "output": None if q is None else q[0], "output_kind": None if q is None else q[1],
            **({"delta": delta} if delta is not None else {}), **(meta or {})}
    return SweepResult(mech.name, mode, {k: np.asarray(v) for k, v in values.items()}, figs, failures, group,
                       {k: float(v[0]) for k, v in nom.items()}, info)


def _map_local(mech: Mechanism, parts: list[dict], positions: int, jobs: int, progress, engine: str,
               delta: float | None = None) -> Iterator:
    """`chunk_figures` of every part, in order as each completes, on ``jobs`` processes (1: in this one)."""
    if jobs <= 1 or len(parts) < 2:
        for i, part in enumerate(parts):
            yield chunk_figures(mech, part, positions, engine, delta)
            if progress:
                progress(i + 1, len(parts), "chunks of variants")
        return
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=min(jobs, len(parts))) as pool:
        n = len(parts)
        tasks = pool.map(chunk_figures, [mech] * n, parts, [positions] * n, [engine] * n, [delta] * n)
        for i, res in enumerate(tasks):
            yield res
            if progress:
                progress(i + 1, len(parts), "chunks of variants")


# ---- summaries ------------------------------------------------------------------------------


def quantiles(res: SweepResult, qs=QUANTILES) -> dict[str, dict[str, float]]:
    """Per figure: nominal, mean, std, the quantiles ``qs`` over the variants that close, and
    how many did not."""
    ok = res.ok
    out = {}
    for name, arr in res.figures.items():
        a = arr[ok & np.isfinite(arr)]
        row = {"nominal": res.nominal.get(name, math.nan), "n": int(a.size),
               "mean": float(a.mean()) if a.size else math.nan,
               "std": float(a.std()) if a.size > 1 else (0.0 if a.size else math.nan)}
        row.update({f"q{q:g}": float(np.quantile(a, q)) if a.size else math.nan for q in qs})
        out[name] = row
    return out


def sensitivities(res: SweepResult) -> dict[str, dict[str, float]]:
    """Per figure, each varied key's share of the figure's spread (0…1, summing to 1), from a
    linear fit over the variants that close: share_k = (b_k·σ_k)² / Σ_j (b_j·σ_j)²; ``"R2"``
    gives the part of the spread the linear fit explains."""
    ok = res.ok
    keys = [k for k, v in res.values.items() if np.ptp(v[ok]) > 0] if ok.any() else []
    out = {}
    for name, arr in res.figures.items():
        use = ok & np.isfinite(arr)
        row = {k: 0.0 for k in res.values}
        if use.sum() > len(keys) + 1 and keys:
            X = np.column_stack([res.values[k][use] for k in keys])
            X = X - X.mean(axis=0)
            y = arr[use] - arr[use].mean()
            sx = X.std(axis=0)
            b = np.linalg.lstsq(X / sx, y, rcond=None)[0]  # standardised: b_k·σ_k
            tot = float(np.sum(b * b))
            row.update({k: float(bk * bk / tot) if tot > 0 else 0.0 for k, bk in zip(keys, b)})
            yy = float(y @ y)
            row["R2"] = 1.0 - float(np.sum((y - (X / sx) @ b) ** 2)) / yy if yy > 0 else 1.0
        else:
            row["R2"] = math.nan
        out[name] = row
    return out


def figure_names() -> list[str]:
    """The figures of merit, in output order."""
    return list(FIGURES)


def combos(axes: Mapping[str, np.ndarray]) -> int:
    """Number of grid variants."""
    return math.prod(len(v) for v in axes.values()) if axes else 1

