"""The dynamics sheet: what it draws agrees with the dynamics it reads — Wittenbauer's
tangents touch the drawn curve and bound it, the segment read off the drawing gives J_I
within the drafting bound, the curves are the computed ones at their scales — and bad
requests end in one line."""

import math
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.plans.scale import standard_scale
from velplan.render.scene import Circle, Polyline, Text
from velplan.sheets.dynamics import PANELS, build_dynamics_sheet

EXAMPLES = Path(velplan.__file__).parent / "examples"
RUN = """
[dynamics]
[[dynamics.inertia]]
name = "flywheel"
inertia = 40.0
ratio = 1.0
[dynamics.motor]
kind = "kloss"
critical_torque = 60.0
synchronous_rpm = 1500.0
critical_rpm = 1200.0
ratio = 24.0
efficiency = 0.9
"""


@pytest.fixture(scope="module")
def shaper():
    return build_dynamics_sheet(velplan.Study("shaper", delta=0.05), lang="en")


def _texts(sheet):
    return [t.text for t in sheet.scene.primitives if isinstance(t, Text)]


def _lines(view, line=None):
    return [p for p in view.view.primitives if isinstance(p, Polyline) and (line is None or p.line == line)]


def test_views_scales_and_results(shaper):
    assert set(shaper.views) == {*PANELS, "wittenbauer", "flywheel", "results"}
    for name in PANELS:
        mu = shaper.scales[name]
        assert standard_scale(mu) == pytest.approx(mu)  # standard drawing scales only
    fly = shaper.dynamics.flywheel
    text = "\n".join(_texts(shaper))
    assert "Energy–mass diagram (Wittenbauer)" in text
    assert shaper.info.title == "Dynamic analysis of the machine: shaping machine"
    assert f"{fly.exact:.3f}" in text  # J_I exact, six figures
    # the second half of the sheet is used: every view is at least 60 mm on its longer side
    for name, v in shaper.views.items():
        assert max(v.view.width_mm, v.view.height_mm) >= 60.0, name


def test_wittenbauer_tangents_touch_and_bound_the_drawn_curve(shaper):
    w = shaper.wittenbauer
    view = shaper.views["wittenbauer"].view
    curve = max(_lines(shaper.views["wittenbauer"], "thick"), key=lambda p: len(p.points))
    xy = np.array(curve.points)
    tangents = [p for p in view.primitives if isinstance(p, Polyline) and p.layer == "dynamics-lines"
                and len(p.points) == 2 and p.points[0][0] != p.points[1][0]
                and abs(p.points[0][1] - p.points[1][1]) > 1e-9]
    assert len(tangents) == 2
    slopes = sorted((b[1] - a[1]) / (b[0] - a[0]) for a, b in (t.points for t in tangents))
    assert slopes[0] == pytest.approx(math.tan(math.radians(w.psi_min_deg)), rel=1e-12)
    assert slopes[1] == pytest.approx(math.tan(math.radians(w.psi_max_deg)), rel=1e-12)
    (k, kt), (l, lt) = sorted(((t.points[0], t.points[1]) for t in tangents), key=lambda q: -q[0][1])
    # both start on the ΔT axis, k above l, kl as read off the drawing
    assert k[0] == pytest.approx(l[0]) and k[1] - l[1] == pytest.approx(w.segment_mm, rel=1e-12)
    for (a, b), side in (((k, kt), -1.0), ((l, lt), 1.0)):
        s = (b[1] - a[1]) / (b[0] - a[0])
        gap = side * (xy[:, 1] - (a[1] + s * (xy[:, 0] - a[0])))
        assert gap.min() > -1e-6  # the curve stays on one side of each tangent …
        assert gap.min() < 0.05  # … and touches it (within the 720-step polyline), mm
    # the segment read off at 0.5 mm gives J_I within μT·0.5/(ω_m²·δ) of the exact one
    fly = shaper.dynamics.flywheel
    bound = w.mu_T * w.precision / (fly.omega_mean**2 * fly.delta)
    assert abs(w.inertia_drawn - fly.exact) <= 0.5 * bound + 1e-9 * fly.exact
    assert w.inertia == pytest.approx(fly.exact, rel=1e-9)


def test_panels_draw_the_computed_curves(shaper):
    d = shaper.dynamics
    c = d.curves(720)
    for name, key, base in (("works", "A_sum", 0.0), ("omega", "omega", d.steady.omega_mean)):
        view = shaper.views[name].view
        mu, mu_phi = view.meta["mu"], view.meta["mu_phi"]
        thick = max(_lines(shaper.views[name], "thick"), key=lambda p: len(p.points))
        xy = np.array(thick.points)
        values = np.abs(c[key]) if key == "omega" else c[key]
        # the curve's ordinates are (value − base)/μ above the φ axis, from the view's origin
        y = xy[:, 1] - xy[0, 1] + (values[0] - base) / mu
        assert np.allclose(y, (values - base) / mu, atol=1e-9)
        assert xy[-1, 0] - xy[0, 0] == pytest.approx(2 * math.pi / mu_phi)
    marks = [p for p in shaper.views["omega"].view.primitives if isinstance(p, Circle) and p.fill == "solid"]
    assert len(marks) == 2


def test_all_languages_and_a_run(tmp_path):
    for lang in ("ru", "uk", "zh"):
        sheet = build_dynamics_sheet(velplan.Study("shaper-lever-rod"), lang=lang)
        assert "wittenbauer" in sheet.views
    path = tmp_path / "run.toml"
    path.write_text((EXAMPLES / "slider-press.toml").read_text() + RUN
                    + "[dynamics.run]\nomega = 6.0\ntravel_deg = 720.0\n")
    sheet = build_dynamics_sheet(velplan.Study(path), lang="en")
    assert set(sheet.views) == {*PANELS, "results"} and sheet.wittenbauer is None
    # the motor's work read from the motion: ΔT = A_d + A_r, and A_d = ∫M_d dφ
    c = sheet.dynamics.curves(4000)
    theta = np.radians(c["travel_deg"])
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (c["M_drive"][1:] + c["M_drive"][:-1]) * np.diff(theta))])
    assert np.allclose(c["A_drive"], integral, atol=1e-4 * np.abs(integral).max())


def test_cli_dynamics_sheet(tmp_path, capsys):
    out = tmp_path / "d.svg"
    assert main(["sheet", "shaper", "--kind", "dynamics", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "crank would stop" in err and "--delta" in err
    assert not out.exists()
    assert main(["sheet", "shaper", "--kind", "dynamics", "--delta", "0.05", "-o", str(out), "--lang", "ru"]) == 0
    assert "Диаграмма энергомасс" in out.read_text("utf-8")
    assert main(["sheet", "shaper", "--delta", "0.05", "-o", str(tmp_path / "k.svg")]) == 2
    assert "--delta belongs to --kind dynamics" in capsys.readouterr().err
    assert main(["sheet", "shaper", "--kind", "dynamics", "--delta", "1.5", "-o", str(out)]) == 2
    assert "between 0 and 1" in capsys.readouterr().err
