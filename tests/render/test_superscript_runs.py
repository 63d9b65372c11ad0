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
