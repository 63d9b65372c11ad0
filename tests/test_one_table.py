"""One table of a study: the sheet's table, the batch's answer key and the note print the same
rows (V/ω1 of the same points, ω/ω1 of the same links)."""

import pytest

import velplan
from velplan import batch


@pytest.mark.parametrize("name", ["crank-slider", "four-bar", "jaw-crusher", "triad-rocker", "shaper"])
def test_the_answer_key_has_the_sheet_tables_rows(name):
    study = velplan.Study(name)
    key = batch._answers(batch.Variant("1", name), study)
    sheet = study.table.rows  # the sheet and the note read the study's table
    assert [f"V_{p}" for p in key["V"]] == [k for k in sheet if k.startswith("V_")]
    assert [f"w_{k}" for k in key["omega"]] == [k for k in sheet if k.startswith("w_")]
    assert list(study.table.rows) == list(sheet)
    assert study.table is study.table  # computed once


def test_centres_of_mass_and_construction_points_get_no_row():
    rows = velplan.Study("four-bar").table.rows
    assert "V_S2" not in rows and "V_S3" not in rows and "V_B" in rows
    assert "V_K3" not in velplan.Study("triad-rocker").table.rows  # Assur's special point
