"""A safeguarded Newton iteration: the roots of many functions at once, each in its bracket.

>>> import numpy as np
>>> def f(x):                                   # x² − a, roots √a
...     return x * x - np.array([2.0, 9.0]), 2 * x
>>> lo, hi = np.array([1.0, 0.0]), np.array([2.0, 4.0])
>>> np.allclose(newton_bisection(f, lo, hi, f(lo)[0], 0.5 * (lo + hi)), [2 ** 0.5, 3.0], rtol=1e-15)
True
"""

from __future__ import annotations

from typing import Callable

import numpy as np

Function = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]
"""x ↦ (f(x), f′(x)), elementwise over an array of abscissae."""


def newton_bisection(f: Function, lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray, x: np.ndarray, *,
                     ulps: float = 8, closed: bool = True, iterations: int = 100) -> np.ndarray:
    """Roots of ``f`` in the brackets [lo, hi] (f changes sign over each), to a few ulp.

    Newton's steps from ``x`` (inside the brackets), a bisection where a step would leave the
    bracket; the bracket shrinks to the side whose sign differs from ``f_lo`` (f at ``lo``).

    Parameters
    ----------
    f : callable
        x ↦ (f(x), f′(x)), elementwise.
    lo, hi, f_lo, x : ndarray
        The brackets, f at their lower ends (only its sign is read), the first guesses.
    ulps : float
        Stop when every step, or every bracket, is within ``ulps`` units in the last place of
        max(|x|, 1), or f(x) = 0.
    closed : bool
        Accept a Newton step that lands on an end of its bracket (else bisect).
    iterations : int
        At most this many evaluations of ``f``.
    """
    eps = np.finfo(float).eps
    for _ in range(iterations):
        fx, dfx = f(x)
        same = np.sign(fx) == np.sign(f_lo)
        lo, hi = np.where(same, x, lo), np.where(same, hi, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = x - fx / dfx
        inside = ((step >= lo) & (step <= hi)) if closed else ((step > lo) & (step < hi))
        x_new = np.where(fx == 0, x, np.where(inside & np.isfinite(step), step, 0.5 * (lo + hi)))
        tol = ulps * eps * np.maximum(np.abs(x_new), 1.0)
        done = (np.abs(x_new - x) <= tol) | (fx == 0) | (hi - lo <= tol)
        x = x_new
        if done.all():
            break
    return x
