"""Sheets: views arranged on a drawing sheet with its frame and title block (ESKD or ISO),
each view at a standard scale, and the files written from them (SVG, PNG, PDF).

Every sheet reads one `velplan.study.Study`.
"""
