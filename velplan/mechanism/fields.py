"""The checks of a mechanism file's values shared by its two forms (the explicit tables,
`velplan.mechanism.loader`, and the joints as drawn, `velplan.mechanism.drawn`): each refuses a
bad value in one line naming it.

>>> finite(2, "crank length")
2.0
>>> finite(True, "crank length")
Traceback (most recent call last):
...
velplan.errors.MechanismError: crank length must be a number, not True
"""

from __future__ import annotations

import math
from typing import Any

from velplan.errors import MechanismError

MAGNITUDE = 1e9
"""Largest magnitude of any number in a mechanism file (m, rad/s, rpm, kg, kg·m², °): beyond it
products of lengths, speeds and masses leave double precision."""


def finite(v: Any, what: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise MechanismError(f"{what} must be a number, not {v!r}")
    v = float(v)
    if not math.isfinite(v):
        raise MechanismError(f"{what} must be finite, not {v}")
    if abs(v) > MAGNITUDE:
        raise MechanismError(f"{what} = {v:g} is out of range (at most {MAGNITUDE:g} in magnitude)")
    return v


def no_unknown(t: dict, allowed: set[str], where: str) -> None:
    extra = sorted(set(t) - allowed)
    if extra:
        raise MechanismError(f"{where}: unknown key {extra[0]!r}; allowed: {', '.join(sorted(allowed))}")


def optional_name(t: dict, key: str) -> str | None:
    v = t.get(key)
    return None if v in (None, "") else str(v)


def fresh_name(stem: str, taken: set[str]) -> str:
    """``stem``, or ``stem`` with the first number from 2 that makes it none of ``taken``."""
    name, k = stem, 1
    while name in taken:
        k += 1
        name = f"{stem}{k}"
    return name


def degrees_of(angle: float) -> float:
    """An angle in degrees in (−180, 180]."""
    d = math.degrees(math.remainder(angle, 2 * math.pi))
    return 180.0 if d == -180.0 else d
