"""Views of the force-analysis sheet, one module per view: the structural groups separated
out with the forces applied to them (`group`), their force polygons (`polygon`), Zhukovsky's
lever (`lever`), the table of the three balancing moments (`table`) and the diagram M_b(φ)
(`diagram`); `common` and `arrows` hold what they share. The views draw the force analysis
(`velplan.forces.ForceAnalysis`) and compute no result of their own.

What each view draws, as a course sheet does (METHOD.md §5, §7):

* **A group with its forces** (:func:`group_view`): the links of one Assur group (or of the
  initial link) at a standard μl, cut free of the frame and of their neighbours; every force
  acting on them — loads, gravity G, inertia Φ, the components of the reactions into which
  the polygon decomposes them (R12τ, R12n, …) and the reactions of the groups solved before —
  as an arrow of a conventional length from its point of application, the couples (M_Φ, and
  M_b on the crank) as curved arrows. Forces are not drawn to scale here; the polygon is.
* **A force polygon** (:func:`polygon_view`): the known vectors head to tail from the pole at
  a standard μF (N/mm), then the two unknown reactions found where the lines of their known
  directions meet (thin construction lines through the last vertex and through the pole); the
  found vectors thick. Vertices are `ForcePolygon.vertices`. A vector shorter than 3 mm is
  not drawn but listed as ≈ 0 with its value; one that would cover another is drawn beside
  it; each reaction is written under the polygon with the equation it comes from
  (`reaction_equations`: its components, or the equilibrium of one link).
* **Zhukovsky's lever** (:func:`lever_view`): the velocity plan turned by 90° (counter-
  clockwise, as `velplan.forces.lever` turns it), every force carried to the image of its
  point with its own direction, a couple replaced by a pair of forces at the images of two
  points of its link, and the balancing force at the image of the crank tip; the balance is
  written under it: M_b by the lever against M_b by kinetostatics. All of it is read from
  `ForceAnalysis.lever`.
* **The table** (:func:`moments_table_view`) and **the diagram** (:func:`moment_diagram_view`)
  of M_b over the revolution.

Layers: ``fgroup-K-G`` (links), ``fgroup-K-G-forces``, ``fgroup-K-G-labels`` for group G at
position K; ``fpoly-K-G``, ``fpoly-K-G-lines``, ``fpoly-K-G-labels`` for its polygon;
``lever-K``, ``lever-K-forces``, ``lever-K-labels``; ``table``; ``mb-diagram``,
``mb-diagram-labels``. A group's name is written in layer names with characters outside
``[a-z0-9-]`` replaced by ``-``.

Every view of the slider press's force sheet at position 2, from its study's results:

>>> import velplan
>>> from velplan.views.forces import *
>>> study = velplan.Study("slider-press", n=4)
>>> fa = study.forces()
>>> group_links(study.mechanism, "2-3"), group_links(study.mechanism, "crank")
(('2', '3'), ('1',))
>>> [name for name, _, _ in group_forces(fa, "2-3", 2)]
['R12τ', 'G2', 'Φ2', 'G3', 'Φ3', 'R12n', 'R03']
>>> [round(x, 4) for x in group_extent_m(fa, "2-3", 2)]          # m
[0.05, 0.1936]
>>> group_view(fa, "2-3", 2, mu_l=0.004, lang="en", sizes=ForceSizes()).name
'group-2-2-3'
>>> [round(x, 3) for x in polygon_extent(fa.kinetostatics.polygons["2-3"], 2)]   # N
[114.219, 409.574]
>>> polygon_view(fa, "2-3", 2, mu_f=50.0, lang="en").name
'polygon-2-2-3'
>>> round(lever_extent(fa, 2)[0], 6), lever_view(fa, 2, mu_v=0.02, lang="en").name
(0.314159, 'lever-2')
>>> lever_balance(fa, 0.02)[1].balancing_moment.shape
(4,)
>>> moments_table_view(fa, lang="en").name, moment_decimals(fa.kinetostatics.balancing_moment)
('table', 2)
>>> curve = study.moment_curve
>>> isinstance(curve, MomentCurve), moment_diagram_view(curve, lang="en").meta["mu_m"]
(True, 20.0)
>>> group_layers(2, "2-3"), lever_layers(2)
(('fgroup-2-2-3', 'fgroup-2-2-3-forces', 'fgroup-2-2-3-labels'), ('lever-2', 'lever-2-forces', 'lever-2-labels'))
>>> polygon_layers(2, "2-3")
('fpoly-2-2-3', 'fpoly-2-2-3-lines', 'fpoly-2-2-3-labels')
>>> force_text("R12τ"), force_text("MΦ4@B"), slug("Crank A")
('R_{12}^{τ}', 'F(M_{Φ4})', 'crank-a')
>>> newton("ru"), newton_metre("en"), number_text(1234.5678, "ru")
('Н', 'N·m', '1235')
>>> LINE_OVERRUN_MM, SHORT_VECTOR_MM   # lines run past their points; shorter: listed as ≈ 0
(8.0, 3.0)
>>> (start, end, text), = place_arrows([((0.0, 0.0), (1.0, 0.0), "F")], 16.0)
>>> end.tolist(), text.text
([16.0, 0.0], 'F')
>>> group_view(fa, "9-9", 2, mu_l=0.004)
Traceback (most recent call last):
...
velplan.errors.VelplanError: slider-press has no group '9-9'; its groups: 2-3, crank
"""

from velplan.views.forces.arrows import place_arrows
from velplan.views.forces.common import (
    ForceSizes, force_text, group_layers, lever_layers, newton, newton_metre, number_text,
    polygon_layers, slug)
from velplan.views.forces.diagram import MomentCurve, moment_diagram_view
from velplan.views.forces.equations import ReactionEquation, reaction_equations
from velplan.views.forces.group import (
    group_extent_m, group_forces, group_links, group_view)
from velplan.views.forces.lever import lever_balance, lever_extent, lever_view
from velplan.views.forces.polygon import (
    LINE_OVERRUN_MM, SHORT_VECTOR_MM, polygon_extent, polygon_view)
from velplan.views.forces.table import moment_decimals, moments_table_view

__all__ = ["ForceSizes", "MomentCurve", "group_forces", "group_view",
           "polygon_view", "lever_view", "lever_balance", "moments_table_view",
           "moment_diagram_view", "group_layers", "polygon_layers", "lever_layers",
           "force_text", "slug", "group_extent_m", "polygon_extent", "lever_extent",
           "group_links", "moment_decimals", "newton", "newton_metre",
           "number_text", "place_arrows", "LINE_OVERRUN_MM", "SHORT_VECTOR_MM",
           "ReactionEquation", "reaction_equations"]
