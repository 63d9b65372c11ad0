"""Peers side by side: pylinkage (with and without numba), mechanism (gabemorris12), pyslvs.

On the four-bar (O = (0, 0), D = (0.3, 0), crank 0.10 m at 10 rad/s, coupler 0.25 m,
rocker 0.20 m, B above) and the crank-slider (crank 0.05 m at 100 rad/s, rod 0.20 m, slider on
y = +0.02 m): the median time per position of each peer and of ``velplan.solve`` (numpy engine,
and the compiled engine where numba is installed) measured in
the same process, alternately, at 12, 360, 10⁴, 10⁵, 10⁶ positions (a peer is not run at a
size where one run would take more than 60 s, extrapolated from the size before; the table
says so), their ratio, and each one's worst error against the 50-digit reference of
``benchmarks/reference.py`` on the points every package gives (A and B: positions,
velocities, accelerations).

Each peer runs in its own subprocess (``--worker``), so that "pylinkage without numba" is the
same code with the numba import blocked (pylinkage then falls back to plain Python).

    pip install -e .[bench]                       # pylinkage, numba, mechanism
    python benchmarks/bench_peers.py              # ~6 min on 2 cores
    python benchmarks/bench_peers.py --quick      # up to 10⁴ positions

Writes ``benchmarks/results/peers.md``.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time

import numpy as np

from _common import (HERE, RESULTS, SIZES, grid, load_average, machine_md, median_time, repeats_for, sci,
                     table, write)

CAP_SECONDS = 60.0
PEERS = ("pylinkage-numba", "pylinkage-python", "pylinkage-python-gen", "mechanism")
PEER_LABEL = {
    "pylinkage-numba": "pylinkage + numba (`step_fast_with_kinematics`)",
    "pylinkage-python": "pylinkage, no numba (`step_fast_with_kinematics`)",
    "pylinkage-python-gen": "pylinkage, no numba (`step_with_derivatives` generator)",
    "mechanism": "mechanism (`Mechanism.iterate`, scipy fsolve)",
}
MECHS = ("four-bar", "crank-slider")
PYSLVS_NOTE = (
    "pyslvs 22.7.0 (2022, the latest on PyPI) ships only an sdist for CPython 3.11. Building it "
    "fails: Cython 3 rejects `pyslvs/bfgs.pyx` (\"Too many members for 'const Point &'\", line "
    "104), and pinning `cython<3` for the build conflicts with the package's own build requirement "
    "`cython>=3.0a6`. It is therefore not measured."
)


# --- models of the two mechanisms in each peer ------------------------------------------------

FOUR_BAR = dict(O=(0.0, 0.0), D=(0.30, 0.0), crank=0.10, omega=10.0, coupler=0.25, rocker=0.20)
CRANK_SLIDER = dict(O=(0.0, 0.0), crank=0.05, omega=100.0, rod=0.20, offset=0.02)


def pylinkage_model(mech: str, n: int):
    """A pylinkage Linkage that records crank angles 0, Δ, 2Δ, … (Δ = 2π/n): its crank starts at
    −Δ because each step turns it before recording. Returns (linkage, index of A, index of B)."""
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRPDyad, RRRDyad
    from pylinkage.simulation import Linkage

    d = 2 * math.pi / n
    if mech == "four-bar":
        p = FOUR_BAR
        O, D = Ground(*p["O"], name="O"), Ground(*p["D"], name="D")
        crank = Crank(anchor=O, radius=p["crank"], angular_velocity=d, initial_angle=-d, name="A")
        B = RRRDyad(crank.output, D, distance1=p["coupler"], distance2=p["rocker"], x=0.25, y=0.19, name="B")
        comps = [O, D, crank, B]
    else:
        p = CRANK_SLIDER
        O = Ground(*p["O"], name="O")
        L1, L2 = Ground(0.0, p["offset"], name="L1"), Ground(1.0, p["offset"], name="L2")
        crank = Crank(anchor=O, radius=p["crank"], angular_velocity=d, initial_angle=-d, name="A")
        B = RRPDyad(crank.output, L1, L2, distance=p["rod"], x=0.25, y=p["offset"], name="B")
        comps = [O, L1, L2, crank, B]
    link = Linkage(comps, name=mech)
    link.set_input_velocity(crank, omega=p["omega"], alpha=0.0)
    return link, comps.index(crank), comps.index(B)


def prepare_pylinkage(mech: str, n: int, generator: bool = False):
    """Build the linkage (and its solver arrays) once; return the call to time and a function
    that reads {A, B: (pos, vel, acc)} from its result."""
    link, ia, ib = pylinkage_model(mech, n)
    link.compile()
    if generator:
        def run():
            pos, vel, acc = [], [], []
            for p, v, a in link.step_with_derivatives(iterations=n):
                pos.append(p)
                vel.append(v)
                acc.append(a)
            return tuple(np.array(x, dtype=float) for x in (pos, vel, acc))
    else:
        def run():
            return link.step_fast_with_kinematics(iterations=n)

    def read(res):
        pos, vel, acc = res
        return {k: (pos[:, i], vel[:, i], acc[:, i]) for k, i in (("A", ia), ("B", ib))}

    return run, read


def mechanism_model(mech: str, phi: np.ndarray):
    """A `mechanism.Mechanism` with vector loops, as in the package's own examples."""
    from mechanism import Mechanism, Vector, get_joints

    n = phi.shape[0]
    if mech == "four-bar":
        p = FOUR_BAR
        O, A, B, D = get_joints("O A B D")
        a = Vector((O, A), r=p["crank"])
        c = Vector((A, B), r=p["coupler"])
        d = Vector((D, B), r=p["rocker"])
        g = Vector((O, D), r=p["D"][0], theta=0, style="ground")

        def loops(x, inp):
            return a(inp) + c(x[0]) - d(x[1]) - g()

        vectors, guess = (a, c, d, g), np.deg2rad([50.0, 100.0])
    else:
        p = CRANK_SLIDER
        O, A, B, P = get_joints("O A B P")
        a = Vector((O, A), r=p["crank"])
        b = Vector((A, B), r=p["rod"])
        c = Vector((P, B), r=p["offset"], theta=np.pi / 2, style="ground")
        d = Vector((O, P), theta=0, style="ground")

        def loops(x, inp):
            return a(inp) + b(x[0]) - c() - d(x[1])

        vectors, guess = (a, b, c, d), np.array([0.1, 0.25])
    m = Mechanism(vectors=vectors, origin=O, loops=loops, pos=phi, vel=np.full(n, p["omega"]),
                  acc=np.zeros(n), guess=(guess, np.ones(2), np.ones(2)))
    return m, A, B


def prepare_mechanism(mech: str, phi: np.ndarray):
    import warnings

    m, A, B = mechanism_model(mech, phi)

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m.iterate()

    def read(_):
        def arr(j):
            return (np.c_[j.x_positions, j.y_positions], np.c_[j.x_velocities, j.y_velocities],
                    np.c_[j.x_accelerations, j.y_accelerations])

        return {"A": arr(A), "B": arr(B)}

    return run, read


# --- the worker: one peer, one mechanism, velplan alongside -------------------------------------

def peer_prepare(peer: str, mech: str, phi: np.ndarray):
    """(run, read) for ``peer`` at the angles ``phi`` (a whole number of equal steps from 0)."""
    if peer in ("pylinkage-numba", "pylinkage-python"):
        return prepare_pylinkage(mech, phi.shape[0])
    if peer == "pylinkage-python-gen":
        return prepare_pylinkage(mech, phi.shape[0], generator=True)
    if peer == "mechanism":
        return prepare_mechanism(mech, phi)
    raise ValueError(peer)


def errors_on(points: dict, ref, mech) -> dict[str, float]:
    """Worst scaled errors of {name: (pos, vel, acc)} (each (n, 2)) against the reference."""
    from _common import point_errors

    names = list(points)
    stack = [np.stack([points[k][q] for k in names], axis=1) for q in range(3)]
    return point_errors(ref, names, *stack, mech=mech)


def worker(peer: str, mech_name: str, sizes) -> dict:
    if peer.startswith("pylinkage-python"):
        sys.modules["numba"] = None  # pylinkage falls back to its no-op njit: plain Python
    import reference as R

    import velplan
    from velplan.analysis import compiled

    out: dict = {"peer": peer, "mech": mech_name, "sizes": {}, "notes": []}
    if compiled.available():
        velplan.solve(velplan.load(mech_name), grid(12), engine="compiled")  # compile, or load the cache
    mech = velplan.load(mech_name)
    # the bundled example must be the mechanism modelled in the peers
    if mech_name == "four-bar":
        assert dict(mech.ground) == {"O": FOUR_BAR["O"], "D": FOUR_BAR["D"]}
    if peer.startswith("pylinkage"):
        import pylinkage
        from pylinkage._numba_compat import HAS_NUMBA

        out["version"] = f"pylinkage {pylinkage.__version__ if hasattr(pylinkage, '__version__') else '?'}"
        if HAS_NUMBA:
            import numba

            out["version"] += f", numba {numba.__version__}"
        out["numba"] = bool(HAS_NUMBA)
        t = time.perf_counter()
        run, _ = peer_prepare(peer, mech_name, grid(12))
        run()
        out["first_call_s"] = time.perf_counter() - t
    else:
        from importlib.metadata import version

        out["version"] = f"mechanism {version('mechanism')}, scipy {version('scipy')}"
    ref = R.reference(mech_name, verbose=False)
    run, read = peer_prepare(peer, mech_name, ref.phi)
    out["error"] = errors_on(read(run()), ref, mech)
    kin = velplan.solve(mech, ref.phi, epsilon1=0.0)
    out["velplan_error"] = errors_on({k: (kin.position(k), kin.velocity(k), kin.acceleration(k)) for k in ("A", "B")},
                                     ref, mech)
    prev = None
    for n in sizes:
        phi = grid(n)
        rec: dict = {}
        est = None if prev is None else prev[1] * n / prev[0]
        if est is not None and est > CAP_SECONDS:
            rec["capped_est_s"] = est
        else:
            one = est if est is not None else 0.0
            # slow runs: about 10 s of repeats per size, but at least 3 while a run takes ≤ 20 s
            r = repeats_for(n) if one < 0.05 else max(3 if one <= 20 else 1, min(repeats_for(n), int(10 / one)))
            run, _ = peer_prepare(peer, mech_name, phi)
            t, r = median_time(run, n, repeats=r, warmup=one < 2)
            rec["peer"], rec["peer_repeats"] = t / n, r
            prev = (n, t)
        t, r = median_time(lambda: velplan.solve(mech, phi, epsilon1=0.0, engine="numpy"), n)
        rec["velplan"], rec["velplan_repeats"] = t / n, r
        if compiled.available():
            t, r = median_time(lambda: velplan.solve(mech, phi, epsilon1=0.0, engine="compiled"), n)
            rec["velplan_compiled"] = t / n
        out["sizes"][str(n)] = rec
    return out


# --- the driver ----------------------------------------------------------------------------------

def importable(mod: str) -> str | None:
    r = subprocess.run([sys.executable, "-c", f"import {mod}; print(getattr({mod}, '__version__', '?'))"],
                       capture_output=True, text=True, cwd=HERE)
    return r.stdout.strip() if r.returncode == 0 else None


def report(results: list[dict], sizes, status: dict, elapsed: float, load: tuple[str, str]) -> str:
    out = ["# Peers side by side", "",
           "Generated by `python benchmarks/bench_peers.py`. Each peer ran in its own process with "
           "`velplan.solve` timed alternately in the same process at the same sizes (median of "
           "repeats, µs per position, P+V+A). Ratio = peer time / velplan time (> 1: velplan is "
           "faster). Errors: worst over 720 angles against the 50-digit reference, on points A and "
           "B (positions, velocities, accelerations), scaled by L, |ω1|·L, ω1²·L.", "",
           "## Machine", "", machine_md(), f"- **load average** (1/5/15 min) at start: {load[0]}; at end: {load[1]} "
           "(other sessions may share these 2 cores)", "", f"Run time of this script: {elapsed:.0f} s.", "",
           "## Peers", ""]
    for k, v in status.items():
        out.append(f"- **{k}**: {v}")
    out += ["", "What each package computes per position: velplan — positions, velocities and "
            "accelerations of every point (6 on the four-bar, 4 on the crank-slider), every link's θ, ω, "
            "ε, slides and condition numbers, closed form, vectorised; pylinkage — the joints' "
            "positions (circle intersections stepped along the crank, the branch nearest to the "
            "previous position), velocities and accelerations (per-joint analytic solves); mechanism "
            "— scipy `fsolve` of the loop equations at each position (position, then velocity and "
            "acceleration loops).", ""]
    out += ["## Time per position (µs) and ratio to velplan", ""]
    rows = []
    for res in results:
        for n in sizes:
            rec = res["sizes"].get(str(n))
            if rec is None:
                continue
            if "peer" in rec:
                peer = f"{rec['peer'] * 1e6:.3g} ({rec['peer_repeats']})"
                ratio = f"{rec['peer'] / rec['velplan']:.3g}×"
            else:
                peer = f"capped (≈{rec['capped_est_s']:.0f} s per run)"
                ratio = "–"
            vc = rec.get("velplan_compiled")
            rows.append([res["mech"], PEER_LABEL[res["peer"]], f"{n:g}", peer, f"{rec['velplan'] * 1e6:.3g}", ratio,
                         "–" if vc is None else f"{vc * 1e6:.3g}",
                         "–" if vc is None or "peer" not in rec else f"{rec['peer'] / vc:.3g}×"])
    out += [table(["mechanism", "peer", "n", "peer µs/pos (repeats)", "velplan µs/pos (numpy)", "ratio",
                   "velplan µs/pos (compiled)", "ratio"], rows), ""]
    out += ["velplan is timed in every worker, so each mechanism has several velplan medians per size; their "
            "spread shows the noise of this shared machine.", ""]
    firsts = [f"{r['mech']}, {PEER_LABEL[r['peer']]}: {r['first_call_s']:.2f} s" for r in results if "first_call_s" in r]
    if firsts:
        out += ["First call (numba JIT compile or load from its cache; not in the medians): "
                + "; ".join(firsts) + ".", ""]
    out += ["## Worst scaled error against the 50-digit reference (points A and B)", ""]
    erows = []
    done = set()
    for res in results:
        e, v = res["error"], res["velplan_error"]
        erows.append([res["mech"], PEER_LABEL[res["peer"]], sci(e.get("pos")), sci(e.get("vel")), sci(e.get("acc"))])
        if res["mech"] not in done:
            done.add(res["mech"])
            erows.append([res["mech"], "**velplan** (`solve`)", sci(v.get("pos")), sci(v.get("vel")), sci(v.get("acc"))])
    out += [table(["mechanism", "package", "position", "velocity", "acceleration"], erows), ""]
    out += ["## Targets (issue 6)", "",
            "velplan analytic P+V+A at 10⁶ positions should be ≥ 5× faster than pylinkage with numba "
            "and ≥ 100× faster than pylinkage without it. pylinkage without numba is capped below 10⁶ "
            "(one run > 60 s); its time per position does not depend on n (a per-step loop), so its "
            "largest measured size is compared with velplan at 10⁶.", ""]
    trows = []
    big = str(max(sizes))
    for mech in MECHS:
        vp = [r for r in results if r["mech"] == mech]
        if not vp:
            continue
        # velplan's faster engine: compiled, where numba is installed (timed beside pylinkage + numba
        # and mechanism; the workers that block numba time the numpy engine only)
        at_big = [r["sizes"][big] for r in vp if big in r["sizes"]]
        fast = [x["velplan_compiled"] for x in at_big if "velplan_compiled" in x]
        v_big = min(np.median([x["velplan"] for x in at_big]), np.median(fast) if fast else np.inf)
        for peer, need in (("pylinkage-numba", 5), ("pylinkage-python", 100), ("pylinkage-python-gen", 100)):
            r = next((x for x in vp if x["peer"] == peer), None)
            if r is None:
                continue
            measured = [int(k) for k, rec in r["sizes"].items() if "peer" in rec]
            if not measured:
                continue
            m = str(max(measured))
            ratio = r["sizes"][m]["peer"] / v_big
            trows.append([mech, PEER_LABEL[peer], f"{int(m):g}", f"{r['sizes'][m]['peer'] * 1e6:.3g}",
                          f"{v_big * 1e6:.3g}", f"{ratio:.3g}×", f"≥ {need}×", "met" if ratio >= need else "missed"])
    out += [table(["mechanism", "peer", "peer at n", "peer µs/pos", f"velplan µs/pos at {int(big):g}",
                   "ratio", "target", "verdict"], trows), ""]
    return "\n".join(out) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="sizes up to 10⁴")
    ap.add_argument("--worker", nargs=2, metavar=("PEER", "MECH"), help=argparse.SUPPRESS)
    ap.add_argument("--sizes", type=str, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--report", action="store_true", help="rewrite results/peers.md from results/peers.json")
    args = ap.parse_args(argv)
    if args.report:
        d = json.loads((RESULTS / "peers.json").read_text())
        write(RESULTS / "peers.md", report(d["results"], tuple(d["sizes"]), d["status"], d["elapsed"], tuple(d["load"])))
        return 0
    sizes = tuple(int(x) for x in args.sizes.split(",")) if args.sizes else (SIZES[:3] if args.quick else SIZES)
    if args.worker:
        print(json.dumps(worker(*args.worker, sizes)))
        return 0
    t0 = time.perf_counter()
    load0 = load_average()
    import reference as R

    R.all_references(MECHS)
    status = {}
    pl, nb, me = importable("pylinkage"), importable("numba"), importable("mechanism")
    status["pylinkage"] = f"importable ({pl})" if pl else "not importable: `pip install pylinkage`"
    status["numba"] = f"importable ({nb})" if nb else "not importable: the numba rows are skipped"
    status["mechanism"] = f"importable ({me})" if me else "not importable: `pip install mechanism`"
    ps = importable("pyslvs")
    status["pyslvs"] = f"importable ({ps}) — not modelled here yet" if ps else PYSLVS_NOTE
    todo = [p for p in PEERS if (p.startswith("pylinkage") and pl and (nb or p != "pylinkage-numba"))
            or (p == "mechanism" and me)]
    results = []
    for mech in MECHS:
        for peer in todo:
            t = time.perf_counter()
            cmd = [sys.executable, str(HERE / "bench_peers.py"), "--worker", peer, mech,
                   "--sizes", ",".join(map(str, sizes))]
            r = subprocess.run(cmd, capture_output=True, text=True, cwd=HERE)
            if r.returncode != 0:
                print(f"{peer} on {mech} failed:\n{r.stderr[-2000:]}")
                status[f"{peer} on {mech}"] = f"failed: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else '?'}"
                continue
            results.append(json.loads(r.stdout.strip().splitlines()[-1]))
            print(f"{mech:<13} {peer:<22} {time.perf_counter() - t:6.0f} s")
    for res in results:
        status.setdefault(PEER_LABEL[res["peer"]].split(" (")[0] + " version", res.get("version", "?"))
    elapsed, load = time.perf_counter() - t0, (load0, load_average())
    (RESULTS / "peers.json").write_text(json.dumps({"sizes": sizes, "status": status, "results": results,
                                                    "elapsed": elapsed, "load": load}, indent=1))
    write(RESULTS / "peers.md", report(results, sizes, status, elapsed, load))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
