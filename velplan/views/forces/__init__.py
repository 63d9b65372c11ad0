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
  found vectors thick. Vertices are `ForcePolygon.vertices`.
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
"""

from velplan.views.forces.arrows import place_arrows
from velplan.views.forces.common import (
    ForceSizes, force_text, group_layers, lever_layers, newton, newton_metre, number_text,
    polygon_layers, slug)
from velplan.views.forces.diagram import MomentCurve, moment_diagram_view
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
           "number_text", "place_arrows", "LINE_OVERRUN_MM", "SHORT_VECTOR_MM"]
