"""``velplan dynamics``: reduction, steady state or run, flywheel of a mechanism's
``[dynamics]`` section (defaults when it has none: steady state, no flywheel unless --delta)."""

from __future__ import annotations

import json

import numpy as np

from velplan.analysis.numbering import position_numbers
from velplan.cli.common import add_mechanism, add_output, emit, positive_int


def register(sub) -> None:
    p = sub.add_parser("dynamics", help="machine dynamics: reduced inertia and moments, ω(φ), flywheel, runs")
    add_mechanism(p)
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="positions in the table (default 12)")
    p.add_argument("--delta", metavar="D", type=float, help="required δ (overrides the file's)")
    p.add_argument("--drive", action="store_true",
                   help="also choose the drive (seed 003) with the defaults when the file has no [dynamics.drive]")
    p.add_argument("--format", choices=("table", "json", "csv", "jsonl", "parquet"), default="table",
                   help="table, json (one document), csv (a row per position), jsonl (a JSON object per "
                        "position, per line) or parquet (the CSV's columns; -o FILE, pip install "
                        "\".[parquet]\"); all but table are written as they are computed")
    p.add_argument("--harmonics", metavar="N,…",
                   help="seed 004: the motion with the press load's Fourier series of N harmonics against the "
                        "exact parabola's, per N (same flywheel)")
    p.add_argument("--plot", metavar="FILE", help="also plot J_red, M_red, works and ω to FILE (.png or .svg)")
    add_output(p)
    p.set_defaults(run=run_dynamics)


def run_dynamics(args) -> int:
    from velplan.dynamics.report import plot, to_table
    from velplan.study import Study

    if args.format not in ("table", "json"):
        from velplan.cli.stream import check_format

        check_format(args.format, args.output)
    study = Study(args.mechanism, delta=args.delta)
    if args.harmonics is not None:
        return _run_harmonics(args, study)
    d = study.dynamics
    drive = None
    if args.drive and d.drive is None:
        from velplan.dynamics.drive import select_drive

        drive = select_drive(d)
    if args.plot:
        plot(d, args.plot)
    if args.format == "table":
        emit(to_table(d, args.positions, drive), args.output)
        return 0
    from velplan.cli.stream import write_rows

    write_rows(args.output, args.format, chunks(d, args.positions, CHUNK), head=lambda: _head(d, drive))
    return 0


CHUNK = 16384
"""Positions computed and written at a time by `stream`."""


def stream(d, fmt: str, n: int = 12, drive=None, *, chunk: int = CHUNK):
    """The rows of `velplan.dynamics.report.to_dict` at ``n`` positions as one JSON document (its
    summary, then the positions), CSV or JSON lines, ``chunk`` positions computed and formatted
    at a time: memory stays bounded however many positions there are."""
    from velplan.cli.stream import json_document, text_pieces

    pieces = text_pieces(chunks(d, n, chunk), fmt)
    return json_document(_head(d, drive), "positions", pieces) if fmt == "json" else pieces


def _head(d, drive) -> dict:
    """The summary of `velplan.dynamics.report.to_dict` (its one position left out)."""
    from velplan.dynamics.report import to_dict

    head = to_dict(d, 1, drive)
    del head["positions"]
    return head


def chunks(d, n: int = 12, chunk: int = CHUNK):
    """(tree, None) of each chunk of ``chunk`` of the ``n`` positions, computed in turn
    (`velplan.cli.stream.write_rows`)."""
    from velplan.dynamics.report import POSITION_KEYS

    travels = d.travels(n)
    for a in range(0, len(travels), chunk):
        rows = d.table_at(travels[a:a + chunk])
        extra = [k for k in rows if k.startswith("M_") and k not in POSITION_KEYS]
        yield {"position": position_numbers(range(a, a + len(rows["omega"]))),
               **{k: rows[k] for k in (*POSITION_KEYS, *extra)}}, None


def _run_harmonics(args, study) -> int:
    from dataclasses import asdict

    from velplan.dynamics.harmonics import compare_harmonics, harmonics_table
    from velplan.errors import VelplanError

    if args.format not in ("table", "json"):
        raise VelplanError(f"--harmonics: --format {args.format} is not available; use table or json")
    ns = []
    for item in args.harmonics.split(","):
        try:
            ns.append(int(item.strip()))
        except ValueError:
            raise VelplanError(f"--harmonics: {item.strip()!r} is not a whole number") from None
    ref, rows = compare_harmonics(study.mechanism, study.loads, ns, delta=args.delta)
    if args.format == "json":
        text = json.dumps({"mechanism": study.mechanism.name, "driving_moment": ref.driving,
                           "harmonics": [asdict(r) for r in rows]}, indent=1, ensure_ascii=False)
    else:
        text = harmonics_table(ref, rows)
    emit(text, args.output)
    return 0
