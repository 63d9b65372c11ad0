"""Issue 35, items 6 and 7: a triad that is a truss is refused in one line naming the joint,
and the points that are not material points (Assur's special point, coincident points) are
marked in the JSON and JSON-lines output, whose velocities and accelerations are those of
their link's point, while every other point's are the derivatives of its positions."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.errors import MechanismError

from tests.test_triad import central_difference

ROCKER = (Path(velplan.__file__).parent / "catalogue" / "triad-rocker.toml").read_text(encoding="utf-8")
FD_LOOSE = 1e-7
"""Relative error allowed to the 12th-order differences of 360 positions (1°; the Whitworth
quick-return's accelerations differ from those of 72 positions by 1e-5)."""
LEADS = ('{ link = "2", joint = "A", length = 0.347 }', '{ link = "4", joint = "E", length = 0.347 }',
         '{ link = "5", joint = "F", length = 0.290 }')


def run_cli(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(list(argv)) == 0
    return out.getvalue()


# ---- item 6: two rods from one joint make a truss, not a group -------------------------------------


@pytest.mark.parametrize("k, m, joint", [(0, 1, "E"), (1, 2, "F"), (0, 2, "A")])
def test_two_rods_from_one_joint_are_refused(k, m, joint):
    text = ROCKER
    for i in (k, m):
        assert LEADS[i] in text
        text = text.replace(LEADS[i], LEADS[i].replace(f'joint = "{"AEF"[i]}"', f'joint = "{joint}"'))
    links = ["245"[i] for i in (k, m)]
    with pytest.raises(MechanismError) as err:
        velplan.parse(text)
    assert str(err.value) == (f"group '3-2-4-5': leads {k + 1} and {m + 1} are rods from the same joint {joint!r}, "
                              f"so links {links[0]}, {links[1]} and 3 make one rigid body (a truss), not a class III "
                              "group")


def test_a_truss_is_refused_by_the_cli_in_one_line(tmp_path, capsys):
    bad = tmp_path / "truss.toml"
    bad.write_text(ROCKER.replace(LEADS[1], '{ link = "4", joint = "A", length = 0.347 }'), encoding="utf-8")
    assert main(["info", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "same joint 'A'" in err and "Traceback" not in err


def test_rods_from_different_joints_and_a_block_are_a_group():
    text = ROCKER.replace(LEADS[2], '{ link = "5", guide = { link = "0", through = "F", angle_deg = 123.0 } }')
    assert velplan.parse(text).groups[0].kind == "triad"


# ---- item 7: the marks of points that are not material -------------------------------------------


def _analysis(name: str, n: int = 360):
    doc = json.loads(run_cli("analyze", name, "--positions", str(n), "--format", "json"))
    lines = [json.loads(t) for t in run_cli("analyze", name, "--positions", str(n), "--format", "jsonl").splitlines()]
    return doc, lines


def _arrays(pos, name):
    get = lambda keys: np.array([[p["points"][name][q] for q in keys] for p in pos])  # noqa: E731
    return get(("x", "y")), get(("vx", "vy")), get(("ax", "ay"))


def _link_point(pos, link: str, origin: str, at: np.ndarray):
    """Velocity and acceleration of the point of ``link`` at ``at`` (n, 2), from its origin's motion
    and the link's ω, ε as the JSON gives them."""
    x, v, a = _arrays(pos, origin)
    w = np.array([p["links"][link]["omega"] for p in pos])[:, None]
    e = np.array([p["links"][link]["epsilon"] for p in pos])[:, None]
    r = at - x
    perp = np.stack([-r[:, 1], r[:, 0]], axis=1)
    return v + w * perp, a + e * perp - w * w * r


@pytest.mark.parametrize("name, marked, origin", [
    ("triad-press", {"K3": ("special", "3")}, "B"),
    ("triad-rocker", {"K3": ("special", "3")}, "B"),
    ("whitworth", {"A3": ("coincident", "3")}, "O3"),
])
def test_marked_points_and_the_derivatives_of_positions(name, marked, origin):
    doc, lines = _analysis(name)
    pos = doc["positions"]
    assert all(p["valid"] for p in pos)
    for p, line in zip(pos, lines):  # the same marks in both formats, at every position
        for k, point in p["points"].items():
            mark = (point.get("kind"), point.get("link"))
            assert mark == ((marked[k]) if k in marked else (None, None))
            assert (line["points"][k].get("kind"), line["points"][k].get("link")) == mark
    phi = np.unwrap(np.radians([p["phi_deg"] for p in pos]))
    h, w1 = float(phi[1] - phi[0]), doc["omega1"]
    for k in pos[0]["points"]:
        x, v, a = _arrays(pos, k)
        fv, fa = w1 * central_difference(x, h), w1 * central_difference(v, h)
        scale_v, scale_a = max(np.abs(v).max(), 1e-9), max(np.abs(a).max(), 1e-9)
        if k not in marked:
            assert np.abs(fv - v).max() <= FD_LOOSE * scale_v, k
            assert np.abs(fa - a).max() <= FD_LOOSE * scale_a, k
            continue
        # a marked point moves over its link: differences of its positions are not its velocity …
        assert np.abs(fv - v).max() > 1e-3 * scale_v, k
        # … which is that of the link's point there
        lv, la = _link_point(pos, marked[k][1], origin, x)
        assert np.abs(lv - v).max() <= 1e-12 * scale_v and np.abs(la - a).max() <= 1e-12 * scale_a


def test_csv_has_the_same_numbers_and_no_text_columns():
    doc = json.loads(run_cli("analyze", "triad-press", "--positions", "3", "--format", "json"))
    rows = run_cli("analyze", "triad-press", "--positions", "3", "--format", "csv").splitlines()
    head = rows[0].split(",")
    assert [h for h in head if h.startswith("K3.")] == [f"K3.{q}" for q in ("x", "y", "vx", "vy", "ax", "ay")]
    values = dict(zip(head, rows[1].split(",")))
    assert float(values["K3.vy"]) == pytest.approx(doc["positions"][0]["points"]["K3"]["vy"], rel=1e-11)
