"""Read the ``[[load]]`` tables of a mechanism file into load values.

Format (declared beside the ``[link.N]`` masses; SI units; N, N·m, m, Pa, degrees)::

    [[load]]                 # a constant force at a point
    kind = "force"
    name = "Q"               # optional; names the load in messages, tables and drawings
    point = "B4"
    link = "4"               # optional: the link the point belongs to (default: its owner)
    fx = -500.0              # N (fx and fy default to 0)
    fy = 0.0

    [[load]]                 # a constant moment on a link, counter-clockwise positive
    kind = "moment"
    link = "4"
    moment = 12.0            # N·m

    [[load]]                 # a magnitude interpolated in a table
    kind = "table"
    point = "F"              # optional for over = "output": the output point
    over = "crank"           # "crank": x in degrees from position 1 in the sense of rotation
                             # "output": x = output displacement from the start of the working
                             # stroke, m; stroke = "working" | "return" | "both" limits it
    x = [0.0, 90.0, 180.0]
    values = [0.0, 800.0, 0.0]   # N
                             # an x given twice is a jump: x = [0, 0.1, 0.1, 0.3] with
                             # values = [0, 0, 1400, 1400] steps up at 0.1 (a ramp narrower
                             # than 1e-6 of the table's span is refused: write it as a jump)
    direction = "guide"      # "guide" (+ along the guide), "against-motion", or give
                             # angle_deg = 270.0 for a fixed direction instead

    [[load]]                 # the shaper's cutting force (seed 002)
    kind = "cutting"
    force = 1400.0           # N, against the output slider's motion
    start = 0.05             # fractions of the working (slow) stroke (defaults 0.05, 0.95)
    end = 0.95

    [[load]]                 # seed 004's press load
    kind = "press"
    p_max = 40000.0          # N, reached at φ_end
    b1 = 0.02                # m: the load starts b1 + b2 before the lower extreme …
    b2 = 0.005               # m: … and is removed b2 before it
    harmonics = 0            # 0 or absent: the exact parabola; N ≥ 1: its Fourier series
    extreme = "lower"        # or "start" / "end" of the working stroke

    [[load]]                 # an indicator diagram (seed 001): F = p·π·d²/4
    kind = "indicator"
    bore = 0.08              # d, m
    head = "start"           # the cylinder head is at this extreme of the working stroke
    travel = [0.0, 0.05, 0.1]            # m from the head
    pressure_away = [0.0, 0.0, 0.0]      # Pa (gauge) while moving away from the head
    pressure_toward = [6e5, 1e5, 0.0]    # Pa while moving toward it (default: pressure_away)

``cutting``, ``press``, ``indicator`` (and ``table`` over the output) act on the output
slider; ``point`` and ``link`` default to the output point and the slider. Every problem
raises `MechanismError` with a one-line message naming the load and the value.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from velplan.errors import MechanismError
from velplan.forces import loads as L
from velplan.mechanism.model import Mechanism

_COMMON = {"kind", "name", "point", "link"}
KEYS: dict[str, set[str]] = {
    "force": _COMMON | {"fx", "fy"},
    "moment": {"kind", "name", "link", "moment"},
    "table": _COMMON | {"over", "x", "values", "direction", "angle_deg", "stroke"},
    "cutting": _COMMON | {"force", "start", "end"},
    "press": _COMMON | {"p_max", "b1", "b2", "harmonics", "extreme"},
    "indicator": _COMMON | {"bore", "head", "travel", "pressure_away", "pressure_toward"},
}


def parse_loads(mech: Mechanism) -> tuple:
    """The load values declared in ``mech.loads`` (the raw ``[[load]]`` tables), in order."""
    out = []
    names: set[str] = set()
    for i, t in enumerate(mech.loads):
        ld = parse_load(mech, t, i)
        if ld.name in names:
            raise MechanismError(f"{L._where(ld.name)}: duplicate load name")
        names.add(ld.name)
        out.append(ld)
    return tuple(out)


def parse_load(mech: Mechanism, t: Any, i: int = 0):
    """One ``[[load]]`` table (number ``i`` from 0) → a load value."""
    if not isinstance(t, Mapping):
        raise MechanismError(f"load #{i + 1} must be a table, not {t!r}")
    kind = t.get("kind")
    name = str(t.get("name", f"#{i + 1}"))
    if name == "" or ("name" in t and name.startswith("#")):
        raise MechanismError(f"load #{i + 1}: name must not be empty or start with '#', not {name!r}")
    where = L._where(name)
    if kind not in KEYS:
        raise MechanismError(f"{where}: unknown kind {kind!r}; known kinds: {', '.join(sorted(KEYS))}")
    extra = sorted(set(t) - KEYS[kind])
    if extra:
        raise MechanismError(f"{where}: unknown key {extra[0]!r}; allowed: {', '.join(sorted(KEYS[kind]))}")
    pt = _opt_str(t, "point", where)
    link = _opt_str(t, "link", where)
    if kind == "force":
        if pt is None:
            raise MechanismError(f"{where}: missing point")
        return L.constant_force(mech, pt, _num(t, "fx", where, 0.0), _num(t, "fy", where, 0.0), link=link, name=name)
    if kind == "moment":
        if link is None:
            raise MechanismError(f"{where}: missing link")
        if "moment" not in t:
            raise MechanismError(f"{where}: missing moment (N·m)")
        return L.constant_moment(mech, link, _num(t, "moment", where), name=name)
    if kind == "table":
        for key in ("x", "values"):
            if key not in t:
                raise MechanismError(f"{where}: missing {key}")
        if "direction" in t and "angle_deg" in t:
            raise MechanismError(f"{where}: give either direction or angle_deg, not both")
        direction = "fixed" if "angle_deg" in t else t.get("direction", "guide")
        if direction == "fixed" and "angle_deg" not in t:
            raise MechanismError(f"{where}: direction must be 'guide' or 'against-motion', not 'fixed' "
                                 "(give angle_deg for a fixed direction)")
        return L.table_force(mech, t["x"], t["values"], point=pt, link=link, over=t.get("over", "crank"),
                             direction=direction, angle_deg=_num(t, "angle_deg", where, 0.0),
                             stroke=t.get("stroke", "both"), name=name)
    if kind == "cutting":
        return L.cutting_force(mech, _num(t, "force", where, 1400.0), start=_num(t, "start", where, 0.05),
                               end=_num(t, "end", where, 0.95), point=pt, link=link, name=name)
    if kind == "press":
        for key in ("p_max", "b1", "b2"):
            if key not in t:
                raise MechanismError(f"{where}: missing {key}")
        h = t.get("harmonics", 0)
        if isinstance(h, bool) or not isinstance(h, int) or h < 0:
            raise MechanismError(f"{where}: harmonics must be a whole number ≥ 0 (0 = the exact parabola), not {h!r}")
        return L.press_load(mech, _num(t, "p_max", where), _num(t, "b1", where), _num(t, "b2", where),
                            harmonics=h or None, extreme=t.get("extreme", "lower"), point=pt, link=link, name=name)
    for key in ("bore", "travel", "pressure_away"):
        if key not in t:
            raise MechanismError(f"{where}: missing {key}")
    return L.indicator_force(mech, _num(t, "bore", where), t["travel"], t["pressure_away"],
                             t.get("pressure_toward"), head=t.get("head", "start"), point=pt, link=link, name=name)


def _num(t: dict, key: str, where: str, default: float | None = None) -> float:
    if key not in t:
        if default is None:
            raise MechanismError(f"{where}: missing {key}")
        return default
    v = t[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise MechanismError(f"{where}: {key} must be a number, not {v!r}")
    if not math.isfinite(v):
        raise MechanismError(f"{where}: {key} must be finite, not {v}")
    if abs(v) > 1e12:
        raise MechanismError(f"{where}: {key} = {v:g} is out of range (at most 1e12 in magnitude)")
    return float(v)


def _opt_str(t: dict, key: str, where: str) -> str | None:
    v = t.get(key)
    if v is None:
        return None
    if not isinstance(v, (str, int)) or isinstance(v, bool) or str(v) == "":
        raise MechanismError(f"{where}: {key} must be a name, not {v!r}")
    return str(v)
