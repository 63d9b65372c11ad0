"""Parquet written as it is computed (``velplan analyze|forces|dynamics --format parquet``: the
CSV's columns, a row group per chunk) and the streamed sweep (``velplan sweep --format
csv|jsonl|parquet``: the rows of the sweep computed whole, written a chunk of variants at a time)."""

import csv
import io
import json
import sys

import numpy as np
import pytest

import velplan
from velplan.cli import dynamics as dyn_cli
from velplan.cli import forces as forces_cli
from velplan.cli import kinematics as kin_cli
from velplan.cli import main
from velplan.mechanism.loader import load
from velplan.sweep import report, run

pq = pytest.importorskip("pyarrow.parquet")

COMMANDS = {"analyze": (["analyze", "four-bar", "--positions", "50"], kin_cli, "STREAM_CHUNK", 16, 4),
            "forces": (["forces", "shaper", "--positions", "30"], forces_cli, "CHUNK", 8, 4),
            "dynamics": (["dynamics", "triad-rocker", "--positions", "40"], dyn_cli, "CHUNK", 16, 3)}


def read_csv(path) -> tuple[list[str], np.ndarray]:
    """The header and the (n, C) numbers of a CSV file (NaN in empty cells)."""
    rows = list(csv.reader(io.StringIO(path.read_text("utf-8"))))
    cells = [[float(x) if x not in ("", "true", "false") else
              {"": np.nan, "true": 1.0, "false": 0.0}[x] for x in row] for row in rows[1:]]
    return rows[0], np.array(cells)


@pytest.mark.parametrize("command", list(COMMANDS))
def test_parquet_holds_the_csv_columns_one_row_group_per_chunk(command, tmp_path, monkeypatch):
    argv, module, name, chunk, groups = COMMANDS[command]
    monkeypatch.setattr(module, name, chunk)
    assert main(argv + ["--format", "csv", "-o", str(tmp_path / "a.csv")]) == 0
    assert main(argv + ["--format", "parquet", "-o", str(tmp_path / "a.parquet")]) == 0
    head, values = read_csv(tmp_path / "a.csv")
    file = pq.ParquetFile(tmp_path / "a.parquet")
    assert file.metadata.num_row_groups == groups
    table = file.read()
    assert table.column_names == head and table.num_rows == len(values)
    for c, column in enumerate(table.columns):
        got = np.array(column.to_pylist(), dtype=float)  # null → NaN, as an empty CSV cell
        if column.type == "double":
            np.testing.assert_allclose(got, values[:, c], rtol=1e-11, atol=0, equal_nan=True, err_msg=head[c])
        else:  # whole numbers and booleans, exactly
            np.testing.assert_array_equal(got, values[:, c], err_msg=head[c])
    assert table.column("position").to_pylist() == list(range(1, len(values) + 1))


def test_parquet_numbers_are_the_analysis_float64_exactly(tmp_path):
    """Not rounded as the CSV is: the analysis's own float64, null where not assembled."""
    assert main(["analyze", "four-bar", "--positions", "24", "--format", "parquet", "-o", str(tmp_path / "k.pq")]) == 0
    kin = velplan.Study("four-bar", n=24).kinematics
    head, cols = kin_cli._columns(kin)
    table = pq.read_table(tmp_path / "k.pq")
    assert all(t == "double" for t in table.schema.types[1:]) and table.schema.types[0] == "int64"
    for name, col in zip(head[1:], cols[1:]):
        np.testing.assert_allclose(table.column(name).to_numpy(), col, rtol=1e-14, atol=1e-14, err_msg=name)


@pytest.mark.parametrize("argv", [["analyze", "four-bar"], ["forces", "shaper"], ["dynamics", "triad-rocker"],
                                  ["sweep", "four-bar", "--vary", "crank.length=0.09:0.11:3"]])
def test_parquet_to_standard_output_is_refused_in_one_line(argv, capsys):
    assert main(argv + ["--format", "parquet"]) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "--format parquet is binary: give -o FILE" in captured.err
    assert captured.out == ""


@pytest.mark.parametrize("argv", [["analyze", "four-bar"], ["dynamics", "triad-rocker"],
                                  ["sweep", "four-bar", "--vary", "crank.length=0.09:0.11:3"]])
def test_parquet_without_pyarrow_is_one_line_naming_the_extra(argv, tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow raises ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    assert main(argv + ["--format", "parquet", "-o", str(tmp_path / "x.parquet")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and 'pip install ".[parquet]"' in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_a_failure_mid_parquet_leaves_no_file(tmp_path, monkeypatch, capsys):
    original = kin_cli.chunks

    def failing(*args, **kwargs):
        for k, item in enumerate(original(*args, **kwargs)):
            if k == 1:
                raise velplan.errors.VelplanError("interrupted mid-stream")
            yield item

    monkeypatch.setattr(kin_cli, "chunks", failing)
    monkeypatch.setattr(kin_cli, "STREAM_CHUNK", 8)
    assert main(["analyze", "four-bar", "--positions", "30", "--format", "parquet", "-o", str(tmp_path / "k.pq")]) == 2
    assert "interrupted mid-stream" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


# ---- the streamed sweep ---------------------------------------------------------------------

MC = ["sweep", "four-bar", "--tolerance", "0.2mm,0.1°", "--samples", "40", "--positions", "72", "--seed", "7"]


def _whole() -> report.SweepResult:
    """The same Monte Carlo as `MC`, computed whole by `run_sweep`."""
    mech = load("four-bar")
    values = run.monte_carlo(mech, run.tolerances(mech, 0.2e-3, 0.1), 40, "7")
    return run.run_sweep(mech, values, mode="monte-carlo", positions=72)


def test_streamed_sweep_rows_equal_the_whole_sweep(tmp_path, monkeypatch):
    monkeypatch.setitem(run.CHUNK, "numpy", 16)  # three chunks of variants
    for fmt in ("csv", "jsonl", "parquet"):
        assert main(MC + ["--format", fmt, "-o", str(tmp_path / f"s.{fmt}"), "--quiet"]) == 0
    res = _whole()
    whole = io.StringIO()
    report.write_csv(res, whole)
    assert (tmp_path / "s.csv").read_text("utf-8") == whole.getvalue()
    columns = report._columns(res)
    lines = [json.loads(t) for t in (tmp_path / "s.jsonl").read_text("utf-8").splitlines()]
    assert len(lines) == 40 and list(lines[0]) == list(columns)
    file = pq.ParquetFile(tmp_path / "s.parquet")
    assert file.metadata.num_row_groups == 3
    table = file.read()
    for name, col in columns.items():
        from_lines = [row[name] for row in lines]
        if col.dtype.kind == "f":
            np.testing.assert_array_equal(np.array(from_lines, dtype=float), col, err_msg=name)
            np.testing.assert_array_equal(np.array(table.column(name).to_pylist(), dtype=float), col, err_msg=name)
        else:
            assert from_lines == table.column(name).to_pylist() == col.tolist(), name
    summary, expected = json.loads(file.metadata.metadata[b"velplan"]), json.loads(json.dumps(report.summary(res)))
    assert summary.pop("meta")["seed"] == "7" and summary == {k: v for k, v in expected.items() if k != "meta"}


def test_zero_tolerance_with_a_seed_gives_the_nominal_figures_and_the_same_bytes(tmp_path, monkeypatch):
    monkeypatch.setitem(run.CHUNK, "numpy", 8)
    zero = ["sweep", "four-bar", "--tolerance", "0mm,0°", "--samples", "20", "--positions", "72", "--seed", "3",
            "--quiet"]
    for fmt in ("csv", "parquet"):
        a, b = tmp_path / f"a.{fmt}", tmp_path / f"b.{fmt}"
        assert main(zero + ["--format", fmt, "-o", str(a)]) == 0 and main(zero + ["--format", fmt, "-o", str(b)]) == 0
        assert a.read_bytes() == b.read_bytes()
    table = pq.read_table(tmp_path / "a.parquet")
    nominal = json.loads(pq.read_metadata(tmp_path / "a.parquet").metadata[b"velplan"])["nominal"]
    for name in ("H", "K", "gamma_min_deg", "v_max"):
        assert set(table.column(name).to_pylist()) == {nominal[name]}, name


def test_streamed_sweep_on_two_processes_gives_the_same_bytes(tmp_path, monkeypatch):
    monkeypatch.setitem(run.CHUNK, "numpy", 16)
    for jobs in ("1", "2"):
        assert main(MC + ["--format", "csv", "--jobs", jobs, "-o", str(tmp_path / f"j{jobs}.csv")]) == 0
    assert (tmp_path / "j1.csv").read_bytes() == (tmp_path / "j2.csv").read_bytes()


def test_a_sweep_failing_mid_stream_leaves_no_file(tmp_path, monkeypatch, capsys):
    original, calls = run.chunk_figures, []

    def failing(*args):
        calls.append(1)
        if len(calls) == 2:
            raise velplan.errors.VelplanError("interrupted mid-sweep")
        return original(*args)

    monkeypatch.setattr(run, "chunk_figures", failing)
    monkeypatch.setitem(run.CHUNK, "numpy", 16)
    for fmt in ("csv", "parquet"):
        calls.clear()
        assert main(MC + ["--format", fmt, "-o", str(tmp_path / f"s.{fmt}")]) == 2
        assert "interrupted mid-sweep" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
