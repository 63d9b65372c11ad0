"""Frozen values that describe a planar linkage: ground points, the driving crank, the class-II
Assur groups attached to it, named points on links and the mass properties of links.

Conventions (SI units throughout: metres, radians, seconds):

* Angles are absolute, measured from +x, counter-clockwise positive.
* Every link has a *frame*: an origin point and a reference direction. A point on a link is
  given by ``along`` (metres along the reference direction from the origin) and ``offset``
  (metres to the left of it). The frames are:

  =========  ==========================  ==========================================
  link of    origin                      reference direction
  =========  ==========================  ==========================================
  crank      pivot                       pivot → tip
  RRR        A (link 1), D (link 2)      A → C, D → C
  RRP        A (rod), C (slider)         A → C; the guide
  RPR        A (block), O (bar)          the bar's guide line (O → A when offset=0)
  PRP        C (both sliders)            guide 1; guide 2
  RPP        B (block), K (runner)       the slot; the external guide
  triad      B (base link)               B → C
             P (rod lead), J (block)     P → J (outer joint → inner joint); the guide
  =========  ==========================  ==========================================

  K, the runner's origin in an RPP group, is the point where its slot crosses its guide line.
  A triad (class III group) has a ternary base link with inner joints B, C, D and three leads,
  each a rod from a known outer joint P to an inner joint J, or a block at J sliding on a guide.

The model knows nothing of solving or drawing (see `velplan.analysis` and `velplan.plans`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Iterator, Literal, Union
from velplan.options import Language

GROUND = "0"
"""Name of the frame (the fixed link)."""

GroupKind = Literal["RRR", "RRP", "RPR", "PRP", "RPP", "triad"]


@dataclass(frozen=True)
class Crank:
    """The driving link: a rod turning about a ground pivot at constant speed.

    Attributes
    ----------
    link : str
        Link name (e.g. ``"1"``).
    pivot, tip : str
        Ground pivot and the moving end (the point the first group attaches to).
    length : float
        Pivot–tip distance, m.
    omega : float
        Angular velocity, rad/s, counter-clockwise positive.
    epsilon : float
        Angular acceleration, rad/s² (0 for a uniformly turning crank).
    """

    link: str
    pivot: str
    tip: str
    length: float
    omega: float
    epsilon: float = 0.0

    @property
    def rpm(self) -> float:
        """Speed in revolutions per minute (signed)."""
        return self.omega * 30.0 / math.pi

    @property
    def sense(self) -> float:
        """The crank's turning sense: +1.0 counter-clockwise (ω ≥ 0), −1.0 clockwise."""
        return turning_sense(self.omega)


def turning_sense(omega):
    """+1.0 for ω ≥ 0 (counter-clockwise), −1.0 for ω < 0; elementwise for an array of ω.
    The one definition of the turning sense (`Crank.sense` reads it).

    >>> turning_sense(-2.0), turning_sense(0.0)
    (-1.0, 1.0)
    """
    if hasattr(omega, "shape") and getattr(omega, "ndim", 0):
        return (omega >= 0) * 2.0 - 1.0
    return 1.0 if omega >= 0 else -1.0


@dataclass(frozen=True)
class Guide:
    """A straight guide line carried by a link (the frame ``"0"`` or a moving link).

    The line passes at distance ``offset`` (m, to the left of its direction) from the point
    ``through`` of that link, in the direction ``angle`` (rad) measured from the link's
    reference direction (from +x for the frame).
    """

    link: str
    through: str
    angle: float = 0.0
    offset: float = 0.0


@dataclass(frozen=True)
class RRR:
    """Dyad of two rods: known joints A and D, unknown middle joint C.

    ``links = (AC, DC)``, ``lengths = (l_AC, l_DC)`` in m; ``branch = +1`` puts C to the left
    of the directed line A → D, ``-1`` to the right.
    """

    name: str
    links: tuple[str, str]
    joints: tuple[str, str]
    point: str
    lengths: tuple[float, float]
    branch: int = 1
    kind: GroupKind = field(default="RRR", init=False)


@dataclass(frozen=True)
class RRP:
    """Rod AC from a known joint A to a slider C that runs on a guide.

    ``links = (rod, slider)``; ``length`` = l_AC in m. ``branch = +1`` puts C ahead, along the
    guide direction, of the foot of the perpendicular from A; ``-1`` behind it.
    ``coincident`` names the point of the guide's link that coincides with C.
    """

    name: str
    links: tuple[str, str]
    joint: str
    point: str
    length: float
    guide: Guide
    branch: int = 1
    coincident: str | None = None
    kind: GroupKind = field(default="RRP", init=False)


@dataclass(frozen=True)
class RPR:
    """Block pivoted at a known joint A sliding on a bar pivoted at a known point O (a guide bar,
    "кулиса", 导杆).

    ``links = (block, bar)``. The bar's guide line passes at ``offset`` (m, to the left) from O.
    ``branch = +1`` puts A ahead of the foot of the perpendicular from O along the guide
    (the only sensible choice when offset = 0). ``coincident`` names the bar's point at A.
    """

    name: str
    links: tuple[str, str]
    joint: str
    pivot: str
    offset: float = 0.0
    branch: int = 1
    coincident: str | None = None
    kind: GroupKind = field(default="RPR", init=False)


@dataclass(frozen=True)
class PRP:
    """Two sliders joined by a revolute C, each running on its own guide.

    ``links = (slider on guide 1, slider on guide 2)``. C lies on both guide lines (their
    offsets place it). ``coincident`` names the points of the two guides' links at C.
    """

    name: str
    links: tuple[str, str]
    point: str
    guides: tuple[Guide, Guide]
    coincident: tuple[str | None, str | None] = (None, None)
    kind: GroupKind = field(default="PRP", init=False)


@dataclass(frozen=True)
class RPP:
    """A block pivoted at a known joint B slides in a slot of a runner that slides on a guide.

    ``links = (block, runner)``. The slot makes the angle ``slot_angle`` (rad) with the
    external guide. ``coincident`` names the runner's point at B (e.g. B4 on the punch of
    the press); ``origin`` optionally names K, the crossing of the slot with the guide line.
    """

    name: str
    links: tuple[str, str]
    joint: str
    guide: Guide
    slot_angle: float = math.pi / 2
    coincident: str | None = None
    origin: str | None = None
    kind: GroupKind = field(default="RPP", init=False)

    @property
    def origin_name(self) -> str:
        """Name of K, the runner's origin (``origin`` or ``"K" + runner``)."""
        return self.origin or f"K{self.links[1]}"


@dataclass(frozen=True)
class Lead:
    """One lead of a class III triad, ending at the inner joint ``joints[i]`` of the base link:
    a rod ``link`` from the known outer joint ``joint`` (``length`` m), or a block ``link``
    pivoted at the inner joint and sliding on ``guide`` (``coincident`` names the guide link's
    point at the inner joint)."""

    link: str
    joint: str | None = None
    length: float = 0.0
    guide: Guide | None = None
    coincident: str | None = None

    @property
    def slider(self) -> bool:
        """True for a block on a guide, False for a rod."""
        return self.guide is not None


@dataclass(frozen=True)
class Triad:
    """Class III group of the third order (Assur's triad): a ternary base link with the inner
    joints B, C, D (``joints``) tied by three leads (``leads[i]`` ends at ``joints[i]``) to
    known links.

    ``sides = (l_BC, l_CD, l_DB)`` in m; ``side = +1`` puts D to the left of B → C. The base
    link's frame starts at B along B → C. ``assembly`` gives approximate positions (m) of one
    or more inner joints at the crank angle ``assembly_phi`` (rad): the branch nearest to them is
    followed continuously over the turn. ``special`` names Assur's special point (the crossing
    of the lines of the two leads ``pair``, a point of the base link; ``None``: the pair whose
    lines cross at the largest angle over the turn).
    """

    name: str
    base: str
    joints: tuple[str, str, str]
    sides: tuple[float, float, float]
    leads: tuple[Lead, Lead, Lead]
    assembly: tuple[tuple[str, tuple[float, float]], ...]
    assembly_phi: float = 0.0
    side: int = 1
    special: str | None = None
    pair: tuple[int, int] | None = None
    kind: GroupKind = field(default="triad", init=False)

    @property
    def links(self) -> tuple[str, ...]:
        """Base link first, then the leads' links."""
        return (self.base,) + tuple(lead.link for lead in self.leads)

    @property
    def special_name(self) -> str:
        """Name of Assur's special point (``special`` or ``"K" + base``)."""
        return self.special or f"K{self.base}"

    def local(self) -> tuple[complex, complex, complex]:
        """B, C, D in the base link's frame (origin B, x along B → C), m."""
        bc, cd, db = self.sides
        along = (bc * bc + db * db - cd * cd) / (2 * bc)
        across = math.sqrt(max(db * db - along * along, 0.0))
        return 0j, complex(bc, 0.0), complex(along, self.side * across)


Group = Union[RRR, RRP, RPR, PRP, RPP, Triad]


class Table(Mapping):
    """A TOML table frozen: an immutable, hashable mapping whose tables are `Table` and whose
    arrays are tuples (`freeze`). The model keeps the ``[[load]]`` and ``[dynamics]`` tables
    so, for the layers above to interpret; its repr is the file's (dicts and lists).

    >>> t = freeze({"kind": "force", "x": [0.0, 1.0]})
    >>> t["x"], hash(t) == hash(freeze({"x": [0.0, 1.0], "kind": "force"})), t
    ((0.0, 1.0), True, {'kind': 'force', 'x': [0.0, 1.0]})
    """

    __slots__ = ("_items", "_hash")

    def __init__(self, items: Mapping[str, Any] = ()):
        self._items = {str(k): freeze(v) for k, v in dict(items).items()}
        self._hash = None

    def __getitem__(self, key: str) -> Any:
        return self._items[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._items.items()))
        return self._hash

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Mapping) and dict(self._items) == dict(other)

    def __repr__(self) -> str:
        return repr(thaw(self))


def freeze(value: Any) -> Any:
    """``value`` with every dict made a `Table` and every list a tuple (recursively)."""
    if isinstance(value, Table):
        return value
    if isinstance(value, Mapping):
        return Table(value)
    if isinstance(value, (list, tuple)):
        return tuple(freeze(v) for v in value)
    return value


def thaw(value: Any) -> Any:
    """The plain dicts and lists of a frozen value (the inverse of `freeze`)."""
    if isinstance(value, Mapping):
        return {k: thaw(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return [thaw(v) for v in value]
    return value


@dataclass(frozen=True)
class LinkPoint:
    """A named point fixed to a link: ``along`` m along the link's reference direction from
    its origin, ``offset`` m to the left of it (see the module docstring for the frames)."""

    name: str
    link: str
    along: float
    offset: float = 0.0


@dataclass(frozen=True)
class LinkMass:
    """Mass properties of a link: ``mass`` in kg, ``inertia`` J_S about the centre in kg·m²
    (``None`` when not given), ``centre`` the name of the centre-of-mass point."""

    link: str
    mass: float
    centre: str
    inertia: float | None = None


@dataclass(frozen=True)
class Output:
    """The output whose extreme positions give the stroke H and the coefficient K: a slider
    point (``point``, displacement along its guide) or a link (``link``, its angle)."""

    point: str | None = None
    link: str | None = None


@dataclass(frozen=True)
class Pair:
    """A lower kinematic pair: ``kind`` "R" (revolute) or "P" (prismatic) joining two links
    (``"0"`` is the frame) at ``point``; for P pairs ``point`` is the slider's joint."""

    name: str
    kind: Literal["R", "P"]
    links: tuple[str, str]
    point: str
    group: str


@dataclass(frozen=True)
class Mechanism:
    """A single-degree-of-freedom planar linkage: crank + Assur groups (class II dyads, class
    III triads), in solving order.

    Attributes
    ----------
    name : str
        Short name (the bundled example name or the file stem).
    ground : tuple of (name, (x, y))
        Fixed points, m.
    crank : Crank
    groups : tuple of Group
        In the order they are solved; each uses only points known before it.
    points : tuple of LinkPoint
        Named points on links (centres of mass, points such as B2 or E).
    masses : tuple of LinkMass
    output : Output or None
    reference_deg : float or None
        Crank angle (deg) of position 1; ``None`` = the start of the slow (working) stroke of
        the output, or 0 without an output.
    loads : tuple of Table
        The ``[[load]]`` tables as the file gives them (frozen), interpreted by the force
        analysis (`velplan.forces.parse_loads`).
    dynamics : Table or None
        The ``[dynamics]`` section (frozen), interpreted by `velplan.dynamics.parse_dynamics`.

    A mechanism is an immutable value: equal files give equal, hashable mechanisms, so results
    of a mechanism can be cached by it (`velplan.analysis.extremes.stroke`).
    names : tuple of (str, str)
        The mechanism's name in the sheets' languages (``[names]``: ``ru = "Строгальный
        станок"``), for the title block; a sheet in another language writes ``name``.
    """

    name: str
    ground: tuple[tuple[str, tuple[float, float]], ...]
    crank: Crank
    groups: tuple[Group, ...] = ()
    points: tuple[LinkPoint, ...] = ()
    masses: tuple[LinkMass, ...] = ()
    output: Output | None = None
    reference_deg: float | None = None
    title: str = ""
    description: str = ""
    gravity: float = 9.81
    loads: tuple = ()
    dynamics: Table | None = None
    names: tuple[tuple[str, str], ...] = ()

    def __post_init__(self):
        # loads and dynamics arrive as parsed TOML (dicts, lists): kept frozen, so hashable
        object.__setattr__(self, "loads", tuple(freeze(ld) for ld in self.loads))
        if self.dynamics is not None:
            object.__setattr__(self, "dynamics", freeze(self.dynamics))

    def name_in(self, lang: Language) -> str:
        """The mechanism's name in ``lang`` (``[names]``), else its ``name``."""
        return dict(self.names).get(lang) or self.name

    @property
    def ground_points(self) -> dict[str, tuple[float, float]]:
        """Ground point name → (x, y) in m."""
        return dict(self.ground)

    @property
    def links(self) -> tuple[str, ...]:
        """Names of the moving links, crank first, in solving order."""
        names = [self.crank.link]
        for g in self.groups:
            names.extend(g.links)
        return tuple(names)

    def group(self, name: str) -> Group:
        """The group called ``name``."""
        for g in self.groups:
            if g.name == name:
                return g
        from velplan.errors import MechanismError

        known = ", ".join(g.name for g in self.groups)
        raise MechanismError(f"unknown group {name!r}; known groups: {known}")
