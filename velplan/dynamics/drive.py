"""Drive selection (seed 003): from the useful power over the working stroke to a motor, a gear
ratio and the torque on each shaft, and the dynamics run again with that motor.

* useful power P(θ) = −Σ M_load(θ)·ω_m over the working stroke (the loads' reduced moments
  at the mean crank speed; gravity left out), its maximum and its mean (work / time);
* spent power P_max/η, required motor power P_max/η · reserve (seed 003: η = 0.75, × 1.1);
* the smallest motor of the catalogue (CSV, validated) not below it — of the preferred
  synchronous speed, else of 1500 rpm, else any;
* gear ratio u = n_nominal / n_crank; torques T = 9550·P/n on the motor shaft (kW, rpm), then
  × η_coupling on the fast shaft and × u·η_gear on the slow (crank) shaft;
* the dynamics again with the motor's rotor (J·u²) as a constant inertia and its Kloss
  characteristic through the rated point (M_K = λ·M_nom): the periodic regime and its δ.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

import numpy as np

from velplan.dynamics.motor import kloss_from_rating
from velplan.dynamics.spec import ConstantInertia, DriveSpec, MotorSpec
from velplan.errors import MechanismError, VelplanError

RPM = 30.0 / math.pi
"""rad/s → rev/min."""
COLUMNS = ("name", "power_kw", "synchronous_rpm", "nominal_rpm", "rotor_inertia", "critical_ratio",
           "starting_ratio")
SAMPLES = 2001
"""Crank travels sampled over the working stroke for the useful power's maximum."""


@dataclass(frozen=True)
class CatalogueMotor:
    """One motor of a catalogue: rated power (kW), synchronous and nominal speed (rpm), rotor
    inertia (kg·m²), critical (maximum) and starting torque over the rated torque."""

    name: str
    power_kw: float
    synchronous_rpm: float
    nominal_rpm: float
    rotor_inertia: float
    critical_ratio: float
    starting_ratio: float

    @property
    def rated_torque(self) -> float:
        """M_nom = 9550·P/n_nom, N·m."""
        return 9550.0 * self.power_kw / self.nominal_rpm


def read_catalogue(source: str | Path | None = None) -> tuple[CatalogueMotor, ...]:
    """Motors of a CSV catalogue (columns `COLUMNS`, ``#`` comment lines); the bundled AIR
    series when ``source`` is None. One-line `MechanismError` naming the row and the column."""
    if source is None:
        text = resources.files("velplan.examples").joinpath("motors.csv").read_text("utf-8")
        where = "the bundled motor catalogue"
    else:
        try:
            text = Path(source).read_text("utf-8-sig")
        except (OSError, UnicodeDecodeError) as exc:
            raise MechanismError(f"cannot read motor catalogue {source}: {exc}") from None
        where = f"motor catalogue {source}"
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    if not rows or tuple(c.strip() for c in rows[0]) != COLUMNS:
        raise MechanismError(f"{where}: the header must be {','.join(COLUMNS)}")
    motors = []
    for k, row in enumerate(rows[1:], 2):
        if len(row) != len(COLUMNS):
            raise MechanismError(f"{where}, row {k}: {len(row)} cells, expected {len(COLUMNS)}")
        values = []
        for col, cell in zip(COLUMNS[1:], row[1:]):
            try:
                x = float(cell)
            except ValueError:
                raise MechanismError(f"{where}, row {k}: {col} {cell!r} is not a number") from None
            if not (math.isfinite(x) and x > 0):
                raise MechanismError(f"{where}, row {k}: {col} must be > 0, not {cell!r}")
            values.append(x)
        m = CatalogueMotor(row[0].strip(), *values)
        if m.nominal_rpm >= m.synchronous_rpm:
            raise MechanismError(f"{where}, row {k} ({m.name}): nominal_rpm {m.nominal_rpm:g} must be below "
                                 f"synchronous_rpm {m.synchronous_rpm:g}")
        if m.critical_ratio <= 1:
            raise MechanismError(f"{where}, row {k} ({m.name}): critical_ratio must be > 1, not {m.critical_ratio:g}")
        motors.append(m)
    if not motors:
        raise MechanismError(f"{where} lists no motors")
    return tuple(motors)


@dataclass(frozen=True, eq=False)
class Drive:
    """The drive chosen for a mechanism.

    Attributes
    ----------
    travel : ndarray
        Crank travels over the working stroke (from position 1), rad.
    useful : ndarray
        Useful power there at ω_m, W.
    useful_max, useful_mean : float
        W (the mean is the work of the loads over the working stroke over its time).
    spent, required : float
        P_max/η and P_max/η·reserve, W.
    motor : CatalogueMotor
    ratio : float
        u = n_nominal / n_crank.
    torques : dict
        ``"motor"``, ``"fast"`` (after the coupling), ``"slow"`` (the crank's shaft), N·m.
    dynamics : Dynamics
        The dynamics again with this motor (Kloss through its rated point) and its rotor.
    delta : float
        δ of that run's periodic regime.
    """

    spec: DriveSpec
    travel: np.ndarray = field(repr=False)
    useful: np.ndarray = field(repr=False)
    useful_max: float
    useful_mean: float
    spent: float
    required: float
    motor: CatalogueMotor
    ratio: float
    torques: dict
    dynamics: object = field(repr=False)
    delta: float

    def to_dict(self) -> dict:
        m = self.motor
        return {"useful_power_max": self.useful_max, "useful_power_mean": self.useful_mean,
                "spent_power": self.spent, "required_power": self.required,
                "efficiency": self.spec.efficiency, "reserve": self.spec.reserve,
                "motor": {"name": m.name, "power_kw": m.power_kw, "synchronous_rpm": m.synchronous_rpm,
                          "nominal_rpm": m.nominal_rpm, "rotor_inertia": m.rotor_inertia,
                          "critical_ratio": m.critical_ratio, "starting_ratio": m.starting_ratio},
                "gear_ratio": self.ratio, "torques": dict(self.torques), "delta": self.delta}


def working_stroke(dyn) -> tuple[float, float]:
    """(start, span) of the working stroke in crank travel from position 1, rad; the whole
    cycle when the mechanism has no output slider or rocker."""
    from velplan.analysis.extremes import stroke

    st = stroke(dyn.mechanism)
    if st is None:
        return 0.0, dyn.spec.cycle
    start = float(np.mod(dyn.sense * (st.start.phi - dyn.reducer.phi1), 2 * np.pi))
    if start > 2 * np.pi - 1e-9:
        start = 0.0
    return start, math.pi + st.theta


def choose_motor(motors, required_w: float, preferred_rpm: float | None) -> CatalogueMotor:
    """The smallest motor not below ``required_w`` (W) of the preferred synchronous speed, else
    of 1500 rpm, else of any speed."""
    enough = [m for m in motors if m.power_kw * 1000.0 >= required_w]
    if not enough:
        biggest = max(motors, key=lambda m: m.power_kw)
        raise VelplanError(f"no motor of the catalogue gives {required_w / 1000:.3g} kW "
                           f"(the largest is {biggest.name}, {biggest.power_kw:g} kW)")
    for rpm in ((preferred_rpm,) if preferred_rpm else ()) + (1500.0, None):
        pick = [m for m in enough if rpm is None or m.synchronous_rpm == rpm]
        if pick:
            return min(pick, key=lambda m: (m.power_kw, -m.synchronous_rpm))
    raise VelplanError(f"no motor of {preferred_rpm:g} rpm gives {required_w / 1000:.3g} kW")  # pragma: no cover


def select_drive(dyn, spec: DriveSpec | None = None) -> Drive:
    """Choose the drive of the mechanism of ``dyn`` (a `velplan.dynamics.Dynamics`) by
    ``spec`` (the file's ``[dynamics.drive]``; its defaults when None). The dynamics with the
    motor reuse the reduction of ``dyn`` (`Dynamics.with_spec`)."""
    spec = spec or dyn.spec.drive or DriveSpec()
    wm = dyn.omega_mean
    if wm <= 0:
        raise VelplanError("drive selection needs the mean crank speed: give rpm or omega in [crank]")
    start, span = working_stroke(dyn)
    theta = start + np.linspace(0.0, span, SAMPLES)
    red = dyn.reducer(np.mod(theta, dyn.profile.cycle))
    loads = [k for k in red.moments if k != "gravity"]
    if not loads:
        raise VelplanError(f"{dyn.mechanism.name} declares no loads: there is no useful power to drive")
    useful = -sum((red.moments[k] for k in loads), np.zeros_like(theta)) * wm
    works = dyn.profile.works(np.mod(np.array([start, start + span]), dyn.profile.cycle))
    labels = list(dyn.profile.labels)
    rows = [labels.index(k) for k in loads]
    w_span = works[rows, 1] - works[rows, 0]
    if start + span > dyn.profile.cycle:  # the stroke runs over the end of the cycle
        w_span = w_span + np.array([dyn.profile.cycle_work()[k] for k in loads])
    useful_mean = float(-np.sum(w_span) * wm / span)
    useful_max = float(np.max(useful))
    if useful_max <= 0:
        raise VelplanError(f"{dyn.mechanism.name}: the loads do no resisting work over the working stroke")
    spent = useful_max / spec.efficiency
    required = spent * spec.reserve
    motor = choose_motor(read_catalogue(spec.catalogue), required, spec.synchronous_rpm)
    n_crank = wm * RPM
    ratio = motor.nominal_rpm / n_crank
    t_motor = 9550.0 * motor.power_kw / motor.nominal_rpm
    t_fast = t_motor * spec.coupling_efficiency
    torques = {"motor": t_motor, "fast": t_fast, "slow": t_fast * ratio * spec.gear_efficiency}
    m_k, n_k = kloss_from_rating(motor.power_kw, motor.nominal_rpm, motor.synchronous_rpm, motor.critical_ratio)
    again = replace(
        dyn.spec, drive=None, run=None,
        inertias=dyn.spec.inertias + (ConstantInertia(f"motor {motor.name}", motor.rotor_inertia, ratio),),
        motor=MotorSpec(kind="kloss", critical_torque=m_k, synchronous_rpm=motor.synchronous_rpm,
                        critical_rpm=n_k, ratio=ratio,
                        efficiency=spec.coupling_efficiency * spec.gear_efficiency))
    rerun = dyn.with_spec(again)
    return Drive(spec, theta, useful, useful_max, useful_mean, spent, required, motor, ratio, torques, rerun,
                 float(rerun.periodic.delta))
