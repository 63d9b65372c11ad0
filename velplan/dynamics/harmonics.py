"""Seed 004's question: how well does the press load's Fourier series with N harmonics stand in
for the exact parabola in the machine's motion? The dynamics is computed with the exact load
and with each N, at the same constant inertia (the flywheel sized for the exact load, when a δ
is required), and ω and t are compared at the same crank travel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from velplan.dynamics.analysis import Dynamics, dynamics_analysis
from velplan.dynamics.spec import ConstantInertia, parse_dynamics
from velplan.errors import VelplanError
from velplan.forces.loads import PressLoad
from velplan.mechanism.model import Mechanism


@dataclass(frozen=True)
class HarmonicRow:
    """The motion with N harmonics against the exact load's.

    Attributes
    ----------
    harmonics : int
    load_max, load_rms : float
        max |P − P_N| and its RMS over a turn, N (the largest of the press loads).
    driving : float
        Constant driving moment, N·m (steady state).
    omega_max_diff : float
        max |ω_N − ω| over the compared travel, rad/s.
    omega_rel_diff : float
        The same over the exact motion's mean |ω|.
    time_diff : float
        max |t_N − t| at the same travel, s (how far φ(t) runs ahead or behind).
    delta : float
        δ of the motion with N harmonics (nan for a run).
    """

    harmonics: int
    load_max: float
    load_rms: float
    driving: float
    omega_max_diff: float
    omega_rel_diff: float
    time_diff: float
    delta: float


def _with(loads: Sequence, harmonics: int | None) -> tuple:
    return tuple(replace(ld, harmonics=harmonics) if isinstance(ld, PressLoad) else ld for ld in loads)


def compare_harmonics(mech: Mechanism, loads: Sequence, ns: Sequence[int], *, delta: float | None = None,
                      samples: int = 2048) -> tuple[Dynamics, list[HarmonicRow]]:
    """(the exact load's dynamics, a row per N of ``ns``) — see the module's docstring.

    ``samples`` travels (evenly over the cycle, or over the run) are compared."""
    press = [ld for ld in loads if isinstance(ld, PressLoad)]
    if not press:
        raise VelplanError(f"--harmonics: {mech.name} has no press load ([[load]] kind = \"press\")")
    bad = [n for n in ns if isinstance(n, bool) or not isinstance(n, int) or n < 1]
    if bad or not ns:
        raise VelplanError(f"--harmonics: give whole numbers ≥ 1, not {bad[0] if bad else 'nothing'!r}")
    spec = parse_dynamics(mech)
    ref = dynamics_analysis(mech, _with(loads, None), spec=spec, delta=delta)
    same = spec
    if ref.flywheel is not None:  # every N turns the exact load's flywheel, not its own
        added = ref.inertia - ref.declared
        inertias = spec.inertias + ((ConstantInertia("flywheel", added, 1.0),) if added > 0 else ())
        same = replace(spec, delta=None, inertias=inertias)
    end = ref.run.travel if ref.run is not None else ref.profile.cycle
    rows = []
    for n in ns:
        d = dynamics_analysis(mech, _with(loads, n), spec=same)
        stop = min(end, d.run.travel) if d.run is not None else end
        theta = np.linspace(0.0, stop, samples + 1)
        t0, w0, _ = ref.speed_at_travel(theta)
        t1, w1, _ = d.speed_at_travel(theta)
        errs = [replace(ld, harmonics=n).approximation_error(n) for ld in press]
        st = d.steady or d.periodic
        rows.append(HarmonicRow(
            n, max(e[0] for e in errs), max(e[1] for e in errs), d.driving,
            float(np.max(np.abs(w1 - w0))), float(np.max(np.abs(w1 - w0)) / np.mean(np.abs(w0))),
            float(np.max(np.abs(t1 - t0))), float(st.delta) if st is not None else math.nan))
    return ref, rows


def harmonics_table(ref: Dynamics, rows: Sequence[HarmonicRow]) -> str:
    """The comparison as a text table."""
    head = (f"{'N':>4} {'max|P-P_N|, N':>14} {'RMS, N':>10} {'M_d, N·m':>11} {'max|Δω|, rad/s':>15} "
            f"{'max|Δω|/ω':>10} {'max|Δt|, s':>11} {'δ':>9}")
    st = ref.steady or ref.periodic
    lines = [f"exact parabola: M_d = {ref.driving:.6g} N·m"
             + (f", δ = {st.delta:.6g}" if st is not None else f", run of {ref.run.time:.6g} s"), head]
    for r in rows:
        lines.append(f"{r.harmonics:>4} {r.load_max:>14.6g} {r.load_rms:>10.4g} {r.driving:>11.6g} "
                     f"{r.omega_max_diff:>15.4g} {r.omega_rel_diff:>10.3g} {r.time_diff:>11.4g} "
                     f"{r.delta:>9.5g}")
    return "\n".join(lines)
