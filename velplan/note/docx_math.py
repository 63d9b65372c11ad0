"""The note's formulas converted beside its text: pandoc converts the note with every formula
written as a one-letter placeholder (`PLACEHOLDER`, inline or displayed as the formula is) while
a second pandoc converts each distinct formula once (`FormulaRun`); the placeholders' Word
equations are then replaced by the formulas' own, in order. The two conversions run at once
(the formulas are nearly half of pandoc's work on a note), and the document is the one pandoc
makes of the whole note: the same paragraphs with the same styles (a displayed placeholder is
a displayed formula to pandoc), the same equations. Where anything does not match — a formula
pandoc would not read as one, a count that differs — `put_formulas` says so and the writer
converts the whole note again as one."""

from __future__ import annotations

import copy
import zipfile
from io import BytesIO
from pathlib import Path

from velplan.note.blocks import Equation, Math, Para
from velplan.note.pandoc import Pandoc

PLACEHOLDER = "q"
"""The TeX each formula is written as in the text pandoc converts."""
_M = "{http://schemas.openxmlformats.org/officeDocument/2006/math}"
_W = "{http://schemas.openxmlformats.org/wordprocessingml/2006/main}"


def formulas(note) -> list[tuple[str, bool]]:
    """(TeX, displayed) of every formula of ``note`` in the order its Markdown writes them."""
    from velplan.note.markdown import para_parts

    out = []
    for b in note.blocks:
        if isinstance(b, Para):
            out += [(x.tex, False) for x in para_parts(b, note.lang) if isinstance(x, Math)]
        elif isinstance(b, Equation):
            out.append((b.tex, True))
    return out


class FormulaRun:
    """Pandoc converting each distinct formula once, one to a paragraph, in the background."""

    def __init__(self, wanted: list[tuple[str, bool]], tmp: Path):
        self.distinct = list(dict.fromkeys(wanted))
        tmp.mkdir(exist_ok=True)
        source = "\n\n".join(f"$${tex}$$" if shown else f"${tex}$" for tex, shown in self.distinct) + "\n"
        self.run = Pandoc(source, "docx", tmp)

    def equations(self) -> dict[tuple[str, bool], object] | None:
        """Each formula's equation element (``m:oMath``, or ``m:oMathPara`` displayed), or None
        where a paragraph holds anything else (pandoc did not read it as a formula)."""
        from docx.oxml import parse_xml

        root = parse_xml(zipfile.ZipFile(BytesIO(self.run.result())).read("word/document.xml"))
        paras = root.find(f"{_W}body").findall(f"{_W}p")
        if len(paras) != len(self.distinct):
            return None
        out = {}
        for (tex, shown), para in zip(self.distinct, paras):
            kids = [k for k in para if k.tag != f"{_W}pPr"]
            if len(kids) != 1 or kids[0].tag != (f"{_M}oMathPara" if shown else f"{_M}oMath"):
                return None
            out[(tex, shown)] = kids[0]
        return out

    def cancel(self) -> None:
        self.run.cancel()


def put_formulas(doc, wanted: list[tuple[str, bool]], equations) -> bool:
    """Replace the placeholders' equations of ``doc`` (python-docx) by ``equations``' own, in
    the order of ``wanted``; False, with ``doc`` unchanged, where they do not match one to one."""
    if equations is None or any(key not in equations for key in wanted):
        return False
    found = [e for e in doc.element.body.iter(f"{_M}oMathPara", f"{_M}oMath")
             if e.getparent().tag != f"{_M}oMathPara"]
    if len(found) != len(wanted):
        return False
    for e, (_, shown) in zip(found, wanted):
        text = "".join(t.text or "" for t in e.iter(f"{_M}t"))
        if e.tag != (f"{_M}oMathPara" if shown else f"{_M}oMath") or text != PLACEHOLDER:
            return False
    for e, key in zip(found, wanted):
        e.getparent().replace(e, copy.deepcopy(equations[key]))
    return True
