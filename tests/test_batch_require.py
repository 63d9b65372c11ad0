"""``velplan batch --random N --require …``: no variant that breaks a constraint is ever
emitted (over 1000 draws, each kept one checked by an independent computation), the draws
are counted, and the answer key records the figures of merit."""

import json
import math

import numpy as np
import pytest

from velplan import batch
from velplan.analysis.extremes import stroke
from velplan.analysis.solver import solve
from velplan.cli import main
from velplan.errors import VelplanError
from velplan.sweep.require import parse_require

REQUIRE = "K>=1.02, gamma_min>=48deg, H=55deg..65deg"


def _gamma_min_deg(mech) -> float:
    """The four-bar's smallest coupler–rocker transmission angle on a fine grid (deg)."""
    kin = solve(mech, np.linspace(0.0, 2 * np.pi, 20_001))
    mu = kin.angle("2") - kin.angle("3")
    return float(np.degrees(np.arcsin(np.abs(np.sin(mu)))).min())


def test_require_never_emits_a_variant_that_breaks_a_constraint():
    stats: dict = {}
    # 50 kept of about 390 drawn (about 340 rejected, a few not assembled): every one checked
    kept, failed = batch.random_variants("four-bar", 50, "TMM-2026 work 3", spread=0.1,
                                         require=parse_require(REQUIRE), stats=stats)
    assert stats["drawn"] >= 300 and stats["rejected"] >= 250 and stats["not_assembled"] > 0
    assert stats["drawn"] == stats["rejected"] + stats["not_assembled"] + len(kept) and not failed
    for v in kept:
        mech, _ = batch.build_variant(v)
        s = stroke(mech)
        assert s.K >= 1.02 - 1e-12
        assert 55.0 - 1e-9 <= math.degrees(s.H) <= 65.0 + 1e-9
        assert _gamma_min_deg(mech) >= 48.0 - 1e-6


def test_require_parse_errors_name_the_item():
    with pytest.raises(VelplanError, match="'Q>=1'"):
        parse_require("K>=1.4, Q>=1")
    with pytest.raises(VelplanError, match="range LO..HI"):
        parse_require("H=0.25")
    c = parse_require("H=250mm..0.35, gamma_min>40°")
    assert (c[0].lo, c[0].hi) == (0.25, 0.35) and c[1].strict and c[1].lo == 40.0


def test_batch_require_cli_records_figures(tmp_path, capsys):
    out = tmp_path / "course"
    assert main(["batch", "--random", "3", "--seed", "w", "--base", "four-bar", "--require", "K>=1.02",
                 "--no-sheets", "--jobs", "1", "--quiet", "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "--require:" in said and "rejected by the constraints" in said
    key = json.loads((out / "answers.json").read_text())
    assert key["require"] == "K>=1.02" and key["draws"]["drawn"] >= 3
    for a in key["variants"]:
        assert a["figures"]["K"] >= 1.02 and a["figures"]["K"] == pytest.approx(a["K"], rel=1e-10)


@pytest.mark.parametrize("argv, words", [
    (["table.csv", "--require", "K>=1"], "--require needs --random N"),
    (["--random", "2", "--seed", "s", "--base", "four-bar", "--require", "Q>1"], "--require 'Q>1': give NAME"),
])
def test_require_errors_are_one_line_and_make_no_directory(tmp_path, capsys, argv, words):
    out = tmp_path / "course"
    assert main(["batch", *argv, "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and not out.exists()
