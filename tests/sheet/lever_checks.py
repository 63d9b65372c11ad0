"""Zhukovsky's lever at least `MIN_LEVER_MM` across on every gallery force sheet (issue 32,
item 8), checked on the sheets `test_gallery_marks_a1_forces.py` and
`test_gallery_marks_a3_forces.py` build for their own checks (each sheet built once in the
suite; `test_lever_size.py` holds the lever's other tests)."""

import numpy as np
import pytest

import velplan
from velplan.sheets.forces import MIN_LEVER_MM, has_forces

from tests.sheet import gallery_marks as gm


def plan_span(fa, k: int) -> float:
    """The larger side of the velocity plan at position `k` (m/s), from the velocities."""
    v = np.asarray(fa.kinematics.velocities[k - 1], float)
    v = np.vstack([v[np.all(np.isfinite(v), axis=1)], [[0.0, 0.0]]])
    return float(np.max(np.ptp(v, axis=0)))


def force_sheets(gallery: gm.GallerySheets) -> dict:
    """name → the gallery's force sheet (None where refused) of every mechanism with forces."""
    return {n: gallery[n, "forces"] for n in gm.NAMES if has_forces(velplan.load(n))}


def check_every_lever_is_at_least_the_floor(gallery: gm.GallerySheets) -> None:
    """On every force sheet that builds (at least half of them), each position's lever has the
    sheet's μv and spans at least the format's floor, measured from the kinematics."""
    sheets = force_sheets(gallery)
    built = {n: s for n, s in sheets.items() if s is not None}
    assert len(built) >= len(sheets) // 2, gallery.refused
    small = []
    for name, sheet in built.items():
        for k in sheet.positions:
            mu = sheet.scales[f"lever-{k}"]
            assert sheet.views[f"lever-{k}"].view.meta["mu_v"] == pytest.approx(mu)
            size = plan_span(sheet.analysis, k) / mu
            if size < MIN_LEVER_MM[gallery.fmt] - 1e-6:
                small.append(f"{name} lever-{k}: {size:.1f} mm")
    assert not small, small


def check_refusals_are_one_line_and_suggest_a_larger_format(gallery: gm.GallerySheets) -> None:
    """A force sheet refused (the lever's floor cannot be given) says so in one line, naming --format."""
    force_sheets(gallery)
    for (name, kind), reason in gallery.refused.items():
        if kind == "forces":
            assert "\n" not in reason, name
            assert "--format" in reason, name
