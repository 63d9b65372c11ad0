"""Zhukovsky's lever: the velocity plan turned by 90° as a rigid lever about its pole.

The lever works from a narrow input — the velocity images of named points (mm from the pole
on the plan, complex or (x, y)) with the plan's scale μv ((m/s)/mm), and the positions of
points (m) for the directions of the crank and of couples — so that it can take the images of
a drawn plan as well as exact ones (`images_from_kinematics`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from velplan.analysis.numbering import position_index
from velplan.analysis.solver import Kinematics
from velplan.errors import VelplanError
from velplan.forces.actions import Actions
from velplan.forces.common import as_complex, cross, material_points, rotation_class
from velplan.mechanism.model import GROUND, Mechanism


def images_from_kinematics(kin: Kinematics, position: int | None, mu_v: float) -> dict[str, complex | np.ndarray]:
    """Velocity images of every point, mm from the pole: V/μv.

    Parameters
    ----------
    kin : Kinematics
    position : int or None
        Position number 1…n of ``kin``; None gives (n,) arrays over all positions.
    mu_v : float
        Scale of the plan, (m/s)/mm.

    >>> import velplan
    >>> kin = velplan.solve(velplan.load("four-bar"), [0.0, 1.0], omega1=10.0)
    >>> images_from_kinematics(kin, 2, 0.01)["B"] == complex(*kin.velocity("B")[1]) / 0.01
    True
    >>> images_from_kinematics(kin, 0, 0.01)
    Traceback (most recent call last):
    ...
    velplan.errors.VelplanError: position 0 is outside 1…2 (positions are numbered from 1)
    """
    if not mu_v > 0:
        raise VelplanError(f"velocity scale μv must be > 0 (m/s)/mm, not {mu_v}")
    i = None if position is None else position_index(position, len(kin))
    z = as_complex(kin.velocities) / mu_v
    return {k: (z[:, j] if i is None else complex(z[i, j])) for k, j in kin.point_index.items()}


def images_from_plan(res, position: int | None = None) -> dict[str, complex | np.ndarray]:
    """Velocity images of every point as constructed on a velocity plan (`velplan.plans.PlanResult`),
    mm from the pole — exact or drafted, as the plan was built — at its ``position``-th position
    (1…; None: (n,) arrays)."""
    if res.kind != "velocity":
        raise VelplanError(f"Zhukovsky's lever is the velocity plan turned by 90°, not the {res.kind} plan")
    i = None if position is None else position_index(position, len(res.index))
    z = {k: v[:, 0] + 1j * v[:, 1] for k, v in res.images.items() if k in res.plan.images["v"]}
    return {k: (v if i is None else complex(v[i])) for k, v in z.items()}


def positions_from_kinematics(kin: Kinematics, position: int | None) -> dict[str, complex | np.ndarray]:
    """Positions of every point (complex, m) at position number ``position`` (1…n of ``kin``;
    None: (n,) arrays).

    >>> import velplan
    >>> kin = velplan.solve(velplan.load("four-bar"), [0.0, 1.0])
    >>> positions_from_kinematics(kin, 1)["A"] == complex(*kin.position("A")[0])
    True
    """
    i = None if position is None else position_index(position, len(kin))
    z = as_complex(kin.positions)
    return {k: (z[:, j] if i is None else complex(z[i, j])) for k, j in kin.point_index.items()}


@dataclass(frozen=True)
class LeverForce:
    """A force carried to the lever: ``image`` is the point's image turned by 90° (mm) and
    ``moment`` its moment about the pole, N·mm (counter-clockwise positive)."""

    label: str
    point: str
    vector: np.ndarray
    image: np.ndarray
    moment: np.ndarray


@dataclass(frozen=True)
class Lever:
    """Result of `zhukovsky_lever`.

    Attributes
    ----------
    forces : tuple of LeverForce
        Every force on the lever, the couples' pairs of forces included.
    balancing_force : ndarray
        F_b at the crank tip, perpendicular to the crank, N, signed along i·(A − O)/l_OA
        (positive: pushing the crank counter-clockwise).
    balancing_moment : ndarray
        M_b = F_b·l_OA, N·m.
    tip_image : ndarray
        The crank tip's image turned by 90°, mm.
    direction : ndarray
        The unit vector i·(A − O)/l_OA (complex) along which ``balancing_force`` is signed.
    scale : float
        μv of the plan the images are on, (m/s)/mm.
    """

    forces: tuple[LeverForce, ...]
    balancing_force: np.ndarray
    balancing_moment: np.ndarray
    tip_image: np.ndarray
    direction: np.ndarray
    scale: float

    def at_scale(self, mu_v: float) -> "Lever":
        """This lever on the plan drawn at ``mu_v`` ((m/s)/mm): the images and the moments
        about the pole (N·mm) scaled by μv_old/μv; the forces, F_b and M_b are unchanged."""
        if not mu_v > 0:
            raise VelplanError(f"velocity scale μv must be > 0 (m/s)/mm, not {mu_v}")
        if mu_v == self.scale:
            return self
        r = self.scale / mu_v
        forces = tuple(replace(f, image=f.image * r, moment=f.moment * r) for f in self.forces)
        return replace(self, forces=forces, tip_image=self.tip_image * r, scale=mu_v)


def _get(m: Mapping, name: str, what: str, needed: str):
    try:
        return as_complex(np.asarray(m[name]))
    except KeyError:
        raise VelplanError(f"{what} has no point {name!r} (needed for {needed})") from None


def _couple_points(mech: Mechanism, link: str, positions: Mapping, images: Mapping) -> tuple[str, str] | None:
    """Two points of ``link``, or of a link turning with it, with images: the farthest apart (a
    triad's special point is left out: it runs to infinity where two lead lines turn parallel)."""
    mp = material_points(mech)
    special = {p for g in mech.groups for p in g.special_points()}
    for member in rotation_class(mech, link):
        if member == GROUND:
            continue
        names = [p for p in mp.get(member, ()) if p in images and p in positions and p not in special]
        best, dist = None, 0.0
        for i, p in enumerate(names):
            for q in names[i + 1:]:
                d = float(np.nanmean(np.abs(as_complex(np.asarray(positions[q])) - as_complex(np.asarray(positions[p])))))
                if d > dist:
                    best, dist = (p, q), d
        if best is not None:
            return best
    return None


def zhukovsky_lever(mech: Mechanism, positions: Mapping, images: Mapping, mu_v: float, actions: Actions) -> Lever:
    """Balancing force and moment from the moment balance of the turned velocity plan.

    Parameters
    ----------
    mech : Mechanism
    positions : Mapping[str, complex or (x, y)]
        Point positions, m (scalars or (n,) arrays).
    images : Mapping[str, complex or (x, y)]
        Velocity images, mm from the pole (scalars or (n,) arrays).
    mu_v : float
        Scale of the plan, (m/s)/mm.
    actions : Actions
        Forces and moments, at the same positions.

    Returns
    -------
    Lever

    Notes
    -----
    Turned by +90°, the image of a point is i·v with v = V/μv, and the moment of F about the
    pole is (i·v) × F = −F·V/μv: the lever balances exactly when the powers do. A couple M on a
    link becomes ±F = ±i·M·(Q − P)/|Q − P|² at the images of two points P, Q of the link (or of a
    link turning with it: a slider block turns with its guide), whose moment is −M·ω/μv; a link
    that only translates carries no couple to the lever. The balancing force F_b ⊥ OA at the
    crank tip's image gives Σ M_pole = 0, and M_b = F_b·l_OA.
    """
    if not mu_v > 0:
        raise VelplanError(f"velocity scale μv must be > 0 (m/s)/mm, not {mu_v}")
    out: list[LeverForce] = []
    for f in actions.forces:
        img = 1j * _get(images, f.point, "the velocity plan", f"force {f.label!r}")
        out.append(LeverForce(f.label, f.point, f.vector, img, cross(img, f.vector)))
    for m in actions.moments:
        pq = _couple_points(mech, m.link, positions, images)
        if pq is None:
            if GROUND in rotation_class(mech, m.link):
                continue  # the link only translates: ω = 0, the couple does no work
            raise VelplanError(f"moment {m.label!r} on link {m.link!r}: the plan has no two points of that link "
                               "to carry the couple")
        p, q = pq
        zp, zq = _get(positions, p, "positions", m.label), _get(positions, q, "positions", m.label)
        ip, iq = 1j * _get(images, p, "the velocity plan", m.label), 1j * _get(images, q, "the velocity plan", m.label)
        d = zq - zp
        with np.errstate(divide="ignore", invalid="ignore"):
            force = 1j * m.moment * d / np.abs(d) ** 2
        out.append(LeverForce(f"{m.label}@{q}", q, force, iq, cross(iq, force)))
        out.append(LeverForce(f"{m.label}@{p}", p, -force, ip, cross(ip, -force)))
    c = mech.crank
    o = _get(positions, c.pivot, "positions", "the crank")
    a = _get(positions, c.tip, "positions", "the crank")
    tip = 1j * _get(images, c.tip, "the velocity plan", "the balancing force")
    l = np.abs(a - o)
    total = sum((f.moment for f in out), np.zeros(np.broadcast(tip, a).shape))
    with np.errstate(divide="ignore", invalid="ignore"):
        e = 1j * (a - o) / l
        fb = -total / cross(tip, e)
    return Lever(tuple(out), fb, fb * l, tip, e, float(mu_v))


def lever_balancing_moment(mech: Mechanism, kin: Kinematics, actions: Actions, mu_v: float = 1.0) -> np.ndarray:
    """M_b (N·m) by the lever with exact images (V/μv) at every position of ``kin``."""
    return zhukovsky_lever(mech, positions_from_kinematics(kin, None), images_from_kinematics(kin, None, mu_v),
                           mu_v, actions).balancing_moment
