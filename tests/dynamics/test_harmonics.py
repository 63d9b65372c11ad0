"""Seed 004: the press load by its Fourier series of N harmonics against the exact parabola,
in the machine's motion (same flywheel): the differences shrink with N and the series' RMS
error is Parseval's."""

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.dynamics.harmonics import compare_harmonics
from velplan.forces.loads import PressLoad


@pytest.fixture(scope="module")
def comparison():
    study = velplan.Study("slider-press")
    return study, compare_harmonics(study.mechanism, study.loads, [1, 5, 20, 80], delta=0.05)


def test_differences_shrink_with_the_harmonics(comparison):
    _, (ref, rows) = comparison
    dw = [r.omega_max_diff for r in rows]
    assert all(a > b for a, b in zip(dw, dw[1:])), dw
    assert dw[-1] < 0.05 * dw[0]
    assert abs(rows[-1].delta - ref.steady.delta) < 0.002  # the same flywheel: δ close to the required 0.05
    assert ref.steady.delta == pytest.approx(0.05, abs=1e-9)
    # the driving moment converges to the exact one (it is the load's work over the turn)
    assert abs(rows[-1].driving - ref.driving) < 1e-3 * abs(ref.driving)


def test_rms_is_parseval(comparison):
    study, (_, rows) = comparison
    (press,) = [ld for ld in study.loads if isinstance(ld, PressLoad)]
    phi = np.linspace(0.0, 2 * np.pi, 400001)[:-1]
    for row in rows[:3]:
        series = press.fourier(row.harmonics)
        rms = float(np.sqrt(np.mean((series(phi) - press.exact(phi)) ** 2)))
        assert row.load_rms == pytest.approx(rms, rel=1e-3)


def test_cli(capsys):
    assert main(["dynamics", "slider-press", "--delta", "0.05", "--harmonics", "2,10"]) == 0
    out = capsys.readouterr().out
    assert "exact parabola" in out and len(out.strip().splitlines()) == 4
    assert main(["dynamics", "shaper", "--harmonics", "3", "--delta", "0.1"]) == 2
    assert capsys.readouterr().err.strip() == 'velplan: error: --harmonics: shaper has no press load ([[load]] kind = "press")'
    assert main(["dynamics", "slider-press", "--delta", "0.05", "--harmonics", "0"]) == 2
    assert "whole numbers ≥ 1" in capsys.readouterr().err
