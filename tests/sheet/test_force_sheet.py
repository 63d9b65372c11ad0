"""The force-analysis sheet (`velplan sheet MECH --kind forces`), checked on the recorded
canvas as a teacher checks the drawing: polygons close, arrows point the way the forces act,
the lever's balance is the kinetostatic one, nothing overlaps, scales and names are written."""

import math
import re

import numpy as np
import pytest

import velplan
from velplan.sheets import drawings
from velplan.cli import main
from velplan.errors import ScaleError, VelplanError
from velplan.sheets.forces import build_force_sheet, force_sheet_text
from velplan.views.forces import group_layers, lever_layers, polygon_layers
from velplan.views.forces.arrows import BESIDE_MM
from velplan.views.forces.polygon import OFFSET_MM
from velplan.render.layout import overlapping_labels
from velplan.render.scene import Polyline
from velplan.views.base import number

from tests.sheet.helpers import assert_views_placed, record_all

NAMES = ("press", "shaper", "slider-press")


@pytest.fixture(scope="module")
def force_sheets():
    """The force sheet of every example with masses, as `python -m velplan.sheets.drawings` draws it."""
    return {name: build_force_sheet(name, **drawings.FORCE_OPTIONS) for name in NAMES}


@pytest.fixture(scope="module")
def force_canvases(force_sheets):
    return record_all(force_sheets)


def _views(sheet, prefix):
    return {k: v for k, v in sheet.views.items() if k.startswith(prefix)}


def _unit(a, b):
    d = np.asarray(b, float) - np.asarray(a, float)
    return d / np.hypot(*d)


def test_examples_with_masses_are_the_force_examples():
    assert tuple(drawings.force_examples()) == NAMES


def test_default_positions(force_sheets):
    # the shaper: a working-stroke position (cutting force on) and the largest |M_b|
    assert force_sheets["shaper"].positions == (4, 10)
    assert force_sheets["slider-press"].positions == (6,)
    assert force_sheets["press"].positions == (12,)
    for sheet in force_sheets.values():
        mb = np.abs(sheet.analysis.kinetostatics.balancing_moment)
        assert sheet.positions[-1] == int(np.argmax(mb)) + 1


@pytest.mark.parametrize("name", NAMES)
def test_every_force_polygon_closes_through_its_vertices(name, force_sheets, force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    polygons = _views(sheet, "polygon-")
    assert len(polygons) == len(sheet.positions) * (len(sheet.mechanism.groups) + 1)
    for view_name, placed in polygons.items():
        meta = placed.view.meta
        arrows = canvas.arrows(polygon_layers(meta["number"], meta["group"])[0])
        assert len(arrows) >= 2, view_name
        # every vector drawn (or listed as ≈ 0), from its vertex to the next: the vertices
        # are the analysis' ForcePolygon.vertices at the written μF, which close
        poly = sheet.analysis.kinetostatics.polygons[meta["group"]]
        z = poly.vertices(meta["mu_f"])[meta["index"]]
        assert abs(z[-1] - z[0]) < 1e-6
        corners = [placed.to_sheet([v.real, v.imag]) for v in z]
        assert sorted(meta["drawn"] + tuple(n for n, _ in meta["small"])) == sorted(meta["labels"])
        assert len(arrows) == len(meta["drawn"])
        for name_, a in zip(meta["drawn"], arrows):
            k = meta["labels"].index(name_)
            tail, head = corners[k], corners[k + 1]
            # on its vertices, or beside them (OFFSET_MM) where it would cover another vector
            shift = np.asarray(a.start) - tail
            assert np.allclose(np.asarray(a.end) - head, shift, atol=1e-6), (view_name, a)
            assert min(abs(math.hypot(*shift) - d) for d in (0.0, OFFSET_MM)) < 1e-6
            assert abs(float(shift @ (head - tail))) < 1e-6
        assert np.isclose(sheet.scales[view_name], meta["mu_f"])


@pytest.mark.parametrize("name", NAMES)
def test_closing_reactions_lie_where_their_known_directions_meet(name, force_sheets,
                                                                  force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    checked = 0
    for view_name, placed in _views(sheet, "polygon-").items():
        meta = placed.view.meta
        poly = sheet.analysis.kinetostatics.polygons[meta["group"]]
        if len(poly.closing) != 2:
            continue
        i = meta["index"]
        z = poly.vertices(meta["mu_f"])[i]
        m = len(poly.vectors)
        at = lambda v: placed.to_sheet([v.real, v.imag])  # noqa: E731
        lines = canvas.polylines(polygon_layers(meta["number"], meta["group"])[1])
        assert len(lines) == 2, view_name
        for line, through, (_, d) in zip(lines, (z[m], z[0]), poly.closing):
            p, q = line.points[0], line.points[-1]
            u = complex(d[i])
            # along the known direction, through the known vertex and the intersection
            assert abs(float(_unit(p, q) @ np.array([u.real, u.imag]))) > 1 - 1e-9
            for point in (at(through), at(z[m + 1])):
                w = np.asarray(point) - p
                e = _unit(p, q)
                assert abs(float(e[0] * w[1] - e[1] * w[0])) < 0.01
        checked += 1
    assert checked >= len(sheet.positions)


@pytest.mark.parametrize("name", NAMES)
def test_force_arrows_on_the_groups_point_the_way_the_forces_act(name, force_sheets,
                                                                  force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    for view_name, placed in _views(sheet, "group-").items():
        meta = placed.view.meta
        arrows = [a for a in canvas.arrows(group_layers(meta["number"], meta["group"])[1])
                  if a.length > 5.0]  # the moments' curved arrows end in short heads
        assert len(arrows) >= len(meta["forces"])
        def at(end, p, u):  # at the point, or level with it beside a link (BESIDE_MM)
            d = np.asarray(end) - p
            return abs(float(d @ u)) < 1e-6 and min(abs(math.hypot(*d) - s)
                                                    for s in (0.0, BESIDE_MM)) < 1e-6

        for label, point, force in meta["forces"]:
            p = placed.to_sheet([point.real, point.imag])
            u = np.array([force.real, force.imag]) / abs(force)
            assert any((at(a.start, p, u) or at(a.end, p, u))
                       and float(_unit(a.start, a.end) @ u) > 1 - 1e-9 for a in arrows), \
                (view_name, label)


@pytest.mark.parametrize("name", NAMES)
def test_curved_arrows_turn_the_way_the_moments_do(name, force_sheets, force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    seen = set()
    for view_name, placed in _views(sheet, "group-").items():
        meta = placed.view.meta
        heads = [a for a in canvas.arrows(group_layers(meta["number"], meta["group"])[1])
                 if a.length < 5.0]
        for label, centre, value in meta["couples"]:
            # the centre is in the view's content mm: model mm at μl
            c = placed.view.to_view(np.asarray(centre) * placed.view.mu) + [placed.x, placed.y]
            mine = [a for a in heads
                    if abs(math.dist(a.end, c) - meta["arc_radius"]) < 1e-6]
            assert len(mine) == 1, (view_name, label)
            a = mine[0]
            r, d = np.asarray(a.start) - c, np.asarray(a.end) - np.asarray(a.start)
            assert np.sign(r[0] * d[1] - r[1] * d[0]) == np.sign(value), (view_name, label)
            seen.add(label)
    assert "M_{ур}" in seen  # M with its index ур set below the line


@pytest.mark.parametrize("name", NAMES)
def test_forces_on_the_lever_act_at_the_images_of_their_points(name, force_sheets,
                                                                force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    for view_name, placed in _views(sheet, "lever-").items():
        meta = placed.view.meta
        arrows = canvas.arrows(lever_layers(meta["number"])[1])
        assert len(arrows) == len(meta["forces"]) + 1  # and the balancing force
        for label, p, force in meta["forces"]:
            q = placed.to_sheet(p)
            u = np.array([force.real, force.imag]) / abs(force)
            assert any((math.dist(a.start, q) < 1e-6 or math.dist(a.end, q) < 1e-6)
                       and float(_unit(a.start, a.end) @ u) > 1 - 1e-9 for a in arrows), \
                (view_name, label)


@pytest.mark.parametrize("name", NAMES)
def test_lever_balance_written_equals_kinetostatics_to_the_printed_digits(name, force_sheets,
                                                                          force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    text = force_sheet_text(sheet)
    written = re.findall(r"^Mур = (\S+) Н·м \(рычаг\) / (\S+) Н·м \(кинетостатика\), "
                         r"Δ = (\S+) %$", text, flags=re.M)
    assert len(written) == len(sheet.positions)
    mb = sheet.analysis.kinetostatics.balancing_moment
    for (lever, kin, pct), k in zip(written, sheet.positions):
        assert lever == kin == number(float(mb[k - 1]), "ru")
        assert pct == "0,00"
    # the table: the three methods agree to the digits printed
    rows = {}
    for t in canvas.texts("table"):
        rows.setdefault(round(t.position[1], 3), []).append(t.text)
    body = [r for r in rows.values() if r[0].startswith("M_{ур} (")]
    assert [r[0] for r in body] == ["M_{ур} (кинетостатика)", "M_{ур} (рычаг)",
                                    "M_{ур} (метод мощностей)"]
    assert body[0][1:] == body[1][1:] == body[2][1:] and len(body[0]) == 13


@pytest.mark.parametrize("name", NAMES)
def test_balancing_force_sits_at_the_crank_tip_image_square_to_the_crank(name, force_sheets,
                                                                          force_canvases):
    sheet, canvas = force_sheets[name], force_canvases[name]
    mech = sheet.mechanism
    for view_name, placed in _views(sheet, "lever-").items():
        meta = placed.view.meta
        k = meta["number"]
        thick = [a for a in canvas.arrows(lever_layers(k)[1]) if a.line == "thick"]
        assert len(thick) == 1
        fb = thick[0]
        kin = sheet.analysis.kinematics
        tip = complex(*kin.velocities[k - 1, kin.point_index[mech.crank.tip]]) / meta["mu_v"]
        image = placed.to_sheet([(1j * tip).real, (1j * tip).imag])
        assert min(math.dist(fb.start, image), math.dist(fb.end, image)) < 1e-6
        crank = kin.position(mech.crank.tip)[k - 1] - kin.position(mech.crank.pivot)[k - 1]
        assert abs(float(_unit(fb.start, fb.end) @ (crank / np.hypot(*crank)))) < 1e-9
        # it turns the crank the way M_b does
        mb = sheet.analysis.kinetostatics.balancing_moment[k - 1]
        u = _unit(fb.start, fb.end)
        assert np.sign(crank[0] * u[1] - crank[1] * u[0]) == np.sign(mb)


@pytest.mark.parametrize("name", NAMES)
def test_no_two_labels_overlap(name, force_sheets):
    assert overlapping_labels(force_sheets[name].scene) == []


@pytest.mark.parametrize("name", NAMES)
def test_views_inside_the_free_area_and_apart(name, force_sheets):
    assert_views_placed(force_sheets[name], overlap_below_mm2=1e-6)


@pytest.mark.parametrize("name", NAMES)
def test_text_names_scales_groups_and_positions(name, force_sheets):
    sheet = force_sheets[name]
    text = force_sheet_text(sheet)
    mech = sheet.mechanism
    assert sheet.info.title == f"Силовой анализ механизма: {velplan.load(name).name_in('ru')}"
    assert "Силовой анализ" in text  # the title block wraps it
    for k in sheet.positions:
        assert re.search(rf"^Положение {k}: φ = ", text, flags=re.M)
    for g in mech.groups:
        assert text.count(f"Группа Ассура {g.name}\n") == len(sheet.positions)
        assert text.count(f"План сил группы {g.name}\n") == len(sheet.positions)
    assert text.count(f"Начальное звено {mech.crank.link}\n") == len(sheet.positions)
    assert text.count("Рычаг Жуковского\n") == len(sheet.positions)
    assert len(re.findall(r"^μF = \S+ Н/мм$", text, flags=re.M)) == len(
        _views(sheet, "polygon-"))
    assert re.search(r"^μl = \S+ м/мм \(М 1:\S+\)$", text, flags=re.M)  # Cyrillic М on a ru sheet
    assert re.search(r"^μv = \S+ \(м/с\)/мм$", text, flags=re.M)
    assert "Диаграмма уравновешивающего момента" in text and "μM = " in text
    assert "ТММ 02.00.000" in text


def test_same_input_same_bytes(force_sheets):
    again = build_force_sheet("slider-press", **drawings.FORCE_OPTIONS).svg()
    assert again == force_sheets["slider-press"].svg()
    assert not re.search(r"20\d\d-\d\d-\d\d|timestamp", again)


@pytest.mark.parametrize("name", NAMES)
def test_force_drawings_are_up_to_date(name, force_sheets):
    path = drawings.DRAWINGS / f"{name}-forces.svg"
    assert path.is_file(), "run `python -m velplan.drawings`"
    assert drawings.same_drawing(path.read_bytes(), force_sheets[name].svg().encode("utf-8")), (
        f"{path} is out of date: run `python -m velplan.drawings`")
    assert f"{name}-forces.svg" in (drawings.DRAWINGS / "README.md").read_text(encoding="utf-8")


def test_scale_error_is_one_line_and_says_what_to_do():
    with pytest.raises(ScaleError) as err:
        build_force_sheet("shaper", fmt="A3", plans=(4, 10))
    message = str(err.value)
    assert "\n" not in message
    assert re.match(r"the groups, force polygons and lever of positions 4, 10 do not fit A3 "
                    r"at any standard scale with drawings of at least 30 mm \(.*\); use fewer "
                    r"--plans or a larger --format$", message)


@pytest.mark.parametrize("options, message", [
    ({"plans": (13,)}, r"^--plans: position 13 is outside 1…12 \(positions are numbered from 1\)$"),
    ({"plans": (6, 6)}, r"^--plans: a position is repeated in 6, 6$"),
    ({"fmt": "A0"}, r"^unknown sheet format 'A0'; known formats: A1, A2, A3$"),
    ({"lang": "de"}, r"^unknown language 'de'; known languages: en, ru, uk, zh$"),
])
def test_bad_options(options, message):
    with pytest.raises(VelplanError, match=message):
        build_force_sheet("slider-press", **options)


def test_mechanism_without_masses_has_no_force_sheet():
    with pytest.raises(VelplanError, match=r"^crank-slider declares no masses and no loads"):
        build_force_sheet("crank-slider")


def test_cli_writes_the_force_sheet(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["sheet", "slider-press", "--kind", "forces", "--lang", "en", "--format", "A2",
                 "--plans", "4", "--author", "Ivanov"]) == 0
    assert capsys.readouterr().out == "wrote slider-press-forces.svg\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slider-press-forces.svg"]
    svg = (tmp_path / "slider-press-forces.svg").read_text(encoding="utf-8")
    for text in ("Force analysis", "Position 4: φ = ", "Zhukovsky's lever",
                 "Force polygon of group 2-3", "Assur group 2-3", "Ivanov", "TMM 02.00.000",
                 "Balancing moment diagram"):
        assert text in svg
    assert main(["sheet", "crank-slider", "--kind", "forces", "-o", str(tmp_path / "x.svg")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("velplan: error: crank-slider declares no masses")
    assert err.count("\n") == 1
    assert not (tmp_path / "x.svg").exists()


def test_chinese_sheet_is_labelled_in_chinese():
    sheet = build_force_sheet("slider-press", lang="zh", fmt="A2")
    text = force_sheet_text(sheet)
    for words in ("机构力分析", "杆组 2-3", "杆组 2-3 力多边形", "原动件 1", "茹科夫斯基杠杆",
                  "平衡力矩线图"):
        assert words in text
    assert sheet.frame_style == "iso" and overlapping_labels(sheet.scene) == []
    assert not any(isinstance(p, Polyline) and not np.all(np.isfinite(p.points))
                   for p in sheet.scene)


@pytest.mark.parametrize("name, partner", [("v-compressor", "2-3"), ("triad-press", "3-2-4-5"), ("shaper", "3-4")])
def test_the_initial_links_polygon_shares_the_muF_of_the_group_that_loads_it(name, partner):
    """R₂₁ = −R₁₂ is a side of both polygons: at one μF the student carries it over with dividers
    (the triad press's crank polygon was one 314 mm segment at 20 N/mm beside its group's at 100)."""
    from velplan.sheets.forces import crank_partner

    sheet = build_force_sheet(name, fmt="A1", lang="en")
    k = sheet.positions[0]
    assert crank_partner(sheet.analysis, k) == partner
    assert sheet.scales[f"polygon-{k}-crank"] == sheet.scales[f"polygon-{k}-{partner}"]
    # R₂₁ is one of the partner's sides, so the crank's polygon is no larger than the partner's
    def side(view):
        x0, y0, x1, y1 = sheet.views[view].bounds
        return max(x1 - x0, y1 - y0)

    assert side(f"polygon-{k}-crank") <= 1.1 * side(f"polygon-{k}-{partner}")
