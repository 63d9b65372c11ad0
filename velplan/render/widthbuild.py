"""``python -m velplan.render.widthbuild [FONT ...]``: remake :mod:`velplan.render.sans_widths`.

Not imported by velplan at run time (fontTools only here). It reads the advance widths of the
fonts a sheet's Latin, Greek and Cyrillic text is drawn with — the bundled Velplan Sans (what
PNG and PDF export fall back on) and DejaVu Sans Condensed (the first family an SVG sheet
names, ``fonts-dejavu-core``'s ``DejaVuSansCondensed.ttf``) — and writes, for every narrow
character the bundled font has in the blocks velplan prints from, the wider of the two
advances in thousandths of an em, rounded up, so that a label measured with the table is never narrower
than it is drawn in either font. A missing font file is skipped with a warning.
"""

from __future__ import annotations

import argparse
import math
import sys
import unicodedata
from pathlib import Path

from velplan.render.fonts import BUNDLED_FONT

#: DejaVu Sans Condensed where Debian and Ubuntu install it.
DEJAVU_CONDENSED = Path("/usr/share/fonts/truetype/dejavu/DejaVuSansCondensed.ttf")
#: Output module.
OUTPUT = Path(__file__).resolve().parent / "sans_widths.py"
#: Unicode blocks measured: Latin, Greek, Cyrillic, punctuation, indices, letterlike signs,
#: arrows, mathematical and technical signs, geometric shapes.
BLOCKS = ((0x20, 0x24F), (0x370, 0x3FF), (0x400, 0x4FF), (0x2000, 0x20CF), (0x2100, 0x23FF),
          (0x25A0, 0x25FF))

_HEADER = '''"""Advance widths of the sheet fonts (Velplan Sans and DejaVu Sans Condensed, the wider of
the two) for the narrow characters a sheet prints: Latin, Greek, Cyrillic, punctuation,
indices, arrows, mathematical and technical signs; thousandths of an em, from the fonts'
horizontal metrics. Generated — do not edit; regenerate with
``python -m velplan.render.widthbuild``."""

from __future__ import annotations

_BY_WIDTH = {
'''
_FOOTER = '''}

WIDTHS: dict[str, float] = {c: w / 1000 for w, chars in _BY_WIDTH.items() for c in chars}
"""Advance width of each character, ems."""
'''


def advances(path: Path) -> dict[int, float]:
    """Advance width of every mapped code point of the font at `path`, ems."""
    from fontTools.ttLib import TTFont

    with TTFont(str(path), lazy=True) as font:
        upm, metrics = font["head"].unitsPerEm, font["hmtx"]
        return {cp: metrics[glyph][0] / upm for cp, glyph in font.getBestCmap().items()}


def table(fonts: list[Path]) -> dict[int, list[str]]:
    """Characters by advance width (thousandths of an em, the widest of `fonts`); only the
    narrow, printable characters of :data:`BLOCKS` the first font has."""
    measured = [advances(p) for p in fonts]
    by_width: dict[int, list[str]] = {}
    for lo, hi in BLOCKS:
        for cp in range(lo, hi + 1):
            char = chr(cp)
            if (cp not in measured[0] or unicodedata.category(char).startswith("C")
                    or unicodedata.east_asian_width(char) in ("W", "F")):
                continue
            width = math.ceil(1000 * max(m[cp] for m in measured if cp in m) - 1e-9)  # never narrower
            by_width.setdefault(width, []).append(char)
    return dict(sorted(by_width.items()))


def main(argv: list[str] | None = None) -> int:
    """Write :data:`OUTPUT` from the bundled font and DejaVu Sans Condensed (or `FONT`s)."""
    parser = argparse.ArgumentParser(prog="python -m velplan.render.widthbuild", description=__doc__)
    parser.add_argument("fonts", nargs="*", type=Path, default=[BUNDLED_FONT, DEJAVU_CONDENSED])
    parser.add_argument("-o", "--output", type=Path, default=OUTPUT)
    args = parser.parse_args(argv)
    fonts = [p for p in args.fonts if p.is_file()]
    for p in set(args.fonts) - set(fonts):
        print(f"widthbuild: {p} not found, skipped", file=sys.stderr)
    if not fonts:
        print("widthbuild: no font to measure", file=sys.stderr)
        return 1
    rows = "".join(f"    {w}: {''.join(chars)!r},\n" for w, chars in table(fonts).items())
    args.output.write_text(_HEADER + rows + _FOOTER, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
