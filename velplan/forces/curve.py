"""The balancing moment over a revolution: the curve M_b(φ) a force sheet draws and its mean.

>>> import numpy as np
>>> turn_mean(np.array([1.0, -1.0, 1.0]))   # closed turn: the last sample repeats the first
0.0
>>> turn_mean(np.array([2.0, 4.0, 2.0]))
3.0
>>> turn_mean(np.array([np.nan, 1.0]))      # fewer than two finite values
nan
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MomentCurve:
    """M_b over a revolution from position 1: turn angles (rad, 0…2π) and moments (N·m) of a
    fine grid, the values at the n positions, and the mean over the turn (N·m; 0 where its
    work over the turn is round-off, NaN with fewer than two finite values)."""

    turn: np.ndarray
    moment: np.ndarray
    at_positions: np.ndarray
    mean: float


def turn_mean(moment: np.ndarray) -> float:
    """Mean (N·m) of a moment sampled over a closed turn (the last sample repeats the first):
    0 where it is round-off of a moment whose work over the turn is nil."""
    ok = moment[np.isfinite(moment)]
    if ok.size < 2:
        return float("nan")
    mean = float(np.mean(ok[:-1]))
    span = max(float(ok.max()), 0.0) - min(float(ok.min()), 0.0)
    return 0.0 if abs(mean) < 1e-9 * max(span, 1e-12) else mean


def moment_curve(turn, positions, sense: float) -> MomentCurve:
    """M_b by kinetostatics of the force analysis ``turn`` over a fine revolution from position 1
    (`velplan.forces.ForceAnalysis`), with the values of the analysis ``positions`` at the n
    positions; ``sense`` is the crank's turning sense (±1)."""
    rot = sense * (turn.kinematics.phi - turn.kinematics.phi[0])
    mom = np.asarray(turn.balancing_moments["kinetostatics"], float)
    return MomentCurve(rot, mom, np.asarray(positions.kinetostatics.balancing_moment, float), turn_mean(mom))
