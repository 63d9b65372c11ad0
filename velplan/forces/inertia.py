"""Inertia forces and moments of the links (d'Alembert), and their single resultant through
the centre of percussion (seed 001).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.analysis.solver import Kinematics, solve
from velplan.errors import MechanismError
from velplan.forces.actions import Actions, AppliedForce, AppliedMoment
from velplan.forces.common import check_point_of_link, link_motion, material_points, point
from velplan.mechanism.model import LinkMass, Mechanism

DEFAULT_K = 10.0
"""Default K in J_S ≈ m·l²/K (course works take K = 8…10)."""


def link_length(mech: Mechanism, link: str) -> float:
    """Characteristic length l of ``link``, m: the crank's or a rod's given length, else the
    largest distance between two named material points of the link at crank angle 0 (a triad's
    base link: its longest side; its rod leads: their lengths)."""
    if link == mech.crank.link:
        return mech.crank.length
    for g in mech.groups:
        lengths = g.link_lengths()
        if link in lengths:
            return lengths[link]
    names = material_points(mech).get(link, ())
    if len(names) < 2:
        return 0.0
    kin = solve(mech, np.zeros(1))
    z = np.array([point(kin, n)[0] for n in names])
    d = np.abs(z[:, None] - z[None, :])
    return float(np.nanmax(d))


def estimated_inertia(mass: float, length: float, k: float = DEFAULT_K) -> float:
    """J_S ≈ m·l²/K, kg·m² (seed 001: K = 8…10 when no moment of inertia is given).

    Parameters
    ----------
    mass : float
        kg.
    length : float
        Link length l, m.
    k : float
        The coefficient K (> 0).
    """
    if not k > 0:
        raise MechanismError(f"coefficient K of J_S ≈ m·l²/K must be > 0, not {k}")
    return mass * length * length / k


def inertia_of(mech: Mechanism, m: LinkMass, k: float = DEFAULT_K) -> float:
    """J_S of a link: the given inertia or `estimated_inertia` with the link's length."""
    return m.inertia if m.inertia is not None else estimated_inertia(m.mass, link_length(mech, m.link), k)


@dataclass(frozen=True)
class Inertia:
    """Inertia force and moment of one link over n positions.

    Attributes
    ----------
    link, centre : str
    mass, inertia : float
        m (kg) and the J_S used (kg·m²).
    force : ndarray, shape (n,), complex
        Φ = −m·a_S, N.
    moment : ndarray, shape (n,)
        M_Φ = −J_S·ε, N·m.
    at : ndarray, shape (n,), complex
        Position of the centre S, m.
    """

    link: str
    centre: str
    mass: float
    inertia: float
    force: np.ndarray
    moment: np.ndarray
    at: np.ndarray

    @property
    def offset(self) -> np.ndarray:
        """h = M_Φ/|Φ|, m: the arm of the single resultant Φ about S — its line of action lies at
        distance |h| from S, on the side that makes its moment about S equal to M_Φ (seed 001's
        shift of the inertia force). NaN where Φ = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(np.abs(self.force) > 0, self.moment / np.abs(self.force), np.nan)

    @property
    def resultant_point(self) -> np.ndarray:
        """A point X of the resultant's line of action: the foot of the perpendicular from S,
        X = S − i·Φ·M_Φ/|Φ|², m (complex). NaN where Φ = 0."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(np.abs(self.force) > 0,
                            self.at - 1j * self.force * self.moment / np.abs(self.force) ** 2, np.nan)

    def percussion_point(self, towards: np.ndarray) -> np.ndarray:
        """Centre of percussion K on the link's line from S towards ``towards`` (complex, m):
        where the resultant's line of action crosses it (NaN where they are parallel).

        Notes
        -----
        (K − S) × Φ = M_Φ with K = S + t·e, e the unit vector S → towards:
        t = M_Φ / (e × Φ).
        """
        with np.errstate(divide="ignore", invalid="ignore"):
            e = towards - self.at
            e = e / np.abs(e)
            den = e.real * self.force.imag - e.imag * self.force.real
            t = np.where(den != 0, self.moment / den, np.nan)
        return self.at + t * e


def inertias(mech: Mechanism, kin: Kinematics, k: float = DEFAULT_K) -> tuple[Inertia, ...]:
    """Φ = −m·a_S and M_Φ = −J_S·ε of every link with a mass.

    Notes
    -----
    a_S is the acceleration of the link's material point at S (`link_motion`); J_S is the
    given inertia or m·l²/K (`inertia_of`).
    """
    out = []
    for m in mech.masses:
        if m.mass == 0 and not m.inertia:
            continue
        check_point_of_link(mech, m.link, m.centre, f"[link.{m.link}] centre")
        s = point(kin, m.centre)
        _, a = link_motion(kin, m.link, s)
        j = inertia_of(mech, m, k)
        out.append(Inertia(m.link, m.centre, m.mass, j, -m.mass * a, -j * kin.epsilon(m.link), s))
    return tuple(out)


def inertia_actions(mech: Mechanism, kin: Kinematics, k: float = DEFAULT_K) -> Actions:
    """The inertia forces Φ (at S, labelled ``"Φ<link>"``) and moments M_Φ (``"MΦ<link>"``)."""
    forces, moments = [], []
    for q in inertias(mech, kin, k):
        if q.mass > 0:
            forces.append(AppliedForce(f"Φ{q.link}", q.link, q.centre, q.force, "inertia"))
        if q.inertia > 0:
            moments.append(AppliedMoment(f"MΦ{q.link}", q.link, q.moment, "inertia"))
    return Actions(tuple(forces), tuple(moments))
