"""The machine dynamics of one mechanism: reduction, steady state (or periodic regime with a
motor, or a run), flywheel — the result the CLI, the study and the sheet read.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Sequence

import numpy as np

from velplan.dynamics.flywheel import Flywheel, size_flywheel
from velplan.dynamics.motor import Motor
from velplan.dynamics.reduction import Profile, Reducer, profile, reducer
from velplan.dynamics.run import Periodic, Run, periodic, simulate
from velplan.dynamics.spec import DynamicsSpec, parse_dynamics
from velplan.dynamics.steady import EnergyCurve, SteadyState, curve_of, steady_state
from velplan.errors import VelplanError, deprecated
from velplan.mechanism.model import Mechanism

PANELS = None
"""Default panels: `velplan.dynamics.reduction.PANELS`, doubled until the error estimate is at
round-off (`velplan.dynamics.reduction.profile`)."""


@dataclass(frozen=True, eq=False)
class Dynamics:
    """The dynamics of a mechanism (see `dynamics_analysis`).

    Attributes
    ----------
    mechanism : Mechanism
    spec : DynamicsSpec
    reducer : Reducer
    profile : Profile
    constants : tuple of (str, float)
        Constant inertias reduced to the crank (the crank's own, then the declared ones), kg·m².
    declared : float
        Their sum, kg·m².
    driving : float
        Constant driving moment from zero cycle work, N·m on the crank (positive when it drives).
    curve : EnergyCurve
        Total work A(θ) = driving·θ + Σ works of loads and gravity, and J(θ).
    flywheel : Flywheel or None
        Sized when δ is required.
    inertia : float
        Constant inertia the motion uses: max(flywheel exact, declared), else declared, kg·m².
    steady : SteadyState or None
        With the constant driving moment at the [crank] speed as ω_m (no run).
    periodic : Periodic or None
        With a speed-dependent motor (kloss or table) and no run.
    run : Run or None
    """

    mechanism: Mechanism = field(repr=False)
    spec: DynamicsSpec
    reducer: Reducer = field(repr=False)
    profile: Profile = field(repr=False)
    constants: tuple
    declared: float
    driving: float
    motor: Motor
    curve: EnergyCurve = field(repr=False)
    flywheel: Flywheel | None
    inertia: float
    steady: SteadyState | None
    periodic: Periodic | None
    run: Run | None

    @property
    def sense(self) -> float:
        return self.reducer.sense

    def travel(self, phi) -> np.ndarray:
        """Crank travel from position 1 of crank angles ``phi`` (rad), in [0, 2π)."""
        return np.mod(self.sense * (np.asarray(phi, dtype=float) - self.reducer.phi1), 2 * np.pi)

    def speed_at_travel(self, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(t s, w = |ω| rad/s, dw/dt rad/s²) at travels ``theta`` (rad) of the computed motion."""
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        if self.run is not None:
            return self.run.at_travel(np.clip(theta, 0.0, self.run.travel))
        if self.periodic is not None:
            return self.periodic.at_travel(theta)
        st = self.steady
        return st.time(theta), st.omega(theta), st.epsilon(theta)

    def motion_at(self, phi) -> tuple[np.ndarray, np.ndarray]:
        """(ω1, ε1) of the crank at crank angles ``phi`` (rad): signed, rad/s and rad/s²."""
        _, w, e = self.speed_at_travel(self.travel(phi))
        return self.sense * w, self.sense * e

    @cached_property
    def omega_mean(self) -> float:
        return abs(self.mechanism.crank.omega)

    def table(self, n: int = 12, *, exact: bool = True) -> dict[str, np.ndarray]:
        """Per-position arrays at ``n`` standard positions (``n``·turns for a 4π cycle; over the
        run's travel, both ends included, for a run): phi_deg (absolute), travel_deg, omega,
        epsilon (signed), t, J_red (links + declared constants), J_red_prime (dJ/dφ),
        J_total (with the flywheel), M_red (loads + gravity, positive when driving), M_sum,
        A_drive, A_resist, A_sum and M_<load> per load.

        ``exact=False`` reads J, J′ and the moments off the tabulated profile instead of
        solving at these positions (equal to round-off between the loads' jumps; for curves
        of many points)."""
        return self.table_at(self.travels(n), exact=exact)

    def travels(self, n: int = 12) -> np.ndarray:
        """Crank travels (rad) of `table`'s ``n`` positions: ``n`` per turn over the cycle, or
        over the run's travel with both ends."""
        if self.run is not None:
            return np.linspace(0.0, self.run.travel, n + 1)
        return np.arange(n * self.spec.cycle_turns) * (2 * np.pi / n)

    def table_at(self, travels: np.ndarray, *, exact: bool = True) -> dict[str, np.ndarray]:
        """`table`'s quantities at the crank travels ``travels`` (rad, from the cycle's start;
        a slice of `travels` for a table written in chunks)."""
        return self._rows(np.asarray(travels, dtype=float), exact)

    def curves(self, m: int = 720) -> dict[str, np.ndarray]:
        """The `table` quantities at ``m`` + 1 evenly spaced travels over the cycle (or the
        run's travel), both ends included, from the profile (no solve): for drawing."""
        end = self.run.travel if self.run is not None else self.profile.cycle
        return self._rows(np.linspace(0.0, end, m + 1), False)

    def _rows(self, theta: np.ndarray, exact: bool) -> dict[str, np.ndarray]:
        t, w, e = self.speed_at_travel(theta)
        cycle = self.profile.cycle
        whole, within = np.divmod(theta, cycle)
        last = (within == 0) & (whole > 0)  # the end of a cycle: the cycle's own values
        whole, within = np.where(last, whole - 1, whole), np.where(last, cycle, within)
        if exact:
            red = self.reducer(np.mod(theta, cycle))
            J, dJ, moments = red.J, red.dJ, red.moments
        else:
            vals = self.profile.values(np.mod(theta, cycle))
            J, dJ = vals[0], vals[1]
            moments = {k: vals[2 + i] for i, k in enumerate(self.profile.labels)}
        labels = self.profile.labels
        works = (self.profile.works(within) + whole * np.array(
            [self.profile.cycle_work()[k] for k in labels])[:, None]) if labels else np.zeros((0, theta.size))
        a_res = works.sum(axis=0)
        resisting = sum(moments.values(), np.zeros(theta.size))
        out = {
            "phi_deg": np.mod(np.degrees(self.reducer.phi(theta)), 360.0), "travel_deg": np.degrees(theta),
            "omega": self.sense * w, "epsilon": self.sense * e, "t": t,
            "J_red": self.declared + J, "J_red_prime": self.sense * dJ,
            "J_total": self.inertia + J, "M_red": resisting,
        }
        drive = self._drive_moment(w)
        out["M_drive"] = drive
        out["M_sum"] = drive + resisting
        out["A_resist"] = a_res
        if self.run is None and self.periodic is None:
            out["A_drive"] = self.driving * theta
            out["A_sum"] = out["A_drive"] + a_res
        else:
            # the motor's work from the motion itself: ΔT = ½(J_I + J)w² − its value at θ = 0
            _, w0, _ = self.speed_at_travel(np.zeros(1))
            j0 = float(self.profile.values(np.zeros(1))[0, 0])
            out["A_sum"] = 0.5 * (self.inertia + J) * w * w - 0.5 * (self.inertia + j0) * float(w0[0]) ** 2
            out["A_drive"] = out["A_sum"] - a_res
        for k, v in moments.items():
            out[f"M_{k}"] = v
        return out

    def wittenbauer(self, size_mm: float = 150.0, precision: float = 0.5, *, mu_J: float | None = None,
                    mu_T: float | None = None):
        """Wittenbauer's diagram of the sized flywheel at scales fitting ``size_mm`` (mm) or
        at the scales given (kg·m²/mm, J/mm), its segment read off at ``precision`` mm
        (`velplan.dynamics.flywheel.wittenbauer`); None when no δ is required."""
        if self.flywheel is None:
            return None
        from velplan.dynamics.flywheel import wittenbauer

        return wittenbauer(self.curve, self.flywheel.omega_mean, self.flywheel.delta,
                           size_mm=size_mm, precision=precision, mu_J=mu_J, mu_T=mu_T,
                           found=list(self.flywheel.found) or None)

    @cached_property
    def drive(self):
        """The drive chosen by the file's ``[dynamics.drive]`` (seed 003), or None without one
        (`velplan.dynamics.drive.select_drive` chooses one with the defaults on request)."""
        if self.spec.drive is None:
            return None
        from velplan.dynamics.drive import select_drive

        return select_drive(self)

    def with_spec(self, spec: DynamicsSpec) -> Dynamics:
        """The same mechanism and reduction under another ``spec`` of the same cycle (another
        motor, inertias, run): no new solve."""
        if abs(spec.cycle - self.profile.cycle) > 1e-12:
            raise VelplanError(f"dynamics: with_spec needs the same cycle ({self.profile.cycle:g} rad), "
                               f"not {spec.cycle:g}")
        return assemble(self.mechanism, spec, self.reducer, self.profile)

    @cached_property
    def errors(self) -> dict[str, float]:
        """Estimated errors of the results (absolute, in their units): ``driving_moment``
        (N·m), ``flywheel_exact``, ``flywheel_mertsalov``, ``flywheel_wittenbauer`` (kg·m²),
        ``omega`` (rad/s, of ω_max, ω_min, ω_m), ``delta``, ``period`` or ``time`` (s),
        ``travel`` (rad, of a run to a time); from the panels' series and the ODE's tolerance."""
        e = {"driving_moment": self.profile.errors["work"] / self.profile.cycle}
        if self.flywheel is not None:
            e.update({f"flywheel_{k}": v for k, v in self.flywheel.errors.items()})
        motion = self.run or self.periodic or self.steady
        e.update(motion.errors)
        return {k: float(v) for k, v in e.items()}

    def _drive_moment(self, w) -> np.ndarray:
        if self.run is None and self.periodic is None:
            return np.full(np.shape(w), self.driving)
        return np.asarray(self.motor.moment(w), dtype=float)


def dynamics_analysis(mech: Mechanism, loads: Sequence | None = None, *, spec: DynamicsSpec | None = None,
            delta: float | None = None, panels: int | None = PANELS) -> Dynamics:
    """The dynamics of ``mech`` from its ``[dynamics]`` section (or ``spec``).

    Parameters
    ----------
    mech : Mechanism
    loads : sequence of loads, optional
        Default: the file's ``[[load]]`` tables.
    spec : DynamicsSpec, optional
        Default: `parse_dynamics` of the file; an absent section gives the defaults (steady
        state with the constant driving moment, no flywheel sizing).
    delta : float, optional
        Overrides the required δ.
    panels : int, optional
        Panels over a cycle (16 exact positions each); None: 64, doubled while the estimated
        relative error exceeds 1e-12.
    """
    spec = parse_dynamics(mech) if spec is None else spec
    if delta is not None:
        if not 0 < delta < 1:
            raise VelplanError(f"--delta must be between 0 and 1 (exclusive), not {delta:g}")
        from dataclasses import replace

        spec = replace(spec, delta=float(delta))
    red = reducer(mech, loads)
    return assemble(mech, spec, red, profile(red, spec.cycle, panels))


analyse = deprecated(dynamics_analysis, "velplan.dynamics.analyse")


def assemble(mech: Mechanism, spec: DynamicsSpec, red: Reducer, prof: Profile) -> Dynamics:
    """The dynamics of ``mech`` by ``spec`` on a reduction already tabulated (``prof`` over
    ``spec.cycle``): what `dynamics_analysis` and `Dynamics.with_spec` share."""
    constants = []
    if red.crank_inertia > 0:
        constants.append((f"crank {mech.crank.link}", red.crank_inertia))
    constants += [(c.name, c.reduced) for c in spec.inertias]
    declared = float(sum(j for _, j in constants))
    driving = -sum(prof.cycle_work().values()) / spec.cycle
    motor = Motor(spec.motor, driving)
    curve = curve_of(prof, driving)
    wm = abs(mech.crank.omega)
    fly = None
    if spec.delta is not None:
        if wm == 0:
            raise VelplanError("dynamics: sizing a flywheel needs the mean crank speed: give rpm or omega in [crank]")
        fly = size_flywheel(curve, wm, spec.delta, declared, spec.flywheel)
    inertia = max(fly.exact, declared) if fly is not None else declared
    steady = per = run = None
    if spec.run is not None:
        r = spec.run
        run = simulate(prof, inertia, motor.moment, abs(r.omega),
                       travel=None if r.travel_deg is None else math.radians(r.travel_deg),
                       time=r.time, time_limit=r.time_limit, scalar=motor.scalar())
    elif motor.depends_on_speed:
        guess = motor.speed_for(driving, wm) or wm or 1.0
        per = periodic(prof, inertia, motor.moment, guess, scalar=motor.scalar())
    else:
        if wm == 0:
            raise VelplanError("dynamics: the steady state needs the mean crank speed: give rpm or omega in [crank]")
        steady = steady_state(curve, wm, inertia, driving, spec.cycle, prof)
    return Dynamics(mech, spec, red, prof, tuple(constants), declared, driving, motor, curve, fly, inertia,
                    steady, per, run)
