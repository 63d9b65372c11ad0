"""The symbols in the note's tables typeset (issue 32): a symbol's index is a subscript run in
the .docx (VA₄ as V with "A4" below the line, ω2, O2, Mд), in the header row too; plain words,
Roman numerals and numbers stay as they are."""

from __future__ import annotations

import pytest

from velplan.note.cells import cell_markdown, split_symbol
from velplan.note.markdown import md_text
from velplan.note.model import Note


@pytest.mark.parametrize("word, split", [("VA₄", ("V", "A4")), ("ω2", ("ω", "2")), ("O2", ("O", "2")),
                                         ("Mд", ("M", "д")), ("JI", ("J", "I")), ("ΔTII", ("ΔT", "II")),
                                         ("aS₄", ("a", "S4")), ("ωmax", ("ω", "max")), ("VBA", ("V", "BA"))])
def test_symbols_split_into_letter_and_index(word, split):
    assert split_symbol(word) == split


@pytest.mark.parametrize("word", ["Value", "II", "XIV", "at", "pa", "ВПВ", "класса", "0,25", "3-4", "Driving"])
def test_words_numbers_and_roman_numerals_are_no_symbols(word):
    assert split_symbol(word) is None


def test_markdown_of_a_cell():
    assert cell_markdown("VA₄ = 1,2", md_text) == "V~A4~ = 1,2"
    assert cell_markdown("Mс, Н·м", md_text) == "M~с~, Н·м"


def test_the_docx_table_sets_indices_as_subscripts(tmp_path):
    pytest.importorskip("pypandoc")
    docx = pytest.importorskip("docx")
    from docx.oxml.ns import qn

    note = Note("ru", "t")
    note.table("Скорости", ["Величина", "ω2, рад/с"], [["VA₄", "1,279"], ["O2", "0"]])
    path = note.save(tmp_path / "t.docx")
    table = docx.Document(str(path)).tables[0]
    subs = []
    for r in table._tbl.iter(qn("w:r")):
        rpr = r.find(qn("w:rPr"))
        va = rpr.find(qn("w:vertAlign")) if rpr is not None else None
        if va is not None and va.get(qn("w:val")) == "subscript":
            subs.append("".join(t.text for t in r.iter(qn("w:t"))))
    assert sorted(subs) == ["2", "2", "A4"]
    text = [c.text for row in table.rows for c in row.cells]
    assert text == ["Величина", "ω2, рад/с", "VA4", "1,279", "O2", "0"]
