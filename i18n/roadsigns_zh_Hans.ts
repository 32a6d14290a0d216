<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="zh_CN" sourcelanguage="en">
<context>
    <name>@default</name>
    <message>
        <location filename="../plugin.py" line="58" />
        <source>Road Sign Inventory</source>
        <translation>道路标志清查</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="56" />
        <source>{layer}: no field 'class'; fields found: {found}</source>
        <translation>{layer}：没有字段 'class'；找到的字段：{found}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="75" />
        <source>{layer}: missing field(s) {missing}; fields found: {found}</source>
        <translation>{layer}：缺少字段 {missing}；找到的字段：{found}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="198" />
        <source>{layer} is in {layer_crs}, the point cloud {cloud} in {cloud_crs}: import the trajectory with the cloud's CRS as target CRS so that every stage works in one CRS</source>
        <translation>{layer} 的坐标参考系为 {layer_crs}，点云 {cloud} 的为 {cloud_crs}：请以点云的坐标参考系作为目标坐标参考系导入轨迹，使每个步骤都在同一坐标参考系中工作</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>warning</source>
        <translation>警告标志</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>prohibitory</source>
        <translation>禁令标志</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>mandatory</source>
        <translation>指示标志</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>information</source>
        <translation>信息标志</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>stop</source>
        <translation>停车让行</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>yield</source>
        <translation>减速让行</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="60" />
        <source>other</source>
        <translation>其他</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="71" />
        <source>{layer}: cannot reproject feature {feature}: {error}</source>
        <translation>{layer}：无法重投影要素 {feature}：{error}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="87" />
        <source>{layer}: sign '{sign_id}' has no valid x, y, z position (no point geometry, and no numbers in the fields x, y, z)</source>
        <translation>{layer}：标志 '{sign_id}' 没有有效的 x、y、z 位置（既无点几何，字段 x、y、z 中也没有数字）</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="88" />
        <source>{layer}, feature {feature}: the field {field} holds '{value}', not a number</source>
        <translation>{layer}，要素 {feature}：字段 {field} 的值为 '{value}'，不是数字</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="95" />
        <source>{layer}: the layer has no feature, nothing to process</source>
        <translation>{layer}：图层没有要素，无可处理的内容</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="116" />
        <source>Cannot write feature {} to the output layer: {}</source>
        <translation>无法将要素 {} 写入输出图层：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="141" />
        <source>{layer} is in {crs}, a geographic CRS (degrees): this needs a projected CRS in metres, the CRS of the point cloud (e.g. a UTM zone)</source>
        <translation>{layer} 的坐标参考系为 {crs}，这是地理坐标参考系（度）：此处需要以米为单位的投影坐标参考系，即点云的坐标参考系（例如 UTM 分带）</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="175" />
        <source>The point cloud {cloud} has no coordinate reference system: give it as Cloud CRS (an advanced parameter; a CRS is never guessed)</source>
        <translation>点云 {cloud} 没有坐标参考系：请在“点云坐标参考系”中指定（高级参数；坐标参考系从不猜测）</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="193" />
        <source>The point cloud {cloud} has no coordinate reference system: give it one with Ground filter (parameter Cloud CRS); a CRS is never guessed</source>
        <translation>点云 {cloud} 没有坐标参考系：请用地面滤波（参数“点云坐标参考系”）为其指定一个；坐标参考系从不猜测</translation>
    </message>
    <message>
        <location filename="../plugin.py" line="51" />
        <source>Sign review panel</source>
        <translation>标志审核面板</translation>
    </message>
</context>
<context>
    <name>DetectSigns</name>
    <message>
        <location filename="../algorithms/detectsigns.py" line="58" />
        <source>Detect signs in panoramas</source>
        <translation>在全景图中检测标志</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="61" />
        <source>Runs an ONNX sign detector on each panorama; one ray per detected sign.</source>
        <translation>在每张全景图上运行 ONNX 标志检测器；每个检测到的标志生成一条射线。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="256" />
        <source>Panorama stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="88" />
        <source>The output of Import trajectory: one point per panorama with its pose and path.</source>
        <translation>“导入轨迹和全景图”的输出：每张全景图一个点，带有其位姿和路径。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>ONNX model (empty: the bundled model)</source>
        <translation>ONNX 模型（留空：使用内置模型）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>A YOLO-family ONNX detector. Empty uses the model bundled with the plugin.</source>
        <translation>YOLO 系列 ONNX 检测器。留空则使用插件内置的模型。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>ONNX 模型 (*.onnx);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="95" />
        <source>Minimum confidence</source>
        <translation>最低置信度</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="95" />
        <source>Detections scoring below this (0-1) are dropped.</source>
        <translation>得分低于此值（0-1）的检测将被丢弃。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="116" />
        <source>Smallest sign kept (panorama pixels)</source>
        <translation>保留的最小标志（全景像素）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="116" />
        <source>Detections whose box is shorter than this on its shorter side are dropped: signs that small are boxed a few pixels off and their class is unsure, and the drive sees them again, larger, from the next stations. 0 keeps every detection.</source>
        <translation>检测框短边小于此值的检测将被丢弃：这么小的标志框会偏差几个像素，类别也不可靠，而车辆在后续站点会以更大的尺寸再次看到它们。0 保留所有检测。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>Class names file (optional)</source>
        <translation>类别名称文件（可选）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>One class name per line, in the model's class order; needed when the model has no names in its metadata and no labels file beside it.</source>
        <translation>每行一个类别名称，按模型的类别顺序排列；当模型元数据中没有名称且旁边没有标签文件时需要提供。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>Text files (*.txt);;All files (*.*)</source>
        <translation>文本文件 (*.txt);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="127" />
        <source>Ray length (m)</source>
        <translation>射线长度 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="127" />
        <source>Length of each detection ray from the panorama centre, in metres.</source>
        <translation>每条检测射线从全景图中心起算的长度，单位为米。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="131" />
        <source>Also look upwards (overhead and gantry signs)</source>
        <translation>同时向上看（悬挂式和门架式标志）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="224" />
        <source>CPU threads (0: all)</source>
        <translation>CPU 线程数（0：全部）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="224" />
        <source>Threads onnxruntime may use on the CPU; 0 lets it use every core.</source>
        <translation>onnxruntime 在 CPU 上可使用的线程数；0 表示使用所有核心。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="230" />
        <source>Detections</source>
        <translation>检测结果</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="234" />
        <source>Number of detections</source>
        <translation>检测数量</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="235" />
        <source>Panoramas skipped</source>
        <translation>跳过的全景图</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="249" />
        <source>ONNX model not found: {}</source>
        <translation>未找到 ONNX 模型：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="268" />
        <source>{} panoramas, {} views each</source>
        <translation>{} 张全景图，每张 {} 个视图</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="304" />
        <source>Skipped {} panorama(s) that could not be read.</source>
        <translation>跳过了 {} 张无法读取的全景图。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="320" />
        <source>{} detections in {} panoramas ({} skipped).</source>
        <translation>{} 个检测，来自 {} 张全景图（跳过 {} 张）。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="312" />
        <source>No sign was detected: the detections layer is empty.</source>
        <translation>未检测到任何标志：检测图层为空。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="230" />
        <source>LineStringZ layer, one ray per detection, with det_id, station_id, image, class, score, code, code_score, u0, v0, u1, v1, n_views and the station's pose fields.</source>
        <translation>LineStringZ 图层，每个检测一条射线，包含字段 det_id、station_id、image、class、score、code、code_score、u0、v0、u1、v1、n_views 以及站点的位姿字段。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="228" />
        <source>in a crop around each detection, voted later across the views of each sign by Refine and merge signs</source>
        <translation>在每个检测结果周围的裁剪图中读取，之后由“精化与合并标志”在每个标志的各视图间投票</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="141" />
        <source>Look ahead and behind more closely (small, far signs)</source>
        <translation>更仔细地向前和向后看（小而远的标志）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="98" />
        <source>Second look from confidence</source>
        <translation>二次检查起始置信度</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="283" />
        <source>Second look: boxes scored from {} to {} are kept where the sign-code classifier reads a code.</source>
        <translation>二次检查：评分在 {} 到 {} 之间、且标志代码分类器读出代码的框被保留。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="141" />
        <source>Adds two views of 53° straight ahead and behind, with 1.5 times the pixels per degree of the horizon views (at a 4096 px panorama's own density), for signs far along the road. Real signs need the pixels: on real street photographs at the horizon views' density the detector found 0.82 of the signs (GTSDB 500-599) and 0.54 of 376 held-out real signs pasted as distant ones; with these views 0.93 and 0.69, precision within 0.01. On held-out generated panoramas: 0.906 of the signs per panorama instead of 0.879. They cost 1.24 times the detection time. On by default; turn it off only for speed on drives with panoramas close together (every sign is then seen from many stations).</source>
        <translation>在正前方和正后方各添加一个 53° 的视图，其每度像素数为地平线视图的 1.5 倍（即 4096 px 全景图自身的密度），用于沿道路远处的标志。真实标志需要这些像素：在真实街道照片上，按地平线视图的密度，检测器找到了 0.82 的标志（GTSDB 500-599）和作为远处标志粘贴的 376 个保留真实标志中的 0.54；加上这些视图后为 0.93 和 0.69，精度变化不超过 0.01。在保留的生成全景图上：每幅全景图找到 0.906 的标志，而不是 0.879。其代价是 1.24 倍的检测时间。默认开启；仅在全景站点很密的行驶采集中为了速度而关闭（此时每个标志都会从许多全景站点被看到）。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="324" />
        <source>Sign codes read in {} of the {} detections (the others: other, or a sign whose code the table lacks).</source>
        <translation>{} 个检测读出了标志代码（共 {} 个检测；其余为 other，或代码表中没有其代码的标志）。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="131" />
        <source>Adds two views tilted 35° up, over the road ahead and behind, for gantry and overhead signs close to the vehicle, above the horizon views. On by default: on five held-out test streets they raised the gantry panels found in a single panorama from 86 % to 91 % for 1.2 times the detection time. A box these views cut at their left or right edge is dropped unless another view finds the same sign: signs beside the road are seen whole in the horizon views. With the second look, a box these views find alone and the sign-code classifier reads as no sign ('other': a facade's dark window, say) is dropped too. Switch it off to save that time where a drive has no overhead signs.</source>
        <translation>增加两个上仰 35° 的视图，分别朝向前方和后方的道路上空，用于车辆附近、位于水平视图上方的门架式和悬挂式标志。默认勾选：在五条未参与调参的测试街道上，单张全景图中找到的门架标志牌从 86 % 提高到 91 %，检测时间为原来的 1.2 倍。这些视图在其左右边缘截断的检测框会被丢弃，除非另一个视图找到了同一个标志：道路两侧的标志在水平视图中是完整可见的。启用二次确认时，仅由这些视图找到、且标志代码分类器判读为非标志（“other”，例如建筑立面上的深色窗户）的检测框也会被丢弃。对于没有悬挂式标志的行驶采集，可取消勾选以节省这部分时间。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="64" />
        <source>Cuts each station's equirectangular panorama into overlapping perspective views (a horizon ring, two closer views ahead and behind, and two views upwards for overhead signs), runs the ONNX detector on each view, maps the boxes back to panorama pixels and merges the same sign found in two views. A box much taller than wide (a sign passed close by, seen nearly edge-on, which the detector boxes about twice as wide as its face) is narrowed to the columns that show sign colours (saturated red, blue or yellow).&lt;br&gt;&lt;br&gt;The &lt;b&gt;model&lt;/b&gt; is the bundled one when left empty, or your own ONNX export: Ultralytics YOLOv8/11 ([1, 4+nc, N]), YOLOv5/7 ([1, N, 5+nc]) or a model with NMS built in ([1, N, 6]). Class names come from the model's metadata (Ultralytics &lt;i&gt;names&lt;/i&gt;) or a labels file (one name per line).&lt;br&gt;&lt;br&gt;Output: one line per detection from the panorama centre along the ray through the box centre, &lt;i&gt;Ray length&lt;/i&gt; long, with the box (u0, v0, u1, v1 in panorama pixels; across the ±180° seam u1 exceeds the width) and the station's pose. A panorama that cannot be read is skipped with a warning and counted.&lt;br&gt;&lt;br&gt;&lt;b&gt;Sign codes&lt;/b&gt;: a second, small ONNX model (the bundled sign-code classifier, or your own) reads what each detected sign says, from a rectified crop of the panorama around its box at the panorama's own resolution: &lt;i&gt;code&lt;/i&gt; (such as DE:274[50], speed limit 50, from the codes table; &lt;i&gt;other&lt;/i&gt; when it knows none) and &lt;i&gt;code_score&lt;/i&gt; (its probability). Refine signs votes them across the views of each sign. The classifier's format is in models/README.md (section &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;).</source>
        <translation>将每个站点的等距柱状全景图切分为相互重叠的透视视图（一圈水平视图、前后方向各一个更近的视图，以及前后各一个用于悬挂式标志的上视视图），在每个视图上运行 ONNX 检测器，将检测框映射回全景图像素，并合并在两个视图中找到的同一标志。高度远大于宽度的检测框（近距离经过、几乎从侧面看到的标志，检测器给出的框约为其标志面宽度的两倍）会收窄到显示标志颜色（饱和的红色、蓝色或黄色）的列。&lt;br&gt;&lt;br&gt;&lt;b&gt;模型&lt;/b&gt;留空时使用内置模型，也可以是您自己导出的 ONNX 模型：Ultralytics YOLOv8/11（[1, 4+nc, N]）、YOLOv5/7（[1, N, 5+nc]）或内置 NMS 的模型（[1, N, 6]）。类别名称来自模型元数据（Ultralytics &lt;i&gt;names&lt;/i&gt;）或标签文件（每行一个名称）。&lt;br&gt;&lt;br&gt;输出：每个检测一条线，从全景图中心沿穿过检测框中心的射线延伸，长度为&lt;i&gt;射线长度&lt;/i&gt;，附带检测框（u0、v0、u1、v1，单位为全景图像素；跨越 ±180° 接缝时 u1 大于图像宽度）和站点位姿。无法读取的全景图将被跳过，并给出警告和计数。&lt;br&gt;&lt;br&gt;&lt;b&gt;标志代码&lt;/b&gt;：第二个小型 ONNX 模型（内置的标志代码分类器或您自己的分类器）从全景图中围绕检测框、按全景图原始分辨率截取的校正裁剪图像中读取每个检测到的标志的内容：&lt;i&gt;code&lt;/i&gt;（例如 DE:274[50]，即限速 50，取自代码表；不认识时为 &lt;i&gt;other&lt;/i&gt;）和 &lt;i&gt;code_score&lt;/i&gt;（其概率）。“精化与合并标志”在每个标志的各视图之间对其进行投票。分类器的格式见 models/README.md（&lt;i&gt;Sign-code classifier: the format&lt;/i&gt; 一节）。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="176" />
        <source>Look again, closer, at small boxes scored under the minimum confidence</source>
        <translation>对低于最低置信度的小框放大再看一次</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="176" />
        <source>A box of at most {px} px that the detector scores from {score} up to the minimum confidence is cut again from the panorama at a higher pixel density (the box {box_px} px across) and detected once more; it is kept when the detector then scores it at the minimum confidence or more, with that score, class and box. All of a panorama's such boxes go through the detector together, in one extra run. It finds far signs, 15-25 px across: on 376 held-out real signs pasted into street photographs the signs found rose from 0.79 to 0.87 (those 14-20 px high from 0.34 to 0.59) at a precision of 0.96; on real street photographs (GTSDB 500-599) the recall stayed at 0.958 and the precision went from 0.971 to 0.958. It costs 1.05-1.09 times the detection time. On by default.</source>
        <translation>检测器评分在 {score} 到最低置信度之间、且不超过 {px} px 的框，会以更高的像素密度从全景图中重新裁切（框宽 {box_px} px）并再次检测；若检测器此时的评分达到最低置信度或更高，则保留该框，并采用这次的评分、类别和框。一幅全景图中所有这样的框会一起送入检测器，只需额外运行一次。它能找到 15-25 px 的远处标志：在粘贴到街景照片中的 376 个预留真实标志上，检出率从 0.79 提高到 0.87（高 14-20 px 的从 0.34 提高到 0.59），精度为 0.96；在真实街景照片（GTSDB 500-599）上，召回率保持 0.958，精度从 0.971 变为 0.958。检测时间约为原来的 1.05-1.09 倍。默认开启。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="296" />
        <source>Zoomed look: boxes of at most {} px scored from {} to {} are detected again at a higher pixel density.</source>
        <translation>放大再看：不超过 {} px、评分在 {} 到 {} 之间的框会以更高的像素密度再次检测。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>Horizon views</source>
        <translation>地平线视图</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>{n} views of {width:g}°</source>
        <translation>{n} 个 {width:g}° 视图</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>{n} views of {width:g}°, turned {yaw:g}°</source>
        <translation>{n} 个 {width:g}° 视图，旋转 {yaw:g}°</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>One band of {width} × {height} px</source>
        <translation>一条 {width} × {height} 像素的条带</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="190" />
        <source>Look again, stretched across, at tall boxes of signs seen edge-on</source>
        <translation>对侧面看到的标志的高框横向拉伸后再看一次</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="290" />
        <source>Edge-on look: boxes at least {} times as tall as wide scored from {} to {} are detected again stretched {} times across.</source>
        <translation>侧面查看：高度至少为宽度 {} 倍、得分在 {} 到 {} 之间的框横向拉伸 {} 倍后再检测一次。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="190" />
        <source>A sign passed close by is seen far off its face's normal, and the view squeezes it to a sliver that the detector scores low. A box at least {ratio} times as tall as wide, of at most {px} px, that the detector scores from {score} up to the minimum confidence is cut again from the panorama (its height {box_px} px) and stretched {stretch} times across, so that the sign's face is about as wide as tall again, and detected once more; it is kept when the detector then scores it at the minimum confidence or more. Its tiles go into the zoomed look's detector runs, and a box both looks take keeps the higher score. On five held-out generated streets it found 701 of 734 signs in single panoramas, against 697 without it (signs seen more than 70° off their face's normal: 27 of 45 against 23), with one false box fewer, in 1.02 to 1.03 times the processor time; real signs of street photographs squeezed across to 0.3 of their width are scored 0.5 or more in 44 of 50 cases stretched, against 11 as they are. On the real street photographs themselves it changed nothing. On by default.</source>
        <translation>车辆从近处经过的标志，其视线远离标志面的法线，视图将其压缩成一条窄条，检测器给出的得分很低。高度至少为宽度 {ratio} 倍、最长边不超过 {px} px、检测器得分在 {score} 到最低置信度之间的框，会从全景图中重新裁切（其高度为 {box_px} px），并横向拉伸 {stretch} 倍，使标志面重新接近宽高相等，然后再检测一次；如果检测器此时的得分达到最低置信度或更高，则保留该框。其切片与放大查看的切片放入同一次检测器运行中，两种查看都选中的框保留较高的得分。在五条留出的生成街道上，单张全景图中找到了 734 个标志中的 701 个，不使用时为 697 个（偏离标志面法线超过 70° 的标志：45 个中找到 27 个，不使用时为 23 个），误检框少一个，处理器时间为 1.02 至 1.03 倍；真实街道照片中的标志横向压缩到其宽度的 0.3 后，拉伸后 50 个中有 44 个得分达到 0.5 或以上，未拉伸时为 11 个。在真实街道照片本身上没有任何变化。默认开启。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="209" />
        <source>Detect in a panorama at least every (m)</source>
        <translation>至少每隔多少米在一幅全景图中检测（米）</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="209" />
        <source>Detects in as few panoramas as leave no more than this distance between one panorama detected in and the next; the ones between are skipped (not read, no detections). The first and the last panorama are always detected in, and a drive whose panoramas stand this far apart or more keeps every one. A sign stays in view over many stations, so skipping saves detection time in proportion, but each sign is then seen from fewer stations: fewer rays to place it, and a sign visible from only a few stations (small, or hidden behind trees or vehicles) may be missed. Measured on two held-out test streets with a panorama every 5 m: every panorama found all 46 and 45 signs; 10 m (every other one) lost 2 of each, 15 m lost 11 of 46. On two held-out streets with a panorama every 1.25 m, one every 5 m found the same 87 signs as one every 2.5 m, in 0.55 times the detection time; the median position error went from 11 to 13 mm, and one sign, read in 3 of its 7 views instead of 13 of 19, was left without a code. 0 detects in every panorama.</source>
        <translation>只在尽可能少的全景图中检测，使相邻两幅被检测的全景图之间的距离不超过此值；其间的全景图被跳过（不读取，无检测结果）。第一幅和最后一幅全景图总会被检测；若全景图之间的间距已达到或超过此值，则全部保留。一个标志在许多测站中都可见，因此跳过可按比例节省检测时间，但每个标志被看到的测站会减少：用于定位的射线更少，仅在少数测站可见的标志（较小，或被树木、车辆遮挡）可能被漏检。在两条留出的测试街道上（每 5 米一幅全景图）测得：使用全部全景图可找到全部 46 和 45 个标志；每 10 米（隔一幅）各漏检 2 个，每 15 米漏检 46 个中的 11 个。在两条每 1.25 米一幅全景图的留出街道上，每 5 米检测一幅与每 2.5 米检测一幅找到的是同样的 87 个标志，检测时间为其 0.55 倍；位置误差中位数从 11 毫米增至 13 毫米，另有一个标志因只在其 7 个视图中的 3 个被读出（而非 19 个中的 13 个）而没有代码。0 表示在每幅全景图中检测。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="274" />
        <source>Detecting in {} of the {} panoramas: one at least every {} m of the drive, the ones between skipped.</source>
        <translation>正在 {} 幅全景图中检测（共 {} 幅）：沿行驶路线至少每 {} 米一幅，其间的跳过。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>How many views of 80° across the horizon ring has. 8 views overlap by 35°. 6 views overlap by 20° and are turned by 30°, so that their seams ahead and behind fall inside the fore-and-aft views: the detection takes 0.8-0.87 times the time. In single panoramas of five held-out test streets, 6 views found 0.946 of the signs at a precision of 0.988, against 0.948 at 0.982 with 8: they lose a few signs 14-20 px high and a few very close ones that no longer fit whole into one view. Through the whole chain, on three held-out streets with a panorama every 5 m, both rings found all 137 signs, with no false sign and positions within 3 mm of each other in median; on the first 100 m of a test drive with a panorama every 1.2 m, the ring of 6 added one false sign (seen in one panorama and scored just over the minimum confidence, flagged for review) to the 6 true ones. The third choice sees the horizon as one equirectangular band of 3264 × 448 px (8.5 px a degree, ±26° of elevation), which the detector runs on whole: it needs a model whose input size is free, as the bundled detector's is. In single panoramas of fifteen held-out test streets it found 2,632 of 2,778 signs at a precision of 0.976, against 2,638 at 0.968 for the ring of 8, in 0.81 times the processor time; through the whole chain on fourteen held-out streets it found all 632 signs, as the ring does, but with one false sign (a logo printed on a billboard) and three sign codes fewer. 8 by default; 6 and the band trade a little accuracy for speed.</source>
        <translation>地平线环包含多少个宽 80° 的视图。8 个视图相互重叠 35°。6 个视图相互重叠 20°，并旋转 30°，使前后方向的接缝落在前后视图之内：检测时间为 0.8-0.87 倍。在五条留出测试街道的单张全景中，6 个视图找到 0.946 的标志，精度 0.988；8 个视图为 0.948，精度 0.982：6 个视图会漏掉少数高 14-20 像素的标志和少数很近、已无法完整落入一个视图的标志。在整条处理链中，在三条每 5 米一张全景的留出街道上，两种环都找到了全部 137 个标志，没有误报，位置中位数相差不到 3 毫米；在一段每 1.2 米一张全景的测试行驶的前 100 米，6 个视图的环在 6 个真实标志之外多出一个误报（只在一张全景中看到，得分刚超过最低置信度，已标记待复核）。第三个选项把地平线视为一条 3264 × 448 像素的等距柱状条带（每度 8.5 像素，仰角 ±26°），检测器整条处理：它需要输入尺寸不固定的模型，随附的检测器即是如此。在十五条留出测试街道的单张全景中，它在 2,778 个标志中找到 2,632 个，精度 0.976；8 个视图的环找到 2,638 个，精度 0.968，而处理器时间为 0.81 倍；在整条处理链中，在十四条留出街道上，它与环一样找到了全部 632 个标志，但多了一个误报（印在广告牌上的标志图案），少读出三个标志代码。默认为 8；6 和条带以少许精度换取速度。</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="98" />
        <source>Boxes the detector scores from this value up to the minimum confidence get a second look: one is kept when the sign-code classifier reads a class of signs in it with a probability of at least {score} (the probabilities of the codes of that class added up: a speed limit whose digits are unsure is still a prohibitory sign), its box is at least {px} px on its shorter side (under {small_px} px only from a detector score of {small_score}) and at least {share:.0%} of it is sign colours (saturated red, blue or yellow); it then takes that class and keeps its own score. On real street photographs (GTSDB 500-599) at the default minimum confidence this finds 0.958 of the signs at a precision of 0.971, against 0.803 at 0.966 without it, for under 5 % of the detection time. The second look also drops any box the classifier reads as the back of a sign (a plain grey plate facing away: its face is seen from the stations on the other side). Needs the sign codes to be read; a value at or above the minimum confidence switches it off.</source>
        <translation>检测器评分介于此值与最低置信度之间的框会接受二次检查：当标志代码分类器以至少 {score} 的概率在框中读出一类标志（该类别各代码的概率之和：数字不确定的限速标志仍是禁令标志）、框的短边至少 {px} 像素（短于 {small_px} 像素时，检测器评分须至少为 {small_score}）且至少 {share:.0%} 的像素为标志颜色（饱和的红、蓝或黄色）时，该框被保留；它随后采用该类别并保留自身的评分。在真实街道照片（GTSDB 500-599）上，使用默认的最低置信度时，它找到 0.958 的标志，精确率为 0.971；不使用时为 0.803，精确率为 0.966。代价不到检测时间的 5 %。第二次查看还会丢弃分类器读为标志背面的任何框（背向相机的素灰色板：其正面可从另一侧的站点看到）。需要读取标志代码；取值等于或高于最低置信度时关闭此功能。</translation>
    </message>
</context>
<context>
    <name>Evaluate</name>
    <message>
        <location filename="../algorithms/evaluate.py" line="106" />
        <source>Evaluate signs against reference</source>
        <translation>对照参考数据评估标志</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="109" />
        <source>Scores a sign layer against reference sign panels and writes an HTML report.</source>
        <translation>将标志图层与参考标志牌进行对比评分，并生成 HTML 报告。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="134" />
        <source>True positives (matched signs)</source>
        <translation>真正例（匹配的标志）</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="134" />
        <source>False positives (unmatched signs)</source>
        <translation>假正例（未匹配的标志）</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="135" />
        <source>False negatives (missed reference panels)</source>
        <translation>假反例（漏检的参考标志牌）</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="135" />
        <source>Precision</source>
        <translation>精确率</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="136" />
        <source>Recall</source>
        <translation>召回率</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="136" />
        <source>F1 score</source>
        <translation>F1 分数</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="137" />
        <source>Class accuracy of matches</source>
        <translation>匹配的类别准确率</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="138" />
        <source>Median 3D position error (m)</source>
        <translation>三维位置误差中位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="139" />
        <source>95th percentile 3D error (m)</source>
        <translation>三维误差第 95 百分位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="140" />
        <source>Median height error (m)</source>
        <translation>高度误差中位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="141" />
        <source>Median azimuth error (°)</source>
        <translation>方位角误差中位数 (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="147" />
        <source>Median horizontal position error (m)</source>
        <translation>水平位置误差中位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="148" />
        <source>Median vertical position error (m)</source>
        <translation>垂直位置误差中位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="209" />
        <source>Sign layer</source>
        <translation>标志图层</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Reference signs (CSV or point layer)</source>
        <translation>参考标志（CSV 或点图层）</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Reference signs (*.csv *.txt *.gpkg *.shp *.geojson);;All files (*.*)</source>
        <translation>参考标志 (*.csv *.txt *.gpkg *.shp *.geojson);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="163" />
        <source>Match radius (m)</source>
        <translation>匹配半径 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="163" />
        <source>A sign and a reference panel farther apart than this (3D distance between panel centres, metres) are never matched.</source>
        <translation>距离超过此值（标志牌中心之间的三维距离，单位为米）的标志与参考标志牌永远不会被匹配。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>Evaluation report</source>
        <translation>评估报告</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>HTML files (*.html)</source>
        <translation>HTML 文件 (*.html)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>HTML report: the summary and one row per sign and reference panel.</source>
        <translation>HTML 报告：汇总信息，以及每个标志和参考标志牌各一行。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="178" />
        <source>Reference file not found: {}</source>
        <translation>未找到参考文件：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="180" />
        <source>Reference CSV {}: coordinates taken in the sign layer's CRS ({})</source>
        <translation>参考 CSV {}：坐标按标志图层的坐标参考系（{}）解释</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="191" />
        <source>Cannot read the reference {}: expected a CSV or a point layer</source>
        <translation>无法读取参考数据 {}：应为 CSV 或点图层</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="195" />
        <source>Reprojecting the reference from {} to {}</source>
        <translation>正在将参考数据从 {} 重投影到 {}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="212" />
        <source>The sign layer is empty: nothing to evaluate.</source>
        <translation>标志图层为空：没有可评估的内容。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="216" />
        <source>The reference {} has no sign: nothing to evaluate against.</source>
        <translation>参考数据 {} 中没有标志：无法进行评估。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="222" />
        <source>Road sign evaluation</source>
        <translation>道路标志评估</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="229" />
        <source>{} signs, {} reference panels: TP {}, FP {}, FN {}; precision {}, recall {}, median error {} m</source>
        <translation>{} 个标志，{} 个参考标志牌：TP {}，FP {}，FN {}；精确率 {}，召回率 {}，误差中位数 {} m</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="144" />
        <source>Code accuracy of matches with a reference code</source>
        <translation>有参考代码的匹配的代码准确率</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="145" />
        <source>Matches whose codes were compared</source>
        <translation>比较了代码的匹配数</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="146" />
        <source>Compared matches whose sign has no code</source>
        <translation>已比较的匹配中标志没有代码的数量</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="152" />
        <source>The sign layer to score (PointZ at the panel centres, e.g. the output of Refine signs), with the fields sign_id, class and optionally height, azimuth, best_image, code.</source>
        <translation>要评分的标志图层（位于标志牌中心的 PointZ，例如“精化与合并标志”的输出），包含字段 sign_id、class，以及可选的 height、azimuth、best_image、code。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Ground truth: a CSV sign_id,class,x,y,z,height,width,panel_height,azimuth (and optionally code) in the sign layer's CRS, or a point layer with those fields (reprojected if its CRS differs).</source>
        <translation>真值数据：位于标志图层坐标参考系中的 CSV sign_id,class,x,y,z,height,width,panel_height,azimuth（以及可选的 code），或具有这些字段的点图层（若其坐标参考系不同则进行重投影）。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="173" />
        <source>Code confusions (reference code -&gt; sign code: count)</source>
        <translation>代码混淆（参考代码 -&gt; 标志代码：次数）</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="235" />
        <source>Code accuracy {} of {} matches with a reference code ({} without a code); confusions: {}</source>
        <translation>代码准确率 {}，基于 {} 个有参考代码的匹配（{} 个没有代码）；混淆：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="235" />
        <source>none</source>
        <translation>无</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="112" />
        <source>Matches each sign to at most one reference panel by optimal assignment (Hungarian method) on the 3D distance between panel centres, within the match radius and ignoring class, then reports precision (matches / signs), recall (matches / reference panels), F1, the class accuracy of the matches, and the median and 95th percentile position error, the median height error, the median azimuth error, and the median and 95th percentile panel size error (the larger of the width and panel height errors, where the layers have the fields width and panel_height).&lt;br&gt;&lt;br&gt;When the reference has a &lt;i&gt;code&lt;/i&gt; column and the sign layer a &lt;i&gt;code&lt;/i&gt; field (OpenStreetMap traffic_sign codes such as DE:274[50]), it also reports the code accuracy of the matches whose reference code is not empty (a sign without a code counts as wrong, and is counted as no code) and the code confusions, most frequent first.&lt;br&gt;&lt;br&gt;The &lt;b&gt;reference&lt;/b&gt; is a CSV &lt;i&gt;sign_id,class,x,y,z,height,width,panel_height,azimuth&lt;/i&gt; (and optionally &lt;i&gt;code&lt;/i&gt;) in the sign layer's CRS, or a point layer with those fields (reprojected to the sign layer's CRS).&lt;br&gt;&lt;br&gt;The HTML report has the summary and one row per sign: matched (with its errors), missed or false.</source>
        <translation>通过最优分配（匈牙利算法），依据标志牌中心之间的三维距离，在匹配半径内且不考虑类别，将每个标志与至多一个参考标志牌匹配；然后报告精确率（匹配数 / 标志数）、召回率（匹配数 / 参考标志牌数）、F1、匹配的类别准确率，以及位置误差的中位数和第 95 百分位数、高度误差中位数、方位角误差中位数，以及标志牌尺寸误差的中位数和第 95 百分位数（宽度误差与标志牌高度误差中的较大者，当图层具有 width 和 panel_height 字段时）。&lt;br&gt;&lt;br&gt;当参考数据有 &lt;i&gt;code&lt;/i&gt; 列且标志图层有 &lt;i&gt;code&lt;/i&gt; 字段（OpenStreetMap traffic_sign 代码，例如 DE:274[50]）时，还会报告参考代码非空的匹配的代码准确率（没有代码的标志计为错误，并计入无代码数）以及代码混淆，按出现次数从多到少排列。&lt;br&gt;&lt;br&gt;&lt;b&gt;参考数据&lt;/b&gt;为位于标志图层坐标参考系中的 CSV &lt;i&gt;sign_id,class,x,y,z,height,width,panel_height,azimuth&lt;/i&gt;（以及可选的 &lt;i&gt;code&lt;/i&gt;），或具有这些字段的点图层（重投影到标志图层的坐标参考系）。&lt;br&gt;&lt;br&gt;HTML 报告包含汇总信息，并为每个标志列出一行：已匹配（附其误差）、漏检或误检。</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="142" />
        <source>Median panel size error (m)</source>
        <translation>标志牌尺寸误差中位数 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="143" />
        <source>95th percentile panel size error (m)</source>
        <translation>标志牌尺寸误差第 95 百分位数 (m)</translation>
    </message>
</context>
<context>
    <name>ExportHandover</name>
    <message>
        <location filename="../algorithms/exporthandover.py" line="49" />
        <source>Export handover package</source>
        <translation>导出交付包</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="52" />
        <source>The reviewed sign layer as a GeoPackage, a CSV and an OpenStreetMap file for handover.</source>
        <translation>将审核后的标志图层导出为 GeoPackage、CSV 和 OpenStreetMap 文件以便交付。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="55" />
        <source>Writes the signs with the review states you choose (default: accepted and corrected) into a folder: &lt;i&gt;handover.gpkg&lt;/i&gt; and &lt;i&gt;handover.csv&lt;/i&gt; with one row per sign in a documented schema (docs/formats.md, section 4.9), and &lt;i&gt;osm_signs.osm&lt;/i&gt; (or .geojson) for OpenStreetMap.&lt;br&gt;&lt;br&gt;Each sign gets its code and class (after review), its position (x, y, z and WGS 84 longitude and latitude), mounting height, panel size, the azimuth its face looks towards (0-359, from true or grid north as chosen; the column azimuth_north says which), the side of the road and the lateral offset relative to the drive, the chainage along the drive (the stations' track), the nearest road segment's id and the fraction along it when a road network is given, condition and pole when the layer has them, survey date, first and last seen, source images and review status.&lt;br&gt;&lt;br&gt;The OpenStreetMap nodes carry &lt;i&gt;traffic_sign&lt;/i&gt; (the code, prefixed with the country) and &lt;i&gt;direction&lt;/i&gt; (true north) and stand beside the road: a sign over the road is moved to its side of the drive.</source>
        <translation>将所选审核状态（默认：已接受和已更正）的标志写入一个文件夹：&lt;i&gt;handover.gpkg&lt;/i&gt; 和 &lt;i&gt;handover.csv&lt;/i&gt;，每个标志一行，采用有文档说明的模式（docs/formats.md 第 4.9 节），以及供 OpenStreetMap 使用的 &lt;i&gt;osm_signs.osm&lt;/i&gt;（或 .geojson）。&lt;br&gt;&lt;br&gt;每个标志包含其代码和类别（审核后）、位置（x、y、z 及 WGS 84 经纬度）、安装高度、标志牌尺寸、标志牌正面朝向的方位角（0-359，按所选从真北或坐标北起算；azimuth_north 列注明是哪一种）、相对于行驶采集方向的道路侧别和横向偏移、沿行驶采集的里程（全景站点的轨迹线）、给定路网时最近路段的 id 及沿该路段的比例、图层中有相应字段时的状况和立杆、采集日期、首次和最后一次看到的时间、来源图像以及审核状态。&lt;br&gt;&lt;br&gt;OpenStreetMap 节点带有 &lt;i&gt;traffic_sign&lt;/i&gt;（代码，前加国家前缀）和 &lt;i&gt;direction&lt;/i&gt;（真北），并位于道路旁边：位于道路上方的标志会被移到其所在的行驶采集一侧。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="145" />
        <source>Reviewed sign layer</source>
        <translation>已审核的标志图层</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="70" />
        <source>The sign layer after review (fields review_status, reviewed_code... as the review panel writes them), in a projected CRS.</source>
        <translation>审核后的标志图层（包含审核面板写入的 review_status、reviewed_code 等字段），采用投影坐标参考系。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="152" />
        <source>Panorama stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="74" />
        <source>The output of Import trajectory for the same drive: its track gives side, offset and chainage, its times first and last seen.</source>
        <translation>同一次行驶采集的“导入轨迹”输出：其轨迹线给出侧别、偏移和里程，其时间给出首次和最后一次看到的时间。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="78" />
        <source>Road network (optional)</source>
        <translation>路网（可选）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="78" />
        <source>Road segments (lines): each sign gets the nearest one's id and the fraction along it. Lines in another CRS are reprojected.</source>
        <translation>路段（线）：每个标志获得最近路段的 id 及沿该路段的比例。其他坐标参考系中的线会被重投影。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="82" />
        <source>Road segment id field</source>
        <translation>路段 id 字段</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="82" />
        <source>The road network's field holding the segment ids; empty: the feature id.</source>
        <translation>路网中存放路段 id 的字段；留空：使用要素 id。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>Review states to hand over</source>
        <translation>要交付的审核状态</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>accepted</source>
        <translation>已接受</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>corrected (accepted with a new class or code)</source>
        <translation>已更正（以新的类别或代码接受）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>rejected</source>
        <translation>已拒绝</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>needs another look</source>
        <translation>需要再看一次</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>not reviewed</source>
        <translation>未审核</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>Only signs with these review states are written (several may be chosen).</source>
        <translation>只写入具有这些审核状态的标志（可多选）。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>Azimuth from</source>
        <translation>方位角起算</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>true north</source>
        <translation>真北</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>grid north</source>
        <translation>坐标北</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>The facing azimuth is written clockwise from true north (grid azimuth plus meridian convergence) or from grid north of the layer's CRS; the file says which.</source>
        <translation>朝向方位角按顺时针从真北（坐标方位角加子午线收敛角）或从图层坐标参考系的坐标北起算写出；文件中注明是哪一种。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="95" />
        <source>Survey date (YYYY-MM-DD)</source>
        <translation>采集日期（YYYY-MM-DD）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="95" />
        <source>The date of the drive: with station times in GPS seconds of the week, first and last seen become dates and times (UTC).</source>
        <translation>行驶采集的日期：当全景站点时间为 GPS 周内秒时，首次和最后一次看到的时间将换算为日期和时间（UTC）。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>Station times are</source>
        <translation>全景站点时间为</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>GPS seconds of the week</source>
        <translation>GPS 周内秒</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>GPS time (seconds since 1980-01-06)</source>
        <translation>GPS 时间（自 1980-01-06 起的秒数）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>UNIX time (seconds since 1970-01-01 UTC)</source>
        <translation>UNIX 时间（自 1970-01-01 UTC 起的秒数）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>The time base of the stations' time field (that of the trajectory).</source>
        <translation>全景站点 time 字段的时间基准（即轨迹的时间基准）。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="122" />
        <source>OpenStreetMap file</source>
        <translation>OpenStreetMap 文件</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>OSM XML (.osm, opens in JOSM)</source>
        <translation>OSM XML（.osm，可在 JOSM 中打开）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>GeoJSON (.geojson)</source>
        <translation>GeoJSON（.geojson）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>The format of the OpenStreetMap nodes file.</source>
        <translation>OpenStreetMap 节点文件的格式。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="109" />
        <source>Country prefix for traffic_sign</source>
        <translation>traffic_sign 的国家前缀</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="109" />
        <source>ISO country code written before codes without one: DE gives traffic_sign=DE:206.</source>
        <translation>写在没有前缀的代码之前的 ISO 国家代码：DE 得到 traffic_sign=DE:206。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="112" />
        <source>Least distance of OSM nodes from the road (m)</source>
        <translation>OSM 节点离道路的最小距离（米）</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="112" />
        <source>OpenStreetMap nodes closer than this to the drive (or to the nearest road line) are moved away from it on the sign's side, so that no sign node sits on the road.</source>
        <translation>离行驶采集轨迹（或最近道路线）比此值更近的 OpenStreetMap 节点会向标志所在一侧移开，使标志节点不会落在道路上。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="117" />
        <source>Handover folder</source>
        <translation>交付文件夹</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="117" />
        <source>The folder the package is written to (created when missing; files of an earlier package are replaced).</source>
        <translation>写入交付包的文件夹（不存在时创建；先前交付包的文件会被替换）。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="120" />
        <source>Handover GeoPackage</source>
        <translation>交付 GeoPackage</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="121" />
        <source>Handover CSV</source>
        <translation>交付 CSV</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="135" />
        <source>Choose at least one review state to hand over.</source>
        <translation>请至少选择一种要交付的审核状态。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="141" />
        <source>The sign layer has no CRS: set its projected CRS (layer properties) and run again.</source>
        <translation>标志图层没有坐标参考系：请在图层属性中设置其投影坐标参考系后再运行。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="143" />
        <source>The sign layer</source>
        <translation>标志图层</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="149" />
        <source>The stations are in {}, the sign layer in {}: use the stations of the drive the signs come from</source>
        <translation>全景站点位于 {}，标志图层位于 {}：请使用标志所来自的行驶采集的全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="175" />
        <source>Handover package: {} signs in {}</source>
        <translation>交付包：{} 个标志，位于 {}</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="185" />
        <source>Survey date '{}' is not a date: write it as YYYY-MM-DD, e.g. 2024-03-14</source>
        <translation>采集日期“{}”不是日期：请写成 YYYY-MM-DD，例如 2024-03-14</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="201" />
        <source>Sign {} has neither a point geometry nor x and y fields</source>
        <translation>标志 {} 既没有点几何，也没有 x 和 y 字段</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="215" />
        <source>The road network has no field {}; fields found: {}</source>
        <translation>路网没有字段 {}；找到的字段：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="220" />
        <source>The road network is in {}: reprojected to {}, the sign layer's CRS.</source>
        <translation>路网位于 {}：已重投影到标志图层的坐标参考系 {}。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="223" />
        <source>No road segment id field chosen: the road ids are the feature ids.</source>
        <translation>未选择路段 id 字段：道路 id 使用要素 id。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="239" />
        <source>The road network has no lines: road_id and road_fraction stay empty.</source>
        <translation>路网中没有线：road_id 和 road_fraction 保持为空。</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="258" />
        <source>Cannot write {}: {}</source>
        <translation>无法写入 {}：{}</translation>
    </message>
</context>
<context>
    <name>FindSignsInCloud</name>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="24" />
        <source>Find signs in the point cloud (no images)</source>
        <translation>在点云中查找标志（无图像）</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="27" />
        <source>Finds retro-reflective sign panels and their poles in the LiDAR cloud alone, and flags faded sheeting.</source>
        <translation>仅在激光雷达点云中查找逆反射标志牌及其杆，并标记出老化褪色的反光膜。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="31" />
        <source>Finds sign panels from the point cloud alone, after the Utah I-15 mobile-LiDAR method (Ai and Tsai): the drive's track (the panorama stations) locates every point along the road; points above the ground (class 2) and beside or above the road are kept; their intensity is normalised for range and incidence angle; a threshold adapted to the cloud (stated in the log) picks the retro-reflective sheeting; planar clusters of sign size and shape at sign heights become panels, each with the pole or gantry that carries it. The cloud is read once and worked through in windows of drive, so memory does not grow with the drive.&lt;br&gt;&lt;br&gt;Outputs: the sign panels (PointZ at the panel centre: size, face normal and azimuth, height above the ground, intensity statistics, the retroreflectivity index and a &lt;b&gt;condition&lt;/b&gt; of good, check or poor), their outlines (PolygonZ), and the poles (sign poles, light poles, gantry posts: foot, height, diameter, lean and the signs each carries).&lt;br&gt;&lt;br&gt;&lt;b&gt;Condition&lt;/b&gt; is a screening flag, not a measurement: the retroreflectivity index is the median normalised intensity of the panel's face, compared with the drive's own healthy signs. It is not the coefficient of retroreflection of the MUTCD (observation angle 0.2°, entrance angle −4°): confirm flagged signs in the field. The cloud needs an intensity dimension and ground points (run Ground filter first).</source>
        <translation>仅根据点云查找标志牌，参照犹他州 I-15 移动激光雷达方法（Ai 和 Tsai）：行驶采集的轨迹线（全景站点）确定每个点沿道路的位置；保留高于地面（类别 2）且位于道路旁或道路上方的点；按距离和入射角对其强度进行归一化；根据点云自适应的阈值（在日志中给出）选出逆反射反光膜；位于标志高度、具有标志大小和形状的平面聚类成为标志牌，每个标志牌附带承载它的杆或门架。点云只读取一次，并按行驶采集的分段窗口处理，因此内存占用不会随行驶采集的长度增长。&lt;br&gt;&lt;br&gt;输出：标志牌（位于标志牌中心的 PointZ：尺寸、牌面法向量和方位角、离地高度、强度统计、逆反射指数以及 good、check 或 poor 的&lt;b&gt;状态&lt;/b&gt;（condition）），其轮廓（PolygonZ），以及杆（标志杆、灯杆、门架立柱：杆底位置、高度、直径、倾斜度以及各自承载的标志）。&lt;br&gt;&lt;br&gt;&lt;b&gt;状态&lt;/b&gt;是筛查标记，而非测量结果：逆反射指数是标志牌牌面归一化强度的中位数，并与本次行驶采集中状况良好的标志进行比较。它不是 MUTCD 规定的逆反射系数（观测角 0.2°，入射角 −4°）：被标记的标志请到现场确认。点云需要强度维度和地面点（请先运行“地面滤波与点云裁剪”）。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="50" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>已地面分类的点云（LAS/LAZ）</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="50" />
        <source>The cloud with ground as class 2 (the output of Ground filter) and an intensity dimension, in the stations' CRS.</source>
        <translation>地面为类别 2 的点云（“地面滤波与点云裁剪”的输出），带有强度维度，与全景站点位于同一坐标参考系。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="87" />
        <source>Panorama stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="54" />
        <source>The output of Import trajectory: the drive's track (positions and times).</source>
        <translation>“导入轨迹和全景图”的输出：行驶采集的轨迹线（位置和时间）。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="57" />
        <source>Corridor half-width (m)</source>
        <translation>走廊半宽 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="57" />
        <source>Signs are searched this far to each side of the track, in metres.</source>
        <translation>在轨迹线两侧各此距离（米）范围内搜索标志。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="61" />
        <source>Sign panels found in the cloud</source>
        <translation>点云中找到的标志牌</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="61" />
        <source>PointZ layer, one point per panel centre, with its size, face normal and azimuth, heights, intensity statistics, retroreflectivity index, condition and support.</source>
        <translation>PointZ 图层，每个标志牌中心一个点，包含其尺寸、牌面法向量和方位角、高度、强度统计、逆反射指数、状态和支撑结构。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="65" />
        <source>Panel outlines</source>
        <translation>标志牌轮廓</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="65" />
        <source>PolygonZ layer of each panel's rectangle in its plane.</source>
        <translation>每个标志牌在其所在平面内的矩形的 PolygonZ 图层。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="68" />
        <source>Poles</source>
        <translation>杆</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="68" />
        <source>PointZ layer, one point per pole foot: kind (sign_pole, light_pole, gantry, other), height, diameter, lean and the ids of the signs it carries.</source>
        <translation>PointZ 图层，每根杆的杆底一个点：类型（sign_pole、light_pole、gantry、other）、高度、直径、倾斜度以及其承载的标志的 ID。</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="72" />
        <source>Sign panels found</source>
        <translation>找到的标志牌数</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="73" />
        <source>Poles found</source>
        <translation>找到的杆数</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="86" />
        <source>The stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="118" />
        <source>{} sign panels and {} poles found in the cloud.</source>
        <translation>在点云中找到 {} 个标志牌和 {} 根杆。</translation>
    </message>
</context>
<context>
    <name>FuseSigns</name>
    <message>
        <location filename="../algorithms/fusesigns.py" line="33" />
        <source>Fuse image and cloud signs</source>
        <translation>融合图像与点云标志</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="36" />
        <source>Merges the signs found in the images with the panels found in the cloud alone: one sign layer that says which sources found each sign.</source>
        <translation>将在图像中找到的标志与仅在点云中找到的标志牌合并：生成一个标志图层，注明每个标志由哪些来源找到。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="111" />
        <source>Signs (from the images)</source>
        <translation>标志（来自图像）</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="57" />
        <source>The output of Refine and merge signs.</source>
        <translation>“精化与合并标志”的输出。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="113" />
        <source>Sign panels found in the cloud</source>
        <translation>点云中找到的标志牌</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="60" />
        <source>The output of Find signs in the point cloud.</source>
        <translation>“在点云中查找标志（无图像）”的输出。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="63" />
        <source>Panorama stations (to classify panels found in the cloud alone)</source>
        <translation>全景站点（用于对仅在点云中找到的标志牌分类）</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="63" />
        <source>The output of Import trajectory. With the panorama folder, the class of each panel no image sign explains is read from the panoramas in front of it.</source>
        <translation>“导入轨迹和全景图”的输出。若提供全景图文件夹，则从标志牌前方的全景图中识别每个没有图像标志与之对应的标志牌的类别。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="68" />
        <source>Panorama folder (optional)</source>
        <translation>全景图文件夹（可选）</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="68" />
        <source>The folder of the panoramas (empty: the paths in the stations layer).</source>
        <translation>全景图所在的文件夹（留空：使用全景站点图层中的路径）。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>ONNX model (empty: the bundled model)</source>
        <translation>ONNX 模型（留空：使用内置模型）</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>The detector that reads the class of panels found in the cloud alone.</source>
        <translation>用于识别仅在点云中找到的标志牌类别的检测器。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>ONNX 模型 (*.onnx);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="76" />
        <source>Minimum confidence</source>
        <translation>最低置信度</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="76" />
        <source>A class read from the panoramas is kept when the detector scores it at least this (0-1).</source>
        <translation>当检测器给出的得分不低于此值（0-1）时，保留从全景图中识别出的类别。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="80" />
        <source>Match radius (m)</source>
        <translation>匹配半径 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="80" />
        <source>An image sign and a cloud panel farther apart than this (3D, metres) are never the same sign.</source>
        <translation>距离超过此值（三维距离，单位为米）的图像标志与点云标志牌永远不会被视为同一个标志。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="92" />
        <source>Signs (fused)</source>
        <translation>标志（融合）</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="92" />
        <source>PointZ sign layer: the sign fields, and source (image, lidar, image+lidar), review (1: to be checked), image_sign_id, cloud_sign_id, retro_index, condition and the review chip of the image sign (chip, relative to the layer's folder).</source>
        <translation>PointZ 标志图层：标志字段，以及 source（image、lidar、image+lidar）、review（1：待检查）、image_sign_id、cloud_sign_id、retro_index、condition 和图像标志的审核切片（chip，相对于图层所在文件夹的路径）。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="97" />
        <source>Signs found by both</source>
        <translation>两者均找到的标志</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="98" />
        <source>Signs found in the images only</source>
        <translation>仅在图像中找到的标志</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="99" />
        <source>Signs found in the cloud only</source>
        <translation>仅在点云中找到的标志</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="117" />
        <source>The signs are in {}, the panels found in the cloud in {}: both must be in the cloud's CRS</source>
        <translation>标志位于 {}，点云中找到的标志牌位于 {}：两者都必须位于点云的坐标参考系中</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="128" />
        <source>No stations given: the {} signs found in the cloud alone keep the class unknown.</source>
        <translation>未提供全景站点：仅在点云中找到的 {} 个标志保留类别 unknown。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="144" />
        <source>{} signs: {} found by both, {} in the images only ({} of them where the cloud was searched: score lowered, to review), {} in the cloud only.</source>
        <translation>{} 个标志：{} 个两者均找到，{} 个仅在图像中找到（其中 {} 个位于点云已搜索的范围内：得分已降低，待审核），{} 个仅在点云中找到。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="157" />
        <source>Panorama stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="163" />
        <source>ONNX model not found: {}</source>
        <translation>未找到 ONNX 模型：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="179" />
        <source>{} of the {} signs found in the cloud alone were recognised in the panoramas; the others keep the class unknown and are to review.</source>
        <translation>有 {} 个（共 {} 个仅在点云中找到的标志）在全景图中被识别；其余标志保留类别 unknown，待审核。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="40" />
        <source>Matches each sign of the image chain (Refine and merge signs) to at most one panel found in the cloud alone (Find signs in the point cloud) by optimal assignment: centres within the match radius and facings within 90°.&lt;br&gt;&lt;br&gt;A matched sign keeps its class and gains the panel's retroreflectivity index and condition (&lt;i&gt;source&lt;/i&gt; = image+lidar). A panel no image sign explains becomes a sign of its own (&lt;i&gt;source&lt;/i&gt; = lidar): with the stations and the panorama folder, the panoramas in front of its face are cut into views centred on it and the detector reads its class there; if none recognises it, its class is &lt;i&gt;unknown&lt;/i&gt; and it is flagged for review. The sign-code classifier reads its code in a crop around each of those detections, and the views vote as Refine and merge signs votes them (code, code_name, code_score, code_views, code_check). An image sign whose place in the cloud holds no retro-reflective panel loses confidence (its score × 0.6) and is flagged for review (&lt;i&gt;source&lt;/i&gt; = image).&lt;br&gt;&lt;br&gt;Output: the sign layer with the fields of Refine and merge signs plus source, review, image_sign_id, cloud_sign_id, retro_index and condition, styled like the sign layer.</source>
        <translation>通过最优分配，将图像流程（“精化与合并标志”）中的每个标志与最多一个仅在点云中找到的标志牌（“在点云中查找标志（无图像）”）进行匹配：中心位于匹配半径内，且朝向相差不超过 90°。&lt;br&gt;&lt;br&gt;匹配上的标志保留其类别，并获得该标志牌的逆反射指数和状态（&lt;i&gt;source&lt;/i&gt; = image+lidar）。没有任何图像标志与之对应的标志牌成为单独的标志（&lt;i&gt;source&lt;/i&gt; = lidar）：若提供全景站点和全景图文件夹，将从其牌面前方的全景图中截取以其为中心的视图，由检测器在其中识别其类别；若均未识别出，其类别为 &lt;i&gt;unknown&lt;/i&gt;，并标记为待审核。标志代码分类器在每个这些检测结果周围的裁剪图中读取其代码，各视图按“精化与合并标志”的方式投票（code、code_name、code_score、code_views、code_check）。若某图像标志在点云中的位置没有逆反射标志牌，则降低其置信度（得分 × 0.6），并标记为待审核（&lt;i&gt;source&lt;/i&gt; = image）。&lt;br&gt;&lt;br&gt;输出：标志图层，包含“精化与合并标志”的字段以及 source、review、image_sign_id、cloud_sign_id、retro_index 和 condition，样式与标志图层相同。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="84" />
        <source>for each sign found in the cloud alone and recognised in the panoramas, in a crop around each of its detections there</source>
        <translation>针对每个仅在点云中找到并在全景图中识别出的标志，在其各检测结果周围的裁剪图中读取</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="86" />
        <source>Minimum code confidence</source>
        <translation>最低代码置信度</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="86" />
        <source>The code voted for a sign found in the cloud alone is kept when its support (its share of the views' weighted vote x the mean probability the classifier gave it, 0-1: the code_score field) is at least this; else the code field stays empty.</source>
        <translation>当仅在点云中找到的标志投票得出的代码的支持度（其在各视图加权投票中的占比 x 分类器给出的平均概率，0-1：即 code_score 字段）不低于此值时保留该代码；否则 code 字段保持为空。</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="184" />
        <source>Sign codes read for {} of them.</source>
        <translation>其中 {} 个读取到了标志代码。</translation>
    </message>
</context>
<context>
    <name>GroundFilter</name>
    <message>
        <location filename="../algorithms/groundfilter.py" line="57" />
        <source>Ground filter and crop point cloud</source>
        <translation>地面滤波与点云裁剪</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="60" />
        <source>Crops a LAS/LAZ cloud and classifies ground (class 2) with CSF or SMRF, PDAL or built-in.</source>
        <translation>裁剪 LAS/LAZ 点云，并使用 CSF 或 SMRF（PDAL 或内置引擎）将地面分类为类别 2。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="97" />
        <source>Point cloud (LAS/LAZ)</source>
        <translation>点云（LAS/LAZ）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="97" />
        <source>The mobile-mapping cloud, LAS 1.2-1.4 or LAZ, any size (it is read in chunks).</source>
        <translation>移动测量点云，LAS 1.2-1.4 或 LAZ，大小不限（分块读取）。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="100" />
        <source>Crop layer (optional)</source>
        <translation>裁剪图层（可选）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="100" />
        <source>Keep only points inside these polygons, or within the crop buffer of these points or lines (e.g. the panorama stations). Empty keeps the whole cloud.</source>
        <translation>仅保留这些多边形内的点，或这些点或线（例如全景站点）的裁剪缓冲距离内的点。留空则保留整个点云。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="104" />
        <source>Crop buffer (m)</source>
        <translation>裁剪缓冲距离 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="104" />
        <source>Grow the crop geometries by this many metres; needed (&gt; 0) for a point or line layer.</source>
        <translation>将裁剪几何外扩的米数；点或线图层必须大于 0。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>Ground method</source>
        <translation>地面分类方法</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>CSF (cloth simulation)</source>
        <translation>CSF（布料模拟）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>SMRF (simple morphological filter)</source>
        <translation>SMRF（简单形态学滤波）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>CSF suits roads and gentle terrain; SMRF suits steeper or rougher terrain.</source>
        <translation>CSF 适用于道路和平缓地形；SMRF 适用于较陡或较崎岖的地形。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Engine</source>
        <translation>引擎</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>PDAL</source>
        <translation>PDAL</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Built-in</source>
        <translation>内置</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="119" />
        <source>Ground distance threshold (m)</source>
        <translation>地面距离阈值 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="119" />
        <source>Points within this height of the ground surface are ground (PDAL's threshold option). PDAL's default is 0.5 m; 0.2 m suits dense mobile-mapping clouds, where it keeps the lowest parts of cars, walls and street furniture off the ground class.</source>
        <translation>距地面表面在此高度以内的点被视为地面（PDAL 的 threshold 选项）。PDAL 的默认值为 0.5 m；0.2 m 适用于密集的移动测量点云，可避免汽车、墙体和街道设施的最低部分被归入地面类别。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="125" />
        <source>Cloth resolution / cell size (m)</source>
        <translation>布料分辨率 / 格网大小 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="125" />
        <source>CSF's cloth resolution or SMRF's cell size, in metres (PDAL's default: 1 m).</source>
        <translation>CSF 的布料分辨率或 SMRF 的格网大小，单位为米（PDAL 默认值：1 m）。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="129" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>点云坐标参考系（文件中没有时）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="129" />
        <source>The cloud's CRS if the file does not record one; a CRS in the file is replaced by it. The CRS is never guessed.</source>
        <translation>当文件未记录坐标参考系时使用的点云坐标参考系；文件中已有的坐标参考系将被其替换。从不猜测坐标参考系。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="133" />
        <source>Reset existing classes</source>
        <translation>重置现有类别</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="133" />
        <source>Set every non-ground point to class 1 (unclassified) instead of keeping its class.</source>
        <translation>将所有非地面点设为类别 1（未分类），而不保留其原有类别。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>Ground-classified cloud</source>
        <translation>已地面分类的点云</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>LAZ (*.laz);;LAS (*.las)</source>
        <translation>LAZ (*.laz);;LAS (*.las)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="148" />
        <source>Engine that ran</source>
        <translation>实际运行的引擎</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="149" />
        <source>Points read</source>
        <translation>读取的点数</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="150" />
        <source>Points written</source>
        <translation>写入的点数</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="151" />
        <source>Ground points</source>
        <translation>地面点数</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="161" />
        <source>The crop layer holds points or lines: give a crop buffer in metres (&gt; 0) to make a corridor around them</source>
        <translation>裁剪图层包含点或线：请给出以米为单位的裁剪缓冲距离（&gt; 0），以便在其周围形成走廊</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="166" />
        <source>Reprojecting the crop layer from {} to {}</source>
        <translation>正在将裁剪图层从 {} 重投影到 {}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="268" />
        <source>Engine: {}; method: {}; {} points read, {} written, {} ground</source>
        <translation>引擎：{}；方法：{}；读取 {} 个点，写入 {} 个，地面点 {} 个</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="172" />
        <source>Cancelled: nothing was written.</source>
        <translation>已取消：未写入任何内容。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="181" />
        <source>The crop layer {} has no feature: nothing to crop by. Leave the crop layer empty to process the whole cloud</source>
        <translation>裁剪图层 {} 没有要素：无可用于裁剪的内容。若要处理整个点云，请将裁剪图层留空</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="185" />
        <source>The crop layer {} has no geometry (its {} features are empty): nothing to crop by</source>
        <translation>裁剪图层 {} 没有几何（其 {} 个要素均为空）：无可用于裁剪的内容</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="200" />
        <source>The crop area (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}) does not overlap the point cloud {} (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}): nothing would be kept</source>
        <translation>裁剪区域（x {:.1f} 至 {:.1f}，y {:.1f} 至 {:.1f}）与点云 {}（x {:.1f} 至 {:.1f}，y {:.1f} 至 {:.1f}）不重叠：不会保留任何点</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="213" />
        <source>PDAL said: {}</source>
        <translation>PDAL 输出：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="214" />
        <source>PDAL failed: {}</source>
        <translation>PDAL 失败：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="235" />
        <source>The output {} must not be the input file</source>
        <translation>输出 {} 不能是输入文件</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="137" />
        <source>Write one tile per input tile</source>
        <translation>每个输入分块写出一个分块</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="257" />
        <source>Writing one tile per input tile to the folder {}, listed in {}</source>
        <translation>正在为每个输入分块写出一个分块到文件夹 {}，并列于 {} 中</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Auto (the faster engine: built-in)</source>
        <translation>自动（更快的引擎：内置引擎）</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Auto: the engine measured faster for the method, today the built-in engine for both (PDAL when the built-in CSF's package is missing). PDAL: its Python bindings or the pdal executable that QGIS has; an error when there is neither.</source>
        <translation>自动：针对所选方法实测更快的引擎，目前两种方法均为内置引擎（缺少内置 CSF 所需的包时使用 PDAL）。PDAL：使用 QGIS 带有的 Python 绑定或 pdal 可执行文件；两者都没有时报错。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="137" />
        <source>Write each input tile to its own file (same name, same header) in a folder named after the output, with a virtual point cloud (.vpc) listing them, instead of one file.</source>
        <translation>将每个输入分块写入各自的文件（同名、同文件头），放在以输出命名的文件夹中，并附带列出它们的虚拟点云（.vpc），而不是写成一个文件。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>The cropped cloud with ground as class 2; LAZ or LAS by the file extension. LAS is about eight times larger (about 30 bytes a point) but needs no compression here nor decompression in the stages that read it next: on a 1 km drive of 38 M points the whole chain ran in 0.84 times the time with a LAS ground cloud. With one tile per input tile: the folder of this name without its extension gets the tiles and &lt;name&gt;.vpc, which is then this output.</source>
        <translation>裁剪后的点云，地面为第 2 类；按文件扩展名为 LAZ 或 LAS。LAS 大约大八倍（每点约 30 字节），但这里无需压缩，后续读取它的步骤也无需解压：在一段 1 公里、3800 万点的行驶数据上，使用 LAS 地面点云时整个处理链的用时为 0.84 倍。每个输入瓦片输出一个瓦片时：以此名称（去掉扩展名）命名的文件夹接收这些瓦片和 &lt;name&gt;.vpc，后者即为此输出。</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="64" />
        <source>Reads the LAS/LAZ cloud in chunks, keeps the points inside the crop area and classifies ground points as class 2 with the cloth simulation filter (CSF, Zhang et al. 2016) or the simple morphological filter (SMRF, Pingel et al. 2013), with PDAL's parameters (defaults tuned for dense mobile-mapping clouds: 0.2 m threshold, 0.5 m cells; PDAL's own are 0.5 m and 1 m). Other classes are kept unless &lt;i&gt;Reset existing classes&lt;/i&gt; is checked. Every dimension, extra bytes, VLRs, scales and offsets and the CRS are written unchanged.&lt;br&gt;&lt;br&gt;&lt;b&gt;Crop&lt;/b&gt;: polygons (grown by the crop buffer), or points and lines such as the panorama stations or detection rays, buffered into a corridor. The crop layer is reprojected to the cloud's CRS.&lt;br&gt;&lt;br&gt;&lt;b&gt;Engine&lt;/b&gt;: PDAL runs filters.csf / filters.smrf through its Python bindings or the &lt;i&gt;pdal&lt;/i&gt; executable (on PATH, in QGIS's bin folder, or set in Processing ▸ Options ▸ Providers ▸ Road sign inventory), holding the cloud in memory (about 150 bytes a point); the built-in engine runs the same filters in Python, streaming the cloud, so clouds larger than memory work (between its two passes it keeps the points uncompressed on disk beside the output, about 30 bytes a point, so a LAZ is decompressed once). A cloud wider or longer than 512 m (a drive) is classified block by block, the ground surface of one block at a time, so the memory does not grow with the drive; its points are then written grouped by block. &lt;b&gt;Auto picks the built-in engine&lt;/b&gt; for both methods: measured against PDAL 2.9.2 on two cores it was as fast for CSF on 8 M points (within 10 %) and 1.6 times faster on 38 M, and 1.4 to 1.7 times faster for SMRF, in about 300 MB where PDAL took 5.6 GB for 38 M points (bench/README.md). Auto uses PDAL only when the built-in CSF's Python package (cloth-simulation-filter) is missing; the log says which engine ran and why.&lt;br&gt;&lt;br&gt;&lt;b&gt;Tiles&lt;/b&gt;: the input may be one LAS/LAZ file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc); PDAL takes the tiles one by one, each with its neighbours' points around it. They are written to one file, or, with &lt;i&gt;Write one tile per input tile&lt;/i&gt;, each to a file of its own name in a folder named after the output (out/ground.laz gives the folder out/ground), with a virtual point cloud listing them (out/ground/ground.vpc, the output to give the next stages). Each tile is classified with its neighbours' points around it, so the classes at tile edges are those of a run on the whole cloud.</source>
        <translation>分块读取 LAS/LAZ 点云，保留裁剪范围内的点，并使用布料模拟滤波（CSF，Zhang 等，2016）或简单形态学滤波（SMRF，Pingel 等，2013）将地面点分类为类别 2，参数与 PDAL 相同（默认值针对密集的移动测量点云调整：阈值 0.2 m，格网 0.5 m；PDAL 自身的默认值为 0.5 m 和 1 m）。除非勾选&lt;i&gt;重置现有类别&lt;/i&gt;，其他类别将被保留。所有维度、额外字节、VLR、缩放与偏移以及坐标参考系均原样写出。&lt;br&gt;&lt;br&gt;&lt;b&gt;裁剪&lt;/b&gt;：多边形（按裁剪缓冲距离外扩），或点和线（例如全景站点或检测射线），缓冲为走廊。裁剪图层会被重投影到点云的坐标参考系。&lt;br&gt;&lt;br&gt;&lt;b&gt;引擎&lt;/b&gt;：PDAL 通过其 Python 绑定或 &lt;i&gt;pdal&lt;/i&gt; 可执行文件（位于 PATH、QGIS 的 bin 文件夹中，或在 处理 ▸ 选项 ▸ 提供者 ▸ Road sign inventory 中设置）运行 filters.csf / filters.smrf，并将整个点云保存在内存中（每个点约 150 字节）；内置引擎在 Python 中以流式方式读取点云并运行相同的滤波器，因此可以处理大于内存的点云（在两遍处理之间，它将未压缩的点保存在输出旁边的磁盘上，每个点约 30 字节，因此 LAZ 只需解压一次）。宽度或长度超过 512 m 的点云（一次行驶）按区块逐个分类，每次只保留一个区块的地面表面，因此内存不会随行驶距离增长；其点随后按区块分组写出。&lt;b&gt;“自动”对两种方法均选择内置引擎&lt;/b&gt;：在双核上与 PDAL 2.9.2 对比实测，CSF 在 8 M 个点上速度相当（相差不到 10 %），在 38 M 个点上快 1.6 倍；SMRF 快 1.4 至 1.7 倍；内存占用约 300 MB，而 PDAL 处理 38 M 个点时占用 5.6 GB（bench/README.md）。仅当缺少内置 CSF 的 Python 包（cloth-simulation-filter）时，“自动”才使用 PDAL；日志会说明运行了哪个引擎及原因。&lt;br&gt;&lt;br&gt;&lt;b&gt;分块&lt;/b&gt;：输入可以是单个 LAS/LAZ 文件、LAS/LAZ 分块文件夹或虚拟点云（.vpc）；PDAL 逐个处理分块，每个分块都带上其周围相邻分块的点。分块写入一个文件，或在勾选&lt;i&gt;每个输入分块写出一个分块&lt;/i&gt;时，各自写入以输出命名的文件夹中与原名相同的文件（out/ground.laz 对应文件夹 out/ground），并附带列出这些分块的虚拟点云（out/ground/ground.vpc，即交给后续步骤的输出）。每个分块在分类时会带上其周围相邻分块的点，因此分块边缘的类别与对整个点云运行所得的相同。</translation>
    </message>
</context>
<context>
    <name>ImportTrajectory</name>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="31" />
        <source>Import trajectory and panoramas</source>
        <translation>导入轨迹和全景图</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="34" />
        <source>Trajectory (CSV or SBET) and image times, or per-image poses, to panorama stations with full pose.</source>
        <translation>由轨迹（CSV 或 SBET）和图像时间，或逐图像位姿，生成带完整位姿的全景站点。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="38" />
        <source>Builds the panorama stations: the position and full orientation of every panorama at its exposure, in the target CRS.&lt;br&gt;&lt;br&gt;Give a &lt;b&gt;trajectory&lt;/b&gt; (CSV &lt;i&gt;time,x,y,z,roll,pitch,heading&lt;/i&gt; or an Applanix SBET .out) with an &lt;b&gt;image times&lt;/b&gt; CSV (&lt;i&gt;image,time&lt;/i&gt;), or a &lt;b&gt;per-image pose&lt;/b&gt; CSV (&lt;i&gt;image,x,y,z,roll,pitch,heading[,time]&lt;/i&gt;) instead. Angles are in degrees (radians in an SBET); heading is clockwise from &lt;b&gt;true&lt;/b&gt; north and is turned into a grid heading with the meridian convergence at each station. Positions are interpolated linearly and attitudes by SLERP at the image times.&lt;br&gt;&lt;br&gt;The &lt;b&gt;camera mount&lt;/b&gt; places the panorama on the vehicle: lever arm in metres in the body frame (x forward, y right, z down) and boresight angles in degrees.&lt;br&gt;&lt;br&gt;Output: one point per panorama at its centre, with the quaternion (qw, qx, qy, qz) that maps panorama rays to world East-North-Up, the forward azimuth and the image size read from its header.</source>
        <translation>生成全景站点：每张全景图在曝光时刻的位置和完整姿态，位于目标坐标参考系中。&lt;br&gt;&lt;br&gt;提供&lt;b&gt;轨迹&lt;/b&gt;（CSV &lt;i&gt;time,x,y,z,roll,pitch,heading&lt;/i&gt; 或 Applanix SBET .out）和&lt;b&gt;图像时间&lt;/b&gt; CSV（&lt;i&gt;image,time&lt;/i&gt;），或者改为提供&lt;b&gt;逐图像位姿&lt;/b&gt; CSV（&lt;i&gt;image,x,y,z,roll,pitch,heading[,time]&lt;/i&gt;）。角度单位为度（SBET 中为弧度）；航向角从&lt;b&gt;真&lt;/b&gt;北起顺时针计算，并在每个站点利用子午线收敛角转换为坐标网格航向。在图像时间处，位置采用线性插值，姿态采用 SLERP 插值。&lt;br&gt;&lt;br&gt;&lt;b&gt;相机安装&lt;/b&gt;参数确定全景相机在车辆上的位置：载体坐标系（x 向前，y 向右，z 向下）中以米为单位的杆臂，以及以度为单位的安置角（boresight）。&lt;br&gt;&lt;br&gt;输出：每张全景图在其中心处一个点，附带将全景射线映射到世界东-北-天坐标的四元数（qw, qx, qy, qz）、前进方向方位角以及从文件头读取的图像尺寸。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory (CSV or SBET)</source>
        <translation>轨迹（CSV 或 SBET）</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory CSV with a header time,x,y,z,roll,pitch,heading (comma, semicolon, tab or space separated), or an Applanix SBET (.out, .sbet). Times increase strictly.</source>
        <translation>带表头 time,x,y,z,roll,pitch,heading 的轨迹 CSV（以逗号、分号、制表符或空格分隔），或 Applanix SBET（.out、.sbet）。时间必须严格递增。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory (*.csv *.txt *.out *.sbet);;All files (*.*)</source>
        <translation>轨迹 (*.csv *.txt *.out *.sbet);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="59" />
        <source>Image times (CSV)</source>
        <translation>图像时间（CSV）</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="59" />
        <source>CSV image,time: each panorama's file name (relative to the panorama folder) and exposure time, in the trajectory's time base.</source>
        <translation>CSV image,time：每张全景图的文件名（相对于全景图文件夹）及曝光时间，与轨迹使用相同的时间基准。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>CSV (*.csv *.txt);;All files (*.*)</source>
        <translation>CSV (*.csv *.txt);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>Per-image poses (CSV, instead of trajectory and image times)</source>
        <translation>逐图像位姿（CSV，替代轨迹和图像时间）</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>CSV image,x,y,z,roll,pitch,heading and optionally time: the vehicle body pose at each exposure. Use instead of a trajectory with image times.</source>
        <translation>CSV image,x,y,z,roll,pitch,heading，可选 time：每次曝光时车辆载体的位姿。用于替代带图像时间的轨迹。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="69" />
        <source>Panorama folder</source>
        <translation>全景图文件夹</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="69" />
        <source>Folder of the equirectangular panoramas (JPEG or PNG, twice as wide as high).</source>
        <translation>等距柱状全景图所在的文件夹（JPEG 或 PNG，宽为高的两倍）。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="73" />
        <source>Trajectory CRS</source>
        <translation>轨迹坐标参考系</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="73" />
        <source>CRS of the trajectory or pose positions (x = longitude, y = latitude, z = ellipsoidal height for a geographic CRS). Ignored for an SBET, which is always WGS 84.</source>
        <translation>轨迹或位姿位置的坐标参考系（地理坐标参考系时 x = 经度，y = 纬度，z = 椭球高）。对 SBET 忽略此项，SBET 始终为 WGS 84。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="78" />
        <source>Target CRS (projected)</source>
        <translation>目标坐标参考系（投影）</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="78" />
        <source>Projected CRS of the outputs (metres, East-North-Up). A compound CRS with a vertical datum turns ellipsoidal heights into that datum when its geoid grid is installed. Empty: the trajectory CRS if it is projected, else its UTM zone.</source>
        <translation>输出的投影坐标参考系（米，东-北-天）。若已安装相应的大地水准面格网，带有高程基准的复合坐标参考系会将椭球高转换到该基准。留空：若轨迹坐标参考系为投影坐标系则使用它，否则使用其所在的 UTM 分带。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="84" />
        <source>Panorama centre relative to the trajectory's reference point, in metres along the body axes: x forward, y right, z down.</source>
        <translation>全景相机中心相对于轨迹参考点的位置，沿载体坐标轴以米为单位：x 向前，y 向右，z 向下。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="86" />
        <source>Lever arm x, forward (m)</source>
        <translation>杆臂 x，向前 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="87" />
        <source>Lever arm y, right (m)</source>
        <translation>杆臂 y，向右 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="88" />
        <source>Lever arm z, down (m)</source>
        <translation>杆臂 z，向下 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="89" />
        <source>Panorama frame relative to the body frame: R_body_from_pano = Rz(yaw) Ry(pitch) Rx(roll), degrees.</source>
        <translation>全景坐标系相对于载体坐标系：R_body_from_pano = Rz(yaw) Ry(pitch) Rx(roll)，单位为度。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="91" />
        <source>Boresight roll (°)</source>
        <translation>安置角：横滚 (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="92" />
        <source>Boresight pitch (°)</source>
        <translation>安置角：俯仰 (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="93" />
        <source>Boresight yaw (°)</source>
        <translation>安置角：偏航 (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="94" />
        <source>Skip images outside the trajectory's time span</source>
        <translation>跳过轨迹时间范围之外的图像</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="94" />
        <source>When checked, images whose time lies outside the trajectory are skipped and counted in the log; otherwise they are an error.</source>
        <translation>勾选时，时间位于轨迹范围之外的图像将被跳过并在日志中计数；否则视为错误。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="98" />
        <source>Warn about trajectory gaps longer than (s)</source>
        <translation>轨迹间隙超过此值时发出警告 (s)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="98" />
        <source>A warning names images that fall between two trajectory samples further apart than this, in seconds.</source>
        <translation>若图像落在间隔大于此值（秒）的两个轨迹采样点之间，将发出警告并列出这些图像。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="102" />
        <source>Fail on a missing or unreadable panorama</source>
        <translation>全景图缺失或无法读取时报错</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="102" />
        <source>When checked, a missing or unreadable panorama is an error; otherwise it is skipped with a warning and counted.</source>
        <translation>勾选时，缺失或无法读取的全景图视为错误；否则将其跳过，给出警告并计数。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="106" />
        <source>Panorama stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="106" />
        <source>PointZ layer, one point per panorama at its centre, with the fields station_id, image, path, time, x, y, z, qw, qx, qy, qz, heading, width, height.</source>
        <translation>PointZ 图层，每张全景图在其中心一个点，包含字段 station_id、image、path、time、x、y、z、qw、qx、qy、qz、heading、width、height。</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="145" />
        <source>{} panorama stations written.</source>
        <translation>已写入 {} 个全景站点。</translation>
    </message>
</context>
<context>
    <name>ProjectDetections</name>
    <message>
        <location filename="../algorithms/projectdetections.py" line="20" />
        <source>Project detections into the point cloud</source>
        <translation>将检测投影到点云</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="23" />
        <source>Finds each detected sign's surface in the LiDAR cloud: one candidate per detection.</source>
        <translation>在激光雷达点云中找到每个检测到的标志的表面：每个检测一个候选。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="70" />
        <source>Detections</source>
        <translation>检测结果</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="43" />
        <source>The output of Detect signs: one ray per detection with its box and station pose.</source>
        <translation>“在全景图中检测标志”的输出：每个检测一条射线，附带其检测框和站点位姿。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="46" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>已地面分类的点云（LAS/LAZ）</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="46" />
        <source>The cloud with ground as class 2 (the output of Ground filter), in the detections' CRS.</source>
        <translation>地面为类别 2 的点云（“地面滤波与点云裁剪”的输出），与检测结果位于同一坐标参考系。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="49" />
        <source>Maximum range (m)</source>
        <translation>最大距离 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="49" />
        <source>Search each frustum up to this distance from the panorama centre, in metres.</source>
        <translation>在距全景图中心此距离（米）以内搜索每个视锥。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="56" />
        <source>Sign candidates</source>
        <translation>标志候选</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="56" />
        <source>PointZ layer, one candidate per detection (no geometry where no surface was found).</source>
        <translation>PointZ 图层，每个检测一个候选（未找到表面时无几何）。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="68" />
        <source>The detections</source>
        <translation>检测结果</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="90" />
        <source>{} detections: {} with a surface in the cloud, {} without</source>
        <translation>{} 个检测：{} 个在点云中找到表面，{} 个未找到</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="52" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>点云坐标参考系（文件中没有时）</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="52" />
        <source>The cloud's CRS when the file records none (it must be the detections' CRS); it overrides a CRS in the file. The CRS is never guessed.</source>
        <translation>文件中没有记录坐标参考系时点云的坐标参考系（必须与检测的坐标参考系相同）；它会覆盖文件中的坐标参考系。坐标参考系从不猜测。</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="26" />
        <source>For each detection, the viewing frustum of its box (the rays through the box edges, widened by a small margin for calibration error) is searched from the panorama centre out to the maximum range. The non-ground points inside it are clustered and the first dense, near-vertical planar surface along the box-centre ray is taken (the sign, not the wall behind it; poles and convex mirrors are passed over). The cloud is read once (only the tiles under some frustum); the points under the frusta are kept on disk and worked through block by block along the drive, so the memory follows a block, not the drive. Within a block, each detection tests only the small tiles its frustum crosses.&lt;br&gt;&lt;br&gt;Output: one point per detection at the candidate surface, with the detection's fields, the range, the point count, the plane normal (normal_e, normal_n, normal_u), a quality score in 0-1 and a status: &lt;i&gt;ok&lt;/i&gt;, &lt;i&gt;no_points&lt;/i&gt; (nothing in the frustum, e.g. out of the scanner's reach) or &lt;i&gt;no_surface&lt;/i&gt;; those two keep no geometry. The cloud must be ground-classified (run Ground filter first).</source>
        <translation>对每个检测，从全景图中心出发直到最大距离，搜索其检测框的视锥（穿过检测框边缘的射线，并为标定误差略微放宽）。对视锥内的非地面点进行聚类，取沿检测框中心射线的第一个密集、近似竖直的平面表面（即标志本身，而非其后的墙体；杆和凸面镜会被跳过）。点云只读取一次（仅读取位于某个视锥之下的瓦片）；视锥下的点暂存于磁盘，并沿行驶路线逐块处理，因此内存取决于一个块的大小，而非整条路线。在一个块内，每个检测只测试其视锥穿过的小分块。&lt;br&gt;&lt;br&gt;输出：每个检测在候选表面处一个点，包含检测的字段、距离、点数、平面法向量（normal_e、normal_n、normal_u）、0-1 的质量分数以及状态：&lt;i&gt;ok&lt;/i&gt;、&lt;i&gt;no_points&lt;/i&gt;（视锥内没有点，例如超出扫描仪的测程）或 &lt;i&gt;no_surface&lt;/i&gt;；后两者没有几何。点云必须已完成地面分类（请先运行“地面滤波与点云裁剪”）。</translation>
    </message>
</context>
<context>
    <name>ReadsCodes</name>
    <message>
        <location filename="../algorithms/codeparams.py" line="21" />
        <source>Read the sign codes</source>
        <translation>读取标志代码</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="21" />
        <source>Reads what each sign says (its code, such as DE:206 for stop) with the sign-code classifier: {}. Unchecked, the code fields stay empty. When the bundled classifier is missing, the log says so and no code is read.</source>
        <translation>使用标志代码分类器读取每个标志的内容（其代码，例如 DE:206 表示停车让行）：{}。不勾选时代码字段保持为空。内置分类器缺失时，日志会加以说明，不读取任何代码。</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>Sign-code classifier (empty: the bundled one)</source>
        <translation>标志代码分类器（留空：使用内置分类器）</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>ONNX 模型 (*.onnx);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>Sign codes table (empty: the bundled one)</source>
        <translation>标志代码表（留空：使用内置代码表）</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>The codes the classifier may answer, with their names and classes: UTF-8 text, semicolon-separated, the header code;name;class (format in models/README.md). Empty uses the bundled table of German codes (models/sign-codes-de.csv).</source>
        <translation>分类器可给出的代码及其名称和类别：UTF-8 文本，以分号分隔，表头为 code;name;class（格式见 models/README.md）。留空则使用内置的德国代码表（models/sign-codes-de.csv）。</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>CSV files (*.csv *.txt);;All files (*.*)</source>
        <translation>CSV 文件 (*.csv *.txt);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="47" />
        <source>Sign codes are not read (Read the sign codes is off).</source>
        <translation>不读取标志代码（“读取标志代码”未勾选）。</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="53" />
        <source>The bundled sign-code classifier {} is missing: no sign code is read.</source>
        <translation>内置标志代码分类器 {} 缺失：不读取任何标志代码。</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="57" />
        <source>Sign-code classifier not found: {}</source>
        <translation>未找到标志代码分类器：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="60" />
        <source>Sign codes: {}</source>
        <translation>标志代码：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>An ONNX classifier of sign crops: float input [N, 3, S, S] (RGB, 0..1), output [N, C], the codes it answers in its metadata 'names' (each in the codes table, 'other', or 'unlisted:' and a class for a sign whose code the table lacks). The format is in models/README.md (section &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;). Empty uses the classifier bundled with the plugin (models/signcodes.onnx).</source>
        <translation>标志裁剪图像的 ONNX 分类器：float 输入 [N, 3, S, S]（RGB，0..1），输出 [N, C]，其可给出的代码写在元数据 'names' 中（每个代码都须在代码表中，或为 'other'，或为 'unlisted:' 加类别，表示代码表中没有其代码的标志）。格式见 models/README.md（&lt;i&gt;Sign-code classifier: the format&lt;/i&gt; 一节）。留空则使用插件内置的分类器（models/signcodes.onnx）。</translation>
    </message>
</context>
<context>
    <name>RefineSigns</name>
    <message>
        <location filename="../algorithms/refinesigns.py" line="47" />
        <source>Refine and merge signs</source>
        <translation>精化与合并标志</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="50" />
        <source>Merges the views of each sign and refines it in the cloud: the sign layer.</source>
        <translation>合并每个标志的多个视图，并在点云中对其精化：生成标志图层。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="160" />
        <source>Sign candidates</source>
        <translation>标志候选</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="89" />
        <source>The output of Project detections.</source>
        <translation>“将检测投影到点云”的输出。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="92" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>已地面分类的点云（LAS/LAZ）</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="92" />
        <source>The same cloud as for Project detections (ground as class 2).</source>
        <translation>与“将检测投影到点云”相同的点云（地面为类别 2）。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="95" />
        <source>Merge radius (m)</source>
        <translation>合并半径 (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="95" />
        <source>Candidates of the same class closer than this (metres) with agreeing plane normals are taken as one sign.</source>
        <translation>类别相同、距离小于此值（米）且平面法向量一致的候选被视为同一个标志。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="121" />
        <source>Panorama folder (for review chips)</source>
        <translation>全景图文件夹（用于审核切片）</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="121" />
        <source>The folder of the panoramas (as for Import trajectory). When given, an image chip of each sign is cut from its best panorama for review.</source>
        <translation>全景图所在的文件夹（与“导入轨迹和全景图”相同）。提供时，将从每个标志的最佳全景图中截取一张图像切片用于审核。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="129" />
        <source>Signs</source>
        <translation>标志</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="129" />
        <source>PointZ sign layer at the panel centres (fields in docs/formats.md), and chip: the relative path of the sign's review picture.</source>
        <translation>位于标志牌中心的 PointZ 标志图层（字段见 docs/formats.md），以及 chip：标志审核图片的相对路径。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="133" />
        <source>Panel outlines</source>
        <translation>标志牌轮廓</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="133" />
        <source>PolygonZ layer of each panel's rectangle in its plane (signs placed from the cloud).</source>
        <translation>每个标志牌在其所在平面内的矩形的 PolygonZ 图层（由点云定位的标志）。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>Sign points</source>
        <translation>标志点</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>LAZ (*.laz);;LAS (*.las)</source>
        <translation>LAZ (*.laz);;LAS (*.las)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>A LAS/LAZ file of the points of every sign panel, all dimensions kept.</source>
        <translation>包含每个标志牌所有点的 LAS/LAZ 文件，保留全部维度。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>Review report</source>
        <translation>审核报告</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>HTML files (*.html)</source>
        <translation>HTML 文件 (*.html)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>An HTML page with every sign's chip and attributes, to confirm signs without opening panoramas (needs the panorama folder).</source>
        <translation>一个 HTML 页面，列出每个标志的切片和属性，无需打开全景图即可确认标志（需要全景图文件夹）。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="158" />
        <source>The candidates</source>
        <translation>候选</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="193" />
        <source>The review report needs the panorama folder: not written.</source>
        <translation>审核报告需要全景图文件夹：未写入。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="199" />
        <source>{} sign points written to {}</source>
        <translation>已将 {} 个标志点写入 {}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="224" />
        <source>{} signs from {} candidates ({})</source>
        <translation>{} 个标志，来自 {} 个候选（{}）</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="234" />
        <source>Review chips need a sign layer written to a file: skipped.</source>
        <translation>审核切片需要写入文件的标志图层：已跳过。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="247" />
        <source>Road signs for review</source>
        <translation>待审核的道路标志</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="249" />
        <source>{} review chips in {}</source>
        <translation>{} 张审核切片，位于 {}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="125" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>点云坐标参考系（文件中没有时）</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="125" />
        <source>The cloud's CRS when the file records none (it must be the candidates' CRS); it overrides a CRS in the file. The CRS is never guessed.</source>
        <translation>文件中没有记录坐标参考系时点云的坐标参考系（必须与候选的坐标参考系相同）；它会覆盖文件中的坐标参考系。坐标参考系从不猜测。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="165" />
        <source>Panorama folder not found: {}</source>
        <translation>未找到全景图文件夹：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="99" />
        <source>Minimum code confidence</source>
        <translation>最低代码置信度</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>Sign codes table (empty: the bundled one)</source>
        <translation>标志代码表（留空：使用内置代码表）</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>The codes table the classifier of Detect signs was run with: it gives each code its name (code_name) and its class (for the class check). Format in models/README.md; empty uses the bundled table of German codes (models/sign-codes-de.csv).</source>
        <translation>运行“在全景图中检测标志”的分类器时所用的代码表：为每个代码提供名称（code_name）和类别（用于类别检查）。格式见 models/README.md；留空则使用内置的德国代码表（models/sign-codes-de.csv）。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>CSV files (*.csv *.txt);;All files (*.*)</source>
        <translation>CSV 文件 (*.csv *.txt);;所有文件 (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="99" />
        <source>A sign's voted code is kept when its support (its share of the views' weighted vote x the mean probability the classifier gave it, 0-1: the code_score field) is at least this; else the code field stays empty. 0 keeps every code but 'other' and 'unlisted:...' (a sign whose code the table lacks).</source>
        <translation>当标志投票得出的代码的支持度（其在各视图加权投票中的占比 x 分类器给出的平均概率，0-1：即 code_score 字段）不低于此值时保留该代码；否则 code 字段保持为空。0 保留除 'other' 和 'unlisted:...'（代码表中没有其代码的标志）以外的所有代码。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="53" />
        <source>Groups the candidates of different panoramas that are the same physical sign (same class, within the merge radius, plane normals agreeing; panels stacked on one pole stay apart), then refines each sign in the cloud: Euclidean clustering, an intensity filter whose threshold adapts to the cloud (Otsu), a near-vertical RANSAC plane and PCA dimensionality to keep the panel and drop the pole.&lt;br&gt;&lt;br&gt;Each sign gets its panel centre, width and panel height, the azimuth its face looks towards (clockwise from grid north), its height above the ground directly below (class-2 points near the sign; the log names any fallback), the bottom height, the number of views and points, the images it was seen in and the best of them (closest, most frontal), the mean intensity and planarity. A sign seen in two or more panoramas but with no cloud points is placed by triangulating its rays (position_source = image).&lt;br&gt;&lt;br&gt;&lt;b&gt;Not signs&lt;/b&gt;, dropped and named in the log: a panel larger than its class allows (a billboard), a curved one (a convex mirror), a picture on a larger flat surface, and a sign seen in one panorama only when its score is under 0.4 or when two or more panoramas nearer to its face, which detected other signs, did not see it (a look-alike boxed once from afar).&lt;br&gt;&lt;br&gt;Optional outputs: panel outlines (PolygonZ) and the sign points (LAS/LAZ).&lt;br&gt;&lt;br&gt;&lt;b&gt;Review&lt;/b&gt;: with the panorama folder, each sign gets an image chip from its best panorama (its box with a margin, undistorted), written into a folder beside the sign layer and linked by the &lt;i&gt;chip&lt;/i&gt; field (a relative path); the review report shows every sign's chip and attributes. The sign layer is styled with a symbol per class and its height as label (a .qml file beside it).&lt;br&gt;&lt;br&gt;&lt;b&gt;Sign codes&lt;/b&gt;: the codes Detect signs read in the views of a sign are put to a vote, each view weighing its detection score x the pixels its crop holds across the sign's narrower side (a sign passed close by, seen at a steep angle, weighs less) x the code's probability. The sign gets &lt;i&gt;code&lt;/i&gt; (empty when the vote says &lt;i&gt;other&lt;/i&gt; or the support is below the minimum code confidence), &lt;i&gt;code_name&lt;/i&gt; (from the codes table), &lt;i&gt;code_score&lt;/i&gt; (the support: the code's share of the vote x its mean probability) and &lt;i&gt;code_views&lt;/i&gt;. When the code's class (codes table) is not the class vote's, the better supported one wins: the code's support against the class's (its share of the score-weighted class vote x its views' mean detection score); &lt;i&gt;code_check&lt;/i&gt; says &lt;i&gt;class_from_code&lt;/i&gt; (the class was taken from the code) or &lt;i&gt;code_dropped&lt;/i&gt; (the code was emptied). The label shows the code's name, or the figure of a speed limit.</source>
        <translation>将来自不同全景图、属于同一实体标志的候选分为一组（类别相同、位于合并半径内、平面法向量一致；同一根杆上叠放的标志牌保持分开），然后在点云中精化每个标志：欧氏聚类、阈值随点云自适应的强度滤波（Otsu）、近似竖直的 RANSAC 平面以及 PCA 维度特征，以保留标志牌并去除杆体。&lt;br&gt;&lt;br&gt;每个标志将得到：标志牌中心、宽度和标志牌高度，牌面朝向的方位角（从坐标北起顺时针），其相对于正下方地面的高度（标志附近的类别 2 点；若使用了替代方法，日志会说明），底部高度，视图数和点数，看到它的图像及其中最佳的一张（最近、最正对），平均强度和平面度。在两张或更多全景图中看到但没有点云点的标志，通过其射线的三角测量定位（position_source = image）。&lt;br&gt;&lt;br&gt;&lt;b&gt;非标志&lt;/b&gt;（丢弃并在日志中列出）：超出其类别允许尺寸的标志牌（广告牌）、弯曲的标志牌（凸面镜）、更大平面上的图案，以及只在一张全景图中出现的标志——其得分低于 0.4，或有两张及以上距其牌面更近、且检测到其他标志的全景图没有看到它（远处被框出一次的类似标志的物体）。&lt;br&gt;&lt;br&gt;可选输出：标志牌轮廓（PolygonZ）和标志点（LAS/LAZ）。&lt;br&gt;&lt;br&gt;&lt;b&gt;审核&lt;/b&gt;：提供全景图文件夹时，每个标志会从其最佳全景图中截取一张图像切片（其检测框加边距，已去畸变），写入标志图层旁的文件夹，并通过 &lt;i&gt;chip&lt;/i&gt; 字段（相对路径）关联；审核报告显示每个标志的切片和属性。标志图层按类别使用不同符号，并以高度作为标注（其旁的 .qml 文件）。&lt;br&gt;&lt;br&gt;&lt;b&gt;标志代码&lt;/b&gt;：“在全景图中检测标志”在一个标志的各视图中读出的代码将进行投票，每个视图的权重为其检测得分 x 其裁剪在标志较窄一边方向上的像素数（近距离驶过、以大角度斜视的标志权重更小）x 该代码的概率。标志将得到 &lt;i&gt;code&lt;/i&gt;（投票结果为 &lt;i&gt;other&lt;/i&gt; 或支持度低于最低代码置信度时为空）、&lt;i&gt;code_name&lt;/i&gt;（取自代码表）、&lt;i&gt;code_score&lt;/i&gt;（支持度：该代码在投票中的占比 x 其平均概率）和 &lt;i&gt;code_views&lt;/i&gt;。当代码的类别（代码表）与类别投票的结果不一致时，支持度更高的一方胜出：比较代码的支持度与类别的支持度（该类别在按得分加权的类别投票中的占比 x 其视图的平均检测得分）；&lt;i&gt;code_check&lt;/i&gt; 注明 &lt;i&gt;class_from_code&lt;/i&gt;（类别取自代码）或 &lt;i&gt;code_dropped&lt;/i&gt;（代码被清空）。标注显示代码的名称，限速标志则显示限速数值。</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="106" />
        <source>Drop a sign seen once when this many nearer panoramas missed it</source>
        <translation>当这么多张更近的全景图未看到时，丢弃只出现一次的标志</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="106" />
        <source>A sign seen in one panorama only is dropped when at least this many other panoramas, which detected other signs, stand nearer to its face and did not see it (within 60 degrees of its normal, at least 4 m away, with the sign at most 20 degrees above their horizon): a look-alike boxed once from afar, such as a convex mirror. 0 keeps every such sign, for example a real sign that a lorry hid from the nearer panoramas.</source>
        <translation>只在一张全景图中出现的标志，若至少有这么多张检测到其他标志的全景图距其牌面更近却没有看到它（在其法向 60 度以内、相距至少 4 m，且标志在其地平线以上不超过 20 度），则被丢弃：这是远处被框出一次的类似标志的物体，例如凸面镜。0 保留所有此类标志，例如被卡车挡住、更近的全景图未能看到的真实标志。</translation>
    </message>
</context>
<context>
    <name>ReviewPanel</name>
    <message>
        <location filename="../gui/reviewpanel.py" line="723" />
        <source>Sign review</source>
        <translation>标志审核</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="145" />
        <source>The sign layer to review (the output of Refine and merge signs, or any point layer with the sign fields).</source>
        <translation>要审核的标志图层（“精化并合并标志”的输出，或任何具有标志字段的点图层）。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="147" />
        <source>Signs</source>
        <translation>标志</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="151" />
        <source>The panorama stations of the drive: with them the panel cuts the sign from every panorama that saw it.</source>
        <translation>行驶采集的全景站点：借助它们，面板从每张看到该标志的全景图中裁出标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="153" />
        <source>Stations</source>
        <translation>全景站点</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="156" />
        <source>The panorama folder; empty: the path field of the stations layer.</source>
        <translation>全景图文件夹；留空：使用全景站点图层的 path 字段。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="157" />
        <source>Panoramas</source>
        <translation>全景图</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="714" />
        <source>Sign</source>
        <translation>标志</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Class</source>
        <translation>类别</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Code</source>
        <translation>代码</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Confidence</source>
        <translation>置信度</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Condition</source>
        <translation>状况</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Sources</source>
        <translation>来源</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Panel</source>
        <translation>标志牌</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Review</source>
        <translation>审核</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="194" />
        <source>The sign's class: pick or type another one, then Change.</source>
        <translation>标志的类别：选择或输入另一个类别，然后点击“更改”。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="196" />
        <source>code</source>
        <translation>代码</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="197" />
        <source>The sign's code (e.g. 206): type it, then Enter or Change.</source>
        <translation>标志的代码（例如 206）：输入后按回车或点击“更改”。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="204" />
        <source>Accept (A)</source>
        <translation>接受 (A)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="204" />
        <source>A real sign, class and code right: next sign.</source>
        <translation>真实的标志，类别和代码正确：下一个标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="206" />
        <source>Reject (R)</source>
        <translation>拒绝 (R)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="206" />
        <source>Not a sign, or a duplicate: next sign.</source>
        <translation>不是标志或是重复项：下一个标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="208" />
        <source>Change (C)</source>
        <translation>更改 (C)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="208" />
        <source>A real sign with the class and code above: next sign.</source>
        <translation>真实的标志，采用上面的类别和代码：下一个标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="210" />
        <source>Look again (L)</source>
        <translation>再看一次 (L)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="210" />
        <source>Needs another look: next sign.</source>
        <translation>需要再看一次：下一个标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="212" />
        <source>Previous (P)</source>
        <translation>上一个 (P)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="212" />
        <source>The sign before this one.</source>
        <translation>当前标志之前的标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="214" />
        <source>Next unreviewed (N)</source>
        <translation>下一个未审核 (N)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="214" />
        <source>The next sign without a verdict.</source>
        <translation>下一个尚无结论的标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="216" />
        <source>Panorama view (V)</source>
        <translation>全景视图 (V)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="216" />
        <source>The panorama around the sign, from its best panorama.</source>
        <translation>从最佳全景图看到的标志周围的全景。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="218" />
        <source>Undo (U)</source>
        <translation>撤销 (U)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="218" />
        <source>Undo the last verdict given here.</source>
        <translation>撤销在此给出的最后一个结论。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="220" />
        <source>Save edits</source>
        <translation>保存编辑</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="220" />
        <source>Write the verdicts to the layer's file.</source>
        <translation>将结论写入图层文件。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="303" />
        <source>Choose a sign layer to review.</source>
        <translation>请选择要审核的标志图层。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="269" />
        <source>The layer {layer} lacks the field(s) {missing}. The review needs a sign layer with the fields {required} (the output of Refine and merge signs).</source>
        <translation>图层 {layer} 缺少字段 {missing}。审核需要具有字段 {required} 的标志图层（“精化并合并标志”的输出）。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="287" />
        <source>(point geometry)</source>
        <translation>（点几何）</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="381" />
        <source>The layer {} has no signs.</source>
        <translation>图层 {} 中没有标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="392" />
        <source>&lt;b&gt;Sign {sign}&lt;/b&gt; ({position} of {total}) &amp;#8212; {reviewed} of {total} reviewed</source>
        <translation>&lt;b&gt;标志 {sign}&lt;/b&gt;（第 {position} 个，共 {total} 个）&amp;#8212; 已审核 {reviewed} / {total}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="395" />
        <source>Sign {}</source>
        <translation>标志 {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="400" />
        <source>(none)</source>
        <translation>（无）</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="411" />
        <source>(no condition field)</source>
        <translation>（无状况字段）</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="416" />
        <source>{source}; seen in {n} panorama(s): {images}</source>
        <translation>{source}；在 {n} 张全景图中看到：{images}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="419" />
        <source>{width} × {height} m, {above} m above the ground, facing {azimuth}°</source>
        <translation>{width} × {height} 米，离地 {above} 米，朝向 {azimuth}°</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="435" />
        <source>accepted</source>
        <translation>已接受</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="435" />
        <source>corrected</source>
        <translation>已更正</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="436" />
        <source>rejected</source>
        <translation>已拒绝</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="436" />
        <source>needs another look</source>
        <translation>需要再看一次</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="437" />
        <source>not reviewed</source>
        <translation>未审核</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="516" />
        <source>review chip</source>
        <translation>审核切片</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="527" />
        <source>no picture</source>
        <translation>无图像</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="527" />
        <source>Choose the stations layer (and the panorama folder) to see the sign in every panorama that saw it.</source>
        <translation>选择全景站点图层（以及全景图文件夹），即可在每张看到该标志的全景图中查看它。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="553" />
        <source>best · </source>
        <translation>最佳 · </translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="554" />
        <source>{} at {:.1f} m; click for the panorama view</source>
        <translation>{}，距离 {:.1f} 米；点击查看全景视图</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="558" />
        <source>{} panorama(s) not found</source>
        <translation>{} 张全景图未找到</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="558" />
        <source>Not found or unreadable: {}. Set the panorama folder.</source>
        <translation>未找到或无法读取：{}。请设置全景图文件夹。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="571" />
        <source>The panorama view needs the stations layer of the drive.</source>
        <translation>全景视图需要行驶采集的全景站点图层。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="580" />
        <source>No panorama of the stations layer saw this sign.</source>
        <translation>全景站点图层中没有全景图看到此标志。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="605" />
        <source>Panorama view: sign {}</source>
        <translation>全景视图：标志 {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="607" />
        <source>{} · {:.1f} m from the sign</source>
        <translation>{} · 距标志 {:.1f} 米</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="634" />
        <source>The layer {} cannot be edited: its verdicts cannot be written.</source>
        <translation>图层 {} 无法编辑：无法写入其结论。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="637" />
        <source>Sign review: {} sign {}</source>
        <translation>标志审核：{} 标志 {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="642" />
        <source>Cannot add the field {} to the layer {}.</source>
        <translation>无法添加字段 {}（图层 {}）。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="663" />
        <source>Cannot save the edits of {}: {}</source>
        <translation>无法保存 {} 的编辑：{}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="675" />
        <source>Every sign has a verdict.</source>
        <translation>所有标志都已有结论。</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="516" />
        <source>best · {} (review chip)</source>
        <translation>最佳 · {}（审核切片）</translation>
    </message>
</context>
<context>
    <name>RoadSigns</name>
    <message>
        <location filename="../core/cloudsigns.py" line="288" />
        <source>The stations do not overlap the cloud {path}: the track passes {gap:.1f} m from the cloud's extent ({xmin:.1f}, {ymin:.1f}) - ({xmax:.1f}, {ymax:.1f}), more than the corridor of {corridor} m; are the cloud and the stations in the same CRS and of the same drive?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景站点与点云 {path} 不重叠：轨迹线距点云范围 ({xmin:.1f}, {ymin:.1f}) - ({xmax:.1f}, {ymax:.1f}) {gap:.1f} m，超出 {corridor} m 的走廊；点云和全景站点是否在同一坐标参考系中、是否来自同一次行驶采集？</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="301" />
        <source>{path} has no intensity dimension (point format {fmt}): signs cannot be found in it without images</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有强度维度（点格式 {fmt}）：没有图像时无法在其中找到标志</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="304" />
        <source>{path} has no classification dimension: run roadsigns:groundfilter on it first</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有分类维度：请先对其运行 roadsigns:groundfilter</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="763" />
        <source>Found {signs} sign panels ({bright} retroreflective) and {poles} poles in {n} points ({cand} kept near the road, {windows} windows of {w} m); condition reference {ref:.3f} ({src})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>在 {n} 个点中找到 {signs} 个标志牌（其中 {bright} 个具有逆反射性）和 {poles} 根杆（道路附近保留 {cand} 个点，{windows} 个 {w} m 的窗口）；状态参考值 {ref:.3f}（{src}）</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="680" />
        <source>No point of {path} lies within {corridor} m of the stations' track ({n} points read)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 中没有点位于全景站点轨迹线 {corridor} m 范围内（已读取 {n} 个点）</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="683" />
        <source>{path} has no ground points (class 2) along the track: run roadsigns:groundfilter on it first (or classify the ground with another tool)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 沿轨迹线没有地面点（类别 2）：请先对其运行 roadsigns:groundfilter（或用其他工具对地面进行分类）</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="687" />
        <source>{path} has no intensity: all {n} points near the track have intensity 0; signs cannot be found in it without images</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有强度：轨迹线附近的全部 {n} 个点强度均为 0；没有图像时无法在其中找到标志</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="698" />
        <source>Intensity: range exponent {alpha:.2f} ({source}), bright threshold {thr:.3f} of full scale at 10 m ({method}; background level {bg:.3f}, bright mode {mode:.3f}; {n} non-ground points near the road)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>强度：距离指数 {alpha:.2f}（{source}），亮度阈值为 10 m 处满量程的 {thr:.3f}（{method}；背景水平 {bg:.3f}，亮峰 {mode:.3f}；道路附近 {n} 个非地面点）</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="757" />
        <source>Searching the drive for signs and poles: window {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在沿行驶路线搜索标志和杆：第 {n} 个窗口，共 {count} 个</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="832" />
        <source>{n} gantry posts</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{n} 根门架立柱</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="690" />
        <source>The cloud's GPS times [{t0:.1f}, {t1:.1f}] do not meet the stations' times: ranges are taken from the nearest track position instead (is one of them in GPS week seconds and the other in adjusted standard GPS time?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>点云的 GPS 时间 [{t0:.1f}, {t1:.1f}] 与全景站点的时间不重合：改为从最近的轨迹线位置计算距离（是否一个使用 GPS 周秒、另一个使用调整后的标准 GPS 时间？）</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="709" />
        <source>{share:.0%} of the points near the road have intensity 0: the bright threshold {thr:.3f} of full scale may be meaningless</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>道路附近 {share:.0%} 的点强度为 0：满量程的亮度阈值 {thr:.3f} 可能没有意义</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="714" />
        <source>{share:.0%} of the points near the road have saturated intensity: the bright threshold {thr:.3f} of full scale and the condition of the signs may be meaningless</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>道路附近 {share:.0%} 的点强度饱和：满量程的亮度阈值 {thr:.3f} 以及标志的状态可能没有意义</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="575" />
        <location filename="../core/cloudsource.py" line="573" />
        <source>expected a virtual point cloud: a JSON FeatureCollection (STAC ItemCollection) whose features each have assets.data.href (the tile's file, relative to the .vpc) and properties, as QGIS's Build virtual point cloud writes it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>应为虚拟点云：一个 JSON FeatureCollection（STAC ItemCollection），其每个要素都有 assets.data.href（分块文件，相对于 .vpc 的路径）和 properties，即 QGIS 的“构建虚拟点云”写出的格式</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="161" />
        <source>no CRS</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="534" />
        <source>The folder {path} holds no LAS or LAZ file (*.las, *.laz); expected a point cloud file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>文件夹 {path} 中没有 LAS 或 LAZ 文件（*.las、*.laz）；应为点云文件、LAS/LAZ 分块文件夹或虚拟点云（.vpc）</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="577" />
        <source>Cannot read {path}: the JSON is not an object; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：该 JSON 不是对象；{expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="580" />
        <source>Cannot read {path}: it is not a 'FeatureCollection' with a 'features' list; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：不是带有 'features' 列表的 'FeatureCollection'；{expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="583" />
        <source>The virtual point cloud {path} lists no tile</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>虚拟点云 {path} 未列出任何分块</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="250" />
        <location filename="../core/pointcloud.py" line="606" />
        <source>{path} has no dimension {names} (point format {fmt})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有维度 {names}（点格式 {fmt}）</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="527" />
        <source>Cannot read the folder {path}: {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取文件夹 {path}：{detail}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="566" />
        <location filename="../core/pointcloud.py" line="72" />
        <source>Cannot read {path}: the file does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：文件不存在</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="568" />
        <location filename="../core/ground/pdal.py" line="306" />
        <location filename="../core/pointcloud.py" line="74" />
        <location filename="../core/pointcloud.py" line="117" />
        <source>Cannot read {path}: {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：{detail}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="572" />
        <source>Cannot read {path}: it is not valid JSON ({detail}); {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：不是有效的 JSON（{detail}）；{expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="590" />
        <source>Cannot read {path}: feature {feature} has no 'assets' object; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：要素 {feature} 没有 'assets' 对象；{expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="598" />
        <source>Cannot read {path}: feature {feature} has no asset with an 'href' (assets.data.href); {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：要素 {feature} 没有带 'href' 的 asset（assets.data.href）；{expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="602" />
        <source>The virtual point cloud {path} lists the remote tile {href}: only local files are read; download the tiles and build the virtual point cloud again</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>虚拟点云 {path} 列出了远程分块 {href}：只读取本地文件；请下载这些分块并重新构建虚拟点云</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="608" />
        <source>The virtual point cloud {path} lists the tile {tile} twice (features {first} and {second})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>虚拟点云 {path} 两次列出分块 {tile}（要素 {first} 和 {second}）</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="612" />
        <source>The virtual point cloud {path} lists the tile {tile} (feature {feature}), which does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>虚拟点云 {path} 列出的分块 {tile}（要素 {feature}）不存在</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="627" />
        <source>The tiles of {path} cannot be read as one cloud: {tile_a} has point format {fmt_a}, {tile_b} point format {fmt_b}; every tile needs the same point format (convert them to one, e.g. with PDAL's translate)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 的分块无法作为一个点云读取：{tile_a} 的点格式为 {fmt_a}，{tile_b} 的点格式为 {fmt_b}；所有分块必须使用相同的点格式（请将其转换为同一格式，例如使用 PDAL 的 translate）</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="633" />
        <source>The tiles of {path} are in different CRSs: {tile_a} in {crs_a}, {tile_b} in {crs_b}; every tile must be in the same CRS (reproject them to one first)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 的分块位于不同的坐标参考系中：{tile_a} 为 {crs_a}，{tile_b} 为 {crs_b}；所有分块必须位于同一坐标参考系中（请先将其重投影到同一坐标参考系）</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="662" />
        <source>The points cannot be written with the first tile's scale {scale} and offset {offset} in {axis}: their coordinates are too far from it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法以第一个分块在 {axis} 方向的缩放 {scale} 和偏移 {offset} 写入这些点：其坐标离偏移太远</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="335" />
        <source>Reading {name}: {done:.1f} of {total:.1f} million points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在读取 {name}：已读 {done:.1f} 百万点，共 {total:.1f} 百万点</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="19" />
        <source>CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="228" />
        <source>{what} file {path}, {location}: x {x}, y {y} lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the CRS of these positions?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，{location}：x {x}，y {y} 位于 {crs} 的适用范围（经度 {west} 至 {east}，纬度 {south} 至 {north}）之外：{crs} 是这些位置的坐标参考系吗？</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="251" />
        <source>{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the CRS of these coordinates?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}：x {xmin} 至 {xmax}，y {ymin} 至 {ymax} 位于 {crs} 的适用范围（经度 {west} 至 {east}，纬度 {south} 至 {north}）之外：{crs} 是这些坐标的坐标参考系吗？</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="22" />
        <source>No {role} given: expected an EPSG code, WKT or PROJ string</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未给出{role}：应为 EPSG 代码、WKT 或 PROJ 字符串</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="113" />
        <location filename="../core/crs.py" line="123" />
        <location filename="../core/trajectory.py" line="489" />
        <source>trajectory CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>轨迹坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="124" />
        <location filename="../core/trajectory.py" line="496" />
        <source>target CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>目标坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="126" />
        <source>The target CRS {crs} is not projected: expected a projected CRS in metres (e.g. a UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>目标坐标参考系 {crs} 不是投影坐标系：应为以米为单位的投影坐标参考系（例如 UTM 分带）</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="224" />
        <source>{what} file {path}, {location}: x {x}, y {y} lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}) and looks like a longitude/latitude: give a geographic CRS (e.g. EPSG:4326) for these positions</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，{location}：x {x}，y {y} 位于 {crs} 的适用范围（经度 {west} 至 {east}，纬度 {south} 至 {north}）之外，且看起来像经纬度：请为这些位置指定地理坐标参考系（例如 EPSG:4326）</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="248" />
        <source>{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}) and look like longitudes/latitudes: is {crs} the CRS of these coordinates?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}：x {xmin} 至 {xmax}，y {ymin} 至 {ymax} 位于 {crs} 的适用范围（经度 {west} 至 {east}，纬度 {south} 至 {north}）之外，且看起来像经纬度：{crs} 是这些坐标的坐标参考系吗？</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="261" />
        <source>{label} is in {crs}, a geographic CRS (degrees): this needs a projected CRS in metres, the CRS of the point cloud (e.g. a UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label} 的坐标参考系为 {crs}，这是地理坐标参考系（度）：此处需要以米为单位的投影坐标参考系，即点云的坐标参考系（例如 UTM 分带）</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="26" />
        <source>Unknown {role} '{crs}': {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法识别的{role} '{crs}'：{error}</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="70" />
        <source>Heights: pass through unchanged (the target CRS has no vertical datum)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>高程：保持不变（目标坐标参考系没有垂直基准）</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="96" />
        <source>Transforming positions from {source} to {target} gave invalid values (outside the CRS's area, or a missing vertical grid)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>将位置从 {source} 转换到 {target} 得到无效值（超出坐标参考系的适用范围，或缺少高程格网）</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="208" />
        <source>{what} file {path}, {location}: x {x}, y {y} is not a longitude/latitude, but {crs} is a geographic CRS: are these projected coordinates? Give the CRS the positions are in</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，{location}：x {x}，y {y} 不是经纬度，但 {crs} 是地理坐标参考系：这些是投影坐标吗？请指定这些位置所在的坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="73" />
        <source>Heights: the geoid grid for {crs} is not installed: heights stay as they are (ellipsoidal), only the horizontal position is transformed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>高程：未安装 {crs} 的大地水准面格网：高程保持原样（椭球高），只转换平面位置</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="77" />
        <source>Heights: transformed to {crs}: {operation}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>高程：已转换到 {crs}：{operation}</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="91" />
        <source>Cannot transform positions from {source} to {target}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法将位置从 {source} 转换到 {target}：{error}</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="104" />
        <source>The detections lack the field(s) {fields}; expected the output of Detect signs</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测结果缺少字段 {fields}；应为“在全景图中检测标志”的输出</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="147" />
        <source>Detection {det_id}: the box ({u0}, {v0}, {u1}, {v1}) is not u0 &lt; u1, v0 &lt; v1 inside a {w} x {h} panorama</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测 {det_id}：检测框 ({u0}, {v0}, {u1}, {v1}) 不满足在 {w} x {h} 全景图内 u0 &lt; u1、v0 &lt; v1</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="155" />
        <source>Detection {det_id}: the station pose is invalid (quaternion norm {norm:.4f}, position {xyz})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测 {det_id}：站点位姿无效（四元数范数 {norm:.4f}，位置 {xyz}）</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="110" />
        <location filename="../core/projection.py" line="417" />
        <source>Detection {det_id}: the field {field} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测 {det_id}：字段 {field} 为空</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="118" />
        <location filename="../core/projection.py" line="409" />
        <source>Detection {det_id}, field {field}: expected a number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测 {det_id}，字段 {field}：应为数字，实际为 '{value}'</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="137" />
        <source>The labels file {path} holds no class names (one name per line)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标签文件 {path} 中没有类别名称（应每行一个名称）</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="174" />
        <source>The model {path} has an output of shape {shape}, which is no layout this plugin decodes for {n_classes} class names; supported: {supported}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的输出形状为 {shape}，不属于本插件能为 {n_classes} 个类别名称解码的任何布局；支持的布局：{supported}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="187" />
        <source>Unknown output layout {layout}: use one of {layouts}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的输出布局 {layout}：请使用以下之一：{layouts}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="191" />
        <source>The model {path} has an output of shape {shape}, which does not fit the layout {layout} with {n_classes} class names</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的输出形状为 {shape}，与具有 {n_classes} 个类别名称的布局 {layout} 不符</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="298" />
        <source>Model not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到模型：{path}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="392" />
        <source>The model {path} names no classes: its metadata has no readable 'names' and there is no labels file ({labels}, one class name per line)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 未给出类别名称：其元数据中没有可读的 'names'，也没有标签文件（{labels}，每行一个类别名称）</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="135" />
        <source>Cannot read the labels file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取标签文件 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="309" />
        <source>{path} is not an ONNX model onnxruntime can load: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 不是 onnxruntime 可以加载的 ONNX 模型：{error}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="335" />
        <source>The model {path} is a {task} model; sign detection needs a detection model</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 是 {task} 模型；标志检测需要检测模型</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="343" />
        <source>The model {path} takes an input of shape {shape}; an image model takes float [batch, 3, height, width] or uint8 [batch, height, width, 3]</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的输入形状为 {shape}；图像模型的输入应为 float [batch, 3, height, width] 或 uint8 [batch, height, width, 3]</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="356" />
        <source>The model {path} has a fixed batch of {batch}; use a batch of 1 or a dynamic batch</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的批大小固定为 {batch}；请使用批大小 1 或动态批大小</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="423" />
        <source>The model {path} takes {w} x {h} px images only; the horizon seen as one band ({bw} x {bh} px) needs a model whose input height and width are free, as the bundled detector's are</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 只接受 {w} x {h} 像素的图像；将地平线作为一条条带（{bw} x {bh} 像素）需要输入高度和宽度不固定的模型，如随附的检测器</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="901" />
        <source>Detecting signs: panorama {n} of {count} ({image})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在检测标志：第 {n} 张全景图，共 {count} 张（{image}）</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="373" />
        <source>The model {path} failed on a blank {w} x {h} image: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 在一张 {w} x {h} 的空白图像上运行失败：{error}</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="59" />
        <source>The track needs at least 2 finite positions, got {n}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>轨迹线至少需要 2 个有限位置，实际为 {n} 个</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="106" />
        <source>The track does not move: all its positions are at one place</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>轨迹线没有移动：其所有位置都在同一处</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="54" />
        <source>The track has {n} positions but {m} times</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>轨迹线有 {n} 个位置，但有 {m} 个时间</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="143" />
        <source>reference signs</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>参考标志</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="176" />
        <source>The signs ({signs}: x {sx0} to {sx1}, y {sy0} to {sy1}) and the reference {reference} (x {rx0} to {rx1}, y {ry0} to {ry1}) do not overlap: are both in the same CRS and the same area?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志（{signs}：x {sx0} 至 {sx1}，y {sy0} 至 {sy1}）与参考 {reference}（x {rx0} 至 {rx1}，y {ry0} 至 {ry1}）不重叠：两者是否位于同一坐标参考系和同一区域？</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="201" />
        <source>match radius {radius} m: expected a positive number of metres</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>匹配半径 {radius} m：应为以米为单位的正数</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="209" />
        <source>{label}: sign '{sign_id}' has no valid x, y, z position</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}：标志 '{sign_id}' 没有有效的 x、y、z 位置</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="412" />
        <source>Code accuracy not computed: neither the signs nor the reference have a 'code' field or column.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未计算代码准确率：标志和参考数据都没有 'code' 字段或列。</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="415" />
        <source>Code accuracy not computed: the reference has no 'code' column or field.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未计算代码准确率：参考数据没有 'code' 列或字段。</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="417" />
        <source>Code accuracy not computed: the signs have no 'code' field.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未计算代码准确率：标志没有 'code' 字段。</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="153" />
        <source>reference signs file {path}, line {line}: sign_id '{sign_id}' already used on line {first}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>参考标志文件 {path}，第 {line} 行：sign_id '{sign_id}' 已在第 {first} 行使用</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="149" />
        <source>reference signs file {path}, line {line}, field '{field}': empty value</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>参考标志文件 {path}，第 {line} 行，字段 '{field}'：值为空</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="162" />
        <source>Image sign</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>图像标志</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="163" />
        <source>Cloud panel</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>点云标志牌</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="106" />
        <source>{what} {index}: position is not finite</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what} {index}：位置不是有限值</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="103" />
        <source>{what} {index}: no position (x, y, z)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what} {index}：没有位置（x, y, z）</translation>
    </message>
    <message>
        <location filename="../core/ground/blocks.py" line="304" />
        <source>Classifying the ground block by block: block {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在逐个区块分类地面：第 {n} 个区块，共 {count} 个</translation>
    </message>
    <message>
        <location filename="../core/ground/csf.py" line="132" />
        <source>The built-in CSF needs the Python package cloth-simulation-filter (module CSF): {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>内置 CSF 需要 Python 包 cloth-simulation-filter（模块 CSF）：{detail}</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="337" />
        <location filename="../core/pointcloud.py" line="274" />
        <source>Cannot write {path}: the output must end in .las or .laz</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法写入 {path}：输出文件必须以 .las 或 .laz 结尾</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="349" />
        <location filename="../core/ground/tiled.py" line="106" />
        <source>point cloud CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>点云坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="422" />
        <source>PDAL not found: using the built-in engine</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到 PDAL：使用内置引擎</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="472" />
        <source>No crop polygons: the crop buffer is ignored</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有裁剪多边形：忽略裁剪缓冲区</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="152" />
        <source>Classifying and writing the points: part {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在分类并写出点：第 {n} 部分，共 {count} 部分</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="259" />
        <source>No point of {path} has the returns '{returns}': nothing was classified</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 中没有回波为 '{returns}' 的点：未分类任何点</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="343" />
        <source>The output {path} must not be the input file</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>输出 {path} 不能是输入文件</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="351" />
        <location filename="../core/ground/tiled.py" line="108" />
        <source>{path} has no coordinate reference system: give the cloud's CRS (it is never guessed)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有坐标参考系：请给出点云的坐标参考系（从不猜测）</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="409" />
        <source>Auto: the built-in engine, measured faster than PDAL for {method} (and it streams the cloud in bounded memory)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>自动：内置引擎，对 {method} 实测比 PDAL 更快（且以有限内存流式处理点云）</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="414" />
        <source>Auto: PDAL, as the built-in {method} needs the Python package cloth-simulation-filter, which is not installed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>自动：PDAL，因为内置 {method} 需要 Python 包 cloth-simulation-filter，而该包未安装</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="420" />
        <source>PDAL was asked for, but neither the pdal Python module nor a pdal executable was found (PATH, QGIS's bin folder)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>要求使用 PDAL，但既没有找到 pdal Python 模块，也没有找到 pdal 可执行文件（PATH、QGIS 的 bin 文件夹）</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="424" />
        <source>Auto: PDAL, measured faster than the built-in engine for {method}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>自动：PDAL，对 {method} 实测比内置引擎更快</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="459" />
        <source>No point of {path} is left after the crop: {output} has no points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>裁剪后 {path} 没有剩余的点：{output} 中没有点</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="245" />
        <source>Not enough free disk space in {folder} to keep the points between the two passes: the cloud is read twice</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{folder} 中的可用磁盘空间不足，无法在两遍处理之间保存点：点云将被读取两次</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="255" />
        <location filename="../core/ground/tiled.py" line="239" />
        <source>Cannot read {path}: the file is corrupt ({detail})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：文件已损坏（{detail}）</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="374" />
        <location filename="../core/ground/tiled.py" line="139" />
        <source>PDAL failed, the built-in engine was used instead: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>PDAL 运行失败，已改用内置引擎：{error}</translation>
    </message>
    <message>
        <location filename="../core/ground/gridsteps.py" line="36" />
        <source>Unknown return type {kinds} in '{returns}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>'{returns}' 中有未知的回波类型 {kinds}</translation>
    </message>
    <message>
        <location filename="../core/ground/lattice.py" line="209" />
        <source>Fitting the ground surface: tile {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在拟合地面：第 {n} 块，共 {count} 块</translation>
    </message>
    <message>
        <location filename="../core/ground/lattice.py" line="60" />
        <source>The area to classify ({w:.0f} m x {h:.0f} m) needs {cells} grid cells of {step} m, more than {limit}: crop the cloud or use a larger cell/resolution</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>待分类区域（{w:.0f} m x {h:.0f} m）需要 {cells} 个 {step} m 的格网单元，超过上限 {limit}：请裁剪点云或使用更大的格网/分辨率</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="36" />
        <source>Unknown {what} {value!r}: expected one of {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的{what} {value!r}：应为以下之一：{names}</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="42" />
        <source>ground method</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>地面分类方法</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="47" />
        <source>engine</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>引擎</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="61" />
        <source>Parameters {params} do not belong to method {method}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>参数 {params} 不属于方法 {method}</translation>
    </message>
    <message>
        <location filename="../core/ground/pdal.py" line="189" />
        <source>PDAL executable {path} not found or not executable</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>PDAL 可执行文件 {path} 不存在或不可执行</translation>
    </message>
    <message>
        <location filename="../core/ground/pdal.py" line="310" />
        <location filename="../core/ground/pdal.py" line="312" />
        <location filename="../core/ground/pdal.py" line="308" />
        <location filename="../core/ground/pdal.py" line="293" />
        <location filename="../core/ground/pdal.py" line="302" />
        <location filename="../core/pointcloud.py" line="211" />
        <location filename="../core/pointcloud.py" line="119" />
        <location filename="../core/pointcloud.py" line="133" />
        <location filename="../core/pointcloud.py" line="196" />
        <location filename="../core/pointcloud.py" line="95" />
        <location filename="../core/pointcloud.py" line="98" />
        <location filename="../core/pointcloud.py" line="114" />
        <source>Cannot read {path}: the file is truncated or corrupt ({detail})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：文件被截断或已损坏（{detail}）</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="172" />
        <source>{n} tiles written to {folder}, listed in {vpc}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已将 {n} 个分块写入 {folder}，并列于 {vpc} 中</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="98" />
        <source>The virtual point cloud's name {name} must be a file name ending in .vpc</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>虚拟点云的名称 {name} 必须是以 .vpc 结尾的文件名</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="70" />
        <source>The output folder {folder} holds the input tile {tile}: choose another folder (the output folder is replaced as a whole)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>输出文件夹 {folder} 中包含输入分块 {tile}：请选择其他文件夹（输出文件夹会被整体替换）</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="73" />
        <source>Two tiles of {path} have the same file name, {name} ({first} and {second}): the output tiles are named as the input tiles, so their names must differ</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 中有两个分块的文件名相同，均为 {name}（{first} 和 {second}）：输出分块与输入分块同名，因此它们的名称必须不同</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="169" />
        <source>No point of {path} is left after the crop: {output} lists no tile</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>裁剪后 {path} 中没有剩余的点：{output} 未列出任何分块</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="158" />
        <source>No point of the tile {tile} lies inside the crop area: no output tile for it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>分块 {tile} 中没有点位于裁剪区域内：不为其生成输出分块</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="304" />
        <source>Unknown time base {base}: expected one of {bases}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的时间基准 {base}：应为 {bases} 之一</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="394" />
        <source>sign layer CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>标志图层坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="318" />
        <source>No output folder given for the handover package</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未指定交付包的输出文件夹</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="324" />
        <source>Cannot write the handover package to {folder}: {path} is a file, not a folder</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法将交付包写入 {folder}：{path} 是文件而不是文件夹</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="390" />
        <source>Unknown review state(s) {states}: expected some of {known}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的审核状态 {states}：应为 {known} 中的若干项</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="393" />
        <source>Unknown north {north}: expected grid or true</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的北方向 {north}：应为 grid 或 true</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="407" />
        <source>No sign has the review state(s) {states} ({counts}): review the signs with the review panel, or choose other states</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有标志具有审核状态 {states}（{counts}）：请用审核面板审核标志，或选择其他状态</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="422" />
        <source>Preparing the handover: sign {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在准备交付：第 {n} 个标志，共 {count} 个</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="479" />
        <source>{n} of {total} signs handed over (review states {states}); left out: {left}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已交付 {n} / {total} 个标志（审核状态 {states}）；未包含：{left}</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="168" />
        <source>The stations layer has fewer than two stations at different places: the export needs the drive's track (chainage, side and offset of each sign)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景站点图层中位于不同位置的全景站点少于两个：导出需要行驶采集的轨迹线（用于每个标志的里程、侧别和偏移）</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="331" />
        <source>Cannot write the handover package to {folder}: the folder {path} is not writable ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法将交付包写入 {folder}：文件夹 {path} 不可写（{error}）</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="411" />
        <source>The station times are GPS seconds of the week: give the survey date to get first and last seen as dates and times (first_seen_s and last_seen_s are written)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景站点时间为 GPS 周内秒：请提供采集日期，以将首次和最后一次看到的时间换算为日期和时间（仍会写出 first_seen_s 和 last_seen_s）</translation>
    </message>
    <message>
        <location filename="../core/outputs.py" line="68" />
        <source>Cannot write {path}: the folder {folder} does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法写入 {path}：文件夹 {folder} 不存在</translation>
    </message>
    <message>
        <location filename="../core/outputs.py" line="80" />
        <location filename="../core/outputs.py" line="92" />
        <location filename="../core/outputs.py" line="147" />
        <location filename="../core/outputs.py" line="209" />
        <location filename="../core/outputs.py" line="178" />
        <location filename="../core/pointcloud.py" line="285" />
        <source>Cannot write {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法写入 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/outputs.py" line="204" />
        <source>The output {path} was not written</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>输出 {path} 未被写入</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="126" />
        <source>The panorama {path} is {width} x {height} pixels, more than the {limit} the plugin reads</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景图 {path} 为 {width} x {height} 像素，超过插件可读取的 {limit}</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="135" />
        <source>The panorama {path} is {width} x {height} pixels: an equirectangular panorama must be twice as wide as it is high</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景图 {path} 为 {width} x {height} 像素：等距柱状全景图的宽度必须是高度的两倍</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="167" />
        <location filename="../core/panorama.py" line="118" />
        <source>Panorama not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到全景图：{path}</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="174" />
        <source>Cannot read the panorama {path}: the file is not a JPEG or PNG image or is corrupt</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取全景图 {path}：该文件不是 JPEG 或 PNG 图像，或已损坏</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="120" />
        <source>The panorama {path} has more pixels than the {limit} the plugin reads</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景图 {path} 的像素数超过插件可读取的 {limit}</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="123" />
        <source>Cannot read the panorama {path}: expected a JPEG or PNG image ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取全景图 {path}：应为 JPEG 或 PNG 图像（{error}）</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="172" />
        <source>Cannot read the panorama {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取全景图 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="384" />
        <source>Cannot use {item!r} as a crop geometry: expected a shapely geometry, WKB or WKT</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法将 {item!r} 用作裁剪几何：应为 shapely 几何、WKB 或 WKT</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="76" />
        <source>Cannot read {path}: expected a LAS or LAZ file ({detail})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 {path}：应为 LAS 或 LAZ 文件（{detail}）</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="507" />
        <source>{path} has no coordinate reference system and none was given</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 没有坐标参考系，也未提供坐标参考系</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="278" />
        <source>Cannot write {path}: the folder does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法写入 {path}：文件夹不存在</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="422" />
        <source>The crop layer has no geometry</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>裁剪图层没有几何</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="430" />
        <source>A corridor needs a positive buffer, got {buffer_m} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>走廊需要正的缓冲距离，实际为 {buffer_m} m</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="440" />
        <source>A corridor needs stations or lines</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>走廊需要站点或线</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="517" />
        <source>No point of {path} lies inside the crop area; {output} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 中没有点位于裁剪区域内；{output} 为空</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="622" />
        <source>{ok} of {count} detections found a surface in the cloud ({no_points} without points, {no_surface} without a planar surface)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{count} 个检测结果中有 {ok} 个在点云中找到了表面（{no_points} 个没有点，{no_surface} 个没有平面）</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="438" />
        <location filename="../core/projection.py" line="702" />
        <source>{source} has no ground points (class 2) where the signs are: run roadsigns:groundfilter on it first (or classify the ground with another tool)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{source} 在标志所在区域没有地面点（类别 2）：请先对其运行 roadsigns:groundfilter（或用其他工具进行地面分类）</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="581" />
        <source>The maximum range must exceed {min} m, got {value} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>最大距离必须大于 {min} m，实际为 {value} m</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="616" />
        <source>Searching the detections' surfaces: {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在搜索检测的表面：{n} / {count}</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="402" />
        <source>The candidates lack the field(s) {fields}; expected the output of Project detections</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>候选缺少字段 {fields}；应为“将检测投影到点云”的输出</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="427" />
        <source>Unknown candidate status {status!r}; expected ok, no_points or no_surface</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未知的候选状态 {status!r}；应为 ok、no_points 或 no_surface</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="431" />
        <source>A candidate with status ok has no position</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>状态为 ok 的候选没有位置</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="452" />
        <source>The point index lacks {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>点索引缺少 {names}</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="586" />
        <source>No detections to project; the candidates are empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有要投影的检测结果；候选为空</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="618" />
        <source>{path} has no point inside the detections' frusta; no candidate found</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} 在检测结果的视锥内没有点；未找到候选</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="141" />
        <source>curved surface (a convex mirror?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>曲面（凸面镜？）</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="142" />
        <source>part of a larger flat surface (a picture on a billboard or a wall?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>较大平面的一部分（广告牌或墙上的图案？）</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1029" />
        <source>{signs} signs from {candidates} candidates ({from_images} placed from the images alone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>从 {candidates} 个候选得到 {signs} 个标志（{from_images} 个仅由图像定位）</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1788" />
        <source>{coded} of {signs} signs have a sign code; {from_code} took their class from the code, {dropped} codes were dropped for the class vote (code_check)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{signs} 个标志中有 {coded} 个带有标志代码；{from_code} 个的类别取自代码，{dropped} 个代码因类别投票被舍弃（code_check）</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1797" />
        <source>the stations' height minus {height} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>站点高度减去 {height} 米</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="422" />
        <source>Detection {det_id} has the sign code {code}, which is not in the sign codes table {table}: give the codes table the classifier was run with</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测 {det_id} 的标志代码 {code} 不在标志代码表 {table} 中：请提供运行分类器时所用的代码表</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1006" />
        <source>The merge radius must be positive, got {value} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>合并半径必须为正数，实际为 {value} m</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1009" />
        <source>No candidates to refine; the sign layer is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有要精化的候选；标志图层为空</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1535" />
        <source>Candidates {ids}: {reason}; placed at the candidates' median</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>候选 {ids}：{reason}；位置取候选的中位数</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1728" />
        <source>Candidates {ids} dropped: a {width:.2f} x {height:.2f} m panel is too large for a {sign_class} sign (a billboard?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已丢弃候选 {ids}：{width:.2f} x {height:.2f} 米的面板对 {sign_class} 标志来说太大（广告牌？）</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1733" />
        <source>Candidates {ids} dropped: seen in one panorama only, with a score of {score:.2f}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已丢弃候选 {ids}：只在一张全景图中出现，得分为 {score:.2f}</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="523" />
        <source>too few points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>点太少</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="526" />
        <source>too few points in the boxes</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>框内的点太少</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="532" />
        <source>no near-vertical plane</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有近似竖直的平面</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="536" />
        <source>too few planar points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>平面点太少</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1469" />
        <source>Refining the signs: {n} of {count} candidate groups</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在精化标志：候选组 {n} / {count}</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1529" />
        <source>no point cloud</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有点云</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1532" />
        <source>Candidates {ids} dropped: {reason}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已丢弃候选 {ids}：{reason}</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1739" />
        <source>Candidates {ids} dropped: seen in one panorama only ({image}, {range:.1f} m away), not in the {missed} panoramas nearer to its face</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已丢弃候选 {ids}：只在一张全景图中出现（{image}，相距 {range:.1f} m），距其牌面更近的 {missed} 张全景图中均未出现</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1798" />
        <source>the lowest points below the sign</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志下方的最低点</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1802" />
        <source>{count} sign(s) have no ground points (class 2) within {radius} m: their height is measured from {source}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{count} 个标志在 {radius} 米内没有地面点（类别 2）：其高度从{source}起算</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="216" />
        <source>Sign codes table {path} is empty: expected the header {expected} and one row per code</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path} 为空：应有表头 {expected}，且每个代码一行</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="219" />
        <source>Sign codes table {path} holds no codes: expected one row per code after the header {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path} 中没有代码：表头 {expected} 之后应每个代码一行</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="429" />
        <source>The box {box} is not four finite pixel coordinates u0, v0, u1, v1</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>检测框 {box} 不是四个有限的像素坐标 u0、v0、u1、v1</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="162" />
        <source>Sign codes table not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到标志代码表：{path}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="164" />
        <source>Cannot read the sign codes table {path}: it is not UTF-8 text (byte {position}); save it as UTF-8</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取标志代码表 {path}：不是 UTF-8 文本（第 {position} 字节）；请另存为 UTF-8</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="167" />
        <source>Cannot read the sign codes table {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取标志代码表 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="192" />
        <source>Sign codes table {path}, line {line}: expected 3 fields separated by semicolons ({expected}), found {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：应有 3 个以分号分隔的字段（{expected}），实际为 {count} 个</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="197" />
        <source>Sign codes table {path}, line {line}: the code is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：代码为空</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="200" />
        <source>Sign codes table {path}, line {line}: the code {code} is reserved for signs the classifier cannot read and must not be in the table</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：代码 {code} 保留给分类器无法识别的标志，不得出现在表中</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="204" />
        <source>Sign codes table {path}, line {line}: the name of {code} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：{code} 的名称为空</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="207" />
        <source>Sign codes table {path}, lines {first} and {line}: the code {code} is there twice</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {first} 行和第 {line} 行：代码 {code} 出现了两次</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="210" />
        <source>Sign codes table {path}, line {line}: unknown class {found} for {code}; expected one of {classes}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：{code} 的类别 {found} 未知；应为以下之一：{classes}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="257" />
        <source>The model {path} is a {task} model; reading sign codes needs a classify model (metadata task = classify)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 是 {task} 模型；读取标志代码需要分类模型（元数据 task = classify）</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="267" />
        <source>The model {path} takes an input {name} of shape {shape} and type {type}; supported: float [batch, 3, S, S] (RGB crops S x S pixels, values 0..1)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的输入 {name} 形状为 {shape}，类型为 {type}；支持：float [batch, 3, S, S]（S x S 像素的 RGB 裁剪图像，值为 0..1）</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="285" />
        <source>The model {path} has an output of shape {shape} for a batch of {batch}; supported: [batch, C] with C = {count}, its number of names</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 在批大小为 {batch} 时的输出形状为 {shape}；支持：[batch, C]，其中 C = {count}，即其名称数量</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="293" />
        <source>The model {path} names no codes: its metadata needs 'names', a JSON list of the sign codes in output order (such as ["DE:206", "other"])</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 未给出任何代码：其元数据需要 'names'，即按输出顺序排列的标志代码 JSON 列表（例如 ["DE:206", "other"]）</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="299" />
        <source>The model {path} names {names} more than once in its metadata 'names'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 在其元数据 'names' 中多次给出 {names}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="305" />
        <source>The model {path} answers codes that are not in the sign codes table {table}: {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 给出的代码不在标志代码表 {table} 中：{names}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="313" />
        <source>The model {path} has the metadata output = {found}; expected {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的元数据 output = {found}；应为 {expected}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="326" />
        <source>The model {path} has the metadata crop_margin = {found}; expected a number from 0 to 2 (the fraction of the box's longer side added on each side)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 的元数据 crop_margin = {found}；应为 0 到 2 之间的数字（在每一侧添加的边距占检测框长边的比例）</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="180" />
        <source>Sign codes table {path}, line {line}: cannot split the line into fields ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：无法将该行拆分为字段（{error}）</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="186" />
        <source>Sign codes table {path}, line {line}: expected the header {expected}, found {found}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>标志代码表 {path}，第 {line} 行：应为表头 {expected}，实际为 {found}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="282" />
        <source>The model {path} failed on a blank {side} x {side} crop: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>模型 {path} 在一张 {side} x {side} 的空白裁剪图像上运行失败：{error}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="50" />
        <source>table</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>表格</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="77" />
        <source>{what} file {path} is empty: expected a header row with the columns {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path} 为空：应有包含列 {expected} 的表头行</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="85" />
        <source>{what} file {path}: missing column(s) {missing}; found {found}; expected {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}：缺少列 {missing}；找到的列：{found}；应有的列：{expected}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="93" />
        <source>{what} file {path} has a header but no data rows</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path} 有表头但没有数据行</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="65" />
        <source>{what} file not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到{what}文件：{path}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="67" />
        <source>Cannot read {what} file {path}: it is not UTF-8 text (byte {position}); save it as CSV in UTF-8</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取{what}文件 {path}：不是 UTF-8 文本（第 {position} 字节）；请另存为 UTF-8 编码的 CSV</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="70" />
        <source>Cannot read {what} file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取{what}文件 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="126" />
        <source>{what} file {path}, line {line}: {count} fields, but the header has {header_count}: decimal commas, or the delimiter inside a value? Write numbers with a decimal point (1.5, not 1,5)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行：有 {count} 个字段，但表头有 {header_count} 个：是否使用了小数逗号，或值中含有分隔符？请用小数点书写数字（应写 1.5，而非 1,5）</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="153" />
        <source>{what} file {path}, line {line}, field '{field}': expected a finite number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行，字段 '{field}'：应为有限数值，实际为 '{value}'</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="41" />
        <source>{what} file {path}, line {line}: cannot split the line into fields ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行：无法将该行拆分为字段（{error}）</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="105" />
        <source>{what} file {path}, line {line}: field '{field}' is missing (the row has {count} fields, the header {header_count})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行：缺少字段 '{field}'（该行有 {count} 个字段，表头有 {header_count} 个）</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="149" />
        <source>{what} file {path}, line {line}, field '{field}': expected a number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行，字段 '{field}'：应为数字，实际为 '{value}'</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="145" />
        <source>{what} file {path}, line {line}, field '{field}': expected a number, found '{value}': a decimal comma? Write numbers with a decimal point (1.5, not 1,5)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行，字段 '{field}'：应为数字，实际为 '{value}'：是否使用了小数逗号？请用小数点书写数字（应写 1.5，而非 1,5）</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="193" />
        <source>is duplicated</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>重复</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="193" />
        <source>goes back in time</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>出现倒退</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="201" />
        <location filename="../core/trajectory.py" line="205" />
        <source>Trajectory</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>轨迹</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="245" />
        <source>SBET</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SBET</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="262" />
        <location filename="../core/trajectory.py" line="264" />
        <source>Image times</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>图像时间</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="353" />
        <location filename="../core/trajectory.py" line="356" />
        <source>Poses</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>位姿</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="194" />
        <source>{what} file {path}, {location}: time {time} {kind} (previous {previous}); times must increase strictly</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，{location}：时间 {time} {kind}（前一个为 {previous}）；时间必须严格递增</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="228" />
        <source>SBET file {path}, record {record}: non-finite value (NaN or infinity)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 文件 {path}，第 {record} 条记录：存在非有限值（NaN 或无穷大）</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="233" />
        <source>SBET file {path}: latitude/longitude out of range for radians: not an SBET, or wrong byte order</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 文件 {path}：纬度/经度超出弧度的取值范围：不是 SBET 文件，或字节序错误</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="238" />
        <source>SBET file {path}, record {record}: roll, pitch, heading or wander out of range for radians, or the height beyond 100 km: not an SBET, or wrong byte order</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 文件 {path}，第 {record} 条记录：横滚角、俯仰角、航向角或游移角超出弧度范围，或高度超过 100 km：不是 SBET 文件，或字节序错误</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="256" />
        <source>Trajectory file not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到轨迹文件：{path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="311" />
        <source>Trajectory file {path} has {count} sample(s): at least 2 are needed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>轨迹文件 {path} 有 {count} 个采样点：至少需要 2 个</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="331" />
        <source>No image time falls inside the trajectory's span [{start}, {end}]</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>没有任何图像时间落在轨迹的时间范围 [{start}, {end}] 内</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="427" />
        <source>Panorama folder not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未找到全景图文件夹：{path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="467" />
        <source>None of the {count} panoramas listed was found in {folder}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>在 {folder} 中未找到所列 {count} 张全景图中的任何一张</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="504" />
        <source>Panorama {image}: its position x {x}, y {y} in the target CRS lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): choose the target CRS of the drive's region (e.g. its UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>全景图 {image}：其在目标坐标参考系中的位置 x {x}，y {y} 位于 {crs} 的适用范围（经度 {west} 至 {east}，纬度 {south} 至 {north}）之外：请选择行驶采集所在区域的目标坐标参考系（例如其 UTM 分带）</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="157" />
        <source>{layer}: station {station}: the quaternion qw, qx, qy, qz has norm {norm:.4f}, not 1; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}：全景站点 {station}：四元数 qw、qx、qy、qz 的模为 {norm:.4f}，不是 1；应为“导入轨迹”的输出</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="218" />
        <source>SBET file {path} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 文件 {path} 为空</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="220" />
        <source>SBET file {path} is {size} bytes, not a multiple of {record} bytes (17 float64 per record): truncated or not an SBET</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 文件 {path} 大小为 {size} 字节，不是 {record} 字节（每条记录 17 个 float64）的整数倍：文件被截断或不是 SBET</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="225" />
        <source>Cannot read SBET file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>无法读取 SBET 文件 {path}：{error}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="272" />
        <source>{what} file {path}, line {line}, field 'image': empty image name</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行，字段 'image'：图像名称为空</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="275" />
        <source>{what} file {path}, line {line}: image '{image}' already listed on line {first}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what}文件 {path}，第 {line} 行：图像 '{image}' 已在第 {first} 行列出</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="318" />
        <source>Image times file {path}, {location}: time {time} of image '{image}' is outside the trajectory's span [{start}, {end}] ({count} image(s) outside in all; set the option to skip them)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>图像时间文件 {path}，{location}：图像 '{image}' 的时间 {time} 超出轨迹的时间范围 [{start}, {end}]（共有 {count} 张图像超出；可设置选项跳过它们）</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="324" />
        <source>Skipped {count} image(s) whose time is outside the trajectory's span [{start}, {end}], the first: {image}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已跳过 {count} 张时间超出轨迹范围 [{start}, {end}] 的图像，第一张：{image}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="341" />
        <source>{count} image(s) fall in a trajectory gap longer than {max_gap} s; the longest gap is {gap:.3f} s around image '{image}' at time {time}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{count} 张图像落在长于 {max_gap} 秒的轨迹间隙中；最长的间隙为 {gap:.3f} 秒，位于图像 '{image}'（时间 {time}）附近</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="407" />
        <source>Skipped {count} panorama(s) that are missing or unreadable; the first: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已跳过 {count} 张缺失或无法读取的全景图；第一张：{path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="430" />
        <source>Give either a per-image pose file, or a trajectory with image times, not both</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>请提供逐图像位姿文件，或带图像时间的轨迹，但不能同时提供两者</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="438" />
        <source>A trajectory file and an image times file are needed (or a per-image pose file instead)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>需要轨迹文件和图像时间文件（或改为提供逐图像位姿文件）</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="460" />
        <source>No target CRS given: using {crs}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>未指定目标坐标参考系：使用 {crs}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="443" />
        <source>SBET trajectory: WGS 84 geographic with ellipsoidal heights, {count} records</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>SBET 轨迹：WGS 84 地理坐标，椭球高，{count} 条记录</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="449" />
        <source>Trajectory: {count} samples over {span:.1f} s</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>轨迹：{count} 个采样，历时 {span:.1f} 秒</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="132" />
        <source>{layer}: station {station} has no value in the field {field}; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}：全景站点 {station} 的字段 {field} 没有值；应为“导入轨迹”的输出</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="143" />
        <source>{layer}: station {station}, field {field}: expected a finite number, found '{value}'; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}：全景站点 {station}，字段 {field}：应为有限数字，实际为 '{value}'；应为“导入轨迹”的输出</translation>
    </message>
    <message>
        <location filename="../core/viewclass.py" line="75" />
        <source>Looking for the cloud's signs in the panoramas: sign {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>正在全景图中查找点云中的标志：第 {n} 个，共 {count} 个</translation>
    </message>
    <message>
        <location filename="../dependencies.py" line="72" />
        <source>The installed shapely is a wheel with its own copy of GEOS, which clashes with QGIS's GEOS {geos} on Linux and crashes QGIS. Install shapely built against the system GEOS: sudo apt install libgeos-dev &amp;&amp; python3 -m pip install --user --break-system-packages --force-reinstall --no-deps --no-binary shapely "shapely&gt;=2"</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>已安装的 shapely 是自带 GEOS 副本的 wheel 包，它与 QGIS 在 Linux 上使用的 GEOS {geos} 冲突，会导致 QGIS 崩溃。请安装基于系统 GEOS 构建的 shapely：sudo apt install libgeos-dev &amp;&amp; python3 -m pip install --user --break-system-packages --force-reinstall --no-deps --no-binary shapely "shapely&gt;=2"</translation>
    </message>
    <message>
        <location filename="../dependencies.py" line="77" />
        <source>Road Sign Inventory needs the Python package(s) {packages}, not found in QGIS's Python. Install with: {command}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>道路标志清查需要 Python 包 {packages}，但在 QGIS 的 Python 中未找到。安装命令：{command}</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="726" />
        <source>The whole road-sign inventory: panorama stations from the trajectory, sign detection in the panoramas, ground filter and crop of the point cloud around the drive, projection of each detection into the cloud, and refinement and merging into the sign layer, with a review chip of every sign and the review report; then the sign panels and poles found in the cloud alone, fused with the image signs into the final inventory (Signs (fused): which sources found each sign, its condition, the signs the cameras missed).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>完整的道路标志清查：由轨迹生成全景站点，在全景图中检测标志，对行驶采集沿线的点云进行地面滤波与裁剪，将每个检测投影到点云，并精化与合并为标志图层，同时生成每个标志的审核切片和审核报告；随后仅在点云中查找标志牌和杆，并与图像标志融合为最终的清查结果（标志（融合）：每个标志由哪些来源找到、其状态，以及相机漏掉的标志）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="727" />
        <source>Boresight pitch (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>安置角：俯仰（°）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="728" />
        <source>Boresight roll (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>安置角：横滚（°）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="729" />
        <source>Boresight yaw (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>安置角：偏航（°）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="730" />
        <source>Your own ONNX sign-code classifier (format in models/README.md), or empty for the bundled one.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>您自己的 ONNX 标志代码分类器（格式见 models/README.md），留空则使用内置分类器。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="731" />
        <source>The codes table of your classifier (code;name;class, format in models/README.md), or empty for the bundled German table.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>您的分类器的代码表（code;name;class，格式见 models/README.md），留空则使用内置的德国代码表。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="732" />
        <source>A sign's voted code whose support (code_score) is below this is left empty.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>标志投票得出的代码的支持度（code_score）低于此值时，代码留空。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="733" />
        <source>Detections scoring below this are dropped.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>得分低于此值的检测将被丢弃。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="734" />
        <source>The views of the horizon ring each panorama is cut into. 6 views, turned so that their seams ahead and behind fall inside the closer views ahead and behind, take about 0.8 times the detection time; on held-out test streets with a panorama every 5 m the chain found the same signs with either, and on a test drive one false sign more with 6 (flagged for review). 8 by default; 6 trades a little accuracy for speed.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>每张全景切分成的地平线环视图。6 个视图经过旋转，使前后方向的接缝落在前后的近景视图之内，检测时间约为 0.8 倍；在每 5 米一张全景的留出测试街道上，两种设置下处理链找到的标志相同，而在一段测试行驶中，6 个视图多出一个误报（已标记待复核）。默认为 8；6 以少许精度换取速度。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="735" />
        <source>Folder of the equirectangular panoramas.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>等距柱状全景图所在的文件夹。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="736" />
        <source>image,time CSV of the panoramas.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>全景图的 image,time CSV。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="737" />
        <source>Lever arm x, forward (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>杆臂 x，向前（m）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="738" />
        <source>Lever arm y, right (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>杆臂 y，向右（m）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="739" />
        <source>Lever arm z, down (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>杆臂 z，向下（m）。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="740" />
        <source>Your own ONNX detector, or empty for the bundled one.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>您自己的 ONNX 检测器；留空则使用内置检测器。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="741" />
        <source>The drive's LiDAR cloud.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>本次行驶采集的激光雷达点云。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="742" />
        <source>Reads what each sign says (its code, such as DE:274[50] for speed limit 50) with the sign-code classifier; unchecked, the code fields stay empty.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>使用标志代码分类器读取每个标志的内容（其代码，例如 DE:274[50] 表示限速 50）；不勾选时代码字段保持为空。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="743" />
        <source>Detects in as few panoramas as leave no more than this distance between one detected in and the next (the ones between are skipped); 0 detects in every panorama. On held-out test streets a panorama every 5 m found every sign, every 10 m lost 2 in 45.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>只在尽可能少的全景图中检测，使相邻两幅被检测的全景图之间的距离不超过此值（其间的跳过）；0 表示在每幅全景图中检测。在留出的测试街道上，每 5 米一幅全景图找到了全部标志，每 10 米则 45 个中漏检 2 个。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="744" />
        <source>Projected CRS of the outputs: the point cloud's CRS.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>输出的投影坐标参考系：即点云的坐标参考系。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="745" />
        <source>time,x,y,z,roll,pitch,heading CSV, or an Applanix SBET.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>time,x,y,z,roll,pitch,heading CSV，或 Applanix SBET。</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="746" />
        <source>CRS of the trajectory positions (ignored for an SBET).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>轨迹位置的坐标参考系（对 SBET 忽略）。</translation>
    </message>
</context>
<context>
    <name>RoadSignsAlgorithm</name>
    <message>
        <location filename="../algorithms/base.py" line="111" />
        <source>Road sign inventory</source>
        <translation>道路标志清查</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="281" />
        <source>Cancelled: nothing was written.</source>
        <translation>已取消：未写入任何内容。</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="287" />
        <source>Out of memory: nothing was written. Crop the point cloud (Ground filter with a crop layer) or process the drive in parts.</source>
        <translation>内存不足：未写入任何内容。请裁剪点云（使用带裁剪图层的地面滤波），或分段处理行驶采集数据。</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="290" />
        <source>Cannot read or write {}: {}. Nothing was written.</source>
        <translation>无法读取或写入 {}：{}。未写入任何内容。</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="293" />
        <source>Unexpected error ({}: {}); nothing was written. The details are in the QGIS message log (Road sign inventory); please report them.</source>
        <translation>意外错误（{}：{}）；未写入任何内容。详细信息见 QGIS 消息日志（Road sign inventory）；请报告。</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="298" />
        <source>{} However, these partial outputs could not be removed: {}</source>
        <translation>{} 但是，以下部分输出无法删除：{}</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="175" />
        <source>Accepted: one LAS/LAZ file (COPC too), a virtual point cloud (.vpc, e.g. from QGIS's Build virtual point cloud) listing tiles, or a folder of LAS/LAZ tiles (type or paste the folder's path). Tiles must share the point format and the CRS.</source>
        <translation>可接受：一个 LAS/LAZ 文件（也支持 COPC）、列出分块的虚拟点云（.vpc，例如由 QGIS 的“构建虚拟点云”生成），或 LAS/LAZ 分块所在的文件夹（输入或粘贴文件夹路径）。各分块的点格式和坐标参考系必须相同。</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="175" />
        <source>Point clouds (*.las *.laz *.vpc *.LAS *.LAZ *.VPC);;LAS/LAZ (*.las *.laz *.LAS *.LAZ);;Virtual point clouds (*.vpc *.VPC);;All files or a folder of tiles (*)</source>
        <translation>点云 (*.las *.laz *.vpc *.LAS *.LAZ *.VPC);;LAS/LAZ (*.las *.laz *.LAS *.LAZ);;虚拟点云 (*.vpc *.VPC);;所有文件或分块文件夹 (*)</translation>
    </message>
</context>
<context>
    <name>RoadSignsProvider</name>
    <message>
        <location filename="../provider/provider.py" line="31" />
        <source>Road sign inventory</source>
        <translation>道路标志清查</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="34" />
        <source>Road sign inventory from mobile mapping (panoramas, trajectory, LiDAR)</source>
        <translation>基于移动测量的道路标志清查（全景图、轨迹、激光雷达）</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="47" />
        <source>PDAL executable for the ground filter (empty: search PATH and QGIS)</source>
        <translation>地面滤波使用的 PDAL 可执行文件（留空：在 PATH 和 QGIS 中查找）</translation>
    </message>
</context>
<context>
    <name>ShippedModel</name>
    <message>
        <location filename="../provider/provider.py" line="94" />
        <source>Sign inventory (whole chain)</source>
        <translation>标志清查（完整流程）</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="107" />
        <source>Road sign inventory</source>
        <translation>道路标志清查</translation>
    </message>
</context>
</TS>