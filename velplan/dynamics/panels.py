"""Piecewise Gauss–Legendre panels over a cycle of crank travel.

The cycle [0, L) is cut at the angles where a load jumps or has a kink (its breakpoints:
every node of a table, on each stroke it acts, and the output's extremes) and each piece into
panels. On every panel a quantity is known exactly at 16 Gauss–Legendre nodes; its
Legendre series through those nodes (degree 15) gives it, its integral and its value at any
travel. For the reduced inertia and the moments of smooth loads between jumps this is exact
to round-off (tests check 1e-12 against the solver), and no node ever sits on a jump.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property, lru_cache

import numpy as np
from numpy.polynomial import legendre as L

ORDER = 16
"""Nodes per panel."""


@dataclass(frozen=True, eq=False)
class Panels:
    """Panels over [0, ``cycle``) with ``ORDER`` Gauss–Legendre nodes each.

    Attributes
    ----------
    edges : ndarray, shape (P + 1,)
        Panel edges, rad of travel; edges[0] = 0, edges[-1] = cycle.
    breaks : ndarray
        The edges where a load may jump (0 and the cycle included), rad.
    """

    edges: np.ndarray
    breaks: np.ndarray
    order: int = ORDER
    _ref: tuple = field(init=False, repr=False)

    def __post_init__(self):
        object.__setattr__(self, "_ref", _reference(self.order))

    @property
    def cycle(self) -> float:
        return float(self.edges[-1])

    @property
    def count(self) -> int:
        return self.edges.size - 1

    @cached_property
    def half(self) -> np.ndarray:
        """(P,) half-widths of the panels, rad."""
        return 0.5 * np.diff(self.edges)

    @cached_property
    def nodes(self) -> np.ndarray:
        """(P, n) travel at the nodes, rad."""
        x = self._ref[0]
        mid = 0.5 * (self.edges[:-1] + self.edges[1:])
        return mid[:, None] + self.half[:, None] * x[None, :]

    @cached_property
    def weights(self) -> np.ndarray:
        """(P, n) quadrature weights, rad."""
        return self.half[:, None] * self._ref[1][None, :]

    def coefficients(self, values: np.ndarray) -> np.ndarray:
        """Legendre coefficients (…, P, n) of node values (…, P, n) on each panel's [−1, 1]."""
        return np.einsum("...pj,kj->...pk", values, self._ref[2])

    def integral(self, values: np.ndarray) -> np.ndarray:
        """∫ from 0 to each edge, (…, P + 1)."""
        per = np.sum(values * self.weights, axis=-1)
        zero = np.zeros(per.shape[:-1] + (1,))
        return np.concatenate((zero, np.cumsum(per, axis=-1)), axis=-1)

    def locate(self, theta, side: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(panel index, local coordinate in [−1, 1]) of travel ``theta`` taken within the
        cycle; a travel on an edge belongs to the panel after it."""
        t = np.mod(np.asarray(theta, dtype=float), self.cycle)
        p = np.clip(np.searchsorted(self.edges, t, side="right") - 1, 0, self.count - 1)
        x = (t - self.edges[p]) / self.half[p] - 1.0
        return p, x

    def evaluate(self, coef: np.ndarray, theta, *, deriv: bool = False):
        """Values at travel ``theta`` (m,) of quantities with coefficients ``coef`` (Q, P, n) →
        (Q, m); with ``deriv``, also their derivatives d/dθ (Q, m), per rad."""
        p, x = self.locate(np.atleast_1d(theta))
        B, dB = legendre_basis(x, coef.shape[-1], deriv)
        c = coef[:, p, :]
        vals = np.einsum("qmn,mn->qm", c, B)
        if not deriv:
            return vals
        return vals, np.einsum("qmn,mn->qm", c, dB) / self.half[p]

    def antiderivative(self, coef: np.ndarray) -> np.ndarray:
        """(Q, P, n + 1) Legendre coefficients of ∫ from each panel's start (in travel, rad)."""
        return L.legint(coef, lbnd=-1.0, axis=-1) * self.half[:, None]

    def integrate_to(self, coef: np.ndarray, edge_integrals: np.ndarray, theta, *,
                     icoef: np.ndarray | None = None) -> np.ndarray:
        """∫ from 0 to ``theta`` (m,) (within one cycle) of quantities (Q, P, n) → (Q, m).

        ``edge_integrals`` (Q, P + 1) from `integral`; ``icoef`` from `antiderivative` (computed
        when None)."""
        if icoef is None:
            icoef = self.antiderivative(coef)
        p, x = self.locate(np.atleast_1d(theta))
        B, _ = legendre_basis(x, icoef.shape[-1])
        return edge_integrals[:, p] + np.einsum("qmn,mn->qm", icoef[:, p, :], B)

    def tail(self, coef: np.ndarray) -> np.ndarray:
        """(…, P) |c_{n−2}| + |c_{n−1}|: the size of the last two terms of each panel's series,
        an estimate of the error of a value read off it (a smooth quantity's series has
        converged to round-off; a kink or a jump inside a panel leaves a slowly decaying
        tail)."""
        return np.abs(coef[..., -2]) + np.abs(coef[..., -1])


@lru_cache(maxsize=None)
def _reference(order: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights of ``order`` points, and the inverse of their
    Legendre–Vandermonde matrix (shared by every panel set of that order)."""
    x, w = L.leggauss(order)
    return x, w, np.linalg.inv(L.legvander(x, order - 1))


def legendre_basis(x: np.ndarray, n: int, deriv: bool = False) -> tuple[np.ndarray, np.ndarray | None]:
    """(m, n) Legendre polynomials P_k(x), k < n, and with ``deriv`` their derivatives P_k′(x)
    (else None), by the three-term recurrences."""
    x = np.asarray(x, dtype=float)
    B = np.empty((x.size, n))
    B[:, 0] = 1.0
    if n > 1:
        B[:, 1] = x
    for k in range(1, n - 1):
        B[:, k + 1] = ((2 * k + 1) * x * B[:, k] - k * B[:, k - 1]) / (k + 1)
    if not deriv:
        return B, None
    dB = np.zeros((x.size, n))
    if n > 1:
        dB[:, 1] = 1.0
    for k in range(1, n - 1):
        dB[:, k + 1] = dB[:, k - 1] + (2 * k + 1) * B[:, k]
    return B, dB


def panels_over(cycle: float, breaks, count: int, order: int = ORDER) -> Panels:
    """``count`` panels over [0, ``cycle``) (or one per piece, if there are more pieces), with
    an edge at every break (rad of travel in [0, cycle)); the pieces between breaks share them
    in proportion to their lengths (largest remainders)."""
    b = np.unique(np.concatenate(([0.0, cycle], np.mod(np.asarray(breaks, dtype=float), cycle))))
    b = b[np.concatenate(([True], np.diff(b) > 1e-12 * cycle))]
    if b[-1] < cycle:
        b[-1] = cycle
    ideal = count * np.diff(b) / cycle
    m = np.maximum(1, np.floor(ideal)).astype(int)
    for _ in range(max(0, count - int(m.sum()))):
        m[int(np.argmax(ideal / m))] += 1
    edges = [np.array([0.0])] + [np.linspace(lo, hi, k + 1)[1:] for lo, hi, k in zip(b[:-1], b[1:], m)]
    return Panels(np.concatenate(edges), b, order)
