"""``python -m velplan.catalogue.gallery OUTDIR [--png]``: a sheet of every catalogue mechanism.

Writes ``OUTDIR/NAME.svg`` (and ``NAME.png`` with ``--png``) — the kinematic-analysis sheet
that ``velplan sheet NAME`` draws — and ``OUTDIR/index.md``, a table of the mechanisms with
their structure, stroke H, time-ratio coefficient K and a link to each sheet. The output is
not kept in the repository; regenerate it when you want to look. ``--contact FILE`` also
writes a contact sheet, every sheet's PNG as a captioned thumbnail on one image (the README's
gallery, ``docs/gallery.png``, is made this way).
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
from velplan.options import Language
from velplan.plans.text import LANGS
from velplan.study import Study


def write_gallery(outdir: str | Path, *, names=None, png: bool = False, lang: Language = "en",
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


def contact_sheet(pngs: dict[str, Path], path: str | Path, *, columns: int = 5,
                  thumb_px: int = 320) -> Path:
    """One image of the sheets' PNGs (``pngs``: caption → file), ``columns`` thumbnails
    ``thumb_px`` pixels wide to a row, each captioned, in 16 greys; written atomically to ``path``."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.image import imread

    if not pngs:
        raise VelplanError("contact sheet: no sheets to put on it")
    images = {name: imread(str(f)) for name, f in pngs.items()}
    aspect = max(img.shape[0] / img.shape[1] for img in images.values())
    rows = math.ceil(len(images) / columns)
    dpi = 100
    cell_w, cell_h = thumb_px / dpi, thumb_px * aspect / dpi + 0.22
    fig = Figure(figsize=(columns * cell_w, rows * cell_h), dpi=dpi)  # no pyplot: the caller's backend stays
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, columns, squeeze=False)
    for ax in axes.flat:
        ax.set_axis_off()
    for ax, (name, img) in zip(axes.flat, images.items()):
        ax.imshow(img, interpolation="lanczos")
        ax.set_title(name, fontsize=8, pad=2)
    fig.subplots_adjust(left=0.005, right=0.995, top=0.99, bottom=0.005, wspace=0.03, hspace=0.12)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    from PIL import Image  # matplotlib's own dependency

    grey = Image.open(io.BytesIO(buf.getvalue())).convert("L").quantize(colors=16)  # line art: 16 greys
    out = io.BytesIO()
    grey.save(out, format="PNG", optimize=True)
    return write_atomic(Path(path), out.getvalue())


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m velplan.catalogue.gallery",
                                description="Draw a sheet of every catalogue mechanism and an index.md.")
    p.add_argument("outdir", metavar="OUTDIR", help="an existing directory for the sheets")
    p.add_argument("--png", action="store_true", help="also write a PNG of each sheet (needs cairosvg)")
    p.add_argument("--lang", choices=LANGS, default="en")
    p.add_argument("--format", choices=("A1", "A2", "A3"), default="A1")
    p.add_argument("--only", metavar="NAME,…", help="only these catalogue mechanisms")
    p.add_argument("--contact", metavar="FILE", help="also a contact sheet of every sheet as one PNG "
                   "(implies --png)")
    args = p.parse_args(argv)
    names = None if args.only is None else [n.strip() for n in args.only.split(",") if n.strip()]

    def progress(i, n, name):
        sys.stderr.write(f"\r[{i}/{n}] {name:<28}")
        if i == n:
            sys.stderr.write("\n")

    try:
        index = write_gallery(args.outdir, names=names, png=args.png or bool(args.contact), lang=args.lang,
                              fmt=args.format, progress=progress)
        if args.contact:
            drawn = names if names is not None else catalogue_names()
            print(contact_sheet({n: Path(args.outdir) / f"{n}.png" for n in drawn}, args.contact))
    except VelplanError as exc:
        sys.stderr.write(f"velplan: error: {exc}\n")
        return 2
    print(index)
    return 0


if __name__ == "__main__":
    sys.exit(main())
