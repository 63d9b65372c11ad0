"""The plans of a class III triad, drawn by Assur's special point.

No vector equation of a triad has only two unknowns, so the plans start from the special point
S of the base link: the crossing of the lines of two leads i, j (a rod's line P→J, or a block's
guide normal through J). As a point of the base link S moves relative to lead i's outer joint
across that lead's line only (both relative terms are ⊥ the rod, or ∥ the guide):

    V_S = V_P + V_JP + V_SJ                 (rod: the last two ⊥ PJ)
    V_S = V_Jg + V_JJg + V_SJ               (block: the last two ∥ the guide; V_Jg = 0 on the frame)
    a_S = a_P + aⁿ_JP + aⁿ_SJ + (⊥ PJ)      (aⁿ_JP = ω_lead²·|JP| from J towards P,
    a_S = a_Jg + aᵏ + aⁿ_SJ + (∥ guide)      aⁿ_SJ = ω_base²·|SJ| from S towards J)

and likewise along lead j: the two lines meet at the image s. The third lead's inner joint J_k
then follows as in a dyad (V_Jk = V_S + V_JkS = its lead's equation), the base link's other
joints by similarity of the figure S, J_k, and the leads from their two images.

Everything here works through the plan builder of `velplan.plans.build` (its sheets, images,
anchors and rotors); the steps are the ordinary ones, with sentences that state the equations.
"""

from __future__ import annotations

from dataclasses import dataclass

from velplan.analysis.solver import special_pair
from velplan.mechanism.model import GROUND, Triad
from velplan.options import Language
from velplan.plans import text as T
from velplan.plans.steps import Coriolis, Intersect, LayOff, Line, Normal, Parallel, Perpendicular, Similar, guide_text


def _join(lang: Language, *sentences: str | None) -> str:
    """Sentences one after another (no space after a full stop in Chinese)."""
    return T.joined("" if lang == "zh" else " ", [x for x in sentences if x is not None])


# -- steps that say what they do in the triad ------------------------------------------------------


@dataclass(frozen=True)
class Said:
    """What a triad step says before its own sentence: the vector equation it starts drawing.

    ``intro`` (special point, base link, lead i, lead j, the joint of lead i and of lead j
    where that lead is a block, else "") names Assur's special point first;
    ``point`` is the point the equation is written for, on the line of ``lead`` (``joint``:
    the point is the joint of the base link and that lead); ``direction`` is the direction of
    the equation's unknown terms."""

    point: str
    equation: T.Sentence
    base: str
    lead: str
    direction: Perpendicular | Parallel
    joint: bool = False
    intro: tuple[str, str, str, str, str, str] | None = None
    known: Parallel | None = None
    """The known direction of the point's velocity, written where the equation has ``{}``."""
    block: str = ""
    """The joint of a block lead: its line is the guide's normal through that joint."""

    def text(self, lang: Language) -> str:
        """The sentences said before the step's own (ending in a separator)."""
        out = [_special(lang, *self.intro)] if self.intro else []
        if self.joint:
            eq = _filled(self.equation, self.known.text(lang)) if self.known else self.equation
            out.append(T.phrase("triad_joint", lang, T.pts(self.point), self.base, self.lead, eq))
        else:
            out.append(T.phrase("triad_block" if self.block else "triad_lead", lang, T.pts(self.point), self.base,
                                self.lead, self.equation, self.direction.text(lang), T.pts(self.block)))
        return _join(lang, *out, "")


@dataclass(frozen=True)
class TriadLine(Line):
    """A construction line of the triad, its sentence preceded by its equation (``said``)."""

    said: Said | None = None

    def describe(self, ctx, vals, i, lang) -> str:
        return (self.said.text(lang) if self.said else "") + super().describe(ctx, vals, i, lang)


@dataclass(frozen=True)
class TriadLayOff(LayOff):
    """A known vector of the triad's acceleration plan, its sentence preceded by the equation
    it starts drawing (``said``)."""

    said: Said | None = None

    def describe(self, ctx, vals, i, lang) -> str:
        return (self.said.text(lang) if self.said else "") + super().describe(ctx, vals, i, lang)


@dataclass(frozen=True)
class SpecialIntersect(Intersect):
    """The intersection that gives the image of Assur's special point (named in its sentence)."""

    special: str = ""
    base: str = ""
    centre: bool = False
    """Both lines pass through the pole of the velocity plan: V_S = 0, S is the base link's
    instant centre of velocities."""

    def describe(self, ctx, vals, i, lang) -> str:
        return _join(lang, super().describe(ctx, vals, i, lang),
                     T.phrase("triad_image", lang, T.pts(self.label), T.pts(self.special), self.base),
                     T.phrase("triad_centre", lang, T.pts(self.special), self.base, T.vector("V_" + self.special))
                     if self.centre else None)


# -- the construction ------------------------------------------------------------------------------


def _special(lang: str, point: str, base: str, li: str, lj: str, ji: str, jj: str) -> str:
    """The sentence naming Assur's special point: the crossing of two leads' lines, a block
    lead's line being the normal to its guide through its joint."""
    if not (ji or jj):
        return T.phrase("triad_special", lang, T.pts(point), base, li, lj)
    lines = [T.phrase("triad_normal", lang, lk, T.pts(jk)) if jk else T.phrase("triad_line", lang, lk)
             for lk, jk in ((li, ji), (lj, jj))]
    return T.phrase("triad_special_of", lang, T.pts(point), base, *lines)


def _sum(*terms: str | None) -> T.Sentence:
    """Vectors added: each of ``terms`` (``V_JP``, ``aⁿ_JP``) marked a vector, None left out."""
    return T.joined(" + ", [T.vector(t) for t in terms if t])


def _equation(*sides: str | T.Sentence) -> T.Sentence:
    """A vector equation: its sides (a vector's symbol, or a `_sum`) joined by " = "."""
    return T.joined(" = ", [side if isinstance(side, T.Sentence) else T.vector(side) for side in sides])


def _filled(sentence: T.Sentence, value: str) -> T.Sentence:
    """``sentence`` with ``value`` in place of its "{}", its symbols kept."""
    parts: list = []
    for x in sentence.parts:
        for n, piece in enumerate(x.split("{}") if isinstance(x, str) else [x]):
            parts += [value, piece] if n else [piece]
    return T.text(*parts)


class TriadPlan:
    """The velocity and acceleration construction of one triad ``g`` through the plan builder
    ``b`` (a `velplan.plans.build._Builder`)."""

    def __init__(self, b, g: Triad):
        self.b, self.g = b, g
        i, j = special_pair(b.mech, g)
        self.pair = (i, j)
        self.third = 3 - i - j
        self.S = g.special_name
        self.intro = (self.S, g.base, g.leads[i].link, g.leads[j].link,
                      g.joints[i] if g.leads[i].slider else "", g.joints[j] if g.leads[j].slider else "")
        self.guide_images: dict[tuple[str, int], str] = {}

    # -- helpers --------------------------------------------------------------------------------

    def _guide_point(self, sheet, k: int) -> str:
        """Image of the guide link's point at block lead k's joint (placed once)."""
        key = (sheet.kind, k)
        if key not in self.guide_images:
            lead, J = self.g.leads[k], self.g.joints[k]
            self.guide_images[key] = self.b.image_on(sheet, lead.guide.link, J, lead.coincident)
        return self.guide_images[key]

    def _guide_points(self, sheet) -> None:
        """The guide links' points at the blocks, placed before the triad's own construction."""
        for k, lead in enumerate(self.g.leads):
            if lead.slider:
                self._guide_point(sheet, k)

    def _guide_name(self, k: int) -> str:
        lead = self.g.leads[k]
        return lead.coincident or f"{self.g.joints[k]}{lead.guide.link}"

    def _direction(self, k: int) -> Perpendicular | Parallel:
        """Direction of the unknown terms along lead k: ⊥ the rod, or ∥ the guide."""

        lead, J = self.g.leads[k], self.g.joints[k]
        if lead.slider:
            return Parallel(lead.guide.link, lead.guide.angle, guide_text(lead.guide, lead.guide.link))
        return Perpendicular(J, lead.joint)

    def _say(self, k: int, equation: T.Sentence, *, intro: bool = False, joint: bool = False) -> Said:
        g = self.g
        known = self._direction(k) if joint and "{}" in equation else None
        block = g.joints[k] if g.leads[k].slider and not joint else ""
        return Said(g.joints[k] if joint else self.S, equation, g.base, g.leads[k].link,
                    Perpendicular(g.joints[k], self.S) if joint else self._direction(k), joint,
                    self.intro if intro else None, known, block)

    def _fixed(self, sheet, point: str) -> bool:
        return sheet.images.get(point) == sheet.pole

    def _line(self, sheet, through: str, direction, component: str, said: Said | None = None) -> str:
        b = self.b
        b.counters["line"] += 1
        return b.add(sheet, TriadLine(f"{sheet.kind}:ℓ{b.counters['line']}", through, direction, component, said))

    def _normal(self, origin: str, link: str, point: str, centre: str, said: Said | None = None) -> str:
        b = self.b
        n = b.aux("n")
        return b.add(b.a, TriadLayOff(f"a:{n}", n, origin, Normal(link, point, centre, b.v.rotor[link]), said))

    # -- velocity plan -------------------------------------------------------------------------

    def _lead_line_v(self, k: int, intro: bool) -> str:
        """Line of V_S through the known image of lead k's outer joint (or guide point)."""
        b, g, S = self.b, self.g, self.S
        lead, J = g.leads[k], g.joints[k]
        if lead.slider:
            through = self._guide_point(b.v, k)
            gname, moving = self._guide_name(k), lead.guide.link != GROUND
            eq = _equation(f"V_{S}", _sum(f"V_{gname}" if moving else None, f"V_{J}{gname}" if moving else f"V_{J}",
                                          f"V_{S}{J}"))
            comp = f"V_{S}{gname}" if moving else f"V_{S}"
        else:
            P = lead.joint
            fixed = self._fixed(b.v, P)
            through = b.v.images[P]
            eq = _equation(f"V_{S}", _sum(f"V_{P}", f"V_{J}{P}", f"V_{S}{J}"))  # V_P = 0 on the frame, as written
            comp = f"V_{S}" if fixed else f"V_{S}{P}"
        return self._line(b.v, through, self._direction(k), comp, self._say(k, eq, intro=intro))

    def _third_lines_v(self, s_v: str) -> tuple[str, str]:
        """V_J = V_S + V_JS (⊥ SJ) = the third lead's own equation, for its inner joint J."""
        b, g, S, k = self.b, self.g, self.S, self.third
        lead, J = g.leads[k], g.joints[k]
        if lead.slider:
            through = self._guide_point(b.v, k)
            gname, moving = self._guide_name(k), lead.guide.link != GROUND
            other = _sum(f"V_{gname}", f"V_{J}{gname}") if moving else None
            comp = f"V_{J}{gname}" if moving else f"V_{J}"
        else:
            P = lead.joint
            through, fixed = b.v.images[P], self._fixed(b.v, P)
            other = _sum(f"V_{P}", f"V_{J}{P}")  # v_C = v_E + v_CE, v_E = 0 on the frame
            comp = f"V_{J}" if fixed else f"V_{J}{P}"
        eq = _equation(f"V_{J}", _sum(f"V_{S}", f"V_{J}{S}"), *([other] if other else []))
        eq = eq if other else T.text(eq, ", ", T.vector(f"V_{J}"), " {}")
        L1 = self._line(b.v, s_v, Perpendicular(J, S), f"V_{J}{S}", self._say(k, eq, joint=True))
        return L1, self._line(b.v, through, self._direction(k), comp)

    def velocity(self) -> None:
        b, g, S = self.b, self.g, self.S
        i, j = self.pair
        s_v = b.target(b.v, S)
        self._guide_points(b.v)
        L1, L2 = self._lead_line_v(i, True), self._lead_line_v(j, False)
        through = {st.target: getattr(st, "through", None) for st in b.steps["v"]}
        centre = through[L1] == through[L2] == b.v.pole
        b.add(b.v, SpecialIntersect(s_v, s_v[2:], (L1, L2), special=S, base=g.base, centre=centre))
        b.v.images[S] = s_v
        J = g.joints[self.third]
        j_v = b.target(b.v, J)
        b.add(b.v, Intersect(j_v, j_v[2:], self._third_lines_v(s_v)))
        b.v.images[J] = j_v
        base_v = b.figure(g.base, S, J)[0]
        b.v.rotor[g.base] = base_v
        for k in (i, j):
            t = b.target(b.v, g.joints[k])
            b.add(b.v, Similar(t, t[2:], g.base, g.joints[k], S, s_v, base_v))
            b.v.images[g.joints[k]] = t
        for lead, Jk in zip(g.leads, g.joints):
            if not lead.slider:
                b.v.rotor[lead.link] = b.figure(lead.link, lead.joint, Jk)[0]

    # -- acceleration plan ---------------------------------------------------------------------

    def _lead_line_a(self, k: int, intro: bool) -> str:
        """Line of a_S: lead k's known terms laid off in turn, then the unknown direction."""
        b, g, S = self.b, self.g, self.S
        lead, J = g.leads[k], g.joints[k]
        if lead.slider:
            start = self._guide_point(b.a, k)
            gname, moving = self._guide_name(k), lead.guide.link != GROUND
            frame = b.v.rotor.get(lead.guide.link) if moving else None
            eq = _equation(f"a_{S}", _sum(f"a_{gname}" if moving else None, f"aᵏ_{J}" if frame is not None else None,
                                          f"aʳ_{J}", f"aⁿ_{S}{J}", f"aᵗ_{S}{J}"))
            said = self._say(k, eq, intro=intro)
            if frame is not None:
                c = b.aux("k")
                cor = Coriolis(frame, self._guide_point(b.v, k), b.v.images[J], J)
                start = b.add(b.a, TriadLayOff(f"a:{c}", c, start, cor, said))
                said = None
            start = self._normal(start, g.base, S, J, said)
            comp = f"aʳ_{S}{J}"
        else:
            P = lead.joint
            eq = _equation(f"a_{S}", _sum(f"a_{P}", f"aⁿ_{J}{P}", f"aᵗ_{J}{P}", f"aⁿ_{S}{J}", f"aᵗ_{S}{J}"))
            start = self._normal(b.a.images[P], lead.link, J, P, self._say(k, eq, intro=intro))
            start = self._normal(start, g.base, S, J)
            comp = f"aᵗ_{S}{P}"
        return self._line(b.a, start, self._direction(k), comp)

    def _third_lines_a(self, s_a: str) -> tuple[str, str]:
        """a_J = a_S + aⁿ_JS + aᵗ_JS (⊥ SJ) = the third lead's own equation."""
        b, g, S, k = self.b, self.g, self.S, self.third
        lead, J = g.leads[k], g.joints[k]
        if lead.slider:
            gname, moving = self._guide_name(k), lead.guide.link != GROUND
            other = _sum(f"a_{gname}" if moving else None, f"aᵏ_{J}" if moving else None, f"aʳ_{J}")
        else:
            P = lead.joint
            other = _sum(f"a_{P}", f"aⁿ_{J}{P}", f"aᵗ_{J}{P}")
        eq = _equation(f"a_{J}", _sum(f"a_{S}", f"aⁿ_{J}{S}", f"aᵗ_{J}{S}"), other)
        start = self._normal(s_a, g.base, J, S, self._say(k, eq, joint=True))
        L1 = self._line(b.a, start, Perpendicular(J, S), f"aᵗ_{J}{S}")
        if lead.slider:
            L2 = b.coriolis_line(lead.guide.link, self._guide_point(b.a, k), (self._guide_point(b.v, k), b.v.images[J]),
                                 self._direction(k), f"aʳ_{J}", J)
        else:
            L2 = b.normal_line(lead.link, J, lead.joint, b.a.images[lead.joint])
        return L1, L2

    def acceleration(self) -> None:
        b, g, S = self.b, self.g, self.S
        i, j = self.pair
        s_a = b.target(b.a, S)
        self._guide_points(b.a)
        M1, M2 = self._lead_line_a(i, True), self._lead_line_a(j, False)
        b.add(b.a, SpecialIntersect(s_a, s_a[2:], (M1, M2), special=S, base=g.base))
        b.a.images[S] = s_a
        J = g.joints[self.third]
        j_a = b.target(b.a, J)
        b.add(b.a, Intersect(j_a, j_a[2:], self._third_lines_a(s_a)))
        b.a.images[J] = j_a
        base_a = b.figure(g.base, S, J)[1]
        for k in (i, j):
            t = b.target(b.a, g.joints[k])
            b.add(b.a, Similar(t, t[2:], g.base, g.joints[k], S, s_a, base_a))
            b.a.images[g.joints[k]] = t

    # -- links ---------------------------------------------------------------------------------

    def register(self) -> None:
        """Anchors and rotors of the base link and the leads, for the points placed later."""
        b, g = self.b, self.g
        J = g.joints[self.third]
        fv, fa = b.figure(g.base, self.S, J)
        b.set_link(g.base, (J, b.v.images[J], b.a.images[J]), fv, fa)
        for lead, Jk in zip(g.leads, g.joints):
            if lead.slider:
                k = lead.guide.link
                moving = k != GROUND
                b.set_link(lead.link, (Jk, b.v.images[Jk], b.a.images[Jk]), b.v.rotor[k] if moving else None,
                           b.a.rotor[k] if moving else None)
            else:
                fv, fa = b.figure(lead.link, lead.joint, Jk)
                b.set_link(lead.link, (lead.joint, b.v.images[lead.joint], b.a.images[lead.joint]), fv, fa)


def build_triad(b, g: Triad) -> None:
    """Emit the triad's velocity then acceleration steps through the plan builder ``b``."""
    t = TriadPlan(b, g)
    t.velocity()
    t.acceleration()
    t.register()
