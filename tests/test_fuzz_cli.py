"""Issue 35 (items 2–5, 8, 9) and 36 (item 2): every count a command takes is bounded, a crank
at rest is refused where the file is read, design keys pass the loader's checks through one
table of keys, and bad or odd options to ``centres``, ``note``, ``sweep`` and ``batch`` end in
one line: exit status 2, no traceback, no Python or numpy warning, no file left behind."""

import json
import math
import random
import re
import tomllib
import warnings
from importlib import resources

import numpy as np
import pytest

from velplan import batch
from velplan.cli import main
from velplan.mechanism.loader import catalogue_names, example_names, load, parse
from velplan.study import Study
from velplan.sweep.merit import figures


def _run(capsys, *argv):
    """(exit status, stdout, stderr, warnings raised) of one in-process command."""
    with warnings.catch_warnings(record=True) as caught, np.errstate(all="warn"):
        warnings.simplefilter("always")
        try:
            rc = main([str(a) for a in argv])
        except SystemExit as exc:  # argparse's own refusals
            rc = exc.code
    out, err = capsys.readouterr()
    return rc, out, err, [str(w.message) for w in caught]


def _refused(capsys, *argv, words=()):
    """Run a command that must be refused: exit 2, one line naming ``words``, nothing on
    stdout, no traceback and no warning. Returns the line."""
    rc, out, err, caught = _run(capsys, *argv)
    assert rc == 2, (argv, rc, err)
    assert err.count("\n") == 1 and err.startswith("velplan: error: "), err
    assert "Traceback" not in err and "Warning" not in err and not caught, (err, caught)
    assert out == "", out
    for w in words:
        assert w in err, (w, err)
    return err


def _text(name: str) -> str:
    package = "velplan.examples" if name in example_names() else "velplan.catalogue"
    return resources.files(package).joinpath(f"{name}.toml").read_text("utf-8")


# ---- 35.2: every count bounded, the refusal naming the option and the cap ----------------------


MANY_ANGLES = ",".join(str(i) for i in range(20_000))


@pytest.mark.parametrize("argv, words", [
    (["centres", "triad-press", "--positions", "100000000"], ["--positions 100000000", "at most 360"]),
    (["centres", "triad-press", "--angles", MANY_ANGLES], ["--angles", "20000 angles", "at most 360"]),
    (["analyze", "shaper", "--angles", MANY_ANGLES], ["--angles", "at most 360"]),
    (["note", "triad-press", "--positions", "1000000"], ["--positions 1000000", "at most 72"]),
    (["sweep", "four-bar", "--tolerance", "0.1mm", "--samples", "1000000000000"], ["--samples", "at most 1000000"]),
    (["sweep", "four-bar", "--vary", "crank.length=0.1,0.11", "--positions", "100000000"],
     ["--positions 100000000", "at most 36000"]),
    (["sweep", "four-bar", "--vary", "crank.length=0.1:0.2:100000000000"], ["100000000000 values", "at most"]),
    (["batch", "--random", "100000000", "--base", "shaper", "--seed", "s", "--require", "K>=1.0"],
     ["--random 100000000", "at most 10000"]),
    (["batch", "--random", "2", "--base", "shaper", "--seed", "s", "--students", ",".join(map(str, range(20_000)))],
     ["--students: 20000 ids", "at most 10000"]),
    (["sweep", "four-bar", "--vary", "crank.length=0.1:0.2:1000000", "--jobs", "1000000"], ["--jobs 1000000", "at most 256"]),
    (["batch", "--random", "2", "--base", "shaper", "--seed", "s", "--jobs", "100000"], ["--jobs 100000", "at most 256"]),
])
def test_every_count_is_bounded(tmp_path, capsys, argv, words):
    out = tmp_path / "out"
    extra = ["-o", str(out) + (".md" if argv[0] == "note" else "")]
    _refused(capsys, *argv, *extra, words=words)
    assert not list(tmp_path.iterdir())


def test_a_sweep_at_many_angles_is_solved_in_smaller_chunks():
    from velplan.sweep.run import CHUNK, chunk_size

    assert chunk_size("numpy", 360) == CHUNK["numpy"] and chunk_size("numpy", 36) == CHUNK["numpy"]
    assert chunk_size("numpy", 36_000) * 36_000 <= CHUNK["numpy"] * 360 and chunk_size("numpy", 10**8) == 1


# ---- 35.3: a crank at rest is refused where the file is read -----------------------------------


@pytest.fixture
def at_rest(tmp_path):
    text = _text("four-bar")
    text = re.sub(r"(?m)^(rpm|omega)\s*=.*$", r"\1 = 0", text, count=1)
    path = tmp_path / "rest.toml"
    path.write_text(text, "utf-8")
    return path


@pytest.mark.parametrize("argv", [
    ["info"], ["centres", "--format", "json"], ["analyze"], ["forces", "--format", "json"],
    ["forces", "--format", "csv"], ["analyze", "--format", "json"], ["sheet", "-o", "{dir}/s.svg"],
])
def test_a_crank_at_rest_is_refused_by_every_command(tmp_path, capsys, at_rest, argv):
    argv = [a.replace("{dir}", str(tmp_path / "o")) for a in argv]
    (tmp_path / "o").mkdir()
    _refused(capsys, argv[0], at_rest, *argv[1:], words=["= 0", "the crank must turn"])
    assert not list((tmp_path / "o").iterdir())


def test_a_speed_of_zero_in_a_sweep_is_refused_as_a_speed(capsys):
    err = _refused(capsys, "sweep", "four-bar", "--vary", "crank.rpm=0,60", words=["crank.rpm = 0", "variant 1"])
    assert "stroke" not in err and "reverse" not in err


def test_a_speed_below_the_smallest_is_refused_in_the_file():
    with pytest.raises(Exception, match="crank omega = 1e-12: the crank must turn"):
        parse(re.sub(r"(?m)^(rpm|omega)\s*=.*$", "omega = 1e-12", _text("four-bar"), count=1), name="slow")


# ---- 35.4 and 36.2: one table of keys, the loader's checks for every value ---------------------


@pytest.mark.parametrize("vary, words", [
    ("crank.length=1e300:1e301:2", ["crank.length = 1e+300", "out of range", "variant 1"]),
    ("crank.length=inf:inf:2", ["values must be finite"]),
    ("crank.length=nan,0.1", ["values must be finite"]),
    ("crank.length=1e-12,0.1", ["crank.length = 1e-12", "length ≥ 1e-09 m"]),
    ("group.2-3.lengths.0=0.1,-0.2", ["group.2-3.lengths.0 = -0.2", "variant 2"]),
    ("ground.D.0=1e10,0", ["ground.D.0 = 1e+10", "out of range"]),
    ("group.2-3.branch=1,0", ["must be +1 or -1"]),
    ("link.9.mass=1,2", ["the base has no [link.9]"]),
    ("group.2-3.sides.0=1,2", ["group 2-3 (RRR) has no 'sides.0'"]),
])
def test_design_values_pass_the_loaders_checks(capsys, vary, words):
    _refused(capsys, "sweep", "four-bar", "--vary", vary, "--positions", "36", words=words)


def test_the_same_key_twice_is_refused(capsys):
    _refused(capsys, "sweep", "four-bar", "--vary", "crank.length=0.1", "--vary", "crank.length=0.11",
             words=["--vary crank.length is given twice"])


def _numeric_leaves(node, trail=()):
    """(path, number) of every number of a parsed mechanism file."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _numeric_leaves(v, trail + (str(k),))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _numeric_leaves(v, trail + (i,))
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield trail, float(node)


def _dotted(data: dict, mech, trail: tuple) -> str | None:
    """The dotted key of a number of the file: list entries by their names (groups, points,
    loads), by index otherwise; None for the lead numbers of a triad's ``pair``."""
    head, rest = trail[0], list(trail[1:])
    if head in ("group", "point", "load"):
        i = rest.pop(0)
        name = mech.groups[i].name if head == "group" else data[head][i]["name"]
        rest = [name] + rest
    if head == "group" and rest[1] == "pair":
        return None
    return ".".join(str(x) for x in [head] + rest)


@pytest.mark.parametrize("name", sorted(example_names() + catalogue_names()))
def test_every_number_of_every_file_is_a_key(name):
    """Each number a bundled file writes is read back by its dotted key, in the file's unit."""
    from velplan.mechanism import keys

    data = tomllib.loads(_text(name))
    mech = load(name)
    seen = 0
    for trail, number in _numeric_leaves(data):
        key = _dotted(data, mech, trail)
        if key is None:
            continue
        assert keys.value(mech, key) == pytest.approx(number, rel=1e-12, abs=1e-12), key
        seen += 1
    assert seen >= 5


TRIAD_SIDE = "group.3-2-4-5.sides.1"


def test_a_triads_side_varies_as_a_single_solve_of_the_varied_file(capsys):
    text = _text("triad-press")
    values = [0.49, 0.505]
    rc, out, err, caught = _run(capsys, "sweep", "triad-press", "--vary", f"{TRIAD_SIDE}=0.49,0.505",
                                "--positions", "72", "--format", "json")
    assert rc == 0 and not caught and "Warning" not in err, err
    doc = json.loads(out)
    cols = doc["columns"]
    for i, side in enumerate(values):
        varied = parse(text.replace("sides = [0.352, 0.498, 0.349]", f"sides = [0.352, {side!r}, 0.349]"),
                       name="triad-press")
        assert varied.groups[0].sides[1] == side
        st = Study(varied, n=12).stroke  # an independent route: the study's own extremes
        assert cols["H"][i] == pytest.approx(st.H, rel=1e-7)
        assert cols["K"][i] == pytest.approx(st.K, rel=1e-6)
        one, _, _ = figures(varied, {}, 72)
        assert cols["gamma_min_deg"][i] == pytest.approx(float(one["gamma_min_deg"][0]), rel=1e-12)
        assert cols["Mb_max"][i] == pytest.approx(float(one["Mb_max"][0]), rel=1e-9)
    assert cols["H"][0] != pytest.approx(cols["H"][1], rel=1e-6)


def test_a_mass_varies_in_a_sweep_as_in_the_file():
    mech = load("triad-press")
    masses = np.array([10.0, 40.0])
    figs, failures, _ = figures(mech, {"link.5.mass": masses}, 36)
    assert failures == ["", ""]
    for m, got in zip(masses, figs["Mb_max"]):
        varied = parse(_text("triad-press").replace("mass = 25.0", f"mass = {m}"), name="triad-press")
        assert got == pytest.approx(float(figures(varied, {}, 36)[0]["Mb_max"][0]), rel=1e-12)
    assert figs["Mb_max"][0] != pytest.approx(figs["Mb_max"][1], rel=1e-3)


def test_batch_and_sweep_read_the_same_keys():
    """A batch override and a design variant of the same keys build the same mechanism."""
    base = batch.base_mechanism("triad-press")
    over = {TRIAD_SIDE: 0.5, "group.3-2-4-5.leads.1.length": 0.35, "link.5.mass": 20.0, "crank.rpm": -50.0}
    built, n = batch.apply_overrides(base, {**over, "positions": 8})
    from velplan.analysis.design import variant

    assert n == 8 and built == variant(base, over)
    assert built.groups[0].sides[1] == 0.5 and built.masses[-1].mass == 20.0
    assert built.crank.omega == pytest.approx(-50.0 * math.pi / 30, rel=1e-15)
    with pytest.raises(Exception, match="do not make a triangle"):
        batch.apply_overrides(base, {TRIAD_SIDE: 5.0})


# ---- 35.5: a scale that cannot be drawn names the option ---------------------------------------


@pytest.mark.parametrize("mu", ["1e-300", "1e300"])
def test_a_scheme_scale_that_cannot_be_drawn_names_the_option(tmp_path, capsys, mu):
    svg = tmp_path / "c.svg"
    _refused(capsys, "centres", "triad-press", "--scale-l", mu, "--svg", svg, words=[f"--scale-l {float(mu):g}"])
    assert not svg.exists()


# ---- 35.8 and 35.9: empty selections, batch arguments ------------------------------------------


def test_an_empty_part_list_is_refused(tmp_path, capsys):
    out = tmp_path / "n.md"
    _refused(capsys, "note", "four-bar", "--parts", "", "-o", out, words=["--parts"])
    assert not out.exists()


@pytest.mark.parametrize("require, words", [
    ("", ["--require: give at least one constraint"]),
    ("K<=0", ["'K<=0'", "at least 1"]),
    ("theta>=400deg", ["'theta>=400deg'", "0° ≤ θ < 180°"]),
    ("K>=1.5,K<=1.2", ["'K>=1.5' and 'K<=1.2'", "no value of K"]),
    ("gamma_min>=91deg", ["gamma_min>=91deg"]),
])
def test_batch_constraints_no_variant_can_meet_are_refused_up_front(tmp_path, capsys, require, words):
    out = tmp_path / "b"
    _refused(capsys, "batch", "--random", "2", "--base", "shaper", "--seed", "s1", "--require", require,
             "-o", out, words=words)
    assert not out.exists()


def test_a_base_that_does_not_load_is_one_line(tmp_path, capsys):
    empty = tmp_path / "empty.toml"
    empty.write_text("", "utf-8")
    out = tmp_path / "b"
    _refused(capsys, "batch", "--base", empty, "--random", "2", "--seed", "s1", "--require", "K>=1", "-o", out,
             words=["base", "missing [ground]"])
    assert not out.exists()


@pytest.mark.parametrize("argv, words", [
    (["--random", "2", "--seed", "s"], ["--random needs --base"]),
    (["--random", "2", "--base", "nope", "--seed", "s"], ["unknown base mechanism 'nope'"]),
    (["--random", "2", "--base", "shaper", "--seed", "s", "--spread", "200%"], ["--spread"]),
    (["--random", "2", "--base", "shaper", "--seed", "s", "--students", ",,"], ["--students"]),
    (["--random", "2", "--base", "shaper", "--seed", "s", "--spread", "x"], ["--spread"]),
])
def test_batch_argument_errors_leave_no_directory(tmp_path, capsys, argv, words):
    out = tmp_path / "b"
    _refused(capsys, "batch", *argv, "-o", out, words=words)
    assert not out.exists()


# ---- the fuzz: odd values of every option, one line or an answer --------------------------------


ODD = ["", "0", "-1", "nan", "inf", "-inf", "1e308", "1e-300", "abc", ",,", "1,,2", "  ", "1e999", "0x10", "2.5"]
OPTIONS = {
    "centres": ["--positions", "--position", "--angles", "--precision", "--angle-precision", "--scale-l", "--mode"],
    "note": ["--positions", "--plans", "--parts", "--delta"],
    "sweep": ["--positions", "--samples", "--vary", "--tolerance", "--delta", "--seed"],
    "batch": ["--random", "--positions", "--spread", "--students", "--require"],
}
BASE = {
    "centres": ["centres", "four-bar", "--positions", "4", "--mode", "drafting"],
    "note": ["note", "four-bar", "--positions", "4", "--parts", "kinematics"],
    "sweep": ["sweep", "four-bar", "--vary", "crank.length=0.1,0.11", "--positions", "24"],
    "batch": ["batch", "--random", "1", "--base", "four-bar", "--seed", "s", "--no-sheets", "--positions", "4"],
}
FORMS = {("sweep", "--vary"): "crank.length={}", ("sweep", "--tolerance"): "{}mm", ("batch", "--require"): "K>={}"}
"""Options whose odd value goes inside a well-formed text."""


def _cases(seed: int = 35, count: int = 50):
    rng = random.Random(seed)
    out = {(cmd, opt, value) for cmd, opts in OPTIONS.items() for opt in opts for value in ("", "nan")}
    while len(out) < count + 2 * sum(len(o) for o in OPTIONS.values()):
        cmd = rng.choice(sorted(OPTIONS))
        out.add((cmd, rng.choice(OPTIONS[cmd]), rng.choice(ODD)))
    return sorted(out)


def _argv(cmd: str, opt: str, value: str, tmp_path) -> list[str]:
    """The base command with ``opt`` set to ``value`` (in place of the base's own value of it)."""
    base = list(BASE[cmd])
    if opt in base:
        i = base.index(opt)
        del base[i:i + 2]
    if cmd == "sweep" and opt in ("--tolerance", "--samples"):
        del base[2:4]  # a Monte Carlo instead of the grid
        if opt == "--samples":
            base += ["--tolerance", "0.1mm"]
    if cmd == "sweep" and opt == "--samples" and value not in ("", "nan"):
        base += ["--distribution", "uniform"]
    value = FORMS.get((cmd, opt), "{}").format(value)
    out = tmp_path / {"batch": "out", "note": "out.md"}.get(cmd, "out.txt")
    return base + [f"{opt}={value}", "-o", str(out)]


@pytest.mark.parametrize("cmd, opt, value", _cases())
def test_odd_option_values_end_in_one_line_or_an_answer(tmp_path, capsys, cmd, opt, value):
    argv = _argv(cmd, opt, value, tmp_path)
    rc, out, err, caught = _run(capsys, *argv)
    assert "Traceback" not in err and "Warning" not in err and not caught, (argv, err, caught)
    if rc != 0 and not (tmp_path / "out" / "answers.json").exists():  # a refusal, not a batch with failures
        assert rc == 2 and err.count("\n") == 1 and err.startswith("velplan: error: "), (argv, err)
        assert not list(tmp_path.iterdir()), argv
