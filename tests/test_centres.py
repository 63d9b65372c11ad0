"""Instant centres (issue 22): exact centres checked against the solver's velocities, the Kennedy
construction, velocities by centres, the CLI's JSON contract and its errors."""

from __future__ import annotations

import json
from functools import lru_cache

import numpy as np
import pytest

import velplan
from velplan.analysis.centres import instant_centres, link_pairs
from velplan.analysis.solver import length_scale
from velplan.cli import main
from velplan.mechanism.loader import catalogue_names, example_names
from velplan.mechanism.structure import material_points
from velplan.plans import Drafting
from velplan.plans.centres import (
    CentreStep, construct_centres, sentence, velocities_by_centres)
from velplan.plans.text import LANGS

NAMES = list(example_names()) + list(catalogue_names())
N = 12


@lru_cache(maxsize=None)
def solved(name: str):
    """The mechanism solved by `velplan.solve` at 12 positions from 7° (ω1 of its file)."""
    mech = velplan.load(name)
    phi = np.radians(7.0) + np.arange(N) * 2 * np.pi / N
    return velplan.solve(mech, phi, omega1=mech.crank.omega)


@lru_cache(maxsize=None)
def standard(name: str):
    """The study's 12 standard positions (the first is an extreme position of the output)."""
    return velplan.Study(name).kinematics


def _z(xy) -> complex:
    return complex(xy[0], xy[1])


def fields(kin, i: int, derivative: bool = False) -> dict:
    """Link → function X ↦ velocity of link's point at X (or its time derivative), built from
    the solver's point velocities at the first named point of each link (not the module's)."""
    out = {"0": lambda x: 0j}
    for link, names in material_points(kin.mechanism).items():
        m = names[0]
        p = _z(kin.position(m)[i])
        v, w = _z(kin.velocity(m)[i]), kin.omega(link)[i]
        if derivative:
            a, e = _z(kin.acceleration(m)[i]), kin.epsilon(link)[i]
            out[link] = lambda x, a=a, v=v, w=w, e=e, p=p: a - 1j * w * v + 1j * e * (x - p)
        else:
            out[link] = lambda x, v=v, w=w, p=p: v + 1j * w * (x - p)
    return out


def _scale(kin, i: int, derivative: bool) -> float:
    """Velocity (or its derivative's) scale of position i: max |V| + max |ω|·L."""
    L = length_scale(kin.mechanism)
    if derivative:
        return float(np.max(np.hypot(*kin.accelerations[i].T)) + np.max(np.abs(kin.epsilons[i])) * L
                     + np.max(np.abs(kin.omegas[i])) ** 2 * L)
    return float(np.max(np.hypot(*kin.velocities[i].T)) + np.max(np.abs(kin.omegas[i])) * L)


def _check_exact(kin) -> None:
    c = instant_centres(kin)
    names = ["0", *kin.mechanism.links]
    assert len(c.pairs) == len(names) * (len(names) - 1) // 2 == len(set(map(frozenset, c.pairs)))
    for i in range(len(kin)):
        if not kin.valid[i]:
            continue
        mech_points = [_z(xy) for xy in kin.positions[i]]
        for k, (a, b) in enumerate(c.pairs):
            lim = bool(c.limit[i, k])
            f = fields(kin, i, derivative=lim)
            tol = 1e-9 * _scale(kin, i, lim)
            p, d = c.points[i, k], c.directions[i, k]
            assert np.isfinite(p) != np.isfinite(d), (a, b, i)
            if np.isfinite(p):  # the two fields agree at P, to 1e-9 of the size (× the rate scale)
                assert abs(f[a](p) - f[b](p)) <= tol, (kin.mechanism.name, i, a, b)
            else:  # the direction at infinity is ⊥ the relative velocity of every point
                assert abs(abs(d) - 1) < 1e-12
                for x in mech_points:
                    w = f[a](x) - f[b](x)
                    assert abs(d.real * w.real + d.imag * w.imag) <= tol, (kin.mechanism.name, i, a, b)


@pytest.mark.parametrize("name", NAMES)
def test_exact_centres_are_where_the_velocity_fields_agree(name):
    _check_exact(solved(name))
    _check_exact(standard(name))


def test_a_centre_at_infinity_is_a_direction_never_a_huge_point():
    kin = solved("crank-slider")
    c = instant_centres(kin)
    k = c.column("0", "3")  # the slider on the frame
    assert c.infinite[:, k].all() and np.allclose(np.abs(c.directions[:, k]), 1)
    assert np.all(np.abs(c.directions[:, k].imag) == pytest.approx(1))  # ⊥ the horizontal guide
    finite = c.points[np.isfinite(c.points)]
    assert np.max(np.abs(finite)) < 1e9 * c.size


@pytest.mark.parametrize("name", NAMES)
def test_the_construction_reaches_every_centre_or_says_why(name):
    for kin in (solved(name), standard(name)):
        c = instant_centres(kin)
        L = length_scale(kin.mechanism)
        for i in range(len(kin)):
            con = construct_centres(kin, i + 1)
            assert len(con.steps) == len(c.pairs)
            assert [len(s.found) + len(s.remaining) for s in con.steps] == [len(c.pairs)] * len(c.pairs)
            for k, (a, b) in enumerate(c.pairs):
                s = con.centre(a, b)
                if s is None:  # unreached: a reason, in every language
                    (u,) = [t for t in con.unreached if set(t.pair) == {a, b}]
                    assert u.reason in ("isolated", "coincident")
                    assert all(sentence(u, con, lang) for lang in LANGS)
                    continue
                if s.how == "kennedy":
                    assert len(s.via) == 2 and len(s.lines) == 2 and 0 <= s.condition <= 1
                if s.infinite:
                    d = c.directions[i, k]
                    assert abs(d.real * s.direction.imag - d.imag * s.direction.real) < 1e-8, (i, a, b)
                else:
                    p = c.points[i, k]
                    assert abs(s.point - p) <= 1e-8 * L * (1 + abs(p) / L) ** 2, (i, a, b)
            assert len(con.describe("zh")) == len(con.steps)
        if kin is solved(name):  # away from the extreme positions nothing is singular
            assert all(not construct_centres(kin, i + 1).unreached for i in range(len(kin)))


def test_unreached_centres_are_stated():
    kin = standard("press")  # position 1: the rocker and the punch at rest, crank and rod in line
    con = construct_centres(kin, 1)
    assert {s.pair for s in con.unreached} == {("1", "3"), ("4", "5")}  # smaller number first
    assert all("Kennedy" in sentence(s, con, "en") and "Кеннеди" in sentence(s, con, "ru")
               for s in con.unreached)
    isolated = CentreStep(1, ("3", "4"), "unreached", reason="isolated")
    assert "Assur" in sentence(isolated, con, "en") and "Ассура" in sentence(isolated, con, "ru")


@pytest.mark.parametrize("name", NAMES)
def test_velocities_by_centres_match_the_analytic_ones(name):
    for kin in (solved(name), standard(name)):
        L = length_scale(kin.mechanism)
        for i in range(len(kin)):
            by = velocities_by_centres(construct_centres(kin, i + 1))
            vs = _scale(kin, i, False)
            for p, v in by.velocities.items():
                assert abs(v - _z(kin.velocity(p)[i])) <= 1e-9 * vs, (i, p)
            for link, w in by.omegas.items():
                assert abs(w - kin.omega(link)[i]) * L <= 1e-9 * vs, (i, link)


@pytest.mark.parametrize("name", ["shaper", "press", "four-bar", "whitworth", "stephenson-six-bar", "jaw-crusher"])
def test_drafted_centres_and_velocities_are_within_the_precision(name):
    kin = solved(name)
    c = instant_centres(kin)
    L = length_scale(kin.mechanism)
    d = Drafting(0.5, 0.5)
    for i in range(len(kin)):
        con = construct_centres(kin, i + 1, drafting=d)
        assert con.mu_l > 0
        for s in con.steps:
            if s.how != "kennedy" or s.infinite or s.bound_m > 0.2 * L:
                continue
            p = c.points[i, c.column(*s.pair)]
            assert np.isfinite(p) and abs(s.point - p) <= s.bound_m, (i, s.pair)
        if all(s.condition >= 0.1 for s in con.steps if s.how == "kennedy"):
            by = velocities_by_centres(con)
            vs = float(np.max(np.hypot(*kin.velocities[i].T)))
            for p, v in by.velocities.items():
                assert abs(v - _z(kin.velocity(p)[i])) <= 0.1 * vs, (i, p)


def test_json_contract(capsys):
    assert main(["centres", "shaper", "--angles", "30,100", "--format", "json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert set(doc) == {"mechanism", "positions"} and doc["mechanism"] == "shaper"
    assert [p["phi_deg"] for p in doc["positions"]] == [pytest.approx(30), pytest.approx(100)]
    mech = velplan.load("shaper")
    pairs = {frozenset(p) for p in link_pairs(mech)}
    for pos in doc["positions"]:
        assert set(pos) == {"phi_deg", "centres"}
        got = [frozenset(c["links"]) for c in pos["centres"]]
        assert len(got) == len(set(got)) == len(pairs) and set(got) == pairs
        for c in pos["centres"]:
            assert all(isinstance(x, str) for x in c["links"])
            if "direction" in c:
                assert set(c) == {"links", "direction"} and np.hypot(*c["direction"]) == pytest.approx(1)
            else:
                assert set(c) == {"links", "x", "y"} and all(isinstance(c[k], float) for k in "xy")
    frame = [c for c in doc["positions"][0]["centres"] if c["links"] == ["0", "6"]]
    assert frame and "direction" in frame[0]  # the ram slides on the frame


def test_table_and_svg(tmp_path, capsys):
    svg = tmp_path / "c.svg"
    assert main(["centres", "four-bar", "--position", "2", "--steps", "--lang", "uk", "--svg", str(svg)]) == 0
    out = capsys.readouterr().out
    assert "P13" in out and "Кеннеді через" in out and "Аронгольда" in out and "ω3" in out  # one language
    assert svg.read_text("utf-8").startswith("<?xml")
    assert main(["centres", "press", "--angles", "0", "--mode", "drafting"]) == 0
    assert "not reached: P13" in capsys.readouterr().out


@pytest.mark.parametrize("argv, message", [
    (["centres", "shaper", "--position", "13"], "outside 1…12"),
    (["centres", "shaper", "--angles", "x"], "not a number"),
    (["centres", "no-such-mechanism"], "no-such-mechanism"),
    (["centres", "shaper", "--position", "1", "--angles", "30"], "not allowed with"),
    (["centres", "shaper", "--scale-l", "-1"], "positive"),
    (["centres", "shaper", "--mode", "drafting", "--precision", "0"], "precision"),
])
def test_cli_errors_are_one_line(argv, message, capsys):
    try:
        status = main(argv)
    except SystemExit as exc:  # argparse's own errors
        status = exc.code
    assert status == 2
    err = capsys.readouterr().err
    assert err.startswith("velplan: error: ") and err.count("\n") == 1 and message in err


def test_svg_into_a_missing_directory_writes_nothing(tmp_path, capsys):
    target = tmp_path / "no" / "c.svg"
    assert main(["centres", "shaper", "--position", "1", "--svg", str(target)]) == 2
    assert capsys.readouterr().err.count("\n") == 1 and not target.exists()


def test_steps_series_of_the_centres(tmp_path, capsys):
    out = tmp_path / "steps"
    assert main(["steps", "four-bar", "--position", "2", "--kind", "centres", "--lang", "ru", "-o", str(out)]) == 0
    files = sorted(p.name for p in out.iterdir())
    assert files == [f"step-c-{k:02d}.svg" for k in range(1, 7)]
    text = (out / "step-c-05.svg").read_text("utf-8")
    assert "Кеннеди" in text or "Аронгольда" in text


def test_centres_on_the_kinematic_sheet(tmp_path, capsys):
    from velplan.sheets.kinematic import build_sheet

    study = velplan.Study("shaper")
    sheet = build_sheet(study, lang="en", centres=(4,), table=False, diagrams=False, data=False)
    marks = [p for p in sheet.scene if p.layer == "centres"]
    assert marks and any(getattr(p, "text", "").startswith("P₂₄") for p in marks)
    placed = sheet.views["mechanism"]
    x0, y0, x1, y1 = placed.bounds
    for p in marks:
        x, y = getattr(p, "centre", getattr(p, "position", None))
        assert x0 <= x <= x1 and y0 <= y <= y1
    assert main(["sheet", "shaper", "--centres", "13", "-o", str(tmp_path / "s.svg")]) == 2
    assert "outside 1…12" in capsys.readouterr().err and not (tmp_path / "s.svg").exists()


def test_the_html_page_marks_the_centres_when_asked():
    from velplan.html import Page

    study = velplan.Study("shaper", n=12)
    assert "P₂₄" in Page(study, lang="en", centres=True).html
    assert "P₂₄" not in Page(study, lang="en").html


@pytest.mark.parametrize("suffix", [".svg", ".png"])
def test_output_named_as_a_drawing_gets_the_figure_and_the_table_is_printed(tmp_path, capsys, suffix):
    target = tmp_path / f"c{suffix}"
    assert main(["centres", "four-bar", "--position", "2", "--lang", "ru", "-o", str(target)]) == 0
    assert "P13" in capsys.readouterr().out  # the table still comes, on standard output
    svg = target.with_suffix(".svg").read_text("utf-8")
    assert svg.startswith("<?xml") and svg.rstrip().endswith("</svg>") and "Кругов" in svg  # the circle diagram
    if suffix == ".png":
        assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    text = tmp_path / "c.txt"
    assert main(["centres", "four-bar", "--position", "2", "-o", str(text)]) == 0
    assert "P13" in text.read_text("utf-8")
