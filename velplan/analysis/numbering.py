"""Position numbers: the public API numbers positions 1…n, as the sheets and the CLI do
(position 1 is the reference position, `velplan.analysis.extremes.reference_angle`); arrays
index them 0…n−1. `position_index` and `position_number` are the one conversion.

>>> position_index(1, 12), position_index(12, 12), position_number(11)
(0, 11, 12)
>>> position_index(0, 12)
Traceback (most recent call last):
...
velplan.errors.VelplanError: position 0 is outside 1…12 (positions are numbered from 1)
"""

from __future__ import annotations

import numbers

import numpy as np

from velplan.errors import VelplanError


def position_index(number: int, n: int) -> int:
    """The array index (0…n−1) of position ``number`` (1…n); `VelplanError` naming the number
    and n otherwise."""
    if isinstance(number, bool) or not isinstance(number, numbers.Integral):
        raise VelplanError(f"position {number!r} is not a whole number 1…{n}")
    if not 1 <= number <= n:
        raise VelplanError(f"position {number} is outside 1…{n} (positions are numbered from 1)")
    return int(number) - 1


def position_indices(numbers_, n: int) -> np.ndarray:
    """(k,) array indices of the position numbers ``numbers_`` (one or several, 1…n), checked
    as `position_index` checks one, in one pass over an array.

    >>> position_indices([1, 12], 12)
    array([ 0, 11])
    """
    arr = np.atleast_1d(numbers_)
    if arr.size == 0:
        raise VelplanError(f"no positions given: give position numbers 1…{n}")
    if arr.dtype.kind not in "iu":
        for k in arr.tolist():
            position_index(k, n)  # names the first that is not a whole number
        arr = arr.astype(int)
    bad = np.flatnonzero((arr < 1) | (arr > n))
    if bad.size:
        position_index(int(arr[bad[0]]), n)
    return arr.astype(np.intp) - 1


def position_number(index: int) -> int:
    """The position number (1…n) of the array index ``index`` (0…n−1)."""
    return int(index) + 1


def position_numbers(indices) -> np.ndarray:
    """(k,) position numbers of the array indices ``indices`` (0…n−1; one or several, e.g. a
    ``range``), in one pass over an array.

    >>> position_numbers(range(3)), position_numbers(range(10, 12))
    (array([1, 2, 3]), array([11, 12]))
    """
    return np.atleast_1d(np.asarray(indices, dtype=int)) + 1
