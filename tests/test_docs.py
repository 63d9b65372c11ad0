"""The documentation's examples run: the complete file of docs/format.md loads, is studied,
and its forces agree by the three methods."""

from pathlib import Path

import numpy as np

import velplan

DOCS = Path(__file__).resolve().parent.parent / "docs" / "format.md"


def _block(after: str, lang: str = "toml") -> str:
    text = DOCS.read_text("utf-8").split(after, 1)[1]
    return text.split(f"```{lang}", 1)[1].split("```", 1)[0]


def test_the_complete_example_file_works():
    mech = velplan.parse(_block("## A complete file"), name="my-slider")
    study = velplan.Study(mech)
    # an offset crank-slider: the stroke exceeds 2·r a little and K is above 1
    assert 2 * 0.08 < study.stroke.H < 2 * 0.08 * 1.01 and study.stroke.K > 1.0
    fa = study.forces()
    assert fa.max_relative_difference() < 1e-9
    # the working load does work: the mean balancing moment is positive (the crank drives)
    assert np.mean(fa.balancing_moments["kinetostatics"]) * np.sign(mech.crank.omega) > 0


def test_the_group_header_example_is_a_group():
    text = _block("Each group is a `[[group]]` table")
    assert text.strip().startswith("[[group]]") and 'kind = "RRR"' in text
