"""The note's figures in the .docx as vector drawings: pandoc embeds each figure's SVG
(``asvg:svgBlip``, which Word 2016 and later draw); the picture it falls back to, the PNG that
LibreOffice, older Word and other readers show, is the figure rasterised by velplan with the
bundled font and put here in the blip's ``r:embed`` (pandoc makes one only where rsvg-convert
is installed; velplan's replaces it, so every reader shows the same lettering)."""

from __future__ import annotations

import io

from docx.oxml.ns import qn

_A = "{http://schemas.openxmlformats.org/drawingml/2006/main}"
_SVG_BLIP = "{http://schemas.microsoft.com/office/drawing/2016/SVG/main}svgBlip"


def svg_blips(doc):
    """(blip element, the SVG's bytes) of every picture of ``doc`` drawn from an SVG."""
    part = doc.part
    out = []
    for blip in part.element.body.iter(f"{_A}blip"):
        svg = next(blip.iter(_SVG_BLIP), None)
        if svg is not None:
            out.append((blip, part.related_parts[svg.get(qn("r:embed"))].blob))
    return out


def add_png_fallbacks(doc, figures: list[tuple[bytes, bytes]]) -> int:
    """Give every SVG picture of ``doc`` its PNG: ``figures`` are the note's (SVG bytes, PNG) in
    order; a picture finds its own by the SVG pandoc embedded, else (a pandoc that rewrote the
    SVG) by its place in the document. Returns the pictures given one."""
    part = doc.part
    by_svg = dict(figures)
    blips = svg_blips(doc)
    done = 0
    for k, (blip, svg) in enumerate(blips):
        png = by_svg.get(svg) or (figures[k][1] if len(blips) == len(figures) else None)
        if png is None:
            continue  # not a figure of the note's: left as pandoc wrote it
        old = blip.get(qn("r:embed"))
        rid, _ = part.get_or_add_image(io.BytesIO(png))
        blip.set(qn("r:embed"), rid)
        if old and old != rid:
            part.drop_rel(old)  # pandoc's own fallback, now referred to by nothing
        done += 1
    return done
