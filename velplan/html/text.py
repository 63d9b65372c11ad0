"""Words of the interactive page, and the worked-solution sentences stored as templates.

A sentence of the worked solution changes from one crank position to the next only in its
numbers ("pa = 26,9 мм …"): each step's sentences are stored once per distinct wording, with
the numbers that do change kept per position.
"""

from __future__ import annotations

import re

from velplan.options import Language
from velplan.render.i18n import label

#: Words of the page that the drawing labels (`velplan.render.i18n`) do not have.
_WORDS: dict[str, dict[str, str]] = {
    "page_title": {"en": "Velocity and acceleration plans", "ru": "Планы скоростей и ускорений",
                   "uk": "Плани швидкостей і прискорень", "zh": "速度与加速度多边形"},
    "play": {"en": "Play", "ru": "Пуск", "uk": "Пуск", "zh": "播放"},
    "pause": {"en": "Pause", "ru": "Пауза", "uk": "Пауза", "zh": "暂停"},
    "first": {"en": "First step", "ru": "Первый шаг", "uk": "Перший крок", "zh": "第一步"},
    "previous": {"en": "Previous step", "ru": "Предыдущий шаг", "uk": "Попередній крок", "zh": "上一步"},
    "next": {"en": "Next step", "ru": "Следующий шаг", "uk": "Наступний крок", "zh": "下一步"},
    "complete": {"en": "Complete plans", "ru": "Планы целиком", "uk": "Плани повністю", "zh": "完整多边形"},
    "complete_hint": {"en": "Both plans are complete. Press “Next step” to build them one step at a time.",
                      "ru": "Оба плана построены. Нажмите «Следующий шаг», чтобы строить их по шагам.",
                      "uk": "Обидва плани побудовано. Натисніть «Наступний крок», щоб будувати їх по кроках.",
                      "zh": "两个多边形已完成。按“下一步”逐步作图。"},
    "drafted": {"en": "drafted", "ru": "графически", "uk": "графічно", "zh": "图解法"},
    "drafting_note": {"en": "drafted: read off the plan drawn to {mm} mm and {deg}° at the page's scale",
                      "ru": "графически: по плану, построенному с точностью {mm} мм и {deg}° в масштабе страницы",
                      "uk": "графічно: за планом, побудованим з точністю {mm} мм і {deg}° у масштабі сторінки",
                      "zh": "图解法：按本页比例尺、以 {mm} mm 和 {deg}° 的精度作图后量取"},
    "not_assembled": {"en": "The mechanism cannot be assembled in this position.",
                      "ru": "В этом положении механизм не собирается.",
                      "uk": "У цьому положенні механізм не збирається.",
                      "zh": "机构在此位置无法装配。"},
    "no_value": {"en": "this step fixes a direction only", "ru": "шаг задаёт только направление",
                 "uk": "крок задає лише напрям", "zh": "此步只确定方向"},
    "fixed_frame": {"en": "plans in one frame for the whole turn", "ru": "планы в одной рамке на весь оборот",
                    "uk": "плани в одній рамці на весь оберт", "zh": "整周使用同一视框"},
    "positions": {"en": "positions", "ru": "положений", "uk": "положень", "zh": "个位置"},
}


def word(key: str, lang: Language) -> str:
    """A word of the page in `lang` (en, ru, uk, zh)."""
    return _WORDS[key][lang]


def page_words(lang: Language) -> dict[str, str]:
    """Every word the page's script writes, in `lang`: its own and the drawing labels."""
    out = {key: word(key, lang) for key in _WORDS}
    for key in ("velocity_plan", "acceleration_plan", "title_mechanism", "position", "step",
                "analytic", "error", "quantity", "crank_angle"):
        out[key] = label(key, lang)
    return out


_NUMBER = re.compile(r"-?\d+(?:[.,]\d+)*(?:e[-+]?\d+)?")
#: Marks a number of a template that changes with the position.
SLOT = "{}"


def templates(sentences: list[str | None]) -> tuple[list[str], list[list | None]]:
    """One step's sentences at every position → (templates, per position
    ``[template index, number, …]`` or None where there is no sentence).

    Numbers that are the same at every position sharing a wording stay in the template; the
    others are replaced by `SLOT` and kept, as written, per position.
    """
    groups: dict[tuple[str, ...], list[int]] = {}
    split: list[tuple[tuple[str, ...], list[str]] | None] = []
    for s in sentences:
        if s is None:
            split.append(None)
            continue
        if SLOT in s:
            raise ValueError(f"a sentence holds the template mark {SLOT!r}: {s!r}")
        parts = tuple(_NUMBER.split(s))
        split.append((parts, _NUMBER.findall(s)))
        groups.setdefault(parts, []).append(len(split) - 1)
    out_templates: list[str] = []
    varying: dict[tuple[str, ...], list[bool]] = {}
    index: dict[tuple[str, ...], int] = {}
    for parts, members in groups.items():
        numbers = [split[m][1] for m in members]
        vary = [len({n[j] for n in numbers}) > 1 for j in range(len(parts) - 1)]
        first = numbers[0]
        text = parts[0]
        for j, v in enumerate(vary):
            text += (SLOT if v else first[j]) + parts[j + 1]
        varying[parts], index[parts] = vary, len(out_templates)
        out_templates.append(text)
    rows: list[list | None] = []
    for entry in split:
        if entry is None:
            rows.append(None)
            continue
        parts, numbers = entry
        rows.append([index[parts]] + [n for n, v in zip(numbers, varying[parts]) if v])
    return out_templates, rows


def fill(template: str, numbers: list[str]) -> str:
    """The sentence of `template` with its slots filled (the page's script does the same)."""
    pieces = template.split(SLOT)
    return "".join(p + (numbers[j] if j < len(numbers) else "") for j, p in enumerate(pieces))
