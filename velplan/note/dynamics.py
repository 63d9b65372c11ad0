"""The section of the note on machine dynamics: the model, the flywheel's formula with its
numbers, the sheet's table of results and its diagrams."""

from __future__ import annotations

from velplan.note.figures import views_figure
from velplan.note.formulas import txt
from velplan.note.numbers import tidy
from velplan.note.model import Equation, Heading, Para
from velplan.note.text import p
from velplan.render.i18n import label
from velplan.views.base import number, unit
from velplan.notation import unicode_text
from velplan.views.dynamics import results_rows

PANELS = (("moments", "reduced_moments"), ("works", "works_energy"), ("inertia", "reduced_inertia"),
          ("omega", "crank_speed"), ("wittenbauer", "energy_mass"), ("flywheel", "flywheel"))


def dynamics_section(note, sheet) -> None:
    """Dynamics as on the dynamics sheet."""
    from velplan.note import dynamics_worked as W

    lang = note.lang
    d = sheet.dynamics
    note.add(Heading(p("sec_dynamics", lang), 1), Para.of(p("dyn_intro", lang, d.mechanism.crank.link)))
    W.worked_position(note, d, 2)
    W.by_position_tables(note, d)
    fly = d.flywheel
    if fly is not None:
        wm, delta = fly.omega_mean, fly.delta
        energy = fly.exact * delta * wm ** 2
        kgm2 = txt(unit("kg·m²", lang))
        note.add(Para.of(p("flywheel_formula", lang)),
                 Equation(rf"J_{{I}} = \frac{{\Delta T_{{I}}}}{{\delta\,\omega_{{m}}^{{2}}}} = "
                          rf"\frac{{{txt(number(energy, lang, 4))}}}{{{txt(number(delta, lang, 4))}\cdot "
                          rf"{txt(number(wm, lang, 5))}^{{2}}}} = {txt(number(fly.exact, lang, 4))}\ {kgm2}"))
        W.flywheel_shafts(note, d)
    rows = results_rows(d, sheet.wittenbauer, lang)
    note.table(p("dyn_results", lang), [p("quantity", lang), p("value", lang), p("unit", lang)],
               [[unicode_text(r[0]), tidy(unicode_text(r[1]), lang), unicode_text(r[2])] for r in rows],
               key="dynamics")
    for view, key in PANELS:
        if view in sheet.views:
            picture, width = views_figure([sheet.views[view]], sheet.style)
            note.figure(label(key, lang), picture, width)
