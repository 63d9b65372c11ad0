"""``velplan plan``, ``velplan compare`` and ``velplan check``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from velplan.analysis.numbering import position_index, position_number
from velplan.cli.common import add_mechanism, add_output, default_language, emit, parse_angles, positive_int
from velplan.errors import VelplanError
from velplan.options import Language
from velplan.plans import EXACT, Drafting
from velplan.plans.check import check_table
from velplan.plans.engine import PlanResult
from velplan.plans.text import LANGS
from velplan.study import Study


def register(sub) -> None:
    p = sub.add_parser("plan", help="construct a velocity or acceleration plan at one position")
    add_mechanism(p)
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--position", metavar="K", type=positive_int, help="position number 1…N from the reference")
    where.add_argument("--angle", metavar="DEG", help="absolute crank angle, degrees")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12, help="positions per revolution (default 12)")
    p.add_argument("--kind", choices=("velocity", "acceleration"), default="velocity")
    _add_plan_options(p)
    p.add_argument("--only", metavar="POINT,…", help="evaluate only the steps these points or links need")
    p.add_argument("--format", choices=("text", "json"), default="text")
    p.add_argument("--lang", choices=LANGS, default=default_language(),
                   help="language of the worked solution (default: the locale's, else en)")
    add_output(p)
    p.set_defaults(run=run_plan)

    p = sub.add_parser("compare", help="graphical against analytic values, per quantity and position")
    add_mechanism(p)
    p.add_argument("--positions", metavar="N", type=positive_int, default=12)
    p.add_argument("--kind", choices=("velocity", "acceleration", "both"), default="both")
    _add_plan_options(p)
    p.add_argument("--format", choices=("table", "json"), default="table")
    add_output(p)
    p.set_defaults(run=run_compare)

    p = sub.add_parser("check", help="check a hand-made table of transfer functions (CSV)")
    add_mechanism(p)
    p.add_argument("--table", metavar="FILE.csv", required=True)
    p.add_argument("--scale-v", metavar="MU", type=float, help="μv the table was drawn at, (m/s)/mm")
    p.add_argument("--precision", metavar="MM", type=float, default=0.5, help="drafting precision, mm (default 0.5)")
    p.add_argument("--angle-precision", metavar="DEG", type=float, default=0.5, help="angular precision, deg (default 0.5)")
    p.add_argument("--key", metavar="answers.json", help="grade against this answer key of velplan batch instead")
    p.add_argument("--variant", metavar="N", help="the variant of --key the table belongs to")
    p.add_argument("--tolerance", metavar="P%", default="5%", help="with --key: allowed error, %% of each row's largest value (default 5%%)")
    add_output(p)
    p.set_defaults(run=run_check)


def _add_plan_options(p) -> None:
    p.add_argument("--scale-v", metavar="MU", type=float, help="μv, (m/s)/mm (default: from the standard series)")
    p.add_argument("--scale-a", metavar="MU", type=float, help="μa, (m/s²)/mm (default: from the standard series)")
    p.add_argument("--mode", choices=("exact", "drafting"), default="exact")
    p.add_argument("--precision", metavar="MM", type=float, default=0.5, help="drafting precision, mm (default 0.5)")
    p.add_argument("--angle-precision", metavar="DEG", type=float, default=0.5, help="angular precision, deg (default 0.5)")


def _drafting(args) -> Drafting:
    return EXACT if args.mode == "exact" else Drafting(args.precision, args.angle_precision)


def run_plan(args) -> int:
    if args.angle is not None:
        phi = parse_angles(args.angle)
        if phi.size != 1:
            raise VelplanError("--angle takes one angle")
        study, index, number = Study(args.mechanism, angles=phi), 0, None
    else:
        if args.position > args.positions:
            raise VelplanError(f"--position {args.position} is outside 1…{args.positions}")
        study, index, number = (Study(args.mechanism, n=args.positions),
                                 position_index(args.position, args.positions), args.position)
    study.require_assembled([position_number(index)])
    only = [x.strip() for x in args.only.split(",")] if args.only else None
    scale_v, scale_a = position_scales(study, position_number(index), args.kind, args.scale_v, args.scale_a)
    res = study.plan(args.kind, positions=[position_number(index)], only=only, scale_v=scale_v, scale_a=scale_a,
                     drafting=_drafting(args))
    doc = plan_json(res, number)
    emit(json.dumps(doc, indent=1, ensure_ascii=False) if args.format == "json" else plan_text(res, doc, args.lang),
         args.output)
    return 0


def position_scales(study: Study, position: int, kind: str, scale_v: float | None,
                    scale_a: float | None) -> tuple[float, float | None]:
    """μv and μa of the plan at position number ``position``: the given ones, else the default
    of that position alone (`PlanResult.position_scale`, the one ``velplan steps`` draws at)."""
    if scale_v is None:
        scale_v = study.plan("velocity").position_scale(position)
    if kind == "acceleration" and scale_a is None:
        scale_a = study.plan("acceleration").position_scale(position)
    return scale_v, scale_a


def _f(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def plan_json(res: PlanResult, number: int | None, i: int = 0) -> dict:
    """The plan at result position ``i`` as a JSON-ready dict (mm on the plan, SI readouts)."""
    acc = res.kind == "acceleration"
    key, comps = ("accelerations", ("ax", "ay")) if acc else ("velocities", ("vx", "vy"))
    ref = res.kin.accelerations if acc else res.kin.velocities
    j = res.index[i]
    doc = {
        "kind": res.kind,
        "mechanism": res.plan.mechanism.name,
        "position": number,
        "phi_deg": float(res.kin.phi_deg[j]),
        "mode": res.mode,
        "scale": res.scale,
        "scales": {"v": res.scales["v"], **({"a": res.scales["a"]} if acc else {})},
        "images": {k: [_f(v[i, 0]), _f(v[i, 1])] for k, v in res.images.items()},
        key: {k: dict(zip(comps, (_f(v[i, 0]), _f(v[i, 1])))) for k, v in res.vectors.items()},
        "analytic": {k: dict(zip(comps, (_f(ref[j, res.kin.point_index[k], 0]), _f(ref[j, res.kin.point_index[k], 1]))))
                     for k in res.vectors if k in res.kin.point_index},
        "omegas": {k: _f(v[i]) for k, v in res.omegas.items()},
        "components": [
            {"name": name, "of": res.component_point(name), "segment": label,
             "length_mm": _f(res.segments[label][i]), "value": _f(value[i])}
            for name, (label, value) in res.components.items()
        ],
        "conditions": {k: _f(v[i]) for k, v in res.conditions.items()},
        "flags": [{"image": f.image, "condition": f.condition, "bound_mm": f.bound_mm, "refused": f.refused}
                  for f in res.flags if f.index == i],
        "steps": [{"kind": type(s).__name__, "target": s.target, "text": s.describe(res.ctx, res.values, i, "en")}
                  for s in res.steps if s.target.startswith(res.kind[0])],
        "evaluated_steps": res.evaluated_steps,
    }
    if acc:
        doc["epsilons"] = {k: _f(v[i]) for k, v in res.epsilons.items()}
    return doc


def plan_text(res: PlanResult, doc: dict, lang: Language) -> str:
    """The plan as text, every word and number in ``lang`` (decimal comma in ru and uk)."""
    from velplan.plans import text as T
    from velplan.render.i18n import label
    from velplan.notation import digits_down

    k = "a" if res.kind == "acceleration" else "v"
    title = label(f"{res.kind}_plan", lang)
    where = f", {label('position', lang).lower()} {doc['position']}" if doc["position"] else ""
    phi = math.fmod(doc["phi_deg"], 360.0) % 360.0
    angle = format(phi, ".3f").replace(".", "," if lang in ("ru", "uk") else ".")
    head = (f"{doc['mechanism']}: {title}{where}, φ = {angle}°, "
            f"μ{k} = {T.num(res.scale, lang)} {T.unit('μ' + k, lang)}, {T.phrase('mode_' + res.mode, lang)}")
    lines = [head, ""]
    lines += [f"{n}. {T.terminal(s)}" for n, s in enumerate(res.describe(lang=lang), 1)]
    lines.append("")
    key = "accelerations" if k == "a" else "velocities"
    ground = dict(res.plan.mechanism.ground)
    for p, v in doc[key].items():
        if p in ground:
            continue
        mag = math.hypot(*(x or 0.0 for x in v.values()))
        lines.append(f"{k}_{p} = {T.num(mag, lang, 6)} {T.unit(k, lang)}")
    def by_link(rates: dict) -> list:
        return sorted(rates.items(), key=lambda kv: (len(kv[0]), kv[0]))

    for link, w in by_link(doc["omegas"]):
        lines.append(f"ω{digits_down(link)} = {T.signed(w, lang)} {T.unit('ω', lang)}")
    for link, e in by_link(doc.get("epsilons", {})):
        lines.append(f"ε{digits_down(link)} = {T.signed(e, lang)} {T.unit('ε', lang)}")
    for f in doc["flags"]:
        lines.append(T.phrase("refused" if f["refused"] else "flagged", lang, f["image"],
                              T.num(f["condition"], lang, 3), T.mm(f["bound_mm"], lang)))
    lines.append(T.phrase("evaluated", lang, doc["evaluated_steps"]))
    return "\n".join(lines)


def run_compare(args) -> int:
    study = Study(args.mechanism, n=args.positions)
    mech = study.mechanism
    kinds = ("velocity", "acceleration") if args.kind == "both" else (args.kind,)
    rows = []
    for kind in kinds:
        rows += compare_rows(study.plan(kind, scale_v=args.scale_v, scale_a=args.scale_a, drafting=_drafting(args)))
    if args.format == "json":
        emit(json.dumps({"mechanism": mech.name, "mode": args.mode, "rows": rows}, indent=1, ensure_ascii=False), args.output)
        return 0
    lines = [f"{'quantity':<12}{'pos':>4}{'φ, °':>9}{'graphical':>14}{'analytic':>14}{'abs error':>12}{'rel error':>11}{'  flag'}"]
    def cell(x, spec: str, width: int) -> str:
        return f"{'—':>{width}}" if x is None else f"{x:>{width}{spec}}"

    for r in rows:
        lines.append(f"{r['quantity']:<12}{r['position']:>4}{r['phi_deg']:>9.2f}{cell(r['graphical'], '.6g', 14)}"
                     f"{cell(r['analytic'], '.6g', 14)}{cell(r['abs_error'], '.2e', 12)}{cell(r['rel_error'], '.2e', 11)}"
                     f"{'  ' + r['flag'] if r['flag'] else ''}")
    emit("\n".join(lines), args.output)
    return 0


def compare_rows(res: PlanResult) -> list[dict]:
    """Per quantity and position: graphical, analytic, absolute and relative error."""
    kin = res.kin
    acc = res.kind == "acceleration"
    ref = kin.accelerations if acc else kin.velocities
    sym = "a" if acc else "V"
    rows = []
    # the plan's own construction points (a coincident point the file does not name) have no
    # analytic counterpart among the solver's points: they are not compared
    quantities = [(f"{sym}_{p}", np.hypot(*v.T), np.hypot(*ref[res.index, kin.point_index[p]].T)) for p, v in res.vectors.items()
                  if p not in dict(kin.mechanism.ground) and p in kin.point_index]
    if acc:
        quantities += [(f"ε{k}", v, kin.epsilon(k)[res.index]) for k, v in res.epsilons.items()]
    else:
        quantities += [(f"ω{k}", v, kin.omega(k)[res.index]) for k, v in res.omegas.items()]
    singular = kin.singular
    for name, got, exact in quantities:
        for i, j in enumerate(res.index):
            if not kin.valid[j]:  # nothing to compare: say why
                rows.append({"quantity": name, "position": position_number(i), "phi_deg": float(kin.phi_deg[j]),
                             "graphical": None, "analytic": None, "abs_error": None, "rel_error": None,
                             "flag": "singular" if singular[j] else "not assembled"})
                continue
            err = abs(got[i] - exact[i])
            flag = ""
            mine = [f for f in res.flags if f.index == i]
            if mine:
                flag = "refused" if any(f.refused for f in mine) else "flagged"
            rows.append({
                "quantity": name, "position": position_number(i), "phi_deg": float(kin.phi_deg[j]),
                "graphical": _f(got[i]), "analytic": _f(exact[i]), "abs_error": _f(err),
                "rel_error": _f(err / abs(exact[i])) if abs(exact[i]) > 1e-12 * max(1.0, np.nanmax(np.abs(exact))) else None,
                "flag": flag,
            })
    return rows


def run_check(args) -> int:
    if args.key is not None or args.variant is not None:
        return _run_grade(args)
    mech = Study(args.mechanism).mechanism
    report = check_table(mech, args.table, scale_v=args.scale_v, drafting=Drafting(args.precision, args.angle_precision))
    emit(report.text(), args.output)
    return 0


def _run_grade(args) -> int:
    from velplan.plans.grade import grade_table, read_key

    if args.key is None or args.variant is None:
        raise VelplanError("--key and --variant go together: the answer key and the student's variant")
    text = args.tolerance.strip()
    try:
        tol = float(text[:-1]) / 100 if text.endswith("%") else float(text)
    except ValueError:
        raise VelplanError(f"--tolerance: {args.tolerance!r} is not a percentage such as 5%") from None
    base = read_key(args.key, args.variant).get("base", "")
    names = {str(args.mechanism), Path(str(args.mechanism)).stem}
    if base and not names & {str(base), Path(str(base)).stem}:
        raise VelplanError(f"variant {args.variant} of {args.key} is a variant of {base!r}, not of {args.mechanism!r}")
    emit(grade_table(args.table, args.key, args.variant, tolerance=tol).text(), args.output)
    return 0
