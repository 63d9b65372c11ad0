"""Zhukovsky's lever: the velocity plan turned by 90° (counter-clockwise, as
`velplan.forces.lever` turns it), every force carried to the image of its point with its own
direction, a couple replaced by a pair of forces at the images of two points of its link, and
the balancing force at the image of the crank tip; the balance is written under it: M_b by the
lever against M_b by kinetostatics. Every number is the force analysis' (`ForceAnalysis.lever`
read at the drawing's μv); the view only draws."""

from __future__ import annotations

import numpy as np
import shapely

from velplan.analysis.numbering import position_index
from velplan.forces.agreement import ForceAnalysis
from velplan.options import Language
from velplan.plans.text import label_of
from velplan.render.i18n import label
from velplan.render.scene import Arrow, Circle, Polyline, Text
from velplan.render.shapes import DESCENDER_DEPTH, text_extent
from velplan.views.base import View, bounds_of, fixed, make_view, scale_text, subscript
from velplan.views.forces.anchored import place_anchored
from velplan.notation import number as _num
from velplan.views.forces.arrows import arrow_obstacle, place_arrows
from velplan.views.forces.common import (
    ForceSizes, Sketch, anchor_of, away_from_lines, force_text, lever_layers, newton,
    newton_metre, note_lines, title_lines, unit_vector, xy)
from velplan.views.plan import plan_steps

#: Margin of the view around what it draws, mm.
PAD_MM = 2.0
#: Image points nearer than this to another (and not one with it) are crowded: each is
#: marked with a dot and its letter set out with a leader, mm.
CROWDED_MM = 3.0
#: The turn by +90° of the lever: x + iy → i(x + iy).
TURN = np.array([[0.0, -1.0], [1.0, 0.0]])


def lever_extent(fa: ForceAnalysis, position: int) -> tuple[float, float]:
    """Width and height of the turned velocity plan at position number ``position`` (1…n) at
    μv = 1 (m/s)/mm, i.e. m/s."""
    v = fa.kinematics.velocities[position_index(position, len(fa.kinematics))]
    v = v[np.all(np.isfinite(v), axis=1)]
    v = np.vstack([v, [[0.0, 0.0]]])
    span = np.ptp(v, axis=0)
    return float(span[1]), float(span[0])


def lever_balance(fa: ForceAnalysis, mu_v: float):
    """(velocity plan at μv, lever at μv): the force analysis' plan and Zhukovsky's lever
    (`ForceAnalysis.lever`, every position) read at the scale μv ((m/s)/mm) of a drawing."""
    res = fa.plan.at_scale(mu_v)
    return res, fa.lever.at_scale(res.scale)


def lever_view(fa: ForceAnalysis, position: int, *, mu_v: float, lang: Language = "ru",
               sizes: ForceSizes = ForceSizes()) -> View:
    """Zhukovsky's lever at position number ``position`` (1…n): the velocity plan at μv
    turned by 90°.

    Returns
    -------
    View
        ``to_view`` maps lever mm (pole at 0, turned) to the view's mm; ``meta`` holds
        ``"mb_lever"``, ``"mb_kinetostatics"`` (N·m, as computed), ``"percent"``,
        ``"balancing_force"`` (N, signed), the texts written (``"balance"``) and the image
        points' letters with their points (``"letters"``, turned mm).
    """
    i, number = position_index(position, len(fa.kinematics)), position
    body_layer, force_layer, text_layer = lever_layers(number)
    res, lever = lever_balance(fa, mu_v)
    drawings = plan_steps(res, number, lang=lang)
    sk = Sketch()
    _draw_turned_plan(sk, drawings, f"plan-v-{number}", body_layer)
    sk.items.append(Circle((0.0, 0.0), 0.8, body_layer, "thin", "solid"))
    images = _image_groups(drawings, res, i)
    crowded = _crowded(images)
    for k in crowded:
        sk.items.append(Circle(tuple(images[k][0]), 0.5, body_layer, "thin", "solid"))
        sk.obstacles.append(shapely.Point(images[k][0]).buffer(0.8))
    letters = [_image_letter(p, names, sk.lines, text_layer, sizes.label_mm)
               for p, names in images]
    forces = _lever_forces(lever, i)
    texts, ends = _draw_forces(sk, fa, lever, i, forces, [p for p, _ in images], letters, lang,
                               sizes, force_layer, text_layer)
    # each label kept by its own image point or arrow end (the nearest of its kind to it)
    anchors = [shapely.Point(p) for p, _ in images] + ends
    kinds = ["point"] * len(images) + ["force"] * len(ends)
    items = sk.items + place_anchored(letters + texts, anchors, kinds, sk.clear_of(), leader_layer=text_layer,
                                      lead=crowded)
    mb_lever = float(lever.balancing_moment[i])
    mb_kin = float(fa.kinetostatics.balancing_moment[i])
    pct = float(fa.lever_difference_percent[i])
    fb = float(lever.balancing_force[i])
    notes = _balance_lines(fa.kinetostatics.mechanism, mb_lever, mb_kin, pct, fb, lang)
    items += note_lines(items, _wrapped(notes, items, sizes), sizes.label_mm, text_layer)
    items += title_lines(items, [
        (label("zhukovsky_lever", lang), sizes.title_mm),
        (scale_text("μv", res.scale, "(m/s)/mm", lang), sizes.label_mm),
        (f"({label('plan_turned', lang)})", sizes.label_mm)], text_layer)
    return make_view(f"lever-{number}", items, pad_mm=PAD_MM, mu=None, origin=(0.0, 0.0),
                     meta={"number": number, "index": i, "mu_v": res.scale,
                           "mb_lever": mb_lever, "mb_kinetostatics": mb_kin, "percent": pct,
                           "balancing_force": fb, "balance": notes[1],
                           "forces": tuple(forces),
                           "letters": tuple((t.text, tuple(p)) for t, (p, _) in zip(letters, images))})


def lever_body_size(fa: ForceAnalysis, position: int, *, mu_v: float, lang: Language = "ru",
                    sizes: ForceSizes = ForceSizes()) -> tuple[float, float]:
    """Width and height (mm, the view's margins included) of the lever's bars and pole as
    `lever_view` draws them at position number ``position`` (1…n) and μv = ``mu_v``, under
    its three title lines and over its two
    lines of notes at least: a lower bound of the view's size, found without its forces and
    letters."""
    number = position
    res, _ = lever_balance(fa, mu_v)
    sk = Sketch()
    body_layer = lever_layers(number)[0]
    _draw_turned_plan(sk, plan_steps(res, number, lang=lang), f"plan-v-{number}", body_layer)
    sk.items.append(Circle((0.0, 0.0), 0.8, body_layer, "thin", "solid"))
    x0, y0, x1, y1 = bounds_of(sk.items)
    label_mm = sizes.label_mm
    titles = 3.0 + 3.2 * label_mm + sizes.title_mm  # `title_lines`: to the heading's top
    notes = 2.0 + (2.6 + DESCENDER_DEPTH) * label_mm  # `note_lines`: to the second line's foot
    return x1 - x0 + 2 * PAD_MM, y1 - y0 + titles + notes + 2 * PAD_MM


def _lever_forces(lever, i: int) -> list[tuple[str, np.ndarray, complex]]:
    """(label, image turned mm, force N) of the forces on the lever at position index `i`,
    those of no size left out."""
    forces = [(f.label, xy(complex(f.image[i])), complex(f.vector[i])) for f in lever.forces]
    scale = max([abs(f) for _, _, f in forces if np.isfinite(f)] or [0.0])
    return [(n, p, f) for n, p, f in forces if np.isfinite(f) and abs(f) > 1e-9 * scale]


def _draw_turned_plan(sk: Sketch, drawings, vec_layer: str, layer: str) -> None:
    """The vectors of the plan's steps, turned by 90°, as the lever's bars."""
    for d in drawings:
        for p in d.items:
            if isinstance(p, Arrow) and p.length > 1e-9:
                a, b = TURN @ np.asarray(p.start), TURN @ np.asarray(p.end)
                sk.items.append(Polyline([a, b], layer, p.line))
            elif isinstance(p, Polyline) and p.layer == vec_layer:
                sk.items.append(Polyline(np.asarray(p.points) @ TURN.T, layer, p.line))
            else:
                continue
            seg = np.asarray(sk.items[-1].points)
            sk.lines.append((seg[0], seg[-1]))
            sk.obstacles.append(shapely.LineString(seg).buffer(0.6))


def _image_groups(drawings, res, i: int) -> list[tuple[np.ndarray, list[str]]]:
    """The turned images of the plan's points (turned mm), coincident ones together."""
    groups: list[tuple[np.ndarray, list[str]]] = []
    for d in drawings:
        for t in d.images:
            zt = complex(res.values[t][i])
            if not np.isfinite(zt):
                continue
            p = TURN @ xy(zt)
            for q, names in groups:
                if np.hypot(*(q - p)) < 0.8:
                    names.append(t)
                    break
            else:
                groups.append((p, [t]))
    return groups


def _crowded(images) -> list[int]:
    """The indices of the image groups within CROWDED_MM of another."""
    pts = [np.asarray(p, float) for p, _ in images]
    return [k for k, p in enumerate(pts)
            if any(j != k and np.hypot(*(p - q)) < CROWDED_MM for j, q in enumerate(pts))]


def _image_letter(p, names, lines, layer: str, size: float) -> Text:
    """The letters of the images at `p`, opposite the bars that leave it (else away from the
    pole)."""
    away = away_from_lines(p, lines)
    if np.hypot(*away) < 0.3:
        away = p / np.hypot(*p) if np.hypot(*p) > 1 else np.array([-0.7, -0.7])
    away = unit_vector(away)
    text = ", ".join(subscript(label_of(t)) for t in dict.fromkeys(names))
    return Text(p + away * (1.2 + 0.45 * size), text, layer, size, anchor_of(away), "middle")


def _draw_forces(sk: Sketch, fa, lever, i: int, forces, marks, letters, lang: Language,
                 sizes: ForceSizes, layer: str, text_layer: str) -> tuple[list[Text], list]:
    """The forces at their images and the balancing force (thick) at the crank tip's image,
    drawn first so that it keeps its place there. Returns their labels and what the labels
    name: the arrows' free ends (away from their points), both ends of the balancing force's
    (its name may stand by either, so no other label stands by its head)."""
    fb = float(lever.balancing_force[i])
    fb_dir = xy(complex(lever.direction[i]) * (1.0 if fb >= 0 else -1.0))
    tip = xy(complex(lever.tip_image[i]))
    entries = [(p, unit_vector(xy(f)), force_text(n)) for n, p, f in forces] + [
        (tip, fb_dir, label("symbol_balancing_force", lang))]
    order = [len(entries) - 1] + list(range(len(entries) - 1))
    placed = dict(zip(order, place_arrows([entries[k] for k in order], sizes.arrow_mm,
                                          sk.obstacles, marks, letters,
                                          layer=text_layer, size=sizes.label_mm)))
    texts: list[Text] = []
    ends = []
    for k in order:
        a, b, tag = placed[k]
        arrow = Arrow(a, b, layer, "thick" if k == len(entries) - 1 else "thin")
        sk.items.append(arrow)
        sk.obstacles.append(arrow_obstacle(arrow))
        texts.append(tag)
        p = np.asarray(entries[k][0], float)
        if k == len(entries) - 1:
            ends.append(shapely.MultiPoint([a, b]))
        else:
            ends.append(shapely.Point(b if np.hypot(*(b - p)) >= np.hypot(*(a - p)) else a))
    return texts, ends


def _balance_lines(mech, mb_lever: float, mb_kin: float, pct: float, fb: float,
                   lang: Language) -> list[str]:
    """The two lines written under the lever: F_b and M_b = F_b·l_OA, then M_b by the lever
    against M_b by kinetostatics and their difference, %."""
    nm = newton_metre(lang)
    mb = label("symbol_balancing_moment", lang)
    symbol_fb = label("symbol_balancing_force", lang)
    balance = (f"{mb} = {_num(mb_lever, lang)} {nm} ({label('method_lever', lang)}) / "
               f"{_num(mb_kin, lang)} {nm} ({label('method_kinetostatics', lang)}), "
               f"Δ = {fixed(pct, lang, 2)} %")
    lab = f"l_{{{mech.crank.pivot}{mech.crank.tip}}}"  # the crank's length, l with O₂A below the line
    return [f"{symbol_fb} = {_num(abs(fb), lang)} {newton(lang)}; {mb} = {symbol_fb}·{lab}",
            balance]


def _wrapped(notes: list[str], items, sizes: ForceSizes) -> list[str]:
    """The lines (at the label height); on small formats the balance, where it is wider than the
    lever itself, on two lines (the two methods)."""
    force_line, balance = notes
    x0, _, x1, _ = bounds_of(items)
    if sizes.wrap_balance and text_extent(balance, sizes.label_mm)[0] > max(
            x1 - x0, text_extent(force_line, sizes.label_mm)[0]):
        cut = balance.index(" / ") + 3
        return [force_line, balance[:cut].rstrip(), balance[cut:]]
    return [force_line, balance]
