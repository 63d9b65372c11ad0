"""A sweep as text: the summary table, JSON (columnar), CSV or JSON lines (a row per variant),
npz (columnar binary); Parquet (a row group per chunk of variants) is written by
`velplan.cli.stream.write_parquet` with `chunk_columns` and `parquet_metadata`. Floats are
written with 17 significant digits (they read back bit for bit); NaN is ``null`` in JSON and
Parquet and an empty cell in CSV."""

from __future__ import annotations

import io
import json
import math
from typing import Mapping

import numpy as np

from velplan.sweep.run import SweepResult, quantiles, sensitivities


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _units(res: SweepResult) -> dict[str, str]:
    angular = res.meta.get("output_kind") == "link"
    return {"H": "rad" if angular else "m", "K": "", "theta_deg": "deg", "phi_start_deg": "deg",
            "phi_end_deg": "deg", "gamma_min_deg": "deg", "gamma_phi_deg": "deg",
            "v_max": "rad/s" if angular else "m/s", "a_max": "rad/s²" if angular else "m/s²",
            "Mb_max": "N·m", "J_I": "kg·m²"}


def to_table(res: SweepResult) -> str:
    """Quantiles of each figure over the variants that close, then each key's share of it."""
    V, ok = len(res), int(res.ok.sum())
    lines = [f"{res.mechanism}: {res.mode} sweep of {V} variant(s) over {', '.join(res.values) or 'nothing'}; "
             f"{ok} close over the turn, {V - ok} do not"]
    units = _units(res)
    qs = quantiles(res)
    cols = ("nominal", "mean", "std", "q0", "q0.05", "q0.5", "q0.95", "q1")
    lines.append(f"{'figure':<16}{'unit':<8}" + "".join(f"{c:>14}" for c in cols))
    for name, row in qs.items():
        lines.append(f"{name:<16}{units.get(name, ''):<8}" + "".join(f"{row[c]:>14.7g}" for c in cols))
    sens = sensitivities(res)
    keys = list(res.values)
    if keys and ok > len(keys) + 1:
        lines += ["", "share of each figure's spread (linear fit over the variants; R² its fit):"]
        width = max(len(k) for k in keys) + 2
        figs = [f for f in sens if f in ("H", "K", "gamma_min_deg", "v_max", "a_max", "Mb_max", "J_I")]
        lines.append(f"{'key':<{width}}" + "".join(f"{f:>14}" for f in figs))
        for k in keys:
            lines.append(f"{k:<{width}}" + "".join(f"{100 * sens[f][k]:>13.1f}%" for f in figs))
        lines.append(f"{'R²':<{width}}" + "".join(f"{sens[f]['R2']:>14.4f}" for f in figs))
    bad = [(i, f) for i, f in enumerate(res.failures) if f]
    for i, f in bad[:5]:
        lines.append(f"variant {i + 1}: {f}")
    if len(bad) > 5:
        lines.append(f"… and {len(bad) - 5} more variant(s) that do not close")
    return "\n".join(lines) + "\n"


def summary(res: SweepResult) -> dict:
    """Everything but the variants: nominal, quantiles, sensitivities, meta."""
    clean = lambda d: {k: (_num(v) if isinstance(v, float) else v) for k, v in d.items()}  # noqa: E731
    return {"mechanism": res.mechanism, "mode": res.mode, "variants": len(res), "closing": int(res.ok.sum()),
            "meta": res.meta, "keys": list(res.values), "units": _units(res),
            "nominal": clean(res.nominal),
            "quantiles": {k: clean(v) for k, v in quantiles(res).items()},
            "sensitivities": {k: clean(v) for k, v in sensitivities(res).items()}}


def write_json(res: SweepResult, out) -> None:
    """The summary and the variants as columns, written piece by piece to ``out``."""
    head = json.dumps(summary(res), ensure_ascii=False, allow_nan=False)
    out.write(head[:-1] + ', "columns": {')
    for n, (name, arr) in enumerate(_columns(res).items()):
        out.write(("" if n == 0 else ", ") + json.dumps(name, ensure_ascii=False) + ": [")
        for a in range(0, len(arr), 4096):
            part = arr[a:a + 4096]
            if part.dtype.kind == "f":
                text = ", ".join("null" if not math.isfinite(x) else repr(float(x)) for x in part)
            elif part.dtype.kind == "i":
                text = ", ".join(str(int(x)) for x in part)
            else:
                text = ", ".join(json.dumps(str(x), ensure_ascii=False) for x in part)
            out.write(("" if a == 0 else ", ") + text)
        out.write("]")
    out.write("}}\n")


def chunk_columns(first: int, values: Mapping[str, np.ndarray], figs: Mapping[str, np.ndarray], failures: list,
                  group: list) -> dict[str, np.ndarray]:
    """The columns of the variants ``first`` + 1 … (a chunk, `velplan.sweep.run.chunk_figures`):
    their numbers, keys, figures, γ_min's group and failure."""
    return {"variant": np.arange(first + 1, first + len(failures) + 1), **values, **figs,
            "gamma_group": np.array(group, dtype=object), "failure": np.array(failures, dtype=object)}


def _columns(res: SweepResult) -> dict[str, np.ndarray]:
    return chunk_columns(0, res.values, res.figures, res.failures, res.gamma_group)


def write_csv(res: SweepResult, out) -> None:
    """A header, then one row per variant: its number, keys, figures, γ_min's group, failure."""
    write_rows(_columns(res), out, "csv", header=True)


def write_rows(cols: Mapping[str, np.ndarray], out, fmt: str, header: bool = False) -> None:
    """The variants of ``cols`` (`chunk_columns`) to the text file ``out``: CSV rows (after the
    header when ``header``) or JSON lines ("jsonl", an object per variant)."""
    import csv

    names, arrays = list(cols), list(cols.values())
    w = csv.writer(out, lineterminator="\n") if fmt == "csv" else None
    if header and w is not None:
        w.writerow(names)
    for a in range(0, len(arrays[0]), 4096):
        rows = [[_cell(arr[i], w is not None) for arr in arrays] for i in range(a, min(a + 4096, len(arrays[0])))]
        if w is not None:
            w.writerows(rows)
        else:
            out.write("".join(json.dumps(dict(zip(names, row)), ensure_ascii=False) + "\n" for row in rows))


def _cell(x, text: bool):
    """A CSV cell (``text``: floats to 17 digits, empty where not finite) or a JSON value (None)."""
    if isinstance(x, (float, np.floating)):
        finite = math.isfinite(x)
        return (repr(float(x)) if finite else "") if text else (float(x) if finite else None)
    if isinstance(x, np.integer):
        return str(x) if text else int(x)
    return str(x)


def parquet_metadata(res: SweepResult) -> dict[str, str]:
    """The Parquet file's key-value metadata: ``velplan``, the `summary` as JSON."""
    return {"velplan": json.dumps(summary(res), ensure_ascii=False)}


def write_npz(res: SweepResult, out) -> None:
    """npz (numpy): one array per key and figure, and ``summary`` (JSON text)."""
    arrays = {k: (v.astype(str) if v.dtype == object else v) for k, v in _columns(res).items()}
    buf = io.BytesIO()
    np.savez(buf, summary=np.array(json.dumps(summary(res), ensure_ascii=False)), **arrays)
    out.write(buf.getvalue())
