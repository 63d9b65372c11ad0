"""The note's figures and its pandoc run, made for a quick first answer: figures kept as SVG
and rasterised only where a format needs pixels; the .docx carries each figure's SVG with
velplan's PNG as the fallback; PNGs made by a helper process while the note is built are the
same bytes as those made in the process; pandoc run directly, its failures one line."""

from __future__ import annotations

import io
import sys
import zipfile

import pytest

pytest.importorskip("cairosvg")
pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")

from velplan.errors import VelplanError  # noqa: E402
from velplan.note import build_note, figures, raster, write_note  # noqa: E402
from velplan.note.blocks import Figure  # noqa: E402
from velplan.note.docx_figures import svg_blips  # noqa: E402
from velplan.note.pandoc import Pandoc, pandoc_program  # noqa: E402
from velplan.note.writers import require  # noqa: E402
from velplan.render.export import svg_to_png  # noqa: E402
from velplan.render.raster_worker import serve  # noqa: E402

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def note():
    return build_note("four-bar", n=4, parts=["kinematics"], lang="en")


def _figures(note):
    return [b for b in note.blocks if isinstance(b, Figure)]


def _png_size(png: bytes) -> tuple[int, int]:
    return int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")


def test_a_figure_is_svg_until_pixels_are_asked_for(note):
    figs = _figures(note)
    assert len(figs) >= 4
    for fig in figs:
        assert fig.svg.startswith("<?xml") and 'width="' in fig.svg and fig.name == f"figure-{figs.index(fig) + 1}"
        png = fig.png
        assert png.startswith(PNG) and fig.png is png  # made once
        assert png == svg_to_png(fig.svg, dpi=fig.picture.dpi, grey=True)
        # the printed width at the figure's dpi: pixels = width (in) × dpi, to a pixel
        width_in = float(fig.svg.split('width="')[1].split("mm")[0]) / 25.4
        assert abs(_png_size(png)[0] - width_in * fig.picture.dpi) <= 1.0
        printed_dpi = fig.picture.dpi * width_in * 25.4 / fig.width_mm
        assert printed_dpi == pytest.approx(figures.DPI, rel=1e-4)  # the SVG states its width to 1 µm


def test_docx_figures_are_svg_with_velplans_png_behind(note, tmp_path):
    path = write_note(note, tmp_path / "n.docx")
    doc = docx.Document(str(path))
    blips = svg_blips(doc)
    figs = _figures(note)
    assert len(blips) == len(figs)
    part = doc.part
    for (blip, svg), fig in zip(blips, figs):
        assert svg == fig.svg.encode("utf-8")
        png = part.related_parts[blip.get("{http://schemas.openxmlformats.org/officeDocument/2006/"
                                          "relationships}embed")].blob
        assert png == fig.png
    names = zipfile.ZipFile(path).namelist()
    assert sum(n.endswith(".svg") for n in names) == sum(n.endswith(".png") for n in names) == len(figs)


@pytest.mark.parametrize("fork", [True, False] if raster.FORK else [False])
def test_pngs_made_aside_are_the_same_bytes(monkeypatch, fork):
    monkeypatch.setattr(raster, "FORK", fork)
    monkeypatch.setattr(raster, "core_free", lambda: True)
    monkeypatch.setattr(raster, "cores", lambda: 2)
    figures._png.cache_clear()
    with raster.rasterise_aside():
        aside = figures.ASIDE
        assert aside is not None and aside.helper is not None
        made = build_note("four-bar", n=4, parts=["kinematics"], lang="en", plans=[2])
        pngs = [f.png for f in _figures(made)]
        assert len(aside.numbers) == len(pngs) and all(aside.answers.values())
        folder = aside.folder
    assert figures.ASIDE is None and not folder.exists() and aside.helper is None
    figures._png.cache_clear()
    assert pngs == [svg_to_png(f.svg, dpi=f.picture.dpi, grey=True) for f in _figures(made)]


def test_a_helper_gone_leaves_the_figures_to_this_process(monkeypatch):
    monkeypatch.setattr(raster, "core_free", lambda: True)
    monkeypatch.setattr(raster, "cores", lambda: 2)
    figures._png.cache_clear()
    with raster.rasterise_aside():
        aside = figures.ASIDE
        made = build_note("four-bar", n=4, parts=["kinematics"], lang="en", plans=[2])
        aside.helper._stop()  # the process ends; its pipes stay open here
        pngs = [f.png for f in _figures(made)]
        assert aside.helper is None  # noticed at the first figure asked for, and closed
    figures._png.cache_clear()
    assert pngs == [svg_to_png(f.svg, dpi=f.picture.dpi, grey=True) for f in _figures(made)]


def test_no_helper_where_it_would_not_help(monkeypatch):
    monkeypatch.setattr(raster, "cores", lambda: 1)
    assert not raster.core_free()
    with raster.rasterise_aside():
        assert figures.ASIDE is None  # one core
    monkeypatch.setattr(raster, "cores", lambda: 2)
    monkeypatch.setattr(raster.os, "getloadavg", lambda: (3.0, 3.0, 3.0))
    assert not raster.core_free()
    with raster.rasterise_aside():
        assert figures.ASIDE is None  # a busy machine
    monkeypatch.setattr(raster.os, "getloadavg", lambda: (1.2, 3.0, 3.0))
    assert raster.core_free()
    with raster.rasterise_aside(enabled=False):
        assert figures.ASIDE is None


def test_the_helper_answers_each_drawing(tmp_path):
    good = '<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm"><line x1="0" y1="0" x2="20" y2="10" stroke="black"/></svg>'
    (tmp_path / "0.svg").write_text(good, encoding="utf-8")
    (tmp_path / "1.svg").write_text("<svg", encoding="utf-8")
    out = io.StringIO()
    assert serve(str(tmp_path), io.StringIO("0 254.0\n1 100.0\n2 100.0\n"), out) == 1
    assert out.getvalue().split("\n") == ["0 ok", "1 failed", "2 failed", ""]
    assert _png_size((tmp_path / "0.png").read_bytes()) == (200, 100)  # 20 mm at 254 dpi


def test_pandoc_failures_are_one_line(tmp_path, monkeypatch):
    with pytest.raises(VelplanError, match=r"^pandoc could not write the note \(docx\): .*unknown-option"):
        Pandoc("text", "docx", tmp_path, ["--an-unknown-option"]).result()
    monkeypatch.setenv("PYPANDOC_PANDOC", str(tmp_path / "no-pandoc"))
    assert pandoc_program() == str(tmp_path / "no-pandoc")
    with pytest.raises(VelplanError, match=r"^pandoc could not write the note \(html\): "):
        Pandoc("text", "html", tmp_path)


def test_require_finds_without_importing(monkeypatch):
    monkeypatch.setitem(sys.modules, "pypandoc", None)
    with pytest.raises(VelplanError, match=r"the note needs pypandoc .*pip install 'velplan\[note\]'"):
        require("docx")
    require("md")  # needs cairosvg only
