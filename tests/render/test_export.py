import os
import sys

import pytest

from velplan.errors import VelplanError
from velplan.render import export
from velplan.render.export import write_pdf, write_png, write_svg
from velplan.render.scene import Arrow, Scene, Text
from velplan.render.svg import to_svg

cairosvg = pytest.importorskip("cairosvg")


def _svg():
    return to_svg(Scene((Arrow((10, 10), (50, 30), "plan-v-1", "thick"),
                         Text((10, 40), "План скоростей", "labels")), 100, 50))


def test_write_svg_roundtrip(tmp_path):
    path = write_svg(_svg(), tmp_path / "sheet.svg")
    assert path.read_text(encoding="utf-8") == _svg()
    assert os.listdir(tmp_path) == ["sheet.svg"]
    assert path.stat().st_mode & 0o777 == 0o644


def test_write_png_size_follows_dpi(tmp_path):
    path = write_png(_svg(), tmp_path / "sheet.png", dpi=254)   # 10 px per mm
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    assert (width, height) == (1000, 500)


def test_write_pdf(tmp_path):
    assert write_pdf(_svg(), tmp_path / "sheet.pdf").read_bytes()[:5] == b"%PDF-"


def test_failed_conversion_leaves_no_file(tmp_path, monkeypatch):
    def broken(**kwargs):
        raise ValueError("renderer exploded\nsecond line")

    monkeypatch.setattr(cairosvg, "svg2png", broken)
    with pytest.raises(VelplanError, match=r"^cairosvg could not convert the sheet "
                                           r"\(svg2png\): renderer exploded$"):
        write_png(_svg(), tmp_path / "sheet.png")
    assert os.listdir(tmp_path) == []


def test_failed_conversion_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "sheet.png"
    target.write_bytes(b"old")
    monkeypatch.setattr(cairosvg, "svg2png", lambda **kw: 1 / 0)
    with pytest.raises(VelplanError):
        write_png(_svg(), target)
    assert target.read_bytes() == b"old"
    assert os.listdir(tmp_path) == ["sheet.png"]


def test_failed_write_removes_temporary_file(tmp_path, monkeypatch):
    def no_replace(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(export.os, "replace", no_replace)
    with pytest.raises(VelplanError, match="cannot write .*sheet.svg: No space left"):
        write_svg(_svg(), tmp_path / "sheet.svg")
    assert os.listdir(tmp_path) == []


def test_missing_directory(tmp_path):
    with pytest.raises(VelplanError, match="cannot write"):
        write_svg(_svg(), tmp_path / "nowhere" / "sheet.svg")


def test_missing_cairosvg_says_how_to_install(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "cairosvg", None)
    with pytest.raises(VelplanError, match=r"pip install cairosvg \(in a checkout: pip install '\.\[export\]'\)") as info:
        write_png(_svg(), tmp_path / "sheet.png")
    assert "\n" not in str(info.value)
    assert os.listdir(tmp_path) == []


def test_bad_dpi():
    with pytest.raises(VelplanError, match="dpi=0"):
        write_png(_svg(), "unused.png", dpi=0)
