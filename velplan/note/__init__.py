"""The explanatory note of a course work (расчётно-пояснительная записка): the calculations of
the sheets written out with their formulas and numbers, as .docx (Word equations), .pdf
(typeset by Typst), .html and .md.

>>> from velplan.note import build_note, write_note
>>> write_note(build_note("shaper", lang="ru", delta=0.05), "note.docx")  # doctest: +SKIP

The writers need the optional extra: ``pip install 'velplan[note]'``.
"""

from velplan.note.build import PARTS, build_note
from velplan.note.model import Note
from velplan.note.writers import FORMATS, note_format, write_note

__all__ = ["PARTS", "FORMATS", "Note", "build_note", "note_format", "write_note"]
