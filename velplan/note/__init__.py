"""The explanatory note of a course work (расчётно-пояснительная записка): the calculations of
the sheets written out with their formulas and numbers, as .docx (Word equations), .pdf
(typeset by Typst), .html and .md.

>>> from velplan.note import build_note, write_note
>>> write_note(build_note("shaper", lang="ru", delta=0.05), "note.docx")  # doctest: +SKIP

The writers need the optional extra: ``pip install 'velplan[note]'``. The parts of a note and
the formats its suffix chooses:

>>> import tempfile
>>> from pathlib import Path
>>> from velplan.note import FORMATS, PARTS, Note, note_format
>>> PARTS, sorted(set(FORMATS.values()))
(('kinematics', 'forces', 'dynamics'), ['docx', 'html', 'md', 'pdf'])
>>> note = build_note("four-bar", n=4, parts=["kinematics"], lang="en")
>>> isinstance(note, Note), note.title
(True, 'Explanatory note: four-bar linkage')
>>> with tempfile.TemporaryDirectory() as tmp:
...     written = write_note(note, Path(tmp) / "note.md")
...     print(written.name, note_format(written), "four-bar" in written.read_text("utf-8"))
note.md md True
>>> note_format("note.txt")
Traceback (most recent call last):
...
velplan.errors.VelplanError: cannot tell the note's format from 'note.txt': name it .docx, .pdf, .html or .md
>>> build_note("four-bar", parts=["statics"])
Traceback (most recent call last):
...
velplan.errors.VelplanError: --parts: unknown part 'statics'; known parts: kinematics, forces, dynamics
"""

from velplan.note.build import PARTS, build_note
from velplan.note.model import Note
from velplan.note.writers import FORMATS, note_format, write_note

__all__ = ["PARTS", "FORMATS", "Note", "build_note", "note_format", "write_note"]
