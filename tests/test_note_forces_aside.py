"""The part on forces built by a fork while the kinematics are written
(`velplan.note.forces_aside`): the same blocks as built in one process, for the default
positions and for positions given; the part written here where the fork has none for the
positions the kinematic sheet draws, or fails."""

from __future__ import annotations

import pytest

from velplan.note import build_note, forces_aside, raster
from velplan.note.blocks import Figure

pytestmark = pytest.mark.skipif(not raster.FORK, reason="the fork is Linux's")


def _same(a, b) -> None:
    assert (a.figures, a.tables) == (b.figures, b.tables)
    assert len(a.blocks) == len(b.blocks)
    for x, y in zip(a.blocks, b.blocks):
        if isinstance(x, Figure):
            assert (x.caption, x.name, x.width_mm, x.svg, x.picture.dpi) == \
                (y.caption, y.name, y.width_mm, y.svg, y.picture.dpi)
        else:
            assert x == y


@pytest.fixture
def aside(monkeypatch):
    monkeypatch.setattr(raster, "core_free", lambda: True)
    parts = []
    real = forces_aside.ForcesAside.part

    def part(self, note, positions):
        parts.append(real(self, note, positions))
        return parts[-1]

    monkeypatch.setattr(forces_aside.ForcesAside, "part", part)
    return parts


@pytest.mark.parametrize("plans", [None, [3]])
def test_the_forks_part_is_the_same(aside, plans):
    alone = build_note("slider-press", n=6, lang="en", plans=plans, parts=["kinematics", "forces"])
    with forces_aside.building_aside():
        assert forces_aside.ENABLED
        made = build_note("slider-press", n=6, lang="en", plans=plans, parts=["kinematics", "forces"])
    assert not forces_aside.ENABLED
    assert aside == [True]
    _same(made, alone)
    assert made.figures > 4 and made.tables > 4


def test_other_positions_are_written_here(aside, monkeypatch):
    alone = build_note("slider-press", n=6, lang="en", parts=["kinematics", "forces"])
    monkeypatch.setattr("velplan.note.build._likely_positions", lambda study, plans: (1, 2))
    with forces_aside.building_aside():
        made = build_note("slider-press", n=6, lang="en", parts=["kinematics", "forces"])
    assert aside == [False]  # the fork built (1, 2); the sheet drew its own two
    _same(made, alone)


def test_a_fork_that_fails_leaves_the_part_here(aside, monkeypatch):
    alone = build_note("slider-press", n=6, lang="en", parts=["kinematics", "forces"])

    def broken(*args):
        raise RuntimeError("the fork fails")

    monkeypatch.setattr(forces_aside, "_serve", broken)  # what the fork runs
    with forces_aside.building_aside():
        made = build_note("slider-press", n=6, lang="en", parts=["kinematics", "forces"])
    assert aside == [False]
    _same(made, alone)


def test_no_fork_where_no_core_is_free(monkeypatch):
    monkeypatch.setattr(raster, "core_free", lambda: False)
    with forces_aside.building_aside():
        assert not forces_aside.ENABLED


def test_the_command_writes_the_same_docx_with_both_helpers(monkeypatch, tmp_path):
    import zipfile

    from velplan.cli import main
    from velplan.note import figures

    def document(name, free):
        monkeypatch.setattr(raster, "core_free", lambda: free)
        figures._MADE.clear()
        assert main(["note", "slider-press", "--positions", "6", "--lang", "uk", "-o", str(tmp_path / name)]) == 0
        z = zipfile.ZipFile(tmp_path / name)
        return {n: z.read(n) for n in z.namelist() if n != "docProps/core.xml"}

    seen = []
    real = forces_aside.ForcesAside.part
    monkeypatch.setattr(forces_aside.ForcesAside, "part", lambda self, note, positions:
                        seen.append(real(self, note, positions)) or seen[-1])
    assert document("aside.docx", True) == document("here.docx", False)
    assert seen == [True]  # the first built its part on forces in the fork, the second here
