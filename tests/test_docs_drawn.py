"""The documentation's drawn-form and PMKS examples run: the drawn file decomposes into the
groups it shows and passes through its joints; the expression reads with its names."""

import math
from pathlib import Path

import pytest

import velplan
from velplan.mechanism import pmks
from velplan.mechanism.loader import from_dict

DOCS = Path(__file__).resolve().parent.parent / "docs" / "format.md"


def _block(after: str, lang: str) -> str:
    text = DOCS.read_text("utf-8").split(after, 1)[1]
    return text.split(f"```{lang}", 1)[1].split("```", 1)[0]


def test_the_drawn_example_decomposes_and_passes_through_its_joints():
    mech = velplan.parse(_block("## The drawn form", "toml"), name="doc")
    assert [(g.kind, g.links) for g in mech.groups] == [("RRR", ("2", "3")), ("RRP", ("4", "5"))]
    k = velplan.solve(mech, math.atan2(0.04, 0.03), order=0)
    for name, xy in {"C": (0.2, 0.15), "F": (0.5, 0.15), "G": (0.7, 0.1), "S3": (0.3, 0.1)}.items():
        assert tuple(k.positions[0, k.point_index[name]]) == pytest.approx(xy, abs=1e-15)


def test_the_pmks_example_reads_with_its_names():
    text = _block("## PMKS expressions", "pmks")
    mech = from_dict(pmks.drawn_data(text, pair=(0, 1), rpm=60), name="rocker")
    assert mech.crank.pivot == "O" and mech.crank.tip == "A" and [g.kind for g in mech.groups] == ["RRR"]
    assert mech.groups[0].lengths == pytest.approx((math.hypot(60.36, 35.44) / 1000, math.hypot(16.72, 67.97) / 1000))
