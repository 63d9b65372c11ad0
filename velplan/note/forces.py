"""Sections of the note on forces: kinetostatics group by group with the force polygons,
Zhukovsky's lever, and the balancing moment by three methods, with the force sheet's numbers."""

from __future__ import annotations

import math

from velplan.analysis.numbering import position_index, position_number
from velplan.note.figures import views_figure
from velplan.note.formulas import force, txt
from velplan.note.model import Equation, Heading, Para
from velplan.note.text import balancing, group_kind, p
from velplan.render.i18n import label
from velplan.sheets.forces import solving_order
from velplan.notation import fixed, number as _num, plain_text, unicode_text
from velplan.views.forces import force_text, moment_decimals, newton, newton_metre, slug


def forces_section(note, sheet) -> None:
    """Every position of the force sheet, then the table of the three methods."""
    lang = note.lang
    note.add(Heading(p("sec_forces", lang), 1), Para.of(p("ks_intro", lang)))
    for k in sheet.positions:
        note.add(Heading(p("sec_kinetostatics", lang, k), 2))
        kin = sheet.analysis.kinematics
        deg = math.degrees(float(kin.phi[position_index(k, len(kin))])) % 360.0
        note.add(Para.of(p("position_phi", lang, k, fixed(deg, lang, 1))))
        for group in solving_order(sheet.mechanism):
            _group(note, sheet, k, group)
        _lever(note, sheet, k)
    _moments(note, sheet)


def _group(note, sheet, k: int, group: str) -> None:
    lang, i = note.lang, position_index(k, len(sheet.analysis.kinematics))
    ks = sheet.analysis.kinetostatics
    poly = ks.polygons[group]
    kind = next((g.kind for g in sheet.mechanism.groups if g.name == group), "")
    title = (p("sec_crank", lang, sheet.mechanism.crank.link) if group == "crank"
             else p("sec_group", lang, group, group_kind(kind, lang)))
    note.add(Heading(title, 3), Para.of(p("known_forces", lang)))
    mu_f = sheet.scales.get(f"polygon-{k}-{slug(group)}")
    rows = []
    for name, vector in poly.vectors:
        value = abs(complex(vector[i]))
        rows.append([unicode_text(force_text(name)), _num(value, lang),
                     fixed(value / mu_f, lang, 1) if mu_f else "—"])  # a drawn length: 0.1 mm
    unit_mm = "мм" if lang in ("ru", "uk") else "mm"
    note.table(title, [p("quantity", lang), f"{p('value', lang)}, {newton(lang)}", f"{p('segment', lang)}, {unit_mm}"], rows,
               key=f"forces-{k}-{group}")
    names = [n for n, _ in poly.vectors] + [n for n, _ in poly.closing_vectors]
    note.add(Para.of(p("equilibrium", lang)),
             Equation(" + ".join(r"\vec{" + force(n) + "}" for n in names) + " = 0"))
    if mu_f:
        note.add(Para.of(p("polygon_scale", lang, _num(mu_f, lang))))
    for rc in ks.reactions.values():
        if rc.pair.group == group:
            note.add(Equation(rf"{force(rc.label)} = {txt(_num(float(rc.magnitude[i]), lang))}\ "
                              rf"{txt(newton(lang))}"))
    if group == "crank":
        note.add(Equation(rf"{balancing('M', lang)} = {txt(_num(float(ks.balancing_moment[i]), lang))}\ "
                          rf"{txt(newton_metre(lang))}\quad\text{{({label('method_kinetostatics', lang)})}}"))
    views = [sheet.views[v] for v in (f"group-{k}-{slug(group)}", f"polygon-{k}-{slug(group)}")
             if v in sheet.views]
    if views:
        picture, width = views_figure(views, sheet.style)
        caption = p("crank_fig", lang) if group == "crank" else p("group_fig", lang, group)
        note.figure(f"{caption} ({label('position', lang).lower()} {k})", picture, width)


def _lever(note, sheet, k: int) -> None:
    name = f"lever-{k}"
    if name not in sheet.views:
        return
    lang = note.lang
    meta = sheet.views[name].view.meta
    mech = sheet.mechanism
    c = mech.crank
    note.add(Heading(p("sec_lever", lang, k), 3), Para.of(p("lever_text", lang)))
    arm = rf"l_{{{c.pivot[0]}_{{{c.pivot[1:]}}}{c.tip}}}" if c.pivot[1:].isdigit() else rf"l_{{{c.pivot}{c.tip}}}"
    from velplan.note.lever import lever_equations

    lever_equations(note, sheet.analysis, k, int(meta["index"]), float(meta["mu_v"]))
    note.add(Equation(rf"{balancing('M', lang)} = {balancing('F', lang)}\cdot {arm} = {txt(_num(abs(meta['balancing_force']), lang))}\cdot "
                      rf"{txt(_num(_crank_length(sheet, int(meta['index'])), lang))} = "
                      rf"{txt(_num(meta['mb_lever'], lang))}\ {txt(newton_metre(lang))}"))
    mb_kin, nm = meta["mb_kinetostatics"], txt(newton_metre(lang))
    note.add(Para.of(p("lever_check", lang)), Equation(
        rf"{balancing('M', lang)} = {txt(_num(meta['mb_lever'], lang))}\ {nm}\ \text{{({label('method_lever', lang)})}},\quad "
        rf"{balancing('M', lang)} = {txt(_num(mb_kin, lang))}\ {nm}\ \text{{({label('method_kinetostatics', lang)})}},\quad "
        rf"\Delta = {txt(fixed(meta['percent'], lang, 2))}\,\%"))
    picture, width = views_figure([sheet.views[name]], sheet.style)
    note.figure(p("lever_fig", lang, k), picture, width)


def _crank_length(sheet, i: int) -> float:
    """l of the crank, m."""
    c = sheet.mechanism.crank
    kin = sheet.analysis.kinematics
    pos = kin.positions
    a, o = kin.point_index[c.tip], kin.point_index[c.pivot]
    return float(abs(complex(*pos[i, a]) - complex(*pos[i, o])))


def _moments(note, sheet) -> None:
    """The sheet's table of the balancing moments, positions as rows."""
    lang = note.lang
    fa = sheet.analysis
    moments = fa.balancing_moments
    decimals = moment_decimals(moments["kinetostatics"])
    mb = plain_text(label("symbol_balancing_moment", lang))  # Mур: the table's cells set its index
    note.add(Heading(p("sec_moments", lang), 2), Para.of(p("moments_text", lang, sheet.mechanism.crank.link)))
    head = [label("position_short", lang), "φ, °"] + [f"{mb} ({label('method_' + key, lang)})"
                                                     for key in ("kinetostatics", "lever", "power")]
    rows = [[str(position_number(j)), fixed(math.degrees(phi) % 360.0, lang, 1)] +
            [fixed(float(moments[key][j]), lang, decimals) for key in ("kinetostatics", "lever", "power")]
            for j, phi in enumerate(fa.kinematics.phi)]
    note.table(f"{label('balancing_moment', lang)} {mb}, {newton_metre(lang)}", head, rows, key="moments")
    if "mb-diagram" in sheet.views:
        picture, width = views_figure([sheet.views["mb-diagram"]], sheet.style)
        note.figure(p("mb_fig", lang), picture, width)


__all__ = ["forces_section"]
