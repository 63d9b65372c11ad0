"""The note's helper process rasterises a figure whose resolution is a numpy number (a shrink
fitted to a standard scale from a view's μ): the request line carries a plain decimal, so the
helper makes it rather than answering "failed" and leaving it to the note's own process."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("cairosvg")

from velplan.note import raster  # noqa: E402
from velplan.render.export import svg_to_png  # noqa: E402

SVG = ('<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm" viewBox="0 0 20 10">'
       '<line x1="0" y1="0" x2="20" y2="10" stroke="black" stroke-width="0.5"/></svg>')


@pytest.mark.parametrize("fork", [True, False] if raster.FORK else [False])
def test_a_numpy_resolution_is_made_aside(fork):
    dpi = np.float64(150.0) * np.float64(0.8620689655172413)  # a shrink to a standard scale
    aside = raster.Aside(fork=fork)
    try:
        assert aside.helper is not None
        aside.submit(SVG, dpi)
        png = aside.png(SVG, dpi)
        assert aside.answers == {0: True}  # made by the helper, not left to this process
    finally:
        aside.close()
    assert png == svg_to_png(SVG, dpi=float(dpi), grey=True)
