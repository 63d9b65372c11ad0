"""Writing the note: .docx (pandoc, formulas as Word equations, figures as SVG with a PNG
fallback), .pdf (pandoc → Typst, typeset by the Typst compiler with the bundled font, its
figures drawn from their SVGs as vector drawings), .html (pandoc, MathML, one self-contained
file) and .md (figures in a folder beside it). Every file is written whole or not at all.
Pandoc runs in the background while the figures are rasterised (`velplan.note.pixels`: by
Typst, in a thread of this process)."""

from __future__ import annotations

import importlib
import io
import os
import shutil
import tempfile
from pathlib import Path

from velplan.errors import VelplanError
from velplan.io import write_atomic
from velplan.note.blocks import Figure
from velplan.note.markdown import to_markdown
from velplan.note.pandoc import INSTALL, Pandoc, installed
FORMATS = {".docx": "docx", ".pdf": "pdf", ".html": "html", ".htm": "html", ".md": "md"}
FONT_DIR = Path(__file__).resolve().parent.parent / "fonts"

TYPST_PREAMBLE = """#set document(title: [{title}])
#set page(paper: "a4", margin: (left: 25mm, right: 15mm, top: 20mm, bottom: 20mm), numbering: "1")
#set text(font: ("Velplan Sans",), size: 11pt, lang: "{lang}")
#show math.equation: set text(font: ("New Computer Modern Math", "Velplan Sans"))
#show math.equation.where(block: true): it => layout(size => {{
  let w = measure(it).width
  if w > size.width {{ scale(x: size.width / w * 100%, y: size.width / w * 100%, reflow: true, it) }} else {{ it }}
}})
#set heading(numbering: "1.1")
#set par(justify: true)
#show figure.caption: it => it.body
#show figure.where(kind: table): set figure.caption(position: top)
#show figure.where(kind: table): set align(left)
#show figure: set block(breakable: false)
#set table(stroke: 0.5pt)
#show table: set text(size: 9pt)
"""


def _module(name: str):
    try:
        return importlib.import_module(name)
    except ImportError as exc:
        raise VelplanError(f"the note needs {name.split('.')[0]} ({exc}); install it with `{INSTALL}`") from None


NEEDS = {"docx": ("typst", "pypandoc", "docx"), "pdf": ("typst", "pypandoc"),
         "html": ("typst", "pypandoc"), "md": ("typst",)}
"""The modules each format needs (typst draws the figures' pixels and typesets the .pdf,
pypandoc brings pandoc), checked before a note is built."""


def require(kind: str) -> None:
    """A one-line error naming the note's extra when a module the format ``kind`` needs is
    missing (checked before minutes of building, not after; found, not imported: each is
    imported where it is used)."""
    for name in NEEDS.get(kind, ()):
        if not installed(name):
            raise VelplanError(f"the note needs {name} (no module named {name!r}); install it with `{INSTALL}`")


def note_format(path: str | os.PathLike) -> str:
    """The format a file name asks for; a one-line error for another suffix."""
    kind = FORMATS.get(Path(path).suffix.lower())
    if kind is None:
        raise VelplanError(f"cannot tell the note's format from {str(path)!r}: name it .docx, .pdf, .html or .md")
    return kind


def write_note(note, path: str | os.PathLike) -> Path:
    """Write ``note`` to ``path`` in the format its suffix names (.docx, .pdf, .html, .md)."""
    kind = note_format(path)
    with tempfile.TemporaryDirectory(prefix="velplan-note-") as tmp:
        tmp = Path(tmp)
        data = {"docx": _docx, "pdf": _pdf, "html": _html, "md": _md}[kind](note, tmp, Path(path))
        return write_atomic(path, data)


def _figures(note) -> list:
    return [b for b in note.blocks if isinstance(b, Figure)]


def _png_files(note, tmp: Path) -> dict[str, str]:
    """Each figure's PNG written into ``tmp``: figure name → file name."""
    from velplan.note.figures import pictures_png

    figs = _figures(note)
    images = {fig.name: f"{fig.name}.png" for fig in figs}
    for fig, png in zip(figs, pictures_png([fig.picture for fig in figs])):
        (tmp / images[fig.name]).write_bytes(png)
    return images


class _Rasterising:
    """The note's PNGs made in a thread (Typst lets go of the interpreter while it draws)."""

    def __init__(self, pictures):
        import threading

        self._pngs, self._error = None, None
        self._thread = threading.Thread(target=self._run, args=(pictures,), daemon=True)
        self._thread.start()

    def _run(self, pictures) -> None:
        from velplan.note.figures import pictures_png

        try:
            self._pngs = pictures_png(pictures)
        except BaseException as exc:  # raised again in the caller's thread
            self._error = exc

    def result(self) -> list[bytes]:
        """The PNGs (waits for them); the thread's error raised here."""
        self.join()
        if self._error is not None:
            raise self._error
        return self._pngs

    def join(self) -> None:
        """Wait for the thread (its temporary files removed by it, not left at exit)."""
        self._thread.join()


def _pandoc(source: str, to: str, tmp: Path, extra=()) -> bytes:
    return Pandoc(source, to, tmp, extra).result()


def _docx(note, tmp: Path, path: Path) -> bytes:
    """pandoc's .docx of the note (its figures SVG files, rasterised meanwhile for their PNG
    fallbacks), laid out as a course note."""
    from velplan.note.docx_math import PLACEHOLDER, FormulaRun, formulas, put_formulas

    images, svgs = {}, {}
    for fig in _figures(note):
        images[fig.name] = f"{fig.name}.svg"
        svgs[fig.name] = fig.svg.encode("utf-8")
        (tmp / images[fig.name]).write_bytes(svgs[fig.name])
    wanted = formulas(note)
    run = Pandoc(to_markdown(note, "docx", images, placeholder=PLACEHOLDER if wanted else None), "docx", tmp,
                 ["--number-sections"])
    math = FormulaRun(wanted, tmp / "math") if wanted else None
    drawing = None
    try:
        drawing = _Rasterising([fig.picture for fig in _figures(note)])
        docx = _module("docx")  # imported while pandoc runs and the figures are drawn
        raw = run.result()
        doc = docx.Document(io.BytesIO(raw))
        if math is not None and not put_formulas(doc, wanted, math.equations()):
            # a formula pandoc reads otherwise on its own: the whole note converted as one
            doc = docx.Document(io.BytesIO(_pandoc(to_markdown(note, "docx", images), "docx", tmp,
                                                   ["--number-sections"])))
        _course_note(docx, doc, note)
        from velplan.note.docx_figures import add_png_fallbacks

        add_png_fallbacks(doc, list(zip((svgs[fig.name] for fig in _figures(note)), drawing.result())))
    finally:
        run.cancel()
        if math is not None:
            math.cancel()
        if drawing is not None:
            drawing.join()  # where anything failed: its temporary files gone before the process ends
    out = io.BytesIO()
    doc.save(out)
    return out.getvalue()


def _course_note(docx, doc, note) -> None:
    """A4 pages with a course note's margins (GOST 2.105), its title, its layout, and the
    contents filled in when Word opens it."""
    mm = docx.shared.Mm
    for section in doc.sections:
        section.page_width, section.page_height = mm(210), mm(297)
        section.left_margin, section.right_margin = mm(25), mm(15)
        section.top_margin = section.bottom_margin = mm(20)
    doc.core_properties.title = note.title
    _layout(doc, note.lang)
    _update_fields_on_open(docx, doc.settings.element)


def _layout(doc, lang: str) -> None:
    """The course note's plain style, ruled tables that fit their columns, the contents
    written out, page numbers in the footer (none on the title page)."""
    from velplan.note import docx_layout, docx_tables, docx_toc

    docx_layout.apply_look(doc, lang)
    docx_layout.heading_spaces(doc)
    docx_layout.centre_unnumbered(doc)
    docx_layout.keep_lead_ins(doc)
    docx_layout.math_size(doc, lang)
    docx_tables.layout_tables(doc, lang)
    docx_toc.fill_contents(doc, lang)
    docx_layout.page_numbers(doc)


_AFTER_UPDATE_FIELDS = ("hdrShapeDefaults", "footnotePr", "endnotePr", "compat", "docVars", "rsids", "mathPr",
                        "attachedSchema", "themeFontLang", "clrSchemeMapping", "doNotIncludeSubdocsInStats",
                        "doNotAutoCompressPictures", "forceUpgrade", "captions", "readModeInkLockDown",
                        "smartTagType", "schemaLibrary", "shapeDefaults", "doNotEmbedSmartTags",
                        "decimalSymbol", "listSeparator")


def _update_fields_on_open(docx, settings) -> None:
    """``<w:updateFields>`` in its place in the schema's order: Word fills the contents in."""
    update = docx.oxml.OxmlElement("w:updateFields")
    update.set(docx.oxml.ns.qn("w:val"), "true")
    for child in settings:
        if child.tag.rsplit("}", 1)[-1] in _AFTER_UPDATE_FIELDS:
            child.addprevious(update)
            return
    settings.append(update)


def _pdf(note, tmp: Path, path: Path) -> bytes:
    """The note typeset by Typst, its figures drawn from their SVGs (vector, in the texts'
    own faces as `velplan.note.pixels` gives them)."""
    from velplan.note.pixels import for_typst

    images = {fig.name: f"{fig.name}.svg" for fig in _figures(note)}
    run = Pandoc(to_markdown(note, "typst", images), "typst", tmp)  # it names the figures' files only
    try:
        for fig in _figures(note):
            (tmp / images[fig.name]).write_text(for_typst(fig.svg), encoding="utf-8")
        body = run.result().decode("utf-8")
    finally:
        run.cancel()
    from velplan.note.markdown import typ_text

    source = TYPST_PREAMBLE.format(title=typ_text(note.title), lang=note.lang) + body
    (tmp / "note.typ").write_text(source, encoding="utf-8")
    typst = _module("typst")
    try:
        # the installed fonts too: the figures' texts in the faces their SVG names, as in their PNGs
        return typst.compile(str(tmp / "note.typ"), root=str(tmp), font_paths=[str(FONT_DIR)])
    except Exception as exc:  # typst raises its own error type with the diagnostics
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise VelplanError(f"typst could not typeset the note: {first}") from None


def _html(note, tmp: Path, path: Path) -> bytes:
    images = _png_files(note, tmp)
    return _pandoc(to_markdown(note, "html", images), "html5", tmp,
                   ["--standalone", "--embed-resources", "--mathml", "--number-sections",
                    "--metadata", f"title={note.title}", "--metadata", f"lang={note.lang}"])


def _md(note, tmp: Path, path: Path) -> bytes:
    """The Markdown, its figures in ``NAME-figures/`` beside it (written first, then moved in)."""
    images = _png_files(note, tmp)
    folder = path.with_name(path.stem + "-figures")
    rel = {k: f"{folder.name}/{v}" for k, v in images.items()}
    text = to_markdown(note, "md", rel)
    staged = Path(tempfile.mkdtemp(prefix=f".{folder.name}.", dir=path.parent if str(path.parent) else "."))
    try:
        for name in images.values():
            shutil.copyfile(tmp / name, staged / name)
        if folder.exists():
            shutil.rmtree(folder)
        os.chmod(staged, 0o755)  # mkdtemp makes it private
        os.replace(staged, folder)
    except OSError as exc:
        shutil.rmtree(staged, ignore_errors=True)
        raise VelplanError(f"cannot write {folder}: {exc.strerror or exc}") from None
    return text.encode("utf-8")
