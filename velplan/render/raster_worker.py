"""A helper process that rasterises SVG files to PNG (`velplan.render.export.svg_to_png`, grey
where the drawing has no colour) while its parent goes on working.

The protocol, one line each way per drawing: the parent writes ``NUMBER DPI`` to the helper's
standard input once ``DIR/NUMBER.svg`` is written; the helper writes ``DIR/NUMBER.png`` and
answers ``NUMBER ok`` on its standard output (``NUMBER failed`` where the conversion fails:
the parent then converts that drawing itself, and reports the error as its own). The helper
stops at the end of its input.

    python -c "from velplan.render.raster_worker import serve; serve()" DIR
"""

from __future__ import annotations

import sys
from pathlib import Path


def serve(folder: str | None = None, stdin=None, stdout=None) -> int:
    """Convert the drawings named on ``stdin`` (default: the process's) in ``folder`` (default:
    the first argument); returns how many were converted."""
    folder = Path(folder if folder is not None else sys.argv[1])
    stdin, stdout = stdin or sys.stdin, stdout or sys.stdout
    from velplan.render.export import shared_fonts, svg_to_png

    done = 0
    with shared_fonts():  # the note's figures: each character measured once
        for line in stdin:
            number, dpi = line.split()
            try:
                svg = (folder / f"{number}.svg").read_text(encoding="utf-8")
                (folder / f"{number}.png").write_bytes(svg_to_png(svg, dpi=float(dpi), grey=True))
                answer = "ok"
                done += 1
            except Exception:  # the parent converts it again and reports the error
                answer = "failed"
            stdout.write(f"{number} {answer}\n")
            stdout.flush()
    return done
