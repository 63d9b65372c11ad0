"""velplan: velocity and acceleration plans of planar linkages by graphical construction,
checked against an analytic solver.

The friendly layer::

    >>> import velplan
    >>> study = velplan.Study("shaper")              # 12 positions at the file's ω1
    >>> study.kinematics.velocity("F").shape
    (12, 2)
    >>> study.plan("acceleration").epsilons["3"].shape
    (12,)
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
    "SingularPositionError", "Study", "TableError", "VelplanError", "analyse", "example_names",
    "extremes", "load", "loads", "positions", "reference_angle", "solve", "stroke",
    "transfer_functions",
]
__version__ = "0.1.0"


def __getattr__(name: str):
    # the study pulls in the plans and the chord method: imported on first use only
    if name == "Study":
        from velplan.study import Study

        return Study
    raise AttributeError(f"module 'velplan' has no attribute {name!r}")
