"""Phrases of the explanatory note in en, ru, uk and zh (the step sentences, table cells and
units come from the sheets themselves: `velplan.plans.text`, `velplan.render.i18n`)."""

from __future__ import annotations

import re

from velplan.options import Language
from velplan.plans.text import check_lang

LANG_INDEX = {"en": 0, "ru": 1, "uk": 2, "zh": 3}

_P: dict[str, tuple[str, str, str, str]] = {
    "note": ("Explanatory note", "Расчётно-пояснительная записка", "Розрахунково-пояснювальна записка",
             "计算说明书"),
    "course": ("to the course project in the theory of machines and mechanisms",
               "к курсовому проекту по теории механизмов и машин",
               "до курсового проєкту з теорії механізмів і машин", "机械原理课程设计"),
    "topic": ("Analysis and synthesis of the {0}", "Исследование механизма: {0}",
              "Дослідження механізму: {0}", "{0}的分析与综合"),
    "organisation": ("Organisation", "Организация", "Організація", "单位"),
    "department": ("Department", "Кафедра", "Кафедра", "教研室"),
    "student": ("Student", "Выполнил студент", "Виконав студент", "学生"),
    "group": ("Group", "Группа", "Група", "班级"),
    "supervisor": ("Supervisor", "Руководитель", "Керівник", "指导教师"),
    "designation": ("Designation", "Обозначение", "Позначення", "代号"),
    "place_year": ("Place, year", "Город, год", "Місто, рік", "地点，年份"),
    "contents": ("Contents", "Содержание", "Зміст", "目录"),
    "figure": ("Figure", "Рисунок", "Рисунок", "图"),
    "table": ("Table", "Таблица", "Таблиця", "表"),
    "table_continued": ("Table {0} (continued)", "Продолжение таблицы {0}", "Продовження таблиці {0}", "续表 {0}"),
    "sec_data": ("Input data", "Исходные данные", "Вихідні дані", "原始数据"),
    "sec_structure": ("Structural analysis", "Структурный анализ механизма", "Структурний аналіз механізму",
                      "机构结构分析"),
    "sec_positions": ("Positions and extreme positions", "Планы положений и крайние положения",
                      "Плани положень і крайні положення", "机构位置与极限位置"),
    "sec_velocity": ("Velocity plan, position {0}", "План скоростей, положение {0}",
                     "План швидкостей, положення {0}", "速度图，位置 {0}"),
    "sec_acceleration": ("Acceleration plan, position {0}", "План ускорений, положение {0}",
                         "План прискорень, положення {0}", "加速度图，位置 {0}"),
    "sec_kinematics": ("Kinematic analysis", "Кинематический анализ", "Кінематичний аналіз", "运动分析"),
    "sec_analogues": ("Table of the velocity analogues", "Таблица аналогов скоростей",
                      "Таблиця аналогів швидкостей", "速度类比量表"),
    "sec_diagrams": ("Kinematic diagrams by the chord method", "Кинематические диаграммы, метод хорд",
                     "Кінематичні діаграми, метод хорд", "运动线图（弦线法）"),
    "sec_forces": ("Force analysis", "Силовой анализ", "Силовий аналіз", "力分析"),
    "sec_kinetostatics": ("Kinetostatics, position {0}", "Кинетостатика, положение {0}",
                          "Кінетостатика, положення {0}", "动态静力分析，位置 {0}"),
    "sec_group": ("Group {0} ({1})", "Группа {0} ({1})", "Група {0} ({1})", "杆组 {0}（{1}）"),
    "sec_crank": ("Initial link {0}", "Начальное звено {0}", "Початкова ланка {0}", "原动件 {0}"),
    "sec_lever": ("Zhukovsky's lever, position {0}", "Рычаг Жуковского, положение {0}",
                  "Важіль Жуковського, положення {0}", "茹科夫斯基杠杆，位置 {0}"),
    "sec_moments": ("Balancing moment by three methods", "Уравновешивающий момент тремя методами",
                    "Зрівноважувальний момент трьома методами", "三种方法求平衡力矩"),
    "sec_dynamics": ("Machine dynamics and the flywheel", "Динамика машины и маховик",
                     "Динаміка машини і маховик", "机器动力学与飞轮"),
    "links_pairs": ("The mechanism has n = {0} moving links and p₅ = {1} lower pairs, p₄ = {2} higher pairs; "
                    "its degree of freedom by Chebyshev's formula:",
                    "Механизм имеет n = {0} подвижных звеньев, p₅ = {1} низших и p₄ = {2} высших пар; "
                    "степень подвижности по формуле Чебышева:",
                    "Механізм має n = {0} рухомих ланок, p₅ = {1} нижчих і p₄ = {2} вищих пар; "
                    "ступінь вільності за формулою Чебишева:",
                    "机构有 n = {0} 个活动构件，p₅ = {1} 个低副，p₄ = {2} 个高副；按切比雪夫公式，自由度为："),
    "pairs_title": ("Kinematic pairs", "Кинематические пары", "Кінематичні пари", "运动副"),
    "class_head": ("Class, order", "Класс, порядок", "Клас, порядок", "级别、阶数"),
    "pairs_head": ("Pair", "Пара", "Пара", "运动副"),
    "kind_head": ("Kind", "Вид", "Вид", "类型"),
    "links_head": ("Links", "Звенья", "Ланки", "构件"),
    "group_head": ("Group", "Группа", "Група", "杆组"),
    "pair_R": ("revolute, class 5", "вращательная, 5 класса", "обертальна, 5 класу", "转动副，5级"),
    "pair_P": ("prismatic, class 5", "поступательная, 5 класса", "поступальна, 5 класу", "移动副，5级"),
    "groups_head": ("Assur groups", "Группы Ассура", "Групи Ассура", "阿苏尔杆组"),
    "class_order": ("class {0}, order {1}", "{0} класса, {1} порядка", "{0} класу, {1} порядку", "{0} 级，{1} 阶"),
    "formula": ("Formula of structure:", "Формула строения:", "Формула будови:", "结构式："),
    "mech_class": ("The mechanism is of class {0}.", "Механизм {0} класса.", "Механізм {0} класу.",
                   "该机构为 {0} 级机构。"),
    "scale_l": ("The scheme is drawn at μl = {0} m/mm ({1}); {2} positions of the crank from the "
                "extreme position, in the sense of ω{3}.",
                "Схема построена в масштабе μl = {0} м/мм ({1}); {2} положений кривошипа от крайнего "
                "положения в направлении ω{3}.",
                "Схему побудовано в масштабі μl = {0} м/мм ({1}); {2} положень кривошипа від крайнього "
                "положення в напрямі ω{3}.",
                "机构简图比例 μl = {0} m/mm（{1}）；自极限位置起沿 ω{3} 方向取曲柄 {2} 个位置。"),
    "scale_l_zero": ("The scheme is drawn at μl = {0} m/mm ({1}); {2} positions of the crank from φ = 0, "
                     "in the sense of ω{3}.",
                     "Схема построена в масштабе μl = {0} м/мм ({1}); {2} положений кривошипа от φ = 0 "
                     "в направлении ω{3}.",
                     "Схему побудовано в масштабі μl = {0} м/мм ({1}); {2} положень кривошипа від φ = 0 "
                     "в напрямі ω{3}.",
                     "机构简图比例 μl = {0} m/mm（{1}）；自 φ = 0 起沿 ω{3} 方向取曲柄 {2} 个位置。"),
    "crank_angles": ("Crank angles of the positions", "Углы поворота кривошипа", "Кути повороту кривошипа",
                     "各位置曲柄转角"),
    "phi": ("crank angle φ, °", "угол φ, °", "кут φ, °", "转角 φ，°"),
    "stroke": ("The stroke, the angle between the extreme positions of the crank and the time-ratio "
               "coefficient:", "Ход выходного звена, угол перекрытия и коэффициент изменения средней "
               "скорости:", "Хід вихідної ланки, кут перекриття та коефіцієнт зміни середньої швидкості:",
               "输出构件行程、极位夹角与行程速比系数："),
    "scheme_fig": ("Scheme of the mechanism in its positions", "Схема механизма в положениях",
                   "Схема механізму в положеннях", "机构位置简图"),
    "plan_scale": ("The plan is drawn at the scale μ{0} = {1} {2} (the sheet's scale).",
                   "План построен в масштабе μ{0} = {1} {2} (масштаб листа).",
                   "План побудовано в масштабі μ{0} = {1} {2} (масштаб аркуша).",
                   "按图纸比例 μ{0} = {1} {2} 作图。"),
    "position_phi": ("Position {0}: crank angle φ = {1}°.", "Положение {0}: угол поворота кривошипа φ = {1}°.",
                     "Положення {0}: кут повороту кривошипа φ = {1}°.", "位置 {0}：曲柄转角 φ = {1}°。"),
    "step": ("Step {0}.", "Шаг {0}.", "Крок {0}.", "第 {0} 步。"),
    "angular": ("Angular velocities of the links (counter-clockwise positive):",
                "Угловые скорости звеньев (против часовой стрелки — положительные):",
                "Кутові швидкості ланок (проти годинникової стрілки — додатні):", "各构件角速度（逆时针为正）："),
    "angular_a": ("Angular accelerations of the links:", "Угловые ускорения звеньев:",
                  "Кутові прискорення ланок:", "各构件角加速度："),
    "ccw": ("counter-clockwise", "против часовой стрелки", "проти годинникової стрілки", "逆时针"),
    "cw": ("clockwise", "по часовой стрелке", "за годинниковою стрілкою", "顺时针"),
    "results_v": ("Velocities found (exact plan, four significant figures)",
                  "Найденные скорости (точный план, четыре значащие цифры)",
                  "Знайдені швидкості (точний план, чотири значущі цифри)", "所求速度（精确图，四位有效数字）"),
    "results_a": ("Accelerations found (exact plan, four significant figures)",
                  "Найденные ускорения (точный план, четыре значащие цифры)",
                  "Знайдені прискорення (точний план, чотири значущі цифри)", "所求加速度（精确图，四位有效数字）"),
    "quantity": ("Quantity", "Величина", "Величина", "量"),
    "value": ("Value", "Значение", "Значення", "数值"),
    "unit": ("Unit", "Ед. изм.", "Од. вим.", "单位"),
    "readings": ("Values read off the drawn plans (as on the sheet)",
                 "Значения, снятые с планов на листе", "Значення, зняті з планів на аркуші", "从图纸上量得的数值"),
    "readings_text": ("A draughtsman reads each vector to 0.5 mm; the table on the sheet gives these "
                      "readings beside the analytic values and their difference.",
                      "Каждый вектор измеряется на чертеже с точностью 0,5 мм; таблица листа сравнивает "
                      "эти значения с аналитическими.",
                      "Кожен вектор вимірюється на кресленні з точністю 0,5 мм; таблиця аркуша порівнює "
                      "ці значення з аналітичними.",
                      "各矢量在图上按 0.5 mm 精度量取；图纸上的表格将其与解析值比较。"),
    "read": ("read off the plan", "по плану", "за планом", "图上量得"),
    "analytic": ("analytic", "аналитически", "аналітично", "解析"),
    "plan_fig": ("{0}, position {1}", "{0}, положение {1}", "{0}, положення {1}", "{0}，位置 {1}"),
    "analogues_text": ("The analogues $V/\\omega_{{{0}}}$ (m) of the points and $\\omega/\\omega_{{{0}}}$ of the links are read off the "
                       "exact velocity plans of all positions (the table of the sheet).",
                       "Аналоги скоростей $V/\\omega_{{{0}}}$ (м) точек и $\\omega/\\omega_{{{0}}}$ звеньев сняты с точных планов скоростей "
                       "всех положений (таблица листа).",
                       "Аналоги швидкостей $V/\\omega_{{{0}}}$ (м) точок і $\\omega/\\omega_{{{0}}}$ ланок знято з точних планів швидкостей "
                       "усіх положень (таблиця аркуша).",
                       "各点速度类比量 $V/\\omega_{{{0}}}$（m）及各构件 $\\omega/\\omega_{{{0}}}$ 取自全部位置的精确速度图（图纸上的表）。"),
    "diagrams_text": ("The displacement diagram s(φ) of the output is plotted from the positions; "
                      "the velocity analogue and acceleration analogue diagrams follow from it by "
                      "graphical differentiation (the chord method): each chord of a curve is "
                      "replaced by a ray from the pole, and the ordinate it cuts is the derivative "
                      "at the middle of the interval. The analytic curves are drawn beside them.",
                      "Диаграмма перемещений s(φ) выходного звена построена по планам положений; "
                      "диаграммы аналогов скорости и ускорения получены графическим "
                      "дифференцированием (методом хорд): каждой хорде кривой соответствует луч из "
                      "полюса, отсекающий ординату производной в середине интервала. Рядом показаны "
                      "аналитические кривые.",
                      "Діаграму переміщень s(φ) вихідної ланки побудовано за планами положень; "
                      "діаграми аналогів швидкості та прискорення отримано графічним "
                      "диференціюванням (методом хорд): кожній хорді кривої відповідає промінь із "
                      "полюса, що відтинає ординату похідної в середині інтервалу. Поруч показано "
                      "аналітичні криві.",
                      "输出构件位移线图 s(φ) 由位置图作出；速度类比量和加速度类比量线图用图解微分法"
                      "（弦线法）求得：曲线的每条弦对应自极点引出的射线，其截取的纵坐标即区间中点的导数。"
                      "旁边给出解析曲线。"),
    "diagrams_fig": ("Kinematic diagrams of the output", "Кинематические диаграммы выходного звена",
                     "Кінематичні діаграми вихідної ланки", "输出构件运动线图"),
    "ks_intro": ("The groups are separated from the mechanism beginning with the one farthest from the "
                 "initial link; the inertia forces $\\Phi = -m\\,a_{{S}}$ and moments $M_{{\\Phi}} = -J_{{S}}\\,\\varepsilon$ are applied "
                 "with the weights and the loads (d'Alembert's principle), and each group's force "
                 "polygon is drawn.",
                 "Группы отделяются от механизма, начиная с наиболее удалённой от начального звена; "
                 "к звеньям прикладываются силы тяжести, внешние нагрузки, силы инерции $\\Phi = -m\\,a_{{S}}$ и "
                 "моменты сил инерции $M_{{\\Phi}} = -J_{{S}}\\,\\varepsilon$ (принцип Даламбера), для каждой группы строится "
                 "план сил.",
                 "Групи відокремлюються від механізму, починаючи з найвіддаленішої від початкової "
                 "ланки; до ланок прикладаються сили тяжіння, зовнішні навантаження, сили інерції "
                 "$\\Phi = -m\\,a_{{S}}$ і моменти сил інерції $M_{{\\Phi}} = -J_{{S}}\\,\\varepsilon$ (принцип Даламбера), для кожної групи "
                 "будується план сил.",
                 "从离原动件最远的杆组开始依次拆分；在各构件上施加重力、外载荷、惯性力 $\\Phi = -m\\,a_{{S}}$ 及惯性力矩 "
                 "$M_{{\\Phi}} = -J_{{S}}\\,\\varepsilon$（达朗贝尔原理），对每个杆组作力多边形。"),
    "known_forces": ("Forces known on the group:", "Известные силы, действующие на группу:",
                     "Відомі сили, що діють на групу:", "作用于杆组的已知力："),
    "equilibrium": ("Equation of equilibrium (the force polygon closes):",
                    "Уравнение равновесия (план сил замкнут):", "Рівняння рівноваги (план сил замкнений):",
                    "平衡方程（力多边形封闭）："),
    "polygon_scale": ("The polygon is drawn at μF = {0} N/mm; the reactions read off it:",
                      "План сил построен в масштабе μF = {0} Н/мм; найденные реакции:",
                      "План сил побудовано в масштабі μF = {0} Н/мм; знайдені реакції:",
                      "力多边形比例 μF = {0} N/mm；所求约束反力："),
    "group_fig": ("Group {0} and its force polygon", "Группа {0} и её план сил", "Група {0} та її план сил",
                  "杆组 {0} 及其力多边形"),
    "crank_fig": ("The initial link and its force polygon", "Начальное звено и его план сил",
                  "Початкова ланка та її план сил", "原动件及其力多边形"),
    "segment": ("segment", "отрезок", "відрізок", "线段"),
    "lever_text": ("The velocity plan turned by 90° is a lever about the pole; the forces are applied at "
                   "the images of their points, and the sum of their moments about the pole gives the "
                   "balancing force at the image of the crank tip:",
                   "Повёрнутый на 90° план скоростей рассматривается как рычаг с опорой в полюсе; силы "
                   "прикладываются в одноимённых точках плана, и из суммы моментов относительно полюса "
                   "находится уравновешивающая сила в точке кривошипа:",
                   "Повернутий на 90° план швидкостей розглядається як важіль з опорою в полюсі; сили "
                   "прикладаються в однойменних точках плану, і з суми моментів відносно полюса "
                   "знаходиться зрівноважувальна сила в точці кривошипа:",
                   "将速度图转过 90° 作为以极点为支点的杠杆；各力作用于其对应点的影像上，由对极点的力矩和"
                   "求得作用于曲柄端点影像上的平衡力："),
    "lever_arms": ("The arm hᵢ of each force is the perpendicular from the pole to its line of action, "
                   "measured on the lever (the velocity plan at μv = {0} (m/s)/mm turned by 90°); a force "
                   "turning the lever counter-clockwise counts positive:",
                   "Плечо hᵢ каждой силы — перпендикуляр из полюса на линию её действия, измеренный на "
                   "рычаге (план скоростей в масштабе μv = {0} (м/с)/мм, повёрнутый на 90°); момент, "
                   "поворачивающий рычаг против часовой стрелки, положителен:",
                   "Плече hᵢ кожної сили — перпендикуляр з полюса на лінію її дії, виміряний на важелі "
                   "(план швидкостей у масштабі μv = {0} (м/с)/мм, повернутий на 90°); момент, що "
                   "повертає важіль проти годинникової стрілки, додатний:",
                   "各力的力臂 hᵢ 为极点到其作用线的垂直距离，在杠杆（比例 μv = {0} (m/s)/mm 的速度图转过 90°）上量取；"
                   "使杠杆逆时针转动的力矩为正："),
    "lever_check": ("The lever against kinetostatics: ", "Сравнение с кинетостатикой: ",
                    "Порівняння з кінетостатикою: ", "与动态静力法比较："),
    "lever_table": ("Forces on the lever and their arms, position {0}", "Силы на рычаге и их плечи, положение {0}",
                    "Сили на важелі та їхні плечі, положення {0}", "杠杆上的力及其力臂，位置 {0}"),
    "lever_fig": ("Zhukovsky's lever, position {0}", "Рычаг Жуковского, положение {0}",
                  "Важіль Жуковського, положення {0}", "茹科夫斯基杠杆，位置 {0}"),
    "moments_text": ("The balancing moment found by kinetostatics, by Zhukovsky's lever and by the "
                     "power method $M_{{b}} = -\\sum P\\,V/\\omega_{{{0}}}$ at every position (the table of the sheet):",
                     "Уравновешивающий момент, найденный кинетостатикой, рычагом Жуковского и методом "
                     "мощностей $M_{{\\text{{ур}}}} = -\\sum P\\,V/\\omega_{{{0}}}$, во всех положениях (таблица листа):",
                     "Зрівноважувальний момент, знайдений кінетостатикою, важелем Жуковського та методом "
                     "потужностей $M_{{\\text{{зр}}}} = -\\sum P\\,V/\\omega_{{{0}}}$, в усіх положеннях (таблиця аркуша):",
                     "用动态静力法、茹科夫斯基杠杆法和功率法 $M_{{b}} = -\\sum P\\,V/\\omega_{{{0}}}$ 求得的各位置平衡力矩（图纸上的表）："),
    "mb_fig": ("Balancing moment over a turn", "Уравновешивающий момент за оборот",
               "Зрівноважувальний момент за оберт", "一周内的平衡力矩"),
    "dyn_intro": ("The links are replaced by a dynamic model on the crank: the reduced moment of inertia "
                  "$J_{{red}} = \\sum (m\\,V_{{S}}^{{2}} + J_{{S}}\\,\\omega^{{2}})/\\omega_{{{0}}}^{{2}}$ and the reduced moment $M_{{red}} = \\sum P\\,V/\\omega_{{{0}}}$ of the forces. "
                  "The work of the driving and of the resisting moments over a cycle gives the change of "
                  "kinetic energy, and the flywheel is sized for the coefficient of speed fluctuation δ.",
                  "Механизм заменяется динамической моделью на кривошипе: приведённый момент инерции "
                  "$J_{{\\text{{пр}}}} = \\sum (m\\,V_{{S}}^{{2}} + J_{{S}}\\,\\omega^{{2}})/\\omega_{{{0}}}^{{2}}$ и приведённый момент сил $M_{{\\text{{пр}}}} = \\sum P\\,V/\\omega_{{{0}}}$. Работы "
                  "движущих сил и сил сопротивления за цикл дают изменение кинетической энергии, по "
                  "которому маховик подбирается для заданного коэффициента неравномерности δ.",
                  "Механізм замінюється динамічною моделлю на кривошипі: зведений момент інерції "
                  "$J_{{\\text{{зв}}}} = \\sum (m\\,V_{{S}}^{{2}} + J_{{S}}\\,\\omega^{{2}})/\\omega_{{{0}}}^{{2}}$ і зведений момент сил $M_{{\\text{{зв}}}} = \\sum P\\,V/\\omega_{{{0}}}$. Роботи рушійних "
                  "сил і сил опору за цикл дають зміну кінетичної енергії, за якою маховик добирається "
                  "для заданого коефіцієнта нерівномірності δ.",
                  "将机构替换为曲柄上的等效动力学模型：等效转动惯量 $J_{{red}} = \\sum (m\\,V_{{S}}^{{2}} + J_{{S}}\\,\\omega^{{2}})/\\omega_{{{0}}}^{{2}}$，等效力矩 "
                  "$M_{{red}} = \\sum P\\,V/\\omega_{{{0}}}$。一个周期内驱动力矩与阻力矩之功给出动能变化，据此按速度波动系数 δ 设计飞轮。"),
    "flywheel_formula": ("The flywheel's moment of inertia from the largest change over the cycle of the "
                         "kinetic energy of the constant-inertia part, $\\Delta T_{{I}}$:",
                         "Момент инерции маховика по наибольшему за цикл изменению кинетической энергии "
                         "звеньев постоянного приведённого момента инерции $\\Delta T_{{I}}$:",
                         "Момент інерції маховика за найбільшою за цикл зміною кінетичної енергії ланок "
                         "сталого зведеного моменту інерції $\\Delta T_{{I}}$:",
                         "由一个周期内常量等效转动惯量部分动能的最大变化量 $\\Delta T_{{I}}$ 求飞轮转动惯量："),
    "dyn_results": ("Results of the dynamics (as on the sheet)", "Результаты динамического анализа (как на листе)",
                    "Результати динамічного аналізу (як на аркуші)", "动力学分析结果（同图纸）"),
    "dyn_fig": ("{0}", "{0}", "{0}", "{0}"),
    "sec_intro": ("Introduction", "Введение", "Вступ", "引言"),
    "sec_conclusion": ("Conclusion", "Заключение", "Висновки", "结论"),
    "sec_references": ("References", "Список использованных источников", "Список використаних джерел",
                       "参考文献"),
    "intro": ("The task of the course project is the study of the {0}: its structure, {1}. "
              "The initial data are those of the task (section 1); the methods follow the textbooks in the "
              "list of references, and every number is that of the drawing sheets.",
              "Задача курсового проекта — исследование механизма: {0}. Выполнены структурный анализ, {1}. "
              "Исходные данные взяты из задания (раздел 1); методы следуют учебникам из списка "
              "использованных источников, все числа совпадают с листами графической части.",
              "Завдання курсового проєкту — дослідження механізму: {0}. Виконано структурний аналіз, {1}. "
              "Вихідні дані взято із завдання (розділ 1); методи відповідають підручникам зі списку "
              "використаних джерел, усі числа збігаються з аркушами графічної частини.",
              "本课程设计的任务是研究{0}：结构分析、{1}。原始数据取自设计任务书（第1节）；方法依据参考文献中的教材，"
              "全部数值与图纸一致。"),
    "concl_structure": ("The mechanism has one degree of freedom W = {0} and is of class {1}.",
                        "Механизм имеет степень подвижности W = {0}, механизм {1} класса.",
                        "Механізм має ступінь вільності W = {0}, механізм {1} класу.",
                        "机构自由度 W = {0}，为 {1} 级机构。"),
    "concl_stroke": ("The stroke, the angle of overlap and the time-ratio coefficient: ",
                     "Ход выходного звена, угол перекрытия и коэффициент изменения средней скорости: ",
                     "Хід вихідної ланки, кут перекриття та коефіцієнт зміни середньої швидкості: ",
                     "输出构件行程、极位夹角与行程速比系数："),
    "concl_extremes": ("extreme positions at φ = {0}° and {1}°", "крайние положения при φ = {0}° и {1}°",
                       "крайні положення при φ = {0}° і {1}°", "极限位置 φ = {0}° 与 {1}°"),
    "concl_motor": ("Motor {0}, {1} kW, {2} rpm; the flywheel is recommended on its shaft: ",
                    "Электродвигатель {0}, {1} кВт, {2} об/мин; маховик рекомендуется установить на его вал: ",
                    "Електродвигун {0}, {1} кВт, {2} об/хв; маховик рекомендовано встановити на його вал: ",
                    "电动机 {0}，{1} kW，{2} r/min；建议将飞轮装在电动机轴上："),
    "concl_mb": ("Over a turn the balancing moment lies within ", "За оборот уравновешивающий момент изменяется в пределах ",
                 "За оберт зрівноважувальний момент змінюється в межах ", "一周内平衡力矩的范围为 "),
    "concl_flywheel": ("The flywheel on the crank shaft needs ", "Маховик на валу кривошипа должен иметь ",
                       "Маховик на валу кривошипа повинен мати ", "曲柄轴上的飞轮需要 "),
    "dyn_worked": ("The reduced moment of inertia of the links other than the crank at position {0} "
                   "(φ = {1}°), from the velocity analogues of the centres of mass and of the links:",
                   "Приведённый момент инерции звеньев, кроме кривошипа, в положении {0} (φ = {1}°) по "
                   "аналогам скоростей центров масс и звеньев:",
                   "Зведений момент інерції ланок, крім кривошипа, у положенні {0} (φ = {1}°) за "
                   "аналогами швидкостей центрів мас і ланок:",
                   "位置 {0}（φ = {1}°）除曲柄外各构件的等效转动惯量，由质心和构件的速度类比量求得："),
    "dyn_worked_m": ("The reduced moment of the loads and weights at the same position, each "
                     "$\\sum P\\,V\\cos\\alpha/\\omega_{{{0}}}$:",
                     "Приведённый момент сил сопротивления и тяжести в том же положении, каждый "
                     "$\\sum P\\,V\\cos\\alpha/\\omega_{{{0}}}$:",
                     "Зведений момент сил опору та тяжіння в тому самому положенні, кожен "
                     "$\\sum P\\,V\\cos\\alpha/\\omega_{{{0}}}$:",
                     "同一位置阻力与重力的等效力矩，各为 $\\sum P\\,V\\cos\\alpha/\\omega_{{{0}}}$："),
    "dyn_tables": ("The same quantities at every position, and the works and energies over the cycle "
                   "($\\Delta T_{{II}}$ the energy of the variable inertia, $\\Delta T_{{I}} = \\Delta T - \\Delta T_{{II}}$ "
                   "that of the constant inertia, from position 1):",
                   "Те же величины во всех положениях, работы и изменения энергии за цикл ($\\Delta T_{{II}}$ — "
                   "энергия переменной части приведённого момента инерции, $\\Delta T_{{I}} = \\Delta T - \\Delta T_{{II}}$ — "
                   "энергия постоянной части, от положения 1):",
                   "Ті самі величини в усіх положеннях, роботи та зміни енергії за цикл ($\\Delta T_{{II}}$ — енергія "
                   "змінної частини зведеного моменту інерції, $\\Delta T_{{I}} = \\Delta T - \\Delta T_{{II}}$ — "
                   "енергія сталої частини, від положення 1):",
                   "各位置的上述各量及一个周期内的功与能量变化（$\\Delta T_{{II}}$ 为变等效转动惯量部分的动能，"
                   "$\\Delta T_{{I}} = \\Delta T - \\Delta T_{{II}}$ 为常量部分的动能，自位置 1 起）："),
    "dyn_table_j": ("Reduced moment of inertia and reduced moments by position",
                    "Приведённый момент инерции и приведённые моменты по положениям",
                    "Зведений момент інерції та зведені моменти за положеннями", "各位置的等效转动惯量与等效力矩"),
    "dyn_table_t": ("Works and changes of kinetic energy by position", "Работы и изменения кинетической энергии по положениям",
                    "Роботи та зміни кінетичної енергії за положеннями", "各位置的功与动能变化"),
    "fly_none": ("The constant inertia already present is enough: no flywheel is needed.",
                 "Имеющегося постоянного момента инерции достаточно: маховик не нужен.",
                 "Наявного сталого моменту інерції досить: маховик не потрібен.", "已有的常量转动惯量足够，无需飞轮。"),
    "fly_shaft": ("On the motor's shaft, turning u = {0} times as fast as the crank (the drive's ratio), the "
                  "flywheel needs:",
                  "На валу двигателя, вращающемся в u = {0} раз быстрее кривошипа (передаточное отношение "
                  "привода), маховик должен иметь:",
                  "На валу двигуна, що обертається в u = {0} разів швидше за кривошип (передатне відношення "
                  "привода), маховик повинен мати:",
                  "安装在转速为曲柄 u = {0} 倍的电动机轴上（传动比）时，飞轮需要："),
    "fly_motor": ("The drive: motor {0}, {1} kW, {2} rpm (required power {3} kW).",
                  "Привод: электродвигатель {0}, {1} кВт, {2} об/мин (требуемая мощность {3} кВт).",
                  "Привід: електродвигун {0}, {1} кВт, {2} об/хв (потрібна потужність {3} кВт).",
                  "驱动：电动机 {0}，{1} kW，{2} r/min（所需功率 {3} kW）。"),
    "fly_motor_default": ("The task gives no drive; by the usual rules (the useful power of the working stroke "
                          "over the drive's efficiency, with a reserve) it needs {3} kW: motor {0}, {1} kW, {2} rpm.",
                          "Привод в задании не указан; по обычным правилам (полезная мощность рабочего хода, "
                          "КПД привода, запас) требуется {3} кВт: электродвигатель {0}, {1} кВт, {2} об/мин.",
                          "Привід у завданні не вказано; за звичайними правилами (корисна потужність робочого "
                          "ходу, ККД привода, запас) потрібно {3} кВт: електродвигун {0}, {1} кВт, {2} об/хв.",
                          "任务书未给出驱动；按常规方法（工作行程有效功率、传动效率及储备系数）所需功率 {3} kW："
                          "电动机 {0}，{1} kW，{2} r/min。"),
    "fly_recommend": ("The flywheel is recommended on the faster shaft: u² = {0} times less inertia, a "
                      "smaller and lighter wheel.",
                      "Маховик рекомендуется ставить на быстроходный вал: момент инерции в u² = {0} раз "
                      "меньше, маховик меньше и легче.",
                      "Маховик рекомендовано ставити на швидкохідний вал: момент інерції в u² = {0} разів "
                      "менший, маховик менший і легший.",
                      "建议将飞轮装在高速轴上：转动惯量减小为 1/u²（u² = {0}），飞轮更小更轻。"),
    "fly_crank_only": ("The drive's ratio is not given: the flywheel is sized for the crank shaft; on a faster "
                       "shaft it would need u² times less inertia.",
                       "Передаточное отношение привода не задано: маховик рассчитан на вал кривошипа; на "
                       "быстроходном валу его момент инерции был бы в u² раз меньше.",
                       "Передатне відношення привода не задано: маховик розраховано на вал кривошипа; на "
                       "швидкохідному валу його момент інерції був би в u² разів менший.",
                       "未给出传动比：飞轮按曲柄轴计算；装在高速轴上时转动惯量可减小为 1/u²。"),
    "turns_with": ("link {0} turns with link {1}", "звено {0} вращается вместе со звеном {1}",
                   "ланка {0} обертається разом з ланкою {1}", "构件 {0} 与构件 {1} 一起转动"),
    "left_out": ("left out: {0}", "не включено: {0}", "не включено: {0}", "未包括：{0}"),
}


def p(key: str, lang: Language, *args) -> str:
    """The phrase ``key`` in ``lang``, formatted with ``args``."""
    return _P[key][LANG_INDEX[check_lang(lang)]].format(*args)


def mechanism_of(name: str, lang: Language) -> str:
    """The mechanism a machine's name ``name`` calls for in the topic and the introduction:
    in en "mechanism of the shaping machine" but "offset crank-slider mechanism" (no
    "mechanism of the … mechanism"), in zh 牛头刨床机构 but 曲柄滑块机构; ru and uk name
    the machine after "механизма:"."""
    if lang == "en":
        return name if re.search(r"\b(mechanism|linkage)\b", name) else f"mechanism of the {name}"
    if lang == "zh":
        return name if name.endswith("机构") or "机构（" in name else name + "机构"
    return name


def direction(value: float, lang: Language) -> str:
    """The sense of a rotation: counter-clockwise for a positive value."""
    return p("ccw" if value > 0 else "cw", lang)


_PAIR_LETTERS = {"ru": {"R": "В", "P": "П"}, "uk": {"R": "О", "P": "П"}, "zh": {"R": "转", "P": "移"}}
_WORDS = {"triad": ("triad", "триада", "тріада", "三杆组"), "crank": ("crank", "кривошип", "кривошип", "曲柄"),
          "dyad": ("dyad", "диада", "діада", "二杆组")}


def group_kind(kind: str, lang: str) -> str:
    """A group's kind as the course of ``lang`` names it: a dyad by its pairs (RPR → ВПВ in
    ru, ОПО in uk, 转移转 in zh), a triad, the crank."""
    lang = check_lang(lang)
    if kind in _WORDS:
        return _WORDS[kind][LANG_INDEX[lang]]
    letters = _PAIR_LETTERS.get(lang)
    if letters and kind and set(kind) <= set(letters):
        return "".join(letters[c] for c in kind)
    return kind


def group_name(group: str, lang: str) -> str:
    """A group's name (``3-4``), or the crank's in words."""
    return group_kind(group, lang) if group in _WORDS else group


_BALANCING = {"ru": "ур", "uk": "зр"}


def balancing(letter: str, lang: str) -> str:
    """TeX of the balancing moment (``"M"``) or force (``"F"``) in the symbol the sheets of
    ``lang`` print (Mур in ru, Mзр in uk, M_b in en/zh): one symbol in text, tables and figures."""
    index = _BALANCING.get(check_lang(lang))
    return f"{letter}_{{\\text{{{index}}}}}" if index else f"{letter}_{{b}}"


def roman(n: int) -> str:
    """The class of a group or mechanism as the course writes it: 2 → II."""
    return {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI"}.get(int(n), str(n))
