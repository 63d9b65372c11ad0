"""The compiled loops of `velplan.cli.numfmt` (imported only when numba is installed)."""

from __future__ import annotations

import math

import numba
import numpy as np

P = 12
_POW = 10.0 ** np.arange(23)


@numba.njit(cache=True, inline="always")
def _scaled(ax, k):
    """ax·10^k in at most two roundings (|k| ≤ 44)."""
    y = ax
    for _ in range(2):
        step = min(max(k, -22), 22)
        y = y * _POW[step] if step >= 0 else y / _POW[-step]
        k -= step
    return y


@numba.njit(cache=True)
def mantissa(x):
    """Per number: the 12-digit mantissa m (10¹¹ ≤ m < 10¹²) and exponent X of '%.12g', and
    its kind: 0 a number, 1 zero, 2 NaN or infinite, 3 too near a rounding tie to trust."""
    n = x.shape[0]
    m = np.zeros(n, dtype=np.int64)
    X = np.zeros(n, dtype=np.int64)
    kind = np.zeros(n, dtype=np.int8)
    lo, hi = 10 ** (P - 1), 10 ** P
    for i in range(n):
        v = x[i]
        if not math.isfinite(v):
            kind[i] = 2
            continue
        if v == 0.0:
            kind[i] = 1
            continue
        ax = abs(v)
        e = int(math.floor(math.log10(ax)))
        ok = False
        for _ in range(3):  # log10 may be one off near a power of ten; rounding may carry
            k = P - 1 - e
            if k > 44 or k < -44:
                break
            y = _scaled(ax, k)
            f = y - math.floor(y)
            if abs(f - 0.5) < 1e-3 or not math.isfinite(y):
                break
            r = int(math.floor(y + 0.5))
            if r >= hi:
                e += 1
            elif r < lo:
                e -= 1
            else:
                m[i], X[i], ok = r, e, True
                break
        if not ok:
            kind[i] = 3
    return m, X, kind


@numba.njit(cache=True)
def _put(out, pos, src, a, b):
    for j in range(a, b):
        out[pos] = src[j]
        pos += 1
    return pos


@numba.njit(cache=True)
def write(m, X, kind, neg, R, C, lit, offs, na, bools, out):
    """Write the rows into ``out``; returns the number of bytes written. A column with
    ``bools[c]`` writes ``true`` (a non-zero number) or ``false`` (zero)."""
    pos = 0
    d = np.empty(P, dtype=np.uint8)
    tf = np.frombuffer(b"truefalse", dtype=np.uint8)
    for r in range(R):
        for c in range(C):
            pos = _put(out, pos, lit, offs[c], offs[c + 1])
            i = r * C + c
            if bools[c]:
                pos = _put(out, pos, tf, 4, 9) if kind[i] == 1 else _put(out, pos, tf, 0, 4)
                continue
            if kind[i] == 2:
                pos = _put(out, pos, na, 0, na.shape[0])
                continue
            if neg[i]:
                out[pos] = 45  # '-'
                pos += 1
            if kind[i] == 1:
                out[pos] = 48
                pos += 1
                continue
            q = np.uint64(m[i])  # unsigned: division by 10 compiles to a multiply
            nd = P
            tail = True
            for j in range(P - 1, -1, -1):
                q10 = q // np.uint64(10)
                dig = q - q10 * np.uint64(10)
                q = q10
                d[j] = np.uint8(48 + dig)
                if tail and dig == 0:
                    nd -= 1
                else:
                    tail = False
            e = X[i]
            if -4 <= e < P:
                if e >= 0:
                    for j in range(max(nd, e + 1)):
                        if j == e + 1:
                            out[pos] = 46
                            pos += 1
                        out[pos] = d[j]
                        pos += 1
                else:
                    out[pos] = 48
                    out[pos + 1] = 46
                    pos += 2
                    for _ in range(-e - 1):
                        out[pos] = 48
                        pos += 1
                    pos = _put(out, pos, d, 0, nd)
            else:
                out[pos] = d[0]
                pos += 1
                if nd > 1:
                    out[pos] = 46
                    pos += 1
                    pos = _put(out, pos, d, 1, nd)
                out[pos] = 101  # 'e'
                out[pos + 1] = 45 if e < 0 else 43
                pos += 2
                ae = abs(e)
                if ae >= 100:
                    out[pos] = 48 + ae // 100
                    pos += 1
                out[pos] = 48 + ae // 10 % 10
                out[pos + 1] = 48 + ae % 10
                pos += 2
        pos = _put(out, pos, lit, offs[C], offs[C + 1])
    return pos
