"""The safeguarded Newton iteration against closed-form roots, bracket edges included."""

import numpy as np
import pytest

from velplan.analysis.roots import newton_bisection

EPS = np.finfo(float).eps


def _counted(f):
    calls = []

    def g(x):
        calls.append(np.array(x))
        return f(x)

    return g, calls


@pytest.mark.parametrize("closed", [True, False])
@pytest.mark.parametrize("ulps", [4, 8])
def test_square_roots_in_their_brackets(closed, ulps):
    a = np.array([2.0, 9.0, 1e-6, 1e6, 0.5])
    lo, hi = np.sqrt(a) * 0.3, np.sqrt(a) * 2.5
    f, _ = _counted(lambda x: (x * x - a, 2 * x))
    x = newton_bisection(f, lo, hi, lo * lo - a, 0.5 * (lo + hi), ulps=ulps, closed=closed)
    assert np.allclose(x, np.sqrt(a), rtol=1e-14, atol=0)


def test_a_step_that_leaves_the_bracket_bisects():
    """arctan from far out: Newton's step overshoots to the other side; the bracket holds."""
    f, calls = _counted(lambda x: (np.arctan(x), 1 / (1 + x * x)))
    lo, hi = np.array([-1.0]), np.array([10.0])
    x = newton_bisection(f, lo, hi, np.arctan(lo), np.array([5.0]))
    assert abs(x[0]) <= 1e-15
    assert all(-1.0 <= c[0] <= 10.0 for c in calls)


def test_a_flat_derivative_bisects():
    """x³ − 8 from x = 0, where f′ = 0: the first step is a bisection, then the root 2."""
    f, calls = _counted(lambda x: (x ** 3 - 8, 3 * x * x))
    x = newton_bisection(f, np.array([0.0]), np.array([3.0]), np.array([-8.0]), np.array([0.0]))
    assert calls[1][0] == 1.5
    assert abs(x[0] - 2.0) <= 4 * EPS * 2


def test_a_root_on_the_bracket_end():
    """x − 1 on [1, 2] (f = 0 at lo): a closed bracket takes Newton's step onto the end and
    stops there; an open one bisects toward it, within the tolerance."""
    lo, hi, f_lo, x0 = np.array([1.0]), np.array([2.0]), np.array([0.0]), np.array([1.5])
    f, calls = _counted(lambda x: (x - 1.0, np.ones_like(x)))
    assert newton_bisection(f, lo, hi, f_lo, x0, closed=True)[0] == 1.0
    assert len(calls) == 2
    f, calls = _counted(lambda x: (x - 1.0, np.ones_like(x)))
    x = newton_bisection(f, lo, hi, f_lo, x0, ulps=4, closed=False)
    assert 1.0 <= x[0] <= 1.0 + 2 * 4 * EPS
    assert len(calls) > 40


def test_many_functions_converge_together():
    """Each bracket shrinks on its own; one slow root does not move the converged ones."""
    k = np.arange(1, 7, dtype=float)
    f = lambda x: (np.sin(x) - 0.5, np.cos(x))       # noqa: E731
    lo, hi = np.full(6, 0.0), np.full(6, 1.0)
    x0 = lo + k * 0.14
    x = newton_bisection(f, lo, hi, np.sin(lo) - 0.5, x0)
    assert np.allclose(x, np.pi / 6, rtol=1e-15, atol=0)


def test_iterations_bound_the_evaluations():
    f, calls = _counted(lambda x: (x - 1.0, np.ones_like(x)))
    newton_bisection(f, np.array([1.0]), np.array([2.0]), np.array([0.0]), np.array([1.5]),
                     closed=False, iterations=5)
    assert len(calls) == 5
