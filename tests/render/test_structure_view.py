"""The structural analysis drawn (`velplan info --svg`): one panel per group after the initial
mechanism, each outer pair ringed, the class and order under each group, in the language
asked; the command writes the file and refuses what it cannot write in one line."""

from __future__ import annotations

import pytest

import velplan
from velplan.cli import main
from velplan.cli.convert import pose
from velplan.mechanism.drawn_write import drawn_tables
from velplan.mechanism.loader import catalogue_names, example_names
from velplan.render.scene import Circle, Text
from velplan.views.structure import structure_view


def _scene(name: str, lang: str = "en"):
    mech = velplan.load(name)
    return mech, structure_view(mech, drawn_tables(mech, *pose(mech))["joint"], lang=lang)


@pytest.mark.parametrize("name", example_names() + catalogue_names())
def test_every_group_is_drawn_apart_with_its_outer_pairs_ringed(name):
    mech, scene = _scene(name)
    rings = [p for p in scene if isinstance(p, Circle) and p.line == "hidden"]
    # a dyad has two outer pairs, a triad three; one more ring is the legend's
    assert len(rings) == sum(3 if g.kind == "triad" else 2 for g in mech.groups) + 1
    texts = [p.text for p in scene if isinstance(p, Text)]
    assert sum(t.startswith("Group of class") for t in texts) == len(mech.groups)
    assert texts.count("Initial mechanism, class I") == 1
    assert any(t.startswith("W = ") and "Formula of structure: I(0, " in t for t in texts)


def test_the_triad_is_written_as_a_group_of_class_three_in_the_language_asked():
    _, scene = _scene("triad-rocker", "ru")
    texts = [p.text for p in scene if isinstance(p, Text)]
    assert "Группа III класса, 3 порядка" in texts and "триада: 3, 2, 4, 5" in texts
    assert {"A", "E", "F", "B", "C", "D"} <= set(texts)


@pytest.mark.parametrize("name", ["shaper", "triad-rocker"])
def test_no_two_letters_overlap(name):
    _, scene = _scene(name)
    boxes = [p.bounds for p in scene if isinstance(p, Text)]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)


def test_info_writes_the_figure(tmp_path, capsys):
    out = tmp_path / "structure.svg"
    assert main(["info", "shaper", "--svg", str(out), "--lang", "uk"]) == 0
    text = out.read_text("utf-8")
    assert "Група II класу, 2 порядку" in text and "ОПО: 3, 4" in text
    assert f"wrote {out}" in capsys.readouterr().out


def test_info_refuses_a_figure_it_cannot_write(tmp_path, capsys):
    assert main(["info", "shaper", "--svg", str(tmp_path / "x.gif")]) == 2
    err = capsys.readouterr().err
    assert err == f"velplan: error: --svg {tmp_path / 'x.gif'}: write a .svg, .png or .pdf file\n"


def test_the_notes_structural_section_shows_the_figure():
    from velplan.note.front import _structure_figure

    class Note:
        lang, figures = "ru", []

        def figure(self, caption, picture, width_mm):
            self.figures.append((caption, picture, width_mm))

    note = Note()
    _structure_figure(note, velplan.load("whitworth"))
    ((caption, picture, width),) = note.figures
    assert caption == "Структурный анализ механизма" and 0 < width <= 170.0
    assert picture.svg.startswith("<?xml") and picture.png().startswith(b"\x89PNG")
