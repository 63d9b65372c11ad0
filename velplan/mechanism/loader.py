"""Read a mechanism from TOML, validating every value at the boundary.

The format is documented in ``docs/format.md``. Every problem raises `MechanismError` with a
one-line message naming the element and the value.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from velplan.errors import MechanismError, deprecated
from velplan.mechanism.fields import finite as _finite, no_unknown as _no_unknown, optional_name as _opt_name
from velplan.mechanism.model import (
    GROUND,
    PRP,
    RPP,
    RPR,
    RRP,
    RRR,
    Crank,
    Group,
    Guide,
    LinkMass,
    Lead,
    LinkPoint,
    Mechanism,
    Output,
    Triad,
)
from velplan.mechanism.structure import point_owners, schedule
from velplan.options import LANGUAGES

_TOP_KEYS = {
    "name", "title", "description", "reference_deg", "output", "ground", "crank", "group",
    "point", "link", "gravity", "load", "dynamics", "names", "joint", "special",
}


def example_names() -> list[str]:
    """Names of the bundled example mechanisms."""
    files = resources.files("velplan.examples")
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".toml"))


def catalogue_names() -> list[str]:
    """Names of the catalogue's course-work mechanisms (`velplan.catalogue`)."""
    files = resources.files("velplan.catalogue")
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".toml"))


def load(source: str | Path) -> Mechanism:
    """Load a mechanism: a bundled example name (``"shaper"``), a catalogue name
    (``"whitworth"``, see `catalogue_names`) or a path to a TOML file.

    The file is parsed and its structure checked (names, lengths, the order the groups can be
    solved in); whether it assembles over a turn and what its loads mean is checked by the
    `velplan.study.Study` that studies it.
    """
    path = Path(source)
    if path.suffix.lower() == ".pmks":
        return load_pmks(path)
    bundled = path.suffix.lower() != ".toml"
    if bundled and str(source) in example_names():
        text = resources.files("velplan.examples").joinpath(f"{source}.toml").read_text("utf-8")
        name = str(source)
    elif bundled and str(source) in catalogue_names():
        text = resources.files("velplan.catalogue").joinpath(f"{source}.toml").read_text("utf-8")
        name = str(source)
    elif path.is_file():
        try:
            text = path.read_text("utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            raise MechanismError(f"cannot read {path}: {exc}") from None
        name = path.stem
    else:
        raise MechanismError(
            f"unknown mechanism {str(source)!r}: not a bundled example ({', '.join(example_names())}) "
            "nor a catalogue name (velplan examples --all) and no such file"
        )
    return parse(text, name=name)


def load_pmks(path: str | Path, **options) -> Mechanism:
    """Load a pyslvs/PMKS expression file (`velplan.mechanism.pmks.drawn_data` gives the
    ``options``: ``unit`` (default mm), ``pair`` (the input pair), ``omega`` or ``rpm``
    (default 1 rad/s), ``names``)."""
    return read_pmks(path, **options)[0]


def read_pmks(path: str | Path, **options) -> tuple[Mechanism, dict]:
    """The mechanism of a .pmks file and its drawn tables (`load_pmks`). A group velplan does
    not solve is refused naming an input pair that avoids it, where one does."""
    from velplan.mechanism.pmks import drawn_data, other_inputs

    path = Path(path)
    try:
        text = path.read_text("utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise MechanismError(f"cannot read {path}: {exc}") from None
    data = drawn_data(text, name=path.stem, **options)
    try:
        return from_dict(dict(data), name=path.stem), data
    except MechanismError as exc:
        if "velplan solves the dyads" not in str(exc):
            raise
        for pair, link in other_inputs(text, options):
            try:
                from_dict(drawn_data(text, **(options | {"pair": pair})))
            except MechanismError:
                continue
            raise MechanismError(f"{exc}; driven by link {link} (--input {pair[0]},{pair[1]}) it decomposes") from None
        raise


def parse(text: str, *, name: str = "mechanism") -> Mechanism:
    """Parse and validate a mechanism from TOML text (see `load`).

    >>> mech = parse('''
    ... [ground]
    ... O = [0.0, 0.0]
    ... [crank]
    ... link = "1"
    ... pivot = "O"
    ... tip = "A"
    ... length = 0.1
    ... rpm = 60
    ... ''', name="crank")
    >>> mech.crank.length, mech.crank.sense
    (0.1, 1.0)
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MechanismError(f"malformed TOML in {name}: {exc}") from None
    return from_dict(data, name=name)


loads = deprecated(parse, "velplan.mechanism.loader.loads")


def from_dict(data: dict[str, Any], *, name: str = "mechanism") -> Mechanism:
    """Build a `Mechanism` from parsed TOML data (structure and values validated); a drawn
    file (``[[joint]]`` tables) is first decomposed into groups (`velplan.mechanism.drawn`)."""
    _no_unknown(data, _TOP_KEYS, "the file")
    if "joint" in data:
        from velplan.mechanism.drawn_groups import explicit

        data = explicit(data, name)
    elif "special" in data:
        raise MechanismError("[[special]] belongs to a drawn file (one with [[joint]] tables)")
    elif "ground" not in data and "group" not in data:
        raise MechanismError("missing [ground] section: give [ground], [crank] and [[group]] tables, or the "
                             "mechanism as drawn ([[joint]] tables and a [crank])")
    for key, most in SIZE_LIMITS.items():
        count = len(data.get(key) or ())
        if count > most:
            raise MechanismError(f"[{key}]: {count} entries; a mechanism file holds at most {most}")
    ground = _ground(_table(data, "ground", required=True))
    crank = _crank(_table(data, "crank", required=True))
    groups = tuple(_group(g, i) for i, g in enumerate(_list(data, "group")))
    _no_truss_on_ground(groups, dict(ground))
    points = tuple(_point(p, i) for i, p in enumerate(_list(data, "point")))
    masses = _masses(_table(data, "link"))
    output = _output(data.get("output"))
    ref = data.get("reference_deg")
    mech = Mechanism(
        name=str(data.get("name", name)),
        title=str(data.get("title", "")),
        description=str(data.get("description", "")),
        ground=ground,
        crank=crank,
        groups=groups,
        points=points,
        masses=masses,
        output=output,
        reference_deg=None if ref is None else _finite(ref, "reference_deg"),
        gravity=_finite(data.get("gravity", 9.81), "gravity"),
        loads=tuple(_list(data, "load")),
        dynamics=_table(data, "dynamics") or None,
        names=_names_table(_table(data, "names")),
    )
    _check_names(mech)
    return mech


# -- sections -------------------------------------------------------------------------------


def _ground(table: dict) -> tuple[tuple[str, tuple[float, float]], ...]:
    if not table:
        raise MechanismError("[ground] needs at least one point, e.g. O = [0.0, 0.0]")
    out = []
    for key, xy in table.items():
        if not (isinstance(xy, list) and len(xy) == 2):
            raise MechanismError(f"ground point {key!r} must be [x, y] in m, not {xy!r}")
        out.append((str(key), (_finite(xy[0], f"ground point {key} x"), _finite(xy[1], f"ground point {key} y"))))
    return tuple(out)


def _crank(t: dict) -> Crank:
    _no_unknown(t, {"link", "pivot", "tip", "length", "omega", "rpm", "epsilon"}, "[crank]")
    if ("omega" in t) == ("rpm" in t):
        raise MechanismError("[crank] needs exactly one of omega (rad/s) or rpm (rev/min), sign = sense (+ counter-clockwise)")
    omega = _finite(t["omega"], "crank omega") if "omega" in t else _finite(t["rpm"], "crank rpm") * math.pi / 30
    check_speed(omega, "crank omega" if "omega" in t else "crank rpm", t.get("omega", t.get("rpm")))
    return Crank(
        link=_name(t, "link", "[crank]"),
        pivot=_name(t, "pivot", "[crank]"),
        tip=_name(t, "tip", "[crank]"),
        length=_length(t, "length", "crank"),
        omega=omega,
        epsilon=_finite(t.get("epsilon", 0.0), "crank epsilon"),
    )


def _guide(t: Any, where: str) -> Guide:
    if not isinstance(t, dict):
        raise MechanismError(f"{where}: guide must be a table {{link, through, angle_deg, offset}}, not {t!r}")
    _no_unknown(t, {"link", "through", "angle_deg", "offset"}, f"{where} guide")
    return Guide(
        link=str(t.get("link", GROUND)),
        through=_name(t, "through", f"{where} guide"),
        angle=math.radians(_finite(t.get("angle_deg", 0.0), f"{where} guide angle_deg")),
        offset=_finite(t.get("offset", 0.0), f"{where} guide offset"),
    )


_GROUP_KEYS = {
    "RRR": {"links", "joints", "point", "lengths", "branch"},
    "RRP": {"links", "joint", "point", "length", "guide", "branch", "coincident"},
    "RPR": {"links", "joint", "pivot", "offset", "branch", "coincident"},
    "PRP": {"links", "point", "guides", "coincident"},
    "RPP": {"links", "joint", "guide", "slot_angle_deg", "coincident", "origin"},
    "TRIAD": {"base", "joints", "sides", "side", "leads", "assembly", "special", "pair"},
}
KINDS = "RRR, RRP, RPR, PRP, RPP, triad"


def _group(t: Any, i: int) -> Group:
    if not isinstance(t, dict):
        raise MechanismError(f"group #{i + 1} must be a table, not {t!r}")
    kind = str(t.get("kind", "")).upper()
    if kind not in _GROUP_KEYS:
        raise MechanismError(f"group #{i + 1}: unknown kind {t.get('kind')!r}; known kinds: {KINDS}")
    if kind == "TRIAD":
        return _triad(t, i)
    links = _pair_of(t, "links", f"group #{i + 1}")
    name = str(t.get("name", "-".join(links)))
    where = f"group {name!r}"
    _no_unknown(t, _GROUP_KEYS[kind] | {"kind", "name"}, where)
    return _PARSERS[kind](t, name, links, where)


def _rrr(t: dict, name: str, links: tuple[str, str], where: str) -> RRR:
    lengths = _pair_of(t, "lengths", where, kind=float)
    for k, v in zip(links, lengths):
        _positive(v, f"{where} length of link {k}")
    return RRR(name, links, _pair_of(t, "joints", where), _name(t, "point", where), lengths, _branch(t, where))


def _rrp(t: dict, name: str, links: tuple[str, str], where: str) -> RRP:
    return RRP(
        name, links, _name(t, "joint", where), _name(t, "point", where), _length(t, "length", where),
        _guide(t.get("guide"), where), _branch(t, where), _opt_name(t, "coincident"),
    )


def _rpr(t: dict, name: str, links: tuple[str, str], where: str) -> RPR:
    return RPR(
        name, links, _name(t, "joint", where), _name(t, "pivot", where),
        _finite(t.get("offset", 0.0), f"{where} offset"), _branch(t, where), _opt_name(t, "coincident"),
    )


def _prp(t: dict, name: str, links: tuple[str, str], where: str) -> PRP:
    gs = t.get("guides")
    if not (isinstance(gs, list) and len(gs) == 2):
        raise MechanismError(f"{where}: guides must be a list of two guide tables")
    co = t.get("coincident", [None, None])
    if not (isinstance(co, list) and len(co) == 2):
        raise MechanismError(f"{where}: coincident must be a list of two point names")
    return PRP(name, links, _name(t, "point", where), (_guide(gs[0], where), _guide(gs[1], where)),
               tuple(None if c in (None, "") else str(c) for c in co))


def _rpp(t: dict, name: str, links: tuple[str, str], where: str) -> RPP:
    slot = _finite(t.get("slot_angle_deg", 90.0), f"{where} slot_angle_deg")
    if abs(math.sin(math.radians(slot))) < 1e-9:
        raise MechanismError(f"{where}: slot_angle_deg = {slot} makes the slot parallel to the guide; the group cannot move")
    return RPP(name, links, _name(t, "joint", where), _guide(t.get("guide"), where), math.radians(slot),
               _opt_name(t, "coincident"), _opt_name(t, "origin"))


#: The dyads' TOML kinds → their parsers (the triad, with no ``links``, is read by `_triad`).
_PARSERS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}


def _triad(t: dict, i: int) -> Triad:
    """A class III triad: ``base``, ``joints`` (B, C, D), ``sides`` (BC, CD, DB), ``side``,
    ``leads`` (three tables: rod {link, joint, length} or block {link, guide, coincident}),
    ``assembly`` {phi_deg, B = [x, y], …}, optional ``special`` and ``pair``."""
    base = _name(t, "base", f"group #{i + 1}")
    joints = _triple(t, "joints", f"group #{i + 1}")
    leads_t = t.get("leads")
    if not (isinstance(leads_t, list) and len(leads_t) == 3 and all(isinstance(x, dict) for x in leads_t)):
        raise MechanismError(f"group #{i + 1}: leads must be a list of three tables "
                             f"({{link, joint, length}} or {{link, guide}}), not {leads_t!r}")
    name = str(t.get("name", "-".join([base] + [str(x.get("link", "?")) for x in leads_t])))
    where = f"group {name!r}"
    _no_unknown(t, _GROUP_KEYS["TRIAD"] | {"kind", "name"}, where)
    sides = tuple(_positive(_finite(x, f"{where} sides"), f"{where} side {k}")
                  for x, k in zip(_triple(t, "sides", where, kind=float), ("BC", "CD", "DB")))
    a, b, c = sorted(sides)
    if a + b < c * (1 - 1e-12):
        raise MechanismError(f"{where}: sides {sides[0]:g}, {sides[1]:g}, {sides[2]:g} m do not make a triangle "
                             "(the longest exceeds the sum of the others)")
    leads = tuple(_lead(x, k, f"{where} lead {k + 1}") for k, x in enumerate(leads_t))
    if all(lead.slider for lead in leads):
        raise MechanismError(f"{where}: at least one lead must be a rod (all three are blocks on guides)")
    _no_truss(leads, base, where)
    asm = t.get("assembly")
    if not isinstance(asm, dict):
        raise MechanismError(f"{where}: missing assembly = {{phi_deg = …, {joints[0]} = [x, y], …}}: the approximate "
                             "position of the inner joints as drawn, which picks the branch")
    _no_unknown(asm, set(joints) | {"phi_deg"}, f"{where} assembly")
    near = tuple((j, tuple(_finite(v, f"{where} assembly {j}") for v in _pair_of(asm, j, f"{where} assembly", kind=float)))
                 for j in joints if j in asm)
    if not near:
        raise MechanismError(f"{where}: assembly names none of the joints {', '.join(joints)}")
    pair = t.get("pair")
    if pair is not None:
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(x, int) and 1 <= x <= 3 for x in pair)
                and pair[0] != pair[1]):
            raise MechanismError(f"{where}: pair must be two different lead numbers 1…3, not {pair!r}")
        pair = (pair[0] - 1, pair[1] - 1)
    return Triad(name, base, joints, sides, leads, near, math.radians(_finite(asm.get("phi_deg", 0.0),
                 f"{where} assembly phi_deg")), _branch_key(t, "side", where), _opt_name(t, "special"), pair)


def _no_truss(leads: tuple[Lead, ...], base: str, where: str) -> None:
    """Refuse two rod leads from one outer joint: with the base link they close a rigid
    triangle (a truss), so the four links are not a class III group."""
    for k, a in enumerate(leads):
        for m in range(k + 1, 3):
            b = leads[m]
            if not (a.slider or b.slider) and a.joint == b.joint:
                raise MechanismError(
                    f"{where}: leads {k + 1} and {m + 1} are rods from the same joint {a.joint!r}, so links "
                    f"{a.link}, {b.link} and {base} make one rigid body (a truss), not a class III group")


def _no_truss_on_ground(groups, ground: dict[str, tuple[float, float]]) -> None:
    """Refuse two rod leads of a triad from two ground points at one place (a truss too)."""
    for g in groups:
        if not isinstance(g, Triad):
            continue
        rods = [(k, lead) for k, lead in enumerate(g.leads) if not lead.slider and lead.joint in ground]
        for n, (k, a) in enumerate(rods):
            for m, b in rods[n + 1:]:
                if a.joint != b.joint and ground[a.joint] == ground[b.joint]:
                    raise MechanismError(
                        f"group {g.name!r}: leads {k + 1} and {m + 1} are rods from {a.joint!r} and {b.joint!r}, "
                        f"both at {list(ground[a.joint])}, so links {a.link}, {b.link} and {g.base} make one rigid "
                        "body (a truss), not a class III group")


def _lead(t: dict, k: int, where: str) -> Lead:
    _no_unknown(t, {"link", "joint", "length", "guide", "coincident"}, where)
    link = _name(t, "link", where)
    if "guide" in t:
        if "joint" in t or "length" in t:
            raise MechanismError(f"{where}: a lead is a rod (joint, length) or a block on a guide, not both")
        return Lead(link, guide=_guide(t["guide"], where), coincident=_opt_name(t, "coincident"))
    if "coincident" in t:
        raise MechanismError(f"{where}: coincident names a guide's point at a block; a rod lead has none")
    return Lead(link, _name(t, "joint", where), _length(t, "length", where))


def _triple(t: dict, key: str, where: str, kind=str) -> tuple:
    v = t.get(key)
    if not (isinstance(v, list) and len(v) == 3):
        raise MechanismError(f"{where}: {key} must be a list of three values, not {v!r}")
    return tuple(v) if kind is float else tuple(str(x) for x in v)


def _point(t: Any, i: int) -> LinkPoint:
    if not isinstance(t, dict):
        raise MechanismError(f"point #{i + 1} must be a table, not {t!r}")
    _no_unknown(t, {"name", "link", "along", "offset"}, f"point #{i + 1}")
    name = _name(t, "name", f"point #{i + 1}")
    link = _name(t, "link", f"point {name!r}")
    if link == GROUND:
        raise MechanismError(f"point {name!r}: link {GROUND!r} is the frame; a fixed point goes in [ground]")
    return LinkPoint(name, link, _finite(t.get("along", 0.0), f"point {name!r} along"),
                     _finite(t.get("offset", 0.0), f"point {name!r} offset"))


def _masses(table: dict) -> tuple[LinkMass, ...]:
    out = []
    for link, t in table.items():
        where = f"[link.{link}]"
        if not isinstance(t, dict):
            raise MechanismError(f"{where} must be a table with mass, centre and optional inertia")
        _no_unknown(t, {"mass", "inertia", "centre"}, where)
        mass = _finite(t.get("mass", 0.0), f"{where} mass")
        if mass < 0:
            raise MechanismError(f"{where} mass must be ≥ 0 kg, not {mass}")
        inertia = t.get("inertia")
        if inertia is not None:
            inertia = _finite(inertia, f"{where} inertia")
            if inertia < 0:
                raise MechanismError(f"{where} inertia must be ≥ 0 kg·m², not {inertia}")
        out.append(LinkMass(str(link), mass, _name(t, "centre", where), inertia))
    return tuple(out)


def _output(t: Any) -> Output | None:
    if t is None:
        return None
    if isinstance(t, str):
        return Output(point=t)
    if isinstance(t, dict) and len(t) == 1 and ("point" in t or "link" in t):
        return Output(point=t.get("point"), link=None if "link" not in t else str(t["link"]))
    raise MechanismError(f"output must be a point name or {{point = ...}} or {{link = ...}}, not {t!r}")


# -- cross-checks ---------------------------------------------------------------------------


def _check_names(mech: Mechanism) -> None:
    seen: dict[str, str] = {}

    def claim(name: str, what: str) -> None:
        if name in seen:
            raise MechanismError(f"duplicate name {name!r}: used for {seen[name]} and for {what}")
        seen[name] = what

    for n, _ in mech.ground:
        claim(n, "a ground point")
    claim(mech.crank.tip, "the crank tip")
    for g in mech.groups:
        for n in _new_points(g):
            claim(n, f"a point of group {g.name!r}")
    for p in mech.points:
        claim(p.name, f"point on link {p.link}")
    links = [mech.crank.link] + [k for g in mech.groups for k in g.links]
    if GROUND in links:
        raise MechanismError(f"link name {GROUND!r} is reserved for the frame")
    dup = sorted({k for k in links if links.count(k) > 1})
    if dup:
        raise MechanismError(f"duplicate link name {dup[0]!r}: each group brings new links (a dyad two, a triad four)")
    group_names = [g.name for g in mech.groups]
    dupg = sorted({k for k in group_names if group_names.count(k) > 1})
    if dupg:
        raise MechanismError(f"duplicate group name {dupg[0]!r}")
    schedule(mech)
    owners = point_owners(mech)
    for m in mech.masses:
        if m.link not in links:
            raise MechanismError(f"[link.{m.link}]: unknown link {m.link!r}; known links: {', '.join(links)}")
        if m.centre not in owners:
            raise MechanismError(f"[link.{m.link}]: unknown centre point {m.centre!r}; known points: {', '.join(owners)}")
    if mech.output is not None:
        if mech.output.point is not None and mech.output.point not in owners:
            raise MechanismError(f"output: unknown point {mech.output.point!r}; known points: {', '.join(owners)}")
        if mech.output.link is not None and mech.output.link not in links:
            raise MechanismError(f"output: unknown link {mech.output.link!r}; known links: {', '.join(links)}")


def _names_table(t: dict) -> tuple[tuple[str, str], ...]:
    """``[names]``: the mechanism's name per sheet language (en, ru, uk, zh)."""
    out = []
    for lang, text in t.items():
        if lang not in SHEET_LANGUAGES:
            raise MechanismError(f"[names]: unknown language {lang!r}; known languages: {', '.join(SHEET_LANGUAGES)}")
        if not isinstance(text, str) or not text.strip():
            raise MechanismError(f"[names] {lang} must be a non-empty string, not {text!r}")
        out.append((lang, text.strip()))
    return tuple(out)


def _new_points(g: Group) -> list[str]:
    """The point names a group brings, each once (a name given twice in one group is an error)."""
    from velplan.mechanism.structure import points_out

    named = g.named_points()
    seen: dict[str, str] = {}
    for key, name in named:
        if not name:
            continue
        if name in seen:
            raise MechanismError(f"group {g.name!r}: {key} {name!r} is already its {seen[name]}; "
                                 "give each point its own name")
        seen[name] = key
    return list(points_out(g))


# -- scalar helpers -------------------------------------------------------------------------


def _table(data: dict, key: str, required: bool = False) -> dict:
    t = data.get(key)
    if t is None:
        if required:
            raise MechanismError(f"missing [{key}] section")
        return {}
    if not isinstance(t, dict):
        raise MechanismError(f"[{key}] must be a table, not {type(t).__name__}")
    return t


def _list(data: dict, key: str) -> list:
    t = data.get(key, [])
    if not isinstance(t, list):
        raise MechanismError(f"{key} must be an array of tables ([[{key}]]), not {type(t).__name__}")
    return t




def _name(t: dict, key: str, where: str) -> str:
    v = t.get(key)
    if v is None or str(v) == "":
        raise MechanismError(f"{where}: missing {key}")
    return str(v)




SHEET_LANGUAGES = LANGUAGES
"""Languages a ``[names]`` table may give (those of the sheets)."""
SIZE_LIMITS = {"ground": 200, "group": 100, "point": 500, "link": 200, "load": 100, "joint": 400}
"""Most entries of each table of a file (a 4000-point file took 1.4 GB to draw)."""
SMALLEST_LENGTH = 1e-9
"""Shortest length a link may have, m."""




SLOWEST = 1e-9
"""Smallest crank speed |ω1|, rad/s: velocities, accelerations, transfer functions and forces
are all per the crank's speed, so a crank at rest (ω1 = 0) is refused where the file is read."""


def check_speed(omega: float, what: str, given: Any = None) -> float:
    """``omega`` (rad/s) if the crank turns (|ω1| ≥ `SLOWEST`); one line naming ``what``."""
    if not abs(omega) >= SLOWEST:
        shown = omega if given is None else given
        raise MechanismError(f"{what} = {shown:g}: the crank must turn (|ω1| ≥ {SLOWEST:g} rad/s); "
                             "velocities, accelerations and forces are all per its speed")
    return omega


def _positive(v: float, what: str) -> float:
    if not v > 0:
        raise MechanismError(f"{what} must be > 0 m, not {v}")
    if v < SMALLEST_LENGTH:
        raise MechanismError(f"{what} = {v:g} m is shorter than {SMALLEST_LENGTH:g} m")
    return v


def _length(t: dict, key: str, where: str) -> float:
    if key not in t:
        raise MechanismError(f"{where}: missing {key} (m)")
    return _positive(_finite(t[key], f"{where} {key}"), f"{where} {key}")


def _branch(t: dict, where: str) -> int:
    return _branch_key(t, "branch", where)


def _branch_key(t: dict, key: str, where: str) -> int:
    b = t.get(key, 1)
    if b not in (1, -1) or isinstance(b, bool):
        raise MechanismError(f"{where}: {key} must be +1 or -1, not {b!r}")
    return int(b)


def _pair_of(t: dict, key: str, where: str, kind=str) -> tuple:
    v = t.get(key)
    if not (isinstance(v, list) and len(v) == 2):
        raise MechanismError(f"{where}: {key} must be a list of two values, not {v!r}")
    if kind is float:
        return tuple(_finite(x, f"{where} {key}") for x in v)
    return tuple(str(x) for x in v)
