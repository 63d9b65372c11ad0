"""The power (energy) method: the balancing moment from the powers of all forces, and
seed 000's static moment (gravity and the working load only) as a table.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.errors import MechanismError
from velplan.forces.actions import Actions
from velplan.forces.common import dot, link_motion, point
from velplan.forces.inertia import DEFAULT_K, inertia_of
from velplan.mechanism.model import Mechanism


def powers(kin: Kinematics, actions: Actions) -> dict[str, np.ndarray]:
    """Label → power of each force (F·V) and moment (M·ω), W, over the positions of ``kin``.

    V is the velocity of the link's material point where the force acts, ω the link's angular
    velocity. Labels repeated in ``actions`` are summed.
    """
    out: dict[str, np.ndarray] = {}
    for f in actions.forces:
        v, _ = link_motion(kin, f.link, point(kin, f.point))
        out[f.label] = out.get(f.label, 0.0) + dot(f.vector, v)
    for m in actions.moments:
        out[m.label] = out.get(m.label, 0.0) + m.moment * kin.omega(m.link)
    return out


def power_balancing_moment(kin: Kinematics, actions: Actions) -> np.ndarray:
    """Balancing moment on the crank by the power method, N·m (counter-clockwise positive).

    Notes
    -----
    M_b·ω1 + Σ F_i·V_i·cos(F_i, V_i) + Σ M_j·ω_j = 0, the sum running over loads, gravity and
    the inertia forces Φ = −m·a_S and moments M_Φ = −J_S·ε (the inertia terms sum to −dT/dt,
    so this is also M_b·ω1 = dT/dt − Σ P_loads). Reactions do no work.
    """
    if np.any(kin.omega1 == 0):
        raise MechanismError("the power method needs a crank speed omega1 ≠ 0")
    total = sum(powers(kin, actions).values(), np.zeros(len(kin)))
    return -total / kin.omega1


def kinetic_energy(mech: Mechanism, kin: Kinematics, k: float = DEFAULT_K) -> np.ndarray:
    """T = Σ (m·V_S²/2 + J_S·ω²/2), J, over the positions of ``kin``."""
    t = np.zeros(len(kin))
    for m in mech.masses:
        v, _ = link_motion(kin, m.link, point(kin, m.centre))
        t = t + 0.5 * m.mass * np.abs(v) ** 2 + 0.5 * inertia_of(mech, m, k) * kin.omega(m.link) ** 2
    return t


def kinetic_energy_rate(mech: Mechanism, kin: Kinematics, k: float = DEFAULT_K) -> np.ndarray:
    """dT/dt = Σ (m·a_S·V_S + J_S·ε·ω), W — equal to −(power of the inertia forces and moments)."""
    out = np.zeros(len(kin))
    for m in mech.masses:
        v, a = link_motion(kin, m.link, point(kin, m.centre))
        out = out + m.mass * dot(a, v) + inertia_of(mech, m, k) * kin.epsilon(m.link) * kin.omega(m.link)
    return out


@dataclass(frozen=True)
class StaticMoment:
    """Seed 000's table: the static moment M_st = −Σ F_i·(V_i/ω1)·cos(F_i, V_i).

    Attributes
    ----------
    phi : ndarray, shape (n,)
        Crank angles, rad.
    labels : tuple of str
        The forces (``"G2"``, …, the loads).
    force : ndarray, shape (n, k)
        |F_i|, N.
    velocity_ratio : ndarray, shape (n, k)
        V_i/ω1, m (the transfer function of the point).
    angle_deg : ndarray, shape (n, k)
        Angle between F_i and V_i in [0°, 180°]; NaN where V_i/ω1 or F_i vanishes.
    terms : ndarray, shape (n, k)
        F_i·(V_i/ω1)·cos(F_i, V_i), N·m.
    moment : ndarray, shape (n,)
        M_st, N·m.
    """

    phi: np.ndarray
    labels: tuple[str, ...]
    force: np.ndarray
    velocity_ratio: np.ndarray
    angle_deg: np.ndarray
    terms: np.ndarray
    moment: np.ndarray


def static_moment(kin: Kinematics, actions: Actions, *, zero_speed: float = 1e-9) -> StaticMoment:
    """The static moment of seed 000 for the given (gravity and load) actions.

    Parameters
    ----------
    kin : Kinematics
    actions : Actions
        Normally ``gravity_actions(...) + load_actions(...)``; inertia actions are refused.
    zero_speed : float
        V/ω1 (m) below which the angle is reported as NaN (the point is at rest there).
    """
    if np.any(kin.omega1 == 0):
        raise MechanismError("the static moment needs a crank speed omega1 ≠ 0")
    if actions.select("inertia").forces or actions.select("inertia").moments:
        raise MechanismError("the static moment takes gravity and loads only, not inertia forces")
    if actions.moments:
        raise MechanismError("the static moment table lists forces only; moment loads "
                             f"({', '.join(m.label for m in actions.moments)}) are not supported")
    labels, force, ratio, angle, terms = [], [], [], [], []
    for f in actions.forces:
        v, _ = link_motion(kin, f.link, point(kin, f.point))
        r = v / kin.omega1
        fm, rm = np.abs(f.vector), np.abs(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            cosine = np.clip(dot(f.vector, r) / (fm * rm), -1.0, 1.0)
            ang = np.where((rm > zero_speed) & (fm > 0), np.degrees(np.arccos(cosine)), np.nan)
        labels.append(f.label)
        force.append(fm)
        ratio.append(rm)
        angle.append(ang)
        terms.append(dot(f.vector, r))
    stack = (lambda xs: np.stack(xs, axis=1)) if labels else (lambda xs: np.zeros((len(kin), 0)))
    t = stack(terms)
    return StaticMoment(kin.phi, tuple(labels), stack(force), stack(ratio), stack(angle), t, -t.sum(axis=1))
