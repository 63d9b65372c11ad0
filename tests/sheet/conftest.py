"""Sheets shared by the tests of this directory: built once per session (about 1 s each)."""

import pytest

import velplan
from velplan.sheets.drawings import OPTIONS
from velplan.sheets.kinematic import build_sheet

from tests.sheet.helpers import record_all


@pytest.fixture(scope="session")
def sheets():
    """Every bundled example's sheet, as `python -m velplan.sheets.drawings` draws it."""
    return {name: build_sheet(name, **OPTIONS) for name in velplan.example_names()}


@pytest.fixture(scope="session")
def recorded(sheets):
    """Each sheet drawn on a recording canvas: name → canvas."""
    return record_all(sheets)
