"""What a teacher checks on the sheet, asserted on the recorded primitives."""

import math

import numpy as np
import pytest

import velplan
from velplan.plans.steps import Intersect, LayOff, Line, Perpendicular, Similar
from velplan.plans.text import label_of
from velplan.render.layout import overlapping_labels
from velplan.render.scene import Polyline, Text
from velplan.render.shapes import arrow_shape
from velplan.views.base import number, subscript

from tests.sheet.helpers import assert_views_placed

NAMES = velplan.example_names()


def _plans(sheet):
    """View name → (placed view, plan at every position, index of the view's position)."""
    return {name: (sheet.views[name], res, sheet.plan_index[name]) for name, res in sheet.plans.items()}


def _on_line(point, a, b, tol=0.02):
    """Distance of `point` from the infinite line a–b is below `tol` mm."""
    d = np.asarray(b, float) - np.asarray(a, float)
    w = np.asarray(point, float) - np.asarray(a, float)
    return abs(d[0] * w[1] - d[1] * w[0]) / np.hypot(*d) < tol


def _unit(a, b):
    d = np.asarray(b, float) - np.asarray(a, float)
    return d / np.hypot(*d)


def _link_on_sheet(sheet, canvas, res, i, p1, p2):
    """Sheet direction of the link p1–p2 as drawn in the scheme at the plan's position,
    after checking that a drawn line of the scheme runs along it."""
    mech = sheet.views["mechanism"]
    a = mech.to_sheet(res.kin.position(p1)[i])
    b = mech.to_sheet(res.kin.position(p2)[i])
    lines = [p for p in canvas.polylines() if p.layer in ("mechanism", "positions")]
    drawn = [p for p in lines if len(p.points) == 2 and _on_line(p.points[0], a, b)
             and _on_line(p.points[1], a, b) and math.dist(*p.points) > 1.0]
    assert drawn, f"link {p1}{p2} of position {i + 1} is not drawn in the scheme"
    return _unit(a, b)


@pytest.mark.parametrize("name", NAMES)
def test_every_line_perpendicular_to_a_link_is_so_on_the_sheet(name, sheets, recorded):
    sheet, canvas = sheets[name], recorded[name]
    checked = 0
    for view_name, (placed, res, i) in _plans(sheet).items():
        kind = res.kind[0]
        layer = f"{view_name}-lines"
        drawn = canvas.polylines(layer)
        to_sheet = placed.to_sheet
        meets = {l: s.target for s in res.steps if isinstance(s, Intersect) for l in s.lines}
        for step in res.steps:
            if not (isinstance(step, Line) and step.target.startswith(kind)
                    and isinstance(step.direction, Perpendicular)):
                continue
            through = to_sheet(np.array([res.values[step.through][i].real,
                                         res.values[step.through][i].imag]))
            x = res.values[meets[step.target]][i]
            cross = to_sheet(np.array([x.real, x.imag]))
            link = _link_on_sheet(sheet, canvas, res, i, step.direction.a, step.direction.b)
            if math.dist(through, cross) < 0.05:
                continue  # a zero component: nothing to see
            lines = [p for p in drawn if _on_line(through, *p.points[:2])
                     and _on_line(cross, *p.points[:2])]
            assert lines, f"{view_name}: no line drawn through {label_of(step.through)} " \
                          f"for {step.component}"
            for p in lines:
                assert abs(float(_unit(*p.points[:2]) @ link)) < 1e-6, (view_name, step)
            # the relative vector the line carries is drawn along it, ⊥ the link too
            arrows = [a for a in canvas.arrows(view_name)
                      if math.dist(a.start, through) < 0.01 and math.dist(a.end, cross) < 0.01]
            assert arrows, f"{view_name}: vector {step.component} not drawn"
            assert abs(float(_unit(arrows[0].start, arrows[0].end) @ link)) < 1e-6
            checked += 1
    assert checked >= 2


@pytest.mark.parametrize("name", NAMES)
def test_arrows_run_from_their_origin_to_their_image_with_the_head_at_the_image(
        name, sheets, recorded):
    sheet, canvas = sheets[name], recorded[name]
    for view_name, (placed, res, i) in _plans(sheet).items():
        kind = res.kind[0]
        pole = f"{kind}:{'p' if kind == 'v' else 'π'}"

        def at(target):
            z = res.values[target][i]
            return placed.to_sheet(np.array([z.real, z.imag]))

        arrows = canvas.arrows(view_name)
        assert arrows
        images = [at(t) for t in res.values if t.startswith(kind + ":")
                  and not isinstance(res.values[t], tuple)]
        for a in arrows:
            assert any(math.dist(a.end, p) < 1e-6 for p in images), (view_name, a)
            head = arrow_shape(a.start, a.end, 4.5, 1.5).head
            if head is not None:
                base = (head[1] + head[2]) / 2
                assert np.allclose(head[0], a.end)
                assert float((np.asarray(a.end) - base) @ (np.asarray(a.end) - a.start)) > 0

        def has_arrow(src, dst):
            return any(math.dist(a.start, src) < 1e-6 and math.dist(a.end, dst) < 1e-6
                       for a in arrows)

        for step in res.steps:
            if not step.target.startswith(kind + ":"):
                continue
            if isinstance(step, LayOff) and math.dist(at(step.origin), at(step.target)) > 1e-6:
                assert has_arrow(at(step.origin), at(step.target)), (view_name, step)
                assert not has_arrow(at(step.target), at(step.origin))
            if isinstance(step, (Intersect, Similar)) and math.dist(at(pole), at(step.target)) > 1e-6:
                assert has_arrow(at(pole), at(step.target)), (view_name, step.target)


@pytest.mark.parametrize("name", NAMES)
def test_no_two_labels_overlap(name, sheets):
    assert overlapping_labels(sheets[name].scene) == []


@pytest.mark.parametrize("name", NAMES)
def test_views_inside_the_free_area_and_apart(name, sheets):
    boxes = assert_views_placed(sheets[name])
    assert {"mechanism", "table", "diagrams"} <= set(boxes)
    assert len([k for k in boxes if k.startswith("plan-")]) == 4


@pytest.mark.parametrize("name", NAMES)
def test_text_names_mechanism_scales_positions_and_every_image(name, sheets):
    sheet = sheets[name]
    texts = [t.text for t in sheet.scene.of_kind(Text)]
    joined = "\n".join(texts)
    assert sheet.info.title.endswith(sheet.mechanism.name_in("ru"))  # the title names it, wrapped in its cell
    assert all(word in joined for word in sheet.info.title.split()) and name not in joined  # the designation is a code
    assert f"μl = {number(sheet.scales['mu_l'], 'ru')} м/мм" in joined
    mech_texts = {t.text for t in sheet.views["mechanism"].primitives if isinstance(t, Text)}
    for k in range(1, 13):
        assert str(k) in mech_texts, k
    for view_name, (placed, res, i) in _plans(sheet).items():
        kind = res.kind[0]
        symbol, unit = ("μv", "(м/с)/мм") if kind == "v" else ("μa", "(м/с²)/мм")
        assert f"{symbol} = {number(res.scale, 'ru')} {unit}" in joined
        number_ = placed.view.meta["number"]
        head = "План скоростей" if kind == "v" else "План ускорений"
        assert f"{head} (пол. {number_})" in joined
        letters = set()
        for t in placed.primitives:
            if isinstance(t, Text) and t.layer == f"{view_name}-labels":
                letters.update(t.text.split(", "))
        wanted = {subscript(label_of(t)) for t in placed.view.meta["images"]}
        assert wanted <= letters, (view_name, wanted - letters)
        assert ("p" if kind == "v" else "π") in letters


def test_thick_position_is_the_first_plan_position(sheets):
    sheet = sheets["shaper"]
    assert sheet.views["mechanism"].view.meta["thick"] == sheet.positions[0]
    assert sheet.positions == (4, 10)
    thick = [p for p in sheet.scene.on_layer("mechanism") if isinstance(p, Polyline)
             and p.line == "thick"]
    assert thick


def test_title_block_carries_the_scale_and_designation(sheets):
    sheet = sheets["shaper"]
    texts = {t.text for t in sheet.scene.on_layer("title").of_kind(Text)}
    assert sheet.info.scale in texts
    assert "ТММ 01.00.000" in texts
