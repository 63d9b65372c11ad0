"""The ``[dynamics]`` section of a mechanism file, parsed into frozen values.

Every error is a one-line `MechanismError` naming the table, the key and the value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from velplan.errors import MechanismError
from velplan.mechanism.model import Mechanism

SHAPES = ("disc", "rim")
MOTOR_KINDS = ("constant", "kloss", "table")


@dataclass(frozen=True)
class ConstantInertia:
    """An inertia turning with the crank at a fixed speed ratio.

    Attributes
    ----------
    name : str
    inertia : float
        About its own axis, kg·m².
    ratio : float
        Its speed over the crank's (> 0).
    """

    name: str
    inertia: float
    ratio: float

    @property
    def reduced(self) -> float:
        """J·u², kg·m² reduced to the crank."""
        return self.inertia * self.ratio**2


@dataclass(frozen=True)
class FlywheelSpec:
    """Where the flywheel sits and its shape.

    ``ratio``: its shaft's speed over the crank's. ``shape``: a solid ``disc`` of width
    b = width_ratio·D, or a ``rim`` of mean diameter D, radial thickness thickness_ratio·D
    and width width_ratio·D (hub and spokes neglected). ``density`` kg/m³.
    """

    ratio: float = 1.0
    shape: Literal["disc", "rim"] = "disc"
    density: float = 7800.0
    width_ratio: float = 0.2
    thickness_ratio: float = 0.1


@dataclass(frozen=True)
class MotorSpec:
    """The driving moment.

    ``constant``: ``torque`` N·m on the motor shaft (None: found from zero cycle work).
    ``kloss``: M = 2·M_K·s·s_K/(s² + s_K²), s = 1 − n/n0, s_K = 1 − n_K/n0.
    ``table``: torque (N·m) interpolated in rpm (increasing), held at the ends.
    ``ratio`` = motor speed / crank speed, ``efficiency`` η of the transmission.
    """

    kind: Literal["constant", "kloss", "table"] = "constant"
    torque: float | None = None
    critical_torque: float = 0.0
    synchronous_rpm: float = 0.0
    critical_rpm: float = 0.0
    rpm: tuple[float, ...] = ()
    torques: tuple[float, ...] = ()
    ratio: float = 1.0
    efficiency: float = 1.0


@dataclass(frozen=True)
class RunSpec:
    """An unsteady run from position 1: ``omega`` rad/s (signed; 0 = from rest), until a
    crank travel ``travel_deg`` or a time ``time`` s; ``time_limit`` s bounds a run to a travel."""

    omega: float
    travel_deg: float | None = None
    time: float | None = None
    time_limit: float = 60.0


@dataclass(frozen=True)
class DriveSpec:
    """Drive selection (seed 003): overall efficiency η, reserve factor, catalogue CSV (None:
    the bundled one), preferred synchronous rpm, stage efficiencies of coupling and gear."""

    efficiency: float = 0.75
    reserve: float = 1.1
    catalogue: str | None = None
    synchronous_rpm: float | None = None
    coupling_efficiency: float = 0.98
    gear_efficiency: float = 0.97


@dataclass(frozen=True)
class DynamicsSpec:
    """The whole ``[dynamics]`` section.

    Attributes
    ----------
    delta : float or None
        Required coefficient of speed fluctuation δ (sizes the flywheel).
    cycle_turns : int
        1 (cycle 2π) or 2 (4π, a four-stroke engine).
    inertias : tuple of ConstantInertia
    flywheel : FlywheelSpec
    motor : MotorSpec
    run : RunSpec or None
    drive : DriveSpec or None
    """

    delta: float | None = None
    cycle_turns: int = 1
    inertias: tuple[ConstantInertia, ...] = ()
    flywheel: FlywheelSpec = FlywheelSpec()
    motor: MotorSpec = MotorSpec()
    run: RunSpec | None = None
    drive: DriveSpec | None = None

    @property
    def cycle(self) -> float:
        """Cycle length, rad of crank travel."""
        return 2.0 * math.pi * self.cycle_turns


# -- helpers -------------------------------------------------------------------------------


def _keys(table: dict, allowed: tuple[str, ...], where: str) -> None:
    if not isinstance(table, Mapping):
        raise MechanismError(f"{where} must be a table, not {table!r}")
    for k in table:
        if k not in allowed:
            raise MechanismError(f"{where}: unknown key {k!r}; known keys: {', '.join(allowed)}")


def _number(table: dict, key: str, where: str, default=None, *, positive=False, nonneg=False):
    if key not in table:
        return default
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise MechanismError(f"{where} {key} must be a finite number, not {v!r}")
    v = float(v)
    if positive and not v > 0:
        raise MechanismError(f"{where} {key} must be > 0, not {v:g}")
    if nonneg and v < 0:
        raise MechanismError(f"{where} {key} must be ≥ 0, not {v:g}")
    return v


def _fraction(table: dict, key: str, where: str, default):
    v = _number(table, key, where, default)
    if v is not None and not 0.0 < v <= 1.0:
        raise MechanismError(f"{where} {key} must be in (0, 1], not {v:g}")
    return v


def _ratio(table: dict, where: str, crank_rpm: float, *, required: bool, default: float = 1.0) -> float:
    if "ratio" in table and "rpm" in table:
        raise MechanismError(f"{where}: give ratio or rpm, not both")
    if "rpm" in table:
        rpm = _number(table, "rpm", where, positive=True)
        if crank_rpm == 0:
            raise MechanismError(f"{where} rpm needs a crank speed ≠ 0 in [crank]; give ratio instead")
        return rpm / abs(crank_rpm)
    if "ratio" in table:
        return _number(table, "ratio", where, positive=True)
    if required:
        raise MechanismError(f"{where}: missing ratio (or rpm)")
    return default


def _list(table: dict, key: str, where: str) -> tuple[float, ...]:
    v = table.get(key)
    if not isinstance(v, (list, tuple)) or len(v) < 2:
        raise MechanismError(f"{where} {key} must be a list of at least 2 numbers, not {v!r}")
    out = []
    for i, x in enumerate(v):
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
            raise MechanismError(f"{where} {key}[{i}] must be a finite number, not {x!r}")
        out.append(float(x))
    return tuple(out)


# -- parsing -------------------------------------------------------------------------------


def parse_dynamics(mech: Mechanism, table: dict | None = None) -> DynamicsSpec:
    """The `DynamicsSpec` of ``mech.dynamics`` (or of ``table``); defaults when absent."""
    table = mech.dynamics if table is None else table
    if table is None:
        return DynamicsSpec()
    where = "[dynamics]"
    _keys(table, ("delta", "cycle_turns", "inertia", "flywheel", "motor", "run", "drive"), where)
    delta = _number(table, "delta", where)
    if delta is not None and not 0.0 < delta < 1.0:
        raise MechanismError(f"[dynamics] delta must be between 0 and 1 (exclusive), not {delta:g}")
    turns = table.get("cycle_turns", 1)
    if isinstance(turns, bool) or turns not in (1, 2):
        raise MechanismError(f"[dynamics] cycle_turns must be 1 (2π) or 2 (4π), not {turns!r}")
    crank_rpm = mech.crank.rpm
    inertias = []
    raw = table.get("inertia", [])
    if isinstance(raw, Mapping):
        raw = [raw]
    if not isinstance(raw, (list, tuple)):
        raise MechanismError(f"[[dynamics.inertia]] must be a list of tables, not {raw!r}")
    for i, t in enumerate(raw, 1):
        w = f"[[dynamics.inertia]] #{i}"
        _keys(t, ("name", "inertia", "rpm", "ratio"), w)
        name = t.get("name", f"#{i}")
        if not isinstance(name, str):
            raise MechanismError(f"{w} name must be a string, not {name!r}")
        w = f"[[dynamics.inertia]] {name!r}"
        if "inertia" not in t:
            raise MechanismError(f"{w}: missing inertia (kg·m²)")
        inertias.append(ConstantInertia(name, _number(t, "inertia", w, nonneg=True),
                                        _ratio(t, w, crank_rpm, required=True)))
    fw = table.get("flywheel", {})
    w = "[dynamics.flywheel]"
    _keys(fw, ("ratio", "rpm", "shape", "density", "width_ratio", "thickness_ratio"), w)
    shape = fw.get("shape", "disc")
    if shape not in SHAPES:
        raise MechanismError(f"{w} shape must be 'disc' or 'rim', not {shape!r}")
    flywheel = FlywheelSpec(_ratio(fw, w, crank_rpm, required=False), shape,
                            _number(fw, "density", w, 7800.0, positive=True),
                            _number(fw, "width_ratio", w, 0.2, positive=True),
                            _number(fw, "thickness_ratio", w, 0.1, positive=True))
    if flywheel.thickness_ratio >= 1.0:
        raise MechanismError(f"{w} thickness_ratio must be < 1 (rim thickness over its mean diameter), "
                             f"not {flywheel.thickness_ratio:g}")
    motor = parse_motor(table.get("motor", {}), crank_rpm)
    run = parse_run(table["run"], mech) if "run" in table else None
    drive = parse_drive(table["drive"]) if "drive" in table else None
    return DynamicsSpec(delta, int(turns), tuple(inertias), flywheel, motor, run, drive)


def parse_motor(t: dict, crank_rpm: float = 0.0) -> MotorSpec:
    w = "[dynamics.motor]"
    _keys(t, ("kind", "torque", "critical_torque", "synchronous_rpm", "critical_rpm", "rpm", "ratio",
              "efficiency"), w)
    kind = t.get("kind", "constant")
    if kind not in MOTOR_KINDS:
        raise MechanismError(f"{w} kind must be one of {', '.join(MOTOR_KINDS)}, not {kind!r}")
    if "ratio" in t:
        ratio = _number(t, "ratio", w, positive=True)
    else:
        ratio = 1.0
    eta = _fraction(t, "efficiency", w, 1.0)
    allowed = {"constant": ("kind", "torque", "ratio", "efficiency"),
               "kloss": ("kind", "critical_torque", "synchronous_rpm", "critical_rpm", "ratio", "efficiency"),
               "table": ("kind", "rpm", "torque", "ratio", "efficiency")}[kind]
    for k in t:
        if k not in allowed:
            raise MechanismError(f"{w}: key {k!r} does not apply to kind = {kind!r}; its keys: {', '.join(allowed)}")
    if kind == "constant":
        return MotorSpec("constant", _number(t, "torque", w), ratio=ratio, efficiency=eta)
    if kind == "kloss":
        for k in ("critical_torque", "synchronous_rpm", "critical_rpm"):
            if k not in t:
                raise MechanismError(f"{w}: kind = 'kloss' needs {k}")
        mk = _number(t, "critical_torque", w, positive=True)
        n0 = _number(t, "synchronous_rpm", w, positive=True)
        nk = _number(t, "critical_rpm", w, positive=True)
        if not nk < n0:
            raise MechanismError(f"{w} critical_rpm must be < synchronous_rpm ({n0:g}), not {nk:g}")
        return MotorSpec("kloss", None, mk, n0, nk, ratio=ratio, efficiency=eta)
    rpm, torque = _list(t, "rpm", w), _list(t, "torque", w)
    if len(rpm) != len(torque):
        raise MechanismError(f"{w} rpm and torque must have the same length ({len(rpm)} ≠ {len(torque)})")
    for i in range(1, len(rpm)):
        if not rpm[i] > rpm[i - 1]:
            raise MechanismError(f"{w} rpm must be increasing; rpm[{i}] = {rpm[i]:g} ≤ {rpm[i - 1]:g}")
    if rpm[0] < 0:
        raise MechanismError(f"{w} rpm must be ≥ 0, not {rpm[0]:g}")
    return MotorSpec("table", rpm=rpm, torques=torque, ratio=ratio, efficiency=eta)


def parse_run(t: dict, mech: Mechanism) -> RunSpec:
    w = "[dynamics.run]"
    _keys(t, ("omega", "travel_deg", "time", "time_limit"), w)
    if "omega" not in t:
        raise MechanismError(f"{w}: missing omega (crank speed at position 1, rad/s)")
    omega = _number(t, "omega", w)
    if omega * mech.crank.sense < 0:
        raise MechanismError(f"{w} omega = {omega:g} turns the crank against the sense of [crank] "
                             f"(omega {mech.crank.omega:+g} rad/s); give it the same sign")
    travel = _number(t, "travel_deg", w, positive=True)
    time = _number(t, "time", w, positive=True)
    if (travel is None) == (time is None):
        raise MechanismError(f"{w}: give travel_deg or time (one of them)")
    limit = _number(t, "time_limit", w, 60.0, positive=True)
    return RunSpec(omega, travel, time, limit)


def parse_drive(t: dict) -> DriveSpec:
    w = "[dynamics.drive]"
    _keys(t, ("efficiency", "reserve", "catalogue", "synchronous_rpm", "coupling_efficiency",
              "gear_efficiency"), w)
    reserve = _number(t, "reserve", w, 1.1, positive=True)
    if reserve < 1.0:
        raise MechanismError(f"{w} reserve must be ≥ 1, not {reserve:g}")
    cat = t.get("catalogue")
    if cat is not None and not isinstance(cat, str):
        raise MechanismError(f"{w} catalogue must be a path to a CSV file, not {cat!r}")
    return DriveSpec(_fraction(t, "efficiency", w, 0.75), reserve, cat,
                     _number(t, "synchronous_rpm", w, positive=True),
                     _fraction(t, "coupling_efficiency", w, 0.98), _fraction(t, "gear_efficiency", w, 0.97))
