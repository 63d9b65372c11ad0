import subprocess
import sys

import pytest

from velplan.render.canvas import render
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.shapes import hatch_segments

pytest.importorskip("matplotlib")


def test_importing_render_does_not_import_matplotlib():
    code = ("import sys, velplan.render, velplan.render.mpl, velplan.sheets.frame, "
            "velplan.render.symbols, velplan.render.export; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"


def test_mpl_canvas_draws_same_geometry_at_sheet_size():
    from velplan.render.mpl import MplCanvas

    scene = Scene((
        Polyline([(0, 0), (100, 0)], "construction", "axis"),
        Polygon([(10, 10), (30, 10), (30, 20), (10, 20)], "diagram", "thick", "hatch"),
        Circle((50, 50), 2, "mechanism", fill="white"),
        Arrow((100, 100), (150, 100), "plan-v-1", "thick"),
        Text((100, 90), "План", "labels", 3.5, "middle"),
    ), 420, 297)
    ax = render(scene, MplCanvas())
    fig = ax.figure
    assert fig.get_size_inches() == pytest.approx((420 / 25.4, 297 / 25.4))
    assert ax.get_xlim() == (0.0, 420.0) and ax.get_ylim() == (0.0, 297.0)
    # axis line + the shared hatch lines of the 20 × 10 box + arrow shaft
    hatch = hatch_segments([(10, 10), (30, 10), (30, 20), (10, 20)], 2.0, 45.0)
    assert len(hatch) == 11
    assert len(ax.lines) == 1 + 11 + 1
    assert ax.lines[1].get_xydata() == pytest.approx(hatch[0])
    axis = ax.lines[0]
    assert axis.get_linewidth() == pytest.approx(0.35 / 25.4 * 72)
    head = ax.patches[-1]
    assert head.get_xy()[0] == pytest.approx((150.0, 100.0))
    text, = ax.texts
    assert text.get_text() == "План" and text.get_ha() == "center"
    assert text.get_fontsize() == pytest.approx(3.5 / 0.72 / 25.4 * 72)
    zorders = [a.get_zorder() for a in (*ax.lines, *ax.patches, *ax.texts)]
    assert len(set(zorders)) == len(zorders)
