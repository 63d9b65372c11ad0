"""The note's figures and its pandoc run, made for a quick first answer: figures kept as SVG
and rasterised only where a format needs pixels (all of a note's at once, by Typst); the .docx
carries each figure's SVG with velplan's PNG as the fallback; pandoc run directly, its failures
one line."""

from __future__ import annotations

import os
import sys
import zipfile

import pytest

pytest.importorskip("typst")
pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")

from velplan.errors import VelplanError  # noqa: E402
from velplan.note import build_note, figures, raster, write_note  # noqa: E402
from velplan.note.blocks import Figure  # noqa: E402
from velplan.note.docx_figures import svg_blips  # noqa: E402
from velplan.note.pandoc import Pandoc, pandoc_program  # noqa: E402
from velplan.note.writers import require  # noqa: E402

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


def test_all_figures_made_in_one_run(monkeypatch):
    from velplan.note import pixels

    made = build_note("four-bar", n=4, parts=["kinematics"], lang="en", plans=[2])
    runs = []
    real = pixels.pngs
    monkeypatch.setattr(pixels, "pngs", lambda pictures: runs.append(len(pictures)) or real(pictures))
    monkeypatch.setattr(figures, "_MADE", {})
    pngs = figures.pictures_png([f.picture for f in _figures(made)] * 2)
    assert runs == [len(_figures(made))] and len(pngs) == 2 * runs[0]  # each drawn once, together
    assert [f.png for f in _figures(made)] == pngs[:runs[0]] and runs == [runs[0]]  # kept


def test_a_helper_only_where_a_core_is_free(monkeypatch):
    monkeypatch.setattr(raster, "cores", lambda: 1)
    assert not raster.core_free()  # one core
    monkeypatch.setattr(raster, "cores", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (3.0, 3.0, 3.0))
    assert not raster.core_free()  # a busy machine
    monkeypatch.setattr(os, "getloadavg", lambda: (1.2, 3.0, 3.0))
    assert raster.core_free()


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
    require("md")  # needs typst only
