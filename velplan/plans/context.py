"""The evaluation context of a plan: the mechanism in its positions, the scales, the drafting
policy, and what the steps record (conditions, error bounds, segment lengths)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from velplan.analysis.solver import Kinematics
from velplan.mechanism.model import GROUND
from velplan.plans.drafting import Drafting

EPS = np.finfo(float).eps


@dataclass(frozen=True)
class Figure:
    """Two points of a link (``p1``, ``p2``: mechanism point names) and their velocity or
    acceleration images (``img1``, ``img2``: step targets): enough to read the link's ω (or ε)
    and to place any other point of it by similarity."""

    link: str
    p1: str
    img1: str
    p2: str
    img2: str
    rigid: bool = False
    """p1 and p2 are fixed to the link: their distance is the same at every position."""

    @property
    def inputs(self) -> tuple[str, str]:
        return (self.img1, self.img2)


class Lazy(dict):
    """A dict whose values may be given as functions of no argument, computed on first access
    (what most requests never read — error bounds, segment lengths — costs nothing)."""

    def __getitem__(self, key):
        value = super().__getitem__(key)
        if callable(value):
            value = value()
            super().__setitem__(key, value)
        return value

    def get(self, key, default=None):
        return self[key] if key in self else default

    def items(self):
        return [(k, self[k]) for k in self]

    def values(self):
        return [self[k] for k in self]


class Context:
    """Positions ``idx`` (indices, or a slice for all) of a solved mechanism, the scales ``mu``
    ({"v": μv, "a": μa}, units per mm), and the drafting policy; collects conditions, bounds and
    segment lengths."""

    def __init__(self, kin: Kinematics, idx: np.ndarray | slice, mu: dict, drafting: Drafting,
                 refuse_below: float, plan_steps: dict):
        self.kin = kin
        self.idx = idx
        self.n = len(kin.phi[idx])
        self.mu = mu
        self.drafting = drafting
        self.refuse_below = refuse_below
        self.plan_steps = plan_steps
        # the crank's ω1, ε1: one value, or one per evaluated position for a computed motion
        self.omega1 = kin.omega1 if np.ndim(kin.omega1) == 0 else kin.omega1[idx]
        self.epsilon1 = kin.epsilon1 if np.ndim(kin.epsilon1) == 0 else kin.epsilon1[idx]
        self.conditions: dict[str, np.ndarray] = {}
        self.bounds: dict[str, np.ndarray] = Lazy()
        self.segments: dict[str, np.ndarray] = Lazy()
        self.segment_plans: dict[str, str] = {}
        self.components: dict[str, tuple[str, str, str]] = {}
        self._pos: dict[str, np.ndarray] = {}
        self._best: int | None = None
        self._omega: dict[Figure, np.ndarray] = {}
        self._memo: dict = {}

    def pos(self, name: str) -> np.ndarray:
        """Complex position (m) of mechanism point ``name`` at the evaluated positions."""
        z = self._pos.get(name)
        if z is None:
            xy = self.kin.positions[self.idx, self.kin._point(name)]
            if xy.strides[-1] == xy.itemsize and xy.dtype == np.float64:
                z = xy.view(np.complex128)[:, 0]  # the solver's own storage: no copy
            else:
                z = xy[:, 0] + 1j * xy[:, 1]
            self._pos[name] = z
        return z

    def memo(self, key, compute):
        """``compute()`` once per context (and the acceleration plan drawn on its velocity plan):
        the geometry both plans share — directions of lines, similarity ratios."""
        value = self._memo.get(key)
        if value is None:
            value = self._memo[key] = compute()
        return value

    def constant_ratio(self, point: str, anchor: str, p1: str, p2: str) -> complex:
        """(point − anchor)/(p2 − p1) for points fixed to links turning together: the same at
        every position, taken at the best-conditioned one evaluated (NaN if none is assembled)."""
        i = self.best_position()
        if i < 0:
            return complex(np.nan, np.nan)
        j = self.kin._point
        P = self.kin.positions[i]
        num, den = complex(*(P[j(point)] - P[j(anchor)])), complex(*(P[j(p2)] - P[j(p1)]))
        return num / den if den != 0 else complex(np.nan, np.nan)

    def best_position(self) -> int:
        """Index (into the whole solution) of the best-conditioned assembled position evaluated,
        −1 if none is."""
        if self._best is None:
            c = np.where(self.kin.valid[self.idx], self.kin.min_condition()[self.idx], -1.0)
            k = int(np.argmax(c)) if c.size else 0
            where = range(len(self.kin))[self.idx] if isinstance(self.idx, slice) else self.idx
            self._best = int(where[k]) if c.size and c[k] >= 0 else -1
        return self._best

    def theta(self, link: str) -> np.ndarray:
        """Angle (rad) of ``link``'s reference direction (0 for the frame)."""
        if link == GROUND:
            return np.zeros(self.n)
        return self.kin.angles[self.idx, self.kin._link(link)]

    def omega_of(self, f: Figure, vals) -> np.ndarray:
        """ω (rad/s) of a link read off the velocity plan: ω = V_rel / l, its sign the sense
        in which the relative velocity turns the link (counter-clockwise positive). Read once
        per figure, as on paper, and reused."""
        w = self._omega.get(f)
        if w is None:
            w = self._omega[f] = self._read_omega(f, vals)
        return w

    def _length2(self, f: Figure, r: np.ndarray):
        """|p2 − p1|² (m²) of a figure: one number when it is rigid, else per position."""
        if f.rigid:
            return self.memo(("length2", f.p1, f.p2), lambda: self._rigid_length2(f))
        return r.real * r.real + r.imag * r.imag

    def _rigid_length2(self, f: Figure) -> float:
        i = self.best_position()
        if i < 0:
            return float("nan")
        d = self.kin.positions[i, self.kin._point(f.p2)] - self.kin.positions[i, self.kin._point(f.p1)]
        return float(d @ d)

    def _read_omega(self, f: Figure, vals) -> np.ndarray:
        r = self.pos(f.p2) - self.pos(f.p1)
        dv = vals[f.img2] - vals[f.img1]
        cross = r.real * dv.imag - r.imag * dv.real
        if self.drafting.exact:
            cross *= self.mu["v"] / self._length2(f, r)
            return cross
        read = self.drafting.length(np.abs(vals[f.img2] - vals[f.img1])) * self.mu["v"]
        return np.sign(cross) * read / np.abs(r)

    def epsilon_of(self, f: Figure, vals) -> np.ndarray:
        """ε (rad/s²) of a link read off the acceleration plan (tangential part / l)."""
        r = self.pos(f.p2) - self.pos(f.p1)
        da = vals[f.img2] - vals[f.img1]
        cross = r.real * da.imag - r.imag * da.real
        cross *= self.mu["a"] / self._length2(f, r)
        return cross

    def record_segment(self, step, label: str, length_mm, component: str) -> None:
        """The segment ``label`` (its length in mm, or a function giving it) and its component."""
        self.segments[label] = length_mm
        self.segment_plans[label] = step.target[0]
        if component:
            self.components[component] = (label, step.target[0], step.target)

    def record_intersection(self, step, sine: np.ndarray, x: np.ndarray, through) -> None:
        """Condition |sin| and the implied error bound (mm) of the intersection ``x``.

        Notes
        -----
        A lateral error δ of either line moves the intersection by about δ/sin along the other:
        δ is round-off (8·eps·size) in exact mode, and the drafting length precision plus the
        angular precision times the distance from the line's base point in drafting mode.
        """
        self.conditions[step.target] = sine

        def bound():
            size = np.maximum(np.maximum(np.abs(x), np.abs(through[0])), np.maximum(np.abs(through[1]), 1.0))
            if self.drafting.exact:
                delta = 8 * EPS * size
            else:
                arm = np.maximum(np.abs(x - through[0]), np.abs(x - through[1]))
                delta = np.hypot(self.drafting.length_mm, np.radians(self.drafting.angle_deg) * arm)
            with np.errstate(divide="ignore", invalid="ignore"):
                return delta / sine

        self.bounds[step.target] = bound

    def refused_mask(self, target: str) -> np.ndarray:
        return ~(self.conditions[target] >= self.refuse_below)
