"""``velplan centres``: the instant centres of velocity, exactly and by the Kennedy construction,
and the velocities they give beside the plan's and the analytic ones."""

from __future__ import annotations

import json
import math

import numpy as np

from velplan.analysis.centres import instant_centres
from velplan.analysis.solver import length_scale
from velplan.cli.common import add_mechanism, add_output, default_language, emit, parse_angles, positive_int
from velplan.errors import VelplanError
from velplan.plans import EXACT, Drafting
from velplan.plans.centres import Construction, centre_name, construct_centres, velocities_by_centres
from velplan.plans.scale import check_scale
from velplan.plans.text import LANGS
from velplan.study import Study


def register(sub) -> None:
    p = sub.add_parser("centres", help="instant centres of velocity (Aronhold–Kennedy) and velocities by them")
    add_mechanism(p)
    where = p.add_mutually_exclusive_group()
    where.add_argument("--position", metavar="K", type=positive_int, help="position number 1…N from the reference")
    where.add_argument("--angles", metavar="DEG,DEG,…", help="absolute crank angles in degrees")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="positions per revolution (default 12); without --position: all of them")
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--mode", choices=("exact", "drafting"), default="exact",
                   help="construction drawn exactly or at the drafting precision")
    p.add_argument("--precision", metavar="MM", type=float, default=0.5, help="drafting precision, mm (default 0.5)")
    p.add_argument("--angle-precision", metavar="DEG", type=float, default=0.5,
                   help="angular precision, deg (default 0.5)")
    p.add_argument("--scale-l", metavar="MU", type=float, help="μl of the scheme, m/mm (default: a standard one)")
    p.add_argument("--steps", action="store_true", help="table: also the worked construction, one sentence a step")
    p.add_argument("--lang", choices=LANGS, default=default_language(),
                   help="language of the steps and the drawing (default: the locale's, else en)")
    p.add_argument("--svg", metavar="FILE", help="draw the scheme with every centre, the Kennedy lines and the "
                   "circle diagram (the first position asked for) to FILE (.svg, or .png beside it)")
    add_output(p)
    p.set_defaults(run=run_centres)


def _study(args) -> tuple[Study, list[int], list[int | None]]:
    """The study, the position indices asked for and their numbers (None for --angles)."""
    if args.angles is not None:
        phi = parse_angles(args.angles)
        study = Study(args.mechanism, angles=phi)
        idx = list(range(len(phi)))
        return study, idx, [None] * len(idx)
    study = Study(args.mechanism, n=args.positions)
    if args.position is not None:
        if args.position > args.positions:
            raise VelplanError(f"--position {args.position} is outside 1…{args.positions}")
        return study, [args.position - 1], [args.position]
    idx = list(range(args.positions))
    return study, idx, [i + 1 for i in idx]


def run_centres(args) -> int:
    drafting = EXACT if args.mode == "exact" else Drafting(args.precision, args.angle_precision)
    mu_l = None if args.scale_l is None else check_scale(args.scale_l, "--scale-l")
    study, idx, numbers = _study(args)
    study.require_assembled([i + 1 for i in idx])
    kin = study.kinematics
    exact = instant_centres(kin)
    if args.svg is not None and not str(args.svg).strip():
        raise VelplanError("--svg: give a file name, not an empty string")
    cons = [construct_centres(kin, i + 1, drafting=drafting, mu_l=mu_l) for i in idx]
    if args.format == "json":
        doc = {"mechanism": study.mechanism.name,
               "positions": [{"phi_deg": round(float(kin.phi_deg[i]), 9), "centres": exact.records(i)} for i in idx]}
        text = json.dumps(doc, indent=1, ensure_ascii=False)
    else:
        blocks = []
        for i, n, con in zip(idx, numbers, cons):
            blocks.append(table(con, exact, _plan(study, drafting, i), n, lang=args.lang, steps=args.steps))
        text = "\n\n".join(blocks)
    if args.svg is not None:
        _draw(args, study, cons[0], numbers[0])
    emit(text, args.output)
    return 0


def _plan(study: Study, drafting: Drafting, i: int):
    """The velocity plan at position index ``i`` (exact: the study's own), or None when the
    mechanism's plan cannot be constructed (its column then reads —)."""
    try:
        return study.plan("velocity") if drafting.exact else study.plan("velocity", drafting=drafting, positions=[i + 1])
    except VelplanError:
        return None


def _draw(args, study: Study, con: Construction, number: int | None) -> None:
    from velplan.render.scene import Scene
    from velplan.render.style import SheetStyle
    from velplan.render.svg import to_svg
    from velplan.sheets.layout import write_outputs
    from velplan.views.centres import centres_view

    view = centres_view(con, fine=study.turn, number=number, lang=args.lang)
    margin = 10.0
    scene = Scene(tuple(view.at(margin, margin).primitives), view.width_mm + 2 * margin,
                  view.height_mm + 2 * margin)
    write_outputs(to_svg(scene, SheetStyle(language=args.lang)), args.svg)


def _cell(x: float, width: int = 12, spec: str = ".6g", scale: float = 0.0) -> str:
    """A right-aligned number after a space; round-off below 1e-12 × ``scale`` prints as 0."""
    if not math.isfinite(x):
        return f" {'—':>{width - 1}}"
    x = 0.0 if abs(x) <= 1e-12 * scale else x
    return f" {x:>{width - 1}{spec}}"


def _direction(d: complex) -> str:
    """A centre at infinity: ∞ and its unit direction."""
    return f" {'∞ ' + format(d.real, '.4f'):>11} {d.imag:>11.4f}"


def _how(s) -> str:
    """How a centre was found, in a few words."""
    if s.how in ("joint", "hinge"):
        return f"{s.how} {s.via[0]}"
    if s.how == "slider":
        return f"slider ⊥ guide at {s.via[0]}"
    return f"Kennedy via {s.via[0]}, {s.via[1]} (sin {s.condition:.3g})"


def _centre_rows(con: Construction, exact, i: int) -> list[str]:
    L = exact.size
    rows = [f"{'centre':<8}{'x, m':>12}{'y, m':>12}  {'construction':<34}{'exact x, m':>12}{'exact y, m':>12}"]
    for k, (a, b) in enumerate(exact.pairs):
        s = con.centre(a, b)
        p, d = exact.points[i, k], exact.directions[i, k]
        ex = _direction(d) if np.isfinite(d) else _cell(p.real, scale=L) + _cell(p.imag, scale=L)
        if s is None:
            how, xy = "not reached", f"{'—':>12}{'—':>12}"
        else:
            xy = _direction(s.direction) if s.infinite else _cell(s.point.real, scale=L) + _cell(s.point.imag, scale=L)
            how = _how(s)
        rows.append(f"{centre_name((a, b)):<8}{xy}  {how:<34}{ex}")
    return rows


def _velocity_rows(con: Construction, res, i: int) -> list[str]:
    kin = con.kin
    by = velocities_by_centres(con)
    rows = [f"{'quantity':<10}{'centres':>12}{'plan':>12}{'analytic':>12}{'err centres':>13}{'err plan':>11}"]
    vs = float(np.nanmax(np.hypot(*kin.velocities[i].T)))
    ws = vs / length_scale(kin.mechanism)
    j = list(res.index).index(i) if res is not None else 0
    plan_v = res.vectors if res is not None else {}
    plan_w = res.omegas if res is not None else {}
    for name, v in by.velocities.items():
        exact = float(np.hypot(*kin.velocity(name)[i]))
        pv = float(np.hypot(*plan_v[name][j])) if name in plan_v else float("nan")
        rows.append(f"{'V_' + name:<10}{_cell(abs(v), scale=vs)}{_cell(pv, scale=vs)}{_cell(exact, scale=vs)}"
                    f"{_cell(abs(v) - exact, 13, '.2e')}{_cell(pv - exact, 11, '.2e')}")
    for link, w in by.omegas.items():
        exact = float(kin.omega(link)[i])
        pw = float(plan_w[link][j]) if link in plan_w else float("nan")
        rows.append(f"{'ω' + link:<10}{_cell(w, scale=ws)}{_cell(pw, scale=ws)}{_cell(exact, scale=ws)}"
                    f"{_cell(w - exact, 13, '.2e')}{_cell(pw - exact, 11, '.2e')}")
    return rows


def table(con: Construction, exact, res, number: int | None, *, lang: str = "en", steps: bool = False) -> str:
    """One position: every centre (constructed beside exact), what was not reached and why, the
    velocities by centres beside the plan's and the analytic ones (m/s, rad/s)."""
    kin, i = con.kin, con.index
    where = f"position {number}, " if number is not None else ""
    lines = [f"{kin.mechanism.name}: instant centres, {where}φ = {float(kin.phi_deg[i]) % 360.0:.3f}°, "
             f"μl = {con.mu_l:g} m/mm, {con.drafting.mode}"]
    lines += _centre_rows(con, exact, i)
    for s in con.unreached:
        lines.append(f"not reached: {con.describe('en')[s.number - 1]}")
    lines.append(f"circle diagram: {len(con.steps) - len(con.unreached)} of {len(con.steps)} centres found")
    lines.append("velocities by centres, off the plan and analytic (|V| m/s, ω rad/s)")
    lines += _velocity_rows(con, res, i)
    if steps:
        lines.append("")
        lines += [f"{n}. {s}" for n, s in enumerate(con.describe(lang), 1)]
    return "\n".join(lines)
