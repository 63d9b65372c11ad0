"""Zhukovsky's lever on the force sheets is drawn at least `MIN_LEVER_MM` across (issue 32,
item 8: a 35 mm lever carrying twenty forces piles their labels on one another): on every
bundled and catalogue mechanism's force sheet that builds on A1 and A3 (the gallery's
rotating language), the lever's turned velocity plan, measured from the kinematics at the
sheet's μv, is at least the floor; the other drawings shrink first, and a sheet that cannot
give the lever its floor refuses with a one-line ScaleError naming the lever. The gallery's
checks run on the sheets the force galleries build (`lever_checks.py`, called from
`test_gallery_marks_a1_forces.py` and `test_gallery_marks_a3_forces.py`); here the press's
lever and the shrinking rows."""

import pytest

from velplan.errors import ScaleError
from velplan.sheets.forces import MIN_LEVER_MM, build_force_sheet
from velplan.sheets.solver import ShrinkingRows
from velplan.views.base import make_view
from velplan.render.scene import Polyline

from tests.sheet.lever_checks import plan_span


def test_triad_press_a3_lever_is_legible_now():
    """The sheet of issue 32's item 8 (a 35 mm lever before): a lever of 70 mm on A3, the
    initial link's polygon under its link to make the room."""
    sheet = build_force_sheet("triad-press", fmt="A3", lang="ru")
    (k,) = sheet.positions
    assert plan_span(sheet.analysis, k) / sheet.scales[f"lever-{k}"] >= MIN_LEVER_MM["A3"]
    crank, poly = sheet.views[f"group-{k}-crank"], sheet.views[f"polygon-{k}-crank"]
    assert poly.bounds[3] <= crank.bounds[1] + 1e-6  # under it
    assert abs(poly.x - crank.x) < 1e-6


class _Boxes(ShrinkingRows):
    """Square drawings of side span/scale; scales halve down to a least side of 10 mm."""

    def view(self, ref):
        side = self.span[ref] / self.scale[ref]
        return make_view(ref, [Polyline([(0.0, 0.0), (side, side)], "l")], pad_mm=0.0)

    def entity(self, ref):
        return ref

    def smaller(self, entity):
        nxt = 2.0 * self.scale[entity]
        return nxt if self.span[entity] / nxt >= 10.0 else None

    def fail(self, why):
        return ScaleError(why)


def test_fit_mode_stacks_only_the_units_that_fit_a_row():
    """Mode "fit": a unit of two 30 mm drawings in a 70 mm row is stacked (30 mm wide), one
    of 50 mm drawings stays side by side (the stack would be 100 mm tall)."""
    span = {"a": 30.0, "b": 30.0, "c": 50.0, "d": 50.0}
    rows = _Boxes([[["a", "b"], ["c", "d"]]], (0.0, 0.0, 500.0, 70.0), 5.0, 70.0, "fit",
                  span, dict.fromkeys(span, 1.0))
    assert rows.solve()
    assert rows.unit_size(["a", "b"]) == pytest.approx((30.0, 65.0))
    assert rows.unit_size(["c", "d"]) == pytest.approx((105.0, 50.0))
    placed: dict = {}
    rows.place_unit(["a", "b"], 0.0, 70.0, placed, {})
    assert placed["a"].y == pytest.approx(40.0) and placed["b"].y == pytest.approx(5.0)  # 5 mm gap
