"""The three balancing moments side by side — kinetostatics, Zhukovsky's lever, power — and
the mean balancing moment over a revolution.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal, Sequence

import numpy as np

from velplan.analysis.solver import Kinematics, solve
from velplan.forces.actions import Actions
from velplan.forces.inertia import DEFAULT_K, inertia_actions
from velplan.forces.kinetostatics import Kinetostatics, kinetostatics
from velplan.forces.lever import Lever, images_from_plan, positions_from_kinematics, zhukovsky_lever
from velplan.forces.loads import gravity_actions, load_actions
from velplan.forces.parse import parse_loads
from velplan.forces.power import power_balancing_moment
from velplan.errors import deprecated
from velplan.mechanism.model import Mechanism

Method = Literal["kinetostatics", "lever", "power"]


def mechanism_actions(mech: Mechanism, kin: Kinematics, loads: Sequence | None = None, *, gravity: bool = True,
                      inertia: bool = True, k: float = DEFAULT_K) -> Actions:
    """Loads (default: those declared in the file), gravity and inertia at the positions of ``kin``."""
    loads = parse_loads(mech) if loads is None else loads
    parts = [load_actions(loads, kin)]
    if gravity:
        parts.append(gravity_actions(mech, kin))
    if inertia:
        parts.append(inertia_actions(mech, kin, k))
    return Actions.join(parts)


@dataclass(frozen=True)
class ForceAnalysis:
    """The force analysis of a mechanism at n positions by the three methods.

    Attributes
    ----------
    kinematics : Kinematics
    actions : Actions
    kinetostatics : Kinetostatics
    lever : Lever
        With exact images at the scale ``mu_v``.
    power : ndarray, shape (n,)
        M_b by the power method, N·m.
    plan : velplan.plans.PlanResult
        The velocity plan the lever is drawn on (every position).
    """

    kinematics: Kinematics = field(repr=False)
    actions: Actions = field(repr=False)
    kinetostatics: Kinetostatics = field(repr=False)
    lever: Lever = field(repr=False)
    power: np.ndarray
    plan: object = field(default=None, repr=False)

    @property
    def balancing_moments(self) -> dict[str, np.ndarray]:
        """Method → M_b (n,), N·m."""
        return {"kinetostatics": self.kinetostatics.balancing_moment,
                "lever": self.lever.balancing_moment, "power": self.power}

    @property
    def lever_difference_percent(self) -> np.ndarray:
        """(n,) per-cent difference of M_b by the lever from M_b by kinetostatics (NaN at a dead
        centre): `lever_difference_percent` of the two."""
        return lever_difference_percent(self.lever.balancing_moment, self.kinetostatics.balancing_moment)

    def max_relative_difference(self) -> float:
        """max |M_b(method) − M_b(kinetostatics)| / max |M_b(kinetostatics)| over positions and methods."""
        ref = self.kinetostatics.balancing_moment
        scale = float(np.nanmax(np.abs(ref))) if ref.size else 0.0
        if scale == 0.0:
            scale = 1.0
        return float(max(np.nanmax(np.abs(m - ref)) for m in (self.lever.balancing_moment, self.power)) / scale)


def force_analysis_at(mech: Mechanism, phi, *, loads: Sequence | None = None, gravity: bool = True,
                   inertia: bool = True, k: float = DEFAULT_K, mu_v: float | None = None,
                   drafting=None) -> ForceAnalysis:
    """Kinetostatics, lever and power method at crank angles ``phi`` (rad).

    Parameters
    ----------
    mech : Mechanism
    phi : float or array_like
        Crank angles, rad.
    loads : sequence of loads, optional
        Default: `parse_loads` of the mechanism's ``[[load]]`` tables; ``()`` for none.
    gravity, inertia : bool
        Include G = m·g and Φ, M_Φ.
    k : float
        K of J_S ≈ m·l²/K for links without a given inertia.
    mu_v : float, optional
        Scale of the velocity plan the lever is drawn from, (m/s)/mm (default: the standard
        scale that fits the plan in 100 mm; in exact mode M_b does not depend on it).
    drafting : velplan.plans.Drafting, optional
        The plan is constructed by the plan engine, exactly (default) or at drafting
        precision; the lever then differs from the kinetostatics by what drafting implies.
    """
    from velplan.plans import EXACT, Plan

    kin = solve(mech, phi)
    plan = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=mu_v, drafting=drafting or EXACT)
    return force_analysis(kin, plan, parse_loads(mech) if loads is None else loads, gravity=gravity,
                          inertia=inertia, k=k, mu_v=mu_v)


def force_analysis(kin: Kinematics, plan, loads: Sequence, *, gravity: bool = True, inertia: bool = True,
                   k: float = DEFAULT_K, mu_v: float | None = None) -> ForceAnalysis:
    """Kinetostatics, lever and power method on a solved mechanism ``kin`` and its velocity
    plan ``plan`` (a `velplan.plans.PlanResult` at every position of ``kin``); the lever is
    drawn at ``mu_v`` (the plan's own scale when omitted)."""
    mech = kin.mechanism
    acts = mechanism_actions(mech, kin, loads, gravity=gravity, inertia=inertia, k=k)
    ks = kinetostatics(mech, kin, acts)
    mu = plan.scale if mu_v is None or not plan.drafting.exact else mu_v
    images = images_from_plan(plan)
    if mu != plan.scale:
        images = {name: z * (plan.scale / mu) for name, z in images.items()}
    lv = zhukovsky_lever(mech, positions_from_kinematics(kin, None), images, mu, acts)
    return ForceAnalysis(kin, acts, ks, lv, power_balancing_moment(kin, acts), plan)


analyse_forces = deprecated(force_analysis_at, "velplan.forces.analyse_forces")


def lever_difference_percent(lever, kinetostatics) -> np.ndarray:
    """Per-cent difference of the lever's balancing moment from the kinetostatic one,
    100·(M_lever − M_kin)/|M_kin| (NaN where M_kin ≈ 0, at dead centres) — the check course works
    make on drawn plans, where a few per cent is accepted."""
    lever, kinetostatics = np.asarray(lever, dtype=float), np.asarray(kinetostatics, dtype=float)
    tiny = 1e-9 * np.nanmax(np.abs(kinetostatics), initial=0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        pct = 100.0 * (lever - kinetostatics) / np.abs(kinetostatics)
    # where M_b vanishes (a dead centre) a per-cent difference means nothing
    return np.where(np.abs(kinetostatics) > tiny, pct, np.nan)


def _nodes(breaks: Sequence[float], n: int, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss–Legendre nodes and weights over [b0, b0 + 2π) split at ``breaks``."""
    b = np.sort(np.mod(np.asarray(breaks, dtype=float), 2 * np.pi))
    b = b[np.concatenate(([True], np.diff(b) > 1e-12))] if b.size else np.zeros(1)
    edges = np.concatenate((b, [b[0] + 2 * np.pi]))
    x, w = np.polynomial.legendre.leggauss(order)
    panels_total = max(n // order, len(edges) - 1)
    nodes, weights = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        if hi - lo <= 0:
            continue
        m = max(1, int(round(panels_total * (hi - lo) / (2 * np.pi))))
        e = np.linspace(lo, hi, m + 1)
        for a, c in zip(e[:-1], e[1:]):
            nodes.append(0.5 * (c - a) * x + 0.5 * (c + a))
            weights.append(0.5 * (c - a) * w)
    return np.concatenate(nodes), np.concatenate(weights)


def mean_balancing_moment(mech: Mechanism, *, loads: Sequence | None = None, n: int = 3600,
                          method: Method = "kinetostatics", quadrature: Literal["piecewise", "uniform"] = "piecewise",
                          gravity: bool = True, inertia: bool = True, k: float = DEFAULT_K) -> float:
    """Mean balancing moment over a revolution, (1/2π)·∫ M_b dφ, N·m — the moment a motor must
    supply on average, equal to the work of the loads per revolution over 2π.

    Parameters
    ----------
    n : int
        Number of crank positions.
    quadrature : {"piecewise", "uniform"}
        ``"piecewise"``: composite 16-point Gauss–Legendre between the angles where a load
        jumps (its `breakpoints`), exact to round-off for piecewise smooth loads.
        ``"uniform"``: the plain mean over n uniform angles (trapezoid rule; its error is of
        order (2π/n)·jump for a load with jumps).
    """
    loads = parse_loads(mech) if loads is None else loads
    if quadrature == "uniform":
        phi, w = np.arange(n) * (2 * np.pi / n), np.full(n, 2 * np.pi / n)
    else:
        breaks = [b for ld in loads for b in ld.breakpoints()]
        phi, w = _nodes(breaks, n)
    res = force_analysis_at(mech, phi, loads=loads, gravity=gravity, inertia=inertia, k=k)
    return float(np.sum(res.balancing_moments[method] * w) / (2 * np.pi))
