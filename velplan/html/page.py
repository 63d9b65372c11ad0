"""The page itself: one HTML file with its style, script and data inline, and `Page`.

The file loads nothing: no fonts, no libraries, no images; the script (page.js, beside this
module) draws the records of the data block (`velplan.html.frames`) into three inline SVG
panels. The same study, language and options give the same bytes.
"""

from __future__ import annotations

import html
import json
from importlib import resources
from pathlib import Path

from velplan.analysis.numbering import position_number
from velplan.errors import VelplanError
from velplan.io import write_atomic
from velplan.notation import digits_down
from velplan.options import Language
from velplan.plans.drafting import Drafting
from velplan.render.i18n import LANGUAGES, label
from velplan.render.style import LINE_TYPES, SheetStyle
from velplan.study import Study
from velplan.html.aside import Aside
from velplan.html.frames import phi_degrees, plan_frames, rates, scheme_frames, scheme_records
from velplan.html.records import stroke_table
from velplan.html.text import page_words, word
from velplan.views.base import number, unit

#: Most positions a page holds (at 720 the shaper's page is about 2.1 MB).
MAX_POSITIONS = 720
#: Height of the page's frame in a notebook, px.
NOTEBOOK_HEIGHT_PX = 1080


def _asset(name: str) -> str:
    return resources.files("velplan.html").joinpath(name).read_text("utf-8")


def _stroke_css(style: SheetStyle) -> str:
    """CSS of the line types in drawing units (0.01 mm): widths and dashes of the sheets."""
    rules = []
    for k, line in enumerate(LINE_TYPES):
        spec = stroke_table(style)[k]
        rule = f".l{k}{{stroke-width:{spec['w']}"
        if spec["dash"]:
            rule += f";stroke-dasharray:{','.join(str(d) for d in spec['dash'])};stroke-linecap:butt"
        rules.append(rule + "}")
    return "svg " + "\nsvg ".join(rules)


#: The share of the scheme's positions a fork draws beside its plans (`velplan.html.aside`),
#: spread over the turn: the two processes' work about even on the shaper (72 positions,
#: CPU s: this process ≈ 0.43 before it takes the fork's part, the fork ≈ 0.44).
ASIDE_SHARE = 0.25


def build_data(study: Study, lang: Language, *, scale_v: float | None = None, scale_a: float | None = None,
               drafting: Drafting = Drafting(0.5, 0.5), centres: bool = False) -> dict:
    """Everything the page's script draws and writes, as a JSON-ready dict. Within
    `velplan.html.aside.building_aside`, a fork draws the plans and a share of the scheme's
    positions meanwhile (the same dict)."""
    style = SheetStyle(language=lang)
    kin = study.kinematics
    # one μv and one μa for the whole turn (the standard ones unless given)
    mu_v = study.plan("velocity", scale_v=scale_v).scale
    mu_a = study.plan("acceleration", scale_a=scale_a).scale
    _ = study.turn  # the trajectories, solved once for both processes
    valid = [position_number(i) for i in range(len(kin)) if kin.valid[i]]
    share = round(len(valid) * ASIDE_SHARE)
    theirs = [valid[k * len(valid) // share] for k in range(share)]

    def plans(positions: list[int]) -> tuple[list[dict], dict[int, list[list]]]:
        return ([plan_frames(study, kind, lang, style, scale_v=mu_v, scale_a=mu_a, drafting=drafting)
                 for kind in ("velocity", "acceleration")],
                scheme_records(study, positions, lang, style, centres=centres))

    part = Aside(lambda: plans(theirs))
    if part.pid is None:  # no fork: all here, the scheme's positions drawn together
        pv_pa, drawn = plans([])
    else:
        try:
            mine = scheme_records(study, [p for p in valid if p not in theirs], lang, style, centres=centres)
            pv_pa, drawn = part.result()
        finally:
            part.close()
        drawn.update(mine)
    return {
        "n": len(kin), "comma": lang in ("ru", "uk"),
        "phi": phi_degrees(study), "valid": [bool(v) for v in kin.valid],
        "words": page_words(lang), "stroke": stroke_table(style),
        "units": {"omega": unit("rad/s", lang), "epsilon": unit("rad/s²", lang)},
        "scheme": scheme_frames(study, lang, style, centres=centres, drawn=drawn), "plans": pv_pa,
        "rates": rates(study),
    }


def page_html(study: Study, lang: Language = "en", *, scale_v: float | None = None, scale_a: float | None = None,
              drafting: Drafting = Drafting(0.5, 0.5), centres: bool = False) -> str:
    """The whole page of `study` in `lang`: a self-contained HTML document.

    Parameters
    ----------
    study : Study
        The mechanism at its positions (every position becomes a stop of the slider).
    lang : {"en", "ru", "uk", "zh"}
    scale_v, scale_a : float, optional
        μv, (m/s)/mm and μa, (m/s²)/mm of the plans for the whole turn (default: the standard
        scales that keep the longest vector within 100 and 120 mm).
    drafting : Drafting
        Precision of the drafted plans the errors are read from (default 0.5 mm, 0.5°).
    centres : bool
        Mark each position's instant centres found by Kennedy lines on the scheme.
    """
    if lang not in LANGUAGES:
        raise VelplanError(f"unknown language {lang!r}; known languages: {', '.join(LANGUAGES)}")
    if len(study.kinematics) > MAX_POSITIONS:
        raise VelplanError(f"a page holds at most {MAX_POSITIONS} positions, not {len(study.kinematics)}")
    if not study.kinematics.valid.any():
        raise VelplanError(f"{study.mechanism.name} cannot be assembled at any of the positions")
    data = build_data(study, lang, scale_v=scale_v, scale_a=scale_a, drafting=drafting, centres=centres)
    mech = study.mechanism
    e = html.escape
    words = data["words"]
    omega = f"ω{digits_down(mech.crank.link)} = {number(abs(mech.crank.omega), lang)} {unit('rad/s', lang)}"
    sub = f"{mech.name_in(lang)} · {data['n']} {word('positions', lang)} · {omega}"
    note = word("drafting_note", lang).format(mm=number(drafting.length_mm, lang),
                                              deg=number(drafting.angle_deg, lang))
    payload = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")

    def box(part) -> str:
        return " ".join(str(v) for v in part["box"])

    pv, pa = data["plans"]
    head = [words["step"], words["quantity"], words["analytic"], word("drafted", lang), words["error"],
            words["error"] + ", %"]
    return f"""<!DOCTYPE html>
<html lang="{lang}">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="velplan">
<title>{e(mech.name_in(lang))} — {e(word('page_title', lang))}</title>
<style>
{_asset('page.css')}{_stroke_css(SheetStyle(language=lang))}
</style>
</head>
<body>
<h1>{e(mech.name_in(lang))}: {e(word('page_title', lang))}</h1>
<p class="sub">{e(sub)}</p>
<div class="bar" id="controls">
<button id="play" type="button" aria-pressed="false">▶ {e(words['play'])}</button>
<input id="pos" type="range" min="1" max="{data['n']}" value="1" step="1" aria-label="{e(words['crank_angle'])}">
<output id="readout-pos"></output>
<output id="readout-phi"></output>
<label><input id="fixed" type="checkbox"> {e(word('fixed_frame', lang))}</label>
</div>
<div class="panels">
<figure><figcaption>{e(label('title_mechanism', lang))}</figcaption>
<svg id="scheme-svg" viewBox="{box(data['scheme'])}" role="img"><g id="under"></g><g id="scheme-now"></g></svg>
<p class="scale" id="mu-l">{e(data['scheme']['scale'])}</p></figure>
<figure><figcaption>{e(label('velocity_plan', lang))}</figcaption>
<svg id="plan-v-svg" viewBox="{box(pv)}" role="img"><g id="plan-v"></g></svg>
<p class="scale" id="mu-v">{e(pv['scale'])}</p></figure>
<figure><figcaption>{e(label('acceleration_plan', lang))}</figcaption>
<svg id="plan-a-svg" viewBox="{box(pa)}" role="img"><g id="plan-a"></g></svg>
<p class="scale" id="mu-a">{e(pa['scale'])}</p></figure>
</div>
<div id="steps">
<div class="bar">
<button id="first" type="button" title="{e(words['first'])}">|◀</button>
<button id="prev" type="button" title="{e(words['previous'])}">◀ {e(words['previous'])}</button>
<span id="step-readout"></span>
<button id="next" type="button" title="{e(words['next'])}">{e(words['next'])} ▶</button>
<button id="all" type="button" title="{e(words['complete'])}">{e(words['complete'])} ▶|</button>
</div>
<p id="caption"></p>
<table id="values"><thead><tr>{''.join(f'<th>{e(h)}</th>' for h in head)}</tr></thead><tbody id="values-body"></tbody></table>
<p class="note">{e(note)}</p>
<p id="rates"></p>
</div>
<script type="application/json" id="velplan-data">{payload}</script>
<script>
{_asset('page.js')}</script>
</body>
</html>
"""


class Page:
    """The interactive page of a study: ``.html`` (str), ``.save(path)``, and shown inline in
    Jupyter (`_repr_html_`, a sandboxed frame: the page needs no kernel to play).

    Parameters
    ----------
    study : Study or str or Path
        A study, or a mechanism (bundled name or TOML file) studied at ``positions``.
    positions : int
        Positions over a turn when ``study`` is a mechanism (default 72: every 5°).
    lang : {"en", "ru", "uk", "zh"}
    scale_v, scale_a, drafting, centres
        As for `page_html`.

    Examples
    --------
    >>> page = Page("shaper", positions=12, lang="en")
    >>> page.html.startswith("<!DOCTYPE html>") and "http" not in page.html
    True
    """

    def __init__(self, study: Study | str | Path, *, positions: int = 72, lang: Language = "en",
                 scale_v: float | None = None, scale_a: float | None = None,
                 drafting: Drafting = Drafting(0.5, 0.5), centres: bool = False):
        if not isinstance(study, Study):
            if not 1 <= positions <= MAX_POSITIONS:
                raise VelplanError(f"positions must be between 1 and {MAX_POSITIONS}, not {positions}")
            study = Study(study, n=positions)
        self.study = study
        self.lang = lang
        self.html = page_html(study, lang, scale_v=scale_v, scale_a=scale_a, drafting=drafting, centres=centres)

    def __repr__(self) -> str:
        return f"Page({self.study.mechanism.name!r}, positions={len(self.study.kinematics)}, lang={self.lang!r})"

    def save(self, path: str | Path) -> Path:
        """Write the page to `path` (atomically: whole or not at all)."""
        return write_atomic(path, self.html)

    def _repr_html_(self) -> str:
        return (f'<iframe srcdoc="{html.escape(self.html, quote=True)}" sandbox="allow-scripts" '
                f'style="width:100%;height:{NOTEBOOK_HEIGHT_PX}px;border:0" '
                f'title="{html.escape(self.study.mechanism.name_in(self.lang))}"></iframe>')
