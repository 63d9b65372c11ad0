"""The shaper's full note in Russian (2 positions, kinematics, forces, dynamics; δ = 0.05) and its
.docx, built once per test process for `test_note.py`, `test_note_content.py` and
`test_note_office.py` (`tests/scheduling.py` has one worker run the three files one after the
other), which read it and write nothing into it."""

from __future__ import annotations

_BUILT: list = []


def shaper_ru(tmp_path_factory):
    """(the study, the note, the .docx's path), the .docx in a folder of the session's temporary
    files; built on the first call of the process."""
    if not _BUILT:
        from velplan.note import build_note, write_note
        from velplan.study import Study

        study = Study("shaper", delta=0.05)
        note = build_note(study, lang="ru")
        _BUILT.append((study, note, write_note(note, tmp_path_factory.mktemp("note-shaper-ru") / "note.docx")))
    return _BUILT[0]
