"""Diagrams of the force analysis: the balancing moment over a revolution, and seed 004's
press load with its Fourier approximations. matplotlib is imported inside the functions only.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Sequence

import numpy as np

from velplan.errors import VelplanError
from velplan.io import write_atomic


def _figure(width: float = 8.0, height: float = 4.5):
    from matplotlib.figure import Figure  # lazily: nothing below render imports matplotlib at import time

    return Figure(figsize=(width, height), layout="constrained")


def _save(fig, path) -> Path:
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ("png", "svg"):
        raise VelplanError(f"cannot plot to {path}: the file must end in .png or .svg, not {path.suffix or '(none)'}")
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, metadata={"Date": None} if fmt == "svg" else None)
    return write_atomic(path, buf.getvalue())


def plot_balancing_moment(res, path, *, sense: float = 1.0) -> dict[str, np.ndarray]:
    """Plot M_b(φ) over a revolution by the three methods, with its mean, to ``path`` (.png/.svg).

    Parameters
    ----------
    res : ForceAnalysis
        The force analysis over a turn from position 1 (`velplan.study.Study.turn_forces`).
    sense : float
        +1 when the crank turns counter-clockwise, −1 otherwise.

    Returns
    -------
    dict
        ``"turn_deg"`` (crank turn from position 1, deg), ``"kinetostatics"``, ``"lever"``,
        ``"power"`` (N·m) — the plotted data.
    """
    mech = res.kinematics.mechanism
    phi = res.kinematics.phi
    turn = np.degrees(sense * (phi - phi[0]))
    data = {"turn_deg": turn, **res.balancing_moments}
    fig = _figure()
    ax = fig.add_subplot()
    styles = {"kinetostatics": ("-", 2.0), "lever": ("--", 1.2), "power": (":", 1.2)}
    for name, (ls, lw) in styles.items():
        ax.plot(turn, data[name], ls, lw=lw, color="black", label=f"M_b, {name}")
    whole = turn[-1] - turn[0] >= 359.999  # a closed turn repeats its first angle: count it once
    mean = float(np.nanmean(data["kinetostatics"][:-1] if whole else data["kinetostatics"]))
    ax.axhline(mean, color="grey", lw=0.8, ls="-.", label=f"mean {mean:.4g} N·m")
    ax.set_xlabel("crank turn from position 1, °")
    ax.set_ylabel("balancing moment M_b, N·m")
    ax.set_title(f"{mech.title or mech.name}: balancing moment")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize="small")
    _save(fig, path)
    return data


def plot_press_load(load, path, *, harmonics: Sequence[int] = tuple(range(1, 11)),
                    samples: int = 1441) -> dict[str, np.ndarray]:
    """Plot a `PressLoad`'s parabola and its truncated Fourier series to ``path`` (.png/.svg).

    Returns
    -------
    dict
        ``"phi_deg"``, ``"exact"`` and ``"N=<k>"`` for each harmonic count (N), plus
        ``"max_error"`` and ``"rms_error"`` (N) per harmonic count, in order.
    """
    phi = np.linspace(0.0, 2 * np.pi, samples)
    data: dict[str, np.ndarray] = {"phi_deg": np.degrees(phi), "exact": load.exact(phi)}
    errors = [load.approximation_error(h) for h in harmonics]
    fig = _figure(9.0, 5.0)
    ax = fig.add_subplot()
    ax.plot(data["phi_deg"], data["exact"] / 1e3, color="black", lw=2.0, label="parabola (exact)")
    shades = np.linspace(0.75, 0.15, len(harmonics))
    for h, shade in zip(harmonics, shades):
        data[f"N={h}"] = load.fourier(h)(phi)
        ax.plot(data["phi_deg"], data[f"N={h}"] / 1e3, color=str(shade), lw=0.9, label=f"N = {h}")
    data["max_error"] = np.array([e[0] for e in errors])
    data["rms_error"] = np.array([e[1] for e in errors])
    ax.set_xlabel("crank angle φ, °")
    ax.set_ylabel("load on the slider P, kN")
    ax.set_title(f"press load {load.name}: P_max = {load.p_max / 1e3:g} kN and its Fourier series")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize="x-small", ncol=2)
    _save(fig, path)
    return data
