"""Every sheet of every bundled example and of every class III catalogue mechanism, in the four
languages: no text over text (estimated boxes overlapping by more than 0.5 mm²), every text
inside the frame and every glyph in the bundled font; plans and schemes filling their zones;
the data block, the readings and the title in the sheet's language. Each sheet is built once
per module (`built`) and shared by the checks; the checks made in every language are in
`test_sheet_quality_<lang>.py` (one file each, so that they spread over the test workers), with
the checks of the English kinematic sheets on A1 and A3 (zones filled, the bundled sheets
legible on A3), whose sheets that file builds anyway."""

import pytest

import velplan
from velplan.sheets.kinematic import build_sheet
from tests.sheet.quality import TRIADS, assert_legible, studies  # noqa: F401 - fixtures


def test_the_catalogue_has_class_iii_mechanisms():
    assert "triad-rocker" in TRIADS
    for name in TRIADS:
        assert any(g.kind == "triad" for g in velplan.load(name).groups), name


def test_all_twelve_velocity_plans_on_one_sheet(tmp_path, capsys):
    from velplan.cli import main
    from velplan.sheets.layout import MIN_PLAN_MM

    study = velplan.Study("shaper")
    sheet = build_sheet(study, kind="velocity", plans=tuple(range(1, 13)), lang="en")
    names = sorted(k for k in sheet.views if k.startswith("plan-v-"))
    assert len(names) == 12
    # one μv would leave some of the twelve plans under the legible size: each states its own
    assert len({sheet.scales[k] for k in names}) == 3
    kin = study.kinematics
    sheet = build_sheet(study, kind="velocity", plans=tuple(range(1, 13)), lang="en",
                        scale_per_plan=True)
    assert len({sheet.scales[k] for k in names}) == 3  # each fitted: 0.02, 0.025, 0.04
    for name in names:
        i = sheet.plan_index[name]
        longest = max(float(abs(complex(*kin.velocities[i, j]))) for j in range(len(kin.point_index)))
        assert longest / sheet.scales[name] >= MIN_PLAN_MM["A1"] or longest == 0
    assert main(["sheet", "shaper", "--kind", "velocity", "--plans", "all", "-o", str(tmp_path / "a.svg")]) == 0
    assert main(["sheet", "shaper", "--plans", "1,x", "-o", str(tmp_path / "b.svg")]) == 2
    assert "(or give: all)" in capsys.readouterr().err


def test_values_read_off_the_plans_are_within_half_the_drafting_step():
    from velplan.views.readings import PRECISION_MM, readings

    study = velplan.Study("shaper")
    sheet = build_sheet(study, lang="ru")
    assert "readings" in sheet.views
    count = 0
    for name, res in sheet.plans.items():
        for point, read, exact in readings(res, sheet.plan_index[name] + 1):
            # a length read to 0.5 mm is off by at most 0.25 mm: 0.25·μ in value
            assert abs(read - exact) <= 0.5 * PRECISION_MM * res.scale * (1 + 1e-9), (name, point)
            count += 1
    assert count >= 20


def test_the_title_names_the_mechanism_in_the_sheets_language(tmp_path):
    study = velplan.Study("shaper")
    assert build_sheet(study, lang="ru").info.title == "Кинематический анализ механизма: поперечно-строгальный станок"
    assert build_sheet(study, lang="zh").info.title == "机构运动分析: 牛头刨床"
    from importlib.resources import files

    src = (files("velplan.examples") / "crank-slider.toml").read_text("utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text(src.replace('zh = "曲柄滑块机构"', 'de = "Schubkurbel"'))
    with pytest.raises(velplan.MechanismError, match=r"^\[names\]: unknown language 'de'; known languages: en, ru, uk, zh$"):
        velplan.load(bad)


@pytest.mark.parametrize("name", TRIADS)
def test_class_iii_velocity_plans_of_every_position_on_one_sheet(studies, name):
    """``--kind velocity --plans all``: twelve plans by Assur's special point, each a view of
    its own, legible together (here in Chinese, the widest letters)."""
    try:
        sheet = build_sheet(studies[name], kind="velocity", plans=tuple(range(1, 13)), lang="zh")
    except velplan.errors.ScaleError as exc:  # a large scheme leaves too little room: said so
        assert name != "triad-rocker" and "do not fit A1" in str(exc) and "\n" not in str(exc)
        return
    assert len([k for k in sheet.views if k.startswith("plan-v-")]) == 12
    assert_legible(sheet, "A1", name, "velocity plans")
