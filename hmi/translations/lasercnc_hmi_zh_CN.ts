<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="zh_CN">
<context>
    <name>AdjustPage</name>
    <message>
        <source>Adjustment and monitoring</source>
        <translation>调整与监控</translation>
    </message>
    <message>
        <source>Laser source</source>
        <translation>激光器</translation>
    </message>
    <message>
        <source>Power setpoint, %</source>
        <translation>功率设定值，%</translation>
    </message>
    <message>
        <source>Set power</source>
        <translation>设定功率</translation>
    </message>
    <message>
        <source>Emission</source>
        <translation>出光</translation>
    </message>
    <message>
        <source>Reset alarm</source>
        <translation>复位报警</translation>
    </message>
    <message>
        <source>State</source>
        <translation>状态</translation>
    </message>
    <message>
        <source>Output (monitor diode), W</source>
        <translation>输出（监测二极管），W</translation>
    </message>
    <message>
        <source>Pump diode, °C</source>
        <translation>泵浦二极管，°C</translation>
    </message>
    <message>
        <source>Alarms</source>
        <translation>报警</translation>
    </message>
    <message>
        <source>Power monitoring</source>
        <translation>功率监测</translation>
    </message>
    <message>
        <source>Measured power, W</source>
        <translation>测量功率，W</translation>
    </message>
    <message>
        <source>Zero the meter</source>
        <translation>功率计调零</translation>
    </message>
    <message>
        <source>Four-beam scanning head</source>
        <translation>四光束扫描头</translation>
    </message>
    <message>
        <source>Start radius, mm</source>
        <translation>起始半径，mm</translation>
    </message>
    <message>
        <source>End radius, mm</source>
        <translation>终止半径，mm</translation>
    </message>
    <message>
        <source>Radius turns</source>
        <translation>半径圈数</translation>
    </message>
    <message>
        <source>Scan speed, mm/s</source>
        <translation>扫描速度，mm/s</translation>
    </message>
    <message>
        <source>Wedge speed, rpm</source>
        <translation>光楔转速，rpm</translation>
    </message>
    <message>
        <source>Beam offset, mm</source>
        <translation>光束偏移，mm</translation>
    </message>
    <message>
        <source>Write parameters</source>
        <translation>写入参数</translation>
    </message>
    <message>
        <source>Run pattern</source>
        <translation>运行扫描</translation>
    </message>
    <message>
        <source>Wedge speed now, rpm</source>
        <translation>当前光楔转速，rpm</translation>
    </message>
    <message>
        <source>Radius now, mm</source>
        <translation>当前半径，mm</translation>
    </message>
    <message>
        <source>Turns done</source>
        <translation>已完成圈数</translation>
    </message>
</context>
<context>
    <name>CutPage</name>
    <message>
        <source>Laser cutting</source>
        <translation>激光切割</translation>
    </message>
    <message>
        <source>Open DXF…</source>
        <translation>打开 DXF…</translation>
    </message>
    <message>
        <source>no drawing</source>
        <translation>无图纸</translation>
    </message>
    <message>
        <source>Plan the cut</source>
        <translation>规划切割</translation>
    </message>
    <message>
        <source>Save G-code…</source>
        <translation>保存 G 代码…</translation>
    </message>
    <message>
        <source>Load into the controller</source>
        <translation>载入控制器</translation>
    </message>
    <message>
        <source>Cutting</source>
        <translation>切割</translation>
    </message>
    <message>
        <source>Kerf, mm</source>
        <translation>割缝宽度，mm</translation>
    </message>
    <message>
        <source>Lead-in, mm</source>
        <translation>引入线，mm</translation>
    </message>
    <message>
        <source>Lead-out, mm</source>
        <translation>引出线，mm</translation>
    </message>
    <message>
        <source>Feed, mm/min</source>
        <translation>进给，mm/min</translation>
    </message>
    <message>
        <source>Power, %</source>
        <translation>功率，%</translation>
    </message>
    <message>
        <source>Pierce, s</source>
        <translation>穿孔，s</translation>
    </message>
    <message>
        <source>Origin X, mm</source>
        <translation>原点 X，mm</translation>
    </message>
    <message>
        <source>Origin Y, mm</source>
        <translation>原点 Y，mm</translation>
    </message>
    <message>
        <source>Outline</source>
        <translation>外轮廓</translation>
    </message>
    <message>
        <source>clockwise (holes counter-clockwise)</source>
        <translation>顺时针（孔逆时针）</translation>
    </message>
    <message>
        <source>counter-clockwise (holes clockwise)</source>
        <translation>逆时针（孔顺时针）</translation>
    </message>
    <message>
        <source>Units</source>
        <translation>单位</translation>
    </message>
    <message>
        <source>from the drawing</source>
        <translation>按图纸</translation>
    </message>
    <message>
        <source>inch</source>
        <translation>英寸</translation>
    </message>
</context>
<context>
    <name>DecompositionPage</name>
    <message>
        <source>Main + auxiliary axes</source>
        <translation>主轴 + 辅助轴</translation>
    </message>
    <message>
        <source>Open DXF…</source>
        <translation>打开 DXF…</translation>
    </message>
    <message>
        <source>no drawing</source>
        <translation>无图纸</translation>
    </message>
    <message>
        <source>Contour speed, m/min</source>
        <translation>轮廓速度，m/min</translation>
    </message>
    <message>
        <source>Step, mm</source>
        <translation>步长，mm</translation>
    </message>
    <message>
        <source>Aux field, mm</source>
        <translation>辅助轴行程场，mm</translation>
    </message>
    <message>
        <source>Main accel, g</source>
        <translation>主轴加速度，g</translation>
    </message>
    <message>
        <source>synchronous</source>
        <translation>同步</translation>
    </message>
    <message>
        <source>published algorithm</source>
        <translation>原始算法</translation>
    </message>
    <message>
        <source>Decompose</source>
        <translation>分解</translation>
    </message>
    <message>
        <source>Export table…</source>
        <translation>导出表格…</translation>
    </message>
    <message>
        <source>first entity</source>
        <translation>首个图元</translation>
    </message>
    <message>
        <source>length mm</source>
        <translation>长度 mm</translation>
    </message>
    <message>
        <source>points</source>
        <translation>点数</translation>
    </message>
    <message>
        <source>time s</source>
        <translation>时间 s</translation>
    </message>
    <message>
        <source>τ s</source>
        <translation>τ s</translation>
    </message>
    <message>
        <source>main a mm/s²</source>
        <translation>主轴 a mm/s²</translation>
    </message>
    <message>
        <source>main v mm/s</source>
        <translation>主轴 v mm/s</translation>
    </message>
    <message>
        <source>aux v mm/s</source>
        <translation>辅轴 v mm/s</translation>
    </message>
    <message>
        <source>aux max mm</source>
        <translation>辅轴最大 mm</translation>
    </message>
    <message>
        <source>a_eff mm/s²</source>
        <translation>a_eff mm/s²</translation>
    </message>
</context>
<context>
    <name>FocalPage</name>
    <message>
        <source>Focal length</source>
        <translation>焦距</translation>
    </message>
    <message>
        <source>Reload holes</source>
        <translation>重新载入孔</translation>
    </message>
    <message>
        <source>Select all</source>
        <translation>全选</translation>
    </message>
    <message>
        <source>Stand-off, mm</source>
        <translation>测距距离，mm</translation>
    </message>
    <message>
        <source>Measure selected</source>
        <translation>测量所选</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>取消</translation>
    </message>
    <message>
        <source>Save offsets</source>
        <translation>保存偏移量</translation>
    </message>
</context>
<context>
    <name>HoleTableModel</name>
    <message>
        <source>Hole</source>
        <translation>孔</translation>
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
        <translation>进给</translation>
    </message>
    <message>
        <source>Layer feed</source>
        <translation>层进给</translation>
    </message>
    <message>
        <source>Layers</source>
        <translation>层数</translation>
    </message>
    <message>
        <source>Depth</source>
        <translation>深度</translation>
    </message>
    <message>
        <source>Power</source>
        <translation>功率</translation>
    </message>
    <message>
        <source>Start radius</source>
        <translation>起始半径</translation>
    </message>
    <message>
        <source>End radius</source>
        <translation>终止半径</translation>
    </message>
    <message>
        <source>Radius turns</source>
        <translation>半径圈数</translation>
    </message>
    <message>
        <source>Scan speed</source>
        <translation>扫描速度</translation>
    </message>
    <message>
        <source>Wedge speed</source>
        <translation>光楔转速</translation>
    </message>
    <message>
        <source>Beam offset</source>
        <translation>光束偏移</translation>
    </message>
    <message>
        <source>Process</source>
        <translation>工艺</translation>
    </message>
    <message>
        <source>Focus offset</source>
        <translation>焦点偏移</translation>
    </message>
</context>
<context>
    <name>MachinePage</name>
    <message>
        <source>Machine</source>
        <translation>机床</translation>
    </message>
    <message>
        <source>Position</source>
        <translation>位置</translation>
    </message>
    <message>
        <source>Cycle start</source>
        <translation>循环启动</translation>
    </message>
    <message>
        <source>Feed hold</source>
        <translation>进给保持</translation>
    </message>
    <message>
        <source>Resume</source>
        <translation>继续</translation>
    </message>
    <message>
        <source>Stop</source>
        <translation>停止</translation>
    </message>
    <message>
        <source>Feed override</source>
        <translation>进给倍率</translation>
    </message>
    <message>
        <source>E-STOP</source>
        <translation>急停</translation>
    </message>
    <message>
        <source>Reset</source>
        <translation>复位</translation>
    </message>
    <message>
        <source>idle</source>
        <translation>空闲</translation>
    </message>
    <message>
        <source>running</source>
        <translation>运行中</translation>
    </message>
    <message>
        <source>feed hold</source>
        <translation>进给保持</translation>
    </message>
    <message>
        <source>stopping</source>
        <translation>停止中</translation>
    </message>
    <message>
        <source>e-stop</source>
        <translation>急停</translation>
    </message>
    <message>
        <source>jog</source>
        <translation>点动</translation>
    </message>
    <message>
        <source>homing</source>
        <translation>回零</translation>
    </message>
    <message>
        <source> mm/°</source>
        <translation> mm/°</translation>
    </message>
    <message>
        <source>Jog −</source>
        <translation>点动 −</translation>
    </message>
    <message>
        <source>Jog +</source>
        <translation>点动 +</translation>
    </message>
    <message>
        <source>Home axis</source>
        <translation>轴回零</translation>
    </message>
    <message>
        <source>Alarms and events</source>
        <translation>报警与事件</translation>
    </message>
    <message>
        <source>Clear the list</source>
        <translation>清空列表</translation>
    </message>
    <message>
        <source>Work</source>
        <translation>工件</translation>
    </message>
    <message>
        <source>Homed</source>
        <translation>已回零</translation>
    </message>
    <message>
        <source>Work offsets</source>
        <translation>工件偏置</translation>
    </message>
    <message>
        <source>Work system</source>
        <translation>工件坐标系</translation>
    </message>
    <message>
        <source>Touch off</source>
        <translation>对刀</translation>
    </message>
    <message>
        <source>Set here</source>
        <translation>设为此处</translation>
    </message>
    <message>
        <source>MDI</source>
        <translation>MDI</translation>
    </message>
    <message>
        <source>G-code, e.g. G1 X10 F600</source>
        <translation>G 代码，例如 G1 X10 F600</translation>
    </message>
    <message>
        <source>Send</source>
        <translation>发送</translation>
    </message>
    <message>
        <source>Job</source>
        <translation>作业</translation>
    </message>
    <message>
        <source>Single block</source>
        <translation>单段</translation>
    </message>
    <message>
        <source>Dry run (laser off)</source>
        <translation>空运行（激光关）</translation>
    </message>
    <message>
        <source>From line</source>
        <translation>从行</translation>
    </message>
    <message>
        <source>start</source>
        <translation>开头</translation>
    </message>
    <message>
        <source>Frame</source>
        <translation>巡边</translation>
    </message>
    <message>
        <source>Acknowledge</source>
        <translation>确认</translation>
    </message>
    <message>
        <source>To go</source>
        <translation>剩余距离</translation>
    </message>
</context>
<context>
    <name>MeasurePage</name>
    <message>
        <source>3D measurement</source>
        <translation>三维测量</translation>
    </message>
    <message>
        <source>Block L, mm</source>
        <translation>工件长 L，mm</translation>
    </message>
    <message>
        <source>W</source>
        <translation>宽</translation>
    </message>
    <message>
        <source>H</source>
        <translation>高</translation>
    </message>
    <message>
        <source>Nominal corner X</source>
        <translation>名义基准角 X</translation>
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
        <translation>旋转，°</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>取消</translation>
    </message>
    <message>
        <source>Apply to the holes…</source>
        <translation>应用到孔…</translation>
    </message>
    <message>
        <source>Best fit with four more points</source>
        <translation>再测四点做最佳拟合</translation>
    </message>
    <message>
        <source>Measure</source>
        <translation>测量</translation>
    </message>
    <message>
        <source>primary</source>
        <translation>第一基准面</translation>
    </message>
    <message>
        <source>secondary</source>
        <translation>第二基准面</translation>
    </message>
    <message>
        <source>tertiary</source>
        <translation>第三基准面</translation>
    </message>
</context>
<context>
    <name>ProcessDbPage</name>
    <message>
        <source>Process database</source>
        <translation>工艺数据库</translation>
    </message>
    <message>
        <source>Add hole</source>
        <translation>添加孔</translation>
    </message>
    <message>
        <source>Remove hole</source>
        <translation>删除孔</translation>
    </message>
    <message>
        <source>Import CSV…</source>
        <translation>导入 CSV…</translation>
    </message>
    <message>
        <source>Export CSV…</source>
        <translation>导出 CSV…</translation>
    </message>
    <message>
        <source>Send the holes to the controller</source>
        <translation>将孔发送到控制器</translation>
    </message>
    <message>
        <source>All columns</source>
        <translation>全部列</translation>
    </message>
    <message>
        <source>Position columns</source>
        <translation>位置列</translation>
    </message>
    <message>
        <source>Process columns</source>
        <translation>工艺列</translation>
    </message>
</context>
<context>
    <name>ProgramPage</name>
    <message>
        <source>Program</source>
        <translation>程序</translation>
    </message>
    <message>
        <source>Open program…</source>
        <translation>打开程序…</translation>
    </message>
    <message>
        <source>no program</source>
        <translation>无程序</translation>
    </message>
    <message>
        <source>Load into the controller</source>
        <translation>载入控制器</translation>
    </message>
    <message>
        <source>Top</source>
        <translation>俯视</translation>
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
        <translation>W，60 s：设定值灰色，输出蓝色，测量值绿色</translation>
    </message>
    <message>
        <source>standby</source>
        <translation>待机</translation>
    </message>
    <message>
        <source>ready</source>
        <translation>就绪</translation>
    </message>
    <message>
        <source>emitting</source>
        <translation>出光中</translation>
    </message>
    <message>
        <source>ALARM</source>
        <translation>报警</translation>
    </message>
    <message>
        <source>idle</source>
        <translation>空闲</translation>
    </message>
    <message>
        <source>spinning up</source>
        <translation>加速中</translation>
    </message>
    <message>
        <source>scanning</source>
        <translation>扫描中</translation>
    </message>
    <message>
        <source>Device</source>
        <translation>设备</translation>
    </message>
    <message>
        <source>Link</source>
        <translation>连接</translation>
    </message>
    <message>
        <source>Requests</source>
        <translation>请求</translation>
    </message>
    <message>
        <source>Failed</source>
        <translation>失败</translation>
    </message>
    <message>
        <source>Retries</source>
        <translation>重试</translation>
    </message>
    <message>
        <source>Last error</source>
        <translation>最近错误</translation>
    </message>
    <message>
        <source>no link</source>
        <translation>无连接</translation>
    </message>
    <message>
        <source>none</source>
        <translation>无</translation>
    </message>
    <message>
        <source>over-temperature</source>
        <translation>过温</translation>
    </message>
    <message>
        <source>laser: %1</source>
        <translation>激光器：%1</translation>
    </message>
    <message>
        <source> (over range)</source>
        <translation>（超量程）</translation>
    </message>
    <message>
        <source>FAULT</source>
        <translation>故障</translation>
    </message>
    <message>
        <source>head: %1</source>
        <translation>扫描头：%1</translation>
    </message>
    <message>
        <source>not configured</source>
        <translation>未配置</translation>
    </message>
    <message>
        <source>connecting…</source>
        <translation>连接中…</translation>
    </message>
    <message>
        <source>up</source>
        <translation>正常</translation>
    </message>
    <message>
        <source>down</source>
        <translation>中断</translation>
    </message>
    <message>
        <source>Refused: %1</source>
        <translation>被拒绝：%1</translation>
    </message>
    <message>
        <source>= %1 W</source>
        <translation>= %1 W</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::CutPage</name>
    <message>
        <source>Open a DXF part to plan its cut.</source>
        <translation>打开 DXF 零件以规划切割。</translation>
    </message>
    <message>
        <source>Open a part</source>
        <translation>打开零件</translation>
    </message>
    <message>
        <source>DXF (*.dxf)</source>
        <translation>DXF (*.dxf)</translation>
    </message>
    <message>
        <source>Save the cutting program</source>
        <translation>保存切割程序</translation>
    </message>
    <message>
        <source>G-code (*.ngc)</source>
        <translation>G 代码 (*.ngc)</translation>
    </message>
    <message>
        <source>Choose the drawing&apos;s units above, then plan again.</source>
        <translation>请在上方选择图纸单位，然后重新规划。</translation>
    </message>
    <message>
        <source>%1 contours (%2 holes, %3 parts), holes first; cut %4 mm, lead-ins %5 mm, rapids %6 mm; about %7 s</source>
        <translation>%1 个轮廓（%2 个孔，%3 个零件），先切孔；切割 %4 mm，引入线 %5 mm，快移 %6 mm；约 %7 s</translation>
    </message>
    <message>
        <source>Planned. Save the program, or load it into the controller.</source>
        <translation>已规划。保存程序或将其加载到控制器。</translation>
    </message>
    <message>
        <source>Cannot write %1: %2</source>
        <translation>无法写入 %1：%2</translation>
    </message>
    <message>
        <source>Saved %1.</source>
        <translation>已保存 %1。</translation>
    </message>
    <message>
        <source>Cannot make %1.</source>
        <translation>无法创建 %1。</translation>
    </message>
    <message>
        <source>Saved %1; not loaded: no link to the controller.</source>
        <translation>已保存 %1；未加载：与控制器无连接。</translation>
    </message>
    <message>
        <source>Loaded %1 into the controller (cycle start on the machine screen).</source>
        <translation>已将 %1 加载到控制器（在机床界面循环启动）。</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::DecompositionPage</name>
    <message>
        <source>Open drawing</source>
        <translation>打开图纸</translation>
    </message>
    <message>
        <source>DXF (*.dxf)</source>
        <translation>DXF (*.dxf)</translation>
    </message>
    <message>
        <source>Export kinematics table</source>
        <translation>导出运动学表</translation>
    </message>
    <message>
        <source>CSV (*.csv)</source>
        <translation>CSV (*.csv)</translation>
    </message>
    <message>
        <source>Drawing %1: set the options and decompose.</source>
        <translation>图纸 %1：设置参数后分解。</translation>
    </message>
    <message>
        <source>Decomposing…</source>
        <translation>分解中…</translation>
    </message>
    <message>
        <source>%1 contours, %2 points at %3 mm; time %4 s; peak main-axis acceleration %5 mm/s² (%6 g), effective %7 mm/s² — %8× lower on the main axes; aux excursion %9 mm; |S1 + S2 − S| ≤ %10 mm</source>
        <translation>%1 个轮廓，%2 个点，步长 %3 mm；时间 %4 s；主轴峰值加速度 %5 mm/s²（%6 g），有效加速度 %7 mm/s² —— 主轴降低 %8 倍；辅助轴偏移 %9 mm；|S1 + S2 − S| ≤ %10 mm</translation>
    </message>
    <message>
        <source>Decomposed.</source>
        <translation>分解完成。</translation>
    </message>
    <message numerus="yes">
        <source>The published algorithm breaks %n limit(s) (see the table&apos;s tooltips); the synchronous mode guarantees them.</source>
        <translation>
            <numerusform>原始算法超出 %n 项限值（见表格提示）；同步模式可保证限值。</numerusform>
        </translation>
    </message>
    <message>
        <source> line %1</source>
        <translation> 第 %1 行</translation>
    </message>
    <message>
        <source>Nothing to export: decompose a drawing first.</source>
        <translation>无可导出内容：请先分解图纸。</translation>
    </message>
    <message>
        <source>Cannot write %1.</source>
        <translation>无法写入 %1。</translation>
    </message>
    <message>
        <source>Exported %1.</source>
        <translation>已导出 %1。</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::DecompositionView</name>
    <message>
        <source>Open a DXF drawing and decompose it.</source>
        <translation>打开 DXF 图纸并进行分解。</translation>
    </message>
    <message>
        <source>S contour (green), S1 main axes X, Y (blue) — mm</source>
        <translation>S 轮廓（绿），S1 主轴 X、Y（蓝）—— mm</translation>
    </message>
    <message>
        <source>S2 = S − S1 auxiliary axes P, Q (red) in the field ±%1 mm</source>
        <translation>S2 = S − S1 辅助轴 P、Q（红），行程场 ±%1 mm</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::FocalPage</name>
    <message>
        <source>Hole</source>
        <translation>孔</translation>
    </message>
    <message>
        <source>X mm</source>
        <translation>X mm</translation>
    </message>
    <message>
        <source>Y mm</source>
        <translation>Y mm</translation>
    </message>
    <message>
        <source>Z mm</source>
        <translation>Z mm</translation>
    </message>
    <message>
        <source>Stored offset mm</source>
        <translation>已存偏移 mm</translation>
    </message>
    <message>
        <source>Distance mm</source>
        <translation>距离 mm</translation>
    </message>
    <message>
        <source>New offset mm</source>
        <translation>新偏移 mm</translation>
    </message>
    <message>
        <source>Status</source>
        <translation>状态</translation>
    </message>
    <message>
        <source>Tick the holes to measure first.</source>
        <translation>请先勾选要测量的孔。</translation>
    </message>
    <message>
        <source>No displacement sensor configured.</source>
        <translation>未配置位移传感器。</translation>
    </message>
    <message numerus="yes">
        <source>Measuring %n hole(s)…</source>
        <translation>
            <numerusform>正在测量 %n 个孔…</numerusform>
        </translation>
    </message>
    <message>
        <source>measured</source>
        <translation>已测量</translation>
    </message>
    <message numerus="yes">
        <source>%n hole(s) measured; save to store the offsets.</source>
        <translation>
            <numerusform>已测量 %n 个孔；保存以存储偏移量。</numerusform>
        </translation>
    </message>
    <message>
        <source>%1 measured, %2 not (see Status); save stores the measured ones.</source>
        <translation>已测量 %1 个，%2 个未测（见状态）；保存将存储已测量的。</translation>
    </message>
    <message>
        <source>Nothing measured to save.</source>
        <translation>没有可保存的测量结果。</translation>
    </message>
    <message numerus="yes">
        <source>Stored the focus offsets of %n hole(s).</source>
        <translation>
            <numerusform>已存储 %n 个孔的焦点偏移。</numerusform>
        </translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::HoleTableModel</name>
    <message>
        <source>hole %1: field 18 process = %2; allowed 0 helix, 1 circle, 2 free shape</source>
        <translation>孔 %1：字段 18 工艺 = %2；允许 0 螺旋、1 圆、2 自由形状</translation>
    </message>
    <message>
        <source>hole %1: %2 must be a whole number</source>
        <translation>孔 %1：%2 必须为整数</translation>
    </message>
    <message>
        <source>hole %1: %2 must be a number</source>
        <translation>孔 %1：%2 必须为数字</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::MachinePage</name>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>未发送：与控制器无连接。</translation>
    </message>
    <message>
        <source>Controller: link lost — %1</source>
        <translation>控制器：连接中断 —— %1</translation>
    </message>
    <message>
        <source>State: unknown</source>
        <translation>状态：未知</translation>
    </message>
    <message>
        <source>Controller: connected</source>
        <translation>控制器：已连接</translation>
    </message>
    <message>
        <source>State: %1</source>
        <translation>状态：%1</translation>
    </message>
    <message>
        <source>Code</source>
        <translation>代码</translation>
    </message>
    <message>
        <source>Line</source>
        <translation>行</translation>
    </message>
    <message>
        <source>What</source>
        <translation>内容</translation>
    </message>
    <message>
        <source>Time</source>
        <translation>时间</translation>
    </message>
    <message>
        <source>Count</source>
        <translation>次数</translation>
    </message>
    <message>
        <source>MDI: a line of at most %1 characters.</source>
        <translation>MDI：一行最多 %1 个字符。</translation>
    </message>
    <message numerus="yes">
        <source>%n to acknowledge</source>
        <translation>
            <numerusform>%n 条待确认</numerusform>
        </translation>
    </message>
    <message>
        <source>homed</source>
        <translation>已回零</translation>
    </message>
    <message>
        <source>not homed</source>
        <translation>未回零</translation>
    </message>
    <message>
        <source> — single block: Resume runs the next block</source>
        <translation> — 单段：“继续”执行下一段</translation>
    </message>
    <message>
        <source> — program pause: Resume goes on</source>
        <translation> — 程序暂停：按“继续”继续</translation>
    </message>
    <message>
        <source> — waiting for input %1</source>
        <translation> — 等待输入 %1</translation>
    </message>
    <message>
        <source>Laser: on, %1 %</source>
        <translation>激光：开，%1 %</translation>
    </message>
    <message>
        <source>Laser: off</source>
        <translation>激光：关</translation>
    </message>
    <message>
        <source>Program: %1</source>
        <translation>程序：%1</translation>
    </message>
    <message>
        <source>Program: none loaded</source>
        <translation>程序：未加载</translation>
    </message>
    <message>
        <source>Line %1</source>
        <translation>第 %1 行</translation>
    </message>
    <message>
        <source>Time left %1</source>
        <translation>剩余 %1</translation>
    </message>
    <message>
        <source>MDI</source>
        <translation>MDI</translation>
    </message>
    <message>
        <source>single block</source>
        <translation>单段</translation>
    </message>
    <message>
        <source>dry run</source>
        <translation>空运行</translation>
    </message>
    <message>
        <source>from line %1</source>
        <translation>从第 %1 行</translation>
    </message>
    <message>
        <source>Gas: high (M8)</source>
        <translation>气体：高压 (M8)</translation>
    </message>
    <message>
        <source>Gas: low (M7)</source>
        <translation>气体：低压 (M7)</translation>
    </message>
    <message>
        <source>Gas: off</source>
        <translation>气体：关</translation>
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
        <translation>机床</translation>
    </message>
    <message>
        <source>Process database</source>
        <translation>工艺数据库</translation>
    </message>
    <message>
        <source>3D measurement</source>
        <translation>三维测量</translation>
    </message>
    <message>
        <source>Focal length</source>
        <translation>焦距</translation>
    </message>
    <message>
        <source>Laser and head</source>
        <translation>激光器与扫描头</translation>
    </message>
    <message>
        <source>Main + auxiliary axes</source>
        <translation>主轴 + 辅助轴</translation>
    </message>
    <message>
        <source>Program</source>
        <translation>程序</translation>
    </message>
    <message>
        <source>Laser cutting</source>
        <translation>激光切割</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::MeasurePage</name>
    <message>
        <source>Point</source>
        <translation>点</translation>
    </message>
    <message>
        <source>Approach X, Y, Z mm; A, C °</source>
        <translation>接近位置 X、Y、Z mm；A、C °</translation>
    </message>
    <message>
        <source>Measured X, Y, Z mm</source>
        <translation>测量值 X、Y、Z mm</translation>
    </message>
    <message>
        <source>Residual mm</source>
        <translation>残差 mm</translation>
    </message>
    <message>
        <source>Apply the measured placement</source>
        <translation>应用测得的位姿</translation>
    </message>
    <message>
        <source>Move every hole of the process database onto the measured placement? Their X, Y, Z, A and C are read as drawing coordinates.</source>
        <translation>将工艺数据库中的所有孔变换到测得的位姿？其 X、Y、Z、A、C 按图纸坐标解读。</translation>
    </message>
    <message>
        <source>No 3D probe configured.</source>
        <translation>未配置三维测头。</translation>
    </message>
    <message>
        <source>Measuring: the machine moves to each point…</source>
        <translation>测量中：机床移动到各点…</translation>
    </message>
    <message>
        <source>Not measured: %1</source>
        <translation>未测量：%1</translation>
    </message>
    <message>
        <source>The block&apos;s datum corner at X %1 Y %2 Z %3 mm, turned %4° about Z, its top tilted %5°; residuals max %6 mm, rms %7 mm.</source>
        <translation>工件基准角位于 X %1 Y %2 Z %3 mm，绕 Z 旋转 %4°，顶面倾斜 %5°；残差最大 %6 mm，均方根 %7 mm。</translation>
    </message>
    <message>
        <source>Measured. Apply the placement to the holes when it looks right.</source>
        <translation>测量完成。确认无误后将位姿应用到孔。</translation>
    </message>
    <message>
        <source>Nothing measured to apply.</source>
        <translation>没有可应用的测量结果。</translation>
    </message>
    <message numerus="yes">
        <source>Moved %n hole(s) onto the measured placement.</source>
        <translation>
            <numerusform>已将 %n 个孔变换到测得的位姿。</numerusform>
        </translation>
    </message>
    <message>
        <source>; %1, %2 (planned)</source>
        <translation>; %1, %2（计划）</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ProcessDbPage</name>
    <message>
        <source>Stored.</source>
        <translation>已保存。</translation>
    </message>
    <message>
        <source>Import hole table</source>
        <translation>导入孔表</translation>
    </message>
    <message>
        <source>CSV (*.csv)</source>
        <translation>CSV (*.csv)</translation>
    </message>
    <message>
        <source>Export hole table</source>
        <translation>导出孔表</translation>
    </message>
    <message numerus="yes">
        <source>%n hole(s)</source>
        <translation>
            <numerusform>%n 个孔</numerusform>
        </translation>
    </message>
    <message>
        <source>Imported %1.</source>
        <translation>已导入 %1。</translation>
    </message>
    <message>
        <source>Exported %1.</source>
        <translation>已导出 %1。</translation>
    </message>
    <message>
        <source>Hole %1 added.</source>
        <translation>已添加孔 %1。</translation>
    </message>
    <message>
        <source>No holes to send.</source>
        <translation>没有可发送的孔。</translation>
    </message>
    <message>
        <source>Cannot write %1.</source>
        <translation>无法写入 %1。</translation>
    </message>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>未发送：与控制器无连接。</translation>
    </message>
    <message>
        <source>Sent %1 holes (%2 with a measured focus offset) to the controller; start the cycle on the machine screen.</source>
        <translation>已将 %1 个孔（其中 %2 个带测得的焦点偏移）发送到控制器；请在机床画面启动循环。</translation>
    </message>
    <message>
        <source>No holes yet.</source>
        <translation>尚无孔。</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ProgramPage</name>
    <message>
        <source>Open program</source>
        <translation>打开程序</translation>
    </message>
    <message>
        <source>G-code (*.ngc *.nc *.gcode);;All (*)</source>
        <translation>G 代码 (*.ngc *.nc *.gcode);;全部 (*)</translation>
    </message>
    <message>
        <source>Checking and planning %1…</source>
        <translation>正在检查并规划 %1…</translation>
    </message>
    <message>
        <source>%1 lines; path %2 mm; planned time %3 s; peak speed %4 mm/s; %5 points drawn</source>
        <translation>%1 行；路径 %2 mm；规划时间 %3 s；峰值速度 %4 mm/s；绘制 %5 个点</translation>
    </message>
    <message>
        <source>Planned. Load it into the controller to run it.</source>
        <translation>规划完成。载入控制器即可运行。</translation>
    </message>
    <message>
        <source>Not sent: no link to the controller.</source>
        <translation>未发送：与控制器无连接。</translation>
    </message>
    <message>
        <source>Sent to the controller; its answer shows on the machine screen.</source>
        <translation>已发送到控制器；其应答显示在机床画面上。</translation>
    </message>
</context>
<context>
    <name>lcnc::hmi::ToolpathView</name>
    <message>
        <source>Open a program to see its toolpath as planned.</source>
        <translation>打开程序以查看规划后的刀具路径。</translation>
    </message>
    <message>
        <source>mm/s</source>
        <translation>mm/s</translation>
    </message>
    <message>
        <source>Cut: X %1 … %2, Y %3 … %4, Z %5 … %6 mm; grid %7 mm</source>
        <translation>切割：X %1 … %2，Y %3 … %4，Z %5 … %6 mm；网格 %7 mm</translation>
    </message>
    <message>
        <source>cut (colour: speed)</source>
        <translation>切割（颜色：速度）</translation>
    </message>
    <message>
        <source>feed, laser off</source>
        <translation>进给，激光关</translation>
    </message>
    <message>
        <source>rapid</source>
        <translation>快速移动</translation>
    </message>
    <message>
        <source>tool axis</source>
        <translation>刀具轴线</translation>
    </message>
</context>
</TS>
