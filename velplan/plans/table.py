"""The table of transfer functions (velocity analogues) V/ω1 (m) and ω/ω1 over the positions,
laid out as course works tabulate them (seed 000, table 2)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

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
        head = "position     " + "".join(f"{i + 1:>8}" for i in cols)
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
        out = ["quantity," + ",".join(str(i + 1) for i in range(n))]
        for name, vals in self.rows.items():
            out.append(f"{name}," + ",".join(f"{v:.6g}" for v in vals))
        return "\n".join(out) + "\n"


def transfer_table(res: PlanResult, *, points: list[str] | None = None) -> TransferTable:
    """Transfer functions read off a velocity plan ``res`` (all its positions).

    Points default to every named moving point but the centres of mass named S… (the usual
    letter) and the runners' auxiliary origins K; links to every link that turns.
    """
    if res.kind != "velocity":
        raise ValueError("transfer functions are read off a velocity plan")
    mech, kin = res.plan.mechanism, res.kin
    w1 = np.abs(kin.crank_rate("omega", res.index))
    ground = dict(mech.ground)
    if points is None:
        centres = {m.centre for m in mech.masses if m.centre.startswith("S")}
        origins = {g.origin_name for g in mech.groups if g.kind == "RPP"}
        points = [p for p in res.vectors if p not in ground and p not in centres | origins]
    rows = {f"V_{p}": np.hypot(*res.vector(p).T) / w1 for p in points}
    for link, fig in res.plan.figures["v"].items():
        if link not in (mech.crank.link, "0") and fig is not None and link in res.omegas:
            rows[f"w_{link}"] = res.omegas[link] / kin.crank_rate("omega", res.index)
    return TransferTable(mech.name, res.phi, rows, res.scale, res.drafting.mode)
