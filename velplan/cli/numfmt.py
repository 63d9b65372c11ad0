"""Rows of numbers as text, fast: ``'%.12g' % x`` for whole arrays at once.

`rows` writes rows made of fixed literal text and number fields (CSV, line-delimited JSON).
With numba installed (``pip install velplan[fast]``) two small compiled loops do it: the first
rounds each number to 12 significant digits by scaling with exact powers of ten, and flags a
number whose scaled value falls within 10⁻³ of a rounding tie (there the scaling's round-off
could decide the last digit); Python formats the flagged few, and the second loop writes the
text. Either way the text is Python's ``'%.12g' % x``, byte for byte, for every finite float.
``exact=True`` writes every number as ``repr`` does (the shortest text that reads back to the
same float, as `json.dumps` writes it), by Python's own formatting.
"""

from __future__ import annotations

import math

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


def rows(values: np.ndarray, literals: list[bytes], *, na: bytes = b"", bools=(), ints=(),
         exact: bool = False) -> bytes:
    """Rows of text: ``literals[0] f0 literals[1] f1 … f[C−1] literals[C]`` per row of
    ``values`` (R, C), each field ``'%.12g' % x`` (``repr(x)`` when ``exact``; ``na`` where x is
    NaN or infinite); the columns in ``bools`` write ``true`` or ``false`` (x ≠ 0 or x = 0), those
    in ``ints`` whole numbers (``'%d'``: the same text as ``'%.12g'`` below 10¹²)."""
    values = np.ascontiguousarray(values, dtype=float)
    R, C = values.shape
    if len(literals) != C + 1:
        raise ValueError(f"rows needs {C + 1} literals for {C} columns, not {len(literals)}")
    flags = np.zeros(C, dtype=np.uint8)
    flags[list(bools)] = 1
    k = None if exact else _kernels()
    if k is None:
        return _rows_python(values, literals, na, flags, set(ints), "%r" if exact else "%.12g")
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


def _rows_python(values: np.ndarray, literals: list[bytes], na: bytes, flags: np.ndarray, ints: set,
                 number: str) -> bytes:
    """`rows` by Python's own formatting, ``number`` (``'%.12g'`` or ``'%r'``) for each number:
    one template per pattern of booleans for the rows whose numbers are all finite."""
    raw = [b.decode("utf-8") for b in literals]
    lits = [t.replace("%", "%%") for t in raw]
    nas = na.decode("utf-8")
    conv = ["%d" if c in ints else number for c in range(len(flags))]
    bools = np.flatnonzero(flags)
    pattern = (values[:, bools] != 0) @ (1 << np.arange(bools.size)) if bools.size else np.zeros(len(values), int)
    templates: dict[int, str] = {}

    def template(key: int) -> str:
        # a boolean's word is literal text; '%.0s' takes its number and writes nothing
        words = {c: ("true" if key >> b & 1 else "false") + "%.0s" for b, c in enumerate(bools)}
        return "".join(lit + words.get(c, conv[c]) for c, lit in enumerate(lits[:-1])) + lits[-1]

    def cell(c: int, v: float) -> str:
        if flags[c]:
            return "true" if v != 0 else "false"
        return (conv[c] % v) if math.isfinite(v) else nas

    out = []
    for ok, key, row in zip(np.isfinite(values).all(axis=1).tolist(), pattern.tolist(), values.tolist()):
        if ok:
            tpl = templates.get(key) or templates.setdefault(key, template(key))
            out.append(tpl % tuple(row))
        else:
            out.append("".join(lit + cell(c, v) for c, (lit, v) in enumerate(zip(raw, row))) + raw[-1])
    return "".join(out).encode("utf-8")
