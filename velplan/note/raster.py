"""Whether the note may hand work to a fork of its process (`velplan.note.forces_aside`): on
Linux, and only where a core is free for it (`core_free`): on a busy machine a helper's
overhead (a fork's copied pages, ≈ 5 % more CPU) made the note slower, measured."""

from __future__ import annotations

from velplan import io

FORK = io.FORK
"""Whether a helper can be a fork of this process (Linux; `velplan.io.FORK`)."""


def cores() -> int:
    """CPU cores this process may run on (`velplan.io.cores`)."""
    return io.cores()


def core_free() -> bool:
    """Whether a second core is free for the helper (`velplan.io.core_free`)."""
    return io.core_free(cores())
