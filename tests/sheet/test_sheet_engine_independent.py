"""A sheet does not depend on which engine solved its mechanism: the numpy and the compiled
engines agree to round-off, and the drawing must not turn on that round-off (the triads'
special point lies on both of its lead lines to the last bits, and their drawing order once
flipped with the engine)."""

import pytest

import velplan
from velplan.sheets.kinematic import build_sheet

pytest.importorskip("numba")


@pytest.mark.parametrize("name", ["triad-press", "triad-rocker"])
def test_the_kinematic_sheet_is_the_same_from_either_engine(name):
    by_numpy = build_sheet(velplan.Study(name, engine="numpy"), lang="ru", fmt="A3").svg()
    by_kernel = build_sheet(velplan.Study(name, engine="compiled"), lang="ru", fmt="A3").svg()
    assert by_numpy == by_kernel


def test_the_force_sheet_is_the_same_from_either_engine():
    """The crank's polygon of two opposite vectors (R₀₁ = −R₂₁) is set beside itself on one
    side, not on the side the round-off of its centre falls."""
    from velplan.sheets.forces import build_force_sheet

    by_numpy = build_force_sheet(velplan.Study("triad-press", engine="numpy"), lang="ru", fmt="A3").svg()
    by_kernel = build_force_sheet(velplan.Study("triad-press", engine="compiled"), lang="ru", fmt="A3").svg()
    assert by_numpy == by_kernel
