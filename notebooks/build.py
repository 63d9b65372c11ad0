"""Build the teaching notebooks of velplan, reproducibly, and run them to store their outputs.

    python notebooks/build.py                 # (re)writes notebooks/*.ipynb, executed
    python notebooks/build.py OUTDIR          # writes them to OUTDIR instead
    python notebooks/build.py --no-execute    # without outputs (fast)

The notebooks' sources are data generated here (fixed cell ids), stored executed with their
outputs so that they read on a code host; ``tests/test_notebooks.py`` checks that the stored
sources are what this script writes, executes them afresh and checks their readouts.

Conventions the tests rely on:

* a cell tagged ``readout`` prints one value per line as ``name = value unit``;
* a cell tagged ``errors`` prints one line per error message, ``error: …``;
* a cell tagged ``mechanism`` defines the TOML text of a mechanism as ``TOML = \"\"\"…\"\"\"``.
"""

from __future__ import annotations

import sys
from pathlib import Path
from textwrap import dedent

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = Path(__file__).resolve().parent

KERNEL = {"display_name": "Python 3", "language": "python", "name": "python3"}
LANGUAGE = {"name": "python", "pygments_lexer": "ipython3"}


def md(text: str):
    return new_markdown_cell(dedent(text).strip("\n"))


def code(text: str, *tags: str):
    cell = new_code_cell(dedent(text).strip("\n"))
    if tags:
        cell.metadata["tags"] = list(tags)
    return cell


def notebook(stem: str, cells: list) -> nbformat.NotebookNode:
    nb = new_notebook(cells=cells, metadata={"kernelspec": KERNEL, "language_info": LANGUAGE})
    for k, cell in enumerate(nb.cells):
        cell.id = f"{stem[:2]}-{k:02d}"  # fixed ids: the same script gives the same bytes
    nbformat.validate(nb)
    return nb


# --------------------------------------------------------------------------------------------
# 01: the press of seed 000, its velocity plan step by step, the table of transfer functions

NB01 = [
    md("""
    # 1 · The velocity plan, step by step

    A velocity plan (план скоростей) is drawn the way a course work draws it: a pole, one
    known vector laid off at a scale μv, lines perpendicular or parallel to the links through
    the images already found, their intersections, and points placed by the similarity
    theorem. velplan keeps every step as data, so it can draw the plan one step at a time.

    **What you will learn**

    * how the press of seed 000 is put together: crank 1, rod 2, rocker 5 (an RRR group), and a
      block 3 pivoted on the rod at B2 that slides in the vertical slot of the punch 4 (an RPP
      group);
    * how its velocity plan at one position is built at μv = 0.0007 (m/s)/mm, step by step, with
      the sentence of the worked solution for every step, in English and in Russian;
    * how speeds and angular velocities are read off the plan (length × μv, ω = V_rel / l) and
      how they compare with the analytic solution;
    * how the plans of 12 positions give the table of transfer functions V/ω1 and ω/ω1 of the
      course work, and its plot.
    """),
    code("""
    import numpy as np
    import matplotlib.pyplot as plt
    from IPython.display import display

    import velplan
    from velplan.notebook import crank_slider, draw_mechanism, draw_plan, draw_steps
    from velplan.plans.table import transfer_table

    N = 12          # crank positions, 30° apart, from the reference position
    POSITION = 3    # the position whose plan we build (numbered from 1, as on the sheet)
    MU_V = 0.0007   # velocity scale μv, (m/s)/mm, as in seed 000
    study = velplan.Study("press", n=N)
    mech, kin = study.mechanism, study.kinematics
    i = POSITION - 1  # its row in the arrays of kin
    print(mech.title)
    print(f"position {POSITION}: crank angle {kin.phi_deg[i] % 360:.1f}°")
    """),
    md("""
    ## The mechanism

    Chebyshev's formula counts the degrees of freedom: W = 3n − 2p5 − p4, with n moving links,
    p5 lower pairs (revolute and prismatic) and p4 higher pairs. One degree of freedom means
    one driving link, the crank, is enough.
    """),
    code("""
    s = velplan.structure(mech)
    print(f"n = {s.n_links}")
    print(f"p5 = {s.p5}")
    print(f"p4 = {s.p4}")
    print(f"W = {3 * s.n_links - 2 * s.p5 - s.p4}")
    for name, kind, *_ in s.groups:
        print(f"group {name}: {kind}")
    """, "readout"),
    md("""
    The scheme in its 12 positions; position 3 is drawn thick. The numbers at the crank tip A
    and at the punch mark the positions, counted from position 1 in the sense of ω1.
    """),
    code("""
    draw_mechanism(study, position=POSITION)
    """),
    md("""
    Turn the crank: with `ipywidgets` installed this is a slider over the crank angle; without
    it, a few positions are drawn side by side.
    """),
    code("""
    crank_slider(mech)
    """),
    md("""
    ## The plan, one step at a time

    Every step below is drawn with what it adds in thick lines; what earlier steps drew stays
    thin. Under each step's number is its sentence in English, then in Russian, as a worked
    solution writes it.

    The first vector is known: V_A = ω1·l_O1A, perpendicular to O1A in the sense of ω1; at
    μv = 0.0007 (m/s)/mm it is pa = 0.05 / 0.0007 = 71.4 mm long.
    """),
    code("""
    res = study.plan("velocity", positions=[POSITION], scale_v=MU_V)
    russian = res.describe(lang="ru")
    for k, ((sentence, drawing), ru) in enumerate(zip(draw_steps(res), russian), start=1):
        print(f"Step {k}. {sentence}")
        print(f"        {ru}")
        display(drawing)
    """),
    md("""
    The whole plan. Two lines through an image meet at the next image: through a the line
    ⊥ CA, through p the line ⊥ CO2, and c is where they cross. b2 lies on ac as B2 lies on AC
    (similarity), and b4 is where the line ∥ the slot through b2 meets the line ∥ the punch's
    guide through p.
    """),
    code("""
    draw_plan(res)
    """),
    md("""
    ## Reading the plan

    A speed is the length of its vector on the plan times μv; an angular velocity is a
    relative velocity divided by the length of the link (ω2 = V_CA / l_CA), its sense read by
    carrying the vector V_CA to C. The readouts below come from the plan.
    """),
    code("""
    V = {p: float(np.hypot(*res.vectors[p][0])) for p in ("A", "B2", "C", "E", "B4")}
    for p, v in V.items():
        print(f"V_{p} = {v:.6f} m/s")
    for link in ("2", "5"):
        print(f"ω{link} = {res.omegas[link][0]:+.6f} rad/s")
    for segment in ("pa", "ac", "pc", "ab2", "pe", "b2b4", "pb4"):
        print(f"{segment} = {res.segments[segment][0]:.4f} mm")
    """, "readout"),
    md("""
    Two checks by hand: the crank's speed is ω1·l1, and E is the middle of the rocker O2C, so
    by similarity pe = pc / 2 and V_E = V_C / 2.
    """),
    code("""
    print(f"ω1·l1 = {abs(mech.crank.omega) * mech.crank.length:.6f} m/s")
    print(f"V_E/V_C = {V['E'] / V['C']:.6f}")
    """, "readout"),
    md("""
    The same quantities from velplan's analytic solver (closed-form positions and their
    exact derivatives). The plan is evaluated exactly here, so the two agree to round-off; a
    hand-drawn plan agrees to about 1 % (see notebook 2).
    """),
    code("""
    worst = 0.0
    for p, v in V.items():
        exact = float(np.hypot(*kin.velocity(p)[i]))
        worst = max(worst, abs(v - exact) / exact)
        print(f"V_{p} analytic = {exact:.6f} m/s")
    for link in ("2", "5"):
        print(f"ω{link} analytic = {kin.omega(link)[i]:+.6f} rad/s")
    print(f"largest relative error = {100 * worst:.6f} %")
    """, "readout"),
    md("""
    ## The table of transfer functions

    Course works draw the plan in all 12 positions and tabulate the velocity analogues V/ω1
    (in metres) and ω/ω1, as seed 000's table 2 does. `transfer_table` reads them off the
    plans at μv = 0.0007 (m/s)/mm.
    """),
    code("""
    table = transfer_table(velplan.Study(mech, n=N).plan("velocity", scale_v=MU_V))
    print(table.text())
    """),
    code("""
    for name, label in (("V_B4", "VB4/ω1"), ("w_5", "ω5/ω1")):
        for k, value in enumerate(table.rows[name], start=1):
            print(f"{label}[{k}] = {value:+.6f}")
    """, "readout"),
    md("""
    The table as curves: the points are the 12 plans, the thin lines the analytic transfer
    functions over the whole turn. The punch stands still at positions 1 and 7: the rocker is
    at its extreme positions there (O2 is placed so, see `velplan/examples/press.toml`).
    """),
    code("""
    turn = np.radians(np.arange(0.0, 360.5, 2.0))
    fine = velplan.solve(mech, table.phi[0] + turn)
    angle = np.degrees(table.phi - table.phi[0])
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    for p in ("A", "B2", "C", "E", "B4"):
        line, = left.plot(angle, table.rows[f"V_{p}"], "o", label=f"V{p}/ω1")
        left.plot(np.degrees(turn), np.hypot(*fine.velocity(p).T) / abs(mech.crank.omega),
                  "-", lw=0.8, color=line.get_color())
    for link in ("2", "5"):
        line, = right.plot(angle, table.rows[f"w_{link}"], "o", label=f"ω{link}/ω1")
        right.plot(np.degrees(turn), fine.omega(link) / mech.crank.omega, "-", lw=0.8,
                   color=line.get_color())
    left.set(xlabel="crank angle from position 1, °", ylabel="V/ω1, m", xticks=range(0, 361, 30))
    right.set(xlabel="crank angle from position 1, °", ylabel="ω/ω1", xticks=range(0, 361, 30))
    for ax in (left, right):
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Press (seed 000): transfer functions, plans (points) and analytic (lines)")
    plt.show()
    """),
    md("""
    ## Exercises

    1. Build the plan at position 9 and compare its readouts with column 9 of seed 000's hand
       table, `velplan/examples/press-table2.csv`. Which entries differ by more than 0.5 mm on
       the plan?
    2. Set `MU_V = 0.001`. Which numbers on the plan change, and which readouts do not?
    3. Print the worked solution in Ukrainian (`res.describe(lang="uk")`) and draw the plan in
       Chinese (`draw_plan(res, lang="zh")`).
    4. Where is the punch fastest? Find it in the table, then with `N = 360`.
    5. Explain, from the plan at position 4, why ω2 is nearly zero there.
    """),
]


# --------------------------------------------------------------------------------------------
# 02: the shaper, exact and drafting modes, errors, a near-dead-centre position, a hand table

NB02 = [
    md("""
    # 2 · Graphical against analytic

    A plan drawn by hand is read to about half a millimetre and half a degree. velplan can
    construct a plan exactly (float64) or as a careful draughtsman would (every length and
    direction rounded or perturbed by a drafting precision), and it compares both with the
    analytic solution.

    **What you will learn**

    * the difference between the exact and the drafting mode of a plan, on the shaper of seed
      002 (crank 2, block 3 on the guide bar 4, rod 5, ram 6);
    * how the error of a drawn plan depends on the drafting precision and on the scale μv —
      and why a larger drawing is not always proportionally better;
    * what happens near a dead centre: where the output stops, and where two construction
      lines become nearly parallel (conditions and flags);
    * how to check a hand-made table of transfer functions (seed 000's table 2) with
      `check_table`, and how its outliers are explained.
    """),
    code("""
    from importlib.resources import files

    import numpy as np
    import matplotlib.pyplot as plt

    import velplan
    from velplan.notebook import draw_plan, side_by_side
    from velplan.plans import EXACT, Drafting, Plan, relative_error
    from velplan.plans.check import check_table

    N = 12
    POSITION = 3
    MU_V = 0.02     # (m/s)/mm
    study = velplan.Study("shaper", n=N)
    mech, kin = study.mechanism, study.kinematics
    plan = Plan.of(mech)
    i = POSITION - 1  # its row in the arrays of kin
    print(mech.title)
    print(f"position {POSITION}: crank angle {kin.phi_deg[i] % 360:.1f}°")
    print(f"ω2 = {mech.crank.omega:.4f} rad/s (80 rpm)")
    """),
    md("""
    ## Exact and drafting modes

    `EXACT` constructs the plan in float64: its readouts equal the analytic values to
    round-off. `Drafting(length_mm, angle_deg)` rounds every length laid off or read to
    `length_mm` and every direction drawn to `angle_deg`, as on paper.
    """),
    code("""
    exact = study.plan("velocity", positions=[POSITION], scale_v=MU_V, drafting=EXACT)
    drawn = study.plan("velocity", positions=[POSITION], scale_v=MU_V,
                       drafting=Drafting(length_mm=0.5, angle_deg=0.5))
    print("left: exact; right: drafted to 0.5 mm and 0.5° (alike to the eye)")
    side_by_side(draw_plan(exact), draw_plan(drawn))
    """),
    code("""
    v_exact = float(np.hypot(*exact.vectors["F"][0]))
    v_drawn = float(np.hypot(*drawn.vectors["F"][0]))
    print(f"V_F exact = {v_exact:.6f} m/s")
    print(f"V_F drafted = {v_drawn:.6f} m/s")
    print(f"ω4 exact = {exact.omegas['4'][0]:+.6f} rad/s")
    print(f"ω4 drafted = {drawn.omegas['4'][0]:+.6f} rad/s")
    print(f"error of V_F drafted = {100 * relative_error(drawn)['F'][0]:.4f} %")
    worst = max(e[0] for e in relative_error(exact, floor=0.01).values())
    print(f"largest error of the exact plan = {100 * worst:.6f} %")
    """, "readout"),
    md("""
    ## Error against drafting precision and scale

    A Monte-Carlo model of a careful hand: every length and direction gets a uniform error of
    ± half the precision. Over the 12 positions and 50 drafts each, the 95th percentile of the
    error of V_F, in per cent of the ram's largest speed, for three precisions and five scales.
    A smaller μv draws a larger plan: the length errors shrink with it, the direction errors do
    not — below some μv a larger drawing stops paying off.
    """),
    code("""
    RUNS = 50
    many = velplan.solve(mech, np.tile(velplan.positions(mech, N), RUNS))
    v_max = np.hypot(*many.velocity("F").T).max()
    precisions = (0.25, 0.5, 1.0)           # mm and degrees
    scales = (0.005, 0.01, 0.02, 0.04, 0.08)  # (m/s)/mm
    errors = {}
    for precision in precisions:
        for mu in scales:
            hand = Drafting(precision, precision, rng=np.random.default_rng(2026))
            res = plan.evaluate(many, kind="velocity", scale_v=mu, drafting=hand, refuse_below=0.0)
            e = np.hypot(*(res.vector("F") - many.velocity("F")).T) / v_max
            errors[precision, mu] = 100 * float(np.quantile(e, 0.95))
            print(f"error(δ={precision}, μv={mu}) = {errors[precision, mu]:.4f} %")
    """, "readout"),
    code("""
    fig, ax = plt.subplots(figsize=(6, 4))
    for precision in precisions:
        ax.loglog(scales, [errors[precision, mu] for mu in scales], "o-",
                  label=f"{precision} mm, {precision}°")
    ax.set(xlabel="μv, (m/s)/mm", ylabel="95th percentile error of V_F, % of max",
           title="Shaper: drafting error against scale")
    ax.minorticks_off()
    ax.set_xticks(scales, labels=[f"{mu:g}" for mu in scales])
    ax.set_yticks([0.2, 0.5, 1, 2], labels=["0.2", "0.5", "1", "2"])
    ax.grid(True, which="both", lw=0.3)
    ax.legend(title="drafting precision")
    plt.show()
    """),
    md("""
    ## Near a dead centre

    ### Where the output stops

    At its extreme positions the ram reverses: the crank is perpendicular to the guide bar,
    the bar stops (ω4 = 0) and the whole plan but pa collapses into the pole. For the shaper
    this happens where O3A ⊥ O2A, i.e. sin φ = −l_O2A / l_O2O3. The intersections stay well
    conditioned (the line ∥ the bar and the line ⊥ the bar always meet at a right angle), but
    the speeds are small, so a relative error means nothing there: read the absolute error,
    in millimetres on the plan.
    """),
    code("""
    stroke = velplan.stroke(mech)
    at = velplan.solve(mech, [stroke.start.phi])
    dead = plan.evaluate(at, kind="velocity", scale_v=MU_V)
    print(f"crank angle at the extreme = {np.degrees(stroke.start.phi) % 360:.4f} deg")
    print(f"V_F at the extreme = {abs(dead.vectors['F'][0][0]):.6f} m/s")
    print(f"ω4 at the extreme = {abs(dead.omegas['4'][0]):.6f} rad/s")
    print(f"sine at a4 at the extreme = {dead.conditions['a4'][0]:.6f}")
    print(f"sine at f at the extreme = {dead.conditions['f'][0]:.6f}")
    print(f"stroke H = {stroke.H:.6f} m")
    """, "readout"),
    code("""
    offsets = np.arange(-10, 11, 2)
    near = velplan.solve(mech, np.repeat(stroke.start.phi + np.radians(offsets), 200))
    hand = Drafting(0.5, 0.5, rng=np.random.default_rng(7))
    res = plan.evaluate(near, kind="velocity", scale_v=MU_V, drafting=hand, refuse_below=0.0)
    gap = np.hypot(*(res.vector("F") - near.velocity("F")).T).reshape(len(offsets), -1)
    speed = np.hypot(*near.velocity("F").T).reshape(len(offsets), -1)[:, 0]
    print(f"{'offset, °':>10}{'V_F, m/s':>10}{'error, mm':>11}{'error, %':>10}")
    for d, v, g in zip(offsets, speed, np.quantile(gap, 0.95, axis=1)):
        rel = f"{100 * g / v:10.1f}" if v > 1e-9 else f"{'—':>10}"
        print(f"{d:>10}{v:>10.4f}{g / MU_V:>11.2f}{rel}")
    """),
    md("""
    ### Where two lines become nearly parallel

    The true dead centre of a construction is an intersection of two nearly parallel lines.
    A four-bar built just inside Grashof's limit (l_AB + l_BD = 0.45 m, l_OA + l_OD = 0.4499 m)
    almost straightens its coupler and rocker at crank angle 180°: the lines ⊥ BA and ⊥ BD,
    which fix b, meet at a tiny angle. Every intersection carries its condition, the sine of
    that angle; below 0.1 it is flagged with a bound on how far the image may be off.
    """),
    code('''
    TOML = """
    name = "four-bar-near-dead-centre"
    [ground]
    O = [0.0, 0.0]
    D = [0.3499, 0.0]
    [crank]
    link = "1"
    pivot = "O"
    tip = "A"
    length = 0.10
    omega = 10.0
    [[group]]
    kind = "RRR"
    name = "2-3"
    links = ["2", "3"]
    joints = ["A", "D"]
    point = "B"
    lengths = [0.25, 0.20]
    branch = 1
    """
    four = velplan.parse(TOML)
    degrees = np.arange(0.0, 360.0, 1.0)
    sweep = Plan.of(four).evaluate(velplan.solve(four, np.radians(degrees)), kind="velocity",
                                   scale_v=MU_V)
    worst = int(np.argmin(sweep.conditions["b"]))
    flagged = sorted({f.index for f in sweep.flags})
    print(f"smallest sine at b = {sweep.conditions['b'][worst]:.6f}")
    print(f"at crank angle = {degrees[worst]:.1f} deg")
    print(f"flagged positions = {len(flagged)}")
    print(f"first flagged angle = {degrees[flagged[0]]:.1f} deg")
    print(f"last flagged angle = {degrees[flagged[-1]]:.1f} deg")
    ''', "mechanism", "readout"),
    md("""
    The exact construction is still right there (its flag only warns). A drawn one is not:
    the same half-millimetre, half-degree hand gives an error thirty times larger at 180° than
    at 90°, about the ratio of the two sines.
    """),
    code("""
    for deg in (90.0, 180.0):
        many = velplan.solve(four, np.full(400, np.radians(deg)))
        hand = Drafting(0.5, 0.5, rng=np.random.default_rng(7))
        res = Plan.of(four).evaluate(many, kind="velocity", scale_v=MU_V, drafting=hand,
                                     refuse_below=0.0)
        e = np.hypot(*(res.vector("B") - many.velocity("B")).T) / np.hypot(*many.velocity("B")[0])
        print(f"drafted error of V_B at {deg:.0f} deg = {100 * np.quantile(e, 0.95):.3f} %")
    """, "readout"),
    md("""
    ## Checking a hand-made table

    Seed 000's table 2 gives the transfer functions of the press read off hand-drawn plans at
    μv = 0.0007 (m/s)/mm. `check_table` compares every entry with the exact value; its
    tolerance is what drafting at 0.5 mm and 0.5° can explain (a Monte-Carlo estimate plus half
    a unit of the last digit written). Entries outside it are explained when possible: a
    column drawn at the wrong crank angle, a value entered in the wrong column, or a
    mis-measured segment.
    """),
    code("""
    press = velplan.load("press")
    report = check_table(press, files("velplan.examples") / "press-table2.csv", scale_v=0.0007)
    for line in report.text().splitlines()[:1]:
        print(line)
    for e in report.flagged:
        print(f"{e.quantity:<7} position {e.position:>2}: given {e.given:.3f}, "
              f"exact {e.exact:.4f} — {e.cause}")
    """),
    code("""
    print(f"entries checked = {len(report.entries)}")
    print(f"entries outside the tolerance = {len(report.flagged)}")
    for e in report.flagged:
        print(f"{e.quantity}[{e.position}] given = {e.given:.6f}")
        print(f"{e.quantity}[{e.position}] exact = {e.exact:.6f}")
    """, "readout"),
    md("""
    ## Exercises

    1. Repeat the precision study for ω4 instead of V_F. Is the same μv best?
    2. Draw the exact and the drafted plan of the shaper 2° after its extreme position. What
       does the drafted plan show for the ram?
    3. Move D of the four-bar to 0.3 m (the bundled `four-bar`). How small does the sine at b get
       now?
    4. Which columns of seed 000's table does `check_table` blame on a wrong crank angle? Draw
       the press at that angle and at the intended one and compare the plans.
    5. Make a table of your own with `transfer_table(...).csv()`, change two entries, and see
       how `check_table` explains them.
    """),
]


# --------------------------------------------------------------------------------------------
# 03: the shaper's acceleration plan and its Coriolis component

NB03 = [
    md("""
    # 3 · The acceleration plan and the Coriolis component

    The block 3 slides along the guide bar 4 while the bar turns, so the acceleration of the
    bar's point A4 that coincides with A has, besides the normal and tangential parts, a
    Coriolis part: aᵏ = 2·ω4 × V_rel, of magnitude 2·ω4·V_A4A, directed as V_A4A turned by 90°
    in the sense of ω4.

    **What you will learn**

    * how the acceleration plan of the shaper (seed 002) is built: the crank's normal
      acceleration, the Coriolis and relative parts along the bar, the normal and tangential
      parts about O3, then the ram;
    * the length of every component on the plan at the chosen scale μa, and its value;
    * that the Coriolis component read off the plan equals 2·ω4·V_rel computed from the
      velocity plan, and that it is turned 90° from V_rel in the sense of ω4;
    * how aᵏ changes over the turn.
    """),
    code("""
    import numpy as np
    import matplotlib.pyplot as plt
    from IPython.display import display

    import velplan
    from velplan.notebook import draw_plan, draw_steps
    from velplan.plans import Plan

    N = 12
    POSITION = 3
    MU_V = 0.02     # (m/s)/mm
    MU_A = 0.1      # (m/s²)/mm
    study = velplan.Study("shaper", n=N)
    mech, kin = study.mechanism, study.kinematics
    plan = Plan.of(mech)
    i = POSITION - 1  # its row in the arrays of kin
    print(f"position {POSITION}: crank angle {kin.phi_deg[i] % 360:.1f}°")
    """),
    md("""
    ## First the velocity plan

    The Coriolis component needs ω4 and the sliding velocity V_A4A of the bar's point A4
    relative to the block; both come from the velocity plan (V_A4A is the segment a a4).
    """),
    code("""
    vel = study.plan("velocity", positions=[POSITION], scale_v=MU_V)
    display(draw_plan(vel))
    omega4 = float(vel.omegas["4"][0])
    segment, v_rel = vel.components["V_A4A"]
    v_rel = float(v_rel[0])
    print(f"ω4 = {omega4:+.6f} rad/s")
    print(f"V_A4A = {v_rel:.6f} m/s")
    print(f"2·ω4·V_A4A = {2 * abs(omega4) * v_rel:.6f} m/s²")
    """, "readout"),
    md("""
    ## The acceleration plan, step by step

    From the pole π: the crank's acceleration πa (normal only, ω2 constant). For A4 two vector
    equations: a_A4 = a_A + aᵏ_A4A + aʳ_A4A (Coriolis laid off from a, then a line ∥ the bar)
    and a_A4 = a_O3 + aⁿ_A4O3 + aᵗ_A4O3 (normal laid off from π towards O3, then a line ⊥ the
    bar). Then b by similarity and the ram F like a crank-slider.
    """),
    code("""
    acc = study.plan("acceleration", positions=[POSITION], scale_v=MU_V, scale_a=MU_A)
    for k, (sentence, drawing) in enumerate(draw_steps(acc), start=1):
        print(f"Step {k}. {sentence}")
        display(drawing)
    """),
    md("""
    ## The components, their lengths and values

    Each component is a segment of the plan; its value is the length × μa.
    """),
    code("""
    for name, (segment, value) in acc.components.items():
        if name.startswith("a"):
            print(f"{name} = {value[0]:.6f} m/s²")
            print(f"{name} on the plan = {acc.segments[segment][0]:.4f} mm")
    """, "readout"),
    md("""
    Against the analytic values: ω4, V_rel and the relative acceleration come from the
    analytic solver (`kin.omega`, `kin.slide` of the prismatic pair P:3/4), and the closed
    forms aⁿ = ω²·l, aᵏ = 2·ω·V_rel.
    """),
    code("""
    w4 = float(kin.omega("4")[i])
    s, s_dot, s_ddot = kin.slide("P:3/4")[i]
    l_O3A = float(np.hypot(*(kin.position("A")[i] - kin.position("O3")[i])))
    print(f"ω2²·l_O2A = {mech.crank.omega ** 2 * mech.crank.length:.6f} m/s²")
    print(f"2·|ω4·V_rel| = {2 * abs(w4 * s_dot):.6f} m/s²")
    print(f"ω4²·l_O3A = {w4 ** 2 * l_O3A:.6f} m/s²")
    print(f"|s̈| = {abs(s_ddot):.6f} m/s²")
    print(f"ε4 = {acc.epsilons['4'][0]:+.6f} rad/s²")
    print(f"ε4 analytic = {kin.epsilon('4')[i]:+.6f} rad/s²")
    print(f"a_F = {acc.vectors['F'][0][0]:+.6f} m/s²")
    print(f"a_F analytic = {kin.acceleration('F')[i][0]:+.6f} m/s²")
    """, "readout"),
    md("""
    ## The direction of the Coriolis component

    On the plan aᵏ runs from a to k1; V_rel runs from a to a4 on the velocity plan. The angle
    from V_rel to aᵏ is +90° when the bar turns counter-clockwise, −90° when it turns clockwise.
    """),
    code("""
    v_dir = complex(*(vel.images["A4"][0] - vel.images["A"][0]))
    k_dir = complex(*(acc.images["k1"][0] - acc.images["A"][0]))
    turn = np.degrees(np.angle(k_dir / v_dir))
    print(f"turn from V_rel to aᵏ = {turn:+.4f} deg")
    print(f"sense of ω4 = {np.sign(omega4):+.0f}")
    """, "readout"),
    md("""
    ## Over the whole turn

    The Coriolis component read off the acceleration plans of all 12 positions, against
    2·|ω4·V_rel| from the analytic solver. It vanishes where the block stops sliding (the crank
    along the bar) and where the bar stops turning (the extreme positions).
    """),
    code("""
    every = plan.evaluate(kin, kind="acceleration", scale_v=MU_V, scale_a=MU_A)
    coriolis = every.components["aᵏ_A4A"][1]
    for k, value in enumerate(coriolis, start=1):
        print(f"aᵏ[{k}] = {value:.6f} m/s²")
    """, "readout"),
    code("""
    turn = np.radians(np.arange(0.0, 360.5, 1.0))
    fine = velplan.solve(mech, kin.phi[0] + np.sign(mech.crank.omega) * turn)
    exact = 2 * np.abs(fine.omega("4") * fine.slide("P:3/4")[:, 1])
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.plot(np.degrees(turn), exact, "-", lw=0.8, label="2·|ω4·V_rel| (analytic)")
    ax.plot(np.arange(N) * 360 / N, coriolis, "o", label="aᵏ read off the plans")
    ax.set(xlabel="crank angle from position 1, °", ylabel="aᵏ, m/s²", xticks=range(0, 361, 30))
    ax.grid(True, lw=0.3)
    ax.legend()
    plt.show()
    """),
    md("""
    ## Exercises

    1. Draw the acceleration plan at position 9 (the return stroke). Which components grow?
    2. At which crank angles is aᵏ zero? Explain both kinds with the velocity plan.
    3. Give the crank an angular acceleration (`epsilon = 5.0` in a copy of `shaper.toml`,
       loaded with `velplan.parse`) and find the new step in the plan.
    4. Halve μa. Which lengths on the plan change, which values do not?
    5. Compute the inertia force of the ram, −m·a_F, at position 3 (m = 52 kg).
    """),
]


# --------------------------------------------------------------------------------------------
# 04: a mechanism written from scratch

TOML_04 = '''
TOML = """
name = "lever-press"
title = "Four-bar with a slider"
output = "F"          # the slider whose extremes give the stroke H

[ground]
O = [0.0, 0.0]        # crank pivot, m
D = [0.30, 0.0]       # rocker pivot, m

[crank]
link = "1"
pivot = "O"
tip = "A"
length = 0.10         # m
omega = 10.0          # rad/s, counter-clockwise

[[group]]             # the four-bar's coupler 2 and rocker 3
kind = "RRR"
name = "2-3"
links = ["2", "3"]
joints = ["A", "D"]
point = "B"
lengths = [0.25, 0.20]   # l_AB, l_DB
branch = 1               # B to the left of A→D: above the ground line

[[point]]             # E on the rocker, 0.15 m from D
name = "E"
link = "3"
along = 0.15

[[group]]             # the rod 4 and the slider 5 on the ground line
kind = "RRP"
name = "4-5"
links = ["4", "5"]
joint = "E"
point = "F"
length = 0.35            # l_EF
branch = 1               # F to the right
guide = { link = "0", through = "D", angle_deg = 0.0, offset = 0.0 }
"""
mech = velplan.parse(TOML)
print(mech.title)
'''

NB04 = [
    md("""
    # 4 · Your own mechanism

    velplan reads a mechanism from a small TOML text: the fixed points, the crank, then the
    Assur groups in the order they are solved. The format is documented in `docs/format.md`.

    **What you will learn**

    * how to write a mechanism from scratch — a crank-rocker four-bar with an extra RRP group
      (a rod from a point of the rocker to a slider) — and load it with `velplan.parse`;
    * how to check its structure (W = 3n − 2p5 − p4), its stroke and its time-ratio coefficient;
    * how to get its velocity plan and readouts;
    * what velplan says when the geometry cannot close, or the file has a mistake: one line
      naming the element and the value;
    * how to draw its sheet (positions, plans, table) with `velplan.sheets.kinematic.build_sheet`.
    """),
    code("""
    import tempfile
    from pathlib import Path

    import numpy as np

    import velplan
    from velplan.notebook import SvgDrawing, draw_mechanism, draw_plan
    from velplan.sheets.kinematic import build_sheet
    """),
    md("""
    ## The file

    Units are SI (metres, radians per second). The four-bar O-A-B-D is a crank-rocker
    (Grashof: 0.10 + 0.30 < 0.25 + 0.20); the point E on the rocker drives the rod EF, and the
    slider F runs on the ground line through D.
    """),
    code(TOML_04, "mechanism"),
    code("""
    s = velplan.structure(mech)
    stroke = velplan.stroke(mech)
    theta = np.degrees(stroke.theta)
    print(f"n = {s.n_links}")
    print(f"p5 = {s.p5}")
    print(f"W = {3 * s.n_links - 2 * s.p5 - s.p4}")
    print(f"stroke H = {stroke.H:.6f} m")
    print(f"θ = {theta:.4f} deg")
    print(f"K = {(180 + theta) / (180 - theta):.6f}")
    """, "readout"),
    code("""
    N = 12
    study = velplan.Study(mech, n=N)
    draw_mechanism(study, position=2)
    """),
    md("""
    ## Its velocity plan at position 2
    """),
    code("""
    POSITION = 2
    res = study.plan("velocity", positions=[POSITION])
    for sentence in res.describe(lang="en"):
        print(sentence)
    draw_plan(res)
    """),
    code("""
    print(f"μv = {res.scale:.6f} (m/s)/mm")
    for p in ("A", "B", "E", "F"):
        print(f"V_{p} = {np.hypot(*res.vectors[p][0]):.6f} m/s")
    for link in ("2", "3", "4"):
        print(f"ω{link} = {res.omegas[link][0]:+.6f} rad/s")
    print(f"V_E/V_B = {np.hypot(*res.vectors['E'][0]) / np.hypot(*res.vectors['B'][0]):.6f}")
    """, "readout"),
    md("""
    ## When the geometry cannot close

    velplan checks a file's structure when it is loaded, and a study of it checks that every
    group closes over the whole turn of the crank: a group that cannot be assembled somewhere
    is refused, naming the group, the crank angles and the point. Every mistake is one line.
    Below, the file above with one change each, loaded and studied.
    """),
    code("""
    broken = {
        "rod EF too short to reach the guide": TOML.replace("length = 0.35", "length = 0.05"),
        "coupler too short for the four-bar": TOML.replace("[0.25, 0.20]", "[0.12, 0.20]"),
        "negative crank": TOML.replace("length = 0.10", "length = -0.10"),
        "a typo in a key": TOML.replace("omega = 10.0", "omgea = 10.0"),
        "a point used before it is solved": TOML.replace('joint = "E"', 'joint = "X"'),
        "a branch that is neither +1 nor -1": TOML.replace("branch = 1               # F",
                                                          "branch = 0               # F"),
    }
    for what, text in broken.items():
        try:
            velplan.Study(velplan.parse(text))
        except velplan.VelplanError as exc:
            print(f"{what}:")
            print(f"error: {exc}")
        else:
            print(f"{what}: no error")
    """, "errors"),
    md("""
    ## Its sheet

    `build_sheet` composes the A3 sheet: the scheme in its 12 positions, the velocity and
    acceleration plans of two positions, and the table of transfer functions, each at a
    standard scale. It is written to a temporary directory and shown from the file.
    """),
    code("""
    sheet = build_sheet(mech, fmt="A3", lang="en")
    with tempfile.TemporaryDirectory() as tmp:
        written = sheet.save(Path(tmp) / "lever-press.svg")
        print("written:", ", ".join(p.name for p in written))
        drawing = SvgDrawing.from_file(written[0])
    print(f"plans drawn = {len(sheet.plans)}")
    print(f"μl = {sheet.scales['mu_l']:.6f} m/mm")
    drawing
    """),
    md("""
    ## Exercises

    1. Replace the RRP group by an RRR group (a second rocker pivoted at a new ground point)
       and draw its plan.
    2. Find the shortest rod EF that still closes over the whole turn, to a millimetre.
    3. Set `branch = -1` in the RRR group. What changes in the drawing, and in W?
    4. Change `omega` to `-10.0`. Which readouts change sign, which do not?
    5. Draw the sheet in Russian (`lang="ru"`) on A1, with the plans of positions 4 and 10.
    """),
]


# --------------------------------------------------------------------------------------------
# 05: the shaper's machine dynamics: reduction, steady state, flywheel by three methods, a run

NB05 = [
    md("""
    # 5 · The flywheel and the equation of motion

    The first half of the course takes the crank's speed as given. The second half computes
    it: the masses and the loads are reduced to the crank, the equation of motion gives ω(φ),
    and a flywheel keeps its fluctuation within the coefficient δ the machine allows.

    **What you will learn**

    * how the reduced moment of inertia J_red(φ) = Σ m·(V_S/ω1)² + J_S·(ω_i/ω1)² and the
      reduced moment M_red(φ) (power equality) come from the velocity analogues of the
      analytic solver, with no numerical differentiation;
    * how the constant driving moment follows from zero work over the cycle, and ΔT(φ) from the
      works;
    * how ω(φ) follows from the energy equation, ε(φ) from Lagrange's equation, and δ from ω;
    * the flywheel for δ = 0.05 by the exact energy–mass envelope, by Wittenbauer's diagram
      (drawn, with its tangents) and by Mertsalov's approximation, and its disc's dimensions;
    * a start-up under an asynchronous motor (Kloss's formula), integrated in time.
    """),
    code("""
    from importlib.resources import files

    import numpy as np
    import matplotlib.pyplot as plt
    from IPython.display import display

    import velplan
    from velplan.notebook import draw_dynamics

    study = velplan.Study("shaper", delta=0.05)   # the shaper of seed 000, δ = 0.05
    d = study.dynamics
    print(study.mechanism.title)
    """),
    md("""
    ## Reduction to the crank

    At 12 positions, the variable part J_II of the reduced inertia (the links other than the
    crank) and the reduced moment of the loads and gravity (negative when they resist).
    """),
    code("""
    table = d.table(12)
    for k in range(12):
        print(f"J_II[{k + 1}] = {table['J_red'][k] - d.declared:.6f} kg·m²")
    for k in range(12):
        print(f"M_red[{k + 1}] = {table['M_red'][k]:.6f} N·m")
    """, "readout"),
    md("""
    ## The steady state

    The driving moment is constant and does the work of the resistances over the cycle:
    M_d·2π + ∮ M_red dφ = 0. The energy equation ½·(J_I + J_II)·ω² = T₀ + A(φ) then gives
    ω(φ), with T₀ chosen so that the mean speed (ω_max + ω_min)/2 is the crank's nominal one.
    """),
    code("""
    st = d.steady
    print(f"M_d = {d.driving:.6f} N·m")
    print(f"ω_m = {st.omega_mean:.9f} rad/s")
    print(f"ω_max = {st.omega_max:.9f} rad/s")
    print(f"ω_min = {st.omega_min:.9f} rad/s")
    print(f"δ = {st.delta:.9f}")
    """, "readout"),
    code("""
    c = d.curves(720)
    fig, ax = plt.subplots(2, 1, figsize=(8, 5), sharex=True)
    ax[0].plot(c["travel_deg"], c["A_sum"], label="ΔT = A_d + A_r, J")
    ax[0].plot(c["travel_deg"], c["A_resist"], label="A_r, J")
    ax[0].legend(); ax[0].grid(True)
    ax[1].plot(c["travel_deg"], np.abs(c["omega"]))
    ax[1].set_xlabel("crank travel from position 1, °"); ax[1].set_ylabel("ω, rad/s"); ax[1].grid(True)
    plt.show()
    """),
    md("""
    ## The flywheel by three methods

    *Exact*: the constant inertia J_I for which max(A − k₊J) − min(A − k₋J) = (k₊ − k₋)·J_I,
    k± = ½ω_m²(1 ± δ/2)². *Wittenbauer*: the same envelope drawn — the tangents to the
    ΔT–J curve at tan ψ = (μJ/μT)·k± cut the segment kl on the ΔT axis, J_I = μT·kl/(ω_m²δ).
    *Mertsalov*: ΔT_I ≈ A − ½ω_m²(J − J(0)), J_I ≈ (max − min)ΔT_I/(ω_m²δ).
    """),
    code("""
    fly = d.flywheel
    print(f"J_I exact = {fly.exact:.6f} kg·m²")
    print(f"J_I Wittenbauer = {fly.wittenbauer:.6f} kg·m²")
    print(f"J_I Mertsalov = {fly.mertsalov:.6f} kg·m²")
    dims = fly.dimensions
    print(f"disc diameter D = {dims.diameter:.3f} m")
    print(f"disc width b = {dims.width:.3f} m")
    print(f"disc inertia = {dims.inertia:.6f} kg·m²")
    """, "readout"),
    code("""
    display(draw_dynamics(study, "wittenbauer"))
    """),
    md("""
    The whole sheet is `velplan sheet shaper --kind dynamics --delta 0.05` on the command
    line, or `velplan.notebook.draw_dynamics_sheet(study)` here.

    ## A start-up under an asynchronous motor

    The same shaper with that flywheel, driven through a gearbox (u = 17.6) by a motor whose
    torque follows Kloss's formula M = 2·M_K·s·s_K/(s² + s_K²), started at a tenth of the
    nominal speed and run for three turns.
    """),
    code("""
    base = (files("velplan.examples") / "shaper.toml").read_text("utf-8")
    extra = "\\n".join([
        "[dynamics]",
        "[[dynamics.inertia]]", 'name = "flywheel"', f"inertia = {fly.exact:.6f}", "ratio = 1.0",
        "[dynamics.motor]", 'kind = "kloss"', "critical_torque = 40.0", "synchronous_rpm = 1500.0",
        "critical_rpm = 1200.0", "ratio = 17.6",
        "[dynamics.run]", f"omega = {0.1 * study.mechanism.crank.omega:.6f}", "travel_deg = 1080.0"])
    run = velplan.Study(velplan.parse(base + "\\n" + extra, name="shaper-start")).dynamics
    r = run.curves(2000)
    plt.figure(figsize=(8, 3))
    plt.plot(r["t"], np.abs(r["omega"]))
    plt.xlabel("t, s"); plt.ylabel("ω, rad/s"); plt.grid(True)
    plt.show()
    print(f"three turns take {run.run.time:.3f} s; the crank ends at {abs(run.run.omega_end):.3f} rad/s")
    """),
    md("""
    ## Exercises

    1. Halve δ. How do the three flywheels change, and why does Mertsalov's error shrink?
    2. Put the flywheel on the motor's shaft (`[dynamics.flywheel] ratio = 17.6`). How much
       lighter is it?
    3. Draw the Wittenbauer diagram by hand at the scales of the sheet and read kl off your
       drawing: what J_I do you get, and how far is it from the exact one?
    4. Start the motor with a weaker critical torque until the crank stops: what does velplan
       say?
    """),
]


# --------------------------------------------------------------------------------------------
# 06: the catalogue of course mechanisms, variant batches with an answer key, DXF for CAD

NB06 = [
    md("""
    # 6 · A course's worth of mechanisms: catalogue, variants, grading and CAD

    A department hands out one variant per student: the same scheme with other lengths, speed,
    masses and loads. velplan carries a catalogue of course-work mechanisms, draws reproducible
    random variants, writes every variant's sheet and an answer key, grades a student's table
    against it, and exports any sheet to DXF for KOMPAS-3D or AutoCAD.

    **What you will learn**

    * which mechanisms the catalogue holds, and the stroke H and time ratio K of one of them
      against their closed form;
    * how random variants are drawn from (student, assignment) so that the same pair always
      gives the same variant, on any machine;
    * how a batch writes the answer key, and how a student's table is graded against it;
    * how a sheet becomes a DXF file with a layer per line type, checked by ezdxf's audit;
    * how the interactive page shows the plans over the whole turn, step by step.
    """),
    code("""
    import io
    import math
    import tempfile
    from pathlib import Path

    import velplan
    from velplan.batch import Options, random_variants, run_batch
    from velplan.mechanism.loader import catalogue_names
    from velplan.plans.grade import grade_table

    names = catalogue_names()
    print(", ".join(names))
    print(f"catalogue mechanisms = {len(names)}")
    """, "readout"),
    md("""
    ## One catalogue mechanism

    The shaper whose slotted lever carries a block on the ram (RPR + PRP): its crank of 0.10 m
    turns about a pivot 0.30 m above the lever's pivot, so the lever swings through
    θ = 2·asin(0.10/0.30) and the ram's stroke is 2·0.52·tan(θ/2).
    """),
    code("""
    study = velplan.Study("shaper-lever-ram")
    st = study.stroke
    print(study.mechanism.title)
    print(f"H = {st.H:.9f} m")
    print(f"θ = {math.degrees(st.theta):.9f} deg")
    print(f"K = {st.K:.9f}")
    """, "readout"),
    md("""
    ## Random variants, reproducible

    Each number of the base file is multiplied by a factor drawn uniformly within ±10 % from a
    generator seeded by the student's id and the assignment's name (SHA-256), rounded to three
    digits, and drawn again until the variant assembles over the whole turn.
    """),
    code("""
    variants, failures = random_variants("shaper", 5, "TMM-2026 work 1", spread=0.10)
    again, _ = random_variants("shaper", 5, "TMM-2026 work 1", spread=0.10)
    print(f"variants drawn = {len(variants)}")
    print(f"the same variants when drawn again = {int([v.overrides for v in variants] == [v.overrides for v in again])}")
    for v in variants:
        print(f"variant {v.name} crank length = {v.overrides['crank.length']} m")
    """, "readout"),
    md("""
    ## The answer key, and a student's table graded against it

    The batch studies every variant (here without drawing its sheet) and writes `answers.json`
    and `answers.csv`. A student's table of V/ω1 for variant 2 with one wrong entry is graded
    within 5 % of each row's largest value.
    """),
    code("""
    with tempfile.TemporaryDirectory() as tmp:
        report = run_batch(variants, Options(outdir=tmp, sheets=False), jobs=1)
        key = report.answers[1]
        rows = ["quantity," + ",".join(str(k) for k in range(1, 13))]
        for point in ("A", "B", "F"):
            values = [f"{x:.4f}" for x in key["V"][point]]
            if point == "F":
                values[4] = f"{2 * float(values[4]) + 0.1:.4f}"   # a slip of the ruler
            rows.append(f"V{point}/ω1," + ",".join(values))
        table = Path(tmp) / "student.csv"
        table.write_text("\\n".join(rows) + "\\n", encoding="utf-8")
        graded = grade_table(table, Path(tmp) / "answers.json", variants[1].name)
    print(graded.text())
    print(f"entries graded = {len(graded.entries)}")
    print(f"entries wrong = {len(graded.entries) - graded.right}")
    """, "readout"),
    md("""
    ## The sheet in CAD

    `velplan sheet NAME -o NAME.dxf` writes the sheet's DXF beside its SVG: R2013, mm, a layer
    per ESKD line type with its lineweight, texts in UTF-8, and only LINE, CIRCLE, LWPOLYLINE
    and TEXT entities.
    """),
    code("""
    import ezdxf
    from velplan.render.dxf import to_dxf
    from velplan.sheets.kinematic import build_sheet

    sheet = build_sheet(study, lang="ru")
    doc = ezdxf.read(io.StringIO(to_dxf(sheet.scene, sheet.style)))
    auditor = doc.audit()
    kinds = sorted({e.dxftype() for e in doc.modelspace()})
    print("entity types:", ", ".join(kinds))
    print(f"DXF audit errors = {len(auditor.errors)}")
    print(f"DXF units code = {doc.header['$INSUNITS']}")
    """, "readout"),
    md("""
    ## The interactive page

    `velplan html NAME -o page.html` writes one self-contained page (no network): a slider over
    the crank's positions, the scheme and both plans, and the construction step by step. Here
    it is shown inline; it needs no kernel once the notebook is saved.
    """),
    code("""
    from IPython.display import display
    from velplan.html import Page

    import json
    import re

    page = Page("shaper-lever-ram", positions=24, lang="en")
    display(page)
    data = json.loads(re.search(r'<script type="application/json" id="velplan-data">(.*?)</script>',
                                page.html, re.S).group(1))
    print(f"page positions = {len(data['phi'])}")
    print(f"first crank angle on the page = {data['phi'][0]} deg")
    print(f"network addresses in the page = {page.html.count('http://') + page.html.count('https://')}")
    """, "readout"),
    md("""
    ## Exercises

    1. Draw a gallery of the catalogue with `python -m velplan.catalogue.gallery OUTDIR`.
    2. Give every student of your group a variant of the Whitworth mechanism, write their sheets
       with `velplan batch --random 30 --seed "…" --base whitworth -o course/` and look at two.
    3. Grade a table with a wrong sign in an ω row: what does the report say?
    4. Open a DXF in a CAD program and switch the THIN layer off.
    """),
]

# --------------------------------------------------------------------------------------------
# 07: a class III group by Assur's special point, and the instant centres of the same linkage

NB07 = [
    md("""
    # 7 · A class III group by Assur's special point, and instant centres

    Every group of notebooks 1–6 is a dyad: two links, and each vector equation of the plan has
    just two unknowns. A **class III group** (Assur's triad) has a ternary base link tied by
    three leads to links already known; no equation of it has only two unknowns. The course
    solves it with **Assur's special point**: the crossing S of the lines of two leads, taken
    as a point of the base link. Its velocity has a known direction from each of the two
    leads, so two lines on the plan meet at s, and the rest of the group follows.

    **What you will learn**

    * the structure of a press whose punch is moved by a triad: class, order, the formula of
      structure;
    * its velocity and acceleration plans built step by step through the special point, with
      the sentences of the worked solution in English and Russian;
    * the second graphical method, the instant centres of velocity, found by the
      Aronhold–Kennedy theorem, and the velocities they give, against the analytic solution.
    """),
    code("""
    import numpy as np
    from IPython.display import display

    import velplan
    from velplan.analysis.centres import instant_centres
    from velplan.analysis.solver import special_pair
    from velplan.notebook import draw_mechanism, draw_plan, draw_steps
    from velplan.plans.centres import construct_centres, velocities_by_centres

    N = 12          # crank positions, 30° apart, from the reference position
    POSITION = 3    # the position whose plans we build (numbered from 1, as on the sheet)
    study = velplan.Study("triad-press", n=N)
    mech, kin = study.mechanism, study.kinematics
    i = POSITION - 1  # its row in the arrays of kin
    print(mech.title)
    print(f"position {POSITION}: crank angle {kin.phi_deg[i] % 360:.1f}°")
    """),
    md("""
    ## Structure

    The crank 1 (class I) carries a triad: the ternary link 3 with the joints B, C, D, the rod 2
    from the crank's tip A to B, the rocker 4 from the frame's E to C, and the block 5 at D that
    slides on a vertical guide of the frame. Four links and six lower pairs: W = 3·4 − 2·6 = 0,
    as every Assur group. The mechanism's class is the highest class of its groups.
    """),
    code("""
    s = velplan.structure(mech)
    print(f"n = {s.n_links}")
    print(f"p5 = {s.p5}")
    print(f"W = {s.mobility}")
    print(f"mechanism class = {s.mechanism_class}")
    print(f"triad order = {s.groups[0][3]}")
    """, "readout"),
    code("""
    print(s.structure_formula(mech.crank.link))
    triad = mech.groups[0]
    a, b = special_pair(mech, triad)
    print(f"special point {triad.special_name}: the crossing of the lines of leads "
          f"{triad.leads[a].link} and {triad.leads[b].link}")
    draw_mechanism(study, position=POSITION)
    """),
    md("""
    ## The velocity plan through the special point

    The line of the rod 2 is AB; the "line" of the block 5 is the normal to its guide through
    D (the block's reaction acts along it). S lies on both. As a point of link 3,
    V_S = V_A + V_BA + V_SB, and V_BA and V_SB are both ⊥ AB: so V_S = V_A + (⊥ AB). Likewise
    V_S = V_D(guide) + (∥ guide) = (∥ guide), the guide being fixed. Two lines, one
    intersection: s. Then C: V_C = V_S + (⊥ SC) = V_E + (⊥ EC), and b, d by similarity.
    """),
    code("""
    res = study.plan("velocity", positions=[POSITION])
    russian = res.describe(lang="ru")
    for k, ((sentence, drawing), ru) in enumerate(zip(draw_steps(res), russian), start=1):
        print(f"Step {k}. {sentence}")
        print(f"        {ru}")
        display(drawing)
    """),
    code("""
    draw_plan(res)
    """),
    md("""
    The readouts from the plan, then from the analytic solver (the triad's closure solved
    exactly and its derivatives from linear systems): the plan is evaluated exactly here, so
    the two agree to round-off.
    """),
    code("""
    for p in ("B", "C", "D", triad.special_name):
        print(f"V_{p} = {float(np.hypot(*res.vectors[p][0])):.6f} m/s")
    for link in ("2", "3", "4"):
        print(f"ω{link} = {res.omegas[link][0]:+.6f} rad/s")
    worst = max(abs(float(np.hypot(*res.vectors[p][0])) - float(np.hypot(*kin.velocity(p)[i])))
                for p in ("B", "C", "D"))
    print(f"largest difference from the analytic velocities = {worst:.2e} m/s")
    """, "readout"),
    md("""
    ## The acceleration plan

    The same special point: a_S = a_A + aⁿ_BA + aⁿ_SB + (⊥ AB), where aⁿ_BA = ω2²·|AB| from B
    towards A and aⁿ_SB = ω3²·|SB| from S towards B are known from the velocity plan; and
    a_S = aⁿ_SD + (∥ guide). Then C as for the velocities, with its normal components.
    """),
    code("""
    acc = study.plan("acceleration", positions=[POSITION])
    for sentence in acc.describe(lang="en"):
        print(sentence)
    draw_plan(acc)
    """),
    code("""
    for p in ("B", "C", "D"):
        print(f"a_{p} = {float(np.hypot(*acc.vectors[p][0])):.6f} m/s²")
    for link in ("2", "3", "4"):
        print(f"ε{link} = {acc.epsilons[link][0]:+.6f} rad/s²")
    """, "readout"),
    md("""
    ## Instant centres (Aronhold–Kennedy)

    Six links (the frame included) have 6·5/2 = 15 instant centres. The joints give some at
    once, the block on the fixed guide gives P05 at infinity ⊥ the guide, and every other one
    is the crossing of two Kennedy lines (P_ij, P_jk, P_ik lie on one line). With the centres,
    V_M = ω_i·|M P0i| for a point M of link i, and ω_j = ω_i·|P0i Pij| / |P0j Pij|.
    """),
    code("""
    con = construct_centres(kin, POSITION)
    for line in con.describe("en"):
        print(line)
    """),
    code("""
    exact = instant_centres(kin.take([i]))
    by_centres = velocities_by_centres(con)
    print(f"instant centres = {len(exact.pairs)}")
    print(f"reached by Kennedy lines = {sum(1 for st in con.steps if st.how != 'unreached')}")
    worst = max(abs(abs(by_centres.velocities[p]) - float(np.hypot(*kin.velocity(p)[i])))
                for p in ("B", "C", "D"))
    print(f"largest difference of velocities by centres = {worst:.2e} m/s")
    for link in ("3", "4"):
        print(f"ω{link} by centres = {by_centres.omegas[link]:+.6f} rad/s")
    """, "readout"),
    md("""
    ## Exercises

    1. `velplan steps triad-press --position 3 -o steps/` writes each step as a figure;
       `velplan steps triad-press --kind centres -o centres/` the Kennedy construction.
    2. Force another special point: add `pair = [1, 2]` to the group in a copy of the file
       (leads 2 and 4). Which plan is easier to draw, and why?
    3. `velplan forces triad-press --positions 12` gives the balancing moment three ways: the
       triad's reactions are all found together.
    """),
]


NOTEBOOKS = {
    "01-velocity-plan-step-by-step": NB01,
    "02-graphical-vs-analytic": NB02,
    "03-acceleration-plan-coriolis": NB03,
    "04-your-own-mechanism": NB04,
    "05-flywheel-and-equation-of-motion": NB05,
    "06-catalogue-variants-and-cad": NB06,
    "07-class-three-and-instant-centres": NB07,
}


def build(outdir: Path = HERE, *, execute: bool = False) -> list[Path]:
    """Write every notebook to `outdir`; returns the files. ``execute``: run each (kernel
    python3, working directory ``notebooks/``) and store it with its outputs, so that it reads
    on a code host without a kernel."""
    outdir = Path(outdir)
    written = []
    for stem, cells in NOTEBOOKS.items():
        path = outdir / f"{stem}.ipynb"
        nb = notebook(stem, cells)
        if execute:
            from nbclient import NotebookClient

            NotebookClient(nb, kernel_name="python3", timeout=300,
                           resources={"metadata": {"path": str(HERE)}}).execute()
            for cell in nb.cells:  # no timings or kernel ids: only what the cells printed or drew
                cell.metadata.pop("execution", None)
            # the kernel's versions are the machine's, not the notebook's
            nb.metadata = nbformat.from_dict({"kernelspec": KERNEL, "language_info": LANGUAGE})
        nbformat.write(nb, str(path), version=4)
        written.append(path)
    return written


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--no-execute"]
    for path in build(Path(args[0]) if args else HERE, execute="--no-execute" not in sys.argv):
        print(path)
