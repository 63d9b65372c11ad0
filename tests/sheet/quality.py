"""What the sheet-quality tests share (`test_sheet_quality.py` and its files per language,
`test_sheet_quality_<lang>.py`, split so that the workers of ``pytest -n … --dist loadfile``
share the sheets out): the studies, each sheet built once per module (`built`), and the checks
made in every language.

A mechanism's sheets in its gallery language (`gallery_marks.lang_of`) are the gallery's too:
the gallery's modules (`test_gallery_marks_*.py`) make these checks on them
(`check_gallery_sheets`), and the files per language leave them out (`in_gallery`), so that
each is built once in the suite. So too the class III kinematic sheets in Russian: the
catalogue gallery's (`test_catalogue_gallery.py`, `_a3.py`; `in_catalogue_gallery`)."""

from importlib.resources import files

import pytest
import shapely

import velplan
from velplan.render.fonts import missing_in_bundled
from velplan.render.layout import label_box, overlapping_labels
from velplan.render.scene import Text
from velplan.sheets.dynamics import build_dynamics_sheet
from velplan.sheets.forces import build_force_sheet, has_forces
from velplan.sheets.frame import frame_bounds
from velplan.sheets.kinematic import build_sheet

from tests.sheet import gallery_marks as gm

LANGS = ("en", "ru", "uk", "zh")
#: The catalogue's class III mechanisms (``kind = "triad"`` files): every sheet kind of each.
TRIADS = tuple(sorted(p.name[:-5] for p in files("velplan.catalogue").iterdir()
                      if p.name.endswith(".toml") and 'kind = "triad"' in p.read_text("utf-8")))


@pytest.fixture(scope="module")
def studies():
    return ({n: velplan.Study(n) for n in velplan.example_names() + list(TRIADS)}
            | {"shaper-δ": velplan.Study("shaper", delta=0.05)})


@pytest.fixture(scope="module")
def built(studies):
    """sheet(name, kind, lang, fmt): the sheet, built on first use and kept for the module."""
    cache: dict = {}
    makers = {"kinematic": build_sheet, "forces": build_force_sheet,
              "dynamics": build_dynamics_sheet}

    def sheet(name, kind, lang, fmt="A1"):
        key = (name, kind, lang, fmt)
        if key not in cache:
            cache[key] = makers[kind](studies[name], lang=lang, fmt=fmt)
        return cache[key]
    return sheet


def in_gallery(name: str, lang: str) -> bool:
    """Whether `lang` is `name`'s gallery language: its sheets in `lang` are checked on the
    gallery's (`check_gallery_sheets`), not built again by the file of `lang`."""
    return name in gm.NAMES and gm.lang_of(name) == lang


def in_catalogue_gallery(name: str, kind: str, lang: str) -> bool:
    """Whether the catalogue gallery (every catalogue mechanism's kinematic sheet in Russian on
    A1 and A3) builds the sheet and makes this module's checks on it, not the file of `lang`."""
    return (name, kind, lang) in {(triad, "kinematic", "ru") for triad in TRIADS}


def triads_in(lang: str) -> list[str]:
    """The class III mechanisms whose sheets the file of `lang` builds (:func:`in_gallery`)."""
    return [name for name in TRIADS if not in_gallery(name, lang)]


def sheets_in(studies, lang, built):
    """(name, kind, sheet) of every A1 sheet checked in `lang` by its file (the others: `in_gallery`)."""
    for name, study in studies.items():
        if name == "shaper-δ":
            yield name, "dynamics", built(name, "dynamics", lang)
            continue
        if in_gallery(name, lang):
            continue
        if not in_catalogue_gallery(name, "kinematic", lang):
            yield name, "kinematic", built(name, "kinematic", lang)
        if has_forces(study.mechanism):
            yield name, "forces", built(name, "forces", lang)
        if name in TRIADS:
            yield name, "dynamics", built(name, "dynamics", lang)


def assert_legible(sheet, fmt, name, kind):
    """No text over text, every text inside the frame, every glyph in the bundled font."""
    frame = shapely.box(*frame_bounds(fmt)).buffer(1e-6)
    pairs = overlapping_labels(sheet.scene, min_area=0.5)
    assert not pairs, (name, kind, fmt, [(a.text, b.text) for a, b in pairs[:5]])
    for t in sheet.scene.of_kind(Text):
        assert frame.contains(label_box(t)), (name, kind, fmt, t.text)
        assert not missing_in_bundled(t.text), (name, kind, t.text)  # every glyph in Velplan Sans


def check_a1_sheets(studies, built, lang):
    """No text over text, all inside the frame, every glyph in the font: every A1 sheet in ``lang``."""
    for name, kind, sheet in sheets_in(studies, lang, built):
        assert_legible(sheet, "A1", name, kind)


def check_class_iii_on_a3(built, name, lang):
    """The kinematic and dynamics sheets of a class III mechanism on A3 too; its force sheet
    there either is legible or says in one line that it does not fit (as the press's)."""
    for kind in ("kinematic", "dynamics"):
        if not in_catalogue_gallery(name, kind, lang):
            assert_legible(built(name, kind, lang, "A3"), "A3", name, kind)
    try:
        sheet = built(name, "forces", lang, "A3")
    except velplan.errors.ScaleError as exc:
        assert "do not fit A3" in str(exc) and "\n" not in str(exc)
    else:
        assert_legible(sheet, "A3", name, "forces")


def check_png(studies, built, lang, tmp_path):
    """Every bundled sheet through the PNG export, whose font choice refuses a text no font can
    draw (one-line error): each comes out, an image of the sheet's size."""
    pytest.importorskip("cairosvg")
    for name, kind, sheet in sheets_in(studies, lang, built):
        assert_png(sheet, tmp_path, name, kind)


def assert_png(sheet, folder, name, kind):
    """The A1 sheet through the PNG export: an image of the sheet's size with something drawn."""
    from PIL import Image

    from velplan.render.export import write_png

    path = write_png(sheet.svg(), folder / f"{name}-{kind}.png", dpi=20)
    with Image.open(path) as im:
        assert im.size == (round(841 / 25.4 * 20), round(594 / 25.4 * 20)), (name, kind, im.size)
        assert im.convert("L").getextrema()[0] < 100  # something is drawn


def assert_zones_filled(sheet, name, fmt):
    """Each plan spans at least half its grid cell, and the scheme half of its share of the top
    band, along one of the two directions (a standard scale one step larger would not fit)."""
    from tests.sheet.test_catalogue_gallery import zone_shares

    assert set(sheet.zones) == {"mechanism", *(k for k in sheet.views if k.startswith("plan-"))}
    for view, share in zone_shares(sheet).items():  # a kind's plans share one μ
        assert share >= 0.5, (name, fmt, view, share)


def check_gallery_sheets(gallery: "gm.GallerySheets", kinds, tmp_path):
    """The checks of the files per language on the gallery's sheets of `kinds` of the bundled
    and class III mechanisms, in their gallery language (:func:`in_gallery`): on A1 every sheet
    legible and through the PNG export; on A3 the class III ones legible, a force sheet legible
    or refused in one line as not fitting A3, and the bundled English kinematic sheets legible;
    the English kinematic sheets' zones filled on both formats."""
    pytest.importorskip("cairosvg")
    fmt, checked = gallery.fmt, 0
    for name in velplan.example_names() + list(TRIADS):
        lang = gm.lang_of(name)
        for kind in kinds:
            if ((kind == "forces" and not has_forces(velplan.load(name)))
                    or (kind == "dynamics" and name not in TRIADS)
                    or (fmt == "A3" and name not in TRIADS and (kind, lang) != ("kinematic", "en"))):
                continue
            sheet = gallery[name, kind]
            if sheet is None:
                reason = gallery.refused[name, kind]
                assert (fmt, kind) == ("A3", "forces") and "do not fit A3" in reason and "\n" not in reason, \
                    (name, kind, reason)
                continue
            assert_legible(sheet, fmt, name, kind)
            if fmt == "A1":
                assert_png(sheet, tmp_path, name, kind)
            if (kind, lang) == ("kinematic", "en"):
                assert_zones_filled(sheet, name, fmt)
            checked += 1
    assert checked >= len(kinds), checked
