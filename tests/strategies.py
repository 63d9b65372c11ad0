"""Hypothesis strategies for random assemblable mechanisms of every group kind.

Each strategy draws lengths in units of a random scale (so 1e-6 m … 1e3 m mechanisms come out
of the same geometry) and returns a `Mechanism` whose groups close over a whole revolution
(for the kinds that allow it), built through the public TOML-dict loader.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

from velplan.mechanism.loader import from_dict

KINDS = ("RRR", "RRP", "RPR", "PRP", "RPP", "RRP-moving")

unit = st.floats(0.0, 1.0, allow_nan=False)


def fixed_points(mech) -> dict[str, list[str]]:
    """Moving link → the named points fixed to it for good (coincident points, a different
    material point at each position, left out)."""
    from velplan.mechanism.structure import coincident_points, point_owners

    owners = point_owners(mech)
    for c in coincident_points(mech):
        owners.pop(c)
    return {link: [p for p, l in owners.items() if l == link] for link in mech.links}


def _crank(r: float, omega: float) -> dict:
    return {"link": "1", "pivot": "O", "tip": "A", "length": r, "omega": omega}


@st.composite
def mechanisms(draw, kind: str | None = None, scale=None, omega=None, probes: bool = False):
    """A random mechanism of group ``kind`` (any kind when None); ``probes``: with two more
    points on every moving link, ``Q<link>`` on its reference line and ``R<link>`` off it (never
    at one place), so that every link has a figure to compare."""
    kind = kind or draw(st.sampled_from(KINDS))
    L = draw(scale) if scale is not None else draw(st.floats(0.05, 5.0))
    w = draw(omega) if omega is not None else draw(st.floats(-50.0, 50.0).filter(lambda x: abs(x) > 0.1))
    r = L * draw(st.floats(0.2, 1.0))
    rot = draw(st.floats(-math.pi, math.pi))
    origin = [L * draw(st.floats(-2, 2)), L * draw(st.floats(-2, 2))]

    def at(dx, dy):
        c, s = math.cos(rot), math.sin(rot)
        return [origin[0] + c * dx - s * dy, origin[1] + s * dx + c * dy]

    deg = math.degrees(rot)
    data = {"ground": {"O": origin}, "crank": _crank(r, w), "point": [], "group": []}
    margin = 0.1 * r
    if kind == "RRR":
        d = r * draw(st.floats(2.0, 5.0))
        S = d + r + margin + draw(unit) * 3 * r
        D = (d - r - margin) * draw(st.floats(-1, 1))
        data["ground"]["D"] = at(d, 0.0)
        data["group"].append({"kind": "RRR", "links": ["2", "3"], "joints": ["A", "D"], "point": "C",
                              "lengths": [(S + D) / 2, (S - D) / 2], "branch": draw(st.sampled_from([1, -1]))})
        data["point"].append({"name": "E", "link": "2", "along": r * draw(st.floats(-1, 2)), "offset": r * draw(st.floats(-1, 1))})
    elif kind in ("RRP", "RRP-moving"):
        e = r * draw(st.floats(-1.5, 1.5))
        rod = abs(e) + r + margin + draw(unit) * 3 * r
        guide = {"link": "0", "through": "O", "angle_deg": deg + draw(st.floats(-90, 90)), "offset": e}
        if kind == "RRP-moving":
            # crank + RPR guide bar + a slider running on the bar (Coriolis on a moving guide)
            d = r * draw(st.floats(1.5, 3.0))
            data["ground"]["Q"] = at(0.0, -d)
            data["group"].append({"kind": "RPR", "links": ["2", "3"], "joint": "A", "pivot": "Q", "coincident": "A3"})
            data["point"].append({"name": "T", "link": "3", "along": 0.0})
            alpha = draw(st.floats(20, 70))
            guide = {"link": "3", "through": "T", "angle_deg": alpha, "offset": 0.0}
            # A is on the bar, at most d + r from T: the rod reaches the slider's line if it is
            # longer than (d + r)·sin α
            rod = (d + r) * math.sin(math.radians(alpha)) + r * draw(st.floats(0.2, 2.0))
            data["group"].append({"kind": "RRP", "links": ["4", "5"], "joint": "A", "point": "C",
                                  "length": rod, "guide": guide, "coincident": "C3",
                                  "branch": draw(st.sampled_from([1, -1]))})
        else:
            data["group"].append({"kind": "RRP", "links": ["2", "3"], "joint": "A", "point": "C", "length": rod,
                                  "guide": guide, "branch": draw(st.sampled_from([1, -1]))})
            data["point"].append({"name": "E", "link": "2", "along": rod * draw(st.floats(0, 1)), "offset": r * draw(st.floats(-1, 1))})
    elif kind == "RPR":
        d = r * draw(st.floats(1.3, 4.0))
        e = (d - r) * draw(st.floats(-0.8, 0.8))
        data["ground"]["Q"] = at(0.0, d)
        data["group"].append({"kind": "RPR", "links": ["2", "3"], "joint": "A", "pivot": "Q", "offset": e,
                              "coincident": "A3"})
        data["point"].append({"name": "E", "link": "3", "along": r * draw(st.floats(-3, 3)), "offset": r * draw(st.floats(-1, 1))})
    elif kind == "PRP":
        # crank-slider first, then two sliders: one on the slider of the first group, one on the frame
        rod = r * draw(st.floats(2.0, 4.0))
        data["group"].append({"kind": "RRP", "links": ["2", "3"], "joint": "A", "point": "B", "length": rod,
                              "guide": {"link": "0", "through": "O", "angle_deg": deg, "offset": 0.0}})
        a1 = draw(st.floats(30, 150))
        data["group"].append({"kind": "PRP", "links": ["4", "5"], "point": "C", "coincident": ["C3", "C0"],
                              "guides": [{"link": "3", "through": "B", "angle_deg": a1, "offset": r * draw(st.floats(-1, 1))},
                                         {"link": "0", "through": "O", "angle_deg": deg + draw(st.floats(-20, 20)), "offset": r}]})
    elif kind == "RPP":
        data["group"].append({"kind": "RPP", "links": ["2", "3"], "joint": "A", "coincident": "A3",
                              "slot_angle_deg": draw(st.floats(30, 150)),
                              "guide": {"link": "0", "through": "O", "angle_deg": deg + draw(st.floats(-90, 90)),
                                        "offset": r * draw(st.floats(-2, 2))}})
    else:
        raise ValueError(kind)
    if probes:
        links = ["1"] + [k for g in data["group"] for k in g["links"]]
        for k in links:
            data["point"] += [{"name": f"Q{k}", "link": k, "along": r * draw(st.floats(0.5, 2.0))},
                              {"name": f"R{k}", "link": k, "along": r * draw(st.floats(-1.0, 1.0)),
                               "offset": r * draw(st.floats(0.5, 1.0))}]
    return from_dict(data, name=f"random-{kind}")
