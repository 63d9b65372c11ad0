"""Machine dynamics: the crank's motion as a result (issue 14).

Layers, each pure functions and frozen results: `spec` (the ``[dynamics]`` section),
`panels` (piecewise Gauss–Legendre series), `reduction` (J, J′, M reduced to the crank),
`steady` (constant driving moment, ω(φ), ε, t, δ), `flywheel` (exact, Mertsalov,
Wittenbauer; dimensions), `motor` (constant, Kloss, table), `run` (unsteady runs, periodic
regime with a motor), `drive` (seed 003's drive selection), `analysis` (all of it for one
mechanism: `dynamics_analysis`), `report` (JSON and table).

>>> import velplan
>>> from velplan.dynamics import Dynamics, DynamicsSpec, dynamics_analysis, parse_dynamics
>>> mech = velplan.load("slider-press")
>>> spec = parse_dynamics(mech)                   # the file's [dynamics] section
>>> isinstance(spec, DynamicsSpec), spec.delta
(True, None)
>>> d = dynamics_analysis(mech, velplan.Study(mech).loads, delta=0.05)
>>> isinstance(d, Dynamics), round(d.steady.delta, 6)   # the flywheel keeps δ as asked
(True, 0.05)
>>> f = d.flywheel                                # exact = Wittenbauer; Mertsalov's estimate above
>>> bool(abs(f.exact - f.wittenbauer) < 1e-6 * f.exact), bool(f.mertsalov >= f.exact)
(True, True)
>>> parse_dynamics(mech, {"delta": -1})
Traceback (most recent call last):
...
velplan.errors.MechanismError: [dynamics] delta must be between 0 and 1 (exclusive), not -1
"""

from velplan.dynamics.analysis import Dynamics, analyse, dynamics_analysis
from velplan.dynamics.spec import DynamicsSpec, parse_dynamics

__all__ = ["Dynamics", "DynamicsSpec", "dynamics_analysis", "parse_dynamics"]
