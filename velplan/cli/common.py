"""Argument helpers shared by the subcommands."""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from velplan.errors import VelplanError
from velplan.io import finite_number, write_atomic


def add_mechanism(p: argparse.ArgumentParser, *, optional: bool = False) -> None:
    """The MECH argument: a bundled example name or a TOML path."""
    if optional:
        p.add_argument("mechanism", metavar="MECH", nargs="?", default="shaper",
                       help="bundled example name or TOML file (default: shaper)")
    else:
        p.add_argument("mechanism", metavar="MECH", help="bundled example name or TOML file")


def add_output(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of standard output")


def emit(text: str, output: str | None) -> None:
    """Print ``text`` or write it atomically to ``output``."""
    if output:
        write_atomic(output, text if text.endswith("\n") else text + "\n")
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


def parse_angles(text: str) -> np.ndarray:
    """``"0,30,45.5"`` → radians; a one-line error naming the bad item. Angles are reduced
    modulo 360° in degrees (exactly) before they are converted."""
    if not text.strip():
        raise VelplanError("--angles: give at least one angle in degrees, e.g. --angles 0,90,200")
    out = []
    for item in text.split(","):
        value = finite_number(item.strip(), "--angles", noun="number of degrees")
        out.append(math.fmod(value, 360.0))
    return np.radians(out)


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be ≥ 1, not {value}")
    return value


def default_language(environ=None) -> str:
    """The drawing language that follows the user's locale (LC_ALL, LC_MESSAGES, LANG):
    ru, uk or zh when it names one, English otherwise."""
    import os

    env = os.environ if environ is None else environ
    for key in ("LC_ALL", "LC_MESSAGES", "LANG"):
        value = env.get(key, "")
        if value:
            code = value.split(".")[0].split("_")[0].lower()
            return code if code in ("ru", "uk", "zh", "en") else "en"
    return "en"
