"""A part of the page built by a fork of this process while this process builds the rest.

Only within `building_aside` (the ``velplan html`` command), on Linux, where a second core is
free (`velplan.io.core_free`, on average or at this instant): elsewhere, and wherever the fork
fails in any way, this process builds the part itself when it asks for it, errors included.
The part is the same either way (it is computed by the same code from the same study), so
the page is the same bytes. On a busy machine the fork made the page slower (both processes
share what the others leave), which is why it waits for a free core.

>>> part = Aside(lambda: sum(range(10)))   # not within building_aside: built when asked
>>> part.result()
45
"""

from __future__ import annotations

import contextlib
import gc
import os
import pickle
from typing import Any, Callable

from velplan.io import FORK, FORK_WAIT_S, core_free, end_fork, fork_answer, forked

ENABLED = False
"""Whether `Aside` hands its part to a fork (within `building_aside`)."""
WAIT_S = FORK_WAIT_S
"""How long this process waits for the fork's answer, s; then it builds the part itself."""


@contextlib.contextmanager
def building_aside(enabled: bool = True):
    """Within the block, each `Aside` builds its part in a fork where a core is free for it,
    and the objects made before the block (or before a fork) are left out of the collections
    (`gc.freeze`): a page makes many objects and few cycles, and each collection of the oldest
    generation walked all the modules' objects again (≈ 5 % of the command's CPU)."""
    global ENABLED
    was = ENABLED
    ENABLED = enabled and FORK and core_free(now=True)
    froze = enabled and gc.get_freeze_count() == 0  # a freeze made by others is theirs
    if froze:
        gc.freeze()
    try:
        yield
    finally:
        ENABLED = was
        if froze:
            gc.unfreeze()


class Aside:
    """``work()`` (a callable returning a picklable value) run by a fork from now on, where
    `building_aside` allows it; `result` reads the fork's value, or runs ``work()`` here."""

    def __init__(self, work: Callable[[], Any]):
        self.work = work
        self.pid: int | None = None
        self.told = -1
        if not ENABLED:
            return
        gc.freeze()  # the fork's collections leave this process's objects (and their pages) alone
        try:
            read, write = os.pipe()

            def child() -> None:
                os.close(read)
                _serve(write, work)

            self.pid = forked(child)
        except OSError:
            self.pid = None
            return
        os.close(write)
        self.told = read

    def result(self) -> Any:
        """The part: the fork's where it made it, else built here."""
        data = b""
        if self.pid is not None:
            data = fork_answer(self.told, WAIT_S)
            self.close()
        return pickle.loads(data) if data else self.work()

    def close(self) -> None:
        """End the fork (if running) and close the pipe."""
        pid, self.pid = self.pid, None
        end_fork(pid, self.told)
        self.told = -1


def _serve(told: int, work: Callable[[], Any]) -> None:
    """In the fork: the part, pickled to `told` (nothing written where anything fails: the
    parent then builds the part itself and meets the error there)."""
    try:
        data = pickle.dumps(work(), protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:
        return
    with open(told, "wb") as out:
        out.write(data)
