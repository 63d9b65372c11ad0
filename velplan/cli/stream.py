"""Output written as it is computed: a text stream to standard output or to a file that
appears, atomically, only when it is complete (no half-written file after an error); rows of
many positions as CSV, JSON lines, one JSON document or Parquet (a row group per chunk), a
chunk of positions at a time."""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import sys
import tempfile
from pathlib import Path
from typing import Callable, Iterable, Iterator

import numpy as np

from velplan.errors import VelplanError

BUFFER = 1 << 20
"""Bytes buffered before a write to the file (1 MiB)."""


@contextlib.contextmanager
def open_output(path: str | os.PathLike | None, *, binary: bool = False) -> Iterator:
    """A file object to write to: standard output when ``path`` is None, else a temporary
    file beside ``path`` renamed into place when the block ends without an error (removed
    otherwise). Text is UTF-8 with ``\\n`` line ends."""
    if path is None:
        sys.stdout.flush()  # what was printed before comes first
        raw = getattr(sys.stdout, "buffer", None)
        try:
            if binary and raw is not None:
                yield raw
                raw.flush()
            else:  # text, or bytes to a text-only stream (redirected in process): whole rows decode
                yield _TextSink(sys.stdout) if binary else sys.stdout
                sys.stdout.flush()
        except BrokenPipeError:  # the reader stopped early (| head): not an error
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise VelplanError(f"cannot write {target}: directory {directory} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
    try:
        raw = os.fdopen(fd, "wb", buffering=BUFFER)
        with (raw if binary else io.TextIOWrapper(raw, encoding="utf-8", newline="\n",
                                                   write_through=False)) as handle:
            yield handle
        try:
            mode = target.stat().st_mode & 0o777
        except OSError:
            mode = 0o644
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException as exc:
        Path(tmp).unlink(missing_ok=True)
        if isinstance(exc, OSError):
            raise VelplanError(f"cannot write {target}: {exc.strerror or exc}") from None
        raise


class _TextSink:
    """Bytes written as UTF-8 text to a text stream."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, data: bytes) -> int:
        return self.stream.write(data.decode("utf-8"))


# ---- rows of many positions as CSV, JSON lines or one JSON document ------------------------
# A command describes one position as a tree: keys, in order, to (n,) arrays (one number per
# position; booleans write true/false, integers whole numbers), to strings (the same text at
# every position) or to nested trees. The writers below turn a chunk of positions into text.


def object_layout(tree: dict, *, before: str = "", after: str = "") -> tuple[list[bytes], np.ndarray, dict]:
    """One JSON object per position as `velplan.cli.numfmt.rows` writes it, between ``before``
    and ``after``: its literal texts, the (n, C) values and the keyword arguments ``bools`` and
    ``ints`` of `rows`."""
    lits: list[str] = []
    cols: list[np.ndarray] = []
    lits.append(_object_text(tree, before, lits, cols) + after)
    return [t.encode("utf-8") for t in lits], *_stacked(cols)


def _object_text(node: dict, pending: str, lits: list[str], cols: list[np.ndarray]) -> str:
    """Append to ``lits`` and ``cols`` the texts before each number of ``node`` (the first after
    ``pending``) and its columns; returns the text after its last number. (A function of the
    module, not a closure: a recursive closure is a reference cycle that would hold a chunk's
    arrays until the garbage collector runs.)"""
    pending += "{"
    for m, (key, value) in enumerate(node.items()):
        pending += ("" if m == 0 else ", ") + json.dumps(key, ensure_ascii=False) + ": "
        if isinstance(value, dict):
            pending = _object_text(value, pending, lits, cols)
        elif isinstance(value, str):
            pending += json.dumps(value, ensure_ascii=False)
        else:
            lits.append(pending)
            cols.append(np.asarray(value))
            pending = ""
    return pending + "}"


def _stacked(cols) -> tuple[np.ndarray, dict]:
    """The (n, C) values of ``cols`` and the keyword arguments ``bools`` and ``ints`` of `rows`."""
    kinds = {"bools": [c for c, a in enumerate(cols) if a.dtype == bool],
             "ints": [c for c, a in enumerate(cols) if a.dtype.kind in "iu"]}
    return np.column_stack(cols).astype(float), kinds


def json_rows(tree: dict, fmt: str, reasons: dict[int, str] | None = None) -> bytes:
    """The positions of ``tree`` as JSON lines (``fmt`` "jsonl": numbers to 12 significant
    digits) or as the entries of `json_document` (``fmt`` "json": numbers exact, each entry
    after ``",\\n  "``); the positions in ``reasons`` (index → text) end with a "reason" key."""
    from velplan.cli.numfmt import rows

    exact = fmt == "json"
    before, after = (",\n  ", "") if exact else ("", "\n")
    if not reasons:
        lits, values, kinds = object_layout(tree, before=before, after=after)
        return rows(values, lits, na=b"null", exact=exact, **kinds)
    lits, values, kinds = object_layout(tree, after="\n")
    lines = rows(values, lits, na=b"null", exact=exact, **kinds).decode("utf-8").split("\n")[:-1]
    for i, text in reasons.items():
        lines[i] = lines[i][:-1] + f', "reason": {json.dumps(text, ensure_ascii=False)}}}'
    return "".join(before + line + after for line in lines).encode("utf-8")


def csv_rows(tree: dict, header: bool) -> bytes:
    """The numbers of ``tree`` as CSV rows (empty cells where not finite), one column per number
    named by its keys joined with dots, after the header line when ``header``."""
    from velplan.cli.numfmt import rows

    names, cols = zip(*_numbers(tree))
    values, kinds = _stacked(cols)
    text = rows(values, [b""] + [b","] * (len(cols) - 1) + [b"\n"], **kinds)
    return (csv_header(list(names)) if header else b"") + text


def _numbers(node: dict, prefix: str = "") -> Iterator[tuple[str, np.ndarray]]:
    """(dotted keys, column) of every number of ``node``, in order."""
    for key, value in node.items():
        if isinstance(value, dict):
            yield from _numbers(value, f"{prefix}{key}.")
        elif not isinstance(value, str):
            yield prefix + key, np.asarray(value)


def csv_header(names: list[str]) -> bytes:
    """A CSV header line (names quoted where CSV needs it)."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow(names)
    return buf.getvalue().encode("utf-8")


def json_document(head: dict, key: str, entries: Iterable[bytes]) -> Iterator[bytes]:
    """A JSON document written as it is computed: the items of ``head`` (laid out as
    ``json.dumps(indent=1)`` lays them out; an ndarray as a list of its numbers, exact), then
    ``key``: a list of the entries of `json_rows` (chunks of ``",\\n  {…}"``), one per line."""
    yield b"{"
    for m, (name, value) in enumerate(head.items()):
        yield f'{"," if m else ""}\n {json.dumps(name, ensure_ascii=False)}: '.encode("utf-8")
        if isinstance(value, np.ndarray):
            yield from _json_numbers(value)
        else:
            yield json.dumps(value, indent=1, ensure_ascii=False).replace("\n", "\n ").encode("utf-8")
    yield f'{"," if head else ""}\n {json.dumps(key, ensure_ascii=False)}: ['.encode("utf-8")
    first = True
    for chunk in entries:
        if first and chunk:
            chunk, first = chunk[1:], False  # the first entry has no comma before it
        yield chunk
    yield b"\n ]\n}\n"


def _json_numbers(values: np.ndarray, chunk: int = 65536) -> Iterator[bytes]:
    """A JSON list of ``values`` (exact; null where not finite), ``chunk`` numbers at a time."""
    from velplan.cli.numfmt import rows

    yield b"["
    for a in range(0, len(values), chunk):
        text = rows(values[a:a + chunk, None], [b", ", b""], na=b"null", exact=True)
        yield text[2:] if a == 0 else text
    yield b"]"


# ---- chunks of rows to a file or standard output --------------------------------------------
# A command yields, per chunk of positions, (tree, reasons): the tree of its numbers (for "csv"
# and "parquet" the CSV's columns) and the positions that say why they have no rates (or None).

BINARY = ("npz", "parquet")
"""Formats that are written only to a file (``-o``)."""


def check_format(fmt: str, output) -> None:
    """Refuse a binary ``fmt`` to standard output, and Parquet without pyarrow (one line each)."""
    if fmt in BINARY and not output:
        raise VelplanError(f"--format {fmt} is binary: give -o FILE")
    if fmt == "parquet":
        try:
            import pyarrow  # noqa: F401
            import pyarrow.parquet  # noqa: F401
        except ImportError:
            raise VelplanError('--format parquet needs pyarrow: pip install ".[parquet]"') from None


def text_pieces(chunks: Iterable[tuple[dict, dict | None]], fmt: str) -> Iterator[bytes]:
    """Each chunk's rows as CSV (the header before the first), JSON lines ("jsonl") or the
    entries of `json_document` ("json")."""
    for n, (tree, reasons) in enumerate(chunks):
        yield csv_rows(tree, header=n == 0) if fmt == "csv" else json_rows(tree, fmt, reasons)


def write_rows(output, fmt: str, chunks: Iterable[tuple[dict, dict | None]], head=None) -> None:
    """Write ``chunks`` to ``output`` (None: standard output) as they come: CSV, JSON lines,
    Parquet, or with ``head`` (a callable giving `json_document`'s head) one JSON document.
    The head and the first chunk are computed before a byte is written: a refusal leaves no
    half document on standard output."""
    import itertools

    chunks = iter(chunks)
    top = head() if fmt == "json" else None
    first = list(itertools.islice(chunks, 1))
    chunks = itertools.chain(first, chunks)
    with open_output(output, binary=True) as out:
        if fmt == "parquet":
            write_parquet(out, (tree for tree, _ in chunks))
            return
        pieces = text_pieces(chunks, fmt)
        for piece in json_document(top, "positions", pieces) if fmt == "json" else pieces:
            out.write(piece)


def write_parquet(out, trees: Iterable[dict], metadata: Callable[[], dict] | None = None) -> int:
    """The numbers of each tree as one row group of a Parquet file written to ``out`` (a binary
    file object): the CSV's columns (dotted names), float64 with null where not finite, whole
    numbers int64, booleans bool, arrays of text strings; then the file's key-value metadata
    ``metadata()`` (str → str), when given, read after the last tree. Returns the number of row
    groups."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    writer, groups = None, 0
    try:
        for tree in trees:
            names, cols = zip(*_numbers(tree))
            table = pa.Table.from_arrays([_arrow(c) for c in cols], names=list(names))
            if writer is None:
                writer = pq.ParquetWriter(out, table.schema)
            writer.write_table(table.cast(writer.schema), row_group_size=max(table.num_rows, 1))
            groups += 1
        if writer is not None and metadata is not None:
            writer.add_key_value_metadata(metadata())
    finally:
        if writer is not None:
            writer.close()
    return groups


def _arrow(column: np.ndarray):
    """One column as an Arrow array: floats with null where not finite."""
    import pyarrow as pa

    a = np.asarray(column)
    if a.dtype.kind == "f":
        return pa.array(a.astype(np.float64, copy=False), mask=~np.isfinite(a))
    return pa.array(a.astype(np.int64, copy=False) if a.dtype.kind in "iu" else a)
