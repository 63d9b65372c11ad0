"""The sheet-quality checks made in every language (`tests/sheet/quality.py`), in Chinese:
every A1 sheet legible, the class III sheets on A3 too, every sheet through the PNG export.
One file per language so that the test workers share the sheets out. The mechanisms whose
gallery language is Chinese are checked on the gallery's sheets (`quality.check_gallery_sheets`)."""

import pytest

from tests.sheet.quality import (built, check_a1_sheets, check_class_iii_on_a3, check_png, studies,  # noqa: F401
                                 triads_in)

LANG = "zh"


def test_no_text_over_text_and_all_inside_the_frame(studies, built):
    check_a1_sheets(studies, built, LANG)


@pytest.mark.parametrize("name", triads_in(LANG))
def test_class_iii_sheets_on_a3_are_legible(built, name):
    check_class_iii_on_a3(built, name, LANG)


def test_every_sheet_renders_to_png_with_every_glyph(studies, built, tmp_path):
    check_png(studies, built, LANG, tmp_path)
