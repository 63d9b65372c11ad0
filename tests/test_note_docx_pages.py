"""The layout model that estimates the note's pages (`velplan.note.docx_pages`): its lines,
its spacing and how it breaks pages, on blocks whose heights are known."""

from __future__ import annotations

import pytest

pytest.importorskip("docx")

from velplan.note import docx_pages as P  # noqa: E402
from velplan.note.serif_widths import WIDTHS  # noqa: E402

PAGE = P.PAGE_PT


def test_a_line_is_the_fonts_ascent_descent_and_gap_times_the_spacing():
    # Times New Roman's hhea: ascent 1825, descent 443, line gap 87 of 2048 units per em
    assert P.line_pt(P.Para(size=12, line=1.5)) == pytest.approx(12 * 1.5 * (1825 + 443 + 87) / 2048, rel=1e-3)
    assert P.PAGE_PT == pytest.approx((297 - 40) / 25.4 * 72)


def test_widths_are_times_advance_widths():
    # Times New Roman: digits half an em, space a quarter, 'm' 1593, 'M' 1821 of 2048 units
    assert {WIDTHS[c] for c in "0123456789"} == {0.5}
    assert WIDTHS[" "] == 0.25
    assert WIDTHS["m"] == pytest.approx(1593 / 2048, abs=5e-4) and WIDTHS["M"] == pytest.approx(1821 / 2048, abs=5e-4)


def test_words_break_greedily_and_chinese_characters_need_no_space():
    words = [(0.0, 3000.0)] + [(250.0, 3000.0)] * 5  # six words of 3000 twips, spaces of 250
    assert P._lines(words, 9638, 0) == 2  # three to a line: 3·3000 + 2·250 = 9500 ≤ 9638
    assert P._lines(words, 9638, 709) == 3  # the first line's indent leaves room for two: 2 + 3 + 1
    cjk = [(0.0, 240.0)] * 80  # 80 characters of 12 pt: 40 to a line of 9638 twips
    assert P._lines(cjk, 9638, 0) == 2


def _line(h=20.0, n=1, **kw):
    return P.Block([h] * n, splits=True, **kw)


def test_a_caption_goes_with_its_table_to_the_next_page():
    filler = P.Block([PAGE - 60.0])
    caption = P.Block([14.0], keep_next=True)
    table = P.Block([13.0] * 5, splits=True, header=13.0)  # 65 pt: does not fit in the 60 left
    pages = P.place([filler, caption, table])
    assert [p for p, _ in pages] == [1, 2, 2]
    assert pages[2][1] == pytest.approx(14.0)


def test_widow_and_orphan_control():
    room = 3 * 20.0 + 5.0
    # three lines, room for three: stays; four lines, room for three: two here, two there
    for n, first_page_lines in ((3, 3), (4, 2), (5, 3)):
        pages = P.place([P.Block([PAGE - room]), _line(n=n), _line()])
        assert pages[1][0] == 1
        assert pages[2] == (2, pytest.approx((n - first_page_lines) * 20.0)), n
    # room for one line of a two-line paragraph: the paragraph moves whole
    pages = P.place([P.Block([PAGE - 25.0]), _line(n=2)])
    assert pages[1] == (2, 0.0)


def test_spacing_the_larger_of_after_and_before_none_at_a_page_the_text_ran_onto():
    a, b = P.Block([20.0], after=6.0), P.Block([20.0], before=12.0)
    assert P.place([a, b])[1] == (1, pytest.approx(32.0))
    fill = P.Block([PAGE - 10.0])
    assert P.place([fill, b])[1] == (2, 0.0)  # a soft break: no space before at the top
    assert P.place([P.Block([], breaks=True), b])[1] == (2, pytest.approx(12.0))  # a page break: kept


def test_a_table_longer_than_a_page_runs_on_under_its_repeated_header():
    table = P.Block([20.0] * 60, splits=True, header=20.0)  # 1200 pt
    after = P.Block([10.0])
    rows_per_page = int(PAGE // 20.0)
    rest = 60 - rows_per_page
    pages = P.place([table, after])
    assert pages[1] == (2, pytest.approx(20.0 + rest * 20.0))


def test_the_last_line_of_a_page_may_hang_by_its_spacing():
    line = P.line_pt(P.Para(size=12, line=1.5))
    slack = line - 12 * P.LINE
    block = P.Block([line], splits=True, slack=slack)
    fill = P.Block([PAGE - line + slack / 2])  # the line's font fits, its spacing does not
    assert P.place([fill, block])[1][0] == 1
    fill = P.Block([PAGE - line + slack * 1.5])
    assert P.place([fill, block])[1][0] == 2
