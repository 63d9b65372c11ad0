"""The reduction worked out in the note: the reduced inertia and moment at one position with
every term and its numbers, then the tables by position (J_II, M_c, the works and the
energies ΔT and ΔT_I), and the flywheel on the crank shaft and, where the drive's ratio is
known, on the faster shaft."""

from __future__ import annotations

import math

import numpy as np

from velplan.note.formulas import txt
from velplan.note.model import Equation, Para
from velplan.note.text import p
from velplan.notation import fixed, number
from velplan.views.dynamics import constant_moment


def travels(d, phi) -> np.ndarray:
    """Crank travel θ from position 1 of each crank angle ``phi``, rad."""
    red = d.reducer
    return np.mod(red.sense * (np.asarray(phi, dtype=float) - red.phi1), 2 * np.pi)


def _fw(lang: str) -> str:
    """Subscript of the flywheel: fw in en, м (маховик) in ru/uk, F in zh."""
    return {"ru": r"\text{м}", "uk": r"\text{м}"}.get(lang, "fw" if lang == "en" else "F")


def flywheel_shafts(note, d) -> None:
    """The flywheel to add on the crank shaft and, where the drive's ratio is known (the
    chosen motor's, or the flywheel shaft's), on the faster shaft, with the recommendation."""
    lang, fly = note.lang, d.flywheel
    kgm2 = txt("кг·м²" if lang in ("ru", "uk") else "kg·m²")
    fw = _fw(lang)
    note.add(Equation(rf"J_{{{fw}}} = J_{{I}} - J_{{0}} = {txt(number(fly.exact, lang))} - "
                      rf"{txt(number(fly.declared, lang))} = {txt(number(fly.added, lang))}\ {kgm2}"))
    if fly.added <= 0:
        note.add(Para.of(p("fly_none", lang)))
        return
    drive = drive_of(d)
    u = drive.ratio if drive is not None else fly.ratio
    if abs(u - 1.0) <= 1e-9:
        note.add(Para.of(p("fly_crank_only", lang)))
        return
    if drive is not None:
        note.add(Para.of(p("fly_motor" if d.drive is not None else "fly_motor_default", lang, motor_name(drive, lang),
                           number(drive.motor.power_kw, lang), number(drive.motor.nominal_rpm, lang),
                           number(drive.required / 1000.0, lang, 3))))
    note.add(Para.of(p("fly_shaft", lang, number(u, lang))),
             Equation(rf"J_{{{fw}}}' = \frac{{J_{{{fw}}}}}{{u^{{2}}}} = \frac{{{txt(number(fly.added, lang))}}}"
                      rf"{{{txt(number(u, lang))}^{{2}}}} = {txt(number(fly.added / u ** 2, lang))}\ {kgm2}"),
             Para.of(p("fly_recommend", lang, number(u ** 2, lang, 3))))


def motor_name(drive, lang: str) -> str:
    """The motor's designation, upright (``АИР100L4`` in ru/uk: the series' own letters)."""
    name = drive.motor.name
    if lang in ("ru", "uk") and name.startswith("AIR"):
        name = "АИР" + name[3:]
    return "$\\text{" + name + "}$"


def drive_of(d):
    """The drive the file declares, else the one velplan's default rules choose for the useful
    power (`velplan.dynamics.drive.select_drive`); None where none can be chosen (no loads,
    no crank speed)."""
    from velplan.dynamics.drive import select_drive
    from velplan.errors import VelplanError

    try:
        return d.drive or select_drive(d)
    except VelplanError:
        return None


def worked_position(note, d, k: int) -> None:
    """J_II and the reduced moments at position number ``k`` of the dynamics' table, every
    term substituted."""
    lang, crank = note.lang, d.mechanism.crank.link
    phi = math.radians(float(d.table(12)["phi_deg"][k - 1]))
    terms = d.reducer.inertia_terms(phi)
    red = d.reducer(travels(d, [phi]))
    note.add(Para.of(p("dyn_worked", lang, k, fixed(math.degrees(phi) % 360.0, lang, 1))))
    terms_tex = [(rf"m_{{{link}}}\left(\frac{{V_{{S_{{{link}}}}}}}{{\omega_{{{crank}}}}}\right)^{{2}}" if kind == "m"
                      else rf"J_{{S_{{{link}}}}}\left(\frac{{\omega_{{{link}}}}}{{\omega_{{{crank}}}}}\right)^{{2}}")
                     for kind, link, _, _ in terms]
    rows = [" + ".join(terms_tex[n:n + 3]) for n in range(0, len(terms_tex), 3)] or ["0"]
    sym = rows[0] if len(rows) == 1 else (r"\begin{aligned} " + r" \\ + ".join(rows) + r" \end{aligned}")
    num = " + ".join(rf"{txt(number(f, lang))}\cdot{txt(number(math.sqrt(a2), lang))}^{{2}}" for _, _, f, a2 in terms)
    kgm2 = txt("кг·м²" if lang in ("ru", "uk") else "kg·m²")
    note.add(Equation(rf"J_{{II}} = {sym}"),
             Equation(rf"J_{{II}} = {num or '0'} = {txt(number(float(red.J[0]), lang))}\ {kgm2}"))
    nm = txt("Н·м" if lang in ("ru", "uk") else "N·m")
    parts = [(name, float(v[0])) for name, v in red.moments.items()]
    if parts:
        note.add(Para.of(p("dyn_worked_m", lang, crank)))
        values = "".join((" - " if v < 0 else (" + " if k else "")) + txt(number(abs(v), lang))
                         for k, (_, v) in enumerate(parts)).strip()
        total = float(red.resisting[0])
        own = r"M_{c}" if constant_moment(d, "en")[0] == "driving_moment" else r"M_{d}"  # an engine's loads drive
        note.add(Equation(own + " = " + " + ".join(rf"M_{{{_load(name, lang)}}}" for name, _ in parts)
                          + " = " + values + rf" = {'-' if total < 0 else ''}{txt(number(abs(total), lang))}\ {nm}"))


def _load(name: str, lang: str) -> str:
    return {"gravity": r"G"}.get(name, r"\text{" + name.replace("_", " ") + "}")


def by_position_tables(note, d) -> None:
    """J_red, M_red, M_d; the works A_d, A_c and the energies ΔT, ΔT_II, ΔT_I at the
    positions of the dynamics' table (`Dynamics.table`, as the sheet)."""
    lang = note.lang
    tab = d.table(12)
    fly = d.flywheel
    wm = fly.omega_mean if fly is not None else d.omega_mean
    works = tab.get("A_sum", tab["A_resist"])
    t2 = (tab["J_red"] - tab["J_red"][0]) * wm ** 2 / 2.0
    t1 = works - t2
    pos = [str(j + 1) for j in range(len(works))]
    nm, jj = ("Н·м", "Дж") if lang in ("ru", "uk") else ("N·m", "J")
    kgm2 = "кг·м²" if lang in ("ru", "uk") else "kg·m²"

    def col(x, digits=4):
        top = max(1.0, float(np.max(np.abs(x))))
        return [number(float(v), lang, digits) if abs(v) > 1e-9 * top else "0" for v in x]

    note.add(Para.of(p("dyn_tables", lang)))
    _, drv, res = constant_moment(d, lang)  # an engine's constant moment resists: Mс, its loads' Mд
    note.table(p("dyn_table_j", lang), [label_pos(lang), "φ, °", f"J, {kgm2}", f"M{res}, {nm}", f"M{drv}, {nm}"],
               list(zip(pos, [fixed(v, lang, 1) for v in tab["phi_deg"]], col(tab["J_red"]), col(tab["M_red"]),
                        col(tab["M_drive"]))), key="dynamics-reduced")
    note.table(p("dyn_table_t", lang), [label_pos(lang), f"A{drv}, {jj}", f"A{res}, {jj}", f"ΔT, {jj}", f"ΔTII, {jj}",
                                         f"ΔTI, {jj}"],
               list(zip(pos, col(tab.get("A_drive", np.zeros_like(works))), col(tab["A_resist"]), col(works),
                        col(t2), col(t1))), key="dynamics-works")
    return t1


def label_pos(lang: str) -> str:
    from velplan.render.i18n import label

    return label("position_short", lang)
