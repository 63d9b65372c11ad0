"""A mechanism prepared once for solving (`velplan.analysis.prepared`) and the default engine's
choice (`velplan.analysis.solver._auto_compiled`): the same results, whichever engine and however
often a mechanism is solved."""

import numpy as np
import pytest

import velplan
from velplan.analysis import compiled, solver
from velplan.analysis.kinematics import length_scale
from velplan.analysis.prepared import prepared
from velplan.mechanism.structure import schedule


def test_a_mechanism_is_prepared_once_by_object_and_by_content():
    mech = velplan.load("shaper")
    prep = prepared(mech)
    assert prepared(mech) is prep
    assert prepared(velplan.load("shaper")) is prep  # an equal mechanism loaded again
    assert prepared(mech, ["F"]) is not prep and prepared(mech, ["F"]) is prepared(mech, ("F",))
    assert prep.shift == complex(*dict(mech.ground)[mech.crank.pivot])
    assert dict(prep.local.ground)[mech.crank.pivot] == (0.0, 0.0)
    assert prep.items == schedule(prep.local) and prep.items[0] is prep.local.crank
    assert prep.scale == length_scale(mech) == 0.370  # the span O3–O2, longer than every rod


def test_repeated_solves_give_equal_independent_results():
    """The preparation is shared; the results are not: writing into one leaves the next alone."""
    mech = velplan.load("shaper")
    phi = np.linspace(0, 2 * np.pi, 13)
    a = velplan.solve(mech, phi, engine="numpy")
    a.positions[:] = 0.0
    b, c = velplan.solve(mech, phi, engine="numpy"), velplan.solve(mech, phi, engine="numpy")
    np.testing.assert_array_equal(b.positions, c.positions)
    assert np.abs(b.positions).max() > 0.1
    O3 = b.point_index["O3"]
    np.testing.assert_array_equal(b.positions[:, O3], 0.0)  # the ground point, shifted back exactly
    np.testing.assert_allclose(b.position("O2"), np.tile([0.0, 0.370], (13, 1)), rtol=0, atol=0)


def test_numpy_and_compiled_agree_at_the_course_sizes():
    pytest.importorskip("numba")
    for name in ("four-bar", "shaper", "crank-slider"):
        mech = velplan.load(name)
        for n in (1, 12, 72):
            phi = np.arange(n) * (2 * np.pi / n) + 0.1
            a, b = velplan.solve(mech, phi, engine="numpy"), velplan.solve(mech, phi, engine="compiled")
            assert a.point_index == b.point_index and a.link_index == b.link_index
            np.testing.assert_array_equal(a.valid, b.valid)
            for x, y in ((a.positions, b.positions), (a.velocities, b.velocities),
                         (a.accelerations, b.accelerations), (a.angles, b.angles)):
                np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-12 * np.abs(x).max())


def test_the_default_engine_loads_the_kernel_once_the_numpy_engine_has_cost_as_much(monkeypatch):
    """Ski rental: the numpy engine until its time in this process reaches what loading the
    compiled kernel costs, then the kernel for every later call."""
    if not compiled.available():
        pytest.skip("numba is not installed")
    mech = velplan.load("four-bar")
    phi = np.linspace(0, 1, 12)
    calls = []
    real = solver._solve_compiled
    monkeypatch.setattr(solver, "_solve_compiled", lambda *a: calls.append(len(a[1])) or real(*a))
    monkeypatch.setattr(solver, "_AUTO_ON", [False])
    monkeypatch.setattr(solver, "_NUMPY_SECONDS", [0.0])
    monkeypatch.setattr(compiled, "loaded", lambda: False)
    monkeypatch.setitem(solver.LOAD_AT_LEAST, "kernel", 0.0)  # the least it may cost
    monkeypatch.setitem(solver.LOAD_AT_LEAST, "numba", 0.0)
    monkeypatch.setattr(compiled, "load_cost", lambda: 1e9)  # never worth it: numpy throughout
    for _ in range(3):
        velplan.solve(mech, phi)
    assert calls == [] and solver._NUMPY_SECONDS[0] > 0
    monkeypatch.setattr(compiled, "load_cost", lambda: solver._NUMPY_SECONDS[0])  # paid for now
    velplan.solve(mech, phi)
    monkeypatch.setattr(compiled, "load_cost", lambda: 1e9)  # once chosen, kept
    kin = velplan.solve(mech, phi)
    assert calls == [12, 12] and kin.valid.all()


def test_the_load_cost_follows_what_is_there_to_load(monkeypatch):
    if not compiled.available():
        pytest.skip("numba is not installed")
    monkeypatch.setattr(compiled, "loaded", lambda: False)
    monkeypatch.setattr(compiled, "_on_disk", lambda: False)
    assert compiled.load_cost() == compiled.LOAD_SECONDS["compile"]
    monkeypatch.setattr(compiled, "_on_disk", lambda: True)
    monkeypatch.setitem(__import__("sys").modules, "numba", __import__("sys").modules.get("numba", object()))
    assert compiled.load_cost() == compiled.LOAD_SECONDS["kernel"]
    monkeypatch.delitem(__import__("sys").modules, "numba")
    assert compiled.load_cost() == compiled.LOAD_SECONDS["numba"]
    monkeypatch.setattr(compiled, "loaded", lambda: True)
    assert compiled.load_cost() == 0.0


def test_a_class_iii_group_is_tracked_once_per_mechanism(monkeypatch):
    from velplan.analysis import triad

    mech = velplan.load("triad-rocker")
    prep = prepared(mech)
    found = prep.tracks(velplan.solve)
    monkeypatch.setattr(triad, "track", lambda *a: pytest.fail("tracked again"))
    assert prep.tracks(velplan.solve) is found
    kin = velplan.solve(mech, np.linspace(0, 2 * np.pi, 12, endpoint=False))
    assert kin.valid.sum() >= 10


def test_the_least_load_cost_is_the_compiled_engines():
    assert solver.LOAD_AT_LEAST == {k: compiled.LOAD_SECONDS[k] for k in ("kernel", "numba")}


def test_the_default_engine_stays_numpy_when_numba_runs_uncompiled(monkeypatch):
    monkeypatch.setenv("NUMBA_DISABLE_JIT", "1")
    monkeypatch.setattr(solver, "_AUTO_ON", [False])
    monkeypatch.setattr(solver, "_NUMPY_SECONDS", [1e9])
    assert not solver._auto_compiled(10**7)


def test_outputs_take_a_value_given_once_for_a_whole_block():
    from velplan.analysis.blocks import _fill

    target = np.zeros((2, 2, 5))
    _fill(target, [[np.arange(5.0), 1.5], [2.0, np.ones(5)]], slice(0, 5))
    np.testing.assert_array_equal(target[0, 0], np.arange(5.0))
    assert (target[0, 1] == 1.5).all() and (target[1, 0] == 2.0).all() and (target[1, 1] == 1.0).all()
    _fill(target, [[np.full(2, 7.0)] * 2] * 2, slice(3, 5))
    assert (target[:, :, 3:] == 7.0).all() and target[0, 0, 2] == 2.0


def test_the_output_layout_is_decided_once_and_results_name_the_same_rows():
    mech = velplan.load("four-bar")
    phi = np.linspace(0, 2 * np.pi, 7)
    a = velplan.solve(mech, phi, engine="numpy")
    prep = prepared(mech)
    assert prep.outputs is not None and prep.outputs["point_index"] is a.point_index
    b = velplan.solve(mech, phi[:3], engine="numpy", order=0)
    assert b.point_index is a.point_index and b.velocities is None
    np.testing.assert_array_equal(b.positions, a.positions[:3])
    assert a.link_origins == {"1": "O", "2": "A", "3": "D"}


def test_time_on_a_class_iii_group_counts_towards_loading_the_kernel(monkeypatch):
    """The compiled engine covers a triad: the numpy engine's time on one counts as on any other."""
    monkeypatch.setattr(solver, "_AUTO_ON", [False])
    monkeypatch.setattr(solver, "_NUMPY_SECONDS", [0.0])
    mech = velplan.load("triad-rocker")
    velplan.solve(mech, np.linspace(0, 1, 12))
    assert (solver._NUMPY_SECONDS[0] > 0.0 or solver._AUTO_ON[0]) and prepared(mech).class_iii




def test_a_mechanism_at_its_pivot_is_not_kept_alive_by_the_cache():
    """A crank pivot at the origin makes `about_pivot` return the mechanism itself: the cache
    must still let each variant be collected (it held every one of them)."""
    import dataclasses
    import gc

    from velplan.analysis import prepared as P

    m = velplan.load("crank-slider")
    assert m.crank.pivot in dict(m.ground) and dict(m.ground)[m.crank.pivot] == (0.0, 0.0)
    before = len(P._BY_ID)
    for k in range(20):
        v = dataclasses.replace(m, crank=dataclasses.replace(m.crank, length=m.crank.length * (1 + 1e-3 * k)))
        velplan.solve(v, np.linspace(0.0, 6.0, 12))
        del v
    gc.collect()
    assert len(P._BY_ID) <= before
