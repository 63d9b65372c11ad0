"""A seeded fuzz of class III groups (issue 35): mutants of the catalogue's triad-press,
triad-rocker, triad-eight-link and of stephenson-six-bar driven by its rocker 5 (the same
chain, then a crank and a triad), with their lengths, assemblies, ``side``, ``pair`` and
leads (a rod made a block on a guide of the frame or of the crank, a block made a rod; two
block leads included) changed at random.

Every mutant either solves or is refused with a one-line `VelplanError`, never another
exception nor a warning. A solved one, at its well-conditioned positions, meets the oracles:
velocities and accelerations are 12th-order differences of its own positions over the turn
(the points the JSON marks as not material excepted), and the balancing moment is the same by
kinetostatics, Zhukovsky's lever and the power balance.
"""

from __future__ import annotations

import cmath
import copy
import json
import math
import tomllib
import warnings
from math import factorial
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.cli.kinematics import to_json
from velplan.errors import VelplanError
from velplan.forces.agreement import mechanism_actions
from velplan.forces.kinetostatics import kinetostatics
from velplan.forces.lever import lever_balancing_moment
from velplan.forces.power import power_balancing_moment
from velplan.mechanism.loader import from_dict

CATALOGUE = Path(velplan.__file__).parent / "catalogue"
MUTANTS = 14
"""Mutants of each of the four mechanisms (about 7 s each on one core)."""
N = 96
"""Positions over the turn for the differences (3.75° apart)."""
WELL = 0.02
"""Condition below which a position is left out of the oracles (differences and force
balances lose digits near a singular position; the solver refuses below 1e-4)."""


def _text(name: str) -> dict:
    return tomllib.loads((CATALOGUE / f"{name}.toml").read_text(encoding="utf-8"))


def _cis(deg: float) -> complex:
    return cmath.exp(1j * math.radians(deg))


def _at(mech, phi_deg: float) -> dict[str, complex]:
    """Every point of ``mech`` at the crank angle ``phi_deg``, complex m."""
    kin = velplan.solve(mech, np.radians([phi_deg]), order=0)
    return {n: complex(*kin.positions[0, i]) for n, i in kin.point_index.items()}


def stephenson_as_triad() -> dict:
    """stephenson-six-bar driven by its rocker 5, shortened to a 0.02 m crank about O5 (the
    only way this chain turns fully from link 5, of those tried: 0.02 … 0.1 m at every 60° of
    the old crank): the coupler 2 (E, A, B) becomes a triad's base tied by the rod 4 to the
    crank's tip D, by the old crank 1 to O1 and by the rocker 3 to O3; the joints as drawn at
    the old crank's 240°."""
    old = _text("stephenson-six-bar")
    at = _at(from_dict(old), 240.0)
    o = {k: complex(*v) for k, v in old["ground"].items()}
    psi = math.degrees(cmath.phase(at["D"] - o["O5"]))
    d = o["O5"] + 0.02 * _cis(psi)
    e, a, b = at["E"], at["A"], at["B"]
    side = 1 if ((a - e).conjugate() * (b - e)).imag > 0 else -1
    rods = {"4": ("D", abs(e - d)), "1": ("O1", abs(a - o["O1"])), "3": ("O3", abs(b - o["O3"]))}
    data = {"name": "stephenson-triad", "ground": old["ground"],
            "crank": {"link": "5", "pivot": "O5", "tip": "D", "length": 0.02, "rpm": 180.0},
            "group": [{"kind": "triad", "base": "2", "joints": ["E", "A", "B"],
                       "sides": [abs(a - e), abs(b - a), abs(e - b)], "side": side,
                       "leads": [{"link": k, "joint": j, "length": ln} for k, (j, ln) in rods.items()],
                       "assembly": {"phi_deg": psi, "E": [e.real, e.imag], "A": [a.real, a.imag],
                                    "B": [b.real, b.imag]}}],
            "point": [{"name": f"S{k}", "link": k, "along": ln / 2, "offset": 0.01} for k, (_, ln) in rods.items()]
            + [{"name": "S2", "link": "2", "along": abs(a - e) / 2, "offset": 0.02 * side}],
            "link": {k: {"mass": 1.0 + 0.5 * i, "inertia": 0.002 * (i + 1), "centre": f"S{k}"}
                     for i, k in enumerate(("1", "2", "3", "4"))},
            "load": [{"kind": "moment", "name": "M3", "link": "3", "moment": -6.0}]}
    return data


BASES = {"triad-press": lambda: _text("triad-press"), "triad-rocker": lambda: _text("triad-rocker"),
         "triad-eight-link": lambda: _text("triad-eight-link"), "stephenson-six-bar": stephenson_as_triad}


# ---- mutations -----------------------------------------------------------------------------------


class Mutant:
    """A mechanism's data with its (first) triad ``g`` and the points known before it at the
    assembly angle (``known``, complex m), and the joints there as drawn (``drawn``)."""

    def __init__(self, data: dict, rng: np.random.Generator):
        self.data, self.rng = copy.deepcopy(data), rng
        self.g = next(g for g in self.data["group"] if g["kind"] == "triad")
        phi = self.g["assembly"]["phi_deg"]
        at = _at(from_dict(data), phi)
        self.drawn = {j: at[j] for j in self.g["joints"]}
        self.known = {k: v for k, v in at.items() if k in self._before()}
        self.crank_angle = phi
        self.size = max(self.g["sides"])
        self.done: list[str] = []

    def _before(self) -> set[str]:
        """Names solved before the triad: ground points, the crank's tip, earlier groups' points."""
        names = set(self.data["ground"]) | {self.data["crank"]["tip"]}
        for g in self.data["group"]:
            if g is self.g:
                break
            names.add(g.get("point", ""))
            names |= {p["name"] for p in self.data.get("point", []) if p["link"] in g.get("links", ())}
        return names - {""}

    def lengths(self) -> None:
        s = self.rng.choice([0.01, 0.01, 0.03, 0.15])
        self.g["sides"] = [x * math.exp(self.rng.normal(0, s)) for x in self.g["sides"]]
        for lead in self.g["leads"]:
            if "length" in lead:
                lead["length"] *= math.exp(self.rng.normal(0, s))
        self.done.append(f"lengths ×e^N(0,{s})")

    def side(self) -> None:
        self.g["side"] = -self.g.get("side", 1)
        self.done.append("side flipped")

    def pair(self) -> None:
        choice = [None, [1, 2], [1, 3], [2, 3], [1, 2], [2, 3], [2, 2]][self.rng.integers(7)]
        self.g.pop("pair", None)
        if choice is not None:
            self.g["pair"] = choice
        self.done.append(f"pair {choice}")

    def assembly(self) -> None:
        asm = {"phi_deg": self.g["assembly"]["phi_deg"]}
        keep = self.g["joints"] if self.rng.random() < 0.7 else [self.g["joints"][self.rng.integers(3)]]
        spread = self.rng.choice([0.01, 0.01, 0.03, 0.5]) * self.size
        for j in keep:
            z = self.drawn[j] + spread * complex(*self.rng.normal(0, 1, 2))
            asm[j] = [z.real, z.imag]
        self.g["assembly"] = asm
        self.done.append(f"assembly {keep} ±{spread:.3g} m")

    def block(self, k: int | None = None, spread: float = 20.0, moving: float = 0.3) -> None:
        """Lead ``k`` (a rod) made a block on a guide through its joint as drawn, along the
        tangent of the rod's arc there give or take ``spread`` degrees: a guide of the frame
        through a ground point, or (with the probability ``moving``) of the crank through its
        tip."""
        rods = [i for i, lead in enumerate(self.g["leads"]) if "length" in lead]
        if not rods:
            return
        k = rods[self.rng.integers(len(rods))] if k is None else k
        j = self.drawn[self.g["joints"][k]]
        tangent = math.degrees(cmath.phase(1j * (j - self.known[self.g["leads"][k]["joint"]])))
        world = tangent + float(self.rng.normal(0.0, spread))
        if self.rng.random() >= moving:
            through = list(self.data["ground"])[self.rng.integers(len(self.data["ground"]))]
            link, angle = "0", world
        else:
            through, link = self.data["crank"]["tip"], self.data["crank"]["link"]
            angle = world - self.crank_angle
        u = _cis(world)
        offset = (u.conjugate() * (j - self.known[through])).imag
        guide = {"link": link, "through": through, "angle_deg": angle, "offset": offset}
        self.g["leads"][k] = {"link": self.g["leads"][k]["link"], "guide": guide}
        self.done.append(f"lead {k + 1} a block on {guide}")

    def rod(self) -> None:
        """A block lead made a rod from a point known before the triad (two rods from one
        point make a truss: refused)."""
        blocks = [i for i, lead in enumerate(self.g["leads"]) if "guide" in lead]
        if not blocks:
            return
        k = blocks[self.rng.integers(len(blocks))]
        used = {lead.get("joint") for lead in self.g["leads"]}
        names = sorted(self.known)
        free = [n for n in names if n not in used]
        pool = free if free and self.rng.random() < 0.8 else names
        p = pool[self.rng.integers(len(pool))]
        length = abs(self.drawn[self.g["joints"][k]] - self.known[p])
        if length < 1e-6:
            return
        self.g["leads"][k] = {"link": self.g["leads"][k]["link"], "joint": p, "length": length}
        self.done.append(f"lead {k + 1} a rod from {p}")


def mutant(name: str, seed: int) -> tuple[dict, list[str]]:
    rng = np.random.default_rng(seed)
    m = Mutant(BASES[name](), rng)
    ops = [m.lengths, m.side, m.pair, m.assembly, m.block, m.rod]
    weights = np.array([4, 1, 2, 2, 3, 2], float)
    if seed % 3 == 0:  # two block leads and one rod, then lengths, pair or assembly
        rods = [i for i, lead in enumerate(m.g["leads"]) if "length" in lead]
        for k in list(rng.permutation(rods))[:len(rods) - 1]:
            m.block(int(k), spread=5.0, moving=0.15)
        weights[[1, 4, 5]] = 0.0
    for k in rng.choice(len(ops), size=rng.integers(1, 3), replace=False, p=weights / weights.sum()):
        ops[k]()
    return m.data, m.done


# ---- the oracles -----------------------------------------------------------------------------------


def central_difference(f: np.ndarray, h: float, m: int) -> np.ndarray:
    """df/dφ of periodic samples (axis 0, step h) by the central difference of order 2m."""
    out = np.zeros_like(f)
    for k in range(1, m + 1):
        w = (-1) ** (k + 1) * factorial(m) ** 2 / (k * factorial(m - k) * factorial(m + k))
        out = out + w * (np.roll(f, -k, axis=0) - np.roll(f, k, axis=0))
    return out / h


def check_derivatives(mech, kin, good: np.ndarray, where: str) -> int:
    """Velocities and accelerations of the unmarked points against differences of positions
    (order 12; the allowance: 1e-6 of the largest value or 30 times the gap to order 8) at the
    positions ``good`` whose stencil is well conditioned too. Returns the points compared."""
    doc = json.loads(to_json(kin))["positions"]
    names = [k for k, p in doc[0]["points"].items() if "kind" not in p]
    assert all(doc[0]["points"][k]["kind"] in ("special", "coincident") for k in doc[0]["points"] if k not in names)
    get = lambda keys: np.array([[[p["points"][n][q] for q in keys] for n in names] for p in doc])  # noqa: E731
    x, v, a = get(("x", "y")), get(("vx", "vy")), get(("ax", "ay"))
    h, w1 = 2 * math.pi / N, mech.crank.omega
    stencil = np.ones(N, bool)
    for k in range(-6, 7):
        stencil &= np.roll(good, k)
    for f, exact, what in ((x, v, "velocity"), (v, a, "acceleration")):
        fd12, fd8 = w1 * central_difference(f, h, 6), w1 * central_difference(f, h, 4)
        scale = np.max(np.abs(exact[stencil]), initial=0.0)
        gap = np.max(np.abs(fd12 - fd8)[stencil], initial=0.0)
        err = np.max(np.abs(fd12 - exact)[stencil], initial=0.0)
        assert err <= max(1e-6 * scale, 30 * gap, 1e-12), f"{where}: {what} differs from the differences by {err:.3g}"
    return len(names) if stencil.any() else 0


def check_forces(mech, kin, good: np.ndarray, where: str) -> None:
    """The balancing moment by the three methods, with the file's loads (or, where a mutant's
    output no longer suits them, gravity and inertia alone)."""
    try:
        acts = mechanism_actions(mech, kin)
    except VelplanError as exc:
        assert "\n" not in str(exc), f"{where}: a refusal of more than one line: {exc}"
        acts = mechanism_actions(mech, kin, loads=())
    mb = kinetostatics(mech, kin, acts).balancing_moment
    scale = np.max(np.abs(mb[good]), initial=0.0)
    for label, other in (("lever", lever_balancing_moment(mech, kin, acts, mu_v=0.01)),
                         ("power", power_balancing_moment(kin, acts))):
        err = np.max(np.abs(other - mb)[good], initial=0.0)
        assert err <= 1e-8 * max(scale, 1e-6), f"{where}: {label} differs from kinetostatics by {err:.3g} N·m"


def run(name: str, seed: int) -> tuple[str, int]:
    """'refused', 'solved' (oracles met) or 'singular' (solved, too few good positions), and
    the number of block leads of the mutant's triad."""
    data, done = mutant(name, seed)
    blocks = sum("guide" in lead for g in data["group"] if g["kind"] == "triad" for lead in g["leads"])
    where = f"{name} seed {seed} ({'; '.join(done) or 'unchanged'}): {json.dumps(data['group'])}"
    try:
        mech = from_dict(data, name=f"{name}-{seed}")
        phi = np.arange(N) * 2 * math.pi / N
        velplan.Study(mech, n=4)  # checks the assembly over the whole turn
        kin = velplan.solve(mech, phi)
    except VelplanError as exc:
        text = str(exc)
        assert text and "\n" not in text, f"{where}: a refusal of more than one line: {text!r}"
        return "refused", blocks
    triad = next(g for g in data["group"] if g["kind"] == "triad")
    outer = [lead["joint"] for lead in triad["leads"] if "joint" in lead]
    assert len(set(outer)) == len(outer), f"{where}: two rods from one joint (a truss) accepted as a triad"
    assert kin.valid.any() or kin.singular.any(), f"{where}: solved, yet not one position closes"
    good = kin.valid & (kin.min_condition() >= WELL)
    if good.sum() < N // 2:
        return "singular", blocks
    compared = check_derivatives(mech, kin, good, where)
    check_forces(mech, kin, good, where)
    return ("solved" if compared else "singular"), blocks


@pytest.mark.parametrize("name", sorted(BASES))
def test_mutants_solve_with_the_oracles_or_are_refused_in_one_line(name):
    outcomes = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning reaching the user is a failure too
        for seed in range(MUTANTS):
            outcomes[seed] = run(name, seed)
    solved = [s for s, (o, _) in outcomes.items() if o == "solved"]
    assert len(solved) >= MUTANTS // 4, f"{name}: too few mutants solved to test anything: {outcomes}"
    assert any(outcomes[s][1] == 2 for s in solved), f"{name}: no mutant with two block leads solved: {outcomes}"


def test_the_stephenson_chain_as_a_triad_turns_fully():
    mech = from_dict(stephenson_as_triad())
    kin = velplan.Study(mech, n=36).kinematics
    assert kin.valid.all() and mech.groups[0].kind == "triad"
    assert [lead.slider for lead in mech.groups[0].leads] == [False, False, False]
