"""Truncated Fourier series of a 2π-periodic load given as a quadratic on one interval of
crank angle and zero elsewhere (the press load of seed 004), with exact coefficients and the
approximation error.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class FourierSeries:
    """P_N(φ) = a0/2 + Σ_{k=1..N} (a_k·cos kφ + b_k·sin kφ), φ in rad, P in N.

    Attributes
    ----------
    c : ndarray, shape (N + 1,), complex
        Complex coefficients c_k = (1/2π)·∫ P(φ)·e^{−ikφ} dφ over one period, k = 0…N;
        a_k = 2·Re c_k, b_k = −2·Im c_k, a0 = 2·c_0.
    mean_square : float
        (1/2π)·∫ P² dφ of the exact load, N², for the RMS error by Parseval.
    """

    c: np.ndarray
    mean_square: float

    @property
    def harmonics(self) -> int:
        """Number of harmonics N."""
        return self.c.shape[0] - 1

    @property
    def a(self) -> np.ndarray:
        """a_0 … a_N, N (a_0 is twice the mean)."""
        return 2.0 * self.c.real

    @property
    def b(self) -> np.ndarray:
        """b_0 … b_N, N (b_0 = 0)."""
        return -2.0 * self.c.imag

    def __call__(self, phi) -> np.ndarray:
        """Value of the truncated series at crank angles ``phi`` (rad), N."""
        phi = np.asarray(phi, dtype=float)
        k = np.arange(1, self.c.shape[0])
        e = np.exp(1j * np.multiply.outer(phi, k))
        return self.c[0].real + 2.0 * (e @ self.c[1:]).real if k.size else np.full(phi.shape, self.c[0].real)

    def rms_error(self) -> float:
        """RMS of P − P_N over a revolution, N, by Parseval:
        √( (1/2π)∫P² − c_0² − 2·Σ_{k=1..N} |c_k|² )."""
        rest = self.mean_square - abs(self.c[0]) ** 2 - 2.0 * np.sum(np.abs(self.c[1:]) ** 2)
        return float(np.sqrt(max(rest, 0.0)))


def quadratic_coefficients(q: np.ndarray, lo: float, hi: float, harmonics: int) -> np.ndarray:
    """c_k = (1/2π)·∫_lo^hi q(φ)·e^{−ikφ} dφ, k = 0…N, for the quadratic q(φ) = q0 + q1·φ + q2·φ².

    Notes
    -----
    With s = −ik ≠ 0, ∫ q·e^{sφ} dφ = e^{sφ}·(q/s − q′/s² + q″/s³) (three integrations by parts).
    """
    q0, q1, q2 = (float(x) for x in q)
    out = np.empty(harmonics + 1, dtype=complex)

    def poly(x):
        return q0 + q1 * x + q2 * x * x

    def dpoly(x):
        return q1 + 2 * q2 * x

    out[0] = (q0 * (hi - lo) + q1 * (hi**2 - lo**2) / 2 + q2 * (hi**3 - lo**3) / 3) / (2 * np.pi)
    k = np.arange(1, harmonics + 1)
    s = -1j * k

    def prim(x):
        return np.exp(s * x) * (poly(x) / s - dpoly(x) / s**2 + 2 * q2 / s**3)

    out[1:] = (prim(hi) - prim(lo)) / (2 * np.pi)
    return out
