"""Variant batches: a department's table of variants → per-variant sheets and an answer key.

A variant table has one row per variant: a base mechanism (a bundled example, a catalogue
name or a TOML path) and overrides of its numbers by the dotted keys of the mechanism file
(`velplan.mechanism.keys`, the one table of keys that ``velplan sweep --vary`` reads too:
``crank.length``, ``group.2-3.lengths.0``, ``group.G.sides.1``, ``link.4.mass``,
``load.Fc.force``, ``dynamics.delta`` …; ``crank.rpm`` or ``crank.omega`` sets the speed),
each value checked as the file loader checks it, and ``positions``, the number of positions
of the variant (default 12).

CSV: a header ``variant,base,key,key,…`` (``variant`` optional: rows are numbered from 1;
``base`` optional when ``--base`` gives it); an empty cell keeps the base's value.
TOML: ``[[variant]]`` tables with ``name``, ``base`` and the keys (quoted when dotted, or as
nested tables: ``crank = { length = 0.1 }``).

Random variants (`random_variants`): for each student id ``s`` of the assignment ``a`` the
generator is ``numpy.random.default_rng(int(sha256(f"{s}\\x1f{a}")[:16 bytes], big-endian))``;
it multiplies every length (crank, groups, a triad's sides and leads, points along their
links, guide offsets and fixed points' coordinates that are not zero), the crank speed, the masses and inertias and the
loads' magnitudes by independent factors uniform in [1 − spread, 1 + spread] (in the order
the base file writes them) and rounds each to 3 significant digits. A draw that does not
assemble over the whole turn (or whose output does not reverse) is drawn again from the
same generator, at most `MAX_TRIES` times. The same (student, assignment, base, spread)
always gives the same variant, on any machine.

`run_batch` studies the variants on every core (one process per core), writes
``<variant>.svg`` (and ``.png``) and the answer key ``answers.json`` + ``answers.csv``:
per variant and position the crank angle, V/ω1 of the points (m), ω/ω1 of the links
(signed, + in the crank's sense), the balancing moment M_b (N·m, kinetostatics, when the
mechanism has masses or loads), and the stroke H and coefficient K.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
import os
import sys
import tomllib
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Callable

import numpy as np

from velplan.errors import VelplanError
from velplan.io import finite_number, write_atomic

MAX_TRIES = 50
"""Draws per random variant before it is reported as failed."""

DEFAULT_POSITIONS = 12


@dataclass(frozen=True)
class Variant:
    """One row of a variant table: its name, base mechanism, overrides and the row it came from."""

    name: str
    base: str
    overrides: dict[str, Any] = field(default_factory=dict)
    row: str = ""

    @property
    def where(self) -> str:
        return f"variant {self.name}" + (f" ({self.row})" if self.row else "")


@dataclass(frozen=True)
class Failure:
    """A variant that could not be studied: its name, where it came from, and why."""

    variant: str
    where: str
    message: str

    def line(self) -> str:
        return f"{self.where}: {self.message}"


@dataclass
class BatchReport:
    """What a batch produced: the answers of the studied variants and the failures."""

    answers: list[dict]
    failures: list[Failure]
    files: list[Path]


# -- reading tables -------------------------------------------------------------------------


def read_variants(source: str | Path, *, base: str | None = None) -> list[Variant]:
    """Read a variant table (CSV, an Excel workbook's first sheet, or TOML); raises
    `VelplanError` only for an unreadable file — bad cells are found when each variant is
    built, so the others still run."""
    path = Path(source)
    if path.suffix.lower() == ".xlsx":
        from velplan.xlsx import read_rows

        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerows(read_rows(path))
        return _read_csv(buf.getvalue(), path, base)
    try:
        text = path.read_text("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise VelplanError(f"cannot read variant table {path}: {exc}") from None
    if path.suffix.lower() == ".toml":
        return _read_toml(text, path, base)
    if path.suffix.lower() in (".csv", ".txt"):
        return _read_csv(text, path, base)
    raise VelplanError(f"variant table {path}: use a .csv, .xlsx or .toml file, not {path.suffix or 'no suffix'!r}")


def _read_csv(text: str, path: Path, base: str | None) -> list[Variant]:
    first = text.splitlines()[0] if text.strip() else ""
    delim = ";" if first.count(";") > first.count(",") else ","
    rows = [r for r in csv.reader(io.StringIO(text), delimiter=delim) if any(c.strip() for c in r)]
    if not rows:
        raise VelplanError(f"variant table {path} is empty")
    head = [c.strip() for c in rows[0]]
    dupes = sorted({h for h in head if head.count(h) > 1})
    if dupes:
        raise VelplanError(f"variant table {path}: column {dupes[0]!r} appears twice")
    out = []
    for i, r in enumerate(rows[1:], start=2):
        cells = dict(zip(head, (c.strip() for c in r)))
        if len(r) > len(head):
            cells["\0extra"] = f"{len(r)} cells, the header has {len(head)}"
        name = cells.pop("variant", "") or str(i - 1)
        b = cells.pop("base", "") or base or ""
        over = {k: (v.replace(",", ".") if delim == ";" else v) for k, v in cells.items() if v != ""}
        out.append(Variant(name, b, over, f"row {i}"))
    return out


def _read_toml(text: str, path: Path, base: str | None) -> list[Variant]:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise VelplanError(f"malformed TOML in {path}: {exc}") from None
    default = data.get("base", base)
    rows = data.get("variant")
    if not isinstance(rows, list) or not rows:
        raise VelplanError(f"variant table {path}: needs [[variant]] tables")
    out = []
    for i, t in enumerate(rows, start=1):
        t = dict(t)
        name = str(t.pop("name", t.pop("variant", i)))
        b = str(t.pop("base", default or ""))
        out.append(Variant(name, b, _flatten(t), f"[[variant]] #{i}"))
    return out


def _flatten(t: dict, prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in t.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


# -- building a variant -----------------------------------------------------------------------


def base_text(base: str) -> tuple[str, str]:
    """(name, TOML text) of a base mechanism: an example, a catalogue name or a TOML path."""
    from velplan.mechanism.loader import catalogue_names, example_names

    if not base:
        raise VelplanError("no base mechanism (give a 'base' column or --base)")
    p = Path(base)
    if p.suffix.lower() != ".toml":
        for package, names in (("velplan.examples", example_names()), ("velplan.catalogue", catalogue_names())):
            if base in names:
                return base, resources.files(package).joinpath(f"{base}.toml").read_text("utf-8")
    if p.is_file():
        try:
            return p.stem, p.read_text("utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            raise VelplanError(f"cannot read base {p}: {exc}") from None
    raise VelplanError(f"unknown base mechanism {base!r}: not a bundled example, a catalogue name or a file")


def apply_overrides(mech, overrides: dict[str, Any]):
    """(``mech`` with ``overrides`` applied, the number of positions): every key read and
    checked by `velplan.mechanism.keys` as the file loader checks it; `VelplanError` naming
    the key for an unknown key or a value that is not a number the file could hold."""
    from velplan.mechanism import keys

    positions = DEFAULT_POSITIONS
    values = {}
    for key, raw in overrides.items():
        if key == "\0extra":
            raise VelplanError(f"the row has {raw}")
        value = finite_number(raw, key)
        if key == "positions":
            if value != int(value) or value < 1:
                raise VelplanError(f"positions: must be a whole number ≥ 1, not {raw!r}")
            positions = int(value)
            continue
        values[key] = value
    return keys.apply(mech, values), positions


def build_variant(v: Variant):
    """(mechanism, positions) of a variant; `VelplanError` for a bad key, value or file."""
    from dataclasses import replace

    mech = base_mechanism(v.base)
    mech, n = apply_overrides(mech, v.overrides)
    return replace(mech, name=f"{mech.name}-{v.name}"), n


def base_mechanism(base: str):
    """The base mechanism ``base`` loaded (`base_text`): `VelplanError` for a bad file."""
    from velplan.mechanism.loader import parse

    from dataclasses import replace

    from velplan.errors import MechanismError

    name, text = base_text(base)
    try:
        mech = parse(text, name=name)
    except MechanismError as exc:
        raise MechanismError(f"base {base}: {exc}") from None
    return replace(mech, name=name)


# -- random variants --------------------------------------------------------------------------


def generator(student: str, assignment: str) -> np.random.Generator:
    """The reproducible generator of (student, assignment): SHA-256 of ``student``, a unit
    separator and ``assignment``; its first 16 bytes, big-endian, seed numpy's default_rng."""
    digest = hashlib.sha256(f"{student}\x1f{assignment}".encode("utf-8")).digest()
    return np.random.default_rng(int.from_bytes(digest[:16], "big"))


def _random_keys(data: dict) -> list[str]:
    """Dotted keys of the numbers a random variant varies, in the order the file writes them."""
    keys = []
    for p, (x, y) in data.get("ground", {}).items():
        keys += [f"ground.{p}.{j}" for j, c in enumerate((x, y)) if c != 0]
    crank = data.get("crank", {})
    keys.append("crank.length")
    keys.append("crank.rpm" if "rpm" in crank else "crank.omega")
    for g in data.get("group", []):
        n = g.get("name")
        if "lengths" in g:
            keys += [f"group.{n}.lengths.{j}" for j in range(len(g["lengths"]))]
        if "length" in g:
            keys.append(f"group.{n}.length")
        for gk in ("offset",):
            if g.get(gk):
                keys.append(f"group.{n}.{gk}")
        if isinstance(g.get("guide"), dict) and g["guide"].get("offset"):
            keys.append(f"group.{n}.guide.offset")
        keys += _triad_keys(g)
    for p in data.get("point", []):
        if p.get("along"):
            keys.append(f"point.{p['name']}.along")
    for link, t in data.get("link", {}).items():
        keys += [f"link.{link}.{k}" for k in ("mass", "inertia") if t.get(k)]
    for ld in data.get("load", []):
        if "name" in ld:
            keys += [f"load.{ld['name']}.{k}" for k in ("force", "p_max", "moment", "fx", "fy") if ld.get(k)]
    return keys


def _triad_keys(g: dict) -> list[str]:
    """A triad's varied numbers: the base link's sides, each rod lead's length and each block
    lead's guide offset (``group.3-2-4-5.sides.0``, ``group.3-2-4-5.leads.1.length``)."""
    if g.get("kind") != "triad":
        return []
    n = g.get("name")
    keys = [f"group.{n}.sides.{j}" for j in range(len(g.get("sides", [])))]
    for j, lead in enumerate(g.get("leads", [])):
        if not isinstance(lead, dict):
            continue
        if "length" in lead:
            keys.append(f"group.{n}.leads.{j}.length")
        if isinstance(lead.get("guide"), dict) and lead["guide"].get("offset"):
            keys.append(f"group.{n}.leads.{j}.guide.offset")
    return keys


def _round3(x: float) -> float:
    if x == 0:
        return 0.0
    return float(f"{x:.3g}")


def random_variants(base: str, n: int, assignment: str, *, spread: float = 0.10,
                    students: list[str] | None = None, require: list | None = None,
                    stats: dict | None = None) -> tuple[list[Variant], list[Failure]]:
    """``n`` random variants of ``base`` (or one per id in ``students``), each assembled.

    ``require``: constraints on figures of merit (`velplan.sweep.require.parse_require`); a
    draw that breaks one is drawn again. ``stats``, when given, receives the number of draws
    (``"drawn"``), of those rejected by ``require`` (``"rejected"``) and of those that did not
    assemble (``"not_assembled"``)."""
    from velplan.analysis.assembly import check_full_rotation
    from velplan.analysis.extremes import stroke
    from velplan.mechanism.keys import value

    if not 0 < spread < 1:
        raise VelplanError(f"--spread must be between 0 and 100 %, not {spread * 100:g} %")
    name, text = base_text(base)
    base_mech = base_mechanism(base)  # a base that does not load: one line, before any draw
    data = tomllib.loads(text)
    keys = _random_keys(data)
    nominal = {k: value(base_mech, k) for k in keys}
    ids = list(students) if students else [str(i) for i in range(1, n + 1)]
    out, failures = [], []
    count = {"drawn": 0, "rejected": 0, "not_assembled": 0} if stats is None else stats
    count.update({k: count.get(k, 0) for k in ("drawn", "rejected", "not_assembled")})
    for sid in ids:
        rng = generator(sid, assignment)
        last = ""
        for _ in range(MAX_TRIES):
            factors = rng.uniform(1 - spread, 1 + spread, size=len(keys))
            over = {}
            for k, f in zip(keys, factors):
                over[k] = _round3(nominal[k] * f)
            count["drawn"] += 1
            try:
                mech, _n = apply_overrides(base_mech, over)
                broken = _broken(mech, require) if require else ""
                if broken:
                    count["rejected"] += 1
                    last = f"breaks {broken}"
                    continue
                check_full_rotation(mech)
                if mech.output is not None:
                    stroke(mech)
            except VelplanError as exc:
                count["not_assembled"] += 1
                last = str(exc)
                continue
            out.append(Variant(sid, base, over, f"student {sid}"))
            break
        else:
            failures.append(Failure(sid, f"variant {sid} (student {sid})",
                                    f"no draw of {MAX_TRIES} assembles; the last: {last}"))
    return out, failures


def _broken(mech, require: list) -> str:
    """The first constraint of ``require`` that ``mech`` breaks (with its value), or ""; a
    mechanism that does not close over the turn raises `VelplanError`."""
    from velplan.sweep.merit import figures
    from velplan.sweep.require import check

    figs, fail, _ = figures(mech, {})
    if fail[0]:
        raise VelplanError(fail[0])
    return check(figs, require, angular=mech.output is not None and mech.output.link is not None)[0]


def figures_of(mech) -> dict[str, float]:
    """The figures of merit of ``mech`` (`velplan.sweep.merit.FIGURES`) for the answer key."""
    from velplan.sweep.merit import figures

    figs, _, group = figures(mech, {})
    out = {k: (float(v[0]) if math.isfinite(v[0]) else None) for k, v in figs.items()}
    out["gamma_group"] = group[0]
    return out


def variants_csv(variants: list[Variant]) -> str:
    """The variant table as CSV (``variant,base,key…``), as `read_variants` reads it."""
    keys: list[str] = []
    for v in variants:
        keys += [k for k in v.overrides if k not in keys]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["variant", "base", *keys])
    for v in variants:
        w.writerow([v.name, v.base, *(_fmt(v.overrides.get(k, "")) for k in keys)])
    return buf.getvalue()


def _fmt(x) -> str:
    return f"{x:.10g}" if isinstance(x, float) else str(x)


# -- running ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Options:
    outdir: str
    png: bool = False
    lang: str = "en"
    fmt: str = "A1"
    sheets: bool = True
    figures: bool = False
    note: str | None = None
    """Write each variant's explanatory note too, in this format (docx, pdf, html, md)."""


def study_variant(v: Variant, opts: Options) -> dict | Failure:
    """Study one variant, write its sheet and return its answers (or the failure). Runs in a
    worker process; never raises for a problem of the variant itself."""
    from velplan.study import Study

    try:
        mech, n = build_variant(v)
        study = Study(mech, n=n)
        answers = _answers(v, study)
        if opts.figures:
            answers["figures"] = figures_of(mech)
        if opts.sheets:
            from velplan.sheets.kinematic import build_sheet

            sheet = build_sheet(study, fmt=opts.fmt, lang=opts.lang)
            files = sheet.save(Path(opts.outdir) / f"{_safe(v.name)}.svg", png=opts.png)
            answers["files"] = [f.name for f in files]
        if opts.note:
            from velplan.note import build_note, write_note

            path = write_note(build_note(study, fmt=opts.fmt, lang=opts.lang),
                              Path(opts.outdir) / f"{_safe(v.name)}-note.{opts.note}")
            answers["note"] = path.name
        return answers
    except VelplanError as exc:
        return Failure(v.name, v.where, str(exc))
    except (ValueError, ArithmeticError) as exc:  # a value the loader let through but the study cannot use
        return Failure(v.name, v.where, f"{type(exc).__name__}: {exc}")


def _safe(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def _answers(v: Variant, study) -> dict:
    table = study.table
    mech = study.mechanism
    st = study.stroke
    out: dict[str, Any] = {
        "variant": v.name,
        "base": v.base,
        "overrides": v.overrides,
        "positions": int(study.n),
        "crank": mech.crank.link,
        "phi_deg": [round(float(math.degrees(p) % 360), 9) for p in study.phi],
        "V": {k[2:]: _clean(vals) for k, vals in table.rows.items() if k.startswith("V_")},
        "omega": {k[2:]: _clean(vals) for k, vals in table.rows.items() if k.startswith("w_")},
    }
    if st is not None:
        angular = st.quantity.startswith("link")
        out["H"] = float(st.H)
        out["H_unit"] = "rad" if angular else "m"
        out["K"] = float(st.K)
    if mech.masses or mech.loads:
        out["M_b"] = _clean(study.forces().balancing_moments["kinetostatics"])
    return out


def _clean(vals) -> list[float]:
    """Floats, with round-off zeros (below 1e-12 of the row's largest value) written as 0."""
    a = np.asarray(vals, dtype=float)
    big = float(np.nanmax(np.abs(a))) if a.size else 0.0
    return [0.0 if abs(x) <= 1e-12 * big else float(x) for x in a]


ProgressFn = Callable[[int, int, str], None]


def progress_bar(stream=None, width: int = 30) -> ProgressFn:
    """A plain-text progress bar on ``stream`` (stderr): ``[#####·····] 12/30 variant 7``."""
    stream = stream or sys.stderr

    def show(done: int, total: int, label: str) -> None:
        fill = int(width * done / total) if total else width
        stream.write(f"\r[{'#' * fill}{'·' * (width - fill)}] {done}/{total} {label:<24}")
        if done >= total:
            stream.write("\n")
        stream.flush()

    return show


def run_batch(variants: list[Variant], opts: Options, *, jobs: int | None = None,
              progress: ProgressFn | None = None, failures: list[Failure] | None = None,
              extra: dict | None = None) -> BatchReport:
    """Study every variant (on ``jobs`` processes, default all cores), write the sheets and the
    answer key into ``opts.outdir``; failures are collected, not raised."""
    out = Path(opts.outdir)
    if not out.is_dir():
        raise VelplanError(f"cannot write the batch: directory {out} does not exist")
    names = [v.name for v in variants]
    dupes = sorted({n for n in names if names.count(n) > 1})
    if dupes:
        raise VelplanError(f"variant {dupes[0]!r} appears twice in the table")
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(variants) or 1))
    results: dict[str, dict | Failure] = {}
    total = len(variants)
    if jobs == 1:
        for i, v in enumerate(variants):
            results[v.name] = study_variant(v, opts)
            if progress:
                progress(i + 1, total, v.where)
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            futures = {pool.submit(study_variant, v, opts): v for v in variants}
            for i, fut in enumerate(as_completed(futures)):
                v = futures[fut]
                results[v.name] = fut.result()
                if progress:
                    progress(i + 1, total, v.where)
    answers = [r for v in variants if isinstance(r := results[v.name], dict)]
    fails = list(failures or []) + [r for v in variants if isinstance(r := results[v.name], Failure)]
    from velplan import __version__

    key = {"velplan": __version__, **(extra or {}), "variants": answers,
           "failures": [{"variant": f.variant, "where": f.where, "error": f.message} for f in fails]}
    files = [write_atomic(out / "answers.json", json.dumps(key, ensure_ascii=False, indent=1) + "\n"),
             write_atomic(out / "answers.csv", answers_csv(answers))]
    return BatchReport(answers, fails, files)


def answers_csv(answers: list[dict]) -> str:
    """The key as CSV: ``variant,quantity,unit,1,2,…`` — φ, v/ω of the crank of the points,
    ω/ω of the crank of the links (named as the sheet's table names them, `quantity_name`),
    M_b at each position, then H and K (in column 1)."""
    from velplan.plans.table import quantity_name

    n = max((a["positions"] for a in answers), default=0)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["variant", "quantity", "unit", *range(1, n + 1)])
    for a in answers:
        v = a["variant"]
        w.writerow([v, "φ", "deg", *(f"{x:.4f}" for x in a["phi_deg"])])
        for p, vals in a["V"].items():
            w.writerow([v, quantity_name(f"V_{p}", a.get("crank", "1")), "m", *(f"{x:.6g}" for x in vals)])
        for link, vals in a["omega"].items():
            w.writerow([v, quantity_name(f"w_{link}", a.get("crank", "1")), "", *(f"{x:.6g}" for x in vals)])
        if "M_b" in a:
            w.writerow([v, "M_b", "N·m", *(f"{x:.6g}" for x in a["M_b"])])
        if "H" in a:
            w.writerow([v, "H", a["H_unit"], f"{a['H']:.6g}"])
            w.writerow([v, "K", "", f"{a['K']:.6g}"])
    return buf.getvalue()
