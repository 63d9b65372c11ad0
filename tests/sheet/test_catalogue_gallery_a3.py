"""The catalogue gallery's A3 sheets (`test_catalogue_gallery.py` checks the A1 ones with the same
checks): no text over text, every text inside the frame, the zones filled, the diagrams present,
one μv and one μa per sheet; a scheme too tall for the top band."""

import pytest

from velplan.sheets.layout import MIN_CRANK_MM
from velplan.sheets.skeleton import sheet_request
from tests.sheet.test_catalogue_gallery import (Gallery, check_no_text_over_text_and_all_inside_the_frame,
                                                check_one_velocity_scale_and_one_acceleration_scale_per_sheet,
                                                check_zones_filled_and_diagrams_present)

FMT = "A3"


@pytest.fixture(scope="module")
def gallery():
    return Gallery()


def test_no_text_over_text_and_all_inside_the_frame(gallery):
    check_no_text_over_text_and_all_inside_the_frame(gallery, FMT)


def test_zones_filled_and_diagrams_present(gallery):
    check_zones_filled_and_diagrams_present(gallery, FMT)


def test_one_velocity_scale_and_one_acceleration_scale_per_sheet(gallery):
    check_one_velocity_scale_and_one_acceleration_scale_per_sheet(gallery, FMT)


def test_a_scheme_too_tall_for_the_top_band_takes_the_height_beside_the_table(gallery):
    """The jaw crusher on A3: at 1:2.5, the last ESKD scale with a crank of 8 mm or more, its
    scheme is about 190 × 240 mm with its labels, taller than the top band; its zone is then the
    whole height of the drawing area left of the table and the title block, and the plans stand
    to its right above the table: the first position's alone, with the compact diagrams under them
    (both positions' plans leave no room for diagrams 30 mm high)."""
    sheet = gallery["jaw-crusher", "A3"]
    fx0, fy0, _, fy1 = sheet_request("jaw-crusher", fmt="A3", lang="ru").area
    assert sheet.scales["mu_l"] == 0.0025 and sheet.mechanism.crank.length / 0.0025 >= MIN_CRANK_MM
    zone = sheet.zones["mechanism"]
    scheme, table = sheet.views["mechanism"].bounds, sheet.views["table"].bounds
    assert (zone[0], zone[1], zone[3]) == (fx0, fy0, fy1) and zone[2] < table[0]
    assert scheme[1] < table[3] and scheme[2] <= zone[2]  # reaches below the top of the table
    plans = [v.bounds for k, v in sheet.views.items() if k.startswith("plan-")]
    assert len(plans) == 2 and all(b[1] > table[3] and b[0] > scheme[2] for b in plans)
    diagrams = sheet.views["diagrams"].bounds
    assert diagrams[0] > scheme[2] and diagrams[1] > table[3] and all(diagrams[3] < b[1] for b in plans)
