"""DXF export (issue 17): a sheet as DXF R2013 in mm that CAD programs import cleanly.

What is measured: ezdxf's audit finds nothing; only LINE/ARC/CIRCLE/LWPOLYLINE/TEXT; a layer
per line type with its lineweight (THICK 0.70 mm, thin 0.25 mm) and linetype (AXIS CENTER,
HIDDEN DASHED, defined from the style's dashes); $INSUNITS 4; Cyrillic, Ukrainian and Chinese
text read back unchanged; every segment, circle, arrowhead and dot of the shaper's and the
force sheet equal to the SVG's of the same scene (drawn at 9 decimals, y flipped) to 1e-6 mm,
every text at its anchor with its height, rotation and alignment; the extents are the sheet;
the DXF drawn back by ezdxf's drawing add-on inks where the SVG drawn by cairosvg does.
"""

import io
import math
import re
import xml.etree.ElementTree as ET
from collections import Counter

import numpy as np
import pytest

import velplan
from velplan.cli import main
from velplan.render.shapes import unicode_text
from velplan.errors import VelplanError
from velplan.render.canvas import RecordingCanvas, render
from velplan.render.dxf import (
    FILL_LAYER, LAYER_OF_LINE, LAYERS, TEXT_LAYER, dxf_text_content, layer_lineweights,
    linetype_pattern, nearest_lineweight, thin_lineweight, to_dxf)
from velplan.render.export import write_dxf
from velplan.render.scene import Arrow, Circle, Polygon, Polyline, Scene, Text
from velplan.render.style import SheetStyle
from velplan.render.svg import to_svg

ezdxf = pytest.importorskip("ezdxf")

ALLOWED = {"LINE", "ARC", "CIRCLE", "LWPOLYLINE", "TEXT"}
TOL = 1e-6  # mm
SVG_NS = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def study():
    return velplan.Study("shaper")


@pytest.fixture(scope="module")
def sheets(study):
    """The shaper's kinematic sheet (ru) and force sheet (zh): their scenes and styles."""
    from velplan.sheets.forces import build_force_sheet
    from velplan.sheets.kinematic import build_sheet

    return {"kinematic": build_sheet(study, lang="ru"),
            "forces": build_force_sheet(study, lang="zh")}


@pytest.fixture(scope="module")
def docs(sheets):
    """Each sheet's DXF text and the document ezdxf reads back from it."""
    out = {}
    for name, sheet in sheets.items():
        text = to_dxf(sheet.scene, sheet.style)
        out[name] = (text, ezdxf.read(io.StringIO(text)))
    return out


def _read(text: str):
    return ezdxf.read(io.StringIO(text))


def _xy(vector) -> tuple[float, float]:
    """x and y of an ezdxf Vec3 or a header tuple."""
    return tuple(ezdxf.math.Vec3(vector).vec2)


# -- the file as CAD programs see it ---------------------------------------------------------

@pytest.mark.parametrize("name", ["kinematic", "forces"])
def test_audit_finds_nothing_and_only_allowed_entities(docs, name):
    text, doc = docs[name]
    auditor = doc.audit()
    assert auditor.has_errors is False and len(auditor.fixes) == 0
    kinds = Counter(e.dxftype() for e in doc.modelspace())
    assert set(kinds) <= ALLOWED, kinds
    assert kinds["LINE"] > 100 and kinds["TEXT"] > 200 and kinds["CIRCLE"] > 30
    # nothing in the paper space, no blocks of our own (no INSERT, no anonymous blocks)
    assert len(doc.paperspace()) == 0
    assert {b.name for b in doc.blocks} == {"*Model_Space", "*Paper_Space"}
    assert doc.dxfversion == "AC1027" and text.startswith("  0\nSECTION\n  2\nHEADER")


def test_units_extents_and_view_are_the_sheet(docs, sheets):
    doc = docs["kinematic"][1]
    sheet = sheets["kinematic"]
    w, h = sheet.scene.width_mm, sheet.scene.height_mm
    header = doc.header
    assert header["$INSUNITS"] == 4 and header["$MEASUREMENT"] == 1 and doc.units == 4
    assert header["$LWDISPLAY"] == 1 and header["$LTSCALE"] == 1.0
    assert _xy(header["$EXTMIN"]) == (0.0, 0.0) and _xy(header["$EXTMAX"]) == (w, h)
    assert tuple(header["$LIMMAX"]) == (w, h)
    # the geometry's own bounding box is the sheet: the trim line is its outermost stroke
    from ezdxf import bbox

    box = bbox.extents(doc.modelspace().query("LINE LWPOLYLINE CIRCLE"), fast=True)
    assert np.allclose([*_xy(box.extmin), *_xy(box.extmax)], [0, 0, w, h], atol=TOL)
    assert np.allclose(sheet.scene.bounds(), (0, 0, w, h), atol=TOL)


def test_layers_lineweights_and_linetypes(docs, sheets):
    doc = docs["kinematic"][1]
    style = sheets["kinematic"].style
    layers = {layer.dxf.name: layer for layer in doc.layers}
    assert set(LAYERS) <= set(layers)
    weights = {n: layers[n].dxf.lineweight for n in LAYERS}
    assert weights == {"THICK": 70, "THIN": 25, "CONSTRUCTION": 25, "AXIS": 25, "HIDDEN": 25,
                       "TEXT": 25, "FILL": 25}
    assert 50 <= weights["THICK"] <= 70
    kinds = {n: layers[n].dxf.linetype for n in LAYERS}
    assert kinds["AXIS"] == "CENTER" and kinds["HIDDEN"] == "DASHED"
    assert all(kinds[n] == "Continuous" for n in ("THICK", "THIN", "CONSTRUCTION", "TEXT", "FILL"))
    assert all(layers[n].description for n in LAYERS)
    # the linetypes are defined in the file, in mm, from the style's dash patterns
    for name, dash in (("CENTER", style.axis_dash), ("DASHED", style.hidden_dash)):
        lt = doc.linetypes.get(name)
        values = [t.value for t in lt.pattern_tags.tags if t.code in (40, 49)]
        assert values == linetype_pattern(dash) == [sum(dash), *(d if i % 2 == 0 else -d
                                                                  for i, d in enumerate(dash))]
    # every entity on one of these layers, with ByLayer colour, linetype and lineweight
    for e in doc.modelspace():
        assert e.dxf.layer in LAYERS
        assert e.dxf.color == 256 and e.dxf.linetype == "BYLAYER" and e.dxf.lineweight == -1
        assert not e.dxf.hasattr("true_color")
    used = Counter(e.dxf.layer for e in doc.modelspace())
    assert used["THICK"] > 20 and used["THIN"] > 100 and used["TEXT"] > 200 and used["FILL"] > 40


def test_lineweights_follow_the_main_line():
    assert nearest_lineweight(0.7) == 70 and nearest_lineweight(0.5) == 50
    assert nearest_lineweight(0.62) == 60 and nearest_lineweight(5.0) == 211
    assert thin_lineweight(0.7) == 25 and thin_lineweight(0.5) == 18   # S/3 rounded up
    weights = layer_lineweights(SheetStyle(thick_mm=0.5))
    assert weights["THICK"] == 50 and weights["HIDDEN"] == 18


def test_a_dashed_construction_line_gets_its_own_linetype():
    style = SheetStyle(construction_dash=(3.0, 1.0), axis_dash=())
    doc = _read(to_dxf(Scene((Polyline([(0, 0), (10, 0), (10, 10)], "plan", "construction"),),
                             100, 50), style))
    assert doc.layers.get("CONSTRUCTION").dxf.linetype == "CONSTRUCTION"
    assert doc.layers.get("AXIS").dxf.linetype == "Continuous"
    assert "CENTER" not in doc.linetypes
    (pl,) = doc.modelspace().query("LWPOLYLINE")
    assert pl.dxf.flags & 128  # the pattern runs on across the vertices


# -- text ------------------------------------------------------------------------------------

TEXTS = ("План скоростей (пол. 4)", "Ґанок і їжак: ω₂, μv = 0,01 (м/с)/мм", "速度图 (位置 4)",
         "机构力分析: shaper", "aᵏ_A4A ⊥ O₂A · 100 %", "S₅ ← π → a₄")


def test_unicode_text_survives_a_round_trip(tmp_path):
    scene = Scene(tuple(Text((10, 10 + 8 * i), t, "labels", 3.5) for i, t in enumerate(TEXTS)),
                  200, 100)
    path = write_dxf(to_dxf(scene, SheetStyle(language="zh")), tmp_path / "t.dxf")
    raw = path.read_bytes()
    assert "速度图".encode("utf-8") in raw and "Ґанок".encode("utf-8") in raw  # stored as is
    back = [t.dxf.text for t in ezdxf.readfile(path).modelspace().query("TEXT")]
    assert back == list(TEXTS)
    assert ezdxf.readfile(path).styles.get("VELPLAN").dxf.font == "simhei.ttf"


def test_percent_signs_and_control_characters_are_kept_harmless():
    scene = Scene((Text((5, 5), "δ = 3 %% и\tдалее", "labels"), Text((5, 15), " ", "labels")),
                  100, 50)
    (entity,) = _read(to_dxf(scene)).modelspace().query("TEXT")  # the blank text is left out
    assert entity.plain_text() == "δ = 3 %% и далее"
    assert dxf_text_content("50 %") == "50 %"


ANCHORS = {("start", "baseline"): (0, 0), ("middle", "baseline"): (1, 0),
           ("end", "baseline"): (2, 0), ("start", "middle"): (0, 2), ("middle", "middle"): (1, 2),
           ("end", "middle"): (2, 2), ("start", "top"): (0, 3), ("middle", "top"): (1, 3),
           ("end", "top"): (2, 3)}


def test_text_alignment_matches_the_anchor():
    items = tuple(Text((20 + 30 * i, 40), f"{a}/{b}", "labels", 2.5, a, b, 30.0 * i)
                  for i, (a, b) in enumerate(ANCHORS))
    texts = _read(to_dxf(Scene(items, 300, 80), SheetStyle(italic=True))).modelspace().query("TEXT")
    for item, entity in zip(items, texts, strict=True):
        assert (entity.dxf.halign, entity.dxf.valign) == ANCHORS[(item.anchor, item.baseline)]
        anchor = entity.dxf.insert if (entity.dxf.halign, entity.dxf.valign) == (0, 0) \
            else entity.dxf.align_point
        assert np.allclose(_xy(anchor), item.position, atol=TOL)
        assert entity.dxf.height == item.size_mm and entity.dxf.rotation == item.rotation_deg
        assert entity.dxf.oblique == 15.0 and entity.dxf.style == "VELPLAN"


# -- geometry against the SVG ----------------------------------------------------------------

def _svg_numbers(text: str) -> list[float]:
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text)]


def _svg_geometry(svg: str, height: float) -> dict:
    """Segments, filled triangles, circles and dots of an SVG, y flipped back up, mm."""
    root = ET.fromstring(svg.split("\n", 1)[1])
    out = {"segments": [], "triangles": [], "circles": [], "dots": []}
    flip = np.array([1.0, -1.0]), np.array([0.0, height])

    def up(values):
        return np.asarray(values, float).reshape(-1, 2) * flip[0] + flip[1]

    for el in root.iter():
        tag = el.tag.replace(SVG_NS, "")
        if tag == "polyline":
            p = up(_svg_numbers(el.get("points")))
            out["segments"] += list(zip(p[:-1], p[1:]))
        elif tag == "polygon":
            p = up(_svg_numbers(el.get("points")))
            if el.get("stroke") == "none":       # an arrowhead: a filled triangle
                out["triangles"].append(p)
            else:
                out["segments"] += list(zip(p, np.roll(p, -1, axis=0)))
        elif tag == "line":
            p = up([el.get(k) for k in ("x1", "y1", "x2", "y2")])
            out["segments"].append((p[0], p[1]))
        elif tag == "path":
            p = up(_svg_numbers(el.get("d")))
            out["segments"] += list(zip(p[0::2], p[1::2]))
        elif tag == "circle":
            c = up([el.get("cx"), el.get("cy")])[0]
            out["circles"].append((*c, float(el.get("r"))))
            if el.get("fill") not in ("none", "white"):
                out["dots"].append((*c, float(el.get("r"))))
    return out


def _dxf_geometry(doc) -> dict:
    """The same from a DXF: LINEs and the edges of width-less LWPOLYLINEs, arrowhead
    outlines on FILL, CIRCLEs, donuts (disc centre and radius), and the lines on FILL that
    fill a solid polygon (``fills``), mm."""
    out = {"segments": [], "triangles": [], "circles": [], "dots": [], "tapers": [], "fills": []}
    for e in doc.modelspace():
        kind = e.dxftype()
        if kind == "LINE" and e.dxf.layer == FILL_LAYER:  # the strokes that fill a solid polygon
            out["fills"].append((np.array(_xy(e.dxf.start)), np.array(_xy(e.dxf.end))))
        elif kind == "LINE":
            out["segments"].append((np.array(_xy(e.dxf.start)), np.array(_xy(e.dxf.end))))
        elif kind == "CIRCLE":
            out["circles"].append((*_xy(e.dxf.center), e.dxf.radius))
        elif kind == "LWPOLYLINE":
            pts = np.array(e.get_points("xyseb"))
            if e.dxf.const_width:              # a donut: two half circles of radius r/2
                centre = pts[:2, :2].mean(axis=0)
                assert np.allclose(pts[:, 4], 1.0) and e.closed
                out["dots"].append((*centre, e.dxf.const_width))
                assert math.isclose(math.dist(pts[0, :2], pts[1, :2]), e.dxf.const_width)
            elif np.any(pts[:, 2:4]):          # an arrowhead's fill: base middle → tip
                out["tapers"].append(pts)
            elif e.dxf.layer == FILL_LAYER:
                out["triangles"].append(pts[:, :2])
            else:
                xy = pts[:, :2]
                ends = np.roll(xy, -1, axis=0) if e.closed else xy[1:]
                out["segments"] += list(zip(xy[: len(ends)], ends))
    return out


def _sorted_segments(segments) -> np.ndarray:
    """Segments as an (n, 4) array, each with its endpoints in a fixed order, rows sorted."""
    rows = []
    for a, b in segments:
        a, b = tuple(np.round(a, 9)), tuple(np.round(b, 9))
        rows.append((*min(a, b), *max(a, b)))
    rows.sort()
    return np.array(rows)


def _sorted_rows(rows, decimals=9) -> np.ndarray:
    return np.array(sorted(tuple(np.round(r, decimals)) for r in rows))


@pytest.mark.parametrize("name", ["kinematic", "forces"])
def test_geometry_equals_the_svg(docs, sheets, name):
    sheet = sheets[name]
    svg = _svg_geometry(to_svg(sheet.scene, sheet.style, precision=9), sheet.scene.height_mm)
    dxf = _dxf_geometry(docs[name][1])
    a, b = _sorted_segments(svg["segments"]), _sorted_segments(dxf["segments"])
    assert a.shape == b.shape and len(a) > 300
    assert np.abs(a - b).max() < TOL
    for key in ("circles", "dots"):
        a, b = _sorted_rows(svg[key]), _sorted_rows(dxf[key])
        assert a.shape == b.shape and len(a) > 0 and np.abs(a - b).max() < TOL, key
    a = _sorted_rows([t.ravel() for t in svg["triangles"]])
    b = _sorted_rows([t.ravel() for t in dxf["triangles"]])
    assert a.shape == b.shape and len(a) > 20 and np.abs(a - b).max() < TOL
    # each tapered fill runs from the middle of its triangle's base, as wide as the base, to
    # the tip at zero width: it covers the triangle exactly
    filled = []
    for taper in dxf["tapers"]:
        (bx, by, w0, w1, _), (tx, ty, *_) = taper
        direction = np.array([tx - bx, ty - by]) / math.hypot(tx - bx, ty - by)
        half = np.array([-direction[1], direction[0]]) * w0 / 2
        filled.append(np.concatenate([[tx, ty], np.array([bx, by]) + half,
                                      np.array([bx, by]) - half]))
        assert w1 == 0.0
    assert np.abs(_sorted_rows(filled) - b).max() < TOL


def test_texts_equal_the_scene(docs, sheets):
    canvas = RecordingCanvas()
    render(sheets["kinematic"].scene, canvas)
    scene = [t for t in canvas.texts() if t.text.strip()]
    texts = list(docs["kinematic"][1].modelspace().query("TEXT"))
    assert len(texts) == len(scene) > 200
    for item, entity in zip(scene, texts, strict=True):
        anchor = entity.dxf.insert if (entity.dxf.halign, entity.dxf.valign) == (0, 0) \
            else entity.dxf.align_point
        assert entity.dxf.text == unicode_text(item.text) and entity.dxf.layer == TEXT_LAYER
        assert np.allclose(_xy(anchor), item.position, atol=TOL)
        assert entity.dxf.height == item.size_mm and entity.dxf.rotation == item.rotation_deg


def test_every_primitive_lands_on_its_line_type_layer():
    scene = Scene((Polyline([(0, 0), (5, 5)], "a", "axis"),
                   Polyline([(0, 0), (5, 5), (9, 1)], "a", "hidden"),
                   Polygon([(10, 10), (20, 10), (20, 20)], "b", "thick", "hatch"),
                   Polygon([(30, 10), (40, 10), (40, 20)], "b", "thin", "solid"),
                   Polygon([(50, 10), (60, 10), (60, 20)], "b", "construction", "white"),
                   Circle((70, 20), 3, "c", "thick", "white"),
                   Circle((80, 20), 2, "c", "thin", "hatch"),
                   Arrow((0, 40), (30, 40), "plan-v-1", "thick"),
                   Arrow((5, 5), (5, 5), "plan-v-1", "thick")), 100, 50)
    layers = [(e.dxftype(), e.dxf.layer) for e in _read(to_dxf(scene)).modelspace()]
    counts = Counter(layers)
    assert layers[:2] == [("LINE", "AXIS"), ("LWPOLYLINE", "HIDDEN")]
    assert counts[("LWPOLYLINE", "THICK")] == 1 and counts[("LWPOLYLINE", "THIN")] == 1
    assert counts[("LWPOLYLINE", "CONSTRUCTION")] == 1 and counts[("CIRCLE", "THICK")] == 1
    assert counts[("LINE", "THIN")] > 5              # hatch lines of the triangle and circle
    assert counts[("LINE", FILL_LAYER)] > 10         # the solid triangle, filled with lines
    assert counts[("LINE", "THICK")] == 1            # the arrow's shaft (the zero one: nothing)
    assert counts[("LWPOLYLINE", FILL_LAYER)] == 2   # its head: outline and tapered fill
    assert set(t for t, _ in layers) <= ALLOWED


def test_a_plan_colour_is_a_true_colour_on_plan_layers_only():
    style = SheetStyle(plan_vector_colour="#1f77b4")
    scene = Scene((Arrow((0, 0), (20, 0), "plan-v-1", "thick"),
                   Polyline([(0, 5), (20, 5)], "mechanism", "thick")), 50, 20)
    entities = list(_read(to_dxf(scene, style)).modelspace())
    assert [e.dxf.get("true_color") for e in entities] == [0x1F77B4] * 3 + [None]
    with pytest.raises(VelplanError, match="not an SVG colour"):
        to_dxf(scene, SheetStyle(plan_vector_colour="no-such-colour"))


# -- as a picture ----------------------------------------------------------------------------

def dxf_to_png(text: str, path, width_mm: float, height_mm: float, dpi: float = 40.0) -> None:
    """Draw a DXF with ezdxf's drawing add-on and matplotlib, to scale: one sheet mm is
    dpi/25.4 px, lineweights in mm as on paper (ezdxf gives matplotlib mm as points)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.config import BackgroundPolicy, ColorPolicy, Configuration
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend

    doc = _read(text)
    fig = plt.figure(figsize=(width_mm / 25.4, height_mm / 25.4), dpi=dpi)
    ax = fig.add_axes([0, 0, 1, 1])
    config = Configuration(background_policy=BackgroundPolicy.WHITE,
                           color_policy=ColorPolicy.BLACK, lineweight_scaling=72 / 25.4)
    Frontend(RenderContext(doc), MatplotlibBackend(ax, adjust_figure=False),
             config=config).draw_layout(doc.modelspace(), finalize=True)
    ax.set_xlim(0, width_mm)
    ax.set_ylim(0, height_mm)
    fig.savefig(path, dpi=dpi, facecolor="white")
    plt.close(fig)


def _ink(path, shape) -> np.ndarray:
    from PIL import Image

    image = Image.open(path).convert("L").resize(shape[::-1])
    return np.asarray(image) < 200  # any pixel darker than light grey


def _grow(mask: np.ndarray, steps: int) -> np.ndarray:
    out = mask.copy()
    for _ in range(steps):
        grown = out.copy()
        grown[1:] |= out[:-1]
        grown[:-1] |= out[1:]
        grown[:, 1:] |= out[:, :-1]
        grown[:, :-1] |= out[:, 1:]
        out = grown
    return out


def test_the_dxf_drawn_back_inks_where_the_svg_does(sheets, tmp_path):
    """The lines, arrows, circles and hatching (no text: its fonts differ from one renderer and
    machine to another) drawn back from the DXF ink where the SVG's do."""
    cairosvg = pytest.importorskip("cairosvg")
    pytest.importorskip("PIL")
    from velplan.render.svg import to_svg

    sheet = sheets["kinematic"]
    w, h = sheet.scene.width_mm, sheet.scene.height_mm
    scene = Scene(tuple(p for p in sheet.scene.primitives if not isinstance(p, Text)), w, h)
    dxf_png, svg_png = tmp_path / "dxf.png", tmp_path / "svg.png"
    dxf_to_png(to_dxf(scene, sheet.style), dxf_png, w, h, dpi=40)
    cairosvg.svg2png(bytestring=to_svg(scene, sheet.style).encode(), write_to=str(svg_png), dpi=40,
                     background_color="white")
    shape = (round(h / 25.4 * 40), round(w / 25.4 * 40))
    dxf, svg = _ink(dxf_png, shape), _ink(svg_png, shape)
    # 98 % of either's ink lies within 1 px (0.64 mm) of the other's: the rest is thin lines
    # 0.25 mm wide instead of 0.35, and what a white fill hides in the SVG and not in the DXF
    assert dxf.sum() > 0.02 * dxf.size and 0.85 < dxf.sum() / svg.sum() < 1.15
    assert (dxf & _grow(svg, 1)).sum() / dxf.sum() > 0.98
    assert (svg & _grow(dxf, 1)).sum() / svg.sum() > 0.98


# -- writing, the command line, errors -------------------------------------------------------

def test_same_scene_same_bytes_and_an_atomic_write(tmp_path, sheets):
    scene = sheets["kinematic"].scene.on_layer("frame", "title")
    text = to_dxf(scene)
    assert to_dxf(scene) == text and "$TDCREATE" in text
    path = write_dxf(text, tmp_path / "s.dxf")
    assert path.read_text(encoding="utf-8") == text and path.stat().st_mode & 0o777 == 0o644
    with pytest.raises(VelplanError, match=r"^write_dxf needs the text of a DXF document"):
        write_dxf("<svg/>", tmp_path / "t.dxf")
    with pytest.raises(VelplanError, match="does not exist"):
        write_dxf(text, tmp_path / "missing" / "t.dxf")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.dxf"]


def test_bad_input_is_one_line(monkeypatch):
    with pytest.raises(VelplanError, match="SheetStyle or None"):
        to_dxf(Scene(width_mm=10, height_mm=10), "ru")
    monkeypatch.setitem(__import__("sys").modules, "ezdxf", None)
    with pytest.raises(VelplanError, match=r"^DXF export needs ezdxf .*pip install ezdxf"):
        to_dxf(Scene(width_mm=10, height_mm=10))


def test_cli_writes_the_dxf_beside_the_svg(tmp_path, capsys, sheets):
    out = tmp_path / "shaper.DXF"
    assert main(["sheet", "shaper", "-o", str(out), "--lang", "ru"]) == 0
    svg, dxf = tmp_path / "shaper.svg", tmp_path / "shaper.dxf"
    assert capsys.readouterr().out == f"wrote {svg}\nwrote {dxf}\n"
    assert svg.read_text(encoding="utf-8") == sheets["kinematic"].svg()
    assert dxf.read_text(encoding="utf-8") == to_dxf(sheets["kinematic"].scene,
                                                    sheets["kinematic"].style)
    assert main(["sheet", "shaper", "--kind", "forces", "--lang", "zh", "--dxf",
                 "-o", str(tmp_path / "f.svg")]) == 0
    assert (tmp_path / "f.dxf").read_text(encoding="utf-8") == to_dxf(
        sheets["forces"].scene, sheets["forces"].style)
    steps = tmp_path / "steps"
    assert main(["steps", "shaper", "--position", "3", "--kind", "velocity", "--dxf",
                 "-o", str(steps)]) == 0
    names = sorted(p.name for p in steps.iterdir())
    assert names and {n[:-4] for n in names if n.endswith(".dxf")} == \
        {n[:-4] for n in names if n.endswith(".svg")}
    capsys.readouterr()
    assert main(["sheet", "shaper", "-o", str(tmp_path / "missing" / "x.dxf")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("velplan: error: cannot write") and err.count("\n") == 1
    assert not (tmp_path / "missing").exists()


def test_a_class_iii_sheet_is_clean_and_equals_its_svg(tmp_path, capsys):
    """The triad's kinematic sheet (its base link a plate with hatched corners, plans by
    Assur's special point), in Chinese, through the CLI: a clean DXF whose segments, circles
    and texts are the SVG's."""
    assert main(["sheet", "triad-rocker", "--lang", "zh", "-o", str(tmp_path / "t.dxf")]) == 0
    assert (tmp_path / "t.svg").is_file()
    doc = ezdxf.readfile(tmp_path / "t.dxf")
    auditor = doc.audit()
    assert auditor.has_errors is False and len(auditor.fixes) == 0
    assert set(Counter(e.dxftype() for e in doc.modelspace())) <= ALLOWED
    from velplan.sheets.kinematic import build_sheet

    sheet = build_sheet(velplan.Study("triad-rocker"), lang="zh")
    svg = _svg_geometry(to_svg(sheet.scene, sheet.style, precision=9), sheet.scene.height_mm)
    dxf = _dxf_geometry(doc)
    a, b = _sorted_segments(svg["segments"]), _sorted_segments(dxf["segments"])
    assert a.shape == b.shape and len(a) > 300 and np.abs(a - b).max() < 1e-3
    texts = [e.dxf.text for e in doc.modelspace().query("TEXT")]
    assert "机构位置图" in texts and "K₃" in texts  # Assur's point where its plans are drawn (issue 32)
