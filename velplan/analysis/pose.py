"""A mechanism in one pose, to be written or drawn as joints (`velplan.mechanism.drawn`)."""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.solver import solve
from velplan.errors import AssemblyError, VelplanError
from velplan.mechanism.model import Mechanism

POSE_STEP_DEG = 5.0
"""The crank angles a pose is chosen among, deg."""


def best_pose(mech: Mechanism) -> float:
    """The crank angle (rad) of the 72 where the worst-conditioned group is best conditioned."""
    phis = np.radians(np.arange(0.0, 360.0, POSE_STEP_DEG))
    k = solve(mech, phis, order=0)
    cond = k.condition.min(axis=1) if k.condition.shape[1] else np.ones(len(phis))
    return float(phis[int(np.argmax(np.where(k.valid, cond, -1.0)))])


def pose(mech: Mechanism, deg: float | None = None) -> tuple[dict[str, complex], dict[str, float]]:
    """Every named point's position (m, as x + iy) and every moving link's frame angle (rad)
    at the crank angle ``deg`` (degrees; default `best_pose`).

    >>> import velplan
    >>> at, angles = pose(velplan.load("four-bar"), 90.0)
    >>> round(at["A"].imag, 6) == round(velplan.load("four-bar").crank.length, 6)
    True
    """
    if deg is not None and not math.isfinite(deg):
        raise VelplanError(f"the pose's crank angle must be finite, not {deg}")
    phi = best_pose(mech) if deg is None else math.radians(deg)
    k = solve(mech, phi, order=0)
    if not k.valid[0]:
        raise AssemblyError(f"{mech.name} does not assemble at the crank angle {math.degrees(phi):g}°")
    at = {n: complex(*k.positions[0, i]) for n, i in k.point_index.items()}
    return at, {n: float(k.angles[0, i]) for n, i in k.link_index.items()}
