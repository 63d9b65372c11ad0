"""``velplan html``: the interactive page of a mechanism, one self-contained HTML file."""

from __future__ import annotations

import math
import sys
from pathlib import Path

from velplan.cli.common import add_mechanism, default_language, positive_int
from velplan.errors import VelplanError
from velplan.render.i18n import LANGUAGES

DEFAULT_POSITIONS = 72
"""Stops of the crank-angle slider by default: every 5°."""


def register(sub) -> None:
    p = sub.add_parser("html", help="an interactive page: the scheme and both plans over a turn, step by step")
    add_mechanism(p, optional=True)
    p.add_argument("-o", "--output", metavar="FILE.html",
                   help="file to write (default: MECH.html in the current directory)")
    p.add_argument("--positions", metavar="N", type=positive_int, default=DEFAULT_POSITIONS,
                   help=f"stops of the crank-angle slider over a turn (default {DEFAULT_POSITIONS})")
    p.add_argument("--lang", choices=LANGUAGES, default=default_language(),
                   help="language of the page and the worked solution (default: the locale's, else en)")
    p.add_argument("--scale-v", metavar="MU", type=float, help="μv, (m/s)/mm (default: from the standard series)")
    p.add_argument("--scale-a", metavar="MU", type=float, help="μa, (m/s²)/mm (default: from the standard series)")
    p.add_argument("--precision", metavar="MM", type=float, default=0.5,
                   help="drafting precision the errors are read at, mm (default 0.5)")
    p.add_argument("--angle-precision", metavar="DEG", type=float, default=0.5,
                   help="angular drafting precision, deg (default 0.5)")
    p.add_argument("--centres", action="store_true",
                   help="mark each position's instant centres (found by Kennedy lines) on the scheme")
    p.set_defaults(run=run_html)


def run_html(args) -> int:
    from velplan.html import MAX_POSITIONS, Page
    from velplan.html.aside import building_aside
    from velplan.plans.drafting import Drafting
    from velplan.study import Study

    if args.positions > MAX_POSITIONS:
        raise VelplanError(f"--positions {args.positions} is more than a page holds (at most {MAX_POSITIONS})")
    for name, value in (("--scale-v", args.scale_v), ("--scale-a", args.scale_a)):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise VelplanError(f"{name} must be a positive scale, not {value:g}")
    out = Path(args.output) if args.output else Path(f"{Path(str(args.mechanism)).stem}.html")
    if out.is_dir():
        raise VelplanError(f"cannot write {out}: it is a directory")
    if not out.parent.is_dir():
        raise VelplanError(f"cannot write {out}: directory {out.parent} does not exist")
    study = Study(args.mechanism, n=args.positions)
    with building_aside():  # a fork draws the plans meanwhile where a core is free
        page = Page(study, lang=args.lang, scale_v=args.scale_v, scale_a=args.scale_a,
                    drafting=Drafting(args.precision, args.angle_precision), centres=args.centres)
    page.save(out)
    sys.stdout.write(f"wrote {out}\n")
    return 0
