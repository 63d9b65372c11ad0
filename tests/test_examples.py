"""Every public name has a runnable example: each name in ``velplan.__all__`` and in each
subpackage's ``__all__`` appears in a doctest example (not skipped) of its own docstring or of
its package's docstring. The examples themselves run with the suite (``--doctest-modules``)."""

import doctest
import importlib
import inspect
import re
from pathlib import Path

import pytest

import velplan

_ROOT = Path(velplan.__file__).resolve().parent
#: The front door and every subpackage that declares ``__all__``.
PACKAGES = sorted(".".join(("velplan",) + init.parent.relative_to(_ROOT).parts)
                  for init in _ROOT.rglob("__init__.py") if "\n__all__" in init.read_text("utf-8"))
_SKIP = doctest.OPTIONFLAGS_BY_NAME["SKIP"]


def _sources(obj, name: str) -> list[str]:
    """The sources of the running (not skipped) examples of ``obj``'s docstrings (a class's
    methods included)."""
    try:
        tests = doctest.DocTestFinder(recurse=inspect.isclass(obj) or inspect.ismodule(obj)).find(obj, name)
    except (TypeError, ValueError):  # a constant or a typing alias: no docstring of its own
        return []
    return [ex.source for t in tests for ex in t.examples if not ex.options.get(_SKIP)]


def _used(name: str, sources: list[str]) -> bool:
    return any(re.search(rf"(?<![\w]){re.escape(name)}(?![\w])", s) for s in sources)


def missing(package: str) -> list[str]:
    """The names of ``package.__all__`` that no running example uses."""
    module = importlib.import_module(package)
    here = _sources(module, package)
    out = []
    for name in module.__all__:
        obj = getattr(module, name)
        if not (_used(name, here) or _used(name, _sources(obj, name))):
            out.append(name)
    return out


@pytest.mark.parametrize("package", PACKAGES)
def test_every_public_name_has_a_running_example(package):
    assert missing(package) == []


def test_the_packages_are_found():
    assert {"velplan", "velplan.forces", "velplan.views.forces", "velplan.render"} <= set(PACKAGES)


def test_the_check_sees_a_name_without_an_example():
    assert not _used("solve", [">>> solved = 1\n"]) and _used("solve", [">>> solve(m)\n"])
    assert _sources(1.5, "x") == []
