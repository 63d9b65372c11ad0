"""Whether the note may hand work to a fork of its process (`velplan.note.forces_aside`): on
Linux, and only where a core is free for it (`core_free`): on a busy machine a helper's
overhead (a fork's copied pages, ≈ 5 % more CPU) made the note slower, measured."""

from __future__ import annotations

import os
import sys

FORK = sys.platform.startswith("linux") and hasattr(os, "fork")
"""Whether a helper can be a fork of this process (Linux)."""


def cores() -> int:
    """CPU cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not on Linux
        return os.cpu_count() or 1


def core_free() -> bool:
    """Whether a second core is free for the helper: two cores or more, and the 1-minute load
    average (this process's own 1 included) at most the cores less half a core."""
    n = cores()
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # no load average (Windows): trust the cores
        load = 1.0
    return n >= 2 and load <= n - 0.5
