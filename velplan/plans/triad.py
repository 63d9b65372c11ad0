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

from velplan.analysis.triad import special_pair
from velplan.mechanism.model import GROUND, Lead, Triad
from velplan.plans import text as T
from velplan.plans.steps import Coriolis, Intersect, LayOff, Line, Normal, Parallel, Perpendicular, Similar


# -- steps that say what they do in the triad ------------------------------------------------------


@dataclass(frozen=True)
class TriadLine(Line):
    """A construction line of the triad, its sentence preceded by the equation it draws.

    ``intro`` (special point, base link, lead i, lead j) names Assur's special point first;
    ``lead`` is the lead (or the joint, with ``joint``) the equation belongs to."""

    equation: str = ""
    base: str = ""
    lead: str = ""
    joint: str = ""
    intro: tuple[str, str, str, str] | None = None

    def describe(self, ctx, vals, i, lang) -> str:
        out = T.phrase("triad_special", lang, *self.intro) + " " if self.intro else ""
        if self.joint:
            out += T.phrase("triad_joint", lang, self.joint, self.base, self.lead, self.equation) + " "
        elif self.equation:
            special = self.equation.split(" ", 1)[0].split("_", 1)[1]
            out += T.phrase("triad_lead", lang, special, self.base, self.lead, self.equation,
                            self.direction.text(lang)) + " "
        return out + super().describe(ctx, vals, i, lang)


@dataclass(frozen=True)
class SpecialIntersect(Intersect):
    """The intersection that gives the image of Assur's special point (named in its sentence)."""

    special: str = ""
    base: str = ""

    def describe(self, ctx, vals, i, lang) -> str:
        return super().describe(ctx, vals, i, lang) + " " + T.phrase("triad_image", lang, self.label, self.special,
                                                                        self.base)


# -- the construction ------------------------------------------------------------------------------


def _sum(*terms: str | None) -> str:
    return " + ".join(t for t in terms if t)


class TriadPlan:
    """The velocity and acceleration construction of one triad ``g`` through the plan builder
    ``b`` (a `velplan.plans.build._Builder`)."""

    def __init__(self, b, g: Triad):
        self.b, self.g = b, g
        i, j = special_pair(b.mech, g)
        self.pair = (i, j)
        self.third = 3 - i - j
        self.S = g.special_name
        self.intro = (self.S, g.base, g.leads[i].link, g.leads[j].link)

    # -- helpers --------------------------------------------------------------------------------

    def _guide_point(self, sheet, k: int) -> str:
        """Image of the guide link's point at block lead k's joint."""
        lead, J = self.g.leads[k], self.g.joints[k]
        return self.b.image_on(sheet, lead.guide.link, J, lead.coincident)

    def _guide_name(self, k: int) -> str:
        lead = self.g.leads[k]
        return lead.coincident or f"{self.g.joints[k]}{lead.guide.link}"

    def _parallel(self, lead: Lead) -> Parallel:
        from velplan.plans.build import _guide_text

        return Parallel(lead.guide.link, lead.guide.angle, _guide_text(lead.guide, lead.guide.link))

    def _fixed(self, sheet, point: str) -> bool:
        return sheet.images.get(point) == sheet.pole

    def _line(self, sheet, through: str, direction, component: str, **say) -> str:
        b = self.b
        b.counters["line"] += 1
        target = f"{sheet.kind}:ℓ{b.counters['line']}"
        return b.add(sheet, TriadLine(target, through, direction, component, base=self.g.base, **say))

    # -- velocity plan -------------------------------------------------------------------------

    def _lead_line_v(self, k: int, intro: bool) -> str:
        """Line of V_S through the known image of lead k's outer joint (or guide point)."""
        b, g, S = self.b, self.g, self.S
        lead, J = g.leads[k], g.joints[k]
        intro = self.intro if intro else None
        if lead.slider:
            through = self._guide_point(b.v, k)
            gname = self._guide_name(k)
            moving = lead.guide.link != GROUND
            eq = f"V_{S} = " + _sum(f"V_{gname}" if moving else None, f"V_{J}{gname}" if moving else f"V_{J}",
                                    f"V_{S}{J}")
            return self._line(b.v, through, self._parallel(lead), f"V_{S}{gname}" if moving else f"V_{S}",
                              equation=eq, lead=lead.link, intro=intro)
        P = lead.joint
        fixed = self._fixed(b.v, P)
        eq = f"V_{S} = " + _sum(None if fixed else f"V_{P}", f"V_{J}{P}", f"V_{S}{J}")
        return self._line(b.v, b.v.images[P], Perpendicular(J, P), f"V_{S}" if fixed else f"V_{S}{P}",
                          equation=eq, lead=lead.link, intro=intro)

    def _third_lines_v(self, s_v: str) -> tuple[str, str]:
        b, g, S, k = self.b, self.g, self.S, self.third
        lead, J = g.leads[k], g.joints[k]
        if lead.slider:
            through = self._guide_point(b.v, k)
            gname = self._guide_name(k)
            moving = lead.guide.link != GROUND
            other = f"V_{gname} + V_{J}{gname}" if moving else None
            direction, comp = self._parallel(lead), f"V_{J}{gname}" if moving else f"V_{J}"
        else:
            P = lead.joint
            through, direction = b.v.images[P], Perpendicular(J, P)
            fixed = self._fixed(b.v, P)
            other = _sum(None if fixed else f"V_{P}", f"V_{J}{P}")
            comp = f"V_{J}" if fixed else f"V_{J}{P}"
        eq = f"V_{J} = V_{S} + V_{J}{S}" + (f" = {other}" if other else "")
        L1 = self._line(b.v, s_v, Perpendicular(J, S), f"V_{J}{S}", equation=eq, lead=lead.link, joint=J)
        L2 = self._line(b.v, through, direction, comp)
        return L1, L2

    def velocity(self) -> None:
        b, g, S = self.b, self.g, self.S
        i, j = self.pair
        s_v = b.target(b.v, S)
        L1, L2 = self._lead_line_v(i, True), self._lead_line_v(j, False)
        b.add(b.v, SpecialIntersect(s_v, s_v[2:], (L1, L2), special=S, base=g.base))
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

    def _normal(self, origin: str, link: str, point: str, centre: str) -> str:
        b = self.b
        n = b.aux("n")
        return b.add(b.a, LayOff(f"a:{n}", n, origin, Normal(link, point, centre, b.v.rotor[link])))

    def _lead_line_a(self, k: int, intro: bool) -> str:
        """Line of a_S: lead k's known acceleration terms laid off, then the unknown direction."""
        b, g, S = self.b, self.g, self.S
        lead, J = g.leads[k], g.joints[k]
        intro = self.intro if intro else None
        if lead.slider:
            start = self._guide_point(b.a, k)
            gname = self._guide_name(k)
            frame = b.v.rotor.get(lead.guide.link) if lead.guide.link != GROUND else None
            if frame is not None:
                c = b.aux("k")
                start = b.add(b.a, LayOff(f"a:{c}", c, start, Coriolis(frame, self._guide_point(b.v, k),
                                                                        b.v.images[J], J)))
            start = self._normal(start, g.base, S, J)
            moving = lead.guide.link != GROUND
            eq = f"a_{S} = " + _sum(f"a_{gname}" if moving else None, f"aᵏ_{J}" if frame is not None else None,
                                    f"aʳ_{J}", f"aⁿ_{S}{J}", f"aᵗ_{S}{J}")
            return self._line(b.a, start, self._parallel(lead), f"aʳ_{S}", equation=eq, lead=lead.link,
                              intro=intro)
        P = lead.joint
        fixed = self._fixed(b.a, P)
        start = self._normal(b.a.images[P], lead.link, J, P)
        start = self._normal(start, g.base, S, J)
        eq = f"a_{S} = " + _sum(None if fixed else f"a_{P}", f"aⁿ_{J}{P}", f"aᵗ_{J}{P}", f"aⁿ_{S}{J}", f"aᵗ_{S}{J}")
        return self._line(b.a, start, Perpendicular(J, P), f"aᵗ_{S}{P}", equation=eq, lead=lead.link, intro=intro)

    def _third_lines_a(self, s_a: str) -> tuple[str, str]:
        b, g, S, k = self.b, self.g, self.S, self.third
        lead, J = g.leads[k], g.joints[k]
        start = self._normal(s_a, g.base, J, S)
        if lead.slider:
            gname = self._guide_name(k)
            moving = lead.guide.link != GROUND
            other = _sum(f"a_{gname}" if moving else None, f"aᵏ_{J}" if moving else None, f"aʳ_{J}")
        else:
            P = lead.joint
            other = _sum(None if self._fixed(b.a, P) else f"a_{P}", f"aⁿ_{J}{P}", f"aᵗ_{J}{P}")
        eq = f"a_{J} = a_{S} + aⁿ_{J}{S} + aᵗ_{J}{S} = {other}"
        L1 = self._line(b.a, start, Perpendicular(J, S), f"aᵗ_{J}{S}", equation=eq, lead=lead.link, joint=J)
        if lead.slider:
            cg_a = self._guide_point(b.a, k)
            L2 = b.coriolis_line(lead.guide.link, cg_a, (self._guide_point(b.v, k), b.v.images[J]),
                                 self._parallel(lead), f"aʳ_{J}", J)
        else:
            L2 = b.normal_line(lead.link, J, lead.joint, b.a.images[lead.joint])
        return L1, L2

    def acceleration(self) -> None:
        b, g, S = self.b, self.g, self.S
        i, j = self.pair
        s_a = b.target(b.a, S)
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
