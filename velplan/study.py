"""The study: one mechanism, its positions and its motion, with every result computed once.

A `Study` is the single place where velplan solves and constructs. Every CLI command, sheet,
notebook helper and view reads it; none calls `velplan.solve` or `Plan.evaluate` itself.
Results are computed on first use and cached:

=====================  =====================================================================
`phi`                  crank angles of the positions (rad): n standard positions from the
                       reference position in the sense of ω1, or angles given
`unit`                 the mechanism at those angles at unit crank speed (ω1 = 1 rad/s,
                       ε1 = 0): velocities are the analogues r′ = dr/dφ (m), accelerations r″
`kinematics`           the same at the study's motion: the file's constant ω1, or the
                       ω(φ), ε(φ) computed by the machine dynamics (``motion="dynamic"``)
`turn`                 a fine turn (720 steps) from position 1, at unit speed
`stroke`, `extremes`   extreme positions, H, θ, K
`plan(kind)`           the velocity / acceleration plan at every position (the acceleration
                       plan drawn on the velocity plan); μ is a view parameter
`table`, `diagrams`    transfer functions read off the plans; chord-method diagrams
`centres(k)`           the instant centres at position k by Kennedy lines, at a scheme's μl
`loads`, `forces()`    the declared loads; kinetostatics, Zhukovsky's lever and power method
`moment_curve`         M_b(φ) over a turn from position 1, its values at the positions, its mean
`dynamics`             reduction, steady state or run, flywheel (`velplan.dynamics`)
=====================  =====================================================================
"""

from __future__ import annotations

from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Literal

import numpy as np

from velplan.analysis.chord import Diagrams, kinematic_diagrams
from velplan.analysis.extremes import Extreme, Stroke, extremes, positions, reference_angle, stroke
from velplan.analysis.numbering import position_indices, position_number
from velplan.analysis.solver import Kinematics, group_point, solve
from velplan.errors import AssemblyError, MechanismError, VelplanError
from velplan.mechanism.loader import load
from velplan.mechanism.model import Mechanism
from velplan.options import Engine
from velplan.options import PlanKind as Kind
from velplan.plans.drafting import EXACT, Drafting
from velplan.plans.engine import Plan, PlanResult
from velplan.plans.table import TransferTable, transfer_table

if TYPE_CHECKING:
    from velplan.dynamics.analysis import Dynamics
    from velplan.forces.agreement import ForceAnalysis
    from velplan.forces.curve import MomentCurve
    from velplan.plans.centres import Construction

Motion = Literal["constant", "dynamic"]

TURN_STEPS = 720
"""Steps of the fine turn (a multiple of 240 and 360: the scheme's trajectories take every
third sample, the chord method's curves every second)."""


class Study:
    """One mechanism at its positions and motion; results computed once, on demand.

    Parameters
    ----------
    mechanism : Mechanism, str or Path
        The mechanism, a bundled example name or a TOML file.
    n : int
        Number of standard positions (12 on a course sheet), from the reference position.
    angles : array_like, optional
        Crank angles (rad) to study instead of the standard positions.
    motion : {"constant", "dynamic"}
        The crank turns at the file's constant ω1 (ε1 = 0), or at the ω(φ), ε(φ) found by the
        machine dynamics of its ``[dynamics]`` section.
    engine : {"numpy", "compiled", "auto"}
        The solver's engine (see `velplan.solve`; "auto", its default, too).
    check_assembly : bool
        Check once, before anything is solved, that the mechanism closes over a whole turn.
    delta : float, optional
        The coefficient of speed fluctuation δ the dynamics sizes the flywheel for (overrides
        the file's ``[dynamics] delta``).
    """

    def __init__(self, mechanism: Mechanism | str | Path, *, n: int = 12, angles=None,
                 motion: Motion = "constant", engine: Engine = "auto", check_assembly: bool = True,
                 delta: float | None = None):
        self.mechanism = load(mechanism) if isinstance(mechanism, (str, Path)) else mechanism
        if motion not in ("constant", "dynamic"):
            raise VelplanError(f"unknown motion {motion!r}; known motions: constant, dynamic")
        if angles is None and n < 1:
            raise MechanismError(f"number of positions must be ≥ 1, not {n}")
        self._angles = None if angles is None else np.atleast_1d(np.asarray(angles, dtype=float))
        self.n = n if self._angles is None else len(self._angles)
        self.motion = motion
        self.engine = engine
        self.delta = delta
        self._plans: dict = {}
        self._forces: dict = {}
        self._centres: dict = {}
        if check_assembly:
            self.check_assembly()

    def __repr__(self) -> str:
        return f"Study({self.mechanism.name!r}, n={self.n}, motion={self.motion!r})"

    # -- structure and positions ---------------------------------------------------------------

    def check_assembly(self) -> None:
        """Raise `AssemblyError` naming the group and the crank angles where it cannot close."""
        if "_assembled" not in self.__dict__:
            from velplan.analysis.assembly import check_full_rotation

            check_full_rotation(self.mechanism)
            self.__dict__["_assembled"] = True

    @cached_property
    def sense(self) -> float:
        """+1 when the crank turns counter-clockwise, −1 clockwise."""
        return self.mechanism.crank.sense

    @cached_property
    def stroke(self) -> Stroke | None:
        """Stroke H, the extremes at the ends of the working stroke, θ and K (None without an
        output)."""
        return stroke(self.mechanism)

    @cached_property
    def extremes(self) -> dict[str, list[Extreme]]:
        """Extreme positions of every link angle and prismatic slide."""
        return extremes(self.mechanism)

    @cached_property
    def reference(self) -> float:
        """Crank angle of position 1, rad (`velplan.analysis.extremes.reference_angle`)."""
        return reference_angle(self.mechanism)

    @cached_property
    def phi(self) -> np.ndarray:
        """(n,) crank angles of the positions, rad: the angles given, else the n standard
        positions (`velplan.analysis.extremes.positions`)."""
        if self._angles is not None:
            return self._angles
        return positions(self.mechanism, self.n)

    def _indices(self, positions) -> list[int]:
        """Array indices (0…n−1) of the position numbers ``positions`` (1…n; one or several);
        `VelplanError` naming a number outside 1…n."""
        return position_indices(positions, self.n).tolist()

    def require_assembled(self, positions=None) -> None:
        """Raise `AssemblyError` naming the group, its point and the crank angle at the first of
        ``positions`` (position numbers 1…n; all by default) where the mechanism is not
        assembled or is singular."""
        kin = self.kinematics
        bad = [i for i in (range(len(kin)) if positions is None else self._indices(positions))
               if not kin.valid[i]]
        if not bad:
            return
        i = bad[0]
        deg = float(kin.phi_deg[i])
        for g in self.mechanism.groups:
            c = kin.condition[i, kin.group_index[g.name]] if g.name in kin.group_index else 1.0
            if not (np.isfinite(c) and c > 0):
                what = "cannot be assembled" if not np.isfinite(c) else "is singular (its lines are parallel)"
                raise AssemblyError(f"group {g.name!r} ({g.kind}) {what}: point {group_point(g)!r} "
                                    f"at crank angle {deg:.6g}°", group=g.name, point=group_point(g), phi_deg=deg)
        raise AssemblyError(f"{self.mechanism.name}: no finite solution at crank angle {deg:.6g}°",
                            group="", point="", phi_deg=deg)

    # -- kinematics ----------------------------------------------------------------------------

    @cached_property
    def unit(self) -> Kinematics:
        """The positions at ω1 = 1 rad/s, ε1 = 0: velocities are the analogues dr/dφ (m),
        accelerations d²r/dφ² (m)."""
        return solve(self.mechanism, self.phi, omega1=1.0, epsilon1=0.0, engine=self.engine)

    @cached_property
    def crank_motion(self) -> tuple[float | np.ndarray, float | np.ndarray]:
        """(ω1, ε1) of the crank at the positions: floats for a constant motion, (n,) arrays
        (rad/s, rad/s²) for the computed one."""
        if self.motion == "constant":
            return self.mechanism.crank.omega, self.mechanism.crank.epsilon
        return self.dynamics.motion_at(self.phi)

    @cached_property
    def kinematics(self) -> Kinematics:
        """The positions at the study's motion."""
        w, e = self.crank_motion
        if self.motion == "constant":
            return solve(self.mechanism, self.phi, omega1=w, epsilon1=e, engine=self.engine)
        return self.unit.at_speed(w, e)

    @cached_property
    def turn(self) -> Kinematics:
        """A whole turn from position 1 in the sense of rotation, `TURN_STEPS` steps, at
        ω1 = 1 rad/s (positions for trajectories and extents; analogues for the diagrams)."""
        rot = np.linspace(0.0, 2 * np.pi, TURN_STEPS + 1)
        return solve(self.mechanism, self.phi[0] + self.sense * rot, omega1=1.0, epsilon1=0.0,
                     engine=self.engine)

    @cached_property
    def other_extreme(self) -> Kinematics | None:
        """The mechanism at the extreme position that ends the working stroke, when it is not
        one of the n positions (None otherwise, or without an output): the scheme draws it."""
        st = self.stroke
        if st is None:
            return None
        gap = np.abs((self.phi - st.end.phi + np.pi) % (2 * np.pi) - np.pi)
        if gap.min() < np.radians(0.5):
            return None
        return solve(self.mechanism, [st.end.phi], omega1=1.0, epsilon1=0.0, order=0, engine=self.engine)

    # -- plans -------------------------------------------------------------------------------

    @cached_property
    def construction(self) -> Plan:
        """The construction (steps) of the mechanism's plans (with the crank's tangential
        acceleration when the crank speeds up or slows down)."""
        return Plan.of(self.mechanism, tangential=True if self.motion == "dynamic" else None)

    def plan(self, kind: Kind = "velocity", *, drafting: Drafting = EXACT, scale_v: float | None = None,
             scale_a: float | None = None, positions=None, only=None,
             on_failure: Literal["nan", "raise"] = "nan") -> PlanResult:
        """The ``kind`` plan at every position (or at ``positions``, position numbers 1…n), drawn
        exactly or at ``drafting`` precision; an acceleration plan is drawn on the velocity plan.

        An exact plan is constructed once and drawn at any scale μv, μa on request (its images
        scale with μ; nothing is constructed again); a drafted one is constructed at its scale,
        since rounding on paper depends on it. ``only`` limits the construction to the steps
        that the named points and links need.
        """
        if kind not in ("velocity", "acceleration"):
            raise VelplanError(f"unknown plan kind {kind!r}; known kinds: velocity, acceleration")
        scale = scale_v if kind == "velocity" else scale_a
        if drafting.exact and positions is None and only is None and on_failure == "nan":
            res = self._plans.get((kind,))
            if res is None:
                velocity = self.plan("velocity") if kind == "acceleration" else None
                res = self._plans[(kind,)] = self.construction.evaluate(
                    self.kinematics, kind=kind, velocity=velocity)
            return res if scale is None else res.at_scale(scale)
        # the numbers, checked (1…n, whole) before the cache is asked
        pos = None if positions is None else tuple(position_number(i) for i in self._indices(positions))
        key = (kind, drafting, scale_v, scale_a, pos, None if only is None else tuple(only), on_failure)
        res = self._plans.get(key)
        if res is None:
            res = self._plans[key] = self.construction.evaluate(
                self.kinematics, kind=kind, drafting=drafting, scale_v=scale_v, scale_a=scale_a,
                positions=None if pos is None else list(pos), only=only, on_failure=on_failure)
        return res

    def centres(self, position: int, *, mu_l: float | None = None, drafting: Drafting = EXACT) -> Construction:
        """The instant centres at position number ``position`` (1…n) found by Kennedy lines
        (`velplan.plans.centres.construct_centres`), at the scheme's scale ``mu_l`` (m/mm; a
        standard one by default) and ``drafting`` precision; `MechanismError` where the mechanism
        is not assembled."""
        i = self._indices(position)[0]
        key = (i, mu_l, drafting)
        con = self._centres.get(key)
        if con is None:
            from velplan.plans.centres import construct_centres

            con = self._centres[key] = construct_centres(self.kinematics, position_number(i), mu_l=mu_l,
                                                         drafting=drafting)
        return con

    # -- tables and diagrams -----------------------------------------------------------------

    @cached_property
    def table(self) -> TransferTable:
        """Transfer functions V/ω1 and ω/ω1 read off the exact velocity plans: the one table of
        the study, whose rows the sheet, the answer key of a batch and the note print."""
        return transfer_table(self.plan("velocity"))

    @cached_property
    def diagrams(self) -> Diagrams:
        """The output's s, ds/dφ, d²s/dφ² over a turn by the chord method and exactly."""
        return kinematic_diagrams(self.mechanism, nodes=self.unit, turn=self.turn.take(slice(None, None, 2)),
                                  sense=self.sense)

    # -- forces ------------------------------------------------------------------------------

    @cached_property
    def loads(self) -> tuple:
        """The file's ``[[load]]`` tables as load values."""
        from velplan.forces.parse import parse_loads

        return parse_loads(self.mechanism)

    def forces(self, *, drafting: Drafting = EXACT, mu_v: float | None = None, gravity: bool = True,
               inertia: bool = True) -> ForceAnalysis:
        """Kinetostatics, Zhukovsky's lever and the power method at every position
        (`velplan.forces.ForceAnalysis`), at the study's motion."""
        key = (drafting, mu_v, gravity, inertia)
        res = self._forces.get(key)
        if res is None:
            from velplan.forces.agreement import force_analysis

            plan = self.plan("velocity", drafting=drafting, scale_v=None if drafting.exact else mu_v)
            res = force_analysis(self.kinematics, plan, self.loads, gravity=gravity, inertia=inertia,
                                 mu_v=mu_v)
            self._forces[key] = res
        return res

    @cached_property
    def moment_curve(self) -> MomentCurve:
        """M_b by kinetostatics over a revolution from position 1 (`turn_forces`), its values at
        the n positions (`forces`) and its mean over the turn."""
        from velplan.forces.curve import moment_curve

        return moment_curve(self.turn_forces(), self.forces(), self.sense)

    def turn_forces(self, *, gravity: bool = True, inertia: bool = True) -> ForceAnalysis:
        """The force analysis over the fine turn (every third step: 241 angles), at the file's
        constant ω1 or at the computed motion."""
        key = ("turn", gravity, inertia)
        res = self._forces.get(key)
        if res is None:
            from velplan.forces.agreement import force_analysis

            unit = self.turn.take(slice(None, None, 3))
            if self.motion == "constant":
                kin = unit.at_speed(self.mechanism.crank.omega, self.mechanism.crank.epsilon)
            else:
                kin = unit.at_speed(*self.dynamics.motion_at(unit.phi))
            plan = self.construction.evaluate(kin, kind="velocity")
            res = self._forces[key] = force_analysis(kin, plan, self.loads, gravity=gravity, inertia=inertia)
        return res

    def forces_in_chunks(self, positions, chunk: int, *, drafting: Drafting = EXACT, mu_v: float | None = None,
                         gravity: bool = True, inertia: bool = True):
        """`forces` at the position numbers ``positions`` (1…n), ``chunk`` positions analysed at
        a time (bounded memory): (first, analysis, lever − kinetostatics in %) per chunk, ``first``
        counting in ``positions``. The plan's scale μv and the largest |M_b| that the per-cent
        difference is judged against are those of all positions, so the numbers are those of
        `forces` (to round-off)."""
        from velplan.analysis.chunks import chunked_kinematics
        from velplan.forces.agreement import force_analysis, lever_difference_percent

        index = position_indices(positions, self.n)
        (w, e), scale_v, peak = self.crank_motion, None if drafting.exact else mu_v, None
        if len(index) < self.n or self.n > chunk:
            scale_v, peak = self._force_extent(chunk, scale_v, gravity=gravity, inertia=inertia)
        pick = lambda x: x[index] if isinstance(x, np.ndarray) else x  # noqa: E731
        for a, kin in chunked_kinematics(self.mechanism, self.phi[index], omega1=pick(w), epsilon1=pick(e),
                                         engine=self.engine, chunk=chunk):
            plan = self.construction.evaluate(kin, kind="velocity", drafting=drafting, scale_v=scale_v)
            res = force_analysis(kin, plan, self.loads, gravity=gravity, inertia=inertia, mu_v=mu_v)
            lever, ks = res.lever.balancing_moment, res.kinetostatics.balancing_moment
            if peak is None:
                yield a, res, lever_difference_percent(lever, ks)
            else:  # judged against the largest |M_b| of all positions, appended as one more
                yield a, res, lever_difference_percent(np.append(lever, 0.0), np.append(ks, peak))[:-1]

    def _force_extent(self, chunk: int, scale_v: float | None, *, gravity: bool, inertia: bool):
        """(μv, (m/s)/mm: ``scale_v`` or the standard scale of all positions; the largest |M_b|
        by kinetostatics, N·m), ``chunk`` positions at a time."""
        from velplan.analysis.chunks import chunked_kinematics
        from velplan.forces.agreement import mechanism_actions
        from velplan.forces.kinetostatics import kinetostatics
        from velplan.plans.engine import auto_scale

        (w, e), mech = self.crank_motion, self.mechanism
        scales, peak = [], 0.0
        for _, kin in chunked_kinematics(mech, self.phi, omega1=w, epsilon1=e, engine=self.engine, chunk=chunk):
            if scale_v is None:  # the standard scale grows with the largest |V|: the largest chunk's
                scales.append(auto_scale(kin, slice(None), "velocity"))
            acts = mechanism_actions(mech, kin, self.loads, gravity=gravity, inertia=inertia)
            peak = max(peak, float(np.nanmax(np.abs(kinetostatics(mech, kin, acts).balancing_moment), initial=0.0)))
        return (max(scales) if scale_v is None else scale_v), peak

    # -- dynamics ----------------------------------------------------------------------------

    @cached_property
    def dynamics(self) -> Dynamics:
        """The machine dynamics of the ``[dynamics]`` section (`velplan.dynamics`)."""
        from velplan.dynamics import dynamics_analysis

        return dynamics_analysis(self.mechanism, loads=self.loads, delta=self.delta)
