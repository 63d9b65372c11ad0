"""The block of input data and main results a course sheet carries: the lengths, the crank's
speed, masses and loads as given, and the output's stroke H, the angle θ, the time-ratio K and
both extreme positions. Layer ``"data"``.
"""

from __future__ import annotations

import math

from velplan.options import Language
from velplan.render.i18n import label
from velplan.render.scene import Primitive, Text
from velplan.notation import force_text
from velplan.views.base import ROUND_OFF, View, digits_down, make_view, number, subscript, unit


def _l(a: str, b: str) -> str:
    """The length symbol of a link between two points, its points below the line (``l_{O2A}``:
    an "l" followed by full-size capitals reads as "I")."""
    return f"l_{{{a}{b}}}"


def data_lines(study, lang: Language) -> list[str]:
    """The lines of the block (without its title), in the sheet's language."""
    mech = study.mechanism
    m = unit("m", lang)
    c = mech.crank
    lengths = [f"{_l(c.pivot, c.tip)} = {number(c.length, lang)} {m}"]
    offsets = []
    for g in mech.groups:
        lengths += [f"{_l(p, q)} = {number(x, lang)} {m}" for (p, q), x in g.sizes()]
        offsets += [f"e{digits_down(k)} = {number(e, lang)} {m}" for k, e in g.offsets()]
    ground = ", ".join(f"{subscript(n)} ({number(x, lang)}; {number(y, lang)})" for n, (x, y) in mech.ground)
    w1 = c.omega
    crank = f"ω{digits_down(c.link)} = {number(w1, lang)} {unit('rad/s', lang)} (n = {number(w1 * 30 / math.pi, lang)} "
    crank += ("об/мин" if lang == "ru" else "об/хв" if lang == "uk" else "rpm") + ")"
    origins = study.kinematics.link_origins
    for p in mech.points:
        if not p.name.startswith("S") and p.along and not p.offset and p.link in origins:
            lengths.append(f"{_l(origins[p.link], p.name)} = {number(abs(p.along), lang)} {m}")
    lines = ["; ".join(lengths[k:k + 4]) for k in range(0, len(lengths), 4)]
    if offsets:
        lines.append("; ".join(offsets))
    lines += [f"{ground}, {m}", crank]
    masses = [f"m{digits_down(ms.link)} = {number(ms.mass, lang)} {unit('kg', lang)}"
              + (f", J_{{S{ms.link}}} = {number(ms.inertia, lang)} {unit('kg·m²', lang)}"
                 if ms.inertia else "") for ms in mech.masses]
    lines += ["; ".join(masses[k:k + 3]) for k in range(0, len(masses), 3)]
    loads = []
    for ld in mech.loads:  # as the file gives them (parsing them would place them on the stroke)
        value = ld.get("force", ld.get("p_max"))
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value:
            loads.append(f"{force_text(ld.get('name', ''))} = {number(float(value), lang)} {unit('N', lang)}")
    if loads:
        lines.append("; ".join(loads))
    st = study.stroke
    if st is not None:
        sym = "H" if st.quantity.startswith("slide") or st.quantity.startswith("point") else "ψ_{max}"
        value = number(st.H, lang) + " " + (m if sym == "H" else unit("rad", lang))
        lines.append(f"{sym} = {value}; θ = {number(math.degrees(st.theta), lang, scale=180.0)}°; "
                     f"K = {number(st.K, lang)}")
        lines.append(f"{label('extreme_positions', lang)}: φ = {number(_turn_degrees(st.start.phi), lang)}°, "
                     f"{number(_turn_degrees(st.end.phi), lang)}° ({label('working_stroke', lang)} "
                     f"{number(math.degrees(st.theta) + 180.0, lang)}°)")
    return lines


def _turn_degrees(phi: float) -> float:
    """The crank angle `phi` (rad) in degrees within [0, 360), one within round-off
    (`velplan.views.base.ROUND_OFF` of a turn) of 0 or 360 as 0 (not "1,018·10⁻¹³" nor "360").

    >>> _turn_degrees(1.776e-15), _turn_degrees(-1.776e-15), _turn_degrees(3.141592653589793)
    (0.0, 0.0, 180.0)
    """
    d = math.degrees(phi) % 360.0
    return 0.0 if min(d, 360.0 - d) <= ROUND_OFF * 360.0 else d


def data_view(study, *, lang: Language, size_mm: float = 2.5, title_mm: float = 3.5,
              width_factor: float = 1.0) -> View:
    """The block: its title, then one text line per `data_lines` entry, its letters narrowed
    to `width_factor`."""
    lines = data_lines(study, lang)
    items: list[Primitive] = [Text((0.0, 0.0), label("input_data", lang), "data", title_mm)]
    y = -0.8 * title_mm
    for line in lines:
        y -= 1.6 * size_mm
        items.append(Text((0.0, y), line, "data", size_mm, "start", "baseline", 0.0, width_factor))
    return make_view("data", items, pad_mm=1.0, meta={"lines": tuple(lines), "size_mm": size_mm,
                                                     "width_factor": width_factor})


__all__ = ["data_lines", "data_view"]
