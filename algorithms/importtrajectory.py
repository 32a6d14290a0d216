"""roadsigns:importtrajectory - trajectory (CSV or SBET) + image times, or per-image poses,
and the camera mount -> a PointZ layer of panorama stations with full pose."""
from qgis.core import Qgis, QgsCoordinateReferenceSystem, QgsGeometry, QgsPoint

from ..core.trajectory import STATION_FIELDS, CameraMount, import_stations
from .base import RoadSignsAlgorithm
from .layers import crs_for_pyproj, qgs_fields, write_records


class ImportTrajectory(RoadSignsAlgorithm):
    ALGORITHM_ID = "importtrajectory"
    REQUIRES = ("numpy", "scipy", "pyproj", "PIL")
    TRAJECTORY = "TRAJECTORY"
    IMAGE_TIMES = "IMAGE_TIMES"
    POSES = "POSES"
    IMAGES = "IMAGES"
    TRAJECTORY_CRS = "TRAJECTORY_CRS"
    TARGET_CRS = "TARGET_CRS"
    LEVER_ARM_X = "LEVER_ARM_X"
    LEVER_ARM_Y = "LEVER_ARM_Y"
    LEVER_ARM_Z = "LEVER_ARM_Z"
    BORESIGHT_ROLL = "BORESIGHT_ROLL"
    BORESIGHT_PITCH = "BORESIGHT_PITCH"
    BORESIGHT_YAW = "BORESIGHT_YAW"
    SKIP_OUTSIDE = "SKIP_OUTSIDE"
    MAX_GAP = "MAX_GAP"
    FAIL_ON_MISSING_IMAGE = "FAIL_ON_MISSING_IMAGE"
    OUTPUT = "OUTPUT"

    def displayName(self):
        return self.tr("Import trajectory and panoramas")

    def shortDescription(self):
        return self.tr("Trajectory (CSV or SBET) and image times, or per-image poses, to panorama stations "
                       "with full pose.")

    def shortHelpString(self):
        return self.tr(
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

    def initAlgorithm(self, config=None):
        self.add_file(
            self.TRAJECTORY, self.tr("Trajectory (CSV or SBET)"),
            self.tr("Trajectory CSV with a header time,x,y,z,roll,pitch,heading (comma, semicolon, tab or "
                    "space separated), or an Applanix SBET (.out, .sbet). Times increase strictly."),
            file_filter=self.tr("Trajectory (*.csv *.txt *.out *.sbet);;All files (*.*)"), optional=True)
        self.add_file(
            self.IMAGE_TIMES, self.tr("Image times (CSV)"),
            self.tr("CSV image,time: each panorama's file name (relative to the panorama folder) and "
                    "exposure time, in the trajectory's time base."),
            file_filter=self.tr("CSV (*.csv *.txt);;All files (*.*)"), optional=True)
        self.add_file(
            self.POSES, self.tr("Per-image poses (CSV, instead of trajectory and image times)"),
            self.tr("CSV image,x,y,z,roll,pitch,heading and optionally time: the vehicle body pose at "
                    "each exposure. Use instead of a trajectory with image times."),
            file_filter=self.tr("CSV (*.csv *.txt);;All files (*.*)"), optional=True)
        self.add_file(
            self.IMAGES, self.tr("Panorama folder"),
            self.tr("Folder of the equirectangular panoramas (JPEG or PNG, twice as wide as high)."),
            folder=True)
        self.add_crs(
            self.TRAJECTORY_CRS, self.tr("Trajectory CRS"),
            self.tr("CRS of the trajectory or pose positions (x = longitude, y = latitude, z = ellipsoidal "
                    "height for a geographic CRS). Ignored for an SBET, which is always WGS 84."),
            default="EPSG:4326")
        self.add_crs(
            self.TARGET_CRS, self.tr("Target CRS (projected)"),
            self.tr("Projected CRS of the outputs (metres, East-North-Up). A compound CRS with a vertical "
                    "datum turns ellipsoidal heights into that datum when its geoid grid is installed. "
                    "Empty: the trajectory CRS if it is projected, else its UTM zone."),
            optional=True)
        lever_help = self.tr("Panorama centre relative to the trajectory's reference point, in metres "
                             "along the body axes: x forward, y right, z down.")
        self.add_number(self.LEVER_ARM_X, self.tr("Lever arm x, forward (m)"), 0.0, lever_help)
        self.add_number(self.LEVER_ARM_Y, self.tr("Lever arm y, right (m)"), 0.0, lever_help)
        self.add_number(self.LEVER_ARM_Z, self.tr("Lever arm z, down (m)"), 0.0, lever_help)
        boresight_help = self.tr("Panorama frame relative to the body frame: R_body_from_pano = Rz(yaw) "
                                 "Ry(pitch) Rx(roll), degrees.")
        self.add_number(self.BORESIGHT_ROLL, self.tr("Boresight roll (°)"), 0.0, boresight_help, -360.0, 360.0)
        self.add_number(self.BORESIGHT_PITCH, self.tr("Boresight pitch (°)"), 0.0, boresight_help, -360.0, 360.0)
        self.add_number(self.BORESIGHT_YAW, self.tr("Boresight yaw (°)"), 0.0, boresight_help, -360.0, 360.0)
        self.add_boolean(
            self.SKIP_OUTSIDE, self.tr("Skip images outside the trajectory's time span"), False,
            self.tr("When checked, images whose time lies outside the trajectory are skipped and counted "
                    "in the log; otherwise they are an error."), advanced=True)
        self.add_number(
            self.MAX_GAP, self.tr("Warn about trajectory gaps longer than (s)"), 0.5,
            self.tr("A warning names images that fall between two trajectory samples further apart than "
                    "this, in seconds."), minimum=0.0, advanced=True)
        self.add_boolean(
            self.FAIL_ON_MISSING_IMAGE, self.tr("Fail on a missing or unreadable panorama"), False,
            self.tr("When checked, a missing or unreadable panorama is an error; otherwise it is skipped "
                    "with a warning and counted."), advanced=True)
        self.add_sink(
            self.OUTPUT, self.tr("Panorama stations"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("PointZ layer, one point per panorama at its centre, with the fields station_id, image, "
                    "path, time, x, y, z, qw, qx, qy, qz, heading, width, height."))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        target_crs = self.parameterAsCrs(parameters, self.TARGET_CRS, context)
        mount = CameraMount(
            lever_arm_m=[self.parameterAsDouble(parameters, name, context)
                         for name in (self.LEVER_ARM_X, self.LEVER_ARM_Y, self.LEVER_ARM_Z)],
            boresight_roll_deg=self.parameterAsDouble(parameters, self.BORESIGHT_ROLL, context),
            boresight_pitch_deg=self.parameterAsDouble(parameters, self.BORESIGHT_PITCH, context),
            boresight_yaw_deg=self.parameterAsDouble(parameters, self.BORESIGHT_YAW, context))
        with self.core_errors():
            result = import_stations(
                images_dir=self.parameterAsFile(parameters, self.IMAGES, context),
                target_crs=crs_for_pyproj(target_crs),
                trajectory_crs=crs_for_pyproj(self.parameterAsCrs(parameters, self.TRAJECTORY_CRS, context)),
                trajectory_path=self.parameterAsFile(parameters, self.TRAJECTORY, context) or None,
                image_times_path=self.parameterAsFile(parameters, self.IMAGE_TIMES, context) or None,
                poses_path=self.parameterAsFile(parameters, self.POSES, context) or None,
                mount=mount,
                skip_outside=self.parameterAsBoolean(parameters, self.SKIP_OUTSIDE, context),
                max_gap_s=self.parameterAsDouble(parameters, self.MAX_GAP, context),
                fail_on_missing_image=self.parameterAsBoolean(parameters, self.FAIL_ON_MISSING_IMAGE, context),
                progress=self.progress(feedback).sub(0.0, 0.9))
        for message in result.messages:
            feedback.pushInfo(self.localise(message))
        for warning in result.warnings:
            feedback.pushWarning(self.localise(warning))

        output_crs = target_crs if target_crs.isValid() else \
            QgsCoordinateReferenceSystem.fromWkt(result.target_crs_wkt)
        sink, dest_id = self.sink(parameters, self.OUTPUT, context, qgs_fields(STATION_FIELDS),
                                  Qgis.WkbType.PointZ, output_crs)
        records = result.stations.records()
        write_records(sink, STATION_FIELDS, records,
                      [QgsGeometry(QgsPoint(r["x"], r["y"], r["z"])) for r in records], feedback, (90, 100))
        feedback.pushInfo(self.tr("{} panorama stations written.").format(len(records)))
        return {self.OUTPUT: dest_id}
