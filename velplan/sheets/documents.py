"""The documents of a course work's sheets: per sheet kind, its title block (the subject and
the document's number) and the stem of the file it is written to.

>>> default_title_of("forces", "four-bar", "en").designation.endswith("02.00.000")
True
>>> file_stem("dynamics")
'dynamics'
"""

from __future__ import annotations

from velplan.errors import VelplanError
from velplan.mechanism.model import Mechanism
from velplan.options import KINEMATIC_SHEET_KINDS, Language, SheetKind
from velplan.sheets.frame import TitleInfo
from velplan.sheets.skeleton import course_title

KINDS: tuple[str, ...] = KINEMATIC_SHEET_KINDS + ("forces", "dynamics")
"""Every sheet kind, in the order of ``velplan sheet --kind``."""

#: Per kind: the document's subject and number in the course work (the title block), and the
#: stem of the file ``velplan sheet`` writes by default (MECH-<stem>.svg).
_DOCUMENTS = {"velocity": ("kinematic_analysis", 1, "sheet"), "acceleration": ("kinematic_analysis", 1, "sheet"),
              "both": ("kinematic_analysis", 1, "sheet"), "forces": ("force_analysis", 2, "forces"),
              "dynamics": ("dynamic_analysis", 3, "dynamics")}


def _check(kind: str) -> str:
    if kind not in KINDS:
        raise VelplanError(f"unknown sheet kind {kind!r}; known kinds: {', '.join(KINDS)}")
    return kind


def default_title_of(kind: SheetKind, mech: Mechanism | str, lang: Language, scale: str = "") -> TitleInfo:
    """The title block of the ``kind`` sheet of ``mech``: the course work's document (the
    kinematic sheet 1, the force sheet 2, the dynamics sheet 3) at the scale text ``scale``."""
    from velplan.mechanism.loader import load

    what, number, _ = _DOCUMENTS[_check(kind)]
    return course_title(mech if isinstance(mech, Mechanism) else load(mech), lang, what, number, scale)


def file_stem(kind: SheetKind) -> str:
    """The stem ``velplan sheet`` names the ``kind`` sheet's file with: MECH-<stem>.svg."""
    return _DOCUMENTS[_check(kind)][2]
