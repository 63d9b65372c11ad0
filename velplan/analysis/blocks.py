"""The numpy engine: the solving schedule cut to the points asked for, and the groups solved
in closed form over a block of crank angles into preallocated outputs (`velplan.analysis.groups`,
`velplan.analysis.triad`). `velplan.analysis.solver.solve` drives it block by block.
"""

from __future__ import annotations

from typing import Iterable

import numpy as np

from velplan.analysis.groups import LinkMotion, Motion, State, carry, cis, crank_tip, wrap_angle
from velplan.analysis.solvers import solve_group
from velplan.analysis.kinematics import SINGULAR_BOUND, WELL_CONDITIONED, Kinematics, velocity_bound
from velplan.errors import AssemblyError, MechanismError
from velplan.mechanism.model import GROUND, Crank, Group, LinkPoint, Mechanism
from velplan.mechanism.structure import guides_of, joints_in, points_out, schedule


def needed_items(mech: Mechanism, points: Iterable[str]) -> tuple:
    """The solving schedule cut to what ``points`` need: the crank, the groups and link points
    that determine them or a point, guide or link they rest on.

    Raises
    ------
    MechanismError
        A name is not a point of ``mech``.
    """
    items = schedule(mech)
    want = set(points)
    made: dict[str, object] = {name: None for name, _ in mech.ground}
    for item in items:
        made.update(dict.fromkeys(_produced(item)[0], item))
    unknown = sorted(want - set(made))
    if unknown:
        raise MechanismError(f"unknown point {unknown[0]!r}; known points: {', '.join(made)}")
    want_links: set[str] = set()
    keep = []
    for item in reversed(items):
        pts, links = _produced(item)
        if isinstance(item, Crank) or pts & want or links & want_links:
            keep.append(item)
            need_pts, need_links = _needs(item)
            want |= need_pts
            want_links |= need_links
    return tuple(reversed(keep))


def _produced(item) -> tuple[set[str], set[str]]:
    if isinstance(item, Crank):
        return {item.tip}, {item.link}
    if isinstance(item, LinkPoint):
        return {item.name}, set()
    return set(points_out(item)), set(item.links)


def _needs(item) -> tuple[set[str], set[str]]:
    if isinstance(item, Crank):
        return {item.pivot}, set()
    if isinstance(item, LinkPoint):
        return set(), {item.link}
    return set(joints_in(item)), {g.link for g in guides_of(item) if g.link != GROUND}


BLOCK = 16384
"""Crank angles solved at a time (the arrays of a block stay in the CPU's caches)."""


def solve_block(mech, phi, w1, e1, scale, on_failure, items, tracks=None,
                sink=None) -> tuple[State, dict[str, np.ndarray]]:
    """The schedule ``items`` solved at the crank angles ``phi`` (rad), crank rates ``w1``, ``e1``:
    the motions and each group's condition estimate (NaN where it does not close). ``tracks``
    holds each class III group's branch over the turn (`velplan.analysis.triad.track`); ``sink``
    (`Outputs.sink`): the block's views of the outputs, written as the items are solved."""
    n = phi.shape[0]
    st = State(n)
    st.sink = sink
    st.fixed = frozenset(name for name, _ in mech.ground)
    zeros = None
    for name, (x, y) in mech.ground:
        slot = st.out_point(name)
        if slot is None:
            zeros = np.zeros(n, dtype=complex) if zeros is None else zeros
            st.points[name] = Motion(np.full(n, complex(x, y)), zeros, zeros)
        else:
            slot.p.fill(complex(x, y))
            slot.v.fill(0.0)
            slot.a.fill(0.0)
            st.points[name] = slot
    zr = np.zeros(n)
    st.links[GROUND] = LinkMotion(mech.ground[0][0], zr, zr, zr)
    conditions: dict[str, np.ndarray] = {}
    with np.errstate(all="ignore"):  # singular positions give inf/NaN, masked by `valid`
        solve_items(items, st, phi, w1, e1, scale, conditions, on_failure, mech, tracks)
    return st, conditions


def solve_items(items, st, phi, w1, e1, scale, conditions, on_failure, mech, tracks=None) -> None:
    """Solve ``items`` in order into the state ``st`` (see `solve_block`)."""
    for item in items:
        if isinstance(item, Crank):
            solve_crank(item, st, phi, w1, e1)
        elif isinstance(item, LinkPoint):
            solve_link_point(item, st)
        else:
            res = solve_group(item, st, scale, phi, tracks[item.name] if item.tracked else None)
            check_closed(item, res.closed, phi, on_failure)
            for name, m in res.points.items():
                st.put_point(name, m)
            for name, m in res.links.items():
                st.put_link(name, m)
            for name, m in res.slides.items():
                st.put_slide(name, m)
            st.units.update(res.units)
            st.spins.update(res.spins)
            slot = None if st.sink is None else st.sink.conditions.get(item.name)
            if slot is None:
                conditions[item.name] = np.where(res.closed, res.condition, np.nan)
            else:
                np.copyto(slot, res.condition)
                if not res.closed.all():
                    slot[~res.closed] = np.nan
                conditions[item.name] = slot


def solve_link_point(item: LinkPoint, st: State) -> None:
    """A point of a link: its position from the link's unit vector (kept for the link's other
    points), its velocity and acceleration carried from the link's origin (`carry`), written
    into the outputs where the state has them."""
    link = st.links[item.link]
    o = st.points[link.origin]
    e = st.units.get(item.link)
    if e is None:  # `link_point`, its unit vector kept for the link's other points
        e = st.units[item.link] = cis(link.theta)
    slot = st.out_point(item.name)
    if slot is None:
        x = o.p + (item.along + 1j * item.offset) * e
        st.points[item.name] = Motion(x, *carry(o.p, o.v, o.a, link.omega, link.epsilon, x))
        return
    x = np.multiply(item.along + 1j * item.offset, e, out=slot.p)
    x += o.p
    r = x - o.p  # as `carry`: the same numbers
    spin = st.spins.get(item.link)
    if spin is None:  # i·ω and i·ε − ω², kept for the link's other points
        acc = np.multiply(link.epsilon, 1j)
        acc -= link.omega * link.omega
        spin = st.spins[item.link] = (1j * link.omega, acc)
    if link.origin in st.fixed:  # the link turns about a ground point: v = i·ω·r, a = (i·ε − ω²)·r
        np.multiply(spin[0], r, out=slot.v)
        np.multiply(spin[1], r, out=slot.a)
        st.points[item.name] = slot
        return
    t = np.multiply(spin[0], r)
    np.add(o.v, t, out=slot.v)
    np.multiply(spin[1], r, out=t)
    np.add(o.a, t, out=slot.a)
    st.points[item.name] = slot


def solve_crank(c: Crank, st: State, phi: np.ndarray, w1: float, e1: float) -> None:
    slot, link = st.out_point(c.tip), st.out_link(c.link)
    if slot is None or link is None or np.ndim(w1) or np.ndim(e1):
        st.points[c.tip] = Motion(*crank_tip(st.points[c.pivot].p, c.length, phi, w1, e1))
        n = phi.shape[0]
        st.links[c.link] = LinkMotion(c.pivot, phi.copy(), np.full(n, w1), np.full(n, e1))
        return
    r = c.length * cis(phi)  # `crank_tip`'s numbers, written into the outputs
    np.add(st.points[c.pivot].p, r, out=slot.p)
    np.multiply(1j * w1, r, out=slot.v)
    np.multiply(1j * e1 - w1 * w1, r, out=slot.a)
    st.points[c.tip] = slot
    np.copyto(link.theta, phi)
    link.omega.fill(w1)
    link.epsilon.fill(e1)
    st.links[c.link] = LinkMotion(c.pivot, link.theta, link.omega, link.epsilon)


def group_point(g: Group) -> str:
    """The point a group is said to solve for, used in messages."""
    return g.solved_point()


def check_closed(g: Group, closed: np.ndarray, phi: np.ndarray, on_failure: str) -> None:
    if on_failure == "raise" and not closed.all():
        bad = float(np.degrees(phi[np.argmin(closed)]))
        raise AssemblyError(
            f"group {g.name!r} ({g.kind}) cannot be assembled: point {group_point(g)!r} "
            f"has no position at crank angle {bad:.6g}°",
            group=g.name,
            point=group_point(g),
            phi_deg=bad,
        )


def about_pivot(mech: Mechanism) -> tuple[Mechanism, np.ndarray]:
    """``mech`` moved so that its crank's pivot is at the origin, and the shift (m)."""
    pivot = np.array(dict(mech.ground)[mech.crank.pivot], float)
    if not pivot.any():
        return mech, pivot
    from dataclasses import replace

    ground = tuple((n, (x - pivot[0], y - pivot[1])) for n, (x, y) in mech.ground)
    groups = tuple(g.shifted(-pivot[0], -pivot[1]) for g in mech.groups)
    return replace(mech, ground=ground, groups=groups), pivot


ONE_ASSIGNMENT = 1024
"""Up to this many positions a block's outputs are written in one assignment per kind (numpy's
dispatch, not the copying, is the cost); above it row by row (one copy, not two)."""


def _fill(target: np.ndarray, rows: list, where: slice) -> None:
    """``target[i, j, where] = rows[i][j]`` for every i, j: in one assignment for a small block
    (unless a value is given once for the whole block), else one row at a time."""
    if where.stop - where.start <= ONE_ASSIGNMENT:
        try:
            target[:, :, where] = rows
            return
        except ValueError:  # a scalar among the rows: each row broadcasts on its own
            pass
    for i, row in enumerate(rows):
        for j, arr in enumerate(row):
            target[i, j, where] = arr


def output_index(st: State, conditions: dict) -> dict:
    """Where each result sits in the outputs (`Kinematics`' point_index, link_index, link_origins,
    slide_index and group_index), in the order the state ``st`` made them."""
    links = [k for k in st.links if k != GROUND]
    return {"point_index": {k: i for i, k in enumerate(st.points)}, "link_index": {k: i for i, k in enumerate(links)},
            "link_origins": {k: st.links[k].origin for k in links},
            "slide_index": {k: i for i, k in enumerate(st.slides)},
            "group_index": {k: i for i, k in enumerate(conditions)}}


class Sink:
    """One block's views of `Outputs` (name → `Motion`, `LinkMotion`, the slide's (s, ṡ, s̈) rows,
    the group's condition row): the state writes what it solves straight into them. A derivative
    above the outputs' ``order`` gets a scratch array."""

    def __init__(self, out: "Outputs", where: slice):
        self.outputs, self.where = out, where
        n = where.stop - where.start
        k = out.order + 1
        idx = out.index

        def rows(arr, i):
            return [arr[d, i, where] for d in range(k)] + [np.empty(n, arr.dtype) for _ in range(3 - k)]

        self.points = {name: Motion(*rows(out.z, i)) for name, i in idx["point_index"].items()}
        self.links = {name: LinkMotion(idx["link_origins"][name], *rows(out.rates, i))
                      for name, i in idx["link_index"].items()}
        self.slides = {name: [out.slides[i, d, where] for d in range(k)] + [np.empty(n) for _ in range(3 - k)]
                       for name, i in idx["slide_index"].items()}
        self.conditions = {name: out.condition[i, where] for name, i in idx["group_index"].items()}


class Outputs:
    """Preallocated result arrays, point- (link-, slide-, group-) major so that each block
    writes contiguous rows; `kinematics` returns (n, …) views of them without a copy. Only the
    derivatives up to ``order`` are kept."""

    def __init__(self, st: State | None, conditions: dict | None, n: int, order: int = 2, index: dict | None = None):
        self.index = output_index(st, conditions) if index is None else index
        """The results' names → rows (`output_index`): given, when known from an earlier solve."""
        self.names = list(self.index["point_index"])
        self.links = list(self.index["link_index"])
        self.slide_names = list(self.index["slide_index"])
        self.groups = list(self.index["group_index"])
        self.order = order
        P, L, S, G = len(self.names), len(self.links), len(self.slide_names), len(self.groups)
        k = order + 1
        self.z = np.empty((k, P, n), dtype=complex)  # positions, velocities, accelerations
        self.rates = np.empty((k, L, n))  # angles, ω, ε
        self.slides = np.empty((S, k, n))
        self.condition = np.empty((G, n))
        self.valid = np.empty(n, dtype=bool)

    def sink(self, where: slice) -> Sink:
        """The views a block at the positions ``where`` is solved into (`solve_block`'s ``sink``)."""
        return Sink(self, where)

    def write(self, st: State, conditions: dict, where: slice) -> None:
        """Copy a block's motions to the positions ``where`` (one assignment per kind of output:
        numpy's dispatch, not the copying, is the cost at a few positions; nothing where the
        block was solved into this `sink`), then mark them (`_mark`) while they are still in the
        CPU's caches."""
        if st.sink is not None and st.sink.outputs is self and st.sink.where == where:
            self._mark(where)
            return
        k = self.order + 1
        pts = [st.points[name] for name in self.names]
        _fill(self.z, [[m.p for m in pts], [m.v for m in pts], [m.a for m in pts]][:k], where)
        if self.links:
            lks = [st.links[name] for name in self.links]
            _fill(self.rates, [[m.theta for m in lks], [m.omega for m in lks], [m.epsilon for m in lks]][:k], where)
        if self.slide_names:
            _fill(self.slides, [[m.p.real, m.v.real, m.a.real][:k]
                                for m in (st.slides[name] for name in self.slide_names)], where)
        if self.groups:
            self.condition[:, where] = [conditions[name] for name in self.groups]
        self._mark(where)

    def _mark(self, where: slice) -> None:
        """Valid positions among ``where`` (every output finite, every group closed and its
        velocities within `SINGULAR_BOUND`), and their angles wrapped into (−π, π]."""
        z, rates, condition = self.z[:, :, where], self.rates[:, :, where], self.condition[:, where]
        with np.errstate(invalid="ignore"):
            total = z.sum(axis=(0, 1)) + rates[1:].sum(axis=(0, 1)) + condition.sum(axis=0)
            valid = np.isfinite(total) & (condition > 0).all(axis=0)
        if self.order >= 1 and condition.size and not np.fmin.reduce(condition, axis=None) >= WELL_CONDITIONED:
            valid &= velocity_bound(condition) <= SINGULAR_BOUND
        self.valid[where] = valid
        if rates.shape[1]:  # cranks and guides may leave (−π, π]: those rows are wrapped
            angles = rates[0]
            for j in np.flatnonzero(((angles > np.pi) | (angles <= -np.pi)).any(axis=1)):
                angles[j] = wrap_angle(angles[j])

    def shift(self, by: complex) -> None:
        """Move every position by ``by`` (m, x + iy), in place."""
        if by:
            self.z[0] += by

    def keep(self, order: int) -> None:
        """Drop the derivatives above ``order`` (views: nothing is copied)."""
        self.order = order
        self.z, self.rates, self.slides = self.z[:order + 1], self.rates[:order + 1], self.slides[:, :order + 1]

    def kinematics(self, mech, phi, w1, e1, st: State, valid: np.ndarray | None = None) -> Kinematics:
        """The results as `Kinematics`: ``valid`` as given (the compiled kernel's, which wraps its
        angles itself) and refused where singular, else as `write` marked it block by block."""
        n = phi.shape[0]
        k = self.order + 1
        xy = self.z.view(float).reshape(k, len(self.names), n, 2).transpose(0, 2, 1, 3)
        if valid is None:
            valid = self.valid
        elif self.order >= 1 and self.condition.size:
            valid = valid & (velocity_bound(self.condition) <= SINGULAR_BOUND)
        rates = self.rates.transpose(0, 2, 1)
        return Kinematics(
            mechanism=mech,
            phi=phi,
            omega1=w1,
            epsilon1=e1,
            positions=xy[0],
            velocities=xy[1] if k > 1 else None,
            accelerations=xy[2] if k > 2 else None,
            angles=rates[0],
            omegas=rates[1] if k > 1 else None,
            epsilons=rates[2] if k > 2 else None,
            slides=self.slides.transpose(2, 0, 1),
            condition=self.condition.T,
            valid=valid,
            order=self.order,
            **self.index,
        )
