import re
import xml.etree.ElementTree as ET

import pytest

from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.sheets.frame import TitleInfo, sheet_scene
from velplan.render.style import SheetStyle
from velplan.render.svg import to_svg

SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def _scene():
    sheet = sheet_scene(TitleInfo(title="План скоростей", designation="ТММ.01",
                                  date="01.02.24"), "A3")
    return sheet.extend(
        Polyline([(40, 200), (210, 200)], "construction", "axis"),
        Polyline([(60, 200), (80.123456, 225)], "mechanism", "thick"),
        Polygon([(40, 80), (90, 80), (90, 110)], "diagram", "thick", "hatch"),
        Circle((80.123456, 225), 1.5, "mechanism", fill="white"),
        Arrow((300, 200), (340, 200), "plan-v-1", "thick"),
        Text((300, 190), "p", "labels", rotation_deg=30),
    )


def test_same_scene_gives_identical_bytes():
    first = to_svg(_scene()).encode("utf-8")
    second = to_svg(_scene()).encode("utf-8")
    assert first == second


def test_svg_parses_and_is_sized_in_mm():
    root = ET.fromstring(to_svg(_scene()).encode("utf-8"))
    assert root.tag == f"{SVG}svg"
    assert root.get("width") == "420mm" and root.get("height") == "297mm"
    assert root.get("viewBox") == "0 0 420 297"


def test_layers_are_groups_with_stable_ids():
    root = ET.fromstring(to_svg(_scene()).encode("utf-8"))
    groups = root.findall(f"{SVG}g")
    ids = [g.get("id") for g in groups]
    assert ids == ["layer-frame", "layer-title", "layer-construction", "layer-mechanism",
                   "layer-diagram", "layer-mechanism-2", "layer-plan-v-1", "layer-labels"]
    assert all(g.get(f"{INKSCAPE}groupmode") == "layer" for g in groups)
    assert groups[6].get("class") == "layer plan-v-1"


def test_y_is_flipped_and_precision_fixed():
    svg = to_svg(Scene((Polyline([(60, 200), (80.123456, 225)], "mechanism"),), 420, 297))
    assert 'points="60,97 80.123,72"' in svg
    assert not re.search(r"\d\.\d{4,}", svg)


def test_axis_is_dash_dot_and_hatch_is_lines_not_pattern():
    svg = to_svg(_scene())
    assert 'stroke-dasharray="12,3,1,3"' in svg
    assert "<pattern" not in svg and "marker" not in svg
    root = ET.fromstring(svg.encode("utf-8"))
    diagram = root.find(f"{SVG}g[@id='layer-diagram']")
    hatch, outline = list(diagram)
    assert hatch.tag == f"{SVG}path" and hatch.get("d").count("M") >= 5
    assert hatch.get("stroke-width") == "0.35"
    assert outline.tag == f"{SVG}polygon" and outline.get("stroke-width") == "0.7"


def test_arrowhead_is_a_filled_polygon_with_tip_at_end():
    root = ET.fromstring(to_svg(_scene()).encode("utf-8"))
    line, head = list(root.find(f"{SVG}g[@id='layer-plan-v-1']"))
    assert line.tag == f"{SVG}line" and head.tag == f"{SVG}polygon"
    assert head.get("fill") == "black" and head.get("stroke") == "none"
    assert head.get("points").split()[0] == "340,97"
    # thick shaft: head 1.75 × 5.25 mm, shaft stops at its base
    assert line.get("x2") == "334.75"


def test_text_font_rotation_and_language():
    root = ET.fromstring(to_svg(_scene(), SheetStyle(language="zh")).encode("utf-8"))
    text = root.find(f"{SVG}g[@id='layer-labels']/{SVG}text")
    assert text.text == "p"
    assert text.get("transform") == "rotate(-30 300 107)"
    assert text.get("font-family").startswith("'Noto Sans CJK SC'")
    # 3.5 mm capitals of a CJK face with ideographs 0.86 em tall
    assert float(text.get("font-size")) == pytest.approx(3.5 / 0.86, abs=1e-3)


def test_white_fill_and_plan_colour():
    style = SheetStyle(plan_vector_colour="blue")
    svg = to_svg(_scene(), style)
    root = ET.fromstring(svg.encode("utf-8"))
    joint = root.find(f"{SVG}g[@id='layer-mechanism-2']/{SVG}circle")
    assert joint.get("fill") == "white"
    head = root.find(f"{SVG}g[@id='layer-plan-v-1']/{SVG}polygon")
    assert head.get("fill") == "blue"


def test_text_and_attributes_are_escaped_and_read_back():
    """Markup characters in a label survive a round trip through an XML parser, in the text and
    in the aria-label an index brings; characters XML forbids become U+FFFD."""
    label = 'R₁ <a & "b"> \x01'
    svg = to_svg(Scene((Text((10, 10), label, "labels"), Text((10, 20), "", "labels")), 100, 50))
    root = ET.fromstring(svg.encode("utf-8"))
    plain, empty = root.iter(f"{SVG}text")
    assert plain.get("aria-label") == label.replace("\x01", "\ufffd")
    index, rest = plain.findall(f"{SVG}tspan")
    assert (plain.text, index.text, rest.text) == ("R", "1", ' <a & "b"> \ufffd')
    assert float(index.get("dy")) == pytest.approx(0.25 * 3.5)  # down to the subscript, and back
    assert float(rest.get("dy")) == pytest.approx(-0.25 * 3.5)
    assert empty.text is None and not list(empty)
    assert svg.startswith('<?xml version="1.0" encoding="utf-8" ?>\n<svg ') and svg.endswith("</svg>\n")


def test_empty_scene_is_a_document_with_only_defs():
    root = ET.fromstring(to_svg(Scene((), 10, 10)).encode("utf-8"))
    assert [child.tag for child in root] == [f"{SVG}defs"]
