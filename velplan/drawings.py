"""Regenerate ``drawings/``: the current sheet of every bundled example.

    python -m velplan.drawings            # rewrite drawings/*.svg, shaper.png, README.md
    python -m velplan.drawings --check    # exit 1 and list what is out of date

Each sheet is A1, in Russian (ESKD frame), with both plans at the two default positions
and 12 positions of the scheme: what ``velplan sheet NAME`` draws; the examples that
declare masses or loads also get their force-analysis sheet, ``NAME-forces.svg``
(``velplan sheet NAME --kind forces``). The SVGs are
byte-stable, so a test compares them with a fresh rendering; the PNG of the shaper depends
on the fonts installed and is not compared.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

#: Where the drawings live: ``drawings/`` at the top of the repository.
DRAWINGS = Path(__file__).resolve().parent.parent / "drawings"

OPTIONS = {"n": 12, "kind": "both", "fmt": "A1", "lang": "ru"}
#: Options of the force-analysis sheets (``velplan.force_sheet.build_force_sheet``).
FORCE_OPTIONS = {"n": 12, "fmt": "A1", "lang": "ru"}
PNG_OF = "shaper"
PNG_DPI = 100.0

README = """# drawings

The current kinematic-analysis sheets of the bundled examples, as `velplan sheet NAME`
draws them: A1, Russian labels, ESKD frame and title block, the scheme in 12 positions,
velocity and acceleration plans for two positions, the kinematic diagrams (chord method
beside the analytic curves) and the table of transfer functions.

{files}

The examples with masses and loads also have their force-analysis sheet, as
`velplan sheet NAME --kind forces` draws it: for the position of the largest balancing
moment (and, when the useful load does not act there, a working-stroke position too) the
Assur groups cut free with their loads, gravity, inertia forces and moments and the
reactions, each group's force polygon at a standard μF, Zhukovsky's lever with the balancing
force and the balance M_b(lever) / M_b(kinetostatics); the diagram M_b(φ) and the table of
the balancing moment by the three methods.

{force_files}

Regenerate them all with one command, from the top of the repository:

    python -m velplan.drawings

`python -m velplan.drawings --check` lists the files that are out of date (exit status 1);
the test suite fails in the same case (`tests/sheet/test_drawings.py`). The SVGs are
byte-stable (fixed precision, stable ids, no timestamps); `{png}.png` is a {dpi:g} dpi
preview made with cairosvg and depends on the fonts installed, so it is not compared.
"""


def expected() -> dict[str, bytes]:
    """File name → the bytes it should hold."""
    from velplan.force_sheet import build_force_sheet
    from velplan.mechanism.loader import example_names
    from velplan.sheet import build_sheet

    out: dict[str, bytes] = {}
    for name in example_names():
        out[f"{name}.svg"] = build_sheet(name, **OPTIONS).svg().encode("utf-8")
    for name in force_examples():
        out[f"{name}-forces.svg"] = build_force_sheet(name, **FORCE_OPTIONS).svg().encode(
            "utf-8")
    out["README.md"] = expected_readme()
    return out


def expected_readme() -> bytes:
    """The bytes of drawings/README.md."""
    from velplan.mechanism.loader import example_names

    listing = "\n".join(f"* [`{name}.svg`]({name}.svg)" for name in example_names())
    forces = "\n".join(f"* [`{name}-forces.svg`]({name}-forces.svg)" for name in force_examples())
    return README.format(files=listing, force_files=forces, png=PNG_OF,
                         dpi=PNG_DPI).encode("utf-8")


def force_examples() -> list[str]:
    """The bundled examples that declare masses or loads: they get a force sheet."""
    from velplan.force_sheet import has_forces
    from velplan.mechanism.loader import example_names, load

    return [name for name in example_names() if has_forces(load(name))]


def stale(directory: Path = DRAWINGS) -> list[str]:
    """Names of the files in `directory` that differ from a fresh rendering (or are missing)."""
    return [name for name, data in expected().items()
            if not (directory / name).is_file() or (directory / name).read_bytes() != data]


def regenerate(directory: Path = DRAWINGS, *, png: bool = True) -> list[Path]:
    """Write every drawing into `directory`; returns the files written."""
    from velplan.io import write_atomic
    from velplan.render.export import write_png

    directory.mkdir(parents=True, exist_ok=True)
    written = []
    for name, data in expected().items():
        written.append(write_atomic(directory / name, data))
        if png and name == f"{PNG_OF}.svg":
            written.append(write_png(data.decode("utf-8"), directory / f"{PNG_OF}.png",
                                     dpi=PNG_DPI))
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m velplan.drawings",
                                     description="Regenerate the sheets in drawings/.")
    parser.add_argument("--check", action="store_true",
                        help="only list the out-of-date files; exit 1 if there are any")
    parser.add_argument("--out", type=Path, default=DRAWINGS, help="directory (default drawings/)")
    parser.add_argument("--no-png", action="store_true", help="skip the PNG preview")
    args = parser.parse_args(argv)
    if args.check:
        names = stale(args.out)
        for name in names:
            print(f"out of date: {args.out / name}")
        return 1 if names else 0
    for path in regenerate(args.out, png=not args.no_png):
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
