"""``velplan sheet``, ``velplan diagrams`` and ``velplan steps``: drawings.

Every file is written atomically (SVG always; PNG and PDF through cairosvg, DXF through ezdxf
when asked) and named on standard output; an error leaves no file behind.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from velplan.cli.common import add_mechanism, default_language, positive_int
from velplan.errors import VelplanError

_FORMATS = ("A1", "A2", "A3")
_KINDS = ("velocity", "acceleration", "both")
_SHEET_KINDS = _KINDS + ("forces", "dynamics")
_LANGS = ("en", "ru", "uk", "zh")


def register(sub) -> None:
    p = sub.add_parser("sheet", help="draw the kinematic-analysis sheet (scheme, plans, "
                                     "diagrams, table), or with --kind forces the "
                                     "force-analysis sheet, as SVG, PNG or PDF")
    add_mechanism(p, optional=True)
    p.add_argument("-o", "--output", metavar="FILE",
                   help="SVG file to write (default: MECH-sheet.svg in the current directory, "
                        "MECH-forces.svg with --kind forces); a .png, .pdf or .dxf name writes "
                        "that too, beside the SVG")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="number of positions of the scheme, table and diagrams (default 12)")
    p.add_argument("--plans", metavar="K,…",
                   help="positions whose plans are drawn, or all (with --kind velocity: the 12 "
                        "velocity plans of a course work; default: two, about a quarter and "
                        "three quarters of the turn, or the first alone where two do not fit); with --kind forces, the positions of the "
                        "force analysis (default: the largest balancing moment)")
    p.add_argument("--kind", choices=_SHEET_KINDS, default="both",
                   help="which plans (default both); forces: the force-analysis sheet "
                        "(groups with their forces, force polygons, Zhukovsky's lever, the "
                        "balancing moment); dynamics: the machine-dynamics sheet (reduced "
                        "moments, works, J_red, ω, Wittenbauer's diagram, the flywheel)")
    p.add_argument("--format", choices=_FORMATS, default="A1", help="sheet format (default A1)")
    p.add_argument("--diagrams", choices=("auto", "yes", "no"), default="auto",
                   help="kinematic diagrams on the sheet: when they fit (auto, the default), "
                        "always (an error if they do not fit), never")
    p.add_argument("--structure", choices=("auto", "yes", "no"), default="auto",
                   help="the structural analysis (initial mechanism and Assur groups drawn apart) "
                        "on the kinematic sheet: where free space is left for it once the enlarged "
                        "details of crowded plans have theirs (auto, the default), always, before the "
                        "details (an error where there is none), never")
    p.add_argument("--no-table", action="store_true",
                   help="leave out the table of transfer functions")
    p.add_argument("--scale-per-plan", action="store_true",
                   help="fit each plan at its own μ (default: one μv for all the velocity "
                        "plans of the sheet and one μa for the acceleration plans)")
    p.add_argument("--centres", metavar="K,…",
                   help="mark the instant centres (found by Kennedy lines) of these positions on the scheme")
    p.add_argument("--delta", metavar="δ", type=float,
                   help="with --kind dynamics: size the flywheel for this coefficient of speed "
                        "fluctuation (overrides the file's [dynamics] delta)")
    _common(p)
    p.add_argument("--frame", choices=("eskd", "iso"),
                   help="title block: ESKD form 1 (default for ru, uk) or the captioned "
                        "ISO-style block (default for en, zh)")
    for name, what in (("title", "name of the drawing"), ("designation", "document designation"),
                       ("author", "designed by"), ("checker", "checked by"),
                       ("approved", "approved by"), ("organisation", "university and group"),
                       ("date", "date as it should be written")):
        p.add_argument(f"--{name}", metavar="TEXT", help=f"title block: {what}")
    p.set_defaults(run=run_sheet)

    p = sub.add_parser("diagrams", help="kinematic diagrams of the output: analytic curves "
                                        "and the chord method")
    add_mechanism(p, optional=True)
    p.add_argument("-o", "--output", metavar="FILE",
                   help="SVG file to write (default: MECH-diagrams.svg)")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="positions the chord method works from (default 12)")
    p.add_argument("--length", metavar="MM", type=float, default=180.0,
                   help="length of the φ axis for one turn, mm (default 180: μφ = 2°/mm)")
    _common(p)
    p.set_defaults(run=run_diagrams)

    p = sub.add_parser("steps", help="one SVG per construction step of the plans at a position")
    add_mechanism(p, optional=True)
    p.add_argument("--position", metavar="K", type=positive_int, required=True,
                   help="the position (1-based) whose plans are built")
    p.add_argument("-o", "--output", metavar="DIR", required=True,
                   help="directory to write step-v-01.svg, … into (created if missing; its parent must exist)")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="number of positions the crank circle is divided into (default 12)")
    p.add_argument("--kind", choices=_KINDS + ("centres",), default="both",
                   help="which plans (default both), or the instant centres by Kennedy lines")
    _common(p)
    p.set_defaults(run=run_steps)


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--lang", choices=_LANGS, default=default_language(),
                   help="language of the drawing (default: the locale's — ru, uk, zh — else en)")
    p.add_argument("--png", action="store_true", help="also write a PNG (needs cairosvg)")
    p.add_argument("--pdf", action="store_true", help="also write a PDF (needs cairosvg)")
    p.add_argument("--dxf", action="store_true",
                   help="also write a DXF (R2013, mm, a layer per line type) for CAD")
    p.add_argument("--dpi", type=float, default=150.0, help="PNG resolution (default 150)")


def parse_plans(text: str | None, n: int | None = None) -> tuple[int, ...] | None:
    """``"3,9"`` → (3, 9); ``"all"`` → every position 1…n; a one-line error naming a bad
    item."""
    if text is None:
        return None
    if text.strip().lower() == "all":
        if n is None:
            raise VelplanError("--plans all needs the number of positions")
        from velplan.analysis.numbering import position_numbers

        return tuple(position_numbers(range(n)).tolist())
    out = []
    for item in text.split(","):
        item = item.strip()
        try:
            out.append(int(item))
        except ValueError:
            raise VelplanError(f"--plans: {item!r} is not a position number (or give: all)") from None
    return tuple(out)


def _write(svg: str, scene, style, path, args) -> list[Path]:
    """Write a drawing's SVG to `path` (a .png, .pdf or .dxf name: beside it) and the PNG, PDF
    and DXF asked for (`velplan.render.export.save_drawing`)."""
    from velplan.render.export import save_drawing

    return save_drawing(svg, path, scene=scene, style=style, png=args.png, pdf=args.pdf, dxf=args.dxf,
                        dpi=args.dpi)


def _report(paths) -> None:
    for path in paths:
        sys.stdout.write(f"wrote {path}\n")


def run_sheet(args) -> int:
    from velplan.options import KINEMATIC_SHEET_KINDS
    from velplan.sheets.frame import TitleInfo
    from velplan.sheets.kinds import build, default_title_of, file_stem
    from velplan.study import Study

    plans = parse_plans(args.plans, args.positions)
    if args.delta is not None and args.kind != "dynamics":
        raise VelplanError("--delta belongs to --kind dynamics")
    if plans is not None and args.kind == "dynamics":
        raise VelplanError("--plans has no meaning for the dynamics sheet (it draws the whole cycle)")
    study = Study(args.mechanism, n=args.positions, delta=args.delta)
    mech = study.mechanism
    fields = {k: getattr(args, k) for k in ("title", "designation", "author", "checker",
                                             "approved", "organisation", "date")
              if getattr(args, k)}
    info = None
    if fields:
        base = default_title_of(args.kind, mech, args.lang)
        info = TitleInfo(**{"title": base.title, "designation": base.designation, **fields})
    options: dict = {"fmt": args.format, "lang": args.lang, "frame_style": args.frame, "info": info}
    if args.kind != "dynamics":
        options.update(plans=plans, diagrams={"auto": None, "yes": True, "no": False}[args.diagrams],
                       table=not args.no_table)
    if args.kind in KINEMATIC_SHEET_KINDS:
        options.update(scale_per_plan=args.scale_per_plan,
                       centres=parse_plans(args.centres, study.n) if args.centres else (),
                       structure={"auto": None, "yes": True, "no": False}[args.structure])
    elif args.structure != "auto":
        raise VelplanError("--structure belongs to the kinematic sheet (--kind velocity, acceleration or both)")
    sheet = build(study, args.kind, **options)
    output = args.output or f"{mech.name}-{file_stem(args.kind)}.svg"
    _report(_write(sheet.svg(), sheet.scene, sheet.style, output, args))
    return 0


def run_diagrams(args) -> int:
    from velplan.study import Study
    from velplan.views.diagram import diagram_view
    from velplan.render.scene import Scene
    from velplan.render.style import SheetStyle
    from velplan.render.svg import to_svg

    if not 60.0 <= args.length <= 600.0:
        raise VelplanError(f"--length must be between 60 and 600 mm, not {args.length:g}")
    if args.positions < 3:
        raise VelplanError(f"the chord method needs at least 3 positions, not {args.positions}")
    study = Study(args.mechanism, n=args.positions)
    mech = study.mechanism
    d = study.diagrams
    view = diagram_view(d, length_mm=args.length, height_mm=40.0, lang=args.lang, omega=mech.crank.omega,
                        arrangement="column")
    margin = 10.0
    scene = Scene(tuple(view.at(margin, margin).primitives), view.width_mm + 2 * margin,
                  view.height_mm + 2 * margin)
    style = SheetStyle(language=args.lang)
    output = args.output or f"{mech.name}-diagrams.svg"
    _report(_write(to_svg(scene, style), scene, style, output, args))
    return 0


def run_steps(args) -> int:
    from velplan.study import Study
    from velplan.views.steps import step_figures
    from velplan.render.style import SheetStyle
    from velplan.render.svg import to_svg

    study = Study(args.mechanism, n=args.positions)
    if not 1 <= args.position <= study.n:
        raise VelplanError(f"--position {args.position} is outside 1…{study.n}")
    kinds = ("velocity", "acceleration") if args.kind == "both" else (args.kind,)
    if args.kind == "centres":
        from velplan.views.centres import centre_step_figures

        study.require_assembled([args.position])
        figures = centre_step_figures(study.centres(args.position),
                                      fine=study.turn, number=args.position, lang=args.lang)
    else:
        figures = step_figures(study.mechanism, study.kinematics, {k: study.plan(k) for k in kinds},
                               args.position, kind=args.kind, lang=args.lang)
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise VelplanError(f"cannot write steps into {out}: it is a file, not a directory")
    if not out.parent.is_dir():
        raise VelplanError(f"cannot write steps into {out}: directory {out.parent} does not exist")
    try:
        out.mkdir(exist_ok=True)
    except OSError as exc:
        raise VelplanError(f"cannot create {out}: {exc.strerror or exc}") from None
    style = SheetStyle(language=args.lang)
    written = []
    for f in figures:
        name = out / f"step-{f.kind}-{f.number:02d}.svg"
        written += _write(to_svg(f.scene, style), f.scene, style, name, args)
    _report(written)
    return 0
