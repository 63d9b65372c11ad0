"""The sheet-quality checks made in every language (`tests/sheet/quality.py`), in Russian:
every A1 sheet legible, the class III sheets on A3 too, every sheet through the PNG export.
One file per language so that the test workers share the sheets out. The mechanisms whose
gallery language is Russian are checked on the gallery's sheets (`quality.check_gallery_sheets`;
the gallery's ratchet on crossed texts, bound 0, holds their A1 sheets to more than
`test_texts_keep_off_the_drawn_lines` here)."""

import pytest
import shapely

from tests.sheet.quality import (TRIADS, built, check_a1_sheets, check_class_iii_on_a3, check_png,  # noqa: F401
                                 sheets_in, studies, triads_in)
from velplan.render.layout import label_box
from velplan.render.scene import Text

LANG = "ru"


def test_no_text_over_text_and_all_inside_the_frame(studies, built):
    check_a1_sheets(studies, built, LANG)


@pytest.mark.parametrize("name", triads_in(LANG))
def test_class_iii_sheets_on_a3_are_legible(built, name):
    check_class_iii_on_a3(built, name, LANG)


def test_every_sheet_renders_to_png_with_every_glyph(studies, built, tmp_path):
    check_png(studies, built, LANG, tmp_path)


def test_texts_keep_off_the_drawn_lines(studies, built):
    """Estimated text boxes crossed by a thick line or a vector over more than 1 mm: at most
    one per sheet (a position number where a curve crosses the φ axis at that very tick, a
    letter squeezed between vectors; before the numbers moved off the curves, 4 to 8); at
    most three on a class III sheet, whose plans fan the images of six or seven links out of
    one pole (a letter inside the fan has no free side)."""
    from velplan.render.scene import Arrow, Polyline

    for name, kind, sheet in sheets_in(studies, "ru", built):
        lines = [shapely.LineString(p.points) for p in sheet.scene.primitives
                 if isinstance(p, Polyline) and p.line == "thick"]
        lines += [shapely.LineString([p.start, p.end]) for p in sheet.scene.primitives
                  if isinstance(p, Arrow) and p.length > 0]
        tree = shapely.STRtree(lines)
        crossed = []
        for t in sheet.scene.of_kind(Text):
            box = label_box(t)
            if any(lines[j].intersection(box).length > 1.0 for j in tree.query(box, predicate="intersects")):
                crossed.append(t.text)
        assert len(crossed) <= (4 if name in TRIADS else 1), (name, kind, crossed)
