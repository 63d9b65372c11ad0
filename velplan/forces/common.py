"""Shared helpers of the force analysis: complex-encoded vectors, the material points of each
link and the motion of a link at any point.

Vectors are complex numbers z = x + i·y (N, m, m/s, …), as in `velplan.analysis.groups`;
angles are counter-clockwise positive and the y axis points up (gravity acts along −y).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.errors import MechanismError
from velplan.mechanism.model import GROUND, Mechanism
from velplan.mechanism.structure import material_points, pairs, point_owners


def cross(a, b):
    """z-component of the cross product a × b of complex-encoded vectors."""
    return np.real(a) * np.imag(b) - np.imag(a) * np.real(b)


def dot(a, b):
    """Scalar product a · b of complex-encoded vectors."""
    return np.real(a) * np.real(b) + np.imag(a) * np.imag(b)


def as_complex(xy) -> np.ndarray:
    """``(..., 2)`` array or complex array → complex array."""
    a = np.asarray(xy)
    if np.iscomplexobj(a):
        return a
    return a[..., 0] + 1j * a[..., 1]


def point(kin: Kinematics, name: str) -> np.ndarray:
    """(n,) complex position of point ``name``, m."""
    return as_complex(kin.position(name))


def link_motion(kin: Kinematics, link: str, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and acceleration (complex, m/s and m/s²) of the material point of ``link``
    that is at ``at`` (complex, m) now.

    Notes
    -----
    V_X = V_O + i·ω·(X − O),   a_X = a_O + (i·ε − ω²)·(X − O), with O the link's frame origin.
    """
    if link == GROUND:
        z = np.zeros_like(at, dtype=complex)
        return z, z
    origin = kin.link_origins[link]
    o = point(kin, origin)
    r = at - o
    w, e = kin.omega(link), kin.epsilon(link)
    return as_complex(kin.velocity(origin)) + 1j * w * r, as_complex(kin.acceleration(origin)) + (1j * e - w * w) * r


def check_point_of_link(mech: Mechanism, link: str, name: str, where: str) -> None:
    """Raise `MechanismError` unless ``name`` is a material point of moving link ``link``."""
    if link == GROUND:
        raise MechanismError(f"{where}: link {GROUND!r} is the frame; a force on it does no work and needs no balancing")
    mp = material_points(mech)
    if link not in mp:
        raise MechanismError(f"{where}: unknown link {link!r}; known links: {', '.join(mech.links)}")
    if name not in point_owners(mech):
        raise MechanismError(f"{where}: unknown point {name!r}; known points: {', '.join(point_owners(mech))}")
    if name not in mp[link]:
        raise MechanismError(
            f"{where}: point {name!r} is not a point of link {link!r}; points of link {link}: {', '.join(mp[link])}"
        )


@lru_cache(maxsize=None)
def _rotation_classes_of(groups: tuple) -> tuple[tuple[str, str], ...]:
    edges = []
    for g in groups:  # a slider turns with its guide's link
        edges += [(slider, guide_link) for slider, guide_link, _ in g.slides()]
    return tuple(edges)


def rotation_class(mech: Mechanism, link: str) -> tuple[str, ...]:
    """Links that turn with ``link`` (a slider turns with its guide's link), ``link`` first;
    the frame ``"0"`` is among them when the link only translates."""
    edges = _rotation_classes_of(mech.groups)
    members = {link}
    changed = True
    while changed:
        changed = False
        for a, b in edges:
            if (a in members) != (b in members):
                members |= {a, b}
                changed = True
    return (link, *sorted(members - {link}))


def slider_pairs(mech: Mechanism):
    """Prismatic pairs of ``mech`` (`Pair` values with kind "P")."""
    return tuple(p for p in pairs(mech) if p.kind == "P")


def guide_frame_link(mech: Mechanism, link: str) -> str | None:
    """The link whose frame's reference direction is the guide ``link`` slides on or carries
    (the slider of a prismatic pair ``link`` belongs to), or None."""
    ps = slider_pairs(mech)
    for p in ps:
        if p.links[0] == link:
            return link
    for p in ps:
        if p.links[1] == link:
            return p.links[0]
    return None
