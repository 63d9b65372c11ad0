"""The notebook layer: drawings of mechanisms and plans that show themselves in Jupyter.

A thin, friendly layer over :mod:`velplan.render` (which it imports lazily, so importing
this module is cheap): every function returns an :class:`SvgDrawing`, a value that Jupyter
displays inline (``_repr_svg_``) and that can be saved as SVG, PNG or PDF. The drawing
itself is done by the view builders of the sheet (``mechanism_view``, ``plan_view``,
``plan_steps``, ``diagram_view``, ``build_sheet``); nothing is drawn here twice.

Examples
--------
>>> import velplan
>>> from velplan.notebook import draw_plan, draw_steps
>>> study = velplan.Study("press")
>>> res = study.plan("velocity", scale_v=0.0007)
>>> drawing = draw_plan(res, position=3, upto=2)   # position 3: the pole and the vector pa
>>> drawing.svg.startswith("<?xml")
True
>>> sentence, picture = next(iter(draw_steps(res, position=3)))
>>> sentence
'Choose the pole p; the images of the fixed points O1, O2 are at the pole.'
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterator, Literal, Sequence


from velplan.analysis.numbering import position_index, position_number
from velplan.analysis.solver import Kinematics
from velplan.errors import VelplanError
from velplan.mechanism.model import Mechanism
from velplan.options import Language
from velplan.study import Study


#: Largest drawing of the scheme a notebook shows, mm (the scale is the largest ESKD scale
#: that keeps the scheme within it).
SCHEME_MM = 170.0
#: Gap between drawings put side by side, mm.
GAP_MM = 10.0


@dataclass(frozen=True)
class SvgDrawing:
    """An SVG drawing that Jupyter shows inline.

    Attributes
    ----------
    svg : str
        The SVG document (sized in mm).
    scene : Scene or None
        The scene it was drawn from (None for a drawing read from a file); drawings with a
        scene can be put side by side (:func:`side_by_side`).
    """

    svg: str
    scene: Any = field(default=None, repr=False, compare=False)

    @classmethod
    def from_scene(cls, scene, *, lang: Language = "en") -> "SvgDrawing":
        """Draw a `Scene` with the default sheet style of `lang`."""
        from velplan.render.style import SheetStyle
        from velplan.render.svg import to_svg

        return cls(to_svg(scene, SheetStyle(language=lang)), scene)

    @classmethod
    def from_file(cls, path: str | os.PathLike) -> "SvgDrawing":
        """Read an SVG file (a sheet written by ``velplan sheet``, say)."""
        try:
            return cls(Path(path).read_text("utf-8"))
        except (OSError, UnicodeDecodeError) as exc:
            raise VelplanError(f"cannot read drawing {path}: {exc}") from None

    @property
    def size_mm(self) -> tuple[float, float] | None:
        """(width, height) of the drawing, mm, when it has a scene."""
        return None if self.scene is None else (self.scene.width_mm, self.scene.height_mm)

    def _repr_svg_(self) -> str:
        return self.svg

    def png(self, *, dpi: float = 96.0) -> bytes:
        """The drawing rasterised to PNG (needs cairosvg: ``pip install velplan[export]``)."""
        from velplan.render import export

        return export.svg_to_png(self.svg, dpi=dpi)

    def save(self, path: str | os.PathLike, *, dpi: float = 150.0) -> Path:
        """Write the drawing to `path`, atomically: SVG, or PNG / PDF by the suffix.

        Returns
        -------
        Path
            The file written.
        """
        from velplan.render import export

        target = Path(path)
        if not target.parent.is_dir():
            raise VelplanError(f"cannot write {target}: directory {target.parent} does not exist")
        suffix = target.suffix.lower()
        if suffix == ".png":
            return export.write_png(self.svg, target, dpi=dpi)
        if suffix == ".pdf":
            return export.write_pdf(self.svg, target)
        if suffix != ".svg":
            raise VelplanError(f"cannot save a drawing as {suffix or 'a file without suffix'!r}; "
                               "use .svg, .png or .pdf")
        return export.write_svg(self.svg, target)


def _drawing(view, lang: Language) -> SvgDrawing:
    from velplan.render.scene import Scene

    return SvgDrawing.from_scene(Scene(view.primitives, view.width_mm, view.height_mm), lang=lang)


def _study(mech: Study | Mechanism | str, n: int = 12) -> Study:
    return mech if isinstance(mech, Study) else Study(mech, n=n)


def draw_mechanism(mech: Study | Mechanism | str, kin: Kinematics | None = None, *, position: int = 1,
                   lang: Language = "en", single: bool = False,
                   mu_l: float | None = None) -> SvgDrawing:
    """The kinematic scheme: position number `position` thick, the others thin.

    Parameters
    ----------
    mech : Study, Mechanism or str
        The study (its positions and turn), or a mechanism studied at 12 positions.
    kin : Kinematics, optional
        Other positions to draw (the study's kinematics by default).
    position : int
        Number (1…n of `kin`) of the position drawn thick; 1 is the reference position.
    lang : {"en", "ru", "uk", "zh"}
    single : bool
        Draw that position alone (no other positions, trajectories or numbers).
    mu_l : float, optional
        Scale, m/mm; by default the largest ESKD scale that keeps the scheme within
        `SCHEME_MM`.

    Raises
    ------
    VelplanError
        If `position` is outside 1…n or the mechanism cannot be assembled there.
    """
    from velplan.views.mechanism import MechanismSizes, extent_m, mechanism_view
    from velplan.views.base import eskd_scales

    study = _study(mech)
    mech = study.mechanism
    kin = study.kinematics if kin is None else kin
    n = len(kin)
    i = position_index(position, n)
    if not kin.valid[i]:
        raise VelplanError(f"{mech.name} cannot be assembled at crank angle "
                           f"{math.degrees(kin.phi[i]):.6g}°")
    fine = study.turn.take(slice(None, None, 3))
    if mu_l is None:
        wx, wy = extent_m(mech, kin, fine)
        mu_l = next((m for m in eskd_scales() if max(wx, wy) / m <= SCHEME_MM),
                    eskd_scales()[-1])
    view = mechanism_view(mech, mu_l=mu_l, n=n, thick=position, lang=lang, kin=kin, fine=fine,
                          sizes=MechanismSizes(4.0, 3.5, 2.5), single=single)
    return _drawing(view, lang)


def _position(res, position: int | None) -> int:
    """The position number drawn: `position`, by default the first the result was evaluated
    at (checked against the result)."""
    position = position_number(res.index[0]) if position is None else position
    res.index_of(position)
    return position


def _partial_plans(res, position: int, lang: Language, upto: Sequence[int]) -> list[tuple[str, SvgDrawing]]:
    """(sentence of step k, the plan as far as step k) for k in `upto` (1-based).

    Every partial plan has the full plan's box and pole, so the figures can be flipped
    through; the step's own vectors and line are thick, earlier ones thin.
    """
    from velplan.views.plan import plan_steps, plan_view
    from velplan.render.scene import Scene
    from velplan.views.steps import partial_plan

    full = plan_view(res, position, lang=lang)
    drawings = plan_steps(res, position, lang=lang)
    total = len(drawings)
    out = []
    for k in upto:
        if not 1 <= k <= total:
            raise VelplanError(f"upto={k}: this plan has steps 1…{total}")
        items = partial_plan(res, position, k, full=full, drawings=drawings, lang=lang)
        scene = Scene(tuple(items), full.width_mm, full.height_mm)
        out.append((drawings[k - 1].sentence, SvgDrawing.from_scene(scene, lang=lang)))
    return out


def draw_plan(res, *, position: int | None = None, upto: int | None = None,
              lang: Language = "en") -> SvgDrawing:
    """The velocity or acceleration plan of `res` at position number `position`.

    Parameters
    ----------
    res : PlanResult
        From ``study.plan(kind)`` (a `velplan.Study`); drawn at its own scale.
    position : int, optional
        Position number (1…n of the result's kinematics) to draw, one the result was
        evaluated at; by default its first (the only one of a plan at one position).
    upto : int, optional
        Draw only the first `upto` construction steps (1-based; the last of them thick),
        in the full plan's frame; the whole plan by default.
    lang : {"en", "ru", "uk", "zh"}
    """
    position = _position(res, position)
    if upto is None:
        from velplan.views.plan import plan_view

        return _drawing(plan_view(res, position, lang=lang), lang)
    return _partial_plans(res, position, lang, [upto])[0][1]


def draw_steps(res, *, position: int | None = None,
               lang: Language = "en") -> Iterator[tuple[str, SvgDrawing]]:
    """The construction of the plan at position number `position` (as for `draw_plan`) step
    by step: (sentence, drawing so far) per step; drawing k shows steps 1…k with step k
    thick."""
    from velplan.views.plan import plan_steps

    position = _position(res, position)
    total = len(plan_steps(res, position, lang=lang))
    return iter(_partial_plans(res, position, lang, range(1, total + 1)))


def draw_diagrams(mech: Study | Mechanism | str, n: int = 12, *, lang: Language = "en",
                  arrangement: Literal["row", "column"] = "row") -> SvgDrawing:
    """Displacement, velocity and acceleration diagrams of the output (chord method beside
    the analytic curves), over `n` positions (a study brings its own)."""
    from velplan.views.diagram import diagram_view

    study = _study(mech, n)
    view = diagram_view(study.diagrams, lang=lang, arrangement=arrangement, omega=study.mechanism.crank.omega,
                        length_mm=120.0)
    return _drawing(view, lang)


def draw_sheet(mech: Study | Mechanism | str, **options) -> SvgDrawing:
    """The kinematic-analysis sheet (``velplan.sheets.kinematic.build_sheet(mech, **options)``)."""
    from velplan.sheets.kinematic import build_sheet

    sheet = build_sheet(mech, **options)
    return SvgDrawing(sheet.svg(), sheet.scene)


def draw_dynamics_sheet(mech: Study | Mechanism | str, **options) -> SvgDrawing:
    """The machine-dynamics sheet (``velplan.sheets.dynamics.build_dynamics_sheet``)."""
    from velplan.sheets.dynamics import build_dynamics_sheet

    sheet = build_dynamics_sheet(mech, **options)
    return SvgDrawing(sheet.svg(), sheet.scene)


def draw_dynamics(mech: Study | Mechanism | str, view: str = "wittenbauer", *, lang: Language = "en",
                  fmt: str = "A1") -> SvgDrawing:
    """One view of the dynamics sheet on its own: ``"moments"``, ``"works"``, ``"inertia"``,
    ``"omega"``, ``"wittenbauer"``, ``"flywheel"`` or ``"results"``."""
    from velplan.sheets.dynamics import build_dynamics_sheet

    sheet = build_dynamics_sheet(mech, lang=lang, fmt=fmt)
    if view not in sheet.views:
        raise VelplanError(f"the dynamics sheet has no view {view!r}; it has {', '.join(sheet.views)}")
    return _drawing(sheet.views[view].view, lang)


def side_by_side(*drawings: SvgDrawing, gap_mm: float = GAP_MM,
                 lang: Language = "en") -> SvgDrawing:
    """Drawings (each with its scene) in one row, bottoms aligned, `gap_mm` apart."""
    from velplan.render.scene import Scene
    from velplan.views.base import shift

    if not drawings:
        raise VelplanError("side_by_side needs at least one drawing")
    items, x, height = [], 0.0, 0.0
    for d in drawings:
        if not isinstance(d, SvgDrawing) or d.scene is None:
            raise VelplanError(f"side_by_side needs drawings made by velplan.notebook, not {d!r}")
        items += [shift(p, x, 0.0) for p in d.scene.primitives]
        x += d.scene.width_mm + gap_mm
        height = max(height, d.scene.height_mm)
    return SvgDrawing.from_scene(Scene(tuple(items), x - gap_mm, height), lang=lang)


def _widgets():
    try:
        import ipywidgets
    except ImportError:
        return None
    return ipywidgets


def crank_slider(mech: Study | Mechanism | str, callback: Callable[[Kinematics], Any] | None = None, *,
                 n: int = 12, fallback: int = 4, interactive: bool | None = None,
                 lang: Language = "en"):
    """A slider over the crank angle that redraws ``callback(kin)`` as it moves.

    Parameters
    ----------
    mech : Mechanism
    callback : callable, optional
        Called with the mechanism solved at one crank angle (a `Kinematics` of length 1);
        returns what to show (an `SvgDrawing`, or anything Jupyter displays). By default
        the scheme in that position.
    n : int
        The slider steps through the `n` positions from the reference position, in the
        sense of ω1 (its value is the angle from the reference, degrees).
    fallback : int
        Without ipywidgets: how many positions (evenly spread over the turn) are drawn side
        by side instead.
    interactive : bool, optional
        True: use ipywidgets (raise if missing); False: always the static row; None: use
        ipywidgets when it can be imported.

    Returns
    -------
    ipywidgets.interactive or SvgDrawing
        The widget, or the static row of drawings (the callback must then return
        `SvgDrawing` values).
    """
    if n < 1 or fallback < 1:
        raise VelplanError(f"crank_slider needs n ≥ 1 and fallback ≥ 1, not {n} and {fallback}")
    study = _study(mech, n)
    n = study.n
    step = 360.0 / n

    def at(offset_deg: float):
        if callback is None:  # the scheme in that position, numbered as on the sheet
            return draw_mechanism(study, position=position_number(int(round(offset_deg / step)) % n),
                                  lang=lang, single=True)
        angle = study.phi[0] + study.sense * math.radians(offset_deg)
        return callback(Study(study.mechanism, angles=[angle], check_assembly=False).kinematics)

    widgets = None if interactive is False else _widgets()
    if interactive and widgets is None:
        raise VelplanError("crank_slider(interactive=True) needs ipywidgets; "
                           "pip install ipywidgets, or pass interactive=None")
    if widgets is not None:
        from IPython.display import display

        slider = widgets.FloatSlider(value=0.0, min=0.0, max=360.0 - step, step=step,
                                     description="φ − φ₁, °", continuous_update=False)
        return widgets.interactive(lambda angle: display(at(angle)), angle=slider)
    count = min(fallback, n)
    offsets = [step * round(k * n / count) for k in range(count)]
    return side_by_side(*(at(a) for a in offsets), lang=lang)


__all__ = ["SvgDrawing", "crank_slider", "draw_diagrams", "draw_dynamics", "draw_dynamics_sheet", "draw_mechanism", "draw_plan",
           "draw_sheet", "draw_steps", "side_by_side"]
