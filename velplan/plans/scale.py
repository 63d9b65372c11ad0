"""Drawing scales from the standard series (1, 2, 2.5, 4, 5) × 10ⁿ."""

from __future__ import annotations

import math

from velplan.errors import ScaleError

SERIES = (1.0, 2.0, 2.5, 4.0, 5.0)


def standard_scale(raw: float) -> float:
    """The smallest standard scale value ≥ ``raw`` (units per mm), so that a quantity of size
    ``raw × L`` fits in L mm."""
    if not (math.isfinite(raw) and raw > 0):
        raise ScaleError(f"cannot choose a scale for a largest value per mm of {raw}")
    e = math.floor(math.log10(raw))
    for exp in (e, e + 1):
        for m in SERIES:
            value = float(f"{m}e{exp}")
            if value >= raw * (1 - 1e-12):
                return value
    raise AssertionError("unreachable")


def check_scale(mu: float, what: str) -> float:
    """Validate a user-given scale (units per mm)."""
    if not (isinstance(mu, (int, float)) and math.isfinite(mu) and mu > 0):
        raise ScaleError(f"{what} must be a positive number of units per mm, not {mu!r}")
    return float(mu)
