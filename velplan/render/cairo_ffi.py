"""cairocffi imported without parsing cairo's header: cairocffi declares cairo's API to cffi as
C source (about 60 kB), which cffi parses with pycparser on every import (about 0.09 s of CPU,
pycparser's own import included). The declarations parsed once are written as cffi's
out-of-line modules (`cffi.FFI.emit_python_code`: the same types and functions, compiled to
tables, no C compiler involved) in the user's cache folder, keyed by cairocffi's files and
cffi's version; later imports give cairocffi those as its ``cairocffi.ffi``. Where anything is
missing or fails (no cache folder, cairocffi built with xcb support, a file cffi cannot load),
cairocffi is imported as it is (and a cache that fails is made again)."""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import importlib.util
import io
import os
import shutil
import sys
import tempfile
import types
from pathlib import Path

_PIXBUF = "ffi_pixbuf.cdef('''"


def import_cairocffi():
    """The cairocffi module, its FFI from the cache where it is there (made there otherwise)."""
    if "cairocffi" in sys.modules:
        return sys.modules["cairocffi"]
    folder = _folder()
    if folder is not None and (folder / "done").is_file():
        try:
            sys.modules["cairocffi.ffi"] = _cached(folder)
            return importlib.import_module("cairocffi")
        except Exception:  # a cache cffi cannot load: cairocffi as it is, and the cache made again
            for name in [n for n in sys.modules if n.startswith(("cairocffi", "_velplan_cairo_"))]:
                del sys.modules[name]
            shutil.rmtree(folder, ignore_errors=True)
    module = importlib.import_module("cairocffi")
    if folder is not None:
        _write(folder)
    return module


def _folder() -> Path | None:
    """The cache folder of this cairocffi and cffi, or None where they cannot be cached."""
    try:
        import _cffi_backend

        spec = importlib.util.find_spec("cairocffi")
        if spec is None or not spec.origin or importlib.util.find_spec("xcffib") is not None:
            return None  # with xcb, cairocffi's FFI includes xcffib's: not cached
        here = Path(spec.origin).parent
        key = hashlib.sha256()
        for name in ("ffi.py", "constants.py"):
            key.update((here / name).read_bytes())
        key.update(f"{_cffi_backend.__version__} {sys.version}".encode())
    except (ImportError, OSError, ValueError):
        return None
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "velplan" / f"cairo-ffi-{key.hexdigest()[:16]}"


def _load(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # the pixbuf module imports the main one by name
    spec.loader.exec_module(module)
    return module


def _cached(folder: Path) -> types.ModuleType:
    """A stand-in for ``cairocffi.ffi`` with the cached FFIs."""
    main = _load(folder / "_velplan_cairo_ffi.py", "_velplan_cairo_ffi")
    pixbuf = _load(folder / "_velplan_cairo_pixbuf_ffi.py", "_velplan_cairo_pixbuf_ffi")
    stand_in = types.ModuleType("cairocffi.ffi", "cairocffi's FFI, from velplan's cache")
    stand_in.ffi, stand_in.ffi_pixbuf = main.ffi, pixbuf.ffi
    return stand_in


def _write(folder: Path) -> None:
    """Parse cairocffi's declarations once more and write them as out-of-line modules (written
    whole into a new folder, then renamed into place: a reader never sees half of it)."""
    staged = None
    try:
        from cffi import FFI

        from cairocffi import constants

        here = Path(importlib.util.find_spec("cairocffi").origin).parent
        source = (here / "ffi.py").read_text(encoding="utf-8")
        start = source.index(_PIXBUF) + len(_PIXBUF)
        pixbuf_decls = source[start:source.index("''')", start)]
        folder.parent.mkdir(parents=True, exist_ok=True)
        staged = Path(tempfile.mkdtemp(prefix=".cairo-ffi-", dir=folder.parent))
        main = FFI()
        main.cdef(constants._CAIRO_HEADERS)
        main.set_source("_velplan_cairo_ffi", None)
        pixbuf = FFI()
        pixbuf.include(main)
        pixbuf.cdef(pixbuf_decls)
        pixbuf.set_source("_velplan_cairo_pixbuf_ffi", None)
        with contextlib.redirect_stdout(io.StringIO()):  # cffi says "generating …" on stdout
            main.emit_python_code(str(staged / "_velplan_cairo_ffi.py"))
            pixbuf.emit_python_code(str(staged / "_velplan_cairo_pixbuf_ffi.py"))
        (staged / "done").write_text("cffi out-of-line modules of cairocffi's declarations\n", encoding="ascii")
        os.replace(staged, folder)
    except Exception:  # nothing cached (or another process cached it first): parsed again next time
        if staged is not None:
            shutil.rmtree(staged, ignore_errors=True)
