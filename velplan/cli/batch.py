"""``velplan batch``: a variant table (or random variants) → sheets and an answer key."""

from __future__ import annotations

import sys
from pathlib import Path

from velplan.cli.common import positive_int
from velplan.errors import VelplanError
from velplan.plans.text import LANGS


def register(sub) -> None:
    p = sub.add_parser("batch", help="sheets and an answer key for a table of variants (CSV, Excel or TOML) or random variants")
    p.add_argument("table", metavar="VARIANTS", nargs="?",
                   help="variant table: .csv (variant,base,key…), .xlsx (the same columns on its first sheet) or .toml ([[variant]] tables)")
    p.add_argument("-o", "--output", metavar="DIR", default="batch",
                   help="output directory (created if its parent exists; default ./batch)")
    p.add_argument("--base", metavar="MECH", help="base mechanism for rows without one (and for --random)")
    p.add_argument("--random", metavar="N", type=positive_int, help="draw N random variants of --base instead of a table")
    p.add_argument("--seed", metavar="TEXT", help="the assignment text the random variants are drawn from")
    p.add_argument("--students", metavar="ID,…", help="student ids, one variant each (default 1…N)")
    p.add_argument("--spread", metavar="P%", default="10%", help="random factor range ±P %% (default 10%%)")
    p.add_argument("--require", metavar="C,…", help="with --random: draw only variants that meet these, e.g. "
                   "'K>=1.4, gamma_min>=40deg, H=0.25..0.35' (H m, K, theta/gamma_min deg, v_max, a_max); "
                   "their figures of merit go into the answer key")
    p.add_argument("--positions", metavar="N", type=positive_int,
                   help="positions of every variant (a 'positions' column overrides it; default 12)")
    p.add_argument("--png", action="store_true", help="also write a PNG of each sheet")
    p.add_argument("--lang", choices=LANGS, default="en")
    p.add_argument("--format", choices=("A1", "A2", "A3"), default="A1", help="sheet format (default A1)")
    p.add_argument("--no-sheets", action="store_true", help="only the answer key")
    p.add_argument("--note", metavar="FORMAT", nargs="?", const="docx", choices=("docx", "pdf", "html", "md"),
                   help="also write each variant's explanatory note (default format docx; needs '.[note]')")
    p.add_argument("--jobs", metavar="N", type=positive_int, help="worker processes (default: all cores)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(run=run_batch_cmd)


def _spread(text: str) -> float:
    t = text.strip()
    try:
        value = float(t[:-1]) / 100 if t.endswith("%") else float(t)
    except ValueError:
        raise VelplanError(f"--spread: {text!r} is not a percentage such as 10%") from None
    return value


MAX_RANDOM = 10_000
"""Most random variants (--random N or --students) one batch draws: each is a sheet."""


def _check(args):
    """Every argument checked before the output directory is made: (constraints, students, spread)."""
    if (args.table is None) == (args.random is None):
        raise VelplanError("give a variant table or --random N (one of them)")
    require = None
    if args.require is not None:
        if args.random is None:
            raise VelplanError("--require needs --random N (it constrains random draws)")
        from velplan.sweep.require import parse_require

        require = parse_require(args.require)
    students, spread = None, None
    if args.random is not None:
        if not args.base or args.seed is None:
            raise VelplanError("--random needs --base MECH and --seed TEXT (the assignment)")
        if args.random > MAX_RANDOM:
            raise VelplanError(f"--random {args.random} is more than a batch draws (at most {MAX_RANDOM})")
        if args.students is not None:
            students = [s.strip() for s in args.students.split(",") if s.strip()]
            if not students:
                raise VelplanError("--students: give at least one student id")
            if len(students) > MAX_RANDOM:
                raise VelplanError(f"--students: {len(students)} ids is more than a batch draws (at most {MAX_RANDOM})")
        spread = _spread(args.spread)
        if not 0 < spread < 1:
            raise VelplanError(f"--spread must be between 0 and 100 %, not {spread * 100:g} %")
    return require, students, spread


def run_batch_cmd(args) -> int:
    require, students, spread = _check(args)
    out = Path(args.output)
    made = False
    if not out.is_dir():
        if not (out.parent if str(out.parent) else Path(".")).is_dir():
            raise VelplanError(f"cannot write {out}: directory {out.parent} does not exist")
        out.mkdir()
        made = True
    try:
        return _run(args, out, require, students, spread)
    except BaseException:
        if made and not any(out.iterdir()):  # refused before anything was written: leave nothing
            out.rmdir()
        raise


def _run(args, out: Path, require, students, spread) -> int:
    from velplan import batch

    failures: list = []
    extra: dict = {}
    if args.random is not None:
        stats: dict = {}
        variants, failures = batch.random_variants(args.base, args.random, args.seed, spread=spread,
                                                   students=students, require=require, stats=stats)
        if require:
            sys.stdout.write(f"--require: {stats['drawn']} draw(s), {stats['rejected']} rejected by the constraints, "
                             f"{stats['not_assembled']} not assembling; {len(variants)} variant(s) kept\n")
        from velplan.io import write_atomic

        write_atomic(out / "variants.csv", batch.variants_csv(variants))
        extra = {"assignment": args.seed, "base": args.base, "spread": spread,
                 **({"require": args.require, "draws": stats} if require else {}),
                 "rule": "numpy default_rng(int(sha256(student + '\\x1f' + assignment)[:16], big-endian)); "
                         "factors uniform in [1 - spread, 1 + spread], rounded to 3 significant digits"}
    else:
        variants = batch.read_variants(args.table, base=args.base)
    if args.positions:
        variants = [batch.Variant(v.name, v.base, {"positions": args.positions, **v.overrides}, v.row)
                    for v in variants]
    opts = batch.Options(str(out), png=args.png, lang=args.lang, fmt=args.format, sheets=not args.no_sheets,
                         note=args.note, figures=bool(args.require))
    report = batch.run_batch(variants, opts, jobs=args.jobs, failures=failures, extra=extra,
                             progress=None if args.quiet else batch.progress_bar())
    sys.stdout.write(f"{len(report.answers)} variant(s) studied into {out}; answer key {report.files[0].name}, "
                     f"{report.files[1].name}\n")
    for f in report.failures:
        sys.stderr.write(f"velplan: error: {f.line()}\n")
    return 2 if report.failures else 0
