"""Numbers of the sheets' tables as the note prints them: results to four significant figures
and powers of ten written as ·10ⁿ, never ``2e-12`` (ГОСТ 2.105; DRAWING.md)."""

from __future__ import annotations

import re

from velplan.notation import MINUS, minus, number, superscript

NUMBER = re.compile(r"(?P<sign>[-−]?)(?P<int>\d+)(?:[.,](?P<frac>\d+))?(?:e(?P<exp>[+-]?\d+))?")
SIGNIFICANT = 4


def tidy(cell: str, lang: str, significant: int = SIGNIFICANT) -> str:
    """``cell`` with each number cut to ``significant`` figures and each exponent as a power."""
    def one(m: re.Match) -> str:
        sign = MINUS if m.group("sign") else ""
        text = m.group("int") + (("." + m.group("frac")) if m.group("frac") else "")
        value = float(text)
        if m.group("exp"):
            exp = int(m.group("exp"))
            return f"{sign}{number(value, lang, 2)}·10{superscript(str(exp))}"
        digits = (m.group("int") + (m.group("frac") or "")).lstrip("0")
        if len(digits) <= significant:
            return minus(m.group(0)) if sign else m.group(0)
        return sign + number(value, lang, significant)

    return NUMBER.sub(one, cell)
