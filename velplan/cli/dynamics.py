"""``velplan dynamics``: reduction, steady state or run, flywheel of a mechanism's
``[dynamics]`` section (defaults when it has none: steady state, no flywheel unless --delta)."""

from __future__ import annotations

import json

from velplan.cli.common import add_mechanism, add_output, emit, positive_int


def register(sub) -> None:
    p = sub.add_parser("dynamics", help="machine dynamics: reduced inertia and moments, ω(φ), flywheel, runs")
    add_mechanism(p)
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="positions in the table (default 12)")
    p.add_argument("--delta", metavar="D", type=float, help="required δ (overrides the file's)")
    p.add_argument("--drive", action="store_true",
                   help="also choose the drive (seed 003) with the defaults when the file has no [dynamics.drive]")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--harmonics", metavar="N,…",
                   help="seed 004: the motion with the press load's Fourier series of N harmonics against the "
                        "exact parabola's, per N (same flywheel)")
    p.add_argument("--plot", metavar="FILE", help="also plot J_red, M_red, works and ω to FILE (.png or .svg)")
    add_output(p)
    p.set_defaults(run=run_dynamics)


def run_dynamics(args) -> int:
    from velplan.dynamics.report import plot, to_dict, to_table
    from velplan.study import Study

    study = Study(args.mechanism, delta=args.delta)
    if args.harmonics is not None:
        return _run_harmonics(args, study)
    d = study.dynamics
    drive = None
    if args.drive and d.drive is None:
        from velplan.dynamics.drive import select_drive

        drive = select_drive(d)
    text = json.dumps(to_dict(d, args.positions, drive), indent=1, ensure_ascii=False) if args.format == "json" \
        else to_table(d, args.positions, drive)
    if args.plot:
        plot(d, args.plot)
    emit(text, args.output)
    return 0


def _run_harmonics(args, study) -> int:
    from dataclasses import asdict

    from velplan.dynamics.harmonics import compare_harmonics, harmonics_table
    from velplan.errors import VelplanError

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
