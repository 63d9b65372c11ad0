"""The plans of class III triads by Assur's special point: exact against the analytic solver,
drafted within their stated precision, narrated in four languages, parallel lead lines reported,
and the CLI commands that draw them."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

import velplan
from velplan.analysis.solver import special_pair
from velplan.cli import main
from velplan.errors import SingularPositionError
from velplan.mechanism.model import GROUND
from velplan.plans import Drafting, Plan
from velplan.plans.steps import Intersect, LayOff, Line, Perpendicular, Similar

CATALOGUE = Path(velplan.__file__).parent / "catalogue"
TRIADS = sorted(p.stem for p in CATALOGUE.glob("*.toml") if re.search(r'^kind\s*=\s*"triad"', p.read_text(), re.M))

# the crank-driven plate of triad-rocker with its numbers, a rod lead 2 from the crank, a rocker
# lead 4 about E, and a third lead {lead5}
_HEAD = """
name = "test-triad"
output = {{ point = "D" }}
[ground]
O1 = [0.0, 0.0]
E = [{E}]
F = [{F}]
H = [0.0, 0.124]
[crank]
link = "1"
pivot = "O1"
tip = "A"
length = 0.078
rpm = 90.0
[[group]]
kind = "triad"
base = "3"
joints = ["B", "C", "D"]
sides = [0.241, 0.205, 0.311]
side = -1
{pair}
leads = [
  {{ link = "2", joint = "A", length = 0.347 }},
  {{ link = "4", joint = "E", length = 0.347 }},
  {lead5},
]
assembly = {{ phi_deg = 90, B = [0.185, 0.372], C = [0.421, 0.323], D = [0.373, 0.124] }}
"""
ROD5 = '{ link = "5", joint = "F", length = 0.290 }'
BLOCK_FIXED = '{ link = "5", guide = { link = "0", through = "H", angle_deg = 0.0 }, coincident = "D0" }'
# the guide through A on the crank, along A → D at φ = 90°: assembled from 87.5° to 100°
BLOCK_MOVING = ('{ link = "5", guide = { link = "1", through = "A", angle_deg = %r }, coincident = "D1" }'
                % (math.degrees(math.atan2(0.124 - 0.078, 0.373)) - 90))


def _triad(lead5: str = ROD5, pair=None, E="0.574, 0.011", F="0.131, -0.035"):
    return velplan.parse(_HEAD.format(E=E, F=F, lead5=lead5, pair=f"pair = {list(pair)}" if pair else ""))


TWELVE = np.linspace(0.0, 2 * np.pi, 13)[:-1]
NEAR_90 = np.radians(np.linspace(88.0, 99.5, 12))
PAIRS = [(1, 2), (1, 3), (2, 3)]
CASES = ([pytest.param(lambda n=n: velplan.load(n), None, id=n) for n in TRIADS]
         + [pytest.param(lambda p=p: _triad(BLOCK_FIXED, p), TWELVE, id=f"block-fixed-guide-pair{p}") for p in PAIRS]
         + [pytest.param(lambda p=p: _triad(BLOCK_MOVING, p), NEAR_90, id=f"block-moving-guide-pair{p}") for p in PAIRS]
         + [pytest.param(lambda p=p: _triad(BLOCK_MOVING.replace(', coincident = "D1"', ""), p), NEAR_90,
                         id=f"block-moving-guide-unnamed-pair{p}") for p in PAIRS[:2]])


def _solve(make, phi):
    mech = make()
    kin = velplan.solve(mech, velplan.positions(mech, 12) if phi is None else phi)
    assert kin.valid.all()
    return mech, kin


def test_the_catalogue_has_a_triad():
    assert "triad-rocker" in TRIADS


@pytest.mark.parametrize("make, phi", CASES)
def test_exact_plan_equals_analytic(make, phi):
    """Every point's image (the special point's too) and every link's ω, ε equal the solver's
    to 1e-12 of the largest at each position."""
    mech, kin = _solve(make, phi)
    plan = Plan.of(mech)
    triads = [g for g in mech.groups if g.kind == "triad"]
    ground_guides = {lead.coincident for g in triads for lead in g.leads if lead.slider and lead.guide.link == GROUND}
    for kind, ref in (("velocity", kin.velocities), ("acceleration", kin.accelerations)):
        res = plan.evaluate(kin, kind=kind)
        assert not res.refused.any()  # flagged ones too: still exact, only less well conditioned
        expected = set(kin.point_index) - set(dict(mech.ground)) - ground_guides
        assert expected <= set(res.vectors) and {g.special_name for g in triads} <= set(res.vectors)
        size = np.hypot(ref[:, :, 0], ref[:, :, 1]).max(axis=1)
        for p, v in res.vectors.items():
            err = np.hypot(*(v - ref[:, kin.point_index[p]]).T) / size
            assert err.max() < 1e-12, (kind, p, err.max())
        rates = res.omegas if kind == "velocity" else res.epsilons
        exact = {k: (kin.omega(k) if kind == "velocity" else kin.epsilon(k)) for k in rates}
        assert set(kin.link_index) <= set(rates)  # every link is read
        largest = np.max([np.abs(e) for e in exact.values()], axis=0)
        for k, w in rates.items():
            assert (np.abs(w - exact[k]) <= 1e-12 * largest).all(), (kind, k)


def test_moving_guide_lead_has_its_coriolis_component():
    mech, kin = _solve(lambda: _triad(BLOCK_MOVING, (1, 3)), NEAR_90)  # the block in the special pair
    res = Plan.of(mech).evaluate(kin, kind="acceleration")
    _, value = res.components["aᵏ_D"]
    v_rel = kin.slide("P:5/1")[:, 1]
    assert np.allclose(value, 2 * np.abs(kin.omega("1") * v_rel), rtol=1e-12, atol=1e-12 * value.max())


def _chain_bound(res, point: str) -> np.ndarray:
    """The precision a drafted plan states for a point's image, mm: the error bounds of the
    intersections it is built on, plus half a step of length and of angle (rounded to 0.5 mm and
    0.5°; counted here as a whole step) for each vector laid off or placed by similarity."""
    k = res.kind[0]
    bound = np.zeros(len(res.index))
    for s in res.plan.needed([res.plan.images[k][point]]):
        if not s.target.startswith(k + ":"):
            continue
        if isinstance(s, Intersect):
            bound += res.ctx.bounds[s.target]
        elif isinstance(s, (LayOff, Similar)):
            length = np.abs(res.values[s.target] - res.values[s.inputs[0]])
            bound += np.hypot(0.5, np.radians(0.5) * length)
    return bound


@pytest.mark.parametrize("make", [pytest.param(lambda n=n: velplan.load(n), id=n) for n in TRIADS]
                         + [pytest.param(lambda: _triad(BLOCK_FIXED), id="block-fixed-guide")])
def test_drafted_plan_is_within_its_stated_precision(make):
    mech, kin = _solve(make, TWELVE)
    plan = Plan.of(mech)
    for kind in ("velocity", "acceleration"):
        exact = plan.evaluate(kin, kind=kind)
        mu_a = exact.scales["a"] if kind == "acceleration" else None
        drafted = plan.evaluate(kin, kind=kind, drafting=Drafting(0.5, 0.5), scale_v=exact.scales["v"], scale_a=mu_a)
        moved = 0.0
        for p, v in exact.vectors.items():
            dev_mm = np.hypot(*(drafted.vectors[p] - v).T) / exact.scale
            assert (dev_mm <= _chain_bound(drafted, p) + 1e-9).all(), (kind, p)
            moved = max(moved, float(dev_mm.max()))
        assert moved > 0.05  # the drafting did change the plan


def _velocity(name="triad-rocker", n=3):
    mech = velplan.load(name)
    kin = velplan.solve(mech, velplan.positions(mech, 12)[n - 1:n])
    return mech, kin, Plan.of(mech)


def test_the_velocity_plan_starts_with_the_special_point():
    mech, kin, plan = _velocity()
    g = mech.groups[0]
    i, j = special_pair(mech, g)
    steps = [s for s in plan.steps if s.target.startswith("v:")]
    first = next(n for n, s in enumerate(steps) if isinstance(s, Line))
    l1, l2, meet = steps[first:first + 3]
    for line, k in zip((l1, l2), (i, j)):  # the perpendiculars to the two leads, through their outer joints
        lead = g.leads[k]
        assert line.direction == Perpendicular(g.joints[k], lead.joint)
        assert line.through == plan.images["v"][lead.joint]
    assert isinstance(meet, Intersect) and meet.lines == (l1.target, l2.target)
    assert meet.target == plan.images["v"][g.special_name]
    # E and F are on the frame: both lines pass through the pole, K3 is link 3's instant centre
    res = plan.evaluate(kin, kind="velocity")
    assert np.abs(res.vector(g.special_name)).max() < 1e-12


@pytest.mark.parametrize("kind", ["velocity", "acceleration"])
def test_sentences_in_four_languages_name_the_special_point(kind):
    mech, kin, plan = _velocity()
    res = plan.evaluate(kin, kind=kind)
    en, ru, uk, zh = (res.describe(lang=lang) for lang in ("en", "ru", "uk", "zh"))
    assert len(en) == len(ru) == len(uk) == len(zh) == len([s for s in res.steps if s.target.startswith(kind[0])])
    for words in zip(en, ru, uk, zh):
        assert len(set(words)) == 4 and all(words)
    head = {"en": "Assur's special point K3 of link 3: the crossing of the lines of leads 4 and 5",
            "ru": "Особая точка Ассура K3 звена 3: пересечение линий поводков 4 и 5",
            "uk": "Особлива точка Ассура K3 ланки 3: перетин ліній повідців 4 і 5",
            "zh": "阿苏尔特殊点 K3（构件 3）：杆 4 与杆 5 所在直线的交点"}
    for lang, said in zip(head, (en, ru, uk, zh)):
        assert sum(head[lang] in x for x in said) == 1, lang
    first = next(x for x in en if "Assur's special point" in x)
    if kind == "velocity":
        assert "V_K3 = V_E + V_CE + V_K3C" in first and "Through p draw a line ⊥ CE" in first
        assert any("k3 is the image of Assur's special point K3" in x and "instant centre" in x for x in en)
        assert any(x.startswith("The joint B of link 3 and lead 2: V_B = V_K3 + V_BK3 = V_A + V_BA.") for x in en)
    else:
        assert "a_K3 = a_E + aⁿ_CE + aᵗ_CE + aⁿ_K3C + aᵗ_K3C" in first and "(aⁿ_CE = " in first
        assert any("(aⁿ_K3C = " in x for x in en)  # ω3²·|K3C|, from K3 towards C
    assert "," in ru[1]  # decimal commas


def test_parallel_lead_lines_are_reported():
    """E under C and F under D: the rockers 4 and 5 stand parallel near φ = 90°. With the pair
    (4, 5) forced the special point runs off to infinity there: the intersection's condition is
    the sine of the angle of the two lead lines, flagged, and refused at round-off."""
    mech = _triad(pair=(2, 3), E="0.421, -0.024", F="0.373, -0.166")
    auto = _triad(E="0.421, -0.024", F="0.373, -0.166")
    assert special_pair(auto, auto.groups[0]) != (1, 2)  # left to itself it takes another pair

    def sine(phi):
        k = velplan.solve(mech, [phi])
        C, E, D, F = (complex(*k.positions[0, k.point_index[n]]) for n in "CEDF")
        u, w = C - E, D - F
        return (u.real * w.imag - u.imag * w.real) / abs(u) / abs(w)

    lo, hi = np.radians(40.0), np.radians(46.0)
    assert sine(lo) * sine(hi) < 0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sine(lo) * sine(mid) > 0 else (lo, mid)
    phi = np.array([lo, lo + 1e-4, lo + 0.05])
    kin = velplan.solve(mech, phi)
    res = Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.01)
    independent = np.abs([sine(x) for x in phi])
    assert np.allclose(res.conditions["k3"], independent, rtol=1e-6, atol=1e-14)
    flagged = {f.index: f for f in res.flags if f.image == "k3"}
    assert set(flagged) == {0, 1, 2} and [f.refused for f in flagged.values()] == [True, False, False]
    assert all(f.bound_mm > 0 for f in flagged.values())
    assert np.isnan(res.vector("B")[0]).all()
    ok = ~res.refused
    assert np.allclose(res.vector("B")[ok], kin.velocity("B")[ok], atol=1e-12)
    with pytest.raises(SingularPositionError, match=r"the lines meeting at k3 are nearly parallel at crank angle"):
        Plan.of(mech).evaluate(kin, kind="velocity", scale_v=0.01, on_failure="raise")


def test_cli_draws_the_triad(tmp_path, capsys):
    assert main(["plan", "triad-rocker", "--position", "3", "--lang", "ru"]) == 0
    assert "Особая точка Ассура K₃ звена 3" in capsys.readouterr().out
    assert main(["plan", "triad-rocker", "--position", "3", "--kind", "acceleration", "--format", "json"]) == 0
    assert main(["steps", "triad-rocker", "--position", "3", "-o", str(tmp_path / "steps")]) == 0
    assert len(list((tmp_path / "steps").glob("step-v-*.svg"))) >= 8
    assert main(["compare", "triad-rocker", "--mode", "drafting"]) == 0
    out = capsys.readouterr().out
    assert "V_K3" in out and "a_K3" in out
    assert main(["html", "triad-rocker", "--positions", "12", "-o", str(tmp_path / "t.html")]) == 0
    assert "Assur" in (tmp_path / "t.html").read_text()
