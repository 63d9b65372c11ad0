"""The dotted keys of a mechanism file: one grammar, one table, one reader.

A key names one number of the file the way the file writes it (``crank.length``,
``group.2-3.lengths.0``, ``link.4.mass``); `velplan batch`, `velplan sweep --vary` and
``--tolerance``, and `velplan.analysis.design` all read and set numbers through `resolve`.
Every value set is checked as the file loader checks it (`check`): finite, at most
`MAGNITUDE` in size, lengths at least `SMALLEST_LENGTH`, a crank that turns, masses ≥ 0,
signs ±1, a slot not parallel to its guide, a triad's sides a triangle.

==========================================  =======  =================================================
key                                         unit     the number
==========================================  =======  =================================================
``crank.length``                            m        the crank's length
``crank.omega`` / ``crank.rpm``             rad/s    the crank's speed (rpm: rev/min; not 0)
``crank.epsilon``                           rad/s²   the crank's angular acceleration
``ground.P.0``, ``ground.P.1``              m        x, y of the fixed point P
``group.N.lengths.0`` (``.1``)              m        an RRR group's lengths
``group.N.length``                          m        an RRP group's rod
``group.N.offset``                          m        an RPR group's offset
``group.N.branch``                          ±1       an RRR, RRP or RPR group's assembly
``group.N.guide.offset`` (``.angle_deg``)   m (deg)  an RRP or RPP group's guide
``group.N.guides.0.offset`` (``.1``, …)     m (deg)  a PRP group's guides (``angle_deg`` too)
``group.N.slot_angle_deg``                  deg      an RPP group's slot
``group.N.sides.0`` (``.1``, ``.2``)        m        a triad's base link: BC, CD, DB
``group.N.side``                            ±1       the side of BC that D is on
``group.N.leads.0.length``                  m        a triad's rod lead (leads 0…2)
``group.N.leads.0.guide.offset``            m        a triad's block lead (``angle_deg`` too)
``group.N.assembly.B.0``, ``.phi_deg``      m, deg   a triad's assembly as drawn
``point.P.along``, ``point.P.offset``       m        a point on a link
``link.L.mass``, ``link.L.inertia``         kg       a link's mass (kg·m²: its inertia J_S)
``load.NAME.FIELD``                         —        a number of the load NAME (``force``, ``p_max`` …)
``dynamics.FIELD``                          —        a number of ``[dynamics]`` (``delta`` …)
``gravity``, ``reference_deg``              m/s², °  the file's top-level numbers
==========================================  =======  =================================================
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from typing import Any, Callable, Mapping

import numpy as np

from velplan.errors import MechanismError
from velplan.mechanism.fields import MAGNITUDE
from velplan.mechanism.loader import SLOWEST, SMALLEST_LENGTH
from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Mechanism, Table, Triad

@dataclass(frozen=True)
class Entry:
    """One row of the table: the key's pattern (``{name}`` a name in the file, ``{i}`` an
    index, ``{field}`` the rest), how its value is checked, its unit, the group kinds it
    belongs to, and the path to the number in the `Mechanism`."""

    pattern: str
    kind: str
    unit: str
    path: Callable[[dict], tuple]
    groups: tuple = ()
    convert: str = ""
    array: bool = False


def _g(rest: tuple) -> Callable[[dict], tuple]:
    return lambda c: ("groups", ("name", c["name"])) + tuple(c.get(x, x) if x in ("i", "field") else x for x in rest)


TABLE: tuple[Entry, ...] = (
    Entry("crank.length", "length", "m", lambda c: ("crank", "length"), array=True),
    Entry("crank.omega", "speed", "rad/s", lambda c: ("crank", "omega"), array=True),
    Entry("crank.rpm", "speed", "rev/min", lambda c: ("crank", "omega"), convert="rpm", array=True),
    Entry("crank.epsilon", "number", "rad/s²", lambda c: ("crank", "epsilon")),
    Entry("ground.{name}.{i}", "number", "m", lambda c: ("ground", ("pair", c["name"]), 1, c["i"]), array=True),
    Entry("group.{name}.lengths.{i}", "length", "m", _g(("lengths", "i")), (RRR,), array=True),
    Entry("group.{name}.length", "length", "m", _g(("length",)), (RRP,), array=True),
    Entry("group.{name}.offset", "number", "m", _g(("offset",)), (RPR,), array=True),
    Entry("group.{name}.branch", "sign", "±1", _g(("branch",)), (RRR, RRP, RPR)),
    Entry("group.{name}.guide.offset", "number", "m", _g(("guide", "offset")), (RRP, RPP), array=True),
    Entry("group.{name}.guide.angle_deg", "number", "deg", _g(("guide", "angle")), (RRP, RPP), "deg", True),
    Entry("group.{name}.guides.{i}.offset", "number", "m", _g(("guides", "i", "offset")), (PRP,), array=True),
    Entry("group.{name}.guides.{i}.angle_deg", "number", "deg", _g(("guides", "i", "angle")), (PRP,), "deg", True),
    Entry("group.{name}.slot_angle_deg", "slot", "deg", _g(("slot_angle",)), (RPP,), "deg", True),
    Entry("group.{name}.sides.{i}", "length", "m", _g(("sides", "i")), (Triad,)),
    Entry("group.{name}.side", "sign", "±1", _g(("side",)), (Triad,)),
    Entry("group.{name}.leads.{i}.length", "length", "m", _g(("leads", "i", "length")), (Triad,)),
    Entry("group.{name}.leads.{i}.guide.offset", "number", "m", _g(("leads", "i", "guide", "offset")), (Triad,)),
    Entry("group.{name}.leads.{i}.guide.angle_deg", "number", "deg", _g(("leads", "i", "guide", "angle")), (Triad,),
          "deg"),
    Entry("group.{name}.assembly.phi_deg", "number", "deg", _g(("assembly_phi",)), (Triad,), "deg"),
    Entry("group.{name}.assembly.{field}.{i}", "number", "m",
          lambda c: ("groups", ("name", c["name"]), "assembly", ("pair", c["field"]), 1, c["i"]), (Triad,)),
    Entry("point.{name}.along", "number", "m", lambda c: ("points", ("name", c["name"]), "along"), array=True),
    Entry("point.{name}.offset", "number", "m", lambda c: ("points", ("name", c["name"]), "offset"), array=True),
    Entry("link.{name}.mass", "mass", "kg", lambda c: ("masses", ("link", c["name"]), "mass")),
    Entry("link.{name}.inertia", "mass", "kg·m²", lambda c: ("masses", ("link", c["name"]), "inertia")),
    Entry("load.{name}.{field}", "number", "", lambda c: ("loads", ("load", c["name"])) + c["field"]),
    Entry("dynamics.{field}", "number", "", lambda c: ("dynamics",) + c["field"]),
    Entry("gravity", "number", "m/s²", lambda c: ("gravity",)),
    Entry("reference_deg", "number", "deg", lambda c: ("reference_deg",)),
)
"""Every key of a mechanism file that holds a number, in the file's order."""

OPTIONAL = {"inertia", "epsilon", "along", "offset", "angle_deg", "reference_deg", "delta", "fx", "fy"}
"""Numbers a key may set where the file leaves them at their defaults (absent)."""


# ---- the reader -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Slot:
    """A key of one mechanism resolved: its table row and the path to its number."""

    key: str
    entry: Entry
    steps: tuple

    @property
    def array(self) -> bool:
        """Whether the design solver takes an array of values here."""
        return self.entry.array

    def get(self, mech: Mechanism) -> float:
        """The number in the key's unit (deg, rev/min …); NaN where the file leaves it out."""
        v = _get(mech, self.steps)
        return math.nan if v is None else _out(self.entry.convert, float(v))

    def set(self, mech: Mechanism, value) -> Mechanism:
        """``mech`` with the number set to ``value`` (a float, or an array where `array`), unchecked."""
        return _put(mech, self.steps, _in(self.entry.convert, value))


def resolve(mech: Mechanism, key: str) -> Slot:
    """The slot of ``key`` in ``mech``; `MechanismError` naming the key and what ``mech`` has."""
    if not isinstance(key, str) or not key.strip():
        raise MechanismError(f"unknown key {key!r}: give a dotted key such as crank.length or link.4.mass")
    parts = key.split(".")
    why = ""
    for entry in TABLE:
        caps = _match(entry.pattern.split("."), parts)
        if caps is None:
            continue
        why = _fits(mech, entry, caps, key)
        if why:
            continue
        steps = entry.path(caps)
        _get(mech, steps, key, entry)  # the path exists (or is an optional number)
        return Slot(key, entry, steps)
    if why:
        raise MechanismError(why)
    raise MechanismError(f"unknown key {key!r}: {_nearest(mech, parts)}")


def value(mech: Mechanism, key: str) -> float:
    """The number at ``key`` in ``mech`` (m, deg, rev/min, rad/s, kg …)."""
    return resolve(mech, key).get(mech)


def set_values(mech: Mechanism, values: Mapping[str, Any]) -> Mechanism:
    """``mech`` with every key of ``values`` set (floats or arrays), unchecked: for the design
    solver, whose values `check_values` has checked."""
    for key, v in values.items():
        mech = resolve(mech, key).set(mech, v)
    return mech


def apply(mech: Mechanism, values: Mapping[str, float]) -> Mechanism:
    """``mech`` with the keys of ``values`` set to single numbers, each checked as the file
    loader checks it, the groups and the crank rebuilt through their constructors."""
    out = mech
    for key, v in values.items():
        slot = resolve(out, key)
        arr = np.array([_number(key, v)])
        check(slot, arr)
        out = slot.set(out, int(arr[0]) if slot.entry.kind == "sign" else float(arr[0]))
    check_triangles(out)
    groups = tuple(replace(g) for g in out.groups)
    return replace(out, crank=replace(out.crank), groups=groups, points=tuple(replace(p) for p in out.points))


def check_values(mech: Mechanism, values: Mapping[str, Any]) -> None:
    """Check arrays of values per key (one per variant) as the loader checks one number; one
    line naming the key, the value and the variant."""
    for key, v in values.items():
        check(resolve(mech, key), np.atleast_1d(np.asarray(v, dtype=float)))
    check_triangles(set_values(mech, {k: v for k, v in values.items() if ".sides." in k}))


def _number(key: str, raw: Any) -> float:
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str, np.floating, np.integer)):
        raise MechanismError(f"{key}: {raw!r} is not a number")
    try:
        return float(raw)
    except ValueError:
        raise MechanismError(f"{key}: {raw!r} is not a number") from None


# ---- checks -----------------------------------------------------------------------------------


def check(slot: Slot, values: np.ndarray) -> None:
    """The loader's checks of the slot's kind on every value (an array over variants)."""
    key, kind = slot.key, slot.entry.kind
    v = np.asarray(values, dtype=float)
    with np.errstate(all="ignore"):
        rules = [(~np.isfinite(v), "must be a finite number"),
                 (np.abs(v) > MAGNITUDE, f"is out of range (at most {MAGNITUDE:g} in magnitude)")]
        if kind == "length":
            rules.append((~(v >= SMALLEST_LENGTH), f"must be a length ≥ {SMALLEST_LENGTH:g} m"))
        elif kind == "speed":
            w = v * math.pi / 30 if slot.entry.convert == "rpm" else v
            rules.append((~(np.abs(w) >= SLOWEST), f"must be a speed (the crank must turn, |ω1| ≥ {SLOWEST:g} rad/s)"))
        elif kind == "mass":
            rules.append((~(v >= 0), "must be ≥ 0"))
        elif kind == "sign":
            rules.append((~((v == 1) | (v == -1)), "must be +1 or -1"))
        elif kind == "slot":
            rules.append((~(np.abs(np.sin(np.radians(v))) >= 1e-9), "makes the slot parallel to its guide"))
    for bad, what in rules:
        if bad.any():
            i = int(np.argmax(bad))
            where = f" (variant {i + 1})" if v.size > 1 else ""
            raise MechanismError(f"{key} = {v[i]:g} {what}{where}")


def check_triangles(mech: Mechanism) -> None:
    """Each triad's sides (numbers or arrays over variants) make a triangle."""
    for g in mech.groups:
        if isinstance(g, Triad):
            s = np.broadcast_arrays(*(np.asarray(x, float) for x in g.sides))
            srt = np.sort(np.stack([np.atleast_1d(x) for x in s]), axis=0)
            bad = srt[0] + srt[1] < srt[2] * (1 - 1e-12)
            if bad.any():
                i = int(np.argmax(bad))
                where = f" (variant {i + 1})" if bad.size > 1 else ""
                sides = ", ".join(f"{np.atleast_1d(x)[i]:g}" for x in s)
                raise MechanismError(f"group {g.name!r}: sides {sides} m do not make a triangle{where}")


# ---- the grammar --------------------------------------------------------------------------------


def _match(pattern: list[str], parts: list[str]) -> dict | None:
    """The captures of ``parts`` against a row's ``pattern`` (a last ``{field}`` takes the
    rest of the key as a tuple), or None."""
    caps: dict = {}
    if pattern[-1] == "{field}" and len(pattern) >= 2 and pattern.count("{field}") == 1 and len(parts) >= len(pattern):
        caps["field"] = tuple(parts[len(pattern) - 1:])
        pattern, parts = pattern[:-1], parts[:len(pattern) - 1]
    if len(parts) != len(pattern):
        return None
    for p, x in zip(pattern, parts):
        if p in ("{name}", "{field}"):
            caps[p[1:-1]] = x
        elif p == "{i}":
            if not x.isdigit():
                return None
            caps["i"] = int(x)
        elif p != x:
            return None
    return caps


def _fits(mech: Mechanism, entry: Entry, caps: dict, key: str) -> str:
    """Why the row does not fit ``mech`` (its group is of another kind, a lead of the other
    sort), or ""."""
    if not entry.groups:
        return ""
    g = next((x for x in mech.groups if x.name == caps["name"]), None)
    if g is None:
        return ""  # the path says which groups there are
    if not isinstance(g, entry.groups):
        return f"unknown key {key!r}: group {g.name} ({g.kind}) has no {key.split('.', 2)[2]!r}"
    if isinstance(g, Triad) and ".leads." in entry.pattern and caps["i"] < 3:
        rod = not g.leads[caps["i"]].slider
        if rod != entry.pattern.endswith(".length"):
            sort = "a rod (length)" if rod else "a block on a guide (guide.offset, guide.angle_deg)"
            return f"unknown key {key!r}: lead {caps['i']} of group {g.name} is {sort}"
    return ""


def _nearest(mech: Mechanism, parts: list[str]) -> str:
    heads = sorted({e.pattern.split(".")[0] for e in TABLE})
    if parts[0] not in heads:
        return f"use a dotted key such as crank.length, group.N.lengths.0 or link.4.mass (first part one of {', '.join(heads)})"
    rows = [e.pattern for e in TABLE if e.pattern.split(".")[0] == parts[0]]
    return f"{parts[0]} keys are {', '.join(rows)}"


# ---- paths into the frozen model ----------------------------------------------------------------


def _child(obj, step, key: str = "", entry: Entry | None = None):
    """The part of ``obj`` that ``step`` names (an attribute, an index, a named item)."""
    if isinstance(step, tuple):
        how, name = step
        items = list(obj or ())
        for k, it in enumerate(items):
            if _name_of(how, it) == name:
                return k
        known = ", ".join(str(_name_of(how, it)) for it in items) or "none"
        what = {"pair": "ground point", "name": "group" if entry and entry.pattern.startswith("group") else "point",
                "link": "link with a mass", "load": "load"}[how]
        if how == "pair" and entry and ".assembly." in entry.pattern:
            what = "assembly point"
        if how == "link":
            raise MechanismError(f"unknown key {key!r}: the base has no [link.{name}]; links with masses: {known}")
        raise MechanismError(f"unknown key {key!r}: no {what} named {name!r}; known: {known}")
    if isinstance(step, int) or (isinstance(step, str) and step.isdigit()):
        i = int(step)
        if not isinstance(obj, tuple):
            raise MechanismError(f"unknown key {key!r}: {step!r} indexes a number, not a list")
        if not 0 <= i < len(obj):
            raise MechanismError(f"unknown key {key!r}: index {i} outside 0…{len(obj) - 1}")
        return i
    return step


def _name_of(how: str, item):
    if how == "pair":
        return item[0]
    if how == "link":
        return item.link
    if how == "load":
        return str(item.get("name", "")) if isinstance(item, Mapping) else None
    return item.name


def _read(obj, step):
    if isinstance(step, int):
        return obj[step]
    if isinstance(obj, Mapping):
        return obj.get(step)
    return getattr(obj, step, None)


def _get(mech: Mechanism, steps: tuple, key: str = "", entry: Entry | None = None):
    obj: Any = mech
    for n, step in enumerate(steps):
        last = n == len(steps) - 1
        s = _child(obj, step, key, entry)
        if obj is None or (not isinstance(s, int) and not isinstance(obj, Mapping) and not hasattr(obj, s)):
            where = ".".join(key.split(".")[:max(n, 1)]) if key else "?"
            raise MechanismError(f"unknown key {key!r}: the file has no {where} to set")
        if isinstance(obj, Mapping) and not isinstance(s, int) and s not in obj:
            if last and s in OPTIONAL:
                return None
            have = ", ".join(k for k, v in obj.items() if isinstance(v, (int, float, tuple, Mapping))) or "none"
            raise MechanismError(f"unknown key {key!r}: {'.'.join(key.split('.')[:-1]) or 'the file'} has no {s!r}; "
                                 f"it has {have}")
        obj = _read(obj, s)
        if last and key:
            if obj is not None and (isinstance(obj, bool) or not isinstance(obj, (int, float, np.ndarray))):
                raise MechanismError(f"unknown key {key!r}: it holds {_shown(obj)}, not a number")
            if obj is None and s not in OPTIONAL and not (entry and entry.kind == "mass"):
                raise MechanismError(f"unknown key {key!r}: the file gives no number there")
    return obj


def _shown(obj) -> str:
    if isinstance(obj, tuple):
        return f"a list of {len(obj)} (give an entry: .0)"
    if isinstance(obj, Mapping):
        return "a table"
    return repr(obj)


def _put(obj, steps: tuple, v):
    if not steps:
        return v
    s = _child(obj, steps[0])
    new = _put(_read(obj, s), steps[1:], v)
    if isinstance(s, int):
        return obj[:s] + (new,) + obj[s + 1:]
    if isinstance(obj, Mapping):
        return Table({**obj, s: new}) if isinstance(obj, Table) else {**obj, s: new}
    out = copy.copy(obj)
    object.__setattr__(out, s, new)
    return out


def _in(convert: str, v):
    if convert == "deg":
        return np.radians(v) if isinstance(v, np.ndarray) else math.radians(v)
    if convert == "rpm":
        return v * (math.pi / 30.0)
    return v


def _out(convert: str, v: float) -> float:
    if convert == "deg":
        return math.degrees(v)
    if convert == "rpm":
        return v * 30.0 / math.pi
    return v


def keys_of(mech: Mechanism, *, speed: bool = False, every: bool = False) -> dict[str, float]:
    """Key → value of ``mech``'s geometry that the design solver carries in arrays, in file
    order: fixed points, the crank's length, class II groups' lengths, offsets and angles, and
    points on links; ``speed`` adds ``crank.omega``; ``every`` adds a triad's sides, leads and
    block guides, branches, masses and gravity."""
    out: dict[str, float] = {}
    for name, _ in mech.ground:
        out[f"ground.{name}.0"], out[f"ground.{name}.1"] = (value(mech, f"ground.{name}.{j}") for j in (0, 1))
    out["crank.length"] = float(mech.crank.length)
    if speed or every:
        out["crank.omega"] = float(mech.crank.omega)
    for g in mech.groups:
        for key in _group_keys(g, every):
            out[key] = value(mech, key)
    for p in mech.points:
        out[f"point.{p.name}.along"], out[f"point.{p.name}.offset"] = float(p.along), float(p.offset)
    if every:
        for m in mech.masses:
            out.update({f"link.{m.link}.{f}": value(mech, f"link.{m.link}.{f}") for f in ("mass", "inertia")
                        if getattr(m, f) is not None})
        out["gravity"] = float(mech.gravity)
    return out


def _group_keys(g, every: bool) -> list[str]:
    return [f"group.{g.name}.{k}" for k in g.design_keys(every)]
