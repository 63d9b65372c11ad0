"""Every catalogue mechanism's kinematic sheet, built once at one language (Russian) on A1
(here) and on A3 (`test_catalogue_gallery_a3.py`, the same checks) and shared by the checks, held to the bars of the bundled sheets: no text over
text, every text inside the frame and every glyph in the bundled font, the scheme and the plans
filling their zones, the kinematic diagrams present, one μv and one μa per sheet; and every
title in four languages naming the mechanism, never its file key. The class III ones' A1 sheets
also through the PNG export and off the thick lines as `test_sheet_quality_ru.py` holds its
sheets (whose file leaves these out: `quality.in_catalogue_gallery`)."""

import pytest
import shapely

import velplan
from tests.sheet import gallery_marks as gm
from tests.sheet import quality
from velplan.mechanism.loader import catalogue_names
from velplan.render.fonts import missing_in_bundled
from velplan.render.layout import label_box, overlapping_labels
from velplan.render.scene import Text
from velplan.sheets.frame import frame_bounds
from velplan.sheets.kinematic import build_sheet, default_title

NAMES = tuple(catalogue_names())
FORMATS = ("A1",)
"""The format this module checks (A3: `test_catalogue_gallery_a3.py`)."""
# every A3 sheet carries its diagrams, each curve 30 mm high at least: the compact block
# (velplan/views/diagram_compact.py) in a free spot, or beside plans fitted smaller, or beside the
# first position's plans alone, or under the scheme with the table back over the title block
# (triad-press; tests/sheet/test_gallery_marks_a3_kinematic.py checks the ranges); may only go up
A3_DIAGRAMS = 25


class Gallery(dict):
    """(name, fmt) → the Russian kinematic sheet, built on first use (a module checks one format:
    the A3 sheets are checked in `test_catalogue_gallery_a3.py`, so that the test workers share
    the two formats out)."""

    def __init__(self):
        super().__init__()
        self.studies: dict = {}

    def __missing__(self, key):
        name, fmt = key
        study = self.studies.setdefault(name, velplan.Study(name))
        # built once with the kinematic gallery's where that is Russian too (`gallery_marks.shared`)
        self[key] = sheet = gm.shared(name, "kinematic", "ru", fmt, lambda: build_sheet(study, fmt=fmt, lang="ru"))
        return sheet


@pytest.fixture(scope="module")
def gallery():
    return Gallery()


def zone_shares(sheet) -> dict:
    """The share of its zone the scheme spans, and per plan kind the largest share a plan of
    that kind spans (the plans of a kind share one μ: the largest fills its cell, the others
    are as much smaller as their velocities), along the better of the two directions."""
    out: dict = {}
    for view, (x0, y0, x1, y1) in sheet.zones.items():
        b = sheet.views[view].bounds
        share = max((b[2] - b[0]) / (x1 - x0), (b[3] - b[1]) / (y1 - y0))
        key = view if view == "mechanism" else view.rsplit("-", 1)[0]
        out[key] = max(out.get(key, 0.0), share)
    return out


def _built(gallery, fmt):
    return [(name, gallery[name, fmt]) for name in NAMES]


def test_the_catalogue_has_25_mechanisms_3_of_class_iii():
    assert len(NAMES) == 25
    triads = [n for n in NAMES if any(g.kind == "triad" for g in velplan.load(n).groups)]
    assert len(triads) == 3, triads


@pytest.mark.parametrize("fmt", FORMATS)
def test_no_text_over_text_and_all_inside_the_frame(gallery, fmt):
    check_no_text_over_text_and_all_inside_the_frame(gallery, fmt)


def check_no_text_over_text_and_all_inside_the_frame(gallery, fmt):
    frame = shapely.box(*frame_bounds(fmt)).buffer(1e-6)
    for name, sheet in _built(gallery, fmt):
        pairs = overlapping_labels(sheet.scene, min_area=0.5)
        assert not pairs, (name, fmt, [(a.text, b.text) for a, b in pairs[:5]])
        outside = [t.text for t in sheet.scene.of_kind(Text) if not frame.contains(label_box(t))]
        assert not outside, (name, fmt, outside)
        unfound = [t.text for t in sheet.scene.of_kind(Text) if missing_in_bundled(t.text)]
        assert not unfound, (name, fmt, unfound)  # every glyph in Velplan Sans


def test_the_class_iii_sheets_print_and_keep_their_texts_off_the_thick_lines(gallery, tmp_path):
    """The class III sheets on A1 (left out of `test_sheet_quality_ru.py`, which holds its own
    so): through the PNG export, and at most four texts crossed by a thick line or a vector."""
    pytest.importorskip("cairosvg")
    for name in quality.TRIADS:
        sheet = gallery[name, "A1"]
        quality.assert_png(sheet, tmp_path, name, "kinematic")
        crossed = gm.crossed_texts(sheet.scene)
        assert len(crossed) <= 4, (name, crossed)


@pytest.mark.parametrize("fmt", FORMATS)
def test_zones_filled_and_diagrams_present(gallery, fmt):
    check_zones_filled_and_diagrams_present(gallery, fmt)


def check_zones_filled_and_diagrams_present(gallery, fmt):
    """Each plan spans at least half its cell and the scheme half its zone (its share of the
    top band, or the whole height beside the table) along one direction; every mechanism with
    an output has its kinematic diagrams on A1, and on A3 where the scheme and the plans leave
    a free corner, a compact block of them on A3."""
    with_diagrams = 0
    for name, sheet in _built(gallery, fmt):
        shares = zone_shares(sheet)
        assert shares.pop("mechanism") >= 0.5, (name, fmt)
        for kind, share in shares.items():
            assert share >= 0.5, (name, fmt, kind, round(share, 2))
        assert sheet.mechanism.output is not None, name
        with_diagrams += "diagrams" in sheet.views
        assert {"mechanism", "table"} <= set(sheet.views), (name, fmt)
    assert with_diagrams >= (25 if fmt == "A1" else A3_DIAGRAMS), (fmt, with_diagrams)


@pytest.mark.parametrize("fmt", FORMATS)
def test_one_velocity_scale_and_one_acceleration_scale_per_sheet(gallery, fmt):
    check_one_velocity_scale_and_one_acceleration_scale_per_sheet(gallery, fmt)


def check_one_velocity_scale_and_one_acceleration_scale_per_sheet(gallery, fmt):
    """One μ per kind of plan, except where one μ would leave a plan illegible (the
    legibility rule, `legible_at`): then each plan states its own."""
    from velplan.sheets.kinematic import legible_at

    shared = 0
    for name, sheet in _built(gallery, fmt):
        for kind in "va":
            names = [k for k in sheet.scales if k.startswith(f"plan-{kind}-")]
            mus = {sheet.scales[k] for k in names}
            shared += len(mus) == 1
            if len(mus) > 1:
                common = max(mus)
                assert not all(legible_at(sheet.plans[k].at_scale(common), sheet.plans[k],
                                          sheet.plan_index[k] + 1, fmt) for k in names), (name, fmt, kind)
    assert shared >= len(NAMES)  # most of the catalogue's plans still share one μ


@pytest.mark.parametrize("lang", ["en", "ru", "uk", "zh"])
def test_no_title_shows_a_file_key(gallery, lang):
    """The title block of the kinematic, force and dynamics sheets (the DXF draws the same
    scene) and the html page's title name every bundled and catalogue mechanism in `lang`."""
    from velplan.html.page import page_html

    from velplan.sheets.dynamics import default_dynamics_title
    from velplan.sheets.forces import default_force_title

    for name in velplan.example_names() + list(NAMES):
        mech = velplan.load(name)
        proper = mech.name_in(lang)
        assert proper and proper.lower() != name.lower(), (name, lang, proper)
        titles = [default_title(mech, lang, "A1", "1:1", "eskd").title,
                  default_force_title(mech, lang, "1:1").title,
                  default_dynamics_title(mech, lang, "1:1").title]
        assert all(t.endswith(": " + proper) for t in titles), (name, lang, titles)
    sheet = gallery["stephenson-six-bar", "A1"]
    title = sheet.info.title
    assert title.endswith(sheet.mechanism.name_in("ru")) and "stephenson" not in title
    assert not any("stephenson" in t.text.lower() for t in sheet.scene.of_kind(Text))  # nor the designation
    page = page_html(velplan.Study("stephenson-six-bar", n=12), lang)
    head = page[page.index("<title>"):page.index("</title>")]
    assert velplan.load("stephenson-six-bar").name_in(lang).split()[0] in head
    assert "stephenson" not in head, head
