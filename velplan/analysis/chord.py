"""Kinematic diagrams and their graphical differentiation by the chord method (seed 003).

The displacement diagram s(φ) of the output is drawn at the scales μs (m/mm) and μφ
(rad/mm). A chord of the s-curve between two neighbouring positions, carried through a pole
P that lies H mm to the left of the origin of the velocity diagram, cuts the ordinate axis
at the height ``y_v = H·Δy_s/Δx`` (mm): the mean slope of the interval, written at the
middle of the interval (the half-step shift). The velocity diagram so drawn has the scale

    μv = μs / (μφ · H)    (m/mm per ω1: the velocity analogue ds/dφ)

and the acceleration diagram is obtained from it the same way, μa = μv / (μφ · H_a),
shifted back by half a step onto the positions. Nothing here draws; everything is numpy.

Examples
--------
>>> import numpy as np
>>> phi = np.arange(12) * (2 * np.pi / 12)
>>> mid, slope = chord_method(np.sin(phi), 2 * np.pi / 12)
>>> float(np.round(mid[0], 4)), float(np.round(slope[0], 4))
(0.2618, 0.9549)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.errors import MechanismError

def chord_method(y, step: float, *, closed: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Slopes of the chords of a curve sampled at equal steps, placed at mid-intervals.

    Parameters
    ----------
    y : array_like of shape (n,)
        Ordinates at x = 0, step, 2·step, …
    step : float
        Abscissa step (rad for a diagram against crank angle).
    closed : bool
        The samples cover one period (position n+1 is position 1): n chords, the last
        one from the last sample back to the first. Otherwise n − 1 chords.

    Returns
    -------
    x_mid : ndarray
        Abscissae of the chord slopes, (i + ½)·step: the half-step shift.
    slope : ndarray
        Δy / step of each chord, units of y per unit of x.

    Notes
    -----
    For y = sin x the chord slope is cos(x_mid)·sin(h/2)/(h/2), h = step, so the relative
    error of the graphical derivative is 1 − sinc(h/2) ≈ h²/24.
    """
    y = np.asarray(y, dtype=float)
    if y.ndim != 1 or y.size < 2:
        raise ValueError(f"chord_method needs a 1-D array of at least 2 ordinates, got shape {y.shape}")
    if not (math.isfinite(step) and step > 0):
        raise ValueError(f"chord_method needs a positive step, got {step!r}")
    nxt = np.roll(y, -1) if closed else y[1:]
    cur = y if closed else y[:-1]
    slope = (nxt - cur) / step
    x_mid = (np.arange(slope.size) + 0.5) * step
    return x_mid, slope


def chord_ordinates_mm(y_mm, dx_mm: float, H_mm: float, *, closed: bool = True) -> np.ndarray:
    """Heights (mm) where the chords carried through the pole cut the ordinate axis.

    ``y_v = H · Δy / Δx`` for each chord of the curve drawn in mm; multiplied by
    μv = μs/(μφ·H) they give the slopes in physical units.
    """
    _, slope = chord_method(y_mm, dx_mm, closed=closed)
    return H_mm * slope


@dataclass(frozen=True)
class Diagrams:
    """Displacement, velocity and acceleration analogues of the output over one crank turn.

    Angles φ count from position 1 in the sense of ω1, rad. The velocity and acceleration
    are analogues: ds/dφ and d²s/dφ² (m, or rad and dimensionless for a rocker); multiply
    by ω1 and ω1² for m/s and m/s² at a constant crank speed.

    Attributes
    ----------
    quantity : str
        ``"point F"`` (displacement along its guide) or ``"link 3"`` (angle of the link).
    angular : bool
        True for a link angle (rad), False for a displacement (m).
    n : int
        Number of positions the chord method uses.
    phi, s : ndarray, shape (n,)
        Crank rotation at the positions and the output's displacement from position 1.
    phi_mid, v_chord : ndarray, shape (n,)
        Chord-method velocity analogue at the mid-intervals (half-step shift).
    a_chord : ndarray, shape (n,)
        Chord-method acceleration analogue (chords of the velocity curve), at the positions.
    phi_fine, s_exact, v_exact, a_exact : ndarray, shape (m,)
        The analytic curves on a fine grid over [0, 2π].
    v_exact_mid, a_exact_nodes : ndarray, shape (n,)
        The analytic analogues where the graphical values are written.
    error_v, error_a : float
        Largest deviation of the graphical curve from the analytic one, as a fraction of
        the largest analytic value.
    """

    quantity: str
    angular: bool
    n: int
    phi: np.ndarray
    s: np.ndarray
    phi_mid: np.ndarray
    v_chord: np.ndarray
    a_chord: np.ndarray
    phi_fine: np.ndarray
    s_exact: np.ndarray
    v_exact: np.ndarray
    a_exact: np.ndarray
    v_exact_mid: np.ndarray
    a_exact_nodes: np.ndarray
    error_v: float
    error_a: float

    @property
    def step(self) -> float:
        """Crank rotation between neighbouring positions, rad."""
        return 2 * math.pi / self.n


def differentiate(s, *, step: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chord-method velocity and acceleration of a periodic sample s over one turn.

    Returns ``(phi_mid, v, a)``: v at the mid-intervals, a (chords of v) back at the nodes.
    """
    s = np.asarray(s, dtype=float)
    h = 2 * math.pi / s.size if step is None else step
    phi_mid, v = chord_method(s, h)
    # chords of v between mid-intervals i-1 and i belong to node i: shift back by half a step
    _, a_shifted = chord_method(v, h)
    a = np.roll(a_shifted, 1)
    return phi_mid, v, a


def relative_error(graph, exact, reference) -> float:
    """max |graph − exact| / max |reference| (0 when the reference is identically 0)."""
    scale = float(np.max(np.abs(reference)))
    if scale == 0.0:
        return 0.0
    return float(np.max(np.abs(np.asarray(graph) - np.asarray(exact))) / scale)


def closed_form_diagrams(s, ds, dds, n: int, *, fine: int = 361, quantity: str = "s",
                         angular: bool = False) -> Diagrams:
    """Diagrams of a closed-form output: `s`, `ds`, `dds` are callables of φ (rad).

    Used to test the chord method against a known answer (``s = sin φ``).
    """
    phi = np.arange(n) * (2 * math.pi / n)
    fine_phi = np.linspace(0.0, 2 * math.pi, fine)
    return _assemble(quantity, angular, phi, np.asarray(s(phi), float), fine_phi,
                     np.asarray(s(fine_phi), float), np.asarray(ds(fine_phi), float),
                     np.asarray(dds(fine_phi), float), ds, dds)


def _assemble(quantity, angular, phi, s_nodes, fine_phi, s_fine, v_fine, a_fine,
              v_at, a_at) -> Diagrams:
    n = phi.size
    phi_mid, v, a = differentiate(s_nodes)
    v_mid = np.asarray(v_at(phi_mid), float)
    a_nodes = np.asarray(a_at(phi), float)
    return Diagrams(
        quantity=quantity, angular=angular, n=n, phi=phi, s=s_nodes, phi_mid=phi_mid,
        v_chord=v, a_chord=a, phi_fine=fine_phi, s_exact=s_fine, v_exact=v_fine,
        a_exact=a_fine, v_exact_mid=v_mid, a_exact_nodes=a_nodes,
        error_v=relative_error(v, v_mid, v_fine), error_a=relative_error(a, a_nodes, a_fine))


def kinematic_diagrams(mech, nodes: Kinematics | int = 12, *, turn: Kinematics | None = None,
                       sense: float | None = None, fine: int = 361,
                       start: float | None = None) -> Diagrams:
    """Diagrams of the mechanism's output (``output`` in its TOML) over one crank turn.

    Parameters
    ----------
    mech : Mechanism
        Needs an ``output``: a slider point (displacement along its guide, m) or a link
        (its angle, rad).
    nodes : Kinematics or int
        The mechanism solved at unit speed (ω1 = 1 rad/s, ε1 = 0) at the n positions the chord
        method works from (12 on a course sheet), from position 1 in the sense of rotation; or
        n, to solve them here.
    turn : Kinematics, optional
        The same at unit speed over a whole turn from position 1 (the analytic curves);
        ``fine`` samples solved here when omitted.
    sense : float, optional
        +1 (counter-clockwise) or −1; the crank's when omitted.
    start : float, optional
        Crank angle of position 1, rad (used only when ``nodes`` is a number;
        `velplan.reference_angle` when omitted).

    Raises
    ------
    MechanismError
        If the mechanism names no output.
    """
    from velplan.analysis.extremes import output_quantity, reference_angle
    from velplan.analysis.solver import solve

    sense = mech.crank.sense if sense is None else float(sense)
    if isinstance(nodes, (int, np.integer)):
        n = int(nodes)
        if n < 3:
            raise MechanismError(f"the chord method needs at least 3 positions, not {n}")
        phi0 = reference_angle(mech) if start is None else float(start)
        nodes = solve(mech, phi0 + sense * np.arange(n) * (2 * math.pi / n), omega1=1.0, epsilon1=0.0)
    n = len(nodes)
    if n < 3:
        raise MechanismError(f"the chord method needs at least 3 positions, not {n}")
    q = output_quantity(mech, nodes)
    if q is None:
        raise MechanismError(f"mechanism {mech.name!r} names no output; add output = \"POINT\" "
                             "or output = {link = \"…\"} to draw its kinematic diagrams")
    label, kind, index = q
    phi0 = float(nodes.phi[0])
    if turn is None:
        turn = solve(mech, phi0 + sense * np.linspace(0.0, 2 * math.pi, fine), omega1=1.0, epsilon1=0.0)
    phi = np.arange(n) * (2 * math.pi / n)
    fine_phi = sense * (turn.phi - phi0)

    def values(kin):
        # d/d(rotation) in the sense of the crank: first analogues × sense, second unchanged
        if kind == "link":
            return (np.unwrap(kin.angles[:, index]), sense * kin.omegas[:, index],
                    kin.epsilons[:, index])
        return kin.slides[:, index, 0], sense * kin.slides[:, index, 1], kin.slides[:, index, 2]

    def at(rot):
        return values(solve(mech, phi0 + sense * np.asarray(rot, float), omega1=1.0, epsilon1=0.0))

    s_nodes, _, a_nodes = values(nodes)
    s_fine, v_fine, a_fine = values(turn)
    start = s_nodes[0]
    # unwrap consistently: a rocker's angle may jump by 2π between the two samplings
    if kind == "link":
        s_nodes = s_nodes - 2 * math.pi * np.round((s_nodes - start) / (2 * math.pi))
        s_fine = s_fine - 2 * math.pi * np.round((s_fine - start) / (2 * math.pi))
    # displacement from position 1, positive along the working stroke
    swing = s_fine - start
    sign = -1.0 if abs(swing.min()) > abs(swing.max()) else 1.0
    return _assemble(
        label, kind == "link", phi, sign * (s_nodes - start), fine_phi, sign * swing,
        sign * v_fine, sign * a_fine,
        lambda x: sign * at(x)[1], lambda x: sign * a_nodes if np.array_equal(x, phi) else sign * at(x)[2])
