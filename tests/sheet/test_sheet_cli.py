"""`velplan sheet`, `velplan diagrams`, `velplan steps` on the command line."""

from velplan.cli import main


def test_sheet_without_mech_draws_the_shaper_here(tmp_path, monkeypatch, capsys, sheets):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("LC_ALL", "ru_RU.UTF-8")  # the drawings' language, from the locale
    assert main(["sheet"]) == 0
    assert capsys.readouterr().out == "wrote shaper-sheet.svg\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["shaper-sheet.svg"]  # no temp files
    assert (tmp_path / "shaper-sheet.svg").read_text(encoding="utf-8") == sheets["shaper"].svg()


def test_sheet_options_and_png(tmp_path, capsys):
    out = tmp_path / "press.svg"
    assert main(["sheet", "press", "-o", str(out), "--format", "A2", "--lang", "en",
                 "--plans", "3,9", "--kind", "velocity", "--png", "--dpi", "20",
                 "--author", "Ivanov", "--date", "12.05.2025"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed == [f"wrote {out}", f"wrote {out.with_suffix('.png')}"]
    svg = out.read_text(encoding="utf-8")
    assert "Velocity plan (pos. 3)" in svg and "Acceleration plan" not in svg
    assert "Ivanov" in svg and "12.05.2025" in svg
    assert out.with_suffix(".png").read_bytes()[:4] == b"\x89PNG"


def test_sheet_errors_are_one_line_and_write_nothing(tmp_path, capsys):
    out = tmp_path / "x.svg"
    assert main(["sheet", "shaper", "-o", str(out), "--plans", "1,x"]) == 2
    assert capsys.readouterr().err == "velplan: error: --plans: 'x' is not a position number (or give: all)\n"
    assert main(["sheet", "shaper", "-o", str(out), "--format", "A3",
                 "--plans", "1,2,3,4,5,6"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("velplan: error: the velocity and acceleration plans") and err.count("\n") == 1
    assert main(["sheet", "shaper", "-o", str(tmp_path / "missing" / "x.svg")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_diagrams_command(tmp_path, capsys):
    out = tmp_path / "d.svg"
    assert main(["diagrams", "crank-slider", "-o", str(out), "--lang", "uk"]) == 0
    assert capsys.readouterr().out == f"wrote {out}\n"
    svg = out.read_text(encoding="utf-8")
    for text in ("Діаграма переміщень", "Діаграма швидкостей", "Діаграма прискорень",
                 "H = ", "μv = μs/(μt·H)", "μt = μφ/ω1 = ", "(м/с)/мм", "δ = "):
        assert text in svg


def test_steps_command(tmp_path, capsys):
    out = tmp_path / "steps"
    assert main(["steps", "crank-slider", "--position", "3", "-o", str(out),
                 "--kind", "velocity", "--lang", "en"]) == 0
    import velplan
    from velplan.plans import Plan

    count = sum(s.target.startswith("v:") for s in Plan.of(velplan.load("crank-slider")).steps)
    files = sorted(p.name for p in out.iterdir())
    assert files == [f"step-v-{k:02d}.svg" for k in range(1, count + 1)]
    assert len(capsys.readouterr().out.splitlines()) == count
    fifth = (out / "step-v-05.svg").read_text(encoding="utf-8")
    assert f"Step 5/{count}" in fifth and "The two lines meet at b" in fifth


def test_steps_position_out_of_range(tmp_path, capsys):
    assert main(["steps", "crank-slider", "--position", "13", "-o", str(tmp_path / "s")]) == 2
    assert capsys.readouterr().err == "velplan: error: --position 13 is outside 1…12\n"
    assert not (tmp_path / "s").exists()


def test_the_language_follows_the_locale():
    from velplan.cli.common import default_language

    assert default_language({"LANG": "uk_UA.UTF-8"}) == "uk"
    assert default_language({"LC_ALL": "zh_CN.UTF-8", "LANG": "ru_RU.UTF-8"}) == "zh"
    assert default_language({"LC_ALL": "", "LANG": "ru_RU.UTF-8"}) == "ru"
    assert default_language({"LANG": "de_DE.UTF-8"}) == "en"
    assert default_language({"LANG": "C"}) == "en"
    assert default_language({}) == "en"


def test_version(capsys):
    import pytest

    import velplan

    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0 and capsys.readouterr().out == f"velplan {velplan.__version__}\n"
