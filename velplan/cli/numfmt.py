"""Rows of numbers as text, fast: ``'%.12g' % x`` for whole arrays at once.

`rows` writes rows made of fixed literal text and number fields (CSV, line-delimited JSON).
With numba installed (``pip install velplan[fast]``) two small compiled loops do it: the first
rounds each number to 12 significant digits by scaling with exact powers of ten, and flags a
number whose scaled value falls within 10⁻³ of a rounding tie (there the scaling's round-off
could decide the last digit); Python formats the flagged few, and the second loop writes the
text. Either way the text is Python's ``'%.12g' % x``, byte for byte, for every finite float.
"""

from __future__ import annotations

import numpy as np

P = 12
"""Significant digits."""

_KERNELS: list = []


def _kernels():
    """The compiled loops, or None without numba (compiled once, cached on disk)."""
    if not _KERNELS:
        try:
            import numba  # noqa: F401
        except ImportError:
            _KERNELS.append(None)
        else:
            from velplan.cli import _numfmt_kernels

            _KERNELS.append(_numfmt_kernels)
    return _KERNELS[0]


def _parse(text: str) -> tuple[int, int]:
    """(12-digit mantissa, exponent) of a '%.12g' text."""
    t = text.lstrip("-")
    if "e" in t:
        mant, exp = t.split("e")
        digits, X = mant.replace(".", ""), int(exp)
    else:
        ip, _, fp = t.partition(".")
        alld = ip + fp
        first = len(alld) - len(alld.lstrip("0"))
        digits, X = alld[first:], len(ip) - 1 - first
    return int((digits + "0" * P)[:P]), X


def rows(values: np.ndarray, literals: list[bytes], *, na: bytes = b"", bools=()) -> bytes:
    """Rows of text: ``literals[0] f0 literals[1] f1 … f[C−1] literals[C]`` per row of
    ``values`` (R, C), each field ``'%.12g' % x`` (``na`` where x is NaN or infinite); the
    columns in ``bools`` write ``true`` or ``false`` (x ≠ 0 or x = 0)."""
    values = np.ascontiguousarray(values, dtype=float)
    R, C = values.shape
    if len(literals) != C + 1:
        raise ValueError(f"rows needs {C + 1} literals for {C} columns, not {len(literals)}")
    flags = np.zeros(C, dtype=np.uint8)
    flags[list(bools)] = 1
    k = _kernels()
    if k is None:
        return _rows_python(values, literals, na, flags)
    x = values.ravel()
    m, X, kind = k.mantissa(x)
    for i in np.flatnonzero(kind == 3):  # near a tie: Python decides
        m[i], X[i] = _parse("%.12g" % x[i])
        kind[i] = 0
    lit = np.frombuffer(b"".join(literals), dtype=np.uint8)
    offs = np.cumsum([0] + [len(b) for b in literals]).astype(np.int64)
    out = np.empty(R * (C * (P + 8 + len(na)) + lit.size), dtype=np.uint8)
    n = k.write(m, X, kind, np.signbit(x), R, C, lit, offs, np.frombuffer(na, dtype=np.uint8), flags, out)
    return out[:n].tobytes()


def _rows_python(values: np.ndarray, literals: list[bytes], na: bytes, flags: np.ndarray) -> bytes:
    """`rows` by Python's own formatting (no numba)."""
    lits = [b.decode("utf-8") for b in literals]
    nas = na.decode("utf-8")

    def cell(v: float, boolean: bool) -> str:
        if boolean:
            return "true" if v != 0 else "false"
        return ("%.12g" % v) if np.isfinite(v) else nas

    if not flags.any():  # the common case: one template per row
        tpl = "".join(f"{lit.replace('%', '%%')}%.12g" for lit in lits[:-1]) + lits[-1].replace("%", "%%")
    out = []
    for ok, row in zip(np.isfinite(values).all(axis=1).tolist(), values.tolist()):
        if ok and not flags.any():
            out.append(tpl % tuple(row))
        else:
            out.append("".join(a + cell(v, bool(b)) for a, v, b in zip(lits, row, flags)) + lits[-1])
    return "".join(out).encode("utf-8")
