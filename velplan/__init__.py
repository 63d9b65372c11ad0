"""velplan: velocity and acceleration plans of planar linkages by graphical construction,
checked against an analytic solver.

The product at the front door: a study of a mechanism, its sheets, its page and its note::

    >>> import velplan
    >>> study = velplan.Study("shaper")              # 12 positions at the file's ω1
    >>> study.kinematics.velocity("F").shape
    (12, 2)
    >>> study.plan("acceleration").epsilons["3"].shape
    (12,)
    >>> velplan.structure(study.mechanism).mobility
    1
    >>> velplan.sheet(study, kind="forces", fmt="A1").save("shaper-forces.svg")  # doctest: +SKIP
    >>> velplan.Page(study, lang="ru").save("shaper.html")                           # doctest: +SKIP
    >>> velplan.explanatory_note(study, lang="ru").save("note.docx")                 # doctest: +SKIP

Every name but the errors and the option types is imported on first use, so ``import velplan``
stays light.

A mechanism, its positions and its motion, one function at a time::

    >>> mech = velplan.load("four-bar")                 # a bundled example, or a TOML path
    >>> isinstance(mech, velplan.Mechanism), "four-bar" in velplan.example_names()
    (True, True)
    >>> phi = velplan.positions(mech, 4)                # position 1 is the reference position
    >>> bool(abs(phi[0] - velplan.reference_angle(mech)) < 1e-12)
    True
    >>> kin = velplan.solve(mech, phi, omega1=10.0)
    >>> isinstance(kin, velplan.Kinematics), kin.velocity("B").shape
    (True, (4, 2))
    >>> sorted(velplan.transfer_functions(kin))[:3]
    ['V_A', 'V_B', 'V_D']
    >>> st = velplan.stroke(mech)                       # the rocker's swing (rad) and K
    >>> round(st.H, 6), round(st.K, 4)
    (1.047762, 1.0175)
    >>> sorted(velplan.extremes(mech))
    ['link 2', 'link 3']
    >>> note = velplan.explanatory_note("four-bar", parts=["kinematics"], lang="en")
    >>> note.title
    'Explanatory note: four-bar linkage'
    >>> velplan.Page(velplan.Study("four-bar", n=4), lang="en").html.startswith("<!DOCTYPE html>")
    True

Bad input is refused in one line by a `VelplanError` (`AssemblyError`, `MechanismError`,
`ScaleError`, `SingularPositionError`, `TableError` are its kinds)::

    >>> from importlib.resources import files
    >>> toml = files("velplan.examples").joinpath("four-bar.toml").read_text("utf-8")
    >>> velplan.Study(velplan.parse(toml.replace("length = 0.10", "length = 0.30")))
    Traceback (most recent call last):
    ...
    velplan.errors.AssemblyError: group '2-3' (RRR) cannot be assembled for crank angles -9.6°…9.6°, 97.2°…262.8°: point 'B' has no position there
    >>> velplan.parse("name = 'no frame'")
    Traceback (most recent call last):
    ...
    velplan.errors.MechanismError: missing [ground] section: give [ground], [crank] and [[group]] tables, or the mechanism as drawn ([[joint]] tables and a [crank])
    >>> errors = (velplan.AssemblyError, velplan.MechanismError, velplan.ScaleError,
    ...           velplan.SingularPositionError, velplan.TableError)
    >>> all(issubclass(e, velplan.VelplanError) for e in errors)
    True

The option types, for type checkers and for the values they allow::

    >>> from typing import get_args
    >>> get_args(velplan.PlanKind), get_args(velplan.SheetKind)[-1]
    (('velocity', 'acceleration'), 'dynamics')
    >>> get_args(velplan.Language) == velplan.LANGUAGES == ('en', 'ru', 'uk', 'zh')
    True
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING, Literal, Sequence, overload

from velplan.errors import (
    AssemblyError,
    MechanismError,
    ScaleError,
    SingularPositionError,
    TableError,
    VelplanError,
)
from velplan.options import LANGUAGES, Format, FrameStyle, Language, PlanKind, SheetKind

if TYPE_CHECKING:  # the lazy names below, as type checkers should see them
    from pathlib import Path

    from velplan.analysis.extremes import extremes, positions, reference_angle, stroke
    from velplan.analysis.solver import Kinematics, solve, transfer_functions
    from velplan.html.page import Page
    from velplan.mechanism.loader import example_names, load, parse
    from velplan.mechanism.model import Mechanism
    from velplan.mechanism.structure import structure
    from velplan.note.build import build_note as explanatory_note
    from velplan.render.style import SheetStyle
    from velplan.sheets.dynamics import DynamicsSheet
    from velplan.sheets.forces import ForceSheet
    from velplan.sheets.frame import TitleInfo
    from velplan.sheets.kinematic import Sheet as KinematicSheet
    from velplan.study import Study

__all__ = [
    "AssemblyError", "Kinematics", "LANGUAGES", "Language", "Mechanism", "MechanismError", "Page",
    "PlanKind", "ScaleError", "SheetKind", "SingularPositionError", "Study", "TableError",
    "VelplanError", "example_names", "explanatory_note", "extremes", "load", "parse", "positions",
    "reference_angle", "sheet", "solve", "stroke", "structure", "transfer_functions",
]
__version__ = "0.1.0"

#: Names imported on first use: name → (module, attribute). Even the computing core waits, so
#: a command that never solves (``velplan --help``, ``velplan examples``) imports no numpy.
_LAZY = {
    **{name: ("velplan.analysis.extremes", name)
       for name in ("extremes", "positions", "reference_angle", "stroke")},
    **{name: ("velplan.analysis.solver", name) for name in ("Kinematics", "solve", "transfer_functions")},
    **{name: ("velplan.mechanism.loader", name) for name in ("example_names", "load", "parse")},
    "Mechanism": ("velplan.mechanism.model", "Mechanism"),
    "structure": ("velplan.mechanism.structure", "structure"),
    "Study": ("velplan.study", "Study"),
    "Page": ("velplan.html.page", "Page"),
    "explanatory_note": ("velplan.note.build", "build_note"),
}
#: Former names, kept for one release: old → new (each use warns).
_DEPRECATED = {"analyse": "structure", "loads": "parse"}


@overload
def sheet(study: Study | Mechanism | str | Path, kind: Literal["velocity", "acceleration", "both"] = "both", *,
          n: int = 12, plans: Sequence[int] | None = None, fmt: Format = "A1", lang: Language = "ru",
          frame_style: FrameStyle | None = None, info: TitleInfo | None = None, diagrams: bool | None = None,
          table: bool = True, style: SheetStyle | None = None, data: bool = True, centres: Sequence[int] = (),
          scale_per_plan: bool = False, structure: bool | None = None) -> KinematicSheet: ...
@overload
def sheet(study: Study | Mechanism | str | Path, kind: Literal["forces"], *, n: int = 12,
          plans: Sequence[int] | None = None, fmt: Format = "A1", lang: Language = "ru",
          frame_style: FrameStyle | None = None, info: TitleInfo | None = None, diagrams: bool | None = None,
          table: bool = True, style: SheetStyle | None = None) -> ForceSheet: ...
@overload
def sheet(study: Study | Mechanism | str | Path, kind: Literal["dynamics"], *, n: int = 12, fmt: Format = "A1",
          lang: Language = "ru", frame_style: FrameStyle | None = None, info: TitleInfo | None = None,
          style: SheetStyle | None = None) -> DynamicsSheet: ...
def sheet(study, kind: SheetKind = "both", **options):
    """The sheet of ``study`` (a `Study`, a `Mechanism`, an example name or a TOML path), as
    ``velplan sheet --kind`` draws it: the kinematic sheet (``"velocity"``, ``"acceleration"``
    or ``"both"`` plans), the force sheet (``"forces"``) or the dynamics sheet (``"dynamics"``).

    ``options`` go to the sheet's builder (``fmt``, ``lang``, ``plans``, ``n``, …: see
    `velplan.sheets.kinematic.build_sheet`, `velplan.sheets.forces.build_force_sheet`,
    `velplan.sheets.dynamics.build_dynamics_sheet`; the overloads spell them out per kind).
    The sheet's ``.svg()`` is its text and ``.save(path)`` saves it, the suffix choosing the
    writer (.svg, .png, .pdf, .dxf).

    >>> s = sheet("four-bar", fmt="A2", lang="en", plans=[3])
    >>> s.positions, s.fmt, s.svg().startswith("<?xml")
    ((3,), 'A2', True)
    >>> sheet("four-bar", "forces")
    Traceback (most recent call last):
    ...
    velplan.errors.VelplanError: four-bar declares no masses and no loads: there are no forces to draw; add [link.N] masses or [[load]] tables
    >>> sheet("four-bar", "plans")
    Traceback (most recent call last):
    ...
    velplan.errors.VelplanError: unknown sheet kind 'plans'; known kinds: velocity, acceleration, both, forces, dynamics
    """
    from velplan.sheets.kinds import build

    return build(study, kind, **options)


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        module, attr = _LAZY[name]
        value = getattr(importlib.import_module(module), attr)
        globals()[name] = value
        return value
    if name in _DEPRECATED:
        new = _DEPRECATED[name]
        warnings.warn(f"velplan.{name} is deprecated; use velplan.{new}", DeprecationWarning, stacklevel=2)
        return __getattr__(new)
    raise AttributeError(f"module 'velplan' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
