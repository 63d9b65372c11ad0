"""The public surface: the product at the top of the package, one name per concept, former
names deprecated for one release, one definition of the turning sense, the standard positions
and the option types, and a mechanism that is a hashable value."""

import ast
import re
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import velplan

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "velplan"


def test_import_velplan_stays_light():
    code = ("import sys, velplan; heavy = [m for m in ('velplan.study', 'velplan.sheets', 'velplan.html', "
            "'velplan.note', 'velplan.plans.engine', 'velplan.forces', 'velplan.dynamics') if m in sys.modules]; "
            "print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_the_product_is_at_the_top():
    from velplan.html.page import Page
    from velplan.note.build import build_note
    from velplan.study import Study

    assert velplan.Study is Study and velplan.Page is Page and velplan.explanatory_note is build_note
    assert {"Study", "Page", "sheet", "explanatory_note", "structure", "parse"} <= set(velplan.__all__)
    assert {"Study", "Page", "explanatory_note"} <= set(dir(velplan))


def test_sheet_dispatches_on_kind():
    sheet = velplan.sheet("crank-slider", kind="velocity", fmt="A3", lang="en")
    assert type(sheet).__name__ == "Sheet" and sheet.svg().startswith("<?xml")
    with pytest.raises(velplan.VelplanError, match="unknown sheet kind 'plans'; known kinds: velocity, "):
        velplan.sheet("crank-slider", kind="plans")


@pytest.mark.parametrize("old, new, call", [
    ("velplan.analyse", "velplan.structure", lambda: velplan.analyse(velplan.load("four-bar"))),
    ("velplan.loads", "velplan.parse", lambda: velplan.loads(velplan.load.__doc__ and _FOUR_BAR)),
    ("velplan.mechanism.structure.analyse", "velplan.mechanism.structure.structure",
     lambda: __import__("velplan.mechanism.structure", fromlist=["x"]).analyse(velplan.load("four-bar"))),
    ("velplan.forces.analyse_forces", "velplan.forces.agreement.force_analysis_at",
     lambda: __import__("velplan.forces", fromlist=["x"]).analyse_forces(velplan.load("shaper"), [0.5])),
    ("velplan.dynamics.analyse", "velplan.dynamics.analysis.dynamics_analysis",
     lambda: __import__("velplan.dynamics", fromlist=["x"]).analyse(velplan.load("shaper"), delta=0.05)),
])
def test_former_names_warn_naming_the_new_one(old, new, call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert call() is not None
    messages = [str(w.message) for w in caught if w.category is DeprecationWarning]
    assert messages and messages[0] == f"{old} is deprecated; use {new}"


_FOUR_BAR = (ROOT / "velplan" / "examples" / "four-bar.toml").read_text("utf-8")


def test_a_mechanism_is_a_hashable_value():
    a, b = velplan.load("shaper"), velplan.parse((PACKAGE / "examples" / "shaper.toml").read_text("utf-8"),
                                                 name="shaper")
    assert a == b and hash(a) == hash(b)
    c = velplan.load("compressor")  # [[load]] tables and a [dynamics] section
    assert c.dynamics is not None and c.loads and hash(c) == hash(velplan.load("compressor"))
    with pytest.raises(TypeError):
        c.loads[0]["kind"] = "force"  # frozen
    assert velplan.stroke(a) is velplan.stroke(b)  # cached by value


def _code_lines(pattern: str):
    rx = re.compile(pattern)
    for path in sorted(PACKAGE.rglob("*.py")):
        for n, line in enumerate(path.read_text("utf-8").splitlines(), 1):
            if rx.search(line.split("#")[0]):
                yield f"{path.relative_to(ROOT)}:{n}"


# views/mechanism.py is being reworked with the sheets; it reads crank.sense after that
_ELSEWHERE = {"velplan/views/mechanism.py"}


def test_the_turning_sense_is_defined_once():
    found = [h for h in _code_lines(r"omega1?(\[[^\]]*\])?\s*(>=|<|>|<=)\s*0\b|sign\([^)]*omega")
             if h.split(":")[0] not in _ELSEWHERE]
    assert all(h.startswith("velplan/mechanism/model.py") for h in found), found


def test_the_standard_positions_are_defined_once():
    """Position 1 and the n standard positions: `reference_angle` and `positions` (the sweep's
    vectorised stroke reads reference_deg only to break the tie of K = 1, as `stroke` does)."""
    found = list(_code_lines(r"math\.radians\([a-z.]*reference_deg\)"))
    assert {h.split(":")[0] for h in found} <= {"velplan/analysis/extremes.py", "velplan/sweep/merit.py"}, found
    again = [h for h in _code_lines(r"reference\w*(\(mech\))? \+ .*sense \* np\.arange")
             if not h.startswith("velplan/analysis/extremes.py")]
    assert again == [], "the standard positions spelled out again"
    study = velplan.Study("shaper")
    assert study.reference == velplan.reference_angle(study.mechanism)
    assert np.array_equal(study.phi, velplan.positions(study.mechanism, 12))


def test_option_types_are_defined_once():
    """No module but velplan.options spells out a Literal of plan kinds or languages."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.name == "options.py":
            continue
        for node in ast.walk(ast.parse(path.read_text("utf-8"))):
            if isinstance(node, ast.Subscript) and getattr(node.value, "id", "") == "Literal":
                values = {getattr(e, "value", None) for e in getattr(node.slice, "elts", [node.slice])}
                if values == {"velocity", "acceleration"} or {"en", "ru"} <= values:
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    # sheets/kinematic.py is being reworked with the sheets; it takes SheetKind after that
    assert [h for h in found if not h.startswith("velplan/sheets/kinematic.py")] == []


def test_py_typed_ships():
    assert (PACKAGE / "py.typed").is_file()
    assert '"velplan" = ["py.typed"]' in (ROOT / "pyproject.toml").read_text("utf-8")


def test_the_readme_python_example_runs(tmp_path, monkeypatch):
    pytest.importorskip("pypandoc")
    text = (ROOT / "README.md").read_text("utf-8")
    (block,) = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    names = {n.attr for n in ast.walk(ast.parse(block))
             if isinstance(n, ast.Attribute) and getattr(n.value, "id", "") == "velplan"}
    assert names <= set(velplan.__all__), names - set(velplan.__all__)  # top-level names only
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my-mechanism.toml").write_text(_FOUR_BAR, "utf-8")
    exec(compile(block, "README.md", "exec"), {})
    assert {"shaper-sheet.svg", "shaper.html", "note.docx"} <= {p.name for p in tmp_path.iterdir()}


def test_the_readme_test_command_prints_the_summary_and_runs_the_doctests():
    import tomllib

    text = (ROOT / "README.md").read_text("utf-8")
    command = re.search(r"<!-- test-command -->\n```bash\n(.*?)\n```", text, flags=re.S).group(1)
    ini = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["tool"]["pytest"]["ini_options"]
    words = command.split("pytest", 1)[1].split() + ini["addopts"].split()
    quiet = sum(w.count("q") for w in words if re.fullmatch(r"-q+", w)) + words.count("--quiet")
    assert quiet <= 1, words  # -qq hides the summary line
    assert "--doctest-modules" in words and "velplan" in ini["testpaths"]
