"""The note's figures in pixels, for the formats that need them (the .docx's fallback picture,
the .html, the .md): every figure's SVG rasterised by Typst (its SVG renderer, resvg) in one
run, each on a page of its own sized so that its PNG has the figure's resolution. Typst is the
note's own dependency (it typesets the .pdf) and imports in milliseconds, where cairo parses
its C declarations at every import; it lays out a text with ``<tspan>`` pieces and a centred
anchor as a whole, so the SVG needs no fitting first. The texts keep the sheets' narrow face:
Typst files "DejaVu Sans Condensed" under "DejaVu Sans" in a condensed width, so a text whose
first family is a condensed or narrow face asks for that width; the bundled Velplan Sans ends
every family list, as for the sheets' PNGs."""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

from velplan.errors import VelplanError

PPI = 150.0
"""The resolution every page is rendered at, dots per inch; each figure's page is scaled from
its SVG's size so that its pixels are those of the figure's own resolution."""
FONT_DIR = Path(__file__).resolve().parent.parent / "fonts"
_SIZE = re.compile(r'<svg\b[^>]*?\bwidth="([0-9.]+)mm"[^>]*?\bheight="([0-9.]+)mm"|'
                   r'<svg\b[^>]*?\bheight="([0-9.]+)mm"[^>]*?\bwidth="([0-9.]+)mm"')
_FAMILY = re.compile(r'font-family="([^"]*)"')
_NARROW = re.compile(r"condensed|narrow", re.IGNORECASE)


def svg_size_mm(svg: str) -> tuple[float, float]:
    """(width, height) in mm that an SVG document states on its root.

    >>> svg_size_mm('<svg height="20mm" width="40.5mm" viewBox="0 0 40.5 20"/>')
    (40.5, 20.0)
    """
    found = _SIZE.search(svg)
    if found is None:
        raise VelplanError("cannot rasterise a figure: its SVG does not state its width and height in mm")
    w, h, h2, w2 = found.groups()
    return (float(w), float(h)) if w is not None else (float(w2), float(h2))


def for_typst(svg: str) -> str:
    """The SVG with each font-family list ending in the bundled Velplan Sans, and a text whose
    first family is a condensed or narrow face asking for the condensed width.

    >>> for_typst('<text font-family="\\'DejaVu Sans Condensed\\', sans-serif">A</text>')
    '<text font-family="\\'DejaVu Sans Condensed\\', sans-serif, \\'Velplan Sans\\'" font-stretch="condensed">A</text>'
    """
    def family(found: re.Match) -> str:
        names = found.group(1)
        narrow = _NARROW.search(names.split(",")[0]) is not None
        return (f'font-family="{names}, \'Velplan Sans\'"' + (' font-stretch="condensed"' if narrow else ""))

    return _FAMILY.sub(family, svg)


def pngs(pictures) -> list[bytes]:
    """The PNG of each picture (an SVG document sized in mm and the dpi of those mm), made by
    one Typst run; a one-line error where Typst cannot."""
    if not pictures:
        return []
    import typst

    with tempfile.TemporaryDirectory(prefix="velplan-figures-") as tmp:
        pages = []
        for k, picture in enumerate(pictures):
            width, height = svg_size_mm(picture.svg)
            scale = picture.dpi / PPI
            (Path(tmp) / f"{k}.svg").write_text(for_typst(picture.svg), encoding="utf-8")
            pages.append(f'#page(width: {width * scale:.6f}mm, height: {height * scale:.6f}mm)'
                         f'[#image("{k}.svg", width: 100%, height: 100%)]')
        main = Path(tmp) / "figures.typ"
        main.write_text("#set page(margin: 0pt, fill: white)\n" + "\n".join(pages) + "\n", encoding="utf-8")
        try:
            made = typst.compile(str(main), root=tmp, format="png", ppi=PPI, font_paths=[str(FONT_DIR)])
        except Exception as exc:  # typst raises its own error type with the diagnostics
            first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
            raise VelplanError(f"typst could not rasterise the note's figures: {first}") from None
    return [made] if isinstance(made, bytes) else list(made)
