"""The notation the sheets, the answer key and `velplan check` share (issue 32, items 6, 7, 9):
one name per quantity, significant figures, the minus sign, powers of ten, indices below the
line, the designation as a code, and the dynamics sheet's axes and labels."""

import csv
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import velplan
from velplan import batch
from velplan.cli import main
from velplan.plans.check import quantity_of
from velplan.plans.engine import Plan
from velplan.plans.grade import grade_table
from velplan.plans.table import natural_key, parse_quantity, quantity_label, quantity_name
from velplan.render.layout import label_box
from velplan.render.scene import Polyline, Text
from velplan.render.shapes import plain_text
from velplan.sheets.kinds import default_title_of
from velplan.views.base import fixed, number, power_of_ten, row_decimals
from velplan.views.table import table_view

SVG = "{http://www.w3.org/2000/svg}"


def _value(cell: str) -> float:
    """A printed number read back: "−0,512" → -0.512."""
    return float(cell.replace("−", "-").replace(",", "."))


def _significant(cell: str) -> int:
    digits = re.sub(r"\D", "", cell).lstrip("0")
    return len(digits)


# -- numbers ---------------------------------------------------------------------------------

@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=-1e12, max_value=1e12, allow_nan=False).filter(lambda x: abs(x) > 1e-300),
       st.sampled_from(["en", "ru", "uk", "zh"]), st.integers(1, 6))
def test_number_reads_back_to_its_significant_figures_without_programmer_notation(x, lang, digits):
    text = number(x, lang, digits)
    assert "e" not in text and "E" not in text and "-" not in text
    assert ("," in text) <= (lang in ("ru", "uk")) and ("." in text) <= (lang in ("en", "zh"))
    assert text.startswith("−") == (x < 0 and float(f"{abs(x):.{digits}g}") != 0)
    m = re.fullmatch(r"(−?)([\d.,]*)(?:·)?(?:10([⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+))?", text)
    assert m, text
    mantissa = float(m.group(2).replace(",", ".")) if m.group(2) else 1.0
    power = int(m.group(3).translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789"))) if m.group(3) else 0
    back = (-1 if m.group(1) else 1) * mantissa * 10.0 ** power
    assert back == pytest.approx(x, rel=0.51 * 10.0 ** (1 - digits))


def test_powers_of_ten_as_a_drawing_writes_them():
    assert power_of_ten(5e-14, "ru", 1) == "5·10⁻¹⁴"
    assert number(-1.25e-14, "ru") == "−1,25·10⁻¹⁴"
    assert number(2.0e-5, "en") == "2·10⁻⁵" and number(1e-5, "en") == "10⁻⁵"
    assert number(0.0005, "ru") == "0,0005" and number(12345.0, "en") == "12345"
    assert number(3.2e8, "en") == "3.2·10⁸"
    assert fixed(-0.5, "en", 2) == "−0.50" and fixed(-0.0001, "ru", 2) == "0,00"


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(min_value=-10.0, max_value=10.0, allow_nan=False), min_size=1, max_size=12))
def test_a_row_keeps_three_significant_figures_of_its_largest_value(values):
    top = max(abs(v) for v in values)
    d = row_decimals(values)
    if top == 0:
        assert d == 0
        return
    largest = fixed(max(values, key=abs), "en", d)
    assert _significant(largest) in (3, 4) or (_significant(largest) == 1 and float(largest) in (1.0, -1.0))
    assert abs(_value(largest) - max(values, key=abs)) <= 0.5 * 10.0 ** -d * (1 + 1e-9)


# -- the table of transfer functions on the sheet -----------------------------------------------

@pytest.mark.parametrize("name", ["jaw-crusher", "triad-press", "shaper", "four-bar"])
def test_table_values_have_three_significant_figures_against_the_solver(name):
    study = velplan.Study(name)
    view = table_view(study.table, study.mechanism, lang="ru")
    texts = [t for t in view.primitives if isinstance(t, Text)]
    crank = study.mechanism.crank.link
    kin = velplan.solve(study.mechanism, study.phi)
    w1 = abs(study.mechanism.crank.omega)
    by_row = {}
    for row in study.table.rows:
        label_text = next(t for t in texts if t.text == quantity_label(row, crank))
        cells = sorted((t for t in texts if abs(t.position[1] - label_text.position[1]) < 1e-6 and t is not label_text),
                       key=lambda t: t.position[0])
        by_row[row] = [c.text for c in cells]
    for row, cells in by_row.items():
        kind, x = row.split("_", 1)
        exact = (np.hypot(*kin.velocity(x).T) / w1 if kind == "V" else kin.omega(x) / study.mechanism.crank.omega)
        decimals = {len(c.split(",")[1]) if "," in c else 0 for c in cells}
        assert len(decimals) == 1, (row, cells)  # one row, one precision
        d = decimals.pop()
        got = np.array([_value(c) for c in cells])
        assert np.all(np.abs(got - exact) <= 0.5 * 10.0 ** -d + 1e-9 * np.abs(exact).max()), (row, cells)
        top = cells[int(np.argmax(np.abs(got)))]
        assert _significant(top) >= 3 or np.abs(exact).max() < 1e-9, (row, top)
        assert not any("-" in c for c in cells)


def test_a_small_mechanism_keeps_its_figures():
    """A 1.7 mm speed analogue prints as 0,00172, not 0,002 (three decimals of a metre)."""
    assert fixed(0.001719, "ru", row_decimals([0.001719, 0.0008])) == "0,00172"


@pytest.mark.parametrize("name,points,links", [
    ("triad-press", ["A", "B", "C", "D"], ["2", "3", "4"]),
    ("shaper", ["A", "A4", "B", "F"], ["3", "4", "5"]),
])
def test_rows_in_point_and_link_order(name, points, links):
    rows = list(velplan.Study(name).table.rows)
    assert rows == [f"V_{p}" for p in points] + [f"w_{k}" for k in links]
    assert sorted(["C10", "C2", "B", "A4", "A"], key=natural_key) == ["A", "A4", "B", "C2", "C10"]


def test_the_sheet_sets_indices_below_the_line_in_the_svg():
    sheet = velplan.sheet("shaper", kind="velocity", lang="ru")
    root = ET.fromstring(sheet.svg())
    rows = [t for t in root.iter(f"{SVG}text") if t.get("aria-label", "").startswith(("v_{", "ω_{"))]
    assert {t.get("aria-label") for t in rows} >= {"v_{A}/ω_{2}", "v_{A4}/ω_{2}", "ω_{4}/ω_{2}"}
    for t in rows:
        spans = t.findall(f"{SVG}tspan")
        index = [s for s in spans if s.get("dy") and float(s.get("dy")) > 0]
        assert index and all(float(s.get("font-size")) < float(t.get("font-size")) for s in index)
        assert "".join(t.itertext()) == plain_text(t.get("aria-label"))
    assert "_{" not in "".join(root.itertext())  # the marks never show


@pytest.mark.parametrize("name,lang", [("shaper", "ru"), ("triad-press", "en")])
def test_numbers_carry_the_minus_sign_and_no_exponent(name, lang):
    sheet = velplan.sheet(name, lang=lang)
    texts = [plain_text(t.text) for t in sheet.scene.of_kind(Text)]
    assert any("−" in t for t in texts)  # the ω rows change sign
    for t in texts:
        assert not re.search(r"(^|[\s(=;:/])-\d", t), t  # a hyphen for a minus
        assert not re.search(r"\de[-+]?\d", t), t
    sep = "," if lang == "ru" else "."
    cells = [t for t in texts if re.fullmatch(r"−?\d+[.,]\d+", t)]
    assert cells and all(sep in c for c in cells)


@pytest.mark.parametrize("lang", ["en", "ru", "uk", "zh"])
@pytest.mark.parametrize("kind", ["both", "forces", "dynamics"])
def test_the_designation_is_a_code_without_the_file_name(kind, lang):
    d = default_title_of(kind, "triad-press", lang).designation
    assert re.fullmatch(r"(ТММ|TMM) \d\d\.00\.000", d)
    assert "triad" not in d
    if lang in ("ru", "uk"):
        assert not re.search(r"[A-Za-z]", d), d


def test_readings_are_read_to_a_tenth_of_a_millimetre_under_merged_position_headers():
    from velplan.views.readings import PRECISION_MM, read_decimals, readings_view

    study = velplan.Study("shaper")
    res = study.plan("velocity", positions=[4])
    view = readings_view({"plan-v-4": (res, 4)}, lang="ru")
    texts = [t for t in view.primitives if isinstance(t, Text)]
    assert PRECISION_MM == 0.1 and read_decimals(0.02) == 3 and read_decimals(0.005) == 4
    heads = [t for t in texts if t.text == "4"]
    (head,) = heads
    v_col, d_col = (next(t for t in texts if t.text.startswith(s)) for s in ("v,", "δ,"))
    assert head.position[0] == pytest.approx((v_col.position[0] + d_col.position[0]) / 2)  # over both
    rules = [p for p in view.primitives if isinstance(p, Polyline) and p.points[0][0] == p.points[1][0]]
    between = [r for r in rules if v_col.position[0] < r.points[0][0] < d_col.position[0]]
    assert between and all(min(r.points[0][1], r.points[1][1]) < head.position[1] - 1 for r in between)
    assert not any(min(r.points[0][1], r.points[1][1]) <= head.position[1] <= max(r.points[0][1], r.points[1][1])
                   for r in between)  # no rule through the merged header
    d = read_decimals(res.scale)
    values = [t.text for t in texts if re.fullmatch(r"\d+,\d+", t.text) and t.position[1] < v_col.position[1]
              and abs(t.position[0] - v_col.position[0]) < 1]
    assert values and all(len(v.split(",")[1]) == d for v in values)


# -- one name in the sheet, the key and `velplan check` ---------------------------------------

def test_names_spellings_and_refusal():
    rows = ["V_A", "V_A4", "w_3"]
    assert quantity_name("V_A4", "2") == "vA4/ω2" == plain_text(quantity_label("V_A4", "2"))
    for text, row in [("vA4/ω2", "V_A4"), ("v_{A4}/ω_{2}", "V_A4"), ("VA4/w2", "V_A4"), ("V_A4", "V_A4"),
                      ("v A4 / ω₂", "V_A4"), ("VA/ω1, m", "V_A"), ("ω₃/ω₂", "w_3"), ("w3/w2", "w_3"),
                      ("omega3/omega2", "w_3"), ("w_3", "w_3"), ("ω3/ω1", "w_3")]:
        assert parse_quantity(text, rows, "2") == row, text
    for text in ("vA/ω3", "VZ/ω2", "ω4/ω2", "vA4/ω", "A4"):
        assert parse_quantity(text, rows, "2") is None, text
    with pytest.raises(velplan.VelplanError, match=r"^unknown quantity 'VA/ω3'; use v<point>/ω2 with a point of A"):
        quantity_of("VA/ω3", ["A"], ["3"], "2")


@pytest.fixture(scope="module")
def course(tmp_path_factory):
    out = tmp_path_factory.mktemp("notation") / "out"
    assert main(["batch", "--random", "2", "--seed", "s", "--base", "shaper", "-o", str(out), "--quiet",
                 "--jobs", "1", "--lang", "ru"]) == 0
    return out


def _sheet_names(svg_path) -> list[tuple[str, str]]:
    """(typeset, plain) name of every row of the table of transfer functions on a sheet."""
    root = ET.parse(svg_path).getroot()
    out = []
    for g in root.iter(f"{SVG}g"):
        if "table" not in g.get("class", "").split():
            continue
        for t in g.iter(f"{SVG}text"):
            plain = "".join(t.itertext())
            if "/ω" in plain and " " not in plain:
                out.append((t.get("aria-label", plain), plain))
    return out


def test_the_key_names_what_the_sheet_prints_and_check_accepts_it(course, tmp_path, capsys):
    key = course / "answers.json"
    rows = list(csv.reader((course / "answers.csv").read_text("utf-8").splitlines()))
    import json

    answers = json.loads(key.read_text("utf-8"))["variants"]
    assert len(answers) == 2
    for a in answers:
        v = a["variant"]
        names = _sheet_names(course / f"{v}.svg")
        assert names, v
        key_names = [r[1] for r in rows[1:] if r[0] == v and "/ω" in r[1]]
        assert [plain for _, plain in names] == key_names  # the same strings, in the same order
        assert all(n.endswith(f"/ω{a['crank']}") for n in key_names) and a["crank"] == "2"
        values = {r[1]: r[3:3 + a["positions"]] for r in rows[1:] if r[0] == v}
        mech, _ = batch.build_variant(batch.Variant(v, a["base"], a["overrides"]))
        for spelling in (0, 1, 2):  # the typeset name, the plain one, ASCII
            table = tmp_path / f"{v}-{spelling}.csv"
            lines = ["quantity," + ",".join(str(i) for i in range(1, a["positions"] + 1))]
            for typeset, plain in names:
                name = (typeset, plain, plain.replace("ω", "w").replace("v", "V", 1))[spelling]
                lines.append(f"{name}," + ",".join(values[plain]))
            table.write_text("\n".join(lines) + "\n", "utf-8")
            report = grade_table(table, key, v)
            assert report.right == len(report.entries) == len(names) * a["positions"]
            assert main(["check", "shaper", "--table", str(table), "--key", str(key), "--variant", v]) == 0
            assert "unknown quantity" not in capsys.readouterr().err
        plan = Plan.of(mech)
        for typeset, plain in names:  # and against the variant's own mechanism, as `velplan check` reads
            kind, x = quantity_of(typeset, list(plan.images["v"]), [k for k in plan.figures["v"] if k != "0"],
                                  mech.crank.link)
            assert quantity_name(f"{kind}_{x}", mech.crank.link) == plain


# -- the dynamics sheet ----------------------------------------------------------------------

@pytest.fixture(scope="module")
def dynamics_sheet():
    return velplan.sheet(velplan.Study("shaper", delta=0.05), kind="dynamics", lang="ru")


def _texts(placed):
    return [t for t in placed.view.primitives if isinstance(t, Text)]


def test_omega_ticks_are_round_and_the_axis_is_omega_m(dynamics_sheet):
    panel = dynamics_sheet.views["omega"]
    texts = _texts(panel)
    (wm,) = [t for t in texts if t.text == "ω_{m}"]
    base = panel.view.meta["base"]
    mu = panel.view.meta["mu"]
    ticks = [t for t in texts if re.fullmatch(r"\d+,\d+", t.text) and t.anchor == "end"]
    assert len(ticks) >= 3
    values = [_value(t.text) for t in ticks]
    step = min(np.diff(sorted(values)))
    assert step * 10 ** 3 == pytest.approx(round(step * 10 ** 3))
    assert {round(v / step, 6) % 1 for v in values} == {0.0}  # multiples of the step: 8,2 8,3 …
    for t, v in zip(ticks, values):  # each where its value is
        assert t.position[1] - wm.position[1] == pytest.approx((v - base) / mu, abs=1e-6)
        assert abs(t.position[1] - wm.position[1]) >= 1.5 * wm.size_mm  # clear of ω_m


def test_k_and_l_stand_beside_the_energy_axis(dynamics_sheet):
    view = dynamics_sheet.views["wittenbauer"].view
    texts = _texts(dynamics_sheet.views["wittenbauer"])
    (arrow,) = [p for p in view.primitives if type(p).__name__ == "Arrow" and p.start[0] == p.end[0] and p.layer == "dynamics"
                and abs(p.end[1] - p.start[1]) > 50]  # the ΔT axis
    origin = arrow.start[0]
    axis = shapely.LineString([arrow.start, arrow.end])
    dots = {round(p.centre[1], 6): p.centre for p in view.primitives
            if type(p).__name__ == "Circle" and abs(p.centre[0] - origin) < 1e-6}
    for mark in ("k", "l"):
        (t,) = [x for x in texts if x.text == mark]
        box = label_box(t)
        assert not box.intersects(axis), mark
        nearest = min(dots.values(), key=lambda c: math.dist(c, t.position))
        assert box.distance(shapely.Point(nearest)) < 6.0


def test_dynamics_sheet_text(dynamics_sheet):
    texts = [t.text for t in dynamics_sheet.scene.of_kind(Text)]
    plain = [plain_text(t) for t in texts]
    for t in plain:
        assert not re.search(r"\de[-+]?\d", t), t
        assert not re.search(r"(^|[\s(=;±])-\d", t), t
        assert "øD" not in t and "⌀D" not in t
    assert any(re.fullmatch(r"⌀\d+", t) for t in texts)
    assert any(re.fullmatch(r"±\d·10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+", t) for t in texts)
    for symbol in ("ω_{m}", "ω_{max}", "ω_{min}", "J_{I}", "J_{II}", "M_{д}", "ψ_{max}", "μ_{φ}"):
        assert any(symbol in t for t in texts), symbol
    for bare in ("ωmax", "ωmin", "JI ", "ψmax", "μφ"):
        assert not any(bare in t for t in texts), bare


def test_no_reference_drawing_writes_a_hyphen_minus_or_an_exponent():
    """Every bundled sheet as committed (drawings/, kept up to date by the sheet tests): numbers
    with "−", powers of ten as ·10ⁿ, no designation made of a file key."""
    from velplan.sheets import drawings

    files = sorted(drawings.DRAWINGS.glob("*.svg"))
    assert len(files) >= 5
    for path in files:
        for t in ET.parse(path).getroot().iter(f"{SVG}text"):
            text = "".join(t.itertext())
            assert not re.search(r"(^|[\s(=;:/±])-\d", text), (path.name, text)
            assert not re.search(r"\de[-+]?\d", text), (path.name, text)
            assert not re.search(r"(ТММ|TMM)\.[a-z]", text), (path.name, text)
