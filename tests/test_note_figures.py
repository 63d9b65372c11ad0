"""Figures of the note drawn for the page: a drawing shrunk to the text width goes to the next
ESKD scale and says so, and its lettering prints at 2.5 mm at least."""

from __future__ import annotations

import pytest

pytest.importorskip("typst")

from velplan.note.figures import LETTER_MM, TEXT_WIDTH_MM, for_page, views_png  # noqa: E402
from velplan.render.scene import Polyline, Text  # noqa: E402
from velplan.views.base import View  # noqa: E402


def _scheme(width: float, mu: float, label: str) -> View:
    return View("mechanism", (Polyline(((0.0, 0.0), (width, 100.0)), "thick"),
                              Text((5.0, 95.0), label, "text", 3.5)), width, 100.0, mu)


def test_a_shrunk_scheme_prints_at_the_next_eskd_scale():
    view = _scheme(300.0, 0.0025, "μl = 0,0025 м/мм (M 1:2,5)")
    _, printed = views_png([view], None)
    assert printed == pytest.approx(150.0)  # 300 mm at 1:2.5 is 150 mm at 1:5, under 170 mm
    text = for_page(view.primitives[1], view.mu, printed / 300.0)
    assert text.text == "μl = 0,005 м/мм (M 1:5)"
    assert text.size_mm * printed / 300.0 == pytest.approx(LETTER_MM)


def test_a_figure_that_fits_keeps_its_scale_and_lettering():
    view = _scheme(120.0, 0.0025, "μl = 0,0025 м/мм (M 1:2,5)")
    _, printed = views_png([view], None)
    assert printed == pytest.approx(120.0)
    assert for_page(view.primitives[1], view.mu, 1.0) is view.primitives[1]


def test_a_drawing_without_a_length_scale_only_fits_the_width():
    view = View("diagram", (Polyline(((0.0, 0.0), (400.0, 50.0)), "thin"), Text((1.0, 1.0), "M, Н·м", "text", 2.5)),
                400.0, 50.0, None)
    _, printed = views_png([view], None)
    assert printed == pytest.approx(TEXT_WIDTH_MM)
    shrink = printed / 400.0
    assert for_page(view.primitives[1], None, shrink).size_mm == pytest.approx(LETTER_MM / shrink)


def test_two_views_stack_rather_than_shrink():
    """A group and its polygon too wide side by side go one above the other at full size."""
    crank = _scheme(150.0, 0.005, "μl = 0,005 м/мм (M 1:5)")
    polygon = View("polygon", (Polyline(((0.0, 0.0), (80.0, 40.0)), "thin"),
                               Text((1.0, 1.0), "μF = 20 Н/мм", "text", 3.5)), 80.0, 40.0, 20.0)
    _, printed = views_png([crank, polygon], None)
    assert printed == pytest.approx(150.0)


def test_two_views_shrink_to_the_scale_of_the_one_drawn_to_scale():
    """Two 200 mm views: stacked, 200 mm wide, they go from 1:5 to the next ESKD scale, 1:10
    (side by side they would need 1:15); the polygon's μF doubles with them."""
    group = _scheme(200.0, 0.005, "μl = 0,005 м/мм (M 1:5)")
    polygon = View("polygon", (Polyline(((0.0, 0.0), (200.0, 40.0)), "thin"),
                               Text((1.0, 1.0), "μF = 20 Н/мм", "text", 3.5)), 200.0, 40.0, 20.0)
    _, printed = views_png([group, polygon], None)
    assert printed == pytest.approx(100.0)
    assert for_page(group.primitives[1], group.mu, 0.5).text == "μl = 0,01 м/мм (M 1:10)"
    assert for_page(polygon.primitives[1], polygon.mu, 0.5).text == "μF = 40 Н/мм"
