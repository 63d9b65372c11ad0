"""``velplan examples``, ``velplan info`` and ``velplan analyze``."""

from __future__ import annotations

import csv
import io
import math

import numpy as np

from velplan.analysis.numbering import position_number, position_numbers
from velplan.analysis.solver import Kinematics, transfer_functions
from velplan.cli.common import add_mechanism, add_output, emit, parse_angles, positive_int
from velplan.mechanism.loader import example_names, load
from velplan.mechanism.structure import pairs, structure
from velplan.study import Study


def register(sub) -> None:
    p = sub.add_parser("examples", help="list the bundled example mechanisms")
    p.add_argument("--all", action="store_true",
                   help="also list the catalogue of course-work mechanisms (velplan.catalogue)")
    p.set_defaults(run=run_examples)

    p = sub.add_parser("info", help="structure, mobility, groups, extreme positions, stroke, K")
    add_mechanism(p)
    p.add_argument("--svg", metavar="FILE", help="also draw the structural analysis (the initial mechanism and "
                                                 "each group apart) to FILE.svg (or .png, .pdf)")
    p.add_argument("--lang", choices=("en", "ru", "uk", "zh"), default=None,
                   help="language of the drawing (default: the locale's, else en)")
    p.set_defaults(run=run_info)

    p = sub.add_parser("analyze", help="positions, velocities, accelerations at crank angles")
    add_mechanism(p)
    where = p.add_mutually_exclusive_group()
    where.add_argument("--angles", metavar="DEG,DEG,…", help="absolute crank angles in degrees")
    where.add_argument("--positions", metavar="N", type=positive_int, default=12,
                       help="N positions evenly spaced from the reference position (default 12)")
    p.add_argument("--format", choices=("table", "csv", "json", "jsonl", "parquet"), default="table",
                   help="table, csv (a row per position), json (one document), jsonl (a JSON object per "
                        "position, per line) or parquet (the CSV's columns; -o FILE, pip install "
                        "\".[parquet]\"); all but table are written as they are computed")
    p.add_argument("--engine", choices=("auto", "numpy", "compiled"), default="auto",
                   help="solver engine: compiled needs numba (pip install numba); "
                        "auto uses it from 2e6 angles when installed (default)")
    add_output(p)
    p.set_defaults(run=run_analyze)


def run_examples(args) -> int:
    lines = []
    for name in example_names():
        mech = load(name)
        lines.append(f"{name:<14} {mech.description or mech.title}")
    if getattr(args, "all", False):
        from velplan.mechanism.loader import catalogue_names

        names = catalogue_names()
        width = max(len(n) for n in names) if names else 0
        lines += ["", "catalogue:"]
        for name in names:
            mech = load(name)
            lines.append(f"{name:<{width}} {mech.description or mech.title}")
    emit("\n".join(lines), None)
    return 0


def run_info(args) -> int:
    study = Study(args.mechanism)
    mech = study.mechanism
    st = structure(mech)
    out = [f"{mech.name}: {mech.title}".rstrip(": "), ""]
    c = mech.crank
    out.append(f"crank {c.link}: {c.pivot}{c.tip} = {c.length:g} m, ω1 = {c.omega:+.6g} rad/s ({c.rpm:+.4g} rpm)")
    out.append(f"moving links n = {st.n_links}, lower pairs p5 = {st.p5}, higher pairs p4 = {st.p4}")
    out.append(f"mobility (Chebyshev): {st.formula()}")
    out.append("groups (Assur's, in solving order):")
    lower = pairs(mech)
    for name, kind, cls, order, links in st.groups:
        outer = ", ".join(p.name for p in lower if p.group == name and not set(p.links) <= set(links))
        out.append(f"  {name:<8} {kind}  class {cls}, order {order}, links {', '.join(links)}; outer pairs {outer}")
    out.append(f"mechanism of class {st.mechanism_class}; structure: {st.structure_formula(c.link)}")
    out.append("extreme positions (crank angle → value):")
    for q, roots in study.extremes.items():
        unit = "°" if q.startswith("link") else " m"
        vals = "; ".join(
            f"{math.degrees(e.phi):.6f}° → {(math.degrees(e.value) if unit == '°' else e.value):.6g}{unit} ({e.kind})"
            for e in roots
        )
        out.append(f"  {q:<10} {vals or 'none (full rotation or no reversal)'}")
    s = study.stroke
    if s is not None:
        h = f"{math.degrees(s.H):.6g}°" if s.quantity.startswith("link") else f"{s.H:.9g} m"
        out.append(f"output {s.quantity}: stroke H = {h}, θ = {math.degrees(s.theta):.6f}°, K = {s.K:.6f}")
        out.append(f"  working (slow) stroke from φ = {math.degrees(s.start.phi):.6f}° to {math.degrees(s.end.phi):.6f}°")
        if s.reversals > 2:
            out.append(f"  warning: the output reverses {s.reversals} times per turn: H is its overall travel, "
                       "θ and K refer to its highest and lowest extremes only")
    out.append(f"reference position 1 at φ = {math.degrees(study.reference):.6f}°")
    if getattr(args, "svg", None):
        out.append(f"wrote {save_structure(mech, args.svg, args.lang)}")
    emit("\n".join(out), None)
    return 0


def save_structure(mech, path: str, lang: str | None) -> str:
    """Draw the structural analysis of ``mech`` to ``path`` (.svg, .png or .pdf)."""
    from pathlib import Path

    from velplan.cli.common import default_language
    from velplan.cli.convert import pose
    from velplan.errors import VelplanError
    from velplan.mechanism.drawn_write import drawn_tables
    from velplan.render import export
    from velplan.render.style import SheetStyle
    from velplan.render.svg import to_svg
    from velplan.views.structure import structure_view

    writers = {".svg": export.write_svg, ".png": export.write_png, ".pdf": export.write_pdf}
    suffix = Path(path).suffix.lower()
    if suffix not in writers:
        raise VelplanError(f"--svg {path}: write a .svg, .png or .pdf file")
    tables = drawn_tables(mech, *pose(mech))
    lang = lang or default_language()
    svg = to_svg(structure_view(mech, tables["joint"], lang=lang), SheetStyle(language=lang))
    writers[suffix](svg, path)
    return path


def run_analyze(args) -> int:
    angles = parse_angles(args.angles) if args.angles is not None else None
    if args.format != "table":
        from velplan.cli.stream import check_format

        check_format(args.format, args.output)
    study = Study(args.mechanism, n=args.positions, angles=angles, engine=args.engine)
    if args.format == "table":
        emit(to_table(study.kinematics), args.output)
        return 0
    from velplan.cli.stream import write_rows

    w, e = study.crank_motion
    write_rows(args.output, args.format, chunks(study, args.format, STREAM_CHUNK),
               head=lambda: _head(study.mechanism.name, w, e))
    return 0


def to_json(kin: Kinematics) -> str:
    """The analysis as JSON in SI units with radians (null where not assembled), as
    ``velplan analyze --format json`` writes it."""
    from velplan.cli.stream import json_document, json_rows

    tree, reasons = _entries(kin, 0)
    return b"".join(json_document(_head(kin.mechanism.name, kin.omega1, kin.epsilon1), "positions",
                                  [json_rows(tree, "json", reasons)])).decode("utf-8")


def _rows(kin: Kinematics) -> tuple[list[str], list[list[float]]]:
    head, cols = _columns(kin)
    return head, [list(r) for r in np.column_stack(cols)]


def to_csv(kin: Kinematics) -> str:
    """One row per position, one column per coordinate (SI units, radians)."""
    head, rows = _rows(kin)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(head)
    for ok, r in zip(kin.valid, rows):
        # a position not assembled or singular: its angle, then empty cells
        w.writerow([int(r[0]), f"{r[1]:.12g}"] + [f"{x:.12g}" if ok and math.isfinite(x) else "" for x in r[2:]])
    return buf.getvalue()


STREAM_CHUNK = 16384
"""Positions solved and written at a time by `stream` (a few MB of arrays)."""


def stream(study: Study, fmt: str = "csv", chunk: int = STREAM_CHUNK):
    """The study's positions as CSV (`to_csv`'s bytes), line-delimited JSON or one JSON
    document (`to_json`'s), in pieces of ``chunk`` positions solved and formatted in turn:
    memory stays bounded however many positions there are. JSON lines hold the document's
    per-position objects with numbers to 12 significant digits (as the CSV); the document's
    numbers are exact."""
    from velplan.cli.stream import json_document, text_pieces

    pieces = text_pieces(chunks(study, fmt, chunk), fmt)
    if fmt != "json":
        return pieces
    w, e = study.crank_motion
    return json_document(_head(study.mechanism.name, w, e), "positions", pieces)


def _head(name: str, omega1, epsilon1) -> dict:
    return {"mechanism": name, "omega1": omega1, "epsilon1": epsilon1}


def chunks(study: Study, fmt: str, chunk: int = STREAM_CHUNK):
    """(tree, reasons) of each chunk of positions (`velplan.cli.stream.write_rows`): the CSV's
    columns for "csv" and "parquet", the JSON objects' keys otherwise."""
    from velplan.analysis.chunks import chunked_kinematics

    w, e = study.crank_motion
    for a, kin in chunked_kinematics(study.mechanism, study.phi, omega1=w, epsilon1=e, engine=study.engine,
                                     chunk=chunk):
        if fmt not in ("csv", "parquet"):
            yield _entries(kin, a)
            continue
        head, cols = _columns(kin, a)
        bad = ~kin.valid  # a position not assembled or singular: its angle, then empty cells
        yield {name: (np.where(bad, np.nan, c) if m > 1 and bad.any() else c)
               for m, (name, c) in enumerate(zip(head, cols))}, None


def _columns(kin: Kinematics, first: int = 0) -> tuple[list[str], list[np.ndarray]]:
    """CSV header and columns of `to_csv`, positions numbered from ``first`` + 1."""
    head = ["position", "phi_deg"]
    cols = [position_numbers(range(first, first + len(kin))), kin.phi_deg]
    for k, j in kin.point_index.items():
        for q, arr in (("x", kin.positions[:, j, 0]), ("y", kin.positions[:, j, 1]),
                       ("vx", kin.velocities[:, j, 0]), ("vy", kin.velocities[:, j, 1]),
                       ("ax", kin.accelerations[:, j, 0]), ("ay", kin.accelerations[:, j, 1])):
            head.append(f"{k}.{q}")
            cols.append(arr)
    for k, j in kin.link_index.items():
        for q, arr in (("angle", kin.angles[:, j]), ("omega", kin.omegas[:, j]), ("epsilon", kin.epsilons[:, j])):
            head.append(f"{k}.{q}")
            cols.append(arr)
    return head, cols


def _entries(kin: Kinematics, first: int) -> tuple[dict, dict]:
    """(tree, reasons) of the positions of ``kin`` (numbered from ``first`` + 1) as JSON objects
    (`velplan.cli.stream.json_rows`); one not assembled or singular has null rates and says why."""
    ok = kin.valid
    singular, least = kin.singular, kin.min_condition()
    reasons = {int(i): (f"singular: a group at a toggle (condition {least[i]:.2g}), velocities undetermined"
                        if singular[i] else "not assembled") for i in np.flatnonzero(~ok)}
    rate = (lambda a: a) if not reasons else (lambda a: np.where(ok, a, np.nan))  # noqa: E731 (never a wrong number)
    P, V, A = kin.positions, kin.velocities, kin.accelerations
    marks = point_marks(kin.mechanism)
    tree = {"position": position_numbers(range(first, first + len(kin))), "phi_deg": kin.phi_deg, "valid": ok,
            "points": {k: {"x": P[:, j, 0], "y": P[:, j, 1], "vx": rate(V[:, j, 0]), "vy": rate(V[:, j, 1]),
                           "ax": rate(A[:, j, 0]), "ay": rate(A[:, j, 1]), **marks.get(k, {})}
                       for k, j in kin.point_index.items()},
            "links": {k: {"angle": kin.angles[:, j], "omega": rate(kin.omegas[:, j]),
                          "epsilon": rate(kin.epsilons[:, j])} for k, j in kin.link_index.items()},
            "slides": {k: {"s": kin.slides[:, j, 0], "v": rate(kin.slides[:, j, 1]), "a": rate(kin.slides[:, j, 2])}
                       for k, j in kin.slide_index.items()},
            "condition": {k: kin.condition[:, j] for k, j in kin.group_index.items()}}
    return tree, reasons


def point_marks(mech) -> dict[str, dict[str, str]]:
    """The points whose velocity and acceleration are not the derivatives of their position:
    name → {"kind": "special" (Assur's special point of a triad) or "coincident" (a guide
    link's point at a slider's joint), "link": the link whose point it is at each instant}."""
    from velplan.mechanism.structure import coincident_points

    special = {p for g in mech.groups for p in g.special_points()}
    return {name: {"kind": "special" if name in special else "coincident", "link": link}
            for name, link in coincident_points(mech).items()}


def to_table(kin: Kinematics) -> str:
    """Transfer functions |V|/ω1 (m) and ω/ω1 per position, then |V| and |a| of every point."""
    tf = transfer_functions(kin) if kin.omega1 else {}
    n = len(kin)
    head = f"{'quantity':<14}" + "".join(f"{k:>11}" for k in position_numbers(range(n)))
    lines = [f"{kin.mechanism.name}: ω1 = {kin.omega1:+.6g} rad/s", head,
             f"{'φ, deg':<14}" + "".join(f"{x:>11.2f}" for x in kin.phi_deg)]

    ok = kin.valid

    def row(label: str, values) -> str:
        # positions not assembled or singular print "—"; round-off at dead centres prints 0,
        # judged against the row's largest finite value at the good positions
        values = np.where(ok, np.asarray(values, dtype=float), np.nan)
        finite = np.isfinite(values)
        big = float(np.max(np.abs(values[finite]), initial=0.0))
        values = np.where(finite & (np.abs(values) <= 1e-12 * big), 0.0, values)
        return f"{label:<14}" + "".join(f"{v:>11.4g}" if math.isfinite(v) else f"{'—':>11}" for v in values)

    lines.append("transfer functions (velocity analogues)")
    for k in kin.point_index:
        if k in dict(kin.mechanism.ground):
            continue
        lines.append(row(f"V_{k}/ω1, m", tf.get(f"V_{k}", np.full(n, np.nan))))
    for k in kin.link_index:
        lines.append(row(f"ω{k}/ω1", tf.get(f"w_{k}", np.full(n, np.nan))))
    lines.append("velocities |V|, m/s and accelerations |a|, m/s²")
    for k, j in kin.point_index.items():
        if k in dict(kin.mechanism.ground):
            continue
        lines.append(row(f"V_{k}", np.hypot(*kin.velocities[:, j].T)))
        lines.append(row(f"a_{k}", np.hypot(*kin.accelerations[:, j].T)))
    for k, j in kin.link_index.items():
        lines.append(row(f"ω{k}, rad/s", kin.omegas[:, j]))
        lines.append(row(f"ε{k}, rad/s²", kin.epsilons[:, j]))
    singular = kin.singular
    if singular.any():
        bad = ", ".join(f"{position_number(i)} (condition {kin.min_condition()[i]:.2g})" for i in np.flatnonzero(singular))
        lines.append(f"singular (a group at a toggle, velocities undetermined) at positions: {bad}")
    if (~kin.valid & ~singular).any():
        bad = ", ".join(str(position_number(i)) for i in np.flatnonzero(~kin.valid & ~singular))
        lines.append(f"not assembled at positions: {bad}")
    return "\n".join(lines)
