"""Every figure of the note laid out for its printed lettering (issue 32): a figure shrunk to the
page has its text enlarged to 2.5 mm printed, and the figure makes room for it — each text's box
inside the figure's box, no text over another — for mechanisms of several kinds and languages."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("cairosvg")

import velplan  # noqa: E402
from velplan.note import figures  # noqa: E402
from velplan.note.build import build_note  # noqa: E402
from velplan.render.layout import overlapping_labels  # noqa: E402
from velplan.render.scene import Text  # noqa: E402
from velplan.render.shapes import text_box  # noqa: E402

CASES = [("shaper", "ru", ("kinematics", "forces", "dynamics")), ("oscillating-cylinder", "en", None),
         ("jaw-crusher", "uk", ("kinematics", "dynamics")), ("triad-press", "zh", ("kinematics",))]


@pytest.fixture(scope="module", params=CASES, ids=[c[0] for c in CASES])
def drawn(request):
    """(scene, shrink) of every figure of the note of one case."""
    name, lang, parts = request.param
    got = []
    page_scene = figures.page_scene

    def record(views):
        out = page_scene(views)
        got.append(out)
        return out

    mp = pytest.MonkeyPatch()
    mp.setattr(figures, "page_scene", record)
    try:
        build_note(velplan.Study(name, delta=0.05), lang=lang, parts=parts)
    finally:
        mp.undo()
    assert len(got) >= 5
    return got


def _outside(scene) -> list[str]:
    """The texts whose box, taken 1.25 times wider than estimated (rendered glyphs run
    wider), leaves the figure."""
    out = []
    for t in scene.of_kind(Text):
        anchor = np.asarray(t.position, float)
        box = anchor + (text_box(t) - anchor) * (1.25, 1.0)
        (x0, y0), (x1, y1) = box.min(axis=0), box.max(axis=0)
        if x0 < -1e-6 or y0 < -1e-6 or x1 > scene.width_mm + 1e-6 or y1 > scene.height_mm + 1e-6:
            out.append(t.text)
    return out


def test_every_text_lies_inside_its_figure(drawn):
    bad = {k: _outside(scene) for k, (scene, _) in enumerate(drawn, 1)}
    assert not {k: v for k, v in bad.items() if v}


def test_no_text_over_another(drawn):
    bad = {k: [(a.text, b.text) for a, b in overlapping_labels(scene, min_area=0.5)]
           for k, (scene, _) in enumerate(drawn, 1)}
    assert not {k: v for k, v in bad.items() if v}


def test_lettering_prints_at_2_5_mm_and_the_figure_fits_the_page(drawn):
    for scene, shrink in drawn:
        assert scene.width_mm * shrink <= figures.TEXT_WIDTH_MM + 1e-6
        assert scene.height_mm * shrink <= figures.FIGURE_HEIGHT_MM + 1e-6
        if shrink < 1.0:
            assert min(t.size_mm for t in scene.of_kind(Text)) * shrink >= figures.LETTER_MM - 1e-9
