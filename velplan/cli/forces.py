"""``velplan forces``: pair reactions and the balancing moment by kinetostatics, Zhukovsky's
lever and the power method."""

from __future__ import annotations

import json
import math

import numpy as np

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
    p.add_argument("--format", choices=("table", "json"), default="table")
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
    angles = parse_angles(args.angles) if args.angles is not None else None
    n = STANDARD if args.position is not None else args.positions
    study = Study(args.mechanism, n=n, angles=angles, motion=args.motion)
    loads = study.loads
    drafting = EXACT if args.mode == "exact" else Drafting(args.precision, args.precision)
    res = study.forces(gravity=not args.no_gravity, inertia=not args.no_inertia, mu_v=args.scale_v,
                       drafting=drafting)
    numbers = [args.position] if args.position is not None else list(range(1, study.n + 1))
    text = (to_json if args.format == "json" else to_table)(res, numbers, [ld.name for ld in loads])
    if args.plot:
        from velplan.forces.plot import plot_balancing_moment

        plot_balancing_moment(study.turn_forces(gravity=not args.no_gravity, inertia=not args.no_inertia),
                              args.plot, sense=study.sense)
    emit(text, args.output)
    return 0


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _omega1(kin) -> float | list:
    w = kin.omega1
    return [float(x) for x in w] if isinstance(w, np.ndarray) else float(w)


def _omega1_text(kin, idx) -> str:
    if not isinstance(kin.omega1, np.ndarray):
        return f"ω1 = {kin.omega1:+.6g} rad/s"
    w = kin.omega1[idx]
    return f"ω1 = {np.min(w):+.6g} … {np.max(w):+.6g} rad/s (computed motion)"


def to_json(res, numbers: list[int], load_names: list[str]) -> str:
    """The analysis as JSON (SI units, N and N·m; null where a position is singular) at the
    positions ``numbers`` (1-based) of ``res``."""
    from velplan.forces.agreement import lever_difference_percent

    kin, ks = res.kinematics, res.kinetostatics
    bm = res.balancing_moments
    pct = lever_difference_percent(bm["lever"], bm["kinetostatics"])
    w1 = kin.crank_rate("omega")
    doc = {"mechanism": kin.mechanism.name, "omega1": _omega1(kin), "loads": load_names, "positions": []}
    for number in numbers:
        i = number - 1 if len(numbers) < len(kin) else numbers.index(number)
        reactions = {}
        for name, r in ks.reactions.items():
            entry = {"x": _num(r.force[i].real), "y": _num(r.force[i].imag), "magnitude": _num(abs(r.force[i])),
                     "on": r.pair.links[0], "from": r.pair.links[1], "kind": r.pair.kind}
            if r.pair.kind == "P":
                at = r.at[i]
                entry.update({"moment": _num(r.moment[i]), "at_x": _num(at.real), "at_y": _num(at.imag)})
            reactions[name] = entry
        doc["positions"].append({
            "position": number,
            "phi_deg": float(np.degrees(kin.phi[i]) % 360.0),
            "omega1": _num(w1[i]),
            "balancing_moment": {k: _num(v[i]) for k, v in bm.items()},
            "lever_difference_percent": _num(pct[i]),
            "balancing_force": _num(res.lever.balancing_force[i]),
            "reactions": reactions,
        })
    return json.dumps(doc, indent=1, ensure_ascii=False)


def to_table(res, numbers: list[int], load_names: list[str]) -> str:
    """M_b by the three methods and |R| of every pair, one column per position ``numbers``
    (1-based) of ``res``."""
    kin, ks = res.kinematics, res.kinetostatics
    idx = [k - 1 for k in numbers] if len(numbers) < len(kin) else list(range(len(kin)))
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
