"""Instant centres by construction (Aronhold–Kennedy), as a student finds them, and velocities
read off the centres.

The obvious centres come first: every revolute pair is the centre of the two links it joins
(a compound hinge is the centre of every two of its links), every prismatic pair puts the
centre of its two links at infinity, perpendicular to the guide. Then each unknown centre
P_ij is the intersection of two Kennedy lines P_ik–P_kj and P_il–P_lj (any three links'
centres lie on one line), through links k, l whose centres with i and j are known; the
circle diagram keeps the bookkeeping of found and remaining centres. The construction uses
the scheme's geometry only (positions and guide directions), never velocities.

Drawn exactly (float64) or as a draughtsman does (`Drafting`: every line's direction to
0.5°, every centre marked to 0.5 mm at the scheme's scale μl), with the sine of the angle
between the two lines as the condition of every intersection.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from velplan.analysis.centres import FAR, canonical, link_names
from velplan.analysis.numbering import position_index
from velplan.analysis.solver import Kinematics, length_scale
from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND
from velplan.mechanism.structure import pairs as lower_pairs
from velplan.mechanism.structure import material_points, point_owners
from velplan.options import Language
from velplan.plans import text as T
from velplan.plans.drafting import EXACT, Drafting
from velplan.plans.scale import standard_scale

SCHEME_MM = 150.0
"""Default size (mm) the scheme is drawn to when μl is chosen automatically."""
COINCIDE = 1e-9
"""Two centres closer than this × the mechanism's size are one point (a line through them is
undefined); two lines closer than that are one line."""


@dataclass(frozen=True)
class Line:
    """A Kennedy line through ``point`` (complex, m) along the unit ``direction``; ``at_infinity``
    for the line at infinity (through two centres at infinity). ``through`` names the two
    centres it is drawn through."""

    point: complex
    direction: complex
    through: tuple[tuple[str, str], tuple[str, str]]
    at_infinity: bool = False


@dataclass(frozen=True)
class CentreStep:
    """One centre of the construction.

    Attributes
    ----------
    number : int
        1-based step number.
    pair : (str, str)
        The links whose centre it is.
    how : {"joint", "hinge", "slider", "kennedy", "unreached"}
    point : complex or None
        The centre as constructed, m (None at infinity or unreached).
    direction : complex or None
        Unit direction of a centre at infinity.
    via : tuple of str
        The links k, l whose Kennedy lines were intersected ("kennedy"), the joint's point
        ("joint", "hinge"), or the slider's joint, the slider and the guide's link ("slider").
    lines : tuple of Line
        The two Kennedy lines used.
    condition : float
        Sine of the angle between the two lines (1 for an obvious centre).
    bound_m : float
        Estimated error of the drafted centre, m (0 when exact or obvious).
    found, remaining : tuple of (str, str)
        Circle-diagram bookkeeping after this step.
    reason : str
        Why an unreached centre could not be found ("isolated": fewer than two links k with
        both centres known; "coincident": the available lines are one line).
    """

    number: int
    pair: tuple[str, str]
    how: str
    point: complex | None = None
    direction: complex | None = None
    via: tuple[str, ...] = ()
    lines: tuple[Line, ...] = ()
    condition: float = 1.0
    bound_m: float = 0.0
    found: tuple[tuple[str, str], ...] = ()
    remaining: tuple[tuple[str, str], ...] = ()
    reason: str = ""

    @property
    def infinite(self) -> bool:
        return self.direction is not None


@dataclass(frozen=True)
class Construction:
    """The instant centres of a mechanism at one position, by construction.

    ``index`` is the position's index into the `Kinematics`; ``mu_l`` the scheme's scale,
    m/mm; ``steps`` the obvious centres, then the Kennedy intersections, then the unreached.
    """

    kin: Kinematics
    index: int
    mu_l: float
    drafting: Drafting
    links: tuple[str, ...]
    steps: tuple[CentreStep, ...]
    centres: dict = field(repr=False)

    @property
    def phi(self) -> float:
        return float(self.kin.phi[self.index])

    def centre(self, a: str, b: str) -> CentreStep | None:
        """The step that found P_ab (either order), None if it was not reached."""
        return self.centres.get(_key(a, b, self.links))

    @property
    def unreached(self) -> tuple[CentreStep, ...]:
        return tuple(s for s in self.steps if s.how == "unreached")

    def describe(self, lang: Language = "en") -> list[str]:
        """One sentence per step, in ``lang`` (en, ru, uk, zh), its centres and joints marked."""
        return [sentence(s, self, lang) for s in self.steps]


def _key(a: str, b: str, links: tuple[str, ...]) -> tuple[str, str]:
    return (a, b) if links.index(a) < links.index(b) else (b, a)


def _z(xy) -> complex:
    return complex(float(xy[0]), float(xy[1]))


def scheme_scale(kin: Kinematics, position: int, target_mm: float = SCHEME_MM) -> float:
    """Standard μl (m/mm) that draws the mechanism at position number ``position`` (1…n)
    within ``target_mm``."""
    xy = kin.positions[position_index(position, len(kin))]
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    span = float(np.ptp(xy, axis=0).max()) if len(xy) > 1 else 0.0
    return standard_scale(max(span, length_scale(kin.mechanism)) / target_mm)


def _mark(z: complex, mu_l: float, drafting: Drafting) -> complex:
    """A centre as marked on the drawing: each coordinate to the drafting precision."""
    if drafting.exact:
        return z
    xy = np.array([z.real, z.imag]) / mu_l
    q = drafting.length_mm
    xy = np.round(xy / q) * q if drafting.rng is None else xy + drafting.rng.uniform(-q / 2, q / 2, 2)
    return complex(xy[0], xy[1]) * mu_l


def _drawn(u: complex, drafting: Drafting) -> complex:
    """A unit direction as drawn."""
    return complex(drafting.direction(np.array([u]))[0])


def _obvious(kin: Kinematics, i: int, drafting: Drafting = EXACT) -> list[tuple[tuple[str, str], str, object, object]]:
    """The centres known at once at position ``i``: (pair, how, point or direction, the joint;
    for a slider (joint, slider, guide's link)).

    A revolute pair is the centre of its links; three or more links on one point (a compound
    hinge) have their centres there pairwise; a prismatic pair ``P:<slider>/<guide link>`` puts
    the centre at infinity perpendicular to the guide, which is the slider's reference
    direction (the model's convention for every group).
    """
    mech = kin.mechanism
    links = link_names(mech)
    out: dict[tuple[str, str], tuple] = {}
    hinge: dict[str, set[str]] = {}
    for p in lower_pairs(mech):
        key = _key(*p.links, links)
        if p.kind == "R":
            out.setdefault(key, (key, "joint", _z(kin.positions[i, kin.point_index[p.point]]), p.point))
            hinge.setdefault(p.point, set()).update(p.links)
        else:
            u = np.exp(1j * kin.angles[i, kin.link_index[p.links[0]]])
            d = complex(canonical(np.array([_drawn(1j * u, drafting)]))[0])
            out.setdefault(key, (key, "slider", d, (p.point, *p.links)))
    for point, on in hinge.items():
        at = _z(kin.positions[i, kin.point_index[point]])
        for a in sorted(on, key=links.index):
            for b in sorted(on, key=links.index):
                key = (a, b)
                if links.index(a) < links.index(b) and key not in out:
                    out[key] = (key, "hinge", at, point)
    return sorted(out.values(), key=lambda t: (links.index(t[0][0]), links.index(t[0][1])))


def _line(c1: CentreStep, c2: CentreStep, size: float, drafting: Drafting) -> Line | None:
    """The Kennedy line through two known centres; None when undefined (one point)."""
    through = (c1.pair, c2.pair)
    if c1.infinite and c2.infinite:  # one point at infinity twice: no line; two: the line at infinity
        if abs(_cross(c1.direction, c2.direction)) <= COINCIDE:
            return None
        return Line(0j, 1 + 0j, through, at_infinity=True)
    if c1.infinite or c2.infinite:
        p, d = (c2.point, c1.direction) if c1.infinite else (c1.point, c2.direction)
        return Line(p, _drawn(d, drafting), through)
    d = c2.point - c1.point
    if abs(d) <= COINCIDE * size:
        return None
    return Line(c1.point, _drawn(d / abs(d), drafting), through)


def _cross(a: complex, b: complex) -> float:
    return a.real * b.imag - a.imag * b.real


def intersect(l1: Line, l2: Line, size: float):
    """(point, direction, sine) of two Kennedy lines: a point, or a direction at infinity;
    None when they are one line or both at infinity."""
    if l1.at_infinity and l2.at_infinity:
        return None
    if l1.at_infinity or l2.at_infinity:
        d = (l2 if l1.at_infinity else l1).direction
        return None, complex(canonical(np.array([d]))[0]), 1.0
    sine = _cross(l1.direction, l2.direction)
    gap = _cross(l2.direction, l2.point - l1.point)
    if abs(sine) <= 1e-15 and abs(gap) <= COINCIDE * size:
        return None
    if abs(gap) >= abs(sine) * FAR * size:
        return None if abs(gap) <= COINCIDE * size else (None, complex(canonical(np.array([l1.direction]))[0]), abs(sine))
    t = -gap / sine
    return l1.point + t * l1.direction, None, abs(sine)


def _candidates(pair, known: dict, links, size: float, drafting: Drafting) -> list[tuple[str, Line]]:
    """(k, Kennedy line P_ik–P_kj) for every link k whose centres with both i and j are known."""
    i, j = pair
    out = []
    for k in links:
        if k in pair:
            continue
        c1, c2 = known.get(_key(i, k, links)), known.get(_key(k, j, links))
        if c1 is None or c2 is None:
            continue
        line = _line(c1, c2, size, drafting)
        if line is not None:
            out.append((k, line))
    return out


def _best(pair, known: dict, links, size: float, drafting: Drafting):
    """The best-conditioned intersection of two Kennedy lines for ``pair``:
    (sine, (k, l), (line k, line l), point, direction), or the reason it has none."""
    cands = _candidates(pair, known, links, size, drafting)
    if len(cands) < 2:
        i, j = pair
        ks = [k for k in links if k not in pair and _key(i, k, links) in known and _key(k, j, links) in known]
        return "isolated" if len(ks) < 2 else "coincident"
    best = None
    for a in range(len(cands)):
        for b in range(a + 1, len(cands)):
            (k, l1), (m, l2) = cands[a], cands[b]
            hit = intersect(l1, l2, size)
            if hit is not None and (best is None or hit[2] > best[0]):
                best = (hit[2], (k, m), (l1, l2), hit[0], hit[1])
    return best if best is not None else "coincident"


def _lateral(line: Line, x: complex, known: dict, mu_l: float, drafting: Drafting) -> float:
    """How far (mm) a drafted Kennedy line may pass from where it should at ``x``: its drawn
    direction's error at that distance, plus the errors of the centres it is drawn through,
    levered by where ``x`` lies between them."""
    c1, c2 = (known[p] for p in line.through)
    reach = abs(x - line.point) / mu_l
    out = drafting.length_mm + reach * math.radians(drafting.angle_deg)
    if c1.infinite or c2.infinite:
        return out + (c2.bound_m if c1.infinite else c1.bound_m) / mu_l
    span = max(abs(c2.point - c1.point), 1e-300)
    return out + (c1.bound_m * abs(x - c2.point) + c2.bound_m * abs(x - c1.point)) / span / mu_l


def _bound(pt, lines: tuple[Line, ...], sine: float, known: dict, mu_l: float, drafting: Drafting) -> float:
    """Error estimate of a drafted intersection, m: each line's lateral error (`_lateral`) over
    the sine of the angle between the lines (0 when exact, or at infinity)."""
    if drafting.exact or pt is None:
        return 0.0
    mm = sum(_lateral(ln, pt, known, mu_l, drafting) for ln in lines) / max(sine, 1e-12)
    return mm * mu_l


def construct_centres(kin: Kinematics, position: int, *, drafting: Drafting = EXACT,
                      mu_l: float | None = None) -> Construction:
    """The instant centres at position number ``position`` (1…n) of ``kin`` by the Kennedy
    construction.

    Parameters
    ----------
    drafting : Drafting
        `EXACT`, or a draughtsman's precision (lines to ``angle_deg``, marks to ``length_mm``
        at the scale ``mu_l``).
    mu_l : float, optional
        Scale of the scheme, m/mm (default: a standard one, `scheme_scale`).

    Returns
    -------
    Construction
        Obvious centres first, then each intersection in the order found (the best
        conditioned available first), then every centre not reachable by Kennedy lines.
    """
    i = position_index(position, len(kin))
    if not kin.valid[i]:
        raise MechanismError(f"the mechanism is not assembled at crank angle {kin.phi_deg[i]:.6g}°")
    mech = kin.mechanism
    links = link_names(mech)
    size = length_scale(mech)
    mu = mu_l if mu_l is not None else scheme_scale(kin, position)
    every = [(a, b) for k, a in enumerate(links) for b in links[k + 1:]]
    known: dict[tuple[str, str], CentreStep] = {}
    steps: list[CentreStep] = []

    def add(step: CentreStep) -> None:
        known[step.pair] = step
        found = tuple(p for p in every if p in known)
        remaining = tuple(p for p in every if p not in known)
        steps.append(CentreStep(**{**step.__dict__, "number": len(steps) + 1, "found": found,
                                   "remaining": remaining}))
        known[step.pair] = steps[-1]

    for pair, how, where, joint in _obvious(kin, i, drafting):
        if how == "slider":  # via: the slider's joint, the slider, the guide's link
            add(CentreStep(0, pair, how, direction=where, via=joint))
        else:
            add(CentreStep(0, pair, how, point=where, via=(joint,)))
    while True:
        options = [(p, _best(p, known, links, size, drafting)) for p in every if p not in known]
        ready = [(p, b) for p, b in options if isinstance(b, tuple)]
        if not ready:
            break
        pair, (sine, via, lines, pt, d) = max(ready, key=lambda t: t[1][0])
        bound = _bound(pt, lines, sine, known, mu, drafting)
        if pt is not None:
            pt = _mark(pt, mu, drafting)
        add(CentreStep(0, pair, "kennedy", point=pt, direction=d, via=via, lines=lines,
                       condition=float(sine), bound_m=bound))
    for pair, reason in ((p, _best(p, known, links, size, drafting)) for p in every if p not in known):
        steps.append(CentreStep(len(steps) + 1, pair, "unreached", reason=reason,
                                found=tuple(p for p in every if p in known),
                                remaining=tuple(p for p in every if p not in known)))
    return Construction(kin, i, mu, drafting, links, tuple(steps), dict(known))


# -- velocities by centres ------------------------------------------------------------------

@dataclass(frozen=True)
class CentreVelocities:
    """ω of every link (rad/s) and the velocity of every named point (complex, m/s) found from
    the centres; ``path`` names, per link, the link and centre its ω came from."""

    omegas: dict
    velocities: dict
    path: dict


def _measure(length_m: float, mu_l: float, drafting: Drafting) -> float:
    """A distance on the scheme as measured, m."""
    return float(drafting.length(np.array([length_m / mu_l]))[0]) * mu_l


def _field_at(f, x: complex, con: Construction) -> complex:
    """Velocity of the point ``x`` of a link with field ``f``: ("rot", ω, P0) or ("trans", V)."""
    if f[0] == "trans":
        return f[1]
    _, w, p0 = f
    r = x - p0
    if abs(r) == 0:
        return 0j
    size = w * _measure(abs(r), con.mu_l, con.drafting)
    return size * _drawn(1j * r / abs(r), con.drafting)


def _next_field(j: str, i: str, fi, con: Construction):
    """The field of link j from the solved link i (field ``fi``), their centre P_ij and j's
    centre with the frame: (field, relative error estimate), or None when they do not
    determine it."""
    p0j, pij = con.centre(GROUND, j), con.centre(i, j)
    if p0j is None or pij is None:
        return None
    if pij.infinite:  # relative translation: ω_j = ω_i about P_0j
        return (("rot", fi[1], p0j.point), 0.0) if fi[0] == "rot" and not p0j.infinite else None
    v = _field_at(fi, pij.point, con)
    arm = pij.bound_m / max(abs(pij.point - fi[2]), 1e-300) if fi[0] == "rot" else 0.0
    if p0j.infinite:  # j translates with the velocity of P_ij
        return ("trans", v), arm
    r = pij.point - p0j.point
    if abs(r) <= COINCIDE * length_scale(con.kin.mechanism):
        return None
    size = _measure(abs(r), con.mu_l, con.drafting)
    error = (pij.bound_m + p0j.bound_m) / abs(r)
    if fi[0] == "rot":  # ω_j = ω_i·|P0i Pij| / |P0j Pij|, opposite senses when P_ij is between
        ri = pij.point - fi[2]
        between = (ri.real * r.real + ri.imag * r.imag) < 0
        ratio = _measure(abs(ri), con.mu_l, con.drafting) / size
        error += arm
        return ("rot", fi[1] * ratio * (-1.0 if between else 1.0), p0j.point), error
    sense = np.sign((v / (1j * r)).real)  # a translating link i: ω_j = |v| / |P0j Pij|
    return ("rot", sense * abs(v) / size, p0j.point), error


def velocities_by_centres(con: Construction) -> CentreVelocities:
    """Every link's ω and every named point's velocity from the centres of ``con``:
    v_M = ω_k × (M − P_0k), ω_j = ω_i·|P_0i P_ij| / |P_0j P_ij| (sign: opposite when P_ij lies
    between P_0i and P_0j), a translating link's velocity that of its centre with a known link.
    Each link is reached from the crank along the path of least estimated error (the fewest
    steps when exact). Distances are measured at the construction's drafting precision. NaN
    where a link's field cannot be reached."""
    kin, i = con.kin, con.index
    mech = kin.mechanism
    w1 = float(np.broadcast_to(kin.omega1, kin.phi.shape)[i])
    pivot = _z(kin.positions[i, kin.point_index[mech.crank.pivot]])
    solved = {GROUND: ("trans", 0j), mech.crank.link: ("rot", w1, pivot)}
    cost = {GROUND: (0.0, 0), mech.crank.link: (0.0, 0)}
    path = {mech.crank.link: (GROUND, (GROUND, mech.crank.link))}
    while True:
        best = None
        for j in con.links:
            for k, fk in ([] if j in solved else solved.items()):
                got = None if k == GROUND else _next_field(j, k, fk, con)
                if got is not None:
                    key = (cost[k][0] + got[1], cost[k][1] + 1)
                    if best is None or key < best[0]:
                        best = (key, j, k, got[0])
        if best is None:
            break
        key, j, k, f = best
        solved[j], cost[j], path[j] = f, key, (k, _key(k, j, con.links))
    nan = complex(np.nan, np.nan)
    omegas = {k: (0.0 if solved[k][0] == "trans" else solved[k][1]) if k in solved else np.nan
              for k in con.links if k != GROUND}
    on: dict[str, list[str]] = {}
    for link, names in material_points(mech).items():
        for name in names:
            on.setdefault(name, []).append(link)
    vel = {}
    for name, link in point_owners(mech).items():
        if link == GROUND:
            continue
        x = _z(kin.positions[i, kin.point_index[name]])
        links = [k for k in on.get(name, [link]) if k in solved] or [link]
        k = min(links, key=lambda k: _point_error(k, x, cost, con))  # a joint: the surer link
        vel[name] = _field_at(solved[k], x, con) if k in solved else nan
    return CentreVelocities(omegas, vel, path)


def _point_error(link: str, x: complex, cost: dict, con: Construction) -> tuple[float, int]:
    """Estimated relative error of a point's velocity read on ``link``: the link's ω, and its
    centre's error over the point's distance from it."""
    if link not in cost:
        return (math.inf, 0)
    p0 = con.centre(GROUND, link)
    extra = 0.0 if p0 is None or p0.infinite else p0.bound_m / max(abs(x - p0.point), 1e-300)
    return (cost[link][0] + extra, cost[link][1])


# -- sentences ------------------------------------------------------------------------------

_PHRASES: dict[str, dict[str, str]] = {
    "joint": {
        "en": "The revolute pair {0} joins links {1} and {2}: it is their centre {3}.",
        "ru": "Вращательная пара {0} соединяет звенья {1} и {2}: это их мгновенный центр {3}.",
        "uk": "Обертальна пара {0} з'єднує ланки {1} і {2}: це їхній миттєвий центр {3}.",
        "zh": "转动副 {0} 连接构件 {1} 与 {2}：它就是瞬心 {3}。",
    },
    "hinge": {
        "en": "Links {1} and {2} both turn about the compound hinge {0}: {3} is at {0}.",
        "ru": "Звенья {1} и {2} входят в сложный шарнир {0}: центр {3} находится в точке {0}.",
        "uk": "Ланки {1} і {2} входять у складний шарнір {0}: центр {3} знаходиться в точці {0}.",
        "zh": "构件 {1} 与 {2} 同在复合铰链 {0}：瞬心 {3} 位于 {0}。",
    },
    "slider": {
        "en": "Link {1} slides on link {2}: {3} is at infinity, perpendicular to the guide ({0}°).",
        "ru": "Звено {1} скользит по звену {2}: центр {3} в бесконечности, перпендикулярно направляющей ({0}°).",
        "uk": "Ланка {1} ковзає по ланці {2}: центр {3} у нескінченності, перпендикулярно до напрямної ({0}°).",
        "zh": "构件 {1} 沿构件 {2} 移动：瞬心 {3} 在垂直于导路的无穷远处（{0}°）。",
    },
    "kennedy": {
        "en": "{0} lies on the line {1}{2} and on the line {3}{4} (Aronhold–Kennedy): they meet at "
              "{0} = ({5}; {6}) {7} (sine of their angle {8}).",
        "ru": "Центр {0} лежит на прямой {1}{2} и на прямой {3}{4} (теорема Аронгольда–Кеннеди): "
              "их пересечение {0} = ({5}; {6}) {7} (синус угла между ними {8}).",
        "uk": "Центр {0} лежить на прямій {1}{2} і на прямій {3}{4} (теорема Аронгольда–Кеннеді): "
              "їх перетин {0} = ({5}; {6}) {7} (синус кута між ними {8}).",
        "zh": "瞬心 {0} 位于直线 {1}{2} 与直线 {3}{4} 上（三心定理）：两线交于 "
              "{0} = ({5}; {6}) {7}（夹角正弦 {8}）。",
    },
    "kennedy_far": {
        "en": "{0} lies on the line {1}{2} and on the line {3}{4}; they are parallel: {0} is at "
              "infinity in their direction ({5}°).",
        "ru": "Центр {0} лежит на прямой {1}{2} и на прямой {3}{4}; они параллельны: {0} в "
              "бесконечности в их направлении ({5}°).",
        "uk": "Центр {0} лежить на прямій {1}{2} і на прямій {3}{4}; вони паралельні: {0} у "
              "нескінченності в їхньому напрямі ({5}°).",
        "zh": "瞬心 {0} 位于直线 {1}{2} 与直线 {3}{4} 上；两线平行：{0} 在其方向的无穷远处（{5}°）。",
    },
    "isolated": {
        "en": "{0} cannot be found by Kennedy lines: fewer than two links have known centres with "
              "both {1} and {2} (a class III group: use Assur's special point or the velocity plan).",
        "ru": "Центр {0} не находится прямыми Кеннеди: меньше двух звеньев имеют известные центры "
              "и с {1}, и с {2} (группа III класса: особая точка Ассура или план скоростей).",
        "uk": "Центр {0} не знаходиться прямими Кеннеді: менше двох ланок мають відомі центри "
              "і з {1}, і з {2} (група III класу: особлива точка Ассура або план швидкостей).",
        "zh": "瞬心 {0} 无法用三心定理直线求得：与 {1}、{2} 均有已知瞬心的构件少于两个"
              "（III 级杆组：用阿苏尔特殊点或速度多边形）。",
    },
    "coincident": {
        "en": "{0} cannot be found by Kennedy lines at this position: the lines available for it "
              "are undefined (their two centres coincide) or are one line — a singular position "
              "of the construction; the analytic centre is its limit.",
        "ru": "Центр {0} в этом положении не находится прямыми Кеннеди: доступные прямые не "
              "определены (их два центра совпадают) или совпадают между собой — особое положение "
              "построения; аналитический центр — его предел.",
        "uk": "Центр {0} у цьому положенні не знаходиться прямими Кеннеді: доступні прямі не "
              "визначені (їхні два центри збігаються) або збігаються між собою — особливе "
              "положення побудови; аналітичний центр — його границя.",
        "zh": "此位置瞬心 {0} 无法用三心定理直线求得：可用直线不确定（其两瞬心重合）或彼此重合"
              "——作图的奇异位置；解析瞬心为其极限。",
    },
    "tally": {
        "en": " Found {0} of {1}.", "ru": " Найдено {0} из {1}.", "uk": " Знайдено {0} з {1}.",
        "zh": " 已求得 {0}/{1}。",
    },
}


def centre_name(pair: tuple[str, str]) -> str:
    """``P02``, or ``P1,12`` when a link name has more than one character."""
    a, b = pair
    return f"P{a}{b}" if len(a) == 1 and len(b) == 1 else f"P{a},{b}"


def sentence(s: CentreStep, con: Construction, lang: Language) -> T.Sentence:
    """The worked-solution sentence of step ``s`` in ``lang``, its centres and joints marked
    (`velplan.plans.text.Sym`)."""
    lang = T.check_lang(lang)
    name = T.pts(centre_name(s.pair))
    ph = lambda key, *a: T.formatted(_PHRASES[key][lang], *a)  # noqa: E731
    if s.how in ("joint", "hinge"):
        text = ph(s.how, T.pts(s.via[0]), s.pair[0], s.pair[1], name)
    elif s.how == "slider":
        deg = round(math.degrees(math.atan2(s.direction.imag, s.direction.real)), 6) + 0.0  # no −0, no 1e-15
        text = ph("slider", T.num(deg, lang), *(s.via[1:] if len(s.via) == 3 else s.pair), name)
    elif s.how == "kennedy":
        k, m = s.via
        (a1, b1), (a2, b2) = s.lines[0].through, s.lines[1].through
        p1, q1, p2, q2 = (T.pts(centre_name(e)) for e in (a1, b1, a2, b2))
        ends = (T.text(p1, "–"), q1, T.text(p2, "–"), q2)
        if s.infinite:
            deg = math.degrees(math.atan2(s.direction.imag, s.direction.real))
            text = ph("kennedy_far", name, *ends, T.num(deg, lang))
        else:
            xy = (T.num(s.point.real / con.mu_l, lang), T.num(s.point.imag / con.mu_l, lang))
            text = ph("kennedy", name, *ends, *xy, T.unit("mm", lang), T.num(s.condition, lang, 3))
    else:
        text = ph(s.reason, name, s.pair[0], s.pair[1])
    if s.how != "unreached":
        text += ph("tally", len(s.found), len(s.found) + len(s.remaining))
    return text
