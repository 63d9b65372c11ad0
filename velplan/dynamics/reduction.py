"""Reduction to the main shaft: reduced inertia J(φ), its derivative, and the reduced moment
of every load and of gravity, from the exact velocity analogues of the analytic solver.

Conventions
-----------
The generalised coordinate is the crank angle φ; its sense of rotation s = sign(ω1) of
``[crank]``. Quantities are tabulated against the crank *travel* θ = s·(φ − φ1) from
position 1, so that the machine moves forward in θ at the speed w = |ω| = dθ/dt.

* J (kg·m²) does not depend on the sense; J′ = dJ/dθ = s·dJ/dφ.
* A reduced moment M (N·m) is the power of a force over the crank speed |ω| in the sense of
  motion: positive when it drives, negative when it resists (the CCW-positive moment on the
  crank is s·M). Loads acting against the motion are evaluated in the sense s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Sequence

import numpy as np

from velplan.analysis.extremes import reference_angle
from velplan.analysis.solver import solve
from velplan.dynamics.panels import Panels, legendre_basis, panels_over
from velplan.errors import MechanismError
from velplan.forces.common import dot, link_motion, point
from velplan.forces.inertia import inertia_of
from velplan.forces.loads import gravity_actions
from velplan.forces.power import powers
from velplan.mechanism.model import Mechanism

GRAVITY = "gravity"
"""Label of gravity's reduced moment."""


@dataclass(frozen=True, eq=False)
class Reduced:
    """Reduced quantities at n crank positions.

    Attributes
    ----------
    theta, phi : ndarray, shape (n,)
        Crank travel from position 1 and crank angle, rad.
    J : ndarray, shape (n,)
        Σ m|r′_S|² + J_S·φ_i′² of the links other than the crank (the variable part J_II), kg·m².
    dJ : ndarray, shape (n,)
        dJ/dθ, kg·m²/rad.
    moments : dict of str to ndarray
        Load name (and ``"gravity"``) → reduced moment, N·m (positive when it drives).
    """

    theta: np.ndarray
    phi: np.ndarray
    J: np.ndarray
    dJ: np.ndarray
    moments: dict

    @property
    def resisting(self) -> np.ndarray:
        """Σ of the reduced moments of loads and gravity, N·m."""
        return sum(self.moments.values(), np.zeros_like(self.theta))


@dataclass(frozen=True, eq=False)
class Reducer:
    """The reduction of one mechanism with its loads; call it at crank travels.

    Attributes
    ----------
    mechanism : Mechanism
    loads : tuple
    sense : float
        +1 counter-clockwise, −1 clockwise.
    phi1 : float
        Crank angle of position 1, rad.
    crank_inertia : float
        The crank's own reduced inertia m|r′_S|² + J_S (constant), kg·m².
    labels : tuple of str
        Labels of the reduced moments (the loads in order, then ``"gravity"`` if any).
    """

    mechanism: Mechanism = field(repr=False)
    loads: tuple = ()
    sense: float = 1.0
    phi1: float = 0.0

    @cached_property
    def _masses(self):
        mech = self.mechanism
        return tuple((m, inertia_of(mech, m)) for m in mech.masses)

    @cached_property
    def crank_inertia(self) -> float:
        crank = self.mechanism.crank.link
        on = [(m, j) for m, j in self._masses if m.link == crank]
        if not on:
            return 0.0
        kin = solve(self.mechanism, np.array([self.phi1]), omega1=1.0, epsilon1=0.0, order=1)
        total = 0.0
        for m, j in on:
            v, _ = _velocity(kin, m)
            total += m.mass * float(abs(v[0])) ** 2 + j
        return total

    @cached_property
    def labels(self) -> tuple[str, ...]:
        names = tuple(ld.name for ld in self.loads)
        grav = any(m.mass > 0 for m in self.mechanism.masses) and self.mechanism.gravity != 0
        return names + ((GRAVITY,) if grav else ())

    def breakpoints(self) -> np.ndarray:
        """Travels θ in [0, 2π) where a load jumps, rad."""
        b = [bp for ld in self.loads for bp in ld.breakpoints()]
        return np.mod(self.sense * (np.asarray(b, dtype=float) - self.phi1), 2 * np.pi)

    def phi(self, theta) -> np.ndarray:
        """Crank angle at travel θ, rad."""
        return self.phi1 + self.sense * np.asarray(theta, dtype=float)

    def inertia_terms(self, phi: float) -> list[tuple[str, str, float, float]]:
        """The terms of J_II at the crank angle ``phi`` (rad), for a worked example: (kind
        "m" or "J", link, its mass kg or inertia J_S kg·m², the squared analogue (v_S/ω₁)² m²
        or (ω/ω₁)²) of each link other than the crank; their sum of products is J_II."""
        mech = self.mechanism
        kin = solve(mech, np.array([phi]), omega1=1.0, epsilon1=0.0)
        out = []
        for m, j in self._masses:
            if m.link == mech.crank.link:
                continue
            v, _ = link_motion(kin, m.link, point(kin, m.centre))
            if m.mass > 0:
                out.append(("m", m.link, m.mass, float(abs(v[0])) ** 2))
            w = float(kin.omega(m.link)[0])
            if j > 0 and w != 0:
                out.append(("J", m.link, j, w * w))
        return out

    def __call__(self, theta) -> Reduced:
        """The reduced quantities at travels ``theta`` (rad), exactly (one solve)."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        phi = self.phi(theta)
        # unit speed in the sense of rotation: v = s·r′, a = r″, so Σ m v·a = ½ dJ/dθ
        kin = solve(self.mechanism, phi, omega1=self.sense, epsilon1=0.0)
        if not np.all(kin.valid):
            bad = float(np.degrees(phi[~kin.valid][0]))
            raise MechanismError(f"dynamics: the mechanism does not assemble at φ = {bad:.6g}°")
        crank = self.mechanism.crank.link
        J = np.zeros(theta.size)
        dJ = np.zeros(theta.size)
        for m, j in self._masses:
            if m.link == crank:
                continue
            v, a = _velocity(kin, m, accel=True)
            w, e = kin.omega(m.link), kin.epsilon(m.link)
            J += m.mass * np.abs(v) ** 2 + j * w * w
            dJ += 2.0 * (m.mass * dot(v, a) + j * w * e)
        moments = {}
        for ld in self.loads:
            p = powers(kin, ld.actions(kin))
            moments[ld.name] = moments.get(ld.name, 0.0) + sum(p.values(), np.zeros(theta.size))
        if GRAVITY in self.labels:
            moments[GRAVITY] = sum(powers(kin, gravity_actions(self.mechanism, kin)).values(),
                                   np.zeros(theta.size))
        return Reduced(theta, phi, J, dJ, moments)


def _velocity(kin, m, accel: bool = False):
    at = point(kin, m.centre)
    if not accel:
        # order-1 solutions: V = V_O + i·ω·(X − O)
        origin = kin.link_origins[m.link]
        o = point(kin, origin)
        vo = kin.velocity(origin)
        return (vo[..., 0] + 1j * vo[..., 1]) + 1j * kin.omega(m.link) * (at - o), None
    return link_motion(kin, m.link, at)


def reducer(mech: Mechanism, loads: Sequence | None = None) -> Reducer:
    """The `Reducer` of ``mech`` with ``loads`` (default: its ``[[load]]`` tables)."""
    if loads is None:
        from velplan.forces.parse import parse_loads

        loads = parse_loads(mech)
    return Reducer(mech, tuple(loads), mech.crank.sense, reference_angle(mech))


@dataclass(frozen=True, eq=False)
class Profile:
    """The reduced quantities over a cycle as piecewise Legendre series on `Panels`:
    J (variable part), J′ and every reduced moment at any travel, and their works.

    Attributes
    ----------
    panels : Panels
    labels : tuple of str
    nodes : Reduced
        Exact values at the panel nodes (flattened, P·n).
    """

    panels: Panels
    labels: tuple[str, ...]
    nodes: Reduced = field(repr=False)

    @cached_property
    def _stack(self) -> np.ndarray:
        P, n = self.panels.nodes.shape
        rows = [self.nodes.J, self.nodes.dJ] + [self.nodes.moments[k] for k in self.labels]
        return np.stack(rows).reshape(len(rows), P, n)

    @cached_property
    def coef(self) -> np.ndarray:
        """(2 + k, P, n) Legendre coefficients of J, J′ and the k moments."""
        return self.panels.coefficients(self._stack)

    @cached_property
    def edge_works(self) -> np.ndarray:
        """(k, P + 1) work of each moment from travel 0 to each panel edge, J."""
        return self.panels.integral(self._stack[2:])

    @cached_property
    def _icoef(self) -> np.ndarray:
        return self.panels.antiderivative(self.coef[2:])

    @cached_property
    def fields(self) -> np.ndarray:
        """(3, P, n) coefficients of J, J′ and the total moment of the loads and gravity."""
        c = self.coef
        return np.stack((c[0], c[1], c[2:].sum(axis=0) if c.shape[0] > 2 else np.zeros_like(c[0])))

    @cached_property
    def errors(self) -> dict[str, float]:
        """Estimated errors of what is read off the series (see `Panels.tail`; round-off added):
        ``"J"`` and ``"dJ"`` of a value of J (kg·m²) and J′ (kg·m²/rad), ``"M"`` of a value of
        the total moment (N·m), ``"work"`` of any work of the total moment from travel 0 (J)."""
        pn, f = self.panels, self.fields
        stack = self._stack
        tail = pn.tail(f)  # (3, P)
        eps = np.finfo(float).eps
        total = stack[2:].sum(axis=0) if stack.shape[0] > 2 else np.zeros(stack.shape[1:])
        scale = [np.abs(stack[0]).max(), np.abs(stack[1]).max(), np.abs(stack[2:]).sum(axis=0).max()
                 if stack.shape[0] > 2 else 0.0]
        roundoff = 64 * eps * float(np.sum(np.abs(total) * pn.weights)) if stack.shape[0] > 2 else 0.0
        return {"J": float(tail[0].max()) + 16 * eps * scale[0],
                "dJ": float(tail[1].max()) + 16 * eps * scale[1],
                "M": float(tail[2].max()) + 16 * eps * scale[2],
                "work": float(np.sum(2.0 * pn.half * tail[2])) + roundoff}

    @cached_property
    def relative_error(self) -> float:
        """The largest of the `errors` over the size of what they measure: the works over
        ∫|M| of the loads, J, J′ and M over their largest magnitudes."""
        e, st, w = self.errors, self._stack, self.panels.weights
        sizes = {"J": np.abs(st[0]).max(), "dJ": np.abs(st[1]).max()}
        if st.shape[0] > 2:
            sizes["M"] = np.abs(st[2:].sum(axis=0)).max()
            sizes["work"] = float(np.sum(np.abs(st[2:]) * w))
        return max((e[k] / v for k, v in sizes.items() if v > 0), default=0.0)

    @property
    def cycle(self) -> float:
        return self.panels.cycle

    def cycle_work(self) -> dict[str, float]:
        """Label → work over the cycle, J."""
        return {k: float(self.edge_works[i, -1]) for i, k in enumerate(self.labels)}

    def values(self, theta) -> np.ndarray:
        """(2 + k, m) J, J′ and the moments at travels ``theta`` (rad, taken within the cycle)."""
        return self.panels.evaluate(self.coef, np.atleast_1d(theta))

    def local(self, theta) -> tuple[np.ndarray, np.ndarray]:
        """((3, m) J, J′, M, (3, m) their derivatives d/dθ) at travels ``theta`` (rad), M the
        total moment of the loads and gravity."""
        return self.panels.evaluate(self.fields, np.atleast_1d(theta), deriv=True)

    @cached_property
    def _energy_coef(self) -> np.ndarray:
        """(4, P, n + 1): the total work's antiderivative, then J, J′ and M padded by a zero."""
        f = self.fields
        total = self._icoef.sum(axis=0) if self._icoef.shape[0] else np.zeros(f.shape[1:-1] + (f.shape[-1] + 1,))
        pad = np.concatenate((f, np.zeros(f.shape[:-1] + (1,))), axis=-1)
        return np.concatenate((total[None], pad))

    def energy(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(W, (3, m) J, J′, M, (3, m) their derivatives d/dθ) at travels ``theta`` (rad, in
        [0, cycle)), W the total work of the loads and gravity from travel 0: one locate and
        one basis for all (what the extremes' Newton steps call)."""
        pn = self.panels
        p, x = pn.locate(np.atleast_1d(theta))
        c = self._energy_coef[:, p, :]
        B, dB = legendre_basis(x, c.shape[-1], True)
        v = np.einsum("qmn,mn->qm", c, B)
        d = np.einsum("qmn,mn->qm", c[1:], dB) / pn.half[p]
        return self.edge_works.sum(axis=0)[p] + v[0], v[1:], d

    def works(self, theta) -> np.ndarray:
        """(k, m) work of each moment from travel 0 to ``theta`` (0 ≤ θ ≤ cycle), J."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        out = self.panels.integrate_to(self.coef[2:], self.edge_works, np.minimum(theta, self.cycle),
                                       icoef=self._icoef)
        at_end = theta >= self.cycle
        if np.any(at_end):
            out[:, at_end] = self.edge_works[:, -1:]
        return out


PANELS = 64
"""Panels a cycle starts with (×16 exact solver positions): with the panels cut at every node
of the loads, enough for round-off on every bundled and catalogue mechanism
(benchmarks/results/dynamics.md)."""
TOLERANCE = 1e-12
"""Relative error estimate (`Profile.relative_error`) above which the panels are doubled."""
MAX_PANELS = 1024


def profile(red: Reducer, cycle: float = 2 * np.pi, panels: int | None = None) -> Profile:
    """Tabulate ``red`` over a cycle (2π or 4π) on ``panels`` panels split at the loads'
    breakpoints (one solve of P·16 positions); ``panels`` None: `PANELS`, doubled while the
    estimated relative error exceeds `TOLERANCE` and halves at least (up to `MAX_PANELS`)."""
    b = red.breakpoints()
    if cycle > 2 * np.pi + 1e-9:
        b = np.concatenate([b + k * 2 * np.pi for k in range(int(round(cycle / (2 * np.pi))))])
    n = PANELS if panels is None else panels
    last = None
    while True:
        pn = panels_over(cycle, b, n)
        prof = Profile(pn, red.labels, red(pn.nodes.ravel()))
        if panels is not None or n >= MAX_PANELS or prof.relative_error <= TOLERANCE:
            return prof
        if last is not None and prof.relative_error > 0.5 * last.relative_error:
            return last  # no better for more panels: the round-off of the loads themselves (a steep ramp)
        last, n = prof, 2 * n
