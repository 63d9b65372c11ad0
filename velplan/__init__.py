"""velplan: velocity and acceleration plans of planar linkages by graphical construction,
checked against an analytic solver.

The friendly layer::

    >>> import velplan
    >>> mech = velplan.load("shaper")
    >>> kin = velplan.solve(mech, [0.0, 1.0])
    >>> kin.velocity("F").shape
    (2, 2)
"""

from velplan.analysis.extremes import extremes, positions, reference_angle, stroke
from velplan.analysis.solver import Kinematics, solve, transfer_functions
from velplan.errors import (
    AssemblyError,
    MechanismError,
    ScaleError,
    SingularPositionError,
    TableError,
    VelplanError,
)
from velplan.mechanism.loader import example_names, load, loads
from velplan.mechanism.model import Mechanism
from velplan.mechanism.structure import analyse

__all__ = [
    "AssemblyError", "Kinematics", "Mechanism", "MechanismError", "ScaleError",
    "SingularPositionError", "TableError", "VelplanError", "analyse", "example_names",
    "extremes", "load", "loads", "positions", "reference_angle", "solve", "stroke",
    "transfer_functions",
]
__version__ = "0.1.0"
