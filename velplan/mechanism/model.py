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
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar, Iterator, Literal, TypeVar, Union

from velplan.errors import MechanismError
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


FACTS = ("joints_in", "guide_lines", "points_out", "revolute_joints", "pairs", "slides", "coincident_names",
         "inner_joints", "link_lines", "link_lengths", "sizes", "offsets", "output_slides", "output_joint",
         "solved_point", "given_lengths", "named_points")
"""The structural facts every group kind states (`AssurGroup`)."""


class AssurGroup:
    """What every Assur group kind states about its own structure; the layers above ask these
    facts, never the kind's class (each layer's own work for a kind sits in one registry keyed
    by the class, read through `kind_entry`).

    A kind defines (`FACTS`): ``joints_in`` (known points it attaches to), ``guide_lines`` (guides it
    slides on), ``points_out`` (points it determines → owner link), ``revolute_joints``
    (joint centre → its links), ``pairs`` (its lower pairs), ``slides`` (its prismatic pairs),
    ``coincident_names``, ``inner_joints`` (the joints it solves for), ``link_lines`` (the
    main line of each link that is a line: its frame's two points), ``link_lengths``,
    ``sizes`` and ``offsets`` (the sizes it is given), ``output_slides``, ``output_joint``,
    ``solved_point``, ``given_lengths`` and ``named_points``.
    """

    group_class: ClassVar[tuple[int, int]] = (2, 2)
    """Assur's class and order."""
    tracked: ClassVar[bool] = False
    """True when its assembly is followed over the turn (no closed form picks the branch)."""

    def slide_pair(self, slider: str, guide_link: str) -> str:
        """Name of the prismatic pair of ``slider`` on ``guide_link``."""
        return f"P:{slider}/{guide_link}"

    def special_points(self) -> tuple[str, ...]:
        """Assur's special points (construction points of a class III group's base link)."""
        return ()

    def construction_points(self) -> tuple[str, ...]:
        """Points it determines only to construct others (an RPP runner's origin, a triad's
        special point): no plan row, no trajectory of their own."""
        return self.special_points()

    def plates(self) -> tuple[tuple[str, tuple[str, ...]], ...]:
        """Its ternary links: (link, its joints)."""
        return ()

    def track_point(self, point: str) -> str:
        """The point whose positions are read for the output point ``point`` of this group."""
        return point

    def line_point(self, slider: str) -> str | None:
        """The point the guide line of ``slider``'s prismatic pair is referred to, when not its
        joint (an RPP runner's origin K)."""
        return None

    def shifted(self, dx: float, dy: float):
        """The group with every absolute position it gives moved by (dx, dy) m."""
        return self

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        """The numbers a design study varies, as dotted paths below ``group.NAME`` (m; deg
        for ``…_deg``) in the file's order; ``every`` adds those solved one variant at a
        time (an assembly's branch, a triad's sides and leads)."""
        return ()


class Dyad(AssurGroup):
    """A class II group of the second order: two links, three pairs, ``links = (a, b)``."""

    def output_joint(self, link: str) -> str | None:
        """The moving joint whose positions are numbered for the output link ``link``."""
        return None

    def given_lengths(self) -> tuple[float, ...]:
        """The lengths it gives, m."""
        return (0.0,)

    def link_lengths(self) -> dict[str, float]:
        """Link → its characteristic length given by the group, m."""
        return {}

    def sizes(self) -> tuple[tuple[tuple[str, str], float], ...]:
        """((from, to), length in m) of every length it gives, as a drawing's data lists them."""
        return ()

    def link_lines(self) -> dict[str, tuple[str, str]]:
        """Link → the two named points its main line runs between (links that are lines)."""
        return {}

    def inner_joints(self) -> tuple[str, ...]:
        """The revolute joints it solves for (their paths are drawn)."""
        return ()

    def coincident_names(self) -> tuple[str, ...]:
        """Its coincident points (points of a guide's link at a slider's joint)."""
        return ()

    def offsets(self) -> tuple[tuple[str, float], ...]:
        """(link, e in m) of every non-zero guide offset it gives."""
        return ()

    def output_slides(self) -> dict[str, tuple[str, str]]:
        """Point that may be the output slider → (slider link, its prismatic pair)."""
        return {}


@dataclass(frozen=True)
class RRR(Dyad):
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

    def joints_in(self) -> tuple[str, ...]:
        return self.joints

    def guide_lines(self) -> tuple[Guide, ...]:
        return ()

    def points_out(self) -> dict[str, str]:
        return {self.point: self.links[0]}

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        a, b = self.links
        return {self.joints[0]: (a,), self.point: (a, b), self.joints[1]: (b,)}

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        return ()

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        (a, b), (A, D) = self.links, self.joints
        return [Pair(A, "R", (a, owner[A]), A, self.name), Pair(self.point, "R", (a, b), self.point, self.name),
                Pair(D, "R", (b, owner[D]), D, self.name)]

    def inner_joints(self) -> tuple[str, ...]:
        return (self.point,)

    def link_lines(self) -> dict[str, tuple[str, str]]:
        return {self.links[0]: (self.joints[0], self.point), self.links[1]: (self.joints[1], self.point)}

    def link_lengths(self) -> dict[str, float]:
        return dict(zip(self.links, self.lengths))

    def sizes(self) -> tuple[tuple[tuple[str, str], float], ...]:
        (a, d), (l1, l2) = self.joints, self.lengths
        return (((a, self.point), l1), ((d, self.point), l2))

    def output_joint(self, link: str) -> str | None:
        return self.point if link in self.links else None

    def solved_point(self) -> str:
        return self.point

    def given_lengths(self) -> tuple[float, ...]:
        return tuple(self.lengths) + (0.0,)

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        return ("lengths.0", "lengths.1") + (("branch",) if every else ())

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        return (("point", self.point),)


@dataclass(frozen=True)
class RRP(Dyad):
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

    def joints_in(self) -> tuple[str, ...]:
        return (self.joint, self.guide.through)

    def guide_lines(self) -> tuple[Guide, ...]:
        return (self.guide,)

    def points_out(self) -> dict[str, str]:
        out = {self.point: self.links[0]}
        if self.coincident:
            out[self.coincident] = self.guide.link
        return out

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        a, b = self.links
        return {self.joint: (a,), self.point: (a, b)}

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        return ((self.links[1], self.guide.link, self.point),)

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        a, b = self.links
        return [Pair(self.joint, "R", (a, owner[self.joint]), self.joint, self.name),
                Pair(self.point, "R", (a, b), self.point, self.name),
                Pair(self.slide_pair(b, self.guide.link), "P", (b, self.guide.link), self.point, self.name)]

    def coincident_names(self) -> tuple[str, ...]:
        return (self.coincident,) if self.coincident else ()

    def inner_joints(self) -> tuple[str, ...]:
        return (self.point,)

    def link_lines(self) -> dict[str, tuple[str, str]]:
        return {self.links[0]: (self.joint, self.point)}

    def link_lengths(self) -> dict[str, float]:
        return {self.links[0]: self.length}

    def sizes(self) -> tuple[tuple[tuple[str, str], float], ...]:
        return (((self.joint, self.point), self.length),)

    def offsets(self) -> tuple[tuple[str, float], ...]:
        return ((self.links[1], self.guide.offset),) if self.guide.offset else ()

    def output_slides(self) -> dict[str, tuple[str, str]]:
        return {self.point: (self.links[1], self.slide_pair(self.links[1], self.guide.link))}

    def output_joint(self, link: str) -> str | None:
        return self.point if link in self.links else None

    def solved_point(self) -> str:
        return self.point

    def given_lengths(self) -> tuple[float, ...]:
        return (self.length,)

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        return ("length", "guide.offset", "guide.angle_deg") + (("branch",) if every else ())

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        return (("point", self.point), ("coincident", self.coincident))


@dataclass(frozen=True)
class RPR(Dyad):
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

    def joints_in(self) -> tuple[str, ...]:
        return (self.joint, self.pivot)

    def guide_lines(self) -> tuple[Guide, ...]:
        return ()

    def points_out(self) -> dict[str, str]:
        return {self.coincident: self.links[1]} if self.coincident else {}

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        a, b = self.links
        return {self.joint: (a,), self.pivot: (b,)}

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        return ((self.links[0], self.links[1], self.joint),)

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        a, b = self.links
        return [Pair(self.joint, "R", (a, owner[self.joint]), self.joint, self.name),
                Pair(self.slide_pair(a, b), "P", (a, b), self.joint, self.name),
                Pair(self.pivot, "R", (b, owner[self.pivot]), self.pivot, self.name)]

    def coincident_names(self) -> tuple[str, ...]:
        return (self.coincident,) if self.coincident else ()

    def link_lines(self) -> dict[str, tuple[str, str]]:
        return {self.links[1]: (self.pivot, self.coincident or self.joint)}

    def offsets(self) -> tuple[tuple[str, float], ...]:
        return ((self.links[1], self.offset),) if self.offset else ()

    def solved_point(self) -> str:
        return self.coincident or self.joint

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        return ("offset",) + (("branch",) if every else ())

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        return (("coincident", self.coincident),)


@dataclass(frozen=True)
class PRP(Dyad):
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

    def joints_in(self) -> tuple[str, ...]:
        return (self.guides[0].through, self.guides[1].through)

    def guide_lines(self) -> tuple[Guide, ...]:
        return self.guides

    def points_out(self) -> dict[str, str]:
        out = {self.point: self.links[0]}
        out.update({name: guide.link for guide, name in zip(self.guides, self.coincident) if name})
        return out

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        return {self.point: self.links}

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        return tuple((k, gd.link, self.point) for k, gd in zip(self.links, self.guides))

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        (a, b), (g1, g2) = self.links, self.guides
        return [Pair(self.slide_pair(a, g1.link), "P", (a, g1.link), self.point, self.name),
                Pair(self.point, "R", (a, b), self.point, self.name),
                Pair(self.slide_pair(b, g2.link), "P", (b, g2.link), self.point, self.name)]

    def coincident_names(self) -> tuple[str, ...]:
        return tuple(c for c in self.coincident if c)

    def inner_joints(self) -> tuple[str, ...]:
        return (self.point,)

    def offsets(self) -> tuple[tuple[str, float], ...]:
        return tuple((k, gd.offset) for k, gd in zip(self.links, self.guides) if gd.offset)

    def output_slides(self) -> dict[str, tuple[str, str]]:
        return {self.point: (self.links[0], self.slide_pair(self.links[0], self.guides[0].link))}

    def solved_point(self) -> str:
        return self.point

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        return ("guides.0.offset", "guides.0.angle_deg", "guides.1.offset", "guides.1.angle_deg")

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        return (("point", self.point),) + tuple(("coincident", c) for c in self.coincident)


@dataclass(frozen=True)
class RPP(Dyad):
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

    def joints_in(self) -> tuple[str, ...]:
        return (self.joint, self.guide.through)

    def guide_lines(self) -> tuple[Guide, ...]:
        return (self.guide,)

    def points_out(self) -> dict[str, str]:
        out = {self.coincident: self.links[1]} if self.coincident else {}
        out[self.origin_name] = self.links[1]
        return out

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        return {self.joint: (self.links[0],)}

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        a, b = self.links
        return ((a, b, self.joint), (b, self.guide.link, self.joint))

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        a, b = self.links
        return [Pair(self.joint, "R", (a, owner[self.joint]), self.joint, self.name),
                Pair(self.slide_pair(a, b), "P", (a, b), self.joint, self.name),
                Pair(self.slide_pair(b, self.guide.link), "P", (b, self.guide.link), self.joint, self.name)]

    def coincident_names(self) -> tuple[str, ...]:
        return (self.coincident,) if self.coincident else ()

    def construction_points(self) -> tuple[str, ...]:
        return (self.origin_name,)

    def offsets(self) -> tuple[tuple[str, float], ...]:
        return ((self.links[1], self.guide.offset),) if self.guide.offset else ()

    def output_slides(self) -> dict[str, tuple[str, str]]:
        slide = (self.links[1], self.slide_pair(self.links[1], self.guide.link))
        return {name: slide for name in (self.coincident, self.origin_name) if name}

    def track_point(self, point: str) -> str:
        return self.origin_name if point == self.coincident else point  # the runner's, on its guide

    def line_point(self, slider: str) -> str | None:
        return self.origin_name if slider == self.links[1] else None  # the runner's guide line passes K

    def solved_point(self) -> str:
        return self.coincident or self.joint

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        return ("guide.offset", "guide.angle_deg", "slot_angle_deg")

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        return (("coincident", self.coincident), ("origin", self.origin_name))


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
class Triad(AssurGroup):
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

    group_class: ClassVar[tuple[int, int]] = (3, 3)
    tracked: ClassVar[bool] = True

    def joints_in(self) -> tuple[str, ...]:
        return tuple(lead.guide.through if lead.slider else lead.joint for lead in self.leads)

    def guide_lines(self) -> tuple[Guide, ...]:
        return tuple(lead.guide for lead in self.leads if lead.slider)

    def points_out(self) -> dict[str, str]:
        out = {j: self.base for j in self.joints}
        out[self.special_name] = self.base
        out.update({lead.coincident: lead.guide.link for lead in self.leads if lead.slider and lead.coincident})
        return out

    def revolute_joints(self) -> dict[str, tuple[str, ...]]:
        out = {j: (self.base, lead.link) for j, lead in zip(self.joints, self.leads)}
        out.update({lead.joint: (lead.link,) for lead in self.leads if not lead.slider})
        return out

    def slides(self) -> tuple[tuple[str, str, str], ...]:
        return tuple((lead.link, lead.guide.link, j) for j, lead in zip(self.joints, self.leads) if lead.slider)

    def pairs(self, owner: Mapping[str, str]) -> list[Pair]:
        """Its six pairs, lead by lead: the outer pair (R at the rod's outer joint, or P of the
        block on its guide), then the inner R joining the lead to the base link."""
        out = []
        for j, lead in zip(self.joints, self.leads):
            if lead.slider:
                out.append(Pair(self.slide_pair(lead.link, lead.guide.link), "P", (lead.link, lead.guide.link), j,
                                self.name))
            else:
                out.append(Pair(lead.joint, "R", (lead.link, owner[lead.joint]), lead.joint, self.name))
            out.append(Pair(j, "R", (lead.link, self.base), j, self.name))
        return out

    def coincident_names(self) -> tuple[str, ...]:
        """The special point too: a different point of the base link at each position."""
        return tuple(n for n in (self.special_name,) + tuple(lead.coincident for lead in self.leads) if n)

    def special_points(self) -> tuple[str, ...]:
        return (self.special_name,)

    def plates(self) -> tuple[tuple[str, tuple[str, ...]], ...]:
        return ((self.base, self.joints),)

    def inner_joints(self) -> tuple[str, ...]:
        return self.joints

    def link_lines(self) -> dict[str, tuple[str, str]]:
        out = {self.base: (self.joints[0], self.joints[1])}
        out.update({ld.link: (ld.joint, j) for ld, j in zip(self.leads, self.joints) if not ld.slider})
        return out

    def link_lengths(self) -> dict[str, float]:
        out = {self.base: max(self.sides)}
        out.update({lead.link: lead.length for lead in self.leads if not lead.slider})
        return out

    def sizes(self) -> tuple[tuple[tuple[str, str], float], ...]:
        b, c, d = self.joints
        out = tuple(zip(((b, c), (c, d), (d, b)), self.sides))
        return out + tuple(((ld.joint, j), ld.length) for ld, j in zip(self.leads, self.joints) if not ld.slider)

    def offsets(self) -> tuple[tuple[str, float], ...]:
        return tuple((ld.link, ld.guide.offset) for ld in self.leads if ld.slider and ld.guide.offset)

    def output_slides(self) -> dict[str, tuple[str, str]]:
        out = {}
        for j, lead in zip(self.joints, self.leads):
            if lead.slider:
                slide = (lead.link, self.slide_pair(lead.link, lead.guide.link))
                out.update({name: slide for name in (j, lead.coincident) if name and name not in out})
        return out

    def output_joint(self, link: str) -> str | None:
        """The inner joint of the output lead (B for the base link)."""
        return self.joints[max(self.links.index(link) - 1, 0)] if link in self.links else None

    def solved_point(self) -> str:
        return self.joints[0]

    def given_lengths(self) -> tuple[float, ...]:
        return self.sides + tuple(lead.length for lead in self.leads)

    def design_keys(self, every: bool = False) -> tuple[str, ...]:
        if not every:
            return ()
        rods = tuple(f"leads.{j}.length" for j, lead in enumerate(self.leads) if not lead.slider)
        guides = tuple(f"leads.{j}.guide.{f}" for j, lead in enumerate(self.leads) if lead.slider
                       for f in ("offset", "angle_deg"))
        return tuple(f"sides.{j}" for j in range(3)) + rods + guides

    def named_points(self) -> tuple[tuple[str, str | None], ...]:
        named = [("joint", j) for j in self.joints] + [("special point", self.special_name)]
        return tuple(named + [("coincident", lead.coincident) for lead in self.leads])

    def shifted(self, dx: float, dy: float):
        return replace(self, assembly=tuple((n, (x + dx, y + dy)) for n, (x, y) in self.assembly))


Group = Union[RRR, RRP, RPR, PRP, RPP, Triad]

KINDS: tuple[type, ...] = (RRR, RRP, RPR, PRP, RPP, Triad)
"""Every group kind of the model (each layer's registry must hold every one)."""

_T = TypeVar("_T")


def kind_entry(registry: Mapping[type, _T], group: Any, where: str) -> _T:
    """The entry of ``group``'s kind in a layer's registry (``where`` names it); a
    `MechanismError` naming the kind and the registry for a kind it does not hold."""
    try:
        return registry[type(group)]
    except (KeyError, TypeError):
        known = ", ".join(k.__name__ for k in registry)
        raise MechanismError(f"group {getattr(group, 'name', '?')!r}: kind {type(group).__name__} is not handled "
                             f"by {where} (it knows {known})") from None


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
