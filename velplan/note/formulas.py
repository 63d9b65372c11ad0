"""TeX of the note's formulas: symbols with subscripts, numbers as the sheets print them."""

from __future__ import annotations

import re

from velplan.notation import MINUS, plain_digits, split_symbol

GREEK = {"ω": r"\omega", "ε": r"\varepsilon", "μ": r"\mu", "π": r"\pi", "Φ": r"\Phi", "φ": r"\varphi",
         "δ": r"\delta", "Δ": r"\Delta", "τ": r"\tau", "ψ": r"\psi", "θ": r"\theta"}
"""TeX of each Greek letter of the course's symbols (the note's formulas and its prose alike)."""
_MARKS = {"ⁿ": "n", "ᵗ": "t", "ᵏ": "k", "ʳ": "r", "τ": r"\tau", "n": "n", "t": "t", "⊥": r"\perp", "∥": r"\parallel"}


def txt(s: str) -> str:
    """A piece of text (a number as printed, a unit) inside a formula, upright."""
    s = plain_digits(s).replace("\\", "").replace("{", "").replace("}", "")
    s = re.sub(r"^-(?=\d)", MINUS, s)  # a negative number: the minus sign, not a hyphen
    return r"\text{" + s + "}"


def name(point: str) -> str:
    """A point or image name with its digits as a subscript: ``A4`` → ``A_{4}``, ``O2`` →
    ``O_{2}``, ``s4`` → ``s_{4}``, ``π`` → ``\\pi``."""
    point = plain_digits(point)
    head = re.match(r"^(\D*)(\d*)(.*)$", point)
    base, digits, rest = head.groups()
    base = "".join(GREEK.get(c, c) + (" " if c in GREEK and base.index(c) < len(base) - 1 else "")
                   for c in base)
    out = base + (f"_{{{digits}}}" if digits else "")
    return out + (name(rest) if rest else "")


def chain(points: str) -> str:
    """Several point names written together (``O3A``, ``A4O3``): each with its subscript."""
    parts = re.findall(r"[^\d]\d*", plain_digits(points))
    return "".join("{" + name(p) + "}" for p in parts)


def seg(a: str, b: str) -> str:
    """A segment of a plan, overlined: ``\\overline{pa_{4}}``."""
    return r"\overline{" + name(a) + " " + name(b) + "}"


def symbol(sym: str) -> str:
    """A component symbol of the plans (``V_A4A``, ``aⁿ_AO2``, ``aᵏ_A4A``, ``V_A``) in TeX."""
    head, _, sub = sym.partition("_")
    mark = ""
    if len(head) > 1 and head[1:] in _MARKS:
        head, mark = head[0], _MARKS[head[1:]]
    head = GREEK.get(head, head)
    out = head
    if mark:
        out += "^{" + mark + "}"
    if sub:
        out += "_{" + chain(sub) + "}"
    return out


def vec(sym: str) -> str:
    """A vector: the symbol overlined by an arrow."""
    return r"\vec{" + symbol(sym) + "}"


def link_rate(kind: str, link: str) -> str:
    """ω or ε of a link: ``\\omega_{4}``."""
    return (r"\omega" if kind == "v" else r"\varepsilon") + "_{" + link + "}"


def force(label: str) -> str:
    """A force label of the kinetostatics (``R05``, ``Φ4``, ``G5``, ``R12τ``, ``MΦ4``) in TeX."""
    found = split_symbol(label)
    if found and not found[1].isdigit() and not re.search(r"\d[τn⊥∥]$|^MΦ", label):  # a load: Fc, Fg5
        index = found[1] if found[1].isascii() else f"\\text{{{found[1]}}}"  # Cyrillic set upright
        return f"{GREEK.get(found[0], found[0])}_{{{index}}}"
    m = re.match(r"^(M?)([A-Za-zΦ]+?)(\d*)(τ|n|⊥|∥)?$", label)
    if not m:
        return txt(label)
    mom, base, digits, mark = m.groups()
    base = GREEK.get(base, base)
    head = ("M_{" + base + "_{" + digits + "}}") if mom else base
    out = head if mom else base + (f"_{{{digits}}}" if digits else "")
    if mark:
        out = "{" + out + "}^{" + _MARKS[mark] + "}"
    return out
