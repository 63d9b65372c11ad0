"""The interactive page: the scheme and both plans over a whole turn, in one HTML file.

``velplan html MECH -o page.html`` and `Page` build a self-contained page (no network: style,
script and data inline): a crank-angle slider over the study's positions with play/pause, the
velocity and acceleration plans built one construction step at a time with the worked
solution's sentence, the scales, and per step the analytic value and the drafting error.
It sits beside the sheets: it reads a `velplan.study.Study` and draws with the views.

>>> import velplan
>>> from velplan.html import MAX_POSITIONS, Page, page_html
>>> html = page_html(velplan.Study("four-bar", n=4), "en")     # the page's text
>>> html.startswith("<!DOCTYPE html>"), "four-bar" in html
(True, True)
>>> Page("four-bar", positions=MAX_POSITIONS + 1)             # a slider stop per position
Traceback (most recent call last):
...
velplan.errors.VelplanError: positions must be between 1 and 720, not 721
"""

from velplan.html.page import MAX_POSITIONS, Page, page_html

__all__ = ["Page", "page_html", "MAX_POSITIONS"]
