"""The table of transfer functions (velocity analogues) V/ω1 (m) and ω/ω1 over the positions,
laid out as course works tabulate them (seed 000, table 2). One table of a study: the sheet, the
answer key of a batch and the note print the same rows (`table_points`), in point and link order
(A, B, C; ω2, ω3), under one name per quantity (`quantity_name`, `quantity_label`) that
``velplan check`` and ``velplan grade`` read back (`parse_quantity`).

>>> quantity_name("V_A4", "2"), quantity_label("V_A4", "2"), quantity_label("w_3", "1")
('vA4/ω2', 'v_{A4}/ω_{2}', 'ω_{3}/ω_{1}')
>>> parse_quantity("VA4/w2", ["V_A4", "w_3"], "2"), parse_quantity("ω₃/ω₂", ["V_A4", "w_3"], "2")
('V_A4', 'w_3')
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.mechanism.model import GROUND, Mechanism
from velplan.mechanism.structure import coincident_points, pairs
from velplan.notation import plain_digits, plain_text
from velplan.plans.engine import PlanResult


@dataclass(frozen=True)
class TransferTable:
    """Rows ``"V_<point>"`` (|V|/ω1, m) and ``"w_<link>"`` (ω/ω1, signed) over positions 1…n."""

    mechanism: str
    phi: np.ndarray
    rows: dict[str, np.ndarray]
    scale_v: float
    mode: str
    crank: str = "1"
    """The crank's link: the ω every row is divided by."""

    def name(self, row: str) -> str:
        """The plain name of row `row` (``"V_A"`` → ``"vA/ω2"``), as the sheet and the key print it."""
        return quantity_name(row, self.crank)

    def text(self, *, digits: int = 3, close: bool = True) -> str:
        """The table as text; ``close`` repeats position 1 at the end, as course works do."""
        n = len(self.phi)
        cols = list(range(n)) + ([0] if close else [])
        head = "position     " + "".join(f"{position_number(i):>8}" for i in cols)
        phi = "φ, deg       " + "".join(f"{math.degrees(self.phi[i]) % 360:>8.1f}" for i in cols)
        lines = [head, phi]
        for name, vals in self.rows.items():
            label = self.name(name) + ("" if name.startswith("w_") else ", m")
            lines.append(f"{label:<13}" + "".join(f"{vals[i]:>8.{digits}f}" for i in cols))
        return "\n".join(lines)

    def csv(self) -> str:
        """quantity,1,2,…,n (the layout `velplan check` reads), a row per quantity by its name."""
        n = len(self.phi)
        out = ["quantity," + ",".join(str(position_number(i)) for i in range(n))]
        for name, vals in self.rows.items():
            out.append(f"{self.name(name)}," + ",".join(f"{v:.6g}" for v in vals))
        return "\n".join(out) + "\n"


def table_points(mech: Mechanism, names) -> list[str]:
    """Of ``names``, the points worth a row, in order: the moving joints and named points, not
    the frame's points (a coincident point of a fixed guide among them), the centres of mass
    (unless a joint is one) nor a construction point (an RPP runner's origin, a triad's special
    point)."""
    ground = set(mech.ground_points) | {n for n, link in coincident_points(mech).items() if link == GROUND}
    joints = {p.point for p in pairs(mech)}
    centres = {m.centre for m in mech.masses}
    origins = {p for g in mech.groups for p in g.construction_points()}  # RPP's K, Assur's point
    return [p for p in names
            if p not in ground and p not in origins and not ((p in centres or p.startswith("S")) and p not in joints)]


def natural_key(name: str) -> tuple:
    """Sort key of a point or link name: letters, then the number (A, A4, B, C10 after C2; 2, 10)."""
    return tuple((0, int(part), "") if part.isdigit() else (1, 0, part)
                 for part in re.findall(r"\d+|\D+", name))


def quantity_label(row: str, crank: str) -> str:
    """The typeset name of table row `row` (``"V_A"``: |v_A|/ω of the crank; ``"w_3"``: ω3/ω
    of the crank) with the crank's link `crank`: ``"v_{A}/ω_{2}"``, indices marked ``_{…}`` as
    the drawings set them below the line."""
    kind, name = row.split("_", 1)
    head = "v" if kind == "V" else "ω"
    return f"{head}_{{{name}}}/ω_{{{crank}}}"


def quantity_name(row: str, crank: str) -> str:
    """The name of table row `row` as one line of plain text (the key's quantity column, what a
    reader copies off the sheet): `quantity_label` without its index marks, ``"vA/ω2"``."""
    return plain_text(quantity_label(row, crank))


def _spellings(row: str, crank: str) -> set[str]:
    """Every spelling of row `row` a table may carry: the sheet's name, ASCII (``VA/w2``,
    ``V_A``, ``omega3/omega2``), with or without the divisor and, for |v|/ω, the unit. ``/ω1``
    is the crank's ω whatever its link (the name tables used before)."""
    kind, name = row.split("_", 1)
    heads = ("v", "V") if kind == "V" else ("ω", "w", "omega")
    over = {"", *(f"/{w}{n}" for w in ("ω", "w", "omega") for n in {crank, "1"})}
    units = ("", ",m", ",м") if kind == "V" else ("",)
    return {f"{h}{sep}{name}{d}{u}" for h in heads for sep in ("", "_") for d in over for u in units}


def parse_quantity(text: str, rows, crank: str) -> str | None:
    """The row of `rows` (``"V_A"``, ``"w_3"`` …) that `text` names, or None: the sheet's
    typeset or plain name, its ASCII spellings (`_spellings`), spaces and ``_{…}`` marks
    ignored, subscript digits read as digits."""
    key = plain_digits(plain_text("".join(text.split())))
    for row in rows:
        if key in _spellings(row, crank):
            return row
    return None


def transfer_table(res: PlanResult, *, points: list[str] | None = None) -> TransferTable:
    """Transfer functions read off a velocity plan ``res`` (all its positions).

    Points default to `table_points` of the solved points (the rows every table of a study
    prints); links to every link that turns.
    """
    if res.kind != "velocity":
        raise ValueError("transfer functions are read off a velocity plan")
    mech, kin = res.plan.mechanism, res.kin
    w1 = np.abs(kin.crank_rate("omega", res.index))
    if points is None:
        points = table_points(mech, list(kin.point_index))
    rows = {f"V_{p}": np.hypot(*res.vector(p).T) / w1 for p in sorted(points, key=natural_key)}
    links = [link for link, fig in res.plan.figures["v"].items()
             if link not in (mech.crank.link, "0") and fig is not None and link in res.omegas]
    for link in sorted(links, key=natural_key):
        rows[f"w_{link}"] = res.omegas[link] / kin.crank_rate("omega", res.index)
    return TransferTable(mech.name, res.phi, rows, res.scale, res.drafting.mode, mech.crank.link)
