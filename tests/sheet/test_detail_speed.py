"""The enlarged detail's shortcuts give the answers of the work they spare
(`velplan.views.plan_detail`): the numeral's spot decided by distance against the buffer of
the whole plan's ink, and the enlarged plan drawn once for a title above the circle and
beside it."""

import math

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.render.layout import label_box
from velplan.render.scene import Text
import velplan
from velplan.sheets.kinematic import build_sheet
from velplan.views import plan_detail
from velplan.views.plan_detail import _first_clear, detail_view

coord = st.floats(-20.0, 20.0, allow_nan=False)


def _by_buffer(texts, ink, pad):
    """The rule `_first_clear` stands for, as it was written before it."""
    grown = shapely.union_all(ink).buffer(pad)
    return next((t for t in texts if not label_box(t).intersects(grown)), texts[0])


@st.composite
def _inks(draw):
    ink = []
    for _ in range(draw(st.integers(0, 8))):
        kind = draw(st.sampled_from(("line", "box", "run")))
        x, y = draw(coord), draw(coord)
        if kind == "box":
            w, h = draw(st.floats(0.5, 6.0)), draw(st.floats(0.5, 4.0))
            ink.append(shapely.box(x, y, x + w, y + h))
        else:
            n = 2 if kind == "line" else draw(st.integers(3, 6))
            pts = [(x, y)] + [(draw(coord), draw(coord)) for _ in range(n - 1)]
            ink.append(shapely.LineString(pts))
    return ink


@given(_inks(), st.lists(st.tuples(coord, coord), min_size=1, max_size=16),
       st.sampled_from(("start", "middle", "end")))
@settings(max_examples=60, deadline=None)
def test_the_first_clear_numeral_is_the_one_the_buffer_gives(ink, spots, anchor):
    texts = [Text(xy, "II", "labels", 3.5, anchor) for xy in spots]
    assert _first_clear(texts, ink, 0.5) is _by_buffer(texts, ink, 0.5)


def test_boxes_at_the_buffers_rim_are_decided_as_the_buffer_decides():
    """Numerals brought to within a few hundredths of a millimetre of 0.5 mm off a line's end
    and off a box's corner, where the buffer's chords stand inside the true distance."""
    ink = [shapely.LineString([(0.0, 0.0), (10.0, 0.0)]), shapely.box(20.0, 0.0, 24.0, 3.0)]
    texts = []
    for a in np.radians(np.arange(0.0, 360.0, 15.0)):
        for corner in ((10.0, 0.0), (24.0, 3.0)):
            for d in (0.47, 0.49, 0.495, 0.5, 0.505, 0.52):
                box = Text((0.0, 0.0), "I", "labels", 3.5, "middle", "middle")
                x0, y0, x1, y1 = label_box(box).bounds
                hw, hh = (x1 - x0) / 2, (y1 - y0) / 2
                cx, cy = corner[0] + (hw + d) * math.cos(a), corner[1] + (hh + d) * math.sin(a)
                texts.append(Text((cx, cy), "I", "labels", 3.5, "middle", "middle"))
    grown = shapely.union_all(ink).buffer(0.5)
    far = Text((1000.0, 1000.0), "I", "labels", 3.5)  # clear of everything
    for t in texts:  # each alone: itself where clear, else the text after it
        assert (_first_clear([t, far], ink, 0.5) is t) == (not label_box(t).intersects(grown))
    assert _first_clear(texts, ink, 0.5) is _by_buffer(texts, ink, 0.5)


def test_a_detail_drawn_again_is_the_one_drawn_afresh():
    """The jaw crusher's A1 sheet's detail: drawn again with its title above the circle and
    beside it, in turn, each the same as drawn with the kept drawing forgotten, and the one on
    the sheet the same as drawn afresh."""
    sheet = build_sheet(velplan.Study("jaw-crusher"), fmt="A1", lang="ru")
    placed = sheet.views["detail-a-4"].view
    meta = placed.meta
    res = sheet.plans["plan-a-4"]
    args = (res, meta["number"], meta["region"], meta["factor"])
    numeral = placed.primitives[-2].text.split()[0]
    drawn = []
    for beside in (False, True, False, True):
        drawn.append(detail_view(*args, lang="ru", numeral=numeral, beside=beside))
        plan_detail._LAST_ENLARGED[0] = None
        assert detail_view(*args, lang="ru", numeral=numeral, beside=beside) == drawn[-1]
    assert drawn[0] == drawn[2] and drawn[1] == drawn[3] and drawn[0] != drawn[1]
    assert placed in drawn[:2]


def test_the_least_detail_size_never_exceeds_the_drawn_detail():
    """`least_detail_size` bounds the detail from below at every enlargement and title place,
    for the crowded acceleration plans of the jaw crusher and the triad press (a sheet skips
    drawing a detail whose bound finds no spot)."""
    for name in ("jaw-crusher", "triad-press"):
        sheet = build_sheet(velplan.Study(name), fmt="A1", lang="ru")
        for key, placed in sheet.views.items():
            if not key.startswith("detail-"):
                continue
            meta = placed.view.meta
            res = sheet.plans[f"plan-{meta['kind']}-{meta['number']}"]
            for factor in plan_detail.FACTORS:
                for beside in (False, True):
                    args = (res, meta["number"], meta["region"], factor)
                    w, h = plan_detail.least_detail_size(*args, lang="ru", beside=beside)
                    drawn = detail_view(*args, lang="ru", beside=beside)
                    assert 0.0 < w <= drawn.width_mm and 0.0 < h <= drawn.height_mm
                    assert w > drawn.width_mm - 60.0  # the circle and titles are most of it
