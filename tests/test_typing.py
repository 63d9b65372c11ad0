"""The typed surface: mypy finds nothing to report in the front door, the study and the entry
points of the sheets, the page and the note (the files of ``[tool.mypy]`` in pyproject.toml),
and the overloads of `velplan.sheet` give each kind its own sheet type."""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = ROOT / "pyproject.toml"


@pytest.fixture(scope="module")
def cache(tmp_path_factory) -> Path:
    """One mypy cache for the module: the second run reads velplan's modules from the first's."""
    return tmp_path_factory.mktemp("mypy-cache")


def _mypy(cache: Path, *args: str) -> tuple[str, int]:
    api = pytest.importorskip("mypy.api", reason="mypy is not installed (pip install '.[test]')")
    out, err, status = api.run(["--config-file", str(PYPROJECT), "--cache-dir", str(cache),
                                "--no-error-summary", *args])
    return out + err, status


def test_the_public_modules_are_clean(cache, monkeypatch):
    monkeypatch.chdir(ROOT)  # the configured files are relative to the checkout
    text, status = _mypy(cache)
    errors = [line for line in text.splitlines() if ": error:" in line]
    assert errors == [] and status == 0, "\n".join(errors or [text])


def test_the_overloads_tell_the_sheets_apart_and_refuse_a_wrong_option(cache, tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MYPYPATH", str(ROOT))  # this checkout's velplan, not an installed one
    use = tmp_path / "use.py"
    use.write_text(
        "import velplan\n"
        "reveal_type(velplan.sheet('shaper'))\n"
        "reveal_type(velplan.sheet('shaper', 'forces'))\n"
        "reveal_type(velplan.sheet('shaper', 'dynamics', fmt='A2'))\n"
        "velplan.sheet('shaper', 'dynamics', plans=[1])\n"
        "velplan.sheet('shaper', lang='fr')\n"
        "reveal_type(velplan.Study('shaper').forces())\n", "utf-8")
    text, status = _mypy(cache, str(use))
    lines = [line.split(": ", 1)[1] for line in text.splitlines() if line.startswith(str(use))]
    assert status == 1
    assert 'note: Revealed type is "velplan.sheets.kinematic.Sheet"' in lines
    assert 'note: Revealed type is "velplan.sheets.forces.ForceSheet"' in lines
    assert 'note: Revealed type is "velplan.sheets.dynamics.DynamicsSheet"' in lines
    assert 'note: Revealed type is "velplan.forces.agreement.ForceAnalysis"' in lines
    assert sum(line.startswith("error: No overload variant") for line in lines) == 2, lines
