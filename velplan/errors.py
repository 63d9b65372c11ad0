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


def deprecated(func, old: str, new: str | None = None):
    """``func`` under its former name ``old``: each call warns (`DeprecationWarning` naming the
    new name, by default ``func``'s) and then calls it. Renamed things keep such an alias for
    one release.

    >>> import warnings
    >>> def twice(x): return 2 * x
    >>> double = deprecated(twice, "double")
    >>> with warnings.catch_warnings(record=True) as w:
    ...     warnings.simplefilter("always")
    ...     double(2), str(w[0].message)
    (4, 'double is deprecated; use twice')
    """
    import functools
    import warnings

    new = new or (f"{func.__module__}.{func.__qualname__}" if "." in old else func.__qualname__)

    @functools.wraps(func)
    def alias(*args, **kwargs):
        warnings.warn(f"{old} is deprecated; use {new}", DeprecationWarning, stacklevel=2)
        return func(*args, **kwargs)

    alias.__doc__ = f"Deprecated alias of `{new}` (removed in the next release)."
    return alias
