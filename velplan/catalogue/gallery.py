"""``python -m velplan.catalogue.gallery OUTDIR [--png]``: a sheet of every catalogue mechanism.

Writes ``OUTDIR/NAME.svg`` (and ``NAME.png`` with ``--png``) — the kinematic-analysis sheet
that ``velplan sheet NAME`` draws — and ``OUTDIR/index.md``, a table of the mechanisms with
their structure, stroke H, time-ratio coefficient K and a link to each sheet. The output is
not kept in the repository; regenerate it when you want to look.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

from velplan.errors import VelplanError
from velplan.io import write_atomic
from velplan.mechanism.loader import catalogue_names
from velplan.mechanism.structure import structure
from velplan.plans.text import LANGS
from velplan.study import Study


def write_gallery(outdir: str | Path, *, names=None, png: bool = False, lang: str = "en",
                  fmt: str = "A1", progress=None) -> Path:
    """Draw the sheet of each catalogue mechanism (``names``: a subset) into ``outdir`` and
    write its ``index.md``; returns the index's path."""
    from velplan.sheets.kinematic import build_sheet

    out = Path(outdir)
    if not out.is_dir():
        raise VelplanError(f"cannot write the gallery: directory {out} does not exist")
    names = list(catalogue_names() if names is None else names)
    unknown = sorted(set(names) - set(catalogue_names()))
    if unknown:
        raise VelplanError(f"not in the catalogue: {', '.join(unknown)}; known: {', '.join(catalogue_names())}")
    rows = []
    for i, name in enumerate(names):
        study = Study(name)
        files = build_sheet(study, fmt=fmt, lang=lang).save(out / f"{name}.svg", png=png)
        mech = study.mechanism
        kinds = " + ".join(g.kind for g in mech.groups)
        st = study.stroke
        if st is None:
            h = k = "—"
        else:
            h = f"{math.degrees(st.H):.2f}°" if st.quantity.startswith("link") else f"{st.H * 1000:.1f} mm"
            k = f"{st.K:.3f}"
        sheet = " · ".join(f"[{f.suffix[1:]}]({f.name})" for f in files)
        rows.append(f"| `{name}` | {mech.title} | crank + {kinds} (W = {structure(mech).mobility}) "
                    f"| {h} | {k} | {sheet} |")
        if progress:
            progress(i + 1, len(names), name)
    text = "\n".join([
        "# Catalogue of course mechanisms",
        "",
        f"Kinematic-analysis sheets ({fmt}, {lang}) of the mechanisms in `velplan/catalogue/`, "
        "drawn by `python -m velplan.catalogue.gallery`. Each file's comment states its numbers.",
        "",
        "| name | mechanism | structure | stroke H | K | sheet |",
        "|---|---|---|---|---|---|",
        *rows,
        "",
    ])
    return write_atomic(out / "index.md", text)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m velplan.catalogue.gallery",
                                description="Draw a sheet of every catalogue mechanism and an index.md.")
    p.add_argument("outdir", metavar="OUTDIR", help="an existing directory for the sheets")
    p.add_argument("--png", action="store_true", help="also write a PNG of each sheet (needs cairosvg)")
    p.add_argument("--lang", choices=LANGS, default="en")
    p.add_argument("--format", choices=("A1", "A2", "A3"), default="A1")
    p.add_argument("--only", metavar="NAME,…", help="only these catalogue mechanisms")
    args = p.parse_args(argv)
    names = None if args.only is None else [n.strip() for n in args.only.split(",") if n.strip()]

    def progress(i, n, name):
        sys.stderr.write(f"\r[{i}/{n}] {name:<28}")
        if i == n:
            sys.stderr.write("\n")

    try:
        index = write_gallery(args.outdir, names=names, png=args.png, lang=args.lang, fmt=args.format,
                              progress=progress)
    except VelplanError as exc:
        sys.stderr.write(f"velplan: error: {exc}\n")
        return 2
    print(index)
    return 0


if __name__ == "__main__":
    sys.exit(main())
