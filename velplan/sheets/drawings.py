"""Regenerate ``drawings/``: the current sheet of every bundled example.

    python -m velplan.drawings            # rewrite drawings/*.svg, shaper.png, README.md
    python -m velplan.drawings --check    # exit 1 and list what is out of date

Each sheet is A1, in Russian (ESKD frame), with both plans at the two default positions
and 12 positions of the scheme: what ``velplan sheet NAME`` draws; the examples that
declare masses or loads also get their force-analysis sheet, ``NAME-forces.svg``
(``velplan sheet NAME --kind forces``). The SVGs are
deterministic, so a test compares them with a fresh rendering (text alike, numbers within
`TOLERANCE`); the PNG of the shaper depends on the fonts installed and is not compared.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

#: Where the drawings live: ``drawings/`` at the top of the repository.
DRAWINGS = Path(__file__).resolve().parents[2] / "drawings"
#: Two drawings agree when their text is the same and every number differs by at most this
#: (mm on the sheet, or the number's own unit): SVGs are written to 0.001 mm, and a value that
#: sits on a rounding boundary may round either way on another machine's floating point.
TOLERANCE = 0.0015

OPTIONS = {"n": 12, "kind": "both", "fmt": "A1", "lang": "ru"}
#: Options of the force-analysis sheets (``velplan.sheets.forces.build_force_sheet``).
FORCE_OPTIONS = {"n": 12, "fmt": "A1", "lang": "ru"}
#: Examples that get a dynamics sheet (``velplan sheet NAME --kind dynamics --delta δ``) → δ.
DYNAMICS = {"shaper": 0.05}
PNG_OF = "shaper"
PNG_DPI = 100.0

README = """# drawings

The current kinematic-analysis sheets of the bundled examples, as `velplan sheet NAME`
draws them: A1, Russian labels, ESKD frame and title block, the scheme in 12 positions,
velocity and acceleration plans for two positions, the kinematic diagrams (chord method
beside the analytic curves), the table of transfer functions and, where free space is left
for it, the structural analysis (the initial mechanism and each Assur group drawn apart).

{files}

The examples with masses and loads also have their force-analysis sheet, as
`velplan sheet NAME --kind forces` draws it: for the position of the largest balancing
moment (and, when the useful load does not act there, a working-stroke position too) the
Assur groups cut free with their loads, gravity, inertia forces and moments and the
reactions, each group's force polygon at a standard μF, Zhukovsky's lever with the balancing
force and the balance M_b(lever) / M_b(kinetostatics); the diagram M_b(φ) and the table of
the balancing moment by the three methods.

{force_files}

The machine dynamics, as `velplan sheet shaper --kind dynamics --delta 0.05` draws it: the
reduced moments, the works and ΔT, the variable part of the reduced inertia and the crank's
ω(φ) over the cycle; Wittenbauer's energy–mass diagram with the tangents at ψmax, ψmin and
the segment kl; the flywheel's section with its dimensions; the table of results (the
flywheel by the exact envelope, by Wittenbauer computed and drawn, and by Mertsalov).

{dynamics_files}

Regenerate them all with one command, from the top of the repository:

    python -m velplan.drawings

`python -m velplan.drawings --check` lists the files that are out of date (exit status 1);
the test suite fails in the same case (`tests/sheet/test_drawings_and_output.py`). The SVGs
are deterministic (fixed precision, stable ids, no timestamps) and are compared as drawings:
the same text, and numbers within 0.0015 mm, since a value on a rounding boundary may round
either way on another machine; `{png}.png` is a {dpi:g} dpi preview made with cairosvg and
depends on the fonts installed, so it is not compared.
"""


def expected() -> dict[str, bytes]:
    """File name → the bytes it should hold."""
    from velplan.mechanism.loader import example_names
    from velplan.sheets.dynamics import build_dynamics_sheet
    from velplan.sheets.forces import build_force_sheet, has_forces
    from velplan.sheets.kinematic import build_sheet
    from velplan.study import Study

    out: dict[str, bytes] = {}
    for name in example_names():
        study = Study(name, n=OPTIONS["n"])  # one study for both sheets of the example
        opts = {k: v for k, v in OPTIONS.items() if k != "n"}
        out[f"{name}.svg"] = build_sheet(study, **opts).svg().encode("utf-8")
        if has_forces(study.mechanism):
            fopts = {k: v for k, v in FORCE_OPTIONS.items() if k != "n"}
            out[f"{name}-forces.svg"] = build_force_sheet(study, **fopts).svg().encode("utf-8")
    for name, delta in DYNAMICS.items():
        study = Study(name, n=OPTIONS["n"], delta=delta)
        out[f"{name}-dynamics.svg"] = build_dynamics_sheet(study, fmt=OPTIONS["fmt"],
                                                           lang=OPTIONS["lang"]).svg().encode("utf-8")
    out["README.md"] = expected_readme()
    return dict(sorted(out.items(), key=lambda kv: (kv[0] == "README.md", kv[0])))


def expected_readme() -> bytes:
    """The bytes of drawings/README.md."""
    from velplan.mechanism.loader import example_names

    listing = "\n".join(f"* [`{name}.svg`]({name}.svg)" for name in example_names())
    forces = "\n".join(f"* [`{name}-forces.svg`]({name}-forces.svg)" for name in force_examples())
    dynamics = "\n".join(f"* [`{name}-dynamics.svg`]({name}-dynamics.svg)" for name in DYNAMICS)
    return README.format(files=listing, force_files=forces, dynamics_files=dynamics, png=PNG_OF,
                         dpi=PNG_DPI).encode("utf-8")


def force_examples() -> list[str]:
    """The bundled examples that declare masses or loads: they get a force sheet."""
    from velplan.mechanism.loader import example_names, load
    from velplan.sheets.forces import has_forces

    return [name for name in example_names() if has_forces(load(name))]


_NUMBER = re.compile(rb"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def same_drawing(a: bytes, b: bytes, tol: float = TOLERANCE) -> bool:
    """Whether two SVG documents are the same drawing: equal text between the numbers, and
    numbers that differ by at most ``tol``."""
    if a == b:
        return True
    if _NUMBER.sub(b"#", a) != _NUMBER.sub(b"#", b):
        return False
    return all(abs(float(x) - float(y)) <= tol for x, y in zip(_NUMBER.findall(a), _NUMBER.findall(b)))


def stale(directory: Path = DRAWINGS) -> list[str]:
    """Names of the files in `directory` that differ from a fresh rendering (or are missing)."""
    return [name for name, data in expected().items()
            if not (directory / name).is_file() or not same_drawing((directory / name).read_bytes(), data)]


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
