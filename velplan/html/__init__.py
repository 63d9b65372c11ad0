"""The interactive page: the scheme and both plans over a whole turn, in one HTML file.

``velplan html MECH -o page.html`` and `Page` build a self-contained page (no network: style,
script and data inline): a crank-angle slider over the study's positions with play/pause, the
velocity and acceleration plans built one construction step at a time with the worked
solution's sentence, the scales, and per step the analytic value and the drafting error.
It sits beside the sheets: it reads a `velplan.study.Study` and draws with the views.
"""

from velplan.html.page import MAX_POSITIONS, Page, page_html

__all__ = ["Page", "page_html", "MAX_POSITIONS"]
