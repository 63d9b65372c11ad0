"""The dynamics sheet's curve panels and flywheel as a teacher reads them (issue 32, item 9):
each curve named once, beside its own curve (or joined to it by a leader), a thin curve that
lies on the φ axis or on another curve not drawn as a line of its own; at least three numbered
ordinate ticks; the scales with their index; the flywheel's width dimensioned as ESKD does,
its size crossed by no line."""

import math

import numpy as np
import pytest
import shapely

from velplan.render.layout import label_box
from velplan.render.scene import Arrow, Polyline, Text
from velplan.views.dynamics import Series, _tick_step, curve_panel, flywheel_view, nice_step

TRAVEL = np.linspace(0.0, 2 * math.pi, 361)


def _panel(series, **kw):
    args = dict(cycle=2 * math.pi, positions=12, length_mm=180.0, height_mm=40.0, title="M", ordinate="M",
                unit_text="N·m", lang="en", mu_symbol="μ_{M}")
    return curve_panel("moments", TRAVEL, series, **{**args, **kw})


def _texts(view):
    return [t for t in view.primitives if isinstance(t, Text)]


def test_a_load_on_the_total_is_named_with_it_and_one_on_the_axis_is_listed():
    gas = -100.0 * np.maximum(np.sin(TRAVEL), 0.0)
    weight = 0.2 * np.cos(TRAVEL)  # 0.2 N·m: far below a millimetre at any scale of 100 N·m
    view = _panel([Series(gas, "thin", "M_{F}"), Series(weight, "thin", "M_{G}"),
                   Series(gas + weight, "thick", "M_{r}"), Series(np.full_like(TRAVEL, 31.8), "hidden", "M_{d}")])
    texts = [t.text for t in _texts(view)]
    assert "M_{r} ≈ M_{F}" in texts and "M_{F}" not in texts and "M_{G}" not in texts
    assert any(t.startswith("M_{G} ≈ 0 (|M_{G}| ≤ 0.2 N·m)") for t in texts)
    assert len([p for p in view.primitives if isinstance(p, Polyline) and len(p.points) > 100]) == 2
    assert set(view.meta["curves"]) == {"M_{r} ≈ M_{F}", "M_{d}"}


def test_a_load_apart_from_the_total_keeps_its_line_and_its_name_by_it():
    # the thin load leaves the thick total only on the second half turn: its name stands there
    drive = -80.0 * np.maximum(-np.sin(TRAVEL), 0.0)
    weight = 40.0 * np.maximum(-np.sin(TRAVEL), 0.0) - 60.0 * np.maximum(np.sin(TRAVEL), 0.0)
    view = _panel([Series(weight, "thin", "M_{G}"), Series(drive, "thin", "M_{F}"),
                   Series(weight + drive, "thick", "M_{r}")])
    curves = {k: shapely.LineString(v) for k, v in view.meta["curves"].items()}
    assert set(curves) == {"M_{G}", "M_{F}", "M_{r}"}
    for name, line in curves.items():
        (t,) = [t for t in _texts(view) if t.text == name]
        box = label_box(t)
        # view mm: the curves' points were drawn shifted by the view's origin
        own = shapely.affinity.translate(line, *view.origin)
        others = [shapely.affinity.translate(g, *view.origin) for k, g in curves.items() if k != name]
        assert box.distance(own) < min(box.distance(g) for g in others), name
        assert box.distance(own) < 6.0
    (g,) = [t for t in _texts(view) if t.text == "M_{G}"]
    assert g.position[0] - view.origin[0] > 90.0  # on the half turn where it is apart


@pytest.mark.parametrize("lo, hi, mu, base", [(5.105, 5.367, 0.01, 5.236), (6.13, 6.44, 0.01, 6.2832),
                                              (-540.0, 163.9, 20.0, 0.0), (0.004, 0.023, 0.001, 0.0)])
def test_an_ordinate_numbers_at_least_three_ticks(lo, hi, mu, base):
    clear = 3.75 if base else 1e-6
    step = _tick_step(lo, hi, mu, base, clear)
    ticks = np.arange(math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9) + 1) * step
    numbered = [v for v in ticks if abs(v - base) / mu >= clear]
    assert len(numbered) >= 3
    assert step / mu >= 4.5 - 1e-9  # the numbers keep apart
    assert step <= nice_step(hi - lo)
    mantissa = step / 10 ** math.floor(math.log10(step) + 1e-9)
    assert min(abs(mantissa - m) for m in (1.0, 2.0, 2.5, 5.0)) < 1e-9


def test_the_omega_panel_numbers_round_values_with_the_sheets_decimal_sign():
    w = 5.236 + 0.13 * np.sin(TRAVEL)
    view = _panel([Series(w, "thick", "")], ordinate="ω", unit_text="рад/с", lang="ru", base=5.236,
                  base_label="ω_{m}", mu_symbol="μ_{ω}", height_mm=26.0)
    numbers = [t.text for t in _texts(view) if t.anchor == "end" and t.text[0].isdigit()]
    assert len(numbers) >= 3 and all("," in n and "." not in n for n in numbers)
    assert any(t.text.startswith("μ_{ω} = ") and "(рад/с)/мм" in t.text for t in _texts(view))


class _Disc:
    shape, outer, inner, width, mass, inertia, required, density = "disc", 0.316, 0.0, 0.064, 39.2, 0.489, 0.48, 7800.0


@pytest.mark.parametrize("scale", [0.015, 0.0025])  # a narrow width (4.3 mm) and a wide one (25.6 mm)
def test_the_flywheels_sizes_read_as_eskd_writes_them_and_no_line_crosses_them(scale):
    view = flywheel_view(_Disc(), scale=scale, lang="ru")
    texts = _texts(view)
    assert any(t.text == "⌀316" for t in texts)
    (width,) = [t for t in texts if t.text == "64"]  # the size alone, no "b ="
    assert width.rotation_deg == 0.0
    lines = [shapely.LineString(p.points) for p in view.primitives if isinstance(p, Polyline)]
    lines += [shapely.LineString([p.start, p.end]) for p in view.primitives if isinstance(p, Arrow)]
    for t in (x for x in texts if x.text in ("64", "⌀316")):
        box = label_box(t).buffer(-0.3)
        assert not any(g.intersects(box) for g in lines), t.text
    # the size stands over its dimension line (the horizontal line under the section)
    under = [g for g in lines if abs(g.coords[0][1] - g.coords[-1][1]) < 1e-9 and g.coords[0][1] < width.position[1]]
    assert min(width.position[1] - g.coords[0][1] for g in under) == pytest.approx(1.0)
