"""The catalogue's contact sheet (the README's gallery): every sheet's PNG as a captioned
thumbnail in a grid, in 16 greys."""

import numpy as np
import pytest
from PIL import Image

from velplan.catalogue.gallery import contact_sheet
from velplan.errors import VelplanError


def _png(path, shade: int, size=(420, 297)):
    Image.fromarray(np.full(size[::-1], shade, dtype=np.uint8)).save(path)
    return path


def test_the_contact_sheet_has_a_thumbnail_per_sheet_in_rows_of_columns(tmp_path):
    pngs = {f"m{k}": _png(tmp_path / f"m{k}.png", 40 * k) for k in range(1, 5)}
    out = contact_sheet(pngs, tmp_path / "contact.png", columns=3, thumb_px=200)
    img = Image.open(out)
    assert img.mode == "P" and len(img.getcolors()) <= 16
    width, height = img.size
    assert width == 600                      # three 200 px columns
    assert 2 * 200 * 297 / 420 < height < 2 * (200 * 297 / 420 + 40)  # two rows and captions
    grey = np.asarray(img.convert("L"))
    # the darkest sheet (shade 40) is drawn: its thumbnail's grey is on the image
    assert np.abs(grey.astype(int) - 40).min() <= 16


def test_no_sheets_is_refused_and_writes_nothing(tmp_path):
    with pytest.raises(VelplanError, match="no sheets"):
        contact_sheet({}, tmp_path / "contact.png")
    assert not (tmp_path / "contact.png").exists()
