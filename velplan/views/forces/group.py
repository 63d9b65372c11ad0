"""A group with its forces: the links of one Assur group (or of the initial link) at a
standard μl, cut free of the frame and of their neighbours, every force on them as an arrow
of a conventional length from its point of application and the couples as curved arrows."""

from __future__ import annotations

import math

import numpy as np
import shapely

from velplan.analysis.numbering import position_index
from velplan.errors import VelplanError
from velplan.forces.agreement import ForceAnalysis
from velplan.forces.kinetostatics import reaction_label
from velplan.mechanism.structure import material_points, pairs
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.render.symbols import (
    JOINT_RADIUS_MM, link, revolute_joint, rotation_arrow, slider_block)
from velplan.views.base import View, bounds_of, free_direction, make_view, scale_mark, scale_text, subscript
from velplan.views.forces.anchored import place_anchored
from velplan.views.forces.arrows import arrow_obstacle, place_arrows
from velplan.views.forces.common import (
    ForceSizes, Sketch, anchor_of, away_from_lines, force_text, group_layers, slug, title_lines,
    unit_vector, xy)
from velplan.views.mechanism import BLOCK_MM, _Geometry, plate_corners

#: Margin of the view around what it draws, mm.
PAD_MM = 2.0
#: Reaction components ("R12τ") drop these suffixes to find their pair.
_SUFFIXES = "τn∥⊥"


# -- where each force acts ---------------------------------------------------------------


def _application_points(fa: ForceAnalysis, i: int) -> dict[str, complex]:
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


def group_forces(fa: ForceAnalysis, group: str, position: int) -> list[tuple[str, complex, complex]]:
    """(label, point m, force N) of every force on the group `group` (or ``"crank"``) at
    position number ``position`` (1…n), in the order of its polygon; zero forces left out."""
    i = position_index(position, len(fa.kinematics))
    poly = fa.kinetostatics.polygons[group]
    points = _application_points(fa, i)
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
    """The links of group `group`, or the crank's link for ``"crank"``."""
    if group == "crank":
        return (mech.crank.link,)
    found = next((g for g in mech.groups if g.name == group), None)
    if found is None:
        known = ", ".join([g.name for g in mech.groups] + ["crank"])
        raise VelplanError(f"{mech.name} has no group {group!r}; its groups: {known}")
    return tuple(found.links)


def group_extent_m(fa: ForceAnalysis, group: str, position: int) -> tuple[float, float]:
    """Width and height of the group's points and points of application at position number
    ``position`` (1…n), m."""
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    i = position_index(position, len(kin))
    links = group_links(mech, group)
    mp = material_points(mech)
    pts = [complex(*kin.position(p)[i]) for lk in links for p in mp.get(lk, ())]
    pts += [z for _, z, _ in group_forces(fa, group, position)]
    pts = np.array([z for z in pts if np.isfinite(z)])
    return float(np.ptp(pts.real)), float(np.ptp(pts.imag))


# -- the view ----------------------------------------------------------------------------


def group_view(fa: ForceAnalysis, group: str, position: int, *, mu_l: float, lang: Language = "ru",
               sizes: ForceSizes = ForceSizes()) -> View:
    """One Assur group (or ``"crank"``, the initial link) with every force on it.

    Parameters
    ----------
    fa : ForceAnalysis
        The analysis at the sheet's positions.
    group : str
        Group name, or ``"crank"``.
    position : int
        Position number (1…n of `fa`), written in the title and the layer names.
    mu_l : float
        Length scale, m/mm.

    Returns
    -------
    View
        ``mu`` is μl, ``to_view`` maps metres to the view's mm; ``meta["forces"]`` holds
        (label, point m, force N) of the drawn arrows, ``meta["arrows"]`` their count,
        ``meta["couples"]`` (label, centre in content mm, moment N·m) of the curved arrows,
        ``meta["letters"]`` (letter, its point m) of the points' letters.
    """
    i, number = position_index(position, len(fa.kinematics)), position
    mech = fa.kinetostatics.mechanism
    links = group_links(mech, group)
    body_layer, force_layer, text_layer = group_layers(number, group)

    def mm(at) -> np.ndarray:  # content mm
        return np.asarray(at, float) / mu_l

    sk = Sketch()
    axes, joints, centres = _draw_links(sk, fa, links, i, mm, body_layer)
    # letters of the points, then the forces: arrows of a conventional length at their points
    named = joints + centres + [f.point for f in fa.actions.forces if f.link in links]
    letters, at = _point_letters(fa.kinematics, i, mm, named, sk.lines, text_layer,
                                 sizes.label_mm)
    forces = group_forces(fa, group, position)
    force_labels, ends = _draw_forces(sk, forces, [mm(fa.kinematics.position(q)[i])
                                                     for q in dict.fromkeys(named)],
                                        letters, mm, force_layer, text_layer, sizes)
    couples = _couples(fa, group, links, i, mm, lang)
    radius = max(4.5, 0.35 * sizes.arrow_mm)
    couple_labels, arcs = _draw_couples(sk, couples, radius, force_layer, text_layer,
                                        sizes.label_mm)
    # each label kept by its own point, arrow or arc (the nearest of its kind to it)
    anchors = [shapely.Point(p) for p in at] + ends + arcs
    kinds = ["point"] * len(at) + ["force"] * len(ends) + ["couple"] * len(arcs)
    items = sk.items + place_anchored(letters + force_labels + couple_labels, anchors, kinds,
                                      sk.clear_of() + axes, leader_layer=text_layer)
    head = (label("initial_link", lang).format(name=mech.crank.link) if group == "crank"
            else label("assur_group", lang).format(name=group))
    items += title_lines(items, [
        (head, sizes.title_mm),
        (scale_text("μl", mu_l, "m/mm", lang) + f" ({scale_mark(mu_l, lang)})", sizes.label_mm)],
        text_layer)
    return make_view(f"group-{number}-{slug(group)}", items, pad_mm=PAD_MM, mu=mu_l,
                     origin=(0.0, 0.0),
                     meta={"group": group, "number": number, "index": i,
                           "forces": tuple(forces), "arrows": len(forces),
                           "couples": tuple((t, tuple(c), v) for t, c, v in couples),
                           "arc_radius": radius,
                           "letters": tuple((t.text, tuple(p * mu_l)) for t, p in zip(letters, at))})


def group_body_size(fa: ForceAnalysis, group: str, position: int, *, mu_l: float,
                    sizes: ForceSizes = ForceSizes()) -> tuple[float, float]:
    """Width and height (mm, the view's margins included) of the group's links as `group_view`
    draws them at position number ``position`` (1…n) and μl = ``mu_l`` (m/mm), under its two
    title lines: a lower bound of the view's size, found without its forces and labels."""
    i = position_index(position, len(fa.kinematics))
    sk = Sketch()
    _draw_links(sk, fa, group_links(fa.kinetostatics.mechanism, group), i,
                lambda at: np.asarray(at, float) / mu_l, group_layers(position, group)[0])
    if not sk.items:
        return 0.0, 0.0
    x0, y0, x1, y1 = bounds_of(sk.items)
    titles = 3.0 + 1.6 * sizes.label_mm + sizes.title_mm  # `title_lines`: to the heading's top
    return x1 - x0 + 2 * PAD_MM, y1 - y0 + titles + 2 * PAD_MM


# -- the links ---------------------------------------------------------------------------


def _draw_links(sk: Sketch, fa, links, i: int, mm, layer: str) -> tuple[list, list, list]:
    """The links of the group: plates, bars, the guides they ride on as axes, blocks, joints
    and centres of mass. Returns (guide axes as shapes, joint names, centre names)."""
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    geo = _Geometry(mech, kin)
    _draw_bars(sk, geo, links, i, mm, layer)
    axes = _draw_guide_axes(sk, fa.kinetostatics, links, i, mm, layer)
    for bl in geo.blocks(i):
        if bl.link not in links:
            continue
        body = slider_block(mm(bl.centre), math.degrees(bl.angle), length_mm=BLOCK_MM[0],
                            width_mm=BLOCK_MM[1], layer=layer)
        sk.items += body
        sk.obstacles.append(shapely.Polygon(body[0].points).buffer(0.8))
    joints = _draw_joints(sk, mech, kin, links, i, mm, layer)
    centres = [m.centre for m in mech.masses if m.link in links]
    for name in centres:
        c = mm(kin.position(name)[i])
        if any(np.hypot(*(c - mm(kin.position(j)[i]))) < 1.0 for j in joints):
            continue
        sk.items.append(Circle(c, 1.0, layer, "thin", "solid"))
        sk.obstacles.append(shapely.Point(c).buffer(1.5))
    return axes, joints, centres


def _draw_bars(sk: Sketch, geo, links, i: int, mm, layer: str) -> None:
    """The plates and bars of `links`, trimmed at their joints."""
    for plate, corners in geo.plates(i):
        if plate in links:
            sk.items += plate_corners(mm(corners), layer=layer)
    for s in geo.segments(i):
        if s.link not in links:
            continue
        a, b = mm(s.a), mm(s.b)
        sk.items += link(a, b, trim_a_mm=JOINT_RADIUS_MM if s.joints[0] else 0.0,
                         trim_b_mm=JOINT_RADIUS_MM if s.joints[1] else 0.0, layer=layer)
        if np.hypot(*(b - a)) > 1e-9:
            sk.obstacles.append(shapely.LineString([a, b]).buffer(0.6))
            sk.lines.append((a, b))


def _draw_guide_axes(sk: Sketch, ks, links, i: int, mm, layer: str) -> list:
    """The axis of every guide a link of the group slides on (a prismatic pair with the frame
    or a neighbour); forces along a guide are drawn on it, so it keeps labels off, not
    arrows. Returns the axes as shapes."""
    axes = []
    for rc in ks.reactions.values():
        p = rc.pair
        if p.kind != "P" or sum(lk in links for lk in p.links) != 1:
            continue
        u = xy(rc.direction[i])
        c = mm(xy(rc.reference[i]))
        half = BLOCK_MM[0] / 2 + 7.0
        axis = Polyline([c - u * half, c + u * half], layer, "axis")
        sk.items.append(axis)
        axes.append(shapely.LineString(axis.points).buffer(0.4))
    return axes


def _draw_joints(sk: Sketch, mech, kin, links, i: int, mm, layer: str) -> list[str]:
    """The revolute joints of the group's links. Returns their point names."""
    joints = []
    for p in pairs(mech):
        if p.kind == "R" and any(lk in links for lk in p.links) and p.point not in joints:
            joints.append(p.point)
    for name in joints:
        c = mm(kin.position(name)[i])
        sk.items += revolute_joint(c, layer=layer)
        sk.obstacles.append(shapely.Point(c).buffer(JOINT_RADIUS_MM + 0.5))
    return joints


def _point_letters(kin, i, mm, names, lines, layer, size) -> tuple[list[Text], list[np.ndarray]]:
    """The letters of the named points (once per place), opposite the lines that leave them,
    and their points (mm)."""
    out: list[Text] = []
    placed: list[np.ndarray] = []
    for name in dict.fromkeys(names):
        p = mm(kin.position(name)[i])
        if not np.all(np.isfinite(p)) or any(np.hypot(*(p - q)) < 1.0 for q in placed):
            continue
        placed.append(p)
        away = away_from_lines(p, lines)
        if np.hypot(*away) < 0.2:
            away = np.array([-1.0, 1.0])
        away = away / np.hypot(*away)
        pos = p + away * (JOINT_RADIUS_MM + 1.2 + 0.5 * size)
        out.append(Text(pos, subscript(name), layer, size, anchor_of(away), "middle"))
    return out, placed


# -- the forces and the couples ----------------------------------------------------------


def _draw_forces(sk: Sketch, forces, marks, letters, mm, layer: str, text_layer: str,
                 sizes: ForceSizes) -> tuple[list[Text], list]:
    """The arrows of `forces` (label, point m, force N), kept clear of the points `marks` (mm)
    and of the letters, beside a link rather than along it. Returns their labels and the
    arrows' free ends (away from the force's point), which the labels name."""
    entries = [(mm(xy(z)), unit_vector(xy(f)), force_text(name)) for name, z, f in forces]
    labels: list[Text] = []
    ends = []
    for (p, _, _), (a, b, tag) in zip(entries, place_arrows(
            entries, sizes.arrow_mm, sk.obstacles, marks, letters, layer=text_layer,
            size=sizes.label_mm, beside=True)):
        arrow = Arrow(a, b, layer, "thin")
        sk.items.append(arrow)
        sk.obstacles.append(arrow_obstacle(arrow))
        sk.lines.append((a, b))
        labels.append(tag)
        ends.append(shapely.Point(b if np.hypot(*(b - p)) >= np.hypot(*(a - p)) else a))
    return labels, ends


def _couples(fa: ForceAnalysis, group: str, links, i: int, mm, lang: Language) -> list[tuple[str, np.ndarray, float]]:
    """(label, centre in content mm, moment N·m) of the couples on the group: the inertia
    moments at the centres of mass, and the balancing moment at the crank's pivot."""
    mech, kin = fa.kinetostatics.mechanism, fa.kinematics
    out: list[tuple[str, np.ndarray, float]] = []
    for m in fa.actions.moments:
        if m.link not in links:
            continue
        value = float(m.moment[i])
        if not np.isfinite(value) or value == 0.0:
            continue
        centre = next((lm.centre for lm in mech.masses if lm.link == m.link), None)
        if centre is None:  # a link without a mass: its first point
            points = material_points(mech).get(m.link, ())
            centre = next(p for p in kin.point_index if p in points)
        out.append((force_text(m.label), mm(kin.position(centre)[i]), value))
    if group == "crank":
        mb = float(fa.kinetostatics.balancing_moment[i])
        out.append((label("symbol_balancing_moment", lang),
                    mm(kin.position(mech.crank.pivot)[i]), mb))
    return out


def _draw_couples(sk: Sketch, couples, radius: float, layer: str, text_layer: str,
                  size: float) -> tuple[list[Text], list]:
    """Curved arrows of the couples, each towards the freest direction about its centre.
    Returns their labels and arcs."""
    labels: list[Text] = []
    arcs = []
    for text, c, value in couples:
        arc, tag = _moment_arc(c, value, text, _busy_angles(c, sk.lines), radius=radius,
                               layer=layer, text_layer=text_layer, size=size)
        sk.items += arc
        sk.obstacles += [shapely.LineString(a.points).buffer(0.5) if isinstance(a, Polyline)
                         else arrow_obstacle(a) for a in arc]
        labels.append(tag)
        arcs.append(shapely.LineString([p for a in arc for p in (
            a.points if isinstance(a, Polyline) else (a.start, a.end))]))
    return labels, arcs


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


def _moment_arc(centre, value: float, text: str, busy: list[float], *, radius: float,
                layer: str, text_layer: str, size: float) -> tuple[list[Primitive], Text]:
    """A curved arrow about `centre` in the sense of `value` (counter-clockwise positive),
    centred on the freest direction, and its label beyond the arc."""
    mid = free_direction(busy)
    sweep = 110.0 if value >= 0 else -110.0
    arc = rotation_arrow(np.asarray(centre, float), radius, mid - sweep / 2, sweep, layer=layer)
    a = math.radians(mid)
    u = np.array([math.cos(a), math.sin(a)])
    where = np.asarray(centre, float) + u * (radius + 1.2 + 0.6 * size)
    return list(arc), Text(where, text, text_layer, size, anchor_of(u), "middle")
