"""Sentences of the worked solution in en, ru, uk and zh, and number formatting per language.

A sentence (`phrase`) is a plain string, as every text output prints it, that keeps the symbols
its caller marked (`Sym`: point names, plan segments, vectors, ω and ε) in its ``parts``; each
output sets them in its own notation from the one mark: the note as formulas
(`velplan.note.prose`), a terminal with Unicode subscripts (`terminal`)."""

from __future__ import annotations

import math
import string
from dataclasses import dataclass
from typing import cast

from velplan.errors import VelplanError
from velplan.notation import MINUS, decimal, digits_down
from velplan.options import Language

LANGS = ("en", "ru", "uk", "zh")

_PHRASES: dict[str, dict[str, str]] = {
    "pole": {
        "en": "Choose the pole {0}; the images of the fixed points {1} are at the pole.",
        "ru": "Выбираем полюс {0}; изображения неподвижных точек {1} совпадают с полюсом.",
        "uk": "Обираємо полюс {0}; зображення нерухомих точок {1} збігаються з полюсом.",
        "zh": "选取极点 {0}；固定点 {1} 的影像与极点重合。",
    },
    "lay_off": {
        "en": "From {0} lay off {1} = {2} {3} ({4} = {5} {6}).",
        "ru": "Из точки {0} откладываем отрезок {1} = {2} {3} ({4} = {5} {6}).",
        "uk": "З точки {0} відкладаємо відрізок {1} = {2} {3} ({4} = {5} {6}).",
        "zh": "自 {0} 作 {1} = {2}，{3}（{4} = {5} {6}）。",
    },
    "line": {
        "en": "Through {0} draw a line {1} (direction of {2}).",
        "ru": "Через точку {0} проводим прямую {1} (направление {2}).",
        "uk": "Через точку {0} проводимо пряму {1} (напрям {2}).",
        "zh": "过 {0} 作直线 {1}（{2} 的方向）。",
    },
    "intersect": {
        "en": "The two lines meet at {0}: {1} (sine of their angle {2}).",
        "ru": "Пересечение прямых даёт точку {0}: {1} (синус угла между ними {2}).",
        "uk": "Перетин прямих дає точку {0}: {1} (синус кута між ними {2}).",
        "zh": "两直线交于 {0}：{1}（夹角正弦 {2}）。",
    },
    "similar": {
        "en": "By similarity of link {1} place {0}: {2} = {3} ({4} · {5} = {4} · {6}).",
        "ru": "По теореме подобия (звено {1}) находим точку {0}: {2} = {3} ({4} · {5} = {4} · {6}).",
        "uk": "За теоремою подібності (ланка {1}) знаходимо точку {0}: {2} = {3} ({4} · {5} = {4} · {6}).",
        "zh": "按影像原理（构件 {1}）求 {0}：{2} = {3}（{4} · {5} = {4} · {6}）。",
    },
    "same_image": {
        "en": "Link {1} does not turn: the image {0} coincides with {2}.",
        "ru": "Звено {1} движется поступательно: точка {0} совпадает с {2}.",
        "uk": "Ланка {1} рухається поступально: точка {0} збігається з {2}.",
        "zh": "构件 {1} 作平动：影像 {0} 与 {2} 重合。",
    },
    "slot": {"en": "the slot", "ru": "пазу", "uk": "пазу", "zh": "导槽"},
    "guide": {"en": "the guide of link {0}", "ru": "направляющей звена {0}", "uk": "напрямної ланки {0}",
              "zh": "构件 {0} 的导路"},
    "perp": {"en": "⊥ {0}", "ru": "⊥ {0}", "uk": "⊥ {0}", "zh": "⊥ {0}"},
    "parallel": {"en": "∥ {0}", "ru": "∥ {0}", "uk": "∥ {0}", "zh": "∥ {0}"},
    "sense_of": {
        "en": " in the sense of {0}", "ru": " в сторону {0}", "uk": " у бік {0}", "zh": "，沿 {0} 的转向",
    },
    "along_to": {
        "en": "∥ {0}, from {1} towards {2}", "ru": "∥ {0}, от точки {1} к точке {2}",
        "uk": "∥ {0}, від точки {1} до точки {2}", "zh": "∥ {0}，由 {1} 指向 {2}",
    },
    "triad_special": {
        "en": "Assur's special point {0} of link {1}: the crossing of the lines of leads {2} and {3}, taken as a "
              "point of link {1}.",
        "ru": "Особая точка Ассура {0} звена {1}: пересечение линий поводков {2} и {3}, рассматриваемое как точка "
              "звена {1}.",
        "uk": "Особлива точка Ассура {0} ланки {1}: перетин ліній повідців {2} і {3}, що розглядається як точка "
              "ланки {1}.",
        "zh": "阿苏尔特殊点 {0}（构件 {1}）：杆 {2} 与杆 {3} 所在直线的交点，视为构件 {1} 上的点。",
    },
    "triad_special_of": {
        "en": "Assur's special point {0} of link {1}: the crossing of {2} and {3}, taken as a point of link {1}.",
        "ru": "Особая точка Ассура {0} звена {1}: пересечение {2} и {3}, рассматриваемое как точка звена {1}.",
        "uk": "Особлива точка Ассура {0} ланки {1}: перетин {2} і {3}, що розглядається як точка ланки {1}.",
        "zh": "阿苏尔特殊点 {0}（构件 {1}）：{2}与{3}的交点，视为构件 {1} 上的点。",
    },
    "triad_line": {"en": "the line of lead {0}", "ru": "линии поводка {0}", "uk": "лінії повідця {0}",
                   "zh": "杆 {0} 所在直线"},
    "triad_normal": {"en": "the normal to the guide of lead {0} through {1}",
                     "ru": "нормали к направляющей поводка {0} в точке {1}",
                     "uk": "нормалі до напрямної повідця {0} у точці {1}", "zh": "过 {1} 的杆 {0} 导路法线"},
    "triad_lead": {
        "en": "{0} lies on the line of lead {2}, so {3}, the unknown terms {4}.",
        "ru": "Точка {0} лежит на линии поводка {2}, поэтому {3}, неизвестные слагаемые {4}.",
        "uk": "Точка {0} лежить на лінії повідця {2}, тому {3}, невідомі доданки {4}.",
        "zh": "{0} 位于杆 {2} 所在直线上，故 {3}，未知分量 {4}。",
    },
    "triad_block": {
        "en": "{0} lies on the normal to the guide of lead {2} through {5}, so {3}, the unknown terms {4}.",
        "ru": "Точка {0} лежит на нормали к направляющей поводка {2} в точке {5}, поэтому {3}, неизвестные "
              "слагаемые {4}.",
        "uk": "Точка {0} лежить на нормалі до напрямної повідця {2} у точці {5}, тому {3}, невідомі доданки {4}.",
        "zh": "{0} 位于过 {5} 的杆 {2} 导路法线上，故 {3}，未知分量 {4}。",
    },
    "triad_joint": {
        "en": "The joint {0} of link {1} and lead {2}: {3}.",
        "ru": "Шарнир {0} звена {1} и поводка {2}: {3}.",
        "uk": "Шарнір {0} ланки {1} і повідця {2}: {3}.",
        "zh": "构件 {1} 与杆 {2} 的铰链 {0}：{3}。",
    },
    "triad_image": {
        "en": "{0} is the image of Assur's special point {1} of link {2}.",
        "ru": "{0} — изображение особой точки Ассура {1} звена {2}.",
        "uk": "{0} — зображення особливої точки Ассура {1} ланки {2}.",
        "zh": "{0} 即构件 {2} 的阿苏尔特殊点 {1} 的影像。",
    },
    "triad_centre": {
        "en": "Both lines pass through the pole: {2} = 0, {0} is the instant centre of velocities of link {1}.",
        "ru": "Обе прямые проходят через полюс: {2} = 0, {0} — мгновенный центр скоростей звена {1}.",
        "uk": "Обидві прямі проходять через полюс: {2} = 0, {0} — миттєвий центр швидкостей ланки {1}.",
        "zh": "两直线均过极点：{2} = 0，{0} 为构件 {1} 的速度瞬心。",
    },
    "v_rel": {"en": "V_rel", "ru": "V_отн", "uk": "V_відн", "zh": "V_rel"},
    "coriolis_dir": {
        "en": "along {1} turned 90° in the sense of {0}",
        "ru": "по {1}, повёрнутой на 90° в сторону {0}",
        "uk": "за {1}, поверненою на 90° у бік {0}",
        "zh": "沿相对速度按 {0} 转向转 90°",
    },
}

_PHRASES.update({
    "mode_exact": {"en": "exact", "ru": "точно", "uk": "точно", "zh": "精确"},
    "mode_drafting": {"en": "drafted", "ru": "с точностью чертежа", "uk": "з точністю креслення", "zh": "按作图精度"},
    "evaluated": {"en": "evaluated steps: {0}", "ru": "выполнено шагов: {0}", "uk": "виконано кроків: {0}",
                  "zh": "已完成步骤：{0}"},
    "flagged": {
        "en": "flagged: the lines at {0} meet at sin = {1}; the image may be off by {2}",
        "ru": "предупреждение: прямые в точке {0} пересекаются под углом с синусом {1}; погрешность изображения до {2}",
        "uk": "попередження: прямі в точці {0} перетинаються під кутом із синусом {1}; похибка зображення до {2}",
        "zh": "警告：{0} 处两直线夹角正弦 {1}；影像误差可达 {2}",
    },
    "refused": {
        "en": "refused: the lines at {0} meet at sin = {1}; the image may be off by {2}",
        "ru": "не построено: прямые в точке {0} пересекаются под углом с синусом {1}; погрешность изображения до {2}",
        "uk": "не побудовано: прямі в точці {0} перетинаються під кутом із синусом {1}; похибка зображення до {2}",
        "zh": "未作出：{0} 处两直线夹角正弦 {1}；影像误差可达 {2}",
    },
})

_UNITS = {
    "v": {"en": "m/s", "ru": "м/с", "uk": "м/с", "zh": "m/s"},
    "a": {"en": "m/s²", "ru": "м/с²", "uk": "м/с²", "zh": "m/s²"},
    "ω": {"en": "rad/s", "ru": "рад/с", "uk": "рад/с", "zh": "rad/s"},
    "ε": {"en": "rad/s²", "ru": "рад/с²", "uk": "рад/с²", "zh": "rad/s²"},
    "μv": {"en": "(m/s)/mm", "ru": "(м/с)/мм", "uk": "(м/с)/мм", "zh": "(m/s)/mm"},
    "μa": {"en": "(m/s²)/mm", "ru": "(м/с²)/мм", "uk": "(м/с²)/мм", "zh": "(m/s²)/mm"},
    "deg": {"en": "°", "ru": "°", "uk": "°", "zh": "°"},
    "mm": {"en": "mm", "ru": "мм", "uk": "мм", "zh": "mm"},
}


def check_lang(lang: str) -> Language:
    if lang not in LANGS:
        raise VelplanError(f"unknown language {lang!r}; known languages: {', '.join(LANGS)}")
    return cast(Language, lang)


@dataclass(frozen=True)
class Sym:
    """A symbol in a sentence, marked so that each output sets it in its own notation: ``text``
    is what every plain-text output prints (``O3A``, ``pa4``, ``π``, ``x–x``, ``V_A4A``,
    ``aⁿ_AO2``, ``ω2``); ``kind`` says how it is built: ``"points"`` (point or image names side
    by side: a point, a link's line, a segment of a plan), ``"vector"`` (a letter, its mark and
    its index after "_"), ``"rate"`` (ω or ε and its link). The note sets it as a formula
    (`velplan.note.prose.sym_tex`)."""

    text: str
    kind: str = "points"

    def __str__(self) -> str:
        return self.text

    def __format__(self, spec: str) -> str:
        return format(self.text, spec)


class Sentence(str):
    """Text of a sentence as every plain-text output prints it (a ``str``) that keeps its
    ``parts``: plain strings and the `Sym` in it, in order.

    >>> s = text("Through ", Sym("a"), " draw ", Sym("O3A"))
    >>> s, s.parts
    ('Through a draw O3A', ('Through ', Sym(text='a', kind='points'), ' draw ', Sym(text='O3A', kind='points')))
    """

    parts: tuple

    def __new__(cls, parts) -> "Sentence":
        flat: list = []
        for piece in parts:
            for x in (piece.parts if isinstance(piece, Sentence) else (piece,)):
                if not isinstance(x, Sym):
                    x = str(x)
                    if not x:
                        continue
                    if flat and isinstance(flat[-1], str):
                        flat[-1] += x
                        continue
                flat.append(x)
        out = super().__new__(cls, "".join(str(x) for x in flat))
        out.parts = tuple(flat)
        return out

    def __add__(self, other) -> "Sentence":
        return text(self, other)

    def __radd__(self, other) -> "Sentence":
        return text(other, self)


def text(*pieces) -> Sentence:
    """Pieces (str, `Sym`, `Sentence`) written one after another, their symbols kept."""
    return Sentence(pieces)


def joined(sep: str, pieces) -> Sentence:
    """``pieces`` with ``sep`` between them (``", ".join`` keeping the symbols)."""
    out: list = []
    for k, x in enumerate(pieces):
        out += [sep, x] if k else [x]
    return Sentence(out)


def pts(name: str) -> Sym:
    """Point or image names side by side (``a``, ``pa4``, ``O3A``, ``x–x``) as a symbol."""
    return Sym(name, "points")


def vector(sym: str) -> Sym:
    """A component or vector symbol (``V_A4A``, ``aⁿ_AO2``, ``V_отн``) as a symbol."""
    return Sym(sym, "vector")


def rate(letter: str, link: str) -> Sym:
    """ω or ε of ``link`` (``ω2``) as a symbol."""
    return Sym(f"{letter}{link}", "rate")


def terminal(sentence: str) -> str:
    """``sentence`` as a terminal prints it: the digits of the point, image and segment names
    and of ω, ε that it marks as Unicode subscripts (``O₃A``, ``pa₄``, ``ω₂``); a vector keeps
    its index after "_" (``V_A4A``), numbers stay as they are.

    >>> terminal(text("Through ", pts("a4"), " ∥ ", pts("O3A"), " (", vector("V_A4A"), ") 2 ", rate("ω", "2")))
    'Through a₄ ∥ O₃A (V_A4A) 2 ω₂'
    """
    parts = sentence.parts if isinstance(sentence, Sentence) else (sentence,)
    return "".join(digits_down(x.text) if isinstance(x, Sym) and x.kind != "vector" else str(x)
                   for x in parts)


_FORMATTER = string.Formatter()


def phrase(key: str, lang: Language, *args) -> Sentence:
    """The sentence ``key`` in ``lang`` with ``args`` in its fields; a plain string whose
    ``parts`` keep each `Sym` argument a symbol (nested sentences spliced in)."""
    return formatted(_PHRASES[key][check_lang(lang)], *args)


def formatted(template: str, *args) -> Sentence:
    """``template`` (``str.format`` fields ``{0}``, ``{1:.3g}``) with ``args`` in its fields, each
    `Sym` or `Sentence` argument kept a symbol in the sentence's ``parts``.

    >>> formatted("{0} lies on {1} ({2:.2f})", pts("P13"), text(pts("P12"), "–", pts("P23")), 0.5).parts
    (Sym(text='P13', kind='points'), ' lies on ', Sym(text='P12', kind='points'), '–', Sym(text='P23', kind='points'), ' (0.50)')
    """
    out: list = []
    for literal, field, spec, conv in _FORMATTER.parse(template):
        out.append(literal)
        if field is not None:
            value = args[int(field)]
            out.append(value if isinstance(value, (Sym, Sentence)) or not (spec or conv)
                       else _FORMATTER.format_field(_FORMATTER.convert_field(value, conv), spec or ""))
    return Sentence(out)


def num(x: float, lang: Language, digits: int = 4) -> str:
    """A number to ``digits`` significant figures, with a decimal comma in ru and uk."""
    if not math.isfinite(x):
        return "—"
    return decimal(f"{x:.{digits}g}" if abs(x) >= 1e-3 or x == 0 else f"{x:.3e}", lang)


def signed(x: float, lang: Language, digits: int = 6) -> str:
    """`num` with the sign always written, the minus as "−" (U+2212)."""
    text = num(abs(x), lang, digits)
    return text if not math.isfinite(x) or x == 0 else (MINUS if x < 0 else "+") + text


def mm(x: float, lang: Language) -> str:
    """A length on the drawing, mm to 0.1 mm."""
    if not math.isfinite(x):
        return "—"
    return decimal(f"{x:.1f}", lang) + " " + _UNITS["mm"][lang]


def unit(plan: str, lang: Language) -> str:
    return _UNITS[plan][lang]


def seg(a: str, b: str) -> str:
    """A segment of the mechanism, named by its end points (``"CA"``)."""
    return f"{a}{b}"


def label_of(target: str) -> str:
    """The letter written on the drawing for a step target (``"v:c"`` → ``"c"``, poles p, π)."""
    return target.split(":", 1)[1]
