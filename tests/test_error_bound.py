"""The stated round-off bound (`Kinematics.error_bound`) holds against the 50-digit oracle for
mechanisms whose lengths spread over four decades and that sit up to 1e9 m from the origin."""

import math

import numpy as np
from hypothesis import given, settings, strategies as st

import velplan
from tests import oracle
from velplan.analysis.solver import length_scale


def _mechanism(kind: str, short: float, decades: float, far: float, bearing: float, omega: float):
    """A four-bar (RRR) or a crank-slider (RRP) with its crank ``10**-decades`` of its largest
    length, its pivot ``far`` m from the origin."""
    x0, y0 = far * math.cos(bearing), far * math.sin(bearing)
    r = short
    big = short * 10**decades
    head = f"""
name = "spread"
[ground]
O = [{x0!r}, {y0!r}]
{'D = [' + repr(x0 + big) + ', ' + repr(y0) + ']' if kind == 'RRR' else ''}
[crank]
link = "1"
pivot = "O"
tip = "A"
length = {r!r}
omega = {omega!r}
"""
    if kind == "RRR":
        group = f"""
[[group]]
kind = "RRR"
name = "2-3"
links = ["2", "3"]
joints = ["A", "D"]
point = "B"
lengths = [{0.6 * big!r}, {0.65 * big!r}]
"""
    else:
        group = f"""
[[group]]
kind = "RRP"
name = "2-3"
links = ["2", "3"]
joint = "A"
point = "B"
length = {big!r}
guide = {{ link = "0", through = "O", angle_deg = 0.0, offset = {0.3 * r!r} }}
"""
    return velplan.parse(head + group)


@settings(max_examples=25, deadline=None, derandomize=True)
@given(kind=st.sampled_from(["RRR", "RRP"]), short=st.floats(1e-3, 1.0), decades=st.floats(0.7, 4.0),
       far_exp=st.floats(0.0, 9.0), bearing=st.floats(-math.pi, math.pi), phi=st.floats(0.0, 2 * math.pi),
       omega=st.floats(0.5, 50.0))
def test_bound_holds_against_mpmath(kind, short, decades, far_exp, bearing, phi, omega):
    mech = _mechanism(kind, short, decades, 10**far_exp, bearing, omega)
    kin = velplan.solve(mech, [phi])
    assert kin.valid[0]
    L = length_scale(mech)
    pts, _ = oracle.derivatives(mech, phi, omega)
    bound_x, bound_v, bound_a = (float(kin.error_bound(q)[0]) for q in ("position", "velocity", "acceleration"))
    for name, (x, y, vx, vy, ax, ay) in pts.items():
        j = kin.point_index[name]
        ex = max(abs(float(kin.positions[0, j, k] - float(v))) for k, v in enumerate((x, y)))
        ev = max(abs(float(kin.velocities[0, j, k]) - float(v)) for k, v in enumerate((vx, vy)))
        ea = max(abs(float(kin.accelerations[0, j, k]) - float(v)) for k, v in enumerate((ax, ay)))
        assert ex <= bound_x * L, (name, ex, bound_x * L)
        assert ev <= bound_v * omega * L, (name, ev, bound_v * omega * L)
        assert ea <= bound_a * omega**2 * L, (name, ea, bound_a * omega**2 * L)
