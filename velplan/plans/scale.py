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


DRAWABLE_MM = (5.0, 5000.0)
"""A drafted plan's longest vector must lie between these lengths, mm (and be at least four
drafting precisions long): shorter, its readings are drafting noise; longer, no sheet holds it."""


def check_scheme_scale(mu: float, size: float, what: str) -> float:
    """Refuse a user-given scheme scale ``mu`` (m/mm) that draws the mechanism, ``size`` m
    across, shorter or longer than `DRAWABLE_MM`: one line naming the option and the value."""
    mu = check_scale(mu, what)
    across = size / mu
    if not (DRAWABLE_MM[0] <= across <= DRAWABLE_MM[1]):
        raise ScaleError(f"{what} {mu:g} draws the mechanism ({size:.3g} m) {across:.3g} mm across, outside "
                         f"{DRAWABLE_MM[0]:g}…{DRAWABLE_MM[1]:g} mm: use {what} between "
                         f"{size / DRAWABLE_MM[1]:.3g} and {size / DRAWABLE_MM[0]:.3g} m/mm")
    return mu


def check_drawable(kin, sel, mu: float, kind: str, drafting) -> None:
    """Refuse to draft a plan at ``mu`` whose longest vector (positions ``sel``) is too short to
    read at the drafting precision or too long for any sheet (`DRAWABLE_MM`); exact plans pass."""
    if getattr(drafting, "exact", False):
        return
    largest = kin.largest(kind, sel)
    if not (math.isfinite(largest) and largest > 0):
        return
    symbol = "μv" if kind == "velocity" else "μa"
    longest = largest / mu
    low = max(DRAWABLE_MM[0], 4.0 * drafting.length_mm)
    if longest < low:
        raise ScaleError(f"{symbol} = {mu:g} draws the longest vector {longest:.3g} mm long, under {low:g} mm "
                         f"(drafting precision {drafting.length_mm:g} mm): its readings would be noise; "
                         f"use {symbol} ≤ {largest / low:.3g}")
    if longest > DRAWABLE_MM[1]:
        raise ScaleError(f"{symbol} = {mu:g} draws the longest vector {longest:.3g} mm long, over "
                         f"{DRAWABLE_MM[1]:g} mm: no sheet holds it; use {symbol} ≥ {largest / DRAWABLE_MM[1]:.3g}")
