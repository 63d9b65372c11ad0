"""The catalogue: course-work mechanisms with masses, loads and dynamics data (TOML files).

Each file is loadable by name with `velplan.load` (``velplan.load("whitworth")``), like the
bundled examples; `velplan.mechanism.loader.catalogue_names` lists them and
``python -m velplan.catalogue.gallery OUTDIR`` draws a sheet of each. The numbers are our own
choices, typical of course-design guides; each file states them in a comment at its top.
"""
