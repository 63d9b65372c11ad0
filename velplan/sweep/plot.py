"""Plots of a sweep (matplotlib, written as SVG and optionally PNG): histograms of the figures
of merit, each key's share of their spread, and the K–γ_min scatter of the variants."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from velplan.io import write_atomic
from velplan.sweep.run import SweepResult, sensitivities

SHOWN = ("H", "K", "gamma_min_deg", "v_max", "a_max", "theta_deg")
LABELS = {"H": "stroke H", "K": "time ratio K", "gamma_min_deg": "γ_min, deg", "v_max": "peak |v|",
          "a_max": "peak |a|", "theta_deg": "θ, deg"}


def _figure(nrows=1, ncols=1, size=(6.4, 4.0)):
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    plt.rcParams["svg.hashsalt"] = "velplan"  # the same sweep, the same bytes
    return plt.subplots(nrows, ncols, figsize=size, squeeze=False)


def _save(fig, path: Path, png: bool) -> list[Path]:
    import matplotlib.pyplot as plt

    out = []
    for ext in ("svg", "png") if png else ("svg",):
        buf = io.BytesIO()
        kw = {"metadata": {"Date": None}} if ext == "svg" else {"dpi": 120, "metadata": {"Software": None}}
        fig.savefig(buf, format=ext, **kw)
        out.append(write_atomic(path.with_suffix(f".{ext}"), buf.getvalue()))
    plt.close(fig)
    return out


def histograms(res: SweepResult, path: Path, png: bool = False) -> list[Path]:
    """One histogram per figure of merit over the variants that close, the nominal marked."""
    names = [n for n in SHOWN if n in res.figures]
    fig, axes = _figure(2, 3, (11, 6))
    ok = res.ok
    for ax, name in zip(axes.flat, names):
        a = res.figures[name][ok & np.isfinite(res.figures[name])]
        if a.size:
            ax.hist(a, bins=min(60, max(10, int(np.sqrt(a.size)))), color="#4c78a8")
        nom = res.nominal.get(name)
        if nom is not None and np.isfinite(nom):
            ax.axvline(nom, color="#e45756", lw=1.2, label="nominal")
        ax.set_title(LABELS.get(name, name), fontsize=10)
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.xaxis.set_major_locator(__import__("matplotlib.ticker").ticker.MaxNLocator(4))
        ax.tick_params(labelsize=8)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.suptitle(f"{res.mechanism}: {res.mode}, {int(ok.sum())} of {len(res)} variants close", fontsize=11)
    fig.tight_layout()
    return _save(fig, path, png)


def sensitivity_bars(res: SweepResult, path: Path, png: bool = False) -> list[Path]:
    """Each key's share of each figure's spread, as horizontal stacked bars."""
    sens = sensitivities(res)
    names = [n for n in SHOWN if n in sens]
    keys = list(res.values)
    fig, axes = _figure(1, 1, (9, 0.5 * len(names) + 2.2))
    ax = axes[0, 0]
    left = np.zeros(len(names))
    cmap = __import__("matplotlib").colormaps["tab20"]
    for k, key in enumerate(keys):
        share = np.array([100 * sens[n].get(key, 0.0) for n in names])
        if np.all(share < 0.5):
            continue
        ax.barh(range(len(names)), share, left=left, color=cmap(k % 20), label=key)
        left += share
    ax.set_yticks(range(len(names)), [LABELS.get(n, n) for n in names])
    ax.set_xlim(0, 100)
    ax.set_xlabel("share of the spread, % (linear fit)")
    ax.invert_yaxis()
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(f"{res.mechanism}: sensitivities", fontsize=11)
    fig.tight_layout()
    return _save(fig, path, png)


def scatter(res: SweepResult, path: Path, png: bool = False) -> list[Path]:
    """K against γ_min of every variant that closes, coloured by the stroke H."""
    fig, axes = _figure(1, 1, (6.4, 4.8))
    ax = axes[0, 0]
    ok = res.ok
    if "K" in res.figures:
        pts = ax.scatter(res.figures["gamma_min_deg"][ok], res.figures["K"][ok], c=res.figures["H"][ok],
                         s=4, cmap="viridis", rasterized=bool(ok.sum() > 5000))
        fig.colorbar(pts, ax=ax, label="H")
        if np.isfinite(res.nominal.get("K", np.nan)):
            ax.plot([res.nominal["gamma_min_deg"]], [res.nominal["K"]], "x", color="#e45756", ms=9, label="nominal")
            ax.legend(fontsize=8)
    ax.set_xlabel("γ_min, deg")
    ax.set_ylabel("K")
    ax.ticklabel_format(useOffset=False)
    ax.set_title(f"{res.mechanism}: K against γ_min", fontsize=11)
    fig.tight_layout()
    return _save(fig, path, png)


def plot_all(res: SweepResult, directory: str | Path, png: bool = False) -> list[Path]:
    """hist, sensitivity and scatter figures into ``directory`` (SVG, and PNG with ``png``)."""
    d = Path(directory)
    out = histograms(res, d / "sweep-hist", png) + scatter(res, d / "sweep-scatter", png)
    if len(res.values) > 0 and res.ok.sum() > len(res.values) + 1:
        out += sensitivity_bars(res, d / "sweep-sensitivity", png)
    return out
