"""The exception hierarchy: every error velplan raises on purpose is a `VelplanError`.

Messages are one line and name the element and the value at fault, so that the CLI can
print them as they are.
"""

from __future__ import annotations


class VelplanError(Exception):
    """Base of all velplan errors; its message is a complete one-line explanation."""


class MechanismError(VelplanError, ValueError):
    """A mechanism description is invalid (unknown name, bad length, malformed file)."""


class AssemblyError(VelplanError):
    """A group cannot be assembled (closed) at some crank angle.

    Attributes
    ----------
    group : str
        Name of the Assur group that fails to close.
    point : str
        The point the group was solving for.
    phi_deg : float
        Crank angle in degrees at which it fails.
    """

    def __init__(self, message: str, *, group: str = "", point: str = "", phi_deg: float = float("nan")):
        super().__init__(message)
        self.group = group
        self.point = point
        self.phi_deg = phi_deg


class SingularPositionError(VelplanError):
    """A result was refused because the position is too close to singular.

    Attributes
    ----------
    condition : float
        The condition estimate (sine of the angle between two intersecting lines, in [0, 1]).
    """

    def __init__(self, message: str, *, condition: float = float("nan")):
        super().__init__(message)
        self.condition = condition


class ScaleError(VelplanError, ValueError):
    """A drawing scale is invalid or the drawing cannot fit the available area."""


class TableError(VelplanError, ValueError):
    """A table of measured values (CSV) is malformed or names unknown quantities."""
