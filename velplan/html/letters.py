"""The letters of a plan at every position of the page, placed together.

`velplan.views.plan.image_letters` places one position's letters with `place_labels`: each
letter, in order, takes the first spot of rings around its wanted one whose box meets no
line or dot of the plan and no letter placed before it; where none is free, the spot clear of
the letters that meets the fewest. Here the same choice is made for all positions at once:
letter k of every position in one pass, the spots examined ring by ring (as `place_labels`
does) only where no free spot was found yet. The obstacles are the plan's lines 0.5 mm wide
each way and its dots 0.3 mm round, as capsules (a segment and a radius), met exactly; shapely
approximates their round ends by polygons, so a box grazing one (within 10⁻³ mm) may read
otherwise there.
"""

from __future__ import annotations

import numpy as np

from velplan.render.scene import Circle, Text
from velplan.views.base import _LABEL_STAGES, _farther, _moved, spots_of, upright_offsets

#: Half-width of a line and clearance round a dot that a letter keeps off, mm (as
#: `image_letters` buffers them).
LINE_CLEAR_MM, DOT_CLEAR_MM = 0.5, 0.3
#: Padding round a letter's enlarged box, mm (as `place_labels`).
PAD_MM = 0.4
#: Rings of spots a letter tries round its wanted spot (as `image_letters` without leaders).
RINGS = 8


def capsules(lines, circles: list[Circle]) -> np.ndarray:
    """The obstacles as capsules, shape (m, 5): start x, y, end x, y, radius, mm."""
    seg = np.array(lines, float).reshape(-1, 4)
    dots = np.array([(*c.centre, *c.centre, c.radius + DOT_CLEAR_MM) for c in circles], float).reshape(-1, 5)
    return np.vstack([np.column_stack([seg, np.full(len(seg), LINE_CLEAR_MM)]), dots])


def _slab(x0, y0, x1, y1, ax, ay, dx, dy) -> np.ndarray:
    """Whether each segment a + t·d, 0 ≤ t ≤ 1, meets each box [x0, x1] × [y0, y1] (closed)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # a flat or tiny step: ±inf
        lo, hi = np.zeros(len(ax)), np.ones(len(ax))
        for a, d, b0, b1 in ((ax, dx, x0, x1), (ay, dy, y0, y1)):
            t0, t1 = (b0 - a) / d, (b1 - a) / d
            inside = (b0 <= a) & (a <= b1)
            flat = d == 0
            lo = np.maximum(lo, np.where(flat, np.where(inside, -np.inf, np.inf), np.minimum(t0, t1)))
            hi = np.minimum(hi, np.where(flat, np.where(inside, np.inf, -np.inf), np.maximum(t0, t1)))
    return lo <= hi


def meets(boxes: np.ndarray, caps: np.ndarray) -> np.ndarray:
    """Whether box k (xmin, ymin, xmax, ymax) meets capsule k (`capsules`), for each k: the
    segment meets the box grown by the radius (two crosswise boxes and four corner discs)."""
    x0, y0, x1, y1 = boxes.T
    ax, ay, bx, by, r = caps.T
    dx, dy = bx - ax, by - ay
    hit = _slab(x0 - r, y0, x1 + r, y1, ax, ay, dx, dy) | _slab(x0, y0 - r, x1, y1 + r, ax, ay, dx, dy)
    dd = dx * dx + dy * dy
    safe = np.where(dd > 0, dd, 1.0)
    for cx, cy in ((x0, y0), (x1, y0), (x0, y1), (x1, y1)):
        with np.errstate(over="ignore"):  # a segment of a few ulp: its nearest point clipped to an end
            t = np.where(dd > 0, np.clip(((cx - ax) * dx + (cy - ay) * dy) / safe, 0.0, 1.0), 0.0)
        ex, ey = ax + t * dx - cx, ay + t * dy - cy
        hit |= ex * ex + ey * ey <= r * r
    return hit


def _overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Whether boxes `a` (…, 4) and `b` (…, 4) overlap, closed intervals, broadcast."""
    return ((a[..., 0] <= b[..., 2]) & (b[..., 0] <= a[..., 2])
            & (a[..., 1] <= b[..., 3]) & (b[..., 1] <= a[..., 3]))


def _cap_bounds(caps: np.ndarray) -> np.ndarray:
    r = caps[..., 4]
    return np.stack([np.minimum(caps[..., 0], caps[..., 2]) - r, np.minimum(caps[..., 1], caps[..., 3]) - r,
                     np.maximum(caps[..., 0], caps[..., 2]) + r, np.maximum(caps[..., 1], caps[..., 3]) + r], -1)


def _padded_stack(arrays: list[np.ndarray], width: int) -> np.ndarray:
    """(n, m, width) of the arrays (mᵢ, width), NaN past each one's rows (NaN meets nothing)."""
    out = np.full((len(arrays), max([len(a) for a in arrays] + [1]), width), np.nan)
    for k, a in enumerate(arrays):
        out[k, :len(a)] = a
    return out


def place_letters(frames: list[tuple[list[Text], np.ndarray]]) -> list[list[Text]]:
    """Per position ``(letters at their wanted spots, capsules)``: the letters placed, in order,
    as `place_labels` places them clear of the capsules (`RINGS` rings)."""
    caps = _padded_stack([c for _, c in frames], 5)
    cap_box = _cap_bounds(caps)
    most = max([len(t) for t, _ in frames] + [0])
    placed = np.full((len(frames), max(most, 1), 4), np.nan)
    out: list[list[Text]] = [[] for _ in frames]
    for k in range(most):
        rows = np.array([f for f, (t, _) in enumerate(frames) if len(t) > k])
        texts = [frames[f][0][k] for f in rows]
        spots = _all_spots(texts)
        offsets = offsets_of(texts)
        bounds = np.concatenate([spots + offsets[:, None, :2] - PAD_MM, spots + offsets[:, None, 2:] + PAD_MM], -1)
        crossings, apart, examined = _survey(bounds, caps[rows], cap_box[rows], placed[rows, :k])
        free = (crossings == 0) & apart & examined
        # the first free spot; else the one clear of the letters meeting the fewest lines; else -1
        fewest = np.where(apart.any(axis=1), np.where(apart, crossings, np.iinfo(int).max).argmin(axis=1), -1)
        spot = np.where(free.any(axis=1), free.argmax(axis=1), fewest)
        for a, f in enumerate(rows):
            j = int(spot[a])
            if j < 0:
                out[f].append(_crowded(texts[a], bounds[a], offsets[a], placed, f, k))
                continue
            placed[f, k] = bounds[a, j]
            out[f].append(texts[a] if j == 0 else _moved(texts[a], position=tuple(spots[a, j].tolist())))
    return out


def _all_spots(texts: list[Text]) -> np.ndarray:
    """`_spots` of every letter (`RINGS` rings), shape (n, spots, 2)."""
    return spots_of(texts, RINGS)


def offsets_of(texts: list[Text]) -> np.ndarray:
    """The enlarged box of every letter as offsets (x0, y0, x1, y1) from its spot, mm, shape
    (n, 4), as `place_labels` makes it."""
    if any(t.rotation_deg != 0.0 for t in texts):
        raise ValueError("a plan's letters are upright")
    return upright_offsets(texts)


def _survey(bounds, caps, cap_box, placed):
    """Per position and spot: obstacles met, clear of the placed letters, examined; the spots
    examined stage by stage (`_LABEL_STAGES`) where no free spot was found before."""
    n, s = bounds.shape[:2]
    crossings = np.zeros((n, s), dtype=int)
    apart = np.ones((n, s), dtype=bool)
    examined = np.zeros((n, s), dtype=bool)
    todo = np.arange(n)
    start = 0
    for stop in [x for x in _LABEL_STAGES if x < s] + [s]:
        b = bounds[todo, start:stop]
        near = _overlap(b[:, :, None, :], cap_box[todo][:, None, :, :])
        i, j, m = np.nonzero(near)
        hit = meets(b[i, j], caps[todo[i], m])
        np.add.at(crossings, (todo[i[hit]], start + j[hit]), 1)
        apart[todo, start:stop] = ~_overlap(b[:, :, None, :], placed[todo][:, None, :, :]).any(axis=2)
        examined[todo, start:stop] = True
        free = ((crossings[todo, start:stop] == 0) & apart[todo, start:stop]).any(axis=1)
        todo = todo[~free]
        if not len(todo):
            break
        start = stop
    return crossings, apart, examined


def _crowded(text: Text, bounds, offsets, placed, f: int, k: int) -> Text:
    """`text` with no spot clear of the letters placed before it: the first spot farther out
    clear of them, else where it was (as `place_labels`); its box into ``placed[f, k]``."""
    import shapely

    others = [shapely.box(*b) for b in placed[f, :k]]
    _, spot, box = _farther(text, *offsets, 0.5 * text.size_mm, RINGS, others)
    if spot is None:
        placed[f, k] = bounds[0]
        return text
    placed[f, k] = shapely.bounds(box)
    return _moved(text, position=(float(spot[0]), float(spot[1])))
