"""The one-way flow of the architecture: no module imports a layer above its own.

model → analysis → plans → forces → dynamics → study → views → sheets → cli, with render
(primitives and backends) below the views and above nothing of the domain.
"""

import ast
from pathlib import Path

import pytest

import velplan

PACKAGE = Path(velplan.__file__).resolve().parent

#: Layer of each top-level part of the package, lowest first. Imports may go down or sideways.
LAYERS = {
    "errors": 0, "io": 0, "xlsx": 0, "options": 0, "notation": 0, "__version__": 0,
    "mechanism": 1, "examples": 1,
    "analysis": 2,
    "plans": 3,
    "forces": 4,
    "dynamics": 5,
    "study": 6,
    "render": 6,
    "views": 7,
    "sheets": 8, "html": 8,
    "notebook": 9, "cli": 9, "batch": 9, "catalogue": 9, "sweep": 9, "note": 9,
    "__init__": 10, "__main__": 10, "drawings": 10,
}
#: The drawing layers may not reach into the domain below the results they draw.
RENDER_MAY_IMPORT = {"errors", "io", "options", "notation", "render"}


def _part(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _imports(path: Path) -> list[tuple[str, int]]:
    """velplan modules imported anywhere in ``path`` (top level or inside functions)."""
    tree = ast.parse(path.read_text("utf-8"))
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            if node.module == "velplan":
                out += [(f"velplan.{a.name}", node.lineno) for a in node.names]
            elif node.module.startswith("velplan."):
                out.append((node.module, node.lineno))
        elif isinstance(node, ast.Import):
            out += [(a.name, node.lineno) for a in node.names if a.name.startswith("velplan.")]
    return out


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))


def _name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    return ".".join(rel.parts)


def test_every_part_has_a_layer():
    parts = {_part(_name(p)) for p in MODULES}
    assert parts <= set(LAYERS), parts - set(LAYERS)


@pytest.mark.parametrize("path", MODULES, ids=_name)
def test_no_module_imports_a_layer_above_its_own(path):
    here = _part(_name(path))
    for module, line in _imports(path):
        there = _part(module)
        assert there in LAYERS, f"{_name(path)}:{line} imports unknown part {module}"
        assert LAYERS[there] <= LAYERS[here], (
            f"{_name(path)}:{line} ({here}, layer {LAYERS[here]}) imports {module} "
            f"({there}, layer {LAYERS[there]})")
        if here == "render":
            assert there in RENDER_MAY_IMPORT, f"{_name(path)}:{line}: render imports {module}"


def test_the_check_sees_a_violation(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from velplan.sheets.kinematic import build_sheet\n", "utf-8")
    assert _imports(bad) == [("velplan.sheets.kinematic", 2)]
    assert LAYERS[_part("velplan.sheets.kinematic")] > LAYERS["analysis"]


#: What the drawing parts import but never call: the solver and its engines, the constructions
#: of plans, centres, tables, diagrams, curves and force analyses. They read these results off
#: a `velplan.Study`.
COMPUTES = (
    "velplan.analysis.solver.solve", "velplan.analysis.blocks", "velplan.analysis.compiled",
    "velplan.analysis.chord.kinematic_diagrams", "velplan.plans.centres.construct_centres",
    "velplan.plans.table.transfer_table", "velplan.forces.curve.moment_curve",
    "velplan.forces.curve.turn_mean", "velplan.forces.agreement.force_analysis",
)
#: The parts that draw (and the products that only print what a study computed).
DRAWING_PARTS = ("views", "sheets", "html", "note", "render")


def _resolved(source: str, module: str) -> list[tuple[str, int]]:
    """Every velplan name imported by ``source`` (the text of module ``module``), resolved to
    its defining module: ``from velplan.analysis.solver import Kinematics, solve`` gives
    ``velplan.analysis.solver.Kinematics`` and ``velplan.analysis.solver.solve``; a relative
    import is resolved against ``module``; a lazy front-door name to where it lives."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = module.split(".")[:-node.level]
                base = ".".join(parent + ([base] if base else []))
            for a in node.names:
                if base == "velplan" and a.name in velplan._LAZY:
                    where, attr = velplan._LAZY[a.name]
                    out.append((f"{where}.{attr}", node.lineno))
                elif base == "velplan" or base.startswith("velplan."):
                    out.append((f"{base}.{a.name}", node.lineno))
        elif isinstance(node, ast.Import):
            out += [(a.name, node.lineno) for a in node.names if a.name.startswith("velplan")]
    return out


def _computing(source: str, module: str) -> list[str]:
    """The computing imports and calls of a drawing module: ``module:line name``."""
    found = [f"{module}:{line} imports {name}" for name, line in _resolved(source, module)
             if any(name == c or name.startswith(c + ".") for c in COMPUTES)]
    if ".evaluate(" in source:
        found.append(f"{module} constructs a plan (.evaluate)")
    return found


def test_the_resolver_sees_a_solver_among_other_names():
    source = "from velplan.analysis.solver import Kinematics, solve\n"
    assert _resolved(source, "velplan.views.x") == [
        ("velplan.analysis.solver.Kinematics", 1), ("velplan.analysis.solver.solve", 1)]
    assert _computing(source, "velplan.views.x") == ["velplan.views.x:1 imports velplan.analysis.solver.solve"]
    assert _computing("def f():\n    from ..analysis.solver import Kinematics, solve\n", "velplan.views.x")
    assert _computing("from velplan import solve as s\n", "velplan.sheets.x")
    assert _computing("import velplan.analysis.blocks\n", "velplan.sheets.x")
    assert _computing("from velplan.plans.centres import construct_centres\n", "velplan.html.x")
    assert not _computing("from velplan.analysis.solver import Kinematics\n", "velplan.views.x")
    assert not _computing("from velplan.plans.table import TransferTable  # solve\n", "velplan.views.x")


@pytest.mark.parametrize("path", [p for p in MODULES if _part(_name(p)) in DRAWING_PARTS], ids=_name)
def test_views_sheets_page_and_note_never_compute(path):
    """They draw the results of a `velplan.Study`: no solver, no construction of a plan, of
    instant centres, of a table or of a curve."""
    assert _computing(path.read_text("utf-8"), _name(path)) == []


def test_the_cli_and_the_notebook_never_solve():
    for path in MODULES:
        if _part(_name(path)) in ("cli", "notebook"):
            source = path.read_text("utf-8")
            solver = [n for n, _ in _resolved(source, _name(path)) if n == "velplan.analysis.solver.solve"]
            assert not solver and ".evaluate(" not in source, _name(path)
