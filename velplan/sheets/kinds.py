"""The sheet kinds, dispatched once: a kind (`velplan.options.SheetKind`) to its builder and its
title block (`velplan.sheets.documents`). `velplan.sheet` and ``velplan sheet --kind`` both draw
through `build`.

>>> default_title_of("forces", "four-bar", "en").designation.endswith("02.00.000")
True
>>> build("four-bar", "plan")
Traceback (most recent call last):
...
velplan.errors.VelplanError: unknown sheet kind 'plan'; known kinds: velocity, acceleration, both, forces, dynamics
"""

from __future__ import annotations

from pathlib import Path

from velplan.mechanism.model import Mechanism
from velplan.options import KINEMATIC_SHEET_KINDS, SheetKind
from velplan.sheets.documents import KINDS, _check, default_title_of, file_stem
from velplan.study import Study

__all__ = ["KINDS", "build", "default_title_of", "file_stem"]


def build(study: Study | Mechanism | str | Path, kind: SheetKind = "both", **options):
    """The ``kind`` sheet of ``study`` (a `Study`, a `Mechanism`, an example name or a TOML
    path), ``options`` passed to its builder (`velplan.sheets.kinematic.build_sheet`,
    `velplan.sheets.forces.build_force_sheet`, `velplan.sheets.dynamics.build_dynamics_sheet`)."""
    if _check(kind) in KINEMATIC_SHEET_KINDS:
        from velplan.sheets.kinematic import build_sheet

        return build_sheet(study, kind=kind, **options)
    if kind == "forces":
        from velplan.sheets.forces import build_force_sheet

        return build_force_sheet(study, **options)
    from velplan.sheets.dynamics import build_dynamics_sheet

    return build_dynamics_sheet(study, **options)
