"""The option types of the public API, defined once (the bottom layer: every layer may import it).

>>> from typing import get_args
>>> get_args(PlanKind), get_args(SheetKind)[-2:]
(('velocity', 'acceleration'), ('forces', 'dynamics'))
>>> LANGUAGES
('en', 'ru', 'uk', 'zh')
>>> get_args(Format), get_args(FrameStyle), get_args(Engine)
(('A1', 'A2', 'A3'), ('eskd', 'iso'), ('numpy', 'compiled', 'auto'))
>>> KINEMATIC_SHEET_KINDS
('velocity', 'acceleration', 'both')
"""

from __future__ import annotations

from typing import Literal, get_args

PlanKind = Literal["velocity", "acceleration"]
"""Which plan: of velocities or of accelerations."""

SheetKind = Literal["velocity", "acceleration", "both", "forces", "dynamics"]
"""Which sheet (`velplan.sheet`, ``velplan sheet --kind``): the kinematic sheet with one kind
of plan or both, the force sheet, the dynamics sheet."""

KINEMATIC_SHEET_KINDS: tuple[str, ...] = ("velocity", "acceleration", "both")
"""The kinds drawn on the kinematic sheet."""

Language = Literal["en", "ru", "uk", "zh"]
"""A language of the sheets, pages, notes and step sentences."""

LANGUAGES: tuple[str, ...] = get_args(Language)
"""The languages, in a stable order (used in error messages)."""

Format = Literal["A1", "A2", "A3"]
"""A sheet format (landscape)."""

FrameStyle = Literal["eskd", "iso"]
"""A title block: ESKD form 1 or the captioned ISO-style block."""

Engine = Literal["numpy", "compiled", "auto"]
"""The solver's engine (`velplan.solve`)."""

__all__ = ["Engine", "Format", "FrameStyle", "KINEMATIC_SHEET_KINDS", "LANGUAGES", "Language", "PlanKind", "SheetKind"]
