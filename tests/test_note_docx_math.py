"""The .docx's formulas converted beside its text (`velplan.note.docx_math`): the document is
the one pandoc makes of the whole note — every part but its date the same bytes — and a formula
pandoc would not read as one on its own sends the writer back to one whole conversion."""

from __future__ import annotations

import io
import zipfile

import pytest

pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")

from velplan.note import build_note, writers  # noqa: E402
from velplan.note.blocks import Equation, Heading, Math, Para  # noqa: E402
from velplan.note.docx_math import FormulaRun, formulas, put_formulas  # noqa: E402
from velplan.note.markdown import to_markdown  # noqa: E402
from velplan.note.model import Note  # noqa: E402
from velplan.note.pandoc import Pandoc  # noqa: E402


def _parts(data: bytes) -> dict[str, bytes]:
    z = zipfile.ZipFile(io.BytesIO(data))
    return {n: z.read(n) for n in z.namelist() if n != "docProps/core.xml"}  # core.xml: the date


def _whole(monkeypatch, note, tmp_path) -> bytes:
    """The .docx as written by one pandoc run of the whole note (no placeholders)."""
    monkeypatch.setattr("velplan.note.docx_math.formulas", lambda note: [])
    (tmp_path / "whole").mkdir()
    return writers._docx(note, tmp_path / "whole", tmp_path / "n.docx")


def _small_note() -> Note:
    note = Note("en", "formulas")
    note.add(Heading("Kinematics", 1),
             Para.of("The speed ", Math(r"v_{A} = \omega_{2} l_{O_{2}A}"), " and again ",
                     Math(r"v_{A} = \omega_{2} l_{O_{2}A}"), "; the angle ", Math(r"\varphi"), "."),
             Equation(r"\frac{a}{b} = \sqrt{c^{2} + d^{2}}"),
             Para.of("After the displayed formula, ", Math(r"x_{1}"), "."),
             Equation(r"\frac{a}{b} = \sqrt{c^{2} + d^{2}}"))
    return note


def test_a_small_note_is_the_whole_conversion(monkeypatch, tmp_path):
    note = _small_note()
    wanted = formulas(note)
    assert [t for t, _ in wanted].count(r"v_{A} = \omega_{2} l_{O_{2}A}") == 2
    assert [shown for _, shown in wanted] == [False, False, False, True, False, True]
    (tmp_path / "split").mkdir()
    split = writers._docx(note, tmp_path / "split", tmp_path / "n.docx")
    assert _parts(split) == _parts(_whole(monkeypatch, note, tmp_path))


def test_a_course_note_is_the_whole_conversion(monkeypatch, tmp_path):
    note = build_note("four-bar", n=4, parts=["kinematics"], lang="ru", plans=[2])
    assert len(formulas(note)) > len(set(formulas(note))) > 20
    (tmp_path / "split").mkdir()
    split = writers._docx(note, tmp_path / "split", tmp_path / "n.docx")
    assert _parts(split) == _parts(_whole(monkeypatch, note, tmp_path))


def test_a_formula_pandoc_does_not_read_falls_back(monkeypatch, tmp_path):
    note = _small_note()
    note.add(Para.of("Not a formula to pandoc: ", Math(" x"), " (a space after the dollar)."))
    wanted = formulas(note)
    run = FormulaRun(wanted, tmp_path / "math")
    assert run.equations() is None  # its paragraph holds text, not an equation
    source = Pandoc(to_markdown(note, "docx", {}, placeholder="q"), "docx", tmp_path).result()
    assert not put_formulas(docx.Document(io.BytesIO(source)), wanted, {})
    (tmp_path / "split").mkdir()
    split = writers._docx(note, tmp_path / "split", tmp_path / "n.docx")
    assert _parts(split) == _parts(_whole(monkeypatch, note, tmp_path))
    assert b" x" in _parts(split)["word/document.xml"]


def test_placeholders_that_do_not_match_change_nothing(tmp_path):
    note = _small_note()
    wanted = formulas(note)
    equations = FormulaRun(wanted, tmp_path / "math").equations()
    assert equations is not None and len(equations) == len(set(wanted)) == 4
    doc = docx.Document(io.BytesIO(Pandoc(to_markdown(note, "docx", {}, placeholder="q"), "docx",
                                          tmp_path).result()))
    before = doc.element.xml
    assert not put_formulas(doc, wanted[:-1], equations)  # one placeholder too many
    assert not put_formulas(doc, [(t, not shown) for t, shown in wanted], equations)  # kinds swapped
    assert doc.element.xml == before
    assert put_formulas(doc, wanted, equations)
    assert "\\frac" not in doc.element.xml and doc.element.xml.count("<m:f>") == 2  # two displayed fractions
