"""Label placement (`velplan.views.base.place_labels`) against a plain search: every spot of
every ring tried in turn, one shapely test at a time."""

import math

import numpy as np
import pytest
import shapely

from velplan.render.scene import Text
from velplan.render.shapes import text_box
from velplan.views.base import place_labels


def _box(text, spot):
    centre = np.asarray(text.position)
    corners = np.asarray(spot) + (text_box(text) - centre) * (1.25, 1.1)
    if text.rotation_deg == 0.0:
        (x0, y0), (x1, y1) = corners.min(axis=0), corners.max(axis=0)
        return shapely.box(x0 - 0.4, y0 - 0.4, x1 + 0.4, y1 + 0.4)
    return shapely.Polygon(corners).buffer(0.4)


def _ring_spots(text, step, first, last):
    x, y = text.position
    return [(x + ring * step * math.cos(math.pi / 4 * k), y + ring * step * math.sin(math.pi / 4 * k))
            for ring in range(first, last + 1) for k in range(8)]


def _plain_search(texts, obstacles, rings, step_mm=None):
    """The first spot clear of the obstacles and of the labels placed before; else the spot off
    the labels that meets the fewest obstacles; else, upright, the first spot off the labels
    farther out; else where it was."""
    placed, out = [], []
    for text in texts:
        step = step_mm or 0.5 * text.size_mm
        spots = [text.position] + _ring_spots(text, step, 1, rings)
        boxes = [_box(text, s) for s in spots]
        met = [sum(box.intersects(o) for o in obstacles) for box in boxes]
        apart = [not any(box.intersects(p) for p in placed) for box in boxes]
        j = next((j for j in range(len(spots)) if apart[j] and not met[j]), None)
        if j is None and any(apart):
            j = min((j for j in range(len(spots)) if apart[j]), key=lambda j: met[j])
        if j is None and text.rotation_deg == 0.0:
            far = [s for s in _ring_spots(text, step, rings + 1, 2 * rings)
                   if not any(_box(text, s).intersects(p) for p in placed)]
            j = len(spots) if far else 0
            spots, boxes = spots + far[:1], boxes + [_box(text, s) for s in far[:1]]
        j = j or 0
        placed.append(boxes[j])
        out.append(Text(spots[j], text.text, text.layer, text.size_mm, text.anchor, text.baseline,
                        text.rotation_deg))
    return out


@pytest.mark.parametrize("seed", range(12))
def test_labels_take_the_spots_of_the_plain_search(seed):
    rng = np.random.default_rng(seed)
    texts = [Text(tuple(rng.uniform(0, 30, 2)), f"B{i}", "labels", size_mm=float(rng.choice([2.5, 3.5])),
                  anchor=str(rng.choice(["start", "middle", "end"])),
                  rotation_deg=float(rng.choice([0.0, 0.0, 0.0, 35.0])))
             for i in range(int(rng.integers(3, 30)))]
    obstacles = [shapely.LineString(rng.uniform(0, 30, (3, 2))).buffer(0.6)
                 for _ in range(int(rng.integers(0, 9)))]
    rings, step = int(rng.integers(1, 9)), (None if seed % 3 else 1.2)
    got = place_labels(texts, obstacles, rings=rings, step_mm=step)
    want = _plain_search(texts, obstacles, rings, step)
    assert [t.text for t in got] == [t.text for t in texts]
    for g, w in zip(got, want):
        assert g.position == pytest.approx(w.position, abs=1e-9), g.text


def test_a_label_in_a_crowd_moves_farther_out_or_stays():
    texts = [Text((1.0, 1.0), "ABCDEF", "labels") for _ in range(12)]
    got = place_labels(texts, [shapely.box(-40, -40, 40, 40)], rings=2)
    assert got == tuple(_plain_search(texts, [shapely.box(-40, -40, 40, 40)], 2))
    assert len({t.position for t in got}) > 1 and got[0].position == (1.0, 1.0)
