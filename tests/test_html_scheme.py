"""The page's scheme letters placed for all positions together (`velplan.html.scheme`): the same
letters and leaders as `place_letters` call by call, and the same views as `mechanism_view`."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from velplan.analysis.numbering import position_number
from velplan.html.scheme import draw_together, place_together
from velplan.render.scene import Text
from velplan.study import Study
from velplan.views.letters import place_letters
from velplan.views.mechanism import LetterRequest, mechanism_view, run_scheme, scheme_steps


def _scheme_args(study: Study, i: int) -> dict:
    kin = study.kinematics
    n = len(kin)
    reference = sorted({int(round(k * n / 6)) % n for k in range(6)})
    idx = sorted(set(reference) | {i})
    return dict(kin=kin.take(idx), fine=study.turn, mu_l=0.002, n=len(idx),
                thick=position_number(idx.index(i)), lang="en", single=True, title=False)


def _requests(study: Study, positions) -> list[LetterRequest]:
    """Every `place_letters` call the schemes of `positions` make, answered one at a time."""
    out = []
    for i in positions:
        steps = scheme_steps(study.mechanism, **_scheme_args(study, i))
        try:
            request = next(steps)
            while True:
                out.append(request)
                request = steps.send(place_letters(*request.args, **request.kwargs))
        except StopIteration:
            pass
    return out


@pytest.mark.parametrize("name", ["shaper", "four-bar", "triad-press", "stephenson-six-bar"])
def test_letters_placed_together_are_those_of_place_letters(name):
    study = Study(name, n=12)
    requests = _requests(study, [i for i in range(12) if study.kinematics.valid[i]])
    assert len(requests) >= 2 * 10
    together = place_together(requests)
    alone = [place_letters(*r.args, **r.kwargs) for r in requests]
    assert together == alone
    assert sum(len(letters) for letters, _ in together) > 4 * len(requests) // 2


@pytest.mark.parametrize("name", ["shaper", "triad-press"])
def test_views_drawn_together_are_those_of_mechanism_view(name):
    study = Study(name, n=12)
    positions = [0, 3, 7, 11]
    together = draw_together([scheme_steps(study.mechanism, **_scheme_args(study, i)) for i in positions])
    for i, view in zip(positions, together):
        for alone in (mechanism_view(study.mechanism, **_scheme_args(study, i)),
                      run_scheme(scheme_steps(study.mechanism, **_scheme_args(study, i)))):
            assert (view.primitives, view.width_mm, view.height_mm, view.origin) == (
                alone.primitives, alone.width_mm, alone.height_mm, alone.origin)
            assert view.meta["thick"] == alone.meta["thick"]


_xy = st.tuples(st.floats(0, 30), st.floats(0, 30))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.lists(st.tuples(_xy, _xy, st.sampled_from(["A", "B₂", "O₁", "S₃"])), min_size=1, max_size=7),
                min_size=1, max_size=5),
       st.lists(st.tuples(_xy, _xy, st.floats(0.3, 2.0)), max_size=25),
       st.lists(st.tuples(_xy, _xy), max_size=10), st.integers(0, 3))
def test_crowded_calls_placed_together_are_those_of_place_letters(calls, lines, thin, taken):
    """Random crowds, several calls at once (leaders and letters over lines included)."""
    obstacles = [shapely.LineString([a, b]).buffer(r) for a, b, r in lines]
    soft = [shapely.LineString([a, b]) for a, b in thin]
    requests = []
    for call in calls:
        texts = [Text(w, name, "labels", 3.5) for _, w, name in call]
        anchors = [a for a, _, _ in call]
        points = anchors + [b for b, _, _ in call[:2]]
        boxes = [shapely.box(x, y, x + 3, y + 4).buffer(0.4) for (x, y), _, _ in call[:taken]]
        requests.append(LetterRequest((texts, anchors, points, obstacles), {"thin": soft, "taken": boxes}))
    assert place_together(requests) == [place_letters(*r.args, **r.kwargs) for r in requests]


def test_a_crowd_with_leaders_is_placed_as_place_letters_places_it():
    rng = np.random.default_rng(7)
    anchors = [tuple(p) for p in rng.uniform(0, 8, (9, 2))]
    texts = [Text((x + 2, y + 2), "B₁₂", "labels", 3.5) for x, y in anchors]
    obstacles = [shapely.LineString([tuple(a), tuple(b)]).buffer(0.6) for a, b in rng.uniform(-5, 13, (20, 2, 2))]
    request = LetterRequest((texts, anchors, anchors, obstacles), {"thin": [], "taken": []})
    (got, leaders), = place_together([request])
    assert (got, leaders) == place_letters(texts, anchors, anchors, obstacles)
    assert leaders  # the crowd forces some letters out on leaders
