"""Prose with the course's typeset symbols: the sentences of the plans and of the note carry
symbols as the sheets print them in plain text (``V_A4``, ``aⁿ_AO2``, ``ω2``, ``O3A``,
``pa4``, ``μv``); here each becomes an inline formula, so no underscore and no letter with a
plain digit for its index reaches the page. ``$…$`` in a phrase is TeX already. The sentences
of the plans' steps mark their symbols themselves (`velplan.plans.text.Sym`): those are set
from the mark (`sym_tex`), not guessed from the text."""

from __future__ import annotations

import re

from velplan.notation import plain_digits
from velplan.note.blocks import Math
from velplan.note.formulas import GREEK, chain, symbol
from velplan.plans.text import Sentence, Sym

_NOT_WORD = r"A-Za-z0-9_"
TOKEN = re.compile(
    r"\$(?P<tex>[^$]+)\$"
    rf"|(?<![{_NOT_WORD}])(?P<sym>[A-Za-zΦΣ][ⁿᵗᵏʳτ]?_[A-Za-zА-Яа-яΦ0-9]+)(?P<sq>²?)"
    rf"|(?<![{_NOT_WORD}])μ(?P<mu>[vlaF])(?![{_NOT_WORD}])"
    rf"|(?<![{_NOT_WORD}])(?P<rate>[ωεφ])(?P<rate_i>[0-9₀-₉]+)(?![{_NOT_WORD}₀-₉])"
    rf"|(?<![{_NOT_WORD}])(?P<ext>[ψωφ])(?P<ext_i>max|min)(?![{_NOT_WORD}])"
    rf"|(?<![{_NOT_WORD}])(?P<greek>[θφδψωε])(?= = )"
    rf"|(?<![{_NOT_WORD}])(?P<pts>[A-Za-zπ][A-Za-zπ]*\d[A-Za-z0-9π]*)(?![{_NOT_WORD}])")
LETTERS = re.compile(rf"(?<![{_NOT_WORD}])(Δ?)([A-Za-z][A-Za-z₀-₉]*)(?![{_NOT_WORD}])")
INDEXED = re.compile(r"(?<![A-Za-z0-9_])([A-Za-z][A-Za-z₀-₉]*[₀-₉][A-Za-z₀-₉]*)"
                     r"|(?<!\w)()([A-Za-z][A-Za-z₀-₉]*)(?= = )")
"""A symbol with a subscript digit (lO₂A, JS₄, m₄, O₃): a symbol in every language; and in
en, where a word may be English, what stands left of " = " (lBF, Fc, H, n)."""
UNIT_AFTER_NUMBER = re.compile(r"(\d) (?=[^\W\d_]|[(%°])")
UNITS = frozenset({"m", "mm", "s", "N", "kg", "rad", "min", "rpm", "W", "kW", "J", "Hz", "deg"})
"""Units a zh note writes in Latin letters (ru/uk write theirs in Cyrillic)."""


def _symbol(sym: str) -> str:
    head, _, sub = sym.partition("_")
    if re.fullmatch(r"[А-Яа-я]+|[a-z]{3,}", sub):  # a word index (V_отн, V_rel, M_ур): upright text
        return symbol(head) + r"_{\text{" + sub + "}}"
    return symbol(sym)


def sym_tex(sym: Sym) -> str:
    """TeX of a symbol the plans' sentences mark (`velplan.plans.text.Sym`): point and image
    names italic with their digits as subscripts (``O3A`` → O₃A, ``pa4``, ``π``, ``x–x``), a
    vector's index below its letter (``V_A4A``, ``aⁿ_AO2``, ``V_отн``), ω or ε with its link."""
    if sym.kind == "vector":
        return _symbol(sym.text)
    if sym.kind == "rate":
        return GREEK[sym.text[0]] + "_{" + sym.text[1:] + "}"
    return "{–}".join(chain(part).replace("π", r"\pi ") for part in sym.text.split("–"))  # x–x: no spaces


def sentence_parts(piece, lang: str = "en") -> list:
    """A piece of a paragraph in plain pieces and `Math`: a sentence of the plans
    (`velplan.plans.text.Sentence`) keeps the symbols it marks, each a formula, and its
    plain text is read as `prose_parts` reads any text."""
    if isinstance(piece, Sym):
        return [Math(sym_tex(piece))]
    if isinstance(piece, Sentence):
        return [y for x in piece.parts for y in sentence_parts(x, lang)]
    return prose_parts(piece, lang)


def prose_parts(text: str, lang: str = "en") -> list:
    """``text`` split into plain pieces and `Math` for each symbol in it; in a ru/uk/zh note
    every other word of Latin letters is a symbol too (``p``, ``pa``, ``H``), a zh unit
    excepted."""
    out = []
    text = UNIT_AFTER_NUMBER.sub("\\1\u00a0", text)  # a number keeps its unit on its line
    for piece in _symbols(text):
        if isinstance(piece, Math):
            out.append(piece)
            continue
        at = 0
        for m in (INDEXED if lang == "en" else LETTERS).finditer(piece):
            if lang == "en":
                out += [x for x in (piece[at:m.start()], Math(_letters("", m.group(1) or m.group(3)))) if x]
                at = m.end()
                continue
            if (lang == "zh" and m.group(2) in UNITS) or re.fullmatch(r"[IVX]+", m.group(2)):
                continue  # a unit of a zh note, a Roman numeral (a class): plain upright text
            if m.start() > at:
                out.append(piece[at:m.start()])
            out.append(Math(_letters(m.group(1), m.group(2))))
            at = m.end()
        if at < len(piece):
            out.append(piece[at:])
    return out


def _letters(delta: str, word: str) -> str:
    """TeX of a word of Latin letters in a ru/uk/zh note: a symbol (``p``, ``pa``; ``JI`` →
    J_I, ``ΔTII`` → ΔT_II)."""
    roman = re.fullmatch(r"([A-Za-z])(I+)", word)
    if roman:
        tex = f"{roman.group(1)}_{{{roman.group(2)}}}"
    elif len(word) == 1:
        tex = word
    elif word[0].isupper() or word[0] in "lme" or re.fullmatch(r"[a-z][₀-₉]+", word):
        rest = plain_digits(word[1:])
        rest_letters = rest.lstrip("0123456789")
        digits = rest[:len(rest) - len(rest_letters)]
        tex = word[0] + "_{" + digits + (chain(rest_letters) if rest_letters else "") + "}"  # lO₂A, JS₄, m₄
    else:
        tex = chain(word)  # pa, bs₅: a segment of a plan, its letters side by side
    return (r"\Delta " if delta else "") + tex


def _symbols(text: str) -> list:
    out: list = []
    at = 0
    for m in TOKEN.finditer(text):
        if m.group("tex"):
            tex = m.group("tex")
        elif m.group("sym"):
            tex = _symbol(m.group("sym")) + ("^{2}" if m.group("sq") else "")
        elif m.group("mu"):
            tex = r"\mu_{" + m.group("mu") + "}"
        elif m.group("ext"):
            tex = GREEK[m.group("ext")] + "_{" + m.group("ext_i") + "}"  # as the note's formulas: ψ_{max}
        elif m.group("greek"):  # θ = 1,564°: the symbol as in the formulas
            tex = GREEK[m.group("greek")]
        elif m.group("rate"):
            tex = GREEK[m.group("rate")] + "_{" + plain_digits(m.group("rate_i")) + "}"
        else:
            tex = chain(m.group("pts")).replace("π", r"\pi ")
        if m.start() > at:
            out.append(text[at:m.start()])
        out.append(Math(tex))
        at = m.end()
    if at < len(text):
        out.append(text[at:])
    return out
