"""drawings/ is current; sheets are byte-stable; files are written whole or not at all."""

import re
import subprocess
import sys

import pytest

import velplan
from velplan.sheets import drawings
from velplan.errors import ScaleError, VelplanError
from velplan.sheets.kinematic import build_sheet, write_outputs


@pytest.mark.parametrize("name", velplan.example_names())
def test_drawings_are_up_to_date(name, sheets):
    path = drawings.DRAWINGS / f"{name}.svg"
    assert path.is_file(), "run `python -m velplan.drawings`"
    assert drawings.same_drawing(path.read_bytes(), sheets[name].svg().encode("utf-8")), (
        f"{path} is out of date: run `python -m velplan.drawings`")


def test_same_drawing_tolerates_round_off_only():
    a = '<path d="M 1.234,5.000 L 2.5,3" font-size="3.5">ω1</path>'.encode()
    assert drawings.same_drawing(a, a.replace(b"1.234", b"1.235"))
    assert not drawings.same_drawing(a, a.replace(b"1.234", b"1.237"))
    assert not drawings.same_drawing(a, a.replace(b"\xcf\x891", b"w1"))
    assert not drawings.same_drawing(a, a.replace(b"L 2.5,3", b"L 2.5,3 4"))


def test_drawings_readme_and_png():
    readme = (drawings.DRAWINGS / "README.md").read_text(encoding="utf-8")
    assert "python -m velplan.drawings" in readme
    for name in velplan.example_names():
        assert f"{name}.svg" in readme
    assert (drawings.DRAWINGS / "README.md").read_bytes() == drawings.expected_readme()
    png = (drawings.DRAWINGS / "shaper.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_same_input_same_bytes(sheets):
    again = build_sheet("shaper", **drawings.OPTIONS).svg()
    assert again == sheets["shaper"].svg()
    assert not re.search(r"20\d\d-\d\d-\d\d|timestamp", again)


def test_svg_converts_to_png(sheets, tmp_path):
    written = sheets["four-bar"].save(tmp_path / "four-bar.svg", png=True, dpi=20)
    assert [p.name for p in written] == ["four-bar.svg", "four-bar.png"]
    assert (tmp_path / "four-bar.png").read_bytes()[:4] == b"\x89PNG"


def test_scale_error_is_one_line_and_says_what_to_do():
    with pytest.raises(ScaleError) as err:
        build_sheet("shaper", fmt="A3", plans=(1, 2, 3, 4, 5, 6))
    message = str(err.value)
    assert "\n" not in message
    assert re.match(r"the velocity and acceleration plans of positions 1, 2, 3, 4, 5, 6 do "
                    r"not fit A3 at any standard scale with vectors of at least 25 mm "
                    r"\(\d+ × \d+ mm free\); use fewer --plans or a larger --format$", message)


def test_diagrams_demanded_go_where_they_fit_else_raise_scale_error():
    sheet = build_sheet("crank-slider", fmt="A1", lang="en")
    assert "diagrams" in sheet.views and sheet.frame_style == "iso"
    demanded = build_sheet("crank-slider", fmt="A1", lang="en", diagrams=True)
    assert demanded.svg() == sheet.svg()  # demanding them draws what "auto" draws
    # on A3 the compact block holds them, 30 mm high at least (tests/sheet/test_gallery_marks_a3_kinematic.py)
    assert "diagrams" in build_sheet("crank-slider", fmt="A3", lang="en").views
    # the jaw crusher's two positions' plans leave them no room (the first position's alone do,
    # but --plans names both): ScaleError rather than squashed diagrams
    with pytest.raises(ScaleError, match=r"^the kinematic diagrams do not fit A3 beside the table, "
                                         r"in a free corner nor beside the plans .* ordinates of at least "
                                         r"30 mm; use a larger --format or fewer --plans$"):
        build_sheet("jaw-crusher", fmt="A3", plans=(4, 10), diagrams=True)


@pytest.mark.parametrize("options, message", [
    ({"plans": (13,)}, r"^--plans: position 13 is outside 1…12 \(positions are numbered from 1\)$"),
    ({"plans": (3, 3)}, r"^--plans: a position is repeated in 3, 3$"),
    ({"fmt": "A0"}, r"^unknown sheet format 'A0'; known formats: A1, A2, A3$"),
    ({"kind": "jerk"}, r"^unknown plan kind 'jerk'; known kinds: velocity, acceleration, both$"),
    ({"lang": "de"}, r"^unknown language 'de'; known languages: en, ru, uk, zh$"),
])
def test_bad_options(options, message):
    with pytest.raises(VelplanError, match=message):
        build_sheet("crank-slider", **options)


def test_failed_conversion_leaves_no_file(tmp_path, monkeypatch):
    from velplan.render import export

    def broken(*args, **kwargs):
        raise VelplanError("cairosvg could not convert the sheet (svg2png): boom")

    monkeypatch.setattr(export, "_convert", broken)
    with pytest.raises(VelplanError, match="boom"):
        write_outputs("<svg/>", tmp_path / "x.svg", png=True)
    assert list(tmp_path.iterdir()) == []


def test_sheet_path_does_not_import_matplotlib():
    code = ("import sys, velplan.cli as c, velplan.sheets.kinematic as s\n"
            "c.main(['analyze', 'crank-slider', '--positions', '2'])\n"
            "s.build_sheet('crank-slider', fmt='A2').svg()\n"
            "assert 'matplotlib' not in sys.modules, 'matplotlib imported'\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
