"""``velplan centres``: the instant centres of velocity, exactly and by the Kennedy construction,
and the velocities they give beside the plan's and the analytic ones."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from velplan.analysis.centres import instant_centres
from velplan.analysis.solver import length_scale
from velplan.analysis.numbering import position_index, position_number
from velplan.cli.common import add_mechanism, default_language, emit, parse_angles, positive_int
from velplan.errors import VelplanError
from velplan.notation import localized, superscript
from velplan.options import Language
from velplan.plans import EXACT, Drafting
from velplan.plans.centres import Construction, centre_name, velocities_by_centres
from velplan.plans.scale import check_scale, check_scheme_scale
from velplan.plans.text import LANGS
from velplan.render.i18n import centres_words as _w
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
    p.add_argument("-o", "--output", metavar="FILE",
                   help="write the table to FILE instead of standard output; a .svg, .png or .pdf name "
                   "draws the figure there (as --svg) and prints the table")
    p.set_defaults(run=run_centres)


#: An ``-o`` name with one of these suffixes is the figure's (`velplan.render.export.save_drawing`).
DRAWING_SUFFIXES = (".svg", ".png", ".pdf")


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
        return study, [position_index(args.position, args.positions)], [args.position]
    idx = list(range(args.positions))
    return study, idx, [position_number(i) for i in idx]


def run_centres(args) -> int:
    for option, v in (("--precision", args.precision), ("--angle-precision", args.angle_precision)):
        if not (math.isfinite(v) and 0 < v <= 10.0):  # checked in either mode: never silently ignored
            raise VelplanError(f"{option} must be > 0 and at most 10 (a draughtsman's precision), not {v:g}")
    drafting = EXACT if args.mode == "exact" else Drafting(args.precision, args.angle_precision)
    mu_l = None if args.scale_l is None else check_scale(args.scale_l, "--scale-l")
    study, idx, numbers = _study(args)
    if mu_l is not None:
        check_scheme_scale(mu_l, length_scale(study.mechanism), "--scale-l")
    study.require_assembled([position_number(i) for i in idx])
    kin = study.kinematics
    exact = instant_centres(kin)
    if args.svg is not None and not str(args.svg).strip():
        raise VelplanError("--svg: give a file name, not an empty string")
    if args.svg is None and args.output and Path(args.output).suffix.lower() in DRAWING_SUFFIXES:
        args.svg, args.output = args.output, None  # -o figure.svg asks for the figure, not the table
    cons = [study.centres(position_number(i), drafting=drafting, mu_l=mu_l) for i in idx]
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
        return study.plan("velocity") if drafting.exact else study.plan("velocity", drafting=drafting, positions=[position_number(i)])
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




def _num(text: str, lang: str) -> str:
    """A formatted number in the language: decimal comma in ru and uk, the minus "−" (en keeps
    the hyphen of a terminal's text)."""
    return localized(text, lang) if lang != "en" else text


def _cell(x: float, width: int = 12, spec: str = ".6g", scale: float = 0.0, lang: str = "en") -> str:
    """A right-aligned number after a space; round-off below 1e-12 × ``scale`` prints as 0."""
    if not math.isfinite(x):
        return f" {'—':>{width - 1}}"
    x = 0.0 if abs(x) <= 1e-12 * scale else x
    text = format(x, spec)
    if spec.endswith("e") and lang != "en":  # a power of ten as written by hand: 1,11·10⁻¹⁶
        mantissa, _, power = text.partition("e")
        text = "0" if x == 0 else f"{mantissa}·10{superscript(str(int(power)))}"
    return f" {_num(text, lang):>{width - 1}}"


def _direction(d: complex, lang: str = "en") -> str:
    """A centre at infinity: ∞ and its unit direction."""
    return f" {'∞ ' + _num(format(d.real, '.4f'), lang):>11} {_num(format(d.imag, '.4f'), lang):>11}"


def _how(s, lang: str = "en") -> str:
    """How a centre was found, in a few words."""
    if s.how in ("joint", "hinge"):
        return _w(s.how, lang, s.via[0])
    if s.how == "slider":
        return _w("slider", lang, s.via[0])
    return _w("kennedy", lang, s.via[0], s.via[1], _num(format(s.condition, ".3g"), lang))


def _centre_rows(con: Construction, exact, i: int, lang: str = "en") -> list[str]:
    L = exact.size
    m = _w("metre", lang)
    rows = [f"{_w('centre', lang):<8}{'x, ' + m:>12}{'y, ' + m:>12}  {_w('construction', lang):<34}"
            f"{_w('exact', lang) + ' x, ' + m:>12}{_w('exact', lang) + ' y, ' + m:>12}"]
    for k, (a, b) in enumerate(exact.pairs):
        s = con.centre(a, b)
        p, d = exact.points[i, k], exact.directions[i, k]
        ex = (_direction(d, lang) if np.isfinite(d)
              else _cell(p.real, scale=L, lang=lang) + _cell(p.imag, scale=L, lang=lang))
        if s is None:
            how, xy = _w("not_reached", lang), f"{'—':>12}{'—':>12}"
        else:
            xy = (_direction(s.direction, lang) if s.infinite
                  else _cell(s.point.real, scale=L, lang=lang) + _cell(s.point.imag, scale=L, lang=lang))
            how = _how(s, lang)
        rows.append(f"{centre_name((a, b)):<8}{xy}  {how:<34}{ex}")
    return rows


def _velocity_rows(con: Construction, res, i: int, lang: str = "en") -> list[str]:
    kin = con.kin
    by = velocities_by_centres(con)
    rows = [f"{_w('quantity', lang):<10}{_w('by_centres', lang):>12}{_w('plan', lang):>12}{_w('analytic', lang):>12}"
            f"{_w('err_centres', lang):>14}{_w('err_plan', lang):>13}"]
    vs = float(np.nanmax(np.hypot(*kin.velocities[i].T)))
    ws = vs / length_scale(kin.mechanism)
    j = list(res.index).index(i) if res is not None else 0
    plan_v = res.vectors if res is not None else {}
    plan_w = res.omegas if res is not None else {}
    for name, v in by.velocities.items():
        exact = float(np.hypot(*kin.velocity(name)[i]))
        pv = float(np.hypot(*plan_v[name][j])) if name in plan_v else float("nan")
        rows.append(f"{'v_' + name:<10}{_cell(abs(v), scale=vs, lang=lang)}{_cell(pv, scale=vs, lang=lang)}"
                    f"{_cell(exact, scale=vs, lang=lang)}"
                    f"{_cell(abs(v) - exact, 14, '.2e', lang=lang)}{_cell(pv - exact, 13, '.2e', lang=lang)}")
    for link, w in by.omegas.items():
        exact = float(kin.omega(link)[i])
        pw = float(plan_w[link][j]) if link in plan_w else float("nan")
        rows.append(f"{'ω' + link:<10}{_cell(w, scale=ws, lang=lang)}{_cell(pw, scale=ws, lang=lang)}"
                    f"{_cell(exact, scale=ws, lang=lang)}"
                    f"{_cell(w - exact, 14, '.2e', lang=lang)}{_cell(pw - exact, 13, '.2e', lang=lang)}")
    return rows


def table(con: Construction, exact, res, number: int | None, *, lang: Language = "en", steps: bool = False) -> str:
    """One position: every centre (constructed beside exact), what was not reached and why, the
    velocities by centres beside the plan's and the analytic ones (m/s, rad/s), in ``lang``."""
    kin, i = con.kin, con.index
    where = f"{_w('position', lang)} {number}, " if number is not None else ""
    phi = _num(format(float(kin.phi_deg[i]) % 360.0, ".3f"), lang)
    mu = _num(format(con.mu_l, "g"), lang)
    lines = [f"{kin.mechanism.name}: {_w('head', lang)}, {where}φ = {phi}°, "
             f"μl = {mu} {_w('metre', lang)}/{'mm' if lang in ('en', 'zh') else 'мм'}, {_w(con.drafting.mode, lang)}"]
    lines += _centre_rows(con, exact, i, lang)
    for s in con.unreached:
        lines.append(_w("not_reached_at", lang, con.describe(lang)[s.number - 1]))
    lines.append(_w("circle_found", lang, len(con.steps) - len(con.unreached), len(con.steps)))
    lines.append(_w("velocities", lang))
    lines += _velocity_rows(con, res, i, lang)
    if steps:
        lines.append("")
        lines += [f"{n}. {s}" for n, s in enumerate(con.describe(lang), 1)]
    return "\n".join(lines)