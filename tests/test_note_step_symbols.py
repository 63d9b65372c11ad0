"""The construction steps' sentences in the note set their point names, segments, vectors and
rates as symbols (italic, digits as subscripts), from the symbols the plans mark
(`velplan.plans.text.Sym`), while the plain-text outputs print the same sentences as before."""

from __future__ import annotations

import re
import subprocess
import sys
import zipfile

import pytest

from velplan.plans import text as T

M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"
W = "{http://schemas.openxmlformats.org/wordprocessingml/2006/main}"


def _math_text(e) -> str:
    """An equation's letters, a subscript written as _{…}, a superscript as ^{…}."""
    tag = e.tag
    if tag == f"{M}t":
        return e.text or ""
    if tag == f"{M}sSub":
        return _math_text(e.find(f"{M}e")) + "_{" + _math_text(e.find(f"{M}sub")) + "}"
    if tag == f"{M}sSup":
        return _math_text(e.find(f"{M}e")) + "^{" + _math_text(e.find(f"{M}sup")) + "}"
    return "".join(_math_text(k) for k in e if not k.tag.endswith("Pr"))


def _italic(run) -> bool:
    """A math run is italic unless it is styled plain (m:sty p) or normal text (m:nor)."""
    rpr = run.find(f"{M}rPr")
    if rpr is None:
        return True
    sty = rpr.find(f"{M}sty")
    return rpr.find(f"{M}nor") is None and (sty is None or sty.get(f"{M}val") != "p")


@pytest.fixture(scope="module", params=["en", "ru", "uk", "zh"])
def note(request, tmp_path_factory):
    """(lang, the paragraphs of the shaper's note: [(prose text, [equation texts], [equations])])."""
    pytest.importorskip("pypandoc")
    from docx.oxml import parse_xml

    from velplan.note import build_note

    lang = request.param
    path = tmp_path_factory.mktemp(lang) / "n.docx"
    build_note("shaper", lang=lang).save(path)
    root = parse_xml(zipfile.ZipFile(path).read("word/document.xml"))
    paras = []
    for p in root.iter(f"{W}p"):
        maths = [e for e in p if e.tag == f"{M}oMath"]
        prose = "".join(t.text or "" for r in p if r.tag == f"{W}r" for t in r.iter(f"{W}t"))
        paras.append((prose, [_math_text(e) for e in maths], maths, p))
    return lang, paras


STEP = {"en": "Step", "ru": "Шаг", "uk": "Крок", "zh": "第"}
LINE = {"en": "Through", "ru": "Через точку", "uk": "Через точку", "zh": "作直线"}


def _steps(lang, paras):
    return [x for x in paras if x[0].startswith(STEP[lang])]


def test_a_line_step_sets_its_point_link_and_vector_as_symbols(note):
    lang, paras = note
    line = next(x for x in _steps(lang, paras) if LINE[lang] in x[0] and "∥" in x[0])
    prose, texts, maths, _ = line
    # "Through a draw a line ∥ O3A (direction of V_A4A)": a, O₃A, V_{A₄A} are formulas
    assert texts[:3] == ["a", "O_{3}A", "V_{A_{4}A}"]
    o3a = maths[1].find(f"{M}sSub")
    assert o3a.find(f"{M}e").find(f".//{M}t").text == "O" and _italic(o3a.find(f"{M}e").find(f"{M}r"))
    assert o3a.find(f"{M}sub").find(f".//{M}t").text == "3"
    assert all(_italic(r) for r in maths[0].iter(f"{M}r"))
    # no point name, link or vector is left in the plain text of the sentence
    words = {"en": r"Step \d+\. Through +draw a line ∥ +\(direction of \)\.",
             "ru": r"Шаг \d+\. Через точку +проводим прямую ∥ +\(направление \)\.",
             "uk": r"Крок \d+\. Через точку +проводимо пряму ∥ +\(напрям \)\.",
             "zh": r"第 \d+\s步。 *过 +作直线 ∥ +（ *的方向）。"}
    assert re.fullmatch(words[lang], prose), prose


def test_no_step_sentence_leaves_a_symbol_in_plain_text(note):
    lang, paras = note
    steps = _steps(lang, paras)
    assert len(steps) >= 20  # the velocity and acceleration plans of two positions
    for prose, texts, _, _ in steps:
        words = re.findall(r"(?<![\w])[A-Za-zπ][A-Za-z0-9π_]*(?![\w])", prose)
        allowed = {"en": {"Step", "Choose", "the", "pole", "images", "of", "fixed", "points", "are", "at", "From",
                          "lay", "off", "from", "in", "sense", "Through", "draw", "a", "line", "direction", "The", "two",
                          "lines", "meet", "sine", "their", "angle", "By", "similarity", "link", "place", "towards",
                          "along", "turned", "mm", "m", "s", "does", "not", "turn", "image", "coincides", "with"}}
        allowed["zh"] = {"mm", "m", "s"}  # units a zh note writes in Latin letters
        assert set(words) <= allowed.get(lang, set()), (prose, set(words) - allowed.get(lang, set()))
        assert not any("_" in t and "_{" not in t for t in texts)


def test_the_pole_and_plan_segments_are_symbols(note):
    lang, paras = note
    steps = _steps(lang, paras)
    found = {t for _, texts, _, _ in steps for t in texts}
    assert {"p", "π", "pa", "πa", "pa_{4}", "ak_{1}", "πn_{1}", "FB", "x–x", "ω_{2}", "ω_{4}"} <= found
    rel = {"en": "V_{rel}", "ru": "V_{отн}", "uk": "V_{відн}"}.get(lang)  # zh says it in words
    assert rel is None or rel in found


def test_tangential_reactions_set_tau_as_an_index(note):
    lang, paras = note
    cells = []
    for _, _, _, p in paras:
        runs = [(r.findtext(f"{W}t") or "", (r.find(f"{W}rPr/{W}vertAlign").get(f"{W}val")
                                             if r.find(f"{W}rPr/{W}vertAlign") is not None else ""))
                for r in p if r.tag == f"{W}r"]
        cells.append(runs)
    assert [("R", ""), ("45", "subscript"), ("τ", "superscript")] in cells


def test_psi_max_is_set_with_its_index(tmp_path):
    pytest.importorskip("pypandoc")
    from velplan.note import build_note
    from velplan.note.markdown import para_parts
    from velplan.note.model import Math, Para

    note = build_note("four-bar", lang="ru")
    data = [b for b in note.blocks if isinstance(b, Para) and "ψmax" in "".join(map(str, b.parts))]
    assert data
    parts = para_parts(data[0], "ru")
    assert any(getattr(x, "tex", "") == r"\psi_{max}" for x in parts)
    assert any(getattr(x, "tex", "") == r"\theta" for x in parts)  # "θ = 1,564°" beside it
    assert not any(isinstance(x, str) and ("ψ" in x or "θ" in x) for x in parts)
    crank = [b for b in note.blocks if isinstance(b, Para) and "".join(map(str, b.parts)).startswith("ω₁ = ")]
    assert crank and para_parts(crank[0], "ru")[0] == Math(r"\omega_{1}")  # the crank's ω₁ of the data


def test_sentences_print_as_before_and_keep_their_symbols():
    line = T.phrase("line", "ru", T.pts("a"), T.phrase("parallel", "ru", T.pts("O3A")), T.vector("V_A4A"))
    assert line == "Через точку a проводим прямую ∥ O3A (направление V_A4A)."
    assert [x for x in line.parts if isinstance(x, T.Sym)] == [T.pts("a"), T.pts("O3A"), T.vector("V_A4A")]
    assert ("Шаг 3. " + line).parts[0] == "Шаг 3. Через точку "
    assert T.phrase("triad_centre", "en", T.pts("K3"), "3", T.vector("V_K3")) == \
        "Both lines pass through the pole: V_K3 = 0, K3 is the instant centre of velocities of link 3."


def test_plan_text_output_in_russian_reads_right():
    out = subprocess.run([sys.executable, "-m", "velplan", "plan", "shaper", "--position", "3", "--lang", "ru"],
                         capture_output=True, text=True, check=True).stdout
    # the names' digits as Unicode subscripts (as on the step figures), a vector's index after "_"
    assert "3. Через точку a проводим прямую ∥ O₃A (направление V_A4A)." in out
    assert "1. Выбираем полюс p; изображения неподвижных точек O₃, O₂ совпадают с полюсом." in out
    assert "bs₅ = 20,7 мм (bf · BS₅/BF = bf · 0,5)" in out
    assert "2. Из точки p откладываем отрезок pa = " in out and "⊥ O₂A в сторону ω₂ (V_A = 1,345 м/с)" in out
    assert "$" not in out and "{" not in out and "Sym(" not in out
