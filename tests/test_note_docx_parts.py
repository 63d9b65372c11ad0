"""The .docx note's parts as a course teacher checks them: the designation a code with no
file name, the headings of the unnumbered parts and the contents' title centred and bold, a
lead-in paragraph ("Формула строения:") kept on the page of what it introduces."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")

from docx.oxml.ns import qn  # noqa: E402

from velplan.note import build_note, write_note  # noqa: E402
from velplan.study import Study  # noqa: E402


@pytest.fixture(scope="module", params=["ru", "en"])
def note_docx(request, tmp_path_factory):
    note = build_note(Study("crank-slider"), n=6, plans=(1,), lang=request.param)
    path = write_note(note, tmp_path_factory.mktemp("parts") / "note.docx")
    return request.param, docx.Document(str(path))


def _style(p) -> str:
    s = p.find(f"{qn('w:pPr')}/{qn('w:pStyle')}")
    return s.get(qn("w:val")) if s is not None else ""


def _text(p) -> str:
    return "".join(t.text or "" for t in p.iter(qn("w:t")))


def test_designation_is_the_course_works_code(note_docx):
    lang, doc = note_docx
    texts = [_text(p) for p in doc.element.body.iter(qn("w:p"))]
    code = {"ru": "ТММ 00.00.000 ПЗ", "en": "TMM 00.00.000"}[lang]
    assert code in texts
    assert not any(re.search(r"(ТММ|TMM)\.", t) for t in texts)  # no "ТММ.crank-slider.00": no file key


def test_unnumbered_parts_and_the_contents_title_are_centred(note_docx):
    _, doc = note_docx
    body = doc.element.body
    unnumbered = [p for p in body.iter(qn("w:p")) if _style(p) == "Heading1"
                  and not re.match(r"\d", _text(p))]
    numbered = [p for p in body.iter(qn("w:p")) if _style(p) == "Heading1" and re.match(r"\d", _text(p))]
    assert len(unnumbered) >= 3 and numbered  # introduction, conclusion, references
    for p in unnumbered:
        assert p.find(f"{qn('w:pPr')}/{qn('w:jc')}").get(qn("w:val")) == "center", _text(p)
        assert p.find(f"{qn('w:pPr')}/{qn('w:ind')}").get(qn("w:firstLine")) == "0"
    for p in numbered:
        assert p.find(f"{qn('w:pPr')}/{qn('w:jc')}") is None, _text(p)
    title = doc.styles.element.find(f"{qn('w:style')}[@{qn('w:styleId')}='TOCHeading']")
    assert title.find(f"{qn('w:pPr')}/{qn('w:jc')}").get(qn("w:val")) == "center"
    bold = title.find(f"{qn('w:rPr')}/{qn('w:b')}")
    assert bold is not None and bold.get(qn("w:val")) in (None, "1", "true")


def test_a_lead_in_is_kept_with_what_it_introduces(note_docx):
    _, doc = note_docx
    leads = [p for p in doc.element.body if p.tag == qn("w:p") and _text(p).rstrip().endswith(":")]
    assert leads
    for p in leads:
        assert p.find(f"{qn('w:pPr')}/{qn('w:keepNext')}") is not None, _text(p)


def _names():
    from pathlib import Path

    import velplan
    from velplan.mechanism.loader import load

    root = Path(velplan.__file__).parent
    return [load(f.stem) for folder in ("examples", "catalogue") for f in sorted((root / folder).glob("*.toml"))]


def test_topic_names_the_mechanism_once():
    """"the mechanism of the offset crank-slider mechanism" and 曲柄滑块机构机构 are not written."""
    from velplan.note.text import mechanism_of, p

    mechanisms = _names()
    assert len(mechanisms) >= 25
    for mech in mechanisms:
        en = p("topic", "en", mechanism_of(mech.name_in("en"), "en"))
        assert len(re.findall(r"\b(?:mechanism|linkage)\b", en)) == 1, en
        zh = p("intro", "zh", mechanism_of(mech.name_in("zh"), "zh"), "")
        assert "机构机构" not in zh and "机构" in zh, zh
        assert p("topic", "ru", mechanism_of(mech.name_in("ru"), "ru")).startswith("Исследование механизма: ")


def test_column_headings_start_with_a_capital_unless_a_symbol(note_docx):
    """ГОСТ 2.105: a table's column headings begin with a capital letter ("По плану",
    "Отрезок, мм"); a symbol keeps its case ("h, мм", "ω3/ω2")."""
    from velplan.note.cells import split_symbol

    _, doc = note_docx
    headings = []
    for tbl in doc.element.body.iter(qn("w:tbl")):
        for tc in tbl.find(qn("w:tr")).findall(qn("w:tc")):
            headings.append("".join(t.text or "" for t in tc.iter(qn("w:t"))))
    assert len(headings) >= 20
    for h in headings:
        word = re.match(r"[^\W\d_]+", h)
        if word and len(word.group(0)) >= 2 and not split_symbol(re.match(r"\w+", h).group(0)):
            assert word.group(0)[0].isupper(), h


def test_what_stands_left_of_an_equals_sign_is_a_formula(note_docx):
    """"lAB = 0.2 m", "Fc = 1400 N", "H = 0.1 m" of the input data are symbols with their
    indices (l_AB, F_c), not words of plain text, in English as in Russian."""
    from tests.note_prose import prose

    _, doc = note_docx
    texts = [text for _, text in prose(doc.element.body)]
    assert texts
    plain = [t for t in texts if re.search(r"(?<!\w)[A-Za-z][A-Za-z₀-₉]* = ", t)]
    assert not plain, plain[:5]


def test_a_dyads_kind_is_plain_text(note_docx):
    """The kind of an Assur dyad (RRP, RPR) is a name, not R with the index "RP"."""
    lang, doc = note_docx
    cells = [tc for tc in doc.element.body.iter(qn("w:tc"))
             if re.search(r"\b[RP]{3}\b", "".join(t.text or "" for t in tc.iter(qn("w:t"))))]
    if lang == "en":
        assert cells
    for tc in cells:
        assert tc.find(f".//{qn('w:vertAlign')}") is None, "".join(t.text or "" for t in tc.iter(qn("w:t")))
