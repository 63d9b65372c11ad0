"""`least_extent`'s height counts what `_draw` surely draws round the panels' points (joint
circles, the rings of outer pairs and blocks, block corners, guide ends): still never above the
drawing, for every bundled and catalogue mechanism at every size the sheet tries, and never
below the points' span alone (the bound it replaced)."""

import numpy as np
import pytest

import velplan
from velplan.mechanism.loader import catalogue_names
from velplan.sheets.structure import FIGURE_SIZES, _joints
from velplan.study import Study
from velplan.views import structure as vs
from velplan.views.base import bounds_of

NAMES = (*velplan.example_names(), *catalogue_names())


@pytest.mark.parametrize("name", NAMES)
def test_the_least_height_is_below_the_drawing_and_above_the_points(name):
    study = Study(name, n=12)
    mech, joints = study.mechanism, _joints(study)
    for panel_mm, text_mm, title_mm in FIGURE_SIZES:
        kw = dict(lang="ru", panel_mm=panel_mm, text_mm=text_mm, title_mm=title_mm)
        _, y0, _, y1 = bounds_of(vs.structure_view(mech, joints, **kw).primitives)
        _, h = vs.least_extent(mech, joints, **kw)
        assert h <= (y1 - y0) * (1 + 1e-12)
        panels = vs._panels(mech, joints, "ru", text_mm)
        spans = [np.ptp(p.points(), axis=0) for p in panels]
        mu = vs._scale(spans, panel_mm)
        assert vs._least_drawing_height(panels, spans, mu) >= max(float(s[1]) * mu for s in spans)


def test_a_ring_round_the_highest_joint_raises_the_bound_by_its_radius():
    """One panel: an outer joint at the top of a vertical link, a plain one at its foot."""
    panel = vs._Panel({"2"}, {"0", "1"}, ("caption",))
    top, foot = np.array([0.0, 1.0]), np.array([0.0, 0.0])
    panel.vertices["2"] += [top, foot]
    panel.joints += [("A", top, True), ("B", foot, False)]
    spans = [np.ptp(panel.points(), axis=0)]
    h = vs._least_drawing_height([panel], spans, 50.0)
    assert h == pytest.approx(50.0 + vs.RING_MM + vs.JOINT_RADIUS_MM, abs=1e-8)
