"""Loads as data: values, directions, and every documented error message."""

import math
import re

import numpy as np
import pytest

import velplan
import velplan.forces as vf
from velplan.forces.common import as_complex, dot
from tests.forces.mechs import example_text


def _with_load(mech: str, body: str):
    return velplan.parse(example_text(mech) + "\n[[load]]\n" + body + "\n", name=mech)


def test_constant_force_and_moment():
    m = _with_load("four-bar", 'kind = "force"\nname = "Q"\npoint = "B"\nfx = 10.0\nfy = -20.0\n'
                               '[[load]]\nkind = "moment"\nname = "M"\nlink = "3"\nmoment = -4.0')
    q, mm = vf.parse_loads(m)
    assert (q.link, q.point, q.fx, q.fy) == ("2", "B", 10.0, -20.0)  # B is owned by the coupler
    kin = velplan.solve(m, [0.0, 1.0])
    acts = vf.load_actions([q, mm], kin)
    np.testing.assert_array_equal(acts.forces[0].vector, [10 - 20j, 10 - 20j])
    np.testing.assert_array_equal(acts.moments[0].moment, [-4.0, -4.0])
    # M_b of a lone moment on the rocker: M_b·ω1 = −M·ω3
    res = vf.force_analysis_at(m, kin.phi)
    np.testing.assert_allclose(res.kinetostatics.balancing_moment,
                               -(dot(10 - 20j, as_complex(kin.velocity("B"))) - 4.0 * kin.omega("3")) / kin.omega1,
                               rtol=1e-12)


def test_table_over_the_crank_angle_along_the_guide():
    mech = velplan.load("crank-slider")
    t = vf.table_force(mech, [0.0, 90.0, 180.0, 270.0], [0.0, 100.0, 0.0, -100.0], point="B", link="3")
    ref = velplan.reference_angle(mech)
    phi = ref + np.radians([0.0, 45.0, 90.0, 315.0, 360.0])
    kin = velplan.solve(mech, phi)
    f = t.actions(kin).forces[0].vector
    np.testing.assert_allclose(f, [0.0, 50.0, 100.0, -50.0, 0.0], atol=1e-9)  # the guide points along +x


def test_table_over_the_output_on_the_working_stroke_only():
    mech = velplan.load("shaper")
    t = vf.table_force(mech, [0.0, 0.6], [0.0, 600.0], over="output", stroke="working", direction="against-motion")
    assert (t.point, t.link) == ("F", "6")
    st = velplan.stroke(mech)
    tr = t.track
    phi = tr.phi(np.array([0.25, 0.5, 0.75]) * tr.span)  # inside the working stroke
    kin = velplan.solve(mech, phi)
    d = np.abs(tr.slide(kin) - tr.s_start)
    f = t.actions(kin).forces[0].vector
    np.testing.assert_allclose(np.abs(f), 1000.0 * d, rtol=1e-12)
    assert np.all(dot(f, as_complex(kin.velocity("F"))) < 0)
    back = velplan.solve(mech, [st.end.phi + 0.5])
    assert t.actions(back).forces[0].vector[0] == 0


def test_fixed_direction():
    mech = velplan.load("four-bar")
    t = vf.table_force(mech, [0.0, 360.0], [50.0, 50.0], point="S3", angle_deg=90.0, direction="fixed")
    kin = velplan.solve(mech, [0.3])
    assert t.actions(kin).forces[0].vector[0] == pytest.approx(50j)


def test_indicator_force_is_pressure_times_piston_area():
    mech = velplan.load("crank-slider")
    travel = [0.0, 0.05, 0.1006]
    away, toward = [1e5, 1e5, 0.0], [8e5, 2e5, 0.0]  # suction then compression, Pa
    g = vf.indicator_force(mech, 0.08, travel, away, toward, head="start")
    tr = g.track
    phi = tr.phi(np.array([0.3, 1.0, 2.5, 3.5, 4.5, 5.5]))
    kin = velplan.solve(mech, phi)
    x = np.abs(tr.slide(kin) - tr.s_start)
    moving_away = tr.psi(phi) < tr.span
    p = np.where(moving_away, np.interp(x, travel, away), np.interp(x, travel, toward))
    f = g.actions(kin).forces[0].vector
    np.testing.assert_allclose(np.abs(f), p * math.pi * 0.08**2 / 4, rtol=1e-12)
    # the gas pushes the piston away from the head (from s_start towards s_end)
    push = np.sign(tr.s_end - tr.s_start) * np.exp(1j * kin.angle("3"))
    np.testing.assert_allclose(f, np.abs(f) * push, atol=1e-9)
    assert g.area == pytest.approx(math.pi * 0.0016)


def test_toml_loads_of_the_examples():
    assert [type(x).__name__ for x in vf.parse_loads(velplan.load("shaper"))] == ["CuttingForce"]
    assert [type(x).__name__ for x in vf.parse_loads(velplan.load("slider-press"))] == ["PressLoad"]
    assert vf.parse_loads(velplan.load("press")) == ()


ERRORS = [
    ("shaper", 'kind = "push"', "load #2: unknown kind 'push'; known kinds: cutting, force, indicator, moment, press, table"),
    ("shaper", 'kind = "force"\npoint = "F"\nfz = 1.0', "load #2: unknown key 'fz'; allowed: fx, fy, kind, link, name, point"),
    ("shaper", 'kind = "force"\nfx = 1.0', "load #2: missing point"),
    ("shaper", 'kind = "force"\nname = ""\npoint = "F"', "load #2: name must not be empty or start with '#', not ''"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "Z"',
     "load 'Q': unknown point 'Z'; known points: O3, O2, A, A4, B, S4, F, S5"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "A"\nlink = "4"',
     "load 'Q': point 'A' is not a point of link '4'; points of link 4: A4, B, S4, O3"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "O3"\nlink = "0"',
     "load 'Q': link '0' is the frame; a force on it does no work and needs no balancing"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "F"\nlink = "9"', "load 'Q': unknown link '9'; known links: 2, 3, 4, 5, 6"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "F"\nfx = "big"', "load 'Q': fx must be a number, not 'big'"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = "F"\nfx = nan', "load 'Q': fx must be finite, not nan"),
    ("shaper", 'kind = "force"\nname = "Q"\npoint = true', "load 'Q': point must be a name, not True"),
    ("shaper", 'kind = "moment"\nname = "M"\nlink = "4"', "load 'M': missing moment (N·m)"),
    ("shaper", 'kind = "moment"\nname = "M"\nmoment = 1.0', "load 'M': missing link"),
    ("shaper", 'kind = "moment"\nname = "M"\nlink = "7"\nmoment = 1.0', "load 'M': unknown link '7'; known links: 2, 3, 4, 5, 6"),
    ("shaper", 'kind = "cutting"\nname = "F2"\nforce = -5.0', "load 'F2': force must be > 0 N, not -5.0"),
    ("shaper", 'kind = "cutting"\nname = "F2"\nstart = 0.9\nend = 0.1',
     "load 'F2': start and end must satisfy 0 ≤ start < end ≤ 1, not 0.9 and 0.1"),
    ("shaper", 'kind = "cutting"\nname = "Fc"', "load 'Fc': duplicate load name"),
    ("four-bar", 'kind = "cutting"\nname = "Fc"',
     "load 'Fc': needs an output slider (output = a point on a guide); mechanism 'four-bar' has output link 3"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.09\nb2 = 0.02',
     "load 'P2': b1 + b2 = 0.11 m exceeds the stroke H = 0.1 m"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 0.0\nb1 = 0.01\nb2 = 0.0', "load 'P2': p_max must be > 0 N, not 0.0"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.0\nb2 = 0.0', "load 'P2': b1 must be > 0 m, not 0.0"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.01\nb2 = -0.02', "load 'P2': b2 must be ≥ 0 m, not -0.02"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.01\nb2 = 0.0\nharmonics = 2.5',
     "load 'P2': harmonics must be a whole number ≥ 0 (0 = the exact parabola), not 2.5"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.01', "load 'P2': missing b2"),
    ("slider-press", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.01\nb2 = 0.0\nextreme = "top"',
     "load 'P2': extreme must be 'lower', 'start' or 'end', not 'top'"),
    ("shaper", 'kind = "press"\nname = "P2"\np_max = 1.0\nb1 = 0.01\nb2 = 0.0',
     "load 'P2': the output moves horizontally, so it has no lower extreme; give extreme = 'start' or 'end'"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0]',
     "load 'T': x and values must have the same length (2 ≠ 1)"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 0.0]\nvalues = [1.0, 2.0]',
     "load 'T': x[1] = 0 is repeated at an end of the table; an x may be given twice, inside the table, to write a jump"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 2.0, 1.0]\nvalues = [1.0, 2.0, 3.0]',
     "load 'T': x must not decrease; x[2] = 1 < 2"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0, 1.0, 1.0, 2.0]\nvalues = [1.0, 2.0, 3.0, 4.0, 5.0]',
     "load 'T': x[3] = 1 is given a third time; an x may be given twice, inside the table, to write a jump"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 100.0, 100.00001, 360.0]\nvalues = [0.0, 0.0, 5.0, 5.0]',
     "load 'T': x[2] = 100.00001 is a near-vertical ramp from x[1] = 100; give the same x twice to write a jump"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, "a"]\nvalues = [1.0, 2.0]',
     "load 'T': x[1] must be a finite number, not 'a'"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0]\nvalues = [1.0]', "load 'T': x needs at least 2 values, not 1"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = 3\nvalues = [1.0]', "load 'T': x must be a list of numbers, not 3"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nvalues = [1.0]', "load 'T': missing x"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]\ndirection = "up"',
     "load 'T': direction must be 'guide' or 'against-motion', not 'up'"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]\ndirection = "guide"\nangle_deg = 3.0',
     "load 'T': give either direction or angle_deg, not both"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "S5"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]',
     "load 'T': link '5' slides on no guide; give angle_deg for a fixed direction"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]\nover = "time"',
     "load 'T': over must be 'crank' or 'output', not 'time'"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]\nstroke = "working"',
     "load 'T': stroke = 'working' needs over = 'output'"),
    ("shaper", 'kind = "table"\nname = "T"\npoint = "F"\nx = [0.0, 1.0]\nvalues = [1.0, 2.0]\nover = "output"\nstroke = "all"',
     "load 'T': stroke must be 'both', 'working' or 'return', not 'all'"),
    ("crank-slider", 'kind = "indicator"\nname = "Fg"\nbore = 0.0\ntravel = [0.0, 0.1]\npressure_away = [1.0, 2.0]',
     "load 'Fg': bore must be > 0 m, not 0.0"),
    ("crank-slider", 'kind = "indicator"\nname = "Fg"\nbore = 0.1\ntravel = [0.0, 0.1]\npressure_away = [1.0, 2.0]\nhead = "top"',
     "load 'Fg': head must be 'start' or 'end', not 'top'"),
    ("crank-slider", 'kind = "indicator"\nname = "Fg"\nbore = 0.1\ntravel = [-0.01, 0.1]\npressure_away = [1.0, 2.0]',
     "load 'Fg': travel must start at ≥ 0 m from the head, not -0.01"),
    ("crank-slider",
     'kind = "indicator"\nname = "Fg"\nbore = 0.1\ntravel = [0.0, 0.1]\npressure_away = [1.0, 2.0]\npressure_toward = [1.0]',
     "load 'Fg': travel and pressure_toward must have the same length (2 ≠ 1)"),
    ("crank-slider", 'kind = "indicator"\nname = "Fg"\nbore = 0.1\ntravel = [0.0, 0.1]', "load 'Fg': missing pressure_away"),
]


@pytest.mark.parametrize("mech, body, message", ERRORS, ids=[e[2][:60] for e in ERRORS])
def test_documented_load_errors(mech, body, message):
    m = _with_load(mech, body)
    with pytest.raises(velplan.MechanismError, match=f"^{re.escape(message)}$"):
        vf.parse_loads(m)


def test_load_that_is_not_a_table():
    import dataclasses

    m = dataclasses.replace(velplan.load("shaper"), loads=(5,))
    with pytest.raises(velplan.MechanismError, match=r"^load #1 must be a table, not 5$"):
        vf.parse_loads(m)


def test_centre_of_mass_must_be_a_point_of_its_link():
    m = velplan.parse(example_text("four-bar") + '\n[link.3]\nmass = 1.0\ncentre = "S2"\n', name="four-bar")
    kin = velplan.solve(m, [0.0])
    with pytest.raises(velplan.MechanismError,
                       match=r"^\[link\.3\] centre: point 'S2' is not a point of link '3'; points of link 3: S3, B, D$"):
        vf.gravity_actions(m, kin)
