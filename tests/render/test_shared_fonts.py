"""`velplan.render.export.shared_fonts`: a batch of conversions measures its texts with one
`CairoFonts`, and draws the same pixels as conversions made one by one."""

from __future__ import annotations

import pytest

pytest.importorskip("cairosvg")

from velplan.render import export  # noqa: E402
from velplan.render.scene import Polyline, Scene, Text  # noqa: E402
from velplan.render.style import SheetStyle  # noqa: E402
from velplan.render.svg import to_svg  # noqa: E402


def _drawing(text: str) -> str:
    scene = Scene((Polyline(((2.0, 2.0), (38.0, 14.0)), "main", "thick"),
                   Text((20.0, 10.0), text, "text", 3.5, anchor="middle")), 40.0, 16.0)
    return to_svg(scene, SheetStyle())


def test_one_cairo_fonts_within_a_batch_and_a_new_one_outside():
    export._cairosvg()
    assert export._fonts() is not export._fonts()
    with export.shared_fonts():
        first = export._fonts()
        assert export._fonts() is first
        with export.shared_fonts():  # nested: the outer batch's
            assert export._fonts() is first
        assert export._fonts() is first
    assert export._BATCH is None
    assert export._fonts() is not first


def test_a_batch_draws_the_same_pixels_as_conversions_one_by_one():
    svgs = [_drawing("ω₁ = 8,38 рад/с"), _drawing("V_B = 0,42 m/s"), _drawing("μl = 0,002 m/mm")]
    alone = [export.svg_to_png(s, dpi=120.0, grey=True) for s in svgs]
    with export.shared_fonts():
        together = [export.svg_to_png(s, dpi=120.0, grey=True) for s in svgs]
    assert together == alone
    assert len(set(alone)) == 3  # three different pictures, not one repeated


def test_the_batch_ends_when_a_conversion_fails():
    with pytest.raises(export.VelplanError):
        with export.shared_fonts():
            export.svg_to_png("<svg", dpi=100.0)
    assert export._BATCH is None
