"""``pytest -n … --dist loadfile`` with the files of :data:`TOGETHER` as one unit of work each.

Test files that read the same costly objects (sheets, a note) from a cache kept for the test
process (`tests/shared_notes.py`, `tests/sheet/gallery_marks.SHARED`) are handed to one worker
together, which runs them one after the other and builds those objects once; any other file is
a unit of its own, as pytest-xdist's ``loadfile`` makes it. Without xdist the one process runs
every file and the caches work the same.
"""

from __future__ import annotations

import pytest

#: Files run by one worker one after the other (the first names the unit), and what they share.
TOGETHER: tuple[tuple[str, ...], ...] = (
    # the shaper's Russian note and its .docx (tests/shared_notes.py)
    ("tests/test_note.py", "tests/test_note_content.py", "tests/test_note_office.py"),
    # the Russian kinematic sheets of the catalogue mechanisms whose gallery language is Russian
    ("tests/sheet/test_gallery_marks_a1_kinematic.py", "tests/sheet/test_catalogue_gallery.py"),
    ("tests/sheet/test_gallery_marks_a3_kinematic.py", "tests/sheet/test_catalogue_gallery_a3.py"),
)

_UNIT = {f: files[0] for files in TOGETHER for f in files}


def unit_of(nodeid: str) -> str:
    """The unit of work of a test: its file, or the first file of its :data:`TOGETHER` group."""
    path = nodeid.split("::", 1)[0]
    return _UNIT.get(path, path)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """``--dist loadfile`` by :func:`unit_of`; the other modes as xdist makes them."""
    if config.getvalue("dist") != "loadfile":
        return None
    from xdist.scheduler import LoadFileScheduling

    class LoadUnitScheduling(LoadFileScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return unit_of(nodeid)

    return LoadUnitScheduling(config, log)
