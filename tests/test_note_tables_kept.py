"""A table of the note's .docx is not broken across pages (ГОСТ 2.105): every row but the
last keeps with the next, so that a table of a page or less (each part of a long one, which
the note splits itself under "Продолжение таблицы N") goes whole to the next page with its
caption, rather than leaving a row there under a repeated header and no continuation caption."""

from __future__ import annotations

import pytest

from velplan.note.model import ROWS_PER_PAGE, Note


def _keeps(tr, qn) -> list[bool]:
    """Whether each paragraph of a row keeps with the next."""
    return [p.find(qn("w:pPr")) is not None and p.find(qn("w:pPr")).find(qn("w:keepNext")) is not None
            for p in tr.iter(qn("w:p"))]


def test_every_row_but_the_last_keeps_with_the_next(tmp_path):
    pytest.importorskip("pypandoc")
    docx = pytest.importorskip("docx")
    from docx.oxml.ns import qn

    note = Note("ru", "t")
    note.table("short", ["a", "b"], [["1", "2"], ["3", "4"], ["5", "6"]])
    note.table("long", ["k", "k²"], [[str(k), str(k * k)] for k in range(ROWS_PER_PAGE + 3)])
    document = docx.Document(str(note.save(tmp_path / "t.docx")))
    assert [len(t.rows) for t in document.tables] == [4, ROWS_PER_PAGE + 1, 4]  # the long one in two parts
    for table in document.tables:
        rows = table._tbl.findall(qn("w:tr"))
        assert all(all(_keeps(tr, qn)) and _keeps(tr, qn) for tr in rows[:-1])
        assert not any(_keeps(rows[-1], qn))  # the table lets the text after it go on the page
        caption = table._tbl.getprevious()  # the caption goes with the table (its style keeps it)
        assert "Таблица" in "".join(t.text or "" for t in caption.iter(qn("w:t"))) or \
            "Продолжение таблицы" in "".join(t.text or "" for t in caption.iter(qn("w:t")))
