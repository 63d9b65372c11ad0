"""The force sheet read as a strict teacher reads it (issue 32, item 8): in every force
polygon each drawn vector is at least 3 mm long with its own arrowhead and its own label
beside it, the shorter ones listed as ≈ 0 with their values; the crank's two collinear
reactions both show; every reaction is written with the equation it comes from, and that
equation holds; on the groups the labels of the forces and of the couples sit by their own
arrows' free ends and arcs, and no force runs along a link."""

import math
import re

import numpy as np
import pytest
import shapely

from velplan.analysis.numbering import position_index
from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Polyline, Text
from velplan.render.style import SheetStyle
from velplan.sheets.forces import build_force_sheet
from velplan.render.i18n import label
from velplan.views.forces import force_text, group_layers, lever_layers, polygon_layers
from velplan.views.forces.equations import reaction_equations
from velplan.views.forces.polygon import SHORT_VECTOR_MM

from tests.sheet.quality import assert_legible

NAMES = ("shaper", "slider-press", "triad-press", "triad-rocker", "compressor")
LANGS = ("ru", "en")
CASES = [(n, lang) for n in NAMES for lang in LANGS]
NEAR_MM = 6.0


@pytest.fixture(scope="module")
def sheets():
    cache: dict = {}

    def sheet(name, lang):
        if (name, lang) not in cache:
            cache[name, lang] = build_force_sheet(name, lang=lang, fmt="A1")
        return cache[name, lang]
    return sheet


def _views(sheet, prefix):
    return {k: v for k, v in sheet.views.items() if k.startswith(prefix)}


def _of(placed, kind, layer):
    return [p for p in placed.primitives if isinstance(p, kind) and p.layer == layer]


def _value(text: str) -> float:
    return float(text.replace("−", "-").replace(",", "."))


def _segment(a: Arrow):
    return shapely.LineString([a.start, a.end])


def _read_at(text, leaders):
    """Where a label is read: its box, or, for a label with a leader, the leader's other end."""
    box = label_box(text)
    for line in leaders:
        a, b = shapely.Point(line.points[0]), shapely.Point(line.points[-1])
        if box.distance(b) < 0.6:
            return a
        if box.distance(a) < 0.6:
            return b
    return box


def _assert_own_nearest(texts, shapes, where, leaders=()):
    """Each text (by position; a text with one of `leaders` by its leader's other end) is within
    NEAR_MM of its own shape and nearer to it than to any other of `shapes`."""
    for k, t in enumerate(texts):
        box = _read_at(t, leaders)
        d = [box.distance(s) for s in shapes]
        assert d[k] <= NEAR_MM, (where, t.text, round(d[k], 2))
        assert all(d[k] < dj for j, dj in enumerate(d) if j != k), (where, t.text, d)


@pytest.mark.parametrize("name, lang", CASES)
def test_no_text_over_text(name, lang, sheets):
    assert_legible(sheets(name, lang), "A1", name, "forces")


@pytest.mark.parametrize("name, lang", CASES)
def test_polygon_vectors_are_drawn_long_or_listed_as_zero(name, lang, sheets):
    sheet = sheets(name, lang)
    head = SheetStyle().arrow_length_mm
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        poly = sheet.analysis.kinetostatics.polygons[meta["group"]]
        vectors = dict(list(poly.vectors) + list(poly.closing_vectors))
        i = meta["index"]
        vec_layer, _, text_layer = polygon_layers(meta["number"], meta["group"])
        arrows = _of(placed, Arrow, vec_layer)
        texts = _of(placed, Text, text_layer)
        drawn, small = meta["drawn"], [n for n, _ in meta["small"]]
        # every vector of the polygon either drawn or listed, none both
        assert sorted(drawn + tuple(small)) == sorted(vectors), view_name
        assert len(arrows) == len(drawn), view_name
        for name_, a in zip(drawn, arrows):
            # its own arrowhead, at least 3 mm, as long as the force at μF
            assert a.length >= SHORT_VECTOR_MM, (view_name, name_, a.length)
            assert (a.head_length or head) <= 0.75 * a.length, (view_name, name_)
            assert a.length == pytest.approx(abs(vectors[name_][i]) / meta["mu_f"], rel=1e-9)
        for name_ in small:
            assert abs(vectors[name_][i]) / meta["mu_f"] < SHORT_VECTOR_MM
            # listed with its value: "G₃ = 58,86 Н"
            m = next(re.search(rf"(?:^|[;:] ){re.escape(force_text(name_))} = ([−\d,.]+) ",
                               t.text + " ") for t in texts
                     if re.search(rf"(?:^|[;:] ){re.escape(force_text(name_))} = ", t.text))
            assert m is not None, (view_name, name_)
            assert _value(m.group(1)) == pytest.approx(abs(vectors[name_][i]), rel=1e-3, abs=1e-6)
        # no two arrowheads in one place
        for j, a in enumerate(arrows):
            for b in arrows[j + 1:]:
                assert math.dist(a.end, b.end) > 1.0, (view_name, a, b)


@pytest.mark.parametrize("name, lang", CASES)
def test_every_polygon_label_is_by_its_own_vector(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        vec_layer, _, text_layer = polygon_layers(meta["number"], meta["group"])
        arrows = _of(placed, Arrow, vec_layer)
        texts = _of(placed, Text, text_layer)
        own = []
        for name_ in meta["drawn"]:
            found = [t for t in texts if t.text == force_text(name_)]
            assert len(found) == 1, (view_name, name_)  # one label per vector, none merged
            own.append(found[0])
        _assert_own_nearest(own, [_segment(a) for a in arrows], view_name, _of(placed, Polyline, text_layer))


@pytest.mark.parametrize("name, lang", CASES)
def test_crank_polygon_shows_both_reactions(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        if meta["group"] != "crank":
            continue
        arrows = _of(placed, Arrow, polygon_layers(meta["number"], "crank")[0])
        assert len(arrows) >= 2, view_name
        heads = [np.asarray(a.end) for a in arrows]
        assert min(math.dist(p, q) for j, p in enumerate(heads) for q in heads[j + 1:]) > 2.0
        # the two are apart along their whole length (side by side where collinear)
        a, b = arrows[0], arrows[-1]
        assert _segment(a).distance(_segment(b)) >= 2.0 or not _segment(a).buffer(0.3).contains(
            _segment(b)), view_name


def _force_lookup(fa, i):
    """Every labelled force of the analysis at position index i (N): actions, components,
    reactions in both senses."""
    out = {f.label: complex(f.vector[i]) for f in fa.actions.forces}
    for poly in fa.kinetostatics.polygons.values():
        for lab, v in list(poly.vectors) + list(poly.closing_vectors):
            out.setdefault(lab, complex(v[i]))
    for rc in fa.kinetostatics.reactions.values():
        k0, k1 = rc.pair.links
        out[rc.label] = complex(rc.force[i])
        out[f"R{k0}{k1}"] = -complex(rc.force[i])
    return out


@pytest.mark.parametrize("name", NAMES)
def test_every_reaction_is_written_with_an_equation_that_holds(name, sheets):
    sheet = sheets(name, "ru")
    fa = sheet.analysis
    n = len(fa.kinematics)
    for k in range(1, n + 1):
        forces = _force_lookup(fa, k - 1)
        scale = max(abs(v) for v in forces.values() if np.isfinite(v))
        for group in fa.kinetostatics.polygons:
            eqs = reaction_equations(fa, group, k)
            pairs = [rc for rc in fa.kinetostatics.reactions.values() if rc.pair.group == group]
            assert len(eqs) == len(pairs)
            for e in eqs:
                assert abs(forces[e.label]) == pytest.approx(e.value, rel=1e-12, abs=1e-9)
                if not e.terms:
                    continue
                total = sum(forces[t] for t in e.terms)
                total = -total if e.negated else total
                assert abs(total - forces[e.label]) <= 1e-9 * scale, (name, k, group, e)
                if e.link is not None:  # ΣF over one link: every term acts on it
                    assert e.label.endswith(e.link) or e.label.endswith("," + e.link)
    # written under the polygons: "R₃₂ = −(R₁₂ + G₂ + Φ₂) = 6295 Н"
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        texts: list[str] = []
        for t in _of(placed, Text, polygon_layers(meta["number"], meta["group"])[2]):
            if t.text.startswith("= ") and texts:  # an equation broken before its result
                texts[-1] = texts[-1].removesuffix(" =") + " = " + t.text.removeprefix("= ")
            else:
                texts.append(t.text)
        for e in reaction_equations(fa, meta["group"], meta["number"]):
            line = next(t for t in texts if t.startswith(force_text(e.label) + " = "))
            assert line.count(" = ") == (2 if e.terms else 1), line
            for term in e.terms:
                assert force_text(term) in line, (view_name, line)
            assert _value(line.rsplit(" = ", 1)[1].split()[0]) == pytest.approx(e.value, rel=1e-3)


@pytest.mark.parametrize("name, lang", CASES)
def test_group_labels_by_their_arrows_and_arcs(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "group-").items():
        meta = placed.view.meta
        _, force_layer, text_layer = group_layers(meta["number"], meta["group"])
        arrows = _of(placed, Arrow, force_layer)[:meta["arrows"]]
        arcs = [p for p in _of(placed, Polyline, force_layer)]
        texts = _of(placed, Text, text_layer)
        labels = [force_text(n) for n, _, _ in meta["forces"]]
        own = [next(t for t in texts if t.text == lab) for lab in labels]
        # a force's label names the free end of its arrow (away from the force's point)
        ends = []
        for (_, z, _), a in zip(meta["forces"], arrows):
            p = placed.to_sheet([z.real, z.imag])
            far = a.end if math.dist(a.end, p) >= math.dist(a.start, p) else a.start
            ends.append(shapely.Point(far))
        _assert_own_nearest(own, ends, view_name)
        couple_texts = [next(t for t in texts if t.text == c[0]) for c in meta["couples"]]
        assert len(arcs) == len(couple_texts)
        _assert_own_nearest(couple_texts, [shapely.LineString(a.points) for a in arcs],
                            view_name)


@pytest.mark.parametrize("name, lang", CASES[::2])
def test_no_force_runs_along_a_link(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "group-").items():
        meta = placed.view.meta
        body, force_layer, _ = group_layers(meta["number"], meta["group"])
        links = shapely.union_all([shapely.LineString(p.points).buffer(0.7)
                                   for p in _of(placed, Polyline, body) if p.line == "thick"])
        for (label, _, _), a in zip(meta["forces"], _of(placed, Arrow, force_layer)):
            shaft = _segment(a)
            hidden = shaft.intersection(links).length / shaft.length
            assert hidden < 0.5, (view_name, label, round(hidden, 2))


@pytest.mark.parametrize("name, lang", CASES)
def test_lever_labels_by_their_arrows(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "lever-").items():
        meta = placed.view.meta
        _, force_layer, text_layer = lever_layers(meta["number"])
        arrows = _of(placed, Arrow, force_layer)
        # the balancing force first, then the forces carried to their images
        assert len(arrows) == len(meta["forces"]) + 1
        names = [label("symbol_balancing_force", lang)] + [force_text(n) for n, _, _ in
                                                           meta["forces"]]
        ends = [[shapely.Point(arrows[0].start), shapely.Point(arrows[0].end)]]
        for (_, p, _), a in zip(meta["forces"], arrows[1:]):
            q = placed.to_sheet(np.asarray(p, float))
            ends.append([shapely.Point(a.end if math.dist(a.end, q) >= math.dist(a.start, q)
                                       else a.start)])
        leaders = _of(placed, Polyline, text_layer)
        for t in _of(placed, Text, text_layer):
            if t.text not in names:
                continue  # a letter of an image point, or a line of the balance
            box = _read_at(t, leaders)  # a label with a leader read at its other end
            d = [min(box.distance(e) for e in es) for es in ends]
            k = int(np.argmin(d))
            assert names[k] == t.text and d[k] <= NEAR_MM, (view_name, t.text, names[k], d[k])


def test_on_a3_the_notes_keep_to_the_polygon_width_and_the_triad_press_fits():
    """The ≈ 0 list and the equations are wrapped to the polygon's width (an equation broken
    before its result), so the class III press's force sheet fits A3 as before."""
    sheet = build_force_sheet("triad-press", lang="ru", fmt="A3")
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        layers = polygon_layers(meta["number"], meta["group"])
        arrows = _of(placed, Arrow, layers[0])
        bottom = min(min(a.start[1], a.end[1]) for a in arrows)
        texts = _of(placed, Text, layers[2])
        notes = [t for t in texts if label_box(t).bounds[3] < bottom - 1.0]
        others = [shapely.LineString(p.points) for p in _of(placed, Polyline, layers[1])]
        others += [_segment(a) for a in arrows] + [label_box(t) for t in texts if t not in notes]
        x0, _, x1, _ = shapely.union_all(others).bounds
        assert notes, view_name
        for t in notes:
            box = label_box(t).bounds
            assert box[2] - box[0] <= max(x1 - x0, 40.0) + 0.5, (view_name, t.text)


@pytest.mark.parametrize("name, lang", CASES)
def test_no_line_crosses_a_polygon_label(name, lang, sheets):
    sheet = sheets(name, lang)
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        vec_layer, line_layer, text_layer = polygon_layers(meta["number"], meta["group"])
        lines = [_segment(a) for a in _of(placed, Arrow, vec_layer)]
        lines += [shapely.LineString(p.points) for layer in (vec_layer, line_layer)
                  for p in _of(placed, Polyline, layer)]
        for t in _of(placed, Text, text_layer):
            box = label_box(t)
            assert all(line.intersection(box).length < 0.5 for line in lines), (view_name, t.text)
