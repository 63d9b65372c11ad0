"""Zhukovsky's lever written out as the course writes it: the moment equation about the pole
with every force and its arm hᵢ read off the lever at the sheet's scale, the numbers
substituted, then F_b and M_b."""

from __future__ import annotations

from velplan.note.formulas import force, txt
from velplan.note.model import Equation, Para
from velplan.note.text import balancing, p
from velplan.notation import fixed, number as _num, unicode_text
from velplan.views.forces import force_text, newton
from velplan.views.forces.lever import lever_balance

TINY = 1e-9
"""Forces below this (N) or with an arm below this (mm) carry no moment and are left out."""


def lever_terms(fa, i: int, mu_v: float) -> tuple[list[tuple[str, float, float, float]], float, float]:
    """(label, F N, arm h mm, signed moment N·mm) of each force on the lever at position index
    ``i`` with the plan at ``mu_v`` ((m/s)/mm); the arm h_b (mm) of F_b and F_b (N, signed)."""
    _, lever = lever_balance(fa, mu_v)
    out = []
    for f in lever.forces:
        size, moment = abs(complex(f.vector[i])), float(f.moment[i])
        if size > TINY and abs(moment) > TINY * size:
            out.append((f.label, size, abs(moment) / size, moment))
    tip, e = complex(lever.tip_image[i]), complex(lever.direction[i])
    arm_b = abs(tip.real * e.imag - tip.imag * e.real)
    return out, arm_b, float(lever.balancing_force[i])


def _symbol(label_: str) -> str:
    if "@" in label_:
        couple, point = label_.split("@", 1)
        return rf"F_{{{force(couple)}}}^{{({point})}}"
    return force(label_)


def lines(first: str, terms: list[tuple[str, str]], per_line: int) -> str:
    """``first`` and the signed ``terms``, ``= 0``, broken after every ``per_line`` terms into
    the lines of an aligned formula (a long sum stays inside the text width)."""
    rows, row = [], first
    for n, (sign, term) in enumerate(terms):
        if n and n % per_line == 0:
            rows.append(row)
            row = ""
        row += f" {sign} {term}"
    rows.append(row + " = 0")
    if len(rows) == 1:
        return rows[0]
    return r"\begin{aligned} " + r" \\ ".join(rows) + r" \end{aligned}"


def lever_equations(note, fa, k: int, i: int, mu_v: float) -> int:
    """The table of forces and arms, the moment equation in symbols and in numbers, F_b and
    M_b; returns the number of force terms."""
    lang = note.lang
    terms, arm_b, fb = lever_terms(fa, i, mu_v)
    mm = "мм" if lang in ("ru", "uk") else "mm"
    rows = [[unicode_text(force_text(lab)), _num(size, lang), fixed(h, lang, 1), _num(moment, lang)]
            for lab, size, h, moment in terms]
    note.add(Para.of(p("lever_arms", lang, _num(mu_v, lang))))
    note.table(p("lever_table", lang, k), [p("quantity", lang), f"F, {newton(lang)}", f"h, {mm}",
                                           f"F·h, {newton(lang)}·{mm}"], rows, key=f"lever-{k}")
    total = sum(m for _, _, _, m in terms)
    sign_b = "-" if total > 0 else ""  # F_b balances the others: its moment is −Σ
    sym = [(("+" if m >= 0 else "-"), rf"{_symbol(lab)}\cdot h_{{{n + 1}}}") for n, (lab, _, _, m) in enumerate(terms)]
    num = [(("+" if m >= 0 else "-"), rf"{txt(_num(size, lang))}\cdot{txt(fixed(h, lang, 1))}")
           for lab, size, h, m in terms]

    note.add(Equation(lines(r"\sum M_{p} = " + rf"{sign_b}{balancing('F', lang)}\cdot h_{{b}}", sym, 5)))
    note.add(Equation(lines(rf"{sign_b}{balancing('F', lang)}\cdot{txt(fixed(arm_b, lang, 1))}", num, 4)))
    note.add(Equation(rf"{balancing('F', lang)} = \frac{{{txt(_num(abs(total), lang))}}}{{{txt(fixed(arm_b, lang, 1))}}} = "
                      rf"{txt(_num(abs(fb), lang))}\ {txt(newton(lang))}"))
    return len(terms)


__all__ = ["lever_equations", "lever_terms"]
