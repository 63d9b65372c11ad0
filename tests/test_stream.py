"""Streamed output of ``velplan analyze --format csv|jsonl``: the same bytes as the whole-array
CSV, JSON lines that agree with the JSON document, number text that is exactly Python's
``'%.12g'`` (compiled and plain paths), bounded memory and no half-written file."""

import json
import math
import tracemalloc

import numpy as np
import pytest

from velplan.cli import main
from velplan.cli import numfmt
from velplan.cli.kinematics import stream, to_csv, to_json
from velplan.cli.stream import open_output
from velplan.study import Study

TRICKY = np.array([0.0, -0.0, 1.0, -1.0, 0.1, 1e-5, 1e-4, 9.9999999999995e-5, 999999999999.5, 1e12, 1e11,
                   123456789012345.0, 0.5, 2.5, 1.5e-300, 5e-324, 1e300, -1e100, 1e-100, 99999999999.95,
                   0.00012345678901234, 360.0, 1234.5, 1e16, 12345678901.25, -2.5e-5, 1e-320, 0.30000000000000004,
                   2.0 ** -30, 1.0000000000005, 1.0000000000015, np.nan, np.inf, -np.inf])


def _python(values, na):
    return "".join("[" + ", ".join(("%.12g" % x) if math.isfinite(x) else na for x in row) + "]\n"
                   for row in values.tolist()).encode()


@pytest.mark.parametrize("compiled", [True, False])
def test_rows_are_pythons_percent_g(compiled, monkeypatch):
    if compiled:
        pytest.importorskip("numba")
    else:
        monkeypatch.setattr(numfmt, "_KERNELS", [None])
    rng = np.random.default_rng(5)
    x = np.concatenate([TRICKY, rng.standard_normal(4000) * 10.0 ** rng.integers(-40, 40, 4000),
                        np.round(rng.standard_normal(2000), 3), rng.integers(-99, 99, 2000) / 8.0])
    x = x[: x.size // 2 * 2].reshape(-1, 2)
    lits = [b"[", b", ", b"]\n"]
    assert numfmt.rows(x, lits, na=b"null") == _python(x, "null")


@pytest.mark.parametrize("name", ["shaper", "four-bar", "press"])
def test_streamed_csv_is_the_whole_array_csv(name):
    study = Study(name, n=50)
    assert b"".join(stream(study, "csv", chunk=7)) == to_csv(study.kinematics).encode()


def test_streamed_csv_leaves_positions_that_do_not_close_empty():
    study = Study("four-bar", angles=np.radians([0.0, 90.0]), check_assembly=False)
    text = b"".join(stream(study, "csv")).decode().splitlines()
    assert text[1:] == to_csv(study.kinematics).splitlines()[1:]


def test_json_lines_agree_with_the_json_document():
    study = Study("shaper", n=9)
    doc = json.loads(to_json(study.kinematics))["positions"]
    lines = [json.loads(t) for t in b"".join(stream(study, "jsonl", chunk=4)).decode().splitlines()]

    def same(a, b):
        if isinstance(a, dict):
            return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
        if a is None or isinstance(a, (bool, str)):  # a string: the mark of a point not material
            return a == b
        return math.isclose(a, b, rel_tol=1e-11, abs_tol=1e-14)

    assert len(lines) == 9 and all(same(a, b) for a, b in zip(doc, lines))


def _peak(n: int) -> tuple[int, int]:
    study = Study("four-bar", n=n)
    study.phi  # noqa: B018 (the angles themselves are the input)
    tracemalloc.start()
    size = sum(len(part) for part in stream(study, "csv"))
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return size, peak


def test_streaming_memory_is_bounded():
    small, peak_small = _peak(40_000)
    big, peak_big = _peak(120_000)
    assert big > 2.9 * small > 50e6  # three times the text …
    assert peak_big < 1.2 * peak_small + 2e6 < 100e6  # … in the same few pieces of memory


def test_analyze_jsonl_cli_and_no_half_written_file(tmp_path, capsys):
    out = tmp_path / "a.jsonl"
    assert main(["analyze", "four-bar", "--positions", "5", "--format", "jsonl", "-o", str(out)]) == 0
    assert [json.loads(t)["position"] for t in out.read_text().splitlines()] == [1, 2, 3, 4, 5]
    with pytest.raises(RuntimeError):
        with open_output(tmp_path / "b.csv") as f:
            f.write("x,y\n")
            raise RuntimeError("interrupted")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.jsonl"]
