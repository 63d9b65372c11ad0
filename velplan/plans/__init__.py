"""The graphical method as data: velocity and acceleration plans built by construction steps.

>>> import velplan
>>> from velplan.plans import Plan
>>> mech = velplan.load("press")
>>> kin = velplan.solve(mech, [0.5])
>>> res = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.0007)
>>> round(float(abs(complex(*res.image("A")[0]))), 1)
71.4
"""

from velplan.plans.drafting import EXACT, Drafting
from velplan.plans.engine import Flag, Plan, PlanResult, auto_scale, plan, relative_error
from velplan.plans.scale import standard_scale

__all__ = ["EXACT", "Drafting", "Flag", "Plan", "PlanResult", "auto_scale", "plan", "relative_error", "standard_scale"]
