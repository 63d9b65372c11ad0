"""The analytic solver's result: `Kinematics` (positions, velocities and accelerations over an
array of crank angles), the mechanism's length scales, and the round-off bound that refuses
singular positions. Both engines (`velplan.analysis.blocks`, `velplan.analysis.compiled`)
fill it; `velplan.analysis.solver.solve` is the entry point.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import Literal, Mapping

import numpy as np

from velplan.errors import MechanismError
from velplan.mechanism.model import Group, Mechanism
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


def group_lengths(g: Group) -> tuple[float, ...]:
    """The lengths a group gives (m): rods, and a triad's base-link sides."""
    return g.given_lengths()


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
