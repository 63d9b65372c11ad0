"""``velplan sweep``: figures of merit over a parameter grid or a tolerance Monte Carlo."""

from __future__ import annotations

import sys
from pathlib import Path

from velplan.cli.common import add_mechanism, add_output, positive_int
from velplan.errors import VelplanError

MAX_VARIANTS = 10_000_000
"""Most variants of a --vary grid."""
MAX_SAMPLES = 1_000_000
"""Most Monte Carlo draws: every toleranced key's values and every figure are kept (≈ 0.3 GB)."""


def register(sub) -> None:
    p = sub.add_parser("sweep", help="figures of merit (H, K, γ_min, peak v, a, M_b, J_I) over a design grid "
                                     "or tolerances")
    add_mechanism(p)
    p.add_argument("--vary", metavar="KEY=FROM:TO:N", action="append", default=[],
                   help="a grid axis over a dotted key (crank.length=0.09:0.11:21, or KEY=A,B,C); repeat for more axes")
    p.add_argument("--tolerance", metavar="T", help="Monte Carlo over every length and angle: ±T such as "
                   "'0.1mm,0.05°' (KEY=0.02mm sets one key)")
    p.add_argument("--samples", metavar="N", type=positive_int, default=10_000, help="Monte Carlo draws (default 10000)")
    p.add_argument("--seed", metavar="S", default="0", help="Monte Carlo seed: a number or any text (default 0)")
    p.add_argument("--distribution", choices=("normal", "uniform"), default="normal",
                   help="deviations: normal with σ = T/3 (default) or uniform in ±T")
    p.add_argument("--positions", metavar="N", type=positive_int, default=360,
                   help="crank angles per variant (default 360)")
    p.add_argument("--delta", metavar="δ", type=float,
                   help="coefficient of speed fluctuation (0 < δ < 1): adds the flywheel's J_I (kg·m²) of each "
                        "variant (a file with loads or masses; the peak balancing moment Mb_max comes without it)")
    p.add_argument("--format", choices=("table", "json", "csv", "jsonl", "npz", "parquet"), default="table",
                   help="table (quantiles, sensitivities), json (the summary and columns), npz (-o FILE), or a "
                        "row per variant written as each chunk is computed: csv, jsonl, parquet (-o FILE; "
                        "the summary in the file's metadata 'velplan'; pip install \".[parquet]\")")
    p.add_argument("--plots", metavar="DIR", help="write sweep-hist, sweep-sensitivity and sweep-scatter SVGs into DIR")
    p.add_argument("--png", action="store_true", help="also PNGs of the plots")
    p.add_argument("--engine", choices=("numpy", "compiled", "auto"), default="numpy",
                   help="numpy (default), compiled (numba, all cores; the same figures to round-off) or auto "
                        "(compiled when numba is installed and the kernel is loaded or there are 2e6 variant-angles)")
    p.add_argument("--jobs", metavar="N", type=positive_int, default=1,
                   help="worker processes (default 1; the results are the same)")
    p.add_argument("--scheduler", metavar="ADDR", help="run the chunks on a Dask cluster (tcp://host:port)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    add_output(p)
    p.set_defaults(run=run_sweep_cmd)


def _values(args, mech):
    from velplan.mechanism.keys import check_values
    from velplan.sweep import run

    if bool(args.vary) == bool(args.tolerance):
        raise VelplanError("give --vary KEY=FROM:TO:N (a grid) or --tolerance T (Monte Carlo), one of them")
    if args.vary:
        axes = run.parse_axes(args.vary)
        if run.combos(axes) > MAX_VARIANTS:
            raise VelplanError(f"--vary: {run.combos(axes)} variants is more than {MAX_VARIANTS}")
        values = run.grid(mech, axes)
        check_values(mech, values)
        return "grid", values, {"axes": {k: [float(x) for x in v] for k, v in axes.items()}}
    if args.samples > MAX_SAMPLES:
        raise VelplanError(f"--samples {args.samples} is more than a sweep keeps (at most {MAX_SAMPLES})")
    length, angle, per = run.parse_tolerance(args.tolerance)
    tol = run.tolerances(mech, length, angle, per)
    values = run.monte_carlo(mech, tol, args.samples, args.seed, args.distribution)
    check_values(mech, values)
    meta = {"seed": args.seed, "samples": args.samples, "distribution": args.distribution,
            "tolerance": {k: float(t) for k, t in tol.items()}}
    return "monte-carlo", values, meta


def run_sweep_cmd(args) -> int:
    from velplan.batch import progress_bar
    from velplan.cli.stream import check_format, open_output
    from velplan.mechanism.loader import load
    from velplan.sweep import report, run

    check_format(args.format, args.output)
    if args.plots and not Path(args.plots).is_dir():
        raise VelplanError(f"--plots: directory {args.plots} does not exist")
    if args.delta is not None and not 0 < args.delta < 1:
        raise VelplanError(f"--delta must be between 0 and 1 (exclusive), not {args.delta:g}")
    mech = load(args.mechanism)
    if args.delta is not None:
        from velplan.sweep.dynamic import has_dynamics

        if not has_dynamics(mech):
            raise VelplanError(f"--delta: {mech.name!r} has no loads or masses: no flywheel to size")
    mode, values, meta = _values(args, mech)
    V = len(next(iter(values.values())))
    show = None if args.quiet or V <= 1024 else progress_bar()
    engine = args.engine
    if engine == "auto":
        from velplan.analysis.compiled import available, loaded
        from velplan.analysis.solver import AUTO_COMPILED

        engine = "compiled" if available() and (loaded() or V * args.positions >= AUTO_COMPILED) else "numpy"
    work = {"positions": args.positions, "scheduler": args.scheduler, "jobs": args.jobs, "engine": engine,
            "delta": args.delta}
    if args.format in STREAMED:
        res = _write_streamed(args, mech, values, {"mode": mode, "meta": meta}, work, show)
    else:
        res = run.run_sweep(mech, values, mode=mode, meta=meta, progress=show, **work)
        with open_output(args.output, binary=args.format == "npz") as out:
            if args.format == "table":
                out.write(report.to_table(res))
            else:
                (report.write_npz if args.format == "npz" else report.write_json)(res, out)
    if args.plots:
        from velplan.sweep.plot import plot_all

        files = plot_all(res, args.plots, png=args.png)
        sys.stderr.write(f"plots: {', '.join(f.name for f in files)} in {args.plots}\n")
    return 0


STREAMED = ("csv", "jsonl", "parquet")
"""Formats written a chunk of variants at a time, as each is computed."""


def _write_streamed(args, mech, values, about: dict, work: dict, progress):
    """Run the sweep, writing each chunk's rows to ``args.output`` (csv, jsonl or parquet) as soon
    as it and those before it are computed; the `SweepResult` (``about``: its mode and meta)."""
    from velplan.cli.stream import open_output, write_parquet
    from velplan.sweep import report, run

    results = []

    def columns():
        first = 0
        for part, r in run.sweep_chunks(mech, values, progress=progress, **work):
            results.append(r)
            yield report.chunk_columns(first, part, *r)
            first += len(r[1])

    done = []

    def finish():  # once every chunk is written (before Parquet's metadata)
        done.append(run.assemble(mech, values, results, positions=work["positions"], engine=work["engine"],
                                 delta=work["delta"], **about))
        return done[0]

    with open_output(args.output, binary=args.format == "parquet") as out:
        if args.format == "parquet":
            write_parquet(out, columns(), metadata=lambda: report.parquet_metadata(finish()))
        else:
            for n, cols in enumerate(columns()):
                report.write_rows(cols, out, args.format, header=n == 0)
            finish()
    return done[0]
