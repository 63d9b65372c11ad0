"""Output written as it is computed: a text stream to standard output or to a file that
appears, atomically, only when it is complete (no half-written file after an error)."""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
from pathlib import Path
from typing import Iterator

from velplan.errors import VelplanError

BUFFER = 1 << 20
"""Bytes buffered before a write to the file (1 MiB)."""


@contextlib.contextmanager
def open_output(path: str | os.PathLike | None, *, binary: bool = False) -> Iterator:
    """A file object to write to: standard output when ``path`` is None, else a temporary
    file beside ``path`` renamed into place when the block ends without an error (removed
    otherwise). Text is UTF-8 with ``\\n`` line ends."""
    if path is None:
        try:
            if binary:
                yield sys.stdout.buffer
                sys.stdout.buffer.flush()
            else:
                yield sys.stdout
                sys.stdout.flush()
        except BrokenPipeError:  # the reader stopped early (| head): not an error
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise VelplanError(f"cannot write {target}: directory {directory} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
    try:
        raw = os.fdopen(fd, "wb", buffering=BUFFER)
        with (raw if binary else io.TextIOWrapper(raw, encoding="utf-8", newline="\n",
                                                   write_through=False)) as handle:
            yield handle
        try:
            mode = target.stat().st_mode & 0o777
        except OSError:
            mode = 0o644
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException as exc:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(exc, OSError):
            raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
        raise
