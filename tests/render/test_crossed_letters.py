"""`crossed_letters`: a text a drawn line runs through over 1 mm, its own leader excepted."""
from velplan.render.layout import crossed_letters, label_box
from velplan.render.scene import Arrow, Polygon, Polyline, Text


def _a():
    return Text((10.0, 10.0), "A", "labels", size_mm=3.5, anchor="middle")


def test_a_line_through_the_letter_crosses_it():
    (x0, y0, x1, y1) = label_box(_a()).bounds
    mid = (y0 + y1) / 2
    through = Polyline([(x0 - 5, mid), (x1 + 5, mid)], "lines", "thin")
    grazing = Polyline([(x0 - 5, y1 + 0.2), (x1 + 5, y1 + 0.2)], "lines", "thin")
    assert crossed_letters([_a(), through]) == [_a()]
    assert crossed_letters([_a(), grazing]) == []
    assert crossed_letters([_a(), Arrow((x0 - 5, mid), (x1 + 5, mid), "vectors", "thick")]) == [_a()]
    ring = Polygon([(x0 + 0.5, y0 - 3), (x0 + 0.5, y1 + 3), (x0 - 3, y1 + 3)], "outlines", "thin")
    assert crossed_letters([_a(), ring]) == [_a()]


def test_its_own_leader_does_not_cross_it_another_does():
    (x0, y0, x1, y1) = label_box(_a()).bounds
    mid = (y0 + y1) / 2
    own = Polyline([(x1 + 8, mid), (x1 - 1.5, mid)], "labels", "thin")  # ends at its box
    other = Polyline([(x1 + 8, mid), (x0 - 8, mid)], "labels", "thin")  # a leader passing through
    assert crossed_letters([_a(), own]) == []
    assert crossed_letters([_a(), other]) == [_a()]
