"""The note's part on forces built by a fork of this process while this process builds the
kinematic sheet and writes its part: the fork builds the force sheet for the positions the
kinematic sheet draws by default, then waits for the number of figures and tables written
before the part, writes the part (`velplan.note.forces.forces_section`) and hands its blocks
back. Only in the ``velplan note`` command (`building_aside`), on Linux, where a core is free
(`velplan.note.raster.core_free`). Where the kinematic sheet draws other positions, or the fork
fails in any way, this process writes the part itself as without it, errors included: the
note is the same either way."""

from __future__ import annotations

import contextlib
import os
import pickle

from velplan.io import FORK_WAIT_S, end_fork, fork_answer, forked

ENABLED = False
"""Whether `build_note` hands the part on forces to a fork (within `building_aside`)."""
WAIT_S = FORK_WAIT_S
"""How long the note waits for the fork's answer, s; then it writes the part itself."""


@contextlib.contextmanager
def building_aside(enabled: bool = True):
    """Within the block, `velplan.note.build_note` builds its part on forces in a fork where a
    core is free for it."""
    global ENABLED
    from velplan.note.raster import FORK, core_free

    was = ENABLED
    ENABLED = enabled and FORK and core_free()
    try:
        yield
    finally:
        ENABLED = was


class ForcesAside:
    """A fork building the part on forces of ``study`` for ``positions``."""

    def __init__(self, study, positions, fmt, lang):
        self.positions = tuple(positions)
        ask, told = os.pipe(), os.pipe()

        def child() -> None:
            os.close(ask[1])
            os.close(told[0])
            _serve(ask[0], told[1], study, self.positions, fmt, lang)

        self.pid = forked(child)
        os.close(ask[0])
        os.close(told[1])
        self.ask, self.told = ask[1], told[0]

    def part(self, note, positions) -> bool:
        """Add the fork's part to ``note`` (numbered after its figures and tables so far); False
        where it has none for ``positions``."""
        if self.pid is None or tuple(positions) != self.positions:
            self.close()
            return False
        try:
            os.write(self.ask, f"{note.figures} {note.tables}\n".encode("ascii"))
            data = fork_answer(self.told, WAIT_S)
        except OSError:
            data = b""
        self.close()
        if not data:
            return False
        blocks, note.figures, note.tables = pickle.loads(data)
        note.add(*blocks)
        return True

    def close(self) -> None:
        """End the fork (if running) and close the pipes."""
        pid, self.pid = self.pid, None
        end_fork(pid, self.ask, self.told)
        self.ask = self.told = -1


def _serve(ask: int, told: int, study, positions, fmt, lang) -> None:
    """In the fork: the force sheet, then the part once the counts arrive (nothing written where
    anything fails: the parent then writes the part itself)."""
    from velplan.note.build import _force_sheet
    from velplan.note.forces import forces_section
    from velplan.note.model import Note

    try:
        sheet = _force_sheet(study, positions, fmt, lang)
    except Exception:  # the parent meets it again and reports it
        return
    with open(ask, "rb") as wanted:
        line = wanted.readline().split()
    if len(line) != 2:
        return
    note = Note(lang, "", figures=int(line[0]), tables=int(line[1]))
    try:
        forces_section(note, sheet)
    except Exception:
        return
    data = pickle.dumps((note.blocks, note.figures, note.tables), protocol=pickle.HIGHEST_PROTOCOL)
    with open(told, "wb") as out:
        out.write(data)

