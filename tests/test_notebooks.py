"""The teaching notebooks run, and show the right numbers (DESIGN.md item 10).

Every notebook in ``notebooks/`` is executed with nbclient (kernel ``python3``, working
directory ``notebooks/``, IPython and Jupyter state in a temporary directory). The cells
tagged ``readout`` print ``name = value unit`` lines; every such line is compared with a value
computed here, independently of the plans: from the analytic solver (``velplan.solve``) and
from closed forms (V_A = ω1·l1, aᵏ = 2·ω·V_rel, the shaper's extreme crank angle and
stroke, the four-bar's transmission angle). A readout this file does not know fails too, so
no number reaches a student unchecked. The stored notebooks are exactly what
``notebooks/build.py`` writes (their outputs aside: they are stored executed).
"""

from __future__ import annotations

import ast
import copy
import csv
import importlib.util
import json
import math
import os
import re
import sys
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path
from typing import Callable

import nbformat
import numpy as np
import pytest
from nbclient import NotebookClient

import velplan
from velplan.plans.check import check_table

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
CELL_TIMEOUT_S = 120
STEMS = ("01-velocity-plan-step-by-step", "02-graphical-vs-analytic",
         "03-acceleration-plan-coriolis", "04-your-own-mechanism",
         "05-flywheel-and-equation-of-motion", "06-catalogue-variants-and-cad",
         "07-class-three-and-instant-centres")


# -- executing ------------------------------------------------------------------------------

def _listing(*dirs: Path) -> set[str]:
    return {str(p) for d in dirs for p in d.rglob("*") if "__pycache__" not in p.parts}


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    """stem → the notebook as executed, plus the files of the repository before and after."""
    state = tmp_path_factory.mktemp("jupyter")
    before = _listing(NOTEBOOKS) | {str(p) for p in ROOT.iterdir()}
    out = {}
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("IPYTHONDIR", str(state / "ipython"))
        mp.setenv("JUPYTER_RUNTIME_DIR", str(state / "runtime"))
        mp.setenv("PYTHONPATH", os.pathsep.join(
            [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
        mp.delenv("MPLBACKEND", raising=False)
        for stem in STEMS:
            nb = nbformat.read(NOTEBOOKS / f"{stem}.ipynb", as_version=4)
            NotebookClient(nb, kernel_name="python3", timeout=CELL_TIMEOUT_S,
                           resources={"metadata": {"path": str(NOTEBOOKS)}}).execute()
            out[stem] = nb
    after = _listing(NOTEBOOKS) | {str(p) for p in ROOT.iterdir()}
    return out, before, after


# -- reading the readouts ----------------------------------------------------------------------

_NUMBER = r"[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?|[-+]?nan|[-+]?inf"
READOUT = re.compile(rf"^(?P<name>\S.*?) = (?P<value>{_NUMBER})(?: (?P<unit>\S.*))?$")


def _stdout(cell) -> str:
    return "".join(o.text for o in cell.get("outputs", [])
                   if o.output_type == "stream" and o.name == "stdout")


def tagged(nb, tag: str) -> list:
    return [c for c in nb.cells if c.cell_type == "code" and tag in c.metadata.get("tags", [])]


def readouts(nb) -> dict[str, float]:
    """Every ``name = value`` line printed by the cells tagged ``readout``."""
    out: dict[str, float] = {}
    for cell in tagged(nb, "readout"):
        for line in _stdout(cell).splitlines():
            if " = " not in line:
                continue  # a heading or a list line ("group 2-5: RRR")
            m = READOUT.match(line.strip())
            if m is None:
                raise ValueError(f"readout line {line!r} is not `name = number unit`")
            if m["name"] in out:
                raise ValueError(f"readout {m['name']!r} is printed twice")
            out[m["name"]] = float(m["value"])
    return out


# -- what the readouts must be -----------------------------------------------------------------

@dataclass(frozen=True)
class Near:
    """The value within `tol` (absolute); `optional`: it need not be printed."""

    value: float
    tol: float
    optional: bool = False

    def ok(self, got: float) -> bool:
        return math.isfinite(got) and abs(got - self.value) <= self.tol

    def __str__(self) -> str:
        return f"{self.value:.8g} ± {self.tol:.2g}"


@dataclass(frozen=True)
class Within:
    """The value in [lo, hi]."""

    lo: float
    hi: float
    optional: bool = False

    def ok(self, got: float) -> bool:
        return math.isfinite(got) and self.lo <= got <= self.hi

    def __str__(self) -> str:
        return f"in [{self.lo:.4g}, {self.hi:.4g}]"


@dataclass
class Expected:
    """Named checks, checks for names matching a pattern, and names that must be printed."""

    fixed: dict
    patterns: list[tuple[re.Pattern, Callable]] = None
    required: list[tuple[re.Pattern, int]] = None  # (pattern, how many names must match it)


def check(found: dict[str, float], expected: Expected) -> list[str]:
    """Failures of `found` readouts against `expected`, one line each."""
    failures = []
    for name, want in expected.fixed.items():
        if name not in found and not want.optional:
            failures.append(f"{name}: not printed (expected {want})")
    for name, got in found.items():
        want = expected.fixed.get(name)
        if want is None:
            for pattern, make in expected.patterns or ():
                m = pattern.fullmatch(name)
                if m:
                    want = make(m)
                    break
        if want is None:
            failures.append(f"{name} = {got}: a readout this test does not check")
        elif not want.ok(got):
            failures.append(f"{name} = {got}, expected {want}")
    for pattern, count in expected.required or ():
        matching = [n for n in found if pattern.fullmatch(n)]
        if len(matching) != count:
            failures.append(f"{count} readouts like {pattern.pattern!r} expected, "
                            f"found {len(matching)}: {', '.join(matching)}")
    return failures


SIX = 2e-6   # a value printed with 6 decimals
FOUR = 2e-4  # with 4 decimals


def _speed(kin, p, i):
    return float(np.hypot(*kin.velocity(p)[i]))


def _standard_up(x: float) -> float:
    """The standard drawing scale (1, 2, 2.5, 4, 5 × 10ᵏ) at or above x."""
    k = math.floor(math.log10(x))
    for m in (1.0, 2.0, 2.5, 4.0, 5.0, 10.0):
        if m * 10.0 ** k >= x * (1 - 1e-12):
            return m * 10.0 ** k
    raise AssertionError(x)


def expected_01() -> Expected:
    """The press (seed 000) at position 3 (φ = 60°), μv = 0.0007 (m/s)/mm."""
    mech = velplan.load("press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    i, mu, w1, l1 = 2, 0.0007, 1.0, 0.05
    assert math.isclose(kin.phi_deg[i] % 360, 60.0)
    v = {p: _speed(kin, p, i) for p in ("A", "B2", "C", "E", "B4")}
    def rel(p, q):  # a relative velocity, mm on the plan
        return float(np.hypot(*(kin.velocity(p)[i] - kin.velocity(q)[i]))) / mu
    fixed = {
        # structure: links 1…5; pairs O1, A, C, O2, B2 (R), slot and guide (P)
        "n": Near(5, 0), "p5": Near(7, 0), "p4": Near(0, 0), "W": Near(1, 0),
        "V_A": Near(w1 * l1, SIX), "pa": Near(w1 * l1 / mu, FOUR),
        "ac": Near(rel("C", "A"), FOUR), "pc": Near(v["C"] / mu, FOUR),
        "ab2": Near(rel("B2", "A"), FOUR), "pe": Near(v["E"] / mu, FOUR),
        "b2b4": Near(rel("B4", "B2"), FOUR), "pb4": Near(v["B4"] / mu, FOUR),
        "ω1·l1": Near(w1 * l1, SIX),
        "V_E/V_C": Near(0.105 / 0.21, SIX),  # E halves the rocker O2C
        "largest relative error": Near(0.0, 1e-5),
    }
    for p in ("B2", "C", "E", "B4"):
        fixed[f"V_{p}"] = Near(v[p], SIX)
    for p in v:
        fixed[f"V_{p} analytic"] = Near(v[p], SIX)
    for link in ("2", "5"):
        fixed[f"ω{link}"] = fixed[f"ω{link} analytic"] = Near(float(kin.omega(link)[i]), SIX)
    # the table: |V_B4|/ω1 and ω5/ω1 at the 12 positions; the punch stops at 1 and 7
    assert _speed(kin, "B4", 0) < 1e-12 and _speed(kin, "B4", 6) < 1e-12
    for k in range(12):
        fixed[f"VB4/ω1[{k + 1}]"] = Near(_speed(kin, "B4", k) / w1, SIX)
        fixed[f"ω5/ω1[{k + 1}]"] = Near(float(kin.omega("5")[k]) / w1, SIX)
    return Expected(fixed)


def _hand(v: float, mu: float) -> float:
    """What a 0.5 mm / 0.5° drafting can do to a speed v drawn at mu, generously."""
    return 2 * 0.5 * mu + abs(v) * math.radians(1.0)


def _transmission_sine(phi, a=0.10, b=0.25, c=0.20, d=0.3499):
    """|sin| of the angle between coupler AB and rocker DB of the four-bar, closed form."""
    ad2 = a * a + d * d - 2 * a * d * np.cos(phi)
    cos_mu = (b * b + c * c - ad2) / (2 * b * c)
    return np.sqrt(1 - cos_mu ** 2)


def _press_table() -> dict[str, list[float | None]]:
    text = (files("velplan.examples") / "press-table2.csv").read_text("utf-8")
    rows = list(csv.reader(text.splitlines()))
    n = 12
    return {r[0]: [float(c) if c.strip() else None for c in r[1:n + 1]] for r in rows[1:]}


def expected_02() -> Expected:
    """The shaper at position 3, μv = 0.02; its extreme position; a near-singular four-bar;
    seed 000's table."""
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    i, mu = 2, 0.02
    vF, w4 = _speed(kin, "F", i), float(kin.omega("4")[i])
    l_O3A = float(np.hypot(*(kin.position("A")[i] - kin.position("O3")[i])))
    fixed = {
        "V_F exact": Near(vF, SIX),
        "V_F drafted": Near(vF, _hand(vF, mu)),
        "ω4 exact": Near(w4, SIX),
        "ω4 drafted": Near(w4, _hand(_speed(kin, "A4", i), mu) / l_O3A),
        "error of V_F drafted": Within(0.0, 100 * _hand(vF, mu) / vF),
        "largest error of the exact plan": Near(0.0, 1e-5),
    }
    # the Monte-Carlo error: between a fifth of and the sum of the two drafting errors
    turn = velplan.solve(mech, np.radians(np.arange(0.0, 360.0, 0.25)))
    v_max = float(np.hypot(*turn.velocity("F").T).max())
    for d in (0.25, 0.5, 1.0):
        for m in (0.005, 0.01, 0.02, 0.04, 0.08):
            bound = 100 * (d * m / v_max + math.radians(d))
            fixed[f"error(δ={d}, μv={m})"] = Within(0.2 * bound, bound)
    # the extreme position: O3A ⊥ O2A, sin φ = −l_O2A / l_O2O3
    r, h, l_bar = 0.1605, 0.370, 0.6914
    phi = -math.asin(r / h)
    dead = velplan.solve(mech, [phi])
    fb = dead.position("F")[0] - dead.position("B")[0]
    fixed.update({
        "crank angle at the extreme": Near(math.degrees(phi) % 360, 1e-3),
        "V_F at the extreme": Near(0.0, SIX),
        "ω4 at the extreme": Near(0.0, SIX),
        "sine at a4 at the extreme": Near(1.0, SIX),  # a line ∥ the bar meets a line ⊥ it
        "sine at f at the extreme": Near(abs(fb[0]) / float(np.hypot(*fb)), SIX),
        "stroke H": Near(2 * l_bar * r / h, SIX),
    })
    # the four-bar next to Grashof's limit
    deg = np.arange(0.0, 360.0, 1.0)
    sine = _transmission_sine(np.radians(deg))
    flagged = deg[sine < 0.1]
    fixed.update({
        "smallest sine at b": Near(float(_transmission_sine(math.pi)), SIX),
        "at crank angle": Near(180.0, 0.05),
        "flagged positions": Near(len(flagged), 0),
        "first flagged angle": Near(flagged[0], 0.05),
        "last flagged angle": Near(flagged[-1], 0.05),
    })
    four = velplan.parse(_toml_of(NOTEBOOKS / f"{STEMS[1]}.ipynb"))
    for d in (90.0, 180.0):
        at = velplan.solve(four, [math.radians(d)])
        vB = _speed(at, "B", 0)
        bound = 100 * _hand(vB, mu) / vB / float(_transmission_sine(math.radians(d)))
        fixed[f"drafted error of V_B at {d:.0f} deg"] = Within(0.1 * bound, bound)
    # seed 000's hand table
    table = _press_table()
    press = velplan.load("press")
    pk = velplan.solve(press, velplan.positions(press, 12))
    cells = sum(v is not None for row in table.values() for v in row)
    report = check_table(press, files("velplan.examples") / "press-table2.csv", scale_v=0.0007)
    fixed["entries checked"] = Near(cells, 0)
    fixed["entries outside the tolerance"] = Near(len(report.flagged), 0)

    def entry(m: re.Match) -> Near | None:
        quantity, position, which = m["q"], int(m["k"]), m["which"]
        given = table[quantity][position - 1]
        if which == "given":
            return Near(given, SIX)
        name = quantity.split("/")[0]
        if name.startswith("V"):
            return Near(_speed(pk, name[1:], position - 1), SIX)  # ω1 = 1 rad/s
        return Near(abs(float(pk.omega(name[1:])[position - 1])), SIX)

    pattern = re.compile(r"(?P<q>(?:V[A-Z]\w*|ω\d+)/ω1)\[(?P<k>\d+)\] (?P<which>given|exact)")
    return Expected(fixed, [(pattern, entry)])


def _split_points(text: str, names) -> list[str]:
    """``"A4O3"`` → ``["A4", "O3"]`` (longest known point names first)."""
    out = []
    while text:
        name = max((p for p in names if text.startswith(p)), key=len, default=None)
        if name is None:
            raise AssertionError(f"no point name at {text!r}")
        out.append(name)
        text = text[len(name):]
    return out


def expected_03() -> Expected:
    """The shaper's acceleration plan at position 3, μv = 0.02, μa = 0.1."""
    mech = velplan.load("shaper")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    i, mu_a = 2, 0.1
    w2 = 80.0 * 2 * math.pi / 60.0
    w4 = kin.omega("4")
    s_dot, s_ddot = kin.slide("P:3/4")[:, 1], kin.slide("P:3/4")[:, 2]
    coriolis = 2 * np.abs(w4 * s_dot)                  # aᵏ = 2·ω4·V_rel
    assert math.isclose(coriolis[i], 2 * abs(w4[i]) * float(np.hypot(
        *(kin.velocity("A4")[i] - kin.velocity("A")[i]))), rel_tol=1e-12)
    l_O3A = float(np.hypot(*(kin.position("A")[i] - kin.position("O3")[i])))
    fixed = {
        "ω4": Near(float(w4[i]), SIX),
        "V_A4A": Near(abs(float(s_dot[i])), SIX),
        "2·ω4·V_A4A": Near(float(coriolis[i]), SIX),
        "ω2²·l_O2A": Near(w2 ** 2 * 0.1605, SIX),
        "2·|ω4·V_rel|": Near(float(coriolis[i]), SIX),
        "ω4²·l_O3A": Near(float(w4[i]) ** 2 * l_O3A, SIX),
        "|s̈|": Near(abs(float(s_ddot[i])), SIX),
        "ε4": Near(float(kin.epsilon("4")[i]), SIX),
        "ε4 analytic": Near(float(kin.epsilon("4")[i]), SIX),
        "a_F": Near(float(kin.acceleration("F")[i][0]), SIX),
        "a_F analytic": Near(float(kin.acceleration("F")[i][0]), SIX),
        "turn from V_rel to aᵏ": Near(90.0 * np.sign(w4[i]), 1e-3),
        "sense of ω4": Near(float(np.sign(w4[i])), 0),
    }
    for k in range(12):
        fixed[f"aᵏ[{k + 1}]"] = Near(float(coriolis[k]), SIX)

    def component(m: re.Match) -> Near:
        """aⁿ, aᵗ: the parts of a_P − a_Q along and across PQ; aᵏ: 2·ω4·V_rel; aʳ: the
        sliding acceleration (the block on the bar, or the ram on its fixed guide)."""
        kind, points = m["kind"], _split_points(m["points"], kin.point_index)
        if kind == "aᵏ":
            value = float(coriolis[i])
        elif kind == "aʳ":
            value = abs(float(s_ddot[i])) if len(points) == 2 else float(
                np.hypot(*kin.acceleration(points[0])[i]))
        else:
            p, q = points
            d = kin.position(p)[i] - kin.position(q)[i]
            u = d / np.hypot(*d)
            a = kin.acceleration(p)[i] - kin.acceleration(q)[i]
            value = abs(float(a @ u)) if kind == "aⁿ" else abs(float(a[0] * u[1] - a[1] * u[0]))
        if m["plan"]:
            return Near(value / mu_a, FOUR)
        return Near(value, SIX)

    pattern = re.compile(r"(?P<kind>a[ⁿᵗᵏʳ])_(?P<points>\w+?)(?P<plan> on the plan)?")
    required = [(re.compile(rf"{k}_\w+?"), count)
                for k, count in (("aⁿ", 3), ("aᵗ", 2), ("aᵏ", 1), ("aʳ", 2))]
    required += [(re.compile(rf"{k}_\w+? on the plan"), count)
                 for k, count in (("aⁿ", 3), ("aᵗ", 2), ("aᵏ", 1), ("aʳ", 2))]
    return Expected(fixed, [(pattern, component)], required)


def _toml_of(path: Path) -> str:
    """The TOML text a notebook's cell tagged ``mechanism`` assigns to ``TOML``."""
    nb = nbformat.read(path, as_version=4)
    (cell,) = tagged(nb, "mechanism")
    for node in ast.walk(ast.parse(cell.source)):
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", None) == "TOML":
            return ast.literal_eval(node.value)
    raise AssertionError(f"{path.name}: the mechanism cell assigns no TOML")


def expected_04() -> Expected:
    """The user's four-bar with a slider (its TOML read from the notebook), position 2."""
    mech = velplan.parse(_toml_of(NOTEBOOKS / f"{STEMS[3]}.ipynb"))
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    i = 1
    # the stroke and the time-ratio from a fine sweep of the slider's travel
    phi = np.radians(np.arange(0.0, 360.0, 0.01))
    x = velplan.solve(mech, phi).position("F")[:, 0]
    lo, hi = int(np.argmin(x)), int(np.argmax(x))
    theta = abs((math.degrees(phi[lo] - phi[hi]) % 360.0) - 180.0)
    speeds = [_speed(kin, p, i) for p in kin.point_index]
    fixed = {
        "n": Near(5, 0), "p5": Near(7, 0), "W": Near(1, 0),   # O, A, B, D, E, F (R); F (P)
        "stroke H": Near(float(x[hi] - x[lo]), SIX),
        "θ": Near(theta, 0.02),
        "K": Near((180 + theta) / (180 - theta), 5e-4),
        "μv": Near(_standard_up(max(speeds) / 100.0), SIX),   # longest vector ≤ 100 mm
        "V_A": Near(10.0 * 0.10, SIX),                        # ω1·l1
        "V_E/V_B": Near(0.15 / 0.20, SIX),                    # E on the rocker DB
    }
    for p in ("B", "E", "F"):
        fixed[f"V_{p}"] = Near(_speed(kin, p, i), SIX)
    for link in ("2", "3", "4"):
        fixed[f"ω{link}"] = Near(float(kin.omega(link)[i]), SIX)
    return Expected(fixed)


def _reduced_by_power(mech, loads, phi):
    """(J_II kg·m², M_red N·m) at crank angles ``phi`` by power equality, from the solver's
    velocities at a unit crank speed in the sense of rotation: J_II = Σ m·V_S² + J_S·ω² over the
    links other than the crank, M_red = Σ F·V (loads) + Σ m·g·V_S (gravity)."""
    from velplan.forces.inertia import inertia_of

    sense = math.copysign(1.0, mech.crank.omega)
    kin = velplan.solve(mech, phi, omega1=sense)
    J = np.zeros(len(phi))
    M = np.zeros(len(phi))
    for m in mech.masses:
        v = kin.velocity(m.centre)
        M += -m.mass * mech.gravity * v[:, 1]
        if m.link != mech.crank.link:
            J += m.mass * (v[:, 0] ** 2 + v[:, 1] ** 2) + inertia_of(mech, m) * kin.omega(m.link) ** 2
    for load in loads:
        for f in load.actions(kin).forces:
            v = kin.velocity(f.point)
            M += f.vector.real * v[:, 0] + f.vector.imag * v[:, 1]
    return J, M


def expected_05() -> Expected:
    """The shaper's dynamics for δ = 0.05: reduction by power equality at the 12 positions;
    the driving moment, ω extremes and the flywheel by the envelope on a fine grid (trapezoids
    over 72 000 steps: about 1e-5 relative with the loads' jumps between nodes)."""
    study = velplan.Study("shaper", delta=0.05)
    mech = study.mechanism
    sense = math.copysign(1.0, mech.crank.omega)
    phi12 = study.phi
    J12, M12 = _reduced_by_power(mech, study.loads, phi12)
    fixed = {}
    for k in range(12):
        fixed[f"J_II[{k + 1}]"] = Near(float(J12[k]), SIX)
        fixed[f"M_red[{k + 1}]"] = Near(float(M12[k]), SIX)
    steps = 72000
    theta = np.linspace(0.0, 2 * math.pi, steps + 1)
    J, M = _reduced_by_power(mech, study.loads, phi12[0] + sense * theta)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (M[1:] + M[:-1]) * np.diff(theta))])
    md = -work[-1] / (2 * math.pi)
    A = md * theta + work
    wm, delta = abs(mech.crank.omega), 0.05
    kp, km = 0.5 * wm**2 * (1 + delta / 2) ** 2, 0.5 * wm**2 * (1 - delta / 2) ** 2
    exact = float(((A - kp * J).max() - (A - km * J).min()) / (kp - km))
    mert = float(np.ptp(A - 0.5 * wm**2 * (J - J[0])) / (delta * wm**2))
    fixed.update({
        "M_d": Near(md, 1e-4 * abs(md)),
        "ω_m": Near(wm, 1e-8),
        "ω_max": Near(wm * (1 + delta / 2), 1e-8),   # δ met exactly, about the mean
        "ω_min": Near(wm * (1 - delta / 2), 1e-8),
        "δ": Near(delta, 1e-8),
        "J_I exact": Near(exact, 5e-5 * exact),
        "J_I Wittenbauer": Near(exact, 5e-5 * exact),
        "J_I Mertsalov": Near(mert, 5e-5 * mert),
    })
    # the disc (b = 0.2·D, steel) for what is added to the crank's own inertia, mm rounded up
    crank = [m for m in mech.masses if m.link == mech.crank.link]
    assert not crank  # the shaper's crank carries no mass: all of J_I is the flywheel
    d_star = (32 * exact / (7800.0 * math.pi * 0.2)) ** 0.2
    fixed["disc diameter D"] = Within(d_star * (1 - 5e-4), d_star * (1 + 5e-4) + 0.001)
    fixed["disc width b"] = Within(0.2 * d_star * (1 - 5e-4), 0.2 * (d_star * (1 + 5e-4) + 0.001) + 0.001)
    fixed["disc inertia"] = Within(exact * (1 - 1e-3), exact * 1.02)
    return Expected(fixed)


def expected_06() -> Expected:
    """The catalogue's size, a slotted-lever shaper's stroke by its closed form, reproducible
    random variants within ±10 % of the shaper's crank, one wrong entry of 36 graded, a DXF
    without audit errors in mm."""
    from velplan.mechanism.loader import catalogue_names

    theta = 2 * math.asin(0.10 / 0.30)  # the lever swings ±asin(r/d)
    r = velplan.load("shaper").crank.length
    fixed = {
        "catalogue mechanisms": Near(len(catalogue_names()), 0),
        "H": Near(2 * 0.52 * math.tan(theta / 2), 1e-8),
        "θ": Near(math.degrees(theta), 1e-7),
        "K": Near((math.pi + theta) / (math.pi - theta), 1e-8),
        "variants drawn": Near(5, 0),
        "the same variants when drawn again": Near(1, 0),
        "entries graded": Near(36, 0),
        "entries wrong": Near(1, 0),
        "DXF audit errors": Near(0, 0),
        "DXF units code": Near(4, 0),  # $INSUNITS 4 = millimetres
        "page positions": Near(24, 0),
        "first crank angle on the page": Near(math.degrees(velplan.Study("shaper-lever-ram", n=24).phi[0]) % 360, 0.006),
        "network addresses in the page": Near(0, 0),
    }
    assert len(catalogue_names()) >= 20
    crank = (re.compile(r"variant \d+ crank length"), lambda m: Within(0.9 * r * 0.995, 1.1 * r * 1.005))
    return Expected(fixed, [crank], [(re.compile(r"variant \d+ crank length"), 5)])


def expected_07() -> Expected:
    """The triad press at position 3: structure (class 3), the plans through the special point
    against the analytic solver, the 15 instant centres and the velocities they give."""
    mech = velplan.load("triad-press")
    kin = velplan.solve(mech, velplan.positions(mech, 12))
    i = 2
    g = mech.groups[0]
    fixed = {
        "n": Near(5, 0), "p5": Near(7, 0), "W": Near(1, 0),
        "mechanism class": Near(3, 0), "triad order": Near(3, 0),
        "largest difference from the analytic velocities": Within(0.0, 1e-12),
        "instant centres": Near(15, 0),
        "reached by Kennedy lines": Near(15, 0),
        "largest difference of velocities by centres": Within(0.0, 1e-12),
    }
    for p in ("B", "C", "D", g.special_name):
        fixed[f"V_{p}"] = Near(_speed(kin, p, i), SIX)
    for p in ("B", "C", "D"):
        fixed[f"a_{p}"] = Near(float(np.hypot(*kin.acceleration(p)[i])), SIX)
    for link in ("2", "3", "4"):
        fixed[f"ω{link}"] = Near(float(kin.omega(link)[i]), SIX)
        fixed[f"ε{link}"] = Near(float(kin.epsilon(link)[i]), SIX)
    for link in ("3", "4"):
        fixed[f"ω{link} by centres"] = Near(float(kin.omega(link)[i]), SIX)
    return Expected(fixed)


EXPECTED = {STEMS[0]: expected_01, STEMS[1]: expected_02, STEMS[2]: expected_03,
            STEMS[3]: expected_04, STEMS[4]: expected_05, STEMS[5]: expected_06,
            STEMS[6]: expected_07}

#: One line each, in order, for the broken variants of notebook 4.
ERRORS_04 = ("group '4-5' (RRP) cannot be assembled for crank angles",
             "group '2-3' (RRR) cannot be assembled for crank angles",
             "crank length must be > 0 m, not -0.1",
             "[crank]: unknown key 'omgea'",
             "group '4-5' uses point 'X', which is not solved before it",
             "group '4-5': branch must be +1 or -1, not 0")


# -- the stored notebooks ----------------------------------------------------------------------

def _build_module():
    spec = importlib.util.spec_from_file_location("notebooks_build", NOTEBOOKS / "build.py")
    module = importlib.util.module_from_spec(spec)
    saved, sys.dont_write_bytecode = sys.dont_write_bytecode, True  # no notebooks/__pycache__
    try:
        spec.loader.exec_module(module)
    finally:
        sys.dont_write_bytecode = saved
    return module


def test_every_notebook_is_tested():
    assert sorted(p.stem for p in NOTEBOOKS.glob("*.ipynb")) == sorted(STEMS)
    assert set(EXPECTED) == set(STEMS)


def _sources(nb: dict) -> dict:
    """A notebook without what execution adds (outputs, execution counts)."""
    nb = copy.deepcopy(nb)
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            cell["outputs"], cell["execution_count"] = [], None
    return nb


def test_stored_notebooks_are_what_build_writes(tmp_path):
    written = _build_module().build(tmp_path)
    assert sorted(p.name for p in written) == sorted(f"{s}.ipynb" for s in STEMS)
    for path in written:
        stored = json.loads((NOTEBOOKS / path.name).read_text("utf-8"))
        assert _sources(stored) == json.loads(path.read_text("utf-8")), (
            f"{path.name} differs from what notebooks/build.py writes; run "
            "`python notebooks/build.py`")


@pytest.mark.parametrize("stem", STEMS)
def test_stored_with_outputs_and_framed(stem):
    nb = nbformat.read(NOTEBOOKS / f"{stem}.ipynb", as_version=4)
    nbformat.validate(nb)
    assert nb.metadata.kernelspec.name == "python3"
    for cell in nb.cells:
        if cell.cell_type == "code":  # executed in order, so that it reads on a code host
            assert cell.execution_count is not None
            assert not any(o.output_type == "error" for o in cell.outputs)
    assert nb.cells[0].cell_type == "markdown" and "What you will learn" in nb.cells[0].source
    assert nb.cells[-1].cell_type == "markdown"
    assert nb.cells[-1].source.startswith("## Exercises")
    assert tagged(nb, "readout"), f"{stem} has no readout cells"
    # the stored readouts are right too
    failures = check(readouts(nb), EXPECTED[stem]())
    assert not failures, "\n".join(failures)


# -- the executed notebooks --------------------------------------------------------------------

@pytest.mark.parametrize("stem", STEMS)
def test_runs_cleanly(executed, stem):
    nb = executed[0][stem]
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        assert cell.execution_count is not None
        for o in cell.outputs:
            assert o.output_type != "error", f"{o.ename}: {o.evalue}"
            assert not (o.output_type == "stream" and o.name == "stderr"), o.text


@pytest.mark.parametrize("stem", STEMS)
def test_readouts_match_the_analytic_solution(executed, stem):
    found = readouts(executed[0][stem])
    failures = check(found, EXPECTED[stem]())
    assert not failures, "\n".join(failures)


def test_no_files_written_outside_a_temporary_directory(executed):
    _, before, after = executed
    assert after == before, f"new: {sorted(after - before)}; gone: {sorted(before - after)}"


def _svg_outputs(cell) -> int:
    return sum("image/svg+xml" in o.get("data", {}) for o in cell.outputs)


def test_every_construction_step_is_drawn_with_its_sentences(executed):
    nb = executed[0][STEMS[0]]
    cell = next(c for c in nb.cells if "draw_steps(" in c.source)
    text = _stdout(cell)
    res = velplan.Study("press").plan("velocity", positions=[3], scale_v=0.0007)   # position 3
    english, russian = res.describe(lang="en"), res.describe(lang="ru")
    assert _svg_outputs(cell) == len(english) == 15
    for k, (en, ru) in enumerate(zip(english, russian), start=1):
        assert f"Step {k}. {en}\n        {ru}\n" in text


def test_acceleration_steps_and_plots_are_shown(executed):
    nb = executed[0][STEMS[2]]
    cell = next(c for c in nb.cells if "draw_steps(acc" in c.source)
    assert _svg_outputs(cell) == _stdout(cell).count("Step ") >= 10
    for stem in STEMS[:3]:
        pngs = sum("image/png" in o.get("data", {}) for c in executed[0][stem].cells
                   if c.cell_type == "code" for o in c.outputs)
        assert pngs >= 1, f"{stem} shows no matplotlib plot"


def test_own_mechanism_errors_are_one_line_each(executed):
    nb = executed[0][STEMS[3]]
    (cell,) = tagged(nb, "errors")
    lines = [ln for ln in _stdout(cell).splitlines() if ln.startswith("error: ")]
    assert "no error" not in _stdout(cell)
    assert len(lines) == len(ERRORS_04)
    for line, fragment in zip(lines, ERRORS_04):
        assert fragment in line, line
    sheet = next(c for c in nb.cells if "build_sheet(" in c.source)
    assert "written: lever-press.svg" in _stdout(sheet)
    assert _svg_outputs(sheet) == 1


# -- the checker itself ------------------------------------------------------------------------

def _doctor(nb, old: str, new: str):
    """A copy of the executed notebook with `old` replaced by `new` in its readout outputs."""
    nb = copy.deepcopy(nb)
    hits = 0
    for cell in tagged(nb, "readout"):
        for o in cell.outputs:
            if o.output_type == "stream" and old in o.text:
                o.text = o.text.replace(old, new)
                hits += 1
    assert hits == 1, f"{old!r} found {hits} times"
    return nb


def _line(nb, name: str) -> str:
    for cell in tagged(nb, "readout"):
        for line in _stdout(cell).splitlines():
            if line.startswith(f"{name} = "):
                return line + "\n"
    raise AssertionError(f"no readout {name}")


def test_checker_fails_on_a_wrong_number(executed):
    nb = executed[0][STEMS[0]]
    assert not check(readouts(nb), expected_01())
    line = _line(nb, "V_C")
    value = float(READOUT.match(line.strip())["value"])
    wrong = _doctor(nb, line, f"V_C = {value * 1.01:.6f} m/s\n")   # 1 % off
    failures = check(readouts(wrong), expected_01())
    assert len(failures) == 1 and failures[0].startswith("V_C = ")


def test_checker_fails_on_a_wrong_coriolis_component(executed):
    nb = executed[0][STEMS[2]]
    line = _line(nb, "aᵏ[3]")
    value = float(READOUT.match(line.strip())["value"])
    wrong = _doctor(nb, line, f"aᵏ[3] = {value / 2:.6f} m/s²\n")  # ω·V_rel, the 2 forgotten
    failures = check(readouts(wrong), expected_03())
    assert failures == [f"aᵏ[3] = {value / 2:.6f}, expected {expected_03().fixed['aᵏ[3]']}"]


def test_checker_fails_on_a_missing_or_unknown_readout(executed):
    nb = executed[0][STEMS[0]]
    missing = _doctor(nb, _line(nb, "pc"), "")
    assert check(readouts(missing), expected_01()) == [
        f"pc: not printed (expected {expected_01().fixed['pc']})"]
    extra = _doctor(nb, _line(nb, "pc"), _line(nb, "pc") + "pd = 1.0 mm\n")
    assert check(readouts(extra), expected_01()) == ["pd = 1.0: a readout this test does not check"]


def test_readout_parser():
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("", metadata={"tags": ["readout"]})
    cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text=(
        "group 2-5: RRR\nV_C = 0.045995 m/s\nω5/ω1[7] = -0.000000\nK = 1.5e-3\n"))]
    nb.cells.append(cell)
    assert readouts(nb) == {"V_C": 0.045995, "ω5/ω1[7]": -0.0, "K": 0.0015}
    cell.outputs[0].text += "V_C = 1.0 m/s\n"
    with pytest.raises(ValueError, match="printed twice"):
        readouts(nb)
    cell.outputs[0].text = "V_C = about 1 m/s\n"
    with pytest.raises(ValueError, match="not `name = number unit`"):
        readouts(nb)
