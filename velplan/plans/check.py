"""Checking a table of values measured by hand against the exact values.

A table is CSV: a ``quantity`` column, then one column per position (``1``, ``2``, …, in the
order of the mechanism's positions from its reference; a repeated ``1`` at the end is ignored).
Quantities by the names the sheet's table and the batch's key print (`velplan.plans.table.
quantity_name`: ``vB2/ω1``, |v|/ω of the crank in m; ``ω2/ω1``, sign ignored when the table gives
magnitudes), typeset (``v_{B2}/ω₁``) or in ASCII (``VB2/w1``, ``V_B2``, ``w_2``; see
`velplan.plans.table.parse_quantity`). Semicolon-separated files with decimal commas are read too.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from velplan.analysis.numbering import position_number, position_numbers
from velplan.analysis.extremes import positions
from velplan.analysis.solver import solve
from velplan.errors import TableError
from velplan.io import finite_number
from velplan.mechanism.model import Mechanism
from velplan.plans.drafting import Drafting
from velplan.plans.engine import Plan, auto_scale
from velplan.plans.scale import check_drawable, check_scale
from velplan.plans.table import natural_key, parse_quantity, quantity_name


@dataclass(frozen=True)
class Entry:
    """One checked entry: the value given, the exact value, the deviation, the tolerance, and
    (when outside it) the likely cause."""

    quantity: str
    position: int
    phi_deg: float
    given: float
    exact: float
    tolerance: float
    deviation_mm: float
    cause: str = ""

    @property
    def deviation(self) -> float:
        return self.given - self.exact

    @property
    def flagged(self) -> bool:
        return abs(self.deviation) > self.tolerance


@dataclass(frozen=True)
class CheckReport:
    mechanism: str
    scale_v: float
    entries: tuple[Entry, ...]

    @property
    def flagged(self) -> list[Entry]:
        return [e for e in self.entries if e.flagged]

    def text(self) -> str:
        lines = [f"{self.mechanism}: {len(self.entries)} entries checked at μv = {self.scale_v:g} (m/s)/mm, "
                 f"{len(self.flagged)} outside the drafting tolerance"]
        lines.append(f"{'quantity':<10}{'pos':>4}{'φ, °':>8}{'given':>10}{'exact':>10}{'dev':>10}{'tol':>9}{'dev, mm':>9}")
        for e in self.entries:
            mark = "  ✗ " + e.cause if e.flagged else ""
            lines.append(f"{e.quantity:<10}{e.position:>4}{e.phi_deg:>8.1f}{e.given:>10.4g}{e.exact:>10.4g}"
                         f"{e.deviation:>+10.2g}{e.tolerance:>9.2g}{e.deviation_mm:>+9.1f}{mark}")
        return "\n".join(lines)


def read_table(source: str | Path) -> tuple[list[str], dict[str, list[float | None]]]:
    """Parse a measured table: returns the position headers and quantity → values."""
    path = Path(source)
    try:
        text = path.read_text("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise TableError(f"cannot read table {path}: {exc}") from None
    first = text.splitlines()[0] if text.strip() else ""
    delim = ";" if first.count(";") > first.count(",") else ","
    rows = [r for r in csv.reader(io.StringIO(text), delimiter=delim) if any(c.strip() for c in r)]
    if len(rows) < 2:
        raise TableError(f"table {path} needs a header row and at least one quantity row")
    head = [c.strip() for c in rows[0]]
    out: dict[str, list[float | None]] = {}
    for r in rows[1:]:
        name = r[0].strip()
        if name.lower().startswith(("φ", "phi", "position")):
            continue
        if len(r) != len(head):
            raise TableError(f"table {path}: row {name!r} has {len(r)} cells, the header has {len(head)}")
        vals = []
        for cell in r[1:]:
            cell = cell.strip().replace(",", ".") if delim == ";" else cell.strip()
            if cell in ("", "-", "—"):
                vals.append(None)
                continue
            vals.append(finite_number(cell, f"table {path}: row {name!r}", error=TableError))
        out[name] = vals
    return head[1:], out


def quantity_of(name: str, points, links, crank: str, what: str = "") -> tuple[str, str]:
    """("V", point) or ("w", link) of a table's quantity `name`; `TableError` naming the names
    known (those of `points` and `links` over the crank's link `crank`) else."""
    rows = [f"w_{k}" for k in links] + [f"V_{p}" for p in points]
    row = parse_quantity(name, rows, crank)
    if row is None:
        v, w = quantity_name("V_<point>", crank), quantity_name("w_<link>", crank)
        raise TableError(f"unknown quantity {name!r}{what}; use {v} with a point of "
                         f"{', '.join(sorted(points, key=natural_key))} or {w} with a link of "
                         f"{', '.join(sorted(links, key=natural_key))}")
    kind, x = row.split("_", 1)
    return kind, x


MC_RUNS = 400
"""Monte-Carlo drafts per position used to set the tolerance of each entry."""


def position_count(head: list[str]) -> int:
    """The number of positions N of a table whose position headers are ``1…N`` (a repeated
    ``1`` at the end, as course works close the table, is not counted); `TableError` else."""
    n = len(head) - (1 if len(head) > 1 and head[-1] == head[0] else 0)
    try:
        numbers = [int(float(c)) for c in head[:n]]
    except ValueError:
        raise TableError(f"position headers must be numbers 1…N, not {head[:n]}") from None
    if numbers != position_numbers(range(n)).tolist():
        raise TableError(f"position headers must be 1…{n} in order, not {numbers}")
    return n


def check_table(mech: Mechanism, source: str | Path, *, scale_v: float | None = None,
                drafting: Drafting = Drafting(), seed: int = 2026) -> CheckReport:
    """Compare a hand-made table with the exact transfer functions and explain the outliers.

    The tolerance of an entry is what drafting at ``drafting``'s precision can explain: the
    95th percentile of the entry's deviation over `MC_RUNS` simulated hand drafts (each length
    and direction laid off or read with a uniform error of that precision, ``seed`` fixed so
    the report is reproducible), plus half a unit of the last digit the row is written to.
    Outliers are explained, when possible, as a column drawn at another crank angle, an
    entry that belongs to another position, or a mis-measured segment (its deviation in mm
    on the plan).
    """
    head, table = read_table(source)
    n = position_count(head)
    phi = positions(mech, n)
    kin = solve(mech, phi)
    mu = check_scale(scale_v, "--scale-v") if scale_v is not None else auto_scale(kin, np.arange(n), "velocity")
    check_drawable(kin, np.arange(n), mu, "velocity", drafting)
    plan = Plan.of(mech)
    points = list(plan.images["v"])
    links = [k for k in plan.figures["v"] if k != "0"]
    quantities = {name: quantity_of(name, points, links, mech.crank.link) for name in table}
    for name, (kind, x) in quantities.items():  # an ω row with a negative entry is signed
        if kind == "w" and any(v is not None and v < 0 for v in table[name]):
            quantities[name] = ("ws", x)
    w1 = np.abs(kin.omega1)
    exact = {name: _analytic(q, kin, w1) for name, q in quantities.items()}
    spread = _drafting_spread(mech, plan, phi, mu, drafting, quantities, exact, seed)
    per_mm = {name: _per_mm(q, plan, kin, mu, w1) for name, q in quantities.items()}
    tol = {name: spread[name] + 0.5 * 10.0 ** -_decimals(vals) for name, vals in table.items()}
    causes = _column_causes(mech, phi, table, quantities, exact, tol, w1)
    entries = []
    for name, vals in table.items():
        for j in range(n):
            g = vals[j]
            if g is None:
                continue
            ex, t = float(exact[name][j]), float(tol[name][j])
            dev_mm = (g - ex) / float(per_mm[name][j])
            cause = ""
            if abs(g - ex) > t:
                cause = causes.get(j) or _entry_cause(mech, phi, j, g, exact[name], t, quantities[name], w1, dev_mm)
            entries.append(Entry(name, position_number(j), float(np.degrees(phi[j]) % 360), g, ex, t, float(dev_mm), cause))
    return CheckReport(mech.name, mu, tuple(entries))


def _analytic(q: tuple[str, str], kin, w1: float) -> np.ndarray:
    kind, x = q
    if kind == "V":
        return np.hypot(*kin.velocity(x).T) / w1
    if kind == "ws":  # + when the link turns in the crank's sense
        return kin.omega(x) / kin.omega1
    return np.abs(kin.omega(x)) / w1


def _per_mm(q, plan, kin, mu: float, w1: float) -> np.ndarray:
    """How much one mm on the plan changes the entry (m per mm, or 1 per mm for ω/ω1)."""
    kind, x = q
    if kind == "V":
        return np.full(len(kin), mu / w1)
    fig = plan.figures["v"][x]
    length = np.hypot(*(kin.position(fig.p2) - kin.position(fig.p1)).T)
    return mu / (length * w1)


def _drafting_spread(mech, plan, phi, mu, drafting, quantities, exact, seed) -> dict[str, np.ndarray]:
    """95th percentile of |drafted − exact| per quantity and position over MC_RUNS drafts."""
    n = len(phi)
    kin = solve(mech, np.tile(phi, MC_RUNS))
    mc = Drafting(drafting.length_mm, drafting.angle_deg, rng=np.random.default_rng(seed))
    res = plan.evaluate(kin, kind="velocity", scale_v=mu, drafting=mc, refuse_below=0.0)
    w1 = np.abs(kin.omega1)
    out = {}
    for name, (kind, x) in quantities.items():
        if kind == "V":
            got = np.hypot(*res.vector(x).T) / w1
        else:
            got = res.omegas[x] / kin.omega1 if kind == "ws" else np.abs(res.omegas[x]) / w1
        dev = np.abs(got.reshape(MC_RUNS, n) - exact[name][None, :])
        out[name] = np.nanquantile(dev, 0.95, axis=0)
    return out


def _decimals(vals) -> int:
    """Decimals the row is written to (the most any of its entries shows)."""
    best = 0
    for v in vals:
        if v is None:
            continue
        s = f"{v:.6g}"
        if "e" not in s and "." in s:
            best = max(best, len(s.split(".")[1]))
    return best


def _column_causes(mech, phi, table, quantities, exact, tol, w1) -> dict[int, str]:
    """Columns with two or more outliers that all fit one other crank angle within tolerance."""
    out = {}
    fine = np.radians(np.arange(-45.0, 45.0001, 0.25))
    sense = mech.crank.sense
    for j in range(len(phi)):
        given = {nm: v[j] for nm, v in table.items() if v[j] is not None}
        bad = [nm for nm in given if abs(given[nm] - exact[nm][j]) > tol[nm][j]]
        if len(bad) < 2:
            continue
        kin_f = solve(mech, phi[j] + sense * fine)
        score = np.max([np.abs(_analytic(quantities[nm], kin_f, w1) - given[nm]) / tol[nm][j] for nm in given], axis=0)
        best = int(np.argmin(score))
        if score[best] <= 1.0 and abs(fine[best]) >= np.radians(2):
            angle = np.degrees(phi[j] + sense * fine[best]) % 360
            out[j] = (f"the whole column fits crank angle {angle:.1f}° ({np.degrees(fine[best]):+.1f}°): "
                      "position drawn at the wrong angle")
    return out


def _entry_cause(mech, phi, j, g, row, t, q, w1, dev_mm) -> str:
    others = [k for k in range(len(row)) if k != j and abs(g - row[k]) <= t]
    if others:
        k = min(others, key=lambda k: abs(g - row[k]))
        return f"equals the exact value at position {position_number(k)} ({np.degrees(phi[k]) % 360:.0f}°): entered in the wrong column?"
    fine = np.radians(np.arange(-45.0, 45.0001, 0.25))
    sense = mech.crank.sense
    near = np.abs(_analytic(q, solve(mech, phi[j] + sense * fine), w1) - g) <= t
    if near.any():
        d = fine[near][np.argmin(np.abs(fine[near]))]
        if abs(d) >= np.radians(2):
            return f"fits crank angle {np.degrees(phi[j] + sense * d) % 360:.1f}°: position drawn at the wrong angle?"
    return f"mis-measured segment: {dev_mm:+.1f} mm on the plan"
