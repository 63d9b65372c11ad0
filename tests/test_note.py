"""The explanatory note (`velplan note`): .docx with Word equations, .pdf typeset by Typst,
.html and .md; its numbers are the sheets' own. Each note is built once per module."""

from __future__ import annotations

import re
import sys
import zipfile

import numpy as np
import pytest

pytest.importorskip("pypandoc")
pytest.importorskip("typst")
pytest.importorskip("docx")
pdfium = pytest.importorskip("pypdfium2")
pdfium_raw = pytest.importorskip("pypdfium2.raw")

from tests import shared_notes  # noqa: E402
from velplan.cli import main  # noqa: E402
from velplan.note import build_note, write_note  # noqa: E402
from velplan.note.blocks import Figure  # noqa: E402
from velplan.note.formulas import force  # noqa: E402
from velplan.note.text import p  # noqa: E402
from velplan.study import Study  # noqa: E402

MM = 72 / 25.4  # PDF points per mm


@pytest.fixture(scope="module")
def ru(tmp_path_factory):
    """The shaper's full note in Russian: 2 positions, kinematics, forces, dynamics."""
    out = tmp_path_factory.mktemp("note-ru")
    study, note, docx = shared_notes.shaper_ru(tmp_path_factory)  # its .docx shared with two files
    paths = {"docx": docx} | {ext: write_note(note, out / f"note.{ext}") for ext in ("pdf", "md")}
    return study, note, paths


@pytest.fixture(scope="module")
def others(tmp_path_factory):
    """The kinematics part in en, uk and zh, as PDF (and HTML in English)."""
    out = tmp_path_factory.mktemp("note-langs")
    study = Study("shaper")
    result = {}
    for lang in ("en", "uk", "zh"):
        note = build_note(study, lang=lang, parts=("kinematics",))
        result[lang] = (note, write_note(note, out / f"note-{lang}.pdf"))
    result["html"] = write_note(result["en"][0], out / "note.html")
    return result


def _close(text: str, value: float) -> bool:
    """``text`` (as printed: decimal comma or point, − or -) equals ``value`` to its digits."""
    s = text.strip().replace(",", ".").replace("−", "-").replace(" ", "")
    decimals = len(s.split(".")[1]) if "." in s else 0
    return abs(float(s) - value) <= 0.5 * 10.0 ** -decimals * (1 + 1e-9) + 1e-12 * abs(value)


def _md_tables(md: str) -> dict[str, list[list[str]]]:
    """Caption → rows (cells, header included) of every table of the Markdown note."""
    tables = {}
    for caption, body in re.findall(r"\*\*(.+?)\*\*\n\n((?:\|.*\|\n?)+)", md):
        rows = [[c.strip().replace("\\", "") for c in line.strip().strip("|").split("|")]
                for line in body.strip().splitlines() if not line.startswith("|-")]
        tables[caption.replace("\\", "")] = rows
    return tables


def _table(tables, start: str, *, contains: str = "") -> list[list[str]]:
    found = [rows for cap, rows in tables.items() if start in cap and contains in cap]
    assert found, f"no table {start!r} {contains!r} in {list(tables)}"
    return found[0]


def test_cli_writes_docx_and_pdf(tmp_path, capsys):
    for ext in ("docx", "pdf"):
        out = tmp_path / f"note.{ext}"
        assert main(["note", "shaper", "--lang", "ru", "--parts", "kinematics", "--plans", "3",
                     "-o", str(out)]) == 0
        assert out.stat().st_size > 10_000
    assert out.read_bytes().startswith(b"%PDF")


def test_docx_has_word_equations_per_velocity_step(ru):
    import docx

    study, note, paths = ru
    doc = docx.Document(str(paths["docx"]))
    assert any(p("note", "ru") in par.text for par in doc.paragraphs)
    xml = zipfile.ZipFile(paths["docx"]).read("word/document.xml").decode("utf-8")
    equations = xml.count("<m:oMath>") + xml.count("<m:oMath ")
    steps = sum(1 for s in study.plan("velocity").steps if s.target.startswith("v:"))
    positions = [b for b in note.blocks if getattr(b, "text", "").startswith("План скоростей")]
    assert len(positions) == 2
    assert equations >= steps * len(positions)
    # each step's paragraph is followed by at least one equation before the next step
    body = re.split(r"Шаг \d+\.", xml)[1:]
    assert body and all("<m:oMath" in part for part in body)
    section = doc.sections[0]
    assert abs(section.page_width.mm - 210) < 0.5 and abs(section.page_height.mm - 297) < 0.5


def test_pdf_pages_figures_and_margins(ru, tmp_path):
    _, note, paths = ru
    pdf = pdfium.PdfDocument(str(paths["pdf"]))
    assert len(pdf) >= 10
    # every figure drawn, as a vector drawing: its lettering is text of the page its caption is on
    pages = [page.get_textpage().get_text_range().replace("\r\n", "\n") for page in pdf]
    figures = [b for b in note.blocks if isinstance(b, Figure)]
    assert len(figures) == note.figures >= 15
    for k, fig in enumerate(figures, 1):
        on = [t for t in pages if re.search(rf"{p('figure', note.lang)} {k} — ", t)]
        words = {w for w in re.findall(r">([^<>]{4,})<", fig.svg) if not w.isspace()}
        assert len(on) == 1 and words, fig.name
        found = [w for w in words if re.sub(r"\s+", "", w) in re.sub(r"\s+", "", on[0])]
        assert len(found) >= 0.8 * len(words), (fig.name, sorted(words - set(found)))
    for k, page in enumerate(pdf):
        w, h = page.get_size()
        text = page.get_textpage()
        for c in range(text.count_chars()):
            box = text.get_charbox(c)
            if box == (0, 0, 0, 0):
                continue
            left, bottom, right, top = box
            assert left >= 10 * MM and right <= w - 10 * MM and bottom >= 5 * MM and top <= h - 10 * MM, \
                f"page {k + 1}: character {c} at {box} runs into the edge"
        png = np.asarray(page.render(scale=0.5).to_pil().convert("L"))
        edge = int(round(8 * MM * 0.5))  # an 8 mm band along each side of the page stays paper
        for band in (png[:, :edge], png[:, -edge:], png[:edge, :], png[-edge:, :]):
            assert band.min() > 200, f"page {k + 1}: ink in the outer 8 mm"


def test_pdf_fonts_embedded(ru, others):
    for path in [ru[2]["pdf"]] + [others[lang][1] for lang in ("en", "uk", "zh")]:
        pdf = pdfium.PdfDocument(str(path))
        for page in pdf:
            for obj in page.get_objects(filter=[pdfium_raw.FPDF_PAGEOBJ_TEXT]):
                font = pdfium_raw.FPDFTextObj_GetFont(obj.raw)
                assert pdfium_raw.FPDFFont_GetIsEmbedded(font), f"{path.name}: a font is not embedded"


def test_numbers_of_the_note_are_the_studys(ru):
    """Velocities, accelerations, ω, ε, reactions, balancing moments and J_I as printed in the
    note equal the study's values to the printed digits."""
    study, note, paths = ru
    md = paths["md"].read_text(encoding="utf-8")
    tables = _md_tables(md)
    checked = 0
    for k in (4, 10):
        i = k - 1
        for kind, start in (("velocity", p("results_v", "ru")), ("acceleration", p("results_a", "ru"))):
            res = study.plan(kind)
            rates = res.omegas if kind == "velocity" else res.epsilons
            rows = _table(tables, start, contains=f"рисунок {_figure_of(note, kind, k)})")[1:]
            for quantity, value, _ in rows:
                name = quantity[1:].translate(str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789"))
                if quantity[0] in "ωε":
                    exact = abs(float(rates[name][i]))
                else:
                    exact = float(np.hypot(*res.vector(name)[i]))
                assert _close(value, exact), (k, quantity, value, exact)
                checked += 1
        ks = study.forces().kinetostatics
        section = md.rsplit(f"# Кинетостатика, положение {k}", 1)[1].split("Рычаг Жуковского, положение")[0]
        for rc in ks.reactions.values():
            m = re.search(re.escape(force(rc.label)) + r" = \\text\{([^}]*)\}", section)
            assert m, rc.label
            assert _close(m.group(1), float(rc.magnitude[i])), (k, rc.label, m.group(1))
            checked += 1
    moments = study.forces().balancing_moments
    rows = _table(tables, "Уравновешивающий момент")[1:]
    for row in rows:
        j = int(row[0]) - 1
        for cell, key in zip(row[2:], ("kinetostatics", "lever", "power")):
            assert _close(cell, float(moments[key][j])), (j, key, cell)
            checked += 1
    fly = study.dynamics.flywheel
    dyn = {r[0]: r[1] for r in _table(tables, p("dyn_results", "ru"))[1:]}
    assert _close(dyn["JI (точно)"], fly.exact)
    assert _close(dyn["JI (Мерцалов)"].split()[0], fly.mertsalov)
    m = re.search(r"J_\{I\} = .* = \\text\{([^}]*)\}\\ \\text\{кг·м²\}", md)
    assert m and _close(m.group(1), fly.exact)
    assert checked > 60


def _figure_of(note, kind: str, k: int) -> int:
    word = "План скоростей" if kind == "velocity" else "План ускорений"
    for block in note.blocks:
        cap = getattr(block, "caption", "")
        if cap.startswith("Рисунок") and f"{word}, положение {k}" in cap:
            return int(cap.split()[1])
    raise AssertionError(f"no figure of the {kind} plan at {k}")


def test_four_languages(ru, others):
    from fontTools.ttLib import TTFont

    from velplan.note.model import Para
    from velplan.note.writers import FONT_DIR

    cmap = TTFont(str(FONT_DIR / "VelplanSans-Regular.ttf")).getBestCmap()
    for lang in ("en", "uk", "zh"):
        note, path = others[lang]
        pdf = pdfium.PdfDocument(str(path))
        title = pdf[0].get_textpage().get_text_range()
        assert p("note", lang) in title.replace("\r\n", " ").replace("\n", " ")
        texts = "".join(x for b in note.blocks if isinstance(b, Para) for x in b.parts if isinstance(x, str))
        missing = {c for c in texts if not c.isspace() and ord(c) not in cmap}
        assert not missing, f"{lang}: no glyph for {sorted(missing)}"
    html = others["html"].read_text(encoding="utf-8")
    assert "<math" in html and 'src="data:image/png;base64,' in html and 'src="figure-' not in html


def test_markdown_figures_beside_it(ru):
    md = ru[2]["md"]
    folder = md.with_name("note-figures")
    assert sorted(x.name for x in folder.iterdir()) == sorted(f"figure-{k}.png" for k in range(1, ru[1].figures + 1))
    assert "](note-figures/figure-1.png)" in md.read_text(encoding="utf-8")


def test_errors_are_one_line_without_output(tmp_path, capsys, monkeypatch):
    out = tmp_path / "n.pdf"
    assert main(["note", "shaper", "-o", str(tmp_path / "n.txt")]) == 2
    assert main(["note", "shaper", "--parts", "speeds", "-o", str(out)]) == 2
    assert main(["note", "shaper", "--plans", "13", "-o", str(out)]) == 2
    monkeypatch.setitem(sys.modules, "typst", None)  # the extra is not installed
    assert main(["note", "shaper", "--parts", "kinematics", "--plans", "2", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 4 and all(line.startswith("velplan: error: ") for line in err)
    assert "pip install" in err[-1] and "[note]" in err[-1]
    assert list(tmp_path.iterdir()) == []


def test_batch_writes_each_variants_note(tmp_path):
    import json

    out = tmp_path / "course"
    assert main(["batch", "--random", "1", "--base", "crank-slider", "--seed", "note test", "--no-sheets",
                 "--note", "md", "--jobs", "1", "--quiet", "-o", str(out)]) == 0
    key = json.loads((out / "answers.json").read_text(encoding="utf-8"))
    name = key["variants"][0]["note"]
    assert name.endswith("-note.md") and (out / name).stat().st_size > 1000
