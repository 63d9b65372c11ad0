"""The first worksheet of an Excel workbook (.xlsx) as rows of text, with the standard library
only: an .xlsx file is a zip of XML parts (ECMA-376); the cells' values are read from the sheet
part and the shared-strings table. Formulas give their cached values; dates stay numbers.
"""

from __future__ import annotations

import re
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

from velplan.errors import VelplanError

_MAIN = "{http://schemas.openxmlformats.org/spreadsheetml/2006/main}"
_REL = "{http://schemas.openxmlformats.org/officeDocument/2006/relationships}"
_PKG = "{http://schemas.openxmlformats.org/package/2006/relationships}"
_CELL = re.compile(r"^([A-Z]+)(\d+)$")
MAX_CELLS = 1_000_000
"""Most cells read from one sheet (a department's variant table has a few thousand)."""


def _column(letters: str) -> int:
    """``"A"`` → 0, ``"Z"`` → 25, ``"AA"`` → 26."""
    n = 0
    for ch in letters:
        n = 26 * n + (ord(ch) - 64)
    return n - 1


def _text(node) -> str:
    """The text of a string item: its plain ``<t>`` and its rich-text runs' ``<t>`` joined
    (phonetic runs ``<rPh>`` left out)."""
    parts = []
    for child in node:
        if child.tag == f"{_MAIN}t":
            parts.append(child.text or "")
        elif child.tag == f"{_MAIN}r":
            parts += [t.text or "" for t in child.iter(f"{_MAIN}t")]
    return "".join(parts)


def _number(text: str) -> str:
    """A stored number as a table would show it: ``"2.0"`` → ``"2"``, else as stored."""
    try:
        value = float(text)
    except ValueError:
        return text
    return str(int(value)) if value.is_integer() and abs(value) < 1e15 else repr(value)


def read_rows(path: str | Path) -> list[list[str]]:
    """The first worksheet of ``path`` as rows of cell texts (empty cells as ``""``)."""
    path = Path(path)
    try:
        with zipfile.ZipFile(path) as z:
            names = set(z.namelist())
            book = ET.fromstring(z.read("xl/workbook.xml"))
            sheets = book.find(f"{_MAIN}sheets")
            first = sheets[0] if sheets is not None and len(sheets) else None
            if first is None:
                raise VelplanError(f"workbook {path} has no worksheet")
            rid = first.get(f"{_REL}id")
            rels = ET.fromstring(z.read("xl/_rels/workbook.xml.rels"))
            target = next((r.get("Target") for r in rels.iter(f"{_PKG}Relationship") if r.get("Id") == rid), None)
            if target is None:
                raise VelplanError(f"workbook {path}: its first sheet's part is missing")
            part = target.lstrip("/") if target.startswith("/") else f"xl/{target}"
            shared = []
            if "xl/sharedStrings.xml" in names:
                sst = ET.fromstring(z.read("xl/sharedStrings.xml"))
                shared = [_text(si) for si in sst.iter(f"{_MAIN}si")]
            sheet = ET.fromstring(z.read(part))
    except (zipfile.BadZipFile, KeyError, ET.ParseError, OSError) as exc:
        raise VelplanError(f"cannot read workbook {path}: {exc}") from None
    cells: dict[tuple[int, int], str] = {}
    for c in sheet.iter(f"{_MAIN}c"):
        m = _CELL.match(c.get("r", ""))
        if m is None:
            continue
        kind = c.get("t", "n")
        v = c.find(f"{_MAIN}v")
        if kind == "s" and v is not None:
            try:
                value = shared[int(v.text)]
            except (ValueError, IndexError):
                raise VelplanError(f"workbook {path}: cell {c.get('r')} names a missing shared string") from None
        elif kind == "inlineStr":
            node = c.find(f"{_MAIN}is")
            value = _text(node) if node is not None else ""
        elif kind == "b" and v is not None:
            value = "true" if v.text == "1" else "false"
        elif v is not None and v.text is not None:
            value = v.text if kind in ("str", "e") else _number(v.text)
        else:
            value = ""
        cells[int(m.group(2)) - 1, _column(m.group(1))] = value
        if len(cells) > MAX_CELLS:
            raise VelplanError(f"workbook {path}: more than {MAX_CELLS} cells")
    if not cells:
        return []
    rows = max(r for r, _ in cells) + 1
    cols = max(c for _, c in cells) + 1
    return [[cells.get((r, c), "") for c in range(cols)] for r in range(rows)]
