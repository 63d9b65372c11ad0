"""The analytic kinematic solver: closed-form positions and analytic derivatives of every
point and link of a mechanism, vectorised over an array of crank angles.

This is the independent reference that the graphical plans are checked against.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal, Mapping

import numpy as np

from velplan.analysis.groups import GroupResult, LinkMotion, Motion, State, carried, solve_group
from velplan.errors import AssemblyError, MechanismError
from velplan.mechanism.model import GROUND, RPP, RPR, Crank, Group, LinkPoint, Mechanism
from velplan.mechanism.structure import schedule


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over an array of crank angles.

    Arrays have a leading positions axis of length n and a trailing xy axis.

    Attributes
    ----------
    mechanism : Mechanism
    phi : ndarray, shape (n,)
        Crank angles, rad (absolute, from +x, counter-clockwise).
    omega1, epsilon1 : float
        Crank angular velocity (rad/s) and acceleration (rad/s²) used.
    positions, velocities, accelerations : ndarray, shape (n, P, 2)
        Point coordinates (m), velocities (m/s), accelerations (m/s²); NaN where not assembled.
    point_index : Mapping[str, int]
    angles, omegas, epsilons : ndarray, shape (n, L)
        Link angles (rad, the reference direction of each link's frame), ω (rad/s), ε (rad/s²).
    link_index : Mapping[str, int]
    link_origins : Mapping[str, str]
        Link → the point its frame starts at.
    slides : ndarray, shape (n, S, 3)
        Prismatic pairs: relative displacement s (m), sliding velocity ṡ (m/s) and
        acceleration s̈ (m/s²) along the guide.
    slide_index : Mapping[str, int]
        Pair name (``"P:<slider>/<guide link>"``) → index.
    condition : ndarray, shape (n, G)
        Condition estimate per group in [0, 1]: the sine of the angle between the two lines
        whose intersection fixes the group (1 = well conditioned, 0 = singular).
    group_index : Mapping[str, int]
    valid : ndarray of bool, shape (n,)
        Every group assembled and every result finite.
    """

    mechanism: Mechanism
    phi: np.ndarray
    omega1: float
    epsilon1: float
    positions: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray
    point_index: Mapping[str, int]
    angles: np.ndarray
    omegas: np.ndarray
    epsilons: np.ndarray
    link_index: Mapping[str, int]
    link_origins: Mapping[str, str]
    slides: np.ndarray
    slide_index: Mapping[str, int]
    condition: np.ndarray
    group_index: Mapping[str, int]
    valid: np.ndarray

    def __len__(self) -> int:
        return self.phi.shape[0]

    def _point(self, name: str) -> int:
        try:
            return self.point_index[name]
        except KeyError:
            raise MechanismError(
                f"unknown point {name!r}; known points: {', '.join(self.point_index)}"
            ) from None

    def _link(self, name: str) -> int:
        try:
            return self.link_index[name]
        except KeyError:
            raise MechanismError(
                f"unknown link {name!r}; known links: {', '.join(self.link_index)}"
            ) from None

    def position(self, name: str) -> np.ndarray:
        """(n, 2) coordinates of point ``name``, m."""
        return self.positions[:, self._point(name)]

    def velocity(self, name: str) -> np.ndarray:
        """(n, 2) velocity of point ``name``, m/s."""
        return self.velocities[:, self._point(name)]

    def acceleration(self, name: str) -> np.ndarray:
        """(n, 2) acceleration of point ``name``, m/s²."""
        return self.accelerations[:, self._point(name)]

    def angle(self, link: str) -> np.ndarray:
        """(n,) angle of ``link``'s reference direction, rad."""
        return self.angles[:, self._link(link)]

    def omega(self, link: str) -> np.ndarray:
        """(n,) angular velocity of ``link``, rad/s (counter-clockwise positive)."""
        return self.omegas[:, self._link(link)]

    def epsilon(self, link: str) -> np.ndarray:
        """(n,) angular acceleration of ``link``, rad/s²."""
        return self.epsilons[:, self._link(link)]

    def slide(self, pair: str) -> np.ndarray:
        """(n, 3) s, ṡ, s̈ of the prismatic pair ``pair``."""
        try:
            return self.slides[:, self.slide_index[pair]]
        except KeyError:
            raise MechanismError(
                f"unknown prismatic pair {pair!r}; known pairs: {', '.join(self.slide_index)}"
            ) from None

    @cached_property
    def phi_deg(self) -> np.ndarray:
        """Crank angles in degrees."""
        return np.degrees(self.phi)

    def error_bound(self, quantity: Literal["position", "velocity", "acceleration"] = "velocity") -> np.ndarray:
        """(n,) bound on the relative round-off error of ``quantity`` at each position.

        Notes
        -----
        Closing a group near a toggle loses accuracy: with the condition estimate c (the sine
        of the angle between the two lines that fix the group), a position is known to about
        ε/c, a velocity (one more division by c) to ε/c², an acceleration to ε/c³, relative to
        the mechanism's size and speed scales (ε = 2.2e-16). The bound sums this over the
        groups with a safety factor of 64; it is infinite where a group is singular.
        """
        power = {"position": 1, "velocity": 2, "acceleration": 3}[quantity]
        eps = np.finfo(float).eps
        if self.condition.shape[1] == 0:
            return np.full(len(self), 64 * eps)
        c = np.where(np.isfinite(self.condition), self.condition, 0.0)
        with np.errstate(divide="ignore"):
            return 64 * eps * (1.0 + np.sum(c ** -float(power), axis=1))

    def min_condition(self) -> np.ndarray:
        """(n,) smallest condition estimate over all groups at each position."""
        if self.condition.shape[1] == 0:
            return np.ones(len(self))
        return self.condition.min(axis=1)


def solve(
    mech: Mechanism,
    phi,
    *,
    omega1: float | None = None,
    epsilon1: float | None = None,
    on_failure: Literal["nan", "raise"] = "nan",
) -> Kinematics:
    """Solve ``mech`` at crank angles ``phi`` (rad, scalar or 1-D array).

    Parameters
    ----------
    mech : Mechanism
    phi : float or array_like
        Absolute crank angles, rad.
    omega1, epsilon1 : float, optional
        Override the crank's angular velocity (rad/s) and acceleration (rad/s²).
    on_failure : {"nan", "raise"}
        ``"nan"``: positions where a group cannot close hold NaN and ``valid`` is False there.
        ``"raise"``: raise `AssemblyError` naming the group, the point and the crank angle.

    Notes
    -----
    Each group is closed in its own closed form (circle–circle, circle–line, line–line),
    and its velocities and accelerations are the exact time derivatives of those closures:
    two linear equations per group, solved by Cramer's rule.
    """
    if on_failure not in ("nan", "raise"):
        raise ValueError(f"on_failure must be 'nan' or 'raise', not {on_failure!r}")
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    if phi.ndim != 1:
        raise ValueError(f"phi must be a scalar or a 1-D array, not shape {phi.shape}")
    crank = mech.crank
    w1 = crank.omega if omega1 is None else float(omega1)
    e1 = crank.epsilon if epsilon1 is None else float(epsilon1)
    n = phi.shape[0]
    st = State(n)
    zeros = np.zeros(n, dtype=complex)
    for name, (x, y) in mech.ground:
        st.points[name] = Motion(np.full(n, complex(x, y)), zeros, zeros)
    zr = np.zeros(n)
    st.links[GROUND] = LinkMotion(mech.ground[0][0], zr, zr, zr)
    scale = length_scale(mech)
    conditions: dict[str, np.ndarray] = {}
    valid = np.ones(n, dtype=bool)
    with np.errstate(all="ignore"):  # singular positions give inf/NaN, masked by `valid`
        _solve_items(mech, st, phi, w1, e1, scale, conditions, on_failure)
    for c in conditions.values():
        valid &= np.isfinite(c) & (c > 0)
    return _pack(mech, phi, w1, e1, st, conditions, valid)


def _solve_items(mech, st, phi, w1, e1, scale, conditions, on_failure) -> None:
    for item in schedule(mech):
        if isinstance(item, Crank):
            _solve_crank(item, st, phi, w1, e1)
        elif isinstance(item, LinkPoint):
            link = st.links[item.link]
            origin = st.points[link.origin]
            x = origin.p + (item.along + 1j * item.offset) * np.exp(1j * link.theta)
            st.points[item.name] = carried(origin, link, x)
        else:
            res = solve_group(item, st, scale)
            _check(item, res, phi, on_failure)
            st.points.update(res.points)
            st.links.update(res.links)
            st.slides.update(res.slides)
            conditions[item.name] = np.where(res.closed, res.condition, np.nan)


def _solve_crank(c: Crank, st: State, phi: np.ndarray, w1: float, e1: float) -> None:
    O = st.points[c.pivot]
    r = c.length * np.exp(1j * phi)
    st.points[c.tip] = Motion(O.p + r, 1j * w1 * r, (1j * e1 - w1 * w1) * r)
    n = phi.shape[0]
    st.links[c.link] = LinkMotion(c.pivot, phi.copy(), np.full(n, w1), np.full(n, e1))


def group_point(g: Group) -> str:
    """The point a group is said to solve for, used in messages."""
    if isinstance(g, (RPR, RPP)):
        return g.coincident or g.joint
    return g.point


def _check(g: Group, res: GroupResult, phi: np.ndarray, on_failure: str) -> None:
    if on_failure == "raise" and not res.closed.all():
        bad = float(np.degrees(phi[np.argmin(res.closed)]))
        raise AssemblyError(
            f"group {g.name!r} ({g.kind}) cannot be assembled: point {group_point(g)!r} "
            f"has no position at crank angle {bad:.6g}°",
            group=g.name,
            point=group_point(g),
            phi_deg=bad,
        )


def length_scale(mech: Mechanism) -> float:
    """A characteristic length of ``mech`` (m): its largest given length or ground span."""
    lengths = [mech.crank.length]
    for g in mech.groups:
        lengths.extend(getattr(g, "lengths", ()))
        lengths.append(getattr(g, "length", 0.0))
    pts = np.array([p for _, p in mech.ground])
    span = float(np.ptp(pts, axis=0).max()) if len(pts) > 1 else 0.0
    return max(max(lengths), span)


def _stack(values, n: int) -> np.ndarray:
    if not values:
        return np.zeros((n, 0, 2))
    z = np.stack(values, axis=1)
    return np.stack([z.real, z.imag], axis=-1)


def _pack(mech, phi, w1, e1, st: State, conditions, valid) -> Kinematics:
    n = phi.shape[0]
    names = list(st.points)
    pos = _stack([st.points[k].p for k in names], n)
    vel = _stack([st.points[k].v for k in names], n)
    acc = _stack([st.points[k].a for k in names], n)
    links = [k for k in st.links if k != GROUND]
    ang = np.stack([st.links[k].theta for k in links], axis=1)
    om = np.stack([st.links[k].omega for k in links], axis=1)
    ep = np.stack([st.links[k].epsilon for k in links], axis=1)
    slides = list(st.slides)
    sl = (
        np.stack([np.stack([st.slides[k].p, st.slides[k].v, st.slides[k].a], -1) for k in slides], 1).real
        if slides
        else np.zeros((n, 0, 3))
    )
    cond = np.stack(list(conditions.values()), axis=1) if conditions else np.zeros((n, 0))
    finite = np.isfinite(pos).all(axis=(1, 2)) & np.isfinite(vel).all(axis=(1, 2))
    finite &= np.isfinite(acc).all(axis=(1, 2)) & np.isfinite(om).all(axis=1)
    ang = np.angle(np.exp(1j * ang))  # wrap to (-π, π]
    return Kinematics(
        mechanism=mech,
        phi=phi,
        omega1=w1,
        epsilon1=e1,
        positions=pos,
        velocities=vel,
        accelerations=acc,
        point_index={k: i for i, k in enumerate(names)},
        angles=ang,
        omegas=om,
        epsilons=ep,
        link_index={k: i for i, k in enumerate(links)},
        link_origins={k: st.links[k].origin for k in links},
        slides=sl,
        slide_index={k: i for i, k in enumerate(slides)},
        condition=cond,
        group_index={k: i for i, k in enumerate(conditions)},
        valid=valid & finite,
    )


def transfer_functions(kin: Kinematics) -> dict[str, np.ndarray]:
    """Velocity analogues: ``"V_<point>"`` → |V|/ω1 (m) and ``"w_<link>"`` → ω/ω1 (signed)."""
    if kin.omega1 == 0:
        raise MechanismError("transfer functions need a crank speed omega1 ≠ 0")
    out = {f"V_{k}": np.hypot(*kin.velocities[:, i].T) / abs(kin.omega1) for k, i in kin.point_index.items()}
    out.update({f"w_{k}": kin.omegas[:, i] / kin.omega1 for k, i in kin.link_index.items()})
    return out


