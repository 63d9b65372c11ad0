"""``velplan note``: the explanatory note of a course work (.docx, .pdf, .html, .md)."""

from __future__ import annotations

import sys
from pathlib import Path

from velplan.cli.common import add_mechanism, default_language, positive_int
from velplan.errors import VelplanError
from velplan.render.i18n import LANGUAGES

FIELDS = (("organisation", "university and department"), ("author", "the student"),
          ("group", "the student's group"), ("checker", "the supervisor"), ("date", "place and year"))


def register(sub) -> None:
    p = sub.add_parser("note", help="the explanatory note: the sheets' calculations written out "
                                    "(.docx with Word equations, .pdf, .html, .md)")
    add_mechanism(p, optional=True)
    p.add_argument("-o", "--output", metavar="FILE",
                   help="FILE.docx, .pdf, .html or .md (default: MECH-note.docx)")
    p.add_argument("--positions", metavar="N", type=positive_int, default=12,
                   help="number of positions of the scheme and the tables (default 12)")
    p.add_argument("--plans", metavar="K,…",
                   help="positions whose plans, groups and lever are written out (default: the sheet's two)")
    p.add_argument("--parts", metavar="P,…",
                   help="of kinematics,forces,dynamics (default: every part the mechanism has data for)")
    p.add_argument("--lang", choices=LANGUAGES, default=default_language(),
                   help="language of the note (default: the locale's, else en)")
    p.add_argument("--delta", metavar="δ", type=float,
                   help="size the flywheel for this coefficient of speed fluctuation "
                        "(overrides the file's [dynamics] delta)")
    p.add_argument("--format", choices=("A1", "A2", "A3"), default="A1",
                   help="the sheets whose scales and drawings the note follows (default A1)")
    for name, what in FIELDS:
        p.add_argument(f"--{name}", metavar="TEXT", help=f"title page: {what}")
    p.set_defaults(run=run_note)


def run_note(args) -> int:
    from velplan.cli.sheet import parse_plans
    from velplan.note import build_note, note_format, write_note
    from velplan.note.forces_aside import building_aside
    from velplan.note.writers import require
    from velplan.study import Study

    out = Path(args.output) if args.output else Path(f"{Path(str(args.mechanism)).stem}-note.docx")
    require(note_format(out))
    if out.is_dir():
        raise VelplanError(f"cannot write {out}: it is a directory")
    if not out.parent.is_dir():
        raise VelplanError(f"cannot write {out}: directory {out.parent} does not exist")
    if args.delta is not None and not (0 < args.delta < 1):
        raise VelplanError(f"--delta must be between 0 and 1, not {args.delta:g}")
    parts = None if args.parts is None else tuple(x.strip() for x in args.parts.split(",") if x.strip())
    if parts == ():
        raise VelplanError("--parts: give at least one of kinematics, forces, dynamics")
    study = Study(args.mechanism, n=args.positions, delta=args.delta)
    fields = {k: getattr(args, k) for k, _ in FIELDS if getattr(args, k)}
    # the part on forces built by a second process while this one builds the rest
    with building_aside():
        note = build_note(study, plans=parse_plans(args.plans, args.positions), parts=parts, lang=args.lang,
                          fmt=args.format, fields=fields)
        write_note(note, out)
    sys.stdout.write(f"wrote {out}\n")
    return 0
