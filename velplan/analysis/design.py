"""The design axis: one mechanism's geometry varied over V variants and solved at its crank
angles in one call.

Variants × angles are flattened into the solver's positions axis, and every varied number
(a length, a pivot's coordinate, a guide's offset or angle, the crank's speed) becomes an
array with one value per element: the closed forms of `velplan.analysis.groups` broadcast,
so the numpy engine solves V·n elements exactly as it solves n angles of one mechanism.

Parameters are named by the dotted keys of the mechanism file, read and checked by
`velplan.mechanism.keys` (the one table of keys, shared with `velplan batch`): every value
passes the file loader's checks before any work. The keys the arrays carry (the crank's length
and speed, fixed points, class II groups' lengths, offsets, guides and slots, points on links)
are solved V·n at a time; any other key (a triad's sides or leads, a branch, a mass …) makes
each variant be built as its file would be and solved alone.

A class III group (`Triad`) is solved in the same arrays: its branch is followed over the turn
in every variant together (`velplan.analysis.triad.tracks`: one batch of roots, the steps in
all variants at once; a variant whose branch needs shorter steps is tracked alone), and each
element takes the root nearest its own variant's branch. Over variants the compiled kernel does
not cover class III groups (it does for one mechanism, `velplan.analysis.compiled`): such a
design is solved by the numpy engine.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Mapping

import numpy as np

from velplan.analysis import triad
from velplan.analysis.groups import LinkMotion, Motion, State, crank_tip
from velplan.analysis.blocks import BLOCK, Outputs, about_pivot, solve_items
from velplan.analysis.kinematics import Kinematics, group_lengths
from velplan.analysis.solver import solve
from velplan.mechanism import keys
from velplan.mechanism.model import GROUND, Mechanism
from velplan.mechanism.structure import schedule


# ---- keys -----------------------------------------------------------------------------------


def design_keys(mech: Mechanism, *, speed: bool = False) -> dict[str, float]:
    """Every geometric key of ``mech`` with its nominal value (m or deg), in file order;
    ``speed`` adds the crank's ``crank.omega`` (rad/s) (`velplan.mechanism.keys.keys_of`)."""
    return keys.keys_of(mech, speed=speed)


def nominal(mech: Mechanism, key: str) -> float:
    """The value of ``key`` in ``mech`` (m, deg, rpm or rad/s)."""
    return keys.value(mech, key)


def _with(obj, **fields):
    """A shallow copy of the frozen value ``obj`` with ``fields`` set (arrays allowed: the
    copy is not validated)."""
    new = copy.copy(obj)
    for k, v in fields.items():
        object.__setattr__(new, k, v)
    return new


def _set(mech: Mechanism, key: str, value) -> Mechanism:
    """``mech`` with the number at ``key`` set to ``value`` (a float or an array), unchecked."""
    return keys.resolve(mech, key).set(mech, value)


def variant(mech: Mechanism, values: Mapping[str, float]) -> Mechanism:
    """``mech`` with the keys ``values`` set: one variant, checked like a loaded file."""
    return keys.apply(mech, values)


# ---- solving --------------------------------------------------------------------------------


@dataclass(frozen=True)
class DesignKinematics:
    """Solutions of V variants at n crank angles each.

    Attributes
    ----------
    mechanism : Mechanism
        The nominal mechanism.
    values : dict of str → ndarray, shape (V,)
        The varied keys' values per variant (m, deg, rpm or rad/s).
    phi : ndarray, shape (V, n)
        Crank angles, rad.
    flat : Kinematics
        All elements in one solution, variant-major: element ``v·n + i`` is variant v at
        angle i (its ``omega1`` an array when the crank's speed varies).
    """

    mechanism: Mechanism
    values: dict
    phi: np.ndarray
    flat: Kinematics

    @property
    def shape(self) -> tuple[int, int]:
        """(V, n)."""
        return self.phi.shape

    def per_variant(self, arr: np.ndarray) -> np.ndarray:
        """An array of ``flat`` (V·n, …) as (V, n, …)."""
        return arr.reshape(self.shape + arr.shape[1:])

    @property
    def valid(self) -> np.ndarray:
        """(V, n) assembled and not singular."""
        return self.per_variant(self.flat.valid)

    def variant(self, v: int) -> Kinematics:
        """Variant ``v``'s solution alone (its positions axis of length n)."""
        n = self.shape[1]
        return self.flat.take(slice(v * n, (v + 1) * n))

    def failures(self) -> list[str]:
        """Per variant: "" when it is valid at every angle, else why not (the first group, in
        solving order, that does not close or is singular, and the crank angle)."""
        V, n = self.shape
        cond = self.per_variant(self.flat.condition)  # (V, n, G)
        names = list(self.flat.group_index)
        valid = self.valid
        out = [""] * V
        for v in np.flatnonzero(~valid.all(axis=1)):
            i = int(np.argmin(valid[v]))
            deg = math.degrees(self.phi[v, i]) % 360.0
            open_ = np.flatnonzero(~np.isfinite(cond[v, i]))
            if open_.size:
                out[v] = f"group {names[open_[0]]!r} does not close at φ = {deg:.6g}°"
            else:
                g = names[int(np.argmin(cond[v, i]))] if names else "?"
                out[v] = f"group {g!r} at a toggle (singular) at φ = {deg:.6g}°"
        return out


def _as_values(values: Mapping[str, object]) -> tuple[dict[str, np.ndarray], int]:
    arrs = {k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in values.items()}
    sizes = {a.shape[0] for a in arrs.values() if a.shape[0] != 1}
    if len(sizes) > 1 or any(a.ndim != 1 for a in arrs.values()):
        raise ValueError(f"design values must be 1-D arrays of one length, not {sorted(sizes)}")
    V = sizes.pop() if sizes else 1
    return {k: np.broadcast_to(a, (V,)).copy() for k, a in arrs.items()}, V


def solve_design(mech: Mechanism, values: Mapping[str, object], phi, *, order: int = 2,
                 engine: str = "numpy") -> DesignKinematics:
    """Solve V variants of ``mech`` at crank angles ``phi`` in one call.

    Parameters
    ----------
    mech : Mechanism
        The nominal mechanism.
    values : mapping of key → array_like, shape (V,) (or scalars)
        Design keys (see the module docstring) and their values per variant.
    phi : array_like, shape (n,) or (V, n)
        Crank angles, rad: the same for every variant, or one row per variant.
    order : {0, 1, 2}
        Highest derivative kept, as in `solve`.
    engine : {"numpy", "compiled"}
        Whole arrays in blocks, or the compiled kernel (numba) with one parameter set per
        variant, on every core; the same values to round-off.

    Returns
    -------
    DesignKinematics
        Positions where a variant does not assemble hold NaN and ``valid`` False there;
        `DesignKinematics.failures` says why. The crank turns at ``crank.omega`` (or the
        varied ``crank.rpm``/``crank.omega``).
    """
    vals, V = _as_values(values)
    keys.check_values(mech, vals)  # an unknown key or a value the file could not hold fails here
    phi = np.asarray(phi, dtype=float)
    if phi.ndim not in (1, 2) or (phi.ndim == 2 and phi.shape[0] != V):
        raise ValueError(f"phi must have shape (n,) or ({V}, n), not {phi.shape}")
    phi2 = np.ascontiguousarray(np.broadcast_to(phi, (V, phi.shape[-1])))
    if engine not in ("numpy", "compiled"):
        raise ValueError(f"engine must be 'numpy' or 'compiled', not {engine!r}")
    if not all(keys.resolve(mech, k).array for k in vals):
        return _each_variant(mech, vals, phi2, order, engine)
    tracks = _triad_tracks(mech, vals, V)
    if engine == "compiled" and not tracks:
        return _solve_compiled(mech, vals, phi2, order)
    n = phi2.shape[1]
    flat_phi = phi2.reshape(-1)
    E = V * n
    speed = _speed(mech, vals)
    w1 = np.repeat(speed, n) if speed.shape[0] > 1 else float(speed[0])
    shift = np.empty((E, 2))
    out = None
    step = max(1, BLOCK // max(n, 1))
    for a in range(0, V, step):
        b = min(V, a + step)
        per = {k: np.repeat(v[a:b], n) for k, v in vals.items()}
        where = slice(a * n, b * n)
        block = {name: triad.Tracks(tuple(t[a:b]), n) for name, t in tracks.items()}
        st, conditions, shift[where] = _solve_elements(mech, per, flat_phi[where], order, block)
        if out is None:
            out = Outputs(st, conditions, E, order)
        out.write(st, conditions, where)
    kin = out.kinematics(mech, flat_phi, w1, float(mech.crank.epsilon) if order >= 2 else 0.0, st)
    return DesignKinematics(mech, vals, phi2, replace(kin, positions=kin.positions + shift[:, None, :]))


def _each_variant(mech: Mechanism, vals: dict, phi2: np.ndarray, order: int, engine: str) -> DesignKinematics:
    """Variants that differ in a number the arrays do not carry (a triad's sides or leads, a
    branch …): each built as a file would be (`variant`) and solved alone, then joined."""
    parts = [solve_design(variant(mech, {k: float(a[v]) for k, a in vals.items()}), {}, phi2[v], order=order,
                          engine=engine).flat for v in range(phi2.shape[0])]
    return DesignKinematics(mech, vals, phi2, _join(parts))


def _join(parts: list[Kinematics]) -> Kinematics:
    """Solutions of the same structure, one after another along the positions axis."""
    cat = lambda f: None if getattr(parts[0], f) is None else np.concatenate([getattr(k, f) for k in parts])  # noqa: E731
    rates = {}
    for f in ("omega1", "epsilon1"):
        each = [np.broadcast_to(np.asarray(getattr(k, f), float), (len(k),)) for k in parts]
        rates[f] = float(each[0][0]) if all(np.all(e == each[0][0]) for e in each) else np.concatenate(each)
    fields = ("phi", "positions", "velocities", "accelerations", "angles", "omegas", "epsilons", "slides",
              "condition", "valid")
    return replace(parts[0], **rates, **{f: cat(f) for f in fields})


def _solve_compiled(mech: Mechanism, vals: dict, phi2: np.ndarray, order: int) -> DesignKinematics:
    """The compiled kernel over V variants: one program, a parameter set per variant."""
    from velplan.analysis import compiled
    from velplan.analysis.blocks import solve_block
    from velplan.analysis.kinematics import length_scale

    V, n = phi2.shape
    el = mech
    for key, arr in vals.items():
        el = _set(el, key, arr)
    ground = {name: np.broadcast_to(np.asarray(x, float), (V,)) + 1j * np.broadcast_to(np.asarray(y, float), (V,))
              for name, (x, y) in el.ground}
    pivot = ground[el.crank.pivot].copy()
    local = _with(el, ground=tuple((name, ((p - pivot).real, (p - pivot).imag)) for name, p in ground.items()))
    items = schedule(local)
    st, conditions = solve_block(mech, np.zeros(1), 1.0, 0.0, length_scale(mech), "nan", schedule(mech))
    E = V * n
    out = Outputs(st, conditions, E, order)  # the kernel writes no derivative above ``order``
    ops, par, gr = compiled.encode_design(local, V, out.names, out.links, out.slide_names, out.groups,
                                          _scale(el, ground), items)
    speed = np.broadcast_to(_speed(mech, vals), (V,)).astype(float)
    eps = float(mech.crank.epsilon)
    valid = np.empty(E, dtype=bool)
    flat_phi = phi2.reshape(-1)
    compiled.run(ops, par, gr, flat_phi, speed, np.full(V, eps), n, out.z, out.rates, out.slides, out.condition, valid)
    w1 = np.repeat(speed, n) if ("crank.omega" in vals or "crank.rpm" in vals) else float(speed[0])
    kin = out.kinematics(mech, flat_phi, w1, eps if order >= 2 else 0.0, st, valid)
    shift = np.repeat(np.column_stack([pivot.real, pivot.imag]), n, axis=0)
    return DesignKinematics(mech, vals, phi2, replace(kin, positions=kin.positions + shift[:, None, :]))


def _speed(mech: Mechanism, vals: dict) -> np.ndarray:
    """The crank's ω1 per variant (rad/s): one value unless a key varies it."""
    if "crank.omega" in vals:
        return vals["crank.omega"]
    if "crank.rpm" in vals:
        return vals["crank.rpm"] * (math.pi / 30.0)
    return np.array([float(mech.crank.omega)])


def _solve_elements(mech: Mechanism, per: dict, phi: np.ndarray, order: int, tracks: dict):
    """One block of elements: the state, the groups' conditions and the pivot shift (E, 2);
    ``tracks`` the block's branches of each class III group (`velplan.analysis.triad.Tracks`)."""
    el = mech
    for key, arr in per.items():
        el = _set(el, key, arr)
    E = phi.shape[0]
    ground = {name: np.broadcast_to(np.asarray(x, float), (E,)) + 1j * np.broadcast_to(np.asarray(y, float), (E,))
              for name, (x, y) in el.ground}
    pivot = ground[el.crank.pivot].copy()
    scale = _scale(el, ground)
    w = el.crank.omega * np.ones(E) if order >= 1 else np.zeros(E)
    e = np.full(E, float(el.crank.epsilon)) if order >= 2 else np.zeros(E)
    st = State(E)
    zeros = np.zeros(E, dtype=complex)
    for name, p in ground.items():
        st.points[name] = Motion(p - pivot, zeros, zeros)  # solved about the crank's pivot
    zr = np.zeros(E)
    st.links[GROUND] = LinkMotion(el.ground[0][0], zr, zr, zr)
    conditions: dict[str, np.ndarray] = {}
    items = schedule(el)
    crank = items[0]
    st.points[crank.tip] = Motion(*crank_tip(st.points[crank.pivot].p, crank.length, phi, w, e))
    st.links[crank.link] = LinkMotion(crank.pivot, phi.copy(), w, e)
    with np.errstate(all="ignore"):
        solve_items(items[1:], st, phi, w, e, scale, conditions, "nan", el, tracks)
    return st, conditions, np.column_stack([pivot.real, pivot.imag])


def _scale(el: Mechanism, ground: dict) -> np.ndarray:
    """`length_scale` per element: the largest length or ground span (m)."""
    lengths = [np.asarray(el.crank.length, float)]
    for g in el.groups:
        lengths.extend(np.asarray(x, float) for x in group_lengths(g))
    pts = np.array(list(ground.values()))  # (Pg, E)
    span = np.maximum(np.ptp(pts.real, axis=0), np.ptp(pts.imag, axis=0)) if len(pts) > 1 else 0.0
    return np.maximum(np.maximum.reduce(np.broadcast_arrays(*lengths)), span)


def _triad_tracks(mech: Mechanism, vals: dict, V: int) -> dict[str, list]:
    """Group name → the branch (`velplan.analysis.triad.Track`, None where it cannot be
    assembled) of each variant, of every class III group of ``mech``, solved about the pivot
    (memoised: a sweep solves the same variants at several sets of angles)."""
    if not any(g.tracked for g in mech.groups):
        return {}
    geometry = tuple((k, a.tobytes()) for k, a in vals.items() if k not in ("crank.omega", "crank.rpm"))
    return _tracks_of(mech, geometry, V)


@lru_cache(maxsize=4)
def _tracks_of(mech: Mechanism, geometry: tuple, V: int) -> dict[str, list]:
    """`_triad_tracks` of the V variants whose varied keys' values are ``geometry`` (key, bytes)."""
    vals = {k: np.broadcast_to(np.frombuffer(b), (V,)) for k, b in geometry}
    local = [about_pivot(variant(mech, {k: float(a[v]) for k, a in vals.items()}))[0] for v in range(V)]
    out = {}
    for i, g in enumerate(mech.groups):
        if g.tracked:
            here = [m.groups[i] for m in local]
            out[g.name] = triad.tracks([triad.upstream(m, h) for m, h in zip(local, here)], here, solve)
    return out
