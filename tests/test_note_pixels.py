"""The note's figures in pixels (`velplan.note.pixels`): drawn by Typst, all of a note's in one
run, at each figure's own resolution; the same drawing as the sheets' PNG export (cairosvg)
makes of the same SVG — the same size in pixels, the same ink, the texts in the same narrow
face; a figure Typst cannot draw is a one-line error."""

from __future__ import annotations

import io

import numpy as np
import pytest

pytest.importorskip("typst")
Image = pytest.importorskip("PIL.Image")

from velplan.errors import VelplanError  # noqa: E402
from velplan.note import build_note  # noqa: E402
from velplan.note.blocks import Figure  # noqa: E402
from velplan.note.figures import Picture, pictures_png  # noqa: E402
from velplan.note.pixels import pngs  # noqa: E402

LINE = ('<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm" viewBox="0 0 20 10">'
        '<line x1="0" y1="5" x2="20" y2="5" stroke="black" stroke-width="1"/></svg>')


def _grey(png: bytes) -> np.ndarray:
    """The PNG's pixels as grey levels 0–255 on white paper."""
    im = Image.open(io.BytesIO(png)).convert("RGBA")
    paper = Image.new("RGBA", im.size, "white")
    paper.alpha_composite(im)
    return np.asarray(paper.convert("L"), dtype=float)


def _blurred(a: np.ndarray, k: int = 5) -> np.ndarray:
    """Mean of each k × k square (what the eye sees of a line's anti-aliased edge)."""
    c = np.cumsum(np.cumsum(np.pad(a, ((1, 0), (1, 0))), 0), 1)
    return (c[k:, k:] - c[:-k, k:] - c[k:, :-k] + c[:-k, :-k]) / (k * k)


def test_a_figure_has_its_resolution_in_pixels():
    png, = pngs([Picture(LINE, 254.0)])
    a = _grey(png)
    assert a.shape == (100, 200)  # 20 × 10 mm at 254 dpi: 10 pixels a mm
    rows = np.flatnonzero(a.mean(axis=1) < 128)
    assert rows.size and abs(rows.mean() - 49.5) <= 1.0 and rows.size <= 12  # the 1 mm line across the middle
    assert a[:30].min() == 255.0 and a[70:].min() == 255.0  # white paper elsewhere


def test_a_numpy_resolution_is_a_plain_number():
    dpi = np.float64(150.0) * np.float64(0.8620689655172413)  # a shrink fitted to a standard scale
    png, = pictures_png([Picture(LINE, dpi)])
    assert _grey(png).shape == (round(10 / 25.4 * float(dpi)), round(20 / 25.4 * float(dpi)))


def test_figures_drawn_as_the_sheets_png_export_draws_them():
    export = pytest.importorskip("velplan.render.export")
    pytest.importorskip("cairosvg")
    note = build_note("four-bar", n=4, parts=["kinematics"], lang="uk", plans=[2])
    figs = [b for b in note.blocks if isinstance(b, Figure)]
    for fig, png in zip(figs, pictures_png([f.picture for f in figs])):
        ours, theirs = _grey(png), _grey(export.svg_to_png(fig.svg, dpi=fig.picture.dpi, grey=True))
        assert ours.shape == theirs.shape, fig.name
        ink, their_ink = (ours < 128).mean(), (theirs < 128).mean()
        assert 0.8 < ink / their_ink < 1.25, (fig.name, ink, their_ink)
        assert np.abs(_blurred(ours) - _blurred(theirs)).mean() < 6.0, fig.name


def test_texts_keep_the_sheets_narrow_face():
    export = pytest.importorskip("velplan.render.export")
    pytest.importorskip("cairosvg")
    from velplan.render.fonts import installed
    from velplan.render.style import DEFAULT_FONT_FAMILIES

    if not installed(DEFAULT_FONT_FAMILIES["ru"][0]):
        pytest.skip(f"{DEFAULT_FONT_FAMILIES['ru'][0]} is not installed")
    families = ", ".join(f"'{f}'" if " " in f else f for f in DEFAULT_FONT_FAMILIES["ru"])
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="10mm" viewBox="0 0 120 10">'
           f'<text x="2" y="7" font-size="5" font-family="{families}">План положений механизма</text></svg>')
    widths = []
    for png in (pngs([Picture(svg, 150.0)])[0], export.svg_to_png(svg, dpi=150.0, grey=True)):
        columns = np.flatnonzero((_grey(png) < 128).any(axis=0))
        widths.append(columns[-1] - columns[0])
    assert widths[0] == pytest.approx(widths[1], rel=0.03)


def test_a_figure_typst_cannot_draw_is_one_line():
    with pytest.raises(VelplanError, match=r"^typst could not rasterise the note's figures: [^\n]+$"):
        pngs([Picture('<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm"><line', 150.0)])
    with pytest.raises(VelplanError, match=r"^cannot rasterise a figure: its SVG does not state"):
        pngs([Picture('<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100"/>', 150.0)])


def test_a_failed_docx_leaves_no_figures_behind(monkeypatch, tmp_path):
    import tempfile

    from velplan.note import pandoc, write_note

    note = build_note("four-bar", n=4, parts=["kinematics"], lang="en", plans=[2])
    work = tmp_path / "tmp"
    work.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(work))
    monkeypatch.setattr("velplan.note.figures._MADE", {})  # the figures drawn again, in the thread

    def fail(self):
        raise VelplanError("pandoc could not write the note (docx): no")

    monkeypatch.setattr(pandoc.Pandoc, "result", fail)
    with pytest.raises(VelplanError, match="^pandoc could not write the note"):
        write_note(note, tmp_path / "n.docx")
    assert not (tmp_path / "n.docx").exists() and list(work.iterdir()) == []  # the thread's files gone too
