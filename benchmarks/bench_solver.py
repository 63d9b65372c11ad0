"""Run time against error for every bundled example (issue 6).

For each example and method: the median wall time per position at 12, 360, 10⁴, 10⁵ and
10⁶ crank positions, and the worst error against the 50-digit reference of
``benchmarks/reference.py`` on 720 angles (0.5° apart). Methods:

* ``analytic``: ``velplan.solve`` (positions, velocities, accelerations of every point and link);
* ``central FD h=…``: central finite differences of velplan's positions in φ, several steps h;
* ``chord N``: the textbook chord method of graphical differentiation applied to the output's
  displacement diagram drawn at N = 12, 24, 72, 360 positions (velocity at the middle of each
  interval, acceleration at the nodes from the chords of the velocity diagram);
* ``plan exact`` and ``plan drafting p mm/p° @t mm``: velplan's velocity and acceleration plans
  (``velplan.plans.Plan``) constructed exactly, or with lengths rounded to p mm and directions
  to p° on a plan whose standard scale makes the longest velocity vector ≤ t mm (see the HOOK
  section; skipped with a note while ``velplan.plans`` has no plan API).

Errors are scaled: positions by the mechanism's length scale L (its largest length or ground
span), velocities by |ω1|·L, accelerations by ω1²·L, link ω and ε by |ω1| and ω1²; the worst
over all angles, points (coincident points excluded for the difference methods: their
position is a different material point at each angle) and components is reported.

Writes ``benchmarks/results/solver.md`` and ``benchmarks/results/solver_pareto.png``.

    python benchmarks/bench_solver.py            # everything (~5 min on 2 cores)
    python benchmarks/bench_solver.py --quick    # sizes up to 10⁴, a smoke test
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from _common import (RESULTS, SIZES, grid, load_average, machine_md, median_time, point_errors, scales, sci,
                     table, us, write)
import reference as R

import velplan  # noqa: E402
from velplan.analysis import compiled  # noqa: E402
from velplan.mechanism.model import RPP, PRP, RRP  # noqa: E402
from velplan.analysis.chord import differentiate  # noqa: E402

FD_STEPS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7)
CHORD_N = (12, 24, 72, 360)
DRAFT_PRECISIONS_MM = (0.1, 0.25, 0.5, 1.0)
LOAD = ["?"]


@dataclass
class Row:
    example: str
    method: str
    family: str
    times: dict[int, float] = field(default_factory=dict)  # n → seconds per position
    repeats: dict[int, int] = field(default_factory=dict)
    errors: dict[str, float] = field(default_factory=dict)  # pos/vel/acc/omega/eps
    note: str = ""

    def worst_derivative(self) -> float:
        vals = [v for k, v in self.errors.items() if k in ("vel", "acc", "omega", "eps")]
        return max(vals) if vals else float("nan")

    def pareto_time(self) -> float:
        """Seconds per position used on the Pareto plot: at the largest size measured."""
        return self.times[max(self.times)] if self.times else float("nan")


def time_sizes(row: Row, make, sizes) -> None:
    """Fill ``row.times`` with the median time per position of ``make(phi)`` at each size."""
    for n in sizes:
        phi = grid(n)
        t, r = median_time(lambda: make(phi), n, warmup=n < 1_000_000)  # warm by the sizes before
        row.times[n], row.repeats[n] = t / n, r


# --- analytic solver -------------------------------------------------------------------------

ENGINES = ("numpy", "compiled") if compiled.available() else ("numpy",)
"""velplan.solve's engines measured: the compiled one where numba is installed."""


def analytic(mech, ref, sizes, engine="numpy") -> Row:
    row = Row(mech.name, "analytic" if engine == "numpy" else f"analytic ({engine})", "analytic")
    kin = velplan.solve(mech, ref.phi, epsilon1=0.0, engine=engine)
    names = list(kin.point_index)
    row.errors = point_errors(ref, names, kin.positions, kin.velocities, kin.accelerations, mech=mech)
    lk = [ref.link(k) for k in kin.link_index]
    w = abs(mech.crank.omega)
    row.errors["omega"] = float(np.max(np.abs((kin.omegas - ref.links[0][:, lk, 1]) - ref.links[1][:, lk, 1])) / w)
    row.errors["eps"] = float(np.max(np.abs((kin.epsilons - ref.links[0][:, lk, 2]) - ref.links[1][:, lk, 2])) / w**2)
    time_sizes(row, lambda phi: velplan.solve(mech, phi, epsilon1=0.0, engine=engine), sizes)
    return row


# --- central finite differences of velplan's positions ----------------------------------------

def fd_derivatives(mech, phi: np.ndarray, h: float):
    """Velocities and accelerations by central differences of positions in φ (ε1 = 0)."""
    n = phi.shape[0]
    kin = velplan.solve(mech, np.concatenate([phi - h, phi, phi + h]), epsilon1=0.0)
    p = kin.positions
    m, c, q = p[:n], p[n:2 * n], p[2 * n:]
    w = mech.crank.omega
    vel = (q - m) * (w / (2 * h))
    acc = (q - 2 * c + m) * (w * w / (h * h))
    return kin.point_index, c, vel, acc


def finite_differences(mech, ref, sizes) -> list[Row]:
    skip = set(R.coincident_owner(mech))
    rows = []
    timed: dict[int, float] = {}
    reps: dict[int, int] = {}
    for n in sizes:  # the run time does not depend on h: time once
        phi = grid(n)
        t, r = median_time(lambda: fd_derivatives(mech, phi, 1e-4), 3 * n, warmup=n < 1_000_000)
        timed[n], reps[n] = t / n, r
    for h in FD_STEPS:
        index, pos, vel, acc = fd_derivatives(mech, ref.phi, h)
        names = [k for k in index if k not in skip]
        j = [index[k] for k in names]
        row = Row(mech.name, f"central FD h={h:g}", "finite differences", dict(timed), dict(reps))
        row.errors = point_errors(ref, names, None, vel[:, j], acc[:, j], mech=mech)
        row.note = "coincident points excluded" if skip else ""
        rows.append(row)
    return rows


# --- chord method (graphical differentiation of the output's displacement diagram) ------------

def output_series(mech):
    """(label, kind, extractor): the output's displacement from a Kinematics, and the reference
    (s, ṡ, s̈) at reference rows. kind "link": θ, ω, ε (rad…); "point": along its fixed guide (m…)."""
    out = mech.output
    if out is None:
        return None
    if out.link is not None:
        def disp(kin):
            return np.unwrap(kin.angle(out.link))

        def refs(ref, rows):
            j = ref.link(out.link)
            return ref.links[0][rows, j, 1] + ref.links[1][rows, j, 1], ref.links[0][rows, j, 2] + ref.links[1][rows, j, 2]

        return f"link {out.link} angle", "link", disp, refs
    guide = None
    for g in mech.groups:
        if isinstance(g, RRP) and out.point in (g.point,):
            guide = g.guide
        elif isinstance(g, RPP) and out.point in (g.coincident, g.origin_name):
            guide = g.guide
        elif isinstance(g, PRP) and out.point == g.point:
            guide = g.guides[0]
    if guide is None or guide.link != "0":
        return None  # the displacement diagram of a point on a moving guide is not drawn here
    u = np.array([np.cos(guide.angle), np.sin(guide.angle)])

    def disp(kin):
        return kin.position(out.point) @ u

    def refs(ref, rows):
        j = ref.point(out.point)
        v = (ref.vel[0][rows, j] + ref.vel[1][rows, j]) @ u
        a = (ref.acc[0][rows, j] + ref.acc[1][rows, j]) @ u
        return v, a

    return f"point {out.point} along its guide", "point", disp, refs


def chord(mech, ref, label_kind) -> list[Row]:
    label, kind, disp, refs = label_kind
    w = mech.crank.omega
    L, V, A = scales(mech)
    vs, as_ = (abs(w), w * w) if kind == "link" else (V, A)
    rows = []
    m = len(ref.phi)
    for N in CHORD_N:
        step = m // N
        nodes = np.arange(N) * step
        mids = nodes + step // 2
        phi = ref.phi[nodes]

        def run(phi=phi):
            kin = velplan.solve(mech, phi, epsilon1=0.0)
            _, v, a = differentiate(disp(kin), step=2 * np.pi / N)  # velplan's chord method
            return v * w, a * (w * w)

        v, a = run()
        rv, _ = refs(ref, mids)
        _, ra = refs(ref, nodes)
        row = Row(mech.name, f"chord N={N}", "chord method")
        row.errors = {"vel": float(np.max(np.abs(v - rv)) / vs), "acc": float(np.max(np.abs(a - ra)) / as_)}
        t, r = median_time(run, N)
        row.times[N], row.repeats[N] = t / N, r
        row.note = f"output only ({label}); velplan.analysis.chord"
        rows.append(row)
    return rows


# --- HOOK: exact and drafting velocity/acceleration plans (velplan.plans) ----------------------
# Uses the committed API: ``Plan.of(mech).evaluate(kin, kind=..., drafting=..., scale_v=...,
# scale_a=...)`` → PlanResult with ``vectors`` (point → (n, 2)), ``omegas``, ``epsilons``.
# Skipped with a printed note when velplan.plans has neither ``Plan`` nor ``velocity_plan``.
# If the API changes, only `_plan_api` and `_plan_evaluate` need adapting: the rest (errors,
# timing, table, plot) only wants (point names, velocities, accelerations, ω, ε dicts).

DRAFT_TARGETS_MM = (100.0, 50.0)
"""Plan scales tried in drafting mode: the standard scale that makes the longest velocity vector
at most this long (mm; the acceleration plan gets 1.2× as much, as velplan's default 100/120)."""


def _plan_api():
    try:
        import velplan.plans as plans
    except ImportError:
        return None
    if hasattr(plans, "Plan"):
        return plans
    return None


def _plan_evaluate(plans, plan, mech, phi, *, drafting=None, target_mm=None, engine="numpy", kin=None,
                   stack=True):
    """Solve (unless ``kin`` is given), then construct the velocity and the acceleration plans at
    every angle.

    Returns (names, vel (n, P, 2), acc (n, P, 2), {link: ω}, {link: ε})."""
    kin = velplan.solve(mech, phi, epsilon1=0.0, engine=engine) if kin is None else kin
    kw = {"drafting": plans.EXACT if drafting is None else drafting}
    if target_mm is not None:
        idx = np.arange(len(kin))
        kw["scale_v"] = plans.auto_scale(kin, idx, "velocity", target_mm)
        kw["scale_a"] = plans.auto_scale(kin, idx, "acceleration", 1.2 * target_mm)
    rv = plan.evaluate(kin, kind="velocity", **kw)
    ra = plan.evaluate(kin, kind="acceleration", velocity=rv, **kw)  # on the velocity plan drawn
    names = [k for k in rv.vectors if k in ra.vectors]  # every point read off both plans
    if not stack:  # timing: the plans' own readout, without this script's (n, P, 2) copies
        return names, None, None, rv.omegas, ra.epsilons
    vel = np.stack([rv.vectors[k] for k in names], axis=1)
    acc = np.stack([ra.vectors[k] for k in names], axis=1)
    return names, vel, acc, rv.omegas, ra.epsilons


def _link_errors(ref, mech, omegas, epsilons) -> dict[str, float]:
    w = abs(mech.crank.omega)
    out = {}
    for key, d, c, s in (("omega", omegas, 1, w), ("eps", epsilons, 2, w * w)):
        errs = [np.max(np.abs((v - ref.links[0][:, ref.link(k), c]) - ref.links[1][:, ref.link(k), c]))
                for k, v in d.items() if k in ref.link_names]
        if errs:
            out[key] = float(max(errs) / s)
    return out


def plan_methods(mech, ref, sizes) -> list[Row]:
    plans = _plan_api()
    if plans is None:
        print(f"note [{mech.name}]: velplan.plans has no Plan/velocity_plan yet — plan rows skipped")
        return []
    plan = plans.Plan.of(mech)
    variants = [("plan exact", "plans", {})]
    variants += [(f"plan drafting {p:g} mm/{p:g}° @{t:g} mm", "drafting",
                  {"drafting": plans.Drafting(length_mm=p, angle_deg=p), "target_mm": t})
                 for t in DRAFT_TARGETS_MM for p in DRAFT_PRECISIONS_MM]
    rows = []
    draft_times = None
    for name, family, kw in variants:
        try:
            names, vel, acc, om, ep = _plan_evaluate(plans, plan, mech, ref.phi, **kw)
        except Exception as exc:  # noqa: BLE001 - the hook must not sink the benchmark
            print(f"note [{mech.name}]: plan hook failed for {name!r} ({type(exc).__name__}: {exc}); "
                  "adapt _plan_evaluate in benchmarks/bench_solver.py")
            return rows
        row = Row(mech.name, name, family)
        row.errors = point_errors(ref, names, None, vel, acc, mech=mech)
        row.errors.update(_link_errors(ref, mech, om, ep))
        row.note = "solve + velocity plan + acceleration plan"
        if family == "plans":
            time_sizes(row, lambda phi: _plan_evaluate(plans, plan, mech, phi, stack=False), sizes)
            rows += plan_timings(plans, plan, mech, sizes, row)
        else:  # drafting costs the same whatever the precision: time one variant
            if draft_times is None:
                probe = Row(mech.name, name, family)
                time_sizes(probe, lambda phi, kw=kw: _plan_evaluate(plans, plan, mech, phi, stack=False, **kw), sizes)
                draft_times = (probe.times, probe.repeats)
            row.times, row.repeats = dict(draft_times[0]), dict(draft_times[1])
        rows.append(row)
    return rows


def plan_timings(plans, plan, mech, sizes, exact: Row) -> list[Row]:
    """Timing-only rows of the exact plans: both plans on an already solved mechanism, and solve
    (compiled engine) + both plans. Their errors are those of ``exact`` (same values)."""
    solved: dict[int, object] = {}

    def given_kin(phi):
        kin = solved.get(phi.shape[0])
        if kin is None:
            kin = solved[phi.shape[0]] = velplan.solve(mech, phi, epsilon1=0.0)
        return _plan_evaluate(plans, plan, mech, phi, kin=kin, stack=False)

    rows = [Row(mech.name, "plan exact, both plans on a solved mechanism", "plans timing",
                errors=dict(exact.errors), note="velocity plan + acceleration plan, without the solve")]
    time_sizes(rows[0], given_kin, sizes)
    solved.clear()
    if "compiled" in ENGINES:
        rows.append(Row(mech.name, "plan exact, compiled solve", "plans timing", errors=dict(exact.errors),
                        note="solve (compiled engine) + velocity plan + acceleration plan"))
        time_sizes(rows[-1], lambda phi: _plan_evaluate(plans, plan, mech, phi, engine="compiled", stack=False),
                   sizes)
    return rows


# --- report --------------------------------------------------------------------------------------

def pareto_plot(rows: list[Row], path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    examples = sorted({r.example for r in rows})
    fam_style = {"analytic": ("o", "C0", 60), "plans": ("D", "C3", 40), "drafting": ("v", "C4", 30),
                 "finite differences": ("s", "C1", 30), "chord method": ("^", "C2", 40), "plans timing": ("d", "C5", 30)}
    short = {"plan exact, both plans on a solved mechanism": "plans only",
             "plan exact, compiled solve": "plans + compiled solve", "plan exact": "plans (exact)"}
    ncol = 3
    nrow = -(-(len(examples) + 1) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.2 * ncol, 4.3 * nrow), squeeze=False)
    for ax, ex in zip(axes.flat, examples):
        pts = []
        for r in rows:
            if r.example != ex:
                continue
            x, y = r.pareto_time() * 1e6, max(r.worst_derivative(), 1e-17)
            mk, col, size = fam_style.get(r.family, ("x", "k", 30))
            ax.scatter(x, y, marker=mk, color=col, s=size, label=r.family, zorder=3, alpha=0.85)
            if r.family == "finite differences":
                label = "h=" + r.method.split("h=")[1]
            elif r.family == "chord method":
                label = r.method.replace("chord ", "")
            elif r.family == "drafting":
                label = None  # one label for the group, below
            else:
                label = short.get(r.method, r.method)
            if label and r.family in ("analytic", "plans", "plans timing"):
                # these sit together at round-off: stagger their labels above and below
                dy = (10, -14, 22, -26, 34)[len([p for p in pts if p[1] < 1e-12]) % 5]
                ax.annotate(label, (x, y), fontsize=6.5, xytext=(2, dy), textcoords="offset points",
                            arrowprops={"arrowstyle": "-", "lw": 0.4, "color": "0.5"})
            elif label:
                ax.annotate(label, (x, y), fontsize=7, xytext=(4, 2), textcoords="offset points")
            pts.append((x, y))
        dr = [(r.pareto_time() * 1e6, r.worst_derivative()) for r in rows
              if r.example == ex and r.family == "drafting"]
        if dr:
            x = max(p[0] for p in dr)
            ax.annotate(f"drafting {min(DRAFT_PRECISIONS_MM):g}–{max(DRAFT_PRECISIONS_MM):g} mm",
                        (x, min(p[1] for p in dr)), fontsize=7, xytext=(6, -10), textcoords="offset points",
                        color="C4")
        pts.sort()
        front, best = [], np.inf
        for x, y in pts:
            if y < best:
                front.append((x, y))
                best = y
        if len(front) > 1:
            fx, fy = zip(*front)
            ax.step(fx, fy, where="post", color="0.4", lw=0.9, ls="--", zorder=2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_ylim(3e-18, 3)
        ax.set_title(ex)
        ax.set_xlabel("µs per position (at 10⁶; chord method at its N)")
        ax.set_ylabel("worst scaled error (velocity, acceleration)")
        ax.grid(True, which="major", lw=0.3)
    rest = list(axes.flat)[len(examples):]
    if rest:
        leg = rest[0]
        for fam, (mk, col, size) in fam_style.items():
            leg.scatter([], [], marker=mk, color=col, s=size, label=fam)
        leg.plot([], [], color="0.4", lw=0.9, ls="--", label="Pareto front (when more than one point)")
        leg.legend(loc="center", fontsize=9, frameon=False)
        leg.text(0.5, 0.06, "Errors scaled by |ω1|·L and ω1²·L; float64 round-off ≈ 1e-16.\n"
                 "Bottom left is best. The analytic solver is the fastest and at round-off;\n"
                 "only the exact plans match its accuracy.", ha="center", fontsize=8,
                 transform=leg.transAxes)
        for ax in rest:
            ax.axis("off")
    fig.suptitle("velplan: run time against error")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
    print(f"wrote {path.relative_to(RESULTS.parent.parent)}")


def report(rows: list[Row], sizes, refs, oracle_check, profile_md: str, elapsed: float) -> str:
    out = ["# Solver benchmark: run time against error", "",
           "Generated by `python benchmarks/bench_solver.py`. Times are wall-clock medians per crank "
           "position (µs); errors are the worst over 720 angles (0.5° apart) against a 50-digit "
           "mpmath reference computed from the closed forms (`benchmarks/reference.py`), scaled by "
           "L, |ω1|·L, ω1²·L (positions, velocities, accelerations) and |ω1|, ω1² (link ω, ε), "
           "with ε1 = 0.", "", "## Machine", "", machine_md(), "",
           f"- **load average** (1/5/15 min) at start: {LOAD[0]}; at end: {load_average()} (other sessions "
           "may share these 2 cores: medians, not minima, are reported)", "",
           f"Total run time of this script: {elapsed:.0f} s.", ""]
    out += ["## Time per position (µs, median of repeats)", ""]
    header = ["example", "method"] + [f"n={n:g}" for n in sizes]
    body = []
    for r in rows:
        if r.family == "chord method":
            continue
        body.append([r.example, r.method] + [us(r.times[n]) if n in r.times else "–" for n in sizes])
    # collapse the FD rows (identical times) to one per example
    seen, rows_t = set(), []
    collapse = {"central FD": "central FD (any h: 3 solves per position)",
                "plan drafting": "plan drafting (any precision and scale) = solve + both plans"}
    for b in body:
        prefix = next((k for k in collapse if b[1].startswith(k)), None)
        if prefix:
            if (b[0], prefix) in seen:
                continue
            seen.add((b[0], prefix))
            b = [b[0], collapse[prefix]] + b[2:]
        elif b[1] == "plan exact":
            b = [b[0], "plan exact = solve + velocity plan + acceleration plan"] + b[2:]
        rows_t.append(b)
    out += [table(header, rows_t), ""]
    out += ["Repeats per size: " + ", ".join(f"{n:g}: {rows[0].repeats.get(n, '–')}" for n in sizes)
            + " (the median is reported; one untimed warm-up run first below 10⁶, where the sizes "
            "before have warmed up the same code).", ""]
    out += ["The chord method's cost is that of drawing its own N positions:", ""]
    out += [table(["example", "method", "µs per position", "repeats"],
                  [[r.example, r.method, us(next(iter(r.times.values()))), next(iter(r.repeats.values()))]
                   for r in rows if r.family == "chord method"]), ""]
    out += ["## Worst scaled error against the 50-digit reference", ""]
    out += [table(["example", "method", "position", "velocity", "acceleration", "link ω", "link ε", "note"],
                  [[r.example, r.method, sci(r.errors.get("pos")), sci(r.errors.get("vel")),
                    sci(r.errors.get("acc")), sci(r.errors.get("omega")), sci(r.errors.get("eps")), r.note]
                   for r in rows]), ""]
    out += ["Pareto plot: `solver_pareto.png` (x: time per position at the largest size measured, "
            "y: the worst of the velocity and acceleration errors).", "", "![pareto](solver_pareto.png)", ""]
    out += ["## Targets (issue 6)", ""]
    tg = [(ex, m, target) for ex, target in (("four-bar", 0.1e-6), ("shaper", 0.2e-6))
          for m in ("analytic", "analytic (compiled)")]
    tg += [(ex, m, 1e-6) for ex in sorted({r.example for r in rows})
           for m in ("plan exact, both plans on a solved mechanism", "plan exact, compiled solve")]
    trows = []
    big = max(sizes)
    for ex, method, target in tg:
        r = next((r for r in rows if r.example == ex and r.method == method), None)
        if r is None or big not in r.times:
            continue
        t = r.times[big]
        trows.append([ex, method, f"{us(t)} µs", f"≤ {us(target)} µs",
                      "met" if t <= target else f"missed ({t / target:.1f}×)"])
    out += [table(["example", "method", f"µs per position at n={big:g}", "target", "verdict"], trows), ""]
    out += ["Ratios to pylinkage: see `peers.md`; cold CLI: see `cli.md`.", ""]
    out += ["## Reference", "",
            f"{len(next(iter(refs.values())).phi)} angles per example at {R.DPS} digits. Checked against the "
            "independent Newton-iteration oracle of `tests/oracle.py` (two angles, scaled difference):", ""]
    out += [table(["example", "as bundled", "lengths and ω1 rounded to 2⁻¹²"],
                  [[k, sci(a), sci(b)] for k, (a, b) in oracle_check.items()]), ""]
    out += ["As bundled, the agreement stops at ~1e-17–1e-16 because `tests/oracle.py` evaluates "
            "`l**2` and `omega1**2` in float64 before entering mpmath; with lengths and ω1 whose "
            "squares are exact in float64 the two agree to ~1e-51, so the closed-form reference is "
            "good to far below float64 resolution.", ""]
    if profile_md:
        out += [profile_md]
    return "\n".join(out) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="sizes up to 10⁴ only, no profile")
    ap.add_argument("--examples", nargs="*", default=None, help="examples to run (default: all)")
    ap.add_argument("--no-profile", action="store_true", help="skip the profile section")
    ap.add_argument("--replot", action="store_true", help="redraw the plot from results/solver.json")
    ap.add_argument("--profile-only", action="store_true",
                    help="re-run only the profile and replace the Profile section of results/solver.md")
    args = ap.parse_args(argv)
    if args.profile_only:
        import profile_solver

        md = (RESULTS / "solver.md").read_text()
        head = md.split("## Profile", 1)[0]
        write(RESULTS / "solver.md", head + profile_solver.run())
        return 0
    if args.replot:
        rows = []
        for d in json.loads((RESULTS / "solver.json").read_text()):
            d["times"] = {int(k): v for k, v in d["times"].items()}
            d["repeats"] = {int(k): v for k, v in d["repeats"].items()}
            rows.append(Row(**d))
        pareto_plot(rows, RESULTS / "solver_pareto.png")
        return 0
    t0 = time.perf_counter()
    LOAD[0] = load_average()
    sizes = SIZES[:3] if args.quick else SIZES
    names = args.examples or velplan.example_names()
    refs = R.all_references(names)
    oracle_check = {k: (R.check_against_oracle(k), R.check_against_oracle(k, dyadic=True)) for k in names}
    rows: list[Row] = []
    for name in names:
        mech = velplan.load(name)
        ref = refs[name]
        t = time.perf_counter()
        rows += [analytic(mech, ref, sizes, engine) for engine in ENGINES]
        rows += plan_methods(mech, ref, sizes)
        rows += finite_differences(mech, ref, sizes)
        series = output_series(mech)
        if series is not None:
            rows += chord(mech, ref, series)
        print(f"{name}: {time.perf_counter() - t:.0f} s")
    profile_md = ""
    if not (args.quick or args.no_profile):
        import profile_solver

        profile_md = profile_solver.run()
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "solver.json").write_text(json.dumps([asdict(r) for r in rows], indent=1))
    pareto_plot(rows, RESULTS / "solver_pareto.png")
    write(RESULTS / "solver.md", report(rows, sizes, refs, oracle_check, profile_md, time.perf_counter() - t0))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
