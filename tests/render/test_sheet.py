import pytest
import shapely

from velplan.errors import VelplanError
from velplan.render.canvas import RecordingCanvas, render
from velplan.render.scene import Text
from velplan.sheets.frame import (
    SHEET_FORMATS, TitleInfo, frame, frame_bounds, free_area, sheet_format, sheet_scene,
    title_block, title_block_bounds)

INFO = TitleInfo(title="Кинематический анализ кривошипно-ползунного механизма",
                 designation="ТММ.КП.01.00.000", scale="1:2", sheet=2, sheets=3,
                 author="Иванов", checker="Петров", organisation="МГТУ, гр. МТ-31",
                 date="12.05.24")


@pytest.mark.parametrize("name", sorted(SHEET_FORMATS))
def test_frame_is_20_mm_from_left_and_5_elsewhere(name):
    f = sheet_format(name)
    x0, y0, x1, y1 = frame_bounds(name)
    assert (x0, y0, f.width_mm - x1, f.height_mm - y1) == (20.0, 5.0, 5.0, 5.0)
    trim, inner = frame(name)
    assert inner.line == "thick" and trim.line == "thin"
    assert inner.bounds == (x0, y0, x1, y1)
    assert trim.bounds == (0.0, 0.0, f.width_mm, f.height_mm)


def test_format_sizes():
    assert (sheet_format("A1").width_mm, sheet_format("A1").height_mm) == (841.0, 594.0)
    assert (sheet_format("A2").width_mm, sheet_format("A2").height_mm) == (594.0, 420.0)
    assert (sheet_format("A3").width_mm, sheet_format("A3").height_mm) == (420.0, 297.0)
    with pytest.raises(VelplanError, match="unknown sheet format 'A0'; known formats: A1, A2"):
        sheet_format("A0")


@pytest.mark.parametrize("name", sorted(SHEET_FORMATS))
@pytest.mark.parametrize("style, size", [("eskd", (185.0, 55.0)), ("iso", (180.0, 36.0))])
def test_title_block_in_lower_right_corner_of_frame(name, style, size):
    fx0, fy0, fx1, fy1 = frame_bounds(name)
    bx0, by0, bx1, by1 = title_block_bounds(name, style)
    assert (bx1, by0) == (fx1, fy0)
    assert (bx1 - bx0, by1 - by0) == size
    assert bx0 >= fx0
    block = shapely.box(bx0, by0, bx1, by1).buffer(1e-6)
    for item in title_block(INFO, name, frame_style=style):
        assert block.contains(shapely.box(*item.bounds)), item


def test_eskd_block_grid_and_texts():
    items = title_block(INFO, "A1", lang="ru")
    texts = {t.text: t for t in items if isinstance(t, Text)}
    for caption in ("Изм.", "Лист", "№ докум.", "Подп.", "Дата", "Разраб.", "Пров.",
                    "Т.контр.", "Н.контр.", "Утв.", "Лит.", "Масса", "Масштаб"):
        assert caption in texts
    assert {"Лист 2", "Листов 3", "Иванов", "Петров", "1:2", "12.05.24"} <= set(texts)
    # the designation sits in the top 120 × 15 cell (A1 block origin: x 651, y 5)
    designation = texts["ТММ.КП.01.00.000"]
    assert designation.position == pytest.approx((651 + 65 + 60, 5 + 47.5))
    assert designation.size_mm == 7.0
    # the long title is wrapped inside graph 1 (70 × 25 mm), words in order
    cell = shapely.box(651 + 65, 5 + 15, 651 + 135, 5 + 40)
    lines = [t for t in items if isinstance(t, Text)
             and cell.contains(shapely.box(*t.bounds))]
    assert len(lines) >= 2
    assert " ".join(t.text for t in lines) == INFO.title
    assert lines[0].position[1] > lines[1].position[1]


def test_ukrainian_and_iso_captions():
    uk = {t.text for t in title_block(INFO, "A3", lang="uk") if isinstance(t, Text)}
    assert {"Змн.", "Розроб.", "Аркушів 3"} <= uk
    iso = {t.text for t in title_block(INFO, "A3", frame_style="iso", lang="en")
           if isinstance(t, Text)}
    assert {"Designed", "Checked", "Drawing No.", "Scale", "2 / 3"} <= iso


def test_free_area_is_frame_minus_title_block():
    area = free_area("A3")
    assert area.area == pytest.approx(395 * 287 - 185 * 55)
    assert not area.contains(shapely.Point(300, 30))
    assert area.contains(shapely.Point(100, 30))
    inset = free_area("A3", margin_mm=10.0)
    assert inset.bounds == pytest.approx((30.0, 15.0, 405.0, 282.0))


def test_sheet_scene_renders_frame_then_title():
    scene = sheet_scene(INFO, "A2", frame_style="iso", lang="en")
    assert (scene.width_mm, scene.height_mm) == (594.0, 420.0)
    assert scene.layers == ("frame", "title")
    canvas = RecordingCanvas()
    render(scene, canvas)
    assert canvas.primitives == scene.primitives


def test_errors():
    with pytest.raises(VelplanError, match="1 <= sheet <= sheets"):
        TitleInfo(sheet=3, sheets=2)
    with pytest.raises(VelplanError, match="unknown frame style 'gb'; known styles: eskd, iso"):
        title_block_bounds("A1", "gb")
    with pytest.raises(VelplanError, match="known languages"):
        title_block(INFO, lang="fr")
