"""Evaluated forces and moments acting on the links, over an array of positions.

Every force analysis (kinetostatics, Zhukovsky's lever, the power method) takes the same
`Actions`: loads, gravity and inertia, each a force at a named material point of a link or a
moment on a link, as arrays over the crank positions of a `Kinematics`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Literal

import numpy as np

Source = Literal["load", "gravity", "inertia"]


@dataclass(frozen=True)
class AppliedForce:
    """A force on ``link`` at its material point ``point``.

    Attributes
    ----------
    label : str
        Name for tables and drawings (``"Fc"``, ``"G4"``, ``"Φ6"``).
    link, point : str
    vector : ndarray, shape (n,), complex
        Fx + i·Fy, N, at each position.
    source : {"load", "gravity", "inertia"}
    """

    label: str
    link: str
    point: str
    vector: np.ndarray
    source: Source = "load"


@dataclass(frozen=True)
class AppliedMoment:
    """A moment (couple) on ``link``: ``moment`` (n,) in N·m, counter-clockwise positive."""

    label: str
    link: str
    moment: np.ndarray
    source: Source = "load"


@dataclass(frozen=True)
class Actions:
    """All the forces and moments applied to a mechanism's links at n positions."""

    forces: tuple[AppliedForce, ...] = ()
    moments: tuple[AppliedMoment, ...] = ()

    def __add__(self, other: "Actions") -> "Actions":
        return Actions(self.forces + other.forces, self.moments + other.moments)

    @staticmethod
    def join(parts: Iterable["Actions"]) -> "Actions":
        """Concatenate several `Actions`."""
        out = Actions()
        for p in parts:
            out = out + p
        return out

    def on(self, link: str) -> "Actions":
        """Only the forces and moments on ``link``."""
        return Actions(tuple(f for f in self.forces if f.link == link),
                       tuple(m for m in self.moments if m.link == link))

    def select(self, *sources: Source) -> "Actions":
        """Only the forces and moments from the given sources."""
        return Actions(tuple(f for f in self.forces if f.source in sources),
                       tuple(m for m in self.moments if m.source in sources))

    def at(self, i) -> "Actions":
        """The same actions at position(s) ``i`` (an index, slice or index array)."""
        return Actions(
            tuple(AppliedForce(f.label, f.link, f.point, np.atleast_1d(f.vector[i]), f.source) for f in self.forces),
            tuple(AppliedMoment(m.label, m.link, np.atleast_1d(m.moment[i]), m.source) for m in self.moments),
        )
