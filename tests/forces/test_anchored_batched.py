"""`place_anchored` costs an upright label's spots a stage at a time with shapely's array
functions (`_best_upright`); it must choose exactly what costing one spot at a time
(`_best_each`, the path rotated labels take) chooses, on random crowds of labels, lines and
anchors, with and without leaders."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from velplan.render.layout import label_box
from velplan.render.scene import Text
from velplan.views.forces import anchored

WORDS = ("A", "B₁", "F₃₂", "G₄", "M_b", "R₁₂", "φ", "Pᵢₙ", "12", "O₂B")


def _crowd(seed: int, n_labels: int, n_lines: int, rotated: bool, side: float = 40.0):
    """Labels crowded into a square of `side` mm over random lines, each naming a point or a
    segment."""
    rng = np.random.default_rng(seed)
    texts, anchors, kinds = [], [], []
    for _ in range(n_labels):
        x, y = rng.uniform(0.0, side, 2)
        texts.append(Text((float(x), float(y)), str(rng.choice(WORDS)), "t", float(rng.choice([2.5, 3.5, 5.0])),
                          anchor=str(rng.choice(["start", "middle", "end"])),
                          baseline=str(rng.choice(["baseline", "middle", "top"])),
                          rotation_deg=float(rng.choice([0.0, 0.0, 30.0, -90.0])) if rotated else 0.0,
                          width_factor=float(rng.choice([1.0, 0.8]))))
        ax, ay = x + rng.normal(0.0, 3.0), y + rng.normal(0.0, 3.0)
        if rng.random() < 0.5:
            anchors.append(shapely.Point(ax, ay))
            kinds.append("point")
        else:
            anchors.append(shapely.LineString([(ax, ay), (ax + rng.normal(0, 10), ay + rng.normal(0, 10))]))
            kinds.append("force")
    lines = [shapely.LineString(rng.uniform(-5.0, side + 5.0, (2, 2))) for _ in range(n_lines)]
    obstacles = [g.buffer(float(rng.choice([0.2, 0.5]))) for g in lines] + [None, shapely.Point()]
    return texts, anchors, kinds, obstacles


def _both(*args, **kwargs):
    """(labels placed, costs chosen) with the upright labels' spots costed a stage at a time,
    and the same with every spot costed one at a time."""
    runs = []
    for best in (anchored._best_upright, anchored._best_each):
        costs = []

        def recorded(*a, best=best, costs=costs):
            chosen = best(*a)
            costs.append(chosen[0])
            return chosen

        with pytest.MonkeyPatch.context() as m:
            m.setattr(anchored, "_best_upright", recorded)
            runs.append((anchored.place_anchored(*args, **kwargs), costs))
    return runs


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n_labels=st.integers(1, 14), n_lines=st.integers(0, 25),
       rotated=st.booleans(), leaders=st.booleans(), side=st.sampled_from([4.0, 15.0, 40.0]),
       rings=st.integers(1, 6))
def test_batched_costing_chooses_as_one_spot_at_a_time(seed, n_labels, n_lines, rotated, leaders, side, rings):
    texts, anchors, kinds, obstacles = _crowd(seed, n_labels, n_lines, rotated, side)
    batched, each = _both(texts, anchors, kinds, obstacles, rings=rings,
                          leader_layer="thin-lines" if leaders else None)
    assert batched == each  # the same labels at the same places, the same leaders


def test_the_crowds_move_labels_and_draw_leaders():
    """The random crowds exercise every part of the cost: labels moved off lines and off each
    other, labels left on a line, leaders drawn."""
    moved = leaders = 0
    costs = []
    for seed in range(12):
        for side, rings in ((40.0, 6), (4.0, 1)):
            texts, anchors, kinds, obstacles = _crowd(seed, 14, 25, False, side)
            batched, each = _both(texts, anchors, kinds, obstacles, rings=rings, leader_layer="thin-lines")
            assert batched == each
            moved += sum(a.position != b.position for a, b in zip(texts, batched[0]))
            leaders += len(batched[0]) - len(texts)
            costs += batched[1]
    parts = {(c // 4000, c % 1000 // 100) for c in costs}  # text over text; lines through letters
    assert moved > 50 and leaders > 0
    assert (0, 0) in parts and any(p[0] >= 1 and p[1] == 0 for p in parts) and any(p[1] > 0 for p in parts)


@given(seed=st.integers(0, 2**32 - 1))
@settings(max_examples=30, deadline=None)
def test_upright_boxes_are_label_boxes(seed):
    texts, *_ = _crowd(seed, 6, 0, False)
    for text in texts:
        spots = anchored._spots(text, 2)
        boxes = anchored._upright_boxes(text, np.array(spots, float))
        for spot, box in zip(spots, boxes):
            assert box.equals_exact(label_box(Text(spot, text.text, text.layer, text.size_mm, anchor=text.anchor,
                                                   baseline=text.baseline, width_factor=text.width_factor)), 0.0)
