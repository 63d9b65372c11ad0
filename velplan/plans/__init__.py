"""The graphical method as data: velocity and acceleration plans built by construction steps.

>>> import velplan
>>> from velplan.plans import Plan
>>> mech = velplan.load("press")
>>> kin = velplan.solve(mech, [0.5])
>>> res = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.0007)
>>> round(float(abs(complex(*res.image("A")[0]))), 1)
71.4

The plans of a four-bar at 4 positions, exact and drawn at a draughtsman's precision, against
the analytic velocities (`relative_error`: per point, per position; ``floor`` a share of the
largest value below which an error is not relative, as at position 1, a dead point of B):

>>> from velplan.plans import EXACT, Drafting, Flag, PlanResult, auto_scale, plan, relative_error, standard_scale
>>> mech = velplan.load("four-bar")
>>> kin = velplan.solve(mech, velplan.positions(mech, 4), omega1=10.0)
>>> exact = plan(mech, kin.phi, kind="velocity")
>>> isinstance(exact, PlanResult), exact.drafting is EXACT, exact.scale
(True, True, 0.02)
>>> bool(relative_error(exact, floor=0.05)["B"].max() < 1e-12)
True
>>> drawn = Plan.of(mech).evaluate(kin, kind="velocity", drafting=Drafting(0.5, 0.5), scale_v=0.02)
>>> relative_error(drawn, floor=0.05)["B"].round(3)
array([0.   , 0.004, 0.209, 0.004])
>>> drawn.flags == [] and Flag.__name__ == "Flag"    # no near-parallel intersection to flag
True
>>> standard_scale(0.013), auto_scale(kin, slice(None), "velocity", target_mm=100.0)
(0.02, 0.02)
>>> standard_scale(0.0)
Traceback (most recent call last):
...
velplan.errors.ScaleError: cannot choose a scale for a largest value per mm of 0.0
>>> Drafting(-1.0)
Traceback (most recent call last):
...
velplan.errors.VelplanError: drafting precision length_mm must be > 0 and at most 10 (a draughtsman's), not -1.0
"""

from velplan.plans.drafting import EXACT, Drafting
from velplan.plans.engine import Flag, Plan, PlanResult, auto_scale, plan, relative_error
from velplan.plans.scale import standard_scale

__all__ = ["EXACT", "Drafting", "Flag", "Plan", "PlanResult", "auto_scale", "plan", "relative_error", "standard_scale"]
