"""Drawing labels in the languages velplan writes sheets in.

A tiny, read-only dictionary: a key names the meaning (``"velocity_plan"``), the language
picks the words. Everything here is immutable; nothing is configured at import time.

Examples
--------
>>> label("velocity_plan", "ru")
'План скоростей'
>>> label("acceleration_plan", "zh")
'加速度多边形'
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Mapping, cast

from velplan.errors import VelplanError
from velplan.options import Language, LANGUAGES



def _entry(en: str, ru: str, uk: str, zh: str) -> Mapping[str, str]:
    return MappingProxyType({"en": en, "ru": ru, "uk": uk, "zh": zh})


_LABELS: Mapping[str, Mapping[str, str]] = MappingProxyType({
    # Views and their captions.
    "velocity_plan": _entry("Velocity plan", "План скоростей", "План швидкостей", "速度多边形"),
    "acceleration_plan": _entry("Acceleration plan", "План ускорений", "План прискорень",
                                "加速度多边形"),
    "velocity_diagram": _entry("Velocity diagram", "Диаграмма скоростей",
                               "Діаграма швидкостей", "速度图"),
    "title_mechanism": _entry("Kinematic scheme of the mechanism",
                              "Кинематическая схема механизма",
                              "Кінематична схема механізму", "机构运动简图"),
    "position": _entry("Position", "Положение", "Положення", "位置"),
    "positions": _entry("Positions", "Положения", "Положення", "位置"),
    "trajectory": _entry("Trajectory", "Траектория", "Траєкторія", "轨迹"),
    "pole": _entry("Pole", "Полюс", "Полюс", "极点"),
    "scale": _entry("Scale", "Масштаб", "Масштаб", "比例"),
    "scale_label": _entry("Scale factor", "Масштабный коэффициент", "Масштабний коефіцієнт",
                          "比例尺"),
    "table_transfer": _entry("Transfer functions", "Передаточные функции",
                             "Передавальні функції", "类速度表"),
    "mass": _entry("Mass", "Масса", "Маса", "质量"),
    # Sheet views (velplan.sheets.kinematic): the scheme, plans, diagrams, tables, steps.
    "kinematic_analysis": _entry("Kinematic analysis of the mechanism",
                                 "Кинематический анализ механизма",
                                 "Кінематичний аналіз механізму", "机构运动分析"),
    "mechanism_positions": _entry("Mechanism in its positions", "План положений механизма",
                                  "План положень механізму", "机构位置图"),
    "plan_positions_bold": _entry("the plans' positions (thick lines)",
                                  "положения планов (толстые линии)",
                                  "положення планів (товсті лінії)", "作图位置(粗实线)"),
    "displacement_diagram": _entry("Displacement diagram", "Диаграмма перемещений",
                                   "Діаграма переміщень", "位移线图"),
    "acceleration_diagram": _entry("Acceleration diagram", "Диаграмма ускорений",
                                   "Діаграма прискорень", "加速度线图"),
    "velocity_analogue_diagram": _entry("Diagram of the velocity analogue", "Диаграмма аналога скорости",
                                        "Діаграма аналога швидкості", "类速度线图"),
    "acceleration_analogue_diagram": _entry("Diagram of the acceleration analogue",
                                            "Диаграмма аналога ускорения",
                                            "Діаграма аналога прискорення", "类加速度线图"),
    "analytic": _entry("analytic", "аналитически", "аналітично", "解析法"),
    "chord_method": _entry("chord method", "метод хорд", "метод хорд", "弦线法"),
    "error": _entry("error", "погрешность", "похибка", "误差"),
    "crank_angle": _entry("crank angle", "угол поворота кривошипа", "кут повороту кривошипа",
                          "曲柄转角"),
    "position_short": _entry("pos.", "пол.", "пол.", "位置"),
    "quantity": _entry("Quantity", "Величина", "Величина", "参数"),
    "step": _entry("Step", "Шаг", "Крок", "步骤"),
    # The force-analysis sheet (velplan.sheets.forces); "{name}" is the group's name.
    "force_analysis": _entry("Force analysis of the mechanism", "Силовой анализ механизма",
                             "Силовий аналіз механізму", "机构力分析"),
    "assur_group": _entry("Assur group {name}", "Группа Ассура {name}", "Група Ассура {name}",
                          "杆组 {name}"),
    "initial_link": _entry("Initial link {name}", "Начальное звено {name}",
                           "Початкова ланка {name}", "原动件 {name}"),
    "force_plan_group": _entry("Force polygon of group {name}", "План сил группы {name}",
                               "План сил групи {name}", "杆组 {name} 力多边形"),
    "force_plan_crank": _entry("Force polygon of initial link {name}",
                               "План сил начального звена {name}",
                               "План сил початкової ланки {name}", "原动件 {name} 力多边形"),
    "forces_not_to_scale": _entry("forces on the groups and the lever not to scale",
                                  "силы на группах и рычаге — без масштаба",
                                  "сили на групах і важелі — без масштабу",
                                  "杆组和杠杆上的力不按比例"),
    "force_small": _entry("≈ 0 (< {mm} {unit} at μF):", "≈ 0 (< {mm} {unit} при μF):",
                          "≈ 0 (< {mm} {unit} при μF):", "≈ 0（μF 下 < {mm} {unit}）："),
    "zhukovsky_lever": _entry("Zhukovsky's lever", "Рычаг Жуковского", "Важіль Жуковського",
                              "茹科夫斯基杠杆"),
    "plan_turned": _entry("velocity plan turned by 90°", "план скоростей, повёрнутый на 90°",
                          "план швидкостей, повернутий на 90°", "速度多边形转过 90°"),
    "method_kinetostatics": _entry("kinetostatics", "кинетостатика", "кінетостатика",
                                   "动态静力法"),
    "method_lever": _entry("lever", "рычаг", "важіль", "杠杆法"),
    "method_power": _entry("power method", "метод мощностей", "метод потужностей", "功率法"),
    "balancing_moment": _entry("Balancing moment", "Уравновешивающий момент",
                               "Зрівноважувальний момент", "平衡力矩"),
    "balancing_moment_diagram": _entry("Balancing moment diagram",
                                       "Диаграмма уравновешивающего момента",
                                       "Діаграма зрівноважувального моменту", "平衡力矩线图"),
    "mean": _entry("mean", "среднее", "середнє", "平均值"),
    "symbol_balancing_moment": _entry("M_{b}", "M_{ур}", "M_{зр}", "M_{b}"),
    "symbol_balancing_force": _entry("F_{b}", "F_{ур}", "F_{зр}", "F_{b}"),
    "unit_newton": _entry("N", "Н", "Н", "N"),
    "unit_newton_metre": _entry("N·m", "Н·м", "Н·м", "N·m"),
    # The dynamics sheet (velplan.sheets.dynamics).
    "dynamic_analysis": _entry("Dynamic analysis of the machine", "Динамический анализ машины",
                               "Динамічний аналіз машини", "机器动力学分析"),
    "reduced_moments": _entry("Reduced moments", "Приведённые моменты", "Зведені моменти",
                              "等效力矩"),
    "works_energy": _entry("Works and the change of kinetic energy",
                           "Работы и изменение кинетической энергии",
                           "Роботи і зміна кінетичної енергії", "功与动能变化"),
    "reduced_inertia": _entry("Reduced moment of inertia (variable part)",
                              "Приведённый момент инерции (переменная часть)",
                              "Зведений момент інерції (змінна частина)", "等效转动惯量（变量部分）"),
    "energy_mass": _entry("Energy–mass diagram (Wittenbauer)", "Диаграмма энергомасс (Виттенбауэра)",
                          "Діаграма енергомас (Віттенбауера)", "能量—质量图（维滕鲍尔）"),
    "crank_speed": _entry("Angular velocity of the crank", "Угловая скорость кривошипа",
                          "Кутова швидкість кривошипа", "曲柄角速度"),
    "flywheel": _entry("Flywheel", "Маховик", "Маховик", "飞轮"),
    "dynamics_results": _entry("Results of the dynamic analysis",
                               "Результаты динамического анализа",
                               "Результати динамічного аналізу", "动力学分析结果"),
    "driving_moment": _entry("Driving moment", "Движущий момент", "Рушійний момент", "驱动力矩"),
    "resisting_moment": _entry("Moment of resistance", "Момент сопротивления", "Момент опору", "阻力矩"),
    "mean_speed": _entry("Mean angular velocity", "Средняя угловая скорость",
                         "Середня кутова швидкість", "平均角速度"),
    "delta_required": _entry("δ required", "δ заданный", "δ заданий", "δ 许用值"),
    "delta_obtained": _entry("δ obtained", "δ полученный", "δ отриманий", "δ 实际值"),
    "estimated_error": _entry("Error estimate", "Оценка погрешности", "Оцінка похибки", "误差估计"),
    "at_travel": _entry("at φ = {angle}", "при φ = {angle}", "при φ = {angle}", "φ = {angle} 处"),
    "method_exact": _entry("exact", "точно", "точно", "精确法"),
    "method_wittenbauer": _entry("Wittenbauer, computed", "Виттенбауэр, расчёт",
                                 "Віттенбауер, розрахунок", "维滕鲍尔法，计算"),
    "method_wittenbauer_drawn": _entry("Wittenbauer, drawn", "Виттенбауэр, по чертежу",
                                       "Віттенбауер, за кресленням", "维滕鲍尔法，图解"),
    "method_mertsalov": _entry("Mertsalov", "Мерцалов", "Мерцалов", "梅尔察洛夫法"),
    "declared_inertia": _entry("Constant inertias given", "Заданные постоянные моменты инерции",
                               "Задані сталі моменти інерції", "已有恒定惯量"),
    "flywheel_added": _entry("Flywheel, reduced to the crank", "Маховик, приведённый к кривошипу",
                             "Маховик, зведений до кривошипа", "飞轮（等效到曲柄）"),
    "flywheel_on_shaft": _entry("Flywheel on its shaft (u = {ratio})", "Маховик на своём валу (u = {ratio})",
                                "Маховик на своєму валу (u = {ratio})", "飞轮在其轴上（u = {ratio}）"),
    "no_flywheel": _entry("no flywheel needed", "маховик не нужен", "маховик не потрібен", "无需飞轮"),
    "density": _entry("density", "плотность", "густина", "密度"),
    "disc": _entry("disc", "диск", "диск", "圆盘"),
    "rim": _entry("rim", "обод", "обід", "轮缘"),
    "symbol_drive": _entry("d", "д", "р", "d"),
    "symbol_resist": _entry("r", "с", "о", "r"),
    "plan_readings": _entry("Read off the plans against the analytic values, lengths to",
                            "Значения по планам и аналитические, длины с точностью",
                            "Значення за планами та аналітичні, довжини з точністю",
                            "图解值与解析值，长度精度"),
    "input_data": _entry("Input data and results", "Исходные данные и результаты",
                         "Вихідні дані та результати", "原始数据与结果"),
    "extreme_positions": _entry("extreme positions", "крайние положения", "крайні положення", "极限位置"),
    "working_stroke": _entry("working stroke", "рабочий ход", "робочий хід", "工作行程"),
    "value": _entry("Value", "Значение", "Значення", "数值"),
    "unit": _entry("Unit", "Ед. изм.", "Од. вим.", "单位"),
    "run": _entry("Run", "Разгон/выбег", "Розгін/вибіг", "运转过程"),
    # Title block (ESKD form 1 and the ISO-style variant).
    "title": _entry("Title", "Наименование", "Найменування", "图名"),
    "designation": _entry("Drawing No.", "Обозначение", "Позначення", "图号"),
    "organisation": _entry("Organisation", "Организация", "Організація", "单位"),
    "material": _entry("Material", "Материал", "Матеріал", "材料"),
    "designed": _entry("Designed", "Разраб.", "Розроб.", "设计"),
    "checked": _entry("Checked", "Пров.", "Перев.", "审核"),
    "tech_control": _entry("Tech. ctrl", "Т.контр.", "Т.контр.", "工艺"),
    "norm_control": _entry("Std. ctrl", "Н.контр.", "Н.контр.", "标准化"),
    "approved": _entry("Approved", "Утв.", "Затв.", "批准"),
    "change": _entry("Rev.", "Изм.", "Змн.", "标记"),
    "sheet_short": _entry("Sheet", "Лист", "Арк.", "页"),
    "document_no": _entry("Doc. No.", "№ докум.", "№ докум.", "文件号"),
    "signature": _entry("Sign.", "Подп.", "Підпис", "签名"),
    "date": _entry("Date", "Дата", "Дата", "日期"),
    "literal": _entry("Lit.", "Лит.", "Літ.", "阶段"),
    "sheet": _entry("Sheet", "Лист", "Аркуш", "张次"),
    "sheets": _entry("Sheets", "Листов", "Аркушів", "总张数"),
    # The structural analysis (velplan info --svg): the initial mechanism and the groups apart.
    "structural_analysis": _entry("Structural analysis of the mechanism", "Структурный анализ механизма",
                                  "Структурний аналіз механізму", "机构结构分析"),
    "initial_mechanism": _entry("Initial mechanism, class I", "Начальный механизм I класса",
                                "Початковий механізм I класу", "I级机构（原动件与机架）"),
    "group_class": _entry("Group of class {cls}, order {order}", "Группа {cls} класса, {order} порядка",
                          "Група {cls} класу, {order} порядку", "{cls}级{order}阶杆组"),
    "outer_pairs": _entry("outer pairs", "внешние пары", "зовнішні пари", "外副"),
    "structure_formula": _entry("Formula of structure", "Формула строения", "Формула будови", "结构式"),
})


def check_language(lang: str) -> Language:
    """Return `lang` if velplan has labels for it, else raise.

    Parameters
    ----------
    lang : str
        Language code, one of :data:`LANGUAGES`.

    Raises
    ------
    VelplanError
        For an unknown language; the message lists the known ones.
    """
    if lang not in LANGUAGES:
        raise VelplanError(
            f"unknown language {lang!r}; known languages: {', '.join(LANGUAGES)}")
    return cast(Language, lang)


def label(key: str, lang: Language) -> str:
    """Return the drawing label `key` in language `lang`.

    Parameters
    ----------
    key : str
        Meaning of the label, e.g. ``"velocity_plan"``; see :func:`label_keys`.
    lang : {"en", "ru", "uk", "zh"}
        Language of the sheet.

    Returns
    -------
    str
        The label text.

    Raises
    ------
    VelplanError
        For an unknown language (the message lists the known ones) or an unknown key.
    """
    check_language(lang)
    try:
        return _LABELS[key][lang]
    except KeyError:
        raise VelplanError(
            f"unknown label key {key!r}; known keys: {', '.join(label_keys())}") from None


def label_keys() -> tuple[str, ...]:
    """Return every label key, sorted."""
    return tuple(sorted(_LABELS))


#: The words of the instant centres' figure and table, in the four languages ("{0}"… the values
#: they carry).
_CENTRES: Mapping[str, Mapping[str, str]] = {
    "title": _entry("Instant centres of velocity", "Мгновенные центры скоростей",
                    "Миттєві центри швидкостей", "速度瞬心"),
    "position": _entry("position", "положение", "положення", "位置"),
    "circle": _entry("Circle diagram", "Круговая диаграмма", "Кругова діаграма", "瞬心多边形"),
    "found": _entry("found {0} of {1}", "найдено {0} из {1}", "знайдено {0} з {1}", "已求得 {0}/{1}"),
    "off": _entry("off the drawing", "вне чертежа", "поза кресленням", "在图外"),
    "metre": _entry("m", "м", "м", "m"),
    "vertical": _entry("at infinity, vertically", "в бесконечности по вертикали",
                       "у нескінченності по вертикалі", "在竖直方向的无穷远处"),
    "horizontal": _entry("at infinity, horizontally", "в бесконечности по горизонтали",
                         "у нескінченності по горизонталі", "在水平方向的无穷远处"),
    "inclined": _entry("at infinity, along the line at {0}° to the horizontal",
                       "в бесконечности по прямой под углом {0}° к горизонтали",
                       "у нескінченності по прямій під кутом {0}° до горизонталі",
                       "在与水平线成 {0}° 的方向的无穷远处"),
    "not_reached": _entry("not reached", "не найден", "не знайдено", "未求得"),
    "head": _entry("instant centres", "мгновенные центры скоростей", "миттєві центри швидкостей", "速度瞬心"),
    "exact": _entry("exact", "точно", "точно", "精确"),
    "drafting": _entry("drafted", "с точностью чертежа", "з точністю креслення", "按作图精度"),
    "centre": _entry("centre", "центр", "центр", "瞬心"),
    "construction": _entry("construction", "построение", "побудова", "作法"),
    "joint": _entry("joint {0}", "шарнир {0}", "шарнір {0}", "铰链 {0}"),
    "hinge": _entry("hinge {0}", "сложный шарнир {0}", "складний шарнір {0}", "复合铰链 {0}"),
    "slider": _entry("slider ⊥ guide at {0}", "ползун: ⊥ направляющей в {0}",
                     "повзун: ⊥ напрямної в {0}", "滑块：在 {0} 处 ⊥ 导路"),
    "kennedy": _entry("Kennedy via {0}, {1} (sin {2})", "Кеннеди через {0}, {1} (sin {2})",
                      "Кеннеді через {0}, {1} (sin {2})", "经 {0}、{1} 的肯尼迪线（sin {2}）"),
    "not_reached_at": _entry("not reached: {0}", "не найден: {0}", "не знайдено: {0}", "未求得：{0}"),
    "circle_found": _entry("circle diagram: {0} of {1} centres found",
                           "круговая диаграмма: найдено {0} из {1} центров",
                           "кругова діаграма: знайдено {0} з {1} центрів",
                           "瞬心多边形：已求得 {0}/{1}"),
    "velocities": _entry("velocities by centres, off the plan and analytic (|v| m/s, ω rad/s)",
                         "скорости по центрам, по плану и аналитически (|v| м/с, ω рад/с)",
                         "швидкості за центрами, за планом і аналітично (|v| м/с, ω рад/с)",
                         "由瞬心、速度多边形与解析法所得速度（|v| m/s，ω rad/s）"),
    "quantity": _entry("quantity", "величина", "величина", "量"),
    "by_centres": _entry("centres", "по центрам", "за центрами", "瞬心法"),
    "plan": _entry("plan", "по плану", "за планом", "速度多边形"),
    "analytic": _entry("analytic", "аналит.", "аналіт.", "解析"),
    "err_centres": _entry("err centres", "погр. центр.", "похиб. центр.", "瞬心法误差"),
    "err_plan": _entry("err plan", "погр. плана", "похиб. плану", "多边形误差"),
}


def centres_words(key: str, lang: Language, *args) -> str:
    """The instant centres' words `key` in `lang`, with `args` put in their places."""
    return _CENTRES[key][lang].format(*args)
