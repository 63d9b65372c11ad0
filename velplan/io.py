"""Input and output at the edge: a file is either written whole or not at all
(`write_atomic`), and a number read from a file or a command line is finite
(`finite_number`, the one parser of the CSV tables, the variants of a batch and the CLI).

>>> finite_number(" 2.5 ", "crank.length")
2.5
>>> finite_number("inf", "crank.length")
Traceback (most recent call last):
...
velplan.errors.VelplanError: crank.length: 'inf' is not a finite number
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
from pathlib import Path

from velplan.errors import VelplanError


def finite_number(raw: object, what: str, *, error: type[VelplanError] = VelplanError,
                  noun: str = "number") -> float:
    """``raw`` (a number or its text) as a finite float; otherwise ``error`` (a `VelplanError`
    subclass) with one line naming ``what`` and the value: "``what``: 'x' is not a ``noun``" or
    "is not a finite ``noun``". A boolean is not a number.

    >>> finite_number(True, "positions")
    Traceback (most recent call last):
    ...
    velplan.errors.VelplanError: positions: True is not a number
    """
    if isinstance(raw, bool) or not isinstance(raw, (int, float, str)):
        raise error(f"{what}: {raw!r} is not a {noun}")
    try:
        value = float(raw)
    except ValueError:
        raise error(f"{what}: {raw!r} is not a {noun}") from None
    if not math.isfinite(value):
        raise error(f"{what}: {raw!r} is not a finite {noun}")
    return value


def write_atomic(path: str | os.PathLike, data: str | bytes) -> Path:
    """Write ``data`` (text as UTF-8) to ``path`` through a temporary file in the same
    directory, then rename it into place.

    An existing file keeps its permissions, a new one gets 0644 (a drawing or a table is an
    ordinary document). Raises `VelplanError` (one line, naming the path) when the directory is
    missing or not writable; no partial file is left behind.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise VelplanError(f"cannot write {target}: directory {directory} does not exist")
    raw = data.encode("utf-8") if isinstance(data, str) else data
    try:
        handle = tempfile.NamedTemporaryFile(dir=directory, prefix=f".{target.name}.", suffix=".tmp", delete=False)
    except OSError as exc:
        raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
    try:
        with handle:
            handle.write(raw)
        os.chmod(handle.name, _mode_for(target))  # mkstemp files are private (0600)
        os.replace(handle.name, target)
    except BaseException as exc:
        Path(handle.name).unlink(missing_ok=True)
        if isinstance(exc, OSError):
            raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
        raise
    return target


def _mode_for(target: Path) -> int:
    try:
        return target.stat().st_mode & 0o777
    except OSError:
        return 0o644


def cores() -> int:
    """CPU cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # not on Linux
        return os.cpu_count() or 1


def core_free(n: int | None = None, *, now: bool = False) -> bool:
    """Whether a second core is free for a helper process: two cores or more (`n`, by default
    `cores`), and the 1-minute load average (this process's own 1 included) at most the cores
    less half a core; or, with `now`, fewer processes running at this instant than the cores
    (`running_now`, this one included): a busy spell that has just ended keeps the average
    high for minutes."""
    n = cores() if n is None else n
    if n < 2:
        return False
    if now:
        running = running_now()
        if running is not None and running <= n - 1:
            return True
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # no load average (Windows): trust the cores
        load = 1.0
    return load <= n - 0.5


def running_now() -> int | None:
    """Processes running at this instant, this one included (Linux's ``procs_running``), or
    None where the system does not say."""
    try:
        with open("/proc/stat", "rb") as stat:
            for line in stat:
                if line.startswith(b"procs_running "):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        return None
    return None


FORK = sys.platform.startswith("linux") and hasattr(os, "fork")
"""Whether a part may be built by a fork of this process (Linux)."""


def forked(child) -> int:
    """Fork: in the fork run ``child()`` and end at ``os._exit`` (nothing of the parent's
    flushed or cleaned up twice; status 0 where it returned, 1 where it raised); in this
    process return the fork's pid. OSError where the system cannot fork."""
    pid = os.fork()
    if pid == 0:
        code = 1
        try:
            child()
            code = 0
        finally:
            os._exit(code)
    return pid


#: How long a parent waits for a fork's answer before building the part itself, s: a fork stuck
#: (on a lock another thread held when it was made) is not waited on forever.
FORK_WAIT_S = 120.0


def fork_answer(fd: int, wait_s: float = FORK_WAIT_S) -> bytes:
    """All a fork writes to the pipe end ``fd`` (the parent's), or b"" where nothing comes within
    ``wait_s`` or the pipe fails."""
    import select

    try:
        if select.select([fd], [], [], wait_s)[0]:
            with open(fd, "rb", closefd=False) as got:
                return got.read()
    except OSError:
        pass
    return b""


def end_fork(pid: int | None, *fds: int) -> None:
    """Close the parent's pipe ends ``fds`` and end the fork ``pid`` (if any): killed, reaped."""
    import contextlib
    import signal

    for fd in fds:
        with contextlib.suppress(OSError):
            os.close(fd)
    if pid is not None:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)
        with contextlib.suppress(OSError):
            os.waitpid(pid, 0)
