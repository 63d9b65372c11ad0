"""Grading a student's table of transfer functions against a batch's answer key.

The table is read as `velplan.plans.check.read_table` reads it (``quantity,1,2,…``; rows
by the names the sheet and the key print, ``vA/ω1`` and ``ω3/ω1``, or as
`velplan.plans.table.parse_quantity` reads them otherwise); the key is the ``answers.json`` that
``velplan batch`` writes. An entry is right when it is within ``tolerance`` × the largest
magnitude of its row in the key, plus half a unit of the last digit the row is written to.
An ω row with a negative entry is compared signed (+ in the crank's sense), a row of
magnitudes by magnitude.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from velplan.analysis.numbering import position_number
from velplan.errors import TableError
from velplan.plans.check import _decimals, position_count, quantity_of, read_table


@dataclass(frozen=True)
class Graded:
    quantity: str
    position: int
    given: float
    key: float
    tolerance: float

    @property
    def right(self) -> bool:
        return abs(self.given - self.key) <= self.tolerance


@dataclass(frozen=True)
class GradeReport:
    variant: str
    tolerance: float
    entries: tuple[Graded, ...]

    @property
    def right(self) -> int:
        return sum(e.right for e in self.entries)

    @property
    def score(self) -> float:
        """Share of the entries that are right, 0…1."""
        return self.right / len(self.entries) if self.entries else 0.0

    def text(self) -> str:
        lines = [f"variant {self.variant}: {self.right} of {len(self.entries)} entries right "
                 f"({100 * self.score:.0f} %) within {100 * self.tolerance:g} % of each row's largest value"]
        wrong = [e for e in self.entries if not e.right]
        if wrong:
            lines.append(f"{'quantity':<10}{'pos':>4}{'given':>11}{'key':>11}{'tol':>10}")
            for e in wrong:
                lines.append(f"{e.quantity:<10}{e.position:>4}{e.given:>11.4g}{e.key:>11.4g}{e.tolerance:>10.2g}  ✗")
        return "\n".join(lines)


def read_key(source: str | Path, variant: str) -> dict:
    """The answers of ``variant`` in an ``answers.json``; `TableError` naming what is missing."""
    path = Path(source)
    try:
        data = json.loads(path.read_text("utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise TableError(f"cannot read answer key {path}: {exc}") from None
    rows = data.get("variants") if isinstance(data, dict) else None
    if not isinstance(rows, list):
        raise TableError(f"{path} is not an answer key of velplan batch (no 'variants')")
    for a in rows:
        if str(a.get("variant")) == str(variant):
            return a
    known = ", ".join(str(a.get("variant")) for a in rows) or "none"
    raise TableError(f"answer key {path} has no variant {variant!r}; it has {known}")


def grade_table(table: str | Path, key: str | Path, variant: str, *, tolerance: float = 0.05) -> GradeReport:
    """Grade the student's ``table`` against ``variant`` of the answer ``key``."""
    if not 0 < tolerance < 1:
        raise TableError(f"tolerance must be between 0 and 100 %, not {100 * tolerance:g} %")
    answers = read_key(key, variant)
    head, rows = read_table(table)
    n = position_count(head)
    if n != answers["positions"]:
        raise TableError(f"the table has {n} positions; variant {variant} of the key has {answers['positions']}")
    entries = []
    for name, vals in rows.items():
        ref, signed = _key_row(name, answers, vals[:n])
        top = max(abs(x) for x in ref) if ref else 0.0
        tol = tolerance * top + 0.5 * 10.0 ** -_decimals(vals[:n])
        for j, g in enumerate(vals[:n]):
            if g is None:
                continue
            k = ref[j] if signed else abs(ref[j])
            entries.append(Graded(name, position_number(j), g, k, tol))
    return GradeReport(str(variant), tolerance, tuple(entries))


def _key_row(name: str, answers: dict, vals) -> tuple[list[float], bool]:
    """The key's row that `name` names (keys written before the crank was recorded: link 1)."""
    kind, x = quantity_of(name, list(answers["V"]), list(answers["omega"]), str(answers.get("crank", "1")),
                          " in the key")
    if kind == "w":
        return answers["omega"][x], any(v is not None and v < 0 for v in vals)
    return answers["V"][x], False
