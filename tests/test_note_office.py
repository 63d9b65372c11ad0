"""The note's .docx as an office program shows it: the contents written out, ruled tables whose
columns hold their numbers, repeated header rows, a space after each heading's number,
upright Roman numerals, black headings; and, where LibreOffice is installed, the .docx
converted to PDF headless: a filled contents page and no number broken across lines."""

from __future__ import annotations

import re
import zipfile

import pytest

pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")
pdfium = pytest.importorskip("pypdfium2")

from docx.oxml.ns import qn  # noqa: E402

from tests import office, shared_notes  # noqa: E402
from velplan.note.docx_tables import CELL_PAD_TWIPS, cell_text, text_twips  # noqa: E402

M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"


@pytest.fixture(scope="module")
def shaper_ru(tmp_path_factory):
    _, note, path = shared_notes.shaper_ru(tmp_path_factory)  # shared with two files
    return note, path


def _body(path):
    return docx.Document(str(path)).element.body


def _size(tbl) -> int:
    sizes = [int(s.get(qn("w:val"))) for s in tbl.iter(qn("w:sz"))]
    return min(sizes) if sizes else 22


def test_contents_carries_its_entries(shaper_ru):
    """Each heading of levels 1–2 listed with a dot leader to its page, the page a PAGEREF
    field (tests/test_note_contents_pages.py checks the pages)."""
    note, path = shaper_ru
    body = _body(path)
    instr = [t.text for t in body.iter(qn("w:instrText"))]
    entries = [p for p in body.iter(qn("w:p")) if any(re.fullmatch(r"TOC\d", s.get(qn("w:val"), ""))
                                                      for s in p.iter(qn("w:pStyle")))]
    headings = [b for b in note.blocks if type(b).__name__ == "Heading" and b.level <= 2]
    assert len(entries) == len(headings) >= 10
    assert sum(t.strip().startswith("PAGEREF _Toc") for t in instr) == len(entries)
    pages = []
    for p, h in zip(entries, headings):
        text = "".join(t.text for t in p.iter(qn("w:t")))
        assert h.text in text, (h.text, text)
        assert p.find(f".//{qn('w:tab')}") is not None  # the dot leader to the page number
        pages.append(int(list(p.iter(qn("w:t")))[-1].text))
    assert pages == sorted(pages) and pages[0] >= 3  # title page, contents, then the text


def test_level3_headings_have_a_space_after_the_number(shaper_ru):
    _, path = shaper_ru
    doc = docx.Document(str(path))
    level3 = [p for p in doc.paragraphs if p.style.name.startswith("Heading 3")]
    assert level3
    for p in level3:
        assert re.match(r"^\d+\.\d+\.\d+ \S", p.text), p.text
        assert "\t" not in p.text


def test_tables_are_ruled_headed_and_fit_their_columns(shaper_ru):
    _, path = shaper_ru
    tables = list(_body(path).iter(qn("w:tbl")))
    assert len(tables) >= 15
    for tbl in tables:
        borders = tbl.find(f"{qn('w:tblPr')}/{qn('w:tblBorders')}")
        assert borders is not None and {b.get(qn("w:val")) for b in borders} == {"single"}
        first = tbl.find(qn("w:tr"))
        assert first.find(f"{qn('w:trPr')}/{qn('w:tblHeader')}") is not None
        grid = [int(c.get(qn("w:w"))) for c in tbl.find(qn("w:tblGrid"))]
        assert sum(grid) <= 9638 + len(grid)
        size = _size(tbl)
        for tr in tbl.findall(qn("w:tr")):
            for tc, width in zip(tr.findall(qn("w:tc")), grid):
                for word in " ".join(cell_text(tc)).split():
                    assert text_twips(word, size) + CELL_PAD_TWIPS <= width + 1, (word, width)


def test_headings_black_roman_numerals_upright_equations_body_size(shaper_ru):
    _, path = shaper_ru
    styles = zipfile.ZipFile(path).read("word/styles.xml").decode("utf-8")
    for level in (1, 2, 3):
        style = re.search(rf'<w:style [^>]*w:styleId="Heading{level}".*?</w:style>', styles, re.S).group(0)
        assert "<w:color" not in style and "<w:i/>" not in style and "<w:b/>" in style
    body = _body(path)
    texts = ["".join(t.text or "" for t in r.iter(f"{M}t")) for r in body.iter(f"{M}r")]
    assert "II" in texts  # the class of a dyad is one upright run, not two italic I's
    body_size = re.search(r'<w:rPrDefault><w:rPr>.*?<w:sz w:val="(\d+)"', styles, re.S).group(1)
    sizes = {s.get(qn("w:val")) for r in body.iter(f"{M}r") for s in r.iter(qn("w:sz"))}
    assert sizes == {body_size}


@pytest.fixture(scope="module")
def office_pdf(shaper_ru, tmp_path_factory):
    exe = office.soffice("to check the .docx as an office program lays it out")
    _, path = shaper_ru
    return office.printed_pages(exe, [path], tmp_path_factory.mktemp("office-pdf"))[path]


def test_libreoffice_shows_a_filled_contents_page(office_pdf):
    contents = office_pdf[1]
    assert "Содержание" in contents
    lines = [x for x in contents.splitlines() if re.search(r"\.{5,}\s*\d+\s*$", x)]
    assert len(lines) >= 10, contents


def _on_the_line(tc) -> str:
    """A cell's text without its raised runs (R₄₅ of "R₄₅^τ"): the PDF's text reads a raised
    letter as a line of its own, above the line it stands on."""
    parts = []
    for p in tc.iter(qn("w:p")):
        for r in p.iter(qn("w:r")):
            align = r.find(f"{qn('w:rPr')}/{qn('w:vertAlign')}")
            if align is None or align.get(qn("w:val")) != "superscript":
                parts.append("".join(t.text or "" for t in r.iter(qn("w:t"))))
        parts.append(" ")
    return "".join(parts)


def test_libreoffice_breaks_no_number_across_lines(shaper_ru, office_pdf):
    """Every number and word of every table cell stands whole on one line of the PDF."""
    _, path = shaper_ru
    lines = {" ".join(x.split()) for page in office_pdf for x in page.splitlines()}
    text = "\n".join(lines)
    words = {w for tbl in _body(path).iter(qn("w:tbl")) for tc in tbl.iter(qn("w:tc"))
             for w in _on_the_line(tc).split() if re.search(r"\d", w) or len(w) >= 6}
    words = {w for w in words if "⁻" not in w}  # pdfium reads a fallback font's superscript minus out of order
    assert len(words) > 100
    missing = sorted(w for w in words if w not in text)
    assert not missing, f"broken across lines in LibreOffice: {missing[:10]}"


def test_properties_in_the_schemas_order(shaper_ru):
    """Word refuses a file whose run, paragraph or style properties are out of the schema's
    order: every such element the note writes or edits keeps it."""
    from lxml import etree

    from velplan.note.docx_layout import _ORDER

    _, path = shaper_ru
    w = "{http://schemas.openxmlformats.org/wordprocessingml/2006/main}"
    archive = zipfile.ZipFile(path)
    checked = 0
    for part in [n for n in archive.namelist() if n.startswith("word/") and n.endswith(".xml")]:
        root = etree.fromstring(archive.read(part))
        for key, order in _ORDER.items():
            for el in root.iter(w + key[2:]):
                ranks = [order.index(c.tag[len(w):]) for c in el if c.tag.startswith(w) and c.tag[len(w):] in order]
                assert ranks == sorted(ranks), (part, key, [c.tag[len(w):] for c in el])
                checked += 1
    assert checked > 500
