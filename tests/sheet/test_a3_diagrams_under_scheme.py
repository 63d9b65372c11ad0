"""Issue 32 on A3: a sheet whose compact diagrams find no room in a free spot nor beside its plans
(the triad press: its table at the ESKD 2.5 mm moved left of the title block, the plans right of
the scheme) gets them under the scheme, the table back over the title block and the plans fitted
again right of the scheme above it; the scheme keeps its scale and the plans lose nothing."""

import numpy as np
import pytest

import velplan
from velplan.sheets.kinematic import build_sheet
from velplan.sheets.layout import MIN_CRANK_MM, MIN_ORDINATE_MM
from velplan.sheets.skeleton import sheet_request
from velplan.render.scene import Polyline

NAME = "triad-press"


@pytest.fixture(scope="module")
def study():
    return velplan.Study(NAME)


@pytest.fixture(scope="module", params=["ru", "uk"])
def sheets(request, study):
    """(the sheet with its diagrams, the same sheet asked without them, its request)."""
    lang = request.param
    return (build_sheet(study, fmt="A3", lang=lang), build_sheet(study, fmt="A3", lang=lang, diagrams=False),
            sheet_request(NAME, fmt="A3", lang=lang))


def test_the_block_lies_under_the_scheme_left_of_the_table_and_the_title_block(sheets):
    sheet, _, req = sheets
    fx0, fy0, fx1, fy1 = req.area
    block, scheme, table = (sheet.views[k].bounds for k in ("diagrams", "mechanism", "table"))
    assert (block[0], block[1]) == pytest.approx((fx0, fy0))
    assert block[3] <= scheme[1] - req.gap + 1e-6
    assert block[2] <= min(table[0], req.title_block[0]) - req.gap + 1e-6
    assert table[1] >= req.title_block[3] and table[2] == pytest.approx(fx1)  # over the title block
    curves = [np.asarray(p.points) for p in sheet.views["diagrams"].primitives
              if isinstance(p, Polyline) and p.line == "thick" and len(p.points) > 5]
    assert len(curves) == 3 and min(np.ptp(c[:, 1]) for c in curves) >= MIN_ORDINATE_MM - 1e-6


def test_the_plans_stand_right_of_the_scheme_above_the_table(sheets):
    sheet, _, req = sheets
    scheme, table = sheet.views["mechanism"].bounds, sheet.views["table"].bounds
    plans = [v.bounds for k, v in sheet.views.items() if k.startswith("plan-")]
    assert len(plans) == 2
    for b in plans:
        assert b[0] >= scheme[2] + req.gap - 1e-6 and b[1] >= table[3] + req.gap - 1e-6 and b[3] <= req.area[3]


def test_the_scheme_keeps_its_scale_and_no_plan_is_drawn_smaller_than_without_the_diagrams(sheets, study):
    """Scale for scale with the sheet asked without diagrams: μl the same (its crank at least
    `MIN_CRANK_MM`), and each plan's μ the same or finer (a larger drawing)."""
    sheet, bare, _ = sheets
    assert "diagrams" not in bare.views
    assert sheet.scales["mu_l"] == bare.scales["mu_l"]
    assert study.mechanism.crank.length / sheet.scales["mu_l"] >= MIN_CRANK_MM
    assert set(sheet.plans) == set(bare.plans)
    for name in bare.plans:
        assert sheet.scales[name] <= bare.scales[name] * (1 + 1e-9), name

