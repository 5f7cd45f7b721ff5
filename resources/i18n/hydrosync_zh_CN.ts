<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="zh_CN" sourcelanguage="en">
    <context>
        <name>hydrosync</name>
        <message>
            <source>&amp;About HydroSync</source>
            <translation>关于 HydroSync(&amp;A)</translation>
        </message>
        <message>
            <source>&amp;Edit</source>
            <translation>编辑(&amp;E)</translation>
        </message>
        <message>
            <source>&amp;Export report…</source>
            <translation>导出报告(&amp;E)…</translation>
        </message>
        <message>
            <source>&amp;File</source>
            <translation>文件(&amp;F)</translation>
        </message>
        <message>
            <source>&amp;Help</source>
            <translation>帮助(&amp;H)</translation>
        </message>
        <message>
            <source>&amp;Import…</source>
            <translation>导入(&amp;I)…</translation>
        </message>
        <message>
            <source>&amp;Language</source>
            <translation>语言(&amp;L)</translation>
        </message>
        <message>
            <source>&amp;New</source>
            <translation>新建(&amp;N)</translation>
        </message>
        <message>
            <source>&amp;Open…</source>
            <translation>打开(&amp;O)…</translation>
        </message>
        <message>
            <source>&amp;Plugins…</source>
            <translation>插件(&amp;P)…</translation>
        </message>
        <message>
            <source>&amp;Quit</source>
            <translation>退出(&amp;Q)</translation>
        </message>
        <message>
            <source>&amp;Save</source>
            <translation>保存(&amp;S)</translation>
        </message>
        <message>
            <source>&amp;Vessel offsets…</source>
            <translation>船体偏移量(&amp;V)…</translation>
        </message>
        <message>
            <source>&amp;View</source>
            <translation>视图(&amp;V)</translation>
        </message>
        <message>
            <source>(no recent projects)</source>
            <translation>(无最近项目)</translation>
        </message>
        <message>
            <source>(not saved)</source>
            <translation>(未保存)</translation>
        </message>
        <message>
            <source>(not set in the vessel sheet)</source>
            <translation>(船舶参数表中未设置)</translation>
        </message>
        <message>
            <source>(unnamed)</source>
            <translation>(未命名)</translation>
        </message>
        <message>
            <source>3 × the median INS interval</source>
            <translation>3 × 惯导数据间隔中值</translation>
        </message>
        <message>
            <source>95 % interval</source>
            <translation>95 % 区间</translation>
        </message>
        <message>
            <source>95 % interval of Δt</source>
            <translation>Δt 的 95 % 区间</translation>
        </message>
        <message>
            <source>; INS attitude taken as exact (no INS accuracy given): σ are a lower bound</source>
            <translation>;惯导姿态视为无误差(未给出惯导精度):σ 为下限</translation>
        </message>
        <message>
            <source>&lt;h3&gt;No analysis plugin is available&lt;/h3&gt;&lt;p&gt;See Help → Plugins and the log for what failed to load.&lt;/p&gt;</source>
            <translation>&lt;h3&gt;没有可用的分析插件&lt;/h3&gt;&lt;p&gt;请查看“帮助 → 插件”和日志,了解加载失败的原因。&lt;/p&gt;</translation>
        </message>
        <message>
            <source>&lt;span style='color:#777'&gt;no iterations yet (Run all)&lt;/span&gt;</source>
            <translation>&lt;span style='color:#777'&gt;尚无迭代(全部运行)&lt;/span&gt;</translation>
        </message>
        <message>
            <source>&lt;span style='color:#d62728'&gt;━&lt;/span&gt;&amp;nbsp;Δ roll&amp;nbsp;&amp;nbsp; &lt;span style='color:#1f77b4'&gt;━&lt;/span&gt;&amp;nbsp;Δ pitch&amp;nbsp;&amp;nbsp; &lt;span style='color:#2ca02c'&gt;━&lt;/span&gt;&amp;nbsp;Δ yaw&amp;nbsp;&amp;nbsp; &lt;span style='color:#6e6e6e'&gt;╌&lt;/span&gt;&amp;nbsp;tolerance&amp;nbsp;&amp;nbsp; &lt;span style='color:#aaa'&gt;┆&lt;/span&gt;&amp;nbsp;new round</source>
            <translation>&lt;span style='color:#d62728'&gt;━&lt;/span&gt;&amp;nbsp;Δ 横摇&amp;nbsp;&amp;nbsp; &lt;span style='color:#1f77b4'&gt;━&lt;/span&gt;&amp;nbsp;Δ 纵摇&amp;nbsp;&amp;nbsp; &lt;span style='color:#2ca02c'&gt;━&lt;/span&gt;&amp;nbsp;Δ 艏摇&amp;nbsp;&amp;nbsp; &lt;span style='color:#6e6e6e'&gt;╌&lt;/span&gt;&amp;nbsp;收敛阈值&amp;nbsp;&amp;nbsp; &lt;span style='color:#aaa'&gt;┆&lt;/span&gt;&amp;nbsp;新一轮</translation>
        </message>
        <message>
            <source>A task is running</source>
            <translation>有任务正在运行</translation>
        </message>
        <message>
            <source>A-priori σ horizontal</source>
            <translation>水平先验 σ</translation>
        </message>
        <message>
            <source>A-priori σ vertical</source>
            <translation>垂直先验 σ</translation>
        </message>
        <message>
            <source>Accelerometer bias σ</source>
            <translation>加速度计零偏 σ</translation>
        </message>
        <message>
            <source>Accelerometer block</source>
            <translation>加速度计分块</translation>
        </message>
        <message>
            <source>Accepted solutions</source>
            <translation>采用的解</translation>
        </message>
        <message>
            <source>Add sensor</source>
            <translation>添加传感器</translation>
        </message>
        <message>
            <source>Advanced</source>
            <translation>高级</translation>
        </message>
        <message>
            <source>After (final values)</source>
            <translation>之后(最终值)</translation>
        </message>
        <message>
            <source>Alignment</source>
            <translation>对准</translation>
        </message>
        <message>
            <source>Alpha</source>
            <translation>透明度</translation>
        </message>
        <message>
            <source>Angle tolerance</source>
            <translation>角度收敛阈值</translation>
        </message>
        <message>
            <source>Antennas</source>
            <translation>天线</translation>
        </message>
        <message>
            <source>Appendix: data sources</source>
            <translation>附录:数据来源</translation>
        </message>
        <message>
            <source>Appendix: data sources, vessel offsets and survey lines</source>
            <translation>附录:数据来源、船体偏移量与测线</translation>
        </message>
        <message>
            <source>Appendix: pool calibration, every patent iteration</source>
            <translation>附录:水池检校,专利方法的每次迭代</translation>
        </message>
        <message>
            <source>Apply to vessel sheet</source>
            <translation>应用到船舶参数表</translation>
        </message>
        <message>
            <source>Apply to vessel sheet…</source>
            <translation>应用到船舶参数表…</translation>
        </message>
        <message>
            <source>Approved by</source>
            <translation>审批</translation>
        </message>
        <message>
            <source>Attitude error against the reference (solution − reference, °), forward and smoothed; dashed: ±1σ of each solution.</source>
            <translation>相对参考的姿态误差(解 − 参考,°),前向滤波和平滑后;虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Attitude error against the reference (solution − reference, °), forward and smoothed; dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的姿态误差(解 − 参考,°),前向滤波和平滑后;虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Attitude error against the reference (solution − reference, °), forward only (no smoothing); dashed: ±1σ of each solution.</source>
            <translation>相对参考的姿态误差(解 − 参考,°),仅前向滤波(无平滑);虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Attitude error against the reference (solution − reference, °), forward only (no smoothing); dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的姿态误差(解 − 参考,°),仅前向滤波(无平滑);虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Attitude from a GNSS antenna array</source>
            <translation>GNSS 天线阵列定姿</translation>
        </message>
        <message>
            <source>Auto</source>
            <translation>自动</translation>
        </message>
        <message>
            <source>Auto Pan Only</source>
            <translation>仅自动平移</translation>
        </message>
        <message>
            <source>Average</source>
            <translation>平均</translation>
        </message>
        <message>
            <source>BGD</source>
            <translation>BGD</translation>
        </message>
        <message>
            <source>BGD iterates</source>
            <translation>BGD 迭代过程</translation>
        </message>
        <message>
            <source>Band refit width</source>
            <translation>带状重拟合宽度</translation>
        </message>
        <message>
            <source>Baseline length tolerance</source>
            <translation>基线长度容差</translation>
        </message>
        <message>
            <source>Baseline residuals</source>
            <translation>基线残差</translation>
        </message>
        <message>
            <source>Before (coarse setup)</source>
            <translation>之前(粗标定)</translation>
        </message>
        <message>
            <source>Boresight and lever arm (body FRD)</source>
            <translation>安装偏角与杆臂(载体坐标系 FRD)</translation>
        </message>
        <message>
            <source>Boresight angles and lever arm: the coarse values of the installation drawing, the patent method's and the joint adjustment's solutions, and the final values to enter in the acquisition software. An undetermined parameter keeps its coarse value (no σ); a parameter whose σ exceeds the warning threshold is flagged.</source>
            <translation>安装偏角与杆臂:安装图给出的粗值、专利方法与联合平差的解,以及应输入采集软件的最终值。无法确定的参数保留其粗值(无 σ);σ 超过警告阈值的参数予以标记。</translation>
        </message>
        <message>
            <source>Boresight corrections of each iteration (about the body axes), the accumulated angles and the largest remaining normal angle.</source>
            <translation>每次迭代的安装偏角改正(绕载体坐标轴)、累计角度及剩余的最大法向夹角。</translation>
        </message>
        <message>
            <source>Boresight pitch</source>
            <translation>纵摇安装偏角</translation>
        </message>
        <message>
            <source>Boresight pitch (final, 1σ)</source>
            <translation>纵摇安装偏角(最终值,1σ)</translation>
        </message>
        <message>
            <source>Boresight roll</source>
            <translation>横摇安装偏角</translation>
        </message>
        <message>
            <source>Boresight roll (final, 1σ)</source>
            <translation>横摇安装偏角(最终值,1σ)</translation>
        </message>
        <message>
            <source>Boresight yaw</source>
            <translation>艏摇安装偏角</translation>
        </message>
        <message>
            <source>Boresight yaw (final, 1σ)</source>
            <translation>艏摇安装偏角(最终值,1σ)</translation>
        </message>
        <message>
            <source>Browse…</source>
            <translation>浏览…</translation>
        </message>
        <message>
            <source>Build tolerance</source>
            <translation>建造容差</translation>
        </message>
        <message>
            <source>Build tolerance (orientation)</source>
            <translation>建造容差(姿态)</translation>
        </message>
        <message>
            <source>Build tolerance (position)</source>
            <translation>建造容差(位置)</translation>
        </message>
        <message>
            <source>Campaign file</source>
            <translation>批处理文件</translation>
        </message>
        <message>
            <source>Cancel</source>
            <translation>取消</translation>
        </message>
        <message>
            <source>Cancel the running task</source>
            <translation>取消正在运行的任务</translation>
        </message>
        <message>
            <source>Cancel the running task and quit?</source>
            <translation>取消正在运行的任务并退出?</translation>
        </message>
        <message>
            <source>Cancelled: the steps that finished are saved in their projects; running the campaign again does only the rest.</source>
            <translation>已取消:已完成的步骤保存在各自项目中;再次运行批处理只做其余部分。</translation>
        </message>
        <message>
            <source>Cancelling: steps already finished stay saved…</source>
            <translation>正在取消:已完成的步骤保持已保存…</translation>
        </message>
        <message>
            <source>Cannot open project</source>
            <translation>无法打开项目</translation>
        </message>
        <message>
            <source>Carries</source>
            <translation>所含内容</translation>
        </message>
        <message>
            <source>Caveat</source>
            <translation>注意事项</translation>
        </message>
        <message>
            <source>Checked by</source>
            <translation>校核</translation>
        </message>
        <message>
            <source>Choose…</source>
            <translation>选择…</translation>
        </message>
        <message>
            <source>Clear list</source>
            <translation>清除列表</translation>
        </message>
        <message>
            <source>Clip to View</source>
            <translation>裁剪到视图</translation>
        </message>
        <message>
            <source>Close</source>
            <translation>关闭</translation>
        </message>
        <message>
            <source>Cluster distance (laser)</source>
            <translation>聚类距离(激光)</translation>
        </message>
        <message>
            <source>Cluster distance (multibeam)</source>
            <translation>聚类距离(多波束)</translation>
        </message>
        <message>
            <source>Coarse</source>
            <translation>粗值</translation>
        </message>
        <message>
            <source>Coarse (setup)</source>
            <translation>粗值(安装)</translation>
        </message>
        <message>
            <source>Coarse setup accuracy (angles)</source>
            <translation>粗标定精度(角度)</translation>
        </message>
        <message>
            <source>Coarse setup accuracy (lever arm)</source>
            <translation>粗标定精度(杆臂)</translation>
        </message>
        <message>
            <source>Computed</source>
            <translation>计算时间</translation>
        </message>
        <message>
            <source>Computed (UTC, version)</source>
            <translation>计算时间(UTC,版本)</translation>
        </message>
        <message>
            <source>Constant offset from the reference (mean of solution − reference) and the share of epochs within 1.96σ, as is / with that offset removed.</source>
            <translation>相对参考的恒定偏差(解 − 参考的均值),以及误差在 1.96σ 以内的历元比例:原样 / 去除该偏差后。</translation>
        </message>
        <message>
            <source>Constraint interval</source>
            <translation>约束间隔</translation>
        </message>
        <message>
            <source>Contents</source>
            <translation>目录</translation>
        </message>
        <message>
            <source>Convergence of the patent's angle iteration</source>
            <translation>专利角度迭代的收敛过程</translation>
        </message>
        <message>
            <source>Convergence of the patent's iteration (steps 3.1–3.6): the largest angle between corresponding plane normals after each boresight update.</source>
            <translation>专利迭代的收敛过程(步骤 3.1–3.6):每次安装偏角更新后对应平面法向间的最大夹角。</translation>
        </message>
        <message>
            <source>Convergence threshold</source>
            <translation>收敛阈值</translation>
        </message>
        <message>
            <source>Correction (final − coarse)</source>
            <translation>改正量(最终 − 粗值)</translation>
        </message>
        <message>
            <source>Correlation R between detrended GNSS height and total heave as a function of the trial latency Δt, one curve per line (eq. 4) over the whole scan range.</source>
            <translation>去趋势 GNSS 高程与总升沉之间的相关系数 R 随试算时间延迟 Δt 的变化,每条测线一条曲线(式 4),覆盖整个搜索范围。</translation>
        </message>
        <message>
            <source>Correlation matrix of the joint adjustment's parameters. Values above 0.9 in magnitude (red) mean the pass geometry barely separates the two parameters.</source>
            <translation>联合平差参数的相关矩阵。绝对值大于 0.9(红色)表示测量几何几乎无法区分这两个参数。</translation>
        </message>
        <message>
            <source>Covariance step</source>
            <translation>协方差步长</translation>
        </message>
        <message>
            <source>Crop tolerance</source>
            <translation>裁剪容差</translation>
        </message>
        <message>
            <source>DBSCAN neighbourhood of the laser face clusters</source>
            <translation>激光面聚类的 DBSCAN 邻域</translation>
        </message>
        <message>
            <source>DBSCAN neighbourhood of the sounding face clusters</source>
            <translation>测深点面聚类的 DBSCAN 邻域</translation>
        </message>
        <message>
            <source>Dask scheduler</source>
            <translation>Dask 调度器</translation>
        </message>
        <message>
            <source>Data ready. &lt;b&gt;Segment&lt;/b&gt; to check the faces found with the coarse setup, or &lt;b&gt;Run all&lt;/b&gt; to calibrate.</source>
            <translation>数据已就绪。按&lt;b&gt;分割&lt;/b&gt;检查用粗标定找到的各面,或按&lt;b&gt;全部运行&lt;/b&gt;进行检校。</translation>
        </message>
        <message>
            <source>Data ready. Check the lever arm and press Run.</source>
            <translation>数据已就绪。请检查杆臂后按“运行”。</translation>
        </message>
        <message>
            <source>Date</source>
            <translation>日期</translation>
        </message>
        <message>
            <source>Delay of the GNSS time tags relative to the attitude/heave time tags, by correlating detrended RTK heights with total heave (Qi et al. 2010).</source>
            <translation>GNSS 时间标签相对姿态/升沉时间标签的时间延迟,由去趋势 RTK 高程与总升沉的相关求得(Qi 等 2010)。</translation>
        </message>
        <message>
            <source>Detail of the correlation peaks: each dot is one line's (Δt, R&lt;sub&gt;max&lt;/sub&gt;), the vertical line the weighted mean and the band its 95 % interval.</source>
            <translation>相关峰细节:每个点为一条测线的 (Δt, R&lt;sub&gt;max&lt;/sub&gt;),竖线为加权平均,色带为其 95 % 区间。</translation>
        </message>
        <message>
            <source>Details</source>
            <translation>详情</translation>
        </message>
        <message>
            <source>Detrend degree</source>
            <translation>去趋势阶数</translation>
        </message>
        <message>
            <source>Direct-method antennas</source>
            <translation>直接法天线</translation>
        </message>
        <message>
            <source>Down-sample above</source>
            <translation>超过此点数则降采样</translation>
        </message>
        <message>
            <source>Downsample</source>
            <translation>降采样</translation>
        </message>
        <message>
            <source>Drift across simulated GNSS outages.</source>
            <translation>模拟 GNSS 中断期间的漂移。</translation>
        </message>
        <message>
            <source>East</source>
            <translation>东</translation>
        </message>
        <message>
            <source>Elevation of the target seen from the vessel (north against up): laser points above the water line and multibeam soundings below it, georeferenced with the final values and coloured by the role of their face; design outlines in grey.</source>
            <translation>从船上看目标物的立面图(北向对天向):水线以上为激光点,水线以下为多波束测深点,用最终值进行地理参考,并按所在面的作用着色;设计轮廓为灰色。</translation>
        </message>
        <message>
            <source>Epoch matching</source>
            <translation>历元匹配</translation>
        </message>
        <message>
            <source>Epoch screening.</source>
            <translation>历元筛选。</translation>
        </message>
        <message>
            <source>Epochs</source>
            <translation>历元</translation>
        </message>
        <message>
            <source>Epochs matched / solved</source>
            <translation>匹配 / 解算历元数</translation>
        </message>
        <message>
            <source>Epochs solved</source>
            <translation>解算历元数</translation>
        </message>
        <message>
            <source>Epochs with an antenna dropped (length check)</source>
            <translation>舍弃了天线的历元数(长度检验)</translation>
        </message>
        <message>
            <source>Epochs with fewer than 3 usable antennas</source>
            <translation>可用天线少于 3 个的历元数</translation>
        </message>
        <message>
            <source>GNSS/INS trajectory, forward filter only (no smoothing)</source>
            <translation>GNSS/INS 轨迹,仅前向滤波(无平滑)</translation>
        </message>
        <message>
            <source>Position error against the reference (solution − reference, m), forward and smoothed; dashed: ±1σ of each solution.</source>
            <translation>相对参考的位置误差(解 − 参考,m),前向滤波和平滑后;虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Position error against the reference (solution − reference, m), forward only (no smoothing); dashed: ±1σ of each solution.</source>
            <translation>相对参考的位置误差(解 − 参考,m),仅前向滤波(无平滑);虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Position error against the reference (solution − reference, m), forward only (no smoothing); dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的位置误差(解 − 参考,m),仅前向滤波(无平滑);虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Position errors (±σ)</source>
            <translation>位置误差(±σ)</translation>
        </message>
        <message>
            <source>Standard deviations of the forward filter (no smoothing in this run).</source>
            <translation>前向滤波的标准差(本次运行未平滑)。</translation>
        </message>
        <message>
            <source>The reference is compared as it is: its own accuracy is not known to this analysis, and a reference computed from the same sensors is not an independent truth. A constant offset (below) is the reference's own axes or point — e.g. a camera whose mounting on the IMU is not given — which no σ of this solution can know about.</source>
            <translation>参考轨迹按原样比较:本分析不知道其自身精度;由同一批传感器计算的参考轨迹不是独立的真值。恒定偏差(见下表)来自参考轨迹自身的坐标轴或参考点(例如安装关系未给出的相机),本解的任何 σ 都无法反映。</translation>
        </message>
        <message>
            <source>Trajectory: GNSS antenna fixes, forward (no smoothing) IMU positions (local east/north from the start).</source>
            <translation>轨迹:GNSS 天线定位、前向滤波(无平滑)的 IMU 位置(以起点为原点的当地东/北坐标)。</translation>
        </message>
        <message>
            <source>Velocity error against the reference (solution − reference, m/s), forward and smoothed; dashed: ±1σ of each solution.</source>
            <translation>相对参考的速度误差(解 − 参考,m/s),前向滤波和平滑后;虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Velocity error against the reference (solution − reference, m/s), forward only (no smoothing); dashed: ±1σ of each solution.</source>
            <translation>相对参考的速度误差(解 − 参考,m/s),仅前向滤波(无平滑);虚线:各解的 ±1σ。</translation>
        </message>
        <message>
            <source>Velocity error against the reference (solution − reference, m/s), forward only (no smoothing); dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的速度误差(解 − 参考,m/s),仅前向滤波(无平滑);虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Velocity errors (±σ)</source>
            <translation>速度误差(±σ)</translation>
        </message>
        <message>
            <source>Attitude errors (±σ)</source>
            <translation>姿态误差(±σ)</translation>
        </message>
        <message>
            <source>Estimator</source>
            <translation>估计方法</translation>
        </message>
        <message>
            <source>Estimator: &lt;b&gt;weighted&lt;/b&gt;, beyond the publication: the high-rate total heave is low-passed to the GNSS band (zero-phase) before eq. 3, and both series are weighted per frequency by their coherence pooled over the day's lines (maximum-likelihood generalised cross-correlation, Knapp and Carter 1976); R&lt;sub&gt;max&lt;/sub&gt; and the curves are the anti-aliased correlation, Δt and σ come from the weighted one. The published estimator stays available (parameter &lt;i&gt;estimator&lt;/i&gt; = qi2010).</source>
            <translation>估计方法:&lt;b&gt;weighted&lt;/b&gt;,超出论文的部分:在式 3 之前先将高频总升沉低通滤波(零相位)到 GNSS 频带,两组序列按当天各测线汇总的相干性逐频率加权(最大似然广义互相关,Knapp 和 Carter 1976);R&lt;sub&gt;max&lt;/sub&gt; 和曲线为抗混叠后的相关,Δt 和 σ 取自加权相关。论文方法仍可使用(参数 &lt;i&gt;estimator&lt;/i&gt; = qi2010)。</translation>
        </message>
        <message>
            <source>Estimator: the published one (raw series), as in Qi et al. (2010).</source>
            <translation>估计方法:论文方法(原始序列),同 Qi 等(2010)。</translation>
        </message>
        <message>
            <source>Every</source>
            <translation>每隔</translation>
        </message>
        <message>
            <source>Export JSON…</source>
            <translation>导出 JSON…</translation>
        </message>
        <message>
            <source>Export report</source>
            <translation>导出报告</translation>
        </message>
        <message>
            <source>Export vessel sheet</source>
            <translation>导出船舶参数表</translation>
        </message>
        <message>
            <source>Exporting report</source>
            <translation>正在导出报告</translation>
        </message>
        <message>
            <source>Face</source>
            <translation>面</translation>
        </message>
        <message>
            <source>Face (multibeam)</source>
            <translation>面(多波束)</translation>
        </message>
        <message>
            <source>Face edge margin</source>
            <translation>面边缘余量</translation>
        </message>
        <message>
            <source>Face pairing and reference planes</source>
            <translation>面的配对与参考平面</translation>
        </message>
        <message>
            <source>Results</source>
            <translation>结果</translation>
        </message>
        <message>
            <source>Convergence</source>
            <translation>收敛</translation>
        </message>
        <message>
            <source>Faces</source>
            <translation>面</translation>
        </message>
        <message>
            <source>Faces of the target design, their role inferred from geometry, points segmented in each cloud, plane-fit RMS, the angle between the laser and the final multibeam plane normals, and the parameters each face determines.</source>
            <translation>目标物设计中的各面、由几何推断的作用、各点云中分割出的点数、平面拟合 RMS、激光与最终多波束平面法向的夹角,以及各面所确定的参数。</translation>
        </message>
        <message>
            <source>Fewest vectors</source>
            <translation>最少矢量数</translation>
        </message>
        <message>
            <source>File</source>
            <translation>文件</translation>
        </message>
        <message>
            <source>Final</source>
            <translation>最终值</translation>
        </message>
        <message>
            <source>Final (joint)</source>
            <translation>最终值(联合)</translation>
        </message>
        <message>
            <source>Final latency Δt (1σ)</source>
            <translation>最终时间延迟 Δt(1σ)</translation>
        </message>
        <message>
            <source>Final values</source>
            <translation>最终值</translation>
        </message>
        <message>
            <source>Final values from</source>
            <translation>最终值来源</translation>
        </message>
        <message>
            <source>Flag above σ (angles)</source>
            <translation>σ 超过此值则标记(角度)</translation>
        </message>
        <message>
            <source>Flag above σ (lever arm)</source>
            <translation>σ 超过此值则标记(杆臂)</translation>
        </message>
        <message>
            <source>Forget hidden traces</source>
            <translation>忽略隐藏曲线</translation>
        </message>
        <message>
            <source>Forward horizontal RMS / yaw RMS vs reference</source>
            <translation>前向滤波相对参考的水平 RMS / 艏摇 RMS</translation>
        </message>
        <message>
            <source>Forward outage drift (max horizontal)</source>
            <translation>前向滤波中断漂移(最大水平)</translation>
        </message>
        <message>
            <source>GGA fix qualities used: auto = only RTK fixed (4) when the log has any, else all with a warning naming them; or a list such as '4,5'</source>
            <translation>采用的 GGA 解算质量:auto = 日志中有 RTK 固定解(4)时只用固定解,否则全部采用并发出警告列出它们;或列表,如 '4,5'</translation>
        </message>
        <message>
            <source>GNSS</source>
            <translation>GNSS</translation>
        </message>
        <message>
            <source>GNSS Attitude</source>
            <translation>GNSS 定姿</translation>
        </message>
        <message>
            <source>GNSS antenna phase centre relative to the motion sensor, body frame x forward, y starboard, z down; default: from the vessel sheet</source>
            <translation>GNSS 天线相位中心相对于姿态传感器的位置,载体坐标系 x 向前、y 向右舷、z 向下;默认取自船舶参数表</translation>
        </message>
        <message>
            <source>GNSS attitude: processing parameters.</source>
            <translation>GNSS 定姿:处理参数。</translation>
        </message>
        <message>
            <source>GNSS error correlation time</source>
            <translation>GNSS 误差相关时间</translation>
        </message>
        <message>
            <source>GNSS fix qualities</source>
            <translation>GNSS 解算质量</translation>
        </message>
        <message>
            <source>GNSS fixes in span / used</source>
            <translation>时段内 / 采用的 GNSS 定位数</translation>
        </message>
        <message>
            <source>GNSS height</source>
            <translation>GNSS 高程</translation>
        </message>
        <message>
            <source>GNSS height, detrended</source>
            <translation>GNSS 高程(去趋势)</translation>
        </message>
        <message>
            <source>GNSS innovation gate</source>
            <translation>GNSS 新息门限</translation>
        </message>
        <message>
            <source>GNSS noise model</source>
            <translation>GNSS 噪声模型</translation>
        </message>
        <message>
            <source>GNSS σ horizontal</source>
            <translation>GNSS 水平 σ</translation>
        </message>
        <message>
            <source>GNSS σ scale</source>
            <translation>GNSS σ 比例因子</translation>
        </message>
        <message>
            <source>GNSS σ vertical</source>
            <translation>GNSS 垂直 σ</translation>
        </message>
        <message>
            <source>GNSS/INS Smoother</source>
            <translation>GNSS/INS 组合导航平滑</translation>
        </message>
        <message>
            <source>GNSS/INS smoother: processing parameters.</source>
            <translation>GNSS/INS 组合导航平滑:处理参数。</translation>
        </message>
        <message>
            <source>GNSS/INS trajectory with RTS smoothing</source>
            <translation>RTS 反向平滑的 GNSS/INS 轨迹</translation>
        </message>
        <message>
            <source>Gap factor</source>
            <translation>间断因子</translation>
        </message>
        <message>
            <source>Gaps / longest</source>
            <translation>间断数 / 最长</translation>
        </message>
        <message>
            <source>Gauss–Markov correlation time of the INS attitude errors</source>
            <translation>惯导姿态误差的高斯–马尔可夫相关时间</translation>
        </message>
        <message>
            <source>Goes to:</source>
            <translation>导入到:</translation>
        </message>
        <message>
            <source>Gravity</source>
            <translation>重力</translation>
        </message>
        <message>
            <source>Grid</source>
            <translation>网格</translation>
        </message>
        <message>
            <source>Gyro bias σ</source>
            <translation>陀螺零偏 σ</translation>
        </message>
        <message>
            <source>H RMS</source>
            <translation>水平 RMS</translation>
        </message>
        <message>
            <source>Heading</source>
            <translation>航向</translation>
        </message>
        <message>
            <source>Heading / pitch / roll</source>
            <translation>航向 / 纵摇 / 横摇</translation>
        </message>
        <message>
            <source>Heading errors (Monte Carlo)</source>
            <translation>航向误差(蒙特卡洛)</translation>
        </message>
        <message>
            <source>Heading formal 1σ, RMS (least squares)</source>
            <translation>航向形式 1σ,RMS(最小二乘)</translation>
        </message>
        <message>
            <source>Heading, pitch and roll from the baselines between the antennas, rotated from ECEF to the local level frame at the array position: the three-antenna direct method and the iterative weighted least squares of Liu et al., and the optimal closed-form (Wahba) rotation as a cross-check. Angles in degrees; heading clockwise from north, pitch bow up, roll starboard down.</source>
            <translation>由天线间基线求得的航向、纵摇和横摇,从 ECEF 旋转到天线阵列处的当地水平坐标系:Liu 等的三天线直接法和迭代加权最小二乘,并以闭合形式最优旋转(Wahba)作为交叉检核。角度单位为度;航向自北顺时针,纵摇艏抬升为正,横摇右舷下沉为正。</translation>
        </message>
        <message>
            <source>Heading, pitch and roll from three or more GNSS antennas: direct method and iterative least squares (Liu et al.), closed-form Wahba cross-check, precision prediction.</source>
            <translation>由三个或更多 GNSS 天线求航向、纵摇和横摇:直接法和迭代最小二乘(Liu 等),闭合形式 Wahba 交叉检核,精度预测。</translation>
        </message>
        <message>
            <source>Heading-error histogram of the simulated swings (cf. Li et al., fig. 4).</source>
            <translation>模拟摆动的航向误差直方图(参见 Li 等,图 4)。</translation>
        </message>
        <message>
            <source>Heave filter</source>
            <translation>升沉滤波器</translation>
        </message>
        <message>
            <source>Heave filter cut-off period</source>
            <translation>升沉滤波器截止周期</translation>
        </message>
        <message>
            <source>Heave filter order</source>
            <translation>升沉滤波器阶数</translation>
        </message>
        <message>
            <source>Heave sign in file</source>
            <translation>文件中的升沉符号</translation>
        </message>
        <message>
            <source>Heave:</source>
            <translation>升沉:</translation>
        </message>
        <message>
            <source>Horizontal tip errors of the simulated swings (cf. Li et al., figs. 6-9).</source>
            <translation>模拟摆动的杆尖水平误差(参见 Li 等,图 6-9)。</translation>
        </message>
        <message>
            <source>Huber threshold</source>
            <translation>Huber 阈值</translation>
        </message>
        <message>
            <source>HydroSync — unexpected error</source>
            <translation>HydroSync — 意外错误</translation>
        </message>
        <message>
            <source>IMU epochs</source>
            <translation>IMU 历元数</translation>
        </message>
        <message>
            <source>IMU epochs / GNSS fixes used</source>
            <translation>IMU 历元数 / 采用的 GNSS 定位数</translation>
        </message>
        <message>
            <source>IMU grade</source>
            <translation>IMU 等级</translation>
        </message>
        <message>
            <source>IMU mounting angles</source>
            <translation>IMU 安装角</translation>
        </message>
        <message>
            <source>IMU samples</source>
            <translation>IMU 采样</translation>
        </message>
        <message>
            <source>INS accuracy (1σ)</source>
            <translation>惯导精度(1σ)</translation>
        </message>
        <message>
            <source>INS attitude</source>
            <translation>惯导姿态</translation>
        </message>
        <message>
            <source>INS attitude taken as exact (no INS accuracy given): the σ are a lower bound</source>
            <translation>惯导姿态视为无误差(未给出惯导精度):σ 为下限</translation>
        </message>
        <message>
            <source>INS error correlation time</source>
            <translation>惯导误差相关时间</translation>
        </message>
        <message>
            <source>INS gap</source>
            <translation>惯导数据间断</translation>
        </message>
        <message>
            <source>INS intervals longer than this are gaps: pings inside are dropped</source>
            <translation>惯导数据间隔超过此值即为间断:其中的 ping 被舍弃</translation>
        </message>
        <message>
            <source>INS roll, pitch and heading accuracy from its specification, propagated into the σ of the result (0: the INS is taken as exact and σ are a lower bound)</source>
            <translation>惯导横摇、纵摇和航向的标称精度,传播到结果的 σ 中(0:视惯导为无误差,σ 为下限)</translation>
        </message>
        <message>
            <source>Import JSON…</source>
            <translation>导入 JSON…</translation>
        </message>
        <message>
            <source>Import a data file into the project</source>
            <translation>将数据文件导入项目</translation>
        </message>
        <message>
            <source>Import data</source>
            <translation>导入数据</translation>
        </message>
        <message>
            <source>Import failed</source>
            <translation>导入失败</translation>
        </message>
        <message>
            <source>Import file</source>
            <translation>导入文件</translation>
        </message>
        <message>
            <source>Import vessel sheet</source>
            <translation>导入船舶参数表</translation>
        </message>
        <message>
            <source>Import warning</source>
            <translation>导入警告</translation>
        </message>
        <message>
            <source>Initial attitude</source>
            <translation>初始姿态</translation>
        </message>
        <message>
            <source>Initial heading</source>
            <translation>初始航向</translation>
        </message>
        <message>
            <source>Initial heading of a tilt RTK pole's MEMS IMU from a swing with the tip on the point, and the tip: Li et al.'s gradient descent (BGD/SGD/MBGD) and SVD, the closed-form heading-only solution, and a joint batch least squares over the whole swing with σ.</source>
            <translation>由杆尖置于点上的摆动求倾斜 RTK 对中杆 MEMS IMU 的初始航向及杆尖:Li 等的梯度下降(BGD/SGD/MBGD)和 SVD、仅航向的闭合形式解,以及覆盖整个摆动过程并给出 σ 的联合批量最小二乘。</translation>
        </message>
        <message>
            <source>Invert Axis</source>
            <translation>反转坐标轴</translation>
        </message>
        <message>
            <source>Item</source>
            <translation>项目</translation>
        </message>
        <message>
            <source>Iterate</source>
            <translation>迭代</translation>
        </message>
        <message>
            <source>Iteration</source>
            <translation>迭代</translation>
        </message>
        <message>
            <source>Iteration and adjustment</source>
            <translation>迭代与平差</translation>
        </message>
        <message>
            <source>Iterations</source>
            <translation>迭代</translation>
        </message>
        <message>
            <source>J(ψ) and iterations</source>
            <translation>J(ψ) 与迭代过程</translation>
        </message>
        <message>
            <source>Joint adjustment</source>
            <translation>联合平差</translation>
        </message>
        <message>
            <source>Joint adjustment ± 1σ</source>
            <translation>联合平差 ± 1σ</translation>
        </message>
        <message>
            <source>Joint adjustment: correlations</source>
            <translation>联合平差:相关系数</translation>
        </message>
        <message>
            <source>Joint estimate (all used lines at once)</source>
            <translation>联合估计(同时使用全部采用的测线)</translation>
        </message>
        <message>
            <source>Joint resid.</source>
            <translation>联合残差</translation>
        </message>
        <message>
            <source>Key results of every module. Values are the final, corrected values; uncertainties are one standard deviation unless stated.</source>
            <translation>各模块的主要结果。数值为最终改正后的值;除另有说明外,不确定度均为一倍标准差。</translation>
        </message>
        <message>
            <source>Kind / shape</source>
            <translation>类型 / 形状</translation>
        </message>
        <message>
            <source>Kind:</source>
            <translation>类型:</translation>
        </message>
        <message>
            <source>LSQ</source>
            <translation>最小二乘</translation>
        </message>
        <message>
            <source>Largest credible line σ</source>
            <translation>测线 σ 可信上限</translation>
        </message>
        <message>
            <source>Largest spread</source>
            <translation>最大离散度</translation>
        </message>
        <message>
            <source>Laser RMS</source>
            <translation>激光 RMS</translation>
        </message>
        <message>
            <source>Laser crop tolerance</source>
            <translation>激光裁剪容差</translation>
        </message>
        <message>
            <source>Laser planes</source>
            <translation>激光平面</translation>
        </message>
        <message>
            <source>Laser pts</source>
            <translation>激光点数</translation>
        </message>
        <message>
            <source>Laser voxel size</source>
            <translation>激光体素大小</translation>
        </message>
        <message>
            <source>Latency</source>
            <translation>时间延迟</translation>
        </message>
        <message>
            <source>Latency between GNSS heights and attitude</source>
            <translation>GNSS 高程与姿态数据间的时间延迟</translation>
        </message>
        <message>
            <source>Latency estimator</source>
            <translation>时间延迟估计方法</translation>
        </message>
        <message>
            <source>Latency Δt (GNSS tags late), 1σ</source>
            <translation>时间延迟 Δt(GNSS 时间标签滞后),1σ</translation>
        </message>
        <message>
            <source>Latency: final result.</source>
            <translation>时间延迟:最终结果。</translation>
        </message>
        <message>
            <source>Latency: processing parameters (lever arm “vessel sheet”: the value above was taken from it).</source>
            <translation>时间延迟:处理参数(杆臂“船舶参数表”:上方的值取自该表)。</translation>
        </message>
        <message>
            <source>Learning rate α</source>
            <translation>学习率 α</translation>
        </message>
        <message>
            <source>Length</source>
            <translation>长度</translation>
        </message>
        <message>
            <source>Levelling time</source>
            <translation>调平时间</translation>
        </message>
        <message>
            <source>Lever arm (antenna − motion sensor)</source>
            <translation>杆臂(天线 − 姿态传感器)</translation>
        </message>
        <message>
            <source>Lever arm GNSS antenna − motion sensor (x fwd, y stbd, z down)</source>
            <translation>杆臂 GNSS 天线 − 姿态传感器(x 向前,y 右舷,z 向下)</translation>
        </message>
        <message>
            <source>Lever arm gnss − motion: fix the table first.</source>
            <translation>杆臂 gnss − 姿态传感器:请先修正表格。</translation>
        </message>
        <message>
            <source>Lever arm gnss − motion: needs sensors named 'gnss' and 'motion' (the Latency plugin uses it).</source>
            <translation>杆臂 gnss − 姿态传感器:需要名为 'gnss' 和 'motion' 的传感器(时间延迟插件使用)。</translation>
        </message>
        <message>
            <source>Lever arm x (forward)</source>
            <translation>杆臂 x(向前)</translation>
        </message>
        <message>
            <source>Lever arm x (forward) (final, 1σ)</source>
            <translation>杆臂 x(向前)(最终值,1σ)</translation>
        </message>
        <message>
            <source>Lever arm y (starboard)</source>
            <translation>杆臂 y(右舷)</translation>
        </message>
        <message>
            <source>Lever arm y (starboard) (final, 1σ)</source>
            <translation>杆臂 y(右舷)(最终值,1σ)</translation>
        </message>
        <message>
            <source>Lever arm z (down)</source>
            <translation>杆臂 z(向下)</translation>
        </message>
        <message>
            <source>Lever arm z (down) (final, 1σ)</source>
            <translation>杆臂 z(向下)(最终值,1σ)</translation>
        </message>
        <message>
            <source>Lever-arm tolerance</source>
            <translation>杆臂收敛阈值</translation>
        </message>
        <message>
            <source>Line</source>
            <translation>测线</translation>
        </message>
        <message>
            <source>Line screening</source>
            <translation>测线筛选</translation>
        </message>
        <message>
            <source>Lines used</source>
            <translation>采用的测线</translation>
        </message>
        <message>
            <source>Link Axis:</source>
            <translation>关联坐标轴:</translation>
        </message>
        <message>
            <source>Loaded and failed plugins</source>
            <translation>已加载和加载失败的插件</translation>
        </message>
        <message>
            <source>Local workers</source>
            <translation>本地工作进程</translation>
        </message>
        <message>
            <source>Log</source>
            <translation>日志</translation>
        </message>
        <message>
            <source>Log X</source>
            <translation>X 对数</translation>
        </message>
        <message>
            <source>Log Y</source>
            <translation>Y 对数</translation>
        </message>
        <message>
            <source>Log messages appear here.</source>
            <translation>日志信息显示在此处。</translation>
        </message>
        <message>
            <source>Log records</source>
            <translation>日志记录</translation>
        </message>
        <message>
            <source>Loosely coupled GNSS/INS EKF (15 or 21 states) with NHC/ZUPT and RTS smoothing (Wang et al.); errors against a reference, GNSS outage simulation.</source>
            <translation>GNSS/INS 松组合 EKF(15 或 21 维状态),带非完整约束/零速修正和 RTS 反向平滑(Wang 等);相对参考的误差,GNSS 中断模拟。</translation>
        </message>
        <message>
            <source>MBES RMS</source>
            <translation>多波束 RMS</translation>
        </message>
        <message>
            <source>MBES pts</source>
            <translation>多波束点数</translation>
        </message>
        <message>
            <source>MBGD (Li et al.)</source>
            <translation>MBGD(Li 等)</translation>
        </message>
        <message>
            <source>MBGD iterates</source>
            <translation>MBGD 迭代过程</translation>
        </message>
        <message>
            <source>Mahony Ki</source>
            <translation>Mahony Ki</translation>
        </message>
        <message>
            <source>Mahony Ki:</source>
            <translation>Mahony Ki:</translation>
        </message>
        <message>
            <source>Mahony Kp</source>
            <translation>Mahony Kp</translation>
        </message>
        <message>
            <source>Mahony Kp:</source>
            <translation>Mahony Kp:</translation>
        </message>
        <message>
            <source>Manual</source>
            <translation>手动</translation>
        </message>
        <message>
            <source>Map</source>
            <translation>地图</translation>
        </message>
        <message>
            <source>Max Traces:</source>
            <translation>最多曲线数:</translation>
        </message>
        <message>
            <source>Max iterations / round</source>
            <translation>每轮最大迭代次数</translation>
        </message>
        <message>
            <source>Max normal angle</source>
            <translation>最大法向夹角</translation>
        </message>
        <message>
            <source>Max points per face</source>
            <translation>每面最多点数</translation>
        </message>
        <message>
            <source>Max rounds</source>
            <translation>最大轮数</translation>
        </message>
        <message>
            <source>Maximum iterations</source>
            <translation>最大迭代次数</translation>
        </message>
        <message>
            <source>Mean</source>
            <translation>均值</translation>
        </message>
        <message>
            <source>Method</source>
            <translation>方法</translation>
        </message>
        <message>
            <source>Method: pool calibration against a laser-scanned target (patent CN 105425246 B). Both point clouds are segmented into the design faces of the target; planes are fitted by total least squares. The patent method iterates the boresight angles from the angles between multibeam and laser plane normals (roll from the wall, pitch and yaw from the oblique faces), then derives the lever arm offsets (x from the wall, y from the oblique faces, z from the horizontal faces). The joint adjustment estimates all six parameters at once by minimising the point-to-plane distances of the multibeam soundings to the laser planes, with their covariance. Angles follow setup.json: R&lt;sub&gt;m&lt;/sub&gt; = Rz(yaw)·Ry(pitch)·Rx(roll); the lever arm is in the body frame (x forward, y starboard, z down).</source>
            <translation>方法:以激光扫描目标物进行水池检校(专利 CN 105425246 B)。两组点云均分割为目标物的设计面;用整体最小二乘拟合平面。专利方法由多波束平面与激光平面法向间的夹角迭代求安装偏角(横摇取自中心墙,纵摇和艏摇取自斜面),然后求杆臂偏移量(x 取自中心墙,y 取自斜面,z 取自水平面)。联合平差通过最小化多波束测深点到激光平面的点面距离,一次估计全部六个参数及其协方差。角度遵循 setup.json:R&lt;sub&gt;m&lt;/sub&gt; = Rz(艏摇)·Ry(纵摇)·Rx(横摇);杆臂在载体坐标系中(x 向前,y 右舷,z 向下)。</translation>
        </message>
        <message>
            <source>Min points per face</source>
            <translation>每面最少点数</translation>
        </message>
        <message>
            <source>Min soundings per face (joint)</source>
            <translation>每面最少测深点数(联合)</translation>
        </message>
        <message>
            <source>Minimum epochs per line</source>
            <translation>每条测线最少历元数</translation>
        </message>
        <message>
            <source>Module</source>
            <translation>模块</translation>
        </message>
        <message>
            <source>Modules with results</source>
            <translation>有结果的模块</translation>
        </message>
        <message>
            <source>Monte-Carlo runs</source>
            <translation>蒙特卡洛次数</translation>
        </message>
        <message>
            <source>Motion constraints</source>
            <translation>运动约束</translation>
        </message>
        <message>
            <source>Mouse Enabled</source>
            <translation>启用鼠标</translation>
        </message>
        <message>
            <source>Mouse Mode</source>
            <translation>鼠标模式</translation>
        </message>
        <message>
            <source>Moving alignment speed</source>
            <translation>动态对准速度</translation>
        </message>
        <message>
            <source>Moving alignment σ</source>
            <translation>动态对准 σ</translation>
        </message>
        <message>
            <source>Multibeam boresight angles and lever arm from a pool target seen by a calibrated laser scanner (patent CN 105425246 B) plus a joint least-squares adjustment.</source>
            <translation>由已检校激光扫描仪观测的水池目标物求多波束安装偏角和杆臂(专利 CN 105425246 B),并进行联合最小二乘平差。</translation>
        </message>
        <message>
            <source>Multibeam georeferenced:</source>
            <translation>多波束地理参考:</translation>
        </message>
        <message>
            <source>Multibeam pings dropped (INS gaps)</source>
            <translation>舍弃的多波束 ping(惯导间断)</translation>
        </message>
        <message>
            <source>NHC σ</source>
            <translation>非完整约束 σ</translation>
        </message>
        <message>
            <source>Name</source>
            <translation>名称</translation>
        </message>
        <message>
            <source>Name (--param)</source>
            <translation>名称(--param)</translation>
        </message>
        <message>
            <source>Needs data: /raw/gnss, /raw/attitude, /raw/lines. Import GNSS, attitude and lines files (or create demo data).</source>
            <translation>需要数据:/raw/gnss、/raw/attitude、/raw/lines。请导入 GNSS、姿态和测线文件(或创建演示数据)。</translation>
        </message>
        <message>
            <source>No analysis module is installed.</source>
            <translation>未安装分析模块。</translation>
        </message>
        <message>
            <source>No imported file is recorded in the project (its raw data were written by a simulator or an older HydroSync).</source>
            <translation>项目中没有导入文件的记录(其原始数据由模拟器或旧版 HydroSync 写入)。</translation>
        </message>
        <message>
            <source>Noise model (what the σ are computed from)</source>
            <translation>噪声模型(σ 的计算依据)</translation>
        </message>
        <message>
            <source>Non-holonomic constraint</source>
            <translation>非完整约束</translation>
        </message>
        <message>
            <source>Normal angle</source>
            <translation>法向夹角</translation>
        </message>
        <message>
            <source>Normal Δ</source>
            <translation>法向 Δ</translation>
        </message>
        <message>
            <source>North</source>
            <translation>北</translation>
        </message>
        <message>
            <source>Not applied</source>
            <translation>未应用</translation>
        </message>
        <message>
            <source>Notes</source>
            <translation>备注</translation>
        </message>
        <message>
            <source>OUT OF DATE</source>
            <translation>已过期</translation>
        </message>
        <message>
            <source>Opacity</source>
            <translation>不透明度</translation>
        </message>
        <message>
            <source>Open &amp;Recent</source>
            <translation>最近打开(&amp;R)</translation>
        </message>
        <message>
            <source>Open a project</source>
            <translation>打开项目</translation>
        </message>
        <message>
            <source>Open project</source>
            <translation>打开项目</translation>
        </message>
        <message>
            <source>Open summary</source>
            <translation>打开汇总</translation>
        </message>
        <message>
            <source>Outage</source>
            <translation>中断</translation>
        </message>
        <message>
            <source>Outage length</source>
            <translation>中断长度</translation>
        </message>
        <message>
            <source>Outcome</source>
            <translation>结果</translation>
        </message>
        <message>
            <source>Outlier limit</source>
            <translation>粗差限值</translation>
        </message>
        <message>
            <source>Pairing</source>
            <translation>配对</translation>
        </message>
        <message>
            <source>Pairing (rule, twin) or why none</source>
            <translation>配对(规则,对应面)或未配对原因</translation>
        </message>
        <message>
            <source>Parameter</source>
            <translation>参数</translation>
        </message>
        <message>
            <source>Parameters</source>
            <translation>参数</translation>
        </message>
        <message>
            <source>Patent</source>
            <translation>专利方法</translation>
        </message>
        <message>
            <source>Patent method</source>
            <translation>专利方法</translation>
        </message>
        <message>
            <source>Patent method: angle iterations</source>
            <translation>专利方法:角度迭代</translation>
        </message>
        <message>
            <source>Peak</source>
            <translation>峰值</translation>
        </message>
        <message>
            <source>Per-line results (as tables 1 and 2 of Qi et al. 2010): maximum correlation R&lt;sub&gt;max&lt;/sub&gt;, the latency at the peak Δt with its uncertainty σΔt (from the peak curvature), and the standard error σ&lt;sub&gt;0&lt;/sub&gt; of height minus total heave (eqs. 5–6) before (Δt = 0) and after synchronisation with the final Δt. Lines not used are greyed.</source>
            <translation>各测线结果(同 Qi 等 2010 表 1 和表 2):最大相关系数 R&lt;sub&gt;max&lt;/sub&gt;,峰值处的时间延迟 Δt 及其不确定度 σΔt(由峰值曲率求得),以及高程减总升沉的中误差 σ&lt;sub&gt;0&lt;/sub&gt;(式 5–6),分别为同步前(Δt = 0)和用最终 Δt 同步后。未采用的测线以灰色显示。</translation>
        </message>
        <message>
            <source>Pitch</source>
            <translation>纵摇</translation>
        </message>
        <message>
            <source>Pitch formal 1σ, RMS (least squares)</source>
            <translation>纵摇形式 1σ,RMS(最小二乘)</translation>
        </message>
        <message>
            <source>Plan view (axes not to scale)</source>
            <translation>平面图(两轴比例不同)</translation>
        </message>
        <message>
            <source>Plan view of the segmented clouds in the target frame (ENU): laser points coloured by the role of their face, multibeam soundings on faces georeferenced with the final values (black), design face outlines in grey. The vertical scale is stretched (axes not to the same scale) to separate the faces.</source>
            <translation>目标物坐标系(ENU)中分割点云的平面图:激光点按所在面的作用着色,面上的多波束测深点用最终值进行地理参考(黑色),设计面轮廓为灰色。垂直比例经拉伸(两轴比例不同)以区分各面。</translation>
        </message>
        <message>
            <source>Plot Options</source>
            <translation>绘图选项</translation>
        </message>
        <message>
            <source>Plugin</source>
            <translation>插件</translation>
        </message>
        <message>
            <source>Plugins</source>
            <translation>插件</translation>
        </message>
        <message>
            <source>Points</source>
            <translation>点</translation>
        </message>
        <message>
            <source>Points kept for views</source>
            <translation>视图保留点数</translation>
        </message>
        <message>
            <source>Pool Calibration</source>
            <translation>水池检校</translation>
        </message>
        <message>
            <source>Pool calibration of multibeam boresight and lever arm</source>
            <translation>多波束安装偏角与杆臂的水池检校</translation>
        </message>
        <message>
            <source>Pool calibration: processing parameters.</source>
            <translation>水池检校:处理参数。</translation>
        </message>
        <message>
            <source>Pool calibration: solution statistics.</source>
            <translation>水池检校:解的统计量。</translation>
        </message>
        <message>
            <source>Position / velocity / attitude</source>
            <translation>位置 / 速度 / 姿态</translation>
        </message>
        <message>
            <source>Position error against the reference (solution − reference, m), forward and smoothed; dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的位置误差(解 − 参考,m),前向滤波和平滑后;虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Power Spectrum (FFT)</source>
            <translation>功率谱(FFT)</translation>
        </message>
        <message>
            <source>Precision vs baseline</source>
            <translation>精度与基线长度</translation>
        </message>
        <message>
            <source>Prepared by</source>
            <translation>编制</translation>
        </message>
        <message>
            <source>Press Run.</source>
            <translation>请按“运行”。</translation>
        </message>
        <message>
            <source>Processing summary.</source>
            <translation>处理概要。</translation>
        </message>
        <message>
            <source>Profiles across faces: distance of each point from the laser plane of the face against height. Multibeam soundings with the coarse setup (grey) lean or sit off the plane; with the final values (colour) they continue the laser points (light blue) below the water line.</source>
            <translation>横跨各面的剖面:各点到该面激光平面的距离随高度的变化。采用粗值(灰色)时多波束测深点倾斜或偏离平面;采用最终值(彩色)时它们在水线以下延续激光点(浅蓝色)。</translation>
        </message>
        <message>
            <source>Project</source>
            <translation>项目</translation>
        </message>
        <message>
            <source>Project created</source>
            <translation>项目创建时间</translation>
        </message>
        <message>
            <source>Project file</source>
            <translation>项目文件</translation>
        </message>
        <message>
            <source>Project file SHA-256</source>
            <translation>项目文件 SHA-256</translation>
        </message>
        <message>
            <source>Project is read-only</source>
            <translation>项目为只读</translation>
        </message>
        <message>
            <source>Project last saved</source>
            <translation>项目最后保存时间</translation>
        </message>
        <message>
            <source>Quantity</source>
            <translation>量</translation>
        </message>
        <message>
            <source>Quit HydroSync</source>
            <translation>退出 HydroSync</translation>
        </message>
        <message>
            <source>R max</source>
            <translation>R max</translation>
        </message>
        <message>
            <source>R threshold</source>
            <translation>R 阈值</translation>
        </message>
        <message>
            <source>R&lt;sub&gt;max&lt;/sub&gt;</source>
            <translation>R&lt;sub&gt;max&lt;/sub&gt;</translation>
        </message>
        <message>
            <source>RANSAC threshold (laser)</source>
            <translation>RANSAC 阈值(激光)</translation>
        </message>
        <message>
            <source>RANSAC threshold (multibeam)</source>
            <translation>RANSAC 阈值(多波束)</translation>
        </message>
        <message>
            <source>RMS MBES</source>
            <translation>多波束 RMS</translation>
        </message>
        <message>
            <source>RMS error against the reference (epochs with GNSS).</source>
            <translation>相对参考的 RMS 误差(有 GNSS 的历元)。</translation>
        </message>
        <message>
            <source>RMS laser</source>
            <translation>激光 RMS</translation>
        </message>
        <message>
            <source>RTS smoothing</source>
            <translation>RTS 反向平滑</translation>
        </message>
        <message>
            <source>Re-crop RANSAC threshold</source>
            <translation>再裁剪 RANSAC 阈值</translation>
        </message>
        <message>
            <source>Re-crop tolerance</source>
            <translation>再裁剪容差</translation>
        </message>
        <message>
            <source>Ready: up-to-date results are not computed again.</source>
            <translation>就绪:已是最新的结果不再重新计算。</translation>
        </message>
        <message>
            <source>Records</source>
            <translation>记录数</translation>
        </message>
        <message>
            <source>Reference</source>
            <translation>参考</translation>
        </message>
        <message>
            <source>Reference (laser)</source>
            <translation>参考(激光)</translation>
        </message>
        <message>
            <source>Reference plane of each face the multibeam may see: a face that crosses the water is compared with its own laser plane; a below-water face with the laser plane of its above-water twin, found by plane (parallel outward normals, overlapping footprints in plan: coplanar, or a parallel offset such as the tops' design height difference) or declared in target.json, moved by the design translation Δ (known to the build tolerance, propagated into σ). Undersides and faces turned away from the vessel are never references. 'Carries': parameters whose σ grows by more than 10 % without the face.</source>
            <translation>多波束可能看到的各面的参考平面:跨越水面的面与其自身的激光平面比较;水下面与其水上对应面的激光平面平移设计平移量 Δ 后比较(Δ 精确到建造容差,并传播到 σ 中),对应面按平面确定(外法向平行、平面投影重叠:共面,或如顶面设计高差那样的平行偏移)或在 target.json 中声明。底面和背向船的面从不作为参考。“所含内容”:去掉该面后 σ 增大超过 10 % 的参数。</translation>
        </message>
        <message>
            <source>Rejection floor</source>
            <translation>剔除下限</translation>
        </message>
        <message>
            <source>Rejection limit</source>
            <translation>剔除限值</translation>
        </message>
        <message>
            <source>Remove sensor</source>
            <translation>删除传感器</translation>
        </message>
        <message>
            <source>Report date</source>
            <translation>报告日期</translation>
        </message>
        <message>
            <source>Report failed</source>
            <translation>报告生成失败</translation>
        </message>
        <message>
            <source>Report not available</source>
            <translation>报告不可用</translation>
        </message>
        <message>
            <source>Reported method</source>
            <translation>报告方法</translation>
        </message>
        <message>
            <source>Role</source>
            <translation>作用</translation>
        </message>
        <message>
            <source>Roll</source>
            <translation>横摇</translation>
        </message>
        <message>
            <source>Roll formal 1σ, RMS (least squares)</source>
            <translation>横摇形式 1σ,RMS(最小二乘)</translation>
        </message>
        <message>
            <source>Round</source>
            <translation>轮次</translation>
        </message>
        <message>
            <source>Run</source>
            <translation>运行</translation>
        </message>
        <message>
            <source>Run &amp;campaign…</source>
            <translation>运行批处理(&amp;C)…</translation>
        </message>
        <message>
            <source>Run a campaign file (many projects x analyses) on Dask</source>
            <translation>在 Dask 上运行批处理文件(多个项目 × 多项分析)</translation>
        </message>
        <message>
            <source>Run all</source>
            <translation>全部运行</translation>
        </message>
        <message>
            <source>Run campaign</source>
            <translation>运行批处理</translation>
        </message>
        <message>
            <source>SGD</source>
            <translation>SGD</translation>
        </message>
        <message>
            <source>SGD iterates</source>
            <translation>SGD 迭代过程</translation>
        </message>
        <message>
            <source>SVD (Wahba)</source>
            <translation>SVD(Wahba 法)</translation>
        </message>
        <message>
            <source>Save &amp;As…</source>
            <translation>另存为(&amp;A)…</translation>
        </message>
        <message>
            <source>Save failed</source>
            <translation>保存失败</translation>
        </message>
        <message>
            <source>Save project as</source>
            <translation>项目另存为</translation>
        </message>
        <message>
            <source>Save the project</source>
            <translation>保存项目</translation>
        </message>
        <message>
            <source>Save the project under a new name</source>
            <translation>以新名称保存项目</translation>
        </message>
        <message>
            <source>Scale-factor states</source>
            <translation>比例因子状态</translation>
        </message>
        <message>
            <source>Scan range</source>
            <translation>搜索范围</translation>
        </message>
        <message>
            <source>Section (looking along east)</source>
            <translation>剖面(沿东向看)</translation>
        </message>
        <message>
            <source>Segment</source>
            <translation>分割</translation>
        </message>
        <message>
            <source>Segmentation</source>
            <translation>分割</translation>
        </message>
        <message>
            <source>Segmented point clouds</source>
            <translation>分割后的点云</translation>
        </message>
        <message>
            <source>Select a node to see its attributes.</source>
            <translation>选择一个节点以查看其属性。</translation>
        </message>
        <message>
            <source>Sensor</source>
            <translation>传感器</translation>
        </message>
        <message>
            <source>Sensor calibration report</source>
            <translation>传感器检校报告</translation>
        </message>
        <message>
            <source>Sensor positions and mounting angles of the vessel</source>
            <translation>船上各传感器的位置和安装角</translation>
        </message>
        <message>
            <source>Sensor positions from the reference point in the body frame: x forward, y starboard, z down (metres). Mounting angles in degrees; leave them blank if not given.</source>
            <translation>传感器相对参考点在载体坐标系中的位置:x 向前、y 右舷、z 向下(米)。安装角以度为单位;未给出时留空。</translation>
        </message>
        <message>
            <source>Set aside</source>
            <translation>剔除</translation>
        </message>
        <message>
            <source>Set outages</source>
            <translation>设置中断</translation>
        </message>
        <message>
            <source>Shortest vector</source>
            <translation>最短矢量</translation>
        </message>
        <message>
            <source>Shot window</source>
            <translation>观测窗口</translation>
        </message>
        <message>
            <source>Show X Grid</source>
            <translation>显示 X 网格</translation>
        </message>
        <message>
            <source>Show Y Grid</source>
            <translation>显示 Y 网格</translation>
        </message>
        <message>
            <source>Signature</source>
            <translation>签名</translation>
        </message>
        <message>
            <source>Size</source>
            <translation>大小</translation>
        </message>
        <message>
            <source>Skip at line start</source>
            <translation>测线起始跳过</translation>
        </message>
        <message>
            <source>Smoothed horizontal RMS / yaw RMS vs reference</source>
            <translation>平滑后相对参考的水平 RMS / 艏摇 RMS</translation>
        </message>
        <message>
            <source>Smoothed outage drift (max horizontal)</source>
            <translation>平滑后中断漂移(最大水平)</translation>
        </message>
        <message>
            <source>Smoother node interval</source>
            <translation>平滑节点间隔</translation>
        </message>
        <message>
            <source>Smoother nodes</source>
            <translation>平滑节点</translation>
        </message>
        <message>
            <source>Software</source>
            <translation>软件</translation>
        </message>
        <message>
            <source>Solution</source>
            <translation>解</translation>
        </message>
        <message>
            <source>Soundings (data)</source>
            <translation>测深点(数据)</translation>
        </message>
        <message>
            <source>Source</source>
            <translation>来源</translation>
        </message>
        <message>
            <source>Standard deviation of the angles over no static interval (the measured scatter of a moving platform is its motion, so only the prediction is given; set a static interval (static_start_s/static_end_s) on a period when it stood still) and the precision predicted from the position covariance (degrees). Liu et al. report 0.066°/0.168°/0.268° (4 antennas, least squares) and 0.092°/0.216°/0.297° (3 antennas, direct) on a static car.</source>
            <translation>未设静态区间时角度的标准差(运动平台实测的离散即其运动本身,故只给出预测值;请在平台静止的时段设置静态区间 static_start_s/static_end_s)以及由位置协方差预测的精度(度)。Liu 等在静止车辆上得到 0.066°/0.168°/0.268°(4 天线,最小二乘)和 0.092°/0.216°/0.297°(3 天线,直接法)。</translation>
        </message>
        <message>
            <source>Standard deviations</source>
            <translation>标准差</translation>
        </message>
        <message>
            <source>Standard deviations, forward and smoothed (the smoother reduces them everywhere, most across GNSS outages).</source>
            <translation>前向滤波和平滑后的标准差(平滑处处减小标准差,在 GNSS 中断处减小最多)。</translation>
        </message>
        <message>
            <source>Standstill accel std</source>
            <translation>静止加速度标准差</translation>
        </message>
        <message>
            <source>Standstill rate</source>
            <translation>静止角速率</translation>
        </message>
        <message>
            <source>Standstill window</source>
            <translation>静止检测窗口</translation>
        </message>
        <message>
            <source>Start an empty project</source>
            <translation>新建空项目</translation>
        </message>
        <message>
            <source>Start – end</source>
            <translation>开始 – 结束</translation>
        </message>
        <message>
            <source>Starting the Dask cluster…</source>
            <translation>正在启动 Dask 集群…</translation>
        </message>
        <message>
            <source>Static alignment time</source>
            <translation>静态对准时间</translation>
        </message>
        <message>
            <source>Static interval end</source>
            <translation>静态区间结束</translation>
        </message>
        <message>
            <source>Static interval start</source>
            <translation>静态区间开始</translation>
        </message>
        <message>
            <source>Status</source>
            <translation>状态</translation>
        </message>
        <message>
            <source>Step</source>
            <translation>步长</translation>
        </message>
        <message>
            <source>Stop threshold ε</source>
            <translation>停止阈值 ε</translation>
        </message>
        <message>
            <source>Subsample</source>
            <translation>抽样</translation>
        </message>
        <message>
            <source>Subtract Mean</source>
            <translation>减去均值</translation>
        </message>
        <message>
            <source>Summary of results</source>
            <translation>结果汇总</translation>
        </message>
        <message>
            <source>Survey lines</source>
            <translation>测线</translation>
        </message>
        <message>
            <source>Survey lines (raw/lines) with their start and end times.</source>
            <translation>测线(raw/lines)及其开始和结束时间。</translation>
        </message>
        <message>
            <source>Swing</source>
            <translation>摆动</translation>
        </message>
        <message>
            <source>Target faces</source>
            <translation>目标物面</translation>
        </message>
        <message>
            <source>The application keeps running; save your work. The details are in the log.</source>
            <translation>程序仍在运行;请保存您的工作。详情见日志。</translation>
        </message>
        <message>
            <source>The campaign file has a problem: fix it and choose it again.</source>
            <translation>批处理文件有问题:请修正后重新选择。</translation>
        </message>
        <message>
            <source>The laser and multibeam clouds are drawn here after &lt;b&gt;Segment&lt;/b&gt; or &lt;b&gt;Run all&lt;/b&gt;.</source>
            <translation>执行&lt;b&gt;分割&lt;/b&gt;或&lt;b&gt;全部运行&lt;/b&gt;后,此处显示激光和多波束点云。</translation>
        </message>
        <message>
            <source>The pole is swung for a few seconds with its tip on the point. Li et al. level the IMU (Mahony filter), form observation vectors between GNSS epochs and solve the heading misalignment by gradient descent (mini-batch after screening the vectors by their own heading; batch; stochastic with the longest vector) or SVD; the tip is the antenna corrected by the rotated pole (eq. 18). HydroSync adds the closed-form heading-only least squares and a joint batch least squares over the whole swing (initial attitude, tip, gyro and accelerometer biases from accelerometers, gyros and GNSS), the reported method by default. Tips in ENU (m); σ 1σ.</source>
            <translation>杆尖置于待测点上,将对中杆摆动几秒钟。Li 等先调平 IMU(Mahony 滤波),在 GNSS 历元间构成观测矢量,用梯度下降(按矢量自身航向筛选后的小批量;批量;用最长矢量的随机梯度)或 SVD 求解航向失准角;杆尖为天线位置经旋转后的对中杆改正所得(式 18)。HydroSync 另加仅航向的闭合形式最小二乘,以及覆盖整个摆动过程的联合批量最小二乘(由加速度计、陀螺和 GNSS 求初始姿态、杆尖、陀螺和加速度计零偏),默认报告后者。杆尖为 ENU 坐标(m);σ 为 1σ。</translation>
        </message>
        <message>
            <source>The project holds no vessel offset sheet.</source>
            <translation>项目中没有船体偏移量表。</translation>
        </message>
        <message>
            <source>The swing: antenna path on its sphere about the tip (plan and side views, from the mean antenna position).</source>
            <translation>摆动:天线在以杆尖为中心的球面上的轨迹(平面图和侧视图,相对天线平均位置)。</translation>
        </message>
        <message>
            <source>Tilt Alignment</source>
            <translation>倾斜测量初始对准</translation>
        </message>
        <message>
            <source>Tilt alignment: processing parameters.</source>
            <translation>倾斜测量初始对准:处理参数。</translation>
        </message>
        <message>
            <source>Tilt pole heading misalignment</source>
            <translation>倾斜测量对中杆航向失准角</translation>
        </message>
        <message>
            <source>Tilt pole tip E, N, U [m] (joint batch LSQ)</source>
            <translation>对中杆杆尖 E, N, U [m](联合批量最小二乘)</translation>
        </message>
        <message>
            <source>Tilt pole tip σ E/N/U</source>
            <translation>对中杆杆尖 σ E/N/U</translation>
        </message>
        <message>
            <source>Tilt-pole heading alignment and tip</source>
            <translation>倾斜测量对中杆的航向对准与杆尖</translation>
        </message>
        <message>
            <source>Time span</source>
            <translation>时间跨度</translation>
        </message>
        <message>
            <source>Time tags</source>
            <translation>时间标签</translation>
        </message>
        <message>
            <source>Tip errors (Monte Carlo)</source>
            <translation>杆尖误差(蒙特卡洛)</translation>
        </message>
        <message>
            <source>Tip tolerance</source>
            <translation>杆尖容差</translation>
        </message>
        <message>
            <source>Total σ</source>
            <translation>总 σ</translation>
        </message>
        <message>
            <source>Track heading speed</source>
            <translation>航迹定向速度</translation>
        </message>
        <message>
            <source>Trajectory: GNSS antenna fixes, forward and smoothed IMU positions (local east/north from the start).</source>
            <translation>轨迹:GNSS 天线定位、前向滤波和平滑后的 IMU 位置(以起点为原点的当地东/北坐标)。</translation>
        </message>
        <message>
            <source>Transforms</source>
            <translation>变换</translation>
        </message>
        <message>
            <source>Twin ΔE</source>
            <translation>对应块 ΔE</translation>
        </message>
        <message>
            <source>Twin ΔN</source>
            <translation>对应块 ΔN</translation>
        </message>
        <message>
            <source>Twin ΔU</source>
            <translation>对应块 ΔU</translation>
        </message>
        <message>
            <source>Uncertainty model</source>
            <translation>不确定度模型</translation>
        </message>
        <message>
            <source>Unsaved changes</source>
            <translation>未保存的修改</translation>
        </message>
        <message>
            <source>Untitled project</source>
            <translation>未命名项目</translation>
        </message>
        <message>
            <source>Up</source>
            <translation>天</translation>
        </message>
        <message>
            <source>Used</source>
            <translation>采用</translation>
        </message>
        <message>
            <source>Used for</source>
            <translation>用于</translation>
        </message>
        <message>
            <source>Value</source>
            <translation>值</translation>
        </message>
        <message>
            <source>Velocity error against the reference (solution − reference, m/s), forward and smoothed; dashed: ±1σ of each solution; shaded: simulated GNSS outages.</source>
            <translation>相对参考的速度误差(解 − 参考,m/s),前向滤波和平滑后;虚线:各解的 ±1σ;阴影:模拟的 GNSS 中断。</translation>
        </message>
        <message>
            <source>Vessel</source>
            <translation>船舶</translation>
        </message>
        <message>
            <source>Vessel name</source>
            <translation>船名</translation>
        </message>
        <message>
            <source>Vessel offset sheet as stored in the project (body frame, relative to the reference point).</source>
            <translation>项目中保存的船体偏移量表(载体坐标系,相对于参考点)。</translation>
        </message>
        <message>
            <source>Vessel offsets</source>
            <translation>船体偏移量</translation>
        </message>
        <message>
            <source>Vessel offsets updated</source>
            <translation>船体偏移量已更新</translation>
        </message>
        <message>
            <source>View All</source>
            <translation>显示全部</translation>
        </message>
        <message>
            <source>ViewBox options</source>
            <translation>视图框选项</translation>
        </message>
        <message>
            <source>Visible Data Only</source>
            <translation>仅可见数据</translation>
        </message>
        <message>
            <source>Wahba (closed form)</source>
            <translation>Wahba(闭合形式)</translation>
        </message>
        <message>
            <source>Wait for the running task to finish, or press Cancel in the status bar, then try again.</source>
            <translation>请等待正在运行的任务结束,或按状态栏中的“取消”,然后再试。</translation>
        </message>
        <message>
            <source>Warn above |correlation|</source>
            <translation>|相关系数| 超过此值则警告</translation>
        </message>
        <message>
            <source>Warning:</source>
            <translation>警告:</translation>
        </message>
        <message>
            <source>Water</source>
            <translation>水</translation>
        </message>
        <message>
            <source>Water-line margin</source>
            <translation>水线余量</translation>
        </message>
        <message>
            <source>Weighted mean</source>
            <translation>加权平均</translation>
        </message>
        <message>
            <source>Weights</source>
            <translation>权</translation>
        </message>
        <message>
            <source>Welcome</source>
            <translation>欢迎</translation>
        </message>
        <message>
            <source>What ran</source>
            <translation>运行内容</translation>
        </message>
        <message>
            <source>Write the PDF report of the project</source>
            <translation>生成项目的 PDF 报告</translation>
        </message>
        <message>
            <source>Write the final boresight angles and lever arm into the vessel sheet's multibeam entry? The previous entry is kept in the project history.</source>
            <translation>将最终安装偏角和杆臂写入船舶参数表的多波束条目?原条目保留在项目历史中。</translation>
        </message>
        <message>
            <source>X axis</source>
            <translation>X 轴</translation>
        </message>
        <message>
            <source>Y axis</source>
            <translation>Y 轴</translation>
        </message>
        <message>
            <source>Yaw</source>
            <translation>艏摇</translation>
        </message>
        <message>
            <source>ZUPT speed limit</source>
            <translation>零速修正速度限值</translation>
        </message>
        <message>
            <source>ZUPT σ</source>
            <translation>零速修正 σ</translation>
        </message>
        <message>
            <source>Zero-velocity updates</source>
            <translation>零速修正</translation>
        </message>
        <message>
            <source>a denser laser scan of the above-water faces</source>
            <translation>对水上面进行更密的激光扫描</translation>
        </message>
        <message>
            <source>a lever-arm component whose σ exceeds this is flagged as poorly determined (default: half an accuracy target of 2 mm)</source>
            <translation>σ 超过此值的杆臂分量标记为确定性差(默认:2 mm 精度目标的一半)</translation>
        </message>
        <message>
            <source>a line whose own uncertainty exceeds this, or 10x the median of the selected lines, is not used (its R peak is too flat to locate); a warning names it</source>
            <translation>自身不确定度超过此值或超过所选测线中值 10 倍的测线不予采用(其 R 峰过于平坦,无法定位);警告中列出该测线</translation>
        </message>
        <message>
            <source>a more accurate INS</source>
            <translation>更高精度的惯导</translation>
        </message>
        <message>
            <source>a vector is rejected when its own heading departs from the median by more than this many robust σ (or the floor below, whichever is larger)</source>
            <translation>矢量自身航向偏离中值超过此倍数的稳健 σ(或下方的下限,取较大者)时被剔除</translation>
        </message>
        <message>
            <source>a-priori 1σ of one horizontal antenna coordinate (RTK fixed: about 1 cm)</source>
            <translation>单个天线水平坐标的先验 1σ(RTK 固定解:约 1 cm)</translation>
        </message>
        <message>
            <source>a-priori 1σ of the antenna height</source>
            <translation>天线高程的先验 1σ</translation>
        </message>
        <message>
            <source>above</source>
            <translation>水上</translation>
        </message>
        <message>
            <source>above water (a reference for its twins)</source>
            <translation>水上(作为其对应面的参考)</translation>
        </message>
        <message>
            <source>an angle whose σ exceeds this is flagged as poorly determined (default: half an accuracy target of 0.02°, so an unflagged angle meets it at about 2σ)</source>
            <translation>σ 超过此值的角度标记为确定性差(默认:0.02° 精度目标的一半,未标记的角度约在 2σ 水平满足目标)</translation>
        </message>
        <message>
            <source>an antenna whose measured distances to the others disagree with the known geometry by more than this is dropped for that epoch</source>
            <translation>某天线到其他天线的实测距离与已知几何相差超过此值时,该历元舍弃此天线</translation>
        </message>
        <message>
            <source>an interval longer than this many median intervals between solved epochs counts as a gap</source>
            <translation>解算历元之间的间隔超过中值间隔的此倍数即视为间断</translation>
        </message>
        <message>
            <source>an interval longer than this many median intervals is a data gap</source>
            <translation>间隔超过中值间隔的此倍数即为数据间断</translation>
        </message>
        <message>
            <source>an underside</source>
            <translation>底面</translation>
        </message>
        <message>
            <source>an underside: no scanner sees it</source>
            <translation>底面:扫描仪看不到</translation>
        </message>
        <message>
            <source>angle iteration + lever-arm step repeated at most this often</source>
            <translation>角度迭代 + 杆臂步骤最多重复的次数</translation>
        </message>
        <message>
            <source>angle iterations per round at most</source>
            <translation>每轮最多角度迭代次数</translation>
        </message>
        <message>
            <source>antenna</source>
            <translation>天线</translation>
        </message>
        <message>
            <source>antenna positions used: fixed = RTK fixed only (Q=1), float = fixed or float (Q&lt;=2), any = every solution</source>
            <translation>采用的天线位置:fixed = 仅 RTK 固定解(Q=1),float = 固定解或浮点解(Q&lt;=2),any = 全部解</translation>
        </message>
        <message>
            <source>as pole.json declares (imu_convention), else instant</source>
            <translation>按 pole.json 的声明(imu_convention),否则为 instant</translation>
        </message>
        <message>
            <source>auto</source>
            <translation>自动</translation>
        </message>
        <message>
            <source>auto: check the file's GNSS σ against the data (forward innovations normalised by their predicted std: RMS 0.8-1.25, autocorrelation at 1 s below 0.3) and, if they disagree, re-estimate — white σ scaled to the residual scatter, the rest as a time-correlated (Gauss-Markov) GNSS error with τ by maximum likelihood — reported with the result; file: the file's σ (× the scale) as white noise</source>
            <translation>auto:用数据检验文件中的 GNSS σ(前向新息除以其预测标准差:RMS 0.8-1.25,1 s 处自相关低于 0.3),不符时重新估计——白噪声 σ 按残差离散缩放,其余作为时间相关(高斯-马尔可夫)GNSS 误差,τ 用最大似然估计——随结果一并报告;file:文件中的 σ(× 比例因子)作为白噪声</translation>
        </message>
        <message>
            <source>automatic: the largest triangle of the antennas present at each epoch</source>
            <translation>自动:每个历元可用天线中最大的三角形</translation>
        </message>
        <message>
            <source>below</source>
            <translation>水下</translation>
        </message>
        <message>
            <source>best</source>
            <translation>最好</translation>
        </message>
        <message>
            <source>build</source>
            <translation>建造容差</translation>
        </message>
        <message>
            <source>choose a campaign file (.toml)</source>
            <translation>选择批处理文件(.toml)</translation>
        </message>
        <message>
            <source>closed form</source>
            <translation>闭合形式</translation>
        </message>
        <message>
            <source>coarse</source>
            <translation>粗值</translation>
        </message>
        <message>
            <source>congruent</source>
            <translation>全等</translation>
        </message>
        <message>
            <source>coplanar</source>
            <translation>共面</translation>
        </message>
        <message>
            <source>correlation R</source>
            <translation>相关系数 R</translation>
        </message>
        <message>
            <source>crop tolerance around the faces once the first solution is known</source>
            <translation>得到首次解后目标物面周围的裁剪容差</translation>
        </message>
        <message>
            <source>crossing</source>
            <translation>跨水线</translation>
        </message>
        <message>
            <source>cut-off period of the declared high-pass heave filter (sensors: 10-30 s)</source>
            <translation>所声明的高通升沉滤波器的截止周期(传感器:10-30 s)</translation>
        </message>
        <message>
            <source>data</source>
            <translation>测深数据</translation>
        </message>
        <message>
            <source>declared</source>
            <translation>声明</translation>
        </message>
        <message>
            <source>degree of the polynomial (tide, squat) removed from each line's heights</source>
            <translation>从每条测线高程中去除的多项式(潮位、下坐)阶数</translation>
        </message>
        <message>
            <source>determined</source>
            <translation>已确定</translation>
        </message>
        <message>
            <source>direct</source>
            <translation>直接法</translation>
        </message>
        <message>
            <source>direct (3 antennas)</source>
            <translation>直接法(3 天线)</translation>
        </message>
        <message>
            <source>distance from the laser plane of wall</source>
            <translation>到中心墙激光平面的距离</translation>
        </message>
        <message>
            <source>down error</source>
            <translation>天向误差</translation>
        </message>
        <message>
            <source>e.g. MV Example</source>
            <translation>例如 MV Example</translation>
        </message>
        <message>
            <source>east</source>
            <translation>东</translation>
        </message>
        <message>
            <source>east error</source>
            <translation>东向误差</translation>
        </message>
        <message>
            <source>empty: local cluster (or DASK_SCHEDULER_ADDRESS); e.g. tcp://host:8786</source>
            <translation>空:本地集群(或 DASK_SCHEDULER_ADDRESS);例如 tcp://host:8786</translation>
        </message>
        <message>
            <source>end (time of week) of the statistics interval</source>
            <translation>统计区间的结束时刻(周内秒)</translation>
        </message>
        <message>
            <source>estimate gyro and accelerometer scale factors (21 states) besides the 15 states of Wang et al. (position, velocity, attitude, gyro and accelerometer biases)</source>
            <translation>在 Wang 等的 15 维状态(位置、速度、姿态、陀螺和加速度计零偏)之外估计陀螺和加速度计比例因子(21 维状态)</translation>
        </message>
        <message>
            <source>extended</source>
            <translation>扩展</translation>
        </message>
        <message>
            <source>faces with fewer points in either cloud are not used</source>
            <translation>任一点云中点数少于此值的面不予采用</translation>
        </message>
        <message>
            <source>faces with more points are randomly thinned (seeded); every sounding dropped widens the σ of the result, so the cap is only a bound on memory (a four-pass session's wall holds about 150 000)</source>
            <translation>点数更多的面随机抽稀(固定随机种子);每舍去一个测深点,结果的 σ 都会变大,因此该上限仅用于限制内存(四个测次的墙面约有 150 000 个点)</translation>
        </message>
        <message>
            <source>factor on the std of the GNSS file</source>
            <translation>GNSS 文件标准差的乘数</translation>
        </message>
        <message>
            <source>fewer retained vectors than this: undetermined</source>
            <translation>保留的矢量少于此数:无法确定</translation>
        </message>
        <message>
            <source>file</source>
            <translation>文件</translation>
        </message>
        <message>
            <source>file to import</source>
            <translation>要导入的文件</translation>
        </message>
        <message>
            <source>final</source>
            <translation>最终值</translation>
        </message>
        <message>
            <source>final values from the joint least-squares adjustment (with σ) or from the patent's iteration</source>
            <translation>最终值取自联合最小二乘平差(带 σ)或专利的迭代法</translation>
        </message>
        <message>
            <source>find the faces in both clouds with the coarse setup (nothing is stored)</source>
            <translation>用粗标定在两组点云中寻找各面(不保存任何结果)</translation>
        </message>
        <message>
            <source>first epoch</source>
            <translation>首历元</translation>
        </message>
        <message>
            <source>fixed</source>
            <translation>固定解</translation>
        </message>
        <message>
            <source>forward</source>
            <translation>前向滤波</translation>
        </message>
        <message>
            <source>forward EKF and RTS smoother</source>
            <translation>前向 EKF 和 RTS 反向平滑</translation>
        </message>
        <message>
            <source>forward EKF only (no smoothing)</source>
            <translation>仅前向 EKF(无平滑)</translation>
        </message>
        <message>
            <source>forward offset</source>
            <translation>前向滤波偏差</translation>
        </message>
        <message>
            <source>forward within 1.96σ %</source>
            <translation>前向滤波在 1.96σ 以内 %</translation>
        </message>
        <message>
            <source>from the IMU grade</source>
            <translation>由 IMU 等级确定</translation>
        </message>
        <message>
            <source>from the data</source>
            <translation>由数据确定</translation>
        </message>
        <message>
            <source>given</source>
            <translation>给定</translation>
        </message>
        <message>
            <source>given (configuration)</source>
            <translation>给定(配置)</translation>
        </message>
        <message>
            <source>gnss</source>
            <translation>gnss</translation>
        </message>
        <message>
            <source>gradient descent stops when its step |L| is below this</source>
            <translation>梯度下降步长 |L| 小于此值时停止</translation>
        </message>
        <message>
            <source>gradient-descent iterations before it is reported not converged</source>
            <translation>报告未收敛之前的梯度下降迭代次数</translation>
        </message>
        <message>
            <source>gradient-descent step factor on the normalised J(ψ) (whose curvature is about 2: 0.5 is a Newton step, above 1 diverges)</source>
            <translation>归一化 J(ψ) 上的梯度下降步长因子(其曲率约为 2:0.5 即牛顿步,大于 1 发散)</translation>
        </message>
        <message>
            <source>heading</source>
            <translation>航向</translation>
        </message>
        <message>
            <source>heading error</source>
            <translation>航向误差</translation>
        </message>
        <message>
            <source>heading predicted</source>
            <translation>航向预测</translation>
        </message>
        <message>
            <source>heading simulated</source>
            <translation>航向模拟</translation>
        </message>
        <message>
            <source>heading-only methods: the tip is the mean of the tilt-compensated epochs of the last seconds of the record (the pole held on the point after the swing)</source>
            <translation>仅航向的方法:杆尖取记录最后若干秒倾斜补偿后历元的平均(摆动后对中杆停在点上)</translation>
        </message>
        <message>
            <source>heave, synchronised</source>
            <translation>升沉,同步后</translation>
        </message>
        <message>
            <source>heave, Δt = 0</source>
            <translation>升沉,Δt = 0</translation>
        </message>
        <message>
            <source>height</source>
            <translation>高程</translation>
        </message>
        <message>
            <source>height / heave</source>
            <translation>高程 / 升沉</translation>
        </message>
        <message>
            <source>height change</source>
            <translation>高程变化</translation>
        </message>
        <message>
            <source>held</source>
            <translation>固定参数</translation>
        </message>
        <message>
            <source>horizontal</source>
            <translation>水平面</translation>
        </message>
        <message>
            <source>horizontal (laser)</source>
            <translation>水平面(激光)</translation>
        </message>
        <message>
            <source>horizontal (multibeam)</source>
            <translation>水平面(多波束)</translation>
        </message>
        <message>
            <source>how far from the design faces laser points are kept</source>
            <translation>保留距设计面多远以内的激光点</translation>
        </message>
        <message>
            <source>how far from the design faces soundings are first looked for (halved twice while the coarse setup is aligned); at least the error of the coarse setup at the target</source>
            <translation>首先在距设计面多远以内寻找测深点(粗标定对准过程中减半两次);至少为粗标定在目标物处的误差</translation>
        </message>
        <message>
            <source>how well a below-water block is oriented relative to its above-water twin (± per axis, half-width; σ = tol/√3), propagated into the σ of the result</source>
            <translation>水下块体相对于其水上对应块体的姿态精度(每轴 ±,半宽;σ = tol/√3),传播到结果的 σ 中</translation>
        </message>
        <message>
            <source>how well a below-water block is placed relative to its above-water twin (± per axis, half-width; σ = tol/√3): the design translation between twins is known only to this, and it is propagated into the σ of the result</source>
            <translation>水下块体相对于其水上对应块体的位置精度(每轴 ±,半宽;σ = tol/√3):对应块体间的设计平移量仅精确到此值,并传播到结果的 σ 中</translation>
        </message>
        <message>
            <source>initial roll/pitch/heading std of a moving alignment (and of a given attitude or heading)</source>
            <translation>动态对准(以及给定姿态或航向)的初始横摇/纵摇/航向标准差</translation>
        </message>
        <message>
            <source>ins</source>
            <translation>ins</translation>
        </message>
        <message>
            <source>integral gain of the Mahony levelling filter (gyro-bias estimate)</source>
            <translation>Mahony 调平滤波器的积分增益(陀螺零偏估计)</translation>
        </message>
        <message>
            <source>iterate and adjust on the faces found by Segment, then store the results</source>
            <translation>在分割得到的面上迭代和平差,然后保存结果</translation>
        </message>
        <message>
            <source>iteration</source>
            <translation>迭代</translation>
        </message>
        <message>
            <source>iterations</source>
            <translation>迭代</translation>
        </message>
        <message>
            <source>joint</source>
            <translation>联合</translation>
        </message>
        <message>
            <source>joint adjustment, converged</source>
            <translation>联合平差,已收敛</translation>
        </message>
        <message>
            <source>joint batch LSQ</source>
            <translation>联合批量最小二乘</translation>
        </message>
        <message>
            <source>joint batch LSQ *</source>
            <translation>联合批量最小二乘 *</translation>
        </message>
        <message>
            <source>joint method: a-priori 1σ of the accelerometer bias; a swing in one plane cannot tell it from the tilt out of that plane, so this bound matters</source>
            <translation>联合法:加速度计零偏的先验 1σ;单平面内的摆动无法将其与该平面外的倾斜区分,因此此约束很重要</translation>
        </message>
        <message>
            <source>joint method: a-priori 1σ of the gyro bias (datasheet bias stability)</source>
            <translation>联合法:陀螺零偏的先验 1σ(器件手册的零偏稳定性)</translation>
        </message>
        <message>
            <source>joint method: accelerometers enter in Hann windows twice this long, one every this many seconds (overlapping by half)</source>
            <translation>联合法:加速度计以两倍此长度的 Hann 窗进入,每隔此秒数一个(重叠一半)</translation>
        </message>
        <message>
            <source>land vehicles: lateral and vertical velocity in the vehicle frame are zero (Wang et al.); leave off for vessels, which sway and heave</source>
            <translation>陆地车辆:车体坐标系中横向和垂向速度为零(Wang 等);船舶有横荡和升沉,应关闭</translation>
        </message>
        <message>
            <source>largest angle between multibeam and laser normals</source>
            <translation>多波束与激光平面法向间的最大夹角</translation>
        </message>
        <message>
            <source>largest mean angular-rate magnitude over the window</source>
            <translation>窗口内平均角速率幅值的上限</translation>
        </message>
        <message>
            <source>largest specific-force standard deviation (any axis) over the window</source>
            <translation>窗口内比力标准差(任一轴)的上限</translation>
        </message>
        <message>
            <source>laser</source>
            <translation>激光</translation>
        </message>
        <message>
            <source>laser clouds with more points are voxel down-sampled</source>
            <translation>点数更多的激光点云进行体素降采样</translation>
        </message>
        <message>
            <source>laser points and soundings stored for the plan views of panel and report</source>
            <translation>为面板和报告平面图保存的激光点和测深点</translation>
        </message>
        <message>
            <source>last epoch</source>
            <translation>末历元</translation>
        </message>
        <message>
            <source>least squares</source>
            <translation>最小二乘</translation>
        </message>
        <message>
            <source>least-squares iterations per epoch before it is flagged not converged</source>
            <translation>每历元最小二乘迭代次数,超过则标记为未收敛</translation>
        </message>
        <message>
            <source>length residual</source>
            <translation>长度残差</translation>
        </message>
        <message>
            <source>line used</source>
            <translation>采用的测线</translation>
        </message>
        <message>
            <source>line used: range of {0}</source>
            <translation>采用的测线:{0} 条的范围</translation>
        </message>
        <message>
            <source>line used: median</source>
            <translation>采用的测线:中位数</translation>
        </message>
        <message>
            <source>line not used: range of {0}</source>
            <translation>未采用的测线:{0} 条的范围</translation>
        </message>
        <message>
            <source>line not used: median</source>
            <translation>未采用的测线:中位数</translation>
        </message>
        <message>
            <source>Correlation R between detrended GNSS height and total heave as a function of the trial latency Δt, the range over the lines (band) and their median (line) (eq. 4) over the whole scan range.</source>
            <translation>去趋势 GNSS 高程与总升沉之间的相关系数 R 随试算时间延迟 Δt 的变化,各测线的范围(色带)及其中位数(曲线)(式 4),覆盖整个搜索范围。</translation>
        </message>
        <message>
            <source>lines whose best correlation R_max is above this are used (Qi et al. 2010: 0.85)</source>
            <translation>最大相关系数 R_max 高于此值的测线予以采用(Qi 等 2010:0.85)</translation>
        </message>
        <message>
            <source>lines whose delay departs from the median by more than K robust σ are not used (0 disables; needs 4 or more lines)</source>
            <translation>时间延迟偏离中值超过 K 倍稳健 σ 的测线不予采用(0 为关闭;需 4 条及以上测线)</translation>
        </message>
        <message>
            <source>lines with fewer GNSS epochs are not used</source>
            <translation>GNSS 历元数少于此值的测线不予采用</translation>
        </message>
        <message>
            <source>log |Δ|</source>
            <translation>log |Δ|</translation>
        </message>
        <message>
            <source>longest baseline</source>
            <translation>最长基线</translation>
        </message>
        <message>
            <source>longest part of the quiet start used for levelling and gyrocompassing (at least 2 s of rest are needed)</source>
            <translation>用于调平和陀螺寻北的平稳起始段的最大长度(至少需要 2 s 静止)</translation>
        </message>
        <message>
            <source>longest time between stored smoother nodes (the smoothed correction is interpolated between nodes)</source>
            <translation>保存的平滑节点之间的最长时间(节点之间对平滑改正进行插值)</translation>
        </message>
        <message>
            <source>lsq</source>
            <translation>lsq</translation>
        </message>
        <message>
            <source>magnitude of gravity at the point</source>
            <translation>该点的重力大小</translation>
        </message>
        <message>
            <source>max horizontal m</source>
            <translation>最大水平 m</translation>
        </message>
        <message>
            <source>max vertical m</source>
            <translation>最大垂直 m</translation>
        </message>
        <message>
            <source>max. normal angle</source>
            <translation>最大法向夹角</translation>
        </message>
        <message>
            <source>method</source>
            <translation>方法</translation>
        </message>
        <message>
            <source>model the GNSS error as white plus a Gauss-Markov error of this correlation time (white part scaled from the residuals, the rest of the file's σ correlated); 0 = chosen by the auto check</source>
            <translation>将 GNSS 误差建模为白噪声加上此相关时间的高斯-马尔可夫误差(白噪声部分按残差缩放,文件 σ 的其余部分为相关误差);0 = 由 auto 检验选定</translation>
        </message>
        <message>
            <source>more passes, slower, at other ranges and on lines crossing the wall at about ±15°</source>
            <translation>更多测次、更慢航速、不同距离,并沿与中心墙约成 ±15° 的测线</translation>
        </message>
        <message>
            <source>motion</source>
            <translation>姿态传感器</translation>
        </message>
        <message>
            <source>moving alignment: the heading is the GNSS course at the first epoch faster than this</source>
            <translation>动态对准:航向取首个速度超过此值历元的 GNSS 航迹向</translation>
        </message>
        <message>
            <source>multibeam</source>
            <translation>多波束</translation>
        </message>
        <message>
            <source>multibeam, final values</source>
            <translation>多波束,最终值</translation>
        </message>
        <message>
            <source>never (the project exists only in memory)</source>
            <translation>从未保存(项目仅在内存中)</translation>
        </message>
        <message>
            <source>no ZUPT while the filter speed exceeds this (a quiet IMU at constant speed is not a standstill)</source>
            <translation>滤波速度超过此值时不做零速修正(匀速运动中平稳的 IMU 并非静止)</translation>
        </message>
        <message>
            <source>no correlation peak for this line</source>
            <translation>此测线没有相关峰</translation>
        </message>
        <message>
            <source>none</source>
            <translation>无</translation>
        </message>
        <message>
            <source>normal gravity at the latitude (geodetic input), else 9.80665</source>
            <translation>该纬度的正常重力(大地坐标输入),否则为 9.80665</translation>
        </message>
        <message>
            <source>north</source>
            <translation>北</translation>
        </message>
        <message>
            <source>north error</source>
            <translation>北向误差</translation>
        </message>
        <message>
            <source>not run (inputs present)</source>
            <translation>未运行(输入已具备)</translation>
        </message>
        <message>
            <source>not saved</source>
            <translation>未保存</translation>
        </message>
        <message>
            <source>not set</source>
            <translation>未设置</translation>
        </message>
        <message>
            <source>note: coarse values (installation drawing)</source>
            <translation>注:粗值(安装图)</translation>
        </message>
        <message>
            <source>oblique</source>
            <translation>斜面</translation>
        </message>
        <message>
            <source>oblique (laser)</source>
            <translation>斜面(激光)</translation>
        </message>
        <message>
            <source>oblique (multibeam)</source>
            <translation>斜面(多波束)</translation>
        </message>
        <message>
            <source>observation vectors (antenna displacements between two epochs) shorter than this horizontally are not used: their heading is dominated by noise</source>
            <translation>水平长度短于此值的观测矢量(两历元间的天线位移)不予采用:其航向主要由噪声决定</translation>
        </message>
        <message>
            <source>order of the declared high-pass heave filter</source>
            <translation>所声明的高通升沉滤波器的阶数</translation>
        </message>
        <message>
            <source>out of date</source>
            <translation>已过期</translation>
        </message>
        <message>
            <source>own</source>
            <translation>自身</translation>
        </message>
        <message>
            <source>own laser plane</source>
            <translation>自身激光平面</translation>
        </message>
        <message>
            <source>pairs of parameters more correlated than this are flagged</source>
            <translation>相关性高于此值的参数对予以标记</translation>
        </message>
        <message>
            <source>paper</source>
            <translation>论文</translation>
        </message>
        <message>
            <source>paper = only Qi et al. 2010's rule (R_max above the threshold); extended = also drop lines whose σ is not credible or that are outliers; auto = paper for qi2010, extended for the other estimators (a peak on the scan's edge is never used)</source>
            <translation>paper = 仅用 Qi 等 2010 的规则(R_max 高于阈值);extended = 另外剔除 σ 不可信或为粗差的测线;auto = qi2010 用 paper,其他估计方法用 extended(峰值位于搜索范围边缘的测线一律不用)</translation>
        </message>
        <message>
            <source>parallel offset</source>
            <translation>平行偏移</translation>
        </message>
        <message>
            <source>passes that determine the held parameters</source>
            <translation>能确定固定参数的测次</translation>
        </message>
        <message>
            <source>peak of a used line</source>
            <translation>采用测线的峰值</translation>
        </message>
        <message>
            <source>per-antenna horizontal position noise (1σ) for the precision prediction and for weights = apriori (Liu et al.: about 0.6 cm)</source>
            <translation>每个天线的水平位置噪声(1σ),用于精度预测以及 weights = apriori(Liu 等:约 0.6 cm)</translation>
        </message>
        <message>
            <source>per-antenna vertical position noise (1σ) for the precision prediction and for weights = apriori</source>
            <translation>每个天线的垂直位置噪声(1σ),用于精度预测以及 weights = apriori</translation>
        </message>
        <message>
            <source>perpendicular</source>
            <translation>垂直面</translation>
        </message>
        <message>
            <source>perpendicular (laser)</source>
            <translation>垂直面(激光)</translation>
        </message>
        <message>
            <source>ping-time block of the cluster-robust check that inflates σ when residuals of neighbouring soundings are correlated</source>
            <translation>聚类稳健检验的 ping 时间分块:相邻测深点残差相关时放大 σ</translation>
        </message>
        <message>
            <source>pitch</source>
            <translation>纵摇</translation>
        </message>
        <message>
            <source>pitch [°]</source>
            <translation>纵摇 [°]</translation>
        </message>
        <message>
            <source>pitch error</source>
            <translation>纵摇误差</translation>
        </message>
        <message>
            <source>pitch predicted</source>
            <translation>纵摇预测</translation>
        </message>
        <message>
            <source>pitch simulated</source>
            <translation>纵摇模拟</translation>
        </message>
        <message>
            <source>pitch °</source>
            <translation>纵摇 °</translation>
        </message>
        <message>
            <source>plane inlier distance of the tight re-crop</source>
            <translation>精细再裁剪的平面内点距离</translation>
        </message>
        <message>
            <source>plane inlier distance, laser points</source>
            <translation>平面内点距离,激光点</translation>
        </message>
        <message>
            <source>plane inlier distance, soundings (coarse setup)</source>
            <translation>平面内点距离,测深点(粗标定)</translation>
        </message>
        <message>
            <source>point-to-plane residuals beyond this are down-weighted (robust adjustment)</source>
            <translation>超过此值的点到平面残差降权(稳健平差)</translation>
        </message>
        <message>
            <source>points this close to a face's edges are not used</source>
            <translation>距面边缘此距离以内的点不予采用</translation>
        </message>
        <message>
            <source>points this close to the water level are not used</source>
            <translation>距水面此距离以内的点不予采用</translation>
        </message>
        <message>
            <source>position covariance of each antenna: file = the std columns of the .pos files (a-priori σ when absent), apriori = the a-priori σ above</source>
            <translation>各天线的位置协方差:file = .pos 文件中的标准差列(缺失时用先验 σ),apriori = 上方的先验 σ</translation>
        </message>
        <message>
            <source>positive down</source>
            <translation>向下为正</translation>
        </message>
        <message>
            <source>positive up</source>
            <translation>向上为正</translation>
        </message>
        <message>
            <source>pred.</source>
            <translation>预测</translation>
        </message>
        <message>
            <source>predicted σ heading</source>
            <translation>预测 σ 航向</translation>
        </message>
        <message>
            <source>predicted σ pitch</source>
            <translation>预测 σ 纵摇</translation>
        </message>
        <message>
            <source>predicted σ roll</source>
            <translation>预测 σ 横摇</translation>
        </message>
        <message>
            <source>proportional gain of the Mahony levelling filter</source>
            <translation>Mahony 调平滤波器的比例增益</translation>
        </message>
        <message>
            <source>qi2010 = the published method (correlation of the raw series); qi2010_antialias = the same after low-passing the high-rate heave to the GNSS band; weighted = coherence-weighted cross-correlation (lower error with coloured sensor noise); auto = qi2010 or weighted, whichever has the smaller uncertainty (see docs/benchmarks.md)</source>
            <translation>qi2010 = 论文方法(原始序列的相关);qi2010_antialias = 先将高频升沉低通滤波到 GNSS 频带后同上;weighted = 相干加权互相关(传感器有色噪声下误差更小);auto = qi2010 与 weighted 中不确定度较小者(见 docs/benchmarks.md)</translation>
        </message>
        <message>
            <source>range of delays tried; symmetric by default since the sign is not known</source>
            <translation>试算的时间延迟范围;符号未知,故默认对称</translation>
        </message>
        <message>
            <source>reading the raw GNSS and attitude data…</source>
            <translation>正在读取原始 GNSS 和姿态数据…</translation>
        </message>
        <message>
            <source>reference</source>
            <translation>参考平面</translation>
        </message>
        <message>
            <source>reject a GNSS fix whose normalised innovation squared exceeds this (3 degrees of freedom: 16.3 = 99.9 %); 0 = accept all</source>
            <translation>归一化新息平方超过此值的 GNSS 定位予以剔除(3 个自由度:16.3 = 99.9 %);0 = 全部接受</translation>
        </message>
        <message>
            <source>remove GNSS for the given length every given interval (length 0 clears the outages); applied at the next Run</source>
            <translation>每隔给定间隔去除给定长度的 GNSS(长度为 0 时清除中断);在下次运行时生效</translation>
        </message>
        <message>
            <source>result written as tip and heading misalignment: joint = batch least squares over the whole swing (attitude, tip, IMU biases; best in the benchmark), mbgd/bgd/sgd = Li et al.'s gradient descent, svd = Wahba, closed_form = exact heading-only least squares; all are always computed</source>
            <translation>作为杆尖和航向失准角输出的结果:joint = 全摆动过程的批量最小二乘(姿态、杆尖、IMU 零偏;基准测试中最优),mbgd/bgd/sgd = Li 等的梯度下降,svd = Wahba 法,closed_form = 仅航向的精确最小二乘;所有方法总会计算</translation>
        </message>
        <message>
            <source>results stored</source>
            <translation>结果已保存</translation>
        </message>
        <message>
            <source>roll</source>
            <translation>横摇</translation>
        </message>
        <message>
            <source>roll [°]</source>
            <translation>横摇 [°]</translation>
        </message>
        <message>
            <source>roll error</source>
            <translation>横摇误差</translation>
        </message>
        <message>
            <source>roll predicted</source>
            <translation>横摇预测</translation>
        </message>
        <message>
            <source>roll simulated</source>
            <translation>横摇模拟</translation>
        </message>
        <message>
            <source>roll °</source>
            <translation>横摇 °</translation>
        </message>
        <message>
            <source>roll, pitch, yaw of the IMU body frame relative to the vehicle frame: C(vehicle ← IMU) = Rz(yaw)·Ry(pitch)·Rx(roll), e.g. yaw 90 when the IMU's x axis points to the vehicle's starboard (the NHC applies in the vehicle frame)</source>
            <translation>IMU 载体坐标系相对于车体坐标系的横摇、纵摇、艏摇:C(车体 ← IMU) = Rz(艏摇)·Ry(纵摇)·Rx(横摇),例如 IMU 的 x 轴指向车辆右舷时艏摇为 90(非完整约束作用于车体坐标系)</translation>
        </message>
        <message>
            <source>roll, pitch, yaw of the body at the first GNSS epoch (C_b^n = Rz(yaw)·Ry(pitch)·Rx(roll)); used as given</source>
            <translation>首个 GNSS 历元时载体的横摇、纵摇、艏摇(C_b^n = Rz(艏摇)·Ry(纵摇)·Rx(横摇));按给定值使用</translation>
        </message>
        <message>
            <source>rounds stop when the lever arm changes less than this</source>
            <translation>杆臂变化小于此值时停止迭代轮次</translation>
        </message>
        <message>
            <source>run the Rauch-Tung-Striebel backward pass after the forward filter</source>
            <translation>前向滤波之后进行 Rauch-Tung-Striebel 反向平滑</translation>
        </message>
        <message>
            <source>runs</source>
            <translation>次数</translation>
        </message>
        <message>
            <source>scan step of the delay (Qi et al. 2010: 0.005 s); refined below the step</source>
            <translation>时间延迟的搜索步长(Qi 等 2010:0.005 s);在步长以下进一步细化</translation>
        </message>
        <message>
            <source>seconds of unsteady run-in skipped at each line start (Qi et al. 2010 skip ≥ 60 s; 0 when the line times already exclude it)</source>
            <translation>每条测线起始处跳过的不稳定上线段秒数(Qi 等 2010 跳过 ≥ 60 s;测线时间已排除时为 0)</translation>
        </message>
        <message>
            <source>see section</source>
            <translation>见相应章节</translation>
        </message>
        <message>
            <source>segment, iterate, adjust and store the results</source>
            <translation>分割、迭代、平差并保存结果</translation>
        </message>
        <message>
            <source>simulated swings like this one (pole, rate, tilt, noise) solved by every method for the error histogram and tip scatter (about 2-6 s each); 0 = none (benchmarks/bench_tilt.py runs the full study)</source>
            <translation>与本次相同(对中杆、速率、倾斜、噪声)的模拟摆动,用每种方法解算,得到误差直方图和杆尖离散(每次约 2-6 s);0 = 不做(完整研究由 benchmarks/bench_tilt.py 运行)</translation>
        </message>
        <message>
            <source>smoothed</source>
            <translation>平滑后</translation>
        </message>
        <message>
            <source>smoothed offset</source>
            <translation>平滑后偏差</translation>
        </message>
        <message>
            <source>smoothed within 1.96σ %</source>
            <translation>平滑后在 1.96σ 以内 %</translation>
        </message>
        <message>
            <source>solution written to attitude.csv and summarised: lsq = iterative weighted least squares (Liu et al.), direct = three-antenna direct method (Liu et al.), wahba = closed-form optimal rotation; all three are always computed</source>
            <translation>写入 attitude.csv 并汇总的解:lsq = 迭代加权最小二乘(Liu 等),direct = 三天线直接法(Liu 等),wahba = 闭合形式最优旋转;三种方法总会计算</translation>
        </message>
        <message>
            <source>speed</source>
            <translation>速度</translation>
        </message>
        <message>
            <source>standard deviation of the lateral and vertical vehicle-frame velocity</source>
            <translation>车体坐标系横向和垂向速度的标准差</translation>
        </message>
        <message>
            <source>standard deviation of the zero velocity</source>
            <translation>零速的标准差</translation>
        </message>
        <message>
            <source>start (time of week) of the interval whose scatter gives the statistics table</source>
            <translation>统计表所用离散区间的开始时刻(周内秒)</translation>
        </message>
        <message>
            <source>static alignment without gyrocompassing or a given heading: the heading is the GNSS course at the first epoch after the rest faster than this, carried back by the gyro</source>
            <translation>无陀螺寻北且未给定航向的静态对准:航向取静止段之后首个速度超过此值历元的 GNSS 航迹向,再由陀螺回推</translation>
        </message>
        <message>
            <source>static alignment: the body's heading at the end of the rest (roll and pitch still from levelling)</source>
            <translation>静态对准:静止段结束时载体的航向(横摇和纵摇仍由调平求得)</translation>
        </message>
        <message>
            <source>static: level at the rest at the start, heading by gyrocompassing (gyro better than 1 °/h), the given heading or the GNSS track once moving (walks, boats at the quay); moving: heading from the GNSS course above the alignment speed; given: the initial attitude given; auto: the configuration's or given attitude, gyrocompassing, moving, else static with the track's heading</source>
            <translation>static:在起始静止段调平,航向由陀螺寻北(陀螺优于 1 °/h)、给定航向或开始运动后的 GNSS 航迹确定(步行、靠码头的船);moving:航向取超过对准速度时的 GNSS 航迹向;given:使用给定的初始姿态;auto:依次采用配置或给定的姿态、陀螺寻北、动态对准,否则用航迹航向的静态对准</translation>
        </message>
        <message>
            <source>statistics interval: drag it or its edges</source>
            <translation>统计区间:拖动区间或其边缘</translation>
        </message>
        <message>
            <source>survey the as-built below-water blocks (smaller build tolerance)</source>
            <translation>实测水下块体的竣工尺寸(减小建造容差)</translation>
        </message>
        <message>
            <source>symmetric band (in robust σ) around each face's own plane kept by the refit (0: off)</source>
            <translation>重拟合在各面自身平面两侧保留的对称带宽(以稳健 σ 计;0:关闭)</translation>
        </message>
        <message>
            <source>the IMU's class, whose documented bias σ are the joint method's priors: consumer gyro 0.1°/s, accelerometer 0.04 m/s²; mems gyro 0.05°/s, accelerometer 0.02 m/s²; industrial gyro 0.02°/s, accelerometer 0.008 m/s²</source>
            <translation>IMU 的等级,其标称零偏 σ 作为联合法的先验:consumer 陀螺 0.1°/s、加速度计 0.04 m/s²;mems 陀螺 0.05°/s、加速度计 0.02 m/s²;industrial 陀螺 0.02°/s、加速度计 0.008 m/s²</translation>
        </message>
        <message>
            <source>the covariance is propagated over blocks of IMU epochs this long (the mechanisation runs at every IMU epoch)</source>
            <translation>协方差按此长度的 IMU 历元块传播(力学编排在每个 IMU 历元进行)</translation>
        </message>
        <message>
            <source>the first seconds of the record, pole held near vertical, used by the Mahony filter to level the IMU before the swing</source>
            <translation>记录开头对中杆近乎竖直的若干秒,Mahony 滤波器在摆动前用其调平 IMU</translation>
        </message>
        <message>
            <source>the joint adjustment uses a face with at least this many soundings: each is one observation against the face's laser reference plane (no plane is fitted to them), so a small top seen at a grazing angle still fixes the vertical lever arm</source>
            <translation>联合平差只用测深点数不少于此值的面:每个测深点都是相对该面激光参考平面的一个观测(不对其拟合平面),因此以掠射角看到的小顶面仍能确定垂直杆臂</translation>
        </message>
        <message>
            <source>the least-squares iteration stops when every angle correction is below this</source>
            <translation>所有角度改正数都小于此值时最小二乘迭代停止</translation>
        </message>
        <message>
            <source>the motion sensor's heave filter: highpass = a causal high-pass (order and cut-off period below), whose phase is removed from the heave and whose gain is applied to the GNSS heights; compensated/none = no phase at wave periods; unknown = not declared (the delay-model check flags a filter's phase or says when it cannot exclude one)</source>
            <translation>姿态传感器的升沉滤波器:highpass = 因果高通滤波(阶数和截止周期见下),从升沉中去除其相位,并将其增益作用于 GNSS 高程;compensated/none = 在波浪周期上无相位;unknown = 未声明(时延模型检验会标记滤波器的相位,或说明无法排除滤波器)</translation>
        </message>
        <message>
            <source>the patent's iteration stops when every angle correction is below this</source>
            <translation>所有角度改正数都小于此值时专利的迭代停止</translation>
        </message>
        <message>
            <source>three antenna names 'A1,A2,A3' for the direct method (A1→A2 the first baseline); empty = the largest triangle among the antennas available</source>
            <translation>直接法的三个天线名 'A1,A2,A3'(A1→A2 为第一条基线);空 = 可用天线中最大的三角形</translation>
        </message>
        <message>
            <source>tilt</source>
            <translation>倾斜</translation>
        </message>
        <message>
            <source>time</source>
            <translation>时间</translation>
        </message>
        <message>
            <source>time between NHC/ZUPT updates (also sets the smoother's node density)</source>
            <translation>非完整约束/零速修正更新的时间间隔(也决定平滑节点密度)</translation>
        </message>
        <message>
            <source>time from first epoch</source>
            <translation>自首历元的时间</translation>
        </message>
        <message>
            <source>time from start</source>
            <translation>自起点的时间</translation>
        </message>
        <message>
            <source>time since line start</source>
            <translation>自测线起点的时间</translation>
        </message>
        <message>
            <source>times of the antenna files are rounded to this before epochs are matched</source>
            <translation>历元匹配前将天线文件的时间取整到此值</translation>
        </message>
        <message>
            <source>tip</source>
            <translation>杆尖</translation>
        </message>
        <message>
            <source>tip error east</source>
            <translation>杆尖东向误差</translation>
        </message>
        <message>
            <source>tip error north</source>
            <translation>杆尖北向误差</translation>
        </message>
        <message>
            <source>tip per epoch</source>
            <translation>各历元杆尖</translation>
        </message>
        <message>
            <source>total heave before (Δt = 0)</source>
            <translation>同步前总升沉(Δt = 0)</translation>
        </message>
        <message>
            <source>turned away from the vessel</source>
            <translation>背向船</translation>
        </message>
        <message>
            <source>turned away from the vessel: no scanner sees it</source>
            <translation>背向船:扫描仪看不到</translation>
        </message>
        <message>
            <source>twin</source>
            <translation>对应面</translation>
        </message>
        <message>
            <source>unknown</source>
            <translation>未知</translation>
        </message>
        <message>
            <source>unpaired: no visible above-water face parallel to it</source>
            <translation>未配对:没有与其平行的可见水上面</translation>
        </message>
        <message>
            <source>up</source>
            <translation>天</translation>
        </message>
        <message>
            <source>vd error</source>
            <translation>vd 误差</translation>
        </message>
        <message>
            <source>ve error</source>
            <translation>ve 误差</translation>
        </message>
        <message>
            <source>vectors</source>
            <translation>矢量</translation>
        </message>
        <message>
            <source>vectors within this of the median heading are always kept</source>
            <translation>航向与中值相差在此值以内的矢量总是保留</translation>
        </message>
        <message>
            <source>vessel sheet (gnss − motion)</source>
            <translation>船舶参数表(gnss − 姿态传感器)</translation>
        </message>
        <message>
            <source>vn error</source>
            <translation>vn 误差</translation>
        </message>
        <message>
            <source>voxel down-sampling of very large laser clouds (0: off)</source>
            <translation>超大激光点云的体素降采样(0:关闭)</translation>
        </message>
        <message>
            <source>wall</source>
            <translation>中心墙</translation>
        </message>
        <message>
            <source>wall (laser)</source>
            <translation>中心墙(激光)</translation>
        </message>
        <message>
            <source>wall (multibeam)</source>
            <translation>中心墙(多波束)</translation>
        </message>
        <message>
            <source>warn when the horizontal circle holding the tip with 95 % probability is wider than this (a swing nearly in one plane leaves the accelerometer bias along the swing axis mixed with the tilt out of the plane)</source>
            <translation>以 95 % 概率包含杆尖的水平圆宽于此值时警告(近乎单平面的摆动会使沿摆动轴的加速度计零偏与平面外倾斜混叠)</translation>
        </message>
        <message>
            <source>water level</source>
            <translation>水面</translation>
        </message>
        <message>
            <source>weighted — coherence-weighted cross-correlation (maximum likelihood)</source>
            <translation>weighted — 相干加权互相关(最大似然)</translation>
        </message>
        <message>
            <source>weights of the line mean: r = R_max of each line (Qi et al. 2010), inverse_variance = 1/uncertainty²</source>
            <translation>测线均值的权:r = 各测线的 R_max(Qi 等 2010),inverse_variance = 1/不确定度²</translation>
        </message>
        <message>
            <source>what one IMU row is: instant = rate and specific force at the time tag; interval-start/-middle/-end = their means (increments / interval) over one sample interval, tagged at its start, middle or end. A wrong choice shows as a GNSS time offset of half a sample</source>
            <translation>一行 IMU 数据的含义:instant = 时间标签时刻的角速率和比力;interval-start/-middle/-end = 一个采样间隔内的平均值(增量 / 间隔),标签在间隔的开始、中间或结束。选错时表现为半个采样的 GNSS 时间偏移</translation>
        </message>
        <message>
            <source>when the per-vector headings spread more than this (robust σ), the vector set is refused as faulty (noise or IMU fault): undetermined</source>
            <translation>各矢量航向的离散(稳健 σ)超过此值时,该矢量集视为异常(噪声或 IMU 故障)而拒绝:无法确定</translation>
        </message>
        <message>
            <source>window of the IMU statistics that detect a standstill</source>
            <translation>检测静止的 IMU 统计窗口</translation>
        </message>
        <message>
            <source>worker processes of the local cluster</source>
            <translation>本地集群的工作进程数</translation>
        </message>
        <message>
            <source>worst</source>
            <translation>最差</translation>
        </message>
        <message>
            <source>write the final boresight and lever arm into the vessel sheet's multibeam entry (recorded in the project history)</source>
            <translation>将最终安装偏角和杆臂写入船舶参数表的多波束条目(记入项目历史)</translation>
        </message>
        <message>
            <source>x fwd [m]</source>
            <translation>x 向前 [m]</translation>
        </message>
        <message>
            <source>y stbd [m]</source>
            <translation>y 右舷 [m]</translation>
        </message>
        <message>
            <source>yaw</source>
            <translation>艏摇</translation>
        </message>
        <message>
            <source>yaw [°]</source>
            <translation>艏摇 [°]</translation>
        </message>
        <message>
            <source>yaw error</source>
            <translation>艏摇误差</translation>
        </message>
        <message>
            <source>yaw °</source>
            <translation>艏摇 °</translation>
        </message>
        <message>
            <source>yes</source>
            <translation>是</translation>
        </message>
        <message>
            <source>z down [m]</source>
            <translation>z 向下 [m]</translation>
        </message>
        <message>
            <source>zero velocity when the IMU is quiet and the filter speed is below the ZUPT speed</source>
            <translation>IMU 平稳且滤波速度低于零速修正速度时视为零速</translation>
        </message>
        <message>
            <source>|Δ angle|</source>
            <translation>|Δ 角度|</translation>
        </message>
        <message>
            <source>± accuracy of the coarse boresight (installation drawing); an angle the data determine no better than this is undetermined and keeps its coarse value</source>
            <translation>粗安装偏角的 ± 精度(安装图);数据确定精度不优于此值的角度视为无法确定,保留其粗值</translation>
        </message>
        <message>
            <source>± accuracy of the coarse lever arm; a component the data determine no better than this is undetermined and keeps its coarse value</source>
            <translation>粗杆臂的 ± 精度;数据确定精度不优于此值的分量视为无法确定,保留其粗值</translation>
        </message>
        <message>
            <source>Δ coarse</source>
            <translation>Δ 粗值</translation>
        </message>
        <message>
            <source>Δ pitch</source>
            <translation>Δ 纵摇</translation>
        </message>
        <message>
            <source>Δ roll</source>
            <translation>Δ 横摇</translation>
        </message>
        <message>
            <source>Δ yaw</source>
            <translation>Δ 艏摇</translation>
        </message>
        <message>
            <source>Δt (GNSS tag late by)</source>
            <translation>Δt(GNSS 时间标签滞后)</translation>
        </message>
        <message>
            <source>Δt, GNSS tags late relative to attitude</source>
            <translation>Δt,GNSS 时间标签相对姿态滞后</translation>
        </message>
        <message>
            <source>δpitch</source>
            <translation>δ纵摇</translation>
        </message>
        <message>
            <source>δroll</source>
            <translation>δ横摇</translation>
        </message>
        <message>
            <source>δyaw</source>
            <translation>δ艏摇</translation>
        </message>
        <message>
            <source>σ above threshold</source>
            <translation>σ 超过阈值</translation>
        </message>
        <message>
            <source>σ budget of the joint adjustment: the 1σ each source alone gives each parameter (their squares add up to the total; the largest in bold). Soundings: more passes, slower, at other ranges and on lines crossing the wall at about ±15°; build tolerance: survey the as-built below-water blocks; laser planes: a denser scan of the above-water faces; INS: a more accurate INS; held parameters: the coarse error of undetermined ones.</source>
            <translation>联合平差的 σ 预算:各误差源单独对各参数产生的 1σ(其平方和为总量;最大者加粗)。测深点:更多测次、更慢航速、不同距离,并沿与中心墙约成 ±15° 的测线;建造容差:实测水下块体的竣工尺寸;激光平面:对水上面进行更密的扫描;惯导:更高精度的惯导;固定参数:无法确定参数的粗值误差。</translation>
        </message>
        <message>
            <source>σ down</source>
            <translation>σ 天向</translation>
        </message>
        <message>
            <source>σ heading</source>
            <translation>σ 航向</translation>
        </message>
        <message>
            <source>σ north</source>
            <translation>σ 北向</translation>
        </message>
        <message>
            <source>σ ping block</source>
            <translation>σ ping 分块</translation>
        </message>
        <message>
            <source>σ pitch</source>
            <translation>σ 纵摇</translation>
        </message>
        <message>
            <source>σ roll</source>
            <translation>σ 横摇</translation>
        </message>
        <message>
            <source>σ yaw</source>
            <translation>σ 艏摇</translation>
        </message>
        <message>
            <source>σ0 after</source>
            <translation>同步后 σ0</translation>
        </message>
        <message>
            <source>σ0 before</source>
            <translation>同步前 σ0</translation>
        </message>
        <message>
            <source>σ&lt;sub&gt;0&lt;/sub&gt; after</source>
            <translation>同步后 σ&lt;sub&gt;0&lt;/sub&gt;</translation>
        </message>
        <message>
            <source>σ&lt;sub&gt;0&lt;/sub&gt; before</source>
            <translation>同步前 σ&lt;sub&gt;0&lt;/sub&gt;</translation>
        </message>
        <message>
            <source>σ₀ before → after (median of used lines)</source>
            <translation>σ₀ 同步前 → 后(采用测线的中值)</translation>
        </message>
        <message>
            <source>ψ RMS</source>
            <translation>ψ RMS</translation>
        </message>
        <message>
            <source>Folder…</source>
            <translation>文件夹…</translation>
        </message>
        <message>
            <source>Add to list</source>
            <translation>加入列表</translation>
        </message>
        <message>
            <source>What the files hold</source>
            <translation>文件内容预览</translation>
        </message>
        <message>
            <source>Choose files to see what they hold.</source>
            <translation>选择文件以查看其内容。</translation>
        </message>
        <message>
            <source>Looks like</source>
            <translation>内容类型</translation>
        </message>
        <message>
            <source>Import a folder</source>
            <translation>导入文件夹</translation>
        </message>
        <message>
            <source>Keep this import and choose another kind or file: OK imports everything listed (and the one above).</source>
            <translation>保留此项导入并选择其他类型或文件:确定将导入列表中的全部项目(以及上方这一项)。</translation>
        </message>
        <message>
            <source>Every file of a folder with an extension the readers accept (hourly logs of one device).</source>
            <translation>文件夹中所有扩展名可被读取的文件(同一设备的逐小时记录)。</translation>
        </message>
        <message>
            <source>file(s) or a folder; several logs of one kind (a day in hourly files) become one table</source>
            <translation>文件或文件夹;同一类型的多个记录文件(按小时分割的一天)合并为一张表</translation>
        </message>
        <message>
            <source>No motion sentence recognised yet: choose the heave sign of your sensor.</source>
            <translation>尚未识别到运动语句:请选择传感器的升沉正方向。</translation>
        </message>
        <message>
            <source>The attitude CSV format is heave positive up; change it only if your file differs.</source>
            <translation>姿态 CSV 格式规定升沉向上为正;仅当文件不同时才更改。</translation>
        </message>
        <message>
            <source>perpendicular side</source>
            <translation>垂直侧面</translation>
        </message>
        <message>
            <source>oblique side</source>
            <translation>斜侧面</translation>
        </message>
        <message>
            <source>top</source>
            <translation>顶面</translation>
        </message>
        <message>
            <source>underside</source>
            <translation>底面</translation>
        </message>
        <message>
            <source>floor</source>
            <translation>池底</translation>
        </message>
        <message>
            <source>other</source>
            <translation>其他</translation>
        </message>
        <message>
            <source>vessel offset sheet vessel.json (sensor offsets, body FRD)</source>
            <translation>船舶偏移量表 vessel.json(传感器偏移量,载体 FRD 坐标系)</translation>
        </message>
        <message>
            <source>GNSS heights CSV (time, height[, lat, lon, quality])</source>
            <translation>GNSS 高程 CSV(时间、高程[、纬度、经度、解算质量])</translation>
        </message>
        <message>
            <source>attitude CSV (time, roll, pitch, heading, heave)</source>
            <translation>姿态 CSV(时间、横摇、纵摇、航向、升沉)</translation>
        </message>
        <message>
            <source>survey lines CSV (name, start, end)</source>
            <translation>测线 CSV(名称、开始、结束)</translation>
        </message>
        <message>
            <source>NMEA GNSS log (GGA / PTNL,GGK [+GST, ZDA]; logger time tags allowed)</source>
            <translation>NMEA GNSS 日志(GGA / PTNL,GGK [+GST、ZDA];可带记录器时间标签)</translation>
        </message>
        <message>
            <source>NMEA motion log (PASHR / PSXN,23 / TSS1)</source>
            <translation>NMEA 姿态传感器日志(PASHR / PSXN,23 / TSS1)</translation>
        </message>
        <message>
            <source>multibeam soundings CSV (time, x, y, z; sensor frame)</source>
            <translation>多波束测深点 CSV(时间、x、y、z;传感器坐标系)</translation>
        </message>
        <message>
            <source>INS trajectory CSV (time, e, n, u, roll, pitch, heading)</source>
            <translation>惯导轨迹 CSV(时间、e、n、u、横摇、纵摇、航向)</translation>
        </message>
        <message>
            <source>laser points (CSV x,y,z / PLY / LAS / LAZ; target ENU)</source>
            <translation>激光点云(CSV x,y,z / PLY / LAS / LAZ;目标物 ENU 坐标系)</translation>
        </message>
        <message>
            <source>pool setup.json (coarse boresight and lever arm)</source>
            <translation>水池检校 setup.json(粗标定的安装偏角和杆臂)</translation>
        </message>
        <message>
            <source>pool target.json (target design)</source>
            <translation>水池检校 target.json(目标物设计)</translation>
        </message>
        <message>
            <source>RTKLIB solution file .pos of one antenna (llh/xyz/enu; the file stem names the antenna)</source>
            <translation>单个天线的 RTKLIB 解算文件 .pos(llh/xyz/enu;文件名即天线名)</translation>
        </message>
        <message>
            <source>position file .geo of one antenna (calendar time, lat, lon, h, 3 sigma; no quality flag; the file stem names the antenna)</source>
            <translation>单个天线的位置文件 .geo(日历时间、纬度、经度、高程、3 个标准差;无质量标志;文件名即天线名)</translation>
        </message>
        <message>
            <source>antenna_positions.csv: time, antenna, x, y, z (ECEF m), quality (GGA) of every antenna of the array</source>
            <translation>antenna_positions.csv:天线阵列中每个天线的时间、天线、x、y、z(ECEF,m)、质量(GGA)</translation>
        </message>
        <message>
            <source>antennas.json: antenna coordinates in the body frame (FRD, m)</source>
            <translation>antennas.json:载体坐标系中的天线坐标(FRD,m)</translation>
        </message>
        <message>
            <source>IMU increments (KF-GINS 7-column text or imu.csv; body FRD)</source>
            <translation>IMU 增量(KF-GINS 7 列文本或 imu.csv;载体 FRD 坐标系)</translation>
        </message>
        <message>
            <source>GNSS antenna positions with std (KF-GINS text or gnss.csv)</source>
            <translation>带标准差的 GNSS 天线位置(KF-GINS 文本或 gnss.csv)</translation>
        </message>
        <message>
            <source>KF-GINS YAML configuration (initial state, IMU noise, lever arm)</source>
            <translation>KF-GINS YAML 配置(初始状态、IMU 噪声、杆臂)</translation>
        </message>
        <message>
            <source>a real recording folder: comma2k19 segment or rtklibexplorer drive/walk (IMU, GNSS, configuration, reference)</source>
            <translation>实测记录文件夹:comma2k19 片段或 rtklibexplorer 驾车/步行数据(IMU、GNSS、配置、参考轨迹)</translation>
        </message>
        <message>
            <source>reference trajectory, 11-column KF-GINS .nav</source>
            <translation>参考轨迹,11 列 KF-GINS .nav</translation>
        </message>
        <message>
            <source>tilt-pole imu.csv: time, gx, gy, gz (rad/s), ax, ay, az (m/s²), body frame, z down along the pole</source>
            <translation>对中杆 imu.csv:时间、gx、gy、gz(rad/s)、ax、ay、az(m/s²),载体坐标系,z 沿杆向下</translation>
        </message>
        <message>
            <source>tilt-pole gnss.csv: time, e, n, u (local ENU) or time, lat, lon, height: the antenna</source>
            <translation>对中杆 gnss.csv:时间、e、n、u(当地 ENU)或时间、纬度、经度、高程:天线位置</translation>
        </message>
        <message>
            <source>tilt-pole pole.json: {"pole_length_m": …, optional "imu_convention": instant|interval-start|interval-middle|interval-end}</source>
            <translation>对中杆 pole.json:{"pole_length_m": …,可选 "imu_convention": instant|interval-start|interval-middle|interval-end}</translation>
        </message>
        <message>
            <source>Clock offset:</source>
            <translation>时钟偏差:</translation>
        </message>
        <message>
            <source>estimated from the turns</source>
            <translation>由转弯估计</translation>
        </message>
        <message>
            <source>GNSS−IMU clock offset S (s): the GNSS epoch tagged t happened at IMU time t + S. Applied and stored; later runs use it.</source>
            <translation>GNSS−IMU 时钟偏差 S(s):时间标签为 t 的 GNSS 历元发生在 IMU 时间 t + S。导入时应用并保存;之后的解算沿用。</translation>
        </message>
    </context>
    <context>
        <name>hydrosync-patterns</name>
        <message>
            <source>Reference: {0}.</source>
            <translation>参考轨迹:{0}。</translation>
        </message>
        <message>
            <source>95 % interval {0} … {1}</source>
            <translation>95 % 区间 {0} … {1}</translation>
        </message>
        <message>
            <source>; INS accuracy roll/pitch/heading {0}/{1}/{2}° (1σ) propagated</source>
            <translation>;已传播惯导精度 横摇/纵摇/航向 {0}/{1}/{2}°(1σ)</translation>
        </message>
        <message>
            <source>; ping-block variance factors 1.00–{0} (largest: {1}){2}</source>
            <translation>;ping 分块方差因子 1.00–{0}(最大:{1}){2}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Joint solution&lt;/b&gt;, &lt;b&gt;NOT converged&lt;/b&gt;. {0}</source>
            <translation>&lt;b&gt;联合平差解&lt;/b&gt;,&lt;b&gt;未收敛&lt;/b&gt;。{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Joint solution&lt;/b&gt;, converged. {0}</source>
            <translation>&lt;b&gt;联合平差解&lt;/b&gt;,已收敛。{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Lever arm needed&lt;/b&gt;: {0}</source>
            <translation>&lt;b&gt;需要杆臂&lt;/b&gt;:{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;No latency&lt;/b&gt;: {0}</source>
            <translation>&lt;b&gt;无时间延迟结果&lt;/b&gt;:{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Out of date&lt;/b&gt;: the results shown no longer match the project — {0}</source>
            <translation>&lt;b&gt;已过期&lt;/b&gt;:显示的结果与项目不再一致 — {0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Parameter error&lt;/b&gt;: {0}</source>
            <translation>&lt;b&gt;参数错误&lt;/b&gt;:{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Patent method solution&lt;/b&gt;, &lt;b&gt;NOT converged&lt;/b&gt;. {0}</source>
            <translation>&lt;b&gt;专利方法解&lt;/b&gt;,&lt;b&gt;未收敛&lt;/b&gt;。{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Patent method solution&lt;/b&gt;, converged. {0}</source>
            <translation>&lt;b&gt;专利方法解&lt;/b&gt;,已收敛。{0}</translation>
        </message>
        <message>
            <source>&lt;b&gt;Read-only.&lt;/b&gt; {0}</source>
            <translation>&lt;b&gt;只读。&lt;/b&gt;{0}</translation>
        </message>
        <message>
            <source>&lt;h3&gt;{0}&lt;/h3&gt;&lt;p style='color:#c00000'&gt;This plugin's panel could not be loaded:&lt;/p&gt;&lt;pre&gt;{1}&lt;/pre&gt;&lt;p&gt;Details are in the log.&lt;/p&gt;</source>
            <translation>&lt;h3&gt;{0}&lt;/h3&gt;&lt;p style='color:#c00000'&gt;无法加载此插件的面板:&lt;/p&gt;&lt;pre&gt;{1}&lt;/pre&gt;&lt;p&gt;详情见日志。&lt;/p&gt;</translation>
        </message>
        <message>
            <source>&lt;h3&gt;{0}&lt;/h3&gt;&lt;p&gt;{1}&lt;/p&gt;&lt;p&gt;&lt;i&gt;Loading…&lt;/i&gt;&lt;/p&gt;</source>
            <translation>&lt;h3&gt;{0}&lt;/h3&gt;&lt;p&gt;{1}&lt;/p&gt;&lt;p&gt;&lt;i&gt;正在加载…&lt;/i&gt;&lt;/p&gt;</translation>
        </message>
        <message>
            <source>&lt;span style='color:#666'&gt;run {0}&lt;/span&gt;</source>
            <translation>&lt;span style='color:#666'&gt;运行于 {0}&lt;/span&gt;</translation>
        </message>
        <message>
            <source>&lt;span style='color:#a05000'&gt;⚠ {0}</source>
            <translation>&lt;span style='color:#a05000'&gt;⚠ {0}</translation>
        </message>
        <message>
            <source>Antenna {0}: present / not accepted (Q) / length rejected / used</source>
            <translation>天线 {0}:存在 / 未接受(Q)/ 长度剔除 / 采用</translation>
        </message>
        <message>
            <source>Estimator: &lt;b&gt;{0}&lt;/b&gt;, beyond the publication: the high-rate total heave is low-passed to the GNSS band (zero-phase) before eq. 3. The published estimator stays available (parameter &lt;i&gt;estimator&lt;/i&gt; = qi2010).</source>
            <translation>估计方法:&lt;b&gt;{0}&lt;/b&gt;,超出论文的部分:在式 3 之前先将高频总升沉低通滤波(零相位)到 GNSS 频带。论文方法仍可使用(参数 &lt;i&gt;estimator&lt;/i&gt; = qi2010)。</translation>
        </message>
        <message>
            <source>Estimator: {0}</source>
            <translation>估计方法:{0}</translation>
        </message>
        <message>
            <source>Lines used: {0}</source>
            <translation>采用的测线:{0}</translation>
        </message>
        <message>
            <source>Every method on this record (* reported). Vectors used {0}, rejected {1}; tilt up to {2}, {3} at the shot.</source>
            <translation>本记录上的各种方法(* 为报告方法)。采用矢量 {0} 个,剔除 {1} 个;最大倾斜 {2},观测时 {3}。</translation>
        </message>
        <message>
            <source>Figure {0}.</source>
            <translation>图 {0}</translation>
        </message>
        <message>
            <source>GNSS σ from the file (white), IMU noise from the configuration; normalised GNSS innovations RMS N/E/D {0}, autocorrelation at 1 s ≤ {1}</source>
            <translation>GNSS σ 取自文件(白噪声),IMU 噪声取自配置;归一化 GNSS 新息 RMS N/E/D {0},1 s 处自相关 ≤ {1}</translation>
        </message>
        <message>
            <source>Heading, pitch and roll: direct method (three antennas) and least squares overlaid (time from the first epoch). Where the record has more than {0} epochs, each 1/{1} of it is drawn as its median (line) and its range (band).</source>
            <translation>航向、纵摇和横摇:直接法(三天线)与最小二乘叠加显示(时间自首历元起算)。记录超过 {0} 个历元时,每 1/{1} 段绘出其中值(线)和范围(带)。</translation>
        </message>
        <message>
            <source>HydroSync report — {0}</source>
            <translation>HydroSync 报告 — {0}</translation>
        </message>
        <message>
            <source>Imported {0}</source>
            <translation>已导入 {0}</translation>
        </message>
        <message>
            <source>Importing {0}</source>
            <translation>正在导入 {0}</translation>
        </message>
        <message>
            <source>Least-squares precision versus baseline length for this layout scaled, with σ = {0} mm horizontal and {1} mm vertical per antenna (cf. Liu et al., fig. 15).</source>
            <translation>按本布设缩放时最小二乘精度随基线长度的变化,每个天线水平 σ = {0} mm、垂直 {1} mm(参见 Liu 等,图 15)。</translation>
        </message>
        <message>
            <source>Lever arm gnss − motion (body FRD): x = {0}</source>
            <translation>杆臂 gnss − 姿态传感器(载体坐标系 FRD):x = {0}</translation>
        </message>
        <message>
            <source>Line {0}, the {1} used line (R&lt;sub&gt;max&lt;/sub&gt; = {2}): σ&lt;sub&gt;0&lt;/sub&gt; {3} m before, {4} m after synchronisation over the whole line; a {5}-s excerpt from its middle (as fig. 4 of Qi et al. 2010).</source>
            <translation>测线 {0},采用测线中{1}的一条(R&lt;sub&gt;max&lt;/sub&gt; = {2}):全测线同步前 σ&lt;sub&gt;0&lt;/sub&gt; {3} m,同步后 {4} m;截取其中间 {5} s(同 Qi 等 2010 图 4)。</translation>
        </message>
        <message>
            <source>Loosely coupled GNSS/INS integration after Wang et al.: strapdown mechanisation in the local-level frame (earth rate, transport rate, normal gravity, coning and sculling), an error-state Kalman filter with {0} states, GNSS position updates with the antenna lever arm, optional non-holonomic and zero-velocity constraints, closed-loop feedback, and a Rauch-Tung-Striebel smoother on the total state. Angles in degrees, NED metres.</source>
            <translation>按 Wang 等的 GNSS/INS 松组合:当地水平坐标系中的捷联力学编排(地球自转角速率、位移角速率、正常重力、圆锥和划船误差补偿),{0} 维状态的误差状态卡尔曼滤波,带天线杆臂的 GNSS 位置更新,可选的非完整约束和零速约束,闭环反馈,以及对全状态的 Rauch-Tung-Striebel 反向平滑。角度单位为度,NED 坐标单位为米。</translation>
        </message>
        <message>
            <source>Measured minus known antenna distances; antennas beyond ±{0} mm are dropped.</source>
            <translation>实测减已知的天线间距离;超出 ±{0} mm 的天线被舍弃。</translation>
        </message>
        <message>
            <source>Method: correlative approximation (Qi et al. 2010). Per survey line the GNSS antenna heights are detrended (eq. 1), the total heave at the antenna is formed from heave, roll and pitch with the lever arm (eq. 2) and interpolated at the corrected GNSS times (eq. 3), and the correlation R (eq. 4) is scanned over Δt. Lines with R&lt;sub&gt;max&lt;/sub&gt; above the threshold are combined by a weighted mean. Δt is how late the GNSS time tags are relative to the attitude time tags: synchronised heights use &lt;i&gt;tag − Δt&lt;/i&gt;.{0}</source>
            <translation>方法:相关逼近法(Qi 等 2010)。对每条测线,先对 GNSS 天线高程去趋势(式 1),由升沉、横摇、纵摇和杆臂求出天线处的总升沉(式 2),并内插到改正后的 GNSS 时刻(式 3),在 Δt 上搜索相关系数 R(式 4)。R&lt;sub&gt;max&lt;/sub&gt; 高于阈值的测线按加权平均合并。Δt 表示 GNSS 时间标签相对姿态时间标签滞后的量:同步后的高程使用 &lt;i&gt;标签 − Δt&lt;/i&gt;。{0}</translation>
        </message>
        <message>
            <source>Modules not run (their sections are omitted): {0}.</source>
            <translation>未运行的模块(其章节从略):{0}。</translation>
        </message>
        <message>
            <source>OUT OF DATE: these results no longer match the project — {0}. Run the analysis again before signing.</source>
            <translation>已过期:这些结果与项目不再一致 — {0}。签署前请重新运行分析。</translation>
        </message>
        <message>
            <source>Objective J(ψ) (normalised) over the screened vectors and the gradient-descent iterates (learning rate {0}, ε {1}°; cf. Li et al., fig. 11).</source>
            <translation>筛选后矢量上的目标函数 J(ψ)(归一化)及梯度下降迭代过程(学习率 {0},ε {1}°;参见 Li 等,图 11)。</translation>
        </message>
        <message>
            <source>Opened {0}</source>
            <translation>已打开 {0}</translation>
        </message>
        <message>
            <source>Opening {0}</source>
            <translation>正在打开 {0}</translation>
        </message>
        <message>
            <source>Passes adjusted jointly ({0})</source>
            <translation>联合平差的测次({0})</translation>
        </message>
        <message>
            <source>Patent iteration, last iteration of each round: the accumulated angles and the largest remaining normal angle. A new round starts after the lever arm has been re-estimated; all {0} iterations are listed in the appendix.</source>
            <translation>专利迭代,每轮的最后一次迭代:累计角度及剩余的最大法向夹角。杆臂重新估计后开始新的一轮;全部 {0} 次迭代列于附录。</translation>
        </message>
        <message>
            <source>Report written to {0}</source>
            <translation>报告已写入 {0}</translation>
        </message>
        <message>
            <source>Saved {0}</source>
            <translation>已保存 {0}</translation>
        </message>
        <message>
            <source>Saving {0}</source>
            <translation>正在保存 {0}</translation>
        </message>
        <message>
            <source>Table {0}.</source>
            <translation>表 {0}</translation>
        </message>
        <message>
            <source>The campaign could not run: {0}</source>
            <translation>批处理无法运行:{0}</translation>
        </message>
        <message>
            <source>The data-sources appendix could not be produced: {0}.</source>
            <translation>无法生成数据来源附录:{0}。</translation>
        </message>
        <message>
            <source>The {0} section could not be produced: {1}. The results stored in the project are unaffected; repair or re-import the damaged data and run the module again.</source>
            <translation>无法生成 {0} 章节:{1}。项目中保存的结果不受影响;请修复或重新导入受损数据后再次运行该模块。</translation>
        </message>
        <message>
            <source>This module provides no report section. Its results are stored in the project under &lt;b&gt;/{0}&lt;/b&gt;: {1}.</source>
            <translation>此模块不提供报告章节。其结果保存在项目的 &lt;b&gt;/{0}&lt;/b&gt; 下:{1}。</translation>
        </message>
        <message>
            <source>about {0}× the passes like these would bring it to {1}</source>
            <translation>约需 {0} 倍于此的测次才能使其达到 {1}</translation>
        </message>
        <message>
            <source>above water ({0})</source>
            <translation>水上({0})</translation>
        </message>
        <message>
            <source>congruent with {0}</source>
            <translation>与 {0} 全等</translation>
        </message>
        <message>
            <source>coplanar with {0}</source>
            <translation>与 {0} 共面</translation>
        </message>
        <message>
            <source>crossing, but {0} laser points (&lt; {1})</source>
            <translation>跨水线,但只有 {0} 个激光点(&lt; {1})</translation>
        </message>
        <message>
            <source>declared with {0}</source>
            <translation>与 {0} 声明配对</translation>
        </message>
        <message>
            <source>final Δt = {0}</source>
            <translation>最终 Δt = {0}</translation>
        </message>
        <message>
            <source>joint adjustment: {0} σ = {1} exceeds {2}: poorly determined</source>
            <translation>联合平差:{0} σ = {1} 超过 {2}:确定性差</translation>
        </message>
        <message>
            <source>joint adjustment: {0} σ = {1} exceeds {2}: poorly determined; {3}</source>
            <translation>联合平差:{0} σ = {1} 超过 {2}:确定性差;{3}</translation>
        </message>
        <message>
            <source>line {0}: before and after Δt = {1}</source>
            <translation>测线 {0}:Δt = {1} 同步前后</translation>
        </message>
        <message>
            <source>more passes cannot bring it to {0}: the {1} part alone gives {2}</source>
            <translation>增加测次无法使其达到 {0}:仅{1}部分就有 {2}</translation>
        </message>
        <message>
            <source>not run: inputs missing ({0})</source>
            <translation>未运行:缺少输入({0})</translation>
        </message>
        <message>
            <source>page {0} of {1}</source>
            <translation>第 {0} 页,共 {1} 页</translation>
        </message>
        <message>
            <source>parallel offset with {0}</source>
            <translation>与 {0} 平行偏移</translation>
        </message>
        <message>
            <source>point-to-plane fit incl. laser-plane errors; build tolerance of the twins ±{0} mm / ±{1}° (rectangular, σ = tol/√3); coarse error of undetermined parameters{2}</source>
            <translation>点到平面拟合(含激光平面误差);对应块体建造容差 ±{0} mm / ±{1}°(矩形分布,σ = tol/√3);无法确定参数的粗值误差{2}</translation>
        </message>
        <message>
            <source>raw {0} … {1} ({2}; not Unix time)</source>
            <translation>原始 {0} … {1}({2};非 Unix 时间)</translation>
        </message>
        <message>
            <source>seed: {0} angle iterations in {1} rounds (converged); final = {2}</source>
            <translation>专利方法:{1} 轮共 {0} 次角度迭代(已收敛);最终值 = {2}</translation>
        </message>
        <message>
            <source>tick to set; unticked: {0}</source>
            <translation>勾选以设置;不勾选:{0}</translation>
        </message>
        <message>
            <source>total heave after (Δt = {0})</source>
            <translation>同步后总升沉(Δt = {0})</translation>
        </message>
        <message>
            <source>unpaired: {0}</source>
            <translation>未配对:{0}</translation>
        </message>
        <message>
            <source>{0}

Default: {1}  (--param {2})</source>
            <translation>{0}

默认值:{1}  (--param {2})</translation>
        </message>
        <message>
            <source>{0} % of its variance from {1} (helps: {2}); {3}</source>
            <translation>其方差的 {0} % 来自{1}(改进办法:{2});{3}</translation>
        </message>
        <message>
            <source>{0} (the project has unsaved changes)</source>
            <translation>{0}(项目有未保存的修改)</translation>
        </message>
        <message>
            <source>{0} IMU epochs, {1} of {2} GNSS fixes used, {3} states.</source>
            <translation>{0} 个 IMU 历元,采用 {1} / {2} 个 GNSS 定位,{3} 维状态。</translation>
        </message>
        <message>
            <source>{0} UTC with HydroSync {1}</source>
            <translation>{0} UTC 由 HydroSync {1} 计算</translation>
        </message>
        <message>
            <source>{0} angle iterations, converged</source>
            <translation>{0} 次角度迭代,已收敛</translation>
        </message>
        <message>
            <source>{0} iterations, converged, {1} soundings, σ₀ = {2} mm</source>
            <translation>{0} 次迭代,已收敛,{1} 个测深点,σ₀ = {2} mm</translation>
        </message>
        <message>
            <source>{0} of {1} (R_max &amp;gt; {2})</source>
            <translation>{0} / {1} 条(R_max &amp;gt; {2})</translation>
        </message>
        <message>
            <source>{0} of {1} (R_max &gt; {2})</source>
            <translation>{0} / {1} 条(R_max &gt; {2})</translation>
        </message>
        <message>
            <source>{0} of {1} epochs solved; {2} with fewer than 3 usable antennas, {3} with an antenna dropped by the length check, {4} gaps. Statistics: scatter and predicted 1σ (°) over the &lt;b&gt;whole record&lt;/b&gt;: on a moving platform the scatter is its motion, not the precision — drag the shaded region onto a period when the platform stood still.</source>
            <translation>解算 {0} / {1} 个历元;{2} 个历元可用天线少于 3 个,{3} 个历元因长度检验舍弃了天线,{4} 处间断。统计量:&lt;b&gt;整个记录&lt;/b&gt;上的离散和预测 1σ(°):运动平台上的离散是其运动而非精度——请将阴影区拖到平台静止的时段。</translation>
        </message>
        <message>
            <source>{0} of {1} epochs solved; {2} with fewer than 3 usable antennas, {3} with an antenna dropped by the length check, {4} gaps. Statistics: scatter and predicted 1σ (°) over the static interval.</source>
            <translation>解算 {0} / {1} 个历元;{2} 个历元可用天线少于 3 个,{3} 个历元因长度检验舍弃了天线,{4} 处间断。统计量:静态区间上的离散和预测 1σ(°)。</translation>
        </message>
        <message>
            <source>{0} of {1} lines used ({2} weights, {3} estimator); auto: {4} (σ {5}; qi2010 {6}, Δt {7})</source>
            <translation>采用 {0} / {1} 条测线({2} 权,{3} 估计方法);自动:{4}(σ {5};qi2010 {6},Δt {7})</translation>
        </message>
        <message>
            <source>{0} of {1} lines used ({2} weights, {3} estimator, {4} line screening)</source>
            <translation>采用 {0} / {1} 条测线({2} 权,{3} 估计方法,{4} 测线筛选)</translation>
        </message>
        <message>
            <source>{0} of {1} lines used ({2} weights, {3} estimator, {4} line screening); auto: {5} (σ {6}; qi2010 {7}, Δt {8})</source>
            <translation>采用 {0} / {1} 条测线({2} 权,{3} 估计方法,{4} 测线筛选);自动:{5}(σ {6};qi2010 {7},Δt {8})</translation>
        </message>
        <message>
            <source>{0} of {1}, weights: peak correlation R</source>
            <translation>{0} / {1},权:峰值相关系数 R</translation>
        </message>
        <message>
            <source>{0} results are out of date: {1}. They were computed from other inputs than the project now holds; run the analysis again before signing.</source>
            <translation>{0} 的结果已过期:{1}。其计算所用输入与项目现有输入不同;签署前请重新运行分析。</translation>
        </message>
        <message>
            <source>{0} simulated swings like this record (same pole, GNSS rate and σ; random shape, IMU grade and biases, hand wobble, GNSS gap): heading error and horizontal tip error (Li et al.'s table 2 form).</source>
            <translation>{0} 次与本记录类似的模拟摆动(相同的对中杆、GNSS 频率和 σ;随机的摆动形状、IMU 等级和零偏、手部抖动、GNSS 中断):航向误差和杆尖水平误差(Li 等表 2 的形式)。</translation>
        </message>
        <message>
            <source>{0} with {1}, which has {2} laser points (&lt; {3}): no reference</source>
            <translation>{0},对应 {1},其激光点只有 {2} 个(&lt; {3}):无参考</translation>
        </message>
        <message>
            <source>{0} with {1}, {2}: no reference</source>
            <translation>{0},对应 {1},{2}:无参考</translation>
        </message>
        <message>
            <source>{0}: horizontal RMS {1}, yaw RMS {2}</source>
            <translation>{0}:水平 RMS {1},艏摇 RMS {2}</translation>
        </message>
        <message>
            <source>{0}: horizontal RMS {1}, yaw RMS {2}, outage drift max {3}, within 1.96σ N/E/D {4}</source>
            <translation>{0}:水平 RMS {1},艏摇 RMS {2},中断漂移最大 {3},1.96σ 以内 N/E/D {4}</translation>
        </message>
        <message>
            <source>{0}: tip {1} (σ {2} mm), heading misalignment {3}°. Vectors used {4}, rejected {5}; tilt up to {6}°.</source>
            <translation>{0}:杆尖 {1}(σ {2} mm),航向失准角 {3}°。采用矢量 {4} 个,剔除 {5} 个;最大倾斜 {6}°。</translation>
        </message>
        <message>
            <source>{0}: {1} pings, {2} soundings, {3} on referenced faces</source>
            <translation>{0}:{1} 个 ping,{2} 个测深点,其中 {3} 个在有参考平面的面上</translation>
        </message>
        <message>
            <source>{0}: {1} pings, {2} soundings, {3} on referenced faces; {4}</source>
            <translation>{0}:{1} 个 ping,{2} 个测深点,其中 {3} 个在有参考平面的面上;{4}</translation>
        </message>
        <message>
            <source>{0}&amp;nbsp;&amp;nbsp; &lt;span style='color:#555'&gt;faint discs: laser · triangles: multibeam · grey: on no face&lt;/span&gt;</source>
            <translation>{0}&amp;nbsp;&amp;nbsp; &lt;span style='color:#555'&gt;浅色圆点:激光 · 三角形:多波束 · 灰色:不在任何面上&lt;/span&gt;</translation>
        </message>
        <message>
            <source>σ from: {0}</source>
            <translation>σ 依据:{0}</translation>
        </message>
        <message>
            <source>σ0 = {0} mm from {1} soundings</source>
            <translation>σ0 = {0} mm,来自 {1} 个测深点</translation>
        </message>
        <message>
            <source>⚠ {0}</source>
            <translation>⚠ {0}</translation>
        </message>
        <message>
            <source>⚠ {0}&lt;/span&gt;</source>
            <translation>⚠ {0}&lt;/span&gt;</translation>
        </message>
        <message>
            <source>Reading {0} file(s)…</source>
            <translation>正在读取 {0} 个文件…</translation>
        </message>
        <message>
            <source>Reading {0} of {1}…</source>
            <translation>正在读取第 {0} 个文件,共 {1} 个…</translation>
        </message>
        <message>
            <source>Import as {0} (what the files hold)</source>
            <translation>按 {0} 导入(与文件内容相符)</translation>
        </message>
        <message>
            <source>{0} found: documented heave positive {1}. Press OK to confirm, or change it if your sensor is set up otherwise.</source>
            <translation>找到 {0}:文档规定的升沉正方向为 {1}。按“确定”确认;若传感器设置不同,请更改。</translation>
        </message>
        <message>
            <source>{0} file(s), {1}; {2}.</source>
            <translation>{0} 个文件,{1};{2}。</translation>
        </message>
        <message>
            <source>{0} file(s), {1}.</source>
            <translation>{0} 个文件,{1}。</translation>
        </message>
        <message>
            <source>folder of {0} files: {1}</source>
            <translation>文件夹,共 {0} 个文件:{1}</translation>
        </message>
        <message>
            <source>folder of 1 file: {0}</source>
            <translation>文件夹,共 1 个文件:{0}</translation>
        </message>
    </context>
    <context>
        <name>signoff</name>
        <message>
            <source>Name</source>
            <translation>姓名</translation>
        </message>
    </context>
</TS>
