"""A mechanism as the tables of its file: `explicit_tables` (the inverse of the loader's
`from_dict`) and `dumps`, a small TOML writer for them.

>>> import velplan
>>> text = dumps(explicit_tables(velplan.load("four-bar")))
>>> velplan.parse(text, name="four-bar") == velplan.load("four-bar")
True
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

from velplan.errors import MechanismError
from velplan.mechanism.model import Guide, Mechanism, thaw


def meta_tables(mech: Mechanism) -> dict[str, Any]:
    """Everything of a file but its structure: names, output, masses, loads, dynamics."""
    out: dict[str, Any] = {"name": mech.name}
    if mech.title:
        out["title"] = mech.title
    if mech.description:
        out["description"] = mech.description
    if mech.output is not None:
        out["output"] = mech.output.point if mech.output.point else {"link": mech.output.link}
    if mech.reference_deg is not None:
        out["reference_deg"] = mech.reference_deg
    if mech.gravity != 9.81:
        out["gravity"] = mech.gravity
    if mech.masses:
        out["link"] = {m.link: {"mass": m.mass, "centre": m.centre} | ({} if m.inertia is None else
                                                                       {"inertia": m.inertia})
                       for m in mech.masses}
    if mech.loads:
        out["load"] = [thaw(ld) for ld in mech.loads]
    if mech.dynamics is not None:
        out["dynamics"] = thaw(mech.dynamics)
    if mech.names:
        out["names"] = dict(mech.names)
    return out


def crank_table(mech: Mechanism) -> dict[str, Any]:
    """The ``[crank]`` table of ``mech``: link, pivot, tip, length (m), omega (rad/s), epsilon (rad/s²)."""
    c = mech.crank
    out = {"link": c.link, "pivot": c.pivot, "tip": c.tip, "length": c.length, "omega": c.omega}
    if c.epsilon:
        out["epsilon"] = c.epsilon
    return out


def explicit_tables(mech: Mechanism) -> dict[str, Any]:
    """The explicit file of ``mech``: ``[ground]``, ``[crank]``, ``[[group]]``, ``[[point]]``
    and the rest (`meta_tables`)."""
    out = meta_tables(mech)
    out["ground"] = {n: list(xy) for n, xy in mech.ground}
    out["crank"] = crank_table(mech)
    out["group"] = [group_table(g) for g in mech.groups]
    if mech.points:
        out["point"] = [{"name": p.name, "link": p.link, "along": p.along, "offset": p.offset} for p in mech.points]
    return out


def guide_table(g: Guide) -> dict[str, Any]:
    """A guide as its table: link, through (a point), angle_deg (deg), offset (m)."""
    return {"link": g.link, "through": g.through, "angle_deg": math.degrees(g.angle), "offset": g.offset}


def _triad_table(g) -> dict[str, Any]:
    """The ``[[group]]`` table of a triad: sides (m), leads, its assembly pose (deg, m)."""
    out = {"base": g.base, "joints": list(g.joints), "sides": list(g.sides), "side": g.side,
           "leads": [{"link": ld.link, "guide": guide_table(ld.guide)} | (
               {"coincident": ld.coincident} if ld.coincident else {}) if ld.slider else
               {"link": ld.link, "joint": ld.joint, "length": ld.length} for ld in g.leads],
           "assembly": {"phi_deg": math.degrees(g.assembly_phi)} | {j: list(xy) for j, xy in g.assembly}}
    if g.special:
        out["special"] = g.special
    if g.pair is not None:
        out["pair"] = [g.pair[0] + 1, g.pair[1] + 1]
    return out


def _prp_table(g) -> dict[str, Any]:
    """The ``[[group]]`` table of a PRP dyad: its point and its two guides."""
    out = {"links": list(g.links), "point": g.point, "guides": [guide_table(x) for x in g.guides]}
    if any(g.coincident):
        out["coincident"] = [c or "" for c in g.coincident]
    return out


def _rpp_table(g) -> dict[str, Any]:
    """The ``[[group]]`` table of an RPP dyad: its joint, guide and slot angle (deg)."""
    out = {"links": list(g.links), "joint": g.joint, "guide": guide_table(g.guide),
           "slot_angle_deg": math.degrees(g.slot_angle)}
    return out | ({"origin": g.origin} if g.origin else {})


TABLES = {
    "RRR": lambda g: {"links": list(g.links), "joints": list(g.joints), "point": g.point,
                      "lengths": list(g.lengths), "branch": g.branch},
    "RRP": lambda g: {"links": list(g.links), "joint": g.joint, "point": g.point, "length": g.length,
                      "guide": guide_table(g.guide), "branch": g.branch},
    "RPR": lambda g: {"links": list(g.links), "joint": g.joint, "pivot": g.pivot, "offset": g.offset,
                      "branch": g.branch},
    "PRP": _prp_table,
    "RPP": _rpp_table,
    "triad": _triad_table,
}
"""Group kind → its ``[[group]]`` table's keys (the loader's inverse)."""


def group_table(g) -> dict[str, Any]:
    """One ``[[group]]`` table."""
    if g.kind not in TABLES:
        raise MechanismError(f"group {g.name!r}: kind {g.kind!r} has no table; known kinds: {', '.join(TABLES)}")
    out: dict[str, Any] = {"kind": g.kind, "name": g.name} | TABLES[g.kind](g)
    co = getattr(g, "coincident", None)
    if isinstance(co, str) and co:
        out["coincident"] = co
    return out


# -- TOML -----------------------------------------------------------------------------------

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    """A TOML key, quoted unless bare."""
    return k if _BARE.match(k) else json.dumps(k, ensure_ascii=False)


def _value(v: Any) -> str:
    """A TOML value: a string, number, boolean, array or inline table."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"TOML cannot hold {v}")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"TOML cannot hold {type(v).__name__}")


def _table_of_tables(v: Any) -> bool:
    """Whether ``v`` is written as an array of tables ([[…]])."""
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


_ORDER = ("ground", "crank", "joint", "group", "point", "special", "link", "load", "dynamics", "names")
"""The order of a file's sections."""


def _section(lines: list[str], path: str, table: dict) -> None:
    """The lines of the TOML section ``path`` (and its sub-tables) appended to ``lines``."""
    if not path:
        table = dict(sorted(table.items(), key=lambda kv: _ORDER.index(kv[0]) if kv[0] in _ORDER else -1))
    plain = {k: v for k, v in table.items() if not isinstance(v, dict) and not _table_of_tables(v)}
    if path and (plain or not table):
        lines += ["", f"[{path}]"]
    lines += [f"{_key(k)} = {_value(v)}" for k, v in plain.items()]
    for k, v in table.items():
        sub = f"{path}.{_key(k)}" if path else _key(k)
        if isinstance(v, dict):
            _section(lines, sub, v)
        elif _table_of_tables(v):
            for item in v:
                lines += ["", f"[[{sub}]]"] + [f"{_key(x)} = {_value(y)}" for x, y in item.items()]


def dumps(data: dict[str, Any]) -> str:
    """TOML text of ``data`` (scalars, lists, tables, arrays of tables); floats as ``repr`` so
    that they read back exactly."""
    lines: list[str] = []
    _section(lines, "", data)
    return "\n".join(lines).lstrip("\n") + "\n"
