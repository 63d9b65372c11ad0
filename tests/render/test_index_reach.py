"""A label's estimated box reaches as low as its drawn letters: a subscript with a descender
("A_{д}", "M_{Fg}") dropped below the baseline goes below the main text's descender line, and
the box the layout places by must hold it, or the name is placed touching its curve (the
dynamics sheets' A_д, A_р and M_Fg sat on their curves)."""

import numpy as np
import pytest

from velplan.render import fonts
from velplan.render.layout import label_box
from velplan.render.scene import Scene, Text
from velplan.render.shapes import DESCENDER_DEPTH, SUBSCRIPT_DROP, script_size, text_box, text_depth
from velplan.render.style import SheetStyle
from velplan.render.svg import to_svg
from velplan.views.table import grid_table


@pytest.fixture(scope="module")
def cairo_ready():
    pytest.importorskip("cairocffi")
    pytest.importorskip("cairosvg")
    assert fonts.register_with_fontconfig()


def _ink_rows(text: str, lang: str, size: float, tmp_path) -> tuple[float, float]:
    """(lowest, highest) ink of `text` drawn on its baseline y = 10 mm, mm up from the page's
    foot (10 px per mm)."""
    from PIL import Image

    from velplan.render.export import write_png

    scene = Scene((Text((10.0, 10.0), text, "labels", size, "start", "baseline"),), 60, 20)
    png = write_png(to_svg(scene, SheetStyle(language=lang)), tmp_path / "t.png", dpi=254)
    rows = np.nonzero((np.asarray(Image.open(png).convert("L")) < 128).any(axis=1))[0]
    return 20.0 - (rows.max() + 1) / 10.0, 20.0 - rows.min() / 10.0


@pytest.mark.parametrize("text, lang", [("A_{д}", "ru"), ("M_{Fg}", "en"), ("M_{р} = 20,65", "uk"), ("Fg₃", "zh")])
def test_a_subscript_descender_is_inside_the_box(text, lang, cairo_ready, tmp_path):
    size = 2.5
    low, high = _ink_rows(text, lang, size, tmp_path)
    x0, y0, x1, y1 = label_box(Text((10.0, 10.0), text, "labels", size, "start", "baseline")).bounds
    assert low >= y0 - 0.15, (low, y0)  # the drawn descender within the box (a pixel and a half)
    assert low < 10.0 - DESCENDER_DEPTH * size  # and below the plain text's descender line
    assert high <= y1 + 0.15


def test_reach_of_indices():
    h = 2.5
    assert text_depth("G₅", h) == (DESCENDER_DEPTH * h, h)  # digits stand on the index's baseline
    assert text_depth("A_{д}", h) == pytest.approx((SUBSCRIPT_DROP * h + DESCENDER_DEPTH * script_size(h), h))
    assert text_depth("Agy", h) == (DESCENDER_DEPTH * h, h)
    t = Text((3.0, 4.0), "M_{Fg}", "labels", h, "middle", "middle", 30.0)
    upright = Text((3.0, 4.0), "M_{Fg}", "labels", h, "middle", "middle")
    assert np.allclose(np.ptp(text_box(upright)[:, 1]), sum(text_depth("M_{Fg}", h)))
    assert np.allclose(upright.bounds, label_box(upright).bounds)
    assert np.allclose(t.bounds, label_box(t).bounds)


@pytest.mark.parametrize("factor", [1.0, 0.75])
def test_a_table_row_holds_its_index_between_its_rules(factor):
    """"Движущий момент M_{д}": the д under the row's rule; each text's box stays inside its row."""
    grid = [["Величина", "Значение"], ["Движущий момент M_{д}", "58,3"], ["ω_{max}", "1"]]
    items, w, h = grid_table(grid, 2.5, width_factor=factor)
    rules = sorted({p.points[0][1] for p in items if hasattr(p, "points") and len(p.points) == 2
                    and p.points[0][1] == p.points[1][1]} | {0.0, h})
    for t in (p for p in items if isinstance(p, Text)):
        _, y0, _, y1 = label_box(t).bounds
        below = max(r for r in rules if r <= y0 + 1e-9)
        above = min(r for r in rules if r >= y1 - 1e-9)
        assert below < y0 and y1 < above, t.text
