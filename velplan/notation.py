"""The course's notation in text, one place for every output (sheets, step and centres
figures, tables, the answer key, the note, the terminal): digits as Unicode subscripts and
superscripts and back, the minus sign, the decimal sign of each language, indices marked
``_{…}``/``^{…}`` for the drawings, and numbers to significant figures.

It sits at the bottom layer (beside `velplan.errors` and `velplan.options`) and imports
nothing of the package, so that the drawing primitives (`velplan.render`), the plans'
sentences (`velplan.plans`) and everything above them write one notation.

>>> subscript("O2"), digits_down("ω2"), plain_digits("VA₄"), superscript("-14")
('O₂', 'ω₂', 'VA4', '⁻¹⁴')
>>> number(-0.0017186, "ru", 3), number(1.25e-14, "en"), unicode_text("v_{A4}, 10^{-5}")
('−0,00172', '1.25·10⁻¹⁴', 'vA₄, 10⁻⁵')
"""

from __future__ import annotations

import math
import re

from velplan.options import Language

DIGITS = "0123456789"
SUBSCRIPT_DIGITS = "₀₁₂₃₄₅₆₇₈₉"
"""The digits below the line, in the order of `DIGITS`."""
SUPERSCRIPT_DIGITS = "⁰¹²³⁴⁵⁶⁷⁸⁹"
"""The digits above the line, in the order of `DIGITS`."""
MINUS = "\u2212"
"""The minus sign of printed numbers ("−", not the hyphen "-")."""

_DOWN = str.maketrans(DIGITS, SUBSCRIPT_DIGITS)
_PLAIN = str.maketrans(SUBSCRIPT_DIGITS, DIGITS)
_UP = str.maketrans(DIGITS + "-" + MINUS + "+", SUPERSCRIPT_DIGITS + "⁻⁻⁺")


def digits_down(text: str) -> str:
    """Every digit as a subscript: ``"2"`` → ``"₂"`` (ω₂, μ₁)."""
    return text.translate(_DOWN)


def plain_digits(text: str) -> str:
    """Every subscript digit as a plain digit (``"R₀₄"`` → ``"R04"``): the inverse of
    `digits_down`."""
    return text.translate(_PLAIN)


def subscript(name: str) -> str:
    """Trailing digits of a point name as subscripts: ``"O2"`` → ``"O₂"``, ``"a4"`` → ``"a₄"``;
    a name of digits only stays as it is.

    >>> subscript("K3"), subscript("AB"), subscript("12")
    ('K₃', 'AB', '12')
    """
    head = name.rstrip(DIGITS)
    return head + name[len(head):].translate(_DOWN) if head else name


def superscript(text: str) -> str:
    """Digits and signs (hyphen, minus, plus) above the line, as a power is written: ``"-5"``
    → ``"⁻⁵"``."""
    return text.translate(_UP)


def minus(text: str) -> str:
    """Every hyphen of a number's text as the minus sign: ``"-0.5"`` → ``"−0.5"``."""
    return text.replace("-", MINUS)


def decimal(text: str, lang: Language) -> str:
    """A number's text with the decimal sign of `lang`: a comma in ru and uk, a point otherwise.

    >>> decimal("1:2.5", "uk"), decimal("1:2.5", "zh")
    ('1:2,5', '1:2.5')
    """
    return text.replace(".", ",") if lang in ("ru", "uk") else text


def localized(text: str, lang: Language) -> str:
    """A number's text as `lang` prints it: the minus sign and the decimal sign of `lang`.

    >>> localized("-1.5e-3", "ru")
    '−1,5e−3'
    """
    return decimal(minus(text), lang)


# -- indices marked for the drawings --------------------------------------------------------

MARKED_INDEX = re.compile(r"([_^])\{([^{}]*)\}")
"""A whole index written out: ``v_{BA}`` is v with the subscript "BA" (letters have no
Unicode subscript forms), ``10^{−12}`` ten with the superscript "−12"; digits and
superscripts outside the marks stay as in the rest of the text."""


def indexed(base: str, index: str, marked: bool = True) -> str:
    """A symbol with its index below the line: ``indexed("ω", "max")`` → ``"ω_{max}"`` (the
    ``_{…}`` mark the drawings set as a subscript); ``marked=False`` writes ``"ωmax"`` (for text
    that is not drawn)."""
    return f"{base}_{{{index}}}" if marked and index else f"{base}{index}"


def plain_text(text: str) -> str:
    """`text` without the ``_{…}``, ``^{…}`` marks of whole indices (``v_{BA}`` → ``vBA``):
    what a backend that draws one plain string writes."""
    return MARKED_INDEX.sub(lambda m: m.group(2), text)


def unicode_text(text: str) -> str:
    """`text` for plain text (a note, a page): a marked superscript in Unicode superscripts
    (``10^{−12}`` → ``10⁻¹²``), a marked subscript's digits as subscripts (``ω_{m}`` → ``ωm``,
    ``v_{A4}`` → ``vA₄``)."""
    return MARKED_INDEX.sub(lambda m: superscript(m.group(2)) if m.group(1) == "^" else digits_down(m.group(2)),
                            text)


# -- numbers ---------------------------------------------------------------------------------

#: Magnitudes below the first or from the second are written with a power of ten (·10⁻⁵).
POWER_BELOW, POWER_FROM = 1e-4, 1e7

ROUND_OFF = 1e-10
"""A value within this fraction of its quantity's scale is zero to round-off (a driving
moment of a cycle whose loads do no work: 7.97·10⁻¹⁶ N·m beside moments of 8 N·m)."""


def significant(x: float, digits: int) -> str:
    """`x` to `digits` significant figures in positional notation, trailing zeros dropped; the
    digits before the point are all kept (never rounded to zeros).

    >>> significant(0.0017186, 3), significant(1234.5, 2), significant(-0.00001, 1)
    ('0.00172', '1234', '-0.00001')
    """
    if x == 0:
        return "0"
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(x))))
    text = f"{x:.{decimals}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def power_of_ten(x: float, lang: Language, digits: int = 4) -> str:
    """`x` as mantissa·10ⁿ (``"1,25·10⁻¹⁴"``; ``"10⁻⁵"`` for a mantissa of 1), `digits`
    significant figures in the mantissa."""
    if not math.isfinite(x) or x == 0:
        return number(x, lang, digits)
    k = math.floor(math.log10(abs(x)))
    mantissa = float(f"{x / 10.0**k:.{digits - 1}f}")
    if abs(mantissa) >= 10.0:
        mantissa, k = mantissa / 10.0, k + 1
    power = "10" + superscript(str(k))
    if abs(mantissa) == 1.0:
        return (MINUS if mantissa < 0 else "") + power
    return localized(significant(mantissa, digits), lang) + "·" + power


def number(x: float, lang: Language, digits: int = 4, scale: float | None = None) -> str:
    """`x` to `digits` significant figures, decimal comma in ru and uk, the minus sign "−";
    a power of ten (`power_of_ten`) below `POWER_BELOW` or from `POWER_FROM`, never "e-14".
    ``scale``: the magnitude of the quantity (its largest value over the cycle); an `x`
    within `ROUND_OFF` of it prints as 0.

    >>> number(7.97e-16, "ru", 5, scale=8.5), number(7.97e-16, "ru", 5), number(0.5, "en", scale=8.5)
    ('0', '7,97·10⁻¹⁶', '0.5')
    """
    if not math.isfinite(x):
        return "—"
    if scale is not None and abs(x) <= ROUND_OFF * abs(scale):
        x = 0.0
    if x != 0 and not POWER_BELOW <= abs(float(f"{x:.{digits}g}")) < POWER_FROM:
        return power_of_ten(x, lang, digits)
    return localized(significant(x, digits), lang)


def fixed(x: float, lang: Language, decimals: int = 3) -> str:
    """`x` with a fixed number of decimals (a table cell), decimal comma in ru and uk, "−".

    >>> fixed(-0.0004, "ru"), fixed(1.5, "en", 2)
    ('0,000', '1.50')
    """
    if not math.isfinite(x):
        return "—"
    text = f"{x:.{decimals}f}"
    if float(text) == 0:
        text = f"{0:.{decimals}f}"
    return localized(text, lang)


# -- symbols written on one line ------------------------------------------------------------

SYMBOL = re.compile(r"^(?P<delta>Δ?)(?P<head>[A-Za-zΦωεφψ])(?P<index>[A-Za-zА-Яа-яΦ0-9₀-₉]+)$")
"""A symbol and its index, one word: a Latin or Greek letter, then what is written below it."""
LOWER_HEADS = frozenset("avlm")
"""Lowercase letters that head a symbol (a, v, l, m: accelerations, velocities, lengths, masses)."""
WORD_INDICES = frozenset({"c", "d", "m", "max", "min", "ср"})
"""Lowercase Latin indices of the course's symbols (Mc, Md, ωm, ωmax)."""


def split_symbol(word: str) -> tuple[str, str] | None:
    """(the symbol with its marks, its index) of a word the tables write as a symbol, else None.

    >>> split_symbol("VA₄"), split_symbol("ω2"), split_symbol("Mд"), split_symbol("ΔTII")
    (('V', 'A4'), ('ω', '2'), ('M', 'д'), ('ΔT', 'II'))
    >>> split_symbol("Value"), split_symbol("II"), split_symbol("at"), split_symbol("0,25"), split_symbol("RPR")
    (None, None, None, None, None)
    """
    m = SYMBOL.match(word)
    if not m or re.fullmatch(r"[IVX]+|[RP]{3}", word):  # a Roman numeral, a dyad's kind (RPR)
        return None
    head, index = m.group("head"), m.group("index")
    if head.islower() and head.isascii() and head not in LOWER_HEADS:
        return None
    digits = any(c.isdigit() for c in index)
    cyrillic = bool(re.fullmatch(r"[А-Яа-яЁё]{1,3}", index))
    capitals = plain_digits(index).strip("0123456789").isupper() or index.strip("Φ") == ""
    if not (digits or cyrillic or capitals or index in WORD_INDICES):
        return None
    if head.isascii() and head.islower() and not (digits or capitals):
        return None
    return m.group("delta") + head, plain_digits(index)


_COMPONENT = re.compile(r"^(?P<head>[A-Za-zΦ]+?)(?P<index>\d+)(?P<mark>[τn⊥∥])$")
"""A reaction's component: its mark (τ, n, ⊥, ∥) after the pair's index (``R12τ``)."""
_COUPLE = re.compile(r"^M(?P<index>Φ\d+)$")
"""The moment of a link's inertia couple (``MΦ4``)."""


def force_text(name: str) -> str:
    """A force's label as drawn, in the note's notation: the pair's index below the line and a
    component's mark above it (``"R12τ"`` → ``"R_{12}^{τ}"``, R₁₂ with τ raised), an inertia
    couple's moment with its force's name below (``"MΦ4"`` → ``"M_{Φ4}"``), other digits as
    subscripts (``"G4"`` → ``"G₄"``), a load's name as the note reads it (``"Fc"`` → ``"F_{c}"``,
    `velplan.notation.split_symbol`); the force of the pair replacing a couple on the lever
    (``"MΦ4@B"``) → ``"F(M_{Φ4})"``. `unicode_text` gives it back on one line (R₁₂τ, MΦ₄).

    >>> force_text("R12τ"), force_text("R45n"), force_text("MΦ4@B"), force_text("Fc"), force_text("G4")
    ('R_{12}^{τ}', 'R_{45}^{n}', 'F(M_{Φ4})', 'F_{c}', 'G₄')
    """
    if "@" in name:
        return f"F({force_text(name.split('@', 1)[0])})"
    if m := _COMPONENT.match(name):
        return f"{m['head']}_{{{m['index']}}}^{{{m['mark']}}}"
    if m := _COUPLE.match(name):
        return f"M_{{{m['index']}}}"
    if (found := split_symbol(name)) and not found[1].isdigit():  # a load's name: Fc → F_{c}, Fg5 → F_{g5}
        return f"{found[0]}_{{{found[1]}}}"
    return digits_down(name)
