"""Constraints on figures of merit, for ``velplan batch --require``:
``"K>=1.4, gamma_min>=40deg, H=0.25..0.35"``.

Names: ``H`` (m, or deg for a rocker: give ``H>=40deg``), ``K``, ``theta`` (deg),
``gamma_min`` (deg), ``v_max`` (m/s or rad/s), ``a_max`` (m/s² or rad/s²), ``Mb_max`` (N·m; a
file with loads or masses). Comparisons:
``>=``, ``<=``, ``>``, ``<`` and ``=LO..HI`` (both ends included). Numbers may carry ``mm``,
``m``, ``deg`` or ``°``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from velplan.errors import VelplanError

NAMES = {"H": "H", "K": "K", "theta": "theta_deg", "theta_deg": "theta_deg", "gamma_min": "gamma_min_deg",
         "gamma_min_deg": "gamma_min_deg", "v_max": "v_max", "a_max": "a_max", "Mb_max": "Mb_max"}
_UNIT = {"": 1.0, "m": 1.0, "mm": 1e-3, "deg": 1.0, "°": 1.0}
_PART = re.compile(r"\s*([A-Za-z_]+)\s*(>=|<=|>|<|=)\s*(.+?)\s*$")
_NUM = re.compile(r"\s*([-+0-9.eE]+)\s*(mm|m|deg|°)?\s*$")


@dataclass(frozen=True)
class Constraint:
    """``lo ≤ figure ≤ hi`` (strict where ``strict``): ``figure`` a name of `FIGURES`,
    ``degrees`` when the bound was given in degrees (an angular H is compared in deg)."""

    text: str
    figure: str
    lo: float = -math.inf
    hi: float = math.inf
    strict: bool = False
    degrees: bool = False

    def holds(self, value: np.ndarray) -> np.ndarray:
        """(V,) True where ``value`` meets the constraint (NaN never does)."""
        v = np.asarray(value, dtype=float)
        with np.errstate(invalid="ignore"):
            if self.strict:
                return (v > self.lo) & (v < self.hi)
            return (v >= self.lo) & (v <= self.hi)


def _number(text: str, item: str) -> tuple[float, bool]:
    m = _NUM.fullmatch(text)
    if not m:
        raise VelplanError(f"--require {item!r}: {text.strip()!r} is not a number (with mm, m, deg or °)")
    try:
        value = float(m.group(1)) * _UNIT[m.group(2) or ""]
    except ValueError:
        raise VelplanError(f"--require {item!r}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise VelplanError(f"--require {item!r}: {text.strip()!r} is not finite")
    return value, m.group(2) in ("deg", "°")


def parse_require(text: str) -> list[Constraint]:
    """The constraints of a ``--require`` text; one line naming the bad item otherwise."""
    out = []
    for item in (t for t in text.split(",") if t.strip()):
        m = _PART.fullmatch(item)
        if not m or m.group(1) not in NAMES:
            raise VelplanError(f"--require {item.strip()!r}: give NAME>=X, NAME<=X or NAME=LO..HI with NAME one of "
                               f"H, K, theta, gamma_min, v_max, a_max, Mb_max")
        name, op, rhs = NAMES[m.group(1)], m.group(2), m.group(3)
        if op == "=":
            lo_t, dots, hi_t = rhs.partition("..")
            if not dots:
                raise VelplanError(f"--require {item.strip()!r}: give a range LO..HI after '='")
            (lo, d1), (hi, d2) = _number(lo_t, item), _number(hi_t, item)
            if lo > hi:
                raise VelplanError(f"--require {item.strip()!r}: the range is empty ({lo:g} > {hi:g})")
            out.append(Constraint(item.strip(), name, lo, hi, False, d1 or d2))
            continue
        x, deg = _number(rhs, item)
        lo, hi = (x, math.inf) if op in (">=", ">") else (-math.inf, x)
        out.append(Constraint(item.strip(), name, lo, hi, op in (">", "<"), deg))
    if not out:
        raise VelplanError("--require: give at least one constraint, e.g. 'K>=1.4, gamma_min>=40deg'")
    return out


def check(figures: dict[str, np.ndarray], constraints: list[Constraint], *, angular: bool = False) -> list[str]:
    """Per variant: "" when it meets every constraint, else the first it breaks with its value.
    ``angular``: the output is a rocker, H is in rad (compared in degrees when so given)."""
    V = len(next(iter(figures.values())))
    out = [""] * V
    for c in constraints:
        if c.figure not in figures:
            why = "loads or masses" if c.figure == "Mb_max" else "output"
            raise VelplanError(f"--require {c.text!r}: the mechanism has no {why}, so no {c.figure}")
        value = np.asarray(figures[c.figure], dtype=float)
        if c.figure == "H" and angular and c.degrees:
            value = np.degrees(value)
        ok = c.holds(value)
        for i in np.flatnonzero(~ok):
            if not out[i]:
                out[i] = f"{c.text} (it is {value[i]:.6g})"
    return out
