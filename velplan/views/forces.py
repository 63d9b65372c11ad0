"""Views of the force-analysis sheet: the structural groups separated out with the forces
applied to them, their force polygons (plans of forces), Zhukovsky's lever, the table of
the three balancing moments and the diagram M_b(φ).

What each view draws, as a course sheet does (METHOD.md §5, §7):

* **A group with its forces** (:func:`group_view`): the links of one Assur group (or of the
  initial link) at a standard μl, cut free of the frame and of their neighbours; every force
  acting on them — loads, gravity G, inertia Φ, the components of the reactions into which
  the polygon decomposes them (R12τ, R12n, …) and the reactions of the groups solved before —
  as an arrow of a conventional length from its point of application, the couples (M_Φ, and
  M_b on the crank) as curved arrows. Forces are not drawn to scale here; the polygon is.
* **A force polygon** (:func:`polygon_view`): the known vectors head to tail from the pole at
  a standard μF (N/mm), then the two unknown reactions found where the lines of their known
  directions meet (thin construction lines through the last vertex and through the pole); the
  found vectors thick. Vertices are `ForcePolygon.vertices`.
* **Zhukovsky's lever** (:func:`lever_view`): the velocity plan turned by 90° (counter-
  clockwise, as `velplan.forces.lever` turns it), every force carried to the image of its
  point with its own direction, a couple replaced by a pair of forces at the images of two
  points of its link, and the balancing force at the image of the crank tip; the balance is
  written under it: M_b by the lever against M_b by kinetostatics.
* **The table** (:func:`moments_table_view`) and **the diagram** (:func:`moment_diagram_view`)
  of M_b over the revolution.

Layers: ``fgroup-K-G`` (links), ``fgroup-K-G-forces``, ``fgroup-K-G-labels`` for group G at
position K; ``fpoly-K-G``, ``fpoly-K-G-lines``, ``fpoly-K-G-labels`` for its polygon;
``lever-K``, ``lever-K-forces``, ``lever-K-labels``; ``table``; ``mb-diagram``,
``mb-diagram-labels``. A group's name is written in layer names with characters outside
``[a-z0-9-]`` replaced by ``-``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import shapely

from velplan.forces.kinetostatics import reaction_label
from velplan.mechanism.structure import pairs
from velplan.plans.text import label_of
from velplan.render.i18n import label
from velplan.views.mechanism import BLOCK_MM, _Geometry, plate_corners
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.render.shapes import text_extent
from velplan.views.table import grid_table
from velplan.render.symbols import (
    JOINT_RADIUS_MM, link, revolute_joint, rotation_arrow, slider_block)
from velplan.views.base import (
    View, axis_numbers_clear, bounds_of, digits_down, fixed, make_view, place_labels, scale_mark,
    scale_text, subscript, unit)
from velplan.views.base import number as _num

#: Polygon vectors shorter than this share one label with their neighbours, mm.
SHORT_VECTOR_MM = 2.5
#: Construction lines run this far past the points they join, mm.
LINE_OVERRUN_MM = 8.0
#: Reaction components ("R12τ") drop these suffixes to find their pair.
_SUFFIXES = "τn∥⊥"


@dataclass(frozen=True)
class ForceSizes:
    """Text heights and the conventional length of a force arrow, mm; ``wrap_balance``: write
    the lever's balance on two lines where it is wider than the lever (small formats)."""

    title_mm: float = 5.0
    label_mm: float = 3.5
    arrow_mm: float = 16.0
    wrap_balance: bool = False


# -- names and small helpers -------------------------------------------------------------


def slug(name: str) -> str:
    """A group's name as it appears in layer and view names (``"3-4"`` → ``"3-4"``)."""
    return re.sub(r"[^a-z0-9-]+", "-", name.lower()).strip("-") or "g"


def group_layers(number: int, group: str) -> tuple[str, str, str]:
    """(links, forces, labels) layers of a group drawn at position `number`."""
    base = f"fgroup-{number}-{slug(group)}"
    return base, f"{base}-forces", f"{base}-labels"


def polygon_layers(number: int, group: str) -> tuple[str, str, str]:
    """(vectors, construction lines, labels) layers of a group's force polygon."""
    base = f"fpoly-{number}-{slug(group)}"
    return base, f"{base}-lines", f"{base}-labels"


def lever_layers(number: int) -> tuple[str, str, str]:
    """(lever, forces, labels) layers of Zhukovsky's lever at position `number`."""
    base = f"lever-{number}"
    return base, f"{base}-forces", f"{base}-labels"


def force_text(name: str) -> str:
    """A force's label as written: digits as subscripts (``"R12τ"`` → ``"R₁₂τ"``); a force
    of the pair replacing a couple on the lever (``"MΦ4@B"``) → ``"F(MΦ₄)"``."""
    if "@" in name:
        return f"F({digits_down(name.split('@', 1)[0])})"
    return digits_down(name)


def newton(lang: str) -> str:
    return label("unit_newton", lang)


def newton_metre(lang: str) -> str:
    return label("unit_newton_metre", lang)


def _xy(z: complex) -> np.ndarray:
    return np.array([float(np.real(z)), float(np.imag(z))])


def _unit_vec(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def _anchor(u) -> str:
    return "start" if u[0] > 0.35 else ("end" if u[0] < -0.35 else "middle")


def _busy_angles(centre, segments) -> list[float]:
    """Directions (deg) of the lines that leave `centre`, or pass by it."""
    out = []
    c = np.asarray(centre, float)
    for a, b in segments:
        a, b = np.asarray(a, float), np.asarray(b, float)
        for here, other in ((a, b), (b, a)):
            if np.hypot(*(here - c)) < 0.8 and np.hypot(*(other - here)) > 1e-9:
                d = other - here
                out.append(math.degrees(math.atan2(d[1], d[0])))
    return out


def _free_angle(busy: list[float]) -> float:
    """The direction (deg, a multiple of 5) farthest from every busy direction."""
    if not busy:
        return 45.0
    best, gap = 45.0, -1.0
    for k in range(72):
        cand = 5.0 * k
        g = min(abs((cand - b + 180.0) % 360.0 - 180.0) for b in busy)
        if g > gap + 1e-9:
            best, gap = cand, g
    return best


def _moment_arc(centre, value: float, text: str, busy: list[float], *, radius: float,
                layer: str, text_layer: str, size: float) -> tuple[list[Primitive], Text]:
    """A curved arrow about `centre` in the sense of `value` (counter-clockwise positive),
    centred on the freest direction, and its label beyond the arc."""
    mid = _free_angle(busy)
    sweep = 110.0 if value >= 0 else -110.0
    arc = rotation_arrow(np.asarray(centre, float), radius, mid - sweep / 2, sweep, layer=layer)
    a = math.radians(mid)
    u = np.array([math.cos(a), math.sin(a)])
    where = np.asarray(centre, float) + u * (radius + 1.2 + 0.6 * size)
    return list(arc), Text(where, text, text_layer, size, _anchor(u), "middle")


def place_arrows(entries, length: float, obstacles=(), points=(), texts=(), *,
                 layer: str = "labels", size: float = 3.5) -> list[tuple]:
    """Force arrows of a conventional length at their points, each drawn either from its
    point (tail there) or into it (head there), and lengthened when that keeps it — and its
    label — off what is already drawn (links, other arrows, other points), as a draughtsman
    would. Forces at one point in one direction are drawn along one line from it, each
    longer than the one before, so that every head shows.

    Parameters
    ----------
    entries : sequence of (point, unit direction, label)
        Points and directions in mm.
    length : float
        Conventional length, mm.
    obstacles : iterable of shapely geometry
        What the shafts should not run along.
    points : iterable of (x, y)
        Points the shafts should keep clear of (other than their own), mm.
    texts : iterable of Text
        Labels already written, which the new labels should keep clear of.
    layer, size : str, float
        Layer and text height of the labels.

    Returns
    -------
    list of (start, end, Text)
        The arrow and its label, beyond its free end.
    """
    from velplan.render.layout import label_box

    fixed_parts = [o for o in obstacles if o is not None]
    marks = [np.asarray(q, float) for q in points]
    drawn: list[tuple] = []  # (point, direction, orientation, span, geometry)
    boxes = [label_box(t).buffer(0.5) for t in texts]
    # forces that share a point and a direction go first (they stack along one line), so
    # that a lone opposite force finds the other side of the point taken
    pts = [np.asarray(e[0], float) for e in entries]
    dirs = [np.asarray(e[1], float) for e in entries]
    mates = [sum(1 for q, w in zip(pts, dirs) if np.hypot(*(q - p)) < 0.5 and float(w @ u) > 0.995)
             for p, u in zip(pts, dirs)]
    order = sorted(range(len(entries)), key=lambda j: (-mates[j], j))
    out: dict[int, tuple] = {}
    for idx in order:
        p, u, text = entries[idx]
        p, u = np.asarray(p, float), np.asarray(u, float)
        near = [shapely.Point(q).buffer(2.5) for q in marks if np.hypot(*(q - p)) > 1.0]
        lines = fixed_parts + near
        best = None
        for step, mult in enumerate((1.0, 1.6, 2.2, 2.8)):
            span = length * mult
            arrows = [geom for q, w, kk, sp, geom in drawn
                      if not (np.hypot(*(q - p)) < 0.5 and float(w @ u) > 0.995 and kk == 0
                              and span >= sp + 0.45 * length)]
            for k, (a, b) in enumerate(((p, p + u * span), (p - u * span, p))):
                shaft = shapely.LineString([a, b])
                over = sum(shaft.intersection(g).length for g in lines if g.intersects(shaft))
                over += 3.0 * sum(shaft.intersection(g).length for g in arrows
                                  if g.intersects(shaft))
                free, out_dir = (b, u) if k == 0 else (a, -u)
                for spot, tag in enumerate(_label_spots(p, free, out_dir, text, layer, size)):
                    box = label_box(tag)
                    crowded = any(g.intersects(box) for g in lines + arrows + boxes)
                    cost = over + 3.0 * step + (5.0 if crowded else 0.0) + 0.8 * spot + 0.01 * k
                    if best is None or cost < best[0] - 1e-9:
                        best = (cost, a, b, k, span, tag)
        _, a, b, k, span, tag = best
        out[idx] = (a, b, tag)
        drawn.append((p, u, k, span, shapely.LineString([a, b]).buffer(0.8)))
        boxes.append(label_box(tag).buffer(0.5))
    return [out[idx] for idx in range(len(entries))]


def _arrow_obstacle(a: Arrow):
    if a.length < 1e-9:
        return None
    return shapely.LineString([a.start, a.end]).buffer(0.6)


def _label_spots(point, free, u, text: str, layer: str, size: float) -> list[Text]:
    """Where an arrow's label may go: beyond its free end, else beside the shaft near the
    free end, on either side."""
    point, free = np.asarray(point, float), np.asarray(free, float)
    out = [_end_label(free, u, text, layer, size)]
    near = point + 0.7 * (free - point)
    for side in (1.0, -1.0):
        n = side * np.array([-u[1], u[0]])
        out.append(Text(near + n * (1.0 + 0.6 * size), text, layer, size, _anchor(n), "middle"))
    return out


def _end_label(at, u, text: str, layer: str, size: float) -> Text:
    """A label beyond the free end `at` of an arrow pointing along `u` there."""
    gap = 1.0 + (0.55 * size if _anchor(u) == "middle" else 0.3 * size)
    return Text(np.asarray(at, float) + u * gap, text, layer, size, _anchor(u), "middle")


def _title_lines(items, lines: list[tuple[str, float]], layer: str) -> list[Text]:
    """Title lines stacked above everything in `items` (first line on top)."""
    x0, _, _, y1 = bounds_of(items)
    out = []
    y = y1 + 3.0
    for text, size in reversed(lines):
        out.append(Text((x0, y), text, layer, size))
        y += 1.6 * size
    return out


def _note_lines(items, lines: list[tuple[str, float]], layer: str) -> list[Text]:
    """Lines written under everything in `items`."""
    x0, y0, _, _ = bounds_of(items)
    out = []
    y = y0 - 2.0
    for text, size in lines:
        y -= size
        out.append(Text((x0, y), text, layer, size))
        y -= 0.6 * size
    return out


# -- where each force acts ---------------------------------------------------------------


def application_points(fa, i: int) -> dict[str, complex]:
    """Label of every force of the analysis → its point of application at position index
    `i`, m (complex): loads, gravity and inertia at their points, a reaction (either sense)
    at its joint or, for a prismatic pair, where its resultant crosses the guide line."""
    kin = fa.kinematics
    out: dict[str, complex] = {}
    for f in fa.actions.forces:
        x, y = kin.position(f.point)[i]
        out[f.label] = complex(x, y)
    for rc in fa.kinetostatics.reactions.values():
        at = complex(rc.at[i])
        if not np.isfinite(at):
            at = complex(rc.reference[i])
        k0, k1 = rc.pair.links
        out.setdefault(rc.label, at)
        out.setdefault(reaction_label(k0, k1), at)
    return out


def _point_of(points: dict[str, complex], name: str) -> complex:
    if name in points:
        return points[name]
    if name and name[-1] in _SUFFIXES and name[:-1] in points:
        return points[name[:-1]]
    raise KeyError(name)


def group_forces(fa, group: str, i: int) -> list[tuple[str, complex, complex]]:
    """(label, point m, force N) of every force on the group `group` (or ``"crank"``) at
    position index `i`, in the order of its polygon; zero forces left out."""
    poly = fa.kinetostatics.polygons[group]
    points = application_points(fa, i)
    parts = list(poly.vectors) + list(poly.closing_vectors)
    scale = max([abs(complex(v[i])) for _, v in parts if np.isfinite(v[i])] or [0.0])
    out = []
    for name, v in parts:
        f = complex(v[i])
        if not np.isfinite(f) or abs(f) <= 1e-9 * max(scale, 1e-300):
            continue
        out.append((name, _point_of(points, name), f))
    return out


def group_links(mech, group: str) -> tuple[str, ...]:
    if group == "crank":
        return (mech.crank.link,)
    return tuple(next(g for g in mech.groups if g.name == group).links)


def group_extent_m(fa, group: str, i: int) -> tuple[float, float]:
    """Width and height of the group's points and points of application, m."""
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    from velplan.mechanism.structure import material_points

    links = group_links(mech, group)
    mp = material_points(mech)
    pts = [complex(*kin.position(p)[i]) for lk in links for p in mp.get(lk, ())]
    pts += [z for _, z, _ in group_forces(fa, group, i)]
    pts = np.array([z for z in pts if np.isfinite(z)])
    return float(np.ptp(pts.real)), float(np.ptp(pts.imag))


# -- a group with its forces -------------------------------------------------------------


def group_view(fa, group: str, i: int, *, mu_l: float, number: int, lang: str = "ru",
               sizes: ForceSizes = ForceSizes()) -> View:
    """One Assur group (or ``"crank"``, the initial link) with every force on it.

    Parameters
    ----------
    fa : ForceAnalysis
        The analysis at the sheet's positions.
    group : str
        Group name, or ``"crank"``.
    i : int
        Position index into `fa`.
    mu_l : float
        Length scale, m/mm.
    number : int
        Position number (1-based) written in the title and the layer names.

    Returns
    -------
    View
        ``mu`` is μl, ``to_view`` maps metres to the view's mm; ``meta["forces"]`` holds
        (label, point m, force N) of the drawn arrows, ``meta["arrows"]`` their count,
        ``meta["couples"]`` (label, centre in content mm, moment N·m) of the curved arrows.
    """
    mech, kin, ks = fa.kinetostatics.mechanism, fa.kinematics, fa.kinetostatics
    links = group_links(mech, group)
    body_layer, force_layer, text_layer = group_layers(number, group)
    geo = _Geometry(mech, kin)
    mm = lambda xy: np.asarray(xy, float) / mu_l  # noqa: E731 - content mm
    items: list[Primitive] = []
    obstacles: list = []
    lines: list[tuple[np.ndarray, np.ndarray]] = []
    axes: list = []

    # the links: lines, blocks, joints, the guides they ride on as axes
    segs = [s for s in geo.segments(i) if s.link in links]
    for plate, corners in geo.plates(i):
        if plate in links:
            items += plate_corners(mm(corners), layer=body_layer)
    for s in segs:
        a, b = mm(s.a), mm(s.b)
        items += link(a, b, trim_a_mm=JOINT_RADIUS_MM if s.joints[0] else 0.0,
                      trim_b_mm=JOINT_RADIUS_MM if s.joints[1] else 0.0, layer=body_layer)
        if np.hypot(*(b - a)) > 1e-9:
            obstacles.append(shapely.LineString([a, b]).buffer(0.6))
            lines.append((a, b))
    for rc in ks.reactions.values():
        p = rc.pair
        if p.kind != "P" or sum(lk in links for lk in p.links) != 1:
            continue
        u = _xy(rc.direction[i])
        c = mm(_xy(rc.reference[i]))
        half = BLOCK_MM[0] / 2 + 7.0
        axis = Polyline([c - u * half, c + u * half], body_layer, "axis")
        items.append(axis)
        # forces along a guide are drawn on its axis: it keeps labels off, not arrows
        axes.append(shapely.LineString(axis.points).buffer(0.4))
    for bl in geo.blocks(i):
        if bl.link not in links:
            continue
        body = slider_block(mm(bl.centre), math.degrees(bl.angle), length_mm=BLOCK_MM[0],
                            width_mm=BLOCK_MM[1], layer=body_layer)
        items += body
        obstacles.append(shapely.Polygon(body[0].points).buffer(0.8))
    joints = []
    for p in pairs(mech):
        if p.kind == "R" and any(lk in links for lk in p.links) and p.point not in joints:
            joints.append(p.point)
    for name in joints:
        c = mm(kin.position(name)[i])
        items += revolute_joint(c, layer=body_layer)
        obstacles.append(shapely.Point(c).buffer(JOINT_RADIUS_MM + 0.5))
    centres = [m.centre for m in mech.masses if m.link in links]
    for name in centres:
        c = mm(kin.position(name)[i])
        if any(np.hypot(*(c - mm(kin.position(j)[i]))) < 1.0 for j in joints):
            continue
        items.append(Circle(c, 1.0, body_layer, "thin", "solid"))
        obstacles.append(shapely.Point(c).buffer(1.5))

    # letters of the points, then the forces: arrows of a conventional length at their points
    letters = _point_letters(kin, i, mm, joints + centres + [
        p for p in dict.fromkeys(f.point for f in fa.actions.forces if f.link in links)],
        lines, text_layer, sizes.label_mm)
    forces = group_forces(fa, group, i)
    entries = [(mm(_xy(z)), _unit_vec(_xy(f)), force_text(name)) for name, z, f in forces]
    force_labels: list[Text] = []
    marks = [mm(kin.position(q)[i]) for q in dict.fromkeys(
        joints + centres + [f.point for f in fa.actions.forces if f.link in links])]
    for a, b, tag in place_arrows(entries, sizes.arrow_mm, obstacles, marks, letters,
                                  layer=text_layer, size=sizes.label_mm):
        arrow = Arrow(a, b, force_layer, "thin")
        items.append(arrow)
        obstacles.append(_arrow_obstacle(arrow))
        lines.append((a, b))
        force_labels.append(tag)

    # couples: the inertia moments, and the balancing moment on the crank
    couples: list[tuple[str, np.ndarray, float]] = []
    for m in fa.actions.moments:
        if m.link not in links:
            continue
        value = float(m.moment[i])
        if not np.isfinite(value) or value == 0.0:
            continue
        centre = next((lm.centre for lm in mech.masses if lm.link == m.link), None)
        centre = centre or next(iter(p for p in kin.point_index
                                     if p in _points_of_link(mech, m.link)))
        couples.append((force_text(m.label), mm(kin.position(centre)[i]), value))
    if group == "crank":
        mb = float(ks.balancing_moment[i])
        couples.append((label("symbol_balancing_moment", lang),
                        mm(kin.position(mech.crank.pivot)[i]), mb))
    radius = max(4.5, 0.35 * sizes.arrow_mm)
    for text, c, value in couples:
        arc, tag = _moment_arc(c, value, text, _busy_angles(c, lines), radius=radius,
                               layer=force_layer, text_layer=text_layer, size=sizes.label_mm)
        items += arc
        obstacles += [shapely.LineString(a.points).buffer(0.5) for a in arc
                      if isinstance(a, Polyline)]
        force_labels.append(tag)

    items += place_labels(letters + force_labels,
                          [o for o in obstacles if o is not None] + axes, rings=10)

    head = (label("initial_link", lang).format(name=mech.crank.link) if group == "crank"
            else label("assur_group", lang).format(name=group))
    items += _title_lines(items, [
        (head, sizes.title_mm),
        (scale_text("μl", mu_l, "m/mm", lang)
         + f" ({scale_mark(mu_l, lang)})", sizes.label_mm)],
        text_layer)
    return make_view(f"group-{number}-{slug(group)}", items, pad_mm=2.0, mu=mu_l,
                     origin=(0.0, 0.0),
                     meta={"group": group, "number": number, "index": i,
                           "forces": tuple(forces), "arrows": len(forces),
                           "couples": tuple((t, tuple(c), v) for t, c, v in couples),
                           "arc_radius": radius})


def _points_of_link(mech, lk: str) -> tuple[str, ...]:
    from velplan.mechanism.structure import material_points

    return material_points(mech).get(lk, ())


def _point_letters(kin, i, mm, names, lines, layer, size) -> list[Text]:
    out: list[Text] = []
    placed: list[np.ndarray] = []
    for name in dict.fromkeys(names):
        p = mm(kin.position(name)[i])
        if not np.all(np.isfinite(p)) or any(np.hypot(*(p - q)) < 1.0 for q in placed):
            continue
        placed.append(p)
        away = np.zeros(2)
        for a, b in lines:
            for here, other in ((a, b), (b, a)):
                if np.hypot(*(here - p)) < 0.8 and np.hypot(*(other - here)) > 1e-9:
                    away -= _unit_vec(other - here)
        if np.hypot(*away) < 0.2:
            away = np.array([-1.0, 1.0])
        away = away / np.hypot(*away)
        pos = p + away * (JOINT_RADIUS_MM + 1.2 + 0.5 * size)
        out.append(Text(pos, subscript(name), layer, size, _anchor(away), "middle"))
    return out


# -- a force polygon ---------------------------------------------------------------------


def polygon_extent(poly, i: int) -> tuple[float, float]:
    """Width and height of the polygon's vertices at μF = 1 N/mm, i.e. N."""
    z = poly.vertices(1.0)[i]
    z = z[np.isfinite(z)]
    return float(np.ptp(z.real)), float(np.ptp(z.imag))


def polygon_view(fa, group: str, i: int, *, mu_f: float, number: int, lang: str = "ru",
                 sizes: ForceSizes = ForceSizes()) -> View:
    """The force polygon of `group` (or ``"crank"``) at position index `i`, at μF (N/mm).

    Returns
    -------
    View
        ``to_view`` maps polygon mm (pole at 0) to the view's mm; ``meta["vertices"]``
        holds the drawn vertices (complex, mm from the pole), ``meta["labels"]`` the vector
        labels in drawing order.
    """
    ks = fa.kinetostatics
    mech = ks.mechanism
    poly = ks.polygons[group]
    vec_layer, line_layer, text_layer = polygon_layers(number, group)
    z = np.asarray(poly.vertices(mu_f)[i])
    names = [n for n, _ in poly.vectors] + [n for n, _ in poly.closing_vectors]
    first_closing = len(poly.vectors)
    items: list[Primitive] = []
    obstacles: list = []
    # construction lines of the two unknown directions, crossing where they meet
    if len(poly.closing) == 2 and np.all(np.isfinite(z)):
        m = first_closing
        x = z[m + 1]
        for through, (_, d) in ((z[m], poly.closing[0]), (z[0], poly.closing[1])):
            u = complex(d[i])
            t = ((x - through) * u.conjugate()).real
            lo, hi = min(0.0, t) - LINE_OVERRUN_MM, max(0.0, t) + LINE_OVERRUN_MM
            seg = [_xy(through + u * lo), _xy(through + u * hi)]
            items.append(Polyline(seg, line_layer, "thin"))
            obstacles.append(shapely.LineString(seg).buffer(0.4))
    drawn: list[tuple[str, np.ndarray, np.ndarray, bool]] = []
    for k, name in enumerate(names):
        a, b = _xy(z[k]), _xy(z[k + 1])
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            continue
        if np.hypot(*(b - a)) < 1e-9:
            continue
        found = k >= first_closing
        arrow = Arrow(a, b, vec_layer, "thick" if found else "thin")
        items.append(arrow)
        obstacles.append(_arrow_obstacle(arrow))
        drawn.append((name, a, b, found))
    items.append(Circle((0.0, 0.0), 0.7, vec_layer, "thin", "solid"))
    # labels: beside each vector on the polygon's outer side; runs of short vectors share one
    pts = np.array([_xy(v) for v in z if np.isfinite(v)])
    area = (0.5 * float(np.sum(pts[:-1, 0] * pts[1:, 1] - pts[1:, 0] * pts[:-1, 1]))
            if len(pts) > 2 else 0.0)
    outward = -1.0 if area > 1e-6 else 1.0  # left of the direction, unless the polygon is ccw
    texts: list[Text] = []
    k = 0
    size = sizes.label_mm
    while k < len(drawn):
        name, a, b, _ = drawn[k]
        if np.hypot(*(b - a)) >= SHORT_VECTOR_MM:
            u = _unit_vec(b - a)
            n = outward * np.array([-u[1], u[0]])
            where = (a + b) / 2 + n * (0.9 + 0.45 * size)
            texts.append(Text(where, force_text(name), text_layer, size, _anchor(n), "middle"))
            k += 1
            continue
        run = [drawn[k]]
        while k + len(run) < len(drawn) and np.hypot(*(drawn[k + len(run)][2] - drawn[
                k + len(run)][1])) < SHORT_VECTOR_MM:
            run.append(drawn[k + len(run)])
        start, end = run[0][1], run[-1][2]
        mid = (start + end) / 2
        centre = pts.mean(axis=0)
        away = mid - centre
        away = _unit_vec(away) if np.hypot(*away) > 1e-6 else np.array([0.0, 1.0])
        texts.append(Text(mid + away * (1.2 + 0.45 * size),
                          ", ".join(force_text(r[0]) for r in run), text_layer, size,
                          _anchor(away), "middle"))
        k += len(run)
    items += place_labels(texts, [o for o in obstacles if o is not None], rings=10)
    head = (label("force_plan_crank", lang).format(name=mech.crank.link) if group == "crank"
            else label("force_plan_group", lang).format(name=group))
    items += _title_lines(items, [
        (head, sizes.title_mm),
        (f"μF = {number_text(mu_f, lang)} {newton(lang)}/{unit('mm', lang)}", sizes.label_mm)],
        text_layer)
    # the results read off the polygon: every reaction of the group, M_b for the crank
    results = []
    for rc in ks.reactions.values():
        if rc.pair.group == group:
            results.append(f"{force_text(rc.label)} = {_num(float(rc.magnitude[i]), lang)} "
                           f"{newton(lang)}")
    if group == "crank":
        results.append(f"{label('symbol_balancing_moment', lang)} = "
                       f"{_num(float(ks.balancing_moment[i]), lang)} {newton_metre(lang)} "
                       f"({label('method_kinetostatics', lang)})")
    items += _note_lines(items, [(r, size) for r in results], text_layer)
    return make_view(f"polygon-{number}-{slug(group)}", items, pad_mm=2.0, mu=None,
                     origin=(0.0, 0.0),
                     meta={"group": group, "number": number, "index": i, "mu_f": mu_f,
                           "vertices": tuple(complex(v) for v in z),
                           "labels": tuple(names)})


def number_text(x: float, lang: str) -> str:
    """A scale value as written (``0.25`` → ``"0,25"`` in ru)."""
    return _num(x, lang)


# -- Zhukovsky's lever -------------------------------------------------------------------


def lever_extent(fa, i: int) -> tuple[float, float]:
    """Width and height of the turned velocity plan at μv = 1 (m/s)/mm, i.e. m/s."""
    v = fa.kinematics.velocities[i]
    v = v[np.all(np.isfinite(v), axis=1)]
    v = np.vstack([v, [[0.0, 0.0]]])
    span = np.ptp(v, axis=0)
    return float(span[1]), float(span[0])


def lever_balance(fa, i: int, mu_v: float):
    """(plan result at μv, lever) of position index `i`: Zhukovsky's lever on the force
    analysis' exact velocity plan drawn at μv."""
    from velplan.forces.lever import images_from_plan, positions_from_kinematics, zhukovsky_lever

    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    res = fa.plan.at_scale(mu_v)
    positions = {k: v[i:i + 1] for k, v in positions_from_kinematics(kin, None).items()}
    images = {k: v[i:i + 1] for k, v in images_from_plan(res).items()}
    lever = zhukovsky_lever(mech, positions, images, res.scale, fa.actions.at([i]))
    return res, lever


def lever_view(fa, i: int, *, mu_v: float, number: int, lang: str = "ru",
               sizes: ForceSizes = ForceSizes()) -> View:
    """Zhukovsky's lever at position index `i`: the velocity plan at μv turned by 90°.

    Returns
    -------
    View
        ``to_view`` maps lever mm (pole at 0, turned) to the view's mm; ``meta`` holds
        ``"mb_lever"``, ``"mb_kinetostatics"`` (N·m, as computed), ``"percent"``,
        ``"balancing_force"`` (N, signed) and the texts written (``"balance"``).
    """
    from velplan.forces.agreement import lever_difference_percent
    from velplan.views.plan import plan_steps

    mech = fa.kinetostatics.mechanism
    kin = fa.kinematics
    body_layer, force_layer, text_layer = lever_layers(number)
    res, lever = lever_balance(fa, i, mu_v)
    drawings = plan_steps(res, i, number=number, lang=lang)
    turn = np.array([[0.0, -1.0], [1.0, 0.0]])  # +90°: x + iy → i(x + iy)
    items: list[Primitive] = []
    obstacles: list = []
    lines: list[tuple[np.ndarray, np.ndarray]] = []
    vec_layer = f"plan-v-{number}"
    for d in drawings:
        for p in d.items:
            if isinstance(p, Arrow) and p.length > 1e-9:
                a, b = turn @ np.asarray(p.start), turn @ np.asarray(p.end)
                items.append(Polyline([a, b], body_layer, p.line))
            elif isinstance(p, Polyline) and p.layer == vec_layer:
                pts = np.asarray(p.points) @ turn.T
                items.append(Polyline(pts, body_layer, p.line))
            else:
                continue
            seg = np.asarray(items[-1].points)
            lines.append((seg[0], seg[-1]))
            obstacles.append(shapely.LineString(seg).buffer(0.6))
    items.append(Circle((0.0, 0.0), 0.8, body_layer, "thin", "solid"))
    # letters of the images (coincident ones share a label)
    groups: list[tuple[np.ndarray, list[str]]] = []
    for d in drawings:
        for t in d.images:
            zt = complex(res.values[t][i])
            if not np.isfinite(zt):
                continue
            p = turn @ _xy(zt)
            for q, names in groups:
                if np.hypot(*(q - p)) < 0.8:
                    names.append(t)
                    break
            else:
                groups.append((p, [t]))
    letters = []
    for p, names in groups:
        away = np.zeros(2)
        for a, b in lines:
            for here, other in ((a, b), (b, a)):
                if np.hypot(*(here - p)) < 0.8 and np.hypot(*(other - here)) > 1e-9:
                    away -= _unit_vec(other - here)
        if np.hypot(*away) < 0.3:
            away = p / np.hypot(*p) if np.hypot(*p) > 1 else np.array([-0.7, -0.7])
        away = _unit_vec(away)
        text = ", ".join(subscript(label_of(t)) for t in dict.fromkeys(names))
        letters.append(Text(p + away * (1.2 + 0.45 * sizes.label_mm), text, text_layer,
                            sizes.label_mm, _anchor(away), "middle"))
    # the forces at the images, and the balancing force at the crank tip's image
    forces = [(f.label, _xy(complex(f.image[0])), complex(f.vector[0])) for f in lever.forces]
    scale = max([abs(f) for _, _, f in forces if np.isfinite(f)] or [0.0])
    forces = [(n, p, f) for n, p, f in forces if np.isfinite(f) and abs(f) > 1e-9 * scale]
    o = complex(*kin.position(mech.crank.pivot)[i])
    a = complex(*kin.position(mech.crank.tip)[i])
    e = 1j * (a - o) / abs(a - o)
    fb = float(lever.balancing_force[0])
    fb_dir = _xy(e * (1.0 if fb >= 0 else -1.0))
    tip = _xy(complex(lever.tip_image[0]))
    symbol_fb = label("symbol_balancing_force", lang)
    entries = [(p, _unit_vec(_xy(f)), force_text(n)) for n, p, f in forces] + [
        (tip, fb_dir, symbol_fb)]
    # the balancing force first, so that it keeps its place at the crank tip's image
    order = [len(entries) - 1] + list(range(len(entries) - 1))
    placed = dict(zip(order, place_arrows([entries[k] for k in order], sizes.arrow_mm,
                                          obstacles, [p for p, _ in groups], letters,
                                          layer=text_layer, size=sizes.label_mm)))
    texts: list[Text] = []
    for k in order:
        a, b, tag = placed[k]
        arrow = Arrow(a, b, force_layer, "thick" if k == len(entries) - 1 else "thin")
        items.append(arrow)
        obstacles.append(_arrow_obstacle(arrow))
        texts.append(tag)
    items += place_labels(letters + texts, [q for q in obstacles if q is not None], rings=10)
    # the balance, written under the lever
    mb_lever = float(lever.balancing_moment[0])
    mb_kin = float(fa.kinetostatics.balancing_moment[i])
    pct = float(lever_difference_percent(np.array([mb_lever]), np.array([mb_kin]))[0])
    nm = newton_metre(lang)
    mb = label("symbol_balancing_moment", lang)
    balance = (f"{mb} = {_num(mb_lever, lang)} {nm} ({label('method_lever', lang)}) / "
               f"{_num(mb_kin, lang)} {nm} ({label('method_kinetostatics', lang)}), "
               f"Δ = {fixed(pct, lang, 2)} %")
    lab = f"l{subscript(mech.crank.pivot)}{subscript(mech.crank.tip)}"
    force_line = (f"{symbol_fb} = {_num(abs(fb), lang)} {newton(lang)}; "
                  f"{mb} = {symbol_fb}·{lab}")
    notes = [(force_line, sizes.label_mm), (balance, sizes.label_mm)]
    x0, _, x1, _ = bounds_of(items)
    if sizes.wrap_balance and text_extent(balance, sizes.label_mm)[0] > max(
            x1 - x0, text_extent(force_line, sizes.label_mm)[0]):
        # wider than the lever itself: the two methods on two lines
        cut = balance.index(" / ") + 3
        notes[1:] = [(balance[:cut].rstrip(), sizes.label_mm), (balance[cut:], sizes.label_mm)]
    items += _note_lines(items, notes, text_layer)
    items += _title_lines(items, [
        (label("zhukovsky_lever", lang), sizes.title_mm),
        (scale_text("μv", res.scale, "(m/s)/mm", lang), sizes.label_mm),
        (f"({label('plan_turned', lang)})", sizes.label_mm)], text_layer)
    return make_view(f"lever-{number}", items, pad_mm=2.0, mu=None, origin=(0.0, 0.0),
                     meta={"number": number, "index": i, "mu_v": res.scale,
                           "mb_lever": mb_lever, "mb_kinetostatics": mb_kin, "percent": pct,
                           "balancing_force": fb, "balance": balance,
                           "forces": tuple(forces)})


# -- the table and the diagram of the balancing moment -----------------------------------



def moment_decimals(values) -> int:
    """Decimals that give the largest |M_b| four significant figures."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)]
    top = float(np.max(np.abs(v))) if v.size else 0.0
    if top == 0.0:
        return 1
    return int(min(4, max(0, 3 - math.floor(math.log10(top)))))


def moments_table_view(fa, *, lang: str = "ru", size_mm: float = 2.5,
                       title_mm: float = 3.5) -> View:
    """The three balancing moments (kinetostatics, lever, power) at every position, N·m."""
    n = len(fa.kinematics)
    moments = fa.balancing_moments
    decimals = moment_decimals(moments["kinetostatics"])
    mb = label("symbol_balancing_moment", lang)
    head = [label("position", lang)] + [str(k + 1) for k in range(n)]
    rows = [[f"φ, {unit('deg', lang)}"] +
            [fixed(math.degrees(p) % 360.0, lang, 1) for p in fa.kinematics.phi]]
    for key in ("kinetostatics", "lever", "power"):
        rows.append([f"{mb} ({label('method_' + key, lang)})"] +
                    [fixed(float(v), lang, decimals) for v in moments[key]])
    items, total_w, total_h = grid_table([head] + rows, size_mm)
    items.append(Text((0.0, total_h + 2.5), f"{label('balancing_moment', lang)} {mb}, "
                      f"{newton_metre(lang)}", "table", title_mm))
    return make_view("table", items, pad_mm=1.0, meta={"n": n, "size_mm": size_mm,
                                                      "decimals": decimals})


@dataclass(frozen=True)
class MomentCurve:
    """M_b over a revolution from position 1: turn angles (rad, 0…2π) and moments (N·m) of a
    fine grid, and the values at the n positions."""

    turn: np.ndarray
    moment: np.ndarray
    at_positions: np.ndarray


def moment_diagram_view(curve: MomentCurve, *, length_mm: float = 240.0,
                        height_mm: float = 60.0, lang: str = "ru",
                        label_mm: float = 2.5, title_mm: float = 3.5) -> View:
    """The diagram M_b(φ) over a revolution: the curve (thick), the n positions marked on
    the φ axis with their values as dots, the mean as a dash-dot line, the scales.

    Parameters
    ----------
    length_mm : float
        Length of the φ axis for a turn, mm (μφ = 2π / length).
    height_mm : float
        Largest span of the ordinates, mm: μM is the standard scale that keeps
        max M_b − min M_b within it.
    """
    from velplan.plans import standard_scale

    turn, mom, at = curve.turn, curve.moment, curve.at_positions
    n = len(at)
    fin = mom[np.isfinite(mom)]
    top_v, bottom_v = max(float(fin.max()), 0.0), min(float(fin.min()), 0.0)
    span = max(top_v - bottom_v, 1e-12)
    mu_m = standard_scale(span / height_mm)
    mu_phi = 2 * math.pi / length_mm
    L = length_mm
    layer, text_layer = "mb-diagram", "mb-diagram-labels"
    top, bottom = max(top_v / mu_m, 5.0), bottom_v / mu_m
    items: list[Primitive] = []
    items.append(Arrow((0.0, 0.0), (L + 8.0, 0.0), layer, "thin", 3.0, 1.0))
    items.append(Arrow((0.0, bottom - 3.0), (0.0, top + 6.0), layer, "thin", 3.0, 1.0))
    items.append(Text((L + 9.0, -1.0), "φ", text_layer, label_mm, "start", "top"))
    mb = label("symbol_balancing_moment", lang)
    items.append(Text((-1.5, top + 6.0), f"{mb}, {newton_metre(lang)}", text_layer, label_mm,
                      "end", "top"))
    every = max(1, int(math.ceil(n / 12)))
    tick_y = -1.8
    for k in range(n + 1):
        x = k * L / n
        items.append(Polyline([(x, -1.0), (x, 1.0)], layer, "thin"))
        if k % every == 0:
            items.append(Text((x, tick_y), str(k % n + 1), text_layer, label_mm, "middle",
                              "top"))
    ok = np.isfinite(mom)
    xy = np.column_stack([turn[ok] / mu_phi, mom[ok] / mu_m])
    items.append(Polyline(xy, layer, "thick"))
    items = axis_numbers_clear(items, [xy])
    for k, v in enumerate(at):
        if np.isfinite(v):
            items.append(Circle((k * L / n, float(v) / mu_m), 0.6, layer, "thin", "solid"))
    mean = float(np.mean(mom[ok][:-1])) if ok.sum() > 1 else float("nan")
    if abs(mean) < 1e-9 * span:
        mean = 0.0  # round-off of a moment whose work over the turn is nil
    if np.isfinite(mean):
        y = mean / mu_m
        items.append(Polyline([(0.0, y), (L, y)], layer, "axis"))
        # above a mean over the axis, below one under it (clear of the axis's φ)
        at, v_anchor = ((y + 1.0, "baseline") if y >= 0 else
                        (min(y - 1.0, -1.0 - label_mm - 1.0), "top"))
        items.append(Text((L + 2.0, at), f"{label('mean', lang)} {_num(mean, lang)} "
                          f"{newton_metre(lang)}", text_layer, label_mm, "start", v_anchor))
    y = top + 8.0 + 1.6 * label_mm
    items.append(Text((0.0, y + 1.8 * label_mm), label("balancing_moment_diagram", lang),
                      text_layer, title_mm))
    items.append(Text((0.0, y), f"μM = {_num(mu_m, lang)} {newton_metre(lang)}/"
                      f"{unit('mm', lang)};  " + scale_text("μφ", mu_phi, "rad/mm", lang) +
                      f" ({_num(math.degrees(mu_phi), lang, 3)}°/{unit('mm', lang)})",
                      text_layer, label_mm))
    return make_view("mb-diagram", items, pad_mm=2.0,
                     meta={"mu_m": mu_m, "mu_phi": mu_phi, "mean": mean})


__all__ = ["ForceSizes", "MomentCurve", "application_points", "group_forces", "group_view",
           "polygon_view", "lever_view", "lever_balance", "moments_table_view",
           "moment_diagram_view", "group_layers", "polygon_layers", "lever_layers",
           "force_text", "slug", "group_extent_m", "polygon_extent", "lever_extent"]
