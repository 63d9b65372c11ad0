"""What the gallery checks of issue 32's "Done when" share (`test_gallery_marks_a1.py`,
`test_gallery_marks_a3.py`, `test_gallery_figures.py`, split so that the test workers share the
sheets out): every bundled and catalogue mechanism's kinematic, force and dynamics sheets, in a
rotating language (the mechanism's index mod 4: en, ru, uk, zh), each built once per module,
and the measures the checks make on them."""

from __future__ import annotations

import re

import numpy as np
import shapely

import velplan
from velplan.errors import VelplanError
from velplan.mechanism.loader import catalogue_names
from velplan.render.i18n import label
from velplan.render.layout import crossed_letters, label_box, overlapping_labels
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Text
from velplan.render.shapes import MIN_WIDTH_FACTOR, script_size, text_runs
from velplan.sheets.dynamics import build_dynamics_sheet
from velplan.sheets.forces import build_force_sheet, has_forces
from velplan.plans.text import label_of
from velplan.sheets.kinematic import build_sheet
from velplan.views.base import subscript
from velplan.views.forces import force_text, group_layers, lever_layers, polygon_layers
from velplan.views.plan import MIN_VECTOR_MM, labelled_vectors

LANGS = ("en", "ru", "uk", "zh")
NAMES = tuple(velplan.example_names()) + tuple(catalogue_names())
#: The ESKD minimum height of printed text, letters and indices, mm.
MIN_TEXT_MM = 2.5
#: A label's own anchor must be within this of it, at print size, mm.
ANCHOR_MM = 6.0


def lang_of(name: str) -> str:
    """The language the gallery checks `name` in: its index in :data:`NAMES` mod 4."""
    return LANGS[NAMES.index(name) % 4]


#: Sheets that two modules run by one worker (`tests/scheduling.py`) both check, kept for the test
#: process: (name, kind, lang, fmt) → the sheet. The catalogue gallery (`test_catalogue_gallery.py`,
#: `_a3.py`) checks every catalogue mechanism's kinematic sheet in Russian; of those whose gallery
#: language is Russian too, the sheet is built once for both.
SHARED: dict = {}


def shared(name: str, kind: str, lang: str, fmt: str, make):
    """The sheet `make()` builds, kept in :data:`SHARED` where another module checks it too."""
    key = (name, kind, lang, fmt)
    if key in SHARED:
        return SHARED[key]
    sheet = make()
    if kind == "kinematic" and lang == "ru" == lang_of(name) and name in catalogue_names():
        SHARED[key] = sheet
    return sheet


class GallerySheets(dict):
    """(name, kind) → the sheet in the format `fmt` and the mechanism's language; a sheet the
    mechanism cannot have (a dynamics sheet without masses, a force sheet too large for A3)
    is None, with the one-line reason in `refused`."""

    MAKERS = {"kinematic": build_sheet, "forces": build_force_sheet, "dynamics": build_dynamics_sheet}

    def __init__(self, fmt: str):
        super().__init__()
        self.fmt, self.studies, self.refused = fmt, {}, {}

    def __missing__(self, key):
        name, kind = key
        study = self.studies.setdefault(name, velplan.Study(name))
        try:
            sheet = shared(name, kind, lang_of(name), self.fmt,
                           lambda: self.MAKERS[kind](study, lang=lang_of(name), fmt=self.fmt))
        except VelplanError as exc:
            self.refused[key] = str(exc)
            sheet = None
        self[key] = sheet
        return sheet

    def found(self, kinds: tuple[str, ...]) -> dict[str, list[str]]:
        """`violations` of the sheets of `kinds`, made once."""
        cache = self.__dict__.setdefault("_found", {})
        if kinds not in cache:
            cache[kinds] = violations(self, kinds)
        return cache[kinds]

    def all(self, kinds=("kinematic", "forces", "dynamics")):
        """(name, kind, sheet) of every sheet of `kinds` the gallery has."""
        for name in NAMES:
            for kind in kinds:
                if kind == "forces" and not has_forces(velplan.load(name)):
                    continue
                if (sheet := self[name, kind]) is not None:
                    yield name, kind, sheet


def overlaps(scene) -> list[tuple[str, str]]:
    """The pairs of texts that overlap by more than 0.5 mm²."""
    return [(a.text, b.text) for a, b in overlapping_labels(scene, min_area=0.5)]


def crossed_texts(scene) -> list[str]:
    """The texts whose estimated box a thick line or a vector crosses over more than 1 mm
    (the measure of `test_sheet_quality_ru.py`)."""
    lines = [shapely.LineString(p.points) for p in scene.primitives if isinstance(p, Polyline) and p.line == "thick"]
    lines += [shapely.LineString([p.start, p.end]) for p in scene.primitives if isinstance(p, Arrow) and p.length > 0]
    tree = shapely.STRtree(lines)
    out = []
    for t in scene.of_kind(Text):
        box = label_box(t)
        if any(lines[j].intersection(box).length > 1.0 for j in tree.query(box, predicate="intersects")):
            out.append(t.text)
    return out


def printed_height(t: Text) -> float:
    """The smallest height a text is printed at, mm: its letters', or its indices' if it has any."""
    indexed = any(r.script for r in text_runs(t.text))
    return min(t.size_mm, script_size(t.size_mm)) if indexed else t.size_mm


def small_texts(scene, *, title: bool) -> list[str]:
    """The texts printed below :data:`MIN_TEXT_MM` (indices included), or narrowed below type A
    lettering (`MIN_WIDTH_FACTOR` of their normal width: the height is then no excuse), of the
    title block (`title`) or of the rest of the sheet. Boxes elsewhere (`label_box`) are the
    narrowed ones, as printed."""
    return [t.text for t in scene.of_kind(Text)
            if (t.layer == "title") == title and (printed_height(t) < MIN_TEXT_MM - 1e-9
                                                  or t.width_factor < MIN_WIDTH_FACTOR - 1e-9)]


def short_unlisted_vectors(sheet) -> list[str]:
    """The labelled plan vectors shorter than 3 mm not listed under their plan as ≈ 0."""
    out = []
    for name, res in sheet.plans.items():
        number = sheet.plan_index[name] + 1
        texts = " ".join(t.text for t in sheet.views[name].primitives if isinstance(t, Text))
        for target, (_, length) in labelled_vectors(res, number).items():
            if length < MIN_VECTOR_MM and ("≈ 0 (" if length > 1e-6 else " = 0") not in texts:
                out.append(f"{name}:{target}")
    return out


def ordinate_ranges(sheet) -> list[float]:
    """The ordinate range of each graphical curve of the kinematic diagrams, mm (none without them)."""
    if "diagrams" not in sheet.views:
        return []
    return [float(np.ptp(np.asarray(p.points)[:, 1])) for p in sheet.views["diagrams"].primitives
            if isinstance(p, Polyline) and p.line == "thick" and len(p.points) > 5]


def wittenbauer_range(sheet) -> list[float]:
    """The ΔT range of the sheet's energy–mass diagram, mm, with its tangents' intercepts (none
    without a flywheel to size)."""
    view = sheet.views.get("wittenbauer")
    return [] if view is None else [view.view.meta["delta_T_mm"]]


def panel_ranges(sheet) -> dict[str, float]:
    """The ordinate range of each curve panel of a dynamics sheet, mm."""
    return {name: v.view.meta["span_mm"] for name, v in sheet.views.items() if "span_mm" in v.view.meta}


#: A dynamics panel's ordinate axis numbers at least this many ticks.
MIN_TICKS = 3


def curve_names(sheet) -> list[str]:
    """The curve names of a dynamics sheet's panels that are not nearer to their own curve than
    to every other curve of the panel and the φ axis, or lie farther than :data:`ANCHOR_MM`
    from it, or name a curve twice ("panel: name …")."""
    out = []
    for name, placed in sheet.views.items():
        curves = placed.view.meta.get("curves")
        if not curves:
            continue
        lines = {k: shapely.LineString([placed.to_sheet(p) for p in xy]) for k, xy in curves.items()}
        axis = shapely.LineString([placed.to_sheet((0.0, 0.0)), placed.to_sheet((max(np.asarray(xy)[:, 0].max()
                                                                                      for xy in curves.values()), 0.0))])
        texts = [t for t in placed.primitives if isinstance(t, Text)]
        for k, line in lines.items():
            own = [t for t in texts if t.text == k]
            if len(own) != 1:
                out.append(f"{name}: {k} written {len(own)} times")
                continue
            box = label_box(own[0])
            d = box.distance(line)
            others = [box.distance(g) for j, g in lines.items() if j != k] + ([box.distance(axis)] if len(lines) > 1
                                                                             else [])
            leader = any(isinstance(q, Polyline) and q.line == "thin" and len(q.points) == 2
                         and line.distance(shapely.Point(q.points[0])) < 1e-6
                         and box.buffer(0.6).contains(shapely.Point(q.points[1])) for q in placed.primitives)
            if not leader and (d > ANCHOR_MM or (others and min(others) < d)):
                out.append(f"{name}: {k} {d:.1f} mm from its curve, {min(others, default=np.inf):.1f} from another")
    return out


def ordinate_numbers(sheet) -> list[str]:
    """What is wrong with the numbers on a dynamics sheet's ordinate axes: fewer than
    :data:`MIN_TICKS`, not the sheet's decimal sign or minus sign, a power written as "e";
    a panel's scale without its index ("μ = "); the ordinate axis without its unit."""
    comma = sheet.lang in ("ru", "uk")
    pattern = re.compile(r"−?\d+(,\d+)?" if comma else r"−?\d+(\.\d+)?")
    out = []
    for name, placed in sheet.views.items():
        if "curves" not in placed.view.meta:
            continue
        texts = [t for t in placed.view.primitives if isinstance(t, Text)]
        numbers = [t.text for t in texts if t.anchor == "end" and t.position[0] < placed.view.origin[0]
                   and re.fullmatch(r"[−\-]?[\d.,e+\-]+", t.text)]
        if len(numbers) < MIN_TICKS:
            out.append(f"{name}: {len(numbers)} numbered ticks {numbers}")
        out += [f"{name}: tick {n!r}" for n in numbers if not pattern.fullmatch(n)]
        if any(t.text.startswith("μ = ") for t in texts):
            out.append(f"{name}: a scale μ without its index")
        if not any(re.fullmatch(r".+, \S+", t.text) and t.anchor == "middle" for t in texts):
            out.append(f"{name}: the ordinate axis without its name and unit")
    return out


def ambiguous_plan_letters(sheet) -> list[str]:
    """The image letters of the plans whose own image is not the image nearest to them
    ("nearer: …") or lies farther than :data:`ANCHOR_MM` from their box ("far: …"); a letter
    joined to its image by a leader excepted: the leader names its point."""
    out = []
    for name in sheet.plans:
        placed = sheet.views[name]
        anchors: dict[str, list] = {}
        for target, z in placed.view.meta["images"].items():
            if np.isfinite(z):
                anchors.setdefault(subscript(label_of(target)), []).append(placed.to_sheet((z.real, z.imag)))
        leaders = [np.asarray(p.points) for p in placed.primitives if isinstance(p, Polyline) and p.line == "thin"
                   and len(p.points) == 2]
        points = [(label, xy) for label, xys in anchors.items() for xy in xys]
        for t in placed.primitives:
            if not isinstance(t, Text):
                continue
            own = [xy for part in t.text.split(", ") for xy in anchors.get(part, [])]
            if not own:
                continue
            box = label_box(t)
            d_own = min(box.distance(shapely.Point(xy)) for xy in own)
            others = [box.distance(shapely.Point(xy)) for label, xy in points
                      if label not in t.text.split(", ") and min(np.hypot(*(xy - o)) for o in own) > 0.5]
            led = any(min(np.hypot(*(lp[0] - o)) for o in own) < 1e-6 and box.buffer(0.6).contains(shapely.Point(lp[1]))
                      for lp in leaders)
            if not led and others and min(others) < d_own:
                out.append(f"nearer: {name}:{t.text}")
            elif not led and d_own > ANCHOR_MM:
                out.append(f"far: {name}:{t.text} {d_own:.1f} mm")
    return out


def led(placed, label: Text, own) -> bool:
    """Whether a thin leader of the view `placed` runs from a point of `own` to the box of
    `label`: the leader names its point, wherever the letter stands."""
    box = label_box(label).buffer(0.6)
    return any(isinstance(p, Polyline) and p.line == "thin" and len(p.points) == 2
               and min(np.hypot(*(np.asarray(p.points[0]) - o)) for o in own) < 1e-6
               and box.contains(shapely.Point(p.points[1])) for p in placed.primitives)


def ambiguous_scheme_letters(sheet, kin) -> list[str]:
    """The point letters of the scheme's thick position whose own point is not the point
    nearest to them ("nearer: …"), or lies farther than :data:`ANCHOR_MM` from their box
    ("far: …"); a letter joined to its point by a leader excepted: the leader names its point."""
    scheme = sheet.views["mechanism"]
    t = int(scheme.view.meta["thick"]) - 1  # a position number, 1-based
    points = {subscript(n): scheme.to_sheet(kin.position(n)[t]) for n in kin.point_index}
    points = {k: xy for k, xy in points.items() if np.all(np.isfinite(xy))}
    out = []
    for letter in (p for p in scheme.primitives if isinstance(p, Text) and p.text in points):
        own, box = points[letter.text], label_box(letter)
        if led(scheme, letter, [own]):
            continue
        d_own = box.distance(shapely.Point(own))
        others = [box.distance(shapely.Point(xy)) for k, xy in points.items() if np.hypot(*(xy - own)) > 1.0]
        if others and min(others) < d_own:
            out.append(f"nearer: mechanism:{letter.text}")
        elif d_own > ANCHOR_MM:
            out.append(f"far: mechanism:{letter.text} {d_own:.1f} mm")
    return out


def class_iii_marks(sheet, kin) -> list[str]:
    """What a class III sheet misses: each triad's special point K (a dot with its letter
    within :data:`ANCHOR_MM`, or joined to it by a leader, and two lead lines through it) on
    the scheme in every drawn position, and its
    base link's image as a closed triangle with a dot at each corner on every plan."""
    from velplan.views.mechanism import special_points

    mech = sheet.mechanism
    scheme = sheet.views["mechanism"]
    prims = scheme.primitives
    axes = [shapely.LineString(p.points) for p in prims if isinstance(p, Polyline) and p.line == "axis"]
    missing = []
    for k_name in sorted(special_points(mech)):
        for k in sheet.positions:
            at = scheme.to_sheet(kin.position(k_name)[k - 1])
            letters = [t for t in prims if isinstance(t, Text) and t.text.startswith(subscript(k_name))
                       and (label_box(t).distance(shapely.Point(at)) <= ANCHOR_MM or led(scheme, t, [at]))]
            dot = any(isinstance(p, Circle) and p.fill == "solid" and np.allclose(p.centre, at, atol=1e-6) for p in prims)
            through = sum(a.distance(shapely.Point(at)) < 1e-6 for a in axes)
            if not letters or not dot or through < 2:
                missing.append(f"{k_name} in position {k}: letter {bool(letters)}, dot {dot}, lead lines {through}")
    for group in (g for g in mech.groups if g.kind == "triad"):
        for name in (k for k in sheet.views if k.startswith("plan-")):
            placed, res, i = sheet.views[name], sheet.plans[name], sheet.plan_index[name]
            corners = [placed.to_sheet(res.image(p)[i]) for p in group.joints]
            closed = [np.asarray(p.points) for p in placed.primitives if isinstance(p, Polyline)
                      and len(p.points) == 4 and np.allclose(p.points[0], p.points[-1])]
            dots = [np.asarray(p.centre) for p in placed.primitives if isinstance(p, Circle) and p.fill == "solid"]
            if not any(np.allclose(c[:3], corners, atol=1e-6) for c in closed):
                missing.append(f"{name}: no triangle {''.join(group.joints)}")
            if any(min(np.hypot(*(d - c)) for d in dots) > 1e-6 for c in corners):
                missing.append(f"{name}: a corner of {''.join(group.joints)} without its dot")
    return missing


def _led_to(leaders, box, own) -> bool:
    """Whether one of `leaders` (thin two-point lines) runs from the shape `own` (within 0.05 mm:
    a curve's leader starts on the curve as drawn to the eye) to `box`."""
    near = box.buffer(0.6)
    return any(own.distance(shapely.Point(p.points[0])) < 0.05 and near.contains(shapely.Point(p.points[1]))
               for p in leaders)


def _free_end(a: Arrow, at) -> shapely.Point:
    """The end of a force's arrow away from its point `at` (sheet mm): what its label names."""
    return shapely.Point(a.end if np.hypot(*(np.subtract(a.end, at))) >= np.hypot(*(np.subtract(a.start, at)))
                         else a.start)


def _force_anchors(name: str, placed, lang: str) -> tuple[list[tuple[str, str, object]], str] | None:
    """(label, kind, anchor shape) of every label a force view writes, and its labels' layer:
    a group's point letters, its forces' free ends and its couples' arcs; a polygon's vectors;
    the lever's image letters, the balancing force's arrow and the forces' free ends."""
    meta = placed.view.meta
    prims = placed.primitives
    if name.startswith("group-"):
        _, forces, texts = group_layers(meta["number"], meta["group"])
        arrows = [p for p in prims if isinstance(p, Arrow) and p.layer == forces][:meta["arrows"]]
        arcs = [p for p in prims if isinstance(p, Polyline) and p.layer == forces]
        out = [(t, "point", shapely.Point(placed.to_sheet(p))) for t, p in meta["letters"]]
        out += [(force_text(f), "force", _free_end(a, placed.to_sheet([z.real, z.imag])))
                for (f, z, _), a in zip(meta["forces"], arrows)]
        out += [(c[0], "couple", shapely.LineString(a.points)) for c, a in zip(meta["couples"], arcs)]
        return out, texts
    if name.startswith("polygon-"):
        vectors, _, texts = polygon_layers(meta["number"], meta["group"])
        arrows = [p for p in prims if isinstance(p, Arrow) and p.layer == vectors]
        return [(force_text(f), "force", shapely.LineString([a.start, a.end]))
                for f, a in zip(meta["drawn"], arrows)], texts
    if name.startswith("lever-"):
        _, forces, texts = lever_layers(meta["number"])
        arrows = [p for p in prims if isinstance(p, Arrow) and p.layer == forces]
        if not arrows:
            return None
        out = [(t, "point", shapely.Point(placed.to_sheet(p))) for t, p in meta["letters"]]
        out.append((label("symbol_balancing_force", lang), "force", shapely.MultiPoint([arrows[0].start, arrows[0].end])))
        out += [(force_text(f), "force", _free_end(a, placed.to_sheet(p)))
                for (f, p, _), a in zip(meta["forces"], arrows[1:])]
        return out, texts
    return None


def _dynamics_anchors(name: str, placed) -> tuple[list[tuple[str, str, object]], str] | None:
    """(label, kind, shape) of the energy–mass diagram's letters k, l and position numbers
    (by their points) and of the curve panels' names (by their curves) and marks (by their dots)."""
    meta = placed.view.meta
    if "marks" in meta:
        return [(t, "point", shapely.Point(placed.to_sheet(p))) for t, p in meta["marks"]], "dynamics-labels"
    if "named" in meta:
        return [(t, "curve", shapely.LineString(placed.to_sheet(np.asarray(ps)))) if len(ps) > 1
                else (t, "point", shapely.Point(placed.to_sheet(ps[0]))) for t, ps in meta["named"]], "dynamics-labels"
    return None


def ambiguous_force_labels(sheet, lang: str) -> list[str]:
    """The labels of a force sheet's groups, polygons and levers (points' letters, forces,
    couples) whose own anchor — a point, an arrow's free end, a couple's arc, a polygon's vector —
    is not the nearest anchor of its kind in its view to them ("nearer: …") or lies farther than
    :data:`ANCHOR_MM` from their box ("far: …"), as `tests/forces/test_force_sheet_legibility.py`
    reads them; a label joined to its anchor by a thin leader excepted: the leader names it.
    On a dynamics sheet: the energy–mass diagram's letters k, l and numbers by their points, the
    curves' names by their curves and the marked extremes by their dots."""
    out = []
    for name, placed in sheet.views.items():
        found = _force_anchors(name, placed, lang) or _dynamics_anchors(name, placed)
        if found is None:
            continue
        anchors, layer = found
        leaders = [p for p in placed.primitives if isinstance(p, Polyline) and p.layer == layer
                   and p.line == "thin" and len(p.points) == 2]
        for t in placed.primitives:
            if not isinstance(t, Text) or t.layer != layer:
                continue
            own = [(k, g) for text, k, g in anchors if text == t.text]
            if not own:
                continue
            kind, box = own[0][0], label_box(t)
            if any(_led_to(leaders, box, g) for _, g in own):
                continue
            d_own = min(box.distance(g) for _, g in own)
            others = [box.distance(g) for text, k, g in anchors if k == kind and text != t.text]
            if others and min(others) < d_own:
                out.append(f"nearer: {name}:{t.text}")
            elif d_own > ANCHOR_MM:
                out.append(f"far: {name}:{t.text} {d_own:.1f} mm")
    return out


CHECKS = ("overlap", "crossed", "crossed_thin", "small", "title_small", "short_vector", "diagram", "ambiguous",
          "far_label", "class_iii", "curve_names", "ordinate_numbers")
"""The checks `violations` makes (the last two on dynamics sheets only)."""


def violations(gallery: GallerySheets, kinds: tuple[str, ...]) -> dict[str, list[str]]:
    """Per check, "name/kind: what" of every sheet of `kinds` in the gallery that fails it."""
    out: dict[str, list[str]] = {k: [] for k in CHECKS}
    for name, kind, sheet in gallery.all(kinds):
        where = f"{name}/{kind}"
        out["overlap"] += [f"{where}: {a} | {b}" for a, b in overlaps(sheet.scene)]
        # every crossed text counts (test_sheet_quality_ru.py's bar lets one a sheet pass, four on a triad)
        out["crossed"] += [f"{where}: {t}" for t in crossed_texts(sheet.scene)]
        # the whole rule: thin lines too, but a text's own leader or construction line
        out["crossed_thin"] += [f"{where}: {t}" for t in crossed_by_any_line(sheet.scene)]
        out["small"] += [f"{where}: {t}" for t in small_texts(sheet.scene, title=False)]
        out["title_small"] += [f"{where}: {t}" for t in small_texts(sheet.scene, title=True)]
        if kind == "dynamics":
            out["diagram"] += [f"{where}: Wittenbauer ΔT {r:.1f} mm" for r in wittenbauer_range(sheet)
                               if r < 30.0 - 0.5]
            # the four curve panels share one column: each keeps at least 20 mm of ordinates
            out["diagram"] += [f"{where}: {name} {r:.1f} mm" for name, r in panel_ranges(sheet).items()
                               if r < 20.0]
            out["curve_names"] += [f"{where}: {v}" for v in curve_names(sheet)]
            out["ordinate_numbers"] += [f"{where}: {v}" for v in ordinate_numbers(sheet)]
        if kind in ("forces", "dynamics"):
            for v in ambiguous_force_labels(sheet, lang_of(name)):
                why, _, what = v.partition(": ")
                out["ambiguous" if why == "nearer" else "far_label"].append(f"{where}: {what}")
        if kind != "kinematic":
            continue
        out["short_vector"] += [f"{where}: {v}" for v in short_unlisted_vectors(sheet)]
        out["diagram"] += [f"{where}: {r:.1f} mm" for r in ordinate_ranges(sheet) if r < 30.0 - 0.5]
        for v in ambiguous_plan_letters(sheet) + ambiguous_scheme_letters(sheet, gallery.studies[name].kinematics):
            why, _, what = v.partition(": ")
            out["ambiguous" if why == "nearer" else "far_label"].append(f"{where}: {what}")
        if any(g.kind == "triad" for g in sheet.mechanism.groups):
            out["class_iii"] += [f"{where}: {v}" for v in class_iii_marks(sheet, gallery.studies[name].kinematics)]
    return out


def check_bounds(found: dict[str, list[str]], bounds: dict[str, int]) -> None:
    """Every check's count of violations at most its bound (0 unless `bounds` names a ratchet)."""
    over = {k: (len(v), bounds.get(k, 0), v[:6]) for k, v in found.items() if len(v) > bounds.get(k, 0)}
    assert not over, over


def ambiguous_labels(scene, anchors) -> list[str]:
    """The texts of a figure naming points of `anchors` (name as written → its points, mm; a
    text names each of its parts: "b₂, s₂", "A (P₁₂)") whose own point is not the point nearest
    to their box ("nearer: …") or lies farther than :data:`ANCHOR_MM` from it ("far: …"); a text
    joined to its point by a thin leader excepted: the leader names its point."""
    points = [(name, np.asarray(xy, float)) for name, xys in anchors.items() for xy in xys]
    leaders = [np.asarray(p.points, float) for p in scene.primitives
               if isinstance(p, Polyline) and p.line == "thin" and len(p.points) == 2]
    out = []
    for t in scene.of_kind(Text):
        parts = [t.text] if t.text in anchors else [p for p in re.split(r", | \(|\)", t.text) if p]
        own = [np.asarray(xy, float) for part in parts for xy in anchors.get(part, ())]
        if not own or not all(part in anchors for part in parts):
            continue
        box = label_box(t)
        d_own = min(box.distance(shapely.Point(xy)) for xy in own)
        others = [box.distance(shapely.Point(xy)) for name, xy in points
                  if name not in parts and min(np.hypot(*(xy - o)) for o in own) > 0.5]
        near = box.buffer(0.6)
        if any(min(np.hypot(*(lp[0] - o)) for o in own) < 1e-6 and near.contains(shapely.Point(lp[1])) for lp in leaders):
            continue
        if others and min(others) < d_own:
            out.append(f"nearer: {t.text}")
        elif d_own > ANCHOR_MM:
            out.append(f"far: {t.text} {d_own:.1f} mm")
    return out


def crossed_by_any_line(scene) -> list[str]:
    """The texts whose estimated box any drawn line crosses over more than 1 mm — thin ones
    too (construction and Kennedy lines, other texts' leaders, outlines) — except the text's
    own leader (a thin segment ending at its box) and the frame: the whole of "no text crossed
    by a drawn line other than its own leader"."""
    return [t.text for t in crossed_letters([p for p in scene.primitives if getattr(p, "layer", "") != "frame"])]
