"""How lengths and directions are laid off and read: exactly, or as a careful draughtsman does.

A `Drafting` policy rounds every length laid off or read to ``length_mm`` and every direction
drawn to ``angle_deg``; with an ``rng`` it adds uniform errors of that size instead (a
Monte-Carlo model of a student's hand). `EXACT` does nothing: float64 construction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from velplan.errors import VelplanError


@dataclass(frozen=True)
class Drafting:
    """Drafting precision: ``length_mm`` (mm) and ``angle_deg`` (deg); ``rng`` for random errors.

    ``exact = True`` (see `EXACT`) makes every operation the identity.
    """

    length_mm: float = 0.5
    angle_deg: float = 0.5
    rng: np.random.Generator | None = field(default=None, compare=False)
    exact: bool = False

    def __post_init__(self):
        if not self.exact:
            for name, most in (("length_mm", 10.0), ("angle_deg", 10.0)):
                v = getattr(self, name)
                if not (math.isfinite(v) and 0 < v <= most):
                    raise VelplanError(f"drafting precision {name} must be > 0 and at most {most:g} "
                                       f"(a draughtsman's), not {v}")

    @property
    def mode(self) -> str:
        return "exact" if self.exact else "drafting"

    def _q(self, x: np.ndarray, step: float) -> np.ndarray:
        if self.rng is None:
            return np.round(x / step) * step
        return x + self.rng.uniform(-step / 2, step / 2, size=np.shape(x))

    def length(self, mm: np.ndarray) -> np.ndarray:
        """A length as laid off or read on the drawing, mm."""
        return mm if self.exact else np.abs(self._q(mm, self.length_mm))

    def direction(self, u: np.ndarray) -> np.ndarray:
        """A unit direction (complex) as drawn."""
        if self.exact:
            return u
        return np.exp(1j * self._q(np.angle(u), math.radians(self.angle_deg)))

    def vector(self, z: np.ndarray) -> np.ndarray:
        """A vector (complex, mm) as laid off: its length and its direction each drafted."""
        if self.exact:
            return z
        size = np.abs(z)
        with np.errstate(invalid="ignore", divide="ignore"):
            unit = np.where(size == 0, 1.0, z / np.where(size == 0, 1.0, size))
        return np.where(size == 0, 0.0, self.length(size) * self.direction(unit))


EXACT = Drafting(exact=True)
