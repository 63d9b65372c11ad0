"""The introduction, the conclusion and the list of references of the note (unnumbered, as
ГОСТ 2.105 and ГОСТ 7.32 place them)."""

from __future__ import annotations

import math

import numpy as np

from velplan.note.dynamics_worked import motor_name
from velplan.note.formulas import txt
from velplan.note.model import Heading, Math, Para
from velplan.note.text import LANG_INDEX, balancing, mechanism_of, p, roman
from velplan.notation import number

REFERENCES = {
    "ru": ("Артоболевский И. И. Теория механизмов и машин. — М.: Наука, 1988. — 640 с.",
           "Фролов К. В., Попов С. А., Мусатов А. К. и др. Теория механизмов и механика машин. — М.: "
           "Высшая школа, 2001. — 496 с.",
           "Попов С. А., Тимофеев Г. А. Курсовое проектирование по теории механизмов и механике машин. — М.: "
           "Высшая школа, 2002. — 411 с.",
           "ГОСТ 2.105–2019. ЕСКД. Общие требования к текстовым документам."),
    "uk": ("Артоболевский И. И. Теория механизмов и машин. — М.: Наука, 1988. — 640 с.",
           "Кіницький Я. Т. Теорія механізмів і машин. — К.: Наукова думка, 2002. — 660 с.",
           "Попов С. А., Тимофеев Г. А. Курсовое проектирование по теории механизмов и механике машин. — М.: "
           "Высшая школа, 2002. — 411 с.",
           "ДСТУ ГОСТ 2.105:2008. ЄСКД. Загальні вимоги до текстових документів."),
    "en": ("Artobolevsky I. I. Theory of Mechanisms and Machines. Moscow: Mir Publishers, 1977.",
           "Uicker J. J., Pennock G. R., Shigley J. E. Theory of Machines and Mechanisms. 5th ed. "
           "New York: Oxford University Press, 2017.",
           "Norton R. L. Design of Machinery. 6th ed. New York: McGraw-Hill, 2019."),
    "zh": ("孙桓，陈作模，葛文杰. 机械原理（第八版）. 北京：高等教育出版社，2013.",
           "申永胜. 机械原理教程（第三版）. 北京：清华大学出版社，2015.",
           "阿尔托包列夫斯基. 机构和机器理论. 北京：高等教育出版社，1983."),
}
"""The standard textbooks whose graphical methods the note follows, per language."""

_INTRO = {
    "kinematics": ("the kinematic analysis by the method of plans", "кинематический анализ методом планов",
                   "кінематичний аналіз методом планів", "用图解法作运动分析"),
    "forces": ("the force analysis by kinetostatics and Zhukovsky's lever",
               "силовой анализ методом кинетостатики и рычагом Жуковского",
               "силовий аналіз методом кінетостатики та важелем Жуковського", "用动态静力法和茹科夫斯基杠杆作力分析"),
    "dynamics": ("the dynamics of the machine and the flywheel", "динамический анализ машины и расчёт маховика",
                 "динамічний аналіз машини та розрахунок маховика", "机器动力学分析与飞轮设计"),
}


def introduction(note, study, parts) -> None:
    lang = note.lang
    done = [_INTRO[k][LANG_INDEX[lang]] for k in ("kinematics", "forces", "dynamics") if k in parts]
    sep = "、" if lang == "zh" else ", "
    note.add(Heading(p("sec_intro", lang), 1, numbered=False),
             Para.of(p("intro", lang, mechanism_of(study.mechanism.name_in(lang), lang), sep.join(done))))


def conclusion(note, study, moments=None, flywheel=None, drive=None) -> None:
    """What was found: W and the class, H, θ and K, the extreme positions, the range of M_b,
    the flywheel and the motor."""
    from velplan.mechanism.structure import structure

    lang = note.lang
    st = structure(study.mechanism)
    note.add(Heading(p("sec_conclusion", lang), 1, numbered=False),
             Para.of(p("concl_structure", lang, st.mobility, roman(st.mechanism_class))))
    stroke = study.stroke
    if stroke is not None:
        sym = "H" if stroke.quantity.startswith(("slide", "point")) else r"\psi_{max}"
        unit = "м" if lang in ("ru", "uk") and sym == "H" else ("m" if sym == "H" else "rad")
        note.add(Para.of(p("concl_stroke", lang), Math(
            rf"{sym} = {txt(number(stroke.H, lang))}\ {txt(unit)},\ \theta = {txt(number(math.degrees(stroke.theta), lang))}"
            rf"^{{\circ}},\ K = {txt(number(stroke.K, lang))}"), "; ",
            p("concl_extremes", lang, *(number(math.degrees(e.phi) % 360.0, lang) for e in (stroke.start, stroke.end))),
            "."))
    nm = "Н·м" if lang in ("ru", "uk") else "N·m"
    if moments is not None:
        mb = np.asarray(moments, dtype=float)
        note.add(Para.of(p("concl_mb", lang), Math(
            rf"{txt(number(float(mb.min()), lang))} \le {balancing('M', lang)} \le {txt(number(float(mb.max()), lang))}\ {txt(nm)}"),
            "."))
    if flywheel is not None:
        kgm2 = "кг·м²" if lang in ("ru", "uk") else "kg·m²"
        note.add(Para.of(p("concl_flywheel", lang), Math(
            rf"J_{{I}} = {txt(number(flywheel.exact, lang))}\ {txt(kgm2)}\ (\delta = {txt(number(flywheel.delta, lang))})"),
            "."))
        if drive is not None and flywheel.added > 0 and abs(drive.ratio - 1.0) > 1e-9:
            note.add(Para.of(p("concl_motor", lang, motor_name(drive, lang), number(drive.motor.power_kw, lang),
                               number(drive.motor.nominal_rpm, lang)), Math(
                rf"J = {txt(number(flywheel.added / drive.ratio ** 2, lang))}\ {txt(kgm2)}\ "
                rf"(u = {txt(number(drive.ratio, lang))})"), "."))


def references(note) -> None:
    lang = note.lang
    note.add(Heading(p("sec_references", lang), 1, numbered=False))
    for k, ref in enumerate(REFERENCES[lang], 1):
        note.add(Para.of(f"{k}. {ref}"))
