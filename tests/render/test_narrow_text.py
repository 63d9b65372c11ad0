"""Narrowed lettering (issue 32: printed text ≥ 2.5 mm high on A1/A3): a text that must fit a
fixed cell keeps its height and is narrowed (`Text.width_factor`), and every writer prints it
narrowed about its anchor: the PNG's ink measured against the same text at full width."""

import io

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.errors import VelplanError
from velplan.render.layout import fit_text, label_box
from velplan.render.scene import Scene, Text
from velplan.render.shapes import MIN_WIDTH_FACTOR, text_extent
from velplan.render.svg import to_svg
from velplan.views.table import grid_table


def test_width_factor_is_checked():
    for bad in (0.5, 1.2, float("nan")):
        with pytest.raises(VelplanError, match="width_factor"):
            Text((0, 0), "Изм.", "title", 2.5, width_factor=bad)


@pytest.mark.parametrize("anchor, rotation", [("start", 0.0), ("middle", 0.0), ("end", 0.0), ("middle", 30.0)])
def test_box_is_narrowed_about_the_anchor(anchor, rotation):
    full = Text((50, 20), "Т.контр. R₃₄", "title", 2.5, anchor, "middle", rotation)
    narrow = Text((50, 20), "Т.контр. R₃₄", "title", 2.5, anchor, "middle", rotation, 0.6)
    a, b = label_box(full), label_box(narrow)
    assert b.area == pytest.approx(0.6 * a.area)
    # the anchor stays put: the same share of the box on each side of it
    share = {"start": 0.0, "middle": 0.5, "end": 1.0}[anchor]
    corners = np.asarray(b.exterior.coords)[:4]
    along = np.array([np.cos(np.radians(rotation)), np.sin(np.radians(rotation))])
    x = (corners - np.array([50.0, 20.0])) @ along
    width = 0.6 * text_extent("Т.контр. R₃₄", 2.5)[0]
    assert x.min() == pytest.approx(-share * width) and x.max() == pytest.approx((1 - share) * width)
    if rotation == 0:  # the plain-arithmetic box of an upright text agrees
        assert narrow.bounds == pytest.approx(b.bounds)


def _ink_columns(text: Text) -> tuple[float, float, float]:
    """(left, right, height) of the ink of `text` alone on a 200 × 20 mm PNG, mm."""
    from PIL import Image

    from velplan.render.export import svg_to_png

    png = svg_to_png(to_svg(Scene((text,), 200, 20)), dpi=254)  # 10 px per mm
    ink = np.asarray(Image.open(io.BytesIO(png)).convert("L")) < 128
    cols, rows = np.flatnonzero(ink.any(axis=0)), np.flatnonzero(ink.any(axis=1))
    return cols[0] / 10.0, (cols[-1] + 1) / 10.0, (rows[-1] + 1 - rows[0]) / 10.0


@pytest.mark.parametrize("anchor", ["start", "middle", "end"])
def test_png_prints_narrowed_letters_at_full_height(anchor):
    pytest.importorskip("cairosvg")
    words = "Изм. № докум. ω₁"
    l1, r1, h1 = _ink_columns(Text((100, 8), words, "title", 5.0, anchor))
    l2, r2, h2 = _ink_columns(Text((100, 8), words, "title", 5.0, anchor, width_factor=0.6))
    assert (r2 - l2) == pytest.approx(0.6 * (r1 - l1), abs=0.3)
    assert h2 == pytest.approx(h1, abs=0.1)  # the height is kept
    # narrowed about the anchor: the point at 0, ½ or 1 of the ink stays at x = 100
    share = {"start": 0.0, "middle": 0.5, "end": 1.0}[anchor]
    assert l2 + share * (r2 - l2) == pytest.approx(l1 + share * (r1 - l1), abs=0.3)


def test_dxf_writes_the_width_factor():
    ezdxf = pytest.importorskip("ezdxf")
    from velplan.render.dxf import to_dxf

    dxf = to_dxf(Scene((Text((5, 5), "Изм.", "title", 2.5, width_factor=0.65),
                        Text((5, 15), "Лист", "title", 2.5)), 50, 20))
    texts = ezdxf.read(io.StringIO(dxf)).modelspace().query("TEXT")
    assert sorted((t.dxf.text, round(t.dxf.width, 6)) for t in texts) == [("Изм.", 0.65), ("Лист", 1.0)]
    assert all(t.dxf.height == 2.5 for t in texts)


@settings(max_examples=60, deadline=None)
@given(words=st.lists(st.sampled_from(["Изм.", "Т.контр.", "Designed", "速度", "12.05.24", "ω₁", "Н·м"]),
                      min_size=1, max_size=5),
       width=st.floats(4.0, 80.0), height=st.floats(4.0, 30.0), size=st.sampled_from([2.5, 3.5, 5.0, 7.0]))
def test_fit_text_never_prints_below_the_least_height(words, width, height, size):
    lines = fit_text(" ".join(words), (0.0, 0.0, width, height), layer="title", size_mm=size, padding_mm=0.7)
    assert lines and all(t.size_mm >= 2.5 and MIN_WIDTH_FACTOR <= t.width_factor <= 1.0 for t in lines)
    assert len({(t.size_mm, t.width_factor) for t in lines}) == 1
    if lines[0].width_factor > MIN_WIDTH_FACTOR:  # narrowed as far as needed, not further: it fits
        for t in lines:
            x0, _, x1, _ = t.bounds
            assert x0 >= 0.7 - 1e-6 and x1 <= width - 0.7 + 1e-6


def test_narrowed_table_is_narrower_and_lower_at_the_same_height():
    grid = [["Положение", "1", "2"], ["VA/ω1", "0,161", "−0,228"], ["ω3/ω1", "0,000", "0,176"]]
    items, w1, h1 = grid_table(grid, 2.5)
    narrow, w2, h2 = grid_table(grid, 2.5, width_factor=0.7)
    texts = [t for t in narrow if isinstance(t, Text)]
    assert all(t.size_mm == 2.5 and t.width_factor == 0.7 for t in texts)
    pads = 2 * 1.0 * 3  # the cells' padding is not narrowed
    assert w2 - pads == pytest.approx(0.7 * (w1 - pads))
    assert h2 < h1
    # every text inside its row: clear of the rules above and below it
    rules = sorted({round(p.points[0][1], 6) for p in narrow if hasattr(p, "points") and len(p.points) == 2
                    and p.points[0][1] == p.points[1][1]} | {0.0, h2})
    for t in texts:
        _, y0, _, y1 = t.bounds
        assert any(lo < y0 and y1 < hi for lo, hi in zip(rules, rules[1:]))
