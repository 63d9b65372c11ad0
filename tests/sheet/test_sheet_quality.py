"""Every sheet of every bundled example and of every class III catalogue mechanism, in the four
languages: no text over text (estimated boxes overlapping by more than 0.5 mm²), every text
inside the frame and every glyph in the bundled font; plans and schemes filling their zones;
the data block, the readings and the title in the sheet's language. Each sheet is built once
per module (`built`) and shared by the checks."""

from importlib.resources import files

import pytest
import shapely

import velplan
from velplan.render.fonts import missing_in_bundled
from velplan.render.layout import label_box, overlapping_labels
from velplan.render.scene import Text
from velplan.sheets.dynamics import build_dynamics_sheet
from velplan.sheets.forces import build_force_sheet, has_forces
from velplan.sheets.frame import frame_bounds
from velplan.sheets.kinematic import build_sheet
from tests.sheet.test_catalogue_gallery import zone_shares

LANGS = ("en", "ru", "uk", "zh")
#: The catalogue's class III mechanisms (``kind = "triad"`` files): every sheet kind of each.
TRIADS = tuple(sorted(p.name[:-5] for p in files("velplan.catalogue").iterdir()
                      if p.name.endswith(".toml") and 'kind = "triad"' in p.read_text("utf-8")))


@pytest.fixture(scope="module")
def studies():
    return ({n: velplan.Study(n) for n in velplan.example_names() + list(TRIADS)}
            | {"shaper-δ": velplan.Study("shaper", delta=0.05)})


@pytest.fixture(scope="module")
def built(studies):
    """sheet(name, kind, lang, fmt): the sheet, built on first use and kept for the module."""
    cache: dict = {}
    makers = {"kinematic": build_sheet, "forces": build_force_sheet,
              "dynamics": build_dynamics_sheet}

    def sheet(name, kind, lang, fmt="A1"):
        key = (name, kind, lang, fmt)
        if key not in cache:
            cache[key] = makers[kind](studies[name], lang=lang, fmt=fmt)
        return cache[key]
    return sheet


def _sheets(studies, lang, built):
    """(name, kind, sheet) of every A1 sheet checked in `lang`."""
    for name, study in studies.items():
        if name == "shaper-δ":
            yield name, "dynamics", built(name, "dynamics", lang)
            continue
        yield name, "kinematic", built(name, "kinematic", lang)
        if has_forces(study.mechanism):
            yield name, "forces", built(name, "forces", lang)
        if name in TRIADS:
            yield name, "dynamics", built(name, "dynamics", lang)


def _assert_legible(sheet, fmt, name, kind):
    """No text over text, every text inside the frame, every glyph in the bundled font."""
    frame = shapely.box(*frame_bounds(fmt)).buffer(1e-6)
    pairs = overlapping_labels(sheet.scene, min_area=0.5)
    assert not pairs, (name, kind, fmt, [(a.text, b.text) for a, b in pairs[:5]])
    for t in sheet.scene.of_kind(Text):
        assert frame.contains(label_box(t)), (name, kind, fmt, t.text)
        assert not missing_in_bundled(t.text), (name, kind, t.text)  # every glyph in Velplan Sans


def test_the_catalogue_has_class_iii_mechanisms():
    assert "triad-rocker" in TRIADS
    for name in TRIADS:
        assert any(g.kind == "triad" for g in velplan.load(name).groups), name


@pytest.mark.parametrize("lang", LANGS)
def test_no_text_over_text_and_all_inside_the_frame(studies, built, lang):
    for name, kind, sheet in _sheets(studies, lang, built):
        _assert_legible(sheet, "A1", name, kind)


@pytest.mark.parametrize("lang", LANGS)
@pytest.mark.parametrize("name", TRIADS)
def test_class_iii_sheets_on_a3_are_legible(built, name, lang):
    """The kinematic and dynamics sheets of a class III mechanism on A3 too; its force sheet
    there either is legible or says in one line that it does not fit (as the press's)."""
    for kind in ("kinematic", "dynamics"):
        _assert_legible(built(name, kind, lang, "A3"), "A3", name, kind)
    try:
        sheet = built(name, "forces", lang, "A3")
    except velplan.errors.ScaleError as exc:
        assert "do not fit A3" in str(exc) and "\n" not in str(exc)
    else:
        _assert_legible(sheet, "A3", name, "forces")


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


def test_bundled_kinematic_sheets_on_a3_are_legible(studies, built):
    """The bundled examples' kinematic sheets on A3 (the catalogue's: `test_catalogue_gallery`)
    hold the bars of A1: no text over text, all inside the frame, every glyph in the font."""
    for name in velplan.example_names():
        _assert_legible(built(name, "kinematic", "en", "A3"), "A3", name, "kinematic")


@pytest.mark.parametrize("fmt", ["A1", "A3"])
def test_schemes_and_plans_fill_at_least_half_their_zones(studies, built, fmt):
    """Each plan spans at least half its grid cell, and the scheme half of its share of the top
    band, along one of the two directions (a standard scale one step larger would not fit)."""
    for name in velplan.example_names() + list(TRIADS):
        sheet = built(name, "kinematic", "en", fmt)
        assert set(sheet.zones) == {"mechanism", *(k for k in sheet.views if k.startswith("plan-"))}
        for view, share in zone_shares(sheet).items():  # a kind's plans share one μ
            assert share >= 0.5, (name, fmt, view, share)


def test_texts_keep_off_the_drawn_lines(studies, built):
    """Estimated text boxes crossed by a thick line or a vector over more than 1 mm: at most
    one per sheet (a position number where a curve crosses the φ axis at that very tick, a
    letter squeezed between vectors; before the numbers moved off the curves, 4 to 8); at
    most three on a class III sheet, whose plans fan the images of six or seven links out of
    one pole (a letter inside the fan has no free side)."""
    from velplan.render.scene import Arrow, Polyline

    for name, kind, sheet in _sheets(studies, "ru", built):
        lines = [shapely.LineString(p.points) for p in sheet.scene.primitives
                 if isinstance(p, Polyline) and p.line == "thick"]
        lines += [shapely.LineString([p.start, p.end]) for p in sheet.scene.primitives
                  if isinstance(p, Arrow) and p.length > 0]
        tree = shapely.STRtree(lines)
        crossed = []
        for t in sheet.scene.of_kind(Text):
            box = label_box(t)
            if any(lines[j].intersection(box).length > 1.0 for j in tree.query(box, predicate="intersects")):
                crossed.append(t.text)
        assert len(crossed) <= (4 if name in TRIADS else 1), (name, kind, crossed)


@pytest.mark.parametrize("lang", LANGS)
def test_every_sheet_renders_to_png_with_every_glyph(studies, built, lang, tmp_path):
    """Every bundled sheet through the PNG export, whose font choice refuses a text no font can
    draw (one-line error): each comes out, an image of the sheet's size."""
    pytest.importorskip("cairosvg")
    from PIL import Image

    from velplan.render.export import write_png

    for name, kind, sheet in _sheets(studies, lang, built):
        path = write_png(sheet.svg(), tmp_path / f"{name}-{kind}.png", dpi=20)
        with Image.open(path) as im:
            assert im.size == (round(841 / 25.4 * 20), round(594 / 25.4 * 20)), (name, kind, im.size)
            assert im.convert("L").getextrema()[0] < 100  # something is drawn


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
    _assert_legible(sheet, "A1", name, "velocity plans")
