"""A value that is zero to round-off prints as 0 on a sheet, not as "−1,018·10⁻¹³": the angle θ
of a mechanism without a time ratio, its extreme positions at φ = 0, and an instant centre on
an axis (the centres figure's note of a centre off the drawing)."""

import re

import pytest

import velplan
from velplan.plans.centres import construct_centres
from velplan.render.scene import Text
from velplan.views.centres import centres_view
from velplan.views.data import data_lines

_POWER = re.compile(r"10[⁻¹²³⁴⁵⁶⁷⁸⁹⁰]+")


@pytest.mark.parametrize("name", ["compressor", "scotch-yoke-pump", "engine-two-stroke"])
def test_theta_and_the_extreme_positions_of_a_centred_slider_read_zero(name):
    lines = [x for x in data_lines(velplan.Study(name), "ru") if "θ" in x or "φ =" in x]
    assert lines and not any(_POWER.search(x) for x in lines), lines
    assert any("θ = 0°" in x for x in lines), lines


def test_a_centre_on_an_axis_has_the_coordinate_zero():
    study = velplan.Study("press")
    view = centres_view(construct_centres(study.kinematics, 4), fine=study.turn, number=4, lang="ru")
    notes = [p.text for p in view.primitives if isinstance(p, Text) and "P₀₂" in p.text and "(" in p.text]
    assert notes and not any(_POWER.search(x) for x in notes), notes
