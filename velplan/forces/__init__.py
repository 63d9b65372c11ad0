"""Force analysis of planar linkages: loads, inertia, kinetostatics (pair reactions and the
balancing moment), Zhukovsky's lever and the power method — three independent routes to the
balancing moment that agree to round-off in exact mode.

    >>> import velplan, velplan.forces as vf
    >>> mech = velplan.load("shaper")
    >>> res = vf.force_analysis_at(mech, velplan.positions(mech, 12))
    >>> res.max_relative_difference() < 1e-9
    True
"""

from velplan.forces.actions import Actions, AppliedForce, AppliedMoment
from velplan.forces.agreement import (
    ForceAnalysis,
    analyse_forces,
    force_analysis,
    force_analysis_at,
    lever_difference_percent,
    mean_balancing_moment,
    mechanism_actions,
)
from velplan.forces.inertia import Inertia, estimated_inertia, inertia_actions, inertias
from velplan.forces.kinetostatics import ForcePolygon, Kinetostatics, Reaction, kinetostatics
from velplan.forces.lever import Lever, images_from_kinematics, positions_from_kinematics, zhukovsky_lever
from velplan.forces.loads import (
    constant_force,
    constant_moment,
    cutting_force,
    gravity_actions,
    indicator_force,
    load_actions,
    press_load,
    table_force,
)
from velplan.forces.parse import parse_loads
from velplan.forces.triad import LeadForces, TriadForcePolygon, triad_polygon
from velplan.forces.power import (
    kinetic_energy,
    kinetic_energy_rate,
    power_balancing_moment,
    powers,
    static_moment,
)

__all__ = [
    "Actions", "AppliedForce", "AppliedMoment", "ForceAnalysis", "ForcePolygon", "Inertia", "Kinetostatics",
    "LeadForces", "Lever", "Reaction", "TriadForcePolygon", "constant_force", "constant_moment", "cutting_force",
    "estimated_inertia", "force_analysis", "force_analysis_at", "gravity_actions", "images_from_kinematics", "indicator_force", "inertia_actions",
    "inertias", "kinetic_energy", "kinetic_energy_rate", "kinetostatics", "lever_difference_percent",
    "load_actions", "mean_balancing_moment", "mechanism_actions", "parse_loads", "positions_from_kinematics",
    "power_balancing_moment", "powers", "press_load", "static_moment", "table_force", "triad_polygon", "zhukovsky_lever",
]
