"""The dynamics as a JSON document and as a text table (the ``velplan dynamics`` contract).

Speeds are signed like the crank's ω (sense × magnitude); moments are positive when they drive;
``phi_deg`` is the absolute crank angle, ``travel_deg`` and ``phi_omega_*_deg`` the crank
travel from position 1 in the sense of rotation.
"""

from __future__ import annotations

import math

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.dynamics.analysis import Dynamics

POSITION_KEYS = ("phi_deg", "travel_deg", "omega", "epsilon", "t", "J_red", "J_red_prime", "J_total",
                 "M_red", "M_drive", "M_sum", "A_drive", "A_resist", "A_sum")


def _num(x):
    x = float(x)
    return x if math.isfinite(x) else None


def to_dict(d: Dynamics, n: int = 12, drive=None) -> dict:
    """The JSON document (see docs/format.md, ``[dynamics]``); ``drive`` (a
    `velplan.dynamics.drive.Drive`, by default the file's) adds the drive selection."""
    s = d.sense
    doc = {"mechanism": d.mechanism.name, "mode": "run" if d.run else "periodic" if d.periodic else "steady",
           "sense": "counter-clockwise" if s > 0 else "clockwise",
           "driving_moment": _num(d.driving),
           "constant_inertias": {name: _num(j) for name, j in d.constants},
           "J_declared": _num(d.declared), "inertia_used": _num(d.inertia),
           "cycle_work": {k: _num(v) for k, v in d.profile.cycle_work().items()},
           "motor": {"kind": d.spec.motor.kind, "ratio": d.spec.motor.ratio, "efficiency": d.spec.motor.efficiency}}
    fly = d.flywheel
    if fly is not None:
        w = fly.diagram
        doc["delta_required"] = fly.delta
        doc["flywheel"] = {"exact": _num(fly.exact), "mertsalov": _num(fly.mertsalov),
                           "wittenbauer": _num(fly.wittenbauer), "wittenbauer_drawn": _num(w.inertia_drawn),
                           "mertsalov_difference_percent": _num(100 * fly.mertsalov_difference)}
        doc["flywheel_added"] = _num(fly.added)
        doc["flywheel_ratio"] = fly.ratio
        doc["flywheel_on_shaft"] = _num(fly.on_shaft)
        doc["wittenbauer"] = {"mu_J": w.mu_J, "mu_T": w.mu_T, "psi_max_deg": w.psi_max_deg,
                              "psi_min_deg": w.psi_min_deg, "intercept_max": w.intercept_max,
                              "intercept_min": w.intercept_min, "segment_mm": w.segment_mm,
                              "segment_drawn_mm": w.segment_drawn_mm, "precision_mm": w.precision,
                              "touch_max": {"J": w.touch_max[0], "dT": w.touch_max[1],
                                            "travel_deg": math.degrees(w.touch_max[2])},
                              "touch_min": {"J": w.touch_min[0], "dT": w.touch_min[1],
                                            "travel_deg": math.degrees(w.touch_min[2])}}
        if fly.dimensions is not None:
            dm = fly.dimensions
            doc["flywheel_dimensions"] = {"shape": dm.shape, "diameter": dm.diameter, "width": dm.width,
                                          "inner_diameter": dm.inner, "outer_diameter": dm.outer,
                                          "density": dm.density, "mass": dm.mass, "inertia": dm.inertia,
                                          "inertia_required": dm.required}
    else:
        doc["flywheel"] = None
    if d.run is not None:
        r = d.run
        doc.update({"time": r.time, "travel_deg": math.degrees(r.travel), "omega_start": s * r.omega_start,
                    "omega_end": s * r.omega_end, "omega_min": s * r.omega_min, "omega_max": s * r.omega_max,
                    "phi_omega_min_deg": math.degrees(r.theta_min)})
    else:
        m = d.steady if d.steady is not None else d.periodic
        doc.update({"omega_mean": s * m.omega_mean, "delta": m.delta, "omega_max": s * m.omega_max,
                    "omega_min": s * m.omega_min, "phi_omega_max_deg": math.degrees(m.theta_max),
                    "phi_omega_min_deg": math.degrees(m.theta_min), "period": m.period})
        if d.periodic is not None:
            doc["omega_start"] = s * d.periodic.omega_start
            doc["periodic_residual"] = d.periodic.residual
    doc["error"] = {k: _num(v) for k, v in d.errors.items()}
    drive = d.drive if drive is None else drive
    if drive is not None:
        doc["drive"] = {k: (_num(v) if isinstance(v, float) else v) for k, v in drive.to_dict().items()}
    tb = d.table(n)
    extra = [k for k in tb if k.startswith("M_") and k not in POSITION_KEYS]
    doc["positions"] = [{"position": position_number(i), **{k: _num(tb[k][i]) for k in (*POSITION_KEYS, *extra)}}
                        for i in range(len(tb["omega"]))]
    return doc


def to_table(d: Dynamics, n: int = 12, drive=None) -> str:
    """A text table: the summary, then one row per position."""
    doc = to_dict(d, n, drive)
    lines = [f"{doc['mechanism']}: machine dynamics ({doc['mode']}, crank turns {doc['sense']})"]
    fmt = lambda v: "—" if v is None else f"{v:.6g}"  # noqa: E731
    for key in ("driving_moment", "J_declared", "inertia_used", "omega_mean", "delta", "delta_required",
                "omega_max", "phi_omega_max_deg", "omega_min", "phi_omega_min_deg", "period", "time",
                "travel_deg", "omega_start", "omega_end", "flywheel_added", "flywheel_on_shaft"):
        if key in doc:
            lines.append(f"  {key:<20} {fmt(doc[key])}")
    if doc.get("flywheel"):
        f = doc["flywheel"]
        lines.append(f"  flywheel J_I, kg·m²: exact {fmt(f['exact'])}, Mertsalov {fmt(f['mertsalov'])} "
                     f"({f['mertsalov_difference_percent']:+.3g} %), Wittenbauer {fmt(f['wittenbauer'])} "
                     f"(drawn {fmt(f['wittenbauer_drawn'])})")
    err = doc["error"]
    names = (("driving_moment", "M_drive", "N·m"), ("flywheel_exact", "J_I", "kg·m²"), ("omega", "ω", "rad/s"),
             ("period", "period", "s"), ("time", "time", "s"), ("travel", "travel", "rad"))
    lines.append("  estimated error: " + ", ".join(f"{sym} ±{err[k]:.2g} {unit}" for k, sym, unit in names
                                                    if err.get(k)))
    if "flywheel_dimensions" in doc:
        dm = doc["flywheel_dimensions"]
        lines.append(f"  flywheel {dm['shape']}: D = {dm['diameter'] * 1000:.0f} mm, b = {dm['width'] * 1000:.0f} mm, "
                     f"m = {dm['mass']:.4g} kg, J = {dm['inertia']:.5g} kg·m²")
    if "drive" in doc:
        dv, m = doc["drive"], doc["drive"]["motor"]
        lines.append(f"  drive: useful power max {fmt(dv['useful_power_max'])} W, mean "
                     f"{fmt(dv['useful_power_mean'])} W; spent {fmt(dv['spent_power'])} W (η = "
                     f"{dv['efficiency']:g}); required {fmt(dv['required_power'])} W (× {dv['reserve']:g})")
        lines.append(f"  motor {m['name']}: {m['power_kw']:g} kW, {m['nominal_rpm']:g} rpm "
                     f"({m['synchronous_rpm']:g} synchronous), rotor {m['rotor_inertia']:g} kg·m²; gear ratio "
                     f"u = {dv['gear_ratio']:.4g}; torques {fmt(dv['torques']['motor'])} / "
                     f"{fmt(dv['torques']['fast'])} / {fmt(dv['torques']['slow'])} N·m (motor / fast / slow "
                     f"shaft); δ with this motor {fmt(dv['delta'])}")
    cols = ("position", "phi_deg", "omega", "epsilon", "t", "J_red", "M_red", "M_sum")
    lines.append("".join(f"{c:>13}" for c in cols))
    for p in doc["positions"]:
        lines.append("".join(f"{p[c]:>13}" if c == "position" else f"{fmt(p[c]):>13}" for c in cols))
    return "\n".join(lines)


def plot(d: Dynamics, path: str, n: int = 360) -> None:
    """J_red, M_red (and driving), works and ω over the cycle (or run) to ``path`` (png/svg)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tb = d.table(n)
    x = tb["travel_deg"]
    fig, ax = plt.subplots(4, 1, figsize=(8, 10), sharex=True)
    ax[0].plot(x, tb["J_red"], label="J_red")
    ax[0].set_ylabel("J, kg·m²")
    ax[1].plot(x, tb["M_red"], label="M_red (loads, gravity)")
    ax[1].plot(x, tb["M_drive"], label="M_drive")
    ax[1].set_ylabel("M, N·m")
    for k in ("A_drive", "A_resist", "A_sum"):
        ax[2].plot(x, tb[k], label=k)
    ax[2].set_ylabel("A, J")
    ax[3].plot(x, tb["omega"], label="ω")
    ax[3].set_ylabel("ω, rad/s")
    ax[3].set_xlabel("crank travel from position 1, °")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(loc="best", fontsize=8)
    fig.suptitle(f"{d.mechanism.name}: machine dynamics")
    fig.tight_layout()
    from velplan.io import write_atomic  # noqa: F401  (the figure is written to a temporary then moved)
    import os
    import tempfile

    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=os.path.splitext(path)[1] or ".png", dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.unlink(tmp)
