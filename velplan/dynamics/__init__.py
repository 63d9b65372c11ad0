"""Machine dynamics: the crank's motion as a result (issue 14).

Layers, each pure functions and frozen results: `spec` (the ``[dynamics]`` section),
`panels` (piecewise Gauss–Legendre series), `reduction` (J, J′, M reduced to the crank),
`steady` (constant driving moment, ω(φ), ε, t, δ), `flywheel` (exact, Mertsalov,
Wittenbauer; dimensions), `motor` (constant, Kloss, table), `run` (unsteady runs, periodic
regime with a motor), `drive` (seed 003's drive selection), `analysis` (all of it for one
mechanism: `dynamics_analysis`), `report` (JSON and table).
"""

from velplan.dynamics.analysis import Dynamics, analyse, dynamics_analysis
from velplan.dynamics.spec import DynamicsSpec, parse_dynamics

__all__ = ["Dynamics", "DynamicsSpec", "dynamics_analysis", "parse_dynamics"]
