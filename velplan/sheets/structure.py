"""The structural analysis on the kinematic sheet: the figure of `velplan.views.structure`
(the initial mechanism and each Assur group drawn apart) in free space of the drawing area,
where it fits legibly — its letters at least 2.5 mm, none over another nor crossed by its
lines, nothing over another view or the title block. It never takes room from the views already placed.

Examples
--------
>>> from velplan.study import Study
>>> view = structure_figure(Study("four-bar", n=12), "en", *FIGURE_SIZES[-1])
>>> view.name, 60.0 < view.width_mm < 200.0
('structure', True)
"""

from __future__ import annotations

import numpy as np
import shapely

from velplan.errors import ScaleError
from velplan.mechanism.drawn_write import drawn_tables
from velplan.render.layout import label_box, overlapping_labels
from velplan.render.scene import Arrow, Polyline, Scene, Text
from velplan.sheets.layout import free_spot
from velplan.study import Study
from velplan.views.base import PlacedView, View, make_view
from velplan.views.structure import FigureLayout, figure_layout, figure_scale, least_extent

#: (widest panel, letters, heading) of the figure, mm, the largest first; the letters never
#: under 2.5 mm (ESKD's smallest legible height on a sheet).
FIGURE_SIZES: tuple[tuple[float, float, float], ...] = (
    (90.0, 3.5, 5.0), (70.0, 3.5, 5.0), (55.0, 3.5, 5.0), (70.0, 2.5, 3.5), (55.0, 2.5, 3.5),
    (45.0, 3.5, 5.0), (45.0, 2.5, 3.5), (35.0, 2.5, 3.5))
#: Margin of the figure's view around what it draws, mm.
PAD_MM = 2.0
#: Shortest crank the figure may show, mm (as on the scheme).
MIN_CRANK_MM = 8.0


def _joints(study: Study) -> list:
    """The study's mechanism as drawn joints (`drawn_tables`), at `_drawn_pose`."""
    return drawn_tables(study.mechanism, *_drawn_pose(study))["joint"]


def _drawn_pose(study: Study):
    """(positions m as x + iy, link angles rad) at the study's position where its worst
    conditioned group is best conditioned (the figure shows its groups clearly apart)."""
    k = study.kinematics
    cond = k.condition.min(axis=1) if k.condition.shape[1] else np.ones(len(k.valid))
    i = int(np.argmax(np.where(k.valid, cond, -1.0)))
    at = {n: complex(*k.positions[i, j]) for n, j in k.point_index.items()}
    return at, {n: float(k.angles[i, j]) for n, j in k.link_index.items()}


def structure_figure(study: Study, lang: str, panel_mm: float, text_mm: float, title_mm: float,
                     joints: list | None = None, layout: FigureLayout | None = None) -> View:
    """The figure as the sheet's view ``"structure"``: its widest panel ``panel_mm`` wide,
    letters ``text_mm`` and heading ``title_mm`` high, mm; its ``meta`` gives ``text_mm`` and
    ``crank_mm``, the crank's length as drawn, mm. ``joints``: the drawn joints, if known;
    ``layout``: the figure's `figure_layout` with these arguments, if made."""
    joints = _joints(study) if joints is None else joints
    crank = study.mechanism.crank.length * figure_scale(study.mechanism, joints, panel_mm)
    scene = (layout or figure_layout(study.mechanism, joints, lang=lang, panel_mm=panel_mm, text_mm=text_mm,
                                     title_mm=title_mm)).scene()
    return make_view("structure", scene.primitives, pad_mm=PAD_MM, meta={"text_mm": text_mm, "crank_mm": crank})


#: How far a thick line or a vector may run through a letter's box before it is crossed, mm.
CROSSING_MM = 1.0


def _crossed(view: View) -> bool:
    """Whether a thick line or a vector of the figure runs through one of its letters."""
    lines = [shapely.LineString(p.points) for p in view.primitives if isinstance(p, Polyline) and p.line == "thick"]
    lines += [shapely.LineString([p.start, p.end]) for p in view.primitives if isinstance(p, Arrow) and p.length > 0]
    if not lines:
        return False
    tree = shapely.STRtree(lines)
    return any(lines[j].intersection(box).length > CROSSING_MM
               for box in (label_box(t) for t in view.primitives if isinstance(t, Text))
               for j in tree.query(box, predicate="intersects"))


def place_structure(study: Study, lang: str, views: dict[str, PlacedView], area, title_block,
                    gap: float, required: bool) -> PlacedView | None:
    """The figure at the largest of `FIGURE_SIZES` whose letters neither overlap nor are
    crossed by its lines, in a free
    spot of ``area`` (sheet mm) clear of ``views`` and the ``title_block`` by ``gap`` mm, the
    spot nearest the scheme's lower left corner; None where there is none, or ScaleError
    (one line) when ``required``."""
    taken = [v.bounds for v in views.values()] + [title_block]
    corner = (views["mechanism"].bounds[0], views["mechanism"].bounds[1])
    joints = _joints(study)
    mech = study.mechanism
    for sizes in FIGURE_SIZES:  # a size whose crank or least extent rules it out is not drawn
        panel_mm, text_mm, title_mm = sizes
        if mech.crank.length * figure_scale(mech, joints, panel_mm) < MIN_CRANK_MM - 1e-9:
            continue
        w, h = least_extent(mech, joints, lang=lang, panel_mm=panel_mm, text_mm=text_mm, title_mm=title_mm)
        if free_spot(w + 2 * PAD_MM - 1e-6, h + 2 * PAD_MM - 1e-6, taken, area, gap, corner) is None:
            continue
        # its texts placed round the panels' boxes (each panel drawn once): they alone find no spot
        layout = figure_layout(mech, joints, lang=lang, panel_mm=panel_mm, text_mm=text_mm, title_mm=title_mm)
        w, h = layout.text_extent()
        if free_spot(w + 2 * PAD_MM - 1e-6, h + 2 * PAD_MM - 1e-6, taken, area, gap, corner) is None:
            continue
        view = structure_figure(study, lang, *sizes, joints=joints, layout=layout)
        at = free_spot(view.width_mm, view.height_mm, taken, area, gap, corner)  # the cheaper test first
        if at is None or overlapping_labels(Scene(view.primitives, view.width_mm, view.height_mm),
                                            min_area=0.05) or _crossed(view):
            continue
        return view.at(*at)
    if required:
        small = structure_figure(study, lang, *FIGURE_SIZES[-1], joints=joints)
        raise ScaleError(f"the structural analysis ({small.width_mm:.0f} × {small.height_mm:.0f} mm with "
                         f"letters of {FIGURE_SIZES[-1][1]:g} mm) finds no free space on the sheet; "
                         f"use a larger --format, or --structure no")
    return None
