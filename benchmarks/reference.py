"""A 50-digit mpmath reference for the bundled examples, computed from the closed forms.

For each crank angle φ (a float64 value, taken exactly), every point is placed by the
closed form of its group evaluated in 50-digit complex arithmetic (circle–circle,
circle–line, line–line, the guide-bar's tangent construction), and velocities and
accelerations are its first and second derivatives in φ by `mpmath.diff` (which raises the
working precision while it differences), times ω1 and ω1² (ε1 = 0). A coincident point
(A4 on the shaper's bar, B4 on the press's punch, …) is differentiated as the material
point of its link that is there at φ, carried with the link's frame.

The closed forms are written here again, in mpmath, from the mechanism description only;
`check_against_oracle` compares them with the independent Newton-iteration oracle of
``tests/oracle.py`` on a few angles.

Values are stored as double-double pairs (hi = nearest float64, lo = the rest) so that the
error of a float64 result can be measured below one ulp: ``err = (x - hi) - lo``.

Results are cached in ``benchmarks/results/cache/<example>-<n>.npz``, keyed by a hash of the
example's TOML text and of the angles.

Run ``python benchmarks/reference.py`` to build the cache for every example and print the
comparison with the oracle.
"""

from __future__ import annotations

import hashlib
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import mpmath as mp
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import velplan  # noqa: E402
from velplan.mechanism.model import PRP, RPP, RPR, RRP, RRR, Crank, LinkPoint, Mechanism  # noqa: E402
from velplan.mechanism.structure import coincident_points, schedule  # noqa: E402

DPS = 50
CACHE = Path(__file__).resolve().parent / "results" / "cache"
N_REF = 720
"""Reference angles: φ_k = k·2π/720 (0.5° apart), so that the nodes and interval midpoints of
the 12-, 24-, 72- and 360-position chord diagrams are all among them."""


def ref_angles(n: int = N_REF) -> np.ndarray:
    """The float64 reference angles k·(2π/n), rad."""
    return np.arange(n) * (2 * np.pi / n)


def _e(theta):
    return mp.mpc(mp.cos(theta), mp.sin(theta))  # expj raises on an mpf in some mpmath releases


def _cross(a, b):
    return a.real * b.imag - a.imag * b.real


def closed_form(mech: Mechanism, phi) -> tuple[dict, dict, dict]:
    """Points {name: mpc}, link angles {link: mpf} and link origins {link: point} at ``phi``."""
    P = {k: mp.mpc(x, y) for k, (x, y) in mech.ground}
    T = {"0": mp.mpf(0)}
    origin = {"0": mech.ground[0][0]}

    def guide(g):
        u = _e(T[g.link] + g.angle)
        return P[g.through] + 1j * mp.mpf(g.offset) * u, u

    for item in schedule(mech):
        if isinstance(item, Crank):
            P[item.tip] = P[item.pivot] + item.length * _e(phi)
            T[item.link], origin[item.link] = mp.mpf(phi), item.pivot
        elif isinstance(item, LinkPoint):
            P[item.name] = P[origin[item.link]] + mp.mpc(item.along, item.offset) * _e(T[item.link])
        elif isinstance(item, RRR):
            A, D = P[item.joints[0]], P[item.joints[1]]
            l1, l2 = (mp.mpf(v) for v in item.lengths)
            d = D - A
            L = abs(d)
            a = (l1**2 - l2**2 + L**2) / (2 * L)
            h = mp.sqrt(l1**2 - a**2)
            C = A + (a + 1j * item.branch * h) * d / L
            P[item.point] = C
            T[item.links[0]], T[item.links[1]] = mp.arg(C - A), mp.arg(C - D)
            origin[item.links[0]], origin[item.links[1]] = item.joints
        elif isinstance(item, RRP):
            A = P[item.joint]
            base, u = guide(item.guide)
            w = (A - base) / u
            s = w.real + item.branch * mp.sqrt(mp.mpf(item.length) ** 2 - w.imag**2)
            C = base + s * u
            P[item.point] = C
            if item.coincident:
                P[item.coincident] = C
            rod, slider = item.links
            T[rod], origin[rod] = mp.arg(C - A), item.joint
            T[slider], origin[slider] = T[item.guide.link] + item.guide.angle, item.point
        elif isinstance(item, RPR):
            A, O = P[item.joint], P[item.pivot]
            r = A - O
            s = item.branch * mp.sqrt(abs(r) ** 2 - mp.mpf(item.offset) ** 2)
            th = mp.arg(r) - mp.arg(mp.mpc(s, item.offset))
            block, bar = item.links
            T[block], T[bar] = th, th
            origin[block], origin[bar] = item.joint, item.pivot
            if item.coincident:
                P[item.coincident] = A
        elif isinstance(item, PRP):
            (b1, u1), (b2, u2) = guide(item.guides[0]), guide(item.guides[1])
            s1 = _cross(b2 - b1, u2) / _cross(u1, u2)
            C = b1 + s1 * u1
            P[item.point] = C
            for k, g in zip(item.links, item.guides):
                T[k], origin[k] = T[g.link] + g.angle, item.point
            for name in item.coincident:
                if name:
                    P[name] = C
        elif isinstance(item, RPP):
            base, u = guide(item.guide)
            v = u * _e(item.slot_angle)
            B = P[item.joint]
            s = _cross(B - base, v) / _cross(u, v)
            P[item.origin_name] = base + s * u
            if item.coincident:
                P[item.coincident] = B
            block, runner = item.links
            th = T[item.guide.link] + item.guide.angle
            T[block], origin[block] = th + item.slot_angle, item.joint
            T[runner], origin[runner] = th, item.origin_name
        else:  # pragma: no cover - a new group kind
            raise NotImplementedError(type(item).__name__)
    return P, T, origin


def coincident_owner(mech: Mechanism) -> dict[str, str]:
    """Coincident point name → the link it is a material point of."""
    return coincident_points(mech)


def derivatives(mech: Mechanism, phi: float, omega1: float):
    """({point: (p, v, a)} as mpc, {link: (θ, ω, ε)} as mpf) at crank angle ``phi`` (ε1 = 0)."""
    phi0 = mp.mpf(phi)
    memo: dict = {}

    def at(t):
        key = (t, mp.mp.prec)
        if key not in memo:
            memo[key] = closed_form(mech, t)
        return memo[key]

    P0, T0, origin = at(phi0)
    coincident = coincident_owner(mech)
    w = mp.mpf(omega1)

    def track(name):
        if name not in coincident:
            return lambda t: at(t)[0][name]
        link = coincident[name]
        local = (P0[name] - P0[origin[link]]) * _e(-T0[link])
        return lambda t: at(t)[0][origin[link]] + local * _e(at(t)[1][link])

    pts = {}
    for name in P0:
        f = track(name)
        d1 = mp.mpc(mp.diff(lambda t: f(t).real, phi0, 1), mp.diff(lambda t: f(t).imag, phi0, 1))
        d2 = mp.mpc(mp.diff(lambda t: f(t).real, phi0, 2), mp.diff(lambda t: f(t).imag, phi0, 2))
        pts[name] = (P0[name], d1 * w, d2 * w**2)
    links = {}
    for name, th0 in T0.items():
        if name == "0":
            continue
        # relative to θ at φ0, so that the branch cut of arg never falls inside the stencil
        g = lambda t, name=name, th0=th0: mp.arg(_e(at(t)[1][name] - th0))  # noqa: E731
        links[name] = (th0, mp.diff(g, phi0, 1) * w, mp.diff(g, phi0, 2) * w**2)
    return pts, links


def _split(x) -> tuple[float, float]:
    hi = float(x)
    return hi, float(x - hi)


@dataclass(frozen=True)
class Reference:
    """Reference values at ``phi`` (float64, exact) as double-double hi/lo pairs.

    ``pos``, ``vel``, ``acc``: (2, n, P, 2) — [hi, lo] × angle × point × xy (m, m/s, m/s²).
    ``links``: (2, n, L, 3) — [hi, lo] × angle × link × (θ, ω, ε) (rad, rad/s, rad/s²).
    """

    name: str
    phi: np.ndarray
    omega1: float
    points: tuple[str, ...]
    link_names: tuple[str, ...]
    pos: np.ndarray
    vel: np.ndarray
    acc: np.ndarray
    links: np.ndarray

    def point(self, name: str) -> int:
        return self.points.index(name)

    def link(self, name: str) -> int:
        return self.link_names.index(name)


def _key(mech_name: str, phi: np.ndarray) -> str:
    src = (ROOT / "velplan" / "examples" / f"{mech_name}.toml").read_bytes()
    h = hashlib.sha256(src + phi.tobytes() + f"dps={DPS}".encode()).hexdigest()
    return h[:16]


def _compute(mech_name: str, phi: np.ndarray) -> Reference:
    mp.mp.dps = DPS
    mech = velplan.load(mech_name)
    w1 = mech.crank.omega
    n = len(phi)
    pts0, links0 = derivatives(mech, float(phi[0]), w1)
    names, lnames = tuple(pts0), tuple(links0)
    pos = np.zeros((2, n, len(names), 2))
    vel = np.zeros_like(pos)
    acc = np.zeros_like(pos)
    lk = np.zeros((2, n, len(lnames), 3))
    for i, p in enumerate(phi):
        pts, links = (pts0, links0) if i == 0 else derivatives(mech, float(p), w1)
        for j, k in enumerate(names):
            for arr, z in zip((pos, vel, acc), pts[k]):
                (arr[0, i, j, 0], arr[1, i, j, 0]) = _split(z.real)
                (arr[0, i, j, 1], arr[1, i, j, 1]) = _split(z.imag)
        for j, k in enumerate(lnames):
            for c, x in enumerate(links[k]):
                lk[0, i, j, c], lk[1, i, j, c] = _split(x)
    return Reference(mech_name, phi.copy(), w1, names, lnames, pos, vel, acc, lk)


def reference(mech_name: str, phi: np.ndarray | None = None, *, verbose: bool = True) -> Reference:
    """The reference for example ``mech_name`` at ``phi`` (default `ref_angles`), cached."""
    phi = ref_angles() if phi is None else np.asarray(phi, dtype=float)
    path = CACHE / f"{mech_name}-{len(phi)}-{_key(mech_name, phi)}.npz"
    if path.exists():
        z = np.load(path)
        return Reference(mech_name, z["phi"], float(z["omega1"]), tuple(z["points"]), tuple(z["link_names"]),
                         z["pos"], z["vel"], z["acc"], z["links"])
    t0 = time.perf_counter()
    ref = _compute(mech_name, phi)
    CACHE.mkdir(parents=True, exist_ok=True)
    np.savez(path, phi=ref.phi, omega1=ref.omega1, points=np.array(ref.points), link_names=np.array(ref.link_names),
             pos=ref.pos, vel=ref.vel, acc=ref.acc, links=ref.links)
    if verbose:
        print(f"reference {mech_name}: {len(phi)} angles at {DPS} digits in {time.perf_counter() - t0:.1f} s")
    return ref


def all_references(names=None, phi=None) -> dict[str, Reference]:
    """References for several examples, computed on both cores when not cached."""
    names = list(velplan.example_names() if names is None else names)
    phi = ref_angles() if phi is None else np.asarray(phi, dtype=float)
    missing = [k for k in names if not (CACHE / f"{k}-{len(phi)}-{_key(k, phi)}.npz").exists()]
    if len(missing) > 1:
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(max_workers=2) as ex:
            list(ex.map(reference, missing, [phi] * len(missing)))
    return {k: reference(k, phi) for k in names}


def _dyadic(mech: Mechanism) -> Mechanism:
    """``mech`` with its RRR/RRP lengths and ω1 rounded to multiples of 2⁻¹², whose float64
    squares are exact: tests/oracle.py computes ``l**2`` and ``omega1**2`` in float64, which
    alone limits its agreement with any exact reference to ~1e-16 relative."""
    from dataclasses import replace

    def r(x):
        return round(x * 4096) / 4096

    groups = []
    for g in mech.groups:
        if isinstance(g, RRR):
            g = replace(g, lengths=tuple(r(x) for x in g.lengths))
        elif isinstance(g, RRP):
            g = replace(g, length=r(g.length))
        groups.append(g)
    return replace(mech, groups=tuple(groups), crank=replace(mech.crank, omega=r(mech.crank.omega)))


def check_against_oracle(mech_name: str, angles=(0.7, 3.3), *, dyadic: bool = False) -> float:
    """Largest difference between this closed-form reference and the Newton oracle of
    ``tests/oracle.py`` (relative to the length, velocity and acceleration scales).

    With ``dyadic``, on a copy of the mechanism whose lengths square exactly in float64."""
    from tests import oracle  # noqa: PLC0415 - optional, needs the source tree

    mp.mp.dps = DPS
    mech = velplan.load(mech_name)
    if dyadic:
        mech = _dyadic(mech)
    w1 = mech.crank.omega
    L = velplan.analysis.solver.length_scale(mech)
    worst = mp.mpf(0)
    for phi in angles:
        mine, _ = derivatives(mech, phi, w1)
        theirs, _ = oracle.derivatives(mech, phi, w1)
        for k, (x, y, vx, vy, ax, ay) in theirs.items():
            p, v, a = mine[k]
            worst = max(worst, abs(p - mp.mpc(x, y)) / L, abs(v - mp.mpc(vx, vy)) / (abs(w1) * L),
                        abs(a - mp.mpc(ax, ay)) / (w1**2 * L))
    return float(worst)


if __name__ == "__main__":
    t = time.perf_counter()
    refs = all_references()
    print(f"references ready in {time.perf_counter() - t:.1f} s")
    for name in refs:
        t = time.perf_counter()
        print(f"{name:<14} closed form vs Newton oracle: {check_against_oracle(name):.2e}; "
              f"with dyadic lengths {check_against_oracle(name, dyadic=True):.2e} "
              f"({time.perf_counter() - t:.1f} s)")
