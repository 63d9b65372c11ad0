"""A plan as data, evaluated lazily: only the steps a request depends on, only at the requested
positions, exactly (float64) or with simulated drafting precision."""

from __future__ import annotations

import copy

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Iterable, Literal, Sequence

import numpy as np

from velplan.analysis.numbering import position_index, position_indices, position_number
from velplan.analysis.solver import Kinematics, solve
from velplan.errors import MechanismError, ScaleError, SingularPositionError, VelplanError
from velplan.mechanism.model import GROUND, Mechanism
from velplan.plans import text as T
from velplan.plans.build import construct
from velplan.plans.context import Context, Figure, Lazy
from velplan.plans.drafting import EXACT, Drafting
from velplan.plans.scale import check_drawable, check_scale, standard_scale
from velplan.plans.steps import Intersect, Step
from velplan.options import Language, PlanKind as Kind

TARGET_MM = {"velocity": 100.0, "acceleration": 120.0}
"""Default length (mm) of the longest vector when the scale is chosen automatically."""
POSITION_PLAN_MM = 160.0
"""Default size (mm) of the plan of one position (`PlanResult.position_scale`): what
``velplan plan`` and ``velplan steps`` draw it to."""
FLAG_BELOW = 0.1
"""Intersections whose |sin| is below this are flagged (the lines meet at < 5.7°)."""
REFUSE_BELOW = {"exact": 1e-8, "drafting": 0.02}
"""Intersections whose |sin| is below this are refused (NaN and a mask)."""


@dataclass(frozen=True)
class Plan:
    """The velocity and acceleration plans of a mechanism as an ordered tuple of steps.

    Build it with `Plan.of(mech)`; evaluate it with `evaluate`.
    """

    mechanism: Mechanism
    steps: tuple[Step, ...]
    images: dict
    figures: dict
    tangential: bool

    @classmethod
    def of(cls, mech: Mechanism, *, tangential: bool | None = None) -> "Plan":
        """The plan of ``mech`` (``tangential``: include the crank's aᵗ step; default ε1 ≠ 0)."""
        tang = mech.crank.epsilon != 0 if tangential is None else tangential
        steps, images, figures = construct(mech, tangential=tang)
        targets = [s.target for s in steps]
        if len(set(targets)) != len(targets):
            dup = next(t for t in targets if targets.count(t) > 1)
            raise MechanismError(f"two construction steps would draw the same image {dup!r}; rename a point")
        return cls(mech, steps, images, figures, tang)

    def _construct(self, ctx: Context, steps: list[Step], kind: str, on_failure: str, vals: dict) -> dict:
        """Evaluate ``steps`` in ``ctx`` (those in ``vals`` are drawn already); raise at the first
        refused intersection if asked."""
        for s in steps:
            if s.target in vals:
                continue
            vals[s.target] = s.evaluate(ctx, vals)
            if on_failure == "raise" and isinstance(s, Intersect) and ctx.refused_mask(s.target).any():
                i = int(np.argmax(ctx.refused_mask(s.target)))
                sine = float(ctx.conditions[s.target][i])
                raise SingularPositionError(
                    f"{kind} plan: the lines meeting at {T.label_of(s.target)} are nearly parallel at crank angle "
                    f"{np.degrees(ctx.kin.phi[ctx.idx][i]):.6g}° (sine of their angle {sine:.3g} < "
                    f"{ctx.refuse_below:g}); refused",
                    condition=sine,
                )
        return vals

    @staticmethod
    def _reuse(velocity: "PlanResult", kin, kind, idx, drafting, mu, ctx: Context, vals: dict) -> None:
        """Start from a velocity plan already drawn: its images, μv and records."""
        if velocity.kind != "velocity" or kind != "acceleration":
            raise ValueError("velocity= takes a velocity plan, for an acceleration plan")
        if velocity.kin is not kin or velocity.drafting != drafting or not np.array_equal(velocity.index, idx):
            raise ValueError("velocity= must be drawn from the same kinematics, positions and drafting")
        vals.update(velocity.values)
        for name in ("conditions", "bounds", "segments", "segment_plans", "components"):
            dict.update(getattr(ctx, name), getattr(velocity.ctx, name))
        v = velocity.ctx
        ctx._best, ctx._pos, ctx._omega, ctx._memo = v._best, dict(v._pos), dict(v._omega), dict(v._memo)

    @cached_property
    def by_target(self) -> dict[str, Step]:
        return {s.target: s for s in self.steps}

    def targets_for(self, kind: Kind, only: Iterable[str] | None) -> list[str]:
        """Step targets a request needs: images of points, or the figures of links (for ω, ε)."""
        k = kind[0]
        if only is None:
            return [s.target for s in self.steps if s.target.startswith(k + ":")]
        out = []
        for name in only:
            if name in self.images[k]:
                out.append(self.images[k][name])
            elif name in self.figures[k]:
                fig = self.figures[k][name]
                out.extend(fig.inputs if fig else [])
                if fig is None:
                    out.append(f"{k}:{'p' if k == 'v' else 'π'}")
            else:
                known = ", ".join(list(self.images[k]) + [f"link {x}" for x in self.figures[k]])
                raise MechanismError(f"unknown point or link {name!r}; known: {known}")
        return out

    def needed(self, targets: Iterable[str]) -> list[Step]:
        """The steps ``targets`` depend on, in construction order."""
        need: set[str] = set()
        stack = list(targets)
        while stack:
            t = stack.pop()
            if t in need:
                continue
            need.add(t)
            stack.extend(self.by_target[t].inputs)
        return [s for s in self.steps if s.target in need]

    def evaluate(
        self,
        kin: Kinematics,
        *,
        kind: Kind = "velocity",
        positions: Sequence[int] | None = None,
        only: Iterable[str] | None = None,
        scale_v: float | None = None,
        scale_a: float | None = None,
        drafting: Drafting = EXACT,
        refuse_below: float | None = None,
        on_failure: Literal["nan", "raise"] = "nan",
        velocity: "PlanResult | None" = None,
    ) -> "PlanResult":
        """Construct the plan at ``positions`` (position numbers 1…n of ``kin``; all by default).

        Parameters
        ----------
        kind : {"velocity", "acceleration"}
        only : iterable of str, optional
            Point or link names the request needs; only their steps are evaluated.
        scale_v, scale_a : float, optional
            μv in (m/s)/mm and μa in (m/s²)/mm; chosen from the standard series when omitted,
            so that the longest vector is at most 100 mm (velocity) or 120 mm (acceleration).
        drafting : Drafting
            `EXACT` (float64) or a drafting precision.
        refuse_below : float, optional
            Refuse intersections whose |sin| is below this (default 1e-8 exact, 0.02 drafting).
        on_failure : {"nan", "raise"}
            What a refused intersection gives: NaN and a mask, or `SingularPositionError`.
        velocity : PlanResult, optional
            For an acceleration plan: the velocity plan already drawn (same kinematics, positions
            and drafting); its images, scale and records are used instead of being drawn again.
        """
        if kind not in ("velocity", "acceleration"):
            raise ValueError(f"kind must be 'velocity' or 'acceleration', not {kind!r}")
        if kin.mechanism is not self.mechanism and kin.mechanism != self.mechanism:
            raise MechanismError("the kinematics were solved for another mechanism")
        if np.any(kin.epsilon1 != 0) and not self.tangential:
            raise MechanismError("ε1 ≠ 0: build the plan with tangential=True")
        idx = np.arange(len(kin)) if positions is None else position_indices(positions, len(kin))
        sel = slice(None) if positions is None else idx  # every position: views, not copies
        mu = {
            "v": velocity.scales["v"] if velocity is not None
            else check_scale(scale_v, "scale μv") if scale_v is not None else auto_scale(kin, sel, "velocity"),
            "a": 1.0,
        }
        if kind == "acceleration":
            mu["a"] = check_scale(scale_a, "scale μa") if scale_a is not None else auto_scale(kin, sel, "acceleration")
        if velocity is None and scale_v is not None:
            check_drawable(kin, sel, mu["v"], "velocity", drafting)
        if kind == "acceleration" and scale_a is not None:
            check_drawable(kin, sel, mu["a"], "acceleration", drafting)
        refuse = REFUSE_BELOW[drafting.mode] if refuse_below is None else refuse_below
        steps = self.needed(self.targets_for(kind, only))
        ctx = Context(kin, sel, mu, drafting, refuse, self.by_target)
        vals: dict = {}
        if velocity is not None:
            self._reuse(velocity, kin, kind, idx, drafting, mu, ctx, vals)
        vals = self._construct(ctx, steps, kind, on_failure, vals)
        return PlanResult(self, kin, kind, idx, mu, drafting, tuple(steps), vals, ctx)


def _xy(z: np.ndarray) -> np.ndarray:
    """(n, 2) x, y of a complex array of its own (a view: no copy)."""
    z = np.ascontiguousarray(z, dtype=complex)
    return z.view(float).reshape(z.shape[0], 2)


def auto_scale(kin: Kinematics, rows, kind: Kind, target_mm: float | None = None) -> float:
    """Standard scale so that the longest vector of ``kind`` in the rows ``rows`` of ``kin`` (a
    slice or array indices 0…n−1, as `Plan.evaluate` selects them) is ≤ ``target_mm``."""
    vmax = kin.largest(kind, rows)
    if vmax == 0:
        raise ScaleError(f"every {kind} is zero at the requested positions; give the scale explicitly")
    return standard_scale(vmax / (target_mm or TARGET_MM[kind]))


@dataclass(frozen=True)
class Flag:
    """A near-parallel intersection: at position ``index`` (into the result's positions) the
    lines meeting at ``image`` make an angle with sine ``condition``; the image may be off by
    ``bound_mm`` on the plan (``refused``: no value was returned)."""

    image: str
    index: int
    condition: float
    bound_mm: float
    refused: bool


@dataclass(frozen=True)
class PlanResult:
    """A constructed plan at some positions: images (mm), readouts (SI), conditions and steps."""

    plan: Plan
    kin: Kinematics
    kind: Kind
    index: np.ndarray
    scales: dict
    drafting: Drafting
    steps: tuple[Step, ...]
    values: dict = field(repr=False)
    ctx: Context = field(repr=False)

    @property
    def scale(self) -> float:
        """μ of this plan: (m/s)/mm or (m/s²)/mm."""
        return self.scales[self.kind[0]]

    def at_scale(self, mu: float) -> "PlanResult":
        """This exact plan drawn at the scale ``mu`` ((m/s)/mm or (m/s²)/mm): every image,
        line and segment of this plan scaled by μ_old/μ, nothing constructed again (an exact
        plan does not depend on its scale; a drafted one does, and is refused)."""
        k = self.kind[0]
        mu = check_scale(mu, "scale μv" if k == "v" else "scale μa")
        if mu == self.scales[k]:
            return self
        if not self.drafting.exact:
            raise MechanismError("a drafted plan is read at the scale it was drawn at; draw it again at the new scale")
        r = self.scales[k] / mu
        values = {}
        for t, v in self.values.items():
            if t.startswith(k + ":"):
                v = (v[0] * r, v[1]) if isinstance(v, tuple) else v * r
            values[t] = v
        ctx = copy.copy(self.ctx)
        ctx.mu = {**self.ctx.mu, k: mu}
        ctx.segments, ctx.bounds = Lazy(), Lazy()
        for label in self.ctx.segments:
            mine = self.ctx.segment_plans.get(label) == k
            ctx.segments[label] = (lambda lb=label, f=(r if mine else 1.0): self.ctx.segments[lb] * f)
        for t in self.ctx.bounds:
            ctx.bounds[t] = (lambda t=t, f=(r if t.startswith(k + ":") else 1.0): self.ctx.bounds[t] * f)
        return replace(self, scales={**self.scales, k: mu}, values=values, ctx=ctx)

    @property
    def phi(self) -> np.ndarray:
        """Crank angles (rad) of the evaluated positions."""
        return self.kin.phi[self.index]

    @property
    def evaluated_steps(self) -> int:
        """Number of construction steps evaluated for this request."""
        return len(self.steps)

    @property
    def mode(self) -> str:
        return self.drafting.mode

    def _image_key(self, name: str) -> str:
        k = self.kind[0]
        try:
            return self.plan.images[k][name]
        except KeyError:
            raise MechanismError(f"unknown point {name!r}; known points: {', '.join(self.plan.images[k])}") from None

    def image(self, name: str) -> np.ndarray:
        """(n, 2) image of point ``name`` on this plan, mm from the pole."""
        z = self.values[self._image_key(name)]
        return _xy(z.copy())

    @cached_property
    def images(self) -> dict[str, np.ndarray]:
        """Every evaluated image of this plan (points by name, construction points by label), mm."""
        k = self.kind[0]
        out = {p: self.image(p) for p, t in self.plan.images[k].items() if t in self.values}
        for t, z in self.values.items():
            if t.startswith(k + ":") and not isinstance(z, tuple) and t not in self.plan.images[k].values():
                out[T.label_of(t)] = _xy(z.copy())
        return out

    def vector(self, name: str) -> np.ndarray:
        """(n, 2) velocity (m/s) or acceleration (m/s²) of point ``name`` read off the plan."""
        z = self.values[self._image_key(name)]
        with np.errstate(invalid="ignore", divide="ignore"):
            read = self.drafting.vector(z) * self.scale
        return _xy(read)

    @cached_property
    def vectors(self) -> dict[str, np.ndarray]:
        """Every point whose image was evaluated → its vector (m/s or m/s²)."""
        k = self.kind[0]
        return {p: self.vector(p) for p, t in self.plan.images[k].items() if t in self.values}

    def _figure_ready(self, fig: Figure | None) -> bool:
        return fig is None or all(t in self.values for t in fig.inputs)

    def _rates(self, plan: str, given: float, read) -> dict[str, np.ndarray]:
        """ω (plan "v") or ε (plan "a") of every link whose figure was evaluated: the crank's is
        given, a link that does not turn has 0, the others are read off the plan."""
        out = {}
        crank = self.plan.mechanism.crank.link
        for link, fig in self.plan.figures[plan].items():
            if link == crank:
                out[link] = np.array(np.broadcast_to(given, (len(self.index),)))
            elif link != GROUND and self._figure_ready(fig):
                out[link] = np.zeros(len(self.index)) if fig is None else read(fig, self.values)
        return out

    @cached_property
    def omegas(self) -> dict[str, np.ndarray]:
        """ω (rad/s, counter-clockwise positive) of every link whose figure was evaluated."""
        return self._rates("v", self.ctx.omega1, self.ctx.omega_of)

    @cached_property
    def epsilons(self) -> dict[str, np.ndarray]:
        """ε (rad/s²) of every link whose acceleration figure was evaluated."""
        return self._rates("a", self.ctx.epsilon1, self.ctx.epsilon_of) if self.kind == "acceleration" else {}

    @property
    def segments(self) -> dict[str, np.ndarray]:
        """Every segment laid off or cut by an intersection: label (``"pa"``, ``"ac"``) → mm."""
        return {k: v for k, v in self.ctx.segments.items()}

    @cached_property
    def components(self) -> dict[str, tuple[str, np.ndarray]]:
        """Named vector components (``"V_CA"``, ``"aⁿ_CA"``, ``"aᵏ_A4A"``, ``"aʳ_F"``) →
        (segment label on the plan, magnitude in SI units read as length × scale)."""
        out = {}
        for name, (label, plan, _) in self.ctx.components.items():
            mm = self.drafting.length(self.ctx.segments[label])
            out[name] = (label, mm * self.scales[plan])
        return out

    def component_point(self, name: str) -> str:
        """The mechanism point whose construction a component belongs to."""
        target = self.ctx.components[name][2]
        step = self.plan.by_target[target]
        vector = getattr(step, "vector", None)
        if vector is not None:
            return getattr(vector, "point", None) or vector.name
        inverse = {t: p for p, t in self.plan.images[target[0]].items()}
        return inverse.get(target, T.label_of(target))

    @property
    def conditions(self) -> dict[str, np.ndarray]:
        """Image label → |sin| of the angle of the two lines fixing it, per position."""
        return {T.label_of(k): v for k, v in self.ctx.conditions.items()}

    @property
    def bounds(self) -> dict[str, np.ndarray]:
        """Image label → error bound of the intersection (mm on the plan), per position."""
        return {T.label_of(k): v for k, v in self.ctx.bounds.items()}

    @cached_property
    def flags(self) -> list[Flag]:
        """Flagged (|sin| < 0.1) and refused intersections, per position."""
        out = []
        for t, c in self.ctx.conditions.items():
            refused = self.ctx.refused_mask(t)
            for i in np.flatnonzero((c < FLAG_BELOW) | refused):
                out.append(Flag(T.label_of(t), int(i), float(c[i]), float(self.ctx.bounds[t][i]), bool(refused[i])))
        return out

    @cached_property
    def flagged(self) -> np.ndarray:
        """(n,) True where some intersection is flagged or refused."""
        m = np.zeros(len(self.index), dtype=bool)
        for f in self.flags:
            m[f.index] = True
        return m

    @cached_property
    def refused(self) -> np.ndarray:
        """(n,) True where some intersection was refused (values are NaN there)."""
        m = np.zeros(len(self.index), dtype=bool)
        for t in self.ctx.conditions:
            m |= self.ctx.refused_mask(t)
        return m

    def index_of(self, position: int) -> int:
        """Index into this result of position number ``position`` (1…n of its kinematics);
        `VelplanError` naming the position when the plan was not evaluated there."""
        j = position_index(position, len(self.kin))
        hit = np.flatnonzero(np.asarray(self.index) == j)
        if hit.size == 0:
            have = ", ".join(str(position_number(k)) for k in self.index)
            raise VelplanError(f"position {position} is not in this plan (its positions: {have})")
        return int(hit[0])

    def position_scale(self, position: int, size_mm: float = POSITION_PLAN_MM) -> float:
        """The default scale of this plan at position number ``position`` alone ((m/s)/mm or
        (m/s²)/mm): the smallest standard value at which the pole and every image fit in a
        square of ``size_mm``. `velplan plan` and `velplan steps` both draw at it."""
        k, i = self.kind[0], self.index_of(position)
        pts = np.array([0j] + [complex(z[i]) for t, z in self.values.items()
                               if t.startswith(k + ":") and not isinstance(z, tuple)])
        pts = pts[np.isfinite(pts)]
        extent = max(float(np.ptp(pts.real)), float(np.ptp(pts.imag)))
        if not extent > 0:
            raise ScaleError(f"the {self.kind} plan at position {position} is a point; give the scale explicitly")
        return standard_scale(self.scale * extent / size_mm)

    def describe(self, position: int | None = None, lang: Language = "en") -> list[str]:
        """The worked solution at position number ``position`` (1…n; the first position of this
        result by default), one sentence per step."""
        T.check_lang(lang)
        i = 0 if position is None else self.index_of(position)
        return [s.describe(self.ctx, self.values, i, lang) for s in self.steps if s.target.startswith(self.kind[0])]


def plan(
    mech: Mechanism,
    phi,
    *,
    kind: Kind = "velocity",
    **options,
) -> PlanResult:
    """Solve ``mech`` at crank angles ``phi`` (rad) and construct its ``kind`` plan there.

    A friendly shortcut for ``Plan.of(mech).evaluate(velplan.solve(mech, phi), kind=kind, …)``.
    """
    kin = solve(mech, phi)
    return Plan.of(mech).evaluate(kin, kind=kind, **options)


def relative_error(result: PlanResult, *, floor: float = 0.0) -> dict[str, np.ndarray]:
    """Per point: |plan − analytic| / max(|analytic|, floor·largest) at each position."""
    arr = result.kin.velocities if result.kind == "velocity" else result.kin.accelerations
    out = {}
    largest = np.abs(arr[result.index]).max()
    for p, v in result.vectors.items():
        ref = arr[result.index, result.kin.point_index[p]]
        den = np.maximum(np.hypot(*ref.T), floor * largest)
        with np.errstate(divide="ignore", invalid="ignore"):
            out[p] = np.hypot(*(v - ref).T) / den
    return out


