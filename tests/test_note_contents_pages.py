"""The note's contents page prints, for every heading, the page the heading is printed on.

Each entry's page is a PAGEREF field to a bookmark in its heading, so an office program
computes it while laying the pages out; the field's stored result is the estimate of
`velplan.note.docx_toc.estimate_pages`. Where LibreOffice is installed, two notes (two
mechanisms, two languages) are converted to PDF and every entry of the printed contents page
is compared with the page on which the PDF carries that heading."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")
pdfium = pytest.importorskip("pypdfium2")

from docx.oxml.ns import qn  # noqa: E402

from tests import office  # noqa: E402
from velplan.note import build_note, write_note  # noqa: E402
from velplan.study import Study  # noqa: E402

CASES = (("crank-slider", "en"), ("four-bar", "zh"))


@pytest.fixture(scope="module")
def notes(tmp_path_factory):
    out = tmp_path_factory.mktemp("contents")
    paths = {}
    for mech, lang in CASES:
        note = build_note(Study(mech), n=6, plans=(1,), lang=lang)
        paths[(mech, lang)] = write_note(note, out / f"{mech}-{lang}.docx")
    return paths


def _entries(path) -> list[tuple[str, str, int]]:
    """(text, bookmark, stored page) of each entry of the contents."""
    out = []
    for p in docx.Document(str(path)).element.body.iter(qn("w:p")):
        style = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
        if style is None or not re.fullmatch(r"TOC\d", style.get(qn("w:val"))):
            continue
        instr = "".join(t.text for t in p.iter(qn("w:instrText")))
        texts = [t.text for t in p.iter(qn("w:t"))]
        out.append((texts[0], instr.split()[1], int(texts[-1])))
    return out


def test_each_entry_is_a_pageref_to_its_heading(notes):
    """No TOC field (LibreOffice would print its stored result as fixed text): each entry's
    page is a PAGEREF to a bookmark inside the heading of the same text."""
    for path in notes.values():
        body = docx.Document(str(path)).element.body
        assert not any(t.text.strip().startswith("TOC") for t in body.iter(qn("w:instrText")))
        headings = {}
        for p in body.iter(qn("w:p")):
            style = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
            if style is not None and style.get(qn("w:val")) in ("Heading1", "Heading2"):
                names = [b.get(qn("w:name")) for b in p.iter(qn("w:bookmarkStart"))]
                text = " ".join("".join(t.text for t in p.iter(qn("w:t"))).split())
                headings.update({n: text for n in names})
        entries = _entries(path)
        assert len(entries) >= 8
        pages = [page for _, _, page in entries]
        assert pages == sorted(pages) and pages[0] >= 3  # title page, contents, then the text
        for text, mark, _ in entries:
            assert headings.get(mark) == text, (mark, text)


@pytest.fixture(scope="module")
def printed(notes, tmp_path_factory):
    """The text of each page of each note as LibreOffice prints it."""
    exe = office.soffice("to compare the contents page with the pages LibreOffice prints the headings on")
    pages = office.printed_pages(exe, list(notes.values()), tmp_path_factory.mktemp("contents-pdf"))
    return {key: pages[path] for key, path in notes.items()}


def _lines(page: str) -> list[str]:
    return [" ".join(x.split()) for x in page.splitlines()]


@pytest.mark.parametrize("case", CASES, ids=["-".join(c) for c in CASES])
def test_contents_page_numbers_are_the_pages_of_the_headings(notes, printed, case):
    pages = printed[case]
    contents = [re.match(r"(.*?)\s*\.{4,}\s*(\d+)$", x) for x in _lines(pages[1])]
    listed = [int(m.group(2)) for m in contents if m]
    entries = _entries(notes[case])
    assert len(listed) == len(entries) >= 8, pages[1]
    at = 2
    for (text, _, _), page in zip(entries, listed):
        found = next((k for k in range(at, len(pages)) if text in _lines(pages[k])), None)
        assert found is not None, f"{case}: heading {text!r} not found after page {at + 1}"
        assert page == found + 1, f"{case}: {text!r} is listed on page {page}, printed on {found + 1}"
        at = found


@pytest.mark.parametrize("case", CASES, ids=["-".join(c) for c in CASES])
def test_stored_pages_estimate_the_printed_ones(notes, printed, case):
    """The fields' stored results (what a viewer that computes no fields shows) are the
    layout model's estimate: within a page of LibreOffice's, and most of them exact."""
    pages = printed[case]
    listed = [int(m.group(2)) for m in (re.match(r"(.*?)\s*\.{4,}\s*(\d+)$", x) for x in _lines(pages[1])) if m]
    stored = [page for _, _, page in _entries(notes[case])]
    assert len(stored) == len(listed)
    off = [abs(a - b) for a, b in zip(stored, listed)]
    assert max(off) <= 1 and off.count(0) >= 0.8 * len(off), list(zip(stored, listed))
