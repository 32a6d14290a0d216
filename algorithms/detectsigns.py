"""roadsigns:detectsigns - run an ONNX sign detector on every station's panorama and write
one ray per detection (LineStringZ from the panorama centre through the box centre)."""
import os

import numpy as np
from qgis.core import (Qgis, QgsFeature, QgsFeatureSink, QgsGeometry,
                       QgsLineString, QgsPoint, QgsProcessingException,
                       QgsProcessingParameterBoolean, QgsProcessingParameterFeatureSource,
                       QgsProcessingParameterFile, QgsProcessingParameterFeatureSink, QgsProcessingOutputNumber)

from ..core.detector import DEFAULT_MIN_BOX_PX
from ..provider.i18n import tr
from .base import RoadSignsAlgorithm
from .layers import DOUBLE, INT, TEXT, make_fields

PLUGIN_DIR = os.path.dirname(os.path.dirname(__file__))
BUNDLED_MODEL = os.path.join(PLUGIN_DIR, "models", "roadsigns.onnx")
STATION_FIELDS = ("station_id", "image", "path", "time", "x", "y", "z", "qw", "qx", "qy", "qz",
                  "heading", "width", "height")
DETECTION_FIELDS = [("det_id", INT), ("station_id", INT),
                    ("image", TEXT), ("class", TEXT),
                    ("score", DOUBLE), ("u0", DOUBLE),
                    ("v0", DOUBLE), ("u1", DOUBLE),
                    ("v1", DOUBLE), ("n_views", INT),
                    ("time", DOUBLE), ("x", DOUBLE),
                    ("y", DOUBLE), ("z", DOUBLE),
                    ("qw", DOUBLE), ("qx", DOUBLE),
                    ("qy", DOUBLE), ("qz", DOUBLE),
                    ("heading", DOUBLE), ("width", INT),
                    ("height", INT)]


def read_stations(source, label):
    """Station attributes as lists, checking the contract's fields are there."""
    names = source.fields().names()
    missing = [f for f in STATION_FIELDS if f not in names]
    if missing:
        raise QgsProcessingException(
            tr("{layer}: missing field(s) {missing}; fields found: {found}; expected the output "
               "of Import trajectory").format(layer=label, missing=", ".join(missing),
                                              found=", ".join(names)))
    rows = []
    for feature in source.getFeatures():
        rows.append({f: feature[f] for f in STATION_FIELDS})
    return rows


class DetectSigns(RoadSignsAlgorithm):
    ALGORITHM_ID = "detectsigns"
    DISPLAY_NAME = "Detect signs in panoramas"
    REQUIRES = ("numpy", "cv2", "onnxruntime")
    SHORT_DESCRIPTION = "Runs an ONNX sign detector on each panorama; one ray per detected sign."
    HELP = (
        "Cuts each station's equirectangular panorama into overlapping perspective views "
        "(a horizon ring, and an upward ring for overhead signs), runs the ONNX detector on "
        "each view, maps the boxes back to panorama pixels and merges the same sign found in "
        "two views.<br><br>The <b>model</b> is the bundled one when left empty, or your own "
        "ONNX export: Ultralytics YOLOv8/11 ([1, 4+nc, N]), YOLOv5/7 ([1, N, 5+nc]) or a model "
        "with NMS built in ([1, N, 6]). Class names come from the model's metadata (Ultralytics "
        "<i>names</i>) or a labels file (one name per line).<br><br>Output: one line per "
        "detection from the panorama centre along the ray through the box centre, "
        "<i>Ray length</i> long, with the box (u0, v0, u1, v1 in panorama pixels; across the "
        "±180° seam u1 exceeds the width) and the station's pose. A panorama that cannot be "
        "read is skipped with a warning and counted.")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterFeatureSource(
            "STATIONS", self.tr("Panorama stations"), [Qgis.ProcessingSourceType.VectorPoint]),
            "The output of Import trajectory: one point per panorama with its pose and path.")
        self.add(QgsProcessingParameterFile(
            "MODEL", self.tr("ONNX model (empty: the bundled model)"),
            behavior=Qgis.ProcessingFileParameterBehavior.File, optional=True,
            fileFilter=self.tr("ONNX models (*.onnx);;All files (*.*)")),
            "A YOLO-family ONNX detector. Empty uses the model bundled with the plugin.")
        self.add_number(
            "CONFIDENCE", "Minimum confidence", 0.4,
            "Detections scoring below this (0-1) are dropped.", minimum=0.0, maximum=1.0)
        self.add_number(
            "MIN_SIZE", "Smallest sign kept (panorama pixels)", DEFAULT_MIN_BOX_PX,
            "Detections whose box is shorter than this on its shorter side are dropped: signs "
            "that small are boxed a few pixels off and their class is unsure, and the drive sees "
            "them again, larger, from the next stations. 0 keeps every detection.",
            minimum=0.0, advanced=True)
        self.add(QgsProcessingParameterFile(
            "LABELS", self.tr("Class names file (optional)"),
            behavior=Qgis.ProcessingFileParameterBehavior.File, optional=True,
            fileFilter=self.tr("Text files (*.txt);;All files (*.*)")),
            "One class name per line, in the model's class order; needed when the model has no "
            "names in its metadata and no labels file beside it.", advanced=True)
        self.add_number(
            "MAX_RANGE", "Ray length (m)", 50.0,
            "Length of each detection ray from the panorama centre, in metres.", minimum=1.0, advanced=True)
        self.add(QgsProcessingParameterBoolean(
            "UPWARD_VIEWS", self.tr("Also look upwards (overhead and gantry signs)"), defaultValue=True),
            "Adds a ring of views tilted 35° up; unchecked halves the work but misses signs "
            "high above the road close to the vehicle.", advanced=True)
        self.add_number(
            "THREADS", "CPU threads (0: all)", 0,
            "Threads onnxruntime may use on the CPU; 0 lets it use every core.", minimum=0, integer=True, advanced=True)
        self.add(QgsProcessingParameterFeatureSink(
            "OUTPUT", self.tr("Detections"), type=Qgis.ProcessingSourceType.VectorLine),
            "LineStringZ layer, one ray per detection, with det_id, station_id, image, class, score, "
            "u0, v0, u1, v1, n_views and the station's pose fields.")
        self.addOutput(QgsProcessingOutputNumber("DETECTIONS", self.tr("Number of detections")))
        self.addOutput(QgsProcessingOutputNumber("SKIPPED_IMAGES", self.tr("Panoramas skipped")))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        self.check_dependencies()
        from ..core import geometry
        from ..core.detector import Detector, detect_drive
        from ..core.panorama import ViewSet

        source = self.parameterAsSource(parameters, "STATIONS", context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, "STATIONS"))
        stations = read_stations(source, self.tr("Panorama stations"))
        model_path = self.parameterAsFile(parameters, "MODEL", context) or BUNDLED_MODEL
        if not os.path.isfile(model_path):
            raise QgsProcessingException(self.tr(
                "ONNX model not found: {}{}").format(model_path, self.tr(
                    " (no model is bundled with this version: give your own)")
                    if model_path == BUNDLED_MODEL else ""))
        labels_path = self.parameterAsFile(parameters, "LABELS", context)
        confidence = self.parameterAsDouble(parameters, "CONFIDENCE", context)
        ray_length_m = self.parameterAsDouble(parameters, "MAX_RANGE", context)
        progress = self.progress(feedback)
        with self.core_errors():
            class_names = None
            if labels_path:
                from ..core.detector import read_labels_file
                class_names = read_labels_file(labels_path)
            detector = Detector(model_path, class_names=class_names,
                                threads=self.parameterAsInt(parameters, "THREADS", context))
            feedback.pushInfo(detector.info().describe())
            views = ViewSet.default(size_px=detector.input_size,
                                    upward=self.parameterAsBoolean(parameters, "UPWARD_VIEWS", context))
            feedback.pushInfo(self.tr("{} panoramas, {} views each").format(len(stations), len(views)))
            found = detect_drive(detector, [s["path"] for s in stations], views, confidence,
                                 min_box_px=self.parameterAsDouble(parameters, "MIN_SIZE", context),
                                 progress=progress.sub(0.0, 0.95))
        if found.skipped:
            feedback.pushWarning(self.tr("Skipped {} panorama(s) that could not be read.").format(
                len(found.skipped)))

        fields = make_fields(DETECTION_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, "OUTPUT", context, fields,
                                             Qgis.WkbType.LineStringZ, source.sourceCrs())
        if sink is None:
            raise QgsProcessingException(self.invalidSinkError(parameters, "OUTPUT"))
        det_id = 0
        for station, detections in zip(stations, found.per_image):
            if detections is None or len(detections) == 0:
                continue
            q = np.array([station["qw"], station["qx"], station["qy"], station["qz"]], float)
            centre = np.array([station["x"], station["y"], station["z"]], float)
            rays = geometry.box_centre_ray_world(detections.u0, detections.v0, detections.u1,
                                                 detections.v1, station["width"], station["height"], q)
            for k in range(len(detections)):
                det_id += 1
                end = centre + ray_length_m * rays[k]
                feature = QgsFeature(fields)
                feature.setGeometry(QgsGeometry(QgsLineString([QgsPoint(*centre), QgsPoint(*end)])))
                feature.setAttributes([
                    det_id, station["station_id"], station["image"], detections.class_name[k],
                    float(detections.score[k]), float(detections.u0[k]), float(detections.v0[k]),
                    float(detections.u1[k]), float(detections.v1[k]), int(detections.n_views[k]),
                    station["time"], *(float(c) for c in centre), *(float(c) for c in q),
                    station["heading"], station["width"], station["height"]])
                sink.addFeature(feature, QgsFeatureSink.Flag.FastInsert)
        feedback.setProgress(100)
        feedback.pushInfo(self.tr("{} detections in {} panoramas ({} skipped).").format(
            det_id, len(stations) - len(found.skipped), len(found.skipped)))
        return {"OUTPUT": dest_id, "DETECTIONS": det_id, "SKIPPED_IMAGES": len(found.skipped)}
