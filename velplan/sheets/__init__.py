"""Sheets: views arranged on a drawing sheet with its frame and title block (ESKD or ISO),
each view at a standard scale, and the files written from them (SVG, PNG, PDF).

Every sheet reads one `velplan.study.Study`. `skeleton` holds what the sheets share (the
checked request, the bottom band, the title block, the scene), `solver` the fit by drawing
(each trial view drawn once); `kinematic`, `forces` and `dynamics` supply their own zones
and views.
"""
