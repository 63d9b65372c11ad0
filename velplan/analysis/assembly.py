"""Assembly check over a whole crank revolution."""

from __future__ import annotations

import numpy as np

from velplan.errors import AssemblyError
from velplan.mechanism.model import Mechanism

SAMPLES = 3600
"""Crank angles sampled by `check_full_rotation` (0.1° apart)."""


def failing_ranges(mask: np.ndarray, phi_deg: np.ndarray) -> list[tuple[float, float]]:
    """Contiguous ranges (deg) of ``phi_deg`` where ``mask`` is True, wrapping at 360°."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    step = phi_deg[1] - phi_deg[0]
    breaks = np.flatnonzero(np.diff(idx) > 1)
    starts = np.concatenate([[idx[0]], idx[breaks + 1]])
    ends = np.concatenate([idx[breaks], [idx[-1]]])
    ranges = [(float(phi_deg[s]), float(phi_deg[e])) for s, e in zip(starts, ends)]
    if len(ranges) > 1 and ranges[0][0] == phi_deg[0] and ranges[-1][1] >= phi_deg[-1] - step / 2:
        ranges = [(ranges[-1][0] - 360.0, ranges[0][1])] + ranges[1:-1]
    return ranges


def check_full_rotation(mech: Mechanism) -> None:
    """Raise `AssemblyError` if some group cannot be closed at some crank angle.

    The message names the first group that fails and every range of crank angles (deg,
    sampled every 0.1°) where it cannot be assembled.
    """
    from velplan.analysis.solver import group_point, solve

    phi_deg = np.arange(SAMPLES) * (360.0 / SAMPLES)
    kin = solve(mech, np.radians(phi_deg))
    for g in mech.groups:
        bad = ~np.isfinite(kin.condition[:, kin.group_index[g.name]])
        if bad.any():
            text = ", ".join(f"{a:.1f}°…{b:.1f}°" for a, b in failing_ranges(bad, phi_deg))
            raise AssemblyError(
                f"group {g.name!r} ({g.kind}) cannot be assembled for crank angles {text}: "
                f"point {group_point(g)!r} has no position there",
                group=g.name,
                point=group_point(g),
                phi_deg=float(phi_deg[np.argmax(bad)]),
            )
