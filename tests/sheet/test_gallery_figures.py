"""Issue 32's "Done when" on the instant-centres figure (`velplan centres X --position 4`) and
the step figures of position 4 of every bundled and catalogue mechanism, in a rotating
language (`gallery_marks.lang_of`): no text over text, no text crossed by a thick line or a
vector, every label nearest its own point and within 6 mm of it (or led to it), every text and
index at least 2.5 mm high."""

import pytest

import velplan
from tests.sheet import gallery_marks as gm
from velplan.plans.centres import construct_centres
from velplan.render.scene import Scene, Text
from velplan.views.centres import centres_view
from velplan.views.steps import step_figures

POSITION = 4


@pytest.fixture(scope="module")
def figures():
    """name → ((the centres figure's scene, its anchors), [(a step figure's scene, its anchors)])."""
    out = {}
    for name in gm.NAMES:
        study, lang = velplan.Study(name), gm.lang_of(name)
        view = centres_view(construct_centres(study.kinematics, POSITION), fine=study.turn, number=POSITION, lang=lang)
        steps = step_figures(study.mechanism, study.kinematics,
                             {k: study.plan(k) for k in ("velocity", "acceleration")}, POSITION, lang=lang)
        out[name] = ((Scene(tuple(view.primitives), view.width_mm, view.height_mm), view.meta["anchors"]),
                     [(f.scene, f.anchors) for f in steps])
    return out


def _each(figures):
    """(where, scene, its points' anchors) of every figure."""
    for name, (centres, steps) in figures.items():
        yield f"{name}/centres", *centres
        yield from ((f"{name}/step {k + 1}", *s) for k, s in enumerate(steps))


def test_no_text_over_text(figures):
    bad = [(where, pairs) for where, scene, _ in _each(figures) if (pairs := gm.overlaps(scene))]
    assert not bad, bad[:5]


def test_texts_keep_off_the_drawn_lines(figures):
    # none since the plans' letters of the step figures and the centres' names on the scheme are
    # placed by their points clear of every line drawn (views/letters.py; 13 crossed texts before)
    every = [(where, t) for where, scene, _ in _each(figures) for t in gm.crossed_texts(scene)]
    assert not every, every


#: Texts crossed by any drawn line, thin ones too (Kennedy and construction lines, outlines,
#: other texts' leaders): none since the circle diagram's numbers break their own chords, the
#: Kennedy lines are broken under the texts that must stand on them, and a leader keeps off the
#: other letters farther out before it crosses one (17 on 27 Nov 2026; a ratchet: stays 0).
CROSSED_BY_ANY_LINE = 0


def test_texts_keep_off_the_thin_lines_too(figures):
    every = [(where, t) for where, scene, _ in _each(figures) for t in gm.crossed_by_any_line(scene)]
    assert len(every) <= CROSSED_BY_ANY_LINE, every


def test_every_label_names_its_own_point(figures):
    """Every point's letter and centre's name has its own point nearest, within 6 mm (or a
    leader to it): the scheme's letters, the plans' image letters, the centres' names."""
    bad = [(where, amb) for where, scene, anchors in _each(figures) if (amb := gm.ambiguous_labels(scene, anchors))]
    assert not bad, bad[:5]
    # every figure tells its points, and its letters are among them (the check is not void)
    assert all(any(t.text.split(", ")[0].split(" (")[0] in anchors for t in scene.of_kind(Text))
               for _, scene, anchors in _each(figures))


def test_every_text_and_index_at_least_2_5_mm(figures):
    bad = [(where, small) for where, scene, _ in _each(figures) if (small := gm.small_texts(scene, title=False))]
    assert not bad, bad[:5]
    assert sum(len(s) for _, s in figures.values()) >= 2 * len(gm.NAMES)  # every mechanism has its steps
