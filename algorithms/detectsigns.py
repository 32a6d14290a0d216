"""roadsigns:detectsigns - run an ONNX sign detector on every station's panorama and write
one ray per detection (LineStringZ from the panorama centre through the box centre)."""
import os
from functools import partial

from qgis.core import (
    Qgis,
    QgsGeometry,
    QgsLineString,
    QgsPoint,
    QgsProcessingException,
    QgsProcessingOutputNumber,
)

from ..core.detections import DETECTION_FIELDS, drive_detections
from ..core.detector import DEFAULT_CONFIDENCE, DEFAULT_MIN_BOX_PX, DEFAULT_STATION_SPACING_M, spaced_stations
from ..core.panorama import (
    DEFAULT_FORE_AFT_VIEWS,
    DEFAULT_HORIZON_VIEWS,
    DEFAULT_UPWARD_VIEWS,
    HORIZON_BAND,
    HORIZON_BAND_SIZE_PX,
    HORIZON_HFOV_DEG,
    HORIZON_RINGS,
)
from ..core.rescue import DEFAULT_RESCUE_CONFIDENCE, DEFAULT_RULE
from ..core.signcodes import is_code
from ..core.trajectory import STATION_FIELDS, Stations
from ..core.zoomlook import DEFAULT_EDGE_ON, DEFAULT_EDGE_ON_LOOK, DEFAULT_ZOOM, DEFAULT_ZOOMED_LOOK
from .base import RoadSignsAlgorithm
from .codeparams import ReadsCodes
from .layers import check_layer_extent, check_metric_crs, qgs_fields, read_columns, write_records
from .paths import BUNDLED_MODEL


class DetectSigns(ReadsCodes, RoadSignsAlgorithm):
    ALGORITHM_ID = "detectsigns"
    REQUIRES = ("numpy", "cv2", "onnxruntime")
    STATIONS = "STATIONS"
    MODEL = "MODEL"
    CONFIDENCE = "CONFIDENCE"
    RESCUE_CONFIDENCE = "RESCUE_CONFIDENCE"
    MIN_SIZE = "MIN_SIZE"
    LABELS = "LABELS"
    MAX_RANGE = "MAX_RANGE"
    UPWARD_VIEWS = "UPWARD_VIEWS"
    FORE_AFT_VIEWS = "FORE_AFT_VIEWS"
    HORIZON_VIEWS = "HORIZON_VIEWS"
    ZOOMED_LOOK = "ZOOMED_LOOK"
    EDGE_ON_LOOK = "EDGE_ON_LOOK"
    THREADS = "THREADS"
    STATION_SPACING = "STATION_SPACING_M"
    OUTPUT = "OUTPUT"
    DETECTIONS = "DETECTIONS"
    SKIPPED_IMAGES = "SKIPPED_IMAGES"

    def displayName(self):
        return self.tr("Detect signs in panoramas")

    def shortDescription(self):
        return self.tr("Runs an ONNX sign detector on each panorama; one ray per detected sign.")

    def shortHelpString(self):
        return self.tr(
            "Cuts each station's equirectangular panorama into overlapping perspective views "
            "(a horizon ring, two closer views ahead and behind, and two views upwards for overhead "
            "signs), runs the ONNX detector on each view, maps the boxes back to panorama pixels and "
            "merges the same sign found in two views. A box much taller than wide (a sign passed close by, "
            "seen nearly edge-on, which the detector boxes about twice as wide as its face) is narrowed to "
            "the columns that show sign colours (saturated red, blue or yellow).<br><br>The <b>model</b> is "
            "the bundled one when "
            "left empty, or your own "
            "ONNX export: Ultralytics YOLOv8/11 ([1, 4+nc, N]), YOLOv5/7 ([1, N, 5+nc]) or a model "
            "with NMS built in ([1, N, 6]). Class names come from the model's metadata (Ultralytics "
            "<i>names</i>) or a labels file (one name per line).<br><br>Output: one line per "
            "detection from the panorama centre along the ray through the box centre, "
            "<i>Ray length</i> long, with the box (u0, v0, u1, v1 in panorama pixels; across the "
            "±180° seam u1 exceeds the width) and the station's pose. A panorama that cannot be "
            "read is skipped with a warning and counted.<br><br><b>Sign codes</b>: a second, small ONNX "
            "model (the bundled sign-code classifier, or your own) reads what each detected sign says, "
            "from a rectified crop of the panorama around its box at the panorama's own resolution: "
            "<i>code</i> (such as DE:274[50], speed limit 50, from the codes table; <i>other</i> when it "
            "knows none) and <i>code_score</i> (its probability). Refine signs votes them across the "
            "views of each sign. The classifier's format is in models/README.md (section <i>Sign-code "
            "classifier: the format</i>).")

    def initAlgorithm(self, config=None):
        self.add_source(
            self.STATIONS, self.tr("Panorama stations"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Import trajectory: one point per panorama with its pose and path."))
        self.add_file(
            self.MODEL, self.tr("ONNX model (empty: the bundled model)"),
            self.tr("A YOLO-family ONNX detector. Empty uses the model bundled with the plugin."),
            file_filter=self.tr("ONNX models (*.onnx);;All files (*.*)"), optional=True)
        self.add_number(
            self.CONFIDENCE, self.tr("Minimum confidence"), DEFAULT_CONFIDENCE,
            self.tr("Detections scoring below this (0-1) are dropped."), minimum=0.0, maximum=1.0)
        self.add_number(
            self.RESCUE_CONFIDENCE, self.tr("Second look from confidence"), DEFAULT_RESCUE_CONFIDENCE,
            self.tr("Boxes the detector scores from this value up to the minimum confidence get a second look: "
                    "one is kept when the sign-code classifier reads a class of signs in it with a probability "
                    "of at least {score} (the probabilities of the codes of that class added up: a speed limit "
                    "whose digits are unsure is still a prohibitory sign), its box is at least {px} px on its "
                    "shorter side (under {small_px} px only from a detector score of {small_score}) and at least "
                    "{share:.0%} of it is sign colours (saturated red, blue or yellow); it then takes that class "
                    "and keeps its own score. On real street photographs (GTSDB 500-599) at the default minimum "
                    "confidence this finds 0.958 of the signs at a precision of 0.971, against 0.803 at 0.966 "
                    "without it, for under 5 % of the detection time. The second look also drops any box the "
                    "classifier reads as the back of a sign (a plain grey plate facing away: its face is seen "
                    "from the stations on the other side). Needs the sign codes to be read; a value "
                    "at or above the minimum confidence switches it off.").format(
                        score=DEFAULT_RULE.min_class_score, px=int(DEFAULT_RULE.min_box_px),
                        small_px=int(DEFAULT_RULE.small_box_px), small_score=DEFAULT_RULE.small_min_score,
                        share=DEFAULT_RULE.min_sheeting),
            minimum=0.0, maximum=1.0, advanced=True)
        self.add_number(
            self.MIN_SIZE, self.tr("Smallest sign kept (panorama pixels)"), DEFAULT_MIN_BOX_PX,
            self.tr("Detections whose box is shorter than this on its shorter side are dropped: signs "
                    "that small are boxed a few pixels off and their class is unsure, and the drive sees "
                    "them again, larger, from the next stations. 0 keeps every detection."),
            minimum=0.0, advanced=True)
        self.add_file(
            self.LABELS, self.tr("Class names file (optional)"),
            self.tr("One class name per line, in the model's class order; needed when the model has no "
                    "names in its metadata and no labels file beside it."),
            file_filter=self.tr("Text files (*.txt);;All files (*.*)"), optional=True, advanced=True)
        self.add_number(
            self.MAX_RANGE, self.tr("Ray length (m)"), 50.0,
            self.tr("Length of each detection ray from the panorama centre, in metres."),
            minimum=1.0, advanced=True)
        self.add_boolean(
            self.UPWARD_VIEWS, self.tr("Also look upwards (overhead and gantry signs)"), DEFAULT_UPWARD_VIEWS,
            self.tr("Adds two views tilted 35° up, over the road ahead and behind, for gantry and overhead signs "
                    "close to the vehicle, above the horizon views. On by default: on five held-out test streets "
                    "they raised the gantry panels found in a single panorama from 86 % to 91 % for 1.2 times "
                    "the detection time. A box these views cut at their left or right edge is dropped unless "
                    "another view finds the same sign: signs beside the road are seen whole in the horizon "
                    "views. With the second look, a box these views find alone and the sign-code classifier reads "
                    "as no sign ('other': a facade's dark window, say) is dropped too. Switch it off to save that "
                    "time where a drive has no overhead signs."), advanced=True)
        self.add_boolean(
            self.FORE_AFT_VIEWS, self.tr("Look ahead and behind more closely (small, far signs)"),
            DEFAULT_FORE_AFT_VIEWS,
            self.tr("Adds two views of 53° straight ahead and behind, with 1.5 times the pixels per degree of "
                    "the horizon views (at a 4096 px panorama's own density), for signs far along the road. Real "
                    "signs need the pixels: on real street photographs at the horizon views' density the "
                    "detector found 0.82 of the signs (GTSDB 500-599) and 0.54 of 376 held-out real signs "
                    "pasted as distant ones; with these views 0.93 and 0.69, precision within 0.01. On held-out "
                    "generated panoramas: 0.906 of the signs per panorama instead of 0.879. They cost 1.24 "
                    "times the detection time. On by default; turn it off only for speed on drives with "
                    "panoramas close together (every sign is then seen from many stations)."), advanced=True)
        self.add_enum(
            self.HORIZON_VIEWS, self.tr("Horizon views"),
            [(n, (self.tr("{n} views of {width:g}°") if not yaw else
                  self.tr("{n} views of {width:g}°, turned {yaw:g}°")).format(n=n, width=HORIZON_HFOV_DEG, yaw=yaw))
             for n, yaw in HORIZON_RINGS.items()]
            + [(HORIZON_BAND, self.tr("One band of {width} × {height} px").format(
                width=HORIZON_BAND_SIZE_PX[0], height=HORIZON_BAND_SIZE_PX[1]))], DEFAULT_HORIZON_VIEWS,
            self.tr("How many views of 80° across the horizon ring has. 8 views overlap by 35°. 6 views overlap by "
                    "20° and are turned by 30°, so that their seams ahead and behind fall inside the fore-and-aft "
                    "views: the detection takes 0.8-0.87 times the time. In single panoramas of five held-out "
                    "test streets, 6 views found 0.946 of the signs at a precision of 0.988, against 0.948 at 0.982 "
                    "with 8: they lose a few signs 14-20 px high and a few very close ones that no longer fit whole "
                    "into one view. Through the whole chain, on three held-out streets with a panorama every 5 m, "
                    "both rings found all 137 signs, with no false sign and positions within 3 mm of each other in "
                    "median; on the first 100 m of a test drive with a panorama every 1.2 m, the ring of 6 added one "
                    "false sign (seen in one panorama and scored just over the minimum confidence, flagged for "
                    "review) to the 6 true ones. The third choice sees the horizon as one equirectangular band "
                    "of 3264 × 448 px (8.5 px a degree, ±26° of elevation), which the detector runs on whole: "
                    "it needs a model whose input size is free, as the bundled detector's is. In single "
                    "panoramas of fifteen held-out test streets it found 2,632 of 2,778 signs at a precision of "
                    "0.976, against 2,638 at 0.968 for the ring of 8, in 0.81 times the processor time; through "
                    "the whole chain on fourteen held-out streets it found all 632 signs, as the ring does, but "
                    "with one false sign (a logo printed on a billboard) and three sign codes fewer. 8 by default; "
                    "6 and the band trade a little accuracy for speed."), advanced=True)
        self.add_boolean(
            self.ZOOMED_LOOK, self.tr("Look again, closer, at small boxes scored under the minimum confidence"),
            DEFAULT_ZOOMED_LOOK,
            self.tr("A box of at most {px} px that the detector scores from {score} up to the minimum confidence "
                    "is cut again from the panorama at a higher pixel density (the box {box_px} px across) and "
                    "detected once more; it is kept when the detector then scores it at the minimum confidence or "
                    "more, with that score, class and box. All of a panorama's such boxes go through the detector "
                    "together, in one extra run. It finds far signs, 15-25 px across: on 376 held-out real signs "
                    "pasted into street photographs the signs found rose from 0.79 to 0.87 (those 14-20 px high "
                    "from 0.34 to 0.59) at a precision of 0.96; on real street photographs (GTSDB 500-599) the "
                    "recall stayed at 0.958 and the precision went from 0.971 to 0.958. It costs 1.05-1.09 times "
                    "the detection time. On by default.").format(
                        px=int(DEFAULT_ZOOM.max_box_px), score=DEFAULT_ZOOM.min_score, box_px=int(DEFAULT_ZOOM.box_px)),
            advanced=True)
        self.add_boolean(
            self.EDGE_ON_LOOK, self.tr("Look again, stretched across, at tall boxes of signs seen edge-on"),
            DEFAULT_EDGE_ON_LOOK,
            self.tr("A sign passed close by is seen far off its face's normal, and the view squeezes it to a sliver "
                    "that the detector scores low. A box at least {ratio} times as tall as wide, of at most {px} px, "
                    "that the detector scores from {score} up to the minimum confidence is cut again from the "
                    "panorama (its height {box_px} px) and stretched {stretch} times across, so that the sign's "
                    "face is about as wide as tall again, and detected once more; it is kept when the detector "
                    "then scores it at the minimum confidence or more. Its tiles go into the zoomed look's detector "
                    "runs, and a box both looks take keeps the higher score. On five held-out generated streets it "
                    "found 701 of 734 signs in single panoramas, against 697 without it (signs seen more than 70° off "
                    "their face's normal: 27 of 45 against 23), with one false box fewer, in 1.02 to 1.03 times the "
                    "processor time; real signs of street photographs squeezed across to 0.3 of their width are "
                    "scored 0.5 or more in 44 of 50 cases stretched, against 11 as they are. On the real street "
                    "photographs themselves it changed nothing. On by default.").format(
                        ratio=DEFAULT_EDGE_ON.min_height_to_width, px=int(DEFAULT_EDGE_ON.max_box_px),
                        score=DEFAULT_EDGE_ON.min_score, box_px=int(DEFAULT_EDGE_ON.box_px),
                        stretch=DEFAULT_EDGE_ON.stretch),
            advanced=True)
        self.add_number(
            self.STATION_SPACING, self.tr("Detect in a panorama at least every (m)"), DEFAULT_STATION_SPACING_M,
            self.tr("Detects in as few panoramas as leave no more than this distance between one panorama "
                    "detected in and the next; the ones between are skipped (not read, no detections). The "
                    "first and the last panorama are always detected in, and a drive whose panoramas stand "
                    "this far apart or more keeps every one. A sign stays in view over many stations, so "
                    "skipping saves detection time in proportion, but each sign is then seen from fewer "
                    "stations: fewer rays to place it, and a sign visible from only a few stations (small, or "
                    "hidden behind trees or vehicles) may be missed. Measured on two held-out test streets with "
                    "a panorama every 5 m: every panorama found all 46 and 45 signs; 10 m (every other one) lost "
                    "2 of each, 15 m lost 11 of 46. On two held-out streets with a panorama every 1.25 m, one every "
                    "5 m found the same 87 signs as one every 2.5 m, in 0.55 times the detection time; the median "
                    "position error went from 11 to 13 mm, and one sign, read in 3 of its 7 views instead of 13 "
                    "of 19, was left without a code. 0 detects in every panorama."),
            minimum=0.0, advanced=True)
        self.add_number(
            self.THREADS, self.tr("CPU threads (0: all)"), 0,
            self.tr("Threads onnxruntime may use on the CPU; 0 lets it use every core."),
            minimum=0, integer=True, advanced=True)
        self.add_code_parameters(self.tr("in a crop around each detection, voted later across the views of "
                                         "each sign by Refine and merge signs"))
        self.add_sink(
            self.OUTPUT, self.tr("Detections"), Qgis.ProcessingSourceType.VectorLine,
            self.tr("LineStringZ layer, one ray per detection, with det_id, station_id, image, class, "
                    "score, code, code_score, u0, v0, u1, v1, n_views and the station's pose fields."))
        self.addOutput(QgsProcessingOutputNumber(self.DETECTIONS, self.tr("Number of detections")))
        self.addOutput(QgsProcessingOutputNumber(self.SKIPPED_IMAGES, self.tr("Panoramas skipped")))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.detections import read_codes
        from ..core.detector import Detector, detect_drive, read_labels_file
        from ..core.panorama import ViewSet
        from ..core.rescue import second_look

        source = self.source(parameters, self.STATIONS, context)
        check_metric_crs(source.sourceCrs(), self.tr("Panorama stations"))
        rows = read_columns(source, STATION_FIELDS, self.tr("Panorama stations"), feedback)
        model_path = self.parameterAsFile(parameters, self.MODEL, context) or BUNDLED_MODEL
        if not os.path.isfile(model_path):
            raise QgsProcessingException(self.tr("ONNX model not found: {}").format(model_path))
        labels_path = self.parameterAsFile(parameters, self.LABELS, context)
        confidence = self.parameterAsDouble(parameters, self.CONFIDENCE, context)
        ray_length_m = self.parameterAsDouble(parameters, self.MAX_RANGE, context)
        progress = self.progress(feedback)
        with self.core_errors():
            stations = Stations.from_records(rows, self.tr("Panorama stations"))
            check_layer_extent(source, self.tr("Panorama stations"))
            class_names = read_labels_file(labels_path) if labels_path else None
            detector = Detector(model_path, class_names=class_names,
                                threads=self.parameterAsInt(parameters, self.THREADS, context))
            feedback.pushInfo(detector.info().describe())
            views = ViewSet.default(size_px=detector.input_size,
                                    upward=self.parameterAsBoolean(parameters, self.UPWARD_VIEWS, context),
                                    fore_aft=self.parameterAsBoolean(parameters, self.FORE_AFT_VIEWS, context),
                                    horizon_views=self.enum_name(parameters, self.HORIZON_VIEWS, context))
            for view in views:
                if view.own_size:               # the horizon band: checked before any work
                    detector.check_runs(view.width_px, view.height_px)
            feedback.pushInfo(self.tr("{} panoramas, {} views each").format(len(stations), len(views)))
            classifier = self.code_classifier(parameters, context, feedback,
                                              self.parameterAsInt(parameters, self.THREADS, context))
            spacing_m = self.parameterAsDouble(parameters, self.STATION_SPACING, context)
            chosen = spaced_stations(stations.xyz_world, spacing_m)
            if len(chosen) < len(stations):
                feedback.pushInfo(self.tr("Detecting in {} of the {} panoramas: one at least every {} m of the "
                                          "drive, the ones between skipped.").format(
                                              len(chosen), len(stations), spacing_m))
            rescue_from = self.parameterAsDouble(parameters, self.RESCUE_CONFIDENCE, context)
            second_look_on = classifier is not None and rescue_from < confidence
            if classifier is None:
                on_panorama = None
            elif second_look_on:
                on_panorama = partial(second_look, classifier, class_names=detector.class_names)
                feedback.pushInfo(self.tr("Second look: boxes scored from {} to {} are kept where the sign-code "
                                          "classifier reads a code.").format(rescue_from, confidence))
            else:
                on_panorama = partial(read_codes, classifier)
            looks = []
            if self.parameterAsBoolean(parameters, self.EDGE_ON_LOOK, context):
                looks.append(DEFAULT_EDGE_ON)
                feedback.pushInfo(self.tr("Edge-on look: boxes at least {} times as tall as wide scored from {} to {} "
                                          "are detected again stretched {} times across.").format(
                                              DEFAULT_EDGE_ON.min_height_to_width, DEFAULT_EDGE_ON.min_score,
                                              confidence, DEFAULT_EDGE_ON.stretch))
            if self.parameterAsBoolean(parameters, self.ZOOMED_LOOK, context):
                looks.append(DEFAULT_ZOOM)
                feedback.pushInfo(self.tr("Zoomed look: boxes of at most {} px scored from {} to {} are detected again "
                                          "at a higher pixel density.").format(int(DEFAULT_ZOOM.max_box_px),
                                                                               DEFAULT_ZOOM.min_score, confidence))
            found = detect_drive(detector, [stations.path[k] for k in chosen], views, confidence,
                                 min_box_px=self.parameterAsDouble(parameters, self.MIN_SIZE, context),
                                 progress=progress.sub(0.0, 0.95), on_panorama=on_panorama,
                                 candidate_confidence=rescue_from if second_look_on else None, zoom=looks)
        if found.skipped:
            feedback.pushWarning(self.tr("Skipped {} panorama(s) that could not be read.").format(
                len(found.skipped)))

        per_image = [None] * len(stations)
        for k, result in zip(chosen, found.per_image):
            per_image[k] = result
        detections = drive_detections(stations, per_image)
        if len(detections) == 0:
            feedback.pushWarning(self.tr("No sign was detected: the detections layer is empty."))
        ends = detections.ray_ends_world(ray_length_m) if len(detections) else []
        rays = [QgsGeometry(QgsLineString([QgsPoint(*start), QgsPoint(*end)]))
                for start, end in zip(detections.centre_world, ends)]
        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(DETECTION_FIELDS),
                                  Qgis.WkbType.LineStringZ, source.sourceCrs())
        write_records(sink, DETECTION_FIELDS, detections.records(), rays, feedback, (95, 100))
        feedback.setProgress(100)
        feedback.pushInfo(self.tr("{} detections in {} panoramas ({} skipped).").format(
            len(detections), len(chosen) - len(found.skipped), len(found.skipped)))
        if classifier is not None and len(detections):
            coded = sum(1 for c in detections.code if is_code(c))
            feedback.pushInfo(self.tr("Sign codes read in {} of the {} detections (the others: other, or "
                                      "a sign whose code the table lacks).").format(coded, len(detections)))
        return {self.OUTPUT: dest_id, self.DETECTIONS: len(detections), self.SKIPPED_IMAGES: len(found.skipped)}

