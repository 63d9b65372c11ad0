"""The input-data block writes its symbols with their indices below the line, as the force and
dynamics sheets do (l_{O2A}: an "l" before full-size capitals reads as "I"), and the note, which
sets its own symbols, gets them on one line (lO₂A, JS₂, ψmax)."""
import re

import pytest

import velplan
from velplan.notation import unicode_text
from velplan.views.data import data_lines


@pytest.mark.parametrize("name", ["triad-rocker", "shaper"])
def test_lengths_inertias_and_the_swing_carry_their_indices(name):
    study = velplan.Study(name)
    text = "\n".join(data_lines(study, "ru"))
    mech = study.mechanism
    c = mech.crank
    assert f"l_{{{c.pivot}{c.tip}}} = " in text
    for ms in mech.masses:
        if ms.inertia:
            assert f"J_{{S{ms.link}}} = " in text
    assert not re.search(r"(^|[ ;])l[A-Z]", text) and "ψmax" not in text and not re.search(r"JS\d", text)
    if study.stroke is not None and not study.stroke.quantity.startswith(("slide", "point")):
        assert "ψ_{max} = " in text
    plain = unicode_text(text)
    assert f"l{c.pivot.translate(str.maketrans('0123456789', '₀₁₂₃₄₅₆₇₈₉'))}{c.tip}" in plain
    assert "_{" not in plain
