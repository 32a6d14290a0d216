"""roadsigns:findsignsincloud - sign panels and the poles that carry them, found in the
LiDAR cloud alone (no images), with a retroreflectivity condition per panel."""
from qgis.core import Qgis, QgsGeometry, QgsPoint, QgsProcessingOutputNumber

from ..core.schema import select
from ..core.trajectory import STATION_FIELDS
from .base import RoadSignsAlgorithm
from .layers import check_same_crs, qgs_fields, read_cloud_crs_wkt, read_columns, write_records


class FindSignsInCloud(RoadSignsAlgorithm):
    ALGORITHM_ID = "findsignsincloud"
    REQUIRES = ("numpy", "scipy", "laspy", "lazrs", "shapely")
    POINT_CLOUD = "POINT_CLOUD"
    STATIONS = "STATIONS"
    CORRIDOR = "CORRIDOR"
    OUTPUT = "OUTPUT"
    OUTLINES = "OUTLINES"
    POLES = "POLES"
    SIGNS_FOUND = "SIGNS_FOUND"
    POLES_FOUND = "POLES_FOUND"

    def displayName(self):
        return self.tr("Find signs in the point cloud (no images)")

    def shortDescription(self):
        return self.tr("Finds retro-reflective sign panels and their poles in the LiDAR cloud alone, and flags "
                       "faded sheeting.")

    def shortHelpString(self):
        return self.tr(
            "Finds sign panels from the point cloud alone, after the Utah I-15 mobile-LiDAR method "
            "(Ai and Tsai): the drive's track (the panorama stations) locates every point along the "
            "road; points above the ground (class 2) and beside or above the road are kept; their "
            "intensity is normalised for range and incidence angle; a threshold adapted to the cloud "
            "(stated in the log) picks the retro-reflective sheeting; planar clusters of sign size and "
            "shape at sign heights become panels, each with the pole or gantry that carries it. The "
            "cloud is read once and worked through in windows of drive, so memory does not grow with "
            "the drive.<br><br>Outputs: the sign panels (PointZ at the panel centre: size, face "
            "normal and azimuth, height above the ground, intensity statistics, the retroreflectivity "
            "index and a <b>condition</b> of good, check or poor), their outlines (PolygonZ), and the "
            "poles (sign poles, light poles, gantry posts: foot, height, diameter, lean and the signs "
            "each carries).<br><br><b>Condition</b> is a screening flag, not a measurement: the "
            "retroreflectivity index is the median normalised intensity of the panel's face, compared "
            "with the drive's own healthy signs. It is not the coefficient of retroreflection of the "
            "MUTCD (observation angle 0.2°, entrance angle −4°): confirm flagged signs in the field. "
            "The cloud needs an intensity dimension and ground points (run Ground filter first).")

    def initAlgorithm(self, config=None):
        self.add_las_file(
            self.POINT_CLOUD, self.tr("Ground-classified point cloud (LAS/LAZ)"),
            self.tr("The cloud with ground as class 2 (the output of Ground filter) and an intensity "
                    "dimension, in the stations' CRS."))
        self.add_source(
            self.STATIONS, self.tr("Panorama stations"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Import trajectory: the drive's track (positions and times)."))
        self.add_number(
            self.CORRIDOR, self.tr("Corridor half-width (m)"), 12.0,
            self.tr("Signs are searched this far to each side of the track, in metres."), minimum=2.0,
            maximum=50.0, advanced=True)
        self.add_sink(
            self.OUTPUT, self.tr("Sign panels found in the cloud"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ layer, one point per panel centre, with its size, face normal and azimuth, "
                    "heights, intensity statistics, retroreflectivity index, condition and support."))
        self.add_sink(
            self.OUTLINES, self.tr("Panel outlines"), Qgis.ProcessingSourceType.VectorPolygon,
            self.tr("PolygonZ layer of each panel's rectangle in its plane."), optional=True)
        self.add_sink(
            self.POLES, self.tr("Poles"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ layer, one point per pole foot: kind (sign_pole, light_pole, gantry, other), "
                    "height, diameter, lean and the ids of the signs it carries."))
        self.addOutput(QgsProcessingOutputNumber(self.SIGNS_FOUND, self.tr("Sign panels found")))
        self.addOutput(QgsProcessingOutputNumber(self.POLES_FOUND, self.tr("Poles found")))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.cloudsigns import CLOUD_SIGN_FIELDS, CloudSignParams, find_signs_in_cloud
        from ..core.drivewindows import Track
        from ..core.poles import POLE_FIELDS
        from ..core.trajectory import Stations

        source = self.source(parameters, self.STATIONS, context)
        cloud_path = self.parameterAsFile(parameters, self.POINT_CLOUD, context)
        rows = read_columns(source, STATION_FIELDS, self.tr("Panorama stations"), feedback)
        with self.core_errors():
            check_same_crs(source.sourceCrs(), read_cloud_crs_wkt(cloud_path), self.tr("The stations"), cloud_path)
            stations = Stations.from_records(rows, self.tr("Panorama stations"))
            params = CloudSignParams(corridor_m=self.parameterAsDouble(parameters, self.CORRIDOR, context))
            result = find_signs_in_cloud(cloud_path, Track.from_stations(stations), params,
                                         progress=self.progress(feedback).sub(0.0, 0.95))
        for message in result.messages:
            feedback.pushInfo(self.localise(message))
        for warning in result.warnings:
            feedback.pushWarning(self.localise(warning))

        crs = source.sourceCrs()
        signs = result.sign_records()
        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(CLOUD_SIGN_FIELDS),
                                  Qgis.WkbType.PointZ, crs)
        write_records(sink, CLOUD_SIGN_FIELDS, signs, [QgsGeometry(QgsPoint(r["x"], r["y"], r["z"])) for r in signs],
                      feedback, (95, 97))
        outputs = {self.OUTPUT: dest_id, self.SIGNS_FOUND: len(signs), self.POLES_FOUND: len(result.poles)}
        outline_schema = select(CLOUD_SIGN_FIELDS, ("sign_id", "width", "panel_height", "condition"))
        outline_sink, outline_id = self.sink(parameters, self.OUTLINES, context, qgs_fields(outline_schema),
                                             Qgis.WkbType.PolygonZ, crs)
        if outline_sink is not None:
            write_records(outline_sink, outline_schema, signs,
                          [QgsGeometry.fromWkt(r["outline_wkt"]) if r.get("outline_wkt") else None for r in signs],
                          feedback, (97, 98))
            outputs[self.OUTLINES] = outline_id
        poles = result.pole_records()
        pole_sink, pole_id = self.sink(parameters, self.POLES, context, qgs_fields(POLE_FIELDS),
                                       Qgis.WkbType.PointZ, crs)
        if pole_sink is not None:
            write_records(pole_sink, POLE_FIELDS, poles,
                          [QgsGeometry(QgsPoint(r["x"], r["y"], r["z_foot"])) for r in poles], feedback, (98, 100))
            outputs[self.POLES] = pole_id
        feedback.pushInfo(self.tr("{} sign panels and {} poles found in the cloud.").format(len(signs), len(poles)))
        return outputs
