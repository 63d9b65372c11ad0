"""A PNG of a cairo image surface in as few bytes per pixel as its colours need.

cairo writes every PNG as 8-bit RGBA, four bytes a pixel, and compresses them all. A drawing
in black, greys and white on a white ground needs one byte a pixel (grey) or two (grey and
alpha): the same pixels, written and compressed in a quarter or half of the work. A surface
with any colour is written by cairo as before.
"""

from __future__ import annotations

import io
import struct
import zlib

import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
COMPRESSION = 6
"""zlib level of the image data (libpng's default)."""


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def grey_png(argb: np.ndarray) -> bytes | None:
    """The PNG of a premultiplied ARGB32 image (h, w, 4 bytes, cairo's B, G, R, A order on a
    little-endian machine) with no colour: 8-bit grey where every pixel is opaque, else grey and
    alpha with the grey unpremultiplied as cairo does; None where a pixel has a colour."""
    b, g, r, a = (argb[..., k] for k in range(4))
    if not (np.array_equal(b, g) and np.array_equal(g, r)):
        return None
    h, w = g.shape
    if (a == 255).all():
        kind, pixels = 0, g
    else:
        # only the pixels not opaque change (a drawing's last row and column, partly covered)
        part = a != 255
        grey, alpha = g[part].astype(np.uint32), a[part].astype(np.uint32)
        un = g.copy()
        un[part] = np.where(alpha > 0, (grey * 255 + alpha // 2) // np.maximum(alpha, 1), 0)
        kind, pixels = 4, np.stack([un, a], axis=-1).reshape(h, 2 * w)
    rows = np.zeros((h, pixels.shape[1] + 1), np.uint8)  # filter type 0 (none) on every row
    rows[:, 1:] = pixels
    header = struct.pack(">IIBBBBB", w, h, 8, kind, 0, 0, 0)
    return (PNG_SIGNATURE + _chunk(b"IHDR", header)
            + _chunk(b"IDAT", zlib.compress(rows.tobytes(), COMPRESSION)) + _chunk(b"IEND", b""))


def surface_png(surface) -> bytes:
    """The PNG of a cairo ARGB32 image surface: `grey_png` where it has no colour, else
    cairo's own."""
    surface.flush()
    w, h, stride = surface.get_width(), surface.get_height(), surface.get_stride()
    if w and h and struct.pack("=I", 1)[0] == 1:  # cairo's ARGB32 is B, G, R, A bytes here
        data = np.frombuffer(surface.get_data(), np.uint8).reshape(h, stride)[:, :4 * w]
        png = grey_png(data.reshape(h, w, 4))
        if png is not None:
            return png
    out = io.BytesIO()
    surface.write_to_png(out)
    return out.getvalue()
