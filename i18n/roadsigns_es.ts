<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="es" sourcelanguage="en">
<context>
    <name>@default</name>
    <message>
        <location filename="../plugin.py" line="58" />
        <source>Road Sign Inventory</source>
        <translation>Inventario de señales viales</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="56" />
        <source>{layer}: no field 'class'; fields found: {found}</source>
        <translation>{layer}: no hay campo 'class'; campos encontrados: {found}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="75" />
        <source>{layer}: missing field(s) {missing}; fields found: {found}</source>
        <translation>{layer}: falta(n) el/los campo(s) {missing}; campos encontrados: {found}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="198" />
        <source>{layer} is in {layer_crs}, the point cloud {cloud} in {cloud_crs}: import the trajectory with the cloud's CRS as target CRS so that every stage works in one CRS</source>
        <translation>{layer} está en {layer_crs} y la nube de puntos {cloud} en {cloud_crs}: importe la trayectoria con el SRC de la nube como SRC de destino para que todas las etapas trabajen en un mismo SRC</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>warning</source>
        <translation>advertencia</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>prohibitory</source>
        <translation>prohibición</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="51" />
        <source>mandatory</source>
        <translation>obligación</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>information</source>
        <translation>información</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>stop</source>
        <translation>stop</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="52" />
        <source>yield</source>
        <translation>ceda el paso</translation>
    </message>
    <message>
        <location filename="../algorithms/style.py" line="60" />
        <source>other</source>
        <translation>otras</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="71" />
        <source>{layer}: cannot reproject feature {feature}: {error}</source>
        <translation>{layer}: no se puede reproyectar la entidad {feature}: {error}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="87" />
        <source>{layer}: sign '{sign_id}' has no valid x, y, z position (no point geometry, and no numbers in the fields x, y, z)</source>
        <translation>{layer}: la señal '{sign_id}' no tiene una posición x, y, z válida (ni geometría de punto ni números en los campos x, y, z)</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="88" />
        <source>{layer}, feature {feature}: the field {field} holds '{value}', not a number</source>
        <translation>{layer}, entidad {feature}: el campo {field} contiene '{value}', no un número</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="95" />
        <source>{layer}: the layer has no feature, nothing to process</source>
        <translation>{layer}: la capa no tiene entidades, no hay nada que procesar</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="116" />
        <source>Cannot write feature {} to the output layer: {}</source>
        <translation>No se puede escribir la entidad {} en la capa de salida: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="141" />
        <source>{layer} is in {crs}, a geographic CRS (degrees): this needs a projected CRS in metres, the CRS of the point cloud (e.g. a UTM zone)</source>
        <translation>{layer} está en {crs}, un SRC geográfico (grados): esto necesita un SRC proyectado en metros, el SRC de la nube de puntos (p. ej. una zona UTM)</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="175" />
        <source>The point cloud {cloud} has no coordinate reference system: give it as Cloud CRS (an advanced parameter; a CRS is never guessed)</source>
        <translation>La nube de puntos {cloud} no tiene sistema de referencia de coordenadas: indíquelo en SRC de la nube (un parámetro avanzado; el SRC nunca se adivina)</translation>
    </message>
    <message>
        <location filename="../algorithms/layers.py" line="193" />
        <source>The point cloud {cloud} has no coordinate reference system: give it one with Ground filter (parameter Cloud CRS); a CRS is never guessed</source>
        <translation>La nube de puntos {cloud} no tiene sistema de referencia de coordenadas: asígnele uno con Filtro de suelo (parámetro SRC de la nube); el SRC nunca se adivina</translation>
    </message>
    <message>
        <location filename="../plugin.py" line="51" />
        <source>Sign review panel</source>
        <translation>Panel de revisión de señales</translation>
    </message>
</context>
<context>
    <name>DetectSigns</name>
    <message>
        <location filename="../algorithms/detectsigns.py" line="58" />
        <source>Detect signs in panoramas</source>
        <translation>Detectar señales en panoramas</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="61" />
        <source>Runs an ONNX sign detector on each panorama; one ray per detected sign.</source>
        <translation>Ejecuta un detector de señales ONNX en cada panorama; un rayo por señal detectada.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="256" />
        <source>Panorama stations</source>
        <translation>Estaciones de panorama</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="88" />
        <source>The output of Import trajectory: one point per panorama with its pose and path.</source>
        <translation>La salida de «Importar trayectoria y panoramas»: un punto por panorama con su pose y su ruta.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>ONNX model (empty: the bundled model)</source>
        <translation>Modelo ONNX (vacío: el modelo incluido)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>A YOLO-family ONNX detector. Empty uses the model bundled with the plugin.</source>
        <translation>Un detector ONNX de la familia YOLO. Vacío usa el modelo incluido con el complemento.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="91" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>Modelos ONNX (*.onnx);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="95" />
        <source>Minimum confidence</source>
        <translation>Confianza mínima</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="95" />
        <source>Detections scoring below this (0-1) are dropped.</source>
        <translation>Se descartan las detecciones con una puntuación inferior a este valor (0-1).</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="116" />
        <source>Smallest sign kept (panorama pixels)</source>
        <translation>Señal más pequeña conservada (píxeles de panorama)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="116" />
        <source>Detections whose box is shorter than this on its shorter side are dropped: signs that small are boxed a few pixels off and their class is unsure, and the drive sees them again, larger, from the next stations. 0 keeps every detection.</source>
        <translation>Se descartan las detecciones cuyo recuadro tiene el lado menor por debajo de este valor: en señales tan pequeñas el recuadro se desvía unos píxeles y la clase es dudosa, y el recorrido las vuelve a ver, más grandes, desde las estaciones siguientes. 0 conserva todas las detecciones.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>Class names file (optional)</source>
        <translation>Archivo de nombres de clase (opcional)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>One class name per line, in the model's class order; needed when the model has no names in its metadata and no labels file beside it.</source>
        <translation>Un nombre de clase por línea, en el orden de clases del modelo; necesario cuando el modelo no tiene nombres en sus metadatos ni un archivo de etiquetas a su lado.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="122" />
        <source>Text files (*.txt);;All files (*.*)</source>
        <translation>Archivos de texto (*.txt);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="127" />
        <source>Ray length (m)</source>
        <translation>Longitud del rayo (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="127" />
        <source>Length of each detection ray from the panorama centre, in metres.</source>
        <translation>Longitud de cada rayo de detección desde el centro del panorama, en metros.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="131" />
        <source>Also look upwards (overhead and gantry signs)</source>
        <translation>Mirar también hacia arriba (señales elevadas y de pórtico)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="224" />
        <source>CPU threads (0: all)</source>
        <translation>Hilos de CPU (0: todos)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="224" />
        <source>Threads onnxruntime may use on the CPU; 0 lets it use every core.</source>
        <translation>Hilos que onnxruntime puede usar en la CPU; 0 le permite usar todos los núcleos.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="230" />
        <source>Detections</source>
        <translation>Detecciones</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="234" />
        <source>Number of detections</source>
        <translation>Número de detecciones</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="235" />
        <source>Panoramas skipped</source>
        <translation>Panoramas omitidos</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="249" />
        <source>ONNX model not found: {}</source>
        <translation>No se encontró el modelo ONNX: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="268" />
        <source>{} panoramas, {} views each</source>
        <translation>{} panoramas, {} vistas cada uno</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="304" />
        <source>Skipped {} panorama(s) that could not be read.</source>
        <translation>Se omitieron {} panorama(s) que no se pudieron leer.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="320" />
        <source>{} detections in {} panoramas ({} skipped).</source>
        <translation>{} detecciones en {} panoramas ({} omitidos).</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="312" />
        <source>No sign was detected: the detections layer is empty.</source>
        <translation>No se detectó ninguna señal: la capa de detecciones está vacía.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="230" />
        <source>LineStringZ layer, one ray per detection, with det_id, station_id, image, class, score, code, code_score, u0, v0, u1, v1, n_views and the station's pose fields.</source>
        <translation>Capa LineStringZ, un rayo por detección, con det_id, station_id, image, class, score, code, code_score, u0, v0, u1, v1, n_views y los campos de pose de la estación.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="228" />
        <source>in a crop around each detection, voted later across the views of each sign by Refine and merge signs</source>
        <translation>en un recorte alrededor de cada detección; «Refinar y fusionar señales» vota después entre las vistas de cada señal</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="141" />
        <source>Look ahead and behind more closely (small, far signs)</source>
        <translation>Mirar hacia delante y hacia atrás con más detalle (señales pequeñas y lejanas)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="98" />
        <source>Second look from confidence</source>
        <translation>Segunda mirada desde la confianza</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="283" />
        <source>Second look: boxes scored from {} to {} are kept where the sign-code classifier reads a code.</source>
        <translation>Segunda mirada: los recuadros puntuados de {} a {} se conservan donde el clasificador de códigos de señal lee un código.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="141" />
        <source>Adds two views of 53° straight ahead and behind, with 1.5 times the pixels per degree of the horizon views (at a 4096 px panorama's own density), for signs far along the road. Real signs need the pixels: on real street photographs at the horizon views' density the detector found 0.82 of the signs (GTSDB 500-599) and 0.54 of 376 held-out real signs pasted as distant ones; with these views 0.93 and 0.69, precision within 0.01. On held-out generated panoramas: 0.906 of the signs per panorama instead of 0.879. They cost 1.24 times the detection time. On by default; turn it off only for speed on drives with panoramas close together (every sign is then seen from many stations).</source>
        <translation>Añade dos vistas de 53° justo delante y detrás, con 1,5 veces los píxeles por grado de las vistas del horizonte (la densidad propia de un panorama de 4096 px), para las señales lejanas a lo largo de la vía. Las señales reales necesitan esos píxeles: en fotografías reales de calles, a la densidad de las vistas del horizonte, el detector encontró 0,82 de las señales (GTSDB 500-599) y 0,54 de 376 señales reales reservadas pegadas como señales lejanas; con estas vistas, 0,93 y 0,69, con una precisión que varía menos de 0,01. En panoramas generados reservados: 0,906 de las señales por panorama en lugar de 0,879. Cuestan 1,24 veces el tiempo de detección. Activado por defecto; desactívelo solo por velocidad en recorridos con panoramas muy próximos (cada señal se ve entonces desde muchas estaciones).</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="324" />
        <source>Sign codes read in {} of the {} detections (the others: other, or a sign whose code the table lacks).</source>
        <translation>Códigos de señal leídos en {} de las {} detecciones (las demás: other, o una señal cuyo código no está en la tabla).</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="131" />
        <source>Adds two views tilted 35° up, over the road ahead and behind, for gantry and overhead signs close to the vehicle, above the horizon views. On by default: on five held-out test streets they raised the gantry panels found in a single panorama from 86 % to 91 % for 1.2 times the detection time. A box these views cut at their left or right edge is dropped unless another view finds the same sign: signs beside the road are seen whole in the horizon views. With the second look, a box these views find alone and the sign-code classifier reads as no sign ('other': a facade's dark window, say) is dropped too. Switch it off to save that time where a drive has no overhead signs.</source>
        <translation>Añade dos vistas inclinadas 35° hacia arriba, sobre la calzada hacia delante y hacia atrás, para las señales de pórtico y elevadas cercanas al vehículo, por encima de las vistas horizontales. Activado por defecto: en cinco calles de prueba no usadas en el ajuste elevaron los paneles de pórtico encontrados en un solo panorama del 86 % al 91 %, con 1,2 veces el tiempo de detección. Un recuadro que estas vistas cortan en su borde izquierdo o derecho se descarta salvo que otra vista encuentre la misma señal: las señales al borde de la calzada se ven enteras en las vistas horizontales. Con la segunda mirada, también se descarta un recuadro que solo estas vistas encuentran y en el que el clasificador de códigos de señal no lee ninguna señal («other»: la ventana oscura de una fachada, por ejemplo). Desactívelo para ahorrar ese tiempo en recorridos sin señales elevadas.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="64" />
        <source>Cuts each station's equirectangular panorama into overlapping perspective views (a horizon ring, two closer views ahead and behind, and two views upwards for overhead signs), runs the ONNX detector on each view, maps the boxes back to panorama pixels and merges the same sign found in two views. A box much taller than wide (a sign passed close by, seen nearly edge-on, which the detector boxes about twice as wide as its face) is narrowed to the columns that show sign colours (saturated red, blue or yellow).&lt;br&gt;&lt;br&gt;The &lt;b&gt;model&lt;/b&gt; is the bundled one when left empty, or your own ONNX export: Ultralytics YOLOv8/11 ([1, 4+nc, N]), YOLOv5/7 ([1, N, 5+nc]) or a model with NMS built in ([1, N, 6]). Class names come from the model's metadata (Ultralytics &lt;i&gt;names&lt;/i&gt;) or a labels file (one name per line).&lt;br&gt;&lt;br&gt;Output: one line per detection from the panorama centre along the ray through the box centre, &lt;i&gt;Ray length&lt;/i&gt; long, with the box (u0, v0, u1, v1 in panorama pixels; across the ±180° seam u1 exceeds the width) and the station's pose. A panorama that cannot be read is skipped with a warning and counted.&lt;br&gt;&lt;br&gt;&lt;b&gt;Sign codes&lt;/b&gt;: a second, small ONNX model (the bundled sign-code classifier, or your own) reads what each detected sign says, from a rectified crop of the panorama around its box at the panorama's own resolution: &lt;i&gt;code&lt;/i&gt; (such as DE:274[50], speed limit 50, from the codes table; &lt;i&gt;other&lt;/i&gt; when it knows none) and &lt;i&gt;code_score&lt;/i&gt; (its probability). Refine signs votes them across the views of each sign. The classifier's format is in models/README.md (section &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;).</source>
        <translation>Corta el panorama equirrectangular de cada estación en vistas en perspectiva superpuestas (un anillo horizontal, dos vistas más cercanas hacia delante y hacia atrás, y dos vistas hacia arriba para las señales elevadas), ejecuta el detector ONNX en cada vista, devuelve los recuadros a píxeles del panorama y fusiona la misma señal encontrada en dos vistas. Un recuadro mucho más alto que ancho (una señal junto a la que se pasa de cerca, vista casi de canto, que el detector encuadra con el doble de ancho que su cara) se estrecha a las columnas que muestran colores de señal (rojo, azul o amarillo saturados).&lt;br&gt;&lt;br&gt;El &lt;b&gt;modelo&lt;/b&gt; es el incluido si se deja vacío, o su propia exportación ONNX: Ultralytics YOLOv8/11 ([1, 4+nc, N]), YOLOv5/7 ([1, N, 5+nc]) o un modelo con NMS integrado ([1, N, 6]). Los nombres de clase provienen de los metadatos del modelo (&lt;i&gt;names&lt;/i&gt; de Ultralytics) o de un archivo de etiquetas (un nombre por línea).&lt;br&gt;&lt;br&gt;Salida: una línea por detección desde el centro del panorama a lo largo del rayo que pasa por el centro del recuadro, de &lt;i&gt;Longitud del rayo&lt;/i&gt; de largo, con el recuadro (u0, v0, u1, v1 en píxeles del panorama; a través de la costura de ±180°, u1 supera el ancho) y la pose de la estación. Un panorama que no se puede leer se omite con una advertencia y se contabiliza.&lt;br&gt;&lt;br&gt;&lt;b&gt;Códigos de señal&lt;/b&gt;: un segundo modelo ONNX, pequeño (el clasificador de códigos de señal incluido, o el suyo propio), lee lo que dice cada señal detectada a partir de un recorte rectificado del panorama alrededor de su recuadro, con la resolución propia del panorama: &lt;i&gt;code&lt;/i&gt; (como DE:274[50], límite de velocidad 50, de la tabla de códigos; &lt;i&gt;other&lt;/i&gt; cuando no conoce ninguno) y &lt;i&gt;code_score&lt;/i&gt; (su probabilidad). «Refinar y fusionar señales» los somete a votación entre las vistas de cada señal. El formato del clasificador está en models/README.md (sección &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;).</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="176" />
        <source>Look again, closer, at small boxes scored under the minimum confidence</source>
        <translation>Volver a mirar, más de cerca, las cajas pequeñas puntuadas por debajo de la confianza mínima</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="176" />
        <source>A box of at most {px} px that the detector scores from {score} up to the minimum confidence is cut again from the panorama at a higher pixel density (the box {box_px} px across) and detected once more; it is kept when the detector then scores it at the minimum confidence or more, with that score, class and box. All of a panorama's such boxes go through the detector together, in one extra run. It finds far signs, 15-25 px across: on 376 held-out real signs pasted into street photographs the signs found rose from 0.79 to 0.87 (those 14-20 px high from 0.34 to 0.59) at a precision of 0.96; on real street photographs (GTSDB 500-599) the recall stayed at 0.958 and the precision went from 0.971 to 0.958. It costs 1.05-1.09 times the detection time. On by default.</source>
        <translation>Una caja de {px} px como máximo que el detector puntúa desde {score} hasta la confianza mínima se recorta de nuevo del panorama con una densidad de píxeles mayor (la caja mide {box_px} px) y se detecta otra vez; se conserva cuando el detector la puntúa entonces con la confianza mínima o más, con esa puntuación, clase y caja. Todas esas cajas de un panorama pasan juntas por el detector, en una sola ejecución adicional. Encuentra señales lejanas, de 15-25 px: en 376 señales reales reservadas, pegadas en fotografías de calles, las señales encontradas subieron de 0,79 a 0,87 (las de 14-20 px de alto, de 0,34 a 0,59) con una precisión de 0,96; en fotografías reales de calles (GTSDB 500-599) la exhaustividad se mantuvo en 0,958 y la precisión pasó de 0,971 a 0,958. Cuesta entre 1,05 y 1,09 veces el tiempo de detección. Activado por defecto.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="296" />
        <source>Zoomed look: boxes of at most {} px scored from {} to {} are detected again at a higher pixel density.</source>
        <translation>Mirada de cerca: las cajas de {} px como máximo puntuadas entre {} y {} se detectan de nuevo con una densidad de píxeles mayor.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>Horizon views</source>
        <translation>Vistas del horizonte</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>{n} views of {width:g}°</source>
        <translation>{n} vistas de {width:g}°</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>{n} views of {width:g}°, turned {yaw:g}°</source>
        <translation>{n} vistas de {width:g}°, giradas {yaw:g}°</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>One band of {width} × {height} px</source>
        <translation>Una banda de {width} × {height} px</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="190" />
        <source>Look again, stretched across, at tall boxes of signs seen edge-on</source>
        <translation>Volver a mirar, estiradas a lo ancho, las cajas altas de señales vistas de canto</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="290" />
        <source>Edge-on look: boxes at least {} times as tall as wide scored from {} to {} are detected again stretched {} times across.</source>
        <translation>Mirada de canto: las cajas al menos {} veces más altas que anchas puntuadas de {} a {} se detectan de nuevo estiradas {} veces a lo ancho.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="190" />
        <source>A sign passed close by is seen far off its face's normal, and the view squeezes it to a sliver that the detector scores low. A box at least {ratio} times as tall as wide, of at most {px} px, that the detector scores from {score} up to the minimum confidence is cut again from the panorama (its height {box_px} px) and stretched {stretch} times across, so that the sign's face is about as wide as tall again, and detected once more; it is kept when the detector then scores it at the minimum confidence or more. Its tiles go into the zoomed look's detector runs, and a box both looks take keeps the higher score. On five held-out generated streets it found 701 of 734 signs in single panoramas, against 697 without it (signs seen more than 70° off their face's normal: 27 of 45 against 23), with one false box fewer, in 1.02 to 1.03 times the processor time; real signs of street photographs squeezed across to 0.3 of their width are scored 0.5 or more in 44 of 50 cases stretched, against 11 as they are. On the real street photographs themselves it changed nothing. On by default.</source>
        <translation>Una señal junto a la que se pasa muy cerca se ve muy lejos de la normal de su cara, y la vista la comprime en una franja estrecha a la que el detector da una puntuación baja. Una caja al menos {ratio} veces más alta que ancha, de {px} px como máximo, que el detector puntúa desde {score} hasta la confianza mínima se recorta de nuevo de la panorámica (su altura a {box_px} px), se estira {stretch} veces a lo ancho, de modo que la cara de la señal vuelve a ser casi tan ancha como alta, y se detecta una vez más; se conserva cuando el detector la puntúa entonces con la confianza mínima o más. Sus recortes van en las mismas ejecuciones del detector que los de la mirada ampliada, y una caja que toman ambas miradas conserva la puntuación más alta. En cinco calles generadas reservadas encontró 701 de 734 señales en panorámicas sueltas, frente a 697 sin ella (señales vistas a más de 70° de la normal de su cara: 27 de 45 frente a 23), con una caja falsa menos, en 1,02 a 1,03 veces el tiempo de procesador; señales reales de fotografías de calle comprimidas a lo ancho a 0,3 de su anchura se puntúan con 0,5 o más en 44 de 50 casos estiradas, frente a 11 tal como están. En las propias fotografías de calle reales no cambió nada. Activada por defecto.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="209" />
        <source>Detect in a panorama at least every (m)</source>
        <translation>Detectar en un panorama al menos cada (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="209" />
        <source>Detects in as few panoramas as leave no more than this distance between one panorama detected in and the next; the ones between are skipped (not read, no detections). The first and the last panorama are always detected in, and a drive whose panoramas stand this far apart or more keeps every one. A sign stays in view over many stations, so skipping saves detection time in proportion, but each sign is then seen from fewer stations: fewer rays to place it, and a sign visible from only a few stations (small, or hidden behind trees or vehicles) may be missed. Measured on two held-out test streets with a panorama every 5 m: every panorama found all 46 and 45 signs; 10 m (every other one) lost 2 of each, 15 m lost 11 of 46. On two held-out streets with a panorama every 1.25 m, one every 5 m found the same 87 signs as one every 2.5 m, in 0.55 times the detection time; the median position error went from 11 to 13 mm, and one sign, read in 3 of its 7 views instead of 13 of 19, was left without a code. 0 detects in every panorama.</source>
        <translation>Detecta en tan pocos panoramas como permitan que entre un panorama detectado y el siguiente no haya más que esta distancia; los intermedios se omiten (no se leen, sin detecciones). El primer y el último panorama se detectan siempre, y un recorrido cuyos panoramas distan esto o más los conserva todos. Una señal permanece visible desde muchas estaciones, así que omitir ahorra tiempo de detección en proporción, pero cada señal se ve desde menos estaciones: menos rayos para situarla, y una señal visible solo desde unas pocas estaciones (pequeña, u oculta tras árboles o vehículos) puede perderse. Medido en dos calles de prueba reservadas con un panorama cada 5 m: todos los panoramas encontraron las 46 y 45 señales; cada 10 m (uno de cada dos) se perdieron 2 de cada una, cada 15 m 11 de 46. En dos calles reservadas con un panorama cada 1,25 m, uno cada 5 m encontró las mismas 87 señales que uno cada 2,5 m, en 0,55 veces el tiempo de detección; la mediana del error de posición pasó de 11 a 13 mm, y una señal, leída en 3 de sus 7 vistas en lugar de 13 de 19, quedó sin código. 0 detecta en todos los panoramas.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="274" />
        <source>Detecting in {} of the {} panoramas: one at least every {} m of the drive, the ones between skipped.</source>
        <translation>Detectando en {} de los {} panoramas: uno al menos cada {} m del recorrido, los intermedios omitidos.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="152" />
        <source>How many views of 80° across the horizon ring has. 8 views overlap by 35°. 6 views overlap by 20° and are turned by 30°, so that their seams ahead and behind fall inside the fore-and-aft views: the detection takes 0.8-0.87 times the time. In single panoramas of five held-out test streets, 6 views found 0.946 of the signs at a precision of 0.988, against 0.948 at 0.982 with 8: they lose a few signs 14-20 px high and a few very close ones that no longer fit whole into one view. Through the whole chain, on three held-out streets with a panorama every 5 m, both rings found all 137 signs, with no false sign and positions within 3 mm of each other in median; on the first 100 m of a test drive with a panorama every 1.2 m, the ring of 6 added one false sign (seen in one panorama and scored just over the minimum confidence, flagged for review) to the 6 true ones. The third choice sees the horizon as one equirectangular band of 3264 × 448 px (8.5 px a degree, ±26° of elevation), which the detector runs on whole: it needs a model whose input size is free, as the bundled detector's is. In single panoramas of fifteen held-out test streets it found 2,632 of 2,778 signs at a precision of 0.976, against 2,638 at 0.968 for the ring of 8, in 0.81 times the processor time; through the whole chain on fourteen held-out streets it found all 632 signs, as the ring does, but with one false sign (a logo printed on a billboard) and three sign codes fewer. 8 by default; 6 and the band trade a little accuracy for speed.</source>
        <translation>Cuántas vistas de 80° de ancho tiene el anillo del horizonte. 8 vistas se solapan 35°. 6 vistas se solapan 20° y están giradas 30°, de modo que sus uniones delante y detrás caen dentro de las vistas hacia delante y hacia atrás: la detección tarda 0,8-0,87 veces el tiempo. En panoramas sueltos de cinco calles de prueba reservadas, 6 vistas encontraron 0,946 de las señales con una precisión de 0,988, frente a 0,948 con 0,982 con 8: pierden algunas señales de 14-20 px de alto y algunas muy cercanas que ya no caben enteras en una vista. En la cadena completa, en tres calles reservadas con un panorama cada 5 m, ambos anillos encontraron las 137 señales, sin ninguna falsa y con posiciones a menos de 3 mm entre sí en la mediana; en los primeros 100 m de un recorrido de prueba con un panorama cada 1,2 m, el anillo de 6 añadió una señal falsa (vista en un solo panorama y puntuada justo por encima de la confianza mínima, marcada para revisión) a las 6 verdaderas. La tercera opción ve el horizonte como una sola banda equirrectangular de 3264 × 448 px (8,5 px por grado, ±26° de elevación), que el detector procesa entera: necesita un modelo cuyo tamaño de entrada sea libre, como el del detector incluido. En panoramas sueltos de quince calles de prueba reservadas encontró 2632 de 2778 señales con una precisión de 0,976, frente a 2638 con 0,968 del anillo de 8, en 0,81 veces el tiempo de procesador; en toda la cadena, en catorce calles reservadas, encontró las 632 señales, como el anillo, pero con una señal falsa (un logotipo impreso en una valla publicitaria) y tres códigos de señal menos. 8 por defecto; 6 y la banda cambian un poco de exactitud por velocidad.</translation>
    </message>
    <message>
        <location filename="../algorithms/detectsigns.py" line="98" />
        <source>Boxes the detector scores from this value up to the minimum confidence get a second look: one is kept when the sign-code classifier reads a class of signs in it with a probability of at least {score} (the probabilities of the codes of that class added up: a speed limit whose digits are unsure is still a prohibitory sign), its box is at least {px} px on its shorter side (under {small_px} px only from a detector score of {small_score}) and at least {share:.0%} of it is sign colours (saturated red, blue or yellow); it then takes that class and keeps its own score. On real street photographs (GTSDB 500-599) at the default minimum confidence this finds 0.958 of the signs at a precision of 0.971, against 0.803 at 0.966 without it, for under 5 % of the detection time. The second look also drops any box the classifier reads as the back of a sign (a plain grey plate facing away: its face is seen from the stations on the other side). Needs the sign codes to be read; a value at or above the minimum confidence switches it off.</source>
        <translation>Los recuadros que el detector puntúa desde este valor hasta la confianza mínima reciben una segunda mirada: se conserva uno cuando el clasificador de códigos de señal lee en él una clase de señales con una probabilidad de al menos {score} (las probabilidades de los códigos de esa clase sumadas: un límite de velocidad cuyas cifras no son seguras sigue siendo una señal de prohibición), su recuadro mide al menos {px} px en su lado más corto (por debajo de {small_px} px, solo con una puntuación del detector de al menos {small_score}) y al menos un {share:.0%} de él son colores de señal (rojo, azul o amarillo saturados); entonces toma esa clase y conserva su propia puntuación. En fotografías reales de calles (GTSDB 500-599), con la confianza mínima por defecto, encuentra 0,958 de las señales con una precisión de 0,971, frente a 0,803 con 0,966 sin ella, por menos de un 5 % del tiempo de detección. La segunda mirada también descarta cualquier recuadro que el clasificador lea como el reverso de una señal (una placa gris lisa vuelta de espaldas: su cara se ve desde las estaciones del otro lado). Necesita que se lean los códigos de señal; un valor igual o superior a la confianza mínima la desactiva.</translation>
    </message>
</context>
<context>
    <name>Evaluate</name>
    <message>
        <location filename="../algorithms/evaluate.py" line="106" />
        <source>Evaluate signs against reference</source>
        <translation>Evaluar señales frente a la referencia</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="109" />
        <source>Scores a sign layer against reference sign panels and writes an HTML report.</source>
        <translation>Puntúa una capa de señales frente a paneles de referencia y escribe un informe HTML.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="134" />
        <source>True positives (matched signs)</source>
        <translation>Verdaderos positivos (señales emparejadas)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="134" />
        <source>False positives (unmatched signs)</source>
        <translation>Falsos positivos (señales sin pareja)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="135" />
        <source>False negatives (missed reference panels)</source>
        <translation>Falsos negativos (paneles de referencia no detectados)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="135" />
        <source>Precision</source>
        <translation>Precisión</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="136" />
        <source>Recall</source>
        <translation>Exhaustividad (recall)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="136" />
        <source>F1 score</source>
        <translation>Puntuación F1</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="137" />
        <source>Class accuracy of matches</source>
        <translation>Exactitud de clase de los emparejamientos</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="138" />
        <source>Median 3D position error (m)</source>
        <translation>Mediana del error de posición 3D (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="139" />
        <source>95th percentile 3D error (m)</source>
        <translation>Percentil 95 del error 3D (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="140" />
        <source>Median height error (m)</source>
        <translation>Mediana del error de altura (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="141" />
        <source>Median azimuth error (°)</source>
        <translation>Mediana del error de acimut (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="147" />
        <source>Median horizontal position error (m)</source>
        <translation>Mediana del error de posición horizontal (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="148" />
        <source>Median vertical position error (m)</source>
        <translation>Mediana del error de posición vertical (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="209" />
        <source>Sign layer</source>
        <translation>Capa de señales</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Reference signs (CSV or point layer)</source>
        <translation>Señales de referencia (CSV o capa de puntos)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Reference signs (*.csv *.txt *.gpkg *.shp *.geojson);;All files (*.*)</source>
        <translation>Señales de referencia (*.csv *.txt *.gpkg *.shp *.geojson);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="163" />
        <source>Match radius (m)</source>
        <translation>Radio de emparejamiento (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="163" />
        <source>A sign and a reference panel farther apart than this (3D distance between panel centres, metres) are never matched.</source>
        <translation>Una señal y un panel de referencia separados más que esto (distancia 3D entre los centros de los paneles, en metros) nunca se emparejan.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>Evaluation report</source>
        <translation>Informe de evaluación</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>HTML files (*.html)</source>
        <translation>Archivos HTML (*.html)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="167" />
        <source>HTML report: the summary and one row per sign and reference panel.</source>
        <translation>Informe HTML: el resumen y una fila por señal y por panel de referencia.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="178" />
        <source>Reference file not found: {}</source>
        <translation>No se encontró el archivo de referencia: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="180" />
        <source>Reference CSV {}: coordinates taken in the sign layer's CRS ({})</source>
        <translation>CSV de referencia {}: coordenadas tomadas en el SRC de la capa de señales ({})</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="191" />
        <source>Cannot read the reference {}: expected a CSV or a point layer</source>
        <translation>No se puede leer la referencia {}: se esperaba un CSV o una capa de puntos</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="195" />
        <source>Reprojecting the reference from {} to {}</source>
        <translation>Reproyectando la referencia de {} a {}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="212" />
        <source>The sign layer is empty: nothing to evaluate.</source>
        <translation>La capa de señales está vacía: no hay nada que evaluar.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="216" />
        <source>The reference {} has no sign: nothing to evaluate against.</source>
        <translation>La referencia {} no tiene ninguna señal: no hay nada con qué comparar.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="222" />
        <source>Road sign evaluation</source>
        <translation>Evaluación de señales viales</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="229" />
        <source>{} signs, {} reference panels: TP {}, FP {}, FN {}; precision {}, recall {}, median error {} m</source>
        <translation>{} señales, {} paneles de referencia: TP {}, FP {}, FN {}; precisión {}, exhaustividad {}, mediana del error {} m</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="144" />
        <source>Code accuracy of matches with a reference code</source>
        <translation>Exactitud de código de los emparejamientos con código de referencia</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="145" />
        <source>Matches whose codes were compared</source>
        <translation>Emparejamientos cuyos códigos se compararon</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="146" />
        <source>Compared matches whose sign has no code</source>
        <translation>Emparejamientos comparados cuya señal no tiene código</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="152" />
        <source>The sign layer to score (PointZ at the panel centres, e.g. the output of Refine signs), with the fields sign_id, class and optionally height, azimuth, best_image, code.</source>
        <translation>La capa de señales que se puntúa (PointZ en los centros de los paneles, p. ej. la salida de «Refinar y fusionar señales»), con los campos sign_id, class y opcionalmente height, azimuth, best_image, code.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="157" />
        <source>Ground truth: a CSV sign_id,class,x,y,z,height,width,panel_height,azimuth (and optionally code) in the sign layer's CRS, or a point layer with those fields (reprojected if its CRS differs).</source>
        <translation>Verdad de terreno: un CSV sign_id,class,x,y,z,height,width,panel_height,azimuth (y opcionalmente code) en el SRC de la capa de señales, o una capa de puntos con esos campos (reproyectada si su SRC es distinto).</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="173" />
        <source>Code confusions (reference code -&gt; sign code: count)</source>
        <translation>Confusiones de código (código de referencia -&gt; código de la señal: número)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="235" />
        <source>Code accuracy {} of {} matches with a reference code ({} without a code); confusions: {}</source>
        <translation>Exactitud de código {} en {} emparejamientos con código de referencia ({} sin código); confusiones: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="235" />
        <source>none</source>
        <translation>ninguna</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="112" />
        <source>Matches each sign to at most one reference panel by optimal assignment (Hungarian method) on the 3D distance between panel centres, within the match radius and ignoring class, then reports precision (matches / signs), recall (matches / reference panels), F1, the class accuracy of the matches, and the median and 95th percentile position error, the median height error, the median azimuth error, and the median and 95th percentile panel size error (the larger of the width and panel height errors, where the layers have the fields width and panel_height).&lt;br&gt;&lt;br&gt;When the reference has a &lt;i&gt;code&lt;/i&gt; column and the sign layer a &lt;i&gt;code&lt;/i&gt; field (OpenStreetMap traffic_sign codes such as DE:274[50]), it also reports the code accuracy of the matches whose reference code is not empty (a sign without a code counts as wrong, and is counted as no code) and the code confusions, most frequent first.&lt;br&gt;&lt;br&gt;The &lt;b&gt;reference&lt;/b&gt; is a CSV &lt;i&gt;sign_id,class,x,y,z,height,width,panel_height,azimuth&lt;/i&gt; (and optionally &lt;i&gt;code&lt;/i&gt;) in the sign layer's CRS, or a point layer with those fields (reprojected to the sign layer's CRS).&lt;br&gt;&lt;br&gt;The HTML report has the summary and one row per sign: matched (with its errors), missed or false.</source>
        <translation>Empareja cada señal con como máximo un panel de referencia mediante asignación óptima (método húngaro) según la distancia 3D entre los centros de los paneles, dentro del radio de emparejamiento y sin tener en cuenta la clase; después informa de la precisión (emparejamientos / señales), la exhaustividad (emparejamientos / paneles de referencia), F1, la exactitud de clase de los emparejamientos, la mediana y el percentil 95 del error de posición, la mediana del error de altura, la mediana del error de acimut, y la mediana y el percentil 95 del error de tamaño del panel (el mayor de los errores de anchura y de altura del panel, cuando las capas tienen los campos width y panel_height).&lt;br&gt;&lt;br&gt;Cuando la referencia tiene una columna &lt;i&gt;code&lt;/i&gt; y la capa de señales un campo &lt;i&gt;code&lt;/i&gt; (códigos traffic_sign de OpenStreetMap como DE:274[50]), también informa de la exactitud de código de los emparejamientos cuyo código de referencia no está vacío (una señal sin código cuenta como errónea y se contabiliza como sin código) y de las confusiones de código, de la más frecuente a la menos frecuente.&lt;br&gt;&lt;br&gt;La &lt;b&gt;referencia&lt;/b&gt; es un CSV &lt;i&gt;sign_id,class,x,y,z,height,width,panel_height,azimuth&lt;/i&gt; (y opcionalmente &lt;i&gt;code&lt;/i&gt;) en el SRC de la capa de señales, o una capa de puntos con esos campos (reproyectada al SRC de la capa de señales).&lt;br&gt;&lt;br&gt;El informe HTML contiene el resumen y una fila por señal: emparejada (con sus errores), no detectada o falsa.</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="142" />
        <source>Median panel size error (m)</source>
        <translation>Mediana del error de tamaño del panel (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/evaluate.py" line="143" />
        <source>95th percentile panel size error (m)</source>
        <translation>Percentil 95 del error de tamaño del panel (m)</translation>
    </message>
</context>
<context>
    <name>ExportHandover</name>
    <message>
        <location filename="../algorithms/exporthandover.py" line="49" />
        <source>Export handover package</source>
        <translation>Exportar paquete de entrega</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="52" />
        <source>The reviewed sign layer as a GeoPackage, a CSV and an OpenStreetMap file for handover.</source>
        <translation>La capa de señales revisada como GeoPackage, CSV y archivo de OpenStreetMap para la entrega.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="55" />
        <source>Writes the signs with the review states you choose (default: accepted and corrected) into a folder: &lt;i&gt;handover.gpkg&lt;/i&gt; and &lt;i&gt;handover.csv&lt;/i&gt; with one row per sign in a documented schema (docs/formats.md, section 4.9), and &lt;i&gt;osm_signs.osm&lt;/i&gt; (or .geojson) for OpenStreetMap.&lt;br&gt;&lt;br&gt;Each sign gets its code and class (after review), its position (x, y, z and WGS 84 longitude and latitude), mounting height, panel size, the azimuth its face looks towards (0-359, from true or grid north as chosen; the column azimuth_north says which), the side of the road and the lateral offset relative to the drive, the chainage along the drive (the stations' track), the nearest road segment's id and the fraction along it when a road network is given, condition and pole when the layer has them, survey date, first and last seen, source images and review status.&lt;br&gt;&lt;br&gt;The OpenStreetMap nodes carry &lt;i&gt;traffic_sign&lt;/i&gt; (the code, prefixed with the country) and &lt;i&gt;direction&lt;/i&gt; (true north) and stand beside the road: a sign over the road is moved to its side of the drive.</source>
        <translation>Escribe en una carpeta las señales con los estados de revisión que elija (por defecto: aceptadas y corregidas): &lt;i&gt;handover.gpkg&lt;/i&gt; y &lt;i&gt;handover.csv&lt;/i&gt;, con una fila por señal en un esquema documentado (docs/formats.md, sección 4.9), y &lt;i&gt;osm_signs.osm&lt;/i&gt; (o .geojson) para OpenStreetMap.&lt;br&gt;&lt;br&gt;Cada señal lleva su código y clase (tras la revisión), su posición (x, y, z y longitud y latitud WGS 84), la altura de montaje, el tamaño del panel, el azimut hacia el que mira su cara (0-359, desde el norte verdadero o el de cuadrícula, según se elija; la columna azimuth_north indica cuál), el lado de la carretera y el desplazamiento lateral respecto al recorrido, el PK a lo largo del recorrido (el trayecto de las estaciones), el id del tramo de carretera más cercano y la fracción a lo largo de él cuando se da una red viaria, el estado y el poste cuando la capa los tiene, la fecha del levantamiento, la primera y la última vez que se vio, las imágenes de origen y el estado de revisión.&lt;br&gt;&lt;br&gt;Los nodos de OpenStreetMap llevan &lt;i&gt;traffic_sign&lt;/i&gt; (el código, precedido del país) y &lt;i&gt;direction&lt;/i&gt; (norte verdadero) y quedan junto a la carretera: una señal sobre la calzada se desplaza a su lado del recorrido.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="145" />
        <source>Reviewed sign layer</source>
        <translation>Capa de señales revisada</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="70" />
        <source>The sign layer after review (fields review_status, reviewed_code... as the review panel writes them), in a projected CRS.</source>
        <translation>La capa de señales tras la revisión (campos review_status, reviewed_code... tal como los escribe el panel de revisión), en un SRC proyectado.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="152" />
        <source>Panorama stations</source>
        <translation>Estaciones de panorama</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="74" />
        <source>The output of Import trajectory for the same drive: its track gives side, offset and chainage, its times first and last seen.</source>
        <translation>La salida de Importar trayectoria del mismo recorrido: su trayecto da el lado, el desplazamiento y el PK; sus tiempos, la primera y la última vez que se vio cada señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="78" />
        <source>Road network (optional)</source>
        <translation>Red viaria (opcional)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="78" />
        <source>Road segments (lines): each sign gets the nearest one's id and the fraction along it. Lines in another CRS are reprojected.</source>
        <translation>Tramos de carretera (líneas): cada señal recibe el id del más cercano y la fracción a lo largo de él. Las líneas en otro SRC se reproyectan.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="82" />
        <source>Road segment id field</source>
        <translation>Campo de id del tramo</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="82" />
        <source>The road network's field holding the segment ids; empty: the feature id.</source>
        <translation>El campo de la red viaria con los ids de los tramos; vacío: el id de la entidad.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>Review states to hand over</source>
        <translation>Estados de revisión a entregar</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>accepted</source>
        <translation>aceptada</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>corrected (accepted with a new class or code)</source>
        <translation>corregida (aceptada con otra clase o código)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>rejected</source>
        <translation>rechazada</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>needs another look</source>
        <translation>hay que volver a mirarla</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>not reviewed</source>
        <translation>sin revisar</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="85" />
        <source>Only signs with these review states are written (several may be chosen).</source>
        <translation>Solo se escriben las señales con estos estados de revisión (se pueden elegir varios).</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>Azimuth from</source>
        <translation>Azimut desde</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>true north</source>
        <translation>norte verdadero</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>grid north</source>
        <translation>norte de cuadrícula</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="91" />
        <source>The facing azimuth is written clockwise from true north (grid azimuth plus meridian convergence) or from grid north of the layer's CRS; the file says which.</source>
        <translation>El azimut de la cara se escribe en sentido horario desde el norte verdadero (azimut de cuadrícula más la convergencia de meridianos) o desde el norte de cuadrícula del SRC de la capa; el archivo indica cuál.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="95" />
        <source>Survey date (YYYY-MM-DD)</source>
        <translation>Fecha del levantamiento (AAAA-MM-DD)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="95" />
        <source>The date of the drive: with station times in GPS seconds of the week, first and last seen become dates and times (UTC).</source>
        <translation>La fecha del recorrido: con tiempos de estación en segundos GPS de la semana, la primera y la última vez que se vio pasan a ser fechas y horas (UTC).</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>Station times are</source>
        <translation>Los tiempos de las estaciones son</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>GPS seconds of the week</source>
        <translation>segundos GPS de la semana</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>GPS time (seconds since 1980-01-06)</source>
        <translation>tiempo GPS (segundos desde 1980-01-06)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>UNIX time (seconds since 1970-01-01 UTC)</source>
        <translation>tiempo UNIX (segundos desde 1970-01-01 UTC)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="99" />
        <source>The time base of the stations' time field (that of the trajectory).</source>
        <translation>La base de tiempo del campo time de las estaciones (la de la trayectoria).</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="122" />
        <source>OpenStreetMap file</source>
        <translation>Archivo de OpenStreetMap</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>OSM XML (.osm, opens in JOSM)</source>
        <translation>OSM XML (.osm, se abre en JOSM)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>GeoJSON (.geojson)</source>
        <translation>GeoJSON (.geojson)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="105" />
        <source>The format of the OpenStreetMap nodes file.</source>
        <translation>El formato del archivo de nodos de OpenStreetMap.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="109" />
        <source>Country prefix for traffic_sign</source>
        <translation>Prefijo de país para traffic_sign</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="109" />
        <source>ISO country code written before codes without one: DE gives traffic_sign=DE:206.</source>
        <translation>Código ISO de país que se antepone a los códigos que no lo tienen: DE da traffic_sign=DE:206.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="112" />
        <source>Least distance of OSM nodes from the road (m)</source>
        <translation>Distancia mínima de los nodos OSM a la carretera (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="112" />
        <source>OpenStreetMap nodes closer than this to the drive (or to the nearest road line) are moved away from it on the sign's side, so that no sign node sits on the road.</source>
        <translation>Los nodos de OpenStreetMap más cercanos que esto al recorrido (o a la línea de carretera más próxima) se alejan de él por el lado de la señal, para que ningún nodo de señal quede sobre la calzada.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="117" />
        <source>Handover folder</source>
        <translation>Carpeta de entrega</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="117" />
        <source>The folder the package is written to (created when missing; files of an earlier package are replaced).</source>
        <translation>La carpeta donde se escribe el paquete (se crea si no existe; los archivos de un paquete anterior se reemplazan).</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="120" />
        <source>Handover GeoPackage</source>
        <translation>GeoPackage de entrega</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="121" />
        <source>Handover CSV</source>
        <translation>CSV de entrega</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="135" />
        <source>Choose at least one review state to hand over.</source>
        <translation>Elija al menos un estado de revisión para entregar.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="141" />
        <source>The sign layer has no CRS: set its projected CRS (layer properties) and run again.</source>
        <translation>La capa de señales no tiene SRC: asígnele su SRC proyectado (propiedades de la capa) y vuelva a ejecutar.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="143" />
        <source>The sign layer</source>
        <translation>La capa de señales</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="149" />
        <source>The stations are in {}, the sign layer in {}: use the stations of the drive the signs come from</source>
        <translation>Las estaciones están en {}, la capa de señales en {}: use las estaciones del recorrido del que proceden las señales</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="175" />
        <source>Handover package: {} signs in {}</source>
        <translation>Paquete de entrega: {} señales en {}</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="185" />
        <source>Survey date '{}' is not a date: write it as YYYY-MM-DD, e.g. 2024-03-14</source>
        <translation>La fecha del levantamiento '{}' no es una fecha: escríbala como AAAA-MM-DD, p. ej. 2024-03-14</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="201" />
        <source>Sign {} has neither a point geometry nor x and y fields</source>
        <translation>La señal {} no tiene ni geometría de punto ni campos x e y</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="215" />
        <source>The road network has no field {}; fields found: {}</source>
        <translation>La red viaria no tiene el campo {}; campos encontrados: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="220" />
        <source>The road network is in {}: reprojected to {}, the sign layer's CRS.</source>
        <translation>La red viaria está en {}: reproyectada a {}, el SRC de la capa de señales.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="223" />
        <source>No road segment id field chosen: the road ids are the feature ids.</source>
        <translation>No se eligió campo de id de tramo: los ids de carretera son los ids de las entidades.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="239" />
        <source>The road network has no lines: road_id and road_fraction stay empty.</source>
        <translation>La red viaria no tiene líneas: road_id y road_fraction quedan vacíos.</translation>
    </message>
    <message>
        <location filename="../algorithms/exporthandover.py" line="258" />
        <source>Cannot write {}: {}</source>
        <translation>No se puede escribir {}: {}</translation>
    </message>
</context>
<context>
    <name>FindSignsInCloud</name>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="24" />
        <source>Find signs in the point cloud (no images)</source>
        <translation>Buscar señales en la nube de puntos (sin imágenes)</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="27" />
        <source>Finds retro-reflective sign panels and their poles in the LiDAR cloud alone, and flags faded sheeting.</source>
        <translation>Encuentra los paneles de señal retrorreflectantes y sus postes solo en la nube LiDAR, y marca las láminas retrorreflectantes deterioradas.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="31" />
        <source>Finds sign panels from the point cloud alone, after the Utah I-15 mobile-LiDAR method (Ai and Tsai): the drive's track (the panorama stations) locates every point along the road; points above the ground (class 2) and beside or above the road are kept; their intensity is normalised for range and incidence angle; a threshold adapted to the cloud (stated in the log) picks the retro-reflective sheeting; planar clusters of sign size and shape at sign heights become panels, each with the pole or gantry that carries it. The cloud is read once and worked through in windows of drive, so memory does not grow with the drive.&lt;br&gt;&lt;br&gt;Outputs: the sign panels (PointZ at the panel centre: size, face normal and azimuth, height above the ground, intensity statistics, the retroreflectivity index and a &lt;b&gt;condition&lt;/b&gt; of good, check or poor), their outlines (PolygonZ), and the poles (sign poles, light poles, gantry posts: foot, height, diameter, lean and the signs each carries).&lt;br&gt;&lt;br&gt;&lt;b&gt;Condition&lt;/b&gt; is a screening flag, not a measurement: the retroreflectivity index is the median normalised intensity of the panel's face, compared with the drive's own healthy signs. It is not the coefficient of retroreflection of the MUTCD (observation angle 0.2°, entrance angle −4°): confirm flagged signs in the field. The cloud needs an intensity dimension and ground points (run Ground filter first).</source>
        <translation>Encuentra paneles de señal solo a partir de la nube de puntos, siguiendo el método de LiDAR móvil de la I-15 de Utah (Ai y Tsai): el trayecto del recorrido (las estaciones de panorama) sitúa cada punto a lo largo de la vía; se conservan los puntos por encima del suelo (clase 2) y junto a la vía o sobre ella; su intensidad se normaliza según la distancia y el ángulo de incidencia; un umbral adaptado a la nube (indicado en el registro) selecciona las láminas retrorreflectantes; los grupos planos con el tamaño y la forma de una señal, a la altura de las señales, se convierten en paneles, cada uno con el poste o pórtico que lo sostiene. La nube se lee una sola vez y se procesa por ventanas del recorrido, de modo que la memoria no crece con la longitud del recorrido.&lt;br&gt;&lt;br&gt;Salidas: los paneles de señal (PointZ en el centro del panel: tamaño, normal y acimut de la cara, altura sobre el suelo, estadísticas de intensidad, el índice de retrorreflexión y un &lt;b&gt;estado&lt;/b&gt; (condition): good, check o poor), sus contornos (PolygonZ) y los postes (postes de señal, postes de alumbrado, postes de pórtico: pie, altura, diámetro, inclinación y las señales que sostiene cada uno).&lt;br&gt;&lt;br&gt;El &lt;b&gt;estado&lt;/b&gt; es un indicador de cribado, no una medición: el índice de retrorreflexión es la mediana de la intensidad normalizada de la cara del panel, comparada con las señales en buen estado del propio recorrido. No es el coeficiente de retrorreflexión del MUTCD (ángulo de observación 0,2°, ángulo de entrada −4°): confirme en campo las señales marcadas. La nube necesita una dimensión de intensidad y puntos de suelo (ejecute antes «Filtro de suelo y recorte de nube de puntos»).</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="50" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>Nube de puntos con suelo clasificado (LAS/LAZ)</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="50" />
        <source>The cloud with ground as class 2 (the output of Ground filter) and an intensity dimension, in the stations' CRS.</source>
        <translation>La nube con el suelo como clase 2 (la salida de «Filtro de suelo y recorte de nube de puntos») y una dimensión de intensidad, en el SRC de las estaciones.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="87" />
        <source>Panorama stations</source>
        <translation>Estaciones de panorama</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="54" />
        <source>The output of Import trajectory: the drive's track (positions and times).</source>
        <translation>La salida de «Importar trayectoria y panoramas»: el trayecto del recorrido (posiciones y tiempos).</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="57" />
        <source>Corridor half-width (m)</source>
        <translation>Semiancho del corredor (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="57" />
        <source>Signs are searched this far to each side of the track, in metres.</source>
        <translation>Las señales se buscan hasta esta distancia a cada lado del trayecto, en metros.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="61" />
        <source>Sign panels found in the cloud</source>
        <translation>Paneles de señal encontrados en la nube</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="61" />
        <source>PointZ layer, one point per panel centre, with its size, face normal and azimuth, heights, intensity statistics, retroreflectivity index, condition and support.</source>
        <translation>Capa PointZ, un punto por centro de panel, con su tamaño, normal y acimut de la cara, alturas, estadísticas de intensidad, índice de retrorreflexión, estado y soporte.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="65" />
        <source>Panel outlines</source>
        <translation>Contornos de los paneles</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="65" />
        <source>PolygonZ layer of each panel's rectangle in its plane.</source>
        <translation>Capa PolygonZ con el rectángulo de cada panel en su plano.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="68" />
        <source>Poles</source>
        <translation>Postes</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="68" />
        <source>PointZ layer, one point per pole foot: kind (sign_pole, light_pole, gantry, other), height, diameter, lean and the ids of the signs it carries.</source>
        <translation>Capa PointZ, un punto por pie de poste: tipo (sign_pole, light_pole, gantry, other), altura, diámetro, inclinación y los identificadores de las señales que sostiene.</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="72" />
        <source>Sign panels found</source>
        <translation>Paneles de señal encontrados</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="73" />
        <source>Poles found</source>
        <translation>Postes encontrados</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="86" />
        <source>The stations</source>
        <translation>La capa de estaciones</translation>
    </message>
    <message>
        <location filename="../algorithms/findsignsincloud.py" line="118" />
        <source>{} sign panels and {} poles found in the cloud.</source>
        <translation>{} paneles de señal y {} postes encontrados en la nube.</translation>
    </message>
</context>
<context>
    <name>FuseSigns</name>
    <message>
        <location filename="../algorithms/fusesigns.py" line="33" />
        <source>Fuse image and cloud signs</source>
        <translation>Fusionar señales de imagen y de nube</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="36" />
        <source>Merges the signs found in the images with the panels found in the cloud alone: one sign layer that says which sources found each sign.</source>
        <translation>Fusiona las señales encontradas en las imágenes con los paneles encontrados solo en la nube: una capa de señales que indica qué fuentes encontraron cada señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="111" />
        <source>Signs (from the images)</source>
        <translation>Señales (de las imágenes)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="57" />
        <source>The output of Refine and merge signs.</source>
        <translation>La salida de «Refinar y fusionar señales».</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="113" />
        <source>Sign panels found in the cloud</source>
        <translation>Paneles de señal encontrados en la nube</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="60" />
        <source>The output of Find signs in the point cloud.</source>
        <translation>La salida de «Buscar señales en la nube de puntos (sin imágenes)».</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="63" />
        <source>Panorama stations (to classify panels found in the cloud alone)</source>
        <translation>Estaciones de panorama (para clasificar los paneles encontrados solo en la nube)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="63" />
        <source>The output of Import trajectory. With the panorama folder, the class of each panel no image sign explains is read from the panoramas in front of it.</source>
        <translation>La salida de «Importar trayectoria y panoramas». Con la carpeta de panoramas, la clase de cada panel que ninguna señal de imagen explica se lee de los panoramas situados frente a él.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="68" />
        <source>Panorama folder (optional)</source>
        <translation>Carpeta de panoramas (opcional)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="68" />
        <source>The folder of the panoramas (empty: the paths in the stations layer).</source>
        <translation>La carpeta de los panoramas (vacía: las rutas de la capa de estaciones).</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>ONNX model (empty: the bundled model)</source>
        <translation>Modelo ONNX (vacío: el modelo incluido)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>The detector that reads the class of panels found in the cloud alone.</source>
        <translation>El detector que lee la clase de los paneles encontrados solo en la nube.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="72" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>Modelos ONNX (*.onnx);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="76" />
        <source>Minimum confidence</source>
        <translation>Confianza mínima</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="76" />
        <source>A class read from the panoramas is kept when the detector scores it at least this (0-1).</source>
        <translation>Una clase leída de los panoramas se conserva si el detector le da una puntuación de al menos este valor (0-1).</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="80" />
        <source>Match radius (m)</source>
        <translation>Radio de emparejamiento (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="80" />
        <source>An image sign and a cloud panel farther apart than this (3D, metres) are never the same sign.</source>
        <translation>Una señal de imagen y un panel de la nube separados más que esto (3D, metros) nunca son la misma señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="92" />
        <source>Signs (fused)</source>
        <translation>Señales (fusionadas)</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="92" />
        <source>PointZ sign layer: the sign fields, and source (image, lidar, image+lidar), review (1: to be checked), image_sign_id, cloud_sign_id, retro_index, condition and the review chip of the image sign (chip, relative to the layer's folder).</source>
        <translation>Capa de señales PointZ: los campos de señal, y source (image, lidar, image+lidar), review (1: por comprobar), image_sign_id, cloud_sign_id, retro_index, condition y la miniatura de revisión de la señal de imagen (chip, relativa a la carpeta de la capa).</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="97" />
        <source>Signs found by both</source>
        <translation>Señales encontradas por ambas fuentes</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="98" />
        <source>Signs found in the images only</source>
        <translation>Señales encontradas solo en las imágenes</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="99" />
        <source>Signs found in the cloud only</source>
        <translation>Señales encontradas solo en la nube</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="117" />
        <source>The signs are in {}, the panels found in the cloud in {}: both must be in the cloud's CRS</source>
        <translation>Las señales están en {} y los paneles encontrados en la nube en {}: ambas capas deben estar en el SRC de la nube</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="128" />
        <source>No stations given: the {} signs found in the cloud alone keep the class unknown.</source>
        <translation>No se indicaron estaciones: las {} señales encontradas solo en la nube conservan la clase unknown.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="144" />
        <source>{} signs: {} found by both, {} in the images only ({} of them where the cloud was searched: score lowered, to review), {} in the cloud only.</source>
        <translation>{} señales: {} encontradas por ambas fuentes, {} solo en las imágenes ({} de ellas donde se buscó en la nube: puntuación reducida, por revisar), {} solo en la nube.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="157" />
        <source>Panorama stations</source>
        <translation>Estaciones de panorama</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="163" />
        <source>ONNX model not found: {}</source>
        <translation>No se encontró el modelo ONNX: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="179" />
        <source>{} of the {} signs found in the cloud alone were recognised in the panoramas; the others keep the class unknown and are to review.</source>
        <translation>{} de las {} señales encontradas solo en la nube se reconocieron en los panoramas; las demás conservan la clase unknown y quedan por revisar.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="40" />
        <source>Matches each sign of the image chain (Refine and merge signs) to at most one panel found in the cloud alone (Find signs in the point cloud) by optimal assignment: centres within the match radius and facings within 90°.&lt;br&gt;&lt;br&gt;A matched sign keeps its class and gains the panel's retroreflectivity index and condition (&lt;i&gt;source&lt;/i&gt; = image+lidar). A panel no image sign explains becomes a sign of its own (&lt;i&gt;source&lt;/i&gt; = lidar): with the stations and the panorama folder, the panoramas in front of its face are cut into views centred on it and the detector reads its class there; if none recognises it, its class is &lt;i&gt;unknown&lt;/i&gt; and it is flagged for review. The sign-code classifier reads its code in a crop around each of those detections, and the views vote as Refine and merge signs votes them (code, code_name, code_score, code_views, code_check). An image sign whose place in the cloud holds no retro-reflective panel loses confidence (its score × 0.6) and is flagged for review (&lt;i&gt;source&lt;/i&gt; = image).&lt;br&gt;&lt;br&gt;Output: the sign layer with the fields of Refine and merge signs plus source, review, image_sign_id, cloud_sign_id, retro_index and condition, styled like the sign layer.</source>
        <translation>Empareja cada señal de la cadena de imágenes («Refinar y fusionar señales») con como máximo un panel encontrado solo en la nube («Buscar señales en la nube de puntos (sin imágenes)») mediante asignación óptima: centros dentro del radio de emparejamiento y orientaciones a menos de 90°.&lt;br&gt;&lt;br&gt;Una señal emparejada conserva su clase y recibe el índice de retrorreflexión y el estado del panel (&lt;i&gt;source&lt;/i&gt; = image+lidar). Un panel que ninguna señal de imagen explica se convierte en una señal propia (&lt;i&gt;source&lt;/i&gt; = lidar): con las estaciones y la carpeta de panoramas, los panoramas situados frente a su cara se recortan en vistas centradas en él y el detector lee allí su clase; si en ninguna se reconoce, su clase es &lt;i&gt;unknown&lt;/i&gt; y se marca para revisión. El clasificador de códigos de señal lee su código en un recorte alrededor de cada una de esas detecciones, y las vistas votan como lo hace «Refinar y fusionar señales» (code, code_name, code_score, code_views, code_check). Una señal de imagen en cuyo lugar de la nube no hay ningún panel retrorreflectante pierde confianza (su puntuación × 0,6) y se marca para revisión (&lt;i&gt;source&lt;/i&gt; = image).&lt;br&gt;&lt;br&gt;Salida: la capa de señales con los campos de «Refinar y fusionar señales» más source, review, image_sign_id, cloud_sign_id, retro_index y condition, con el mismo estilo que la capa de señales.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="84" />
        <source>for each sign found in the cloud alone and recognised in the panoramas, in a crop around each of its detections there</source>
        <translation>para cada señal encontrada solo en la nube y reconocida en los panoramas, en un recorte alrededor de cada una de sus detecciones allí</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="86" />
        <source>Minimum code confidence</source>
        <translation>Confianza mínima de código</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="86" />
        <source>The code voted for a sign found in the cloud alone is kept when its support (its share of the views' weighted vote x the mean probability the classifier gave it, 0-1: the code_score field) is at least this; else the code field stays empty.</source>
        <translation>El código votado para una señal encontrada solo en la nube se conserva cuando su apoyo (su proporción en la votación ponderada de las vistas x la probabilidad media que le dio el clasificador, 0-1: el campo code_score) es al menos este valor; si no, el campo code queda vacío.</translation>
    </message>
    <message>
        <location filename="../algorithms/fusesigns.py" line="184" />
        <source>Sign codes read for {} of them.</source>
        <translation>Códigos de señal leídos para {} de ellas.</translation>
    </message>
</context>
<context>
    <name>GroundFilter</name>
    <message>
        <location filename="../algorithms/groundfilter.py" line="57" />
        <source>Ground filter and crop point cloud</source>
        <translation>Filtro de suelo y recorte de nube de puntos</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="60" />
        <source>Crops a LAS/LAZ cloud and classifies ground (class 2) with CSF or SMRF, PDAL or built-in.</source>
        <translation>Recorta una nube LAS/LAZ y clasifica el suelo (clase 2) con CSF o SMRF, mediante PDAL o el motor integrado.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="97" />
        <source>Point cloud (LAS/LAZ)</source>
        <translation>Nube de puntos (LAS/LAZ)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="97" />
        <source>The mobile-mapping cloud, LAS 1.2-1.4 or LAZ, any size (it is read in chunks).</source>
        <translation>La nube de cartografía móvil, LAS 1.2-1.4 o LAZ, de cualquier tamaño (se lee por bloques).</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="100" />
        <source>Crop layer (optional)</source>
        <translation>Capa de recorte (opcional)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="100" />
        <source>Keep only points inside these polygons, or within the crop buffer of these points or lines (e.g. the panorama stations). Empty keeps the whole cloud.</source>
        <translation>Conserva solo los puntos dentro de estos polígonos, o dentro del búfer de recorte de estos puntos o líneas (p. ej. las estaciones de panorama). Vacío conserva la nube entera.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="104" />
        <source>Crop buffer (m)</source>
        <translation>Búfer de recorte (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="104" />
        <source>Grow the crop geometries by this many metres; needed (&gt; 0) for a point or line layer.</source>
        <translation>Amplía las geometrías de recorte en estos metros; necesario (&gt; 0) para una capa de puntos o de líneas.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>Ground method</source>
        <translation>Método de suelo</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>CSF (cloth simulation)</source>
        <translation>CSF (simulación de tela)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>SMRF (simple morphological filter)</source>
        <translation>SMRF (filtro morfológico simple)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="108" />
        <source>CSF suits roads and gentle terrain; SMRF suits steeper or rougher terrain.</source>
        <translation>CSF es adecuado para calles y terreno suave; SMRF, para terreno más empinado o accidentado.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Engine</source>
        <translation>Motor</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>PDAL</source>
        <translation>PDAL</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Built-in</source>
        <translation>Integrado</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="119" />
        <source>Ground distance threshold (m)</source>
        <translation>Umbral de distancia al suelo (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="119" />
        <source>Points within this height of the ground surface are ground (PDAL's threshold option). PDAL's default is 0.5 m; 0.2 m suits dense mobile-mapping clouds, where it keeps the lowest parts of cars, walls and street furniture off the ground class.</source>
        <translation>Los puntos a menos de esta altura de la superficie del suelo son suelo (opción threshold de PDAL). El valor por defecto de PDAL es 0,5 m; 0,2 m es adecuado para nubes densas de cartografía móvil, en las que deja fuera de la clase suelo las partes más bajas de coches, muros y mobiliario urbano.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="125" />
        <source>Cloth resolution / cell size (m)</source>
        <translation>Resolución de la tela / tamaño de celda (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="125" />
        <source>CSF's cloth resolution or SMRF's cell size, in metres (PDAL's default: 1 m).</source>
        <translation>Resolución de la tela de CSF o tamaño de celda de SMRF, en metros (valor por defecto de PDAL: 1 m).</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="129" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>SRC de la nube (si el archivo no tiene)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="129" />
        <source>The cloud's CRS if the file does not record one; a CRS in the file is replaced by it. The CRS is never guessed.</source>
        <translation>El SRC de la nube si el archivo no registra ninguno; un SRC presente en el archivo se sustituye por este. El SRC nunca se adivina.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="133" />
        <source>Reset existing classes</source>
        <translation>Restablecer las clases existentes</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="133" />
        <source>Set every non-ground point to class 1 (unclassified) instead of keeping its class.</source>
        <translation>Asigna la clase 1 (sin clasificar) a todos los puntos que no son suelo en lugar de conservar su clase.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>Ground-classified cloud</source>
        <translation>Nube con suelo clasificado</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>LAZ (*.laz);;LAS (*.las)</source>
        <translation>LAZ (*.laz);;LAS (*.las)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="148" />
        <source>Engine that ran</source>
        <translation>Motor utilizado</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="149" />
        <source>Points read</source>
        <translation>Puntos leídos</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="150" />
        <source>Points written</source>
        <translation>Puntos escritos</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="151" />
        <source>Ground points</source>
        <translation>Puntos de suelo</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="161" />
        <source>The crop layer holds points or lines: give a crop buffer in metres (&gt; 0) to make a corridor around them</source>
        <translation>La capa de recorte contiene puntos o líneas: indique un búfer de recorte en metros (&gt; 0) para formar un corredor a su alrededor</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="166" />
        <source>Reprojecting the crop layer from {} to {}</source>
        <translation>Reproyectando la capa de recorte de {} a {}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="268" />
        <source>Engine: {}; method: {}; {} points read, {} written, {} ground</source>
        <translation>Motor: {}; método: {}; {} puntos leídos, {} escritos, {} de suelo</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="172" />
        <source>Cancelled: nothing was written.</source>
        <translation>Cancelado: no se escribió nada.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="181" />
        <source>The crop layer {} has no feature: nothing to crop by. Leave the crop layer empty to process the whole cloud</source>
        <translation>La capa de recorte {} no tiene entidades: no hay nada con qué recortar. Deje vacía la capa de recorte para procesar toda la nube</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="185" />
        <source>The crop layer {} has no geometry (its {} features are empty): nothing to crop by</source>
        <translation>La capa de recorte {} no tiene geometría (sus {} entidades están vacías): no hay nada con qué recortar</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="200" />
        <source>The crop area (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}) does not overlap the point cloud {} (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}): nothing would be kept</source>
        <translation>El área de recorte (x {:.1f} a {:.1f}, y {:.1f} a {:.1f}) no se superpone con la nube de puntos {} (x {:.1f} a {:.1f}, y {:.1f} a {:.1f}): no se conservaría nada</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="213" />
        <source>PDAL said: {}</source>
        <translation>PDAL dijo: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="214" />
        <source>PDAL failed: {}</source>
        <translation>PDAL falló: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="235" />
        <source>The output {} must not be the input file</source>
        <translation>La salida {} no debe ser el archivo de entrada</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="137" />
        <source>Write one tile per input tile</source>
        <translation>Escribir una tesela por cada tesela de entrada</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="257" />
        <source>Writing one tile per input tile to the folder {}, listed in {}</source>
        <translation>Escribiendo una tesela por cada tesela de entrada en la carpeta {}, enumeradas en {}</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Auto (the faster engine: built-in)</source>
        <translation>Automático (el motor más rápido: el integrado)</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="112" />
        <source>Auto: the engine measured faster for the method, today the built-in engine for both (PDAL when the built-in CSF's package is missing). PDAL: its Python bindings or the pdal executable that QGIS has; an error when there is neither.</source>
        <translation>Automático: el motor que resultó más rápido en las mediciones para el método; hoy, el motor integrado para ambos (PDAL cuando falta el paquete del CSF integrado). PDAL: sus enlaces de Python o el ejecutable pdal que tenga QGIS; un error si no hay ninguno de los dos.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="137" />
        <source>Write each input tile to its own file (same name, same header) in a folder named after the output, with a virtual point cloud (.vpc) listing them, instead of one file.</source>
        <translation>Escribe cada tesela de entrada en su propio archivo (mismo nombre, misma cabecera) dentro de una carpeta que lleva el nombre de la salida, con una nube de puntos virtual (.vpc) que las enumera, en lugar de un solo archivo.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="141" />
        <source>The cropped cloud with ground as class 2; LAZ or LAS by the file extension. LAS is about eight times larger (about 30 bytes a point) but needs no compression here nor decompression in the stages that read it next: on a 1 km drive of 38 M points the whole chain ran in 0.84 times the time with a LAS ground cloud. With one tile per input tile: the folder of this name without its extension gets the tiles and &lt;name&gt;.vpc, which is then this output.</source>
        <translation>La nube recortada con el suelo como clase 2; LAZ o LAS según la extensión del archivo. LAS ocupa unas ocho veces más (unos 30 bytes por punto), pero no necesita compresión aquí ni descompresión en las etapas que la leen después: en un recorrido de 1 km con 38 M de puntos, la cadena completa tardó 0,84 veces el tiempo con una nube de suelo LAS. Con una tesela por tesela de entrada: la carpeta con este nombre sin su extensión recibe las teselas y &lt;name&gt;.vpc, que es entonces esta salida.</translation>
    </message>
    <message>
        <location filename="../algorithms/groundfilter.py" line="64" />
        <source>Reads the LAS/LAZ cloud in chunks, keeps the points inside the crop area and classifies ground points as class 2 with the cloth simulation filter (CSF, Zhang et al. 2016) or the simple morphological filter (SMRF, Pingel et al. 2013), with PDAL's parameters (defaults tuned for dense mobile-mapping clouds: 0.2 m threshold, 0.5 m cells; PDAL's own are 0.5 m and 1 m). Other classes are kept unless &lt;i&gt;Reset existing classes&lt;/i&gt; is checked. Every dimension, extra bytes, VLRs, scales and offsets and the CRS are written unchanged.&lt;br&gt;&lt;br&gt;&lt;b&gt;Crop&lt;/b&gt;: polygons (grown by the crop buffer), or points and lines such as the panorama stations or detection rays, buffered into a corridor. The crop layer is reprojected to the cloud's CRS.&lt;br&gt;&lt;br&gt;&lt;b&gt;Engine&lt;/b&gt;: PDAL runs filters.csf / filters.smrf through its Python bindings or the &lt;i&gt;pdal&lt;/i&gt; executable (on PATH, in QGIS's bin folder, or set in Processing ▸ Options ▸ Providers ▸ Road sign inventory), holding the cloud in memory (about 150 bytes a point); the built-in engine runs the same filters in Python, streaming the cloud, so clouds larger than memory work (between its two passes it keeps the points uncompressed on disk beside the output, about 30 bytes a point, so a LAZ is decompressed once). A cloud wider or longer than 512 m (a drive) is classified block by block, the ground surface of one block at a time, so the memory does not grow with the drive; its points are then written grouped by block. &lt;b&gt;Auto picks the built-in engine&lt;/b&gt; for both methods: measured against PDAL 2.9.2 on two cores it was as fast for CSF on 8 M points (within 10 %) and 1.6 times faster on 38 M, and 1.4 to 1.7 times faster for SMRF, in about 300 MB where PDAL took 5.6 GB for 38 M points (bench/README.md). Auto uses PDAL only when the built-in CSF's Python package (cloth-simulation-filter) is missing; the log says which engine ran and why.&lt;br&gt;&lt;br&gt;&lt;b&gt;Tiles&lt;/b&gt;: the input may be one LAS/LAZ file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc); PDAL takes the tiles one by one, each with its neighbours' points around it. They are written to one file, or, with &lt;i&gt;Write one tile per input tile&lt;/i&gt;, each to a file of its own name in a folder named after the output (out/ground.laz gives the folder out/ground), with a virtual point cloud listing them (out/ground/ground.vpc, the output to give the next stages). Each tile is classified with its neighbours' points around it, so the classes at tile edges are those of a run on the whole cloud.</source>
        <translation>Lee la nube LAS/LAZ por bloques, conserva los puntos dentro del área de recorte y clasifica los puntos de suelo como clase 2 con el filtro de simulación de tela (CSF, Zhang et al. 2016) o el filtro morfológico simple (SMRF, Pingel et al. 2013), con los parámetros de PDAL (valores por defecto ajustados para nubes densas de cartografía móvil: umbral de 0,2 m, celdas de 0,5 m; los de PDAL son 0,5 m y 1 m). Las demás clases se conservan salvo que se marque &lt;i&gt;Restablecer las clases existentes&lt;/i&gt;. Todas las dimensiones, los bytes extra, los VLR, las escalas y desplazamientos y el SRC se escriben sin cambios.&lt;br&gt;&lt;br&gt;&lt;b&gt;Recorte&lt;/b&gt;: polígonos (ampliados con el búfer de recorte), o puntos y líneas como las estaciones de panorama o los rayos de detección, convertidos en un corredor mediante un búfer. La capa de recorte se reproyecta al SRC de la nube.&lt;br&gt;&lt;br&gt;&lt;b&gt;Motor&lt;/b&gt;: PDAL ejecuta filters.csf / filters.smrf mediante sus enlaces de Python o el ejecutable &lt;i&gt;pdal&lt;/i&gt; (en el PATH, en la carpeta bin de QGIS o configurado en Procesos ▸ Opciones ▸ Proveedores ▸ Road sign inventory), manteniendo la nube en memoria (unos 150 bytes por punto); el motor integrado ejecuta los mismos filtros en Python, procesando la nube en flujo continuo, por lo que funciona con nubes más grandes que la memoria (entre sus dos pasadas guarda los puntos sin comprimir en el disco junto a la salida, unos 30 bytes por punto, de modo que un LAZ se descomprime una sola vez). Una nube de más de 512 m de ancho o de largo (un recorrido) se clasifica bloque a bloque, con la superficie del terreno de un solo bloque a la vez, de modo que la memoria no crece con el recorrido; sus puntos se escriben entonces agrupados por bloque. &lt;b&gt;Automático elige el motor integrado&lt;/b&gt; para ambos métodos: medido frente a PDAL 2.9.2 con dos núcleos, fue igual de rápido para CSF con 8 M de puntos (con una diferencia inferior al 10 %) y 1,6 veces más rápido con 38 M, y de 1,4 a 1,7 veces más rápido para SMRF, con unos 300 MB, mientras que PDAL ocupó 5,6 GB para 38 M de puntos (bench/README.md). Automático usa PDAL solo cuando falta el paquete de Python del CSF integrado (cloth-simulation-filter); el registro indica qué motor se ejecutó y por qué.&lt;br&gt;&lt;br&gt;&lt;b&gt;Teselas&lt;/b&gt;: la entrada puede ser un archivo LAS/LAZ, una carpeta de teselas LAS/LAZ o una nube de puntos virtual (.vpc); PDAL toma las teselas una a una, cada una con los puntos de sus vecinas a su alrededor. Se escriben en un solo archivo o, con &lt;i&gt;Escribir una tesela por cada tesela de entrada&lt;/i&gt;, cada una en un archivo con su propio nombre dentro de una carpeta que lleva el nombre de la salida (out/ground.laz da la carpeta out/ground), con una nube de puntos virtual que las enumera (out/ground/ground.vpc, la salida que se da a las etapas siguientes). Cada tesela se clasifica con los puntos de sus vecinas a su alrededor, de modo que las clases en los bordes de las teselas son las de una ejecución sobre la nube entera.</translation>
    </message>
</context>
<context>
    <name>ImportTrajectory</name>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="31" />
        <source>Import trajectory and panoramas</source>
        <translation>Importar trayectoria y panoramas</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="34" />
        <source>Trajectory (CSV or SBET) and image times, or per-image poses, to panorama stations with full pose.</source>
        <translation>Trayectoria (CSV o SBET) y tiempos de imagen, o poses por imagen, a estaciones de panorama con pose completa.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="38" />
        <source>Builds the panorama stations: the position and full orientation of every panorama at its exposure, in the target CRS.&lt;br&gt;&lt;br&gt;Give a &lt;b&gt;trajectory&lt;/b&gt; (CSV &lt;i&gt;time,x,y,z,roll,pitch,heading&lt;/i&gt; or an Applanix SBET .out) with an &lt;b&gt;image times&lt;/b&gt; CSV (&lt;i&gt;image,time&lt;/i&gt;), or a &lt;b&gt;per-image pose&lt;/b&gt; CSV (&lt;i&gt;image,x,y,z,roll,pitch,heading[,time]&lt;/i&gt;) instead. Angles are in degrees (radians in an SBET); heading is clockwise from &lt;b&gt;true&lt;/b&gt; north and is turned into a grid heading with the meridian convergence at each station. Positions are interpolated linearly and attitudes by SLERP at the image times.&lt;br&gt;&lt;br&gt;The &lt;b&gt;camera mount&lt;/b&gt; places the panorama on the vehicle: lever arm in metres in the body frame (x forward, y right, z down) and boresight angles in degrees.&lt;br&gt;&lt;br&gt;Output: one point per panorama at its centre, with the quaternion (qw, qx, qy, qz) that maps panorama rays to world East-North-Up, the forward azimuth and the image size read from its header.</source>
        <translation>Construye las estaciones de panorama: la posición y la orientación completa de cada panorama en su exposición, en el SRC de destino.&lt;br&gt;&lt;br&gt;Indique una &lt;b&gt;trayectoria&lt;/b&gt; (CSV &lt;i&gt;time,x,y,z,roll,pitch,heading&lt;/i&gt; o un SBET .out de Applanix) con un CSV de &lt;b&gt;tiempos de imagen&lt;/b&gt; (&lt;i&gt;image,time&lt;/i&gt;), o en su lugar un CSV de &lt;b&gt;poses por imagen&lt;/b&gt; (&lt;i&gt;image,x,y,z,roll,pitch,heading[,time]&lt;/i&gt;). Los ángulos están en grados (radianes en un SBET); el rumbo se mide en sentido horario desde el norte &lt;b&gt;verdadero&lt;/b&gt; y se convierte en rumbo de cuadrícula con la convergencia de meridianos en cada estación. Las posiciones se interpolan linealmente y las actitudes por SLERP en los tiempos de imagen.&lt;br&gt;&lt;br&gt;El &lt;b&gt;montaje de la cámara&lt;/b&gt; sitúa el panorama en el vehículo: brazo de palanca en metros en el sistema del vehículo (x adelante, y derecha, z abajo) y ángulos de boresight en grados.&lt;br&gt;&lt;br&gt;Salida: un punto por panorama en su centro, con el cuaternión (qw, qx, qy, qz) que transforma los rayos del panorama al sistema mundial Este-Norte-Arriba, el acimut de avance y el tamaño de la imagen leído de su cabecera.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory (CSV or SBET)</source>
        <translation>Trayectoria (CSV o SBET)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory CSV with a header time,x,y,z,roll,pitch,heading (comma, semicolon, tab or space separated), or an Applanix SBET (.out, .sbet). Times increase strictly.</source>
        <translation>CSV de trayectoria con la cabecera time,x,y,z,roll,pitch,heading (separado por comas, punto y coma, tabuladores o espacios), o un SBET de Applanix (.out, .sbet). Los tiempos deben aumentar estrictamente.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="54" />
        <source>Trajectory (*.csv *.txt *.out *.sbet);;All files (*.*)</source>
        <translation>Trayectoria (*.csv *.txt *.out *.sbet);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="59" />
        <source>Image times (CSV)</source>
        <translation>Tiempos de imagen (CSV)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="59" />
        <source>CSV image,time: each panorama's file name (relative to the panorama folder) and exposure time, in the trajectory's time base.</source>
        <translation>CSV image,time: el nombre de archivo de cada panorama (relativo a la carpeta de panoramas) y su tiempo de exposición, en la base de tiempo de la trayectoria.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>CSV (*.csv *.txt);;All files (*.*)</source>
        <translation>CSV (*.csv *.txt);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>Per-image poses (CSV, instead of trajectory and image times)</source>
        <translation>Poses por imagen (CSV, en lugar de trayectoria y tiempos de imagen)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="64" />
        <source>CSV image,x,y,z,roll,pitch,heading and optionally time: the vehicle body pose at each exposure. Use instead of a trajectory with image times.</source>
        <translation>CSV image,x,y,z,roll,pitch,heading y opcionalmente time: la pose del vehículo en cada exposición. Úselo en lugar de una trayectoria con tiempos de imagen.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="69" />
        <source>Panorama folder</source>
        <translation>Carpeta de panoramas</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="69" />
        <source>Folder of the equirectangular panoramas (JPEG or PNG, twice as wide as high).</source>
        <translation>Carpeta de los panoramas equirrectangulares (JPEG o PNG, el doble de anchos que de altos).</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="73" />
        <source>Trajectory CRS</source>
        <translation>SRC de la trayectoria</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="73" />
        <source>CRS of the trajectory or pose positions (x = longitude, y = latitude, z = ellipsoidal height for a geographic CRS). Ignored for an SBET, which is always WGS 84.</source>
        <translation>SRC de las posiciones de la trayectoria o de las poses (x = longitud, y = latitud, z = altura elipsoidal para un SRC geográfico). Se ignora para un SBET, que siempre está en WGS 84.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="78" />
        <source>Target CRS (projected)</source>
        <translation>SRC de destino (proyectado)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="78" />
        <source>Projected CRS of the outputs (metres, East-North-Up). A compound CRS with a vertical datum turns ellipsoidal heights into that datum when its geoid grid is installed. Empty: the trajectory CRS if it is projected, else its UTM zone.</source>
        <translation>SRC proyectado de las salidas (metros, Este-Norte-Arriba). Un SRC compuesto con un datum vertical convierte las alturas elipsoidales a ese datum si su malla del geoide está instalada. Vacío: el SRC de la trayectoria si es proyectado; si no, su zona UTM.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="84" />
        <source>Panorama centre relative to the trajectory's reference point, in metres along the body axes: x forward, y right, z down.</source>
        <translation>Centro del panorama respecto al punto de referencia de la trayectoria, en metros a lo largo de los ejes del vehículo: x adelante, y derecha, z abajo.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="86" />
        <source>Lever arm x, forward (m)</source>
        <translation>Brazo de palanca x, adelante (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="87" />
        <source>Lever arm y, right (m)</source>
        <translation>Brazo de palanca y, derecha (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="88" />
        <source>Lever arm z, down (m)</source>
        <translation>Brazo de palanca z, abajo (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="89" />
        <source>Panorama frame relative to the body frame: R_body_from_pano = Rz(yaw) Ry(pitch) Rx(roll), degrees.</source>
        <translation>Sistema del panorama respecto al sistema del vehículo: R_body_from_pano = Rz(yaw) Ry(pitch) Rx(roll), en grados.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="91" />
        <source>Boresight roll (°)</source>
        <translation>Boresight: alabeo (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="92" />
        <source>Boresight pitch (°)</source>
        <translation>Boresight: cabeceo (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="93" />
        <source>Boresight yaw (°)</source>
        <translation>Boresight: guiñada (°)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="94" />
        <source>Skip images outside the trajectory's time span</source>
        <translation>Omitir las imágenes fuera del intervalo de tiempo de la trayectoria</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="94" />
        <source>When checked, images whose time lies outside the trajectory are skipped and counted in the log; otherwise they are an error.</source>
        <translation>Si se marca, las imágenes cuyo tiempo queda fuera de la trayectoria se omiten y se cuentan en el registro; si no, son un error.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="98" />
        <source>Warn about trajectory gaps longer than (s)</source>
        <translation>Avisar de huecos de la trayectoria mayores que (s)</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="98" />
        <source>A warning names images that fall between two trajectory samples further apart than this, in seconds.</source>
        <translation>Una advertencia nombra las imágenes situadas entre dos muestras de la trayectoria separadas más que esto, en segundos.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="102" />
        <source>Fail on a missing or unreadable panorama</source>
        <translation>Fallar ante un panorama que falta o no se puede leer</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="102" />
        <source>When checked, a missing or unreadable panorama is an error; otherwise it is skipped with a warning and counted.</source>
        <translation>Si se marca, un panorama que falta o no se puede leer es un error; si no, se omite con una advertencia y se contabiliza.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="106" />
        <source>Panorama stations</source>
        <translation>Estaciones de panorama</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="106" />
        <source>PointZ layer, one point per panorama at its centre, with the fields station_id, image, path, time, x, y, z, qw, qx, qy, qz, heading, width, height.</source>
        <translation>Capa PointZ, un punto por panorama en su centro, con los campos station_id, image, path, time, x, y, z, qw, qx, qy, qz, heading, width, height.</translation>
    </message>
    <message>
        <location filename="../algorithms/importtrajectory.py" line="145" />
        <source>{} panorama stations written.</source>
        <translation>{} estaciones de panorama escritas.</translation>
    </message>
</context>
<context>
    <name>ProjectDetections</name>
    <message>
        <location filename="../algorithms/projectdetections.py" line="20" />
        <source>Project detections into the point cloud</source>
        <translation>Proyectar detecciones en la nube de puntos</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="23" />
        <source>Finds each detected sign's surface in the LiDAR cloud: one candidate per detection.</source>
        <translation>Encuentra la superficie de cada señal detectada en la nube LiDAR: un candidato por detección.</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="70" />
        <source>Detections</source>
        <translation>Detecciones</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="43" />
        <source>The output of Detect signs: one ray per detection with its box and station pose.</source>
        <translation>La salida de «Detectar señales en panoramas»: un rayo por detección con su recuadro y la pose de la estación.</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="46" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>Nube de puntos con suelo clasificado (LAS/LAZ)</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="46" />
        <source>The cloud with ground as class 2 (the output of Ground filter), in the detections' CRS.</source>
        <translation>La nube con el suelo como clase 2 (la salida de «Filtro de suelo y recorte de nube de puntos»), en el SRC de las detecciones.</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="49" />
        <source>Maximum range (m)</source>
        <translation>Alcance máximo (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="49" />
        <source>Search each frustum up to this distance from the panorama centre, in metres.</source>
        <translation>Busca en cada frustum hasta esta distancia desde el centro del panorama, en metros.</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="56" />
        <source>Sign candidates</source>
        <translation>Candidatos de señal</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="56" />
        <source>PointZ layer, one candidate per detection (no geometry where no surface was found).</source>
        <translation>Capa PointZ, un candidato por detección (sin geometría donde no se encontró superficie).</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="68" />
        <source>The detections</source>
        <translation>Las detecciones</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="90" />
        <source>{} detections: {} with a surface in the cloud, {} without</source>
        <translation>{} detecciones: {} con superficie en la nube, {} sin ella</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="52" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>SRC de la nube (si el archivo no tiene)</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="52" />
        <source>The cloud's CRS when the file records none (it must be the detections' CRS); it overrides a CRS in the file. The CRS is never guessed.</source>
        <translation>El SRC de la nube cuando el archivo no registra ninguno (debe ser el SRC de las detecciones); sustituye al SRC del archivo. El SRC nunca se adivina.</translation>
    </message>
    <message>
        <location filename="../algorithms/projectdetections.py" line="26" />
        <source>For each detection, the viewing frustum of its box (the rays through the box edges, widened by a small margin for calibration error) is searched from the panorama centre out to the maximum range. The non-ground points inside it are clustered and the first dense, near-vertical planar surface along the box-centre ray is taken (the sign, not the wall behind it; poles and convex mirrors are passed over). The cloud is read once (only the tiles under some frustum); the points under the frusta are kept on disk and worked through block by block along the drive, so the memory follows a block, not the drive. Within a block, each detection tests only the small tiles its frustum crosses.&lt;br&gt;&lt;br&gt;Output: one point per detection at the candidate surface, with the detection's fields, the range, the point count, the plane normal (normal_e, normal_n, normal_u), a quality score in 0-1 and a status: &lt;i&gt;ok&lt;/i&gt;, &lt;i&gt;no_points&lt;/i&gt; (nothing in the frustum, e.g. out of the scanner's reach) or &lt;i&gt;no_surface&lt;/i&gt;; those two keep no geometry. The cloud must be ground-classified (run Ground filter first).</source>
        <translation>Para cada detección se recorre el frustum de visión de su recuadro (los rayos por los bordes del recuadro, ampliados con un pequeño margen por el error de calibración) desde el centro del panorama hasta el alcance máximo. Los puntos que no son suelo dentro de él se agrupan y se toma la primera superficie plana densa y casi vertical a lo largo del rayo por el centro del recuadro (la señal, no la pared de detrás; los postes y los espejos convexos se descartan). La nube se lee una sola vez (solo las teselas bajo algún frustum); los puntos bajo los frustums se guardan en disco y se procesan bloque a bloque a lo largo del recorrido, de modo que la memoria depende de un bloque y no del recorrido. Dentro de un bloque, cada detección prueba solo las pequeñas teselas que atraviesa su frustum.&lt;br&gt;&lt;br&gt;Salida: un punto por detección en la superficie candidata, con los campos de la detección, la distancia, el número de puntos, la normal del plano (normal_e, normal_n, normal_u), una puntuación de calidad en 0-1 y un estado: &lt;i&gt;ok&lt;/i&gt;, &lt;i&gt;no_points&lt;/i&gt; (nada en el frustum, p. ej. fuera del alcance del escáner) o &lt;i&gt;no_surface&lt;/i&gt;; estos dos no tienen geometría. La nube debe tener el suelo clasificado (ejecute antes «Filtro de suelo y recorte de nube de puntos»).</translation>
    </message>
</context>
<context>
    <name>ReadsCodes</name>
    <message>
        <location filename="../algorithms/codeparams.py" line="21" />
        <source>Read the sign codes</source>
        <translation>Leer los códigos de señal</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="21" />
        <source>Reads what each sign says (its code, such as DE:206 for stop) with the sign-code classifier: {}. Unchecked, the code fields stay empty. When the bundled classifier is missing, the log says so and no code is read.</source>
        <translation>Lee lo que dice cada señal (su código, como DE:206 para la señal de stop) con el clasificador de códigos de señal: {}. Si se desmarca, los campos de código quedan vacíos. Cuando falta el clasificador incluido, el registro lo indica y no se lee ningún código.</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>Sign-code classifier (empty: the bundled one)</source>
        <translation>Clasificador de códigos de señal (vacío: el incluido)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>ONNX models (*.onnx);;All files (*.*)</source>
        <translation>Modelos ONNX (*.onnx);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>Sign codes table (empty: the bundled one)</source>
        <translation>Tabla de códigos de señal (vacío: la incluida)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>The codes the classifier may answer, with their names and classes: UTF-8 text, semicolon-separated, the header code;name;class (format in models/README.md). Empty uses the bundled table of German codes (models/sign-codes-de.csv).</source>
        <translation>Los códigos que el clasificador puede responder, con sus nombres y clases: texto UTF-8, separado por punto y coma, con la cabecera code;name;class (formato en models/README.md). Vacío usa la tabla incluida de códigos alemanes (models/sign-codes-de.csv).</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="34" />
        <source>CSV files (*.csv *.txt);;All files (*.*)</source>
        <translation>Archivos CSV (*.csv *.txt);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="47" />
        <source>Sign codes are not read (Read the sign codes is off).</source>
        <translation>Los códigos de señal no se leen («Leer los códigos de señal» está desactivado).</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="53" />
        <source>The bundled sign-code classifier {} is missing: no sign code is read.</source>
        <translation>Falta el clasificador de códigos de señal incluido {}: no se lee ningún código de señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="57" />
        <source>Sign-code classifier not found: {}</source>
        <translation>No se encontró el clasificador de códigos de señal: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="60" />
        <source>Sign codes: {}</source>
        <translation>Códigos de señal: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/codeparams.py" line="26" />
        <source>An ONNX classifier of sign crops: float input [N, 3, S, S] (RGB, 0..1), output [N, C], the codes it answers in its metadata 'names' (each in the codes table, 'other', or 'unlisted:' and a class for a sign whose code the table lacks). The format is in models/README.md (section &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;). Empty uses the classifier bundled with the plugin (models/signcodes.onnx).</source>
        <translation>Un clasificador ONNX de recortes de señales: entrada float [N, 3, S, S] (RGB, 0..1), salida [N, C], los códigos que puede responder en sus metadatos 'names' (cada uno en la tabla de códigos, 'other', o bien 'unlisted:' y una clase para una señal cuyo código no está en la tabla). El formato está en models/README.md (sección &lt;i&gt;Sign-code classifier: the format&lt;/i&gt;). Vacío usa el clasificador incluido con el complemento (models/signcodes.onnx).</translation>
    </message>
</context>
<context>
    <name>RefineSigns</name>
    <message>
        <location filename="../algorithms/refinesigns.py" line="47" />
        <source>Refine and merge signs</source>
        <translation>Refinar y fusionar señales</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="50" />
        <source>Merges the views of each sign and refines it in the cloud: the sign layer.</source>
        <translation>Fusiona las vistas de cada señal y la refina en la nube: la capa de señales.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="160" />
        <source>Sign candidates</source>
        <translation>Candidatos de señal</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="89" />
        <source>The output of Project detections.</source>
        <translation>La salida de «Proyectar detecciones en la nube de puntos».</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="92" />
        <source>Ground-classified point cloud (LAS/LAZ)</source>
        <translation>Nube de puntos con suelo clasificado (LAS/LAZ)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="92" />
        <source>The same cloud as for Project detections (ground as class 2).</source>
        <translation>La misma nube que para «Proyectar detecciones en la nube de puntos» (suelo como clase 2).</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="95" />
        <source>Merge radius (m)</source>
        <translation>Radio de fusión (m)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="95" />
        <source>Candidates of the same class closer than this (metres) with agreeing plane normals are taken as one sign.</source>
        <translation>Los candidatos de la misma clase más cercanos que esto (metros) y con normales de plano concordantes se toman como una sola señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="121" />
        <source>Panorama folder (for review chips)</source>
        <translation>Carpeta de panoramas (para las miniaturas de revisión)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="121" />
        <source>The folder of the panoramas (as for Import trajectory). When given, an image chip of each sign is cut from its best panorama for review.</source>
        <translation>La carpeta de los panoramas (como para «Importar trayectoria y panoramas»). Si se indica, se recorta una miniatura de cada señal de su mejor panorama para la revisión.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="129" />
        <source>Signs</source>
        <translation>Señales</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="129" />
        <source>PointZ sign layer at the panel centres (fields in docs/formats.md), and chip: the relative path of the sign's review picture.</source>
        <translation>Capa de señales PointZ en los centros de los paneles (campos en docs/formats.md), y chip: la ruta relativa de la imagen de revisión de la señal.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="133" />
        <source>Panel outlines</source>
        <translation>Contornos de los paneles</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="133" />
        <source>PolygonZ layer of each panel's rectangle in its plane (signs placed from the cloud).</source>
        <translation>Capa PolygonZ con el rectángulo de cada panel en su plano (señales situadas a partir de la nube).</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>Sign points</source>
        <translation>Puntos de las señales</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>LAZ (*.laz);;LAS (*.las)</source>
        <translation>LAZ (*.laz);;LAS (*.las)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="137" />
        <source>A LAS/LAZ file of the points of every sign panel, all dimensions kept.</source>
        <translation>Un archivo LAS/LAZ con los puntos de cada panel de señal, con todas las dimensiones.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>Review report</source>
        <translation>Informe de revisión</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>HTML files (*.html)</source>
        <translation>Archivos HTML (*.html)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="140" />
        <source>An HTML page with every sign's chip and attributes, to confirm signs without opening panoramas (needs the panorama folder).</source>
        <translation>Una página HTML con la miniatura y los atributos de cada señal, para confirmar las señales sin abrir los panoramas (necesita la carpeta de panoramas).</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="158" />
        <source>The candidates</source>
        <translation>Los candidatos</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="193" />
        <source>The review report needs the panorama folder: not written.</source>
        <translation>El informe de revisión necesita la carpeta de panoramas: no se escribió.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="199" />
        <source>{} sign points written to {}</source>
        <translation>{} puntos de señales escritos en {}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="224" />
        <source>{} signs from {} candidates ({})</source>
        <translation>{} señales a partir de {} candidatos ({})</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="234" />
        <source>Review chips need a sign layer written to a file: skipped.</source>
        <translation>Las miniaturas de revisión necesitan una capa de señales escrita en un archivo: se omiten.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="247" />
        <source>Road signs for review</source>
        <translation>Señales viales para revisión</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="249" />
        <source>{} review chips in {}</source>
        <translation>{} miniaturas de revisión en {}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="125" />
        <source>Cloud CRS (when the file has none)</source>
        <translation>SRC de la nube (si el archivo no tiene)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="125" />
        <source>The cloud's CRS when the file records none (it must be the candidates' CRS); it overrides a CRS in the file. The CRS is never guessed.</source>
        <translation>El SRC de la nube cuando el archivo no registra ninguno (debe ser el SRC de los candidatos); sustituye al SRC del archivo. El SRC nunca se adivina.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="165" />
        <source>Panorama folder not found: {}</source>
        <translation>No se encontró la carpeta de panoramas: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="99" />
        <source>Minimum code confidence</source>
        <translation>Confianza mínima de código</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>Sign codes table (empty: the bundled one)</source>
        <translation>Tabla de códigos de señal (vacío: la incluida)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>The codes table the classifier of Detect signs was run with: it gives each code its name (code_name) and its class (for the class check). Format in models/README.md; empty uses the bundled table of German codes (models/sign-codes-de.csv).</source>
        <translation>La tabla de códigos con la que se ejecutó el clasificador de «Detectar señales en panoramas»: da a cada código su nombre (code_name) y su clase (para la comprobación de clase). Formato en models/README.md; vacío usa la tabla incluida de códigos alemanes (models/sign-codes-de.csv).</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="115" />
        <source>CSV files (*.csv *.txt);;All files (*.*)</source>
        <translation>Archivos CSV (*.csv *.txt);;Todos los archivos (*.*)</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="99" />
        <source>A sign's voted code is kept when its support (its share of the views' weighted vote x the mean probability the classifier gave it, 0-1: the code_score field) is at least this; else the code field stays empty. 0 keeps every code but 'other' and 'unlisted:...' (a sign whose code the table lacks).</source>
        <translation>El código votado de una señal se conserva cuando su apoyo (su proporción en la votación ponderada de las vistas x la probabilidad media que le dio el clasificador, 0-1: el campo code_score) es al menos este valor; si no, el campo code queda vacío. 0 conserva todos los códigos salvo 'other' y 'unlisted:...' (una señal cuyo código no está en la tabla).</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="53" />
        <source>Groups the candidates of different panoramas that are the same physical sign (same class, within the merge radius, plane normals agreeing; panels stacked on one pole stay apart), then refines each sign in the cloud: Euclidean clustering, an intensity filter whose threshold adapts to the cloud (Otsu), a near-vertical RANSAC plane and PCA dimensionality to keep the panel and drop the pole.&lt;br&gt;&lt;br&gt;Each sign gets its panel centre, width and panel height, the azimuth its face looks towards (clockwise from grid north), its height above the ground directly below (class-2 points near the sign; the log names any fallback), the bottom height, the number of views and points, the images it was seen in and the best of them (closest, most frontal), the mean intensity and planarity. A sign seen in two or more panoramas but with no cloud points is placed by triangulating its rays (position_source = image).&lt;br&gt;&lt;br&gt;&lt;b&gt;Not signs&lt;/b&gt;, dropped and named in the log: a panel larger than its class allows (a billboard), a curved one (a convex mirror), a picture on a larger flat surface, and a sign seen in one panorama only when its score is under 0.4 or when two or more panoramas nearer to its face, which detected other signs, did not see it (a look-alike boxed once from afar).&lt;br&gt;&lt;br&gt;Optional outputs: panel outlines (PolygonZ) and the sign points (LAS/LAZ).&lt;br&gt;&lt;br&gt;&lt;b&gt;Review&lt;/b&gt;: with the panorama folder, each sign gets an image chip from its best panorama (its box with a margin, undistorted), written into a folder beside the sign layer and linked by the &lt;i&gt;chip&lt;/i&gt; field (a relative path); the review report shows every sign's chip and attributes. The sign layer is styled with a symbol per class and its height as label (a .qml file beside it).&lt;br&gt;&lt;br&gt;&lt;b&gt;Sign codes&lt;/b&gt;: the codes Detect signs read in the views of a sign are put to a vote, each view weighing its detection score x the pixels its crop holds across the sign's narrower side (a sign passed close by, seen at a steep angle, weighs less) x the code's probability. The sign gets &lt;i&gt;code&lt;/i&gt; (empty when the vote says &lt;i&gt;other&lt;/i&gt; or the support is below the minimum code confidence), &lt;i&gt;code_name&lt;/i&gt; (from the codes table), &lt;i&gt;code_score&lt;/i&gt; (the support: the code's share of the vote x its mean probability) and &lt;i&gt;code_views&lt;/i&gt;. When the code's class (codes table) is not the class vote's, the better supported one wins: the code's support against the class's (its share of the score-weighted class vote x its views' mean detection score); &lt;i&gt;code_check&lt;/i&gt; says &lt;i&gt;class_from_code&lt;/i&gt; (the class was taken from the code) or &lt;i&gt;code_dropped&lt;/i&gt; (the code was emptied). The label shows the code's name, or the figure of a speed limit.</source>
        <translation>Agrupa los candidatos de distintos panoramas que son la misma señal física (misma clase, dentro del radio de fusión, normales de plano concordantes; los paneles apilados en un mismo poste se mantienen separados) y después refina cada señal en la nube: agrupamiento euclidiano, un filtro de intensidad cuyo umbral se adapta a la nube (Otsu), un plano RANSAC casi vertical y la dimensionalidad PCA para conservar el panel y descartar el poste.&lt;br&gt;&lt;br&gt;Cada señal obtiene el centro de su panel, el ancho y el alto del panel, el acimut hacia el que mira su cara (en sentido horario desde el norte de cuadrícula), su altura sobre el suelo justo debajo (puntos de clase 2 cerca de la señal; el registro indica cualquier alternativa usada), la altura inferior, el número de vistas y de puntos, las imágenes en las que se vio y la mejor de ellas (la más cercana y frontal), la intensidad media y la planaridad. Una señal vista en dos o más panoramas pero sin puntos en la nube se sitúa triangulando sus rayos (position_source = image).&lt;br&gt;&lt;br&gt;&lt;b&gt;No son señales&lt;/b&gt;, descartadas y nombradas en el registro: un panel mayor de lo que admite su clase (una valla publicitaria), uno curvo (un espejo convexo), una imagen sobre una superficie plana mayor, y una señal vista en un solo panorama cuando su puntuación es menor que 0,4 o cuando dos o más panoramas más cercanos a su cara, que detectaron otras señales, no la vieron (algo parecido a una señal, recuadrado una vez desde lejos).&lt;br&gt;&lt;br&gt;Salidas opcionales: contornos de los paneles (PolygonZ) y los puntos de las señales (LAS/LAZ).&lt;br&gt;&lt;br&gt;&lt;b&gt;Revisión&lt;/b&gt;: con la carpeta de panoramas, cada señal obtiene una miniatura de su mejor panorama (su recuadro con un margen, sin distorsión), escrita en una carpeta junto a la capa de señales y enlazada por el campo &lt;i&gt;chip&lt;/i&gt; (una ruta relativa); el informe de revisión muestra la miniatura y los atributos de cada señal. La capa de señales se simboliza con un símbolo por clase y su altura como etiqueta (un archivo .qml a su lado).&lt;br&gt;&lt;br&gt;&lt;b&gt;Códigos de señal&lt;/b&gt;: los códigos que «Detectar señales en panoramas» leyó en las vistas de una señal se someten a votación, y cada vista pesa su puntuación de detección x los píxeles que su recorte tiene a lo ancho del lado más estrecho de la señal (una señal pasada de cerca, vista en un ángulo pronunciado, pesa menos) x la probabilidad del código. La señal obtiene &lt;i&gt;code&lt;/i&gt; (vacío cuando la votación dice &lt;i&gt;other&lt;/i&gt; o el apoyo queda por debajo de la confianza mínima de código), &lt;i&gt;code_name&lt;/i&gt; (de la tabla de códigos), &lt;i&gt;code_score&lt;/i&gt; (el apoyo: la proporción del código en la votación x su probabilidad media) y &lt;i&gt;code_views&lt;/i&gt;. Cuando la clase del código (tabla de códigos) no es la de la votación de clase, gana la que tiene más apoyo: el apoyo del código frente al de la clase (su proporción en la votación de clase ponderada por la puntuación x la puntuación de detección media de sus vistas); &lt;i&gt;code_check&lt;/i&gt; indica &lt;i&gt;class_from_code&lt;/i&gt; (la clase se tomó del código) o &lt;i&gt;code_dropped&lt;/i&gt; (el código se vació). La etiqueta muestra el nombre del código, o la cifra de un límite de velocidad.</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="106" />
        <source>Drop a sign seen once when this many nearer panoramas missed it</source>
        <translation>Descartar una señal vista una sola vez cuando tantos panoramas más cercanos no la vieron</translation>
    </message>
    <message>
        <location filename="../algorithms/refinesigns.py" line="106" />
        <source>A sign seen in one panorama only is dropped when at least this many other panoramas, which detected other signs, stand nearer to its face and did not see it (within 60 degrees of its normal, at least 4 m away, with the sign at most 20 degrees above their horizon): a look-alike boxed once from afar, such as a convex mirror. 0 keeps every such sign, for example a real sign that a lorry hid from the nearer panoramas.</source>
        <translation>Una señal vista en un solo panorama se descarta cuando al menos este número de otros panoramas, que detectaron otras señales, están más cerca de su cara y no la vieron (a menos de 60 grados de su normal, a 4 m o más, con la señal a lo sumo 20 grados por encima de su horizonte): algo parecido a una señal, recuadrado una vez desde lejos, como un espejo convexo. 0 conserva todas esas señales, por ejemplo una señal real que un camión ocultó a los panoramas más cercanos.</translation>
    </message>
</context>
<context>
    <name>ReviewPanel</name>
    <message>
        <location filename="../gui/reviewpanel.py" line="723" />
        <source>Sign review</source>
        <translation>Revisión de señales</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="145" />
        <source>The sign layer to review (the output of Refine and merge signs, or any point layer with the sign fields).</source>
        <translation>La capa de señales a revisar (la salida de Refinar y fusionar señales, o cualquier capa de puntos con los campos de señal).</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="147" />
        <source>Signs</source>
        <translation>Señales</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="151" />
        <source>The panorama stations of the drive: with them the panel cuts the sign from every panorama that saw it.</source>
        <translation>Las estaciones de panorama del recorrido: con ellas el panel recorta la señal de cada panorama que la vio.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="153" />
        <source>Stations</source>
        <translation>Estaciones</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="156" />
        <source>The panorama folder; empty: the path field of the stations layer.</source>
        <translation>La carpeta de panoramas; vacía: el campo path de la capa de estaciones.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="157" />
        <source>Panoramas</source>
        <translation>Panoramas</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="714" />
        <source>Sign</source>
        <translation>Señal</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Class</source>
        <translation>Clase</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Code</source>
        <translation>Código</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Confidence</source>
        <translation>Confianza</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Condition</source>
        <translation>Estado</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Sources</source>
        <translation>Fuentes</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Panel</source>
        <translation>Panel</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="180" />
        <source>Review</source>
        <translation>Revisión</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="194" />
        <source>The sign's class: pick or type another one, then Change.</source>
        <translation>La clase de la señal: elija o escriba otra y pulse Cambiar.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="196" />
        <source>code</source>
        <translation>código</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="197" />
        <source>The sign's code (e.g. 206): type it, then Enter or Change.</source>
        <translation>El código de la señal (p. ej. 206): escríbalo y pulse Intro o Cambiar.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="204" />
        <source>Accept (A)</source>
        <translation>Aceptar (A)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="204" />
        <source>A real sign, class and code right: next sign.</source>
        <translation>Una señal real, con clase y código correctos: siguiente señal.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="206" />
        <source>Reject (R)</source>
        <translation>Rechazar (R)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="206" />
        <source>Not a sign, or a duplicate: next sign.</source>
        <translation>No es una señal, o es un duplicado: siguiente señal.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="208" />
        <source>Change (C)</source>
        <translation>Cambiar (C)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="208" />
        <source>A real sign with the class and code above: next sign.</source>
        <translation>Una señal real con la clase y el código de arriba: siguiente señal.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="210" />
        <source>Look again (L)</source>
        <translation>Volver a mirar (L)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="210" />
        <source>Needs another look: next sign.</source>
        <translation>Hay que volver a mirarla: siguiente señal.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="212" />
        <source>Previous (P)</source>
        <translation>Anterior (P)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="212" />
        <source>The sign before this one.</source>
        <translation>La señal anterior a esta.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="214" />
        <source>Next unreviewed (N)</source>
        <translation>Siguiente sin revisar (N)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="214" />
        <source>The next sign without a verdict.</source>
        <translation>La siguiente señal sin veredicto.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="216" />
        <source>Panorama view (V)</source>
        <translation>Vista del panorama (V)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="216" />
        <source>The panorama around the sign, from its best panorama.</source>
        <translation>El panorama alrededor de la señal, desde su mejor panorama.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="218" />
        <source>Undo (U)</source>
        <translation>Deshacer (U)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="218" />
        <source>Undo the last verdict given here.</source>
        <translation>Deshace el último veredicto dado aquí.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="220" />
        <source>Save edits</source>
        <translation>Guardar ediciones</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="220" />
        <source>Write the verdicts to the layer's file.</source>
        <translation>Escribe los veredictos en el archivo de la capa.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="303" />
        <source>Choose a sign layer to review.</source>
        <translation>Elija una capa de señales para revisar.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="269" />
        <source>The layer {layer} lacks the field(s) {missing}. The review needs a sign layer with the fields {required} (the output of Refine and merge signs).</source>
        <translation>A la capa {layer} le faltan los campos {missing}. La revisión necesita una capa de señales con los campos {required} (la salida de Refinar y fusionar señales).</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="287" />
        <source>(point geometry)</source>
        <translation>(geometría de punto)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="381" />
        <source>The layer {} has no signs.</source>
        <translation>La capa {} no tiene señales.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="392" />
        <source>&lt;b&gt;Sign {sign}&lt;/b&gt; ({position} of {total}) &amp;#8212; {reviewed} of {total} reviewed</source>
        <translation>&lt;b&gt;Señal {sign}&lt;/b&gt; ({position} de {total}) &amp;#8212; {reviewed} de {total} revisadas</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="395" />
        <source>Sign {}</source>
        <translation>Señal {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="400" />
        <source>(none)</source>
        <translation>(ninguno)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="411" />
        <source>(no condition field)</source>
        <translation>(sin campo de estado)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="416" />
        <source>{source}; seen in {n} panorama(s): {images}</source>
        <translation>{source}; vista en {n} panorama(s): {images}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="419" />
        <source>{width} × {height} m, {above} m above the ground, facing {azimuth}°</source>
        <translation>{width} × {height} m, a {above} m sobre el suelo, orientada a {azimuth}°</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="435" />
        <source>accepted</source>
        <translation>aceptada</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="435" />
        <source>corrected</source>
        <translation>corregida</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="436" />
        <source>rejected</source>
        <translation>rechazada</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="436" />
        <source>needs another look</source>
        <translation>hay que volver a mirarla</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="437" />
        <source>not reviewed</source>
        <translation>sin revisar</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="516" />
        <source>review chip</source>
        <translation>miniatura de revisión</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="527" />
        <source>no picture</source>
        <translation>sin imagen</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="527" />
        <source>Choose the stations layer (and the panorama folder) to see the sign in every panorama that saw it.</source>
        <translation>Elija la capa de estaciones (y la carpeta de panoramas) para ver la señal en cada panorama que la vio.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="553" />
        <source>best · </source>
        <translation>mejor · </translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="554" />
        <source>{} at {:.1f} m; click for the panorama view</source>
        <translation>{} a {:.1f} m; pulse para la vista del panorama</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="558" />
        <source>{} panorama(s) not found</source>
        <translation>{} panorama(s) no encontrado(s)</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="558" />
        <source>Not found or unreadable: {}. Set the panorama folder.</source>
        <translation>No encontrados o ilegibles: {}. Indique la carpeta de panoramas.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="571" />
        <source>The panorama view needs the stations layer of the drive.</source>
        <translation>La vista del panorama necesita la capa de estaciones del recorrido.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="580" />
        <source>No panorama of the stations layer saw this sign.</source>
        <translation>Ningún panorama de la capa de estaciones vio esta señal.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="605" />
        <source>Panorama view: sign {}</source>
        <translation>Vista del panorama: señal {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="607" />
        <source>{} · {:.1f} m from the sign</source>
        <translation>{} · a {:.1f} m de la señal</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="634" />
        <source>The layer {} cannot be edited: its verdicts cannot be written.</source>
        <translation>La capa {} no se puede editar: no se pueden escribir sus veredictos.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="637" />
        <source>Sign review: {} sign {}</source>
        <translation>Revisión de señales: {} señal {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="642" />
        <source>Cannot add the field {} to the layer {}.</source>
        <translation>No se puede añadir el campo {} a la capa {}.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="663" />
        <source>Cannot save the edits of {}: {}</source>
        <translation>No se pueden guardar las ediciones de {}: {}</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="675" />
        <source>Every sign has a verdict.</source>
        <translation>Todas las señales tienen veredicto.</translation>
    </message>
    <message>
        <location filename="../gui/reviewpanel.py" line="516" />
        <source>best · {} (review chip)</source>
        <translation>mejor · {} (miniatura de revisión)</translation>
    </message>
</context>
<context>
    <name>RoadSigns</name>
    <message>
        <location filename="../core/cloudsigns.py" line="288" />
        <source>The stations do not overlap the cloud {path}: the track passes {gap:.1f} m from the cloud's extent ({xmin:.1f}, {ymin:.1f}) - ({xmax:.1f}, {ymax:.1f}), more than the corridor of {corridor} m; are the cloud and the stations in the same CRS and of the same drive?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Las estaciones no se solapan con la nube {path}: el trayecto pasa a {gap:.1f} m de la extensión de la nube ({xmin:.1f}, {ymin:.1f}) - ({xmax:.1f}, {ymax:.1f}), más que el corredor de {corridor} m; ¿están la nube y las estaciones en el mismo SRC y son del mismo recorrido?</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="301" />
        <source>{path} has no intensity dimension (point format {fmt}): signs cannot be found in it without images</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene dimensión de intensidad (formato de punto {fmt}): sin imágenes no se pueden encontrar señales en ella</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="304" />
        <source>{path} has no classification dimension: run roadsigns:groundfilter on it first</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene dimensión de clasificación: ejecute primero roadsigns:groundfilter sobre ella</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="763" />
        <source>Found {signs} sign panels ({bright} retroreflective) and {poles} poles in {n} points ({cand} kept near the road, {windows} windows of {w} m); condition reference {ref:.3f} ({src})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Se encontraron {signs} paneles de señal ({bright} retrorreflectantes) y {poles} postes en {n} puntos ({cand} conservados cerca de la vía, {windows} ventanas de {w} m); referencia de estado {ref:.3f} ({src})</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="680" />
        <source>No point of {path} lies within {corridor} m of the stations' track ({n} points read)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ningún punto de {path} está a menos de {corridor} m del trayecto de las estaciones ({n} puntos leídos)</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="683" />
        <source>{path} has no ground points (class 2) along the track: run roadsigns:groundfilter on it first (or classify the ground with another tool)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene puntos de suelo (clase 2) a lo largo del trayecto: ejecute primero roadsigns:groundfilter sobre ella (o clasifique el suelo con otra herramienta)</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="687" />
        <source>{path} has no intensity: all {n} points near the track have intensity 0; signs cannot be found in it without images</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene intensidad: los {n} puntos cercanos al trayecto tienen intensidad 0; sin imágenes no se pueden encontrar señales en ella</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="698" />
        <source>Intensity: range exponent {alpha:.2f} ({source}), bright threshold {thr:.3f} of full scale at 10 m ({method}; background level {bg:.3f}, bright mode {mode:.3f}; {n} non-ground points near the road)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Intensidad: exponente de distancia {alpha:.2f} ({source}), umbral de brillo {thr:.3f} del fondo de escala a 10 m ({method}; nivel de fondo {bg:.3f}, moda brillante {mode:.3f}; {n} puntos que no son de suelo cerca de la vía)</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="757" />
        <source>Searching the drive for signs and poles: window {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Buscando señales y postes a lo largo del recorrido: ventana {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="832" />
        <source>{n} gantry posts</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{n} postes de pórtico</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="690" />
        <source>The cloud's GPS times [{t0:.1f}, {t1:.1f}] do not meet the stations' times: ranges are taken from the nearest track position instead (is one of them in GPS week seconds and the other in adjusted standard GPS time?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Los tiempos GPS de la nube [{t0:.1f}, {t1:.1f}] no coinciden con los de las estaciones: las distancias se toman en su lugar desde la posición más cercana del trayecto (¿está uno en segundos de la semana GPS y el otro en tiempo GPS estándar ajustado?)</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="709" />
        <source>{share:.0%} of the points near the road have intensity 0: the bright threshold {thr:.3f} of full scale may be meaningless</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El {share:.0%} de los puntos cercanos a la vía tiene intensidad 0: el umbral de brillo {thr:.3f} del fondo de escala puede carecer de sentido</translation>
    </message>
    <message>
        <location filename="../core/cloudsigns.py" line="714" />
        <source>{share:.0%} of the points near the road have saturated intensity: the bright threshold {thr:.3f} of full scale and the condition of the signs may be meaningless</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El {share:.0%} de los puntos cercanos a la vía tiene la intensidad saturada: el umbral de brillo {thr:.3f} del fondo de escala y el estado de las señales pueden carecer de sentido</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="575" />
        <location filename="../core/cloudsource.py" line="573" />
        <source>expected a virtual point cloud: a JSON FeatureCollection (STAC ItemCollection) whose features each have assets.data.href (the tile's file, relative to the .vpc) and properties, as QGIS's Build virtual point cloud writes it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>se esperaba una nube de puntos virtual: una FeatureCollection JSON (ItemCollection de STAC) cuyas entidades tengan cada una assets.data.href (el archivo de la tesela, relativo al .vpc) y properties, tal como la escribe «Construir nube de puntos virtual» de QGIS</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="161" />
        <source>no CRS</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>sin SRC</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="534" />
        <source>The folder {path} holds no LAS or LAZ file (*.las, *.laz); expected a point cloud file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La carpeta {path} no contiene ningún archivo LAS ni LAZ (*.las, *.laz); se esperaba un archivo de nube de puntos, una carpeta de teselas LAS/LAZ o una nube de puntos virtual (.vpc)</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="577" />
        <source>Cannot read {path}: the JSON is not an object; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: el JSON no es un objeto; {expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="580" />
        <source>Cannot read {path}: it is not a 'FeatureCollection' with a 'features' list; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: no es una 'FeatureCollection' con una lista 'features'; {expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="583" />
        <source>The virtual point cloud {path} lists no tile</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La nube de puntos virtual {path} no enumera ninguna tesela</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="250" />
        <location filename="../core/pointcloud.py" line="606" />
        <source>{path} has no dimension {names} (point format {fmt})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene la dimensión {names} (formato de punto {fmt})</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="527" />
        <source>Cannot read the folder {path}: {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer la carpeta {path}: {detail}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="566" />
        <location filename="../core/pointcloud.py" line="72" />
        <source>Cannot read {path}: the file does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: el archivo no existe</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="568" />
        <location filename="../core/ground/pdal.py" line="306" />
        <location filename="../core/pointcloud.py" line="74" />
        <location filename="../core/pointcloud.py" line="117" />
        <source>Cannot read {path}: {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: {detail}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="572" />
        <source>Cannot read {path}: it is not valid JSON ({detail}); {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: no es un JSON válido ({detail}); {expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="590" />
        <source>Cannot read {path}: feature {feature} has no 'assets' object; {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: la entidad {feature} no tiene objeto 'assets'; {expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="598" />
        <source>Cannot read {path}: feature {feature} has no asset with an 'href' (assets.data.href); {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: la entidad {feature} no tiene ningún asset con 'href' (assets.data.href); {expected}</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="602" />
        <source>The virtual point cloud {path} lists the remote tile {href}: only local files are read; download the tiles and build the virtual point cloud again</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La nube de puntos virtual {path} enumera la tesela remota {href}: solo se leen archivos locales; descargue las teselas y vuelva a construir la nube de puntos virtual</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="608" />
        <source>The virtual point cloud {path} lists the tile {tile} twice (features {first} and {second})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La nube de puntos virtual {path} enumera la tesela {tile} dos veces (entidades {first} y {second})</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="612" />
        <source>The virtual point cloud {path} lists the tile {tile} (feature {feature}), which does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La nube de puntos virtual {path} enumera la tesela {tile} (entidad {feature}), que no existe</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="627" />
        <source>The tiles of {path} cannot be read as one cloud: {tile_a} has point format {fmt_a}, {tile_b} point format {fmt_b}; every tile needs the same point format (convert them to one, e.g. with PDAL's translate)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Las teselas de {path} no se pueden leer como una sola nube: {tile_a} tiene el formato de punto {fmt_a}, {tile_b} el formato de punto {fmt_b}; todas las teselas necesitan el mismo formato de punto (conviértalas a uno solo, p. ej. con translate de PDAL)</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="633" />
        <source>The tiles of {path} are in different CRSs: {tile_a} in {crs_a}, {tile_b} in {crs_b}; every tile must be in the same CRS (reproject them to one first)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Las teselas de {path} están en SRC distintos: {tile_a} en {crs_a}, {tile_b} en {crs_b}; todas las teselas deben estar en el mismo SRC (reproyéctelas antes a uno solo)</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="662" />
        <source>The points cannot be written with the first tile's scale {scale} and offset {offset} in {axis}: their coordinates are too far from it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Los puntos no se pueden escribir con la escala {scale} y el desplazamiento {offset} de la primera tesela en {axis}: sus coordenadas están demasiado lejos de ellos</translation>
    </message>
    <message>
        <location filename="../core/cloudsource.py" line="335" />
        <source>Reading {name}: {done:.1f} of {total:.1f} million points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Leyendo {name}: {done:.1f} de {total:.1f} millones de puntos</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="19" />
        <source>CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SRC</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="228" />
        <source>{what} file {path}, {location}: x {x}, y {y} lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the CRS of these positions?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, {location}: x {x}, y {y} queda fuera del área de uso de {crs} (longitud {west} a {east}, latitud {south} a {north}): ¿es {crs} el SRC de estas posiciones?</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="251" />
        <source>{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): is {crs} the CRS of these coordinates?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}: x {xmin} a {xmax}, y {ymin} a {ymax} quedan fuera del área de uso de {crs} (longitud {west} a {east}, latitud {south} a {north}): ¿es {crs} el SRC de estas coordenadas?</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="22" />
        <source>No {role} given: expected an EPSG code, WKT or PROJ string</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se indicó ningún {role}: se esperaba un código EPSG, WKT o una cadena PROJ</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="113" />
        <location filename="../core/crs.py" line="123" />
        <location filename="../core/trajectory.py" line="489" />
        <source>trajectory CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SRC de la trayectoria</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="124" />
        <location filename="../core/trajectory.py" line="496" />
        <source>target CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SRC de destino</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="126" />
        <source>The target CRS {crs} is not projected: expected a projected CRS in metres (e.g. a UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El SRC de destino {crs} no es proyectado: se esperaba un SRC proyectado en metros (p. ej. una zona UTM)</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="224" />
        <source>{what} file {path}, {location}: x {x}, y {y} lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}) and looks like a longitude/latitude: give a geographic CRS (e.g. EPSG:4326) for these positions</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, {location}: x {x}, y {y} queda fuera del área de uso de {crs} (longitud {west} a {east}, latitud {south} a {north}) y parece una longitud/latitud: indique un SRC geográfico (p. ej. EPSG:4326) para estas posiciones</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="248" />
        <source>{label}: x {xmin} to {xmax}, y {ymin} to {ymax} lie outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}) and look like longitudes/latitudes: is {crs} the CRS of these coordinates?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}: x {xmin} a {xmax}, y {ymin} a {ymax} quedan fuera del área de uso de {crs} (longitud {west} a {east}, latitud {south} a {north}) y parecen longitudes/latitudes: ¿es {crs} el SRC de estas coordenadas?</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="261" />
        <source>{label} is in {crs}, a geographic CRS (degrees): this needs a projected CRS in metres, the CRS of the point cloud (e.g. a UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label} está en {crs}, un SRC geográfico (grados): esto necesita un SRC proyectado en metros, el SRC de la nube de puntos (p. ej. una zona UTM)</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="26" />
        <source>Unknown {role} '{crs}': {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se reconoce el {role} '{crs}': {error}</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="70" />
        <source>Heights: pass through unchanged (the target CRS has no vertical datum)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Alturas: se mantienen sin cambios (el SRC de destino no tiene datum vertical)</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="96" />
        <source>Transforming positions from {source} to {target} gave invalid values (outside the CRS's area, or a missing vertical grid)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La transformación de las posiciones de {source} a {target} dio valores no válidos (fuera del área del SRC, o falta una malla vertical)</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="208" />
        <source>{what} file {path}, {location}: x {x}, y {y} is not a longitude/latitude, but {crs} is a geographic CRS: are these projected coordinates? Give the CRS the positions are in</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, {location}: x {x}, y {y} no es una longitud/latitud, pero {crs} es un SRC geográfico: ¿son coordenadas proyectadas? Indique el SRC en que están las posiciones</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="73" />
        <source>Heights: the geoid grid for {crs} is not installed: heights stay as they are (ellipsoidal), only the horizontal position is transformed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Alturas: la rejilla del geoide para {crs} no está instalada: las alturas quedan como están (elipsoidales), solo se transforma la posición horizontal</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="77" />
        <source>Heights: transformed to {crs}: {operation}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Alturas: transformadas a {crs}: {operation}</translation>
    </message>
    <message>
        <location filename="../core/crs.py" line="91" />
        <source>Cannot transform positions from {source} to {target}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se pueden transformar las posiciones de {source} a {target}: {error}</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="104" />
        <source>The detections lack the field(s) {fields}; expected the output of Detect signs</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>A las detecciones les faltan los campos {fields}; se esperaba la salida de «Detectar señales en panoramas»</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="147" />
        <source>Detection {det_id}: the box ({u0}, {v0}, {u1}, {v1}) is not u0 &lt; u1, v0 &lt; v1 inside a {w} x {h} panorama</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Detección {det_id}: el recuadro ({u0}, {v0}, {u1}, {v1}) no cumple u0 &lt; u1, v0 &lt; v1 dentro de un panorama de {w} x {h}</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="155" />
        <source>Detection {det_id}: the station pose is invalid (quaternion norm {norm:.4f}, position {xyz})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Detección {det_id}: la pose de la estación no es válida (norma del cuaternión {norm:.4f}, posición {xyz})</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="110" />
        <location filename="../core/projection.py" line="417" />
        <source>Detection {det_id}: the field {field} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Detección {det_id}: el campo {field} está vacío</translation>
    </message>
    <message>
        <location filename="../core/detections.py" line="118" />
        <location filename="../core/projection.py" line="409" />
        <source>Detection {det_id}, field {field}: expected a number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Detección {det_id}, campo {field}: se esperaba un número, se encontró '{value}'</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="137" />
        <source>The labels file {path} holds no class names (one name per line)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo de etiquetas {path} no contiene nombres de clase (uno por línea)</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="174" />
        <source>The model {path} has an output of shape {shape}, which is no layout this plugin decodes for {n_classes} class names; supported: {supported}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene una salida de forma {shape}, que no corresponde a ninguna disposición que este complemento decodifique para {n_classes} nombres de clase; admitidas: {supported}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="187" />
        <source>Unknown output layout {layout}: use one of {layouts}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Disposición de salida desconocida {layout}: use una de {layouts}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="191" />
        <source>The model {path} has an output of shape {shape}, which does not fit the layout {layout} with {n_classes} class names</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene una salida de forma {shape}, que no encaja con la disposición {layout} con {n_classes} nombres de clase</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="298" />
        <source>Model not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró el modelo: {path}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="392" />
        <source>The model {path} names no classes: its metadata has no readable 'names' and there is no labels file ({labels}, one class name per line)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} no nombra ninguna clase: sus metadatos no tienen 'names' legibles y no hay archivo de etiquetas ({labels}, un nombre de clase por línea)</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="135" />
        <source>Cannot read the labels file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el archivo de etiquetas {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="309" />
        <source>{path} is not an ONNX model onnxruntime can load: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no es un modelo ONNX que onnxruntime pueda cargar: {error}</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="335" />
        <source>The model {path} is a {task} model; sign detection needs a detection model</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} es un modelo de {task}; la detección de señales necesita un modelo de detección</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="343" />
        <source>The model {path} takes an input of shape {shape}; an image model takes float [batch, 3, height, width] or uint8 [batch, height, width, 3]</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} recibe una entrada de forma {shape}; un modelo de imagen recibe float [batch, 3, height, width] o uint8 [batch, height, width, 3]</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="356" />
        <source>The model {path} has a fixed batch of {batch}; use a batch of 1 or a dynamic batch</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene un lote fijo de {batch}; use un lote de 1 o un lote dinámico</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="423" />
        <source>The model {path} takes {w} x {h} px images only; the horizon seen as one band ({bw} x {bh} px) needs a model whose input height and width are free, as the bundled detector's are</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} solo admite imágenes de {w} x {h} px; el horizonte visto como una sola banda ({bw} x {bh} px) necesita un modelo cuya altura y anchura de entrada sean libres, como las del detector incluido</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="901" />
        <source>Detecting signs: panorama {n} of {count} ({image})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Detectando señales: panorama {n} de {count} ({image})</translation>
    </message>
    <message>
        <location filename="../core/detector.py" line="373" />
        <source>The model {path} failed on a blank {w} x {h} image: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} falló con una imagen en blanco de {w} x {h}: {error}</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="59" />
        <source>The track needs at least 2 finite positions, got {n}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El trayecto necesita al menos 2 posiciones finitas; se recibieron {n}</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="106" />
        <source>The track does not move: all its positions are at one place</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El trayecto no se desplaza: todas sus posiciones están en el mismo lugar</translation>
    </message>
    <message>
        <location filename="../core/drivewindows.py" line="54" />
        <source>The track has {n} positions but {m} times</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El trayecto tiene {n} posiciones pero {m} tiempos</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="143" />
        <source>reference signs</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>señales de referencia</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="176" />
        <source>The signs ({signs}: x {sx0} to {sx1}, y {sy0} to {sy1}) and the reference {reference} (x {rx0} to {rx1}, y {ry0} to {ry1}) do not overlap: are both in the same CRS and the same area?</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Las señales ({signs}: x {sx0} a {sx1}, y {sy0} a {sy1}) y la referencia {reference} (x {rx0} a {rx1}, y {ry0} a {ry1}) no se superponen: ¿están ambas en el mismo SRC y en la misma zona?</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="201" />
        <source>match radius {radius} m: expected a positive number of metres</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Radio de emparejamiento {radius} m: se esperaba un número positivo de metros</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="209" />
        <source>{label}: sign '{sign_id}' has no valid x, y, z position</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{label}: la señal '{sign_id}' no tiene una posición x, y, z válida</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="412" />
        <source>Code accuracy not computed: neither the signs nor the reference have a 'code' field or column.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Exactitud de código no calculada: ni las señales ni la referencia tienen un campo o columna 'code'.</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="415" />
        <source>Code accuracy not computed: the reference has no 'code' column or field.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Exactitud de código no calculada: la referencia no tiene columna ni campo 'code'.</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="417" />
        <source>Code accuracy not computed: the signs have no 'code' field.</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Exactitud de código no calculada: las señales no tienen campo 'code'.</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="153" />
        <source>reference signs file {path}, line {line}: sign_id '{sign_id}' already used on line {first}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de señales de referencia {path}, línea {line}: el sign_id '{sign_id}' ya se usó en la línea {first}</translation>
    </message>
    <message>
        <location filename="../core/evaluate.py" line="149" />
        <source>reference signs file {path}, line {line}, field '{field}': empty value</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de señales de referencia {path}, línea {line}, campo '{field}': valor vacío</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="162" />
        <source>Image sign</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>Señal de imagen</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="163" />
        <source>Cloud panel</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>Panel de la nube</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="106" />
        <source>{what} {index}: position is not finite</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what} {index}: la posición no es finita</translation>
    </message>
    <message>
        <location filename="../core/fusion.py" line="103" />
        <source>{what} {index}: no position (x, y, z)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{what} {index}: sin posición (x, y, z)</translation>
    </message>
    <message>
        <location filename="../core/ground/blocks.py" line="304" />
        <source>Classifying the ground block by block: block {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Clasificando el terreno bloque a bloque: bloque {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/ground/csf.py" line="132" />
        <source>The built-in CSF needs the Python package cloth-simulation-filter (module CSF): {detail}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El CSF integrado necesita el paquete de Python cloth-simulation-filter (módulo CSF): {detail}</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="337" />
        <location filename="../core/pointcloud.py" line="274" />
        <source>Cannot write {path}: the output must end in .las or .laz</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede escribir {path}: la salida debe terminar en .las o .laz</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="349" />
        <location filename="../core/ground/tiled.py" line="106" />
        <source>point cloud CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SRC de la nube de puntos</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="422" />
        <source>PDAL not found: using the built-in engine</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró PDAL: se usa el motor integrado</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="472" />
        <source>No crop polygons: the crop buffer is ignored</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No hay polígonos de recorte: se ignora el búfer de recorte</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="152" />
        <source>Classifying and writing the points: part {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Clasificando y escribiendo los puntos: parte {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="259" />
        <source>No point of {path} has the returns '{returns}': nothing was classified</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ningún punto de {path} tiene los retornos '{returns}': no se clasificó nada</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="343" />
        <source>The output {path} must not be the input file</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La salida {path} no puede ser el archivo de entrada</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="351" />
        <location filename="../core/ground/tiled.py" line="108" />
        <source>{path} has no coordinate reference system: give the cloud's CRS (it is never guessed)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene sistema de referencia de coordenadas: indique el SRC de la nube (nunca se adivina)</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="409" />
        <source>Auto: the built-in engine, measured faster than PDAL for {method} (and it streams the cloud in bounded memory)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Automático: el motor integrado, más rápido que PDAL en las mediciones para {method} (y procesa la nube en flujo continuo con memoria acotada)</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="414" />
        <source>Auto: PDAL, as the built-in {method} needs the Python package cloth-simulation-filter, which is not installed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Automático: PDAL, porque el {method} integrado necesita el paquete de Python cloth-simulation-filter, que no está instalado</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="420" />
        <source>PDAL was asked for, but neither the pdal Python module nor a pdal executable was found (PATH, QGIS's bin folder)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Se pidió PDAL, pero no se encontró ni el módulo de Python pdal ni un ejecutable pdal (PATH, carpeta bin de QGIS)</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="424" />
        <source>Auto: PDAL, measured faster than the built-in engine for {method}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Automático: PDAL, más rápido que el motor integrado en las mediciones para {method}</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="459" />
        <source>No point of {path} is left after the crop: {output} has no points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No queda ningún punto de {path} tras el recorte: {output} no tiene puntos</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="245" />
        <source>Not enough free disk space in {folder} to keep the points between the two passes: the cloud is read twice</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No hay espacio libre suficiente en el disco en {folder} para guardar los puntos entre las dos pasadas: la nube se lee dos veces</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="255" />
        <location filename="../core/ground/tiled.py" line="239" />
        <source>Cannot read {path}: the file is corrupt ({detail})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: el archivo está dañado ({detail})</translation>
    </message>
    <message>
        <location filename="../core/ground/engine.py" line="374" />
        <location filename="../core/ground/tiled.py" line="139" />
        <source>PDAL failed, the built-in engine was used instead: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>PDAL falló; se usó el motor integrado en su lugar: {error}</translation>
    </message>
    <message>
        <location filename="../core/ground/gridsteps.py" line="36" />
        <source>Unknown return type {kinds} in '{returns}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tipo de retorno desconocido {kinds} en '{returns}'</translation>
    </message>
    <message>
        <location filename="../core/ground/lattice.py" line="209" />
        <source>Fitting the ground surface: tile {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ajustando la superficie del terreno: tesela {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/ground/lattice.py" line="60" />
        <source>The area to classify ({w:.0f} m x {h:.0f} m) needs {cells} grid cells of {step} m, more than {limit}: crop the cloud or use a larger cell/resolution</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El área que se va a clasificar ({w:.0f} m x {h:.0f} m) necesita {cells} celdas de {step} m, más de {limit}: recorte la nube o use una celda/resolución mayor</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="36" />
        <source>Unknown {what} {value!r}: expected one of {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se reconoce el {what} {value!r}: se esperaba uno de {names}</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="42" />
        <source>ground method</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>método de suelo</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="47" />
        <source>engine</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>motor</translation>
    </message>
    <message>
        <location filename="../core/ground/params.py" line="61" />
        <source>Parameters {params} do not belong to method {method}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Los parámetros {params} no pertenecen al método {method}</translation>
    </message>
    <message>
        <location filename="../core/ground/pdal.py" line="189" />
        <source>PDAL executable {path} not found or not executable</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El ejecutable de PDAL {path} no existe o no es ejecutable</translation>
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
        <translation>No se puede leer {path}: el archivo está truncado o dañado ({detail})</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="172" />
        <source>{n} tiles written to {folder}, listed in {vpc}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{n} teselas escritas en {folder}, enumeradas en {vpc}</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="98" />
        <source>The virtual point cloud's name {name} must be a file name ending in .vpc</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El nombre de la nube de puntos virtual {name} debe ser un nombre de archivo terminado en .vpc</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="70" />
        <source>The output folder {folder} holds the input tile {tile}: choose another folder (the output folder is replaced as a whole)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La carpeta de salida {folder} contiene la tesela de entrada {tile}: elija otra carpeta (la carpeta de salida se reemplaza por completo)</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="73" />
        <source>Two tiles of {path} have the same file name, {name} ({first} and {second}): the output tiles are named as the input tiles, so their names must differ</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Dos teselas de {path} tienen el mismo nombre de archivo, {name} ({first} y {second}): las teselas de salida se nombran como las de entrada, por lo que sus nombres deben ser distintos</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="169" />
        <source>No point of {path} is left after the crop: {output} lists no tile</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No queda ningún punto de {path} tras el recorte: {output} no enumera ninguna tesela</translation>
    </message>
    <message>
        <location filename="../core/ground/tiled.py" line="158" />
        <source>No point of the tile {tile} lies inside the crop area: no output tile for it</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ningún punto de la tesela {tile} está dentro del área de recorte: no hay tesela de salida para ella</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="304" />
        <source>Unknown time base {base}: expected one of {bases}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Base de tiempo desconocida {base}: se esperaba una de {bases}</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="394" />
        <source>sign layer CRS</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>SRC de la capa de señales</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="318" />
        <source>No output folder given for the handover package</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se indicó carpeta de salida para el paquete de entrega</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="324" />
        <source>Cannot write the handover package to {folder}: {path} is a file, not a folder</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede escribir el paquete de entrega en {folder}: {path} es un archivo, no una carpeta</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="390" />
        <source>Unknown review state(s) {states}: expected some of {known}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Estado(s) de revisión desconocido(s) {states}: se esperaba alguno de {known}</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="393" />
        <source>Unknown north {north}: expected grid or true</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Norte desconocido {north}: se esperaba grid o true</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="407" />
        <source>No sign has the review state(s) {states} ({counts}): review the signs with the review panel, or choose other states</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ninguna señal tiene el estado o estados de revisión {states} ({counts}): revise las señales con el panel de revisión o elija otros estados</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="422" />
        <source>Preparing the handover: sign {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Preparando la entrega: señal {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="479" />
        <source>{n} of {total} signs handed over (review states {states}); left out: {left}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{n} de {total} señales entregadas (estados de revisión {states}); excluidas: {left}</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="168" />
        <source>The stations layer has fewer than two stations at different places: the export needs the drive's track (chainage, side and offset of each sign)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La capa de estaciones tiene menos de dos estaciones en lugares distintos: la exportación necesita el trayecto del recorrido (PK, lado y desplazamiento de cada señal)</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="331" />
        <source>Cannot write the handover package to {folder}: the folder {path} is not writable ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede escribir el paquete de entrega en {folder}: en la carpeta {path} no se puede escribir ({error})</translation>
    </message>
    <message>
        <location filename="../core/handover.py" line="411" />
        <source>The station times are GPS seconds of the week: give the survey date to get first and last seen as dates and times (first_seen_s and last_seen_s are written)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Los tiempos de las estaciones son segundos GPS de la semana: indique la fecha del levantamiento para obtener la primera y la última vez que se vio como fechas y horas (se escriben first_seen_s y last_seen_s)</translation>
    </message>
    <message>
        <location filename="../core/outputs.py" line="68" />
        <source>Cannot write {path}: the folder {folder} does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede escribir {path}: la carpeta {folder} no existe</translation>
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
        <translation>No se puede escribir {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/outputs.py" line="204" />
        <source>The output {path} was not written</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La salida {path} no se escribió</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="126" />
        <source>The panorama {path} is {width} x {height} pixels, more than the {limit} the plugin reads</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El panorama {path} tiene {width} x {height} píxeles, más que los {limit} que lee el complemento</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="135" />
        <source>The panorama {path} is {width} x {height} pixels: an equirectangular panorama must be twice as wide as it is high</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El panorama {path} tiene {width} x {height} píxeles: un panorama equirrectangular debe ser el doble de ancho que de alto</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="167" />
        <location filename="../core/panorama.py" line="118" />
        <source>Panorama not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró el panorama: {path}</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="174" />
        <source>Cannot read the panorama {path}: the file is not a JPEG or PNG image or is corrupt</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el panorama {path}: el archivo no es una imagen JPEG o PNG o está dañado</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="120" />
        <source>The panorama {path} has more pixels than the {limit} the plugin reads</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El panorama {path} tiene más píxeles que los {limit} que lee el complemento</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="123" />
        <source>Cannot read the panorama {path}: expected a JPEG or PNG image ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el panorama {path}: se esperaba una imagen JPEG o PNG ({error})</translation>
    </message>
    <message>
        <location filename="../core/panorama.py" line="172" />
        <source>Cannot read the panorama {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el panorama {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="384" />
        <source>Cannot use {item!r} as a crop geometry: expected a shapely geometry, WKB or WKT</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede usar {item!r} como geometría de recorte: se esperaba una geometría de shapely, WKB o WKT</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="76" />
        <source>Cannot read {path}: expected a LAS or LAZ file ({detail})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer {path}: se esperaba un archivo LAS o LAZ ({detail})</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="507" />
        <source>{path} has no coordinate reference system and none was given</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene sistema de referencia de coordenadas y no se indicó ninguno</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="278" />
        <source>Cannot write {path}: the folder does not exist</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede escribir {path}: la carpeta no existe</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="422" />
        <source>The crop layer has no geometry</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La capa de recorte no tiene geometría</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="430" />
        <source>A corridor needs a positive buffer, got {buffer_m} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Un corredor necesita un búfer positivo; se recibió {buffer_m} m</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="440" />
        <source>A corridor needs stations or lines</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Un corredor necesita estaciones o líneas</translation>
    </message>
    <message>
        <location filename="../core/pointcloud.py" line="517" />
        <source>No point of {path} lies inside the crop area; {output} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ningún punto de {path} está dentro del área de recorte; {output} está vacío</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="622" />
        <source>{ok} of {count} detections found a surface in the cloud ({no_points} without points, {no_surface} without a planar surface)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{ok} de {count} detecciones encontraron una superficie en la nube ({no_points} sin puntos, {no_surface} sin superficie plana)</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="438" />
        <location filename="../core/projection.py" line="702" />
        <source>{source} has no ground points (class 2) where the signs are: run roadsigns:groundfilter on it first (or classify the ground with another tool)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{source} no tiene puntos de suelo (clase 2) donde están las señales: ejecute primero roadsigns:groundfilter sobre ella (o clasifique el suelo con otra herramienta)</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="581" />
        <source>The maximum range must exceed {min} m, got {value} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El alcance máximo debe superar {min} m; se recibió {value} m</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="616" />
        <source>Searching the detections' surfaces: {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Buscando las superficies de las detecciones: {n} de {count}</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="402" />
        <source>The candidates lack the field(s) {fields}; expected the output of Project detections</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>A los candidatos les faltan los campos {fields}; se esperaba la salida de «Proyectar detecciones en la nube de puntos»</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="427" />
        <source>Unknown candidate status {status!r}; expected ok, no_points or no_surface</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Estado de candidato desconocido {status!r}; se esperaba ok, no_points o no_surface</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="431" />
        <source>A candidate with status ok has no position</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Un candidato con estado ok no tiene posición</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="452" />
        <source>The point index lacks {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Al índice de puntos le falta {names}</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="586" />
        <source>No detections to project; the candidates are empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No hay detecciones que proyectar; los candidatos están vacíos</translation>
    </message>
    <message>
        <location filename="../core/projection.py" line="618" />
        <source>{path} has no point inside the detections' frusta; no candidate found</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{path} no tiene puntos dentro de los troncos de visión de las detecciones; no se encontró ningún candidato</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="141" />
        <source>curved surface (a convex mirror?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>superficie curva (¿un espejo convexo?)</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="142" />
        <source>part of a larger flat surface (a picture on a billboard or a wall?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>parte de una superficie plana mayor (¿una imagen en una valla publicitaria o una pared?)</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1029" />
        <source>{signs} signs from {candidates} candidates ({from_images} placed from the images alone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{signs} señales a partir de {candidates} candidatos ({from_images} situadas solo a partir de las imágenes)</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1788" />
        <source>{coded} of {signs} signs have a sign code; {from_code} took their class from the code, {dropped} codes were dropped for the class vote (code_check)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{coded} de {signs} señales tienen código de señal; {from_code} tomaron su clase del código, {dropped} códigos se descartaron por la votación de clase (code_check)</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1797" />
        <source>the stations' height minus {height} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>la altura de las estaciones menos {height} m</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="422" />
        <source>Detection {det_id} has the sign code {code}, which is not in the sign codes table {table}: give the codes table the classifier was run with</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La detección {det_id} tiene el código de señal {code}, que no está en la tabla de códigos de señal {table}: indique la tabla de códigos con la que se ejecutó el clasificador</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1006" />
        <source>The merge radius must be positive, got {value} m</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El radio de fusión debe ser positivo; se recibió {value} m</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1009" />
        <source>No candidates to refine; the sign layer is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No hay candidatos que refinar; la capa de señales está vacía</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1535" />
        <source>Candidates {ids}: {reason}; placed at the candidates' median</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Candidatos {ids}: {reason}; situados en la mediana de los candidatos</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1728" />
        <source>Candidates {ids} dropped: a {width:.2f} x {height:.2f} m panel is too large for a {sign_class} sign (a billboard?)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Candidatos {ids} descartados: un panel de {width:.2f} x {height:.2f} m es demasiado grande para una señal {sign_class} (¿una valla publicitaria?)</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1733" />
        <source>Candidates {ids} dropped: seen in one panorama only, with a score of {score:.2f}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Candidatos {ids} descartados: vistos en una sola panorámica, con una puntuación de {score:.2f}</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="523" />
        <source>too few points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>muy pocos puntos</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="526" />
        <source>too few points in the boxes</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>muy pocos puntos en los recuadros</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="532" />
        <source>no near-vertical plane</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>ningún plano casi vertical</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="536" />
        <source>too few planar points</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>muy pocos puntos planos</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1469" />
        <source>Refining the signs: {n} of {count} candidate groups</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Refinando las señales: {n} de {count} grupos de candidatos</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1529" />
        <source>no point cloud</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>sin nube de puntos</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1532" />
        <source>Candidates {ids} dropped: {reason}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Candidatos {ids} descartados: {reason}</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1739" />
        <source>Candidates {ids} dropped: seen in one panorama only ({image}, {range:.1f} m away), not in the {missed} panoramas nearer to its face</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Candidatos {ids} descartados: vistos en un solo panorama ({image}, a {range:.1f} m), no en los {missed} panoramas más cercanos a su cara</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1798" />
        <source>the lowest points below the sign</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>los puntos más bajos bajo la señal</translation>
    </message>
    <message>
        <location filename="../core/refine.py" line="1802" />
        <source>{count} sign(s) have no ground points (class 2) within {radius} m: their height is measured from {source}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{count} señal(es) no tienen puntos de suelo (clase 2) a menos de {radius} m: su altura se mide desde {source}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="216" />
        <source>Sign codes table {path} is empty: expected the header {expected} and one row per code</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La tabla de códigos de señal {path} está vacía: se esperaba la cabecera {expected} y una fila por código</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="219" />
        <source>Sign codes table {path} holds no codes: expected one row per code after the header {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>La tabla de códigos de señal {path} no contiene códigos: se esperaba una fila por código tras la cabecera {expected}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="429" />
        <source>The box {box} is not four finite pixel coordinates u0, v0, u1, v1</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El recuadro {box} no son cuatro coordenadas de píxel finitas u0, v0, u1, v1</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="162" />
        <source>Sign codes table not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró la tabla de códigos de señal: {path}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="164" />
        <source>Cannot read the sign codes table {path}: it is not UTF-8 text (byte {position}); save it as UTF-8</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer la tabla de códigos de señal {path}: no es texto UTF-8 (byte {position}); guárdela como UTF-8</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="167" />
        <source>Cannot read the sign codes table {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer la tabla de códigos de señal {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="192" />
        <source>Sign codes table {path}, line {line}: expected 3 fields separated by semicolons ({expected}), found {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: se esperaban 3 campos separados por punto y coma ({expected}), se encontraron {count}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="197" />
        <source>Sign codes table {path}, line {line}: the code is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: el código está vacío</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="200" />
        <source>Sign codes table {path}, line {line}: the code {code} is reserved for signs the classifier cannot read and must not be in the table</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: el código {code} está reservado para las señales que el clasificador no puede leer y no debe figurar en la tabla</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="204" />
        <source>Sign codes table {path}, line {line}: the name of {code} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: el nombre de {code} está vacío</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="207" />
        <source>Sign codes table {path}, lines {first} and {line}: the code {code} is there twice</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, líneas {first} y {line}: el código {code} aparece dos veces</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="210" />
        <source>Sign codes table {path}, line {line}: unknown class {found} for {code}; expected one of {classes}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: clase desconocida {found} para {code}; se esperaba una de {classes}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="257" />
        <source>The model {path} is a {task} model; reading sign codes needs a classify model (metadata task = classify)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} es un modelo de {task}; la lectura de códigos de señal necesita un modelo de clasificación (metadatos task = classify)</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="267" />
        <source>The model {path} takes an input {name} of shape {shape} and type {type}; supported: float [batch, 3, S, S] (RGB crops S x S pixels, values 0..1)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} recibe una entrada {name} de forma {shape} y tipo {type}; admitido: float [batch, 3, S, S] (recortes RGB de S x S píxeles, valores 0..1)</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="285" />
        <source>The model {path} has an output of shape {shape} for a batch of {batch}; supported: [batch, C] with C = {count}, its number of names</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene una salida de forma {shape} para un lote de {batch}; admitida: [batch, C] con C = {count}, su número de nombres</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="293" />
        <source>The model {path} names no codes: its metadata needs 'names', a JSON list of the sign codes in output order (such as ["DE:206", "other"])</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} no nombra ningún código: sus metadatos necesitan 'names', una lista JSON de los códigos de señal en el orden de salida (como ["DE:206", "other"])</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="299" />
        <source>The model {path} names {names} more than once in its metadata 'names'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} nombra {names} más de una vez en sus metadatos 'names'</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="305" />
        <source>The model {path} answers codes that are not in the sign codes table {table}: {names}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} responde códigos que no están en la tabla de códigos de señal {table}: {names}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="313" />
        <source>The model {path} has the metadata output = {found}; expected {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene en sus metadatos output = {found}; se esperaba {expected}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="326" />
        <source>The model {path} has the metadata crop_margin = {found}; expected a number from 0 to 2 (the fraction of the box's longer side added on each side)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} tiene en sus metadatos crop_margin = {found}; se esperaba un número de 0 a 2 (la fracción del lado mayor del recuadro que se añade a cada lado)</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="180" />
        <source>Sign codes table {path}, line {line}: cannot split the line into fields ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: no se puede dividir la línea en campos ({error})</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="186" />
        <source>Sign codes table {path}, line {line}: expected the header {expected}, found {found}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Tabla de códigos de señal {path}, línea {line}: se esperaba la cabecera {expected}, se encontró {found}</translation>
    </message>
    <message>
        <location filename="../core/signcodes.py" line="282" />
        <source>The model {path} failed on a blank {side} x {side} crop: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El modelo {path} falló con un recorte en blanco de {side} x {side}: {error}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="50" />
        <source>table</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>tabla</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="77" />
        <source>{what} file {path} is empty: expected a header row with the columns {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo de {what} {path} está vacío: se esperaba una fila de cabecera con las columnas {expected}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="85" />
        <source>{what} file {path}: missing column(s) {missing}; found {found}; expected {expected}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}: faltan columnas {missing}; se encontraron {found}; se esperaban {expected}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="93" />
        <source>{what} file {path} has a header but no data rows</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo de {what} {path} tiene cabecera pero ninguna fila de datos</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="65" />
        <source>{what} file not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró el archivo de {what}: {path}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="67" />
        <source>Cannot read {what} file {path}: it is not UTF-8 text (byte {position}); save it as CSV in UTF-8</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el archivo de {what} {path}: no es texto UTF-8 (byte {position}); guárdelo como CSV en UTF-8</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="70" />
        <source>Cannot read {what} file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el archivo de {what} {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="126" />
        <source>{what} file {path}, line {line}: {count} fields, but the header has {header_count}: decimal commas, or the delimiter inside a value? Write numbers with a decimal point (1.5, not 1,5)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}: {count} campos, pero la cabecera tiene {header_count}: ¿comas decimales, o el delimitador dentro de un valor? Escriba los números con punto decimal (1.5, no 1,5)</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="153" />
        <source>{what} file {path}, line {line}, field '{field}': expected a finite number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}, campo '{field}': se esperaba un número finito, se encontró '{value}'</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="41" />
        <source>{what} file {path}, line {line}: cannot split the line into fields ({error})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}: no se puede dividir la línea en campos ({error})</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="105" />
        <source>{what} file {path}, line {line}: field '{field}' is missing (the row has {count} fields, the header {header_count})</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}: falta el campo '{field}' (la fila tiene {count} campos, la cabecera {header_count})</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="149" />
        <source>{what} file {path}, line {line}, field '{field}': expected a number, found '{value}'</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}, campo '{field}': se esperaba un número, se encontró '{value}'</translation>
    </message>
    <message>
        <location filename="../core/tables.py" line="145" />
        <source>{what} file {path}, line {line}, field '{field}': expected a number, found '{value}': a decimal comma? Write numbers with a decimal point (1.5, not 1,5)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}, campo '{field}': se esperaba un número, se encontró '{value}': ¿una coma decimal? Escriba los números con punto decimal (1.5, no 1,5)</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="193" />
        <source>is duplicated</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>está duplicado</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="193" />
        <source>goes back in time</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>va hacia atrás</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="201" />
        <location filename="../core/trajectory.py" line="205" />
        <source>Trajectory</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>trayectoria</translation>
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
        <translation>tiempos de imagen</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="353" />
        <location filename="../core/trajectory.py" line="356" />
        <source>Poses</source>
        <extracomment>A word filled into {what}, {role} or {kind} of messages (a kind of file or CRS, or 'is duplicated'): write it to fit those messages' translations, lowercase.</extracomment>
        <translation>poses</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="194" />
        <source>{what} file {path}, {location}: time {time} {kind} (previous {previous}); times must increase strictly</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, {location}: el tiempo {time} {kind} (anterior {previous}); los tiempos deben aumentar estrictamente</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="228" />
        <source>SBET file {path}, record {record}: non-finite value (NaN or infinity)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo SBET {path}, registro {record}: valor no finito (NaN o infinito)</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="233" />
        <source>SBET file {path}: latitude/longitude out of range for radians: not an SBET, or wrong byte order</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo SBET {path}: latitud/longitud fuera de rango para radianes: no es un SBET o el orden de bytes es incorrecto</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="238" />
        <source>SBET file {path}, record {record}: roll, pitch, heading or wander out of range for radians, or the height beyond 100 km: not an SBET, or wrong byte order</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo SBET {path}, registro {record}: alabeo, cabeceo, rumbo o ángulo de deriva fuera de rango para radianes, o la altura más allá de 100 km: no es un SBET, o el orden de bytes es incorrecto</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="256" />
        <source>Trajectory file not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró el archivo de trayectoria: {path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="311" />
        <source>Trajectory file {path} has {count} sample(s): at least 2 are needed</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo de trayectoria {path} tiene {count} muestra(s): se necesitan al menos 2</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="331" />
        <source>No image time falls inside the trajectory's span [{start}, {end}]</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Ningún tiempo de imagen cae dentro del intervalo de la trayectoria [{start}, {end}]</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="427" />
        <source>Panorama folder not found: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró la carpeta de panoramas: {path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="467" />
        <source>None of the {count} panoramas listed was found in {folder}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se encontró en {folder} ninguno de los {count} panoramas de la lista</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="504" />
        <source>Panorama {image}: its position x {x}, y {y} in the target CRS lies outside the area of use of {crs} (longitude {west} to {east}, latitude {south} to {north}): choose the target CRS of the drive's region (e.g. its UTM zone)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Panorama {image}: su posición x {x}, y {y} en el SRC de destino queda fuera del área de uso de {crs} (longitud {west} a {east}, latitud {south} a {north}): elija el SRC de destino de la región del recorrido (p. ej. su zona UTM)</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="157" />
        <source>{layer}: station {station}: the quaternion qw, qx, qy, qz has norm {norm:.4f}, not 1; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}: estación {station}: el cuaternión qw, qx, qy, qz tiene norma {norm:.4f}, no 1; se esperaba la salida de Importar trayectoria</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="218" />
        <source>SBET file {path} is empty</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo SBET {path} está vacío</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="220" />
        <source>SBET file {path} is {size} bytes, not a multiple of {record} bytes (17 float64 per record): truncated or not an SBET</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El archivo SBET {path} tiene {size} bytes, que no es múltiplo de {record} bytes (17 float64 por registro): truncado o no es un SBET</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="225" />
        <source>Cannot read SBET file {path}: {error}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se puede leer el archivo SBET {path}: {error}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="272" />
        <source>{what} file {path}, line {line}, field 'image': empty image name</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}, campo 'image': nombre de imagen vacío</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="275" />
        <source>{what} file {path}, line {line}: image '{image}' already listed on line {first}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de {what} {path}, línea {line}: la imagen '{image}' ya figura en la línea {first}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="318" />
        <source>Image times file {path}, {location}: time {time} of image '{image}' is outside the trajectory's span [{start}, {end}] ({count} image(s) outside in all; set the option to skip them)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Archivo de tiempos de imagen {path}, {location}: el tiempo {time} de la imagen '{image}' está fuera del intervalo de la trayectoria [{start}, {end}] ({count} imagen(es) fuera en total; active la opción para omitirlas)</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="324" />
        <source>Skipped {count} image(s) whose time is outside the trajectory's span [{start}, {end}], the first: {image}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Se omitieron {count} imagen(es) cuyo tiempo está fuera del intervalo de la trayectoria [{start}, {end}]; la primera: {image}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="341" />
        <source>{count} image(s) fall in a trajectory gap longer than {max_gap} s; the longest gap is {gap:.3f} s around image '{image}' at time {time}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{count} imagen(es) caen en un hueco de la trayectoria de más de {max_gap} s; el hueco más largo es de {gap:.3f} s, en torno a la imagen '{image}' en el tiempo {time}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="407" />
        <source>Skipped {count} panorama(s) that are missing or unreadable; the first: {path}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Se omitieron {count} panorámica(s) que faltan o no se pueden leer; la primera: {path}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="430" />
        <source>Give either a per-image pose file, or a trajectory with image times, not both</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Indique un archivo de poses por imagen o una trayectoria con tiempos de imagen, no ambos</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="438" />
        <source>A trajectory file and an image times file are needed (or a per-image pose file instead)</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Se necesitan un archivo de trayectoria y un archivo de tiempos de imagen (o, en su lugar, un archivo de poses por imagen)</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="460" />
        <source>No target CRS given: using {crs}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>No se indicó SRC de destino: se usa {crs}</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="443" />
        <source>SBET trajectory: WGS 84 geographic with ellipsoidal heights, {count} records</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Trayectoria SBET: WGS 84 geográfico con alturas elipsoidales, {count} registros</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="449" />
        <source>Trajectory: {count} samples over {span:.1f} s</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Trayectoria: {count} muestras en {span:.1f} s</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="132" />
        <source>{layer}: station {station} has no value in the field {field}; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}: la estación {station} no tiene valor en el campo {field}; se esperaba la salida de Importar trayectoria</translation>
    </message>
    <message>
        <location filename="../core/trajectory.py" line="143" />
        <source>{layer}: station {station}, field {field}: expected a finite number, found '{value}'; expected the output of Import trajectory</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>{layer}: estación {station}, campo {field}: se esperaba un número finito, se encontró '{value}'; se esperaba la salida de Importar trayectoria</translation>
    </message>
    <message>
        <location filename="../core/viewclass.py" line="75" />
        <source>Looking for the cloud's signs in the panoramas: sign {n} of {count}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Buscando en los panoramas las señales de la nube: señal {n} de {count}</translation>
    </message>
    <message>
        <location filename="../dependencies.py" line="72" />
        <source>The installed shapely is a wheel with its own copy of GEOS, which clashes with QGIS's GEOS {geos} on Linux and crashes QGIS. Install shapely built against the system GEOS: sudo apt install libgeos-dev &amp;&amp; python3 -m pip install --user --break-system-packages --force-reinstall --no-deps --no-binary shapely "shapely&gt;=2"</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>El shapely instalado es un wheel con su propia copia de GEOS, que entra en conflicto con el GEOS {geos} de QGIS en Linux y hace que QGIS se cierre. Instale shapely compilado con el GEOS del sistema: sudo apt install libgeos-dev &amp;&amp; python3 -m pip install --user --break-system-packages --force-reinstall --no-deps --no-binary shapely "shapely&gt;=2"</translation>
    </message>
    <message>
        <location filename="../dependencies.py" line="77" />
        <source>Road Sign Inventory needs the Python package(s) {packages}, not found in QGIS's Python. Install with: {command}</source>
        <extracomment>Message: keep every {field} exactly as written; they are filled in afterwards.</extracomment>
        <translation>Inventario de señales viales necesita los paquetes de Python {packages}, que no se encuentran en el Python de QGIS. Instálelos con: {command}</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="726" />
        <source>The whole road-sign inventory: panorama stations from the trajectory, sign detection in the panoramas, ground filter and crop of the point cloud around the drive, projection of each detection into the cloud, and refinement and merging into the sign layer, with a review chip of every sign and the review report; then the sign panels and poles found in the cloud alone, fused with the image signs into the final inventory (Signs (fused): which sources found each sign, its condition, the signs the cameras missed).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>El inventario completo de señales viales: estaciones de panorama a partir de la trayectoria, detección de señales en los panoramas, filtro de suelo y recorte de la nube de puntos alrededor del recorrido, proyección de cada detección en la nube, y refinado y fusión en la capa de señales, con una miniatura de revisión de cada señal y el informe de revisión; después, los paneles de señal y los postes encontrados solo en la nube, fusionados con las señales de imagen en el inventario final (Señales (fusionadas): qué fuentes encontraron cada señal, su estado y las señales que las cámaras no vieron).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="727" />
        <source>Boresight pitch (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Boresight: cabeceo (°).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="728" />
        <source>Boresight roll (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Boresight: alabeo (°).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="729" />
        <source>Boresight yaw (°).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Boresight: guiñada (°).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="730" />
        <source>Your own ONNX sign-code classifier (format in models/README.md), or empty for the bundled one.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Su propio clasificador ONNX de códigos de señal (formato en models/README.md), o vacío para el incluido.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="731" />
        <source>The codes table of your classifier (code;name;class, format in models/README.md), or empty for the bundled German table.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>La tabla de códigos de su clasificador (code;name;class, formato en models/README.md), o vacío para la tabla alemana incluida.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="732" />
        <source>A sign's voted code whose support (code_score) is below this is left empty.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>El código votado de una señal cuyo apoyo (code_score) sea inferior a este valor se deja vacío.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="733" />
        <source>Detections scoring below this are dropped.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Se descartan las detecciones con una puntuación inferior a este valor.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="734" />
        <source>The views of the horizon ring each panorama is cut into. 6 views, turned so that their seams ahead and behind fall inside the closer views ahead and behind, take about 0.8 times the detection time; on held-out test streets with a panorama every 5 m the chain found the same signs with either, and on a test drive one false sign more with 6 (flagged for review). 8 by default; 6 trades a little accuracy for speed.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Las vistas del anillo del horizonte en que se corta cada panorama. 6 vistas, giradas para que sus uniones delante y detrás caigan dentro de las vistas más cercanas hacia delante y hacia atrás, tardan unas 0,8 veces el tiempo de detección; en calles de prueba reservadas con un panorama cada 5 m, la cadena encontró las mismas señales con ambas, y en un recorrido de prueba una señal falsa más con 6 (marcada para revisión). 8 por defecto; 6 cambia un poco de exactitud por velocidad.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="735" />
        <source>Folder of the equirectangular panoramas.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Carpeta de los panoramas equirrectangulares.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="736" />
        <source>image,time CSV of the panoramas.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>CSV image,time de los panoramas.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="737" />
        <source>Lever arm x, forward (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Brazo de palanca x, adelante (m).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="738" />
        <source>Lever arm y, right (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Brazo de palanca y, derecha (m).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="739" />
        <source>Lever arm z, down (m).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Brazo de palanca z, abajo (m).</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="740" />
        <source>Your own ONNX detector, or empty for the bundled one.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Su propio detector ONNX, o vacío para usar el incluido.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="741" />
        <source>The drive's LiDAR cloud.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>La nube LiDAR del recorrido.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="742" />
        <source>Reads what each sign says (its code, such as DE:274[50] for speed limit 50) with the sign-code classifier; unchecked, the code fields stay empty.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Lee lo que dice cada señal (su código, como DE:274[50] para el límite de velocidad 50) con el clasificador de códigos de señal; si se desmarca, los campos de código quedan vacíos.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="743" />
        <source>Detects in as few panoramas as leave no more than this distance between one detected in and the next (the ones between are skipped); 0 detects in every panorama. On held-out test streets a panorama every 5 m found every sign, every 10 m lost 2 in 45.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>Detecta en tan pocos panoramas como permitan que entre uno detectado y el siguiente no haya más que esta distancia (los intermedios se omiten); 0 detecta en todos los panoramas. En calles de prueba reservadas, un panorama cada 5 m encontró todas las señales; cada 10 m se perdieron 2 de 45.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="744" />
        <source>Projected CRS of the outputs: the point cloud's CRS.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>SRC proyectado de las salidas: el SRC de la nube de puntos.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="745" />
        <source>time,x,y,z,roll,pitch,heading CSV, or an Applanix SBET.</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>CSV time,x,y,z,roll,pitch,heading, o un SBET de Applanix.</translation>
    </message>
    <message>
        <location filename="../models/sign_inventory.model3" line="746" />
        <source>CRS of the trajectory positions (ignored for an SBET).</source>
        <extracomment>Help of the shipped Processing model (models/*.model3).</extracomment>
        <translation>SRC de las posiciones de la trayectoria (se ignora para un SBET).</translation>
    </message>
</context>
<context>
    <name>RoadSignsAlgorithm</name>
    <message>
        <location filename="../algorithms/base.py" line="111" />
        <source>Road sign inventory</source>
        <translation>Inventario de señales viales</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="281" />
        <source>Cancelled: nothing was written.</source>
        <translation>Cancelado: no se escribió nada.</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="287" />
        <source>Out of memory: nothing was written. Crop the point cloud (Ground filter with a crop layer) or process the drive in parts.</source>
        <translation>Memoria insuficiente: no se escribió nada. Recorte la nube de puntos (Filtro de suelo con una capa de recorte) o procese el recorrido por partes.</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="290" />
        <source>Cannot read or write {}: {}. Nothing was written.</source>
        <translation>No se puede leer o escribir {}: {}. No se escribió nada.</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="293" />
        <source>Unexpected error ({}: {}); nothing was written. The details are in the QGIS message log (Road sign inventory); please report them.</source>
        <translation>Error inesperado ({}: {}); no se escribió nada. Los detalles están en el registro de mensajes de QGIS (Road sign inventory); por favor, notifíquelos.</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="298" />
        <source>{} However, these partial outputs could not be removed: {}</source>
        <translation>{} Sin embargo, estas salidas parciales no se pudieron eliminar: {}</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="175" />
        <source>Accepted: one LAS/LAZ file (COPC too), a virtual point cloud (.vpc, e.g. from QGIS's Build virtual point cloud) listing tiles, or a folder of LAS/LAZ tiles (type or paste the folder's path). Tiles must share the point format and the CRS.</source>
        <translation>Se admite: un archivo LAS/LAZ (también COPC), una nube de puntos virtual (.vpc, p. ej. de «Construir nube de puntos virtual» de QGIS) que enumera teselas, o una carpeta de teselas LAS/LAZ (escriba o pegue la ruta de la carpeta). Las teselas deben compartir el formato de punto y el SRC.</translation>
    </message>
    <message>
        <location filename="../algorithms/base.py" line="175" />
        <source>Point clouds (*.las *.laz *.vpc *.LAS *.LAZ *.VPC);;LAS/LAZ (*.las *.laz *.LAS *.LAZ);;Virtual point clouds (*.vpc *.VPC);;All files or a folder of tiles (*)</source>
        <translation>Nubes de puntos (*.las *.laz *.vpc *.LAS *.LAZ *.VPC);;LAS/LAZ (*.las *.laz *.LAS *.LAZ);;Nubes de puntos virtuales (*.vpc *.VPC);;Todos los archivos o una carpeta de teselas (*)</translation>
    </message>
</context>
<context>
    <name>RoadSignsProvider</name>
    <message>
        <location filename="../provider/provider.py" line="31" />
        <source>Road sign inventory</source>
        <translation>Inventario de señales viales</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="34" />
        <source>Road sign inventory from mobile mapping (panoramas, trajectory, LiDAR)</source>
        <translation>Inventario de señales viales a partir de cartografía móvil (panoramas, trayectoria, LiDAR)</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="47" />
        <source>PDAL executable for the ground filter (empty: search PATH and QGIS)</source>
        <translation>Ejecutable de PDAL para el filtro de suelo (vacío: buscar en el PATH y en QGIS)</translation>
    </message>
</context>
<context>
    <name>ShippedModel</name>
    <message>
        <location filename="../provider/provider.py" line="94" />
        <source>Sign inventory (whole chain)</source>
        <translation>Inventario de señales (cadena completa)</translation>
    </message>
    <message>
        <location filename="../provider/provider.py" line="107" />
        <source>Road sign inventory</source>
        <translation>Inventario de señales viales</translation>
    </message>
</context>
</TS>