"""roadsigns:projectdetections - each detection's viewing frustum searched in the point
cloud for the first dense planar surface: one candidate sign position per detection."""
from qgis.core import Qgis, QgsCoordinateReferenceSystem, QgsGeometry, QgsPoint

from ..core.detections import DETECTION_POSE_FIELDS, REQUIRED_POSE_FIELDS
from .base import RoadSignsAlgorithm
from .layers import check_cloud_extent, check_same_crs, cloud_crs_wkt, qgs_fields, read_columns, write_records


class ProjectDetections(RoadSignsAlgorithm):
    ALGORITHM_ID = "projectdetections"
    REQUIRES = ("numpy", "scipy", "laspy", "lazrs", "shapely")
    DETECTIONS = "DETECTIONS"
    POINT_CLOUD = "POINT_CLOUD"
    MAX_RANGE = "MAX_RANGE"
    CLOUD_CRS = "CLOUD_CRS"
    OUTPUT = "OUTPUT"

    def displayName(self):
        return self.tr("Project detections into the point cloud")

    def shortDescription(self):
        return self.tr("Finds each detected sign's surface in the LiDAR cloud: one candidate per detection.")

    def shortHelpString(self):
        return self.tr(
            "For each detection, the viewing frustum of its box (the rays through the box edges, "
            "widened by a small margin for calibration error) is searched from the panorama centre "
            "out to the maximum range. The non-ground points inside it are clustered and the first "
            "dense, near-vertical planar surface along the box-centre ray is taken (the sign, not "
            "the wall behind it; poles and convex mirrors are passed over). The cloud is read once "
            "(only the tiles under some frustum); the points under the frusta are kept on disk and "
            "worked through block by block along the drive, so the memory follows a block, not the "
            "drive. Within a block, each detection tests only the small tiles its frustum "
            "crosses.<br><br>Output: one point per detection at the candidate "
            "surface, with the detection's fields, the range, the point count, the plane normal "
            "(normal_e, normal_n, normal_u), a quality score in 0-1 and a status: <i>ok</i>, "
            "<i>no_points</i> (nothing in the frustum, e.g. out of the scanner's reach) or "
            "<i>no_surface</i>; those two keep no geometry. The cloud must be ground-classified "
            "(run Ground filter first).")

    def initAlgorithm(self, config=None):
        self.add_source(
            self.DETECTIONS, self.tr("Detections"), Qgis.ProcessingSourceType.VectorLine,
            self.tr("The output of Detect signs: one ray per detection with its box and station pose."))
        self.add_las_file(
            self.POINT_CLOUD, self.tr("Ground-classified point cloud (LAS/LAZ)"),
            self.tr("The cloud with ground as class 2 (the output of Ground filter), in the detections' CRS."))
        self.add_number(
            self.MAX_RANGE, self.tr("Maximum range (m)"), 30.0,
            self.tr("Search each frustum up to this distance from the panorama centre, in metres."), minimum=1.0)
        self.add_crs(
            self.CLOUD_CRS, self.tr("Cloud CRS (when the file has none)"),
            self.tr("The cloud's CRS when the file records none (it must be the detections' CRS); it overrides "
                    "a CRS in the file. The CRS is never guessed."), optional=True, advanced=True)
        self.add_sink(
            self.OUTPUT, self.tr("Sign candidates"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ layer, one candidate per detection (no geometry where no surface was found)."))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.projection import CANDIDATE_FIELDS, STATUS_OK, Detections, project_detections

        source = self.source(parameters, self.DETECTIONS, context)
        cloud_path = self.parameterAsFile(parameters, self.POINT_CLOUD, context)
        with self.core_errors():
            crs_wkt = cloud_crs_wkt(self.parameterAsCrs(parameters, self.CLOUD_CRS, context), cloud_path)
            check_same_crs(source.sourceCrs(), crs_wkt, self.tr("The detections"), cloud_path)
            check_cloud_extent(cloud_path, crs_wkt)
        rows = read_columns(source, DETECTION_POSE_FIELDS, self.tr("Detections"), feedback,  # code fields: optional
                            required=REQUIRED_POSE_FIELDS,
                            allow_empty=True)  # no detections: a warning and an empty layer
        with self.core_errors():
            detections = Detections.from_records(rows)
        del rows   # the layer's columns, copied: not held through the drive's work
        with self.core_errors():
            result = project_detections(
                detections, cloud_path,
                max_range_m=self.parameterAsDouble(parameters, self.MAX_RANGE, context),
                progress=self.progress(feedback).sub(0.0, 0.95))
        output_crs = source.sourceCrs() if source.sourceCrs().isValid() else \
            QgsCoordinateReferenceSystem.fromWkt(crs_wkt)
        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(CANDIDATE_FIELDS),
                                  Qgis.WkbType.PointZ, output_crs)
        found = [status == STATUS_OK for status in result.status]
        geometries = (QgsGeometry(QgsPoint(*map(float, result.xyz_world[k]))) if ok else None
                      for k, ok in enumerate(found))
        write_records(sink, CANDIDATE_FIELDS, result.iter_records(), geometries, feedback, (95, 100),
                      count=len(result))  # a feature made at a time: a drive's candidates are not held twice
        feedback.pushInfo(self.tr("{} detections: {} with a surface in the cloud, {} without").format(
            len(result), sum(found), len(result) - sum(found)))
        return {self.OUTPUT: dest_id}
