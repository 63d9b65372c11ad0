"""A power of ten's exponent is drawn as one raised index: "¹" beside "⁻" and "⁴" is not left
as the font's own smaller glyph ("±4·10⁻¹4" was printed on the dynamics sheet's error rows)."""

import pytest

from velplan.render.shapes import TextRun, text_extent, text_runs
from velplan.views.base import power_of_ten


@pytest.mark.parametrize("x, exponent", [(4e-14, "−14"), (2e-12, "−12"), (5e-13, "−13"), (3e-21, "−21"),
                                         (7.97e-16, "−16"), (1e-5, "−5")])
def test_the_whole_exponent_is_one_raised_run(x, exponent):
    runs = text_runs(power_of_ten(x, "en", 1))
    assert runs[-1] == TextRun(exponent, "super")
    assert all(r.script == "" for r in runs[:-1])


def test_a_lone_square_or_cube_keeps_its_glyph():
    assert text_runs("kg·m²") == (TextRun("kg·m²", ""),)
    assert text_runs("(m/s²)/mm") == (TextRun("(m/s²)/mm", ""),)


def test_the_exponent_is_measured_as_drawn():
    # "10⁻¹⁴" is as wide as "10" and the raised "−14"; "¹" no longer counts as a full-size glyph
    whole = text_extent("10⁻¹⁴", 5.0)[0]
    assert whole == pytest.approx(text_extent("10^{−14}", 5.0)[0])


def test_a_raised_exponent_is_reached_and_its_table_row_keeps_it_off_the_rules():
    from velplan.render.shapes import SUPERSCRIPT_RISE, script_size, text_depth
    from velplan.views.table import grid_table

    h = 2.5
    assert text_depth("±4·10⁻¹⁴", h)[1] == pytest.approx(SUPERSCRIPT_RISE * h + script_size(h))
    items, _, total = grid_table([["a", "b"], ["c", "±4·10⁻¹⁴"]], h, width_factor=0.75)
    rule = max(p.points[0][1] for p in items if type(p).__name__ == "Polyline")  # the row's top rule
    text = next(p for p in items if getattr(p, "text", "") == "±4·10⁻¹⁴")
    from velplan.render.shapes import text_origin
    top = text_origin(text)[1] + text_depth(text.text, h)[1]
    assert top < rule - 0.05 * h  # the exponent keeps off the rule above it
