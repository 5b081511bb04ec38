<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="ru_RU">
<context>
    <name>AdjustPage</name>
    <message>
        <source>Adjustment and monitoring</source>
        <translation>Настройка и контроль</translation>
    </message>
    <message>
        <source>Laser source</source>
        <translation>Лазерный источник</translation>
    </message>
    <message>
        <source>Power setpoint, %</source>
        <translation>Уставка мощности, %</translation>
    </message>
    <message>
        <source>Set power</source>
        <translation>Задать мощность</translation>
    </message>
    <message>
        <source>Emission</source>
        <translation>Излучение</translation>
    </message>
    <message>
        <source>Reset alarm</source>
        <translation>Сбросить аварию</translation>
    </message>
    <message>
        <source>State</source>
        <translation>Состояние</translation>
    </message>
    <message>
        <source>Output (monitor diode), W</source>
        <translation>Выход (контрольный диод), Вт</translation>
    </message>
    <message>
        <source>Pump diode, °C</source>
        <translation>Диод накачки, °C</translation>
    </message>
    <message>
        <source>Alarms</source>
        <translation>Аварии</translation>
    </message>
    <message>
        <source>Power monitoring</source>
        <translation>Контроль мощности</translation>
    </message>
    <message>
        <source>Measured power, W</source>
        <translation>Измеренная мощность, Вт</translation>
    </message>
    <message>
        <source>Zero the meter</source>
        <translation>Обнулить измеритель</translation>
    </message>
    <message>
        <source>Four-beam scanning head</source>
        <translation>Четырёхлучевая сканирующая головка</translation>
    </message>
    <message>
        <source>Start radius, mm</source>
        <translation>Начальный радиус, мм</translation>
    </message>
    <message>
        <source>End radius, mm</source>
        <translation>Конечный радиус, мм</translation>
    </message>
    <message>
        <source>Radius turns</source>
        <translation>Витков по радиусу</translation>
    </message>
    <message>
        <source>Scan speed, mm/s</source>
        <translation>Скорость сканирования, мм/с</translation>
    </message>
    <message>
        <source>Wedge speed, rpm</source>
        <translation>Скорость клиньев, об/мин</translation>
    </message>
    <message>
        <source>Beam offset, mm</source>
        <translation>Смещение луча, мм</translation>
    </message>
    <message>
        <source>Write parameters</source>
        <translation>Записать параметры</translation>
    </message>
    <message>
        <source>Run pattern</source>
        <translation>Запустить узор</translation>
    </message>
    <message>
        <source>Wedge speed now, rpm</source>
        <translation>Текущая скорость клиньев, об/мин</translation>
    </message>
    <message>
        <source>Radius now, mm</source>
        <translation>Текущий радиус, мм</translation>
    </message>
    <message>
        <source>Turns done</source>
        <translation>Выполнено витков</translation>
    </message>
</context>
<context>
    <name>CutPage</name>
    <message>
        <source>Laser cutting</source>
        <translation>Лазерная резка</translation>
    </message>
    <message>
        <source>Open DXF…</source>
        <translation>Открыть DXF…</translation>
    </message>
    <message>
        <source>no drawing</source>
        <translation>нет чертежа</translation>
    </message>
    <message>
        <source>Plan the cut</source>
        <translation>Рассчитать резку</translation>
    </message>
    <message>
        <source>Save G-code…</source>
        <translation>Сохранить G-код…</translation>
    </message>
    <message>
        <source>Load into the controller</source>
        <translation>Загрузить в контроллер</translation>
    </message>
    <message>
        <source>Cutting</source>
        <translation>Резка</translation>
    </message>
    <message>
        <source>Kerf, mm</source>
        <translation>Ширина реза, мм</translation>
    </message>
    <message>
        <source>Lead-in, mm</source>
        <translation>Врезка, мм</translation>
    </message>
    <message>
        <source>Lead-out, mm</source>
        <translation>Вывод, мм</translation>
    </message>
    <message>
        <source>Feed, mm/min</source>
        <translation>Подача, мм/мин</translation>
    </message>
    <message>
        <source>Power, %</source>
        <translation>Мощность, %</translation>
    </message>
    <message>
        <source>Pierce, s</source>
        <translation>Пробивка, с</translation>
    </message>
    <message>
        <source>Origin X, mm</source>
        <translation>Начало X, мм</translation>
    </message>
    <message>
        <source>Origin Y, mm</source>
        <translation>Начало Y, мм</translation>
    </message>
    <message>
        <source>Outline</source>
        <translation>Внешний контур</translation>
    </message>
    <message>
        <source>clockwise (holes counter-clockwise)</source>
        <translation>по часовой (отверстия — против)</translation>
    </message>
    <message>
        <source>counter-clockwise (holes clockwise)</source>
        <translation>против часовой (отверстия — по)</translation>
    </message>
    <message>
        <source>Units</source>
        <translation>Единицы</translation>
    </message>
    <message>
        <source>from the drawing</source>
        <translation>из чертежа</translation>
    </message>
    <message>
        <source>inch</source>
        <translation>дюйм</translation>
    </message>
</context>
<context>
    <name>DecompositionPage</name>
    <message>
        <source>Main + auxiliary axes</source>
        <translation>Основные + вспомогательные оси</translation>
    </message>
    <message>
        <source>Open DXF…</source>
        <translation>Открыть DXF…</translation>
    </message>
    <message>
        <source>no drawing</source>
        <translation>нет чертежа</translation>
    </message>
    <message>
        <source>Contour speed, m/min</source>
        <translation>Контурная скорость, м/мин</translation>
    </message>
    <message>
        <source>Step, mm</source>
        <translation>Шаг, мм</translation>
    </message>
    <message>
        <source>Aux field, mm</source>
        <translation>Поле вспом. осей, мм</translation>
    </message>
    <message>
        <source>Main accel, g</source>
        <translation>Ускорение осн. осей, g</translation>
    </message>
    <message>
        <source>synchronous</source>
        <translation>синхронный</translation>
    </message>
    <message>
        <source>published algorithm</source>
        <translation>исходный алгоритм</translation>
    </message>
    <message>
        <source>Decompose</source>
        <translation>Разложить</translation>
    </message>
    <message>
        <source>Export table…</source>
        <translation>Экспорт таблицы…</translation>
    </message>
    <message>
        <source>first entity</source>
        <translation>первый элемент</translation>
    </message>
    <message>
        <source>length mm</source>
        <translation>длина, мм</translation>
    </message>
    <message>
        <source>points</source>
        <translation>точки</translation>
    </message>
    <message>
        <source>time s</source>
        <translation>время, с</translation>
    </message>
    <message>
        <source>τ s</source>
        <translation>τ, с</translation>
    </message>
    <message>
        <source>main a mm/s²</source>
        <translation>осн. a, мм/с²</translation>
    </message>
    <message>
        <source>main v mm/s</source>
        <translation>осн. v, мм/с</translation>
    </message>
    <message>
        <source>aux v mm/s</source>
        <translation>доп. v, мм/с</translation>
    </message>
    <message>
        <source>aux max mm</source>
        <translation>доп. макс., мм</translation>
    </message>
    <message>
        <source>a_eff mm/s²</source>
        <translation>a_eff, мм/с²</translation>
    </message>
</context>
<context>
    <name>FocalPage</name>
    <message>
        <source>Focal length</source>
        <translation>Фокусное расстояние</translation>
    </message>
    <message>
        <source>Reload holes</source>
        <translation>Обновить отверстия</translation>
    </message>
    <message>
        <source>Select all</source>
        <translation>Выбрать все</translation>
    </message>
    <message>
        <source>Stand-off, mm</source>
        <translation>Расстояние до поверхности, мм</translation>
    </message>
    <message>
        <source>Measure selected</source>
        <translation>Измерить выбранные</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Отмена</translation>
    </message>
    <message>
        <source>Save offsets</source>
        <translation>Сохранить смещения</translation>
    </message>
</context>
<context>
    <name>HoleTableModel</name>
    <message>
        <source>Hole</source>
        <translation>Отверстие</translation>
    </message>
    <message>
        <source>X</source>
        <translation>X</translation>
    </message>
    <message>
        <source>Y</source>
        <translation>Y</translation>
    </message>
    <message>
        <source>Z</source>
        <translation>Z</translation>
    </message>
    <message>
        <source>A</source>
        <translation>A</translation>
    </message>
    <message>
        <source>C</source>
        <translation>C</translation>
    </message>
    <message>
        <source>Feed</source>
        <translation>Подача</translation>
    </message>
    <message>
        <source>Layer feed</source>
        <translation>Подача на слой</translation>
    </message>
    <message>
        <source>Layers</source>
        <translation>Слои</translation>
    </message>
    <message>
        <source>Depth</source>
        <translation>Глубина</translation>
    </message>
    <message>
        <source>Power</source>
        <translation>Мощность</translation>
    </message>
    <message>
        <source>Start radius</source>
        <translation>Начальный радиус</translation>
    </message>
    <message>
        <source>End radius</source>
        <translation>Конечный радиус</translation>
    </message>
    <message>
        <source>Radius turns</source>
        <translation>Витков по радиусу</translation>
    </message>
    <message>
        <source>Scan speed</source>
        <translation>Скорость сканирования</translation>
    </message>
    <message>
        <source>Wedge speed</source>
        <translation>Скорость клиньев</translation>
    </message>
    <message>
        <source>Beam offset</source>
        <translation>Смещение луча</translation>
    </message>
    <message>
        <source>Process</source>
        <translation>Процесс</translation>
    </message>
    <message>
        <source>Focus offset</source>
        <translation>Смещение фокуса</translation>
    </message>
</context>
<context>
    <name>MachinePage</name>
    <message>
        <source>Machine</source>
        <translation>Станок</translation>
    </message>
    <message>
        <source>Position</source>
        <translation>Положение</translation>
    </message>
    <message>
        <source>Cycle start</source>
        <translation>Пуск цикла</translation>
    </message>
    <message>
        <source>Feed hold</source>
        <translation>Останов подачи</translation>
    </message>
    <message>
        <source>Resume</source>
        <translation>Продолжить</translation>
    </message>
    <message>
        <source>Stop</source>
        <translation>Стоп</translation>
    </message>
    <message>
        <source>Feed override</source>
        <translation>Коррекция подачи</translation>
    </message>
    <message>
        <source>E-STOP</source>
        <translation>АВАР. СТОП</translation>
    </message>
    <message>
        <source>Reset</source>
        <translation>Сброс</translation>
    </message>
    <message>
        <source>idle</source>
        <translation>простой</translation>
    </message>
    <message>
        <source>running</source>
        <translation>работа</translation>
    </message>
    <message>
        <source>feed hold</source>
        <translation>останов подачи</translation>
    </message>
    <message>
        <source>stopping</source>
        <translation>остановка</translation>
    </message>
    <message>
        <source>e-stop</source>
        <translation>аварийный стоп</translation>
    </message>
    <message>
        <source>jog</source>
        <translation>толчок</translation>
    </message>
    <message>
        <source>homing</source>
        <translation>выход в ноль</translation>
    </message>
    <message>
        <source> mm/°</source>
        <translation> мм/°</translation>
    </message>
    <message>
        <source>Jog −</source>
        <translation>Толчок −</translation>
    </message>
    <message>
        <source>Jog +</source>
        <translation>Толчок +</translation>
    </message>
    <message>
        <source>Home axis</source>
        <translation>Ось в ноль</translation>
    </message>
    <message>
        <source>Alarms and events</source>
        <translation>Аварии и события</translation>
    </message>
    <message>
        <source>Clear the list</source>
        <translation>Очистить список</translation>
    </message>
    <message>
        <source>Work</source>
        <translation>Рабочие</translation>
    </message>
    <message>
        <source>Homed</source>
        <translation>Ноль</translation>
    </message>
    <message>
        <source>Work offsets</source>
        <translation>Смещения нуля</translation>
    </message>
    <message>
        <source>Work system</source>
        <translation>Система координат</translation>
    </message>
    <message>
        <source>Touch off</source>
        <translation>Привязка</translation>
    </message>
    <message>
        <source>Set here</source>
        <translation>Задать здесь</translation>
    </message>
    <message>
        <source>MDI</source>
        <translation>MDI</translation>
    </message>
    <message>
        <source>G-code, e.g. G1 X10 F600</source>
        <translation>G-код, напр. G1 X10 F600</translation>
    </message>
    <message>
        <source>Send</source>
        <translation>Отправить</translation>
    </message>
    <message>
        <source>Job</source>
        <translation>Задание</translation>
    </message>
    <message>
        <source>Single block</source>
        <translation>Покадрово</translation>
    </message>
    <message>
        <source>Dry run (laser off)</source>
        <translation>Пробный прогон (лазер выкл.)</translation>
    </message>
    <message>
        <source>From line</source>
        <translation>С строки</translation>
    </message>
    <message>
        <source>start</source>
        <translation>начало</translation>
    </message>
    <message>
        <source>Frame</source>
        <translation>Контур рамки</translation>
    </message>
    <message>
        <source>Acknowledge</source>
        <translation>Квитировать</translation>
    </message>
    <message>
        <source>To go</source>
        <translation>Осталось</translation>
    </message>
</context>
<context>
    <name>MeasurePage</name>
    <message>
        <source>3D measurement</source>
        <translation>3D-измерение</translation>
    </message>
    <message>
        <source>Block L, mm</source>
        <translation>Заготовка Д, мм</translation>
    </message>
    <message>
        <source>W</source>
        <translation>Ш</translation>
    </message>
    <message>
        <source>H</source>
        <translation>В</translation>
    </message>
    <message>
        <source>Nominal corner X</source>
        <translation>Номинальный угол X</translation>
    </message>
    <message>
        <source>Y</source>
        <translation>Y</translation>
    </message>
    <message>
        <source>Z</source>
        <translation>Z</translation>
    </message>
    <message>
        <source>turned, °</source>
        <translation>поворот, °</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Отмена</translation>
    </message>
    <message>
        <source>Apply to the holes…</source>
        <translation>Применить к отверстиям…</translation>
    </message>
    <message>
        <source>Best fit with four more points</source>
        <translation>Наилучшее приближение по четырём доп. точкам</translation>
    </message>
    <message>
        <source>Measure</source>
        <translation>Измерить</translation>
    </message>
    <message>
        <source>primary</source>
        <translation>основная</translation>
    </message>
    <message>
        <source>secondary</source>
        <translation>вторая</translation>
    </message>
    <message>
        <source>tertiary</source>
        <translation>третья</translation>
    </message>
</context>
<context>
    <name>ProcessDbPage</name>
    <message>
        <source>Process database</source>
        <translation>База технологических данных</translation>
    </message>
    <message>
        <source>Add hole</source>
        <translation>Добавить отверстие</translation>
    </message>
    <message>
        <source>Remove hole</source>
        <translation>Удалить отверстие</translation>
    </message>
    <message>
        <source>Import CSV…</source>
        <translation>Импорт CSV…</translation>
    </message>
    <message>
        <source>Export CSV…</source>
        <translation>Экспорт CSV…</translation>
    </message>
    <message>
        <source>Send the holes to the controller</source>
        <translation>Отправить отверстия в контроллер</translation>
    </message>
    <message>
        <source>All columns</source>
        <translation>Все столбцы</translation>
    </message>
    <message>
        <source>Position columns</source>
        <translation>Столбцы положения</translation>
    </message>
    <message>
        <source>Process columns</source>
        <translation>Столбцы процесса</translation>
    </message>
</context>
<context>
    <name>ProgramPage</name>
    <message>
        <source>Program</source>
        <translation>Программа</translation>
    </message>
    <message>
        <source>Open program…</source>
        <translation>Открыть программу…</translation>
    </message>
    <message>
        <source>no program</source>
        <translation>нет программы</translation>
    </message>
    <message>
        <source>Load into the controller</source>
        <translation>Загрузить в контроллер</translation>
    </message>
    <message>
        <source>Top</source>
        <translation>Сверху</translation>
    </message>
    <message>
        <source>3D</source>
        <translation>3D</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::AdjustPage</name>
    <message>
        <source>W, 60 s: setpoint grey, output blue, measured green</source>
        <translation>Вт, 60 с: уставка — серый, выход — синий, измерено — зелёный</translation>
    </message>
    <message>
        <source>standby</source>
        <translation>ожидание</translation>
    </message>
    <message>
        <source>ready</source>
        <translation>готов</translation>
    </message>
    <message>
        <source>emitting</source>
        <translation>излучает</translation>
    </message>
    <message>
        <source>ALARM</source>
        <translation>АВАРИЯ</translation>
    </message>
    <message>
        <source>idle</source>
        <translation>простой</translation>
    </message>
    <message>
        <source>spinning up</source>
        <translation>разгон</translation>
    </message>
    <message>
        <source>scanning</source>
        <translation>сканирование</translation>
    </message>
    <message>
        <source>Device</source>
        <translation>Устройство</translation>
    </message>
    <message>
        <source>Link</source>
        <translation>Связь</translation>
    </message>
    <message>
        <source>Requests</source>
        <translation>Запросы</translation>
    </message>
    <message>
        <source>Failed</source>
        <translation>Ошибки</translation>
    </message>
    <message>
        <source>Retries</source>
        <translation>Повторы</translation>
    </message>
    <message>
        <source>Last error</source>
        <translation>Последняя ошибка</translation>
    </message>
    <message>
        <source>no link</source>
        <translation>нет связи</translation>
    </message>
    <message>
        <source>none</source>
        <translation>нет</translation>
    </message>
    <message>
        <source>over-temperature</source>
        <translation>перегрев</translation>
    </message>
    <message>
        <source>laser: %1</source>
        <translation>лазер: %1</translation>
    </message>
    <message>
        <source> (over range)</source>
        <translation> (вне диапазона)</translation>
    </message>
    <message>
        <source>FAULT</source>
        <translation>НЕИСПРАВНОСТЬ</translation>
    </message>
    <message>
        <source>head: %1</source>
        <translation>головка: %1</translation>
    </message>
    <message>
        <source>not configured</source>
        <translation>не настроено</translation>
    </message>
    <message>
        <source>connecting…</source>
        <translation>подключение…</translation>
    </message>
    <message>
        <source>up</source>
        <translation>есть</translation>
    </message>
    <message>
        <source>down</source>
        <translation>нет</translation>
    </message>
    <message>
        <source>Refused: %1</source>
        <translation>Отклонено: %1</translation>
    </message>
    <message>
        <source>= %1 W</source>
        <translation>= %1 Вт</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::CutPage</name>
    <message>
        <source>Open a DXF part to plan its cut.</source>
        <translation>Откройте деталь DXF, чтобы рассчитать резку.</translation>
    </message>
    <message>
        <source>Open a part</source>
        <translation>Открыть деталь</translation>
    </message>
    <message>
        <source>DXF (*.dxf)</source>
        <translation>DXF (*.dxf)</translation>
    </message>
    <message>
        <source>Save the cutting program</source>
        <translation>Сохранить программу резки</translation>
    </message>
    <message>
        <source>G-code (*.ngc)</source>
        <translation>G-код (*.ngc)</translation>
    </message>
    <message>
        <source>Choose the drawing&apos;s units above, then plan again.</source>
        <translation>Выберите единицы чертежа выше и рассчитайте снова.</translation>
    </message>
    <message>
        <source>%1 contours (%2 holes, %3 parts), holes first; cut %4 mm, lead-ins %5 mm, rapids %6 mm; about %7 s</source>
        <translation>контуров: %1 (отверстий %2, деталей %3), сначала отверстия; рез %4 мм, врезки %5 мм, быстрые ходы %6 мм; около %7 с</translation>
    </message>
    <message>
        <source>Planned. Save the program, or load it into the controller.</source>
        <translation>Рассчитано. Сохраните программу или загрузите её в контроллер.</translation>
    </message>
    <message>
        <source>Cannot write %1: %2</source>
        <translation>Не удаётся записать %1: %2</translation>
    </message>
    <message>
        <source>Saved %1.</source>
        <translation>Сохранено: %1.</translation>
    </message>
    <message>
        <source>Cannot make %1.</source>
        <translation>Не удаётся создать %1.</translation>
    </message>
    <message>
        <source>Saved %1; not loaded: no link to the controller.</source>
        <translation>Сохранено: %1; не загружено: нет связи с контроллером.</translation>
    </message>
    <message>
        <source>Loaded %1 into the controller (cycle start on the machine screen).</source>
        <translation>%1 загружена в контроллер (пуск цикла — на экране станка).</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::DecompositionPage</name>
    <message>
        <source>Open drawing</source>
        <translation>Открыть чертёж</translation>
    </message>
    <message>
        <source>DXF (*.dxf)</source>
        <translation>DXF (*.dxf)</translation>
    </message>
    <message>
        <source>Export kinematics table</source>
        <translation>Экспорт кинематической таблицы</translation>
    </message>
    <message>
        <source>CSV (*.csv)</source>
        <translation>CSV (*.csv)</translation>
    </message>
    <message>
        <source>Drawing %1: set the options and decompose.</source>
        <translation>Чертёж %1: задайте параметры и разложите.</translation>
    </message>
    <message>
        <source>Decomposing…</source>
        <translation>Разложение…</translation>
    </message>
    <message>
        <source>%1 contours, %2 points at %3 mm; time %4 s; peak main-axis acceleration %5 mm/s² (%6 g), effective %7 mm/s² — %8× lower on the main axes; aux excursion %9 mm; |S1 + S2 − S| ≤ %10 mm</source>
        <translation>контуров: %1, точек: %2 с шагом %3 мм; время %4 с; пиковое ускорение основных осей %5 мм/с² (%6 g), эффективное %7 мм/с² — на основных осях в %8 раз меньше; отклонение вспом. осей %9 мм; |S1 + S2 − S| ≤ %10 мм</translation>
    </message>
    <message>
        <source>Decomposed.</source>
        <translation>Разложено.</translation>
    </message>
    <message numerus="yes">
        <source>The published algorithm breaks %n limit(s) (see the table&apos;s tooltips); the synchronous mode guarantees them.</source>
        <translation>
            <numerusform>Исходный алгоритм нарушает %n ограничение (см. подсказки таблицы); синхронный режим их гарантирует.</numerusform>
            <numerusform>Исходный алгоритм нарушает %n ограничения (см. подсказки таблицы); синхронный режим их гарантирует.</numerusform>
            <numerusform>Исходный алгоритм нарушает %n ограничений (см. подсказки таблицы); синхронный режим их гарантирует.</numerusform>
        </translation>
    </message>
    <message>
        <source> line %1</source>
        <translation>, строка %1</translation>
    </message>
    <message>
        <source>Nothing to export: decompose a drawing first.</source>
        <translation>Нечего экспортировать: сначала разложите чертёж.</translation>
    </message>
    <message>
        <source>Cannot write %1.</source>
        <translation>Не удаётся записать %1.</translation>
    </message>
    <message>
        <source>Exported %1.</source>
        <translation>Экспортировано: %1.</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::DecompositionView</name>
    <message>
        <source>Open a DXF drawing and decompose it.</source>
        <translation>Откройте чертёж DXF и разложите его.</translation>
    </message>
    <message>
        <source>S contour (green), S1 main axes X, Y (blue) — mm</source>
        <translation>S контур (зелёный), S1 основные оси X, Y (синий) — мм</translation>
    </message>
    <message>
        <source>S2 = S − S1 auxiliary axes P, Q (red) in the field ±%1 mm</source>
        <translation>S2 = S − S1 вспомогательные оси P, Q (красный) в поле ±%1 мм</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::FocalPage</name>
    <message>
        <source>Hole</source>
        <translation>Отверстие</translation>
    </message>
    <message>
        <source>X mm</source>
        <translation>X мм</translation>
    </message>
    <message>
        <source>Y mm</source>
        <translation>Y мм</translation>
    </message>
    <message>
        <source>Z mm</source>
        <translation>Z мм</translation>
    </message>
    <message>
        <source>Stored offset mm</source>
        <translation>Сохранённое смещение, мм</translation>
    </message>
    <message>
        <source>Distance mm</source>
        <translation>Расстояние, мм</translation>
    </message>
    <message>
        <source>New offset mm</source>
        <translation>Новое смещение, мм</translation>
    </message>
    <message>
        <source>Status</source>
        <translation>Статус</translation>
    </message>
    <message>
        <source>Tick the holes to measure first.</source>
        <translation>Сначала отметьте отверстия для измерения.</translation>
    </message>
    <message>
        <source>No displacement sensor configured.</source>
        <translation>Датчик перемещения не настроен.</translation>
    </message>
    <message numerus="yes">
        <source>Measuring %n hole(s)…</source>
        <translation>
            <numerusform>Измеряется %n отверстие…</numerusform>
            <numerusform>Измеряются %n отверстия…</numerusform>
            <numerusform>Измеряются %n отверстий…</numerusform>
        </translation>
    </message>
    <message>
        <source>measured</source>
        <translation>измерено</translation>
    </message>
    <message numerus="yes">
        <source>%n hole(s) measured; save to store the offsets.</source>
        <translation>
            <numerusform>Измерено %n отверстие; сохраните, чтобы записать смещения.</numerusform>
            <numerusform>Измерено %n отверстия; сохраните, чтобы записать смещения.</numerusform>
            <numerusform>Измерено %n отверстий; сохраните, чтобы записать смещения.</numerusform>
        </translation>
    </message>
    <message>
        <source>%1 measured, %2 not (see Status); save stores the measured ones.</source>
        <translation>Измерено: %1, не измерено: %2 (см. «Статус»); сохраняются измеренные.</translation>
    </message>
    <message>
        <source>Nothing measured to save.</source>
        <translation>Нет измерений для сохранения.</translation>
    </message>
    <message numerus="yes">
        <source>Stored the focus offsets of %n hole(s).</source>
        <translation>
            <numerusform>Сохранено смещение фокуса %n отверстия.</numerusform>
            <numerusform>Сохранены смещения фокуса %n отверстий.</numerusform>
            <numerusform>Сохранены смещения фокуса %n отверстий.</numerusform>
        </translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::HoleTableModel</name>
    <message>
        <source>hole %1: field 18 process = %2; allowed 0 helix, 1 circle, 2 free shape</source>
        <translation>отверстие %1: поле 18 процесс = %2; допустимо 0 спираль, 1 окружность, 2 произвольная форма</translation>
    </message>
    <message>
        <source>hole %1: %2 must be a whole number</source>
        <translation>отверстие %1: %2 должно быть целым числом</translation>
    </message>
    <message>
        <source>hole %1: %2 must be a number</source>
        <translation>отверстие %1: %2 должно быть числом</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::MachinePage</name>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>Не отправлено: нет связи с контроллером.</translation>
    </message>
    <message>
        <source>Controller: link lost — %1</source>
        <translation>Контроллер: связь потеряна — %1</translation>
    </message>
    <message>
        <source>State: unknown</source>
        <translation>Состояние: неизвестно</translation>
    </message>
    <message>
        <source>Controller: connected</source>
        <translation>Контроллер: подключён</translation>
    </message>
    <message>
        <source>State: %1</source>
        <translation>Состояние: %1</translation>
    </message>
    <message>
        <source>Code</source>
        <translation>Код</translation>
    </message>
    <message>
        <source>Line</source>
        <translation>Строка</translation>
    </message>
    <message>
        <source>What</source>
        <translation>Что</translation>
    </message>
    <message>
        <source>Time</source>
        <translation>Время</translation>
    </message>
    <message>
        <source>Count</source>
        <translation>Кол-во</translation>
    </message>
    <message>
        <source>MDI: a line of at most %1 characters.</source>
        <translation>MDI: строка не длиннее %1 символов.</translation>
    </message>
    <message numerus="yes">
        <source>%n to acknowledge</source>
        <translation>
            <numerusform>%n для квитирования</numerusform>
            <numerusform>%n для квитирования</numerusform>
            <numerusform>%n для квитирования</numerusform>
        </translation>
    </message>
    <message>
        <source>homed</source>
        <translation>в нуле</translation>
    </message>
    <message>
        <source>not homed</source>
        <translation>не в нуле</translation>
    </message>
    <message>
        <source> — single block: Resume runs the next block</source>
        <translation> — покадрово: «Продолжить» выполняет следующий кадр</translation>
    </message>
    <message>
        <source> — program pause: Resume goes on</source>
        <translation> — пауза программы: «Продолжить» для продолжения</translation>
    </message>
    <message>
        <source> — waiting for input %1</source>
        <translation> — ожидание входа %1</translation>
    </message>
    <message>
        <source>Laser: on, %1 %</source>
        <translation>Лазер: вкл., %1 %</translation>
    </message>
    <message>
        <source>Laser: off</source>
        <translation>Лазер: выкл.</translation>
    </message>
    <message>
        <source>Program: %1</source>
        <translation>Программа: %1</translation>
    </message>
    <message>
        <source>Program: none loaded</source>
        <translation>Программа: не загружена</translation>
    </message>
    <message>
        <source>Line %1</source>
        <translation>Строка %1</translation>
    </message>
    <message>
        <source>Time left %1</source>
        <translation>Осталось %1</translation>
    </message>
    <message>
        <source>MDI</source>
        <translation>MDI</translation>
    </message>
    <message>
        <source>single block</source>
        <translation>покадрово</translation>
    </message>
    <message>
        <source>dry run</source>
        <translation>пробный прогон</translation>
    </message>
    <message>
        <source>from line %1</source>
        <translation>со строки %1</translation>
    </message>
    <message>
        <source>Gas: high (M8)</source>
        <translation>Газ: высокое давление (M8)</translation>
    </message>
    <message>
        <source>Gas: low (M7)</source>
        <translation>Газ: низкое давление (M7)</translation>
    </message>
    <message>
        <source>Gas: off</source>
        <translation>Газ: выкл.</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::MainWindow</name>
    <message>
        <source>LaserCNC</source>
        <translation>LaserCNC</translation>
    </message>
    <message>
        <source>Machine</source>
        <translation>Станок</translation>
    </message>
    <message>
        <source>Process database</source>
        <translation>База технологических данных</translation>
    </message>
    <message>
        <source>3D measurement</source>
        <translation>3D-измерение</translation>
    </message>
    <message>
        <source>Focal length</source>
        <translation>Фокусное расстояние</translation>
    </message>
    <message>
        <source>Laser and head</source>
        <translation>Лазер и головка</translation>
    </message>
    <message>
        <source>Main + auxiliary axes</source>
        <translation>Основные + вспомогательные оси</translation>
    </message>
    <message>
        <source>Program</source>
        <translation>Программа</translation>
    </message>
    <message>
        <source>Laser cutting</source>
        <translation>Лазерная резка</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::MeasurePage</name>
    <message>
        <source>Point</source>
        <translation>Точка</translation>
    </message>
    <message>
        <source>Approach X, Y, Z mm; A, C °</source>
        <translation>Подход X, Y, Z мм; A, C °</translation>
    </message>
    <message>
        <source>Measured X, Y, Z mm</source>
        <translation>Измерено X, Y, Z мм</translation>
    </message>
    <message>
        <source>Residual mm</source>
        <translation>Невязка, мм</translation>
    </message>
    <message>
        <source>Apply the measured placement</source>
        <translation>Применить измеренное положение</translation>
    </message>
    <message>
        <source>Move every hole of the process database onto the measured placement? Their X, Y, Z, A and C are read as drawing coordinates.</source>
        <translation>Перенести все отверстия базы на измеренное положение? Их X, Y, Z, A и C считаются координатами чертежа.</translation>
    </message>
    <message>
        <source>No 3D probe configured.</source>
        <translation>3D-щуп не настроен.</translation>
    </message>
    <message>
        <source>Measuring: the machine moves to each point…</source>
        <translation>Измерение: станок перемещается к каждой точке…</translation>
    </message>
    <message>
        <source>Not measured: %1</source>
        <translation>Не измерено: %1</translation>
    </message>
    <message>
        <source>The block&apos;s datum corner at X %1 Y %2 Z %3 mm, turned %4° about Z, its top tilted %5°; residuals max %6 mm, rms %7 mm.</source>
        <translation>Базовый угол заготовки: X %1 Y %2 Z %3 мм, поворот %4° вокруг Z, наклон верхней грани %5°; невязка макс. %6 мм, СКО %7 мм.</translation>
    </message>
    <message>
        <source>Measured. Apply the placement to the holes when it looks right.</source>
        <translation>Измерено. Если всё верно, примените положение к отверстиям.</translation>
    </message>
    <message>
        <source>Nothing measured to apply.</source>
        <translation>Нет измерения для применения.</translation>
    </message>
    <message numerus="yes">
        <source>Moved %n hole(s) onto the measured placement.</source>
        <translation>
            <numerusform>Перенесено %n отверстие на измеренное положение.</numerusform>
            <numerusform>Перенесено %n отверстия на измеренное положение.</numerusform>
            <numerusform>Перенесено %n отверстий на измеренное положение.</numerusform>
        </translation>
    </message>
    <message>
        <source>; %1, %2 (planned)</source>
        <translation>; %1, %2 (план)</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ProcessDbPage</name>
    <message>
        <source>Stored.</source>
        <translation>Сохранено.</translation>
    </message>
    <message>
        <source>Import hole table</source>
        <translation>Импорт таблицы отверстий</translation>
    </message>
    <message>
        <source>CSV (*.csv)</source>
        <translation>CSV (*.csv)</translation>
    </message>
    <message>
        <source>Export hole table</source>
        <translation>Экспорт таблицы отверстий</translation>
    </message>
    <message numerus="yes">
        <source>%n hole(s)</source>
        <translation>
            <numerusform>%n отверстие</numerusform>
            <numerusform>%n отверстия</numerusform>
            <numerusform>%n отверстий</numerusform>
        </translation>
    </message>
    <message>
        <source>Imported %1.</source>
        <translation>Импортировано: %1.</translation>
    </message>
    <message>
        <source>Exported %1.</source>
        <translation>Экспортировано: %1.</translation>
    </message>
    <message>
        <source>Hole %1 added.</source>
        <translation>Отверстие %1 добавлено.</translation>
    </message>
    <message>
        <source>No holes to send.</source>
        <translation>Нет отверстий для отправки.</translation>
    </message>
    <message>
        <source>Cannot write %1.</source>
        <translation>Не удаётся записать %1.</translation>
    </message>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>Не отправлено: нет связи с контроллером.</translation>
    </message>
    <message>
        <source>Sent %1 holes (%2 with a measured focus offset) to the controller; start the cycle on the machine screen.</source>
        <translation>Отправлено отверстий: %1 (с измеренным смещением фокуса: %2); запустите цикл на экране станка.</translation>
    </message>
    <message>
        <source>No holes yet.</source>
        <translation>Отверстий пока нет.</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ProgramPage</name>
    <message>
        <source>Open program</source>
        <translation>Открыть программу</translation>
    </message>
    <message>
        <source>G-code (*.ngc *.nc *.gcode);;All (*)</source>
        <translation>G-код (*.ngc *.nc *.gcode);;Все (*)</translation>
    </message>
    <message>
        <source>Checking and planning %1…</source>
        <translation>Проверка и планирование %1…</translation>
    </message>
    <message>
        <source>%1 lines; path %2 mm; planned time %3 s; peak speed %4 mm/s; %5 points drawn</source>
        <translation>строк: %1; путь %2 мм; плановое время %3 с; пиковая скорость %4 мм/с; точек на рисунке: %5</translation>
    </message>
    <message>
        <source>Planned. Load it into the controller to run it.</source>
        <translation>Спланировано. Загрузите в контроллер, чтобы выполнить.</translation>
    </message>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>Не отправлено: нет связи с контроллером.</translation>
    </message>
    <message>
        <source>Sent to the controller; its answer shows on the machine screen.</source>
        <translation>Отправлено в контроллер; его ответ — на экране станка.</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ToolpathView</name>
    <message>
        <source>Open a program to see its toolpath as planned.</source>
        <translation>Откройте программу, чтобы увидеть спланированную траекторию.</translation>
    </message>
    <message>
        <source>mm/s</source>
        <translation>мм/с</translation>
    </message>
    <message>
        <source>Cut: X %1 … %2, Y %3 … %4, Z %5 … %6 mm; grid %7 mm</source>
        <translation>Рез: X %1 … %2, Y %3 … %4, Z %5 … %6 мм; сетка %7 мм</translation>
    </message>
    <message>
        <source>cut (colour: speed)</source>
        <translation>рез (цвет: скорость)</translation>
    </message>
    <message>
        <source>feed, laser off</source>
        <translation>подача, лазер выкл.</translation>
    </message>
    <message>
        <source>rapid</source>
        <translation>быстрый ход</translation>
    </message>
    <message>
        <source>tool axis</source>
        <translation>ось инструмента</translation>
    </message>
</context>
</TS>
