"""The results of kinetostatics that other modules draw or decompose: a pair's reaction and a
group's force polygon (see `velplan.forces.kinetostatics` for the conventions)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.forces.common import dot
from velplan.mechanism.model import Pair


def reaction_label(frm: str, on: str) -> str:
    """R<from><on> (R21: the force of link 2 on link 1), with a comma for long link names."""
    return f"R{frm}{on}" if len(frm) == 1 and len(on) == 1 else f"R{frm},{on}"


@dataclass(frozen=True)
class Reaction:
    """The reaction in one pair over n positions.

    Attributes
    ----------
    pair : Pair
    force : ndarray, shape (n,), complex
        Force on ``pair.links[0]`` from ``pair.links[1]``, N.
    moment : ndarray, shape (n,)
        Prismatic pairs: the couple on ``pair.links[0]`` about ``reference``, N·m; zeros for
        revolute pairs.
    reference : ndarray, shape (n,), complex
        The joint (R) or the reference point on the guide line (P), m.
    direction : ndarray, shape (n,), complex
        Prismatic pairs: the guide's unit direction u; NaN for revolute pairs.
    """

    pair: Pair
    force: np.ndarray
    moment: np.ndarray
    reference: np.ndarray
    direction: np.ndarray

    @property
    def label(self) -> str:
        """R<k1><k0>: the force of links[1] on links[0]."""
        return reaction_label(self.pair.links[1], self.pair.links[0])

    @property
    def magnitude(self) -> np.ndarray:
        """|R|, N."""
        return np.abs(self.force)

    @property
    def at(self) -> np.ndarray:
        """Point of application, m: the joint, or reference + (M/N)·u along the guide (NaN where
        N = 0)."""
        if self.pair.kind == "R":
            return self.reference
        n = dot(self.force, 1j * self.direction)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(n != 0, self.reference + self.moment / n * self.direction, np.nan)


@dataclass(frozen=True)
class ForcePolygon:
    """The force polygon of one group (or of the crank) as data, ready to draw at a scale μF.

    The ``vectors`` are laid head to tail from the pole; the polygon is closed by two vectors
    of known direction (``closing``, unit vectors) whose magnitudes come from intersecting the
    line through the last vertex along the first direction with the line through the pole
    along the second (``closing_vectors``). For the crank the closing vector (the frame's
    reaction) is a single vector of unknown direction and ``closing`` is empty.

    Attributes
    ----------
    group : str
        Group name, or ``"crank"``.
    vectors : tuple of (label, ndarray (n,) complex)
        Known forces in drawing order, N: the components found from moment equations first,
        then the loads, gravity and inertia forces and the reactions of later groups.
    closing : tuple of (label, ndarray (n,) complex)
        Unit directions of the two unknown components.
    closing_vectors : tuple of (label, ndarray (n,) complex)
        The closing vectors found by the intersection, N.
    """

    group: str
    kind: str
    vectors: tuple[tuple[str, np.ndarray], ...]
    closing: tuple[tuple[str, np.ndarray], ...]
    closing_vectors: tuple[tuple[str, np.ndarray], ...]

    def vertices(self, mu_f: float = 1.0) -> np.ndarray:
        """(n, k + 1) complex vertices from the pole, mm at the scale ``mu_f`` (N/mm): the pole,
        then the end of each vector and closing vector (the last is back at the pole)."""
        parts = [v for _, v in self.vectors] + [v for _, v in self.closing_vectors]
        n = parts[0].shape[0] if parts else 0
        z = np.cumsum(np.stack([np.zeros(n, complex)] + parts, axis=1), axis=1)
        return z / mu_f

    def misclosure(self) -> np.ndarray:
        """(n,) |Σ of all vectors|, N (0 up to round-off)."""
        return np.abs(self.vertices()[:, -1])
