"""Force analysis of planar linkages: loads, inertia, kinetostatics (pair reactions and the
balancing moment), Zhukovsky's lever and the power method — three independent routes to the
balancing moment that agree to round-off in exact mode.

    >>> import velplan, velplan.forces as vf
    >>> mech = velplan.load("shaper")
    >>> res = vf.force_analysis_at(mech, velplan.positions(mech, 12))
    >>> res.max_relative_difference() < 1e-9
    True

The steps one at a time, on the slider press at 4 positions: its loads (`parse_loads`), the
actions on its links (gravity, inertia, loads), the three balancing moments::

    >>> import numpy as np
    >>> mech = velplan.load("slider-press")
    >>> kin = velplan.solve(mech, velplan.positions(mech, 4))
    >>> loads = vf.parse_loads(mech)
    >>> acts = vf.mechanism_actions(mech, kin, loads)
    >>> isinstance(acts, vf.Actions)
    True
    >>> all(isinstance(f, vf.AppliedForce) for f in acts.forces), all(isinstance(m, vf.AppliedMoment) for m in acts.moments)
    (True, True)
    >>> [f.label for f in vf.gravity_actions(mech, kin).forces], [f.label for f in vf.load_actions(loads, kin).forces]
    (['G1', 'G2', 'G3'], ['P'])
    >>> inertia = vf.inertia_actions(mech, kin)
    >>> [f.label for f in inertia.forces], [m.label for m in inertia.moments]
    (['Φ1', 'Φ2', 'Φ3'], ['MΦ1', 'MΦ2'])
    >>> [i.link for i in vf.inertias(mech, kin) if isinstance(i, vf.Inertia)]
    ['1', '2', '3']
    >>> round(vf.estimated_inertia(12.0, 0.3), 9)    # m·l²/k with k = 10, kg·m², where a file gives no J
    0.108
    >>> ks = vf.kinetostatics(mech, kin, acts)
    >>> isinstance(ks, vf.Kinetostatics), sorted(ks.reactions)
    (True, ['A', 'B', 'O', 'P:3/0'])
    >>> isinstance(ks.reactions["A"], vf.Reaction), isinstance(ks.polygons["2-3"], vf.ForcePolygon)
    (True, True)
    >>> lever = vf.zhukovsky_lever(mech, vf.positions_from_kinematics(kin, None),
    ...                            vf.images_from_kinematics(kin, None, 0.01), 0.01, acts)
    >>> isinstance(lever, vf.Lever), bool(np.allclose(lever.balancing_moment, ks.balancing_moment, atol=1e-9))
    (True, True)
    >>> bool(np.allclose(vf.power_balancing_moment(kin, acts), ks.balancing_moment, atol=1e-9))
    True
    >>> sorted(vf.powers(kin, acts))            # the power of each action, W
    ['G1', 'G2', 'G3', 'MΦ1', 'MΦ2', 'P', 'Φ1', 'Φ2', 'Φ3']
    >>> vf.kinetic_energy(mech, kin).shape, vf.kinetic_energy_rate(mech, kin).shape
    ((4,), (4,))
    >>> vf.lever_difference_percent(np.array([101.0, 50.0]), np.array([100.0, 50.0]))
    array([1., 0.])
    >>> fa = vf.force_analysis(kin, velplan.Study(mech, n=4).plan("velocity"), loads)
    >>> isinstance(fa, vf.ForceAnalysis), fa.max_relative_difference() < 1e-9
    (True, True)
    >>> round(vf.mean_balancing_moment(mech, n=360), 3)     # over a turn, N·m
    78.523
    >>> vf.static_moment(kin, acts)
    Traceback (most recent call last):
    ...
    velplan.errors.MechanismError: the static moment takes gravity and loads only, not inertia forces
    >>> round(float(vf.static_moment(kin, vf.gravity_actions(mech, kin)).moment[1]), 6) == round(
    ...     float(vf.power_balancing_moment(kin, vf.gravity_actions(mech, kin))[1]), 6)
    True

Loads made in code, as the ``[[load]]`` tables make them (H: the stroke, m)::

    >>> H = velplan.stroke(mech).H
    >>> made = [vf.constant_force(mech, "B", fx=100.0), vf.constant_moment(mech, "2", 5.0),
    ...         vf.press_load(mech, 1000.0, 0.5 * H, 0.1 * H),
    ...         vf.table_force(mech, [0.0, 6.3], [0.0, 100.0], point="B", link="3", name="T"),
    ...         vf.indicator_force(mech, 0.1, [0.0, H], [1e5, 0.0])]
    >>> made_acts = vf.load_actions(made, kin)
    >>> [f.label for f in made_acts.forces], [m.label for m in made_acts.moments]
    (['F', 'P', 'T', 'Fg'], ['M'])
    >>> vf.press_load(mech, 1000.0, H, 0.1)
    Traceback (most recent call last):
    ...
    velplan.errors.MechanismError: load 'P': b1 + b2 = 0.2 m exceeds the stroke H = 0.1 m
    >>> vf.cutting_force(velplan.load("shaper"), 1400.0, start=0.9, end=0.1)
    Traceback (most recent call last):
    ...
    velplan.errors.MechanismError: load 'Fc': start and end must satisfy 0 ≤ start < end ≤ 1, not 0.9 and 0.1

A class III triad's polygon is closed through Assur's special point, each lead's outer
reaction split along and across it::

    >>> tri = velplan.load("triad-press")
    >>> tkin = velplan.solve(tri, velplan.positions(tri, 2))
    >>> poly = vf.kinetostatics(tri, tkin, vf.mechanism_actions(tri, tkin)).polygons["3-2-4-5"]
    >>> isinstance(poly, vf.TriadForcePolygon), poly.pair, all(isinstance(a, vf.LeadForces) for a in poly.leads)
    (True, (0, 2), True)
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
    "power_balancing_moment", "powers", "press_load", "static_moment", "table_force", "zhukovsky_lever",
]
