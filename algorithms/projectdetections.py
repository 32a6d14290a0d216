"""roadsigns:projectdetections - each detection's viewing frustum searched in the point
cloud for the first dense planar surface: one candidate sign position per detection."""
from qgis.core import (Qgis, QgsGeometry, QgsPoint, QgsProcessingException,
                       QgsProcessingParameterFeatureSink, QgsProcessingParameterFeatureSource,
                       QgsProcessingParameterFile)

from .base import RoadSignsAlgorithm
from .layers import DOUBLE, INT, TEXT, check_same_crs, make_fields, read_records, write_records

CANDIDATE_SPEC = [
    ("det_id", INT), ("station_id", INT), ("image", TEXT), ("class", TEXT), ("score", DOUBLE),
    ("u0", DOUBLE), ("v0", DOUBLE), ("u1", DOUBLE), ("v1", DOUBLE), ("width", INT), ("height", INT),
    ("x", DOUBLE), ("y", DOUBLE), ("z", DOUBLE), ("qw", DOUBLE), ("qx", DOUBLE), ("qy", DOUBLE),
    ("qz", DOUBLE), ("cand_x", DOUBLE), ("cand_y", DOUBLE), ("cand_z", DOUBLE), ("range_m", DOUBLE),
    ("n_points", INT), ("normal_e", DOUBLE), ("normal_n", DOUBLE), ("normal_u", DOUBLE),
    ("quality", DOUBLE), ("status", TEXT)]


class ProjectDetections(RoadSignsAlgorithm):
    ALGORITHM_ID = "projectdetections"
    DISPLAY_NAME = "Project detections into the point cloud"
    REQUIRES = ("numpy", "scipy", "laspy", "lazrs", "shapely")
    SHORT_DESCRIPTION = "Finds each detected sign's surface in the LiDAR cloud: one candidate per detection."
    HELP = (
        "For each detection, the viewing frustum of its box (the rays through the box edges, "
        "widened by a small margin for calibration error) is searched from the panorama centre "
        "out to the maximum range. The non-ground points inside it are clustered and the first "
        "dense, near-vertical planar surface along the box-centre ray is taken (the sign, not "
        "the wall behind it; poles and convex mirrors are passed over). The cloud is read once "
        "into a tiled index restricted to the frusta, and each tile is tested against every "
        "detection that crosses it.<br><br>Output: one point per detection at the candidate "
        "surface, with the detection's fields, the range, the point count, the plane normal "
        "(normal_e, normal_n, normal_u), a quality score in 0-1 and a status: <i>ok</i>, "
        "<i>no_points</i> (nothing in the frustum, e.g. out of the scanner's reach) or "
        "<i>no_surface</i>; those two keep no geometry. The cloud must be ground-classified "
        "(run Ground filter first).")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterFeatureSource(
            "DETECTIONS", self.tr("Detections"), [Qgis.ProcessingSourceType.VectorLine]),
            "The output of Detect signs: one ray per detection with its box and station pose.")
        self.add(QgsProcessingParameterFile(
            "POINT_CLOUD", self.tr("Ground-classified point cloud (LAS/LAZ)"),
            behavior=Qgis.ProcessingFileParameterBehavior.File,
            fileFilter=self.tr("LAS/LAZ point clouds (*.las *.laz *.LAS *.LAZ);;All files (*.*)")),
            "The cloud with ground as class 2 (the output of Ground filter), in the detections' CRS.")
        self.add_number(
            "MAX_RANGE", "Maximum range (m)", 30.0,
            "Search each frustum up to this distance from the panorama centre, in metres.", minimum=1.0)
        self.add(QgsProcessingParameterFeatureSink(
            "OUTPUT", self.tr("Sign candidates"), type=Qgis.ProcessingSourceType.VectorPoint),
            "PointZ layer, one candidate per detection (no geometry where no surface was found).")

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        self.check_dependencies()
        from ..core.pointcloud import read_crs_wkt
        from ..core.projection import DETECTION_FIELDS, Detections, project_detections

        source = self.parameterAsSource(parameters, "DETECTIONS", context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, "DETECTIONS"))
        cloud_path = self.parameterAsFile(parameters, "POINT_CLOUD", context)
        rows = read_records(source, DETECTION_FIELDS, self.tr("Detections"), feedback)
        with self.core_errors():
            check_same_crs(source.sourceCrs(), read_crs_wkt(cloud_path), self.tr("The detections"),
                           cloud_path)
            result = project_detections(
                Detections.from_records(rows), cloud_path,
                max_range_m=self.parameterAsDouble(parameters, "MAX_RANGE", context),
                progress=self.progress(feedback).sub(0.0, 0.95))
        records = result.records()
        fields = make_fields(CANDIDATE_SPEC)
        sink, dest_id = self.parameterAsSink(parameters, "OUTPUT", context, fields,
                                             Qgis.WkbType.PointZ, source.sourceCrs())
        if sink is None:
            raise QgsProcessingException(self.invalidSinkError(parameters, "OUTPUT"))
        geometries = [QgsGeometry(QgsPoint(r["cand_x"], r["cand_y"], r["cand_z"]))
                      if r["status"] == "ok" else None for r in records]
        write_records(sink, fields, CANDIDATE_SPEC, records, geometries, feedback, (95, 100))
        found = sum(r["status"] == "ok" for r in records)
        feedback.pushInfo(self.tr("{} detections: {} with a surface in the cloud, {} without").format(
            len(records), found, len(records) - found))
        return {"OUTPUT": dest_id}
