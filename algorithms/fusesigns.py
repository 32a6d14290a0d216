"""roadsigns:fusesigns - the image chain's signs and the panels found in the cloud alone
merged into one sign layer that says which sources found each sign."""
from qgis.core import Qgis, QgsGeometry, QgsPoint, QgsProcessingException, QgsProcessingOutputNumber

from ..core.detector import DEFAULT_CONFIDENCE
from ..core.review import CHIP_FIELD
from ..core.signcodes import DEFAULT_CODE_CONFIDENCE
from ..core.trajectory import STATION_FIELDS
from .base import RoadSignsAlgorithm
from .codeparams import ReadsCodes
from .layers import crs_label, qgs_fields, read_records, write_records
from .paths import BUNDLED_MODEL
from .style import SignLayerStyler, file_of, write_sign_style


class FuseSigns(ReadsCodes, RoadSignsAlgorithm):
    ALGORITHM_ID = "fusesigns"
    REQUIRES = ("numpy", "scipy", "shapely", "cv2", "onnxruntime")
    SIGNS = "SIGNS"
    CLOUD_SIGNS = "CLOUD_SIGNS"
    STATIONS = "STATIONS"
    IMAGES = "IMAGES"
    MODEL = "MODEL"
    CONFIDENCE = "CONFIDENCE"
    MATCH_RADIUS = "MATCH_RADIUS"
    CODE_CONFIDENCE = "CODE_CONFIDENCE"
    OUTPUT = "OUTPUT"
    BOTH = "BOTH"
    IMAGE_ONLY = "IMAGE_ONLY"
    LIDAR_ONLY = "LIDAR_ONLY"

    def displayName(self):
        return self.tr("Fuse image and cloud signs")

    def shortDescription(self):
        return self.tr("Merges the signs found in the images with the panels found in the cloud alone: "
                       "one sign layer that says which sources found each sign.")

    def shortHelpString(self):
        return self.tr(
            "Matches each sign of the image chain (Refine and merge signs) to at most one panel found in "
            "the cloud alone (Find signs in the point cloud) by optimal assignment: centres within the "
            "match radius and facings within 90°.<br><br>A matched sign keeps its class and gains the "
            "panel's retroreflectivity index and condition (<i>source</i> = image+lidar). A panel no "
            "image sign explains becomes a sign of its own (<i>source</i> = lidar): with the stations "
            "and the panorama folder, the panoramas in front of its face are cut into views centred on "
            "it and the detector reads its class there; if none recognises it, its class is "
            "<i>unknown</i> and it is flagged for review. The sign-code classifier reads its code in a crop "
            "around each of those detections, and the views vote as Refine and merge signs votes them "
            "(code, code_name, code_score, code_views, code_check). An image sign whose place in the cloud holds "
            "no retro-reflective panel loses confidence (its score × 0.6) and is flagged for review "
            "(<i>source</i> = image).<br><br>Output: the sign layer with the fields of Refine and merge "
            "signs plus source, review, image_sign_id, cloud_sign_id, retro_index and condition, "
            "styled like the sign layer.")

    def initAlgorithm(self, config=None):
        self.add_source(
            self.SIGNS, self.tr("Signs (from the images)"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Refine and merge signs."))
        self.add_source(
            self.CLOUD_SIGNS, self.tr("Sign panels found in the cloud"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Find signs in the point cloud."))
        self.add_source(
            self.STATIONS, self.tr("Panorama stations (to classify panels found in the cloud alone)"),
            Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Import trajectory. With the panorama folder, the class of each panel "
                    "no image sign explains is read from the panoramas in front of it."), optional=True)
        self.add_file(
            self.IMAGES, self.tr("Panorama folder (optional)"),
            self.tr("The folder of the panoramas (empty: the paths in the stations layer)."),
            folder=True, optional=True)
        self.add_file(
            self.MODEL, self.tr("ONNX model (empty: the bundled model)"),
            self.tr("The detector that reads the class of panels found in the cloud alone."),
            file_filter=self.tr("ONNX models (*.onnx);;All files (*.*)"), optional=True, advanced=True)
        self.add_number(
            self.CONFIDENCE, self.tr("Minimum confidence"), DEFAULT_CONFIDENCE,
            self.tr("A class read from the panoramas is kept when the detector scores it at least this "
                    "(0-1)."), minimum=0.0, maximum=1.0, advanced=True)
        self.add_number(
            self.MATCH_RADIUS, self.tr("Match radius (m)"), 1.0,
            self.tr("An image sign and a cloud panel farther apart than this (3D, metres) are never the "
                    "same sign."), minimum=0.05, advanced=True)
        self.add_code_parameters(self.tr("for each sign found in the cloud alone and recognised in the "
                                         "panoramas, in a crop around each of its detections there"))
        self.add_number(
            self.CODE_CONFIDENCE, self.tr("Minimum code confidence"), DEFAULT_CODE_CONFIDENCE,
            self.tr("The code voted for a sign found in the cloud alone is kept when its support (its share of "
                    "the views' weighted vote x the mean probability the classifier gave it, 0-1: the "
                    "code_score field) is at least this; else the code field stays empty."),
            minimum=0.0, maximum=1.0, advanced=True)
        self.add_sink(
            self.OUTPUT, self.tr("Signs (fused)"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ sign layer: the sign fields, and source (image, lidar, image+lidar), review "
                    "(1: to be checked), image_sign_id, cloud_sign_id, retro_index, condition and the "
                    "review chip of the image sign (chip, relative to the layer's folder)."))
        self.addOutput(QgsProcessingOutputNumber(self.BOTH, self.tr("Signs found by both")))
        self.addOutput(QgsProcessingOutputNumber(self.IMAGE_ONLY, self.tr("Signs found in the images only")))
        self.addOutput(QgsProcessingOutputNumber(self.LIDAR_ONLY, self.tr("Signs found in the cloud only")))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.cloudsigns import CLOUD_SIGN_FIELDS
        from ..core.fusion import FUSED_SIGN_FIELDS, SOURCE_LIDAR, FusionParams, fuse_signs
        from ..core.refine import SIGN_FIELDS
        from ..core.signcodes import SIGN_CODE_FIELDS

        source = self.source(parameters, self.SIGNS, context)
        cloud_source = self.source(parameters, self.CLOUD_SIGNS, context)
        code_fields = [f.name for f in SIGN_CODE_FIELDS]  # absent from sign layers made before codes were read
        signs = read_records(source, SIGN_FIELDS, self.tr("Signs (from the images)"), feedback, allow_empty=True,
                             required=[f.name for f in SIGN_FIELDS if f.name not in code_fields])
        panels = read_records(cloud_source, CLOUD_SIGN_FIELDS, self.tr("Sign panels found in the cloud"),
                              feedback, allow_empty=True)
        if source.sourceCrs().isValid() and cloud_source.sourceCrs().isValid() and \
                source.sourceCrs() != cloud_source.sourceCrs():
            raise QgsProcessingException(self.tr(
                "The signs are in {}, the panels found in the cloud in {}: both must be in the cloud's "
                "CRS").format(crs_label(source.sourceCrs()), crs_label(cloud_source.sourceCrs())))
        with self.core_errors():
            fused = fuse_signs(signs, panels, params=FusionParams(
                match_radius_m=self.parameterAsDouble(parameters, self.MATCH_RADIUS, context)))
        lidar_only = [r for r in fused.signs if r["source"] == SOURCE_LIDAR]
        stations_source = self.parameterAsSource(parameters, self.STATIONS, context)
        if lidar_only and stations_source is not None:
            self._classify(lidar_only, stations_source, parameters, context, feedback)
        elif lidar_only:
            feedback.pushInfo(self.tr("No stations given: the {} signs found in the cloud alone keep the "
                                      "class unknown.").format(len(lidar_only)))
        feedback.setProgress(90)
        chips = {r["sign_id"]: r.get("chip") for r in signs}  # review pictures of the image signs
        for record in fused.signs:
            record["chip"] = chips.get(record["image_sign_id"])
        schema = FUSED_SIGN_FIELDS + (CHIP_FIELD,)
        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(schema),
                                  Qgis.WkbType.PointZ, source.sourceCrs())
        write_records(sink, schema, fused.signs,
                      [QgsGeometry(QgsPoint(r["x"], r["y"], r["z"])) for r in fused.signs], feedback, (90, 100))
        layer_file = file_of(dest_id)
        if layer_file:
            write_sign_style(self.output_file(layer_file[:layer_file.rfind(".")] + ".qml"), source.sourceCrs())
        if context.willLoadLayerOnCompletion(dest_id):
            context.layerToLoadOnCompletionDetails(dest_id).setPostProcessor(SignLayerStyler.create())
        feedback.pushInfo(self.tr("{} signs: {} found by both, {} in the images only ({} of them where the cloud "
                                  "was searched: score lowered, to review), {} in the cloud only.").format(
            len(fused.signs), fused.n_both, fused.n_image_only, fused.n_unconfirmed, fused.n_lidar_only))
        return {self.OUTPUT: dest_id, self.BOTH: fused.n_both, self.IMAGE_ONLY: fused.n_image_only,
                self.LIDAR_ONLY: fused.n_lidar_only}

    def _classify(self, lidar_only, stations_source, parameters, context, feedback):
        """Class, score and images of the signs found in the cloud alone, from the panoramas."""
        import os

        from ..core.detector import Detector
        from ..core.viewclass import classify_from_views

        stations = read_records(stations_source, STATION_FIELDS, self.tr("Panorama stations"), feedback)
        model_path = self.parameterAsFile(parameters, self.MODEL, context) or BUNDLED_MODEL
        folder = self.parameterAsFile(parameters, self.IMAGES, context) or None
        with self.core_errors():
            detector = Detector(model_path) if os.path.isfile(model_path) else None
            if detector is None:
                feedback.pushWarning(self.tr("ONNX model not found: {}").format(model_path))
                return
            codes = self.code_classifier(parameters, context, feedback)
            found = classify_from_views(lidar_only, stations, detector, folder,
                                        confidence=self.parameterAsDouble(parameters, self.CONFIDENCE, context),
                                        progress=self.progress(feedback).sub(0.1, 0.9), codes=codes,
                                        code_confidence=self.parameterAsDouble(parameters, self.CODE_CONFIDENCE,
                                                                               context))
        for record, view_class in zip(lidar_only, found):
            if view_class.images_found:
                record.update({"class": view_class.klass, "review": 0, "n_views": len(view_class.images_found),
                               "source_images": ";".join(view_class.images_found),
                               "best_image": view_class.images_found[0], "score": view_class.score})
                if view_class.code is not None:
                    record.update(view_class.code.fields())
        named = sum(bool(v.images_found) for v in found)
        feedback.pushInfo(self.tr("{} of the {} signs found in the cloud alone were recognised in the "
                                  "panoramas; the others keep the class unknown and are to review.").format(
            named, len(found)))
        if codes is not None:
            coded = sum(bool(v.code and v.code.code) for v in found)
            feedback.pushInfo(self.tr("Sign codes read for {} of them.").format(coded))
