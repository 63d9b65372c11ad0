"""The interactive page (``velplan html``): one self-contained file, deterministic, small, with
every position, the worked solution in the page's language and the analytic values."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from velplan.cli import main
from velplan.errors import VelplanError
from velplan.html import Page
from velplan.html.text import fill, templates
from velplan.render.i18n import label
from velplan.study import Study
from velplan.html.frames import readable  # the page's form of a caption: whole indices marked _{…}


def data_of(page_html: str) -> dict:
    """The page's data block."""
    block = re.search(r'<script type="application/json" id="velplan-data">(.*?)</script>', page_html, re.S)
    assert block is not None
    return json.loads(block.group(1))


@pytest.fixture(scope="module")
def shaper_ru():
    study = Study("shaper", n=12)
    return study, Page(study, lang="ru")


@pytest.fixture(scope="module")
def shaper_360():
    return Page("shaper", positions=360, lang="en")


def test_same_input_gives_the_same_bytes(shaper_ru, tmp_path):
    _, page = shaper_ru
    assert Page(Study("shaper", n=12), lang="ru").html == page.html
    for name in ("a.html", "b.html"):
        assert main(["html", "shaper", "--positions", "12", "--lang", "ru", "-o", str(tmp_path / name)]) == 0
    assert (tmp_path / "a.html").read_bytes() == (tmp_path / "b.html").read_bytes()
    assert (tmp_path / "a.html").read_bytes() == page.html.encode("utf-8")


def test_the_page_loads_nothing(shaper_ru):
    text = shaper_ru[1].html
    assert not re.search(r"(?i)https?:|//[a-z0-9.-]+\.[a-z]{2,}/", text)
    assert not re.search(r"(?i)\b(src|href|xlink:href)\s*=", text)
    assert "url(" not in text and "@import" not in text and "<link" not in text
    assert text.count("<script") == 2  # the data and the page's own script, both inline


def test_360_positions_of_the_shaper_fit_in_2_mb(shaper_360):
    size = len(shaper_360.html.encode("utf-8"))
    assert size <= 2 * 1024 * 1024, size


def test_every_position_is_there(shaper_360):
    data = data_of(shaper_360.html)
    n = 360
    assert data["n"] == n and len(data["phi"]) == n and len(set(data["phi"])) == n
    assert np.allclose(np.diff(np.unwrap(np.radians(data["phi"]))) % (2 * np.pi), 2 * np.pi / n)
    assert len(data["scheme"]["frames"]) == n and all(data["scheme"]["frames"])
    for plan in data["plans"]:
        assert len(plan["items"]) == len(plan["values"]) == len(plan["sentences"]) == len(plan["frames"]) == n
        # every construction step draws or writes something at some position
        drawn = {it[0] for items in plan["items"] for it in items}
        assert drawn == set(range(1, plan["steps"] + 1))
    assert 'max="360"' in shaper_360.html


def test_step_sentences_in_russian_are_those_of_the_worked_solution(shaper_ru):
    study, page = shaper_ru
    data = data_of(page.html)
    assert '<html lang="ru">' in page.html and "План скоростей" in page.html
    for plan, kind in zip(data["plans"], ("velocity", "acceleration")):
        res = study.plan(kind)
        for i in (0, 4, 9):
            expected = [readable(s) for s in res.describe(i + 1, "ru")]
            got = [fill(plan["tpl"][j][row[0]], row[1:]) for j, row in enumerate(plan["sentences"][i])]
            assert got == expected
    first = fill(data["plans"][0]["tpl"][1][data["plans"][0]["sentences"][4][1][0]], data["plans"][0]["sentences"][4][1][1:])
    assert first.startswith("Из точки p откладываем отрезок pa = ")
    assert data["words"]["step"] == label("step", "ru") == "Шаг"


def test_analytic_values_are_the_solvers_and_drafting_errors_small(shaper_ru):
    study, page = shaper_ru
    data = data_of(page.html)
    pv = data["plans"][0]
    row = next(j for j, rows in enumerate(pv["rows"]) if "v_{A}" in rows)  # v, lowercase, its index marked (issue 32)
    at = 2 * sum(len(r) for r in pv["rows"][:row])
    kin = study.kinematics
    for i in range(12):
        analytic, error = pv["values"][i][at], pv["values"][i][at + 1]
        assert analytic == pytest.approx(np.hypot(*kin.velocity("A")[i]), rel=1e-4)
        # drawn to 0.5 mm at μv: the error is within a few half-millimetres of the plan
        assert abs(error) <= 3 * 0.5 * pv["mu"]
    assert pv["scale"] == "μv = 0,05 (м/с)/мм" and data["plans"][1]["scale"].startswith("μa = ")


def test_templates_keep_only_the_changing_numbers():
    tpl, rows = templates(["pa = 26,9 мм ⊥ O₂A (V = 1,3)", "pa = 27,1 мм ⊥ O₂A (V = 1,3)", None])
    assert tpl == ["pa = {} мм ⊥ O₂A (V = 1,3)"] and rows == [[0, "26,9"], [0, "27,1"], None]
    assert fill(tpl[0], rows[1][1:]) == "pa = 27,1 мм ⊥ O₂A (V = 1,3)"


def test_shown_in_jupyter_without_a_kernel(shaper_ru):
    shown = shaper_ru[1]._repr_html_()
    assert shown.startswith("<iframe srcdoc=") and 'sandbox="allow-scripts"' in shown
    assert "<script" not in shown  # all of it escaped inside the frame's document
    assert "http" not in shown


@pytest.mark.parametrize("argv, message", [
    (["--positions", "721"], "at most 720"),
    (["--positions", "0"], "must be ≥ 1"),
    (["--lang", "fr"], "invalid choice"),
    (["--scale-v", "-0.05"], "positive scale"),
    (["--scale-v", "1e-6"], "no sheet holds it"),
])
def test_bad_arguments_are_one_line_and_no_file(argv, message, tmp_path, capsys):
    out = tmp_path / "page.html"
    try:
        code = main(["html", "shaper", "-o", str(out), *argv])
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("velplan: error: ") and err.count("\n") == 1 and message in err
    assert not out.exists() and not list(tmp_path.iterdir())


def test_bad_output_and_language(tmp_path, capsys):
    assert main(["html", "shaper", "-o", str(tmp_path / "missing" / "p.html")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert main(["html", "shaper", "-o", str(tmp_path)]) == 2
    assert "is a directory" in capsys.readouterr().err
    with pytest.raises(VelplanError, match="unknown language"):
        Page("shaper", positions=4, lang="de")
    with pytest.raises(VelplanError, match="between 1 and 720"):
        Page("shaper", positions=1000)
