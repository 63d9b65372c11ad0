"""Loads as data: frozen values that evaluate to `Actions` over the positions of a `Kinematics`.

Each load is built against one mechanism by a named constructor, which validates it and
resolves everything that depends only on the mechanism (the output's stroke, the crank angles
where a load starts and stops) once:

=====================  ===============================================================
`constant_force`       F = (Fx, Fy) at a point, N
`constant_moment`      M on a link, N·m (counter-clockwise positive)
`table_force`          magnitude interpolated in a table over the crank angle or over the
                       output's displacement, along a guide, against the motion or fixed
`cutting_force`        the shaper's cutting resistance: constant, against the ram, over a
                       fraction of the working (slow) stroke (seed 002)
`press_load`           seed 004's parabola between φ_start and φ_end, or its truncated
                       Fourier series
`indicator_force`      F = p·π·d²/4 from an indicator diagram p(travel) (seed 001)
=====================  ===============================================================

`gravity_actions` adds G = m·g (along −y) at the centre of every link with a mass. The
TOML form of these loads is read by `velplan.forces.parse.parse_loads`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, Protocol, Sequence

import numpy as np

from velplan.analysis.extremes import reference_angle, stroke
from velplan.analysis.roots import newton_bisection
from velplan.analysis.solver import Kinematics, solve
from velplan.errors import MechanismError
from velplan.forces.actions import Actions, AppliedForce, AppliedMoment
from velplan.forces.common import as_complex, check_point_of_link, dot, guide_frame_link, link_motion, point
from velplan.forces.fourier import FourierSeries, quadratic_coefficients
from velplan.mechanism.model import Mechanism

TWO_PI = 2.0 * math.pi


class Load(Protocol):
    """What every load value offers."""

    name: str

    def actions(self, kin: Kinematics) -> Actions:
        """Forces and moments of the load at the positions of ``kin``."""

    def breakpoints(self) -> tuple[float, ...]:
        """Crank angles (rad) where the load or its slope jumps (for piecewise integration)."""


# -- the output slider --------------------------------------------------------------------


@dataclass(frozen=True)
class Track:
    """The output slider and its working (slow) stroke, resolved once per mechanism.

    Attributes
    ----------
    point, link, pair : str
        The output point, the slider link it is a point of, its prismatic pair with the guide.
    sense : float
        +1 when the crank turns counter-clockwise, −1 otherwise.
    start_phi, end_phi : float
        Crank angles (rad) of the extremes at the start and end of the working stroke.
    s_start, s_end : float
        Slide s (m, along the guide direction u) at those extremes.
    span : float
        Crank turn during the working stroke, π + θ, rad.
    """

    point: str
    link: str
    pair: str
    sense: float
    start_phi: float
    end_phi: float
    s_start: float
    s_end: float
    span: float
    mechanism: Mechanism = field(repr=False, compare=False)

    @property
    def H(self) -> float:
        """Stroke, m."""
        return abs(self.s_end - self.s_start)

    def psi(self, phi) -> np.ndarray:
        """Crank turn from the start of the working stroke in the sense of rotation, [0, 2π)."""
        return np.mod(self.sense * (np.asarray(phi, dtype=float) - self.start_phi), TWO_PI)

    def phi(self, psi) -> np.ndarray:
        """Crank angle (rad) after a turn ``psi`` from the start of the working stroke."""
        return self.start_phi + self.sense * np.asarray(psi, dtype=float)

    def slide(self, kin: Kinematics) -> np.ndarray:
        """(n,) slide s of the output, m."""
        return kin.slide(self.pair)[:, 0]

    def direction(self, kin: Kinematics) -> np.ndarray:
        """(n,) complex unit vector u of the guide (s grows along u)."""
        return np.exp(1j * kin.angle(self.link))

    def psi_where(self, target, lo: float, hi: float) -> np.ndarray:
        """Turns ψ in [lo, hi] (on which s is monotonic) where s = ``target`` (m), to round-off.

        One solve on a grid brackets every target; a safeguarded Newton iteration on the exact
        analogue ds/dψ = ±ds/dφ (bisection where a step would leave the bracket, as at an
        extreme, where ds/dψ = 0) then takes two or three solves of all targets together.
        """
        target = np.atleast_1d(np.asarray(target, dtype=float))
        grid = np.linspace(float(lo), float(hi), 65)

        def s_of(psi):
            k = solve(self.mechanism, self.phi(psi), omega1=1.0, epsilon1=0.0, points=[self.point])
            sl = k.slide(self.pair)
            return sl[:, 0], self.sense * sl[:, 1]

        s, _ = s_of(grid)
        up = 1.0 if s[-1] >= s[0] else -1.0
        j = np.clip(np.searchsorted(up * s, up * target), 1, grid.size - 1)
        lo_, hi_ = grid[j - 1], grid[j]
        f_lo, f_hi = s[j - 1] - target, s[j] - target
        with np.errstate(divide="ignore", invalid="ignore"):
            x = lo_ - f_lo * (hi_ - lo_) / (f_hi - f_lo)
        x = np.where((x >= lo_) & (x <= hi_), x, 0.5 * (lo_ + hi_))

        def f(psi):
            sx, ds = s_of(psi)
            return sx - target, ds

        return newton_bisection(f, lo_, hi_, f_lo, x, ulps=4, closed=False)


def output_slider(mech: Mechanism) -> tuple[str, str, str] | None:
    """(output point, slider link, prismatic pair) of a slider output, or None."""
    out = mech.output
    if out is None or out.point is None:
        return None
    for g in mech.groups:
        slide = g.output_slides().get(out.point)
        if slide is not None:
            return (out.point, *slide)
    return None


def output_track(mech: Mechanism, where: str = "load") -> Track:
    """The output slider's `Track`; `MechanismError` naming ``where`` if there is none."""
    found = output_slider(mech)
    if found is None:
        what = "no output" if mech.output is None else (
            f"output link {mech.output.link}" if mech.output.link else f"output point {mech.output.point!r}, not a slider")
        raise MechanismError(f"{where}: needs an output slider (output = a point on a guide); "
                             f"mechanism {mech.name!r} has {what}")
    pt, link, pair = found
    st = stroke(mech)  # the output slider's stroke: its extremes' values are the slide s there
    return Track(pt, link, pair, mech.crank.sense, st.start.phi, st.end.phi,
                 float(st.start.value), float(st.end.value), float(math.pi + st.theta), mech)


def _where(name: str) -> str:
    """How messages name a load: ``load 'Fc'``, or ``load #2`` for an unnamed one."""
    return f"load {name}" if name.startswith("#") else f"load {name!r}"


def _link_and_point(mech: Mechanism, name: str, point: str | None, link: str | None,
                    track: Track | None = None) -> tuple[str, str]:
    where = _where(name)
    if point is None:
        if track is None:
            raise MechanismError(f"{where}: missing point")
        point = track.point
    if link is None:
        if track is not None and point == track.point:
            link = track.link
        else:
            from velplan.mechanism.structure import point_owners

            owners = point_owners(mech)
            if point not in owners:
                raise MechanismError(f"{where}: unknown point {point!r}; known points: {', '.join(owners)}")
            link = owners[point]
    check_point_of_link(mech, link, point, where)
    return link, point


def _positive(v: float, what: str, where: str, unit: str) -> float:
    if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0):
        raise MechanismError(f"{where}: {what} must be > 0 {unit}, not {v!r}")
    return float(v)


# -- constant force and moment --------------------------------------------------------------


@dataclass(frozen=True)
class PointForce:
    """A constant force (fx, fy), N, on ``link`` at its point ``point``."""

    name: str
    link: str
    point: str
    fx: float
    fy: float

    def actions(self, kin: Kinematics) -> Actions:
        v = np.full(len(kin), complex(self.fx, self.fy))
        return Actions((AppliedForce(self.name, self.link, self.point, v),))

    def breakpoints(self) -> tuple[float, ...]:
        return ()


@dataclass(frozen=True)
class LinkMoment:
    """A constant moment ``moment`` (N·m, counter-clockwise positive) on ``link``."""

    name: str
    link: str
    moment: float

    def actions(self, kin: Kinematics) -> Actions:
        return Actions((), (AppliedMoment(self.name, self.link, np.full(len(kin), float(self.moment))),))

    def breakpoints(self) -> tuple[float, ...]:
        return ()


def constant_force(mech: Mechanism, point: str, fx: float = 0.0, fy: float = 0.0, *,
                   link: str | None = None, name: str = "F") -> PointForce:
    """A constant force (fx, fy) in N at ``point`` of ``link`` (default: the point's owner)."""
    link, point = _link_and_point(mech, name, point, link)
    return PointForce(name, link, point, float(fx), float(fy))


def constant_moment(mech: Mechanism, link: str, moment: float, *, name: str = "M") -> LinkMoment:
    """A constant moment in N·m on ``link`` (counter-clockwise positive)."""
    if link not in mech.links:
        raise MechanismError(f"{_where(name)}: unknown link {link!r}; known links: {', '.join(mech.links)}")
    return LinkMoment(name, link, float(moment))


# -- direction helpers ----------------------------------------------------------------------

Direction = Literal["guide", "against-motion", "fixed"]


def _guide_link(mech: Mechanism, link: str, where: str) -> str:
    g = guide_frame_link(mech, link)
    if g is None:
        raise MechanismError(f"{where}: link {link!r} slides on no guide; give angle_deg for a fixed direction")
    return g


def _unit(kin: Kinematics, direction: str, guide: str | None, angle: float, link: str, at: np.ndarray) -> np.ndarray:
    if direction == "fixed":
        return np.full(len(kin), np.exp(1j * angle))
    u = np.exp(1j * kin.angle(guide))
    if direction == "guide":
        return u
    v, _ = link_motion(kin, link, at)
    return -np.sign(dot(v, u)) * u


# -- tables ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class TableForce:
    """A force whose magnitude is interpolated (linearly) in a table.

    ``over = "crank"``: ``x`` are crank turns in degrees from position 1 in the sense of
    rotation, periodic over 360°. ``over = "output"``: ``x`` are the output's displacements
    from the start of the working stroke, m (values beyond the table are held at its ends);
    ``stroke`` limits the load to the working or the return stroke.
    The force is ``value``·e along e: the guide's direction u (``"guide"``), −sign(V·u)·u
    (``"against-motion"``) or the fixed direction ``angle`` (rad, ``"fixed"``).
    """

    name: str
    link: str
    point: str
    over: Literal["crank", "output"]
    x: tuple[float, ...]
    values: tuple[float, ...]
    direction: Direction
    angle: float
    guide: str | None
    stroke: Literal["both", "working", "return"]
    ref_phi: float
    sense: float
    track: Track | None
    nodes: tuple[float, ...] = ()

    def magnitude(self, kin: Kinematics) -> np.ndarray:
        """(n,) signed magnitude, N."""
        x, y = np.asarray(self.x), np.asarray(self.values)
        if self.over == "crank":
            turn = np.degrees(np.mod(self.sense * (kin.phi - self.ref_phi), TWO_PI))
            # one period either side, sorted stably: an x given twice stays a jump in order
            # (np.interp's own period= sorts without that guarantee)
            xm = np.mod(x, 360.0)
            order = np.argsort(xm, kind="stable")
            xm, ym = xm[order], y[order]
            return np.interp(turn, np.concatenate((xm - 360.0, xm, xm + 360.0)), np.tile(ym, 3))
        t = self.track
        d = (t.slide(kin) - t.s_start) * np.sign(t.s_end - t.s_start)
        mag = np.interp(d, x, y)
        if self.stroke != "both":
            working = t.psi(kin.phi) < t.span
            mag = np.where(working if self.stroke == "working" else ~working, mag, 0.0)
        return mag

    def actions(self, kin: Kinematics) -> Actions:
        at = point(kin, self.point)
        e = _unit(kin, self.direction, self.guide, self.angle, self.link, at)
        return Actions((AppliedForce(self.name, self.link, self.point, self.magnitude(kin) * e),))

    def breakpoints(self) -> tuple[float, ...]:
        """Crank angles (rad) of every node of the table (a kink, or a jump at a repeated x)
        and of the output's extremes."""
        out = list(self.nodes)
        if self.over == "crank":
            out += [float(self.ref_phi + self.sense * math.radians(v)) for v in self.x]
        if self.track is not None:
            out += [self.track.start_phi, self.track.end_phi]
        return tuple(out)


def table_force(mech: Mechanism, x: Sequence[float], values: Sequence[float], *, point: str | None = None,
                link: str | None = None, over: Literal["crank", "output"] = "crank",
                direction: Direction = "guide", angle_deg: float = 0.0,
                stroke: Literal["both", "working", "return"] = "both", name: str = "F") -> TableForce:
    """A force interpolated in a table ``x`` → ``values`` (N); see `TableForce`."""
    where = _where(name)
    if over not in ("crank", "output"):
        raise MechanismError(f"{where}: over must be 'crank' or 'output', not {over!r}")
    if direction not in ("guide", "against-motion", "fixed"):
        raise MechanismError(f"{where}: direction must be 'guide' or 'against-motion', not {direction!r}")
    if stroke not in ("both", "working", "return"):
        raise MechanismError(f"{where}: stroke must be 'both', 'working' or 'return', not {stroke!r}")
    xs, ys = _table(x, values, where, "x", "values")
    if over == "crank" and point is None and output_slider(mech) is None:
        raise MechanismError(f"{where}: missing point")
    track = output_track(mech, where) if (over == "output" or point is None) else None
    if over == "crank" and stroke != "both":
        raise MechanismError(f"{where}: stroke = {stroke!r} needs over = 'output'")
    link, point = _link_and_point(mech, name, point, link, track)
    guide = _guide_link(mech, link, where) if direction != "fixed" else None
    nodes = ()
    if over == "output":
        nodes = _travel_nodes(track, xs, working=stroke != "return", back=stroke != "working", head="start")
    return TableForce(name, link, point, over, xs, ys, direction, math.radians(angle_deg), guide, stroke,
                      reference_angle(mech), mech.crank.sense, track, nodes)


def _travel_nodes(track: Track, travel: Sequence[float], *, working: bool, back: bool,
                  head: str) -> tuple[float, ...]:
    """Crank angles (rad, in [0, 2π)) where the output is at each ``travel`` (m from the extreme
    ``head``, "start" or "end" of the working stroke) strictly inside the stroke, on the working
    stroke and/or the return stroke: the nodes of a table over the output."""
    H = track.H
    d = np.unique(np.asarray(travel, dtype=float))
    d = d[(d > 1e-12 * H) & (d < H * (1 - 1e-12))]
    if d.size == 0:
        return ()
    s0, s1 = (track.s_start, track.s_end) if head == "start" else (track.s_end, track.s_start)
    target = s0 + d * math.copysign(1.0, s1 - s0)
    psi = []
    if working:
        psi.append(track.psi_where(target, 0.0, track.span))
    if back:
        psi.append(track.psi_where(target, track.span, TWO_PI))
    return tuple(float(v) for v in np.mod(track.phi(np.concatenate(psi)), TWO_PI))


RAMP = 1e-6
"""A table step narrower than this fraction of the table's span is refused as a near-vertical ramp."""


def _table(x, values, where: str, xname: str, yname: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Validated (x, values) of a piecewise-linear table. An x given twice is a jump (the value
    before it, then the value after it); a step of x narrower than `RAMP` × the span (a
    near-vertical ramp) is refused, so that no ramp is integrated as if it were smooth."""
    xs, ys = _numbers(x, where, xname), _numbers(values, where, yname)
    if len(xs) != len(ys):
        raise MechanismError(f"{where}: {xname} and {yname} must have the same length ({len(xs)} ≠ {len(ys)})")
    if len(xs) < 2:
        raise MechanismError(f"{where}: {xname} needs at least 2 values, not {len(xs)}")
    span = xs[-1] - xs[0]
    for i in range(1, len(xs)):
        if xs[i] < xs[i - 1]:
            raise MechanismError(f"{where}: {xname} must not decrease; {xname}[{i}] = {xs[i]:g} < {xs[i - 1]:g}")
        if xs[i] == xs[i - 1] and (i == 1 or i == len(xs) - 1 or xs[i - 2] == xs[i]):
            what = "repeated at an end of the table" if i in (1, len(xs) - 1) else "given a third time"
            raise MechanismError(f"{where}: {xname}[{i}] = {xs[i]:g} is {what}; an x may be given twice, "
                                 "inside the table, to write a jump")
        if 0 < xs[i] - xs[i - 1] <= RAMP * span:
            raise MechanismError(f"{where}: {xname}[{i}] = {xs[i]:.10g} is a near-vertical ramp from "
                                 f"{xname}[{i - 1}] = {xs[i - 1]:.10g}; give the same x twice to write a jump")
    return xs, ys


def _numbers(v, where: str, what: str) -> tuple[float, ...]:
    if not isinstance(v, (list, tuple, np.ndarray)):
        raise MechanismError(f"{where}: {what} must be a list of numbers, not {v!r}")
    out = []
    for i, x in enumerate(v):
        if isinstance(x, bool) or not isinstance(x, (int, float, np.floating, np.integer)) or not math.isfinite(x):
            raise MechanismError(f"{where}: {what}[{i}] must be a finite number, not {x!r}")
        out.append(float(x))
    return tuple(out)


# -- the shaper's cutting force (seed 002) --------------------------------------------------


@dataclass(frozen=True)
class CuttingForce:
    """Constant ``force`` (N) against the output slider's motion while it is between the
    fractions ``start`` and ``end`` of the working (slow) stroke from its start extreme.

    Notes
    -----
    Active where 0 ≤ ψ < π + θ (the working stroke) and start ≤ (s − s_start)/(s_end − s_start)
    ≤ end; F = −force·sign(s_end − s_start)·u. The work per revolution is
    force·(end − start)·H.
    """

    name: str
    link: str
    point: str
    force: float
    start: float
    end: float
    track: Track
    phi_on: float
    phi_off: float

    def active(self, kin: Kinematics) -> np.ndarray:
        """(n,) mask of the positions where the force acts."""
        t = self.track
        f = (t.slide(kin) - t.s_start) / (t.s_end - t.s_start)
        return (t.psi(kin.phi) < t.span) & (f >= self.start) & (f <= self.end)

    def actions(self, kin: Kinematics) -> Actions:
        t = self.track
        e = -np.sign(t.s_end - t.s_start) * t.direction(kin)
        v = np.where(self.active(kin), self.force * e, 0.0)
        return Actions((AppliedForce(self.name, self.link, self.point, v),))

    @property
    def work(self) -> float:
        """Work of the force per revolution, J: force·(end − start)·H."""
        return self.force * (self.end - self.start) * self.track.H

    def breakpoints(self) -> tuple[float, ...]:
        return (self.phi_on, self.phi_off)


def cutting_force(mech: Mechanism, force: float = 1400.0, *, start: float = 0.05, end: float = 0.95,
                  point: str | None = None, link: str | None = None, name: str = "Fc") -> CuttingForce:
    """The cutting resistance of a shaper (seed 002: 1400 N over 5…95 % of the working stroke)."""
    where = _where(name)
    force = _positive(force, "force", where, "N")
    for v, what in ((start, "start"), (end, "end")):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise MechanismError(f"{where}: {what} must be a fraction of the stroke, not {v!r}")
    if not 0.0 <= start < end <= 1.0:
        raise MechanismError(f"{where}: start and end must satisfy 0 ≤ start < end ≤ 1, not {start:g} and {end:g}")
    track = output_track(mech, where)
    link, point = _link_and_point(mech, name, point, link, track)
    ds = track.s_end - track.s_start
    on, off = track.psi_where([track.s_start + start * ds, track.s_start + end * ds], 0.0, track.span)
    return CuttingForce(name, link, point, force, float(start), float(end), track,
                        float(np.mod(track.phi(on), TWO_PI)), float(np.mod(track.phi(off), TWO_PI)))


# -- the press load of seed 004 -------------------------------------------------------------


@dataclass(frozen=True)
class PressLoad:
    """Seed 004's press load on the output slider: zero except while the slider approaches its
    lower extreme from the distance b1 + b2 (crank angle φ_start) to the distance b2 (φ_end),
    where it grows as a parabola in the crank angle to P_max at φ_end.

    ``harmonics`` None: the exact parabola; N ≥ 1: its Fourier series truncated after N
    harmonics. The force pushes the slider away from the lower extreme.

    Notes
    -----
    With ψ the crank turn from φ_start (in the sense of rotation) and Δ = ψ(φ_end):
    P(ψ) = P_max·ψ·(2Δ − ψ)/Δ² for 0 ≤ ψ ≤ Δ, else 0 — the parabola a·φ² + b·φ + c through
    (φ_start, 0), (φ_end, P_max) and (2·φ_end − φ_start, 0), vertex at φ_end.
    """

    name: str
    link: str
    point: str
    p_max: float
    b1: float
    b2: float
    harmonics: int | None
    track: Track
    phi_start: float
    phi_end: float
    away: float

    @property
    def width(self) -> float:
        """Δ = crank turn from φ_start to φ_end, rad."""
        return float(np.mod(self.track.sense * (self.phi_end - self.phi_start), TWO_PI))

    @property
    def parabola(self) -> tuple[float, float, float]:
        """(a, b, c) of P = a·φ² + b·φ + c (N/rad², N/rad, N), φ_end taken within one turn after
        φ_start in the sense of rotation."""
        d = self.width
        pe = self.phi_start + self.track.sense * d
        a = -self.p_max / d**2
        return a, -2.0 * a * pe, self.p_max + a * pe * pe

    def exact(self, phi) -> np.ndarray:
        """The discontinuous load P(φ), N (P_max at φ_end itself)."""
        d = self.width
        psi = np.mod(self.track.sense * (np.asarray(phi, dtype=float) - self.phi_start), TWO_PI)
        return np.where(psi <= d, self.p_max * psi * (2 * d - psi) / d**2, 0.0)

    def fourier(self, harmonics: int) -> FourierSeries:
        """Exact coefficients of the series of `exact` in φ, with ``harmonics`` harmonics."""
        d, p = self.width, self.p_max
        c = quadratic_coefficients((0.0, 2 * p / d, -p / d**2), 0.0, d, harmonics)
        if self.track.sense < 0:
            c = np.conj(c)
        c = c * np.exp(-1j * np.arange(harmonics + 1) * self.phi_start)
        return FourierSeries(c, p * p * (8.0 / 15.0) * d / TWO_PI)

    def approximation_error(self, harmonics: int, samples: int = 8192) -> tuple[float, float]:
        """(max |P − P_N|, RMS of P − P_N) over a revolution, N.

        The maximum is taken on ``samples`` uniform angles and at φ_start and both sides of
        the jump at φ_end; the RMS is exact (Parseval)."""
        series = self.fourier(harmonics)
        phi = np.linspace(0.0, TWO_PI, samples, endpoint=False)
        err = np.abs(series(phi) - self.exact(phi))
        s_end = float(series(np.array([self.phi_end]))[0])
        s_start = float(series(np.array([self.phi_start]))[0])
        worst = max(float(err.max()), abs(s_end - self.p_max), abs(s_end), abs(s_start))
        return worst, series.rms_error()

    def magnitude(self, phi) -> np.ndarray:
        """(n,) load magnitude used: the parabola or its truncated series, N."""
        return self.exact(phi) if self.harmonics is None else self.fourier(self.harmonics)(phi)

    def actions(self, kin: Kinematics) -> Actions:
        v = self.magnitude(kin.phi) * self.away * self.track.direction(kin)
        return Actions((AppliedForce(self.name, self.link, self.point, v),))

    def breakpoints(self) -> tuple[float, ...]:
        return () if self.harmonics is not None else (self.phi_start, self.phi_end)


def press_load(mech: Mechanism, p_max: float, b1: float, b2: float, *, harmonics: int | None = None,
               extreme: Literal["lower", "start", "end"] = "lower", point: str | None = None,
               link: str | None = None, name: str = "P") -> PressLoad:
    """Seed 004's parabolic press load (see `PressLoad`); ``extreme`` picks the extreme the
    load works towards: the lower one (smaller y of the point) or that at the start or end of
    the working stroke."""
    where = _where(name)
    p_max = _positive(p_max, "p_max", where, "N")
    b1 = _positive(b1, "b1", where, "m")
    if isinstance(b2, bool) or not isinstance(b2, (int, float)) or not math.isfinite(b2) or b2 < 0:
        raise MechanismError(f"{where}: b2 must be ≥ 0 m, not {b2!r}")
    if harmonics is not None and (isinstance(harmonics, bool) or not isinstance(harmonics, int) or harmonics < 1):
        raise MechanismError(f"{where}: harmonics must be a whole number ≥ 1 (0 or absent = the exact parabola), "
                             f"not {harmonics!r}")
    if extreme not in ("lower", "start", "end"):
        raise MechanismError(f"{where}: extreme must be 'lower', 'start' or 'end', not {extreme!r}")
    track = output_track(mech, where)
    link, point = _link_and_point(mech, name, point, link, track)
    if b1 + b2 > track.H:
        raise MechanismError(f"{where}: b1 + b2 = {b1 + b2:g} m exceeds the stroke H = {track.H:.6g} m")
    if extreme == "lower":
        k = solve(mech, [track.start_phi, track.end_phi])
        y = as_complex(k.position(point)).imag
        if abs(y[0] - y[1]) <= 1e-9 * max(track.H, 1e-300):
            raise MechanismError(f"{where}: the output moves horizontally, so it has no lower extreme; "
                                 "give extreme = 'start' or 'end'")
        to_end = bool(y[1] < y[0])
    else:
        to_end = extreme == "end"
    # Approach: from the other extreme to the chosen one, a half-stroke on which s is monotonic.
    if to_end:
        lo, hi, s_far, s_near = 0.0, track.span, track.s_start, track.s_end
    else:
        lo, hi, s_far, s_near = track.span, TWO_PI, track.s_end, track.s_start
    toward = math.copysign(1.0, s_near - s_far)
    on, off = track.psi_where([s_near - toward * (b1 + b2), s_near - toward * b2], lo, hi)
    if b2 == 0.0:
        off = np.float64(hi)
    return PressLoad(name, link, point, p_max, b1, float(b2), harmonics, track,
                     float(np.mod(track.phi(on), TWO_PI)), float(np.mod(track.phi(off), TWO_PI)), -toward)


# -- indicator diagram (seed 001) -----------------------------------------------------------


@dataclass(frozen=True)
class IndicatorForce:
    """Gas force on a piston: F = p·π·d²/4 with the gauge pressure p read off an indicator
    diagram at the piston's travel x from the cylinder head (the extreme ``head``).

    ``pressure_away`` applies while the piston moves away from the head (expansion, suction),
    ``pressure_toward`` while it returns (compression, exhaust). The force pushes the piston
    away from the head. One crank revolution is one cycle (a two-stroke engine, a single-acting
    compressor).
    """

    name: str
    link: str
    point: str
    bore: float
    travel: tuple[float, ...]
    pressure_away: tuple[float, ...]
    pressure_toward: tuple[float, ...]
    head: Literal["start", "end"]
    track: Track
    nodes: tuple[float, ...] = ()

    @property
    def area(self) -> float:
        """Piston area π·d²/4, m²."""
        return math.pi * self.bore**2 / 4

    def pressure(self, kin: Kinematics) -> np.ndarray:
        """(n,) gauge pressure, Pa."""
        t = self.track
        s_head, s_other = (t.s_start, t.s_end) if self.head == "start" else (t.s_end, t.s_start)
        x = np.abs(t.slide(kin) - s_head)
        psi = t.psi(kin.phi)
        away = psi < t.span if self.head == "start" else psi >= t.span
        tr = np.asarray(self.travel)
        return np.where(away, np.interp(x, tr, self.pressure_away), np.interp(x, tr, self.pressure_toward))

    def actions(self, kin: Kinematics) -> Actions:
        t = self.track
        s_head, s_other = (t.s_start, t.s_end) if self.head == "start" else (t.s_end, t.s_start)
        e = np.sign(s_other - s_head) * t.direction(kin)
        return Actions((AppliedForce(self.name, self.link, self.point, self.pressure(kin) * self.area * e),))

    def breakpoints(self) -> tuple[float, ...]:
        """The extremes and the crank angles where the piston passes every travel of the
        diagram, on both strokes (kinks or jumps of the pressure)."""
        return (self.track.start_phi, self.track.end_phi) + self.nodes


def indicator_force(mech: Mechanism, bore: float, travel: Sequence[float], pressure_away: Sequence[float],
                    pressure_toward: Sequence[float] | None = None, *, head: Literal["start", "end"] = "start",
                    point: str | None = None, link: str | None = None, name: str = "Fg") -> IndicatorForce:
    """An indicator-diagram load (see `IndicatorForce`): ``bore`` d in m, ``travel`` in m from
    the head, pressures in Pa (gauge)."""
    where = _where(name)
    bore = _positive(bore, "bore", where, "m")
    if head not in ("start", "end"):
        raise MechanismError(f"{where}: head must be 'start' or 'end', not {head!r}")
    tr, pa = _table(travel, pressure_away, where, "travel", "pressure_away")
    if pressure_toward is None:
        pt = pa
    else:
        _, pt = _table(travel, pressure_toward, where, "travel", "pressure_toward")
    if tr[0] < 0:
        raise MechanismError(f"{where}: travel must start at ≥ 0 m from the head, not {tr[0]:g}")
    track = output_track(mech, where)
    link, point = _link_and_point(mech, name, point, link, track)
    nodes = _travel_nodes(track, tr, working=True, back=True, head=head)
    return IndicatorForce(name, link, point, bore, tr, pa, pt, head, track, nodes)


# -- gravity ----------------------------------------------------------------------------------


def gravity_actions(mech: Mechanism, kin: Kinematics) -> Actions:
    """G = m·g along −y at the centre of every link with a mass (N); g = ``mech.gravity``."""
    forces = []
    for m in mech.masses:
        if m.mass > 0 and mech.gravity != 0:
            check_point_of_link(mech, m.link, m.centre, f"[link.{m.link}] centre")
            forces.append(AppliedForce(f"G{m.link}", m.link, m.centre,
                                       np.full(len(kin), -1j * m.mass * mech.gravity), "gravity"))
    return Actions(tuple(forces))


def load_actions(loads: Sequence[Load], kin: Kinematics) -> Actions:
    """The actions of all ``loads`` at the positions of ``kin``."""
    return Actions.join(ld.actions(kin) for ld in loads)
