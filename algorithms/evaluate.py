"""roadsigns:evaluate - a sign layer against reference sign panels: precision, recall,
position, height and azimuth errors, class and code accuracy, and an HTML report."""
import math
import os

import numpy as np
from qgis.core import (
    Qgis,
    QgsCoordinateTransform,
    QgsCsException,
    QgsFeatureRequest,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsVectorLayer,
)

from ..core.crs import check_extent
from ..core.evaluate import (
    CODE_CONFUSIONS,
    OUTPUT_NAMES,
    SignSet,
    check_overlap,
    confusions_text,
    evaluate,
    read_reference_csv,
    write_html_report,
)
from .base import RoadSignsAlgorithm
from .i18n import tr
from .layers import check_layer_extent, check_metric_crs, crs_for_pyproj

CSV_EXTENSIONS = (".csv", ".txt")


def _field_values(layer_fields, feature, name, default):
    index = layer_fields.lookupField(name)
    if index < 0:
        return default
    value = feature.attribute(index)
    return default if value is None or (hasattr(value, "isNull") and value.isNull()) else value


def _number_or_nan(value):
    try:
        number = float(value)
    except (TypeError, ValueError):
        return math.nan
    return number


def sign_set_from_features(features, fields, transform, label, id_field="sign_id"):
    """A core SignSet from point features (PointZ geometry, or x, y, z fields); with codes
    (NULL: no code) when the layer has a field ``code``, else without (codes not scored)."""
    if fields.lookupField("class") < 0:
        raise QgsProcessingException(
            tr("{layer}: no field 'class'; fields found: {found}").format(
                layer=label, found=", ".join(fields.names())))
    ids, classes, xyz, height, azimuth, width, panel_height, images = [], [], [], [], [], [], [], []
    has_codes = fields.lookupField("code") >= 0
    codes = []
    for k, feature in enumerate(features):
        geometry = feature.geometry()
        if geometry.isNull() or geometry.isEmpty():
            point = [_number_or_nan(_field_values(fields, feature, c, None)) for c in "xyz"]
        else:
            if transform is not None:
                try:
                    geometry.transform(transform)
                except QgsCsException as error:
                    raise QgsProcessingException(tr("{layer}: cannot reproject feature {feature}: {error}").format(
                        layer=label, feature=k + 1, error=error))
            vertex = geometry.vertexAt(0)  # the point (the first one of a multipoint)
            z = vertex.z() if vertex.is3D() else _number_or_nan(_field_values(fields, feature, "z", None))
            point = [vertex.x(), vertex.y(), z]
        ids.append(str(_field_values(fields, feature, id_field, k + 1)))
        classes.append(str(_field_values(fields, feature, "class", "")))
        xyz.append(point)
        height.append(_number_or_nan(_field_values(fields, feature, "height", None)))
        azimuth.append(_number_or_nan(_field_values(fields, feature, "azimuth", None)))
        width.append(_number_or_nan(_field_values(fields, feature, "width", None)))
        panel_height.append(_number_or_nan(_field_values(fields, feature, "panel_height", None)))
        images.append(str(_field_values(fields, feature, "best_image", "")))
        if has_codes:
            codes.append(str(_field_values(fields, feature, "code", "")))
        if not np.isfinite(point).all():
            raise QgsProcessingException(tr(
                "{layer}: sign '{sign_id}' has no valid x, y, z position (no point geometry, and no numbers "
                "in the fields x, y, z)").format(layer=label, sign_id=ids[-1]))
    return SignSet(ids, classes, np.array(xyz, float).reshape(-1, 3), np.array(height),
                   np.array(azimuth), np.array(width), np.array(panel_height), images,
                   codes if has_codes else None)


class Evaluate(RoadSignsAlgorithm):
    ALGORITHM_ID = "evaluate"
    REQUIRES = ("numpy", "scipy")
    SIGNS = "SIGNS"
    REFERENCE = "REFERENCE"
    MATCH_RADIUS = "MATCH_RADIUS"
    OUTPUT_REPORT = "OUTPUT_REPORT"
    MEDIAN_HORIZONTAL_ERROR = "MEDIAN_HORIZONTAL_ERROR"
    MEDIAN_VERTICAL_ERROR = "MEDIAN_VERTICAL_ERROR"

    def displayName(self):
        return self.tr("Evaluate signs against reference")

    def shortDescription(self):
        return self.tr("Scores a sign layer against reference sign panels and writes an HTML report.")

    def shortHelpString(self):
        return self.tr(
            "Matches each sign to at most one reference panel by optimal assignment (Hungarian "
            "method) on the 3D distance between panel centres, within the match radius and "
            "ignoring class, then reports precision (matches / signs), recall (matches / "
            "reference panels), F1, the class accuracy of the matches, and the median and 95th "
            "percentile position error, the median height error, the median azimuth error, and "
            "the median and 95th percentile panel size error (the larger of the width and panel "
            "height errors, where the layers have the fields width and panel_height)."
            "<br><br>When the reference has a <i>code</i> column and the sign layer a <i>code</i> "
            "field (OpenStreetMap traffic_sign codes such as DE:274[50]), it also reports the code "
            "accuracy of the matches whose reference code is not empty (a sign without a code "
            "counts as wrong, and is counted as no code) and the code confusions, most frequent "
            "first."
            "<br><br>The <b>reference</b> is a CSV <i>sign_id,class,x,y,z,height,width,"
            "panel_height,azimuth</i> (and optionally <i>code</i>) in the sign layer's CRS, or a "
            "point layer with those fields (reprojected to the sign layer's CRS).<br><br>The HTML "
            "report has the summary and one row per sign: matched (with its errors), missed or "
            "false.")

    def output_labels(self):
        """Output name (core's ``OUTPUT_NAMES`` and the two extra errors) -> translated label."""
        return {
            "TP": self.tr("True positives (matched signs)"), "FP": self.tr("False positives (unmatched signs)"),
            "FN": self.tr("False negatives (missed reference panels)"), "PRECISION": self.tr("Precision"),
            "RECALL": self.tr("Recall"), "F1": self.tr("F1 score"),
            "CLASS_ACCURACY": self.tr("Class accuracy of matches"),
            "MEDIAN_ERROR": self.tr("Median 3D position error (m)"),
            "P95_ERROR": self.tr("95th percentile 3D error (m)"),
            "MEDIAN_HEIGHT_ERROR": self.tr("Median height error (m)"),
            "MEDIAN_AZIMUTH_ERROR": self.tr("Median azimuth error (°)"),
            "MEDIAN_SIZE_ERROR": self.tr("Median panel size error (m)"),
            "P95_SIZE_ERROR": self.tr("95th percentile panel size error (m)"),
            "CODE_ACCURACY": self.tr("Code accuracy of matches with a reference code"),
            "CODE_COMPARED": self.tr("Matches whose codes were compared"),
            "NO_CODE": self.tr("Compared matches whose sign has no code"),
            self.MEDIAN_HORIZONTAL_ERROR: self.tr("Median horizontal position error (m)"),
            self.MEDIAN_VERTICAL_ERROR: self.tr("Median vertical position error (m)"),
        }

    def initAlgorithm(self, config=None):
        self.add_source(
            self.SIGNS, self.tr("Sign layer"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The sign layer to score (PointZ at the panel centres, e.g. the output of Refine "
                    "signs), with the fields sign_id, class and optionally height, azimuth, best_image, "
                    "code."))
        self.add_file(
            self.REFERENCE, self.tr("Reference signs (CSV or point layer)"),
            self.tr("Ground truth: a CSV sign_id,class,x,y,z,height,width,panel_height,azimuth (and "
                    "optionally code) in the sign layer's CRS, or a point layer with those fields "
                    "(reprojected if its CRS differs)."),
            file_filter=self.tr("Reference signs (*.csv *.txt *.gpkg *.shp *.geojson);;All files (*.*)"))
        self.add_number(
            self.MATCH_RADIUS, self.tr("Match radius (m)"), 1.0,
            self.tr("A sign and a reference panel farther apart than this (3D distance between panel "
                    "centres, metres) are never matched."), minimum=0.001)
        self.add_file_destination(
            self.OUTPUT_REPORT, self.tr("Evaluation report"), self.tr("HTML files (*.html)"),
            self.tr("HTML report: the summary and one row per sign and reference panel."))
        labels = self.output_labels()
        for name in OUTPUT_NAMES + (self.MEDIAN_HORIZONTAL_ERROR, self.MEDIAN_VERTICAL_ERROR):
            self.addOutput(QgsProcessingOutputNumber(name, labels[name]))
        self.addOutput(QgsProcessingOutputString(
            CODE_CONFUSIONS, self.tr("Code confusions (reference code -> sign code: count)")))

    def _reference(self, path, signs_crs, context, feedback):
        if not path or not os.path.isfile(path):
            raise QgsProcessingException(self.tr("Reference file not found: {}").format(path))
        if os.path.splitext(path)[1].lower() in CSV_EXTENSIONS:
            feedback.pushInfo(self.tr("Reference CSV {}: coordinates taken in the sign layer's CRS "
                                      "({})").format(path, signs_crs.authid() or signs_crs.description()))
            with self.core_errors():
                reference = read_reference_csv(path)
                finite = reference.xyz[np.isfinite(reference.xyz).all(axis=1)]
                if signs_crs.isValid() and len(finite):
                    check_extent(crs_for_pyproj(signs_crs), (finite[:, 0].min(), finite[:, 1].min(),
                                                             finite[:, 0].max(), finite[:, 1].max()), path)
                return reference
        layer = QgsVectorLayer(path, "reference", "ogr")
        if not layer.isValid():
            raise QgsProcessingException(self.tr(
                "Cannot read the reference {}: expected a CSV or a point layer").format(path))
        transform = None
        if layer.crs().isValid() and signs_crs.isValid() and layer.crs() != signs_crs:
            feedback.pushInfo(self.tr("Reprojecting the reference from {} to {}").format(
                layer.crs().authid(), signs_crs.authid()))
            transform = QgsCoordinateTransform(layer.crs(), signs_crs, context.transformContext())
        return sign_set_from_features(layer.getFeatures(), layer.fields(), transform,
                                      "Reference {}".format(path))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        source = self.source(parameters, self.SIGNS, context)
        check_metric_crs(source.sourceCrs(), self.tr("Sign layer"))
        with self.core_errors():
            check_layer_extent(source, self.tr("Sign layer"))
        radius_m = self.parameterAsDouble(parameters, self.MATCH_RADIUS, context)
        report_path = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        signs = sign_set_from_features(source.getFeatures(QgsFeatureRequest()), source.fields(), None,
                                       self.tr("Sign layer"))
        if len(signs) == 0:
            raise QgsProcessingException(self.tr("The sign layer is empty: nothing to evaluate."))
        reference_path = self.parameterAsFile(parameters, self.REFERENCE, context)
        reference = self._reference(reference_path, source.sourceCrs(), context, feedback)
        if len(reference) == 0:
            raise QgsProcessingException(self.tr("The reference {} has no sign: nothing to evaluate against.")
                                         .format(reference_path))
        feedback.setProgress(30)
        with self.core_errors():
            check_overlap(signs, reference, radius_m, source.sourceName(), reference_path)
            result = evaluate(signs, reference, radius_m)
            write_html_report(result, self.output_file(report_path), title=self.tr("Road sign evaluation"),
                              sign_label=source.sourceName(), reference_label=reference_path)
        feedback.setProgress(100)
        outputs = dict(result.as_outputs())
        outputs[self.MEDIAN_HORIZONTAL_ERROR] = result.median_horizontal_error_m
        outputs[self.MEDIAN_VERTICAL_ERROR] = result.median_vertical_error_m
        outputs = {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in outputs.items()}
        feedback.pushInfo(self.tr("{} signs, {} reference panels: TP {}, FP {}, FN {}; precision {}, "
                                  "recall {}, median error {} m").format(
            len(signs), len(reference), outputs["TP"], outputs["FP"], outputs["FN"],
            _fmt(outputs["PRECISION"]), _fmt(outputs["RECALL"]), _fmt(outputs["MEDIAN_ERROR"])))
        outputs[CODE_CONFUSIONS] = confusions_text(result.code_confusions)
        if result.codes_scored:
            feedback.pushInfo(self.tr("Code accuracy {} of {} matches with a reference code ({} without a "
                                      "code); confusions: {}").format(
                _fmt(outputs["CODE_ACCURACY"]), result.code_compared, result.no_code,
                outputs[CODE_CONFUSIONS] or self.tr("none")))
        else:
            feedback.pushInfo(self.localise(result.code_note))
        outputs[self.OUTPUT_REPORT] = report_path
        return outputs


def _fmt(value):
    return "n/a" if value is None else "{:.3f}".format(value)
