"""Writing sheets to disk: SVG and DXF as they are, PNG and PDF through cairosvg (optional).

Every write is atomic: the bytes go to a temporary file in the target's directory, which
then replaces the target with :func:`os.replace`. A failed conversion or write leaves the
directory as it was — no half-written file, an existing file untouched.
"""

from __future__ import annotations

import importlib
import os
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


def _cairosvg():
    try:
        return importlib.import_module("cairosvg")
    except (ImportError, OSError) as exc:  # OSError: cairosvg present, libcairo missing
        raise VelplanError(f"PNG/PDF export needs cairosvg and the cairo library "
                           f"({type(exc).__name__}: {exc}); install it with "
                           f"`{_INSTALL_HINT}`") from exc


def _convert(function: str, svg_text: str, **options) -> bytes:
    converter = getattr(_cairosvg(), function)
    try:
        return converter(bytestring=svg_text.encode("utf-8"), **options)
    except Exception as exc:
        first_line = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise VelplanError(f"cairosvg could not convert the sheet ({function}): "
                           f"{first_line}") from exc
