"""Positions are numbered 1…n everywhere public (position 1 is the reference position), and
the sheets, the page, the note and the notebooks' drawings save files with one verb, ``save``.

The guards read the public modules: no public signature takes a 0-based position index, every
parameter that names positions says it numbers them from 1, and array indices become numbers
(and back) only through `velplan.analysis.numbering`.
"""

from __future__ import annotations

import ast
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.analysis.numbering import position_index, position_number
from velplan.errors import VelplanError
from velplan.plans.drafting import Drafting

PACKAGE = Path(velplan.__file__).resolve().parent
PUBLIC = ["study.py", "notebook.py", "html/page.py", "html/frames.py", "note/build.py",
          "note/kinematics.py", "note/forces.py", "views/plan.py", "views/steps.py",
          "views/readings.py", "views/mechanism.py", "views/centres.py", "views/table.py",
          "views/dynamics.py", "views/forces/group.py", "views/forces/polygon.py",
          "views/forces/lever.py", "plans/centres.py", "plans/engine.py"]
#: Parameter names that would hold a 0-based position index.
INDEX_NAMES = {"i", "index", "idx"}
#: Parameter names that hold position numbers (``positions`` annotated ``int`` is a count).
NUMBER_NAMES = {"position", "positions", "thick", "bold"}
SAYS_ONE_BASED = re.compile(r"1…n|1-based|numbered from 1|position numbers?|numbers? \(1")


def _public_functions(path: Path):
    """Public functions of the module and public methods of its public classes."""
    def public(nodes, kinds):
        return [n for n in nodes if isinstance(n, kinds) and not n.name.startswith("_")]

    body = ast.parse(path.read_text("utf-8")).body
    yield from public(body, ast.FunctionDef)
    for cls in public(body, ast.ClassDef):
        yield from public(cls.body, ast.FunctionDef)


@pytest.mark.parametrize("rel", PUBLIC)
def test_public_signatures_take_position_numbers(rel):
    for fn in _public_functions(PACKAGE / rel):
        args = fn.args.posonlyargs + fn.args.args + fn.args.kwonlyargs
        names = {a.arg for a in args}
        assert not names & INDEX_NAMES, f"{rel}:{fn.lineno} {fn.name} takes a position index"
        counts = {a.arg for a in args if isinstance(a.annotation, ast.Name) and a.annotation.id == "int"
                  and a.arg == "positions"}
        numbered = (names & NUMBER_NAMES) - counts
        if numbered:
            doc = ast.get_docstring(fn) or ""
            assert SAYS_ONE_BASED.search(doc), (
                f"{rel}:{fn.lineno} {fn.name}({', '.join(sorted(numbered))}) does not say that "
                "positions are numbered from 1")


@pytest.mark.parametrize("rel", PUBLIC)
def test_indices_and_numbers_convert_in_one_place(rel):
    """``number - 1`` and ``str(i + 1)`` belong to `velplan.analysis.numbering` alone."""
    text = (PACKAGE / rel).read_text("utf-8")
    found = re.findall(r"\b(?:position|positions|thick|number|number_k)\s*-\s*1\b|str\(\w+\s*\+\s*1\)", text)
    assert not found, f"{rel}: {found}"


@pytest.mark.parametrize("bad", [0, 13, -1])
def test_a_number_outside_1_to_n_is_one_line_naming_it(bad):
    with pytest.raises(VelplanError) as err:
        position_index(bad, 12)
    assert str(err.value) == f"position {bad} is outside 1…12 (positions are numbered from 1)"


def test_numbers_and_indices_round_trip():
    assert [position_index(position_number(i), 5) for i in range(5)] == list(range(5))
    assert position_index(np.int64(3), 5) == 2
    for bad in (2.0, True, "2"):
        with pytest.raises(VelplanError, match="is not a whole number 1…5"):
            position_index(bad, 5)


@pytest.fixture(scope="module")
def press():
    return velplan.Study("press")


def test_study_plan_takes_position_numbers(press):
    one = press.plan("velocity", positions=[3], drafting=Drafting(0.5, 0.5), scale_v=0.0007)
    assert one.index.tolist() == [2]
    assert np.isclose(one.kin.phi[one.index[0]], press.phi[2])
    both = press.plan("velocity", positions=[1, 12], only=["C"])
    assert both.index.tolist() == [0, 11]
    for bad in ([0], [13]):
        with pytest.raises(VelplanError, match=rf"^position {bad[0]} is outside 1…12 "):
            press.plan("velocity", positions=bad, only=["C"])
    for bad in ([2.5], [True], []):  # not a whole position number, or none at all
        with pytest.raises(VelplanError, match=r"^(position .* is not a whole number 1…12|no positions given)"):
            press.plan("velocity", positions=bad, only=["C"])


def test_require_assembled_takes_position_numbers(press):
    press.require_assembled([1, 12])
    press.require_assembled(12)
    with pytest.raises(VelplanError, match=r"^position 0 is outside 1…12 "):
        press.require_assembled([0])


def test_views_take_the_number_of_a_position_the_plan_holds(press):
    from velplan.views.plan import extent_mm, plan_view
    from velplan.views.readings import readings

    full, one = press.plan("velocity"), press.plan("velocity", positions=[5], only=["C"])
    assert full.index_of(5) == 4 and one.index_of(5) == 0
    view = plan_view(full, 5, lang="en")
    assert view.meta["number"] == 5 and view.name == "plan-v-5"
    assert extent_mm(full, 5) != extent_mm(full, 6)
    assert {p for p, *_ in readings(full, 5)} >= {"A", "C"}
    with pytest.raises(VelplanError, match=r"^position 4 is not in this plan \(its positions: 5\)$"):
        one.index_of(4)
    with pytest.raises(TypeError):        # the former keyword is gone: old calls fail loudly
        plan_view(full, 4, number=5)


# -- one verb for writing files --------------------------------------------------------------

def test_every_product_saves(tmp_path, press):
    from velplan.html.page import Page
    from velplan.note.model import Note
    from velplan.notebook import SvgDrawing
    from velplan.sheets.layout import SheetOutput

    for cls in (SheetOutput, Page, Note, SvgDrawing):
        assert callable(getattr(cls, "save")), cls
    assert not hasattr(Page, "write") and not hasattr(Note, "write") and not hasattr(SvgDrawing, "write")


def test_sheet_write_is_a_deprecated_save(tmp_path):
    sheet = velplan.sheet("crank-slider", kind="velocity", fmt="A3", lang="en")
    saved = sheet.save(tmp_path / "a.svg")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        written = sheet.write(tmp_path / "b.svg")
    assert [str(w.message) for w in caught if w.category is DeprecationWarning] == [
        "SheetOutput.write is deprecated; use SheetOutput.save"]
    assert written[0].read_bytes() == saved[0].read_bytes()
