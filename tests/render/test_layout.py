import pytest
import shapely

from velplan.errors import ScaleError
from velplan.render.layout import (
    fit_text, label_box, overlapping_labels, place_views)
from velplan.render.scene import Circle, Scene, Text
from velplan.render.shapes import text_extent
from velplan.sheets.frame import free_area


def test_overlap_found_for_overlapping_pair_only():
    a = Text((100, 100), "VA", "labels", 5.0)       # box x 100…108.56
    b = Text((105, 102), "VB", "labels", 5.0)       # overlaps a
    c = Text((200, 100), "VC", "labels", 5.0)       # far away
    d = Text((100 + text_extent("VA", 5.0)[0], 100), "VD", "labels", 5.0)  # touches a, overlaps b
    scene = Scene((a, Circle((0, 0), 1, "mechanism"), b, c, d))
    assert overlapping_labels(scene) == [(a, b), (b, d)]


def test_separated_labels_do_not_overlap():
    scene = Scene((Text((10, 10), "a", "labels"), Text((30, 10), "b", "labels"),
                   Text((10, 30), "c", "plan-v-1")))
    assert overlapping_labels(scene) == []


def test_overlap_layer_filter():
    a, b = Text((0, 0), "AAA", "labels"), Text((1, 0), "BBB", "title")
    assert overlapping_labels(Scene((a, b)), layers=["labels"]) == []
    assert overlapping_labels(Scene((a, b))) == [(a, b)]


def test_views_fill_the_l_shaped_area_without_overlap():
    area = free_area("A3", margin_mm=5.0)   # x 25…410, y 10…287, title block cut out
    boxes = place_views([(150, 120), (150, 120), (150, 100), (200, 60)], area, gap_mm=10)
    assert boxes[0] == (25.0, 167.0, 175.0, 287.0)
    assert boxes[1] == (185.0, 167.0, 335.0, 287.0)
    for i, a in enumerate(boxes):
        assert area.buffer(1e-6).contains(shapely.box(*a))
        for b in boxes[i + 1:]:
            assert shapely.box(*a).distance(shapely.box(*b)) >= 10 - 1e-9


def test_view_too_large_raises_scale_error():
    with pytest.raises(ScaleError, match=r"view 2 \(500.0 × 100.0 mm\) does not fit"):
        place_views([(10, 10), (500, 100)], free_area("A3"))


def test_fit_text_keeps_size_when_it_fits():
    lines = fit_text("1:2", (0, 0, 18, 15), layer="title", size_mm=5.0)
    assert len(lines) == 1
    assert lines[0].size_mm == 5.0 and lines[0].position == (9.0, 7.5)
    assert lines[0].anchor == "middle" and lines[0].baseline == "middle"


def test_fit_text_narrows_below_the_least_height_then_wraps():
    # 8 characters: 14 mm wide at 2.5 mm, too wide for 12 - 2 mm (less the 15 % margin: 8.7 mm):
    # kept 2.5 mm high (the ESKD least), its letters narrowed to 8.7 / 14 = 0.62, floored
    date = fit_text("12.05.24", (0, 0, 12, 5), layer="title", size_mm=2.5)
    assert [(t.size_mm, t.width_factor) for t in date] == [(2.5, 0.62)]
    assert label_box(date[0]).bounds[2] - label_box(date[0]).bounds[0] <= 10.0 / 1.15
    # never narrower than type A lettering, even where the cell is too small
    assert fit_text("12.05.2024 12:00", (0, 0, 12, 5), layer="title", size_mm=2.5)[0].width_factor == 0.6
    title = "Kinematic analysis of a crank slider mechanism"
    lines = fit_text(title, (0, 0, 70, 25), layer="title", size_mm=5.0)
    assert len(lines) > 1
    assert " ".join(t.text for t in lines) == title
    for t in lines:
        assert shapely.box(0, 0, 70, 25).contains(label_box(t))


def test_fit_text_empty():
    assert fit_text("  ", (0, 0, 10, 5), layer="title") == ()


def test_fit_text_never_starts_a_line_with_the_unit_of_the_number_before_it():
    sentence = "Шаг 5/11. Пересечение прямых даёт точку a4: aa4 = 20,8 мм; pa4 = 63,9 мм (синус угла между ними 1)."
    for width in range(60, 300, 7):
        lines = [t.text for t in fit_text(sentence, (0, 0, width, 40), layer="labels", size_mm=5.0)]
        assert " ".join(lines) == sentence
        assert not any(line.startswith(("мм", "(мм")) for line in lines), (width, lines)
        assert not any(line.endswith(("20,8", "63,9")) for line in lines), (width, lines)
