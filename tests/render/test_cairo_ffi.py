"""cairocffi imported with its FFI from velplan's cache (`velplan.render.cairo_ffi`): the first
import writes the cache, later ones do not parse cairo's header (pycparser not imported), and
the pictures are the same bytes either way; a broken cache is passed over and made again."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("cairosvg")

ROOT = Path(__file__).resolve().parents[2]
PROBE = """
import sys, hashlib
from velplan.render.export import svg_to_png, svg_to_pdf
svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="30mm" height="12mm" viewBox="0 0 30 12">'
       '<line x1="1" y1="1" x2="29" y2="11" stroke="black" stroke-width="0.4"/>'
       '<text x="2" y="10" font-size="3.5" font-family="DejaVu Sans">AB₁ μ</text></svg>')
png = svg_to_png(svg, dpi=200) + svg_to_png(svg, dpi=150, grey=True)
print(hashlib.sha256(png).hexdigest(), 'pycparser' in sys.modules, type(sys.modules['cairocffi.ffi'].ffi).__module__)
"""


def _probe(cache: Path) -> list[str]:
    env = dict(os.environ, XDG_CACHE_HOME=str(cache), PYTHONPATH=str(ROOT))
    out = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, check=True)
    assert out.stderr == ""
    return out.stdout.split()


def test_the_cache_is_written_then_read(tmp_path):
    first = _probe(tmp_path)
    folders = list((tmp_path / "velplan").glob("cairo-ffi-*"))
    assert len(folders) == 1 and (folders[0] / "done").is_file()
    assert sorted(p.name for p in (tmp_path / "velplan").iterdir()) == [folders[0].name]  # nothing staged left
    second = _probe(tmp_path)
    assert first[1] == "True" and second[1] == "False"  # the header parsed the first time only
    assert first[0] == second[0]  # the same pictures


def test_a_broken_cache_is_passed_over(tmp_path):
    first = _probe(tmp_path)
    folder = next((tmp_path / "velplan").glob("cairo-ffi-*"))
    (folder / "_velplan_cairo_ffi.py").write_text("raise ImportError('broken')\n", encoding="utf-8")
    again = _probe(tmp_path)
    assert again[0] == first[0] and again[1] == "True"  # cairocffi imported as it is
    mended = _probe(tmp_path)  # ... and the cache made again
    assert mended[0] == first[0] and mended[1] == "False"


def test_no_cache_folder(tmp_path):
    blocked = tmp_path / "file"
    blocked.write_text("not a folder", encoding="utf-8")
    first, second = _probe(blocked), _probe(blocked)
    assert first[0] == second[0] and first[1] == second[1] == "True"
