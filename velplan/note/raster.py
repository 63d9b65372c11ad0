"""The note's figures rasterised beside the build: `rasterise_aside` starts a helper process
(`velplan.render.raster_worker`) that imports cairo and makes each figure's PNG as soon as the
figure is drawn, while this process goes on laying out the sheets; the writers then find the
PNGs made. Only where a core is free for it: two cores or more, and a load average (this
process included) half a core below their number — on a busy machine the helper's own imports
(numpy, cairo: as much CPU again as the rasterising) would only slow the note down. The PNGs
are the same bytes either way. Where the helper cannot start, dies or fails on a figure, that
figure is rasterised in this process as without it, errors included."""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

_START = ("import sys; sys.argv[2] in sys.path or sys.path.insert(0, sys.argv[2]); "
          "from velplan.render.raster_worker import serve; serve()")


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


class Aside:
    """The helper process and the drawings handed to it: (SVG, dpi) → number."""

    def __init__(self):
        self.folder = Path(tempfile.mkdtemp(prefix="velplan-figures-"))
        self.numbers: dict[tuple[str, float], int] = {}
        self.answers: dict[int, bool] = {}
        root = str(Path(__file__).resolve().parents[2])  # the folder velplan is imported from
        try:
            self.proc: subprocess.Popen | None = subprocess.Popen(
                [sys.executable, "-c", _START, str(self.folder), root], stdin=subprocess.PIPE,
                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, encoding="ascii", bufsize=1)
        except OSError:
            self.proc = None

    def submit(self, svg: str, dpi: float) -> None:
        """Hand a drawing to the helper (once)."""
        if self.proc is None or (svg, dpi) in self.numbers:
            return
        number = len(self.numbers)
        try:
            (self.folder / f"{number}.svg").write_text(svg, encoding="utf-8")
            self.proc.stdin.write(f"{number} {dpi!r}\n")
            self.proc.stdin.flush()
        except OSError:  # the helper is gone: the figures are rasterised here
            self.close()
            return
        self.numbers[(svg, dpi)] = number

    def png(self, svg: str, dpi: float) -> bytes | None:
        """The helper's PNG of a drawing handed to it (waiting for it), or None."""
        number = self.numbers.get((svg, dpi))
        while self.proc is not None and number is not None and number not in self.answers:
            line = self.proc.stdout.readline().split()
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
        """Stop the helper and remove its files."""
        proc, self.proc = self.proc, None
        if proc is not None:
            proc.kill()  # its PNGs are read (or not wanted): no need to wait for its interpreter to end
            proc.wait()
            for pipe in (proc.stdin, proc.stdout):
                with contextlib.suppress(OSError):
                    pipe.close()
        shutil.rmtree(self.folder, ignore_errors=True)


@contextlib.contextmanager
def rasterise_aside(enabled: bool = True):
    """Within the block, every figure drawn (`velplan.note.figures.views_figure`) is rasterised
    by a helper process where a core is free for it (`core_free`); nothing changes otherwise."""
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
