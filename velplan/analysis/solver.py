"""The analytic kinematic solver: closed-form positions and analytic derivatives of every
point and link of a mechanism, vectorised over an array of crank angles.

This is the independent reference that the graphical plans are checked against.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import Iterable, Literal, Mapping

import numpy as np

from velplan.analysis.groups import LinkMotion, Motion, State, crank_tip, link_point, solve_group, wrap_angle
from velplan.errors import AssemblyError, MechanismError
from velplan.mechanism.model import GROUND, RPP, RPR, Crank, Group, LinkPoint, Mechanism, Triad
from velplan.mechanism.structure import guides_of, joints_in, points_out, schedule
from velplan.options import PlanKind


@dataclass(frozen=True)
class Kinematics:
    """Positions, velocities and accelerations over an array of crank angles.

    Arrays have a leading positions axis of length n and a trailing xy axis.

    Attributes
    ----------
    mechanism : Mechanism
    phi : ndarray, shape (n,)
        Crank angles, rad (absolute, from +x, counter-clockwise).
    omega1, epsilon1 : float or ndarray, shape (n,)
        Crank angular velocity (rad/s) and acceleration (rad/s²) used: one value, or one per
        position for a computed motion.
    positions, velocities, accelerations : ndarray, shape (n, P, 2)
        Point coordinates (m), velocities (m/s), accelerations (m/s²); NaN where not assembled;
        None above the ``order`` solved.
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
    order : int
        Highest derivative solved: 0 positions, 1 velocities, 2 accelerations.
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
    order: int = 2

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

    def _need(self, order: int, what: str) -> None:
        if self.order < order:
            raise MechanismError(f"{what} were not solved (order={self.order}); solve with order={order}")

    def velocity(self, name: str) -> np.ndarray:
        """(n, 2) velocity of point ``name``, m/s."""
        self._need(1, "velocities")
        return self.velocities[:, self._point(name)]

    def acceleration(self, name: str) -> np.ndarray:
        """(n, 2) acceleration of point ``name``, m/s²."""
        self._need(2, "accelerations")
        return self.accelerations[:, self._point(name)]

    def angle(self, link: str) -> np.ndarray:
        """(n,) angle of ``link``'s reference direction, rad."""
        return self.angles[:, self._link(link)]

    def omega(self, link: str) -> np.ndarray:
        """(n,) angular velocity of ``link``, rad/s (counter-clockwise positive)."""
        self._need(1, "velocities")
        return self.omegas[:, self._link(link)]

    def epsilon(self, link: str) -> np.ndarray:
        """(n,) angular acceleration of ``link``, rad/s²."""
        self._need(2, "accelerations")
        return self.epsilons[:, self._link(link)]

    def crank_rate(self, which: Literal["omega", "epsilon"] = "omega", idx=slice(None)) -> np.ndarray:
        """The crank's ω1 (rad/s) or ε1 (rad/s²) at positions ``idx``, one value per position."""
        value = self.omega1 if which == "omega" else self.epsilon1
        if isinstance(value, np.ndarray):
            return value[idx]
        return np.full(len(self.phi[idx]), value)

    def take(self, idx) -> "Kinematics":
        """The solution at positions ``idx`` only (indices or a slice)."""
        pick = lambda a: None if a is None else a[idx]  # noqa: E731
        w = self.omega1[idx] if isinstance(self.omega1, np.ndarray) else self.omega1
        e = self.epsilon1[idx] if isinstance(self.epsilon1, np.ndarray) else self.epsilon1
        return replace(self, phi=self.phi[idx], omega1=w, epsilon1=e, positions=self.positions[idx],
                       velocities=pick(self.velocities), accelerations=pick(self.accelerations),
                       angles=self.angles[idx], omegas=pick(self.omegas), epsilons=pick(self.epsilons),
                       slides=self.slides[idx], condition=self.condition[idx], valid=self.valid[idx])

    @property
    def steady(self) -> bool:
        """True when the crank turns at one constant ω1 (ε1 = 0)."""
        return not isinstance(self.omega1, np.ndarray) and not isinstance(self.epsilon1, np.ndarray) \
            and self.epsilon1 == 0

    def at_speed(self, omega1, epsilon1=0.0) -> "Kinematics":
        """The same positions moved at another crank motion: ω1, ε1 scalars or one per position.

        Exact for the unit-speed solution (ω1 = 1, ε1 = 0), whose velocities are the analogues
        r′ and accelerations r″: v = ω·r′, a = ω²·r″ + ε·r′ (links' ω, ε and slides alike).
        Other solutions are first brought back to unit speed (needs ω1 ≠ 0, ε1 = 0).
        """
        n = len(self)
        w = np.broadcast_to(np.asarray(omega1, dtype=float), (n,))
        e = np.broadcast_to(np.asarray(epsilon1, dtype=float), (n,))
        if isinstance(self.omega1, np.ndarray) or self.omega1 == 0 or np.any(self.epsilon1 != 0):
            raise MechanismError("at_speed needs a solution at one constant crank speed ω1 ≠ 0 with ε1 = 0")
        w0 = float(self.omega1)
        k = w / w0  # velocity analogue scale: v_new = ω·v_old/ω0
        vel = acc = om = ep = None
        sl = self.slides.copy()
        if self.order >= 1:
            vel = self.velocities * k[:, None, None]
            om = self.omegas * k[:, None]
            sl[:, :, 1] = self.slides[:, :, 1] * k[:, None]
        if self.order >= 2:
            r1 = self.velocities / w0  # r′
            acc = self.accelerations * (k * k)[:, None, None] + r1 * e[:, None, None]
            ep = self.epsilons * (k * k)[:, None] + (self.omegas / w0) * e[:, None]
            sl[:, :, 2] = self.slides[:, :, 2] * (k * k)[:, None] + (self.slides[:, :, 1] / w0) * e[:, None]
        w_out = float(omega1) if np.ndim(omega1) == 0 else np.array(w)
        e_out = float(epsilon1) if np.ndim(epsilon1) == 0 else np.array(e)
        return replace(self, omega1=w_out, epsilon1=e_out, velocities=vel, accelerations=acc,
                       omegas=om, epsilons=ep, slides=sl)

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
        spread = length_spread(self.mechanism)
        far = 0.0
        if quantity == "position":  # absolute coordinates carry ε·|x| of their own
            far = float(np.max(np.abs([xy for _, xy in self.mechanism.ground]))) / length_scale(self.mechanism)
        if self.condition.shape[1] == 0:
            return np.full(len(self), 64 * eps * (spread + far))
        c = np.where(np.isfinite(self.condition), self.condition, 0.0)
        with np.errstate(divide="ignore"):
            return 64 * eps * (spread * (1.0 + np.sum(c ** -float(power), axis=1)) + far)

    def largest(self, quantity: PlanKind, idx=slice(None)) -> float:
        """The largest |V| (m/s) or |a| (m/s²) of any point at positions ``idx`` (indices or a
        slice; all by default, computed once), positions not assembled left out."""
        key = f"_largest_{quantity}"
        if isinstance(idx, slice) and idx == slice(None) and key in self.__dict__:
            return self.__dict__[key]
        arr = self.velocities if quantity == "velocity" else self.accelerations
        z = arr[idx].view(complex)[..., 0].T  # (P, n): the solver's point-major rows
        size2 = z.real * z.real + z.imag * z.imag
        vmax2 = np.fmax.reduce(size2, axis=None, initial=0.0)  # NaN (not assembled) skipped
        if not np.isfinite(vmax2):
            vmax2 = np.max(size2, initial=0.0, where=np.isfinite(size2))
        out = float(np.sqrt(vmax2))
        if isinstance(idx, slice) and idx == slice(None):
            self.__dict__[key] = out  # a frozen dataclass: cached like functools.cached_property
        return out

    @property
    def singular(self) -> np.ndarray:
        """(n,) positions where every group closes but one is at a toggle: refused (``valid``
        False) because velocities there are not determined to `SINGULAR_BOUND`."""
        if self.condition.shape[1] == 0 or self.order < 1:
            return np.zeros(len(self), dtype=bool)
        closed = np.isfinite(self.condition).all(axis=1) & np.isfinite(self.positions).all(axis=(1, 2))
        return closed & ~self.valid

    def min_condition(self) -> np.ndarray:
        """(n,) smallest condition estimate over all groups at each position."""
        if self.condition.shape[1] == 0:
            return np.ones(len(self))
        return self.condition.min(axis=1)


def solve(
    mech: Mechanism,
    phi,
    *,
    omega1=None,
    epsilon1=None,
    points: Iterable[str] | None = None,
    order: Literal[0, 1, 2] = 2,
    on_failure: Literal["nan", "raise"] = "nan",
    engine: Literal["numpy", "compiled", "auto"] = "numpy",
) -> Kinematics:
    """Solve ``mech`` at crank angles ``phi`` (rad, scalar or 1-D array).

    Parameters
    ----------
    mech : Mechanism
    phi : float or array_like
        Absolute crank angles, rad.
    omega1, epsilon1 : float or array_like, optional
        The crank's angular velocity (rad/s) and acceleration (rad/s²): one value, or one per
        angle (a computed motion ω(φ), ε(φ)); the file's constant speed when omitted.
    points : iterable of str, optional
        Only these points (and what they depend on) are solved: groups and link points that
        none of them needs are skipped and absent from the result.
    order : {0, 1, 2}
        Highest derivative computed: positions only (0), + velocities (1), + accelerations (2).
        What is not computed is absent (`Kinematics.velocity` etc. raise naming the order).
    on_failure : {"nan", "raise"}
        ``"nan"``: positions where a group cannot close hold NaN and ``valid`` is False there.
        ``"raise"``: raise `AssemblyError` naming the group, the point and the crank angle.
    engine : {"numpy", "compiled", "auto"}
        ``"numpy"``: whole arrays, in cache-sized blocks. ``"compiled"``: the same closed forms
        run per position by numba on every core (``pip install velplan[fast]``; the first call
        on a machine compiles for ≈ 20 s, later processes load it in ≈ 0.1 s after numba's own
        import); ``points=`` and ``order=`` reach its kernel, which writes nothing else. ``"auto"``:
        compiled when numba is installed and either the kernel is loaded already or there are
        at least `AUTO_COMPILED` angles. Both give the same values to round-off.

    Notes
    -----
    Each group is closed in its own closed form (circle–circle, circle–line, line–line),
    and its velocities and accelerations are the exact time derivatives of those closures:
    two linear equations per group, solved by Cramer's rule.

    A motion given per angle is applied to the unit-speed solution (ω1 = 1, ε1 = 0, whose
    velocities are the analogues r′ = dr/dφ and accelerations r″): v = ω·r′,
    a = ω²·r″ + ε·r′, and likewise for the links' ω, ε and the slides' ṡ, s̈.
    """
    if on_failure not in ("nan", "raise"):
        raise ValueError(f"on_failure must be 'nan' or 'raise', not {on_failure!r}")
    if order not in (0, 1, 2):
        raise ValueError(f"order must be 0, 1 or 2, not {order!r}")
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    if phi.ndim != 1:
        raise ValueError(f"phi must be a scalar or a 1-D array, not shape {phi.shape}")
    crank = mech.crank
    w1 = _crank_rate(crank.omega if omega1 is None else omega1, "omega1", phi.shape[0])
    e1 = _crank_rate(crank.epsilon if epsilon1 is None else epsilon1, "epsilon1", phi.shape[0])
    if isinstance(w1, np.ndarray) or isinstance(e1, np.ndarray):
        unit = solve(mech, phi, omega1=1.0, epsilon1=0.0, points=points, order=order,
                     on_failure=on_failure, engine=engine)
        return unit.at_speed(w1, e1)
    local, shift = _about_pivot(mech)
    kin = _solve_scalar_rate(local, phi, w1, e1, points, order, on_failure, engine)
    if local is not mech:  # solved about the pivot: velocities do not lose digits to |x|
        kin = replace(kin, mechanism=mech, positions=kin.positions + shift)
    return kin


def _solve_scalar_rate(mech, phi, w1, e1, points, order, on_failure, engine) -> Kinematics:
    """`solve` at one crank speed and acceleration."""
    if engine not in ("numpy", "compiled", "auto"):
        raise ValueError(f"engine must be 'numpy', 'compiled' or 'auto', not {engine!r}")
    if engine == "compiled" or (engine == "auto" and _compiled().available()
                                and (_compiled().loaded() or phi.shape[0] >= AUTO_COMPILED)):
        kin = _solve_compiled(mech, phi, w1, e1, points, order, on_failure, engine)
        if kin is not None:
            return kin
    scale = length_scale(mech)
    items = schedule(mech) if points is None else needed_items(mech, points)
    w1o, e1o = (w1 if order >= 1 else 0.0), (e1 if order >= 2 else 0.0)
    out: _Outputs | None = None
    # cache-sized blocks written into preallocated outputs: 2.5× faster at 10⁶ positions
    for start in range(0, max(phi.shape[0], 1), BLOCK):
        block = phi[start:start + BLOCK]
        st, conditions = _solve_block(mech, block, w1o, e1o, scale, on_failure, items)
        if out is None:
            out = _Outputs(st, conditions, phi.shape[0], order)
        out.write(st, conditions, slice(start, start + block.shape[0]))
    return out.kinematics(mech, phi, w1, e1, st)


def _compiled():
    """The compiled engine's module, imported when an engine choice needs it (it brings
    hashlib and inspect, and numba only when it runs)."""
    from velplan.analysis import compiled

    return compiled


def _crank_rate(value, what: str, n: int):
    """A crank rate as a float, or as an (n,) array when it varies with the angle."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return float(arr)
    if arr.ndim != 1 or arr.shape[0] != n:
        raise ValueError(f"{what} must be a scalar or have one value per angle ({n}), not shape {arr.shape}")
    return arr


def needed_items(mech: Mechanism, points: Iterable[str]) -> tuple:
    """The solving schedule cut to what ``points`` need: the crank, the groups and link points
    that determine them or a point, guide or link they rest on.

    Raises
    ------
    MechanismError
        A name is not a point of ``mech``.
    """
    items = schedule(mech)
    want = set(points)
    made: dict[str, object] = {name: None for name, _ in mech.ground}
    for item in items:
        made.update(dict.fromkeys(_produced(item)[0], item))
    unknown = sorted(want - set(made))
    if unknown:
        raise MechanismError(f"unknown point {unknown[0]!r}; known points: {', '.join(made)}")
    want_links: set[str] = set()
    keep = []
    for item in reversed(items):
        pts, links = _produced(item)
        if isinstance(item, Crank) or pts & want or links & want_links:
            keep.append(item)
            need_pts, need_links = _needs(item)
            want |= need_pts
            want_links |= need_links
    return tuple(reversed(keep))


def _produced(item) -> tuple[set[str], set[str]]:
    if isinstance(item, Crank):
        return {item.tip}, {item.link}
    if isinstance(item, LinkPoint):
        return {item.name}, set()
    return set(points_out(item)), set(item.links)


def _needs(item) -> tuple[set[str], set[str]]:
    if isinstance(item, Crank):
        return {item.pivot}, set()
    if isinstance(item, LinkPoint):
        return set(), {item.link}
    return set(joints_in(item)), {g.link for g in guides_of(item) if g.link != GROUND}


BLOCK = 16384
"""Crank angles solved at a time (the arrays of a block stay in the CPU's caches)."""
AUTO_COMPILED = 2_000_000
"""From this many angles ``engine="auto"`` loads the compiled engine (≈ 0.5 s: numba's import and
the kernel from its disk cache; ≈ 20 s the first time on a machine; it saves ≈ 0.4 µs per angle);
once loaded in a process, "auto" always uses it."""


def _solve_compiled(mech, phi, w1, e1, points, order, on_failure, engine) -> Kinematics | None:
    """The compiled engine's solution, or None where it does not apply: a class III group (with a
    warning when ``engine="compiled"`` was asked for), solved by the numpy engine instead."""
    compiled = _compiled()
    lay = compiled.layout(mech, points)
    if lay.triad is not None:
        if engine == "compiled":
            import warnings

            warnings.warn(f"engine='compiled' does not cover class III groups (group {lay.triad!r}); "
                          "solving with the numpy engine", stacklevel=4)
        return None
    kin = compiled.solve(lay, mech, phi, w1, e1, order)
    if on_failure == "raise" and not kin.valid.all():
        for item in lay.items:  # the first group, in solving order, that fails to close
            if not isinstance(item, (Crank, LinkPoint)):
                closed = ~np.isnan(kin.condition[:, kin.group_index[item.name]])
                _check(item, closed, phi, on_failure)
    return kin


def _solve_block(mech, phi, w1, e1, scale, on_failure, items) -> tuple[State, dict[str, np.ndarray]]:
    n = phi.shape[0]
    st = State(n)
    zeros = np.zeros(n, dtype=complex)
    for name, (x, y) in mech.ground:
        st.points[name] = Motion(np.full(n, complex(x, y)), zeros, zeros)
    zr = np.zeros(n)
    st.links[GROUND] = LinkMotion(mech.ground[0][0], zr, zr, zr)
    conditions: dict[str, np.ndarray] = {}
    with np.errstate(all="ignore"):  # singular positions give inf/NaN, masked by `valid`
        _solve_items(items, st, phi, w1, e1, scale, conditions, on_failure, mech)
    return st, conditions


def _solve_items(items, st, phi, w1, e1, scale, conditions, on_failure, mech, tracks=None) -> None:
    for item in items:
        if isinstance(item, Crank):
            _solve_crank(item, st, phi, w1, e1)
        elif isinstance(item, LinkPoint):
            link = st.links[item.link]
            o = st.points[link.origin]
            st.points[item.name] = Motion(*link_point(o.p, o.v, o.a, link.theta, link.omega, link.epsilon,
                                                      item.along, item.offset))
        else:
            if isinstance(item, Triad):
                from velplan.analysis import triad

                trk = tracks[item.name] if tracks else triad.track(triad.upstream(mech, item), item, solve)
                res = triad.solve_triad(item, st, phi, trk, scale)
            else:
                res = solve_group(item, st, scale)
            _check(item, res.closed, phi, on_failure)
            st.points.update(res.points)
            st.links.update(res.links)
            st.slides.update(res.slides)
            conditions[item.name] = np.where(res.closed, res.condition, np.nan)


def _solve_crank(c: Crank, st: State, phi: np.ndarray, w1: float, e1: float) -> None:
    st.points[c.tip] = Motion(*crank_tip(st.points[c.pivot].p, c.length, phi, w1, e1))
    n = phi.shape[0]
    st.links[c.link] = LinkMotion(c.pivot, phi.copy(), np.full(n, w1), np.full(n, e1))


def special_pair(mech: Mechanism, g: Triad) -> tuple[int, int]:
    """The two leads (indices 0…2) of the triad ``g`` of ``mech`` whose lines give Assur's
    special point: the file's ``pair``, else the pair whose lines cross at the largest smallest
    angle over the tracked branch."""
    if g.pair is not None:
        return g.pair
    from velplan.analysis import triad

    local, _ = _about_pivot(mech)
    here = local.groups[mech.groups.index(g)]
    return triad.track(triad.upstream(local, here), here, solve).pair


def group_point(g: Group) -> str:
    """The point a group is said to solve for, used in messages."""
    if isinstance(g, (RPR, RPP)):
        return g.coincident or g.joint
    if isinstance(g, Triad):
        return g.joints[0]
    return g.point


def _check(g: Group, closed: np.ndarray, phi: np.ndarray, on_failure: str) -> None:
    if on_failure == "raise" and not closed.all():
        bad = float(np.degrees(phi[np.argmin(closed)]))
        raise AssemblyError(
            f"group {g.name!r} ({g.kind}) cannot be assembled: point {group_point(g)!r} "
            f"has no position at crank angle {bad:.6g}°",
            group=g.name,
            point=group_point(g),
            phi_deg=bad,
        )


def group_lengths(g: Group) -> tuple[float, ...]:
    """The lengths a group gives (m): rods, and a triad's base-link sides."""
    if isinstance(g, Triad):
        return g.sides + tuple(lead.length for lead in g.leads)
    return tuple(getattr(g, "lengths", ())) + (getattr(g, "length", 0.0),)


def length_scale(mech: Mechanism) -> float:
    """A characteristic length of ``mech`` (m): its largest given length or ground span."""
    lengths = [mech.crank.length]
    for g in mech.groups:
        lengths.extend(group_lengths(g))
    pts = np.array([p for _, p in mech.ground])
    span = float(np.ptp(pts, axis=0).max()) if len(pts) > 1 else 0.0
    return max(max(lengths), span)


def length_spread(mech: Mechanism) -> float:
    """The largest length of ``mech`` (`length_scale`) over its shortest link length (≥ 1)."""
    lengths = [mech.crank.length]
    for g in mech.groups:
        lengths.extend(group_lengths(g))
    shortest = min((x for x in lengths if x > 0), default=1.0)
    return max(1.0, length_scale(mech) / shortest)


def _about_pivot(mech: Mechanism) -> tuple[Mechanism, np.ndarray]:
    """``mech`` moved so that its crank's pivot is at the origin, and the shift (m)."""
    pivot = np.array(dict(mech.ground)[mech.crank.pivot], float)
    if not pivot.any():
        return mech, pivot
    from dataclasses import replace

    ground = tuple((n, (x - pivot[0], y - pivot[1])) for n, (x, y) in mech.ground)
    groups = tuple(replace(g, assembly=tuple((n, (x - pivot[0], y - pivot[1])) for n, (x, y) in g.assembly))
                   if isinstance(g, Triad) else g for g in mech.groups)
    return replace(mech, ground=ground, groups=groups), pivot


class _Outputs:
    """Preallocated result arrays, point- (link-, slide-, group-) major so that each block
    writes contiguous rows; `kinematics` returns (n, …) views of them without a copy. Only the
    derivatives up to ``order`` are kept."""

    def __init__(self, st: State, conditions: dict, n: int, order: int = 2):
        self.names = list(st.points)
        self.links = [k for k in st.links if k != GROUND]
        self.slide_names = list(st.slides)
        self.groups = list(conditions)
        self.order = order
        P, L, S, G = len(self.names), len(self.links), len(self.slide_names), len(self.groups)
        k = order + 1
        self.z = np.empty((k, P, n), dtype=complex)  # positions, velocities, accelerations
        self.rates = np.empty((k, L, n))  # angles, ω, ε
        self.slides = np.empty((S, k, n))
        self.condition = np.empty((G, n))
        self.valid = np.empty(n, dtype=bool)

    def write(self, st: State, conditions: dict, where: slice) -> None:
        """Copy a block's motions to the positions ``where``, then mark them (`_mark`) while
        they are still in the CPU's caches."""
        k = self.order + 1
        for j, name in enumerate(self.names):
            m = st.points[name]
            for d, arr in zip(range(k), (m.p, m.v, m.a)):
                self.z[d, j, where] = arr
        for j, name in enumerate(self.links):
            m = st.links[name]
            for d, arr in zip(range(k), (m.theta, m.omega, m.epsilon)):
                self.rates[d, j, where] = arr
        for j, name in enumerate(self.slide_names):
            m = st.slides[name]
            for d, arr in zip(range(k), (m.p, m.v, m.a)):
                self.slides[j, d, where] = arr.real
        for j, name in enumerate(self.groups):
            self.condition[j, where] = conditions[name]
        self._mark(where)

    def _mark(self, where: slice) -> None:
        """Valid positions among ``where`` (every output finite, every group closed and its
        velocities within `SINGULAR_BOUND`), and their angles wrapped into (−π, π]."""
        z, rates, condition = self.z[:, :, where], self.rates[:, :, where], self.condition[:, where]
        with np.errstate(invalid="ignore"):
            valid = np.isfinite(z.sum(axis=(0, 1))) & np.isfinite(rates[1:].sum(axis=(0, 1)))
            valid &= (np.isfinite(condition) & (condition > 0)).all(axis=0)
        if self.order >= 1 and condition.size and not np.fmin.reduce(condition, axis=None) >= WELL_CONDITIONED:
            valid &= velocity_bound(condition) <= SINGULAR_BOUND
        self.valid[where] = valid
        for row in rates[0]:  # cranks and guides may leave (−π, π]; wrap_angle keeps the others
            if ((row > np.pi) | (row <= -np.pi)).any():
                row[:] = wrap_angle(row)

    def keep(self, order: int) -> None:
        """Drop the derivatives above ``order`` (views: nothing is copied)."""
        self.order = order
        self.z, self.rates, self.slides = self.z[:order + 1], self.rates[:order + 1], self.slides[:, :order + 1]

    def kinematics(self, mech, phi, w1, e1, st: State, valid: np.ndarray | None = None) -> Kinematics:
        """The results as `Kinematics`: ``valid`` as given (the compiled kernel's, which wraps its
        angles itself) and refused where singular, else as `write` marked it block by block."""
        n = phi.shape[0]
        k = self.order + 1
        xy = self.z.view(float).reshape(k, len(self.names), n, 2).transpose(0, 2, 1, 3)
        if valid is None:
            valid = self.valid
        elif self.order >= 1 and self.condition.size:
            valid = valid & (velocity_bound(self.condition) <= SINGULAR_BOUND)
        rates = self.rates.transpose(0, 2, 1)
        return Kinematics(
            mechanism=mech,
            phi=phi,
            omega1=w1,
            epsilon1=e1,
            positions=xy[0],
            velocities=xy[1] if k > 1 else None,
            accelerations=xy[2] if k > 2 else None,
            point_index={name: i for i, name in enumerate(self.names)},
            angles=rates[0],
            omegas=rates[1] if k > 1 else None,
            epsilons=rates[2] if k > 2 else None,
            link_index={name: i for i, name in enumerate(self.links)},
            link_origins={name: st.links[name].origin for name in self.links},
            slides=self.slides.transpose(2, 0, 1),
            slide_index={name: i for i, name in enumerate(self.slide_names)},
            condition=self.condition.T,
            group_index={name: i for i, name in enumerate(self.groups)},
            valid=valid,
            order=self.order,
        )


SINGULAR_BOUND = 1e-6
"""A position whose velocities' round-off bound (`Kinematics.error_bound`) exceeds this relative
error is refused as singular (``valid`` False): a group there is at, or within about 10⁻⁴ of, a
toggle (change point), where velocities are not determined."""


WELL_CONDITIONED = 1e-2
"""Where every group's condition is at least this, velocities are known far within
`SINGULAR_BOUND` (64·ε·(1 + G·10⁴) < 10⁻⁸ for G < 1000 groups): their bound is not computed."""


def velocity_bound(condition: np.ndarray) -> np.ndarray:
    """(n,) relative round-off bound of velocities from the groups' condition estimates
    (G, n): 64·ε·(1 + Σ c⁻²); groups that do not close (NaN) are left out."""
    c = np.where(np.isfinite(condition), condition, np.inf)
    with np.errstate(divide="ignore"):
        return 64 * np.finfo(float).eps * (1.0 + np.sum(np.abs(c) ** -2.0, axis=0))


def transfer_functions(kin: Kinematics) -> dict[str, np.ndarray]:
    """Velocity analogues: ``"V_<point>"`` → |V|/ω1 (m) and ``"w_<link>"`` → ω/ω1 (signed)."""
    if np.any(kin.omega1 == 0):
        raise MechanismError("transfer functions need a crank speed omega1 ≠ 0")
    out = {f"V_{k}": np.hypot(*kin.velocities[:, i].T) / np.abs(kin.omega1) for k, i in kin.point_index.items()}
    out.update({f"w_{k}": kin.omegas[:, i] / kin.omega1 for k, i in kin.link_index.items()})
    return out


