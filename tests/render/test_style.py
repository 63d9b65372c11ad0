import pytest

from velplan.errors import VelplanError
from velplan.render.style import SheetStyle


def test_defaults_follow_eskd():
    style = SheetStyle()
    assert style.width("thick") == 0.7
    assert style.width("thin") == 0.35
    assert style.dash("axis") == (12.0, 3.0, 1.0, 3.0)
    assert style.dash("thick") == ()
    assert style.stroke_colour("plan-v-1") == "black"
    assert style.font_families[0] == "DejaVu Sans Condensed"
    assert style.font_size_em(3.6) == pytest.approx(5.0)


def test_chinese_gets_cjk_fonts_first():
    style = SheetStyle(language="zh")
    assert style.font_families[0] == "Noto Sans CJK SC"
    assert "sans-serif" in style.font_families
    assert style.font_css.startswith("'Noto Sans CJK SC', 'Source Han Sans SC'")


def test_plan_colour_applies_to_plan_layers_only():
    style = SheetStyle(plan_vector_colour="navy")
    assert style.stroke_colour("plan-a-3") == "navy"
    assert style.stroke_colour("mechanism") == "black"


@pytest.mark.parametrize("kwargs, message", [
    ({"language": "fr"}, "known languages: en, ru, uk, zh"),
    ({"thick_mm": 0}, "thick_mm must be a positive length"),
    ({"thin_mm": -0.2}, "thin_mm must be a positive length"),
    ({"text_height_mm": 1.5}, "at least 1.8 mm"),
    ({"text_height_mm": 4.0}, "not a standard height; use one of 1.8, 2.5, 3.5, 5, 7"),
    ({"axis_dash": (5.0, 2.0, 1.0)}, "even number of positive lengths"),
    ({"font_family": ()}, "non-empty tuple of font names"),
])
def test_invalid_style_raises(kwargs, message):
    with pytest.raises(VelplanError, match=message):
        SheetStyle(**kwargs)


def test_unknown_line_type():
    with pytest.raises(VelplanError, match="unknown line type 'bold'"):
        SheetStyle().width("bold")
