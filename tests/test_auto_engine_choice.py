"""The "auto" engine's choice depends on what the process has solved, not on how long it took:
the same calls choose the same engine under any load, so what is printed does not change with it."""
import numpy as np
import pytest

import velplan
from velplan.analysis import solver


def test_the_numpy_time_is_modelled_not_measured(monkeypatch):
    monkeypatch.setattr(solver, "_NUMPY_SECONDS", [0.0])
    monkeypatch.setattr(solver, "_AUTO_ON", [False])
    monkeypatch.setattr(solver, "_auto_compiled", lambda n: False)  # numpy, loaded kernel or not
    mech = velplan.load("four-bar")
    phi = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
    spent = []
    for _ in range(3):
        before = solver._NUMPY_SECONDS[0]
        velplan.solve(mech, phi, engine="auto")
        spent.append(solver._NUMPY_SECONDS[0] - before)
    groups = len(solver.prepared(mech, None).items)
    call, angle = solver.NUMPY_COST
    assert spent == pytest.approx([call + angle * groups * 12] * 3, rel=1e-9)
