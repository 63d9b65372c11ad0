"""What a teacher reads in the note: prose in the course's notation (no underscore, no plain
digit for an index, no English word in a ru/zh note), Zhukovsky's lever as a moment equation
with one term and one arm per force, the dynamics worked at a position and tabulated by
position, an introduction, a conclusion and references, and "from the extreme position" only
where position 1 is one. Each note is built once per module."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

pytest.importorskip("pypandoc")
docx = pytest.importorskip("docx")

from tests import shared_notes  # noqa: E402
from tests.note_prose import ascii_subscripts, latin_words, prose  # noqa: E402

from velplan.note import build_note, write_note  # noqa: E402
from velplan.note.blocks import Equation, Heading, Para, Table  # noqa: E402
from velplan.note.text import p  # noqa: E402
from velplan.study import Study  # noqa: E402


def _value(text: str) -> float:
    return float(text.replace("−", "-").replace(",", ".").replace(" ", ""))


@pytest.fixture(scope="module")
def notes(tmp_path_factory):
    """The shaper in ru (every part), the V compressor in zh, the triad press in en."""
    out = tmp_path_factory.mktemp("note-content")
    result = {"ru": shared_notes.shaper_ru(tmp_path_factory)}  # shared with two files
    for name, lang, delta in (("v-compressor", "zh", None), ("triad-press", "en", None)):
        study = Study(name, delta=delta)
        note = build_note(study, lang=lang)
        result[lang] = (study, note, write_note(note, out / f"{name}-{lang}.docx"))
    return result


def test_prose_has_no_programmer_notation(notes):
    for lang, (_, _, path) in notes.items():
        body = docx.Document(str(path)).element.body
        found = [(style, w) for style, text in prose(body) if style != "Compact" for w in ascii_subscripts(text)]
        assert not found, f"{lang}: {found[:10]}"


def test_no_english_words_in_ru_and_zh_notes(notes):
    for lang in ("ru", "zh"):
        body = docx.Document(str(notes[lang][2])).element.body
        found = [(style, w) for style, text in prose(body) for w in latin_words(text, lang)]
        assert not found, f"{lang}: {found[:10]}"


def _lever_sections(note):
    """(position, table, equations) of each lever section of the note."""
    out, blocks = [], note.blocks
    for k, b in enumerate(blocks):
        if isinstance(b, Table) and b.key.startswith("lever-"):
            eqs = [x.tex for x in blocks[k + 1:k + 8] if isinstance(x, Equation)]
            out.append((int(b.key.split("-")[1]), b, eqs))
    return out


def test_zhukovsky_lever_has_one_term_per_force_with_its_arm(notes):
    study, note, _ = notes["ru"]
    sections = _lever_sections(note)
    assert len(sections) == 2
    lever_mb = study.forces().balancing_moments["lever"]
    crank = study.mechanism.crank
    for k, table, eqs in sections:
        symbols, numbers, fb = eqs[:3]
        rows = table.rows
        assert r"\sum M_{p}" in symbols and symbols.count("h_{") == len(rows) + 1
        for n in range(1, len(rows) + 1):
            assert f"h_{{{n}}}" in symbols
        # the equation in numbers: every F·h of the table, with its sign; it balances F_b·h_b
        terms = re.findall(r"([+-]?) ?\\text\{([^}]*)\}\\cdot\\text\{([^}]*)\}", numbers)
        assert len(terms) == len(rows)
        for (sign, f, h), row in zip(terms, rows):
            assert (f, h) == (row[1], row[2])
        total = sum((-1 if s == "-" else 1) * _value(f) * _value(h) for s, f, h in terms)
        h_b = _value(re.search(r"\\cdot\\text\{([^}]*)\}", numbers).group(1))
        f_b = _value(re.search(r"= \\text\{([^}]*)\}\\ \\text\{Н\}$", fb).group(1))
        assert abs(abs(total) - f_b * h_b) <= 0.01 * abs(total) + 0.05 * f_b
        # M_b = F_b·l_OA is the study's M_b by the lever
        kin = study.kinematics
        i = k - 1
        l_oa = float(np.hypot(*(kin.positions[i, kin.point_index[crank.tip]]
                                - kin.positions[i, kin.point_index[crank.pivot]])))
        assert abs(f_b * l_oa - abs(float(lever_mb[i]))) <= 1e-3 * abs(float(lever_mb[i])) + 0.05


def test_dynamics_worked_position_and_tables(notes):
    study, note, _ = notes["ru"]
    tables = {b.key: b for b in note.blocks if isinstance(b, Table)}
    reduced, works = tables["dynamics-reduced"], tables["dynamics-works"]
    assert len(reduced.rows) == len(works.rows) == study.n
    # J_II at position 2, term by term, equals Σ(m·V_S² + J_S·ω²)/ω² from the velocity plan
    worked = next(b.tex for b in note.blocks if isinstance(b, Equation) and b.tex.startswith("J_{II} = \\text"))
    printed = _value(re.findall(r"\\text\{([^}]*)\}", worked)[-2])
    res = study.plan("velocity")
    mech = study.mechanism
    w1 = abs(float(res.omegas[mech.crank.link][1]))
    from velplan.forces.inertia import inertia_of

    exact = 0.0
    for m in mech.masses:
        if m.link == mech.crank.link:
            continue
        v = float(np.hypot(*res.vector(m.centre)[1]))
        w = float(res.omegas[m.link][1]) if m.link in res.omegas else 0.0
        exact += (m.mass * v * v + inertia_of(mech, m) * w * w) / w1 ** 2
    assert abs(printed - exact) <= 5e-4 * exact
    assert abs(_value(reduced.rows[1][2]) - exact) <= 5e-4 * exact
    # ΔT_I = ΔT − ΔT_II in every row, to the printed digits
    for row in works.rows:
        dt, dt2, dt1 = (_value(x) for x in row[3:6])
        assert abs(dt1 - (dt - dt2)) <= 1e-3 * max(1.0, abs(dt), abs(dt2)) + 0.06
    # A_d grows by M_d·Δθ from position to position
    md = _value(reduced.rows[0][4])
    ad = [_value(r[1]) for r in works.rows]
    assert np.allclose(np.diff(ad), md * 2 * math.pi / study.n, rtol=2e-3)


def test_introduction_conclusion_references(notes):
    for lang, (study, note, _) in notes.items():
        heads = [b for b in note.blocks if isinstance(b, Heading) and b.level == 1]
        assert heads[0].text == p("sec_intro", lang) and not heads[0].numbered
        assert [h.text for h in heads[-2:]] == [p("sec_conclusion", lang), p("sec_references", lang)]
        refs = note.blocks[note.blocks.index(heads[-1]) + 1:]
        assert len(refs) >= 3 and all(isinstance(r, Para) for r in refs)
    study, note, _ = notes["ru"]
    concl = note.blocks[note.blocks.index(next(b for b in note.blocks if getattr(b, "text", "") == "Заключение")):]
    tex = " ".join(x.tex for b in concl if isinstance(b, Para) for x in b.parts if hasattr(x, "tex"))
    assert "H = " in tex and "K = " in tex and "J_{I}" in tex and r"\le M_{" in tex
    assert any("Артоболевский" in x for b in concl if isinstance(b, Para) for x in b.parts if isinstance(x, str))


def test_extreme_position_only_where_position_1_is_one(tmp_path):
    """The shaper starts at an extreme of its ram; the same linkage without ``output`` starts
    at φ = 0, and its note says so."""
    from pathlib import Path

    from velplan.note.kinematics import _starts_at_extreme

    assert _starts_at_extreme(Study("shaper"))
    source = Path(__file__).resolve().parent.parent / "velplan" / "examples" / "shaper.toml"
    toml = tmp_path / "six-link.toml"
    toml.write_text("\n".join(x for x in source.read_text(encoding="utf-8").splitlines()
                               if not x.startswith("output =")), encoding="utf-8")
    study = Study(str(toml))
    assert study.stroke is None and not _starts_at_extreme(study)
    note = build_note(study, lang="ru", parts=("kinematics",))
    text = " ".join(x for b in note.blocks if isinstance(b, Para) for x in b.parts if isinstance(x, str))
    assert "от крайнего положения" not in text and "от φ = 0" in text


def test_flywheel_on_the_motor_shaft_where_the_ratio_is_known(notes):
    """The shaper gives no drive: the note chooses the motor by the default rules, says so,
    and puts the flywheel on its shaft with J/u², recommended there."""
    from velplan.dynamics.drive import select_drive

    study, note, _ = notes["ru"]
    drive = select_drive(study.dynamics)
    fly = study.dynamics.flywheel
    shaft = next(b.tex for b in note.blocks if isinstance(b, Equation) and r"}' = \frac" in b.tex)
    printed = [_value(x) for x in re.findall(r"\\text\{([−\d,. ]+)\}", shaft)]
    assert printed[0] == pytest.approx(fly.added, rel=5e-4) and printed[1] == pytest.approx(drive.ratio, rel=5e-4)
    assert printed[2] == pytest.approx(fly.added / drive.ratio ** 2, rel=5e-4)
    text = " ".join(x for b in note.blocks if isinstance(b, Para) for x in b.parts if isinstance(x, str))
    assert "Привод в задании не указан" in text and "быстроходный вал" in text
    assert drive.ratio > 5  # a motor's shaft turns much faster than a shaper's crank
