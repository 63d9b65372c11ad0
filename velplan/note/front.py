"""The front of the note: title page, contents, input data, structural analysis."""

from __future__ import annotations

from velplan.mechanism.structure import structure, pairs
from velplan.note.model import Contents, Equation, Heading, PageBreak, Para, TitlePage
from velplan.note.text import group_kind, group_name, mechanism_of, p, roman
from velplan.notation import unicode_text
from velplan.views.data import data_lines

BLANK = "____________"


def title_page(note, study, fields: dict | None = None) -> None:
    """Title page with the ESKD fields (``organisation``, ``author``, ``group``, ``checker``,
    ``date``; blank lines for what velplan does not know: it never reads the clock). The
    designation is the course work's code, the sheets' (``ТММ 01.00.000``…) with number 00 and
    "ПЗ" in ru/uk: no file name (ГОСТ 2.201)."""
    lang, mech = note.lang, study.mechanism
    fields = dict(fields or {})
    prefix = "ТММ" if lang in ("ru", "uk") else "TMM"
    suffix = " ПЗ" if lang in ("ru", "uk") else ""
    note.add(TitlePage(
        organisation=fields.get("organisation") or BLANK,
        kind=p("note", lang), course=p("course", lang),
        topic=p("topic", lang, mechanism_of(mech.name_in(lang), lang)),
        designation=f"{prefix} 00.00.000{suffix}",
        fields=((p("student", lang), fields.get("author") or BLANK),
                (p("group", lang), fields.get("group") or BLANK),
                (p("supervisor", lang), fields.get("checker") or BLANK)),
        place_year=fields.get("date") or BLANK))
    note.add(PageBreak(), Contents(p("contents", lang)), PageBreak())


def data_section(note, study) -> None:
    """The input data as the sheet writes them, one line per paragraph."""
    note.add(Heading(p("sec_data", note.lang), 1))
    for line in data_lines(study, note.lang):
        note.add(Para.of(unicode_text(line)))  # lO₂A: the note's text sets its symbols


def structure_section(note, study) -> None:
    """Links, pairs, W by Chebyshev, the Assur groups (any class), the formula of structure."""
    lang, mech = note.lang, study.mechanism
    st = structure(mech)
    note.add(Heading(p("sec_structure", lang), 1))
    note.add(Para.of(p("links_pairs", lang, st.n_links, st.p5, st.p4)))
    note.add(Equation(rf"W = 3n - 2p_{{5}} - p_{{4}} = 3\cdot {st.n_links} - 2\cdot {st.p5} - {st.p4} = "
                      rf"{st.mobility}"))
    rows = [[pr.name.replace("P:", ""), p(f"pair_{pr.kind}", lang) if pr.kind in "RP" else pr.kind,
             " – ".join(pr.links), group_name(pr.group, lang)] for pr in pairs(mech)]
    note.table(p("pairs_title", lang), [p("pairs_head", lang), p("kind_head", lang), p("links_head", lang),
                                       p("group_head", lang)], rows, key="pairs")
    groups = [[name, group_kind(kind, lang), p("class_order", lang, roman(cls), order), ", ".join(links)]
              for name, kind, cls, order, links in st.groups]
    note.table(p("groups_head", lang), [p("group_head", lang), p("kind_head", lang), p("class_head", lang),
                                         p("links_head", lang)],
               groups, key="groups")
    note.add(Para.of(p("formula", lang)), Equation(_structure_tex(st, mech.crank.link)),
             Para.of(p("mech_class", lang, roman(st.mechanism_class))))
    _structure_figure(note, mech)



def _structure_figure(note, mech) -> None:
    """The initial mechanism and each group drawn apart, their outer pairs ringed."""
    from velplan.analysis.pose import pose
    from velplan.mechanism.drawn_write import drawn_tables
    from velplan.note.figures import views_figure
    from velplan.render.i18n import label
    from velplan.render.style import SheetStyle
    from velplan.views.structure import structure_view

    scene = structure_view(mech, drawn_tables(mech, *pose(mech))["joint"], lang=note.lang, title=False)
    picture, width = views_figure([scene], SheetStyle(language=note.lang))
    note.figure(label("structural_analysis", note.lang), picture, width)


def _structure_tex(st, crank: str) -> str:
    parts = [rf"\text{{I}}(0, {crank})"] + [rf"\text{{{roman(c)}}}({', '.join(links)})"
                                             for _, _, c, _, links in st.groups]
    return r" \rightarrow ".join(parts)
