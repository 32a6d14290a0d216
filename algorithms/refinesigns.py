"""roadsigns:refinesigns - merge the views of each physical sign and refine it in the
cloud: the sign layer handed to a road authority."""
import os

from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsGeometry,
    QgsLineString,
    QgsPoint,
    QgsPolygon,
    QgsProcessingException,
)

from ..core.review import CHIP_FIELD
from .base import RoadSignsAlgorithm
from .layers import (
    check_cloud_extent,
    check_same_crs,
    cloud_crs_wkt,
    destination_file,
    qgs_fields,
    read_columns,
    write_records,
)
from .paths import BUNDLED_CODES_TABLE
from .style import SignLayerStyler, write_sign_style


class RefineSigns(RoadSignsAlgorithm):
    ALGORITHM_ID = "refinesigns"
    REQUIRES = ("numpy", "scipy", "laspy", "lazrs", "shapely")
    CANDIDATES = "CANDIDATES"
    POINT_CLOUD = "POINT_CLOUD"
    MERGE_RADIUS = "MERGE_RADIUS"
    CODE_CONFIDENCE = "CODE_CONFIDENCE"
    SINGLE_VIEW_MISSES = "SINGLE_VIEW_MAX_NEARER_MISSES"
    CODES_TABLE = "CODES_TABLE"
    IMAGES = "IMAGES"
    CLOUD_CRS = "CLOUD_CRS"
    OUTPUT = "OUTPUT"
    OUTLINES = "OUTLINES"
    SIGN_POINTS = "SIGN_POINTS"
    REVIEW_REPORT = "REVIEW_REPORT"

    def displayName(self):
        return self.tr("Refine and merge signs")

    def shortDescription(self):
        return self.tr("Merges the views of each sign and refines it in the cloud: the sign layer.")

    def shortHelpString(self):
        return self.tr(
            "Groups the candidates of different panoramas that are the same physical sign (same "
            "class, within the merge radius, plane normals agreeing; panels stacked on one pole "
            "stay apart), then refines each sign in the cloud: Euclidean clustering, an intensity "
            "filter whose threshold adapts to the cloud (Otsu), a near-vertical RANSAC plane and "
            "PCA dimensionality to keep the panel and drop the pole.<br><br>Each sign gets its "
            "panel centre, width and panel height, the azimuth its face looks towards (clockwise "
            "from grid north), its height above the ground directly below (class-2 points near "
            "the sign; the log names any fallback), the bottom height, the number of views and "
            "points, the images it was seen in and the best of them (closest, most frontal), the "
            "mean intensity and planarity. A sign seen in two or more panoramas but with no cloud "
            "points is placed by triangulating its rays (position_source = image).<br><br>"
            "<b>Not signs</b>, dropped and named in the log: a panel larger than its class allows (a "
            "billboard), a curved one (a convex mirror), a picture on a larger flat surface, and a sign "
            "seen in one panorama only when its score is under 0.4 or when two or more panoramas "
            "nearer to its face, which detected other signs, did not see it (a look-alike boxed once "
            "from afar).<br><br>"
            "Optional outputs: panel outlines (PolygonZ) and the sign points (LAS/LAZ).<br><br>"
            "<b>Review</b>: with the panorama folder, each sign gets an image chip from its best "
            "panorama (its box with a margin, undistorted), written into a folder beside the sign "
            "layer and linked by the <i>chip</i> field (a relative path); the review report shows "
            "every sign's chip and attributes. The sign layer is styled with a symbol per class "
            "and its height as label (a .qml file beside it).<br><br>"
            "<b>Sign codes</b>: the codes Detect signs read in the views of a sign are put to a vote, each "
            "view weighing its detection score x the pixels its crop holds across the sign's narrower side "
            "(a sign passed close by, seen at a steep angle, weighs less) x the code's probability. The sign gets "
            "<i>code</i> (empty when the vote says <i>other</i> or the support is below the minimum code "
            "confidence), <i>code_name</i> (from the codes table), <i>code_score</i> (the support: the "
            "code's share of the vote x its mean probability) and <i>code_views</i>. When the code's class "
            "(codes table) is not the class vote's, the better supported one wins: the code's support "
            "against the class's (its share of the score-weighted class vote x its views' mean detection "
            "score); <i>code_check</i> says <i>class_from_code</i> (the class was taken from the code) or "
            "<i>code_dropped</i> (the code was emptied). The label shows the code's name, or the figure "
            "of a speed limit.")

    def initAlgorithm(self, config=None):
        self.add_source(
            self.CANDIDATES, self.tr("Sign candidates"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Project detections."))
        self.add_las_file(
            self.POINT_CLOUD, self.tr("Ground-classified point cloud (LAS/LAZ)"),
            self.tr("The same cloud as for Project detections (ground as class 2)."))
        self.add_number(
            self.MERGE_RADIUS, self.tr("Merge radius (m)"), 1.0,
            self.tr("Candidates of the same class closer than this (metres) with agreeing plane normals "
                    "are taken as one sign."), minimum=0.05)
        self.add_number(
            self.CODE_CONFIDENCE, self.tr("Minimum code confidence"), 0.5,  # core.refine.DEFAULT_CODE_CONFIDENCE
            self.tr("A sign's voted code is kept when its support (its share of the views' weighted vote x "
                    "the mean probability the classifier gave it, 0-1: the code_score field) is at least "
                    "this; else the code field stays empty. 0 keeps every code but 'other' and 'unlisted:...' (a sign "
                    "whose code the table lacks)."),
            minimum=0.0, maximum=1.0)
        self.add_number(
            self.SINGLE_VIEW_MISSES, self.tr("Drop a sign seen once when this many nearer panoramas missed it"),
            2,  # core.refine.RefineParams.single_view_max_nearer_misses
            self.tr("A sign seen in one panorama only is dropped when at least this many other panoramas, "
                    "which detected other signs, stand nearer to its face and did not see it (within 60 "
                    "degrees of its normal, at least 4 m away, with the sign at most 20 degrees above their "
                    "horizon): a look-alike boxed once from afar, such as a convex mirror. 0 keeps every such "
                    "sign, for example a real sign that a lorry hid from the nearer panoramas."),
            minimum=0, integer=True, advanced=True)
        self.add_file(
            self.CODES_TABLE, self.tr("Sign codes table (empty: the bundled one)"),
            self.tr("The codes table the classifier of Detect signs was run with: it gives each code its name "
                    "(code_name) and its class (for the class check). Format in models/README.md; empty uses "
                    "the bundled table of German codes (models/sign-codes-de.csv)."),
            file_filter=self.tr("CSV files (*.csv *.txt);;All files (*.*)"), optional=True, advanced=True)
        self.add_file(
            self.IMAGES, self.tr("Panorama folder (for review chips)"),
            self.tr("The folder of the panoramas (as for Import trajectory). When given, an image chip of "
                    "each sign is cut from its best panorama for review."), folder=True, optional=True)
        self.add_crs(
            self.CLOUD_CRS, self.tr("Cloud CRS (when the file has none)"),
            self.tr("The cloud's CRS when the file records none (it must be the candidates' CRS); it overrides "
                    "a CRS in the file. The CRS is never guessed."), optional=True, advanced=True)
        self.add_sink(
            self.OUTPUT, self.tr("Signs"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ sign layer at the panel centres (fields in docs/formats.md), and chip: the "
                    "relative path of the sign's review picture."))
        self.add_sink(
            self.OUTLINES, self.tr("Panel outlines"), Qgis.ProcessingSourceType.VectorPolygon,
            self.tr("PolygonZ layer of each panel's rectangle in its plane (signs placed from the cloud)."),
            optional=True)
        self.add_file_destination(
            self.SIGN_POINTS, self.tr("Sign points"), self.tr("LAZ (*.laz);;LAS (*.las)"),
            self.tr("A LAS/LAZ file of the points of every sign panel, all dimensions kept."), optional=True)
        self.add_file_destination(
            self.REVIEW_REPORT, self.tr("Review report"), self.tr("HTML files (*.html)"),
            self.tr("An HTML page with every sign's chip and attributes, to confirm signs without opening "
                    "panoramas (needs the panorama folder)."), optional=True)

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.detections import OPTIONAL_FIELDS
        from ..core.projection import CANDIDATE_FIELDS, ProjectionResult
        from ..core.refine import OUTLINE_FIELDS, SIGN_FIELDS, RefineParams, refine_signs, write_sign_points
        from ..core.signcodes import read_codes_table

        sign_layer_fields = SIGN_FIELDS + (CHIP_FIELD,)  # the sign fields and the review chip's path

        source = self.source(parameters, self.CANDIDATES, context)
        cloud_path = self.parameterAsFile(parameters, self.POINT_CLOUD, context)
        with self.core_errors():
            crs_wkt = cloud_crs_wkt(self.parameterAsCrs(parameters, self.CLOUD_CRS, context), cloud_path)
            check_same_crs(source.sourceCrs(), crs_wkt, self.tr("The candidates"), cloud_path)
            check_cloud_extent(cloud_path, crs_wkt)
        rows = read_columns(source, CANDIDATE_FIELDS, self.tr("Sign candidates"), feedback,
                            required=[f.name for f in CANDIDATE_FIELDS if f.name not in OPTIONAL_FIELDS],
                            allow_empty=True)  # no candidates: a warning and an empty layer
        images_dir = self.parameterAsFile(parameters, self.IMAGES, context)
        if images_dir and not os.path.isdir(images_dir):
            raise QgsProcessingException(self.tr("Panorama folder not found: {}").format(images_dir))
        output_crs = source.sourceCrs() if source.sourceCrs().isValid() else \
            QgsCoordinateReferenceSystem.fromWkt(crs_wkt)
        progress = self.progress(feedback)
        with self.core_errors():
            candidates = ProjectionResult.from_records(rows)
        del rows   # the layer's columns, copied: not held through the drive's work
        with self.core_errors():
            codes_table = read_codes_table(
                self.parameterAsFile(parameters, self.CODES_TABLE, context) or BUNDLED_CODES_TABLE)
            result = refine_signs(candidates, cloud_path,
                                  merge_radius_m=self.parameterAsDouble(parameters, self.MERGE_RADIUS, context),
                                  params=RefineParams(single_view_max_nearer_misses=self.parameterAsInt(
                                      parameters, self.SINGLE_VIEW_MISSES, context)),
                                  progress=progress.sub(0.0, 0.85), codes_table=codes_table,
                                  code_confidence=self.parameterAsDouble(parameters, self.CODE_CONFIDENCE, context))
        records = result.records()

        # files first, under temporary names (moved into place when the run succeeds), then the layers
        layer_file, _ = destination_file(self.parameterAsOutputLayer(parameters, self.OUTPUT, context), context)
        report_path = self.parameterAsFileOutput(parameters, self.REVIEW_REPORT, context)
        outputs = {}
        if images_dir:
            self._review(records, candidates, result, images_dir, layer_file,
                         report_path, progress.sub(0.85, 0.9), feedback)
            if report_path:
                outputs[self.REVIEW_REPORT] = report_path
        elif report_path:
            feedback.pushWarning(self.tr("The review report needs the panorama folder: not written."))
        points_path = self.parameterAsFileOutput(parameters, self.SIGN_POINTS, context)
        if points_path:
            with self.core_errors():
                n = write_sign_points(cloud_path, self.output_file(points_path), result.point_index,
                                      progress=progress.sub(0.9, 0.95))
            feedback.pushInfo(self.tr("{} sign points written to {}").format(n, points_path))
            outputs[self.SIGN_POINTS] = points_path
        if layer_file:
            write_sign_style(self.output_file(os.path.splitext(layer_file)[0] + ".qml"), output_crs)

        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(sign_layer_fields),
                                  Qgis.WkbType.PointZ, output_crs)
        write_records(sink, sign_layer_fields, records,
                      [QgsGeometry(QgsPoint(r["x"], r["y"], r["z"])) for r in records], feedback, (95, 97))
        outputs[self.OUTPUT] = dest_id
        if context.willLoadLayerOnCompletion(dest_id):
            context.layerToLoadOnCompletionDetails(dest_id).setPostProcessor(SignLayerStyler.create())

        outline_sink, outline_id = self.sink(parameters, self.OUTLINES, context, qgs_fields(OUTLINE_FIELDS),
                                             Qgis.WkbType.PolygonZ, output_crs)
        if outline_sink is not None:
            placed = [(r, c) for r, c in zip(records, result.outlines_world) if c is not None]
            polygons = [QgsGeometry(QgsPolygon(QgsLineString([QgsPoint(*p) for p in list(c) + [c[0]]])))
                        for _, c in placed]
            write_records(outline_sink, OUTLINE_FIELDS, [r for r, _ in placed], polygons,
                          feedback, (97, 100))
            outputs[self.OUTLINES] = outline_id
        by_source = {}
        for r in records:
            by_source[r["position_source"]] = by_source.get(r["position_source"], 0) + 1
        feedback.pushInfo(self.tr("{} signs from {} candidates ({})").format(
            len(records), len(candidates), ", ".join("{} {}".format(v, k) for k, v in sorted(by_source.items()))))
        return outputs

    def _review(self, records, candidates, result, images_dir, layer_file, report_path, progress, feedback):
        """Chips beside the sign layer (or the report), their relative paths in ``chip``; the
        chips folder and the report are written under temporary names (see the boundary)."""
        from ..core.review import best_view_boxes, write_chips, write_review_report
        base = layer_file or report_path
        if not base:
            feedback.pushWarning(self.tr("Review chips need a sign layer written to a file: skipped."))
            return
        chips_dir = os.path.splitext(base)[0] + "_chips"
        with self.core_errors():
            names = write_chips(records, best_view_boxes(candidates, result), images_dir,
                                self.output_folder(chips_dir), progress)
        layer_dir = os.path.dirname(layer_file or report_path)
        for record, name in zip(records, names):
            record["chip"] = os.path.relpath(os.path.join(chips_dir, name), layer_dir) if name else None
        if report_path:
            report_dir = os.path.dirname(os.path.abspath(report_path))
            links = [os.path.relpath(os.path.join(chips_dir, n), report_dir) if n else "" for n in names]
            with self.core_errors():
                write_review_report(records, links, self.output_file(report_path),
                                    title=self.tr("Road signs for review"))
        feedback.pushInfo(self.tr("{} review chips in {}").format(sum(bool(n) for n in names), chips_dir))
