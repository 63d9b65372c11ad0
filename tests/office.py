"""LibreOffice for the tests that read a .docx as an office program lays it out: the program,
or the test skipped with the reason, and the pages' text of the PDFs it prints."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest


def soffice(why: str) -> str:
    """The LibreOffice program, else the calling test skipped, saying it would check `why`."""
    exe = shutil.which("soffice") or shutil.which("libreoffice")
    if exe is None:
        pytest.skip(f"LibreOffice (soffice) is not installed: install Debian's libreoffice-writer-nogui "
                    f"(.ci/run does) {why}")
    return exe


def printed_pages(exe: str, docs: list[Path], out: Path) -> dict[Path, list[str]]:
    """Each .docx of `docs` printed to PDF by LibreOffice in one call (PDFs in `out`): the text
    of each page, by pdfium, lines ending in "\\n"."""
    import pypdfium2 as pdfium

    run = subprocess.run([exe, f"-env:UserInstallation={(out / 'profile').as_uri()}", "--headless",
                          "--convert-to", "pdf", "--outdir", str(out), *map(str, docs)],
                         capture_output=True, text=True, timeout=600)
    pages = {}
    for path in docs:
        pdf = out / (Path(path).stem + ".pdf")
        assert pdf.exists(), run.stderr
        doc = pdfium.PdfDocument(str(pdf))
        pages[path] = [doc[k].get_textpage().get_text_range().replace("\r\n", "\n") for k in range(len(doc))]
    return pages
