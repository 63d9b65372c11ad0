"""The mechanism expressions of pyslvs and PMKS, read and written.

An expression lists joints: ``M[J[R, color[Green], P[x, y], L[ground, L1, L2]], J[RP, A[30.0],
P[x, y], L[L3, L2]], …]``. A joint is ``R`` (revolute), ``P`` (``L[guide link, slider]``: the
slider moves along the guide without turning) or ``RP`` (the pins of ``L[guide link, pins…]``
turn in a block that slides on the guide); ``A[deg]`` is the guide's direction, ``P[x, y]`` the
position (in mm by default), ``L[…]`` the links (``ground`` is the frame; ``L3`` is velplan's
link ``3``). ``#`` starts a comment: velplan writes its joint and block names there
(``# velplan joints: O A B C``), so that they come back. Joint i is ``P{i}`` otherwise.

>>> joints, _ = parse("M[J[R, color[Green], P[0, 0], L[ground, L1]], J[R, P[10, 0], L[L1, L2]]]")
>>> [(j.name, j.links, j.at) for j in joints]
[('P0', ('0', '1'), (0.0, 0.0)), ('P1', ('1', '2'), (0.01, 0.0))]
"""

from __future__ import annotations

import math
import re
from typing import Any, Mapping, Sequence

from velplan.errors import MechanismError
from velplan.mechanism.drawn import FRAME_NAMES, Joint
from velplan.mechanism.model import GROUND

UNITS = {"mm": 1e-3, "m": 1.0}
"""Length of one unit of an expression's coordinates, m."""
_TOKEN = re.compile(r"\s*(?:(?P<num>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<name>[A-Za-z_][A-Za-z0-9_-]*)"
                    r"|(?P<sym>[\[\](),]))")
_LINK = re.compile(r"^L([1-9]\d*)$")
_CNAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_MARK = "# velplan "


class _Tokens:
    """The tokens of an expression (numbers, names, brackets), each with its character (1-based)."""

    def __init__(self, text: str):
        self.items: list[tuple[str, str, int]] = []
        pos, end = 0, len(text)
        while pos < end:
            if text[pos].isspace():
                pos += 1
                continue
            m = _TOKEN.match(text, pos)
            if not m:
                raise MechanismError(f"malformed expression at character {pos + 1}: unexpected {text[pos:pos + 12]!r}")
            kind = m.lastgroup or "sym"
            self.items.append((kind, m.group(kind), m.start(kind) + 1))
            pos = m.end()
        self.i = 0

    def peek(self) -> tuple[str, str, int]:
        """The next token (kind, text, character), or ("end", …, −1)."""
        return self.items[self.i] if self.i < len(self.items) else ("end", "end of text", -1)

    def take(self, value: str | None = None, kind: str | None = None) -> str:
        """The next token's text, which must be ``value`` or of ``kind`` (one-line error else)."""
        k, v, at = self.peek()
        if (value is not None and v != value) or (kind is not None and k != kind):
            where = "at the end" if at < 0 else f"at character {at}"
            wanted = repr(value) if value else {"num": "a number", "name": "a name"}.get(kind or "", kind)
            raise MechanismError(f"malformed expression {where}: expected {wanted}, found {v!r}")
        self.i += 1
        return v

    def keyword(self, word: str) -> None:
        """``word[`` (the word in any case)."""
        self.take(kind="name") if self.peek()[1].lower() == word.lower() else self.take(word)
        self.take("[")


def _strip_comments(text: str) -> tuple[str, dict[str, str]]:
    """The text without ``#`` comments, and velplan's own comment lines (key → value)."""
    marks = {}
    for line in text.splitlines():
        line = line.strip()
        if line.startswith(_MARK) and ":" in line:
            key, value = line[len(_MARK):].split(":", 1)
            marks[key.strip()] = value.strip()
    text = re.sub(r"#\[[\s\S]*?#\][^\n]*", " ", text)
    return re.sub(r"#[^\n]*", " ", text), marks


def parse(text: str, *, unit: str = "mm", names: Sequence[str] | None = None) -> tuple[tuple[Joint, ...], dict]:
    """The joints of an expression (positions in m) and velplan's comment marks. ``names``
    names the joints in order (default: the names velplan wrote, else ``P0``, ``P1``, …)."""
    if unit not in UNITS:
        raise MechanismError(f"unknown unit {unit!r}; known units: {', '.join(UNITS)}")
    body, marks = _strip_comments(text)
    tok = _Tokens(body)
    tok.keyword("M")
    raw = []
    while tok.peek()[1] != "]":
        raw.append(_joint(tok, len(raw)))
        if tok.peek()[1] == ",":
            tok.take(",")
        elif tok.peek()[1] != "]":
            tok.take("]")
    tok.take("]")
    if tok.peek()[0] != "end":
        raise MechanismError(f"malformed expression at character {tok.peek()[2]}: text after the closing ]")
    if not raw:
        raise MechanismError("the expression M[…] holds no joint")
    given = list(names) if names is not None else marks.get("joints", "").split()
    if names is not None and len(given) != len(raw):
        raise MechanismError(f"--names gives {len(given)} names for {len(raw)} joints")
    if len(given) != len(raw):
        given = [f"P{i}" for i in range(len(raw))]
    blocks = dict(item.split("=", 1) for item in marks.get("blocks", "").split() if "=" in item)
    scale = UNITS[unit]
    joints = tuple(Joint(n, kind, (x * scale, y * scale), links, math.radians(angle),
                         blocks.get(n) if kind == "RP" else None, None, color)
                   for n, (kind, angle, color, x, y, links) in zip(given, raw))
    return joints, marks


def _number(tok: _Tokens) -> float:
    """The next token as a number."""
    return float(tok.take(kind="num"))


def _joint(tok: _Tokens, i: int) -> tuple:
    """Joint ``i`` read: (kind, guide angle deg, colour, x, y in the expression's unit, links)."""
    tok.keyword("J")
    kind = tok.take(kind="name")
    if kind.upper() not in ("R", "P", "RP"):
        raise MechanismError(f"joint {i}: unknown joint kind {kind!r}; known kinds: R, P, RP")
    kind = kind.upper()
    angle, color = 0.0, None
    tok.take(",")
    if tok.peek()[1] == "A":
        tok.keyword("A")
        angle = _number(tok)
        tok.take("]")
        tok.take(",")
    elif kind != "R":
        raise MechanismError(f"joint {i}: a {kind} joint needs A[deg], its guide's direction, after its kind")
    if tok.peek()[1].lower() == "color":
        tok.keyword("color")
        if tok.peek()[1] == "(":
            tok.take("(")
            rgb = [tok.take(kind="num")]
            for _ in range(2):
                tok.take(",")
                rgb.append(tok.take(kind="num"))
            tok.take(")")
            color = f"({', '.join(rgb)})"
        else:
            color = tok.take(kind="name")
        tok.take("]")
        tok.take(",")
    tok.keyword("P")
    x = _number(tok)
    tok.take(",")
    y = _number(tok)
    tok.take("]")
    tok.take(",")
    tok.keyword("L")
    links = []
    while tok.peek()[1] != "]":
        links.append(_link_in(tok.take(kind="name")))
        if tok.peek()[1] == ",":
            tok.take(",")
    tok.take("]")
    tok.take("]")
    if not links:
        raise MechanismError(f"joint {i}: L[] names no link")
    return kind, angle, color, x, y, tuple(links)


def _link_in(name: str) -> str:
    """velplan's name of an expression's link: ``ground`` → "0", ``L3`` → "3"."""
    if name in FRAME_NAMES:
        return GROUND
    m = _LINK.match(name)
    return m.group(1) if m else name


def _link_out(name: str) -> str:
    """An expression's name of velplan's link: "0" → ``ground``, "3" → ``L3``."""
    if name == GROUND:
        return "ground"
    if name.isdigit():
        return f"L{name}"
    if not _CNAME.match(name) or _LINK.match(name):
        raise MechanismError(f"link {name!r} cannot be written in an expression (a letter, then letters, digits, _)")
    return name


def _num(v: float) -> str:
    """A coordinate or angle as written: exact (repr), or "10.0" for a whole number."""
    return repr(float(v)) if v != int(v) or abs(v) >= 1e15 else f"{float(v):.1f}"


def dumps(joints: Sequence[dict], *, unit: str = "mm") -> str:
    """The expression of drawn joint tables (``name``, ``at`` in m, ``kind``, ``links``,
    ``angle_deg``, ``block``, ``color``), with velplan's names in a comment."""
    if unit not in UNITS:
        raise MechanismError(f"unknown unit {unit!r}; known units: {', '.join(UNITS)}")
    scale = UNITS[unit]
    rows = []
    for j in joints:
        kind = j.get("kind", "R")
        head = kind if kind == "R" else f"{kind}, A[{_num(j['angle_deg'])}]"
        color = f", color[{j['color']}]" if j.get("color") else ", color[Green]"
        x, y = (v / scale for v in j["at"])
        links = ", ".join(_link_out(str(k)) for k in j["links"])
        rows.append(f"J[{head}{color}, P[{_num(x)}, {_num(y)}], L[{links}]]")
    names = " ".join(str(j["name"]) for j in joints)
    out = []
    if all(re.match(r"^\S+$", str(j["name"])) and "=" not in str(j["name"]) for j in joints):
        out.append(f"{_MARK}joints: {names}")
    blocks = " ".join(f"{j['name']}={j['block']}" for j in joints if j.get("block"))
    if blocks:
        out.append(f"{_MARK}blocks: {blocks}")
    return "\n".join(out + ["M[", ",\n".join(f"  {r}" for r in rows), "]"]) + "\n"


def input_pair(joints: Sequence[Joint], pair: tuple[int, int] | None) -> tuple[str, str]:
    """The crank (link, pivot joint) of an input pair ``(B, D)`` as pyslvs numbers joints: the
    link shared by joints B and D, turning about B; default: the first frame joint's single
    moving link."""
    if pair is None:
        for j in joints:
            moving = [k for k in j.links if k != GROUND]
            if j.kind == "R" and GROUND in j.links and len(moving) == 1:
                return moving[0], j.name
        raise MechanismError("no R joint of the frame with a single moving link: give the input pair (--input B,D)")
    b, d = pair
    for k in pair:
        if not 0 <= k < len(joints):
            raise MechanismError(f"--input {b},{d}: joints are numbered 0…{len(joints) - 1}, not {k}")
    jb, jd = joints[b], joints[d]
    shared = [k for k in jb.links if k in jd.links and k != GROUND] if b != d else []
    if len(shared) != 1:
        raise MechanismError(f"--input {b},{d}: joints {jb.name} and {jd.name} share {len(shared)} moving links, "
                             "not one (the crank)")
    if jb.kind != "R" or GROUND not in jb.links:
        raise MechanismError(f"--input {b},{d}: joint {jb.name} is not an R joint of the frame; the crank turns about one")
    return shared[0], jb.name


def other_inputs(text: str, options: Mapping[str, Any]) -> list[tuple[tuple[int, int], str]]:
    """Every input pair (B, D) of an expression: a moving link on an R joint B of the frame,
    and another joint D of that link; with the link."""
    joints, _ = parse(text, unit=options.get("unit", "mm"), names=options.get("names"))
    out = []
    for b, jb in enumerate(joints):
        if jb.kind != "R" or GROUND not in jb.links:
            continue
        for link in (k for k in jb.links if k != GROUND):
            d = next((i for i, j in enumerate(joints) if i != b and link in j.links), None)
            if d is not None and (b, d) != options.get("pair"):
                out.append(((b, d), link))
    return out


def drawn_data(text: str, *, name: str = "mechanism", unit: str = "mm", pair: tuple[int, int] | None = None,
               omega: float | None = None, rpm: float | None = None,
               names: Sequence[str] | None = None) -> dict[str, Any]:
    """A drawn file's tables (`velplan.mechanism.drawn`) from an expression: the joints, and
    the crank from the input pair turning at ``omega`` rad/s or ``rpm`` (default 1 rad/s)."""
    joints, _ = parse(text, unit=unit, names=names)
    link, pivot = input_pair(joints, pair)
    crank: dict[str, Any] = {"link": link, "pivot": pivot}
    if omega is not None and rpm is not None:
        raise MechanismError("give the crank's speed as omega or rpm, not both")
    crank |= {"rpm": rpm} if rpm is not None else {"omega": 1.0 if omega is None else omega}
    return {"name": name, "crank": crank, "joint": [joint_table(j) for j in joints]}


def joint_table(j: Joint) -> dict[str, Any]:
    """A `Joint` as its ``[[joint]]`` table."""
    t: dict[str, Any] = {"name": j.name, "at": list(j.at), "links": list(j.links)}
    if j.kind != "R":
        t |= {"kind": j.kind, "angle_deg": math.degrees(j.angle)}
    if j.block:
        t["block"] = j.block
    if j.coincident:
        t["coincident"] = j.coincident
    if j.color:
        t["color"] = j.color
    return t
