"""A force polygon (plan of forces): the known vectors head to tail from the pole at a
standard μF (N/mm), then the two unknown reactions found where the lines of their known
directions meet (thin construction lines through the last vertex and through the pole); the
found vectors thick. Vertices are `ForcePolygon.vertices`."""

from __future__ import annotations

import numpy as np
import shapely

from velplan.analysis.numbering import position_index
from velplan.forces.agreement import ForceAnalysis
from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Arrow, Circle, Polyline, Text
from velplan.views.base import View, make_view, place_labels, unit
from velplan.views.base import number as _num
from velplan.views.forces.arrows import arrow_obstacle
from velplan.views.forces.common import (
    ForceSizes, Sketch, anchor_of, force_text, newton, newton_metre, note_lines, number_text,
    polygon_layers, slug, title_lines, unit_vector, xy)

#: Polygon vectors shorter than this share one label with their neighbours, mm.
SHORT_VECTOR_MM = 2.5
#: Construction lines run this far past the points they join, mm.
LINE_OVERRUN_MM = 8.0


def polygon_extent(poly, position: int) -> tuple[float, float]:
    """Width and height of the polygon's vertices at position number ``position`` (1…n) at
    μF = 1 N/mm, i.e. N."""
    verts = poly.vertices(1.0)
    z = np.asarray(verts[position_index(position, len(verts))])
    z = z[np.isfinite(z)]
    return float(np.ptp(z.real)), float(np.ptp(z.imag))


def polygon_view(fa: ForceAnalysis, group: str, position: int, *, mu_f: float, lang: Language = "ru",
                 sizes: ForceSizes = ForceSizes()) -> View:
    """The force polygon of `group` (or ``"crank"``) at position number ``position`` (1…n), at
    μF (N/mm).

    Returns
    -------
    View
        ``to_view`` maps polygon mm (pole at 0) to the view's mm; ``meta["vertices"]``
        holds the drawn vertices (complex, mm from the pole), ``meta["labels"]`` the vector
        labels in drawing order.
    """
    i, number = position_index(position, len(fa.kinematics)), position
    ks = fa.kinetostatics
    mech = ks.mechanism
    poly = ks.polygons[group]
    vec_layer, line_layer, text_layer = polygon_layers(number, group)
    z = np.asarray(poly.vertices(mu_f)[i])
    names = [n for n, _ in poly.vectors] + [n for n, _ in poly.closing_vectors]
    sk = Sketch()
    _draw_construction_lines(sk, poly, z, i, line_layer)
    drawn = _draw_vectors(sk, names, z, len(poly.vectors), vec_layer)
    sk.items.append(Circle((0.0, 0.0), 0.7, vec_layer, "thin", "solid"))
    texts = _vector_labels(drawn, z, text_layer, sizes.label_mm)
    items = sk.items + list(place_labels(texts, sk.clear_of(), rings=10))
    head = (label("force_plan_crank", lang).format(name=mech.crank.link) if group == "crank"
            else label("force_plan_group", lang).format(name=group))
    items += title_lines(items, [
        (head, sizes.title_mm),
        (f"μF = {number_text(mu_f, lang)} {newton(lang)}/{unit('mm', lang)}", sizes.label_mm)],
        text_layer)
    items += note_lines(items, [(r, sizes.label_mm) for r in _results(ks, group, i, lang)],
                        text_layer)
    return make_view(f"polygon-{number}-{slug(group)}", items, pad_mm=2.0, mu=None,
                     origin=(0.0, 0.0),
                     meta={"group": group, "number": number, "index": i, "mu_f": mu_f,
                           "vertices": tuple(complex(v) for v in z),
                           "labels": tuple(names)})


def _draw_construction_lines(sk: Sketch, poly, z, i: int, layer: str) -> None:
    """The lines of the two unknown directions, through the last known vertex and through the
    pole, crossing where they meet."""
    if len(poly.closing) != 2 or not np.all(np.isfinite(z)):
        return
    m = len(poly.vectors)
    x = z[m + 1]
    for through, (_, d) in ((z[m], poly.closing[0]), (z[0], poly.closing[1])):
        u = complex(d[i])
        t = ((x - through) * u.conjugate()).real
        lo, hi = min(0.0, t) - LINE_OVERRUN_MM, max(0.0, t) + LINE_OVERRUN_MM
        seg = [xy(through + u * lo), xy(through + u * hi)]
        sk.items.append(Polyline(seg, layer, "thin"))
        sk.obstacles.append(shapely.LineString(seg).buffer(0.4))


def _draw_vectors(sk: Sketch, names, z, first_closing: int, layer: str) -> list[tuple]:
    """The vectors head to tail, the found ones thick. Returns (label, tail, head, found) of
    those drawn (of some length, finite)."""
    drawn: list[tuple[str, np.ndarray, np.ndarray, bool]] = []
    for k, name in enumerate(names):
        a, b = xy(z[k]), xy(z[k + 1])
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            continue
        if np.hypot(*(b - a)) < 1e-9:
            continue
        found = k >= first_closing
        arrow = Arrow(a, b, layer, "thick" if found else "thin")
        sk.items.append(arrow)
        sk.obstacles.append(arrow_obstacle(arrow))
        drawn.append((name, a, b, found))
    return drawn


def _vector_labels(drawn, z, layer: str, size: float) -> list[Text]:
    """A label beside each vector on the polygon's outer side; a run of short vectors shares
    one, written away from the polygon's centre."""
    pts = np.array([xy(v) for v in z if np.isfinite(v)])
    area = (0.5 * float(np.sum(pts[:-1, 0] * pts[1:, 1] - pts[1:, 0] * pts[:-1, 1]))
            if len(pts) > 2 else 0.0)
    outward = -1.0 if area > 1e-6 else 1.0  # left of the direction, unless the polygon is ccw
    texts: list[Text] = []
    k = 0
    while k < len(drawn):
        name, a, b, _ = drawn[k]
        if np.hypot(*(b - a)) >= SHORT_VECTOR_MM:
            u = unit_vector(b - a)
            n = outward * np.array([-u[1], u[0]])
            where = (a + b) / 2 + n * (0.9 + 0.45 * size)
            texts.append(Text(where, force_text(name), layer, size, anchor_of(n), "middle"))
            k += 1
            continue
        run = [drawn[k]]
        while k + len(run) < len(drawn) and np.hypot(*(drawn[k + len(run)][2] - drawn[
                k + len(run)][1])) < SHORT_VECTOR_MM:
            run.append(drawn[k + len(run)])
        texts.append(_run_label(run, pts.mean(axis=0), layer, size))
        k += len(run)
    return texts


def _run_label(run, centre, layer: str, size: float) -> Text:
    """One label for a run of short vectors, beside its middle away from `centre`."""
    mid = (run[0][1] + run[-1][2]) / 2
    away = mid - centre
    away = unit_vector(away) if np.hypot(*away) > 1e-6 else np.array([0.0, 1.0])
    return Text(mid + away * (1.2 + 0.45 * size), ", ".join(force_text(r[0]) for r in run),
                layer, size, anchor_of(away), "middle")


def _results(ks, group: str, i: int, lang: Language) -> list[str]:
    """The results read off the polygon: every reaction of the group, M_b for the crank."""
    results = []
    for rc in ks.reactions.values():
        if rc.pair.group == group:
            results.append(f"{force_text(rc.label)} = {_num(float(rc.magnitude[i]), lang)} "
                           f"{newton(lang)}")
    if group == "crank":
        results.append(f"{label('symbol_balancing_moment', lang)} = "
                       f"{_num(float(ks.balancing_moment[i]), lang)} {newton_metre(lang)} "
                       f"({label('method_kinetostatics', lang)})")
    return results
