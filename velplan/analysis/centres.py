"""Instant centres of velocity of every pair of links, exactly, from the analytic velocities.

A point X of link k moves with V_k(X) = V_O + i·ω_k·(X − O) (complex numbers, O any point of
the link). The centre P_ij of links i and j is where the two fields agree: with the relative
field W(X) = V_i(X) − V_j(X) = a + i·Δω·(X − O_i),

    P_ij = O_i + i·a / Δω,

and when Δω vanishes (relative translation) P_ij is at infinity, in the direction
perpendicular to the relative velocity a. "Vanishes" is judged by size, not by an absolute
threshold: the centre is at infinity when it would lie further than `FAR` mechanism sizes.

At an instant where two links have no relative motion at all (both at rest, as the links
after a rocker in its extreme position), the centre is the limit as the crank turns on: the
zero of the fields' time derivative ∂V/∂t(X) = A_O − i·ω·V_O + i·ε·(X − O), which has the same
rigid form with ε in place of ω.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.analysis.solver import Kinematics, length_scale
from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND, Mechanism

FAR = 1e9
"""A centre further than FAR × the mechanism's size from its link's origin is at infinity."""
QUIET = 1e-9
"""A relative motion below QUIET × the position's velocity scale is no motion at all."""


def link_names(mech: Mechanism) -> tuple[str, ...]:
    """The frame ``"0"`` and the moving links in the textbook's order, by number (2 before 10;
    names that are not numbers after them): the order of the circle diagram and of each
    centre's name (P23, never P32)."""
    def natural(name: str):
        return (0, int(name), "") if name.isdigit() else (1, 0, name)
    return (GROUND,) + tuple(sorted((k for k in mech.links if k != GROUND), key=natural))


def link_pairs(mech: Mechanism) -> tuple[tuple[str, str], ...]:
    """Every unordered pair of links (frame included) once, in the order of `link_names`."""
    names = link_names(mech)
    return tuple((a, b) for k, a in enumerate(names) for b in names[k + 1:])


@dataclass(frozen=True)
class Centres:
    """The instant centres of every pair of links at the positions of a `Kinematics`.

    Attributes
    ----------
    mechanism : Mechanism
    phi : ndarray, shape (n,)
        Crank angles, rad.
    pairs : tuple of (str, str)
        The unordered link pairs (`link_pairs`), one column each.
    points : ndarray of complex, shape (n, P)
        Finite centres x + i·y, m; NaN where the centre is at infinity or undetermined.
    directions : ndarray of complex, shape (n, P)
        Unit direction of a centre at infinity (x ≥ 0, the sense is immaterial); NaN elsewhere.
    limit : ndarray of bool, shape (n, P)
        Found as the limit at an instant of no relative motion (from accelerations).
    size : float
        The mechanism's size L, m (`velplan.analysis.solver.length_scale`).
    """

    mechanism: Mechanism
    phi: np.ndarray
    pairs: tuple[tuple[str, str], ...]
    points: np.ndarray
    directions: np.ndarray
    limit: np.ndarray
    size: float

    def __len__(self) -> int:
        return len(self.phi)

    def column(self, a: str, b: str) -> int:
        """Column of the pair (a, b), in either order."""
        for k, p in enumerate(self.pairs):
            if p in ((a, b), (b, a)):
                return k
        known = ", ".join(sorted({x for p in self.pairs for x in p}))
        raise MechanismError(f"no instant centre of links {a!r} and {b!r}; known links: {known}")

    @property
    def infinite(self) -> np.ndarray:
        """(n, P) bool: the centre is at infinity."""
        return np.isfinite(self.directions)

    def records(self, i: int) -> list[dict]:
        """The centres at position index ``i`` as JSON-ready records: ``{"links", "x", "y"}`` (m)
        or ``{"links", "direction"}`` (a unit vector) at infinity; x, y null if undetermined."""
        out = []
        for k, (a, b) in enumerate(self.pairs):
            p, d = self.points[i, k], self.directions[i, k]
            if np.isfinite(d):
                out.append({"links": [a, b], "direction": [float(d.real), float(d.imag)]})
            else:
                ok = np.isfinite(p)
                out.append({"links": [a, b], "x": float(p.real) if ok else None,
                            "y": float(p.imag) if ok else None})
        return out


def _fields(kin: Kinematics, derivative: bool) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Link → (base, rate, origin), (n,) each: the field V(X) = base + i·rate·(X − origin), or its
    time derivative (``derivative``: base A_O − i·ω·V_O, rate ε)."""
    n = len(kin)
    zero = np.zeros(n, complex)
    out = {GROUND: (zero, np.zeros(n), zero)}
    for link, j in kin.link_index.items():
        o = kin.point_index[kin.link_origins[link]]
        origin = kin.positions[:, o] @ np.array([1.0, 1j])
        v = kin.velocities[:, o] @ np.array([1.0, 1j])
        w = kin.omegas[:, j]
        if derivative:
            a = kin.accelerations[:, o] @ np.array([1.0, 1j])
            out[link] = (a - 1j * w * v, kin.epsilons[:, j], origin)
        else:
            out[link] = (v, w, origin)
    return out


def _scale(fields: dict, size: float) -> np.ndarray:
    """(n,) the largest |base| + |rate|·L over the links: the position's velocity scale."""
    return np.max([np.abs(b) + np.abs(r) * size for b, r, _ in fields.values()], axis=0)


def canonical(d: np.ndarray) -> np.ndarray:
    """Unit directions with the sense chosen alike: x > 0, or x = 0 (to round-off) and y > 0."""
    d = np.asarray(d, complex)
    flip = (d.real < -1e-12) | ((np.abs(d.real) <= 1e-12) & (d.imag < 0))
    return np.where(flip, -d, d)


def _pair(fi, fj, size: float, scale: np.ndarray):
    """Centre of two links from their fields: (point, direction, quiet), (n,) each."""
    bi, wi, oi = fi
    bj, wj, oj = fj
    a = bi - (bj + 1j * wj * (oi - oj))  # relative field at O_i
    dw = wi - wj
    quiet = (np.abs(a) <= QUIET * scale) & (np.abs(dw) * size <= QUIET * scale)
    far = ~quiet & (np.abs(dw) * size * FAR <= np.abs(a))
    with np.errstate(invalid="ignore", divide="ignore"):
        point = oi + 1j * a / dw
        direction = canonical(1j * a / np.abs(a))
    nan = complex(np.nan, np.nan)
    return np.where(quiet | far, nan, point), np.where(far, direction, nan), quiet


def instant_centres(kin: Kinematics) -> Centres:
    """All instant centres of ``kin``'s mechanism at its positions (velocities needed; the limit
    at an instant of no relative motion needs accelerations too).

    Returns
    -------
    Centres
        Points in m, directions as unit vectors; NaN where not assembled or undetermined.
    """
    if kin.order < 1:
        raise MechanismError("instant centres need velocities: solve with order ≥ 1")
    mech = kin.mechanism
    size = length_scale(mech)
    pairs = link_pairs(mech)
    first = _fields(kin, False)
    second = _fields(kin, True) if kin.order >= 2 else None
    s1 = _scale(first, size)
    s2 = _scale(second, size) if second is not None else None
    n = len(kin)
    points = np.full((n, len(pairs)), complex(np.nan, np.nan))
    directions = points.copy()
    limit = np.zeros((n, len(pairs)), bool)
    for k, (a, b) in enumerate(pairs):
        p, d, quiet = _pair(first[a], first[b], size, s1)
        if second is not None and quiet.any():
            p2, d2, _ = _pair(second[a], second[b], size, s2)
            p, d = np.where(quiet, p2, p), np.where(quiet, d2, d)
            limit[:, k] = quiet
        points[:, k], directions[:, k] = p, d
    bad = ~np.asarray(kin.valid, bool)
    points[bad], directions[bad] = complex(np.nan, np.nan), complex(np.nan, np.nan)
    return Centres(mech, np.asarray(kin.phi), pairs, points, directions, limit, size)
