"""The flywheel for a required coefficient of speed fluctuation δ, by three methods, and its
dimensions.

With A(θ) the total work from position 1, J(θ) the variable part of the reduced inertia and
k± = ½·ω_m²·(1 ± δ/2)²:

* exact (energy–mass envelope): J_I = (max(A − k₊J) − min(A − k₋J))/(k₊ − k₋);
* Wittenbauer: the ΔT–J curve drawn at scales μ_J, μ_T, tangents at tan ψ± = (μ_J/μ_T)·k±;
  the segment kl they cut on the ΔT axis gives J_I = μ_T·kl/(ω_m²·δ) — since k₊ − k₋ = ω_m²δ
  exactly, the same value as the exact method when kl is computed, and a drafting error when
  kl is read off the drawing;
* Mertsalov (approximate): ΔT_I ≈ A − ½ω_m²(J − J(0)), J_I = (max − min)ΔT_I/(δ·ω_m²).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from velplan.dynamics.spec import FlywheelSpec
from velplan.dynamics.steady import EnergyCurve, Target, extremes
from velplan.errors import VelplanError

NICE = (1.0, 2.0, 2.5, 4.0, 5.0, 10.0)


def nice_scale(x: float) -> float:
    """The smallest 1, 2, 2.5, 4, 5 × 10ᵏ ≥ x (x > 0)."""
    if not x > 0:
        return 1.0
    e = math.floor(math.log10(x))
    for m in NICE:
        s = m * 10.0**e
        if s >= x * (1 - 1e-12):
            return s
    return 10.0 ** (e + 1)


@dataclass(frozen=True)
class Wittenbauer:
    """Wittenbauer's energy–mass diagram as data (lengths in mm on the drawing).

    Attributes
    ----------
    mu_J : float
        kg·m² per mm (abscissa J, from J = 0).
    mu_T : float
        J per mm (ordinate ΔT = A).
    psi_max_deg, psi_min_deg : float
        Tangent angles to the J axis, tan ψ = (μ_J/μ_T)·k±.
    touch_max, touch_min : tuple of float
        Tangent points (J, ΔT) in kg·m², J, and the travels there (rad): (J, ΔT, θ).
    intercept_max, intercept_min : float
        Where the tangents cut the ΔT axis, J.
    segment_mm : float
        kl = (intercept_max − intercept_min)/μ_T, mm (computed).
    segment_drawn_mm : float
        kl read off the drawing at ``precision`` mm.
    inertia : float
        J_I from the computed tangents, kg·m².
    inertia_drawn : float
        J_I from the drawn segment, kg·m².
    precision : float
        Drafting precision, mm.
    """

    mu_J: float
    mu_T: float
    psi_max_deg: float
    psi_min_deg: float
    touch_max: tuple
    touch_min: tuple
    intercept_max: float
    intercept_min: float
    segment_mm: float
    segment_drawn_mm: float
    inertia: float
    inertia_drawn: float
    precision: float


@dataclass(frozen=True)
class FlywheelDimensions:
    """A disc (D, b) or a rim (D mean, D₁ inner, D₂ outer, b) of density ρ, rounded up to
    whole mm, and the inertia and mass of those dimensions."""

    shape: str
    diameter: float
    width: float
    inner: float
    outer: float
    density: float
    mass: float
    inertia: float
    required: float


@dataclass(frozen=True)
class Flywheel:
    """The flywheel by three methods.

    Attributes
    ----------
    delta, omega_mean : float
    exact, mertsalov, wittenbauer : float
        Constant inertia J_I each requires, reduced to the crank, kg·m².
    declared : float
        The constant inertias already present (crank, [[dynamics.inertia]]), reduced, kg·m².
    added : float
        exact − declared (≤ 0: none needed), reduced to the crank, kg·m².
    ratio : float
        Speed of the flywheel's shaft over the crank's.
    on_shaft : float
        added / ratio², kg·m².
    diagram : Wittenbauer
    dimensions : FlywheelDimensions or None
        None when no flywheel is needed.
    errors : dict
        Estimated errors of ``"exact"``, ``"mertsalov"``, ``"wittenbauer"`` (computed), kg·m².
    """

    delta: float
    omega_mean: float
    exact: float
    mertsalov: float
    wittenbauer: float
    declared: float
    added: float
    ratio: float
    on_shaft: float
    diagram: Wittenbauer
    dimensions: FlywheelDimensions | None
    errors: dict = field(default_factory=dict)
    found: tuple = field(default=(), repr=False)

    @property
    def mertsalov_difference(self) -> float:
        """(Mertsalov − exact)/exact."""
        return (self.mertsalov - self.exact) / self.exact


def _ks(omega_mean: float, delta: float) -> tuple[float, float]:
    return 0.5 * omega_mean**2 * (1 + delta / 2) ** 2, 0.5 * omega_mean**2 * (1 - delta / 2) ** 2


def _found(c: EnergyCurve, omega_mean: float, delta: float) -> list[tuple[float, float]]:
    """The four extremes the three methods need, found together: max of A − k₊J, min of
    A − k₋J, max and min of A − k(J − J(0)) with k = ½ω_m²."""
    kp, km = _ks(omega_mean, delta)
    k = 0.5 * omega_mean**2
    A, J = c.on_grid
    j0 = float(c.J(np.array([0.0]))[0])
    me = A - k * (J - j0)
    return extremes(c, [Target(A - kp * J, "max", k=kp), Target(A - km * J, "min", k=km),
                        Target(me, "max", k * j0, k), Target(me, "min", k * j0, k)])


def envelope(c: EnergyCurve, omega_mean: float, delta: float, found=None):
    """((θ₊, c₊), (θ₋, c₋), k₊, k₋): max of A − k₊J and min of A − k₋J."""
    found = found or _found(c, omega_mean, delta)
    kp, km = _ks(omega_mean, delta)
    return found[0], found[1], kp, km


def exact_inertia(c: EnergyCurve, omega_mean: float, delta: float, found=None) -> float:
    """J_I by the energy–mass envelope, kg·m²."""
    (_, cp), (_, cm), kp, km = envelope(c, omega_mean, delta, found)
    return (cp - cm) / (kp - km)


def mertsalov_inertia(c: EnergyCurve, omega_mean: float, delta: float, found=None) -> float:
    """J_I by Mertsalov's approximation, kg·m²."""
    found = found or _found(c, omega_mean, delta)
    return (found[2][1] - found[3][1]) / (delta * omega_mean**2)


def wittenbauer(c: EnergyCurve, omega_mean: float, delta: float, *, size_mm: float = 150.0,
                precision: float = 0.5, mu_J: float | None = None, mu_T: float | None = None,
                found=None) -> Wittenbauer:
    """Wittenbauer's diagram at scales fitting the curve in ``size_mm`` (or given), its
    tangents and the segment they cut, computed and read at ``precision`` mm."""
    A, J = c.on_grid
    mu_J = mu_J or nice_scale(float(J.max()) / size_mm)
    mu_T = mu_T or nice_scale(float(A.max() - A.min()) / size_mm)
    (tp, cp), (tm, cm), kp, km = envelope(c, omega_mean, delta, found)
    w2d = omega_mean**2 * delta
    seg = (cp - cm) / mu_T
    drawn = round(seg / precision) * precision
    touch = lambda t: (float(c.J(np.array([t]))[0]), float(c.A(np.array([t]))[0]), t)  # noqa: E731
    return Wittenbauer(mu_J, mu_T, math.degrees(math.atan(mu_J / mu_T * kp)), math.degrees(math.atan(mu_J / mu_T * km)),
                       touch(tp), touch(tm), cp, cm, seg, drawn, mu_T * seg / w2d, mu_T * drawn / w2d, precision)


def dimensions(inertia: float, spec: FlywheelSpec) -> FlywheelDimensions:
    """Disc or rim dimensions (mm-rounded up) for ``inertia`` kg·m² on its own shaft.

    Disc: I = ρπbD⁴/32 with b = width_ratio·D. Rim of mean diameter D, thickness
    h = thickness_ratio·D, width b = width_ratio·D: I = ρπb(D₂⁴ − D₁⁴)/32, D₂,₁ = D ± h
    (I = m(D₂² + D₁²)/8). D, b and h are rounded up to whole mm and I recomputed from them.
    """
    if not inertia > 0:
        raise VelplanError(f"flywheel: inertia must be > 0 kg·m² to size one, not {inertia:g}")
    rho, kb, kh = spec.density, spec.width_ratio, spec.thickness_ratio
    up = lambda x: math.ceil(x * 1000.0 - 1e-9) / 1000.0  # noqa: E731
    if spec.shape == "disc":
        D = (32.0 * inertia / (rho * math.pi * kb)) ** 0.2
        D, b = up(D), None
        b = up(kb * D)
        mass = rho * math.pi * D * D * b / 4.0
        inert = mass * D * D / 8.0
        return FlywheelDimensions("disc", D, b, 0.0, D, rho, mass, inert, inertia)
    g = (1 + kh) ** 4 - (1 - kh) ** 4
    D = up((32.0 * inertia / (rho * math.pi * kb * g)) ** 0.2)
    h, b = up(kh * D), up(kb * D)
    d2, d1 = D + h, D - h
    mass = rho * math.pi * (d2 * d2 - d1 * d1) * b / 4.0
    inert = mass * (d2 * d2 + d1 * d1) / 8.0
    return FlywheelDimensions("rim", D, b, d1, d2, rho, mass, inert, inertia)


def size_flywheel(c: EnergyCurve, omega_mean: float, delta: float, declared: float = 0.0,
                  spec: FlywheelSpec = FlywheelSpec(), precision: float = 0.5) -> Flywheel:
    """The flywheel for δ at ω_m (rad/s, > 0) by the three methods, what to add after the
    ``declared`` constant inertias (kg·m², reduced), on its shaft, and its dimensions."""
    if not 0 < delta < 1:
        raise VelplanError(f"delta must be between 0 and 1 (exclusive), not {delta:g}")
    found = _found(c, omega_mean, delta)
    ex = exact_inertia(c, omega_mean, delta, found)
    me = mertsalov_inertia(c, omega_mean, delta, found)
    wd = wittenbauer(c, omega_mean, delta, precision=precision, found=found)
    added = ex - declared
    on_shaft = added / spec.ratio**2
    dims = dimensions(on_shaft, spec) if on_shaft > 0 else None
    kp, km = _ks(omega_mean, delta)
    eA, eJ = c.errors["A"], c.errors["J"]
    # each extreme errs by at most eA + k·eJ (a shifted maximum moves the value only to 2nd order)
    errors = {"exact": (2 * eA + (kp + km) * eJ) / (kp - km),
              "mertsalov": (2 * eA + omega_mean**2 * eJ) / (delta * omega_mean**2)}
    errors["wittenbauer"] = errors["exact"]
    return Flywheel(delta, omega_mean, ex, me, wd.inertia, declared, added, spec.ratio, on_shaft, wd, dims, errors,
                    tuple(found))
