"""The sheet-quality checks made in every language (`tests/sheet/quality.py`), in English:
every A1 sheet legible, the class III sheets on A3 too, every sheet through the PNG export.
One file per language so that the test workers share the sheets out. Here too the checks of
the English kinematic sheets on A1 and A3 (moved from `test_sheet_quality.py`: the A1 sheets
and the triads' A3 sheets are this module's own). The mechanisms whose gallery language is
English are checked on the gallery's sheets (`quality.check_gallery_sheets`)."""

import pytest

import velplan
from tests.sheet.quality import (TRIADS, assert_legible, assert_zones_filled, built, check_a1_sheets,  # noqa: F401
                                 check_class_iii_on_a3, check_png, in_gallery, studies, triads_in)

LANG = "en"


def test_no_text_over_text_and_all_inside_the_frame(studies, built):
    check_a1_sheets(studies, built, LANG)


@pytest.mark.parametrize("name", triads_in(LANG))
def test_class_iii_sheets_on_a3_are_legible(built, name):
    check_class_iii_on_a3(built, name, LANG)


def test_every_sheet_renders_to_png_with_every_glyph(studies, built, tmp_path):
    check_png(studies, built, LANG, tmp_path)


def test_bundled_kinematic_sheets_on_a3_are_legible(studies, built):
    """The bundled examples' kinematic sheets on A3 (the catalogue's: `test_catalogue_gallery`)
    hold the bars of A1: no text over text, all inside the frame, every glyph in the font."""
    for name in velplan.example_names():
        if not in_gallery(name, LANG):
            assert_legible(built(name, "kinematic", "en", "A3"), "A3", name, "kinematic")


@pytest.mark.parametrize("fmt", ["A1", "A3"])
def test_schemes_and_plans_fill_at_least_half_their_zones(studies, built, fmt):
    """Each plan spans at least half its grid cell, and the scheme half of its share of the top
    band, along one of the two directions (a standard scale one step larger would not fit)."""
    for name in velplan.example_names() + list(TRIADS):
        if not in_gallery(name, LANG):
            assert_zones_filled(built(name, "kinematic", "en", fmt), name, fmt)
