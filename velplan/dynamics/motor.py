"""Driving moments: constant, an asynchronous motor by Kloss's formula, or a speed–torque
table, reduced to the crank through a gear ratio u and an efficiency η.

Kloss (continuous form): M = 2·M_K·s·s_K/(s² + s_K²), s = 1 − n/n0, s_K = 1 − n_K/n0; it is
0 at n = n0 and M_K at s = s_K, and negative (a brake) above n0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from velplan.dynamics.spec import MotorSpec

RPM = 30.0 / math.pi
"""rad/s → rev/min."""


def kloss(s, s_k: float, m_k: float):
    """Kloss's torque at slip ``s`` (scalar or array), N·m."""
    s = np.asarray(s, dtype=float)
    return 2.0 * m_k * s * s_k / (s * s + s_k * s_k)


def kloss_from_rating(power_kw: float, nominal_rpm: float, synchronous_rpm: float, overload: float):
    """(M_K N·m, n_K rpm) of a motor from its rating: M_nom = 9550·P/n_nom, M_K = λ·M_nom,
    s_K = s_nom·(λ + √(λ² − 1)) (Kloss's formula through the rated point)."""
    m_nom = 9550.0 * power_kw / nominal_rpm
    s_nom = 1.0 - nominal_rpm / synchronous_rpm
    lam = max(overload, 1.0 + 1e-9)
    s_k = s_nom * (lam + math.sqrt(lam * lam - 1.0))
    return lam * m_nom, synchronous_rpm * (1.0 - s_k)


@dataclass(frozen=True)
class Motor:
    """A driving moment as a function of the crank speed.

    ``found`` is the constant driving moment on the crank (N·m) used by ``kind="constant"``
    without a torque (the one from zero cycle work).
    """

    spec: MotorSpec
    found: float | None = None

    def shaft_torque(self, rpm):
        """Torque on the motor shaft at ``rpm`` (rev/min, of the motor), N·m."""
        sp = self.spec
        rpm = np.asarray(rpm, dtype=float)
        if sp.kind == "kloss":
            n0 = sp.synchronous_rpm
            return kloss(1.0 - rpm / n0, 1.0 - sp.critical_rpm / n0, sp.critical_torque)
        if sp.kind == "table":
            return np.interp(rpm, sp.rpm, sp.torques)
        return np.full_like(rpm, sp.torque if sp.torque is not None else 0.0)

    def moment(self, w):
        """Moment on the crank (N·m, positive when it drives) at crank speed w = |ω| (rad/s):
        u·η·M when the motor drives, u·M/η when it brakes."""
        sp = self.spec
        if sp.kind == "constant" and sp.torque is None:
            return np.full_like(np.asarray(w, dtype=float), self.found or 0.0)
        m = self.shaft_torque(sp.ratio * np.asarray(w, dtype=float) * RPM)
        return np.where(m >= 0, m * sp.ratio * sp.efficiency, m * sp.ratio / sp.efficiency)

    def scalar(self):
        """``moment`` for one speed in plain floats (w rad/s → N·m): what an ODE's right-hand
        side calls."""
        sp = self.spec
        if sp.kind == "constant":
            value = (self.found or 0.0) if sp.torque is None else sp.torque * sp.ratio * (
                sp.efficiency if sp.torque >= 0 else 1.0 / sp.efficiency)
            return lambda w: value
        up, down, k = sp.ratio * sp.efficiency, sp.ratio / sp.efficiency, sp.ratio * RPM
        if sp.kind == "kloss":
            n0, sk, mk = sp.synchronous_rpm, 1.0 - sp.critical_rpm / sp.synchronous_rpm, sp.critical_torque

            def kloss_moment(w):
                s = 1.0 - k * w / n0
                m = 2.0 * mk * s * sk / (s * s + sk * sk)
                return m * up if m >= 0 else m * down

            return kloss_moment
        return lambda w: float(self.moment(w))

    @property
    def depends_on_speed(self) -> bool:
        return self.spec.kind != "constant"

    def speed_for(self, moment: float, w_hint: float) -> float | None:
        """Crank speed w (rad/s) at which the motor gives ``moment`` on the crank on its stable
        branch (between the critical and the synchronous speed), or None."""
        from scipy.optimize import brentq

        sp = self.spec
        if sp.kind == "kloss":
            lo, hi = sp.critical_rpm / sp.ratio / RPM, sp.synchronous_rpm / sp.ratio / RPM
        elif sp.kind == "table":
            lo, hi = sp.rpm[0] / sp.ratio / RPM, sp.rpm[-1] / sp.ratio / RPM
        else:
            return w_hint
        f = lambda w: float(self.moment(w)) - moment  # noqa: E731
        if f(lo) * f(hi) > 0:
            return None
        return brentq(f, lo, hi, xtol=1e-13)
