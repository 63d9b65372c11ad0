"""``velplan forces``: pair reactions and the balancing moment by kinetostatics, Zhukovsky's
lever and the power method."""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_indices, position_numbers
from velplan.cli.common import add_mechanism, add_output, emit, parse_angles, positive_int
from velplan.errors import VelplanError

STANDARD = 12
"""Number of standard positions that ``--position K`` counts in."""


def register(sub) -> None:
    p = sub.add_parser("forces", help="pair reactions and the balancing moment (kinetostatics, lever, power)")
    add_mechanism(p)
    where = p.add_mutually_exclusive_group()
    where.add_argument("--position", metavar="K", type=positive_int,
                       help=f"only position K of the {STANDARD} standard positions")
    where.add_argument("--positions", metavar="N", type=positive_int, default=STANDARD,
                       help=f"N positions evenly spaced from the reference position (default {STANDARD})")
    where.add_argument("--angles", metavar="DEG,…", help="crank angles in degrees, e.g. 0,45,90")
    p.add_argument("--motion", choices=("constant", "dynamic"), default="constant",
                   help="the crank at the file's constant speed, or at the ω(φ), ε(φ) computed by "
                        "its [dynamics] section (default constant)")
    p.add_argument("--format", choices=("table", "json", "csv", "jsonl", "parquet"), default="table",
                   help="table, json (one document), csv (a row per position), jsonl (a JSON object per "
                        "position, per line) or parquet (the CSV's columns; -o FILE, pip install "
                        "\".[parquet]\"); all but table are written as they are computed")
    p.add_argument("--no-inertia", action="store_true", help="leave out the inertia forces and moments")
    p.add_argument("--no-gravity", action="store_true", help="leave out gravity")
    p.add_argument("--mode", choices=("exact", "drafting"), default="exact",
                   help="velocity plan for the lever: exact, or at drafting precision")
    p.add_argument("--scale-v", metavar="MU", type=float, help="μv of the lever's plan, (m/s)/mm")
    p.add_argument("--precision", metavar="MM", type=float, default=0.5, help="drafting precision, mm (default 0.5)")
    p.add_argument("--plot", metavar="FILE", help="also plot M_b over a revolution to FILE (.png or .svg)")
    add_output(p)
    p.set_defaults(run=run_forces)


def run_forces(args) -> int:
    from velplan.plans import EXACT, Drafting
    from velplan.study import Study

    if args.position is not None and args.position > STANDARD:
        raise VelplanError(f"--position {args.position}: must be between 1 and {STANDARD}")
    if args.format != "table":
        from velplan.cli.stream import check_format

        check_format(args.format, args.output)
    angles = parse_angles(args.angles) if args.angles is not None else None
    n = STANDARD if args.position is not None else args.positions
    study = Study(args.mechanism, n=n, angles=angles, motion=args.motion)
    options = {"drafting": EXACT if args.mode == "exact" else Drafting(args.precision, args.precision),
               "mu_v": args.scale_v, "gravity": not args.no_gravity, "inertia": not args.no_inertia}
    numbers = [args.position] if args.position is not None else position_numbers(range(study.n)).tolist()
    text = None
    if args.format == "table":  # a few positions, side by side
        text = to_table(study.forces(**options), numbers, [ld.name for ld in study.loads])
    if args.plot:
        from velplan.forces.plot import plot_balancing_moment

        plot_balancing_moment(study.turn_forces(gravity=not args.no_gravity, inertia=not args.no_inertia),
                              args.plot, sense=study.sense)
    if text is not None:
        emit(text, args.output)
        return 0
    from velplan.cli.stream import write_rows

    write_rows(args.output, args.format, chunks(study, numbers, chunk=CHUNK, **options),
               head=lambda: _head(study))
    return 0


def _omega1_text(kin, idx) -> str:
    if not isinstance(kin.omega1, np.ndarray):
        return f"ω1 = {kin.omega1:+.6g} rad/s"
    w = kin.omega1[idx]
    return f"ω1 = {np.min(w):+.6g} … {np.max(w):+.6g} rad/s (computed motion)"


CHUNK = 4096
"""Positions analysed and written at a time by `stream` (≈ 100 MB of arrays)."""


def stream(study, fmt: str, numbers: list[int], *, drafting, mu_v: float | None = None, gravity: bool = True,
           inertia: bool = True, chunk: int = CHUNK):
    """The force analysis at the positions ``numbers`` (1-based) of ``study`` as one JSON document
    (SI units, N and N·m; null where a position is singular), CSV or JSON lines, ``chunk``
    positions analysed and formatted at a time (`chunks`): memory stays bounded however many
    positions there are; the numbers are those of `Study.forces`."""
    from velplan.cli.stream import json_document, text_pieces

    pieces = text_pieces(chunks(study, numbers, drafting=drafting, mu_v=mu_v, gravity=gravity, inertia=inertia,
                                chunk=chunk), fmt)
    return json_document(_head(study), "positions", pieces) if fmt == "json" else pieces


def _head(study) -> dict:
    return {"mechanism": study.mechanism.name, "omega1": study.crank_motion[0],
            "loads": [ld.name for ld in study.loads]}


def chunks(study, numbers: list[int], *, drafting, mu_v: float | None = None, gravity: bool = True,
           inertia: bool = True, chunk: int = CHUNK):
    """(tree, None) of each chunk of ``chunk`` positions of ``numbers`` (1-based), analysed in turn
    (`velplan.study.Study.forces_in_chunks`; `velplan.cli.stream.write_rows`)."""
    for a, res, pct in study.forces_in_chunks(numbers, chunk, drafting=drafting, mu_v=mu_v, gravity=gravity,
                                              inertia=inertia):
        yield _position_tree(res, pct, np.asarray(numbers[a:a + len(pct)])), None


def _position_tree(res, pct: np.ndarray, numbers: np.ndarray) -> dict:
    """One position's keys (`velplan.cli.stream.object_layout`) over the positions of ``res``."""
    kin, ks = res.kinematics, res.kinetostatics
    reactions = {}
    for name, r in ks.reactions.items():
        entry = {"x": r.force.real, "y": r.force.imag, "magnitude": np.hypot(r.force.real, r.force.imag),
                 "on": r.pair.links[0], "from": r.pair.links[1], "kind": r.pair.kind}
        if r.pair.kind == "P":
            entry.update({"moment": r.moment, "at_x": r.at.real, "at_y": r.at.imag})
        reactions[name] = entry
    return {"position": numbers, "phi_deg": np.degrees(kin.phi) % 360.0, "omega1": kin.crank_rate("omega"),
            "balancing_moment": res.balancing_moments, "lever_difference_percent": pct,
            "balancing_force": res.lever.balancing_force, "reactions": reactions}


def to_table(res, numbers: list[int], load_names: list[str]) -> str:
    """M_b by the three methods and |R| of every pair, one column per position ``numbers``
    (1-based) of ``res``."""
    kin, ks = res.kinematics, res.kinetostatics
    idx = position_indices(numbers, len(kin)).tolist() if len(numbers) < len(kin) else list(range(len(kin)))
    bm = res.balancing_moments
    from velplan.forces.agreement import lever_difference_percent

    labels = [f"  {k}" for k in bm] + ["  lever − kinetost., %"] + [
        f"  {name} ({r.pair.links[0]}←{r.pair.links[1]})" for name, r in ks.reactions.items()]
    w = max(len(x) for x in labels + ["quantity"]) + 2
    head = f"{'quantity':<{w}}" + "".join(f"{k:>12}" for k in numbers)
    lines = [f"{kin.mechanism.name}: {_omega1_text(kin, idx)}; loads: {', '.join(load_names) or 'none'}",
             head, f"{'φ, deg':<{w}}" + "".join(f"{x:>12.2f}" for x in np.degrees(kin.phi[idx]) % 360.0)]

    def row(label: str, values, scale: float | None = None) -> str:
        # round-off (below 1e-9 of the row's largest value, or of ``scale``) prints as 0, never −0
        values = np.asarray(values, dtype=float)[idx]
        finite = np.isfinite(values)
        big = scale if scale is not None else float(np.max(np.abs(values[finite]), initial=0.0))
        values = np.where(finite & (np.abs(values) <= 1e-9 * big), 0.0, values) + 0.0
        return f"{label:<{w}}" + "".join(f"{v:>12.5g}" if math.isfinite(v) else f"{'—':>12}" for v in values)

    lines.append("balancing moment M_b, N·m")
    for k, v in bm.items():
        lines.append(row(f"  {k}", v))
    lines.append(row("  lever − kinetost., %", lever_difference_percent(bm["lever"], bm["kinetostatics"]), 1e3))
    lines.append("reactions |R|, N (on the first link from the second)")
    for name, r in ks.reactions.items():
        lines.append(row(f"  {name} ({r.pair.links[0]}←{r.pair.links[1]})", np.abs(r.force)))
    return "\n".join(lines)
