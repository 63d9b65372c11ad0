"""The bundled font and the text of PNG and PDF sheets: no character drawn as a box ("tofu").

Glyph coverage is read two ways: from the bundled font's cmap with fontTools, and from
cairo itself (the glyph index cairosvg would draw: 0 is ``.notdef``). Indices are drawn as
shifted plain characters, so the fonts need no "₅".
"""

import os
import subprocess
import sys
import textwrap
from xml.etree import ElementTree

import numpy as np
import pytest
from fontTools.ttLib import TTFont

from velplan.cli import main
from velplan.render import fontbuild, fonts
from velplan.render.fonts import BUNDLED_FAMILY, BUNDLED_FONT, missing_in_bundled
from velplan.render.i18n import LANGUAGES, label, label_keys
from velplan.render.scene import Scene, Text
from velplan.render.shapes import (SCRIPT_SCALE, SUBSCRIPT_DROP, script_size, text_extent,
                                   text_runs)
from velplan.render.style import SheetStyle
from velplan.render.svg import to_svg

SVG = "{http://www.w3.org/2000/svg}"
#: A character no font has (Supplementary Private Use Area-A).
NO_FONT_HAS = "\U000F0000"


@pytest.fixture(scope="module")
def cmap():
    with TTFont(str(BUNDLED_FONT), lazy=True) as font:
        return set(font.getBestCmap())


@pytest.fixture(scope="module")
def sheets():
    """The shaper's kinematic sheet in Chinese and Russian."""
    from velplan.sheets.kinematic import build_sheet
    from velplan.study import Study

    study = Study("shaper")
    return {lang: build_sheet(study, lang=lang) for lang in ("zh", "ru")}


@pytest.fixture(scope="module")
def cairo_fonts():
    cairocffi = pytest.importorskip("cairocffi")
    pytest.importorskip("cairosvg")
    assert fonts.register_with_fontconfig()
    return fonts.CairoFonts(cairocffi)


def _drawn(text: str) -> str:
    """The characters a backend draws for `text` (indices as plain characters)."""
    return "".join(run.text for run in text_runs(text))


def _lacking(text: str, cmap) -> str:
    return "".join(sorted({c for c in text if not c.isspace() and ord(c) not in cmap}))


# -- the font itself -------------------------------------------------------------------


def test_bundled_font_is_velplan_sans_under_the_ofl():
    with TTFont(str(BUNDLED_FONT), lazy=True) as font:
        assert font["name"].getDebugName(1) == BUNDLED_FAMILY
        assert "Open Font License" in font["name"].getDebugName(13)
        assert "glyf" in font and font["head"].unitsPerEm == 1000
    licence = (BUNDLED_FONT.parent / "OFL.txt").read_text(encoding="utf-8")
    assert "SIL OPEN FONT LICENSE Version 1.1" in licence
    assert licence.count("Reserved Font Name 'Source'") == 2  # both sources' notices
    assert BUNDLED_FONT.stat().st_size < 2.5e6


@pytest.mark.parametrize("lang", LANGUAGES)
def test_every_label_has_a_glyph(lang, cmap):
    for key in label_keys():
        text = label(key, lang)
        assert not _lacking(_drawn(text), cmap), (key, lang, text)
        assert not _lacking(text, cmap), (key, lang, text)  # matplotlib draws "₂" itself


def test_the_chinese_of_the_bundled_files_and_gb2312_has_glyphs(cmap):
    assert not _lacking(fontbuild.data_characters(), cmap)
    hanzi = fontbuild.gb2312_hanzi()
    assert len(hanzi) == 6763 and not _lacking(hanzi, cmap)


def test_missing_in_bundled_names_each_character_once():
    assert missing_in_bundled("速度 V₂ є ⌀") == ""
    assert missing_in_bundled(f"a{NO_FONT_HAS}b{NO_FONT_HAS}") == NO_FONT_HAS


@pytest.mark.parametrize("lang", ["zh", "ru"])
def test_every_text_of_a_sheet_has_a_glyph_in_the_bundled_font(lang, sheets, cmap):
    texts = [p.text for p in sheets[lang].scene.primitives if isinstance(p, Text)]
    assert len(texts) > 100
    assert not _lacking(_drawn("".join(texts)), cmap)


# -- PNG and PDF: the font cairo uses ---------------------------------------------------


@pytest.mark.parametrize("lang", ["zh", "ru"])
def test_every_text_of_a_sheet_gets_a_font_that_has_all_its_glyphs(lang, sheets, cmap,
                                                                    cairo_fonts):
    from velplan.render.export import texts_for_cairo

    fitted = ElementTree.fromstring(texts_for_cairo(sheets[lang].svg(), cairo_fonts))
    chosen = {}
    for element in fitted.iter(SVG + "text"):
        family, text = element.get("font-family"), "".join(element.itertext())
        assert "," not in family
        assert cairo_fonts.missing(family, text) == "", (family, text)
        if family == BUNDLED_FAMILY:
            assert not _lacking(text, cmap), text
        chosen[family] = chosen.get(family, 0) + 1
    assert len(chosen) == 1, chosen  # one face for the whole sheet, not a mix
    if lang == "zh" and not fonts.installed("Noto Sans CJK SC"):
        assert set(chosen) == {BUNDLED_FAMILY}


def _ink(cairocffi, family: str, char: str) -> np.ndarray:
    """The pixels of `char` drawn by cairo's toy API in `family`, as cairosvg draws it."""
    surface = cairocffi.ImageSurface(cairocffi.FORMAT_A8, 64, 64)
    context = cairocffi.Context(surface)
    context.select_font_face(family)
    context.set_font_size(40)
    context.move_to(8, 48)
    context.text_path(char)
    context.fill()
    surface.flush()
    return np.frombuffer(bytes(surface.get_data()), np.uint8).reshape(64, -1)[:, :64].copy()


def test_zh_png_has_no_tofu(sheets, cairo_fonts, tmp_path):
    """The sheet converts; and no character of it, drawn in the font chosen for it, looks
    like the font's .notdef box."""
    import cairocffi

    from velplan.render.export import texts_for_cairo, write_png

    svg = sheets["zh"].svg()
    assert write_png(svg, tmp_path / "zh.png", dpi=50).stat().st_size > 10_000
    fitted = ElementTree.fromstring(texts_for_cairo(svg, cairo_fonts))
    by_family = {}
    for element in fitted.iter(SVG + "text"):
        by_family.setdefault(element.get("font-family"), set()).update(
            c for c in "".join(element.itertext()) if not c.isspace())
    for family, chars in by_family.items():
        tofu = _ink(cairocffi, family, NO_FONT_HAS)
        assert tofu.any()  # the box is drawn: a missing glyph would look like this
        looks_missing = [c for c in sorted(chars)
                         if np.array_equal(_ink(cairocffi, family, c), tofu)]
        assert not looks_missing, (family, looks_missing)
    assert {"速", "度", "ω", "2"} <= by_family[next(iter(by_family))]


@pytest.mark.parametrize("suffix", [".png", ".pdf"])
def test_a_title_no_font_has_is_a_one_line_error_and_no_file(suffix, tmp_path, capsys):
    pytest.importorskip("cairosvg")
    code = main(["sheet", "shaper", "--lang", "zh", "--title", f"牛头刨床{NO_FONT_HAS}",
                 "-o", str(tmp_path / f"sheet{suffix}")])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and err.startswith("velplan: error: cannot draw the text")
    assert "U+F0000" in err and BUNDLED_FAMILY in err and suffix[1:].upper() in err
    assert os.listdir(tmp_path) == []


def test_a_machine_without_fonts_still_draws_every_language(tmp_path):
    """fontconfig with no font directory at all (a fresh machine, pip only): every label
    language still converts, in Velplan Sans."""
    pytest.importorskip("cairosvg")
    config = tmp_path / "fonts.conf"
    config.write_text('<?xml version="1.0"?><fontconfig><cachedir>'
                      f'{tmp_path / "cache"}</cachedir></fontconfig>', encoding="utf-8")
    script = textwrap.dedent(f"""
        import cairocffi
        from xml.etree import ElementTree
        from velplan.render import fonts
        from velplan.render.export import texts_for_cairo, write_png
        from velplan.render.scene import Scene, Text
        from velplan.render.style import SheetStyle
        from velplan.render.svg import to_svg
        assert fonts.installed("DejaVu Sans") is False
        for lang, words in (("en", "Velocity plan"), ("ru", "План ускорений ω₃/ω₂"),
                            ("uk", "Зрівноважувальний момент, їх"),
                            ("zh", "加速度多边形 ⌀")):
            svg = to_svg(Scene((Text((5, 10), words, "labels", 3.5),), 120, 20),
                         SheetStyle(language=lang))
            write_png(svg, {str(tmp_path)!r} + f"/{{lang}}.png")
            fitted = texts_for_cairo(svg, fonts.CairoFonts(cairocffi))
            assert 'font-family="Velplan Sans"' in fitted, fitted
        print("ok")
    """)
    env = {**os.environ, "FONTCONFIG_FILE": str(config)}
    run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0 and run.stdout.strip() == "ok", run.stderr
    assert sorted(os.listdir(tmp_path)) == ["cache", "en.png", "fonts.conf", "ru.png",
                                            "uk.png", "zh.png"]


def test_installed_tells_a_font_from_a_substitute(cairo_fonts):
    assert fonts.installed(BUNDLED_FAMILY) is True
    assert fonts.installed("No Such Font Velplan") is False
    usable = cairo_fonts.usable(["No Such Font Velplan", "sans-serif"])
    assert usable == [BUNDLED_FAMILY, "sans-serif"]


# -- indices: shifted plain characters, measured as drawn -------------------------------


def test_indices_are_drawn_as_shifted_smaller_characters():
    style = SheetStyle(language="zh")
    svg = to_svg(Scene((Text((10, 10), "ω₃/ω₂, aⁿ", "labels", 3.5),), 100, 50), style)
    text = ElementTree.fromstring(svg).find(f".//{SVG}text")
    assert not set("₃₂ⁿ") & set("".join(text.itertext()))
    assert text.text == "ω" and [t.text for t in text] == ["3", "/ω", "2", ", a", "n"]
    assert text.get("aria-label") == "ω₃/ω₂, aⁿ"  # the label's meaning, for readers
    size = float(text.get("font-size"))
    sub, back = text[0], text[1]
    # 2.5 mm, the ESKD minimum, not 0.7 × 3.5 = 2.45 mm
    assert float(sub.get("font-size")) == pytest.approx(2.5 / 3.5 * size, abs=1e-3)
    assert float(sub.get("dy")) == pytest.approx(SUBSCRIPT_DROP * 3.5)
    assert float(back.get("dy")) == pytest.approx(-SUBSCRIPT_DROP * 3.5)
    assert back.get("font-size") is None
    assert float(text[4].get("dy")) < 0  # the superscript rises


def test_a_text_without_indices_is_one_text_as_before():
    svg = to_svg(Scene((Text((10, 10), "План скоростей m/s²", "labels", 3.5),), 100, 50))
    assert "<tspan" not in svg and "План скоростей m/s²</text>" in svg


def test_text_extent_counts_indices_at_their_drawn_size():
    s, four = 0.596 / 0.72, 0.572 / 0.72  # advances per capital height ("S", "4": ems over 0.72)
    width, _ = text_extent("S₄", 5.0)
    assert width == pytest.approx(5.0 * (s + four * SCRIPT_SCALE), abs=0.01)
    width, _ = text_extent("S₄", 2.0)  # an index never below 2.5 mm, nor above its letter
    assert width == pytest.approx(2.0 * (s + four), abs=0.01) and script_size(3.0) == 2.5
    assert [r.script for r in text_runs("aᵏ₅²")] == ["", "super", "sub", ""]


@pytest.mark.parametrize("anchor", ["middle", "end"])
def test_an_aligned_text_with_indices_lands_where_it_should(anchor, cairo_fonts, tmp_path):
    """cairosvg aligns each tspan by itself; the export anchors the whole text at its
    measured start instead, so its ink is centred (or ends) on the anchor."""
    from PIL import Image

    from velplan.render.export import write_png

    scene = Scene((Text((60, 10), "VA₄/ω₂, м", "labels", 5.0, anchor),), 120, 20)
    png = write_png(to_svg(scene), tmp_path / "t.png", dpi=254)  # 10 px per mm
    ink = np.nonzero(np.asarray(Image.open(png).convert("L")) < 128)[1] / 10.0
    if anchor == "middle":
        assert (ink.min() + ink.max()) / 2 == pytest.approx(60, abs=0.6)
    else:  # the last letter's right side bearing is left of the anchor
        assert 59.0 < ink.max() <= 60.1
    assert ink.max() - ink.min() == pytest.approx(
        text_extent("VA₄/ω₂, м", 5.0)[0], rel=0.35)


def test_matplotlib_draws_chinese_in_velplan_sans_without_missing_glyphs(recwarn):
    pytest.importorskip("matplotlib")
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from velplan.render.mpl import MplCanvas, _installed_families
    from velplan.render.canvas import render

    assert BUNDLED_FAMILY in _installed_families(SheetStyle(language="zh").font_families)
    ax = render(Scene((Text((5, 10), "速度多边形 ω₂ є ⌀", "labels", 3.5),), 60, 20),
                MplCanvas(style=SheetStyle(language="zh")))
    FigureCanvasAgg(ax.figure).draw()
    assert not [w for w in recwarn if "missing from" in str(w.message)]
