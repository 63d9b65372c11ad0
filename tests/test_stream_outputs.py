"""Streamed output of ``velplan analyze --format json`` and of ``velplan forces`` and ``velplan
dynamics`` (json, csv, jsonl): the documents read back equal to those built whole in memory,
rows equal to the in-memory analyses, and no half-written file after a bad path or a failure."""

import csv
import io
import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.cli import dynamics as dyn_cli
from velplan.cli import forces as forces_cli
from velplan.cli import main
from velplan.cli.kinematics import stream, to_json
from velplan.mechanism.structure import coincident_points
from velplan.plans import EXACT, Drafting
from velplan.study import Study

DATA = Path(__file__).parent / "dynamics" / "data"
ROD_EQUALS_CRANK = (Path(__file__).parent / "test_never_silently_wrong.py").read_text("utf-8") \
    .split('ROD_EQUALS_CRANK = """')[1].split('"""')[0]


def _num(x):
    return float(x) if math.isfinite(x) else None


def whole_analysis_document(kin) -> dict:
    """The JSON document of ``velplan analyze`` as it was built before it streamed: one dict of
    every position, read back from ``json.dumps(indent=1)``."""
    doc = {"mechanism": kin.mechanism.name, "omega1": kin.omega1, "epsilon1": kin.epsilon1, "positions": []}
    special = {g.special_name for g in kin.mechanism.groups if g.kind == "triad"}
    marks = {k: {"kind": "special" if k in special else "coincident", "link": link}
             for k, link in coincident_points(kin.mechanism).items()}  # points not material: marked
    for i in range(len(kin)):
        ok = bool(kin.valid[i])
        rate = _num if ok else (lambda x: None)
        entry = {"position": i + 1, "phi_deg": float(kin.phi_deg[i]), "valid": ok,
                 "points": {k: dict(zip(("x", "y", "vx", "vy", "ax", "ay"),
                                        (*map(_num, kin.positions[i, j]), *map(rate, kin.velocities[i, j]),
                                         *map(rate, kin.accelerations[i, j]))), **marks.get(k, {}))
                            for k, j in kin.point_index.items()},
                 "links": {k: {"angle": _num(kin.angles[i, j]), "omega": rate(kin.omegas[i, j]),
                               "epsilon": rate(kin.epsilons[i, j])} for k, j in kin.link_index.items()},
                 "slides": {k: dict(zip(("s", "v", "a"), (_num(kin.slides[i, j, 0]), *map(rate, kin.slides[i, j, 1:]))))
                            for k, j in kin.slide_index.items()},
                 "condition": {k: _num(kin.condition[i, j]) for k, j in kin.group_index.items()}}
        if not ok:
            entry["reason"] = (f"singular: a group at a toggle (condition {kin.min_condition()[i]:.2g}), "
                               "velocities undetermined" if kin.singular[i] else "not assembled")
        doc["positions"].append(entry)
    return json.loads(json.dumps(doc, indent=1))


def same(a, b) -> bool:
    """Equal documents: the same keys in the same order, the same values of the same types."""
    if isinstance(a, dict):
        return list(a) == list(b) and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    return type(a) is type(b) and a == b


def agree(a, b) -> bool:
    """`same`, but numbers computed again (in other chunks) need only agree to round-off."""
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-12)
    if isinstance(a, dict):
        return list(a) == list(b) and all(agree(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(agree(x, y) for x, y in zip(a, b))
    return type(a) is type(b) and a == b


def _streamed(pieces) -> str:
    return b"".join(pieces).decode("utf-8")


@pytest.fixture
def cs(tmp_path):
    path = tmp_path / "cs.toml"
    path.write_text(ROD_EQUALS_CRANK)
    return path


@pytest.mark.parametrize("name", ["shaper", "press", "triad-rocker"])
def test_analyze_json_reads_back_as_the_whole_document(name):
    study = Study(name, n=25)
    expected = whole_analysis_document(study.kinematics)
    assert same(json.loads(to_json(study.kinematics)), expected)  # the very numbers, written exactly
    assert agree(json.loads(_streamed(stream(study, "json", chunk=4))), expected)


def test_analyze_json_of_positions_not_assembled_or_singular(cs):
    mech = velplan.load("four-bar")
    g = mech.groups[0]  # a coupler too short to close over part of the turn
    short = replace(mech, groups=(replace(g, lengths=(0.6 * g.lengths[0], g.lengths[1])),) + mech.groups[1:])
    toggle = Study(cs, angles=np.radians([45.0, 90.0, 180.0]))
    for study in (Study(short, angles=np.radians(np.arange(0.0, 360.0, 7.5)), check_assembly=False), toggle):
        doc = json.loads(_streamed(stream(study, "json", chunk=5)))
        assert agree(doc, whole_analysis_document(study.kinematics))
        bad = [p for p in doc["positions"] if not p["valid"]]
        assert bad and all("reason" in p and p["points"]["B"]["vx"] is None for p in bad)
    assert doc["positions"][1]["reason"].startswith("singular")
    # JSON lines hold the same objects (numbers to 12 digits)
    lines = [json.loads(t) for t in _streamed(stream(toggle, "jsonl", chunk=2)).splitlines()]
    assert [p.get("reason") for p in lines] == [p.get("reason") for p in doc["positions"]]
    assert lines[1]["points"]["B"]["vx"] is None and lines[0]["points"]["B"]["vx"] == pytest.approx(
        doc["positions"][0]["points"]["B"]["vx"], rel=1e-11)


def test_analyze_json_cli_writes_the_document(tmp_path):
    out = tmp_path / "a.json"
    assert main(["analyze", "shaper", "--positions", "5", "--format", "json", "-o", str(out)]) == 0
    assert agree(json.loads(out.read_text("utf-8")), whole_analysis_document(Study("shaper", n=5).kinematics))


# ---- velplan forces ------------------------------------------------------------------------

OPTIONS = {"drafting": EXACT, "mu_v": None, "gravity": True, "inertia": True}


def _close(a, b, scale):
    """``a`` equals ``b`` to round-off, relative to ``scale`` (both None where not finite)."""
    if a is None or b is None or not math.isfinite(b):
        return a is None and (b is None or not math.isfinite(b))
    return abs(a - b) <= 1e-11 * scale


@pytest.mark.parametrize("chunk", [16384, 5])
@pytest.mark.parametrize("fmt", ["json", "jsonl", "csv"])
def test_forces_rows_are_the_in_memory_analysis(fmt, chunk):
    study = Study("shaper", n=12)
    res = study.forces()
    text = _streamed(forces_cli.stream(study, fmt, list(range(1, 13)), chunk=chunk, **OPTIONS))
    if fmt == "json":
        rows = json.loads(text)["positions"]
    elif fmt == "jsonl":
        rows = [json.loads(t) for t in text.splitlines()]
    else:
        rows = list(csv.DictReader(io.StringIO(text)))
        assert "reactions.O3.magnitude" in rows[0]
    bm = res.balancing_moments
    scale = max(float(np.max(np.abs(v))) for v in bm.values())
    force = max(float(np.max(np.abs(r.force))) for r in res.kinetostatics.reactions.values())
    assert [int(p["position"]) for p in rows] == list(range(1, 13))
    for i, p in enumerate(rows):
        get = (lambda k: p[k]) if fmt != "csv" else (lambda k: float(p[k]) if p[k] else None)
        sub = (lambda k, q: p[k][q]) if fmt != "csv" else (lambda k, q: get(f"{k}.{q}"))
        assert _close(get("phi_deg"), math.degrees(study.phi[i]) % 360.0, 360.0)
        for method, values in bm.items():
            assert _close(sub("balancing_moment", method), values[i], scale)
        for name, r in res.kinetostatics.reactions.items():
            for q, value in (("x", r.force[i].real), ("y", r.force[i].imag), ("magnitude", abs(r.force[i]))):
                got = p["reactions"][name][q] if fmt != "csv" else get(f"reactions.{name}.{q}")
                assert _close(got, value, force)


def test_forces_json_reads_back_as_the_whole_document():
    """One chunk: the very numbers of the analysis of all positions at once."""
    study = Study("press", n=7)
    res = study.forces()
    doc = json.loads(_streamed(forces_cli.stream(study, "json", list(range(1, 8)), **OPTIONS)))
    assert doc["mechanism"] == "press" and doc["omega1"] == study.mechanism.crank.omega
    from velplan.forces.agreement import lever_difference_percent

    pct = lever_difference_percent(res.balancing_moments["lever"], res.balancing_moments["kinetostatics"])
    r = res.kinetostatics.reactions["C"]
    for i, p in enumerate(doc["positions"]):
        assert agree(p["balancing_moment"], {k: float(v[i]) for k, v in res.balancing_moments.items()})
        assert agree(p["lever_difference_percent"], _num(pct[i]))
        assert agree(p["balancing_force"], float(res.lever.balancing_force[i]))
        assert agree(p["reactions"]["C"]["magnitude"], float(abs(r.force[i])))


def test_forces_one_position_and_a_drafted_plan_in_chunks():
    """The plan's scale is that of all positions, whichever positions are written."""
    study = Study("shaper", n=12)
    drafted = {**OPTIONS, "drafting": Drafting(0.5, 0.5)}
    whole = study.forces(drafting=drafted["drafting"])
    doc = json.loads(_streamed(forces_cli.stream(study, "json", [4], **drafted)))
    assert [p["position"] for p in doc["positions"]] == [4]
    assert doc["positions"][0]["balancing_moment"]["lever"] == pytest.approx(whole.balancing_moments["lever"][3],
                                                                             rel=1e-12)
    rows = [json.loads(t) for t in _streamed(forces_cli.stream(study, "jsonl", list(range(1, 13)), chunk=5,
                                                               **drafted)).splitlines()]
    lever = whole.balancing_moments["lever"]
    assert [p["balancing_moment"]["lever"] for p in rows] == pytest.approx(lever, rel=1e-11)


def test_forces_computed_motion_streams_its_omega(tmp_path):
    study = Study(DATA / "slider-dyn.toml", n=12, motion="dynamic")
    doc = json.loads(_streamed(forces_cli.stream(study, "json", list(range(1, 13)), chunk=5, **OPTIONS)))
    w = study.kinematics.crank_rate("omega")
    assert doc["omega1"] == pytest.approx(w.tolist(), rel=1e-14)
    assert [p["omega1"] for p in doc["positions"]] == pytest.approx(w.tolist(), rel=1e-14)


# ---- velplan dynamics ----------------------------------------------------------------------

@pytest.mark.parametrize("fmt", ["json", "jsonl", "csv"])
def test_dynamics_rows_are_the_table(fmt):
    from velplan.dynamics.report import to_dict

    d = Study(DATA / "slider-dyn.toml", delta=0.05).dynamics
    text = _streamed(dyn_cli.stream(d, fmt, 30, chunk=7))
    table = d.table(30)
    if fmt == "json":
        doc = json.loads(text)
        whole = json.loads(json.dumps(to_dict(d, 30), indent=1))
        assert agree(doc, whole)
        return
    rows = [json.loads(t) for t in text.splitlines()] if fmt == "jsonl" else list(csv.DictReader(io.StringIO(text)))
    assert len(rows) == 30 and [int(p["position"]) for p in rows] == list(range(1, 31))
    for key, values in table.items():
        got = [float(p[key]) for p in rows]
        assert got == pytest.approx(values.tolist(), rel=1e-11, abs=1e-11 * float(np.max(np.abs(values))))


def test_dynamics_run_rows_have_both_ends(tmp_path):
    from velplan.dynamics.report import to_dict

    src = (Path(velplan.__file__).parent / "examples" / "slider-press.toml").read_text("utf-8")
    path = tmp_path / "run.toml"
    path.write_text(src + '\n[dynamics]\n[[dynamics.inertia]]\nname = "flywheel"\ninertia = 40.0\nratio = 1.0\n'
                    '[dynamics.motor]\nkind = "kloss"\ncritical_torque = 120.0\nsynchronous_rpm = 1500.0\n'
                    'critical_rpm = 1200.0\nratio = 24.0\nefficiency = 0.9\n'
                    '[dynamics.run]\nomega = 6.2\ntravel_deg = 360.0\n')
    d = Study(path).dynamics
    doc = json.loads(_streamed(dyn_cli.stream(d, "json", 10, chunk=4)))
    assert doc["mode"] == "run" and len(doc["positions"]) == 11
    assert agree(doc, json.loads(json.dumps(to_dict(d, 10), indent=1)))


# ---- no half-written file ------------------------------------------------------------------

@pytest.mark.parametrize("argv", [["forces", "shaper", "--format", "csv"],
                                  ["dynamics", str(DATA / "slider-dyn.toml"), "--format", "jsonl"],
                                  ["analyze", "shaper", "--format", "json"]])
def test_a_bad_output_path_is_refused_in_one_line(argv, tmp_path, capsys):
    target = tmp_path / "missing" / "out.txt"
    assert main(argv + ["-o", str(target)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "missing" in err and "Traceback" not in err
    assert not target.parent.exists() and list(tmp_path.iterdir()) == []


def test_a_failure_mid_stream_leaves_no_file(tmp_path, monkeypatch, capsys):
    """The second chunk fails: neither the output nor its temporary file remains."""
    original = Study.forces_in_chunks

    def failing(self, *args, **kwargs):
        for k, item in enumerate(original(self, *args, **kwargs)):
            if k == 1:
                raise velplan.errors.VelplanError("interrupted mid-stream")
            yield item

    monkeypatch.setattr(Study, "forces_in_chunks", failing)
    monkeypatch.setattr(forces_cli, "CHUNK", 4)
    target = tmp_path / "f.jsonl"
    assert main(["forces", "shaper", "--format", "jsonl", "-o", str(target)]) == 2
    assert "interrupted mid-stream" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    assert main(["forces", "shaper", "--format", "jsonl", "-o", str(target)]) == 0
    assert [json.loads(t)["position"] for t in target.read_text("utf-8").splitlines()] == list(range(1, 13))
