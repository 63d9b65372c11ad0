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
    feasible(out)
    return out


RANGES = {"K": (1.0, math.inf, False, "K = (180° + θ)/(180° − θ) is at least 1"),
          "theta_deg": (0.0, 180.0, True, "θ lies in 0° ≤ θ < 180°"),
          "gamma_min_deg": (0.0, 90.0, False, "a transmission angle lies in 0°…90°"),
          "H": (0.0, math.inf, False, "a stroke is ≥ 0"), "v_max": (0.0, math.inf, False, "a peak |v| is ≥ 0"),
          "a_max": (0.0, math.inf, False, "a peak |a| is ≥ 0"), "Mb_max": (0.0, math.inf, False, "a peak |M_b| is ≥ 0")}
"""Every value a figure can take: (lowest, highest, the highest excluded, why)."""


def feasible(constraints: list[Constraint]) -> None:
    """Refuse, naming them, constraints no value can meet: one outside the figure's range
    (`RANGES`: ``K<=0``, ``theta>=400deg``) or two on one figure that exclude each other
    (``K>=1, K<=0.5``); a stroke in degrees and one in metres are not compared."""
    bounds: dict = {}
    for c in constraints:
        lo0, hi0, open_hi, why = RANGES[c.figure]
        key = (c.figure, c.degrees and c.figure == "H")
        lo, lo_open, lo_by, hi, hi_open, hi_by = bounds.get(key, (lo0, False, None, hi0, open_hi, None))
        if c.lo > lo or (c.lo == lo and c.strict):
            lo, lo_open, lo_by = c.lo, c.strict, c
        if c.hi < hi or (c.hi == hi and c.strict):
            hi, hi_open, hi_by = c.hi, c.strict, c
        if lo > hi or (lo == hi and (lo_open or hi_open)):
            both = [x.text for x in (lo_by, hi_by) if x is not None]
            if len(both) == 2 and both[0] != both[1]:
                raise VelplanError(f"--require {both[0]!r} and {both[1]!r}: no value of {c.figure} meets both")
            raise VelplanError(f"--require {c.text!r}: no variant can meet it ({why})")
        bounds[key] = (lo, lo_open, lo_by, hi, hi_open, hi_by)


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
