"""A group kind is a class that knows its structure: every layer asks the kind's facts, and keeps
one lookup keyed by kind that refuses, naming it, a kind it does not hold.

* A fake kind (a frozen dataclass registered nowhere) is refused by every layer's lookup, and
  `unhandled` lists the modules that do not handle it (what a contributor adding a kind must
  still write); for every real kind that list is empty.
* The facts each real kind states equal what the switches over the kinds computed before the
  facts moved onto the kinds (`_old_*` below, kept as the reference), for every bundled and
  catalogue mechanism.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field, replace

import numpy as np
import pytest

import velplan
from velplan.analysis import compiled, solvers
from velplan.analysis.design import design_keys
from velplan.errors import MechanismError
import velplan.forces as vf
from velplan.mechanism import drawn_write, loader
from velplan.mechanism.loader import catalogue_names, example_names
from velplan.mechanism.model import FACTS, KINDS, PRP, RPP, RPR, RRP, RRR, AssurGroup, Dyad, Triad
from velplan.mechanism.structure import (coincident_points, facts, guides_of, joints_in, pairs, point_owners,
                                         points_out, revolute_joints, structure)
from velplan.plans import build
from velplan.views import mechanism as vm

NAMES = example_names() + catalogue_names()
fk = importlib.import_module("velplan.forces.kinetostatics")  # the package's name is its function

#: Each layer's lookup by kind: (module, its registry, its kinds may be absent when `tracked`).
REGISTRIES = (
    ("velplan.analysis.solvers", lambda: solvers.SOLVERS, False),
    ("velplan.analysis.compiled", lambda: compiled._ROWS, True),  # a tracked kind runs on numpy
    ("velplan.plans.build", lambda: build.BUILDERS, False),
    ("velplan.forces.kinetostatics", lambda: fk.POLYGONS, False),
    ("velplan.views.mechanism", lambda: vm.DRAWINGS, False),
    ("velplan.mechanism.drawn_write", lambda: drawn_write.SLIDES, False),
)


def unhandled(kind: type) -> list[str]:
    """The modules whose lookup by kind does not hold ``kind``."""
    return [module for module, registry, may_skip in REGISTRIES
            if kind not in registry() and not (may_skip and getattr(kind, "tracked", False))]


@dataclass(frozen=True)
class Fake(Dyad):
    """A dyad kind no layer knows: the four-bar's rods under another name."""

    name: str
    links: tuple[str, str]
    joints: tuple[str, str]
    point: str
    lengths: tuple[float, float]
    branch: int = 1
    kind: str = field(default="FAKE", init=False)


for _fact in FACTS:
    setattr(Fake, _fact, getattr(RRR, _fact))


@dataclass(frozen=True)
class Mute(AssurGroup):
    """A group kind that states none of its structure."""

    name: str
    links: tuple[str, str]
    kind: str = field(default="MUTE", init=False)


@dataclass(frozen=True)
class Bare:
    """A group value that is no `AssurGroup` at all: it states no structure."""

    name: str
    links: tuple[str, str]
    kind: str = field(default="BARE", init=False)


def _fake_four_bar():
    mech = velplan.load("four-bar")
    (g,) = mech.groups
    return mech, replace(mech, groups=(Fake(g.name, g.links, g.joints, g.point, g.lengths, g.branch),))


def test_every_real_kind_is_in_every_lookup():
    assert {module: [k.__name__ for k in KINDS if module in unhandled(k)] for module, _, _ in REGISTRIES} == {
        module: [] for module, _, _ in REGISTRIES}
    assert set(loader._PARSERS) | {"TRIAD"} == set(loader._GROUP_KEYS)


def test_a_fake_kind_is_refused_by_every_layer_naming_it():
    """Each layer, run on a mechanism with the fake kind, raises one line naming the kind and
    its lookup; the modules that refused are exactly the ones `unhandled` lists."""
    mech, fake = _fake_four_bar()
    assert unhandled(Fake) == [module for module, _, _ in REGISTRIES]
    kin = velplan.solve(mech, np.radians([10.0, 50.0]))
    acts = vf.mechanism_actions(mech, kin)
    runs = {
        "velplan.analysis.solvers": lambda: velplan.solve(fake, np.radians([10.0]), engine="numpy"),
        "velplan.analysis.compiled": lambda: compiled._program(fake, *_registers(mech), 1.0, None),
        "velplan.plans.build": lambda: build.construct(fake),
        "velplan.forces.kinetostatics": lambda: fk.kinetostatics(fake, kin, acts),
        "velplan.views.mechanism": lambda: vm._Geometry(fake, kin).segments(0),
        "velplan.mechanism.drawn_write": lambda: drawn_write._slides_of(fake.groups[0], {}, {}, {}, [], set()),
    }
    refused = []
    for module, run in runs.items():
        with pytest.raises(MechanismError) as err:
            run()
        text = str(err.value)
        assert "Fake" in text and module in text and "\n" not in text, text
        refused.append(module)
    assert refused == unhandled(Fake), f"modules that do not handle Fake: {unhandled(Fake)}"
    assert structure(fake).groups == ((fake.groups[0].name, "FAKE", 2, 2, fake.groups[0].links),)  # the model knows it


def _registers(mech):
    """The register names the compiled program of ``mech`` is laid out over."""
    kin = velplan.solve(mech, np.zeros(1))
    return list(kin.point_index), list(kin.link_index), list(kin.slide_index), list(kin.group_index)


def test_a_value_that_is_no_group_kind_is_refused_by_the_structure():
    mech = velplan.load("four-bar")
    bare = replace(mech, groups=(Bare("x", ("2", "3")),))
    for run in (lambda: pairs(bare), lambda: point_owners(bare), lambda: facts(bare.groups[0])):
        with pytest.raises(MechanismError, match="kind Bare is not an Assur group kind"):
            run()
    with pytest.raises(MechanismError, match="kind Mute does not state its joints_in, guide_lines, .*named_points$"):
        pairs(replace(mech, groups=(Mute("x", ("2", "3")),)))


# ---- the reference: what the switches over the kinds computed --------------------------------


def _old_joints_in(group):
    if isinstance(group, Triad):
        return tuple(lead.guide.through if lead.slider else lead.joint for lead in group.leads)
    if isinstance(group, RRR):
        return group.joints
    if isinstance(group, RRP):
        return (group.joint, group.guide.through)
    if isinstance(group, RPR):
        return (group.joint, group.pivot)
    if isinstance(group, PRP):
        return (group.guides[0].through, group.guides[1].through)
    return (group.joint, group.guide.through)


def _old_guides_of(group):
    if isinstance(group, Triad):
        return tuple(lead.guide for lead in group.leads if lead.slider)
    if isinstance(group, (RRP, RPP)):
        return (group.guide,)
    if isinstance(group, PRP):
        return group.guides
    return ()


def _old_points_out(group):
    if isinstance(group, Triad):
        out = {j: group.base for j in group.joints}
        out[group.special_name] = group.base
        out.update({lead.coincident: lead.guide.link for lead in group.leads if lead.slider and lead.coincident})
        return out
    a, b = group.links
    out = {}
    if isinstance(group, (RRR, RRP)):
        out[group.point] = a
    if isinstance(group, PRP):
        out[group.point] = a
        for guide, name in zip(group.guides, group.coincident):
            if name:
                out[name] = guide.link
    elif isinstance(group, RRP) and group.coincident:
        out[group.coincident] = group.guide.link
    elif isinstance(group, RPR) and group.coincident:
        out[group.coincident] = b
    elif isinstance(group, RPP):
        if group.coincident:
            out[group.coincident] = b
        out[group.origin_name] = b
    return out


def _old_revolute_joints(group):
    if isinstance(group, Triad):
        out = {j: (group.base, lead.link) for j, lead in zip(group.joints, group.leads)}
        out.update({lead.joint: (lead.link,) for lead in group.leads if not lead.slider})
        return out
    a, b = group.links
    if isinstance(group, RRR):
        return {group.joints[0]: (a,), group.point: (a, b), group.joints[1]: (b,)}
    if isinstance(group, RRP):
        return {group.joint: (a,), group.point: (a, b)}
    if isinstance(group, RPR):
        return {group.joint: (a,), group.pivot: (b,)}
    if isinstance(group, PRP):
        return {group.point: (a, b)}
    return {group.joint: (a,)}


def _old_pairs(g, owner):
    """The pairs of one group as (name, kind, links, point), before compound-hinge renaming."""
    if isinstance(g, Triad):
        out = []
        for j, lead in zip(g.joints, g.leads):
            if lead.slider:
                out.append((f"P:{lead.link}/{lead.guide.link}", "P", (lead.link, lead.guide.link), j))
            else:
                out.append((lead.joint, "R", (lead.link, owner[lead.joint]), lead.joint))
            out.append((j, "R", (lead.link, g.base), j))
        return out
    a, b = g.links
    if isinstance(g, RRR):
        A, D = g.joints
        return [(A, "R", (a, owner[A]), A), (g.point, "R", (a, b), g.point), (D, "R", (b, owner[D]), D)]
    if isinstance(g, RRP):
        return [(g.joint, "R", (a, owner[g.joint]), g.joint), (g.point, "R", (a, b), g.point),
                (f"P:{b}/{g.guide.link}", "P", (b, g.guide.link), g.point)]
    if isinstance(g, RPR):
        return [(g.joint, "R", (a, owner[g.joint]), g.joint), (f"P:{a}/{b}", "P", (a, b), g.joint),
                (g.pivot, "R", (b, owner[g.pivot]), g.pivot)]
    if isinstance(g, PRP):
        g1, g2 = g.guides
        return [(f"P:{a}/{g1.link}", "P", (a, g1.link), g.point), (g.point, "R", (a, b), g.point),
                (f"P:{b}/{g2.link}", "P", (b, g2.link), g.point)]
    return [(g.joint, "R", (a, owner[g.joint]), g.joint), (f"P:{a}/{b}", "P", (a, b), g.joint),
            (f"P:{b}/{g.guide.link}", "P", (b, g.guide.link), g.joint)]


def _old_coincident(g):
    if isinstance(g, Triad):
        names = (g.special_name,) + tuple(lead.coincident for lead in g.leads)
    else:
        names = g.coincident if isinstance(g, PRP) else (getattr(g, "coincident", None),)
    return tuple(n for n in names if n)


def _old_rotation_edges(g):
    if isinstance(g, Triad):
        return [(lead.link, lead.guide.link) for lead in g.leads if lead.slider]
    a, b = g.links
    if isinstance(g, RRP):
        return [(b, g.guide.link)]
    if isinstance(g, RPR):
        return [(a, b)]
    if isinstance(g, PRP):
        return [(a, g.guides[0].link), (b, g.guides[1].link)]
    if isinstance(g, RPP):
        return [(a, b), (b, g.guide.link)]
    return []


def _old_output_slide(g, point):
    if isinstance(g, Triad):
        for j, lead in zip(g.joints, g.leads):
            if lead.slider and point in (j, lead.coincident):
                return lead.link, f"P:{lead.link}/{lead.guide.link}"
        return None
    a, b = g.links
    if isinstance(g, RRP) and g.point == point:
        return b, f"P:{b}/{g.guide.link}"
    if isinstance(g, PRP) and g.point == point:
        return a, f"P:{a}/{g.guides[0].link}"
    if isinstance(g, RPP) and point in (g.coincident, g.origin_name):
        return b, f"P:{b}/{g.guide.link}"
    return None


def _old_main_points(g):
    out = {}
    if isinstance(g, RRR):
        out[g.links[0]] = (g.joints[0], g.point)
        out[g.links[1]] = (g.joints[1], g.point)
    elif isinstance(g, RRP):
        out[g.links[0]] = (g.joint, g.point)
    elif isinstance(g, RPR):
        out[g.links[1]] = (g.pivot, g.coincident or g.joint)
    elif isinstance(g, Triad):
        out[g.base] = (g.joints[0], g.joints[1])
        out.update({ld.link: (ld.joint, j) for ld, j in zip(g.leads, g.joints) if not ld.slider})
    return out


def _old_sizes(g):
    """(lengths as ((from, to), l), offsets as (link, e)) of the sheet's data block."""
    lengths, offsets = [], []
    if isinstance(g, RRR):
        lengths += [((g.joints[0], g.point), g.lengths[0]), ((g.joints[1], g.point), g.lengths[1])]
    elif isinstance(g, RRP):
        lengths.append(((g.joint, g.point), g.length))
    if isinstance(g, (RRP, RPP)) and g.guide.offset:
        offsets.append((g.links[1], g.guide.offset))
    if isinstance(g, RPR) and g.offset:
        offsets.append((g.links[1], g.offset))
    if isinstance(g, PRP):
        offsets += [(k, gd.offset) for k, gd in zip(g.links, g.guides) if gd.offset]
    if isinstance(g, Triad):
        b, c, d = g.joints
        lengths += list(zip(((b, c), (c, d), (d, b)), g.sides))
        lengths += [((ld.joint, j), ld.length) for ld, j in zip(g.leads, g.joints) if not ld.slider]
        offsets += [(ld.link, ld.guide.offset) for ld in g.leads if ld.slider and ld.guide.offset]
    return lengths, offsets


def _old_link_length(g, link):
    if isinstance(g, Triad):
        if link == g.base:
            return max(g.sides)
        return {lead.link: lead.length for lead in g.leads if not lead.slider}.get(link)
    if isinstance(g, RRR) and link in g.links:
        return g.lengths[g.links.index(link)]
    if isinstance(g, RRP) and link == g.links[0]:
        return g.length
    return None


def _old_misc(g):
    """(group point, given lengths, inner joints, special points, construction points, output
    joint of each link, class and order)."""
    point = g.coincident or g.joint if isinstance(g, (RPR, RPP)) else g.joints[0] if isinstance(g, Triad) else g.point
    given = (g.sides + tuple(lead.length for lead in g.leads) if isinstance(g, Triad)
             else tuple(getattr(g, "lengths", ())) + (getattr(g, "length", 0.0),))
    inner = (g.point,) if isinstance(g, (RRR, RRP, PRP)) else tuple(g.joints) if isinstance(g, Triad) else ()
    special = (g.special_name,) if isinstance(g, Triad) else ()
    construction = (g.origin_name,) if isinstance(g, RPP) else special
    joints = {k: (g.point if isinstance(g, (RRR, RRP)) else g.joints[max(g.links.index(k) - 1, 0)]
                  if isinstance(g, Triad) else None) for k in g.links}
    return point, given, inner, special, construction, joints, (3, 3) if isinstance(g, Triad) else (2, 2)


def _old_design_keys(g):
    out = {}
    if isinstance(g, RRR):
        out.update({f"lengths.{j}": float(v) for j, v in enumerate(g.lengths)})
    elif isinstance(g, RRP):
        out["length"] = float(g.length)
    elif isinstance(g, RPR):
        out["offset"] = float(g.offset)
    guides = {"guide": g.guide} if isinstance(g, (RRP, RPP)) else {}
    if isinstance(g, PRP):
        guides = {f"guides.{k}": gd for k, gd in enumerate(g.guides)}
    for where, gd in guides.items():
        out[f"{where}.offset"] = float(gd.offset)
        out[f"{where}.angle_deg"] = math.degrees(gd.angle)
    if isinstance(g, RPP):
        out["slot_angle_deg"] = math.degrees(g.slot_angle)
    return out


def _old_named(g):
    named = [("point", getattr(g, "point", None))]
    co = getattr(g, "coincident", None)
    named += [("coincident", c) for c in (co if isinstance(co, tuple) else (co,))]
    named += [("origin", getattr(g, "origin_name", None) if isinstance(g, RPP) else None)]
    if isinstance(g, Triad):
        named = [("joint", j) for j in g.joints] + [("special point", g.special_name)]
        named += [("coincident", lead.coincident) for lead in g.leads]
    return [(k, n) for k, n in named if n]


def test_the_mechanisms_cover_every_kind():
    kinds = {type(g) for name in NAMES for g in velplan.load(name).groups}
    assert kinds == set(KINDS)


@pytest.mark.parametrize("name", NAMES)
def test_the_facts_of_each_kind_equal_the_old_switches(name):
    mech = velplan.load(name)
    owner = point_owners(mech)
    for g in mech.groups:
        assert joints_in(g) == _old_joints_in(g)
        assert guides_of(g) == _old_guides_of(g)
        assert points_out(g) == _old_points_out(g)
        assert revolute_joints(g) == _old_revolute_joints(g)
        assert [(p.name, p.kind, p.links, p.point) for p in g.pairs(owner)] == _old_pairs(g, owner)
        assert all(p.group == g.name for p in g.pairs(owner))
        assert g.coincident_names() == _old_coincident(g)
        assert [(s, gl) for s, gl, _ in g.slides()] == _old_rotation_edges(g)
        assert g.link_lines() == _old_main_points(g)
        assert (list(g.sizes()), list(g.offsets())) == _old_sizes(g)
        for link in g.links:
            assert g.link_lengths().get(link) == _old_link_length(g, link)
        for point in points_out(g) | dict.fromkeys(joints_in(g)):
            assert g.output_slides().get(point) == _old_output_slide(g, point), point
        joints = {k: g.output_joint(k) for k in g.links}
        assert (g.solved_point(), g.given_lengths(), g.inner_joints(), g.special_points(), g.construction_points(),
                joints, g.group_class) == _old_misc(g)
        assert [(k, n) for k, n in g.named_points() if n] == _old_named(g)
    assert coincident_points(mech) == {n: owner[n] for g in mech.groups for n in _old_coincident(g)}
    keys = design_keys(mech)
    for g in mech.groups:
        assert {k: v for k, v in keys.items() if k.startswith(f"group.{g.name}.")} == {
            f"group.{g.name}.{k}": v for k, v in _old_design_keys(g).items()}
