"""Assembling the note from a study and the sheets velplan draws of it (built once each), so
that every number and figure is the sheets' own."""

from __future__ import annotations

import sys

from velplan.errors import ScaleError, VelplanError
from velplan.note.model import Heading, Note
from velplan.note.text import p
from velplan.options import Format, Language

PARTS = ("kinematics", "forces", "dynamics")


def build_note(mech, *, n: int = 12, plans=None, parts=None, lang: Language = "ru", fmt: Format = "A1",
               delta: float | None = None, fields: dict | None = None) -> Note:
    """The explanatory note of ``mech`` (a `Study`, a mechanism, a name or a TOML path).

    Parameters
    ----------
    plans : sequence of int, optional
        Positions (1-based) whose plans, groups and lever are written out; the kinematic
        sheet's two by default.
    parts : sequence of str, optional
        Of ``kinematics``, ``forces``, ``dynamics``; by default every part the mechanism has
        data for (a dynamics that cannot be solved is then left out with a warning).
    fmt : str
        The sheets whose scales and drawings the note follows (A1 as a course work's).
    fields : dict, optional
        Title page: ``organisation``, ``author``, ``group``, ``checker``, ``date``.
    """
    from velplan.note import ends
    from velplan.render.i18n import check_language
    from velplan.sheets.forces import has_forces
    from velplan.sheets.kinematic import build_sheet
    from velplan.study import Study

    check_language(lang)
    study = mech if isinstance(mech, Study) else Study(mech, n=n, delta=delta)
    asked = parts is not None
    parts = tuple(parts) if asked else PARTS
    for part in parts:
        if part not in PARTS:
            raise VelplanError(f"--parts: unknown part {part!r}; known parts: {', '.join(PARTS)}")
    aside = _forces_aside(study, parts, plans, fmt, lang)
    try:
        sheet = build_sheet(study, plans=plans, fmt=fmt, lang=lang)
        note = _kinematics(study, sheet, parts, asked, fields, lang)
        if "forces" in parts:
            if has_forces(study.mechanism):
                _optional("forces", asked, lambda: _forces(note, study, sheet, fmt, lang, aside))
            elif asked:
                raise VelplanError(f"{study.mechanism.name} declares no masses and no loads: there are no forces "
                                   f"to write out; add [link.N] masses or [[load]] tables")
    finally:
        if aside is not None:
            aside.close()
    if "dynamics" in parts:
        _optional("dynamics", asked, lambda: _dynamics(note, study, fmt, lang))
    _conclusion(note, study, parts)
    ends.references(note)
    return note


def _kinematics(study, sheet, parts, asked, fields, lang) -> Note:
    """The note up to its part on forces: title, introduction, data, structure, positions and
    (where asked for) the kinematics."""
    from velplan.note import ends, front, kinematics as K
    from velplan.sheets.forces import has_forces

    note = Note(lang, f"{p('note', lang)}: {study.mechanism.name_in(lang)}")
    front.title_page(note, study, fields)
    ends.introduction(note, study, [x for x in parts if x != "forces" or has_forces(study.mechanism)])
    front.data_section(note, study)
    front.structure_section(note, study)
    K.positions_section(note, study, sheet)
    if "kinematics" in parts:
        note.add(Heading(p("sec_kinematics", lang), 1))
        for k in sheet.positions:
            for kind in ("v", "a"):
                if f"plan-{kind}-{k}" in sheet.plans:
                    K.plan_section(note, sheet, k, kind)
        K.analogues_section(note, study, sheet)
        K.diagrams_section(note, sheet, study)
    return note


def _forces_aside(study, parts, plans, fmt, lang):
    """The fork building the part on forces (`velplan.note.forces_aside`), where enabled and
    the note has that part: for the positions given, else the kinematic sheet's default two."""
    from velplan.note import forces_aside
    from velplan.sheets.forces import has_forces

    if not forces_aside.ENABLED or "forces" not in parts or not has_forces(study.mechanism):
        return None
    try:
        return forces_aside.ForcesAside(study, _likely_positions(study, plans), fmt, lang)
    except OSError:  # no fork: the part is written here
        return None


def _likely_positions(study, plans) -> tuple[int, ...]:
    """The positions the kinematic sheet will likely draw: those given, else its default two
    (it keeps the first alone where the two do not fit)."""
    from velplan.sheets.kinematic import default_plan_positions

    return tuple(plans) if plans is not None else tuple(default_plan_positions(study.plan("velocity")))


def _forces(note, study, sheet, fmt, lang, aside) -> None:
    """The part on forces: the fork's, else written here."""
    if aside is not None and aside.part(note, sheet.positions):
        return
    from velplan.note import forces as F

    F.forces_section(note, _force_sheet(study, sheet.positions, fmt, lang))


def _conclusion(note, study, parts) -> None:
    """The conclusion from the parts the note holds (a part left out adds nothing)."""
    from velplan.note import ends
    from velplan.note.blocks import Heading

    heads = {b.text for b in note.blocks if isinstance(b, Heading)}
    moments = (study.forces().balancing_moments["kinetostatics"]
               if p("sec_forces", note.lang) in heads else None)
    fly = study.dynamics.flywheel if p("sec_dynamics", note.lang) in heads else None
    drive = None
    if fly is not None:
        from velplan.note.dynamics_worked import drive_of

        drive = drive_of(study.dynamics)
    ends.conclusion(note, study, moments, fly, drive)


def _optional(part: str, asked: bool, write) -> None:
    """Write a part; one the user did not ask for by name is left out, with a warning, when
    its sheet cannot be made (a dynamics without a flywheel's δ, polygons too large)."""
    try:
        write()
    except VelplanError as exc:
        if asked:
            raise
        sys.stderr.write(f"velplan: note: {part} left out: {exc}\n")


def _force_sheet(study, positions, fmt, lang):
    from velplan.sheets.forces import build_force_sheet

    try:
        return build_force_sheet(study, plans=positions, fmt=fmt, lang=lang)
    except ScaleError:  # both positions do not fit the sheet: the sheet's own choice
        return build_force_sheet(study, fmt=fmt, lang=lang)


def _dynamics(note, study, fmt, lang) -> None:
    from velplan.note.dynamics import dynamics_section
    from velplan.sheets.dynamics import build_dynamics_sheet

    dynamics_section(note, build_dynamics_sheet(study, fmt=fmt, lang=lang))
