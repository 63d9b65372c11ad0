"""An enlarged detail that finds no free spot on the sheet takes the empty room inside the plan
of positions (the jaw crusher's needle of an acceleration plan on A3), clear of its ink."""
from dataclasses import replace

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from velplan.errors import ScaleError
from velplan.render.layout import label_box
from velplan.render.scene import Text
from velplan.sheets.kinematic import build_sheet
from velplan.sheets.layout import _free_square, check_layout, ink_boxes


@pytest.fixture(scope="module")
def jaw():
    return build_sheet("jaw-crusher", fmt="A3", lang="ru")


def test_the_needle_gets_its_detail_inside_the_scheme(jaw):
    detail = jaw.views["detail-a-4"]
    assert detail.view.meta["inside"] == "mechanism"
    box = shapely.box(*detail.bounds)
    scheme = jaw.views["mechanism"]
    assert shapely.box(*scheme.bounds).contains(box)  # inside the scheme's box ...
    for p in scheme.primitives:  # ... and clear of every line and letter of it
        shape = label_box(p) if isinstance(p, Text) else None
        if shape is None and hasattr(p, "points"):
            shape = shapely.LineString(p.points)
        if shape is not None:
            assert not box.intersects(shape), p


def test_a_detail_moved_onto_the_scheme_lines_is_refused(jaw):
    views = dict(jaw.views)
    scheme, detail = views["mechanism"], views["detail-a-4"]
    x0, y0, x1, y1 = scheme.bounds
    mid = np.array([(x0 + x1) / 2, (y0 + y1) / 2])  # onto the line nearest the scheme's middle
    ends = [np.asarray(p.points) for p in scheme.primitives if hasattr(p, "points")]
    cx, cy = min((e.mean(axis=0) for e in ends), key=lambda c: np.hypot(*(c - mid)))
    views["detail-a-4"] = replace(detail, x=cx - detail.view.width_mm / 2, y=cy - detail.view.height_mm / 2)
    with pytest.raises(ScaleError, match="lies on the drawing of the mechanism view"):
        check_layout(views, "A3", "eskd")


def test_ink_boxes_cover_every_line_and_leave_the_room(jaw):
    scheme = jaw.views["mechanism"]
    boxes = np.array(ink_boxes(scheme))
    for p in scheme.primitives:
        if hasattr(p, "points"):
            line = shapely.LineString(p.points)
            for d in np.linspace(0.0, line.length, 7):
                x, y = line.interpolate(d).coords[0]
                assert np.any((boxes[:, 0] <= x + 0.06) & (x - 0.06 <= boxes[:, 2])
                              & (boxes[:, 1] <= y + 0.06) & (y - 0.06 <= boxes[:, 3]))
    for p in scheme.primitives:  # a plate or a block: not a room to put a detail in
        if type(p).__name__ == "Polygon":
            x, y = np.asarray(p.points).mean(axis=0)
            assert np.any((boxes[:, 0] <= x) & (x <= boxes[:, 2]) & (boxes[:, 1] <= y) & (y <= boxes[:, 3]))
    covered = sum((b[2] - b[0]) * (b[3] - b[1]) for b in boxes)
    x0, y0, x1, y1 = scheme.bounds
    assert covered < 0.5 * (x1 - x0) * (y1 - y0)  # pieces, not the whole box


boxes = st.lists(st.tuples(st.floats(0, 300), st.floats(0, 300), st.floats(0, 60), st.floats(0, 60)),
                 max_size=25)


@settings(max_examples=150, deadline=None)
@given(boxes, st.floats(5, 80), st.floats(5, 80), st.floats(0, 12))
def test_square_gap_spots_against_every_corner_tested_alone(raw, w, h, gap):
    taken = [(x, y, x + dx, y + dy) for x, y, dx, dy in raw]
    gx, gy = np.arange(0.0, 320.0 - w + 1e-9, 5.0), np.arange(0.0, 300.0 - h + 1e-9, 5.0)
    free = _free_square(gx, gy, w, h, taken, gap)
    for j, y in enumerate(gy[::3]):
        for i, x in enumerate(gx[::3]):
            clear = all(not (x < b[2] + gap and b[0] - gap < x + w and y < b[3] + gap and b[1] - gap < y + h)
                        for b in taken)
            assert free[3 * j, 3 * i] == clear
