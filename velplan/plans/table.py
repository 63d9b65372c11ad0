"""The table of transfer functions (velocity analogues) V/ω1 (m) and ω/ω1 over the positions,
laid out as course works tabulate them (seed 000, table 2). One table of a study: the sheet, the
answer key of a batch and the note print the same rows (`table_points`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.mechanism.model import GROUND, Mechanism
from velplan.mechanism.structure import coincident_points, pairs
from velplan.plans.engine import PlanResult


@dataclass(frozen=True)
class TransferTable:
    """Rows ``"V_<point>"`` (|V|/ω1, m) and ``"w_<link>"`` (ω/ω1, signed) over positions 1…n."""

    mechanism: str
    phi: np.ndarray
    rows: dict[str, np.ndarray]
    scale_v: float
    mode: str

    def text(self, *, digits: int = 3, close: bool = True) -> str:
        """The table as text; ``close`` repeats position 1 at the end, as course works do."""
        n = len(self.phi)
        cols = list(range(n)) + ([0] if close else [])
        head = "position     " + "".join(f"{position_number(i):>8}" for i in cols)
        phi = "φ, deg       " + "".join(f"{math.degrees(self.phi[i]) % 360:>8.1f}" for i in cols)
        lines = [head, phi]
        for name, vals in self.rows.items():
            label = f"{name[2:]}/ω1" if name.startswith("w_") else f"V{name[2:]}/ω1, m"
            label = ("ω" + label) if name.startswith("w_") else label
            lines.append(f"{label:<13}" + "".join(f"{vals[i]:>8.{digits}f}" for i in cols))
        return "\n".join(lines)

    def csv(self) -> str:
        """quantity,1,2,…,n (the layout `velplan check` reads)."""
        n = len(self.phi)
        out = ["quantity," + ",".join(str(position_number(i)) for i in range(n))]
        for name, vals in self.rows.items():
            out.append(f"{name}," + ",".join(f"{v:.6g}" for v in vals))
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
    rows = {f"V_{p}": np.hypot(*res.vector(p).T) / w1 for p in points}
    for link, fig in res.plan.figures["v"].items():
        if link not in (mech.crank.link, "0") and fig is not None and link in res.omegas:
            rows[f"w_{link}"] = res.omegas[link] / kin.crank_rate("omega", res.index)
    return TransferTable(mech.name, res.phi, rows, res.scale, res.drafting.mode)
