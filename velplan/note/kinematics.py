"""Sections of the note on kinematics: the positions, the plans of each chosen position written
out step by step, the table of analogues and the diagrams."""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.note.figures import lettered_for_page, views_figure
from velplan.note.formulas import txt
from velplan.note.model import Equation, Heading, Para
from velplan.note.steps import rate_equation, step_equations
from velplan.note.text import direction, p
from velplan.plans import text as T
from velplan.render.i18n import label
from velplan.views.base import fixed, number, ratio_text, subscript, unit
from velplan.views.readings import readings


def positions_section(note, study, sheet) -> None:
    """The scheme in its positions, the crank angles, the stroke, θ and K."""
    lang = note.lang
    note.add(Heading(p("sec_positions", lang), 1))
    mu_l = sheet.scales["mu_l"]
    note.add(Para.of(p("scale_l" if _starts_at_extreme(study) else "scale_l_zero", lang, number(mu_l, lang), ratio_text(mu_l, lang), study.n,
                       study.mechanism.crank.link)))
    picture, width = views_figure([sheet.views["mechanism"]], sheet.style)
    k = note.figure(p("scheme_fig", lang), picture, width)
    head = [label("position", lang)] + [str(position_number(j)) for j in range(study.n)]
    angles = [fixed(math.degrees(a) % 360.0, lang, 1) for a in study.phi]
    if study.n > 12:
        note.table(p("crank_angles", lang), [label("position", lang), p("phi", lang)],
                   [[str(position_number(j)), a] for j, a in enumerate(angles)], key="angles")
    else:
        note.table(p("crank_angles", lang), head, [[p("phi", lang)] + angles], key="angles")
    st = study.stroke
    if st is None:
        return
    note.add(Para.of(p("stroke", lang) + f" ({p('figure', lang).lower()} {k})"))
    deg = unit("deg", lang)
    theta = number(math.degrees(st.theta), lang)
    sym = "H" if st.quantity.startswith(("slide", "point")) else r"\psi_{max}"
    h_unit = unit("m", lang) if sym == "H" else unit("rad", lang)
    note.add(Equation(rf"{sym} = {txt(number(st.H, lang))}\ {txt(h_unit)},\quad "
                      rf"\theta = {txt(number(math.degrees(st.theta), lang) + deg)}"),
             Equation(rf"K = \frac{{180{txt(deg)} + \theta}}{{180{txt(deg)} - \theta}} = "
                      rf"\frac{{180 + {txt(theta)}}}{{180 - {txt(theta)}}} = {txt(number(st.K, lang))}"))


def _starts_at_extreme(study) -> bool:
    """Whether position 1 is an extreme position of the output."""
    st = study.stroke
    if st is None:
        return False
    phi0 = float(study.phi[0])
    return any(abs(math.remainder(phi0 - e.phi, 2 * math.pi)) < 1e-6 for e in (st.start, st.end))


def plan_section(note, sheet, number_k: int, kind: str) -> None:
    """The plan of ``kind`` (``"v"``, ``"a"``) at position ``number_k`` as on the sheet: its
    scale, each step's sentence and formulas, ω or ε of the links, the values found."""
    lang = note.lang
    view = f"plan-{kind}-{number_k}"
    res, i = sheet.plans[view], sheet.plan_index[view]
    title = p("sec_velocity" if kind == "v" else "sec_acceleration", lang, number_k)
    note.add(Heading(title, 2))
    deg = math.degrees(float(res.phi[i])) % 360.0
    unit_key = "(m/s)/mm" if kind == "v" else "(m/s²)/mm"
    note.add(Para.of(p("position_phi", lang, number_k, fixed(deg, lang, 1)) + " " +
                     p("plan_scale", lang, kind, number(res.scale, lang), unit(unit_key, lang))))
    count = 0
    for step in res.steps:
        if not step.target.startswith(kind):
            continue
        count += 1
        note.add(Para.of(p("step", lang, count) + " " + step.describe(res.ctx, res.values, i, lang)))
        note.add(*(Equation(tex) for tex in step_equations(res, step, i, lang)))
    rates = res.omegas if kind == "v" else res.epsilons
    note.add(Para.of(p("angular" if kind == "v" else "angular_a", lang)))
    seen: dict[tuple, str] = {}
    for link in rates:
        fig = res.plan.figures[kind].get(link)
        key = (fig.img1, fig.img2) if fig is not None else None
        value = float(rates[link][i])
        if key in seen:  # a block turning with its rocker: the same rate, not computed again
            sym = (r"\omega_{" if kind == "v" else r"\varepsilon_{")
            note.add(Equation(rf"{sym}{link}}} = {sym}{seen[key]}}} = {txt(T.num(abs(value), lang))}\ "
                              rf"{txt(unit('rad/s' if kind == 'v' else 'rad/s²', lang))}\quad "
                              rf"\text{{({p('turns_with', lang, link, seen[key])})}}"))
            continue
        if key is not None:
            seen[key] = link
        tex = rate_equation(res, link, i, lang)
        if tex is not None:
            note.add(Equation(tex + (rf"\quad \text{{({direction(value, lang)})}}" if value != 0 else "")))
    picture, width = views_figure([sheet.views[view]], sheet.style)
    fig = note.figure(p("plan_fig", lang, label("velocity_plan" if kind == "v" else "acceleration_plan", lang),
                        number_k), picture, width)
    _results_table(note, res, i, kind, number_k, fig)


def _results_table(note, res, i: int, kind: str, number_k: int, fig: int) -> None:
    """The values found on the plan (four significant figures, as the step sentences), and the
    values read off the drawn plan at 0.5 mm beside the analytic ones (the sheet's table)."""
    lang = note.lang
    ground = set(res.plan.mechanism.ground_points)
    sym = "V" if kind == "v" else "a"
    u = T.unit(kind, lang)
    rows = [[f"{sym}{subscript(pt)}", T.num(float(np.hypot(*v[i])), lang), u]
            for pt, v in res.vectors.items() if pt not in ground]
    rates = res.omegas if kind == "v" else res.epsilons
    ru = unit("rad/s" if kind == "v" else "rad/s²", lang)
    rows += [[("ω" if kind == "v" else "ε") + subscript(link), T.num(abs(float(r[i])), lang), ru]
             for link, r in rates.items()]
    caption = p("results_v" if kind == "v" else "results_a", lang) + f" ({p('figure', lang).lower()} {fig})"
    note.table(caption, [p("quantity", lang), p("value", lang), p("unit", lang)], rows,
               key=f"{'velocities' if kind == 'v' else 'accelerations'}-{number_k}")
    note.add(Para.of(p("readings_text", lang)))
    read_rows = []
    for pt, read, exact in readings(res, number_k):
        err = 100.0 * (read - exact) / exact if exact > 1e-12 * max(read, 1.0) else float("nan")
        read_rows.append([f"{sym}{subscript(pt)}", fixed(read, lang, 3), fixed(exact, lang, 3),
                          fixed(err, lang, 1) if np.isfinite(err) else "—"])
    note.table(p("readings", lang) + f", {sym}, {u}",
               [p("quantity", lang), p("read", lang), p("analytic", lang), "δ, %"],
               read_rows, key=f"readings-{kind}-{number_k}")


def analogues_section(note, study, sheet) -> None:
    """The table of transfer functions of the sheet, positions as rows."""
    from velplan.views.table import _row_label

    lang = note.lang
    table = study.table
    mech = study.mechanism
    note.add(Heading(p("sec_analogues", lang), 2), Para.of(p("analogues_text", lang, mech.crank.link)))
    head = [label("position_short", lang), f"φ, {unit('deg', lang)}"] + [
        _row_label(name, mech.crank.link, lang) for name in table.rows]
    rows = []
    for j, phi in enumerate(table.phi):
        rows.append([str(position_number(j)), fixed(math.degrees(phi) % 360.0, lang, 1)] +
                    [fixed(float(np.asarray(v)[j]), lang, 3) for v in table.rows.values()])
    note.table(label("table_transfer", lang), head, rows, key="analogues")


def diagrams_section(note, sheet, study=None) -> None:
    """The diagrams of the output by the chord method, as drawn on the sheet."""
    lang = note.lang
    if "diagrams" not in sheet.views:
        return
    note.add(Heading(p("sec_diagrams", lang), 2), Para.of(p("diagrams_text", lang)))
    view = _diagrams_for_page(sheet, study) if study is not None else sheet.views["diagrams"]
    picture, width = views_figure([view], sheet.style)
    note.figure(p("diagrams_fig", lang), picture, width)


def _diagrams_for_page(sheet, study):
    """The sheet's three diagrams one above the other, φ axes aligned, at the sheet's own
    scales: side by side (as on the sheet) they would print at a third of their size, too
    small for their titles and scales at 2.5 mm. The sheet's view where its scales cannot be
    told again."""
    from velplan.sheets.kinematic import DIAGRAM_HEIGHTS
    from velplan.views.diagram import DiagramSizes, choose_scales, diagram_view

    view = getattr(sheet.views["diagrams"], "view", sheet.views["diagrams"])
    scales = view.meta.get("scales")
    for height in DIAGRAM_HEIGHTS:
        if scales is not None and choose_scales(study.diagrams, length_mm=scales.length_mm,
                                                height_mm=height) == scales:
            return lettered_for_page(lambda sizes: diagram_view(
                study.diagrams, length_mm=scales.length_mm, height_mm=height, lang=sheet.style.language,
                arrangement="column", omega=study.mechanism.crank.omega, sizes=sizes,
                wrap_mm=scales.length_mm), DiagramSizes())
    return view
