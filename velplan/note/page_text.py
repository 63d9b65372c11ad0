"""The lettering of a figure drawn for the page: a view shrunk to the note's text width keeps
its text at 2.5 mm printed (`velplan.note.figures.for_page` enlarges it about its anchor), and
here the layout makes room for the larger letters: lines of a block (a title over its scales,
the notes under a force plan) spaced by their real height, a number or label that the larger
letters run into moved clear, and the figure's box grown to hold every text."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Text
from velplan.render.shapes import text_box
from velplan.views.base import bounds_of, place_labels, shift

LINE_GAP = 2.2
"""Two texts are lines of one block when their baselines are at most this many text heights
apart (the views write theirs 1.5–1.8 heights apart)."""
MARGIN_MM = 1.0
"""Room kept round the outermost text of a figure, figure mm."""
OVERLAP_MM2 = 0.1
"""Texts whose estimated boxes share more than this, mm², are moved apart."""
_NUMBER = re.compile(r"^[−\-+]?[\d.,]+$")


def settle(before, after, shrink: float = 1.0) -> list:
    """``after`` (the primitives of ``before`` with their text enlarged for the page, printed
    at ``shrink``) with the blocks of lines re-spaced and the texts that now overlap moved
    apart."""
    items = _respace_blocks(list(before), list(after), shrink)
    return _apart(items)


def boxed(items, width: float, height: float) -> tuple[list, float, float]:
    """``items`` moved so that every text lies inside the figure's box, which grows (on the
    side a text runs out of) from ``width`` × ``height`` mm; returns (items, width, height)."""
    boxes = [rendered_box(p) for p in items if isinstance(p, Text)]
    if not boxes:
        return items, width, height
    x0, y0 = np.min([b.min(axis=0) for b in boxes], axis=0)
    x1, y1 = np.max([b.max(axis=0) for b in boxes], axis=0)
    left, bottom = max(0.0, MARGIN_MM - x0), max(0.0, MARGIN_MM - y0)
    right, top = max(0.0, x1 + MARGIN_MM - width), max(0.0, y1 + MARGIN_MM - height)
    if left or bottom:
        items = [shift(p, left, bottom) for p in items]
    return items, width + left + right, height + bottom + top


def rendered_box(text: Text) -> np.ndarray:
    """Corners of the box `text` may take when rendered, mm: its estimated box 1.25 times
    wider and 1.1 times taller about its anchor (glyphs such as ⊥ and Δ run wider than the
    estimate)."""
    position = np.asarray(text.position, float)
    return position + (text_box(text) - position) * (1.25, 1.1)


def _block_of(texts: list[tuple[int, Text]]) -> list[list[int]]:
    """The blocks of lines among upright ``texts`` (index, text): texts on one baseline
    column (same x and anchor), each line within `LINE_GAP` heights of the next, top first."""
    columns: dict = {}
    for i, t in texts:
        columns.setdefault((round(t.position[0], 2), t.anchor), []).append((i, t))
    blocks = []
    for column in columns.values():
        column.sort(key=lambda it: -it[1].position[1])
        run = [column[0][0]]
        for (_, upper), (j, lower) in zip(column, column[1:]):
            if upper.position[1] - lower.position[1] <= LINE_GAP * max(upper.size_mm, lower.size_mm):
                run.append(j)
            else:
                blocks.append(run)
                run = [j]
        blocks.append(run)
    return [b for b in blocks if len(b) > 1]


def _respace_blocks(before: list, after: list, shrink: float) -> list:
    """Each block of lines spaced in proportion to its enlarged lettering, a line of several
    statements (``"μ = …;  μφ = …"``) broken into one line each: the line nearest the
    drawing stays, the others move away from it (a title block over a diagram grows upwards,
    notes under a plan grow downwards)."""
    lines = [(i, t) for i, t in enumerate(before) if isinstance(t, Text) and t.rotation_deg == 0.0
             and t.baseline == "baseline" and not _NUMBER.match(t.text.strip())]
    drawing = [p for p in before if not isinstance(p, Text)]
    middle = 0.5 * (bounds_of(drawing)[1] + bounds_of(drawing)[3]) if drawing else 0.0
    out, extra = list(after), []
    for block in _block_of(lines):
        ys = [before[i].position[1] for i in block]  # top first
        grow = [after[i].size_mm / before[i].size_mm for i in block]
        parts = [_statements(after[i], shrink) if grow[k] > SPLIT_GROWTH else [after[i].text]
                 for k, i in enumerate(block)]
        pitch = [PITCH * after[i].size_mm for i in block]
        steps = [(ys[k] - ys[k + 1]) * max(grow[k], grow[k + 1]) + (len(parts[k]) - 1) * pitch[k]
                 for k in range(len(block) - 1)]
        if min(ys) >= middle:  # above the drawing: the lowest line stays
            new = [ys[-1] + sum(steps[k:]) + (len(parts[-1]) - 1) * pitch[-1] for k in range(len(block))]
        else:  # beside or below it: the top line stays
            new = [ys[0] - sum(steps[:k]) for k in range(len(block))]
        for k, (i, y) in enumerate(zip(block, new)):
            out[i] = replace(out[i], text=parts[k][0], position=(out[i].position[0], y))
            extra += [replace(out[i], text=part, position=(out[i].position[0], y - j * pitch[k]))
                      for j, part in enumerate(parts[k][1:], 1)]
    return out + extra


SPLIT_GROWTH = 1.1
"""Only a line enlarged by more than this for the page is broken (a view drawn for the page
breaks its own lines)."""
SPLIT_MM = 80.0
"""A line of several statements printed wider than this, mm, is broken into one line each."""
PITCH = 1.6
"""Baselines of the lines a statement block is broken into, text heights apart."""


def _statements(text: Text, shrink: float) -> list[str]:
    """The statements of a line written ``"a;  b;  c"`` (two spaces after each semicolon), one
    line each where the line prints wider than `SPLIT_MM`."""
    box = rendered_box(text)
    if ";  " not in text.text or (box[:, 0].max() - box[:, 0].min()) * shrink <= SPLIT_MM:
        return [text.text]
    return [s.strip() for s in text.text.split(";  ")]


def _apart(items: list) -> list:
    """The texts that overlap moved apart: the later of two overlapping texts is placed again
    (`place_labels`) clear of the other texts and of the lines, unless it heads a block
    (then the earlier one moves)."""
    texts = [i for i, p in enumerate(items) if isinstance(p, Text)]
    boxes = [label_box(items[i]) for i in texts]  # kept up to date as texts move
    lines = None  # the drawn lines do not move: made once, where a text has to
    for _ in range(3):
        tree = shapely.STRtree(boxes)
        movers = set()
        for a, box in enumerate(boxes):
            for b in tree.query(box, predicate="intersects"):
                if b > a and int(b) not in movers and a not in movers \
                        and box.intersection(boxes[b]).area > OVERLAP_MM2:
                    movers.add(_mover(items[texts[a]], items[texts[b]], a, int(b)))
        if not movers:
            break
        lines = _lines(items) if lines is None else lines
        for k in sorted(movers):
            others = [boxes[j] for j in range(len(texts)) if j != k]
            moved, = place_labels([items[texts[k]]], others + lines)
            items[texts[k]] = moved
            boxes[k] = label_box(moved)
    return items


def _mover(a: Text, b: Text, i: int, j: int) -> int:
    """Which of two overlapping texts moves: a label rather than a number on an axis, the
    smaller rather than the larger, else the later."""
    numbers = [bool(_NUMBER.match(t.text.strip())) for t in (a, b)]
    if numbers[0] != numbers[1]:
        return j if numbers[0] else i
    if a.size_mm != b.size_mm:
        return i if a.size_mm < b.size_mm else j
    return j


def _lines(items) -> list:
    """The drawn lines of ``items`` as shapely geometries (what a moved label keeps clear of)."""
    from velplan.render.scene import Arrow, Circle, Polygon, Polyline

    out = []
    for p in items:
        if isinstance(p, (Polyline, Polygon)) and len(p.points) >= 2:
            out.append(shapely.LineString(np.asarray(p.points, float)))
        elif isinstance(p, Arrow):
            out.append(shapely.LineString([p.start, p.end]))
        elif isinstance(p, Circle):
            out.append(shapely.Point(p.centre).buffer(p.radius).exterior)
    return out
