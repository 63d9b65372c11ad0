"""The analysis layer's one lookup by group kind: each kind's solver of positions and exact
derivatives over an array of crank angles (the dyads' closed forms, `velplan.analysis.groups`;
the class III triad's tracked roots, `velplan.analysis.triad`).

>>> from velplan.mechanism.model import KINDS
>>> set(SOLVERS) == set(KINDS)
True
"""

from __future__ import annotations

from typing import Callable

from velplan.analysis.groups import GroupResult, State, solve_prp, solve_rpp, solve_rpr, solve_rrp, solve_rrr
from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Group, Triad, kind_entry


def _solve_triad(g, st: State, length_scale: float, phi, track) -> GroupResult:
    from velplan.analysis import triad  # imported by the mechanisms that have a triad only

    return triad.solve_triad(g, st, phi, track, length_scale)


#: The analysis layer's one lookup by group kind: kind → solver(g, st, length_scale, φ, track);
#: ``track`` is the branch followed over the turn of a kind that is `tracked` (else None).
SOLVERS: dict[type, Callable[..., GroupResult]] = {
    RRR: lambda g, st, scale, phi, track: solve_rrr(g, st),
    RRP: lambda g, st, scale, phi, track: solve_rrp(g, st),
    RPR: lambda g, st, scale, phi, track: solve_rpr(g, st, scale),
    PRP: lambda g, st, scale, phi, track: solve_prp(g, st),
    RPP: lambda g, st, scale, phi, track: solve_rpp(g, st),
    Triad: _solve_triad,
}


def solve_group(g: Group, st: State, length_scale: float, phi=None, track=None) -> GroupResult:
    """Dispatch to the solver of ``g``'s kind (call under ``np.errstate(all="ignore")``:
    singular positions give inf/NaN); a `MechanismError` for a kind with no solver."""
    return kind_entry(SOLVERS, g, "velplan.analysis.solvers.SOLVERS")(g, st, length_scale, phi, track)
