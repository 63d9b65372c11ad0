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
    "errors": 0, "io": 0, "xlsx": 0, "options": 0, "__version__": 0,
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
RENDER_MAY_IMPORT = {"errors", "io", "options", "render"}


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


def test_views_and_sheets_never_solve():
    """Views and sheets draw results: neither calls the solver nor constructs a plan."""
    for path in MODULES:
        if _part(_name(path)) in ("views", "sheets", "html", "cli", "notebook", "render"):
            text = path.read_text("utf-8")
            assert "import solve" not in text and ".evaluate(" not in text, _name(path)
