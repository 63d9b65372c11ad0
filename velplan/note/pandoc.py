"""Running pandoc for the note's writers: the program pypandoc ships (or the one named by
``PYPANDOC_PANDOC``, or ``pandoc`` on the path), started directly — pypandoc itself is not
imported, and no ``pandoc --version`` is run to choose one — so that the note can draw its
figures while pandoc converts the text."""

from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import sys
from pathlib import Path

from velplan.errors import VelplanError

INSTALL = "pip install 'velplan[note]' (in a checkout: pip install '.[note]')"


def installed(module: str) -> bool:
    """Whether ``module`` can be imported, without importing it (False where a test or a user
    has put None in its place in ``sys.modules``)."""
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        return False


def pandoc_program() -> str:
    """The pandoc program: ``PYPANDOC_PANDOC``, else the one pypandoc ships, else ``pandoc`` on
    the path, else the environment's own; a one-line error naming the note's extra if none."""
    named = os.environ.get("PYPANDOC_PANDOC")
    if named:
        return named
    exe = "pandoc.exe" if sys.platform == "win32" else "pandoc"
    spec = importlib.util.find_spec("pypandoc") if installed("pypandoc") else None
    candidates = []
    if spec is not None and spec.origin:
        candidates.append(Path(spec.origin).resolve().parent / "files" / exe)
    on_path = shutil.which("pandoc")
    candidates += [Path(on_path)] if on_path else []
    candidates.append(Path(sys.exec_prefix) / ("Scripts" if sys.platform == "win32" else "bin") / exe)
    for path in candidates:
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    raise VelplanError(f"the note needs pandoc (not found: pypandoc's own, or `pandoc` on the path); "
                       f"install it with `{INSTALL}`")


class Pandoc:
    """One pandoc conversion of Markdown in ``tmp`` running in the background: started on
    construction, its output's bytes from `result`."""

    def __init__(self, source: str, to: str, tmp: Path, extra=()):
        self.to, self.out = to, tmp / f"out.{to}"
        (tmp / "in.md").write_text(source, encoding="utf-8")
        self._err = open(tmp / "pandoc.err", "w+b")
        try:
            self._proc = subprocess.Popen(
                [pandoc_program(), "--from=markdown", f"--to={to}", f"--output={self.out}", "--resource-path",
                 str(tmp), *extra, str(tmp / "in.md")],
                cwd=str(tmp), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=self._err)
        except OSError as exc:
            self._err.close()
            raise VelplanError(f"pandoc could not write the note ({to}): {exc.strerror or exc}") from None

    def result(self) -> bytes:
        """The converted file (waits for pandoc); a one-line error with pandoc's first line of
        complaint if it failed."""
        code = self._proc.wait()
        self._err.seek(0)
        err = self._err.read().decode("utf-8", "replace").strip()
        self._err.close()
        if code != 0 or not self.out.is_file():
            first = err.splitlines()[0] if err else f"exit status {code}"
            raise VelplanError(f"pandoc could not write the note ({self.to}): {first}")
        return self.out.read_bytes()

    def cancel(self) -> None:
        """Stop pandoc (when the note fails elsewhere)."""
        if self._proc.poll() is None:
            self._proc.kill()
            self._proc.wait()
        if not self._err.closed:
            self._err.close()
