"""The drawn form: every bundled and catalogue mechanism written as joints comes back as the
same groups moving the same way; random chains of dyads and triads given only as joints
decompose into the groups that generated them; what cannot be decomposed is refused."""

from __future__ import annotations

import cmath
import math
import random

import pytest
from hypothesis import assume, example, given, settings, strategies as st

import velplan
from velplan.cli.convert import convert_text
from velplan.errors import MechanismError
from velplan.mechanism.loader import catalogue_names, example_names, from_dict

from .helpers import ANGLES, canonical, same_motion

NAMES = example_names() + catalogue_names()


@pytest.mark.parametrize("name", NAMES)
def test_a_mechanism_written_as_joints_comes_back_the_same(name):
    mech = velplan.load(name)
    drawn = velplan.parse(convert_text(mech, "drawn"), name=name)
    assert [canonical(g) for g in drawn.groups] == [canonical(g) for g in mech.groups]
    assert same_motion(mech, drawn) == len(set(velplan.solve(mech, 0.0, order=0).point_index))
    # and back to groups: the explicit file of the drawn one moves the same
    again = velplan.parse(convert_text(drawn, "explicit"), name=name)
    assert again == drawn or same_motion(drawn, again)
    assert (drawn.masses, drawn.loads, drawn.dynamics, drawn.names) == (mech.masses, mech.loads, mech.dynamics,
                                                                        mech.names)


@pytest.mark.parametrize("name", NAMES)
def test_a_mechanism_written_as_a_pmks_expression_comes_back_the_same(name, tmp_path):
    mech = velplan.load(name)
    path = tmp_path / f"{name}.pmks"
    path.write_text(convert_text(mech, "pmks"), "utf-8")
    back = velplan.mechanism.loader.load_pmks(path, pair=(0, 1), omega=mech.crank.omega)
    assert [canonical(g) for g in back.groups] == [canonical(g) for g in mech.groups]
    special = {g.special_name for g in mech.groups if g.kind == "triad"}
    assert same_motion(mech, back, skip=special) >= len(mech.ground) + 1


def test_the_drawn_pose_is_reproduced_by_the_solution():
    text = """
[crank]
link = "1"
pivot = "O"
rpm = 60
[[joint]]
name = "O"
at = [0.0, 0.0]
links = ["ground", "1"]
[[joint]]
name = "A"
at = [0.03, 0.04]
links = ["1", "2"]
[[joint]]
name = "C"
at = [0.2, 0.15]
links = ["2", "3"]
[[joint]]
name = "D"
at = [0.25, 0.0]
links = ["3", "0"]
[[joint]]
name = "F"
at = [0.5, 0.15]
links = ["3", "4"]
[[joint]]
name = "G"
at = [0.7, 0.1]
kind = "RP"
angle_deg = 180
links = ["0", "4"]
block = "5"
"""
    mech = velplan.parse(text, name="drawn")
    assert [(g.kind, g.links) for g in mech.groups] == [("RRR", ("2", "3")), ("RRP", ("4", "5"))]
    # lengths from the coordinates; the branches as drawn: C left of A → D, G behind F on the guide (180°)
    assert mech.groups[0].lengths == pytest.approx((math.hypot(0.17, 0.11), math.hypot(0.05, 0.15)), rel=1e-15)
    assert mech.groups[0].branch == 1 and mech.groups[1].branch == -1
    k = velplan.solve(mech, math.atan2(0.04, 0.03), order=0)
    drawn = {"O": (0, 0), "A": (0.03, 0.04), "C": (0.2, 0.15), "D": (0.25, 0), "F": (0.5, 0.15), "G": (0.7, 0.1)}
    for name, xy in drawn.items():
        assert tuple(k.positions[0, k.point_index[name]]) == pytest.approx(xy, abs=1e-15)


# -- random chains given as joints ----------------------------------------------------------


class _Chain:
    """A random chain of groups drawn in one pose: the joints, and the explicit tables of the
    same groups computed here from the same coordinates (lengths, branches)."""

    def __init__(self, rnd: random.Random):
        self.rnd = rnd
        self.joints: list[dict] = []
        self.points: dict[str, complex] = {}  # point → position
        self.on: dict[str, list[str]] = {}  # link → its points
        self.ground: dict[str, list[float]] = {}
        self.groups: list[dict] = []
        self.links = 1
        self.add_joint("O", 0j, ["0", "1"])
        self.phi = rnd.uniform(-math.pi, math.pi)
        self.add_joint("A", cmath.rect(rnd.uniform(0.5, 1.0), self.phi), ["1"])
        self.ground["O"] = [0.0, 0.0]

    def add_joint(self, name, at, links, **extra):
        self.joints.append({"name": name, "at": [at.real, at.imag], "links": list(links)} | extra)
        self.points[name] = at
        for k in links:
            self.on.setdefault(k, []).append(name)

    def new_link(self) -> str:
        self.links += 1
        return str(self.links)

    def known(self) -> str:
        """A known point: a new ground pivot or a point of a known moving link (a new joint on it)."""
        rnd = self.rnd
        if rnd.random() < 0.4:
            name = f"G{len(self.ground)}"
            at = complex(rnd.uniform(-3, 3), rnd.uniform(-3, 3))
            self.ground[name] = [at.real, at.imag]
            self.add_joint(name, at, ["0"])
            return name
        slides = {j["name"] for j in self.joints if j.get("kind") == "P"}  # a P joint joins two links
        return rnd.choice([p for p in self.points if p not in slides and any(p in v for k, v in self.on.items()
                                                                            if k != "0")])

    def near(self, p: str) -> complex:
        return self.points[p] + cmath.rect(self.rnd.uniform(1.0, 2.0), self.rnd.uniform(-math.pi, math.pi))

    def attach(self, point: str, link: str) -> None:
        """``link`` turns about the known ``point`` (the joint gets one more link)."""
        for j in self.joints:
            if j["name"] == point:
                j["links"].append(link)
        self.on.setdefault(link, []).append(point)

    def rrr(self):
        a, b = self.new_link(), self.new_link()
        A, D = self.known(), self.known()
        while D == A:
            D = self.known()
        C = self.near(A)
        name = f"C{a}"
        self.attach(A, a)
        self.attach(D, b)
        self.add_joint(name, C, [a, b])
        pa, pd = self.points[A], self.points[D]
        side = ((C - pa) / (pd - pa)).imag
        self.groups.append({"kind": "RRR", "links": [a, b], "joints": [A, D], "point": name,
                            "lengths": [abs(C - pa), abs(C - pd)], "branch": 1 if side > 0 else -1})

    def rrp(self):
        rod, slider = self.new_link(), self.new_link()
        A = self.known()
        C = self.near(A)
        angle = self.rnd.uniform(-180, 180)
        u = cmath.rect(1.0, math.radians(angle))
        name = f"C{rod}"
        self.attach(A, rod)
        self.add_joint(name, C, ["0", rod], kind="RP", angle_deg=angle, block=slider)
        off = (C / u).imag  # the guide through O (the frame's origin) at this offset
        pa = self.points[A]
        self.groups.append({"kind": "RRP", "links": [rod, slider], "joint": A, "point": name, "length": abs(C - pa),
                            "guide": {"link": "0", "through": "O", "angle_deg": angle, "offset": off},
                            "branch": 1 if ((C - pa) / u).real > 0 else -1})

    def rpr(self):
        block, bar = self.new_link(), self.new_link()
        A = self._pin()
        O = self.known()
        while O == A:
            O = self.known()
        pa, po = self.points[A], self.points[O]
        theta = math.atan2((pa - po).imag, (pa - po).real) + self.rnd.uniform(-0.5, 0.5)
        u = cmath.rect(1.0, theta)
        w = (pa - po) / u
        for j in self.joints:
            if j["name"] == A:  # A becomes the pin of the block in the bar's slot
                j["links"] = [bar] + j["links"]
                j |= {"kind": "RP", "angle_deg": math.degrees(theta), "block": block}
        self.attach(O, bar)
        self.on.setdefault(bar, []).append(A)
        self.groups.append({"kind": "RPR", "links": [block, bar], "joint": A, "pivot": O, "offset": w.imag,
                            "branch": 1 if w.real > 0 else -1})

    def _pin(self, avoid=()) -> str:
        """A known point that is a plain R joint (a pin can hold one block)."""
        p = self.known()
        while p in avoid or any(j["name"] == p and j.get("kind") == "RP" for j in self.joints):
            p = self.known()
        return p

    def _guide_on(self, link: str, through: complex, angle_deg: float) -> dict:
        """The explicit guide of ``link`` along ``angle_deg`` (absolute) through ``through``."""
        origin, theta = self._frames()[link] if link != "0" else (0j, 0.0)
        ref = "O" if link == "0" else next(p for p in self.on[link] if p in self.points)
        u = cmath.rect(1.0, math.radians(angle_deg))
        return {"link": link, "through": ref, "angle_deg": angle_deg - math.degrees(theta),
                "offset": ((through - self.points[ref]) / u).imag}

    def prp(self):
        a, b = self.new_link(), self.new_link()
        g2 = self.rnd.choice(["0"] + [k for k in self.on if k not in ("0",) and k in self._frames()])
        C = complex(self.rnd.uniform(-3, 3), self.rnd.uniform(-3, 3))
        a1 = self.rnd.uniform(-180, 180)
        a2 = a1 + self.rnd.choice([-1, 1]) * self.rnd.uniform(30, 150)
        name = f"C{a}"
        guides = [self._guide_on("0", C, a1), self._guide_on(g2, C, a2)]
        self.add_joint(f"P{a}", C, ["0", a], kind="P", angle_deg=a1)
        self.add_joint(name, C, [g2, a], kind="RP", angle_deg=a2, block=b)
        self.on.setdefault(b, []).append(name)
        self.groups.append({"kind": "PRP", "links": [a, b], "point": name, "guides": guides})

    def rpp(self):
        block, runner = self.new_link(), self.new_link()
        B = self._pin()
        pb = self.points[B]
        ag = self.rnd.uniform(-180, 180)
        slot = self.rnd.choice([-1, 1]) * self.rnd.uniform(30, 150)
        v = cmath.rect(1.0, math.radians(ag + slot))
        K = pb + self.rnd.uniform(-2, 2) * v  # the slot's line through B meets the guide here
        for j in self.joints:
            if j["name"] == B:
                j["links"] = [runner] + j["links"]
                j |= {"kind": "RP", "angle_deg": ag + slot, "block": block}
        self.add_joint(f"K{runner}", K, ["0", runner], kind="P", angle_deg=ag)
        self.groups.append({"kind": "RPP", "links": [block, runner], "joint": B, "origin": f"K{runner}",
                            "guide": self._guide_on("0", K, ag), "slot_angle_deg": slot})

    def triad(self):
        base = self.new_link()
        leads = [self.new_link() for _ in range(3)]
        outer = []
        while len(outer) < 3:
            p = self.known()
            if p not in outer:
                outer.append(p)
        inner, tables = [], []
        for k, (p, lead) in enumerate(zip(outer, leads)):
            J = self.near(p)
            name = f"J{base}{k}"
            self.attach(p, lead)
            self.add_joint(name, J, [base, lead])
            inner.append(name)
            tables.append({"link": lead, "joint": p, "length": abs(J - self.points[p])})
        B, C, D = (self.points[n] for n in inner)
        self.groups.append({"kind": "triad", "base": base, "joints": inner,
                            "sides": [abs(C - B), abs(D - C), abs(B - D)],
                            "side": 1 if ((D - B) / (C - B)).imag > 0 else -1, "leads": tables,
                            "assembly": {"phi_deg": math.degrees(self.phi)} |
                                        {n: [self.points[n].real, self.points[n].imag] for n in inner}})

    def explicit(self) -> dict:
        A = self.points["A"]
        crank = {"link": "1", "pivot": "O", "tip": "A", "length": abs(A), "omega": 3.0}
        data = {"ground": self.ground, "crank": crank, "group": self.groups, "point": self._link_points()}
        return data

    def _link_points(self) -> list[dict]:
        """Points that groups join at but no group places (a second point on a known link)."""
        placed = {"O", "A"} | set(self.ground)
        for g in self.groups:
            placed |= {g.get("point"), g.get("origin")} | (set(g["joints"]) if g["kind"] == "triad" else set())
        out = []
        frames = self._frames()
        for j in self.joints:
            if j["name"] in placed or j["name"] in self.ground:
                continue
            link = j["links"][1] if j.get("kind") in ("RP", "P") else j["links"][0]
            origin, angle = frames[link]
            local = (self.points[j["name"]] - origin) * cmath.rect(1.0, -angle)
            out.append({"name": j["name"], "link": link, "along": local.real, "offset": local.imag})
        return out

    def _frames(self) -> dict:
        P = self.points
        frames = {"1": (0j, cmath.phase(P["A"]))}
        for g in self.groups:
            if g["kind"] == "RRR":
                (a, b), (A, D) = g["links"], g["joints"]
                frames[a] = (P[A], cmath.phase(P[g["point"]] - P[A]))
                frames[b] = (P[D], cmath.phase(P[g["point"]] - P[D]))
            elif g["kind"] == "RRP":
                rod, slider = g["links"]
                frames[rod] = (P[g["joint"]], cmath.phase(P[g["point"]] - P[g["joint"]]))
                frames[slider] = (P[g["point"]], math.radians(g["guide"]["angle_deg"]))
            elif g["kind"] == "RPR":
                w = (P[g["joint"]] - P[g["pivot"]]) / complex(g["branch"] * 1.0, 0.0)
                theta = cmath.phase(P[g["joint"]] - P[g["pivot"]]) - cmath.phase(
                    complex(g["branch"] * math.sqrt(abs(w) ** 2 - g["offset"] ** 2), g["offset"]))
                frames[g["links"][0]] = (P[g["joint"]], theta)
                frames[g["links"][1]] = (P[g["pivot"]], theta)
            elif g["kind"] == "PRP":
                for k, guide in zip(g["links"], g["guides"]):
                    theta = 0.0 if guide["link"] == "0" else frames[guide["link"]][1]
                    frames[k] = (P[g["point"]], theta + math.radians(guide["angle_deg"]))
            elif g["kind"] == "RPP":
                ag = math.radians(g["guide"]["angle_deg"])
                frames[g["links"][0]] = (P[g["joint"]], ag + math.radians(g["slot_angle_deg"]))
                frames[g["links"][1]] = (P[g["origin"]], ag)
            else:
                B, C = (P[n] for n in g["joints"][:2])
                frames[g["base"]] = (B, cmath.phase(C - B))
                for lead, J in zip(g["leads"], g["joints"]):
                    frames[lead["link"]] = (P[lead["joint"]], cmath.phase(P[J] - P[lead["joint"]]))
        return frames

    def drawn(self) -> dict:
        joints = list(self.joints)
        self.rnd.shuffle(joints)
        return {"crank": {"link": "1", "pivot": "O", "omega": 3.0}, "joint": joints}


@settings(max_examples=60, deadline=None)
@example(seed=43357, kinds=["triad"])  # two labellings of one triad: their points K differ
@given(st.integers(0, 2**32 - 1), st.lists(st.sampled_from(["RRR", "RRP", "RPR", "PRP", "RPP", "triad"]),
                                                  min_size=1, max_size=4))
def test_random_chains_given_as_joints_decompose_into_their_groups(seed, kinds):
    chain = _Chain(random.Random(seed))
    for kind in kinds:
        getattr(chain, kind.lower())()
    made = from_dict(chain.explicit(), name="made")
    found = from_dict(chain.drawn(), name="found")
    assert sorted(map(canonical_key, found.groups)) == sorted(map(canonical_key, made.groups))
    # near the drawn pose, where both assemble on the drawn branch, away from singular positions
    phis = chain.phi + ANGLES[:5] * 0.02
    try:
        k = velplan.solve(made, phis, order=0)
    except MechanismError:  # a triad that comes back in another assembly after a turn
        assume(False)
    assume(k.valid.all() and k.condition.min() > 0.05)
    assert same_motion(made, found, phis=phis, tol=1e-9, special=False) >= len(chain.points)


def canonical_key(group) -> tuple:
    """`canonical` with sorted links; a triad without its side (the order of its joints in a
    shuffled list of joints is another labelling of the same group)."""
    kind, links, rest = canonical(group)[0], canonical(group)[1], canonical(group)[2:]
    return kind, tuple(sorted(links)), rest[:1] if kind == "triad" else rest


# -- refusals -------------------------------------------------------------------------------

FOUR_BAR = [("O", [0, 0], ["0", "1"]), ("A", [0.1, 0.1], ["1", "2"]), ("C", [0.5, 0.4], ["2", "3"]),
            ("D", [0.6, 0.0], ["3", "0"])]


def _file(joints, crank="1") -> dict:
    return {"crank": {"link": crank, "pivot": "O", "omega": 1.0},
            "joint": [{"name": n, "at": xy, "links": links} for n, xy, links in joints]}


def test_a_chain_of_two_degrees_of_freedom_is_refused_naming_w_and_the_links():
    five_bar = FOUR_BAR[:3] + [("D", [0.6, 0.3], ["3", "4"]), ("E", [0.7, 0.0], ["4", "0"])]
    with pytest.raises(MechanismError, match=r"W = 2 \(3·4 − 2·5\), not 1, for links 1, 2, 3, 4"):
        from_dict(_file(five_bar))


def test_a_locked_chain_is_refused_naming_its_links():
    # W = 1 overall, but link 4 ties the four-bar's coupler to the frame (W = −1 there) while
    # link 5 dangles from the crank (W = +1)
    chain = FOUR_BAR + [("E", [0.3, 0.25], ["2", "4"]), ("F", [0.4, -0.3], ["4", "0"]),
                        ("H", [0.05, 0.05], ["1", "5"])]
    with pytest.raises(MechanismError, match=r"link 4 is held by more pairs than it can move in \(a locked sub-chain"):
        from_dict(_file(chain))


def test_a_class_four_group_is_refused_naming_its_links():
    # Stephenson's chain driven by a binary link next to a ternary one: a contour of four links
    stephenson = [("O", [0, 0], ["0", "1"]), ("A", [-7, 41], ["1", "2"]), ("B", [9, 92], ["2", "5"]),
                  ("C", [41, 19], ["2", "4"]), ("D", [74, 43], ["3", "4"]), ("E", [130, -12], ["0", "3"]),
                  ("F", [102, 93], ["3", "5"])]
    with pytest.raises(MechanismError, match=r"links 2, 5, 4, 3 form a class IV group"):
        from_dict(_file(stephenson))


@pytest.mark.parametrize("joint, message", [
    ({"name": "X", "at": [0, 0], "links": ["1", "2"], "kind": "Q"}, "unknown joint kind 'Q'; known kinds: R, P, RP"),
    ({"name": "X", "at": [0, 0], "links": ["1", "2"], "kind": "P"}, "a P joint needs angle_deg"),
    ({"name": "X", "at": [0], "links": ["1", "2"]}, r"at must be \[x, y\]"),
    ({"name": "X", "at": [0, 0], "links": []}, "links must be a list of link names"),
    ({"name": "A", "at": [0, 0], "links": ["1", "2"]}, "duplicate joint name 'A'"),
    ({"name": "X", "at": [0, 0], "links": ["1", "2"], "block": "3"}, "belong to P and RP joints"),
])
def test_a_bad_joint_is_refused_in_one_line(joint, message):
    data = _file(FOUR_BAR)
    data["joint"].append(joint)
    with pytest.raises(MechanismError, match=message) as err:
        from_dict(data)
    assert "\n" not in str(err.value)


def test_joints_and_groups_together_are_refused():
    data = _file(FOUR_BAR) | {"ground": {"O": [0, 0]}}
    with pytest.raises(MechanismError, match="instead of"):
        from_dict(data)


def test_a_crank_pivot_off_the_frame_is_refused():
    data = _file(FOUR_BAR)
    data["crank"]["pivot"] = "A"
    with pytest.raises(MechanismError, match="must be an R joint of the frame and link 1"):
        from_dict(data)
