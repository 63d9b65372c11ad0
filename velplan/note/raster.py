"""The note's figures rasterised beside the build: `rasterise_aside` starts a helper process
(`velplan.render.raster_worker`) that makes each figure's PNG as soon as the figure is drawn,
while this process goes on laying out the sheets; the writers then find the PNGs made. On
Linux the helper is a fork of this process, so it has velplan and numpy already and imports
only cairo, which this process then never imports; elsewhere it is a fresh interpreter.
Only where a core is free for it (`core_free`): on a busy machine the helper's overhead (a
fork's copied pages, ≈ 5 % more CPU; a fresh interpreter's imports, as much again as the
rasterising) made the note slower, measured. The PNGs are the same bytes either way. Where
the helper cannot start, dies or fails on a figure, that figure is rasterised in this process
as without it, errors included."""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

from velplan import io

_START = ("import sys; sys.argv[2] in sys.path or sys.path.insert(0, sys.argv[2]); "
          "from velplan.render.raster_worker import serve; serve()")
FORK = sys.platform.startswith("linux") and hasattr(os, "fork")
"""Whether the helper is a fork of this process (Linux), rather than a fresh interpreter."""


def cores() -> int:
    """CPU cores this process may run on (`velplan.io.cores`)."""
    return io.cores()


def core_free() -> bool:
    """Whether a second core is free for the helper (`velplan.io.core_free`)."""
    return io.core_free(cores())


class Helper:
    """A helper process: the pipes that carry the protocol's lines, and how to stop it."""

    def __init__(self, send, recv, stop):
        self.send, self.recv, self._stop = send, recv, stop

    @classmethod
    def forked(cls, folder: Path) -> "Helper":
        """A fork of this process serving ``folder`` (it ends at ``os._exit``: nothing of this
        process's is flushed or cleaned up twice)."""
        from velplan.render.raster_worker import serve

        requests, answers = os.pipe(), os.pipe()
        pid = os.fork()
        if pid == 0:  # the helper
            code = 1
            try:
                os.close(requests[1])
                os.close(answers[0])
                with open(requests[0], encoding="ascii") as rd, open(answers[1], "w", encoding="ascii") as wr:
                    serve(str(folder), rd, wr)
                code = 0
            finally:
                os._exit(code)
        os.close(requests[0])
        os.close(answers[1])

        def stop():
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
            with contextlib.suppress(OSError):
                os.waitpid(pid, 0)

        return cls(open(requests[1], "w", encoding="ascii"), open(answers[0], encoding="ascii"), stop)

    @classmethod
    def spawned(cls, folder: Path) -> "Helper":
        """A fresh interpreter serving ``folder``."""
        root = str(Path(__file__).resolve().parents[2])  # the folder velplan is imported from
        proc = subprocess.Popen([sys.executable, "-c", _START, str(folder), root], stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, encoding="ascii")

        def stop():
            proc.kill()
            proc.wait()

        return cls(proc.stdin, proc.stdout, stop)

    def kill(self) -> None:
        """End the helper and close the pipes."""
        self._stop()
        for pipe in (self.send, self.recv):
            with contextlib.suppress(OSError):
                pipe.close()


class Aside:
    """The helper process and the drawings handed to it: (SVG, dpi) → number."""

    def __init__(self, fork: bool = FORK):
        self.folder = Path(tempfile.mkdtemp(prefix="velplan-figures-"))
        self.numbers: dict[tuple[str, float], int] = {}
        self.answers: dict[int, bool] = {}
        try:
            self.helper: Helper | None = Helper.forked(self.folder) if fork else Helper.spawned(self.folder)
        except OSError:
            self.helper = None

    def submit(self, svg: str, dpi: float) -> None:
        """Hand a drawing to the helper (once)."""
        if self.helper is None or (svg, dpi) in self.numbers:
            return
        number = len(self.numbers)
        try:
            (self.folder / f"{number}.svg").write_text(svg, encoding="utf-8")
            self.helper.send.write(f"{number} {float(dpi)!r}\n")  # numpy's repr is not a number
            self.helper.send.flush()
        except OSError:  # the helper is gone: the figures are rasterised here
            self.close()
            return
        self.numbers[(svg, dpi)] = number

    def png(self, svg: str, dpi: float) -> bytes | None:
        """The helper's PNG of a drawing handed to it (waiting for it), or None."""
        number = self.numbers.get((svg, dpi))
        while self.helper is not None and number is not None and number not in self.answers:
            line = self.helper.recv.readline().split()
            if len(line) != 2:  # the helper is gone
                self.close()
                return None
            self.answers[int(line[0])] = line[1] == "ok"
        if number is None or not self.answers.get(number):
            return None
        try:
            return (self.folder / f"{number}.png").read_bytes()
        except OSError:
            return None

    def close(self) -> None:
        """Stop the helper (its PNGs are read, or not wanted: no need to let it end by itself)
        and remove its files."""
        helper, self.helper = self.helper, None
        if helper is not None:
            helper.kill()
        shutil.rmtree(self.folder, ignore_errors=True)


@contextlib.contextmanager
def rasterise_aside(enabled: bool = True):
    """Within the block, every figure drawn (`velplan.note.figures.views_figure`) is rasterised
    by a helper process (a fork on Linux) where a core is free for it (`core_free`); nothing
    changes otherwise."""
    from velplan.note import figures

    if not enabled or figures.ASIDE is not None or not core_free():
        yield
        return
    aside = Aside()
    figures.ASIDE = aside
    try:
        yield
    finally:
        figures.ASIDE = None
        aside.close()
