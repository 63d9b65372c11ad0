"""The one notation layer (`velplan.notation`, issue 32): its tables checked against Unicode's
own decompositions, round trips, the minus and decimal signs, and that its former users (the
views, the drawings' text runs, the plans' sentences and table, the centres' table, the note)
print through it: no module keeps a table of its own, and their outputs are what they were."""

import re
import unicodedata
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

import velplan
from velplan import notation as N
from velplan.cli.centres import _cell
from velplan.note.cells import split_symbol
from velplan.note.formulas import chain, txt
from velplan.note.numbers import tidy
from velplan.plans.table import parse_quantity, quantity_name
from velplan.plans.text import Sentence, Sym, signed, terminal
from velplan.views.plan import plan_steps
from velplan.views.steps import readable, written

PACKAGE = Path(velplan.__file__).resolve().parent
LANGS = ("en", "ru", "uk", "zh")


def _decomposed(char: str) -> tuple[str, str]:
    """(kind, plain character) of a Unicode compatibility character: ("<sub>", "4") for "₄"."""
    kind, _, code = unicodedata.decomposition(char).partition(" ")
    return kind, chr(int(code, 16))


def test_every_subscript_and_superscript_digit_is_unicodes_own():
    for d, sub, sup in zip(N.DIGITS, N.SUBSCRIPT_DIGITS, N.SUPERSCRIPT_DIGITS, strict=True):
        assert _decomposed(sub) == ("<sub>", d)
        assert _decomposed(sup) == ("<super>", d)
        assert N.digits_down(d) == sub and N.plain_digits(sub) == d and N.superscript(d) == sup
    assert N.superscript("-") == N.superscript(N.MINUS) == "⁻" and N.superscript("+") == "⁺"
    assert unicodedata.normalize("NFKC", "⁻") == N.MINUS == "\u2212"


@given(st.text(alphabet="AaBbOπωK0123456789 ,.–", max_size=24))
def test_digits_down_and_back_is_the_identity(text):
    down = N.digits_down(text)
    assert not re.search(r"\d", down.translate({ord(c): None for c in N.SUBSCRIPT_DIGITS}))
    assert N.plain_digits(down) == text
    assert unicodedata.normalize("NFKC", down) == text  # Unicode's own reading agrees


@given(st.from_regex(r"[A-Za-zπ]{1,3}[0-9]{0,3}", fullmatch=True) | st.from_regex(r"[0-9]{1,3}", fullmatch=True))
def test_subscript_lowers_only_a_names_trailing_digits(name):
    out = N.subscript(name)
    assert N.plain_digits(out) == name
    head = name.rstrip(N.DIGITS)
    if head:
        assert out == head + N.digits_down(name[len(head):])
    else:  # a name of digits only (a link number) stays as written
        assert out == name


@given(st.lists(st.tuples(st.sampled_from("_^"), st.from_regex(r"[A-Za-z0-9]{1,4}|[−+][0-9]{1,2}", fullmatch=True),
                          st.text(alphabet="vaω= ", max_size=3)), max_size=4))
def test_marked_indices_read_as_unicode_and_as_plain_text_alike(pieces):
    text = "".join(f"{lead}{mark}{{{index}}}" for mark, index, lead in pieces)
    plain = N.plain_text(text)
    assert "{" not in plain and "}" not in plain
    # Unicode's compatibility reading of the sub- and superscripts is the plain text
    assert unicodedata.normalize("NFKC", N.unicode_text(text)) == plain


@given(st.floats(min_value=1e-3, max_value=1e6) | st.floats(min_value=-1e6, max_value=-1e-3),
       st.sampled_from(LANGS), st.integers(2, 6))
def test_a_number_reads_back_in_every_language(x, lang, digits):
    out = N.number(x, lang, digits)
    assert "-" not in out and "e" not in out
    assert out.startswith(N.MINUS) == (x < 0)
    assert ("." in out) == (lang not in ("ru", "uk") and "." in N.number(x, "en", digits))
    back = float(out.replace(",", ".").replace(N.MINUS, "-"))
    assert back == pytest.approx(x, rel=10.0 ** (1 - digits))
    assert N.number(-x, lang, digits) == (out[1:] if x < 0 else N.MINUS + out)


@given(st.floats(min_value=-1e-30, max_value=1e-30, allow_subnormal=False).filter(lambda v: v != 0) | st.floats(1e7, 1e30))
def test_a_power_of_ten_has_no_programmer_notation(x):
    out = N.number(x, "ru")
    m = re.fullmatch(r"(?:(?P<mantissa>−?[0-9]+(?:,[0-9]+)?)·|(?P<sign>−?))10(?P<power>[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)", out)
    assert m, out
    exponent = int(unicodedata.normalize("NFKC", m["power"]).replace(N.MINUS, "-"))
    value = float(m["mantissa"].replace(",", ".").replace(N.MINUS, "-")) if m["mantissa"] else (-1.0 if m["sign"] else 1.0)
    assert value * 10.0 ** exponent == pytest.approx(x, rel=1e-3)


def test_no_module_keeps_a_table_of_its_own():
    """The digit tables and the minus sign are written once, in `velplan.notation`."""
    copies = []
    for path in PACKAGE.rglob("*.py"):
        if path.name == "notation.py" or path.name.endswith("_widths.py"):
            continue  # (the fonts' width tables group characters by width: data, not notation)
        source = path.read_text("utf-8")
        for table in (N.SUBSCRIPT_DIGITS, N.SUPERSCRIPT_DIGITS, "maketrans(\"0123456789", "\"\\u2212\""):
            if table in source:
                copies.append(f"{path.relative_to(PACKAGE)}: {table}")
        copies += [f"{path.relative_to(PACKAGE)}: a hyphen made a minus"
                   for _ in re.finditer(r"""replace\(["']-["'], ["']−["']\)""", source)]
    assert copies == []


def test_the_views_and_the_drawings_name_the_notations_own_functions():
    from velplan.render import shapes
    from velplan.views import base
    for name in ("digits_down", "subscript", "number", "fixed", "power_of_ten", "indexed", "MINUS", "ROUND_OFF"):
        assert getattr(base, name) is getattr(N, name), name
    assert shapes.plain_text is N.plain_text and shapes.unicode_text is N.unicode_text


def test_former_users_print_as_before():
    assert signed(-2.5, "ru") == "−2,5" and signed(2.5, "en") == "+2.5"
    assert terminal(Sentence(["Through ", Sym("O3A"), " ∥ ", Sym("V_A4A", "vector")])) == "Through O₃A ∥ V_A4A"
    assert _cell(-1.11e-16, spec=".2e", lang="ru").strip() == "−1,11·10⁻¹⁶"
    assert _cell(-0.5, lang="en").strip() == "-0.5"  # the terminal's English table keeps the hyphen
    assert _cell(-0.5, lang="zh").strip() == "−0.5"
    assert tidy("-2e-12 и 0.123456", "ru") == "−2·10⁻¹² и 0,1235"
    assert split_symbol("R₀₄") == ("R", "04") and chain("O₃A") == "{O_{3}}{A}" and txt("-1,5") == r"\text{−1,5}"
    assert parse_quantity("vA₄/ω₂", ["V_A4", "w_3"], "2") == "V_A4" == parse_quantity(quantity_name("V_A4", "2"),
                                                                                       ["V_A4"], "2")


# -- the step figures set the symbols their sentences mark ----------------------------------------


def _sentences(name: str, position: int, lang: str):
    study = velplan.Study(name)
    return [d.sentence for kind in ("velocity", "acceleration")
            for d in plan_steps(study.plan(kind), position, lang=lang)]


@pytest.mark.parametrize("name", ["triad-press", "triad-rocker", "shaper"])
@pytest.mark.parametrize("lang", ["en", "ru"])
def test_every_vector_of_a_step_sentence_is_marked_and_set_from_its_mark(name, lang):
    vector = re.compile(r"(?<![A-Za-z0-9_])[VaR][ⁿᵗᵏʳ]?_[A-Za-zА-Яа-я0-9]+")
    for s in _sentences(name, 4, lang):
        assert isinstance(s, Sentence)
        plain = [x for x in s.parts if isinstance(x, str)]
        assert not any(vector.search(x) for x in plain), s  # no symbol left unmarked
        caption = readable(s)
        for sym in (x for x in s.parts if isinstance(x, Sym)):
            assert written(sym) in caption
            if sym.kind == "vector":
                head, _, index = sym.text.partition("_")
                assert written(sym) == ("v" + head[1:] if head[0] == "V" else head) + "_{" + index + "}"
            else:
                assert N.plain_digits(written(sym)) == sym.text
        assert caption == readable(str(s))  # the marks and the sentence's look agree


def test_a_triads_equations_are_vectors_side_by_side():
    (s,) = [x for x in _sentences("triad-press", 4, "en") if "V_C = " in x]
    vectors = [x.text for x in s.parts if isinstance(x, Sym) and x.kind == "vector"]
    assert vectors[:5] == ["V_C", "V_K3", "V_CK3", "V_E", "V_CE"]
    assert "v_{C} = v_{K3} + v_{CK3} = v_{E} + v_{CE}" in readable(s)


def test_the_page_names_the_cranks_rate_by_its_link():
    from velplan.html.page import page_html
    study = velplan.Study("shaper")
    assert study.mechanism.crank.link == "2"
    page = page_html(study, "en")
    assert f"· ω₂ = {N.number(abs(study.mechanism.crank.omega), 'en')} rad/s" in page and "ω₁" not in page


@pytest.mark.parametrize("name", ["shaper", "triad-rocker", "stephenson-six-bar"])
def test_a_centres_sentence_marks_its_centres_and_joints(name):
    for lang in ("en", "zh"):
        for s in velplan.Study(name).centres(4).describe(lang):
            assert isinstance(s, Sentence)
            plain = "".join(x for x in s.parts if isinstance(x, str))
            assert not re.search(r"(?<![A-Za-z])(P\d|[A-Z]\d)", plain), s  # every centre and joint is a symbol
            marks = [x.text for x in s.parts if isinstance(x, Sym)]
            assert marks and all(re.fullmatch(r"P[0-9,]+|[A-Z][0-9]*", m) for m in marks), marks
            assert readable(s) == readable(str(s))


def test_a_force_is_one_symbol_on_the_sheet_in_the_notes_tables_and_in_its_formulas():
    """R₁₂ with τ raised, M with Φ₄ below, a load Fc as F with c below: the sheet's marks
    (`force_text`), the note's TeX (`formulas.force`) and the note's cells (`split_symbol`)."""
    from velplan.note.cells import cell_markdown
    from velplan.note.formulas import force
    from velplan.views.forces import force_text

    cases = {"R12τ": ("R_{12}^{τ}", r"{R_{12}}^{\tau}", "R~12~^τ^"),
             "MΦ4": ("M_{Φ4}", r"M_{\Phi_{4}}", "M~Φ4~"),
             "Fc": ("F_{c}", "F_{c}", "F~c~"),
             "Fg5": ("F_{g5}", "F_{g5}", "F~g5~"),
             "G4": ("G₄", "G_{4}", "G~4~"),
             "R45n": ("R_{45}^{n}", r"{R_{45}}^{n}", "R~45~^n^"),
             "R23⊥": ("R_{23}^{⊥}", r"{R_{23}}^{\perp}", "R~23~^⊥^")}
    for name, (drawn, tex, cell) in cases.items():
        assert force_text(name) == drawn and force(name) == tex, name
        assert cell_markdown(N.unicode_text(drawn), str) == cell, name
