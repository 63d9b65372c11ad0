"""The analytic kinematic solver: closed-form positions and analytic derivatives of every
point and link of a mechanism, vectorised over an array of crank angles.

This is the independent reference that the graphical plans are checked against. `solve` chooses
the engine: the numpy one (`velplan.analysis.blocks`, block by block) or the compiled one
(`velplan.analysis.compiled`); both fill a `Kinematics` (`velplan.analysis.kinematics`).
"""

from __future__ import annotations

import os
import sys
from typing import Iterable, Literal

import numpy as np

from velplan.analysis import blocks
from velplan.analysis.blocks import Outputs, check_closed, group_point, needed_items, solve_block
from velplan.analysis.kinematics import (SINGULAR_BOUND, WELL_CONDITIONED, Kinematics, group_lengths, length_scale,
                                         length_spread, transfer_functions, velocity_bound)
from velplan.analysis.prepared import Prepared, prepared
from velplan.mechanism.model import Crank, LinkPoint, Mechanism, Triad

__all__ = ["solve", "special_pair", "triad_tracks", "Kinematics", "SINGULAR_BOUND", "WELL_CONDITIONED",
           "group_lengths", "group_point", "length_scale", "length_spread", "needed_items",
           "transfer_functions", "velocity_bound"]


def solve(
    mech: Mechanism,
    phi,
    *,
    omega1=None,
    epsilon1=None,
    points: Iterable[str] | None = None,
    order: Literal[0, 1, 2] = 2,
    on_failure: Literal["nan", "raise"] = "nan",
    engine: Literal["numpy", "compiled", "auto"] = "auto",
) -> Kinematics:
    """Solve ``mech`` at crank angles ``phi`` (rad, scalar or 1-D array).

    Parameters
    ----------
    mech : Mechanism
    phi : float or array_like
        Absolute crank angles, rad.
    omega1, epsilon1 : float or array_like, optional
        The crank's angular velocity (rad/s) and acceleration (rad/s²): one value, or one per
        angle (a computed motion ω(φ), ε(φ)); the file's constant speed when omitted.
    points : iterable of str, optional
        Only these points (and what they depend on) are solved: groups and link points that
        none of them needs are skipped and absent from the result.
    order : {0, 1, 2}
        Highest derivative computed: positions only (0), + velocities (1), + accelerations (2).
        What is not computed is absent (`Kinematics.velocity` etc. raise naming the order).
    on_failure : {"nan", "raise"}
        ``"nan"``: positions where a group cannot close hold NaN and ``valid`` is False there.
        ``"raise"``: raise `AssemblyError` naming the group, the point and the crank angle.
    engine : {"numpy", "compiled", "auto"}
        ``"numpy"``: whole arrays, in cache-sized blocks. ``"compiled"``: the same closed forms
        run per position by numba on every core (``pip install velplan[fast]``; the first call
        on a machine compiles for ≈ 10 s, later processes load it in ≈ 0.05 s after numba's own
        import, itself ≈ 0.3 s); ``points=`` and ``order=`` reach its kernel, which writes nothing else. ``"auto"``:
        compiled when numba is installed and either the kernel is loaded already or there are
        at least `AUTO_COMPILED` angles. Both give the same values to round-off.

    Notes
    -----
    Each group is closed in its own closed form (circle–circle, circle–line, line–line),
    and its velocities and accelerations are the exact time derivatives of those closures:
    two linear equations per group, solved by Cramer's rule.

    A motion given per angle is applied to the unit-speed solution (ω1 = 1, ε1 = 0, whose
    velocities are the analogues r′ = dr/dφ and accelerations r″): v = ω·r′,
    a = ω²·r″ + ε·r′, and likewise for the links' ω, ε and the slides' ṡ, s̈.
    """
    if on_failure not in ("nan", "raise"):
        raise ValueError(f"on_failure must be 'nan' or 'raise', not {on_failure!r}")
    if order not in (0, 1, 2):
        raise ValueError(f"order must be 0, 1 or 2, not {order!r}")
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    if phi.ndim != 1:
        raise ValueError(f"phi must be a scalar or a 1-D array, not shape {phi.shape}")
    crank = mech.crank
    w1 = _crank_rate(crank.omega if omega1 is None else omega1, "omega1", phi.shape[0])
    e1 = _crank_rate(crank.epsilon if epsilon1 is None else epsilon1, "epsilon1", phi.shape[0])
    if isinstance(w1, np.ndarray) or isinstance(e1, np.ndarray):
        unit = solve(mech, phi, omega1=1.0, epsilon1=0.0, points=points, order=order,
                     on_failure=on_failure, engine=engine)
        return unit.at_speed(w1, e1)
    return _solve_scalar_rate(prepared(mech, points), mech, phi, w1, e1, order, on_failure, engine)


def _solve_scalar_rate(prep: Prepared, mech, phi, w1, e1, order, on_failure, engine) -> Kinematics:
    """`solve` at one crank speed and acceleration, solved about the crank's pivot (velocities
    do not lose digits to |x|) and shifted back."""
    if engine not in ("numpy", "compiled", "auto"):
        raise ValueError(f"engine must be 'numpy', 'compiled' or 'auto', not {engine!r}")
    if engine == "compiled" or (engine == "auto" and _auto_compiled(phi.shape[0])):
        kin = _solve_compiled(prep, phi, w1, e1, order, on_failure, engine, mech)
        if kin is not None:
            return kin
    w1o, e1o = (w1 if order >= 1 else 0.0), (e1 if order >= 2 else 0.0)
    n = phi.shape[0]
    # cache-sized blocks solved straight into preallocated outputs (their layout known from an
    # earlier solve; a few positions are copied in one assignment per kind: `Outputs.write`)
    out = None if prep.outputs is None else Outputs(None, None, n, order, prep.outputs)
    tracks = prep.tracks(solve)
    for start in range(0, max(n, 1), blocks.BLOCK):
        block = phi[start:start + blocks.BLOCK]
        where = slice(start, start + block.shape[0])
        sink = out.sink(where) if out is not None and block.shape[0] > blocks.ONE_ASSIGNMENT else None
        st, conditions = solve_block(prep.local, block, w1o, e1o, prep.scale, on_failure, prep.items, tracks, sink)
        if out is None:
            out = Outputs(st, conditions, n, order, prep.outputs)
            prep.outputs = out.index
        out.write(st, conditions, where)
    out.shift(prep.shift)
    kin = out.kinematics(mech, phi, w1, e1, st)
    if engine == "auto":  # time the compiled engine could have saved, as modelled
        _NUMPY_SECONDS[0] += NUMPY_COST[0] + NUMPY_COST[1] * len(prep.items) * n
    return kin


def _compiled():
    """The compiled engine's module, imported when an engine choice needs it (it brings
    hashlib and inspect, and numba only when it runs)."""
    from velplan.analysis import compiled

    return compiled


def _crank_rate(value, what: str, n: int):
    """A crank rate as a float, or as an (n,) array when it varies with the angle."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return float(arr)
    if arr.ndim != 1 or arr.shape[0] != n:
        raise ValueError(f"{what} must be a scalar or have one value per angle ({n}), not shape {arr.shape}")
    return arr








AUTO_COMPILED = 2_000_000
"""From this many angles one ``engine="auto"`` call loads the compiled engine (≈ 0.35 s: numba's
import and the kernel from its disk cache; it saves ≈ 0.4 µs per angle)."""
NUMPY_COST = (5e-5, 2e-7)
"""A numpy solve's cost as modelled, s: per call, and per angle and group (this 2-core machine,
`benchmarks/bench_small.py`: four-bar 12 angles ≈ 45 µs; 10⁵ angles ≈ 0.5 µs each)."""
_NUMPY_SECONDS = [0.0]
"""Time this process's ``engine="auto"`` calls have spent in the numpy engine, s, as modelled by
`NUMPY_COST` — not measured, so that which engine solves (and the last bits of what is printed)
does not depend on the machine's load."""
_AUTO_ON = [False]


LOAD_AT_LEAST = {"kernel": 0.05, "numba": 0.35}
"""The least loading the compiled kernel costs (s; `compiled.LOAD_SECONDS`), numba imported already
or not: below it "auto" does not even import the compiled engine's module."""


def _auto_compiled(n: int) -> bool:
    """Whether an ``engine="auto"`` call of ``n`` angles runs compiled: numba installed, and the
    kernel loaded already, or ``n`` at least `AUTO_COMPILED`, or the time spent in the numpy
    engine so far at least what loading the kernel costs (`compiled.load_cost`) — a process that
    solves little never pays for loading it, one that solves much pays at most twice."""
    if _AUTO_ON[0]:
        return True
    spent, least = _NUMPY_SECONDS[0], LOAD_AT_LEAST["kernel" if "numba" in sys.modules else "numba"]
    if n < AUTO_COMPILED and spent < least and "velplan.analysis.compiled" not in sys.modules:
        return False  # nothing loaded, nothing worth loading: not even the module
    if os.environ.get("NUMBA_DISABLE_JIT", "0") not in ("", "0"):
        return False  # the kernel would run as plain Python: numpy is far faster
    c = _compiled()
    if not c.available():
        return False
    if c.loaded() or n >= AUTO_COMPILED or (spent >= least and spent >= c.load_cost()):
        _AUTO_ON[0] = True
    return _AUTO_ON[0]


def _solve_compiled(prep: Prepared, phi, w1, e1, order, on_failure, engine, mech) -> Kinematics | None:
    """The compiled engine's solution of ``mech`` (prepared as ``prep``), or None where it does not
    apply: a class III group without a branch the kernel can follow (with a warning when
    ``engine="compiled"`` was asked for), solved by the numpy engine instead. A class III group's
    angles the kernel finds ambiguous are solved again by the numpy engine."""
    compiled = _compiled()
    tracks = prep.tracks(solve) if prep.class_iii else None
    lay = prep.layout(tracks)
    if lay.triad is not None:
        if engine == "compiled":
            import warnings

            warnings.warn(f"engine='compiled' does not cover class III groups (group {lay.triad!r}); "
                          "solving with the numpy engine", stacklevel=4)
        return None
    kin = compiled.solve(lay, mech, phi, w1, e1, order, shift=prep.shift, tracks=tracks,
                         again=lambda idx: _solve_scalar_rate(prep, mech, phi[idx], w1, e1, order, "nan", "numpy"))
    if on_failure == "raise" and not kin.valid.all():
        for item in lay.items:  # the first group, in solving order, that fails to close
            if not isinstance(item, (Crank, LinkPoint)):
                closed = ~np.isnan(kin.condition[:, kin.group_index[item.name]])
                check_closed(item, closed, phi, on_failure)
    return kin


def special_pair(mech: Mechanism, g: Triad) -> tuple[int, int]:
    """The two leads (indices 0…2) of the triad ``g`` of ``mech`` whose lines give Assur's
    special point: the file's ``pair``, else the pair whose lines cross at the largest smallest
    angle over the tracked branch."""
    if g.pair is not None:
        return g.pair
    prep = prepared(mech)
    return prep.tracks(solve)[prep.local.groups[mech.groups.index(g)].name].pair


def triad_tracks(mech: Mechanism, items) -> dict:
    """Each class III group of ``items``: its branch followed over the turn (`velplan.analysis.triad.track`),
    for the numpy engine's blocks."""
    triads = [g for g in items if getattr(g, "tracked", False)]
    if not triads:
        return {}
    from velplan.analysis import triad

    return {g.name: triad.track(triad.upstream(mech, g), g, solve) for g in triads}
