"""Kinematic diagrams on paper: displacement, velocity and acceleration of the output
against crank angle, the chord-method construction beside the analytic curves (seed 003).

Each diagram has its φ axis (positions 1…n marked), its ordinate axis, the pole P at the
pole distance H to the left of the origin with the rays parallel to the chords of the
diagram above it, the graphical curve (thick, through the chord-method points, shifted by
half a step), the analytic curve (thin dashed), the scales and the error of the graphical
curve written beside it. Layer ``"diagram"`` (curves and axes), ``"diagram-lines"``
(construction rays) and ``"diagram-labels"`` (text).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from velplan.analysis.numbering import position_number
from velplan.analysis.chord import Diagrams
from velplan.errors import ScaleError
from velplan.options import Language
from velplan.plans.scale import standard_scale
from velplan.render.i18n import label
from velplan.render.shapes import text_extent
from velplan.render.scene import Arrow, Circle, Polyline, Primitive, Text
from velplan.views.base import View, axis_numbers_clear, make_view, number, scale_text, unit

Arrangement = Literal["row", "column", "grid"]

#: Pole distances a draughtsman picks from, mm.
POLE_DISTANCES_MM: tuple[float, ...] = (10.0, 12.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 80.0)


def standard_up(raw: float) -> float:
    """The smallest value of the series (1, 2, 2.5, 4, 5)·10ⁿ not below `raw`."""
    try:
        return standard_scale(raw)
    except ScaleError:
        raise ScaleError(f"cannot choose a diagram scale for a value per mm of {raw!r}") from None


@dataclass(frozen=True)
class DiagramScales:
    """Drawing scales of the three diagrams (units per mm) and the pole distances (mm).

    ``mu_v = mu_s / (mu_phi · H_v)`` and ``mu_a = mu_v / (mu_phi · H_a)``.
    """

    length_mm: float
    mu_phi: float
    mu_s: float
    H_v: float
    mu_v: float
    H_a: float
    mu_a: float


def choose_scales(d: Diagrams, *, length_mm: float, height_mm: float) -> DiagramScales:
    """Scales for diagrams `length_mm` long (one crank turn) with ordinates ≤ `height_mm`.

    μφ = 2π / L; μs from the standard series; each pole distance H is the largest of
    :data:`POLE_DISTANCES_MM` that keeps the derived diagram within `height_mm` (the
    smallest one if none does).
    """
    if not (length_mm > 0 and height_mm > 0):
        raise ScaleError(f"diagram axes must be positive, got {length_mm} × {height_mm} mm")
    mu_phi = 2 * math.pi / length_mm
    peak_s = max(float(np.max(np.abs(d.s_exact))), 1e-12)
    mu_s = standard_up(peak_s / height_mm)
    most = 0.4 * length_mm  # a pole farther out than the diagram is long wastes the sheet
    H_v = _pole(mu_s, mu_phi, float(np.max(np.abs(np.r_[d.v_chord, d.v_exact]))), height_mm,
                most)
    mu_v = mu_s / (mu_phi * H_v)
    H_a = _pole(mu_v, mu_phi, float(np.max(np.abs(np.r_[d.a_chord, d.a_exact]))), height_mm,
                most)
    mu_a = mu_v / (mu_phi * H_a)
    return DiagramScales(length_mm, mu_phi, mu_s, H_v, mu_v, H_a, mu_a)


def _pole(mu_y: float, mu_phi: float, peak: float, height: float, limit: float) -> float:
    allowed = [h for h in POLE_DISTANCES_MM if h <= limit + 1e-9] or [POLE_DISTANCES_MM[0]]
    if peak <= 0:
        return allowed[-1]
    # ordinate = peak / (mu_y / (mu_phi·H)) = peak·mu_phi·H/mu_y ≤ height
    most = height * mu_y / (mu_phi * peak)
    fitting = [h for h in allowed if h <= most + 1e-9]
    return fitting[-1] if fitting else allowed[0]


@dataclass(frozen=True)
class DiagramSizes:
    """Text heights, mm."""

    title_mm: float = 3.5
    label_mm: float = 2.5


def _names(d: Diagrams, lang: Language, timed: bool) -> tuple[str, str, str, str, str, str]:
    """Ordinate symbols of s, v, a and their units: velocities and accelerations in time at a
    constant crank speed (``timed``), else the analogues."""
    if d.angular:
        if timed:
            return "ψ", "ω", "ε", unit("rad", lang), unit("rad/s", lang), unit("rad/s²", lang)
        return "ψ", "dψ/dφ", "d²ψ/dφ²", unit("rad", lang), "", ""
    if timed:
        return "S", "V", "a", unit("m", lang), unit("m/s", lang), unit("m/s²", lang)
    return "S", "dS/dφ", "d²S/dφ²", unit("m", lang), unit("m", lang), unit("m", lang)


@dataclass(frozen=True)
class _Curve:
    """One diagram's data: its scale (units per mm), ordinate symbol and unit, pole distance
    (mm, None for S), the graphical points (closed over the turn) and the points marked, the
    analytic curve, the error of the graphical curve and the title."""

    mu: float
    symbol: str
    unit: str
    H: float | None
    graphical: tuple[np.ndarray, np.ndarray]
    marks: tuple[np.ndarray, np.ndarray]
    analytic: tuple[np.ndarray, np.ndarray]
    error: float | None
    title: str


def _curve(kind: str, d: Diagrams, sc: DiagramScales, lang: Language, timed: bool) -> _Curve:
    """The data of diagram `kind` ("s", "v" or "a")."""
    sym_s, sym_v, sym_a, u, u_v, u_a = _names(d, lang, timed)
    exact = {"s": d.s_exact, "v": d.v_exact, "a": d.a_exact}[kind]
    if kind == "s":
        return _Curve(sc.mu_s, sym_s, u, None, (np.append(d.phi, 2 * math.pi), np.append(d.s, d.s[0])),
                      (d.phi, d.s), (d.phi_fine, exact), None, label("displacement_diagram", lang))
    if kind == "v":
        # the mid-interval points, closed over the turn
        edge = 0.5 * (d.v_chord[0] + d.v_chord[-1])
        graphical = (np.concatenate([[0.0], d.phi_mid, [2 * math.pi]]),
                     np.concatenate([[edge], d.v_chord, [edge]]))
        title = "velocity_diagram" if timed else "velocity_analogue_diagram"
        return _Curve(sc.mu_v, sym_v, u_v, sc.H_v, graphical, (d.phi_mid, d.v_chord),
                      (d.phi_fine, exact), d.error_v, label(title, lang))
    title = "acceleration_diagram" if timed else "acceleration_analogue_diagram"
    return _Curve(sc.mu_a, sym_a, u_a, sc.H_a,
                  (np.append(d.phi, 2 * math.pi), np.append(d.a_chord, d.a_chord[0])),
                  (d.phi, d.a_chord), (d.phi_fine, exact), d.error_a, label(title, lang))


def phi_axes(length: float, top: float, bottom: float, n: int, ordinate: str, *, layer: str,
             text_layer: str, label_mm: float, tick_mm: float) -> list[Primitive]:
    """The axes of a diagram over a turn, mm from its origin: the φ axis `length` long with
    the n positions marked (numbered from 1, at most twelve numbers), and the ordinate axis
    from `bottom` to `top` named `ordinate`; numbers `tick_mm` high, names `label_mm`."""
    items: list[Primitive] = [
        Arrow((0.0, 0.0), (length + 8.0, 0.0), layer, "thin", 3.0, 1.0),
        Arrow((0.0, bottom - 3.0), (0.0, top + 6.0), layer, "thin", 3.0, 1.0),
        Text((length + 9.0, -1.0), "φ", text_layer, label_mm, "start", "top"),
        Text((-1.5, top + 6.0), ordinate, text_layer, label_mm, "end", "top")]
    every = max(1, int(math.ceil(n / 12)))
    for k in range(n + 1):
        x = k * length / n
        items.append(Polyline([(x, -1.0), (x, 1.0)], layer, "thin"))
        if k % every == 0:
            items.append(Text((x, -1.8), str(position_number(k % n)), text_layer, tick_mm, "middle", "top"))
    return items


def _plot(kind: str, d: Diagrams, sc: DiagramScales, *, lang: Language, sizes: DiagramSizes,
          text_top: float | None = None, omega: float = 0.0, wrap_mm: float | None = None,
          titled: bool = True) -> list[Primitive]:
    """One diagram with its origin at (0, 0), mm. With the crank's speed ``omega`` (rad/s,
    ≠ 0) the velocity and acceleration diagrams are read in time — V = ω·dS/dφ, a = ω²·d²S/dφ²,
    μt = μφ/ω — else as the analogues. Without ``titled``, no title, scales nor error above
    it (the compact form writes them elsewhere)."""
    c = _curve(kind, d, sc, lang, abs(omega) > 0)
    top, bottom = _span(c.analytic[1], c.graphical[1], c.mu)
    items = phi_axes(sc.length_mm, top, bottom, d.n, f"{c.symbol}, {c.unit}" if c.unit else c.symbol,
                     layer="diagram", text_layer="diagram-labels", label_mm=sizes.label_mm,
                     tick_mm=sizes.label_mm * 0.8 if sizes.label_mm > 2.5 else sizes.label_mm)
    if c.H is not None:
        items += _pole_rays(kind, d, sc, c.H, sizes.label_mm)
    # curves: analytic thin dashed, graphical thick through its points
    exact_xy = np.column_stack([c.analytic[0] / sc.mu_phi, c.analytic[1] / c.mu])
    drawn_xy = np.column_stack([c.graphical[0] / sc.mu_phi, c.graphical[1] / c.mu])
    items.append(Polyline(exact_xy, "diagram", "hidden"))
    items.append(Polyline(drawn_xy, "diagram", "thick"))
    items = axis_numbers_clear(items, [exact_xy, drawn_xy])
    for x, y in zip(*c.marks):
        items.append(Circle((float(x / sc.mu_phi), float(y / c.mu)), 0.5, "diagram", "thin",
                            "solid"))
    if not titled:
        return items
    return items + _heading(kind, d, sc, c, top, lang=lang, sizes=sizes, text_top=text_top, omega=omega,
                            wrap_mm=wrap_mm)


def _heading(kind: str, d: Diagrams, sc: DiagramScales, c: _Curve, top: float, *, lang: Language,
             sizes: DiagramSizes, text_top: float | None, omega: float, wrap_mm: float | None) -> list[Text]:
    """The title, the scales and the error written above a diagram whose curves reach `top`
    (or above `text_top`, the diagrams' common top), mm."""
    lines = _scale_lines(kind, d, sc, c, lang, abs(omega))
    if wrap_mm is not None:  # one statement a line where a line runs wider than wrap_mm
        lines = [part.strip() for line in lines
                 for part in (line.split(";  ") if text_extent(line, sizes.label_mm)[0] > wrap_mm else [line])]
    y = (top if text_top is None else text_top) + 8.0 + 1.6 * sizes.label_mm * len(lines)
    items = [Text((-(c.H or 0.0), y + 1.8 * sizes.label_mm), c.title, "diagram-labels", sizes.title_mm)]
    for k, line in enumerate(lines):
        items.append(Text((-(c.H or 0.0), y - 1.6 * sizes.label_mm * k), line, "diagram-labels",
                          sizes.label_mm))
    return items


def least_row_width(d: Diagrams, *, length_mm: float, height_mm: float, lang: Language = "ru",
                    sizes: DiagramSizes = DiagramSizes(), gap_mm: float = 12.0, omega: float = 0.0) -> float:
    """A lower bound of the width (mm) of ``diagram_view(d, arrangement="row")`` with these
    arguments (no ``wrap_mm``), found without drawing the curves: each diagram at least as
    wide as what its drawing keeps in place (its axes and their names, its pole and rays, the
    lines above it; `axis_numbers_clear` moves only the position numbers), the three
    `gap_mm` apart, padded as the view is."""
    from velplan.views.base import bounds_of

    sc = choose_scales(d, length_mm=length_mm, height_mm=height_mm)
    common = max(_tops(d, sc))
    width = 2 * gap_mm + 2 * 2.0
    for kind in "sva":
        c = _curve(kind, d, sc, lang, abs(omega) > 0)
        top, bottom = _span(c.analytic[1], c.graphical[1], c.mu)
        axes = phi_axes(sc.length_mm, top, bottom, d.n, f"{c.symbol}, {c.unit}" if c.unit else c.symbol,
                        layer="diagram", text_layer="diagram-labels", label_mm=sizes.label_mm,
                        tick_mm=sizes.label_mm * 0.8 if sizes.label_mm > 2.5 else sizes.label_mm)
        items = [p for p in axes if not (isinstance(p, Text) and p.text.isdigit())]
        if c.H is not None:
            items += _pole_rays(kind, d, sc, c.H, sizes.label_mm)
        items += _heading(kind, d, sc, c, top, lang=lang, sizes=sizes, text_top=common, omega=omega, wrap_mm=None)
        x0, _, x1, _ = bounds_of(items)
        width += x1 - x0
    return width


def _pole_rays(kind: str, d: Diagrams, sc: DiagramScales, H: float, size: float) -> list[Primitive]:
    """The pole P at the distance H left of the origin and the rays parallel to the chords of
    the diagram above (S for V, V for a)."""
    parent = d.s if kind == "v" else d.v_chord
    parent_mu = sc.mu_s if kind == "v" else sc.mu_v
    step = d.step / sc.mu_phi  # mm between positions
    intercepts = H * (np.roll(parent, -1) - parent) / parent_mu / step
    items: list[Primitive] = [Polyline([(-H, 0.0), (0.0, 0.0)], "diagram", "thin"),
                              Circle((-H, 0.0), 0.6, "diagram", "thin", "solid"),
                              # left of the pole: its rays and the axis run to the right
                              Text((-H - 1.2, 0.0), "P", "diagram-labels", size, "end", "middle")]
    for yi in intercepts:
        if abs(yi) > 1e-6:
            items.append(Polyline([(-H, 0.0), (0.0, float(yi))], "diagram-lines", "construction"))
    return items


def _scale_lines(kind: str, d: Diagrams, sc: DiagramScales, c: _Curve, lang: Language,
                 w: float) -> list[str]:
    """The lines written above a diagram: its scales (in time at the crank speed `w` rad/s
    when ≠ 0), and the error of the chord method for V and a."""
    if kind == "s":
        return [scale_text("μ" + ("ψ" if d.angular else "s"), c.mu, "m/mm" if not d.angular else "rad/mm", lang),
                scale_text("μφ", sc.mu_phi, "rad/mm", lang) +
                f" ({number(math.degrees(sc.mu_phi), lang, 3)}°/{unit('mm', lang)})"]
    up = "μs" if kind == "v" else "μv"
    sym_mu = "μv" if kind == "v" else "μa"
    error = (f"δ = {number(100 * c.error, lang, 2)} % ({label('error', lang)}, "
             f"{label('chord_method', lang)})")
    if w > 0:
        # the same drawing read in time: μt = μφ/ω, μv = μs/(μt·H), μa = μv/(μt·H)
        value = c.mu * w if kind == "v" else c.mu * w * w
        unit_key = {("v", False): "(m/s)/mm", ("a", False): "(m/s²)/mm",
                    ("v", True): "(rad/s)/mm", ("a", True): "(rad/s²)/mm"}[kind, d.angular]
        return [f"H = {number(c.H, lang, 3)} {unit('mm', lang)};  μt = μφ/ω1 = "
                f"{number(sc.mu_phi / w, lang, 3)} {unit('s/mm', lang)};  {sym_mu} = {up}/(μt·H) = "
                f"{number(value, lang, 3)} {unit(unit_key, lang)}", error]
    unit_txt = unit("m/mm", lang) if not d.angular else unit("1/mm", lang)
    return [f"H = {number(c.H, lang, 3)} {unit('mm', lang)};  {sym_mu} = {up}/(μφ·H) = "
            f"{number(c.mu, lang, 3)} {unit_txt}", error]


def _span(fy, gy, mu) -> tuple[float, float]:
    top = max(float(np.max(fy)) / mu, float(np.max(gy)) / mu, 5.0)
    bottom = min(float(np.min(fy)) / mu, float(np.min(gy)) / mu, 0.0)
    return top, bottom


def _tops(d: Diagrams, sc: DiagramScales) -> list[float]:
    edge = 0.5 * (d.v_chord[0] + d.v_chord[-1])
    return [_span(d.s_exact, d.s, sc.mu_s)[0],
            _span(d.v_exact, np.r_[d.v_chord, edge], sc.mu_v)[0],
            _span(d.a_exact, d.a_chord, sc.mu_a)[0]]


def _legend(x: float, y: float, lang: Language, size: float) -> list[Primitive]:
    """The two line samples and their names; the second sample 45 mm along, or further where
    the first name (at `size`) runs longer."""
    from velplan.render.shapes import text_extent

    first = label("chord_method", lang)
    second = x + max(45.0, 12.0 + 1.25 * text_extent(first, size)[0] + size)
    return [Polyline([(x, y), (x + 10.0, y)], "diagram", "thick"),
            Text((x + 12.0, y), first, "diagram-labels", size, "start", "middle"),
            Polyline([(second, y), (second + 10.0, y)], "diagram", "hidden"),
            Text((second + 12.0, y), label("analytic", lang), "diagram-labels", size, "start",
                 "middle")]


def diagram_view(d: Diagrams, *, length_mm: float = 180.0, height_mm: float = 40.0,
                 lang: Language = "ru", arrangement: Arrangement = "column",
                 sizes: DiagramSizes = DiagramSizes(), gap_mm: float = 12.0,
                 omega: float = 0.0, wrap_mm: float | None = None) -> View:
    """The three diagrams of `d` as one view.

    Parameters
    ----------
    d : Diagrams
        From :func:`velplan.analysis.chord.kinematic_diagrams`.
    length_mm : float
        Length of the φ axis for one crank turn, mm (μφ = 2π / length).
    height_mm : float
        Largest ordinate of each diagram, mm (the scales are chosen to keep within it).
    arrangement : {"row", "column", "grid"}
        Diagrams side by side, one above the other (φ axes aligned), or s and v side by
        side with a under s.
    omega : float
        The crank's constant speed, rad/s: the velocity and acceleration diagrams are then
        read in time (V in m/s, a in m/s², with the time scale μt = μφ/ω); 0 draws the
        analogues dS/dφ, d²S/dφ² (m) under their own titles.
    wrap_mm : float, optional
        A line of scales wider than this, mm, is written one statement a line.
    """
    sc = choose_scales(d, length_mm=length_mm, height_mm=height_mm)
    tops = _tops(d, sc)
    common = max(tops) if arrangement != "column" else None
    plots = [_plot(k, d, sc, lang=lang, sizes=sizes, text_top=common, omega=omega, wrap_mm=wrap_mm)
             for k in "sva"]
    from velplan.views.base import bounds_of, shift

    items: list[Primitive] = []
    cursor = 0.0
    if arrangement == "grid":
        (ax0, ay0, ax1, _), (bx0, by0, _, _), (cx0, _, _, cy1) = (bounds_of(p) for p in plots)
        items += [shift(q, -ax0, 0.0) for q in plots[0]]
        items += [shift(q, ax1 - ax0 + gap_mm - bx0, 0.0) for q in plots[1]]
        below = min(ay0, by0) - gap_mm - cy1
        items += [shift(q, -cx0, below) for q in plots[2]]
        plots = []
    for p in plots:
        x0, y0, x1, y1 = bounds_of(p)
        if arrangement == "row":
            items += [shift(q, cursor - x0, 0.0) for q in p]
            cursor += (x1 - x0) + gap_mm
        else:
            # stack downwards, φ axes aligned at x = 0
            items += [shift(q, 0.0, cursor - y1) for q in p]
            cursor += -(y1 - y0) - gap_mm
    x0, y0, x1, y1 = bounds_of(items)
    items += _legend(x0, y0 - 4.0, lang, sizes.label_mm)
    return make_view("diagrams", items, pad_mm=2.0,
                     meta={"scales": sc, "error_v": d.error_v, "error_a": d.error_a,
                           "quantity": d.quantity, "omega": abs(omega),
                           "ranges": ordinate_ranges(d, sc)})


def ordinate_ranges(d: Diagrams, sc: DiagramScales) -> tuple[float, float, float]:
    """The drawn ordinate range (highest minus lowest point of the analytic and the
    graphical curve) of the s, v and a diagrams at the scales `sc`, mm."""
    out = []
    for exact, drawn, mu in ((d.s_exact, d.s, sc.mu_s), (d.v_exact, d.v_chord, sc.mu_v),
                             (d.a_exact, d.a_chord, sc.mu_a)):
        y = np.r_[exact, drawn] / mu
        out.append(float(np.max(y) - np.min(y)))
    return out[0], out[1], out[2]

