"""Checks shared by the kinematic and the force sheet tests."""

import shapely

from velplan.render.canvas import RecordingCanvas, render
from velplan.sheets.frame import free_area


def record_all(sheets) -> dict:
    """Each sheet drawn on a recording canvas: name → canvas."""
    out = {}
    for name, sheet in sheets.items():
        canvas = RecordingCanvas()
        render(sheet.scene, canvas)
        out[name] = canvas
    return out


def assert_views_placed(sheet, *, overlap_below_mm2: float | None = None) -> dict:
    """Every view inside the sheet's free area, no two views overlapping (area exactly 0, or
    below ``overlap_below_mm2``), and every primitive of a view inside its box (to 1e-6 mm);
    returns the boxes."""
    area = free_area(sheet.fmt, frame_style=sheet.frame_style).buffer(1e-6)
    boxes = {k: shapely.box(*v.bounds) for k, v in sheet.views.items()}
    for k, box in boxes.items():
        assert area.contains(box), k
        for j, other in boxes.items():
            if j < k:
                overlap = box.intersection(other).area
                assert overlap == 0 if overlap_below_mm2 is None else overlap < overlap_below_mm2, (j, k)
    for k, placed in sheet.views.items():
        box = shapely.box(*placed.bounds).buffer(1e-6)
        for p in placed.primitives:
            assert box.contains(shapely.box(*p.bounds)), (k, p)
    return boxes


def calls_with_and_without(monkeypatch, sheet, counted: str, shortcuts) -> tuple[int, int]:
    """(the calls of ``kinematic.<counted>`` that building ``sheet()`` makes, the calls with
    every ``(owner, name, value)`` of ``shortcuts`` patched in to turn a shortcut off), after
    asserting that both builds give the same SVG: a shortcut of the layout search may save
    drawings, never change the sheet."""
    from velplan.sheets import kinematic

    calls = []
    real = getattr(kinematic, counted)
    monkeypatch.setattr(kinematic, counted, lambda *a, **kw: calls.append(1) or real(*a, **kw))
    quick = sheet().svg()
    saved = len(calls)
    for owner, name, value in shortcuts:
        monkeypatch.setattr(owner, name, value)
    calls.clear()
    assert sheet().svg() == quick
    return saved, len(calls)
