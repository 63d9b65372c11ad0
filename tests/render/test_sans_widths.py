"""The width table text_extent measures with agrees with the fonts a sheet is drawn with."""

from __future__ import annotations

import importlib

import pytest

from velplan.render import widthbuild
from velplan.render.fonts import BUNDLED_FONT
from velplan.render.sans_widths import WIDTHS
from velplan.render.shapes import NARROW_CHAR_WIDTH, script_size, text_extent

LABELS = ("G₅", "G₆", "ω₂", "F₂₁", "M_{д}", "v_{BA}", "1000 Н", "Фи = 12 м/с²", "ЯКІР", "pv = 4,2 мм")


def _fonts():
    return [p for p in (BUNDLED_FONT, widthbuild.DEJAVU_CONDENSED) if p.is_file()]


def test_table_is_the_widest_advance_of_the_fonts():
    measured = [widthbuild.advances(p) for p in _fonts()]
    for char in "G5Жaω ₅.,=/²⌀±→":
        widest = max(m[ord(char)] for m in measured if ord(char) in m)
        assert widest <= WIDTHS[char] < widest + 0.001, char


def test_labels_are_measured_no_narrower_than_either_font_draws_them():
    cairo = pytest.importorskip("cairocffi")
    from velplan.render import fonts
    from velplan.render.shapes import _characters

    fonts.register_with_fontconfig()
    cairo_fonts = fonts.CairoFonts(cairo)
    families = [f for f in ("DejaVu Sans Condensed", fonts.BUNDLED_FAMILY) if cairo_fonts.missing(f, "G") == ""]
    assert families
    for size in (2.5, 3.5, 5.0):
        for label in LABELS:
            estimate = text_extent(label, size)[0]
            for family in families:
                drawn = sum(cairo_fonts.advance(family, c, size / 0.72 * (script_size(size) / size if s else 1.0))
                            for c, s in _characters(label))
                # never narrower; no wider than the other font's extra (≤ 10 %)
                assert drawn - 1e-6 <= estimate <= 1.10 * drawn, (label, size, family)


def test_unknown_characters_fall_back_to_the_estimate():
    assert "\ue000" not in WIDTHS
    assert text_extent("\ue000", 4.0)[0] == pytest.approx(NARROW_CHAR_WIDTH * 4.0)


def test_the_module_is_what_widthbuild_writes(tmp_path):
    if len(_fonts()) < 2:
        pytest.skip("DejaVu Sans Condensed is not installed here")
    out = tmp_path / "sans_widths.py"
    assert widthbuild.main(["-o", str(out)]) == 0
    module = importlib.import_module("velplan.render.sans_widths")
    assert out.read_text(encoding="utf-8") == open(module.__file__, encoding="utf-8").read()
