"""roadsigns:importtrajectory - trajectory (CSV or SBET) + image times, or per-image poses,
and the camera mount -> a PointZ layer of panorama stations with full pose."""
import math

from qgis.core import (Qgis, QgsCoordinateReferenceSystem, QgsFeature, QgsFeatureSink,
                       QgsGeometry, QgsPoint, QgsProcessingException,
                       QgsProcessingParameterBoolean, QgsProcessingParameterCrs,
                       QgsProcessingParameterFeatureSink, QgsProcessingParameterFile)

from ..core.trajectory import CameraMount, import_stations
from .base import RoadSignsAlgorithm
from .layers import DOUBLE, INT, TEXT, make_fields

FILE = Qgis.ProcessingFileParameterBehavior.File
FOLDER = Qgis.ProcessingFileParameterBehavior.Folder

STATION_FIELDS = [("station_id", INT), ("image", TEXT),
                  ("path", TEXT), ("time", DOUBLE),
                  ("x", DOUBLE), ("y", DOUBLE),
                  ("z", DOUBLE), ("qw", DOUBLE),
                  ("qx", DOUBLE), ("qy", DOUBLE),
                  ("qz", DOUBLE), ("heading", DOUBLE),
                  ("width", INT), ("height", INT)]


def crs_for_pyproj(crs: QgsCoordinateReferenceSystem):
    """Authority id when QGIS has one (what pyproj reads best), else WKT2; None if invalid."""
    if not crs.isValid():
        return None
    return crs.authid() or crs.toWkt(Qgis.CrsWktVariant.Wkt2_2019Simplified)


class ImportTrajectory(RoadSignsAlgorithm):
    ALGORITHM_ID = "importtrajectory"
    DISPLAY_NAME = "Import trajectory and panoramas"
    REQUIRES = ("numpy", "scipy", "pyproj", "PIL")
    SHORT_DESCRIPTION = "Trajectory (CSV or SBET) and image times, or per-image poses, to panorama stations with full pose."
    HELP = (
        "Builds the panorama stations: the position and full orientation of every panorama "
        "at its exposure, in the target CRS.<br><br>"
        "Give a <b>trajectory</b> (CSV <i>time,x,y,z,roll,pitch,heading</i> or an Applanix "
        "SBET .out) with an <b>image times</b> CSV (<i>image,time</i>), or a <b>per-image "
        "pose</b> CSV (<i>image,x,y,z,roll,pitch,heading[,time]</i>) instead. Angles are in "
        "degrees (radians in an SBET); heading is clockwise from <b>true</b> north and is "
        "turned into a grid heading with the meridian convergence at each station. Positions "
        "are interpolated linearly and attitudes by SLERP at the image times.<br><br>"
        "The <b>camera mount</b> places the panorama on the vehicle: lever arm in metres in the "
        "body frame (x forward, y right, z down) and boresight angles in degrees.<br><br>"
        "Output: one point per panorama at its centre, with the quaternion (qw, qx, qy, qz) "
        "that maps panorama rays to world East-North-Up, the forward azimuth and the image "
        "size read from its header.")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterFile(
            "TRAJECTORY", self.tr("Trajectory (CSV or SBET)"), behavior=FILE, optional=True,
            fileFilter=self.tr("Trajectory (*.csv *.txt *.out *.sbet);;All files (*.*)")),
            "Trajectory CSV with a header time,x,y,z,roll,pitch,heading (comma, semicolon, tab or "
            "space separated), or an Applanix SBET (.out, .sbet). Times increase strictly.")
        self.add(QgsProcessingParameterFile(
            "IMAGE_TIMES", self.tr("Image times (CSV)"), behavior=FILE, optional=True,
            fileFilter=self.tr("CSV (*.csv *.txt);;All files (*.*)")),
            "CSV image,time: each panorama's file name (relative to the panorama folder) and "
            "exposure time, in the trajectory's time base.")
        self.add(QgsProcessingParameterFile(
            "POSES", self.tr("Per-image poses (CSV, instead of trajectory and image times)"),
            behavior=FILE, optional=True,
            fileFilter=self.tr("CSV (*.csv *.txt);;All files (*.*)")),
            "CSV image,x,y,z,roll,pitch,heading and optionally time: the vehicle body pose at "
            "each exposure. Use instead of a trajectory with image times.")
        self.add(QgsProcessingParameterFile(
            "IMAGES", self.tr("Panorama folder"), behavior=FOLDER),
            "Folder of the equirectangular panoramas (JPEG or PNG, twice as wide as high).")
        self.add(QgsProcessingParameterCrs(
            "TRAJECTORY_CRS", self.tr("Trajectory CRS"), defaultValue="EPSG:4326"),
            "CRS of the trajectory or pose positions (x = longitude, y = latitude, z = ellipsoidal "
            "height for a geographic CRS). Ignored for an SBET, which is always WGS 84.")
        self.add(QgsProcessingParameterCrs(
            "TARGET_CRS", self.tr("Target CRS (projected)"), optional=True),
            "Projected CRS of the outputs (metres, East-North-Up). A compound CRS with a vertical "
            "datum turns ellipsoidal heights into that datum when its geoid grid is installed. "
            "Empty: the trajectory CRS if it is projected, else its UTM zone.")
        lever_help = ("Panorama centre relative to the trajectory's reference point, in metres "
                      "along the body axes: x forward, y right, z down.")
        self.add_number("LEVER_ARM_X", "Lever arm x, forward (m)", 0.0, lever_help)
        self.add_number("LEVER_ARM_Y", "Lever arm y, right (m)", 0.0, lever_help)
        self.add_number("LEVER_ARM_Z", "Lever arm z, down (m)", 0.0, lever_help)
        boresight_help = ("Panorama frame relative to the body frame: R_body_from_pano = Rz(yaw) "
                          "Ry(pitch) Rx(roll), degrees.")
        self.add_number("BORESIGHT_ROLL", "Boresight roll (°)", 0.0, boresight_help, -360.0, 360.0)
        self.add_number("BORESIGHT_PITCH", "Boresight pitch (°)", 0.0, boresight_help, -360.0, 360.0)
        self.add_number("BORESIGHT_YAW", "Boresight yaw (°)", 0.0, boresight_help, -360.0, 360.0)
        self.add(QgsProcessingParameterBoolean(
            "SKIP_OUTSIDE", self.tr("Skip images outside the trajectory's time span"),
            defaultValue=False),
            "When checked, images whose time lies outside the trajectory are skipped and counted "
            "in the log; otherwise they are an error.", advanced=True)
        self.add_number(
            "MAX_GAP", "Warn about trajectory gaps longer than (s)", 0.5,
            "A warning names images that fall between two trajectory samples further apart than "
            "this, in seconds.", minimum=0.0, advanced=True)
        self.add(QgsProcessingParameterBoolean(
            "FAIL_ON_MISSING_IMAGE", self.tr("Fail on a missing or unreadable panorama"),
            defaultValue=False),
            "When checked, a missing or unreadable panorama is an error; otherwise it is skipped "
            "with a warning and counted.", advanced=True)
        self.add(QgsProcessingParameterFeatureSink(
            "OUTPUT", self.tr("Panorama stations"), type=Qgis.ProcessingSourceType.VectorPoint),
            "PointZ layer, one point per panorama at its centre, with the fields station_id, image, "
            "path, time, x, y, z, qw, qx, qy, qz, heading, width, height.")

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        self.check_dependencies()
        target_crs = self.parameterAsCrs(parameters, "TARGET_CRS", context)
        mount = CameraMount(
            lever_arm_m=[self.parameterAsDouble(parameters, "LEVER_ARM_" + a, context) for a in "XYZ"],
            boresight_roll_deg=self.parameterAsDouble(parameters, "BORESIGHT_ROLL", context),
            boresight_pitch_deg=self.parameterAsDouble(parameters, "BORESIGHT_PITCH", context),
            boresight_yaw_deg=self.parameterAsDouble(parameters, "BORESIGHT_YAW", context))
        with self.core_errors():
            result = import_stations(
                images_dir=self.parameterAsFile(parameters, "IMAGES", context),
                target_crs=crs_for_pyproj(target_crs),
                trajectory_crs=crs_for_pyproj(self.parameterAsCrs(parameters, "TRAJECTORY_CRS", context)),
                trajectory_path=self.parameterAsFile(parameters, "TRAJECTORY", context) or None,
                image_times_path=self.parameterAsFile(parameters, "IMAGE_TIMES", context) or None,
                poses_path=self.parameterAsFile(parameters, "POSES", context) or None,
                mount=mount,
                skip_outside=self.parameterAsBoolean(parameters, "SKIP_OUTSIDE", context),
                max_gap_s=self.parameterAsDouble(parameters, "MAX_GAP", context),
                fail_on_missing_image=self.parameterAsBoolean(parameters, "FAIL_ON_MISSING_IMAGE", context),
                progress=self.progress(feedback).sub(0.0, 0.9))
        for message in result.messages:
            feedback.pushInfo(self.localise(message))
        for warning in result.warnings:
            feedback.pushWarning(self.localise(warning))

        output_crs = target_crs if target_crs.isValid() else \
            QgsCoordinateReferenceSystem.fromWkt(result.target_crs_wkt)
        fields = make_fields(STATION_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, "OUTPUT", context, fields,
                                             Qgis.WkbType.PointZ, output_crs)
        if sink is None:
            raise QgsProcessingException(self.invalidSinkError(parameters, "OUTPUT"))
        stations = result.stations
        for k in range(len(stations)):
            if feedback.isCanceled():
                break
            x, y, z = (float(c) for c in stations.xyz_world[k])
            qw, qx, qy, qz = (float(c) for c in stations.q_world_from_pano_wxyz[k])
            time_s = float(stations.time_s[k])
            feature = QgsFeature(fields)
            feature.setGeometry(QgsGeometry(QgsPoint(x, y, z)))
            feature.setAttributes([k + 1, stations.image[k], stations.path[k],
                                   None if math.isnan(time_s) else time_s, x, y, z, qw, qx, qy, qz,
                                   float(stations.heading_deg[k]), int(stations.width_px[k]),
                                   int(stations.height_px[k])])
            sink.addFeature(feature, QgsFeatureSink.Flag.FastInsert)
            feedback.setProgress(90 + 10 * (k + 1) / len(stations))
        feedback.pushInfo(self.tr("{} panorama stations written.").format(len(stations)))
        return {"OUTPUT": dest_id}
