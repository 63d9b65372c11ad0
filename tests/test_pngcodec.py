"""The grey PNG writer: the same pixels as cairo's own PNG, in fewer bytes."""

import io

import numpy as np
import pytest

cairocffi = pytest.importorskip("cairocffi")

from velplan.render.pngcodec import surface_png  # noqa: E402


def _pixels(png: bytes):
    s = cairocffi.ImageSurface.create_from_png(io.BytesIO(png))
    return s.get_width(), s.get_height(), bytes(s.get_data())


def _cairo_png(surface) -> bytes:
    out = io.BytesIO()
    surface.write_to_png(out)
    return out.getvalue()


def _drawing(colour, background):
    s = cairocffi.ImageSurface(cairocffi.FORMAT_ARGB32, 53, 31)
    c = cairocffi.Context(s)
    if background:
        c.set_source_rgb(1, 1, 1)
        c.paint()
    c.set_source_rgba(*colour)
    c.set_line_width(1.3)
    c.move_to(2.2, 3.7)
    c.line_to(50.1, 27.4)
    c.arc(20.5, 15.2, 9.7, 0, 5)
    c.stroke()
    return s


@pytest.mark.parametrize("colour, background, kind", [
    ((0, 0, 0, 1), True, 0),        # black on white: 8-bit grey
    ((0.3, 0.3, 0.3, 0.6), False, 4),  # translucent grey on nothing: grey and alpha
    ((0.8, 0.1, 0.1, 1), True, None),  # a colour: cairo's own PNG
])
def test_same_pixels_as_cairo(colour, background, kind):
    s = _drawing(colour, background)
    mine, theirs = surface_png(s), _cairo_png(s)
    if kind is None:
        assert mine == theirs
        return
    assert mine[25] == kind  # IHDR colour type
    assert _pixels(mine) == _pixels(theirs)
    assert len(mine) < len(theirs)


def test_antialiased_edges_unpremultiplied_as_cairo():
    s = _drawing((0.5, 0.5, 0.5, 0.37), False)
    data = np.frombuffer(s.get_data(), np.uint8)
    assert len(set(data[3::4].tolist())) > 3  # partial alphas are there to unpremultiply
    assert _pixels(surface_png(s)) == _pixels(_cairo_png(s))
