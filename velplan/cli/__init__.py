"""The ``velplan`` command: a thin layer of argument parsing over the library.

Every error is one line on stderr (``velplan: error: …``), exit status 2, no traceback and
no partial output file. Subcommands live in small modules, each with ``register(subparsers)``.
"""

from __future__ import annotations

import argparse
import sys
from importlib import import_module

from velplan.errors import VelplanError

COMMANDS = ("kinematics", "plan", "sheet", "forces", "dynamics", "batch", "html", "centres", "sweep", "note", "convert")
"""Modules of `velplan.cli` that register subcommands (a missing one is skipped)."""
SUBCOMMANDS = {
    "examples": "kinematics", "info": "kinematics", "analyze": "kinematics",
    "plan": "plan", "compare": "plan", "check": "plan",
    "sheet": "sheet", "diagrams": "sheet", "steps": "sheet",
    "forces": "forces", "dynamics": "dynamics", "batch": "batch", "html": "html",
    "centres": "centres", "sweep": "sweep", "note": "note", "convert": "convert",
}
"""Subcommand → the module that registers it: a command imports only its own module (a test
checks this table against what the modules register)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, exit 2, as every other error
        sys.stderr.write(f"velplan: error: {message}\n")
        raise SystemExit(2)


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The argument parser; with ``argv`` naming a known subcommand, only that subcommand's
    module is imported (a cold `velplan sheet` does not import the note's or the sweep's)."""
    from velplan import __version__

    parser = _Parser(prog="velplan", description="Velocity and acceleration plans of planar linkages.")
    parser.add_argument("--version", action="version", version=f"velplan {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    first = next((a for a in argv or () if not a.startswith("-")), None)
    if first in SUBCOMMANDS:
        modules = (SUBCOMMANDS[first],)
    else:  # the list of commands, for the help; `velplan --version` needs none of them
        modules = () if first is None and "--version" in (argv or ()) else COMMANDS
    for name in modules:
        try:
            module = import_module(f"velplan.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"velplan.cli.{name}":
                raise
            continue
        module.register(sub)
    return parser


POSITION_LIMITS = {"analyze": 1_000_000, "sheet": 72, "diagrams": 720, "steps": 360, "plan": 3600,
                   "compare": 3600, "forces": 36_000, "dynamics": 3600, "batch": 72, "centres": 360,
                   "note": 72, "sweep": 36_000}
"""Most --positions (and --angles) each command accepts: beyond them a drawing or a table is
unreadable (and `analyze` as a table stops at 360 columns; `analyze`, `forces` and `dynamics`
as CSV or JSON at 10⁶ rows, ≈ 1 GB; `centres` constructs every centre of every position, ≈ 1.5 ms
a position; the note follows the sheets; `sweep` solves each variant at 0.01° at the finest)."""


MAX_JOBS = 256
"""Most worker processes a command starts (--jobs)."""


def _check_common(args) -> None:
    """Options many commands share, checked once: an output name, a PNG resolution, the
    number of positions."""
    import math

    n = getattr(args, "positions", None)
    most = POSITION_LIMITS.get(getattr(args, "command", ""), None)
    streamed = getattr(args, "command", "") in ("analyze", "forces", "dynamics")
    if streamed and getattr(args, "format", "table") != "table":  # written as computed, in bounded memory
        most = POSITION_LIMITS["analyze"]
    elif getattr(args, "command", "") == "analyze":
        most = 360
    if isinstance(n, int) and most is not None and n > most:
        raise VelplanError(f"--positions {n} is more than velplan {args.command} draws or prints usefully "
                           f"(at most {most})")
    angles = getattr(args, "angles", None)
    if isinstance(angles, str) and most is not None and angles.count(",") + 1 > most:
        raise VelplanError(f"--angles: {angles.count(',') + 1} angles is more than velplan {args.command} "
                           f"draws or prints usefully (at most {most})")
    jobs = getattr(args, "jobs", None)
    if isinstance(jobs, int) and jobs > MAX_JOBS:
        raise VelplanError(f"--jobs {jobs} is more worker processes than velplan starts (at most {MAX_JOBS})")
    out = getattr(args, "output", None)
    if out is not None and not str(out).strip():
        raise VelplanError("-o/--output: give a file name, not an empty string")
    dpi = getattr(args, "dpi", None)
    if dpi is not None and not (math.isfinite(dpi) and 10 <= dpi <= 2400):
        raise VelplanError(f"--dpi must be between 10 and 2400, not {dpi:g}")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv)
    args = parser.parse_args(argv)
    try:
        _check_common(args)
        return int(args.run(args) or 0)
    except VelplanError as exc:
        sys.stderr.write(f"velplan: error: {exc}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("velplan: interrupted\n")
        return 130
