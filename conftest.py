"""Collection of the package's doctests (``--doctest-modules`` over ``velplan/``): modules that
run code when imported, or that import an optional dependency the test extra does not
install, are left out."""

from importlib.util import find_spec

# `pytest -n … --dist loadfile`: files sharing a cached fixture go to one worker (tests/scheduling.py)
pytest_plugins = ["tests.scheduling"]

collect_ignore = ["velplan/__main__.py", "setup.py"]
if find_spec("numba") is None:  # the compiled kernels (the [fast] extra)
    collect_ignore.append("velplan/cli/_numfmt_kernels.py")
