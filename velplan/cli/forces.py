"""``velplan forces``: pair reactions and the balancing moment by kinetostatics, Zhukovsky's
lever and the power method."""

from __future__ import annotations

import json
import math

import numpy as np

from velplan.analysis.extremes import positions
from velplan.cli.common import add_mechanism, add_output, emit, positive_int
from velplan.errors import VelplanError
from velplan.mechanism.loader import load

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
    from velplan.forces.agreement import analyse_forces
    from velplan.forces.parse import parse_loads

    mech = load(args.mechanism)
    loads = parse_loads(mech)
    if args.position is not None:
        if args.position > STANDARD:
            raise VelplanError(f"--position {args.position}: must be between 1 and {STANDARD}")
        phi = positions(mech, STANDARD)[args.position - 1:args.position]
        numbers = [args.position]
    else:
        phi = positions(mech, args.positions)
        numbers = list(range(1, args.positions + 1))
    from velplan.plans import EXACT, Drafting

    drafting = EXACT if args.mode == "exact" else Drafting(args.precision, args.precision)
    res = analyse_forces(mech, phi, loads=loads, gravity=not args.no_gravity, inertia=not args.no_inertia,
                         mu_v=args.scale_v, drafting=drafting)
    text = (to_json if args.format == "json" else to_table)(res, numbers, [ld.name for ld in loads])
    if args.plot:
        from velplan.forces.plot import plot_balancing_moment

        plot_balancing_moment(mech, args.plot, loads=loads, gravity=not args.no_gravity,
                              inertia=not args.no_inertia)
    emit(text, args.output)
    return 0


def _num(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def to_json(res, numbers: list[int], load_names: list[str]) -> str:
    """The analysis as JSON (SI units, N and N·m; null where a position is singular)."""
    from velplan.forces.agreement import lever_difference_percent

    kin, ks = res.kinematics, res.kinetostatics
    bm = res.balancing_moments
    pct = lever_difference_percent(bm["lever"], bm["kinetostatics"])
    doc = {"mechanism": kin.mechanism.name, "omega1": kin.omega1, "loads": load_names, "positions": []}
    for i, number in enumerate(numbers):
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
            "balancing_moment": {k: _num(v[i]) for k, v in bm.items()},
            "lever_difference_percent": _num(pct[i]),
            "balancing_force": _num(res.lever.balancing_force[i]),
            "reactions": reactions,
        })
    return json.dumps(doc, indent=1, ensure_ascii=False)


def to_table(res, numbers: list[int], load_names: list[str]) -> str:
    """M_b by the three methods and |R| of every pair, one column per position."""
    kin, ks = res.kinematics, res.kinetostatics
    bm = res.balancing_moments
    head = f"{'quantity':<22}" + "".join(f"{k:>11}" for k in numbers)
    lines = [f"{kin.mechanism.name}: ω1 = {kin.omega1:+.6g} rad/s; loads: {', '.join(load_names) or 'none'}",
             head, f"{'φ, deg':<22}" + "".join(f"{x:>11.2f}" for x in np.degrees(kin.phi) % 360.0)]

    def row(label: str, values) -> str:
        return f"{label:<22}" + "".join(f"{v:>11.5g}" if math.isfinite(v) else f"{'—':>11}" for v in values)

    lines.append("balancing moment M_b, N·m")
    for k, v in bm.items():
        lines.append(row(f"  {k}", v))
    from velplan.forces.agreement import lever_difference_percent

    lines.append(row("  lever − kinetost., %", lever_difference_percent(bm["lever"], bm["kinetostatics"])))
    lines.append("reactions |R|, N (on the first link from the second)")
    for name, r in ks.reactions.items():
        lines.append(row(f"  {name} ({r.pair.links[0]}←{r.pair.links[1]})", np.abs(r.force)))
    return "\n".join(lines)
