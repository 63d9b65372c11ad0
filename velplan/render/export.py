"""Writing sheets to disk: SVG and DXF as they are, PNG and PDF through cairosvg (optional).

Every write is atomic: the bytes go to a temporary file in the target's directory, which
then replaces the target with :func:`os.replace`. A failed conversion or write leaves the
directory as it was — no half-written file, an existing file untouched.

Before cairosvg sees a sheet, its texts are fitted to what cairosvg can do
(:func:`texts_for_cairo`): each gets the one font family that has all its characters
(:mod:`velplan.render.fonts`; the bundled Velplan Sans when the named fonts lack some), and
a centred or right-aligned text with indices (``<tspan>``) is measured and anchored at its
start, since cairosvg would align each piece on its own. A character no font has is a
one-line error rather than a box in the picture. The SVG written to disk keeps its
font-family lists and anchors.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import re
import sys
from pathlib import Path

from velplan.errors import VelplanError
from velplan.io import write_atomic

_INSTALL_HINT = "pip install cairosvg (in a checkout: pip install '.[export]')"


def write_svg(svg_text: str, path: str | os.PathLike) -> Path:
    """Write an SVG document atomically, UTF-8 encoded.

    Parameters
    ----------
    svg_text : str
        The SVG document, e.g. from :func:`velplan.render.svg.to_svg`.
    path : str or PathLike
        Target file.

    Returns
    -------
    Path
        The written file.
    """
    return write_atomic(path, svg_text)


def write_dxf(dxf_text: str, path: str | os.PathLike) -> Path:
    """Write a DXF document atomically, UTF-8 encoded (as DXF R2007 and later require).

    Parameters
    ----------
    dxf_text : str
        The DXF document, e.g. from :func:`velplan.render.dxf.to_dxf`.
    path : str or PathLike
        Target file.

    Returns
    -------
    Path
        The written file.

    Raises
    ------
    VelplanError
        If `dxf_text` is not a DXF document, or the file cannot be written.
    """
    if not isinstance(dxf_text, str) or dxf_text.split(None, 2)[:2] != ["0", "SECTION"]:
        raise VelplanError(f"write_dxf needs the text of a DXF document (from to_dxf), got "
                           f"{type(dxf_text).__name__} {str(dxf_text)[:20]!r}")
    return write_atomic(path, dxf_text)


def write_png(svg_text: str, path: str | os.PathLike, *, dpi: float = 150.0,
              background: str = "white") -> Path:
    """Rasterise an SVG document (sized in mm) to PNG at `dpi`, atomically.

    Parameters
    ----------
    svg_text : str
        The SVG document.
    path : str or PathLike
        Target file.
    dpi : float
        Resolution, dots per inch; an A3 sheet at 150 dpi is 2480 × 1754 px.
    background : str
        Colour under the drawing (paper).

    Raises
    ------
    VelplanError
        If cairosvg is missing or the conversion fails.
    """
    if not dpi > 0:
        raise VelplanError(f"PNG resolution must be positive, got dpi={dpi!r}")
    data = _convert("svg2png", svg_text, dpi=dpi, background_color=background)
    return write_atomic(path, data)


def write_pdf(svg_text: str, path: str | os.PathLike) -> Path:
    """Convert an SVG document (sized in mm) to a vector PDF of the same size, atomically.

    Raises
    ------
    VelplanError
        If cairosvg is missing or the conversion fails.
    """
    return write_atomic(path, _convert("svg2pdf", svg_text))


def svg_to_png(svg_text: str, *, dpi: float = 150.0, background: str = "white", grey: bool = False) -> bytes:
    """The PNG of an SVG document (sized in mm) at ``dpi`` (needs cairosvg); with ``grey``, a
    drawing without colour is written as grey (and alpha) pixels rather than RGBA, the same
    pixels in fewer bytes and less time (`velplan.render.pngcodec`)."""
    if not dpi > 0:
        raise VelplanError(f"PNG resolution must be positive, got dpi={dpi!r}")
    return _convert("svg2png", svg_text, grey=grey, dpi=dpi, background_color=background)


def _grey_png(cairosvg):
    """cairosvg's PNG converter, its pixels written by `velplan.render.pngcodec.surface_png`."""
    from velplan.render.pngcodec import surface_png

    class GreyPNGSurface(cairosvg.surface.PNGSurface):
        def finish(self):
            if self.output is not None:
                self.output.write(surface_png(self.cairo))
            return cairosvg.surface.Surface.finish(self)

    return GreyPNGSurface.convert


def svg_to_pdf(svg_text: str) -> bytes:
    """The vector PDF of an SVG document (sized in mm), of the same size (needs cairosvg)."""
    return _convert("svg2pdf", svg_text)


#: The files a drawing saves to, by suffix (the SVG is always written).
SUFFIXES = (".svg", ".png", ".pdf", ".dxf")


def save_drawing(svg_text: str, path: str | os.PathLike, *, scene=None, style=None, png: bool = False,
                 pdf: bool = False, dxf: bool = False, dpi: float = 150.0) -> list[Path]:
    """Save a drawing, its writer chosen by the suffix of ``path`` as matplotlib's ``savefig``
    chooses: the SVG always (at ``path``, or beside a ``.png``, ``.pdf`` or ``.dxf`` name), and
    the PNG, PDF and DXF that the suffix or ``png``, ``pdf``, ``dxf`` ask for, beside it. The
    DXF needs the drawing's ``scene`` and ``style``. Every conversion runs before anything is
    written, so a failure leaves no file behind. Returns the files written, the SVG first.

    >>> save_drawing("<svg/>", "sheet.dxf")
    Traceback (most recent call last):
    ...
    velplan.errors.VelplanError: cannot write sheet.dxf: a DXF needs the drawing's scene and style
    """
    target = Path(path)
    suffix = target.suffix.lower()
    png, pdf, dxf = png or suffix == ".png", pdf or suffix == ".pdf", dxf or suffix == ".dxf"
    if suffix in (".png", ".pdf", ".dxf"):
        target = target.with_suffix(".svg")
    if dxf and (scene is None or style is None):
        raise VelplanError(f"cannot write {target.with_suffix('.dxf')}: a DXF needs the drawing's scene and style")
    if not target.parent.is_dir():
        raise VelplanError(f"cannot write {target}: directory {target.parent} does not exist")
    blobs: list[tuple[bytes | str, Path]] = []
    if dxf:
        from velplan.render.dxf import to_dxf

        blobs.append((to_dxf(scene, style), target.with_suffix(".dxf")))
    if png:
        blobs.append((svg_to_png(svg_text, dpi=dpi), target.with_suffix(".png")))
    if pdf:
        blobs.append((svg_to_pdf(svg_text), target.with_suffix(".pdf")))
    written = [write_svg(svg_text, target)]
    blobs = blobs[1:] + blobs[:1] if dxf else blobs  # PNG, PDF, then DXF
    for data, where in blobs:
        written.append(write_dxf(data, where) if where.suffix == ".dxf" else write_atomic(where, data))
    return written


def _cairosvg():
    try:
        if "cairocffi" not in sys.modules and sys.platform.startswith("linux"):
            _import_cairocffi_by_soname()
        return importlib.import_module("cairosvg")
    except (ImportError, OSError) as exc:  # OSError: cairosvg present, libcairo missing
        raise VelplanError(f"PNG/PDF export needs cairosvg and the cairo library "
                           f"({type(exc).__name__}: {exc}); install it with "
                           f"`{_INSTALL_HINT}`") from exc


def _import_cairocffi_by_soname() -> None:
    """Import cairocffi letting the dynamic loader find ``libcairo.so.2`` itself: cairocffi first
    asks `ctypes.util.find_library` for three names, which on Linux runs ``ldconfig -p`` for
    each and then gcc and ld for the two it does not find (about 0.1 s of seven processes);
    the loader's answer is the one find_library would give. (Linux only: elsewhere
    find_library also searches folders the loader does not.)"""
    import ctypes.util

    found = ctypes.util.find_library
    ctypes.util.find_library = lambda name: None  # cairocffi then opens its file names
    try:
        module = importlib.import_module("cairocffi")
    finally:
        ctypes.util.find_library = found
    module.find_library = found  # for its later look-ups (gdk-pixbuf)


_BATCH: dict | None = None
"""The conversions' shared `CairoFonts` within `shared_fonts` (None outside it)."""


@contextlib.contextmanager
def shared_fonts():
    """Within the block the conversions measure their texts with one `CairoFonts`, made at the
    first: a batch converted together (a note's figures) asks cairo about each character once,
    not once a drawing. Outside it each conversion asks afresh (fonts may be installed between
    two)."""
    global _BATCH
    if _BATCH is not None:  # within an outer batch: its fonts
        yield
        return
    _BATCH = {}
    try:
        yield
    finally:
        _BATCH = None


def _fonts():
    """The `CairoFonts` a conversion measures with: the batch's, else a new one."""
    from velplan.render.fonts import CairoFonts

    if _BATCH is None:
        return CairoFonts(importlib.import_module("cairocffi"))
    if "fonts" not in _BATCH:
        _BATCH["fonts"] = CairoFonts(importlib.import_module("cairocffi"))
    return _BATCH["fonts"]


def _convert(function: str, svg_text: str, *, grey: bool = False, **options) -> bytes:
    converter = _grey_png(_cairosvg()) if grey else getattr(_cairosvg(), function)
    from velplan.render.fonts import register_with_fontconfig

    register_with_fontconfig()
    fonts = _fonts()
    fitted = texts_for_cairo(svg_text, fonts, what=function.removeprefix("svg2").upper())
    try:
        return converter(bytestring=fitted.encode("utf-8"), **options)
    except Exception as exc:
        first_line = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise VelplanError(f"cairosvg could not convert the sheet ({function}): "
                           f"{first_line}") from exc


_SVG_NS = "{http://www.w3.org/2000/svg}"
# Text properties a <text> inherits from its groups (presentation attributes only).
_INHERITED = ("font-family", "font-size", "font-style", "text-anchor")


def texts_for_cairo(svg_text: str, fonts, *, what: str = "PNG") -> str:
    """The SVG document with its texts fitted to cairosvg.

    Parameters
    ----------
    svg_text : str
        The SVG document.
    fonts : velplan.render.fonts.CairoFonts
        Glyph coverage and advances as cairo sees them.
    what : str
        Name of the output, for the error message.

    Returns
    -------
    str
        The document, each ``<text>`` with a single font family that has all its
        characters; a centred or right-aligned one with ``<tspan>`` children anchored at
        its measured start.

    Raises
    ------
    VelplanError
        One line naming the characters no font has and the text they are in.
    """
    try:  # cairosvg's own dependency, hardened against entity expansion
        from defusedxml import ElementTree
    except ImportError:  # pragma: no cover - cairosvg brings it
        from xml.etree import ElementTree

    try:
        root = ElementTree.fromstring(svg_text.encode("utf-8"))
    except Exception as exc:
        raise VelplanError(f"cannot convert to {what}: the SVG does not parse "
                           f"({type(exc).__name__}: {exc})") from exc
    problems = [problem for element, props in _text_elements(root, {})
                if (problem := _fit_text(element, props, fonts))]
    if problems:
        raise VelplanError(_missing_glyphs_message(problems, what))
    from xml.etree import ElementTree as SerialTree

    return SerialTree.tostring(root, encoding="unicode")


def _text_elements(element, inherited: dict):
    """Each ``<text>`` under `element`, with the text properties it inherits, in order."""
    props = {**inherited, **{k: element.get(k) for k in _INHERITED if element.get(k)}}
    if element.tag == _SVG_NS + "text":
        yield element, props
        return
    for child in element:
        yield from _text_elements(child, props)


def _fit_text(element, props: dict, fonts) -> tuple[str, str, list[str]] | None:
    """Give a ``<text>`` the family that covers it (and a start anchor if it has pieces);
    or return (text, characters no family has, the families tried)."""
    from velplan.render.fonts import css_families

    text = "".join(element.itertext())
    families = css_families(props.get("font-family"))
    italic = props.get("font-style") in ("italic", "oblique")
    family = fonts.choose_family(families, text, italic=italic)
    if family is None:
        tried = fonts.usable(families)
        lacking = "".join(c for c in fonts.missing(tried[0], text, italic=italic)
                          if all(fonts.missing(f, c, italic=italic) for f in tried))
        return text, lacking, tried
    element.set("font-family", family)
    if len(element) and props.get("text-anchor") in ("middle", "end"):
        _anchor_at_start(element, props, family, italic, fonts)
    return None


def _anchor_at_start(element, props: dict, family: str, italic: bool, fonts) -> None:
    """Turn a centred or right-aligned text made of pieces into a start-anchored one at
    the same place (cairosvg aligns each ``<tspan>`` by itself); leave it as it is when its
    position or sizes are not plain numbers."""
    try:
        x, size = float(element.get("x")), float(props["font-size"])
        pieces = [(element.text or "", size)]
        for child in element:
            if len(child):
                return
            pieces += [(child.text or "", float(child.get("font-size", size))),
                       (child.tail or "", size)]
    except (TypeError, ValueError, KeyError):
        return
    width = sum(fonts.advance(family, re.sub(r"\s+", " ", t), s, italic=italic)
                for t, s in pieces)
    shift = width / 2.0 if props["text-anchor"] == "middle" else width
    element.set("x", f"{x - shift:.3f}")
    element.set("text-anchor", "start")


def _missing_glyphs_message(problems: list[tuple[str, str, list[str]]], what: str) -> str:
    """One line: the first text that cannot be drawn, what it lacks, what was tried."""
    text, lacking, tried = problems[0]
    if lacking:
        what_lacks = "no installed font has " + ", ".join(
            f"{c} (U+{ord(c):04X})" for c in lacking[:5])
    else:
        what_lacks = "no installed font has all of its characters"
    more = f"; and {len(problems) - 1} more text(s)" if len(problems) > 1 else ""
    return (f"cannot draw the text {text[:40]!r} in the {what}: {what_lacks} (tried "
            f"{', '.join(tried)}){more}; install a font that has it, or change the text")
