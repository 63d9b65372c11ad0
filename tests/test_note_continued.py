"""Long tables of the note (ГОСТ 2.105): split in parts of `ROWS_PER_PAGE` rows, each part
after the first captioned "Продолжение таблицы N" (uk, en, zh likewise) over the header
repeated; in the .docx every table's header row is marked to repeat on the next page."""

from __future__ import annotations

import pytest

from velplan.note.blocks import Table
from velplan.note.model import ROWS_PER_PAGE, Note

CONTINUED = {"ru": "Продолжение таблицы 2", "uk": "Продовження таблиці 2", "en": "Table 2 (continued)",
             "zh": "续表 2"}


@pytest.mark.parametrize("lang", sorted(CONTINUED))
def test_a_long_table_goes_in_parts_with_the_continuation_caption(lang):
    note = Note(lang, "t")
    note.table("short", ["a"], [["1"]])
    rows = [[str(k), str(k * k)] for k in range(2 * ROWS_PER_PAGE + 5)]
    assert note.table("long", ["k", "k²"], rows, key="squares") == 2
    tables = [b for b in note.blocks if isinstance(b, Table)]
    assert [len(t.rows) for t in tables] == [1, ROWS_PER_PAGE, ROWS_PER_PAGE, 5]
    assert [t.caption for t in tables[2:]] == [CONTINUED[lang]] * 2
    assert all(t.header == ("k", "k²") for t in tables[1:])
    assert [r for t in tables[1:] for r in t.rows] == [tuple(r) for r in rows]  # every row once, in order
    assert note.table("next", ["b"], [["2"]]) == 3  # the parts share their number


def test_a_table_that_fits_is_one_part():
    note = Note("ru", "t")
    note.table("fits", ["k"], [[str(k)] for k in range(ROWS_PER_PAGE)])
    assert sum(isinstance(b, Table) for b in note.blocks) == 1


def test_docx_header_rows_repeat(tmp_path):
    pytest.importorskip("pypandoc")
    docx = pytest.importorskip("docx")
    from docx.oxml.ns import qn

    note = Note("ru", "t")
    note.table("long", ["k", "k²"], [[str(k), str(k * k)] for k in range(ROWS_PER_PAGE + 3)])
    document = docx.Document(str(note.save(tmp_path / "t.docx")))
    assert len(document.tables) == 2
    for table in document.tables:
        rows = table._tbl.findall(qn("w:tr"))
        heads = [tr.find(qn("w:trPr")) is not None and tr.find(qn("w:trPr")).find(qn("w:tblHeader")) is not None
                 for tr in rows]
        assert heads == [True] + [False] * (len(rows) - 1)
        assert [c.text for c in table.rows[0].cells] == ["k", "k²"]
    text = "\n".join(p.text for p in document.paragraphs)
    assert "Продолжение таблицы 1" in text
