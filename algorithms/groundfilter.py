"""roadsigns:groundfilter - crop a point cloud (a LAS/LAZ file, a folder of tiles or a
virtual point cloud) and classify its ground (class 2) with the CSF or SMRF filter, by the
built-in engine or PDAL (Auto: the one measured faster, core/ground/params.py AUTO_ENGINES);
one output file, or one output tile per input tile and a virtual point cloud listing them."""
import os
from contextlib import contextmanager

from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsWkbTypes,
)

from .base import RoadSignsAlgorithm
from .layers import check_cloud_extent, check_metric_crs

#: Provider setting (Processing ▸ Options ▸ Providers) and environment variable for a
#: ``pdal`` executable that is neither on PATH nor in QGIS's bin folder.
PDAL_SETTING = "ROADSIGNS_PDAL_EXECUTABLE"


def configured_pdal_executable():
    """The ``pdal`` path from the provider's settings or ``ROADSIGNS_PDAL_EXECUTABLE``; None if unset."""
    path = os.environ.get(PDAL_SETTING, "")
    try:
        from processing.core.ProcessingConfig import ProcessingConfig
        path = ProcessingConfig.getSetting(PDAL_SETTING) or path
    except Exception:  # processing plugin not loaded
        pass
    return path or None


class GroundFilter(RoadSignsAlgorithm):
    ALGORITHM_ID = "groundfilter"
    REQUIRES = ("numpy", "scipy", "pyproj", "laspy", "lazrs", "shapely")
    INPUT = "INPUT"
    CROP = "CROP"
    CROP_BUFFER = "CROP_BUFFER"
    METHOD = "METHOD"
    ENGINE = "ENGINE"
    THRESHOLD = "THRESHOLD"
    CELL_SIZE = "CELL_SIZE"
    CLOUD_CRS = "CLOUD_CRS"
    RESET_CLASSES = "RESET_CLASSES"
    OUTPUT_TILES = "OUTPUT_TILES"
    OUTPUT = "OUTPUT"
    ENGINE_USED = "ENGINE_USED"
    POINTS_IN = "POINTS_IN"
    POINTS_OUT = "POINTS_OUT"
    GROUND_POINTS = "GROUND_POINTS"

    def displayName(self):
        return self.tr("Ground filter and crop point cloud")

    def shortDescription(self):
        return self.tr("Crops a LAS/LAZ cloud and classifies ground (class 2) with CSF or SMRF, PDAL or "
                       "built-in.")

    def shortHelpString(self):
        return self.tr(
            "Reads the LAS/LAZ cloud in chunks, keeps the points inside the crop area and "
            "classifies ground points as class 2 with the cloth simulation filter (CSF, Zhang et "
            "al. 2016) or the simple morphological filter (SMRF, Pingel et al. 2013), with PDAL's "
            "parameters (defaults tuned for dense mobile-mapping clouds: 0.2 m threshold, 0.5 m "
            "cells; PDAL's own are 0.5 m and 1 m). Other classes are kept unless <i>Reset existing classes</i> is "
            "checked. Every dimension, extra bytes, VLRs, scales and offsets and the CRS are "
            "written unchanged.<br><br><b>Crop</b>: polygons (grown by the crop buffer), or points "
            "and lines such as the panorama stations or detection rays, buffered into a corridor. "
            "The crop layer is reprojected to the cloud's CRS.<br><br><b>Engine</b>: PDAL runs "
            "filters.csf / filters.smrf through its Python bindings or the <i>pdal</i> executable "
            "(on PATH, in QGIS's bin folder, or set in Processing ▸ Options ▸ Providers ▸ Road sign "
            "inventory), holding the cloud in memory (about 150 bytes a point); the built-in engine runs "
            "the same filters in Python, streaming the cloud, so clouds larger than memory work (between its "
            "two passes it keeps the points uncompressed on disk beside the output, about 30 bytes a point, so a "
            "LAZ is decompressed once). A cloud wider or longer than 512 m (a drive) is classified block by "
            "block, the ground surface of one block at a time, so the memory does not grow with the drive; "
            "its points are then written grouped by block. "
            "<b>Auto picks the built-in engine</b> for both methods: measured against PDAL 2.9.2 on two "
            "cores it was as fast for CSF on 8 M points (within 10 %) and 1.6 times faster on 38 M, and 1.4 to "
            "1.7 times faster for SMRF, in about 300 MB where PDAL took 5.6 GB for 38 M points "
            "(bench/README.md). Auto uses PDAL "
            "only when the built-in CSF's Python package (cloth-simulation-filter) is missing; the log "
            "says which engine ran and why.<br><br><b>Tiles</b>: the input may be one "
            "LAS/LAZ file, a folder of LAS/LAZ tiles or a virtual point cloud (.vpc); PDAL takes the tiles one "
            "by one, each with its neighbours' points around it. They are written to one file, or, with "
            "<i>Write one tile "
            "per input tile</i>, each to a file of its own name in a folder named after the output (out/ground.laz "
            "gives the folder out/ground), with a virtual point cloud listing them (out/ground/ground.vpc, the "
            "output to give the next stages). Each tile is classified with its neighbours' points around it, so "
            "the classes at tile edges are those of a run on the whole cloud.")

    def initAlgorithm(self, config=None):
        self.add_las_file(
            self.INPUT, self.tr("Point cloud (LAS/LAZ)"),
            self.tr("The mobile-mapping cloud, LAS 1.2-1.4 or LAZ, any size (it is read in chunks)."))
        self.add_source(
            self.CROP, self.tr("Crop layer (optional)"), Qgis.ProcessingSourceType.VectorAnyGeometry,
            self.tr("Keep only points inside these polygons, or within the crop buffer of these points or "
                    "lines (e.g. the panorama stations). Empty keeps the whole cloud."), optional=True)
        self.add_number(
            self.CROP_BUFFER, self.tr("Crop buffer (m)"), 0.0,
            self.tr("Grow the crop geometries by this many metres; needed (> 0) for a point or line layer."),
            minimum=0.0)
        self.add_enum(
            self.METHOD, self.tr("Ground method"),
            [("csf", self.tr("CSF (cloth simulation)")), ("smrf", self.tr("SMRF (simple morphological filter)"))],
            "csf", self.tr("CSF suits roads and gentle terrain; SMRF suits steeper or rougher terrain."))
        self.add_enum(
            self.ENGINE, self.tr("Engine"),
            [("auto", self.tr("Auto (the faster engine: built-in)")), ("pdal", self.tr("PDAL")),
             ("builtin", self.tr("Built-in"))],
            "auto", self.tr("Auto: the engine measured faster for the method, today the built-in engine for both "
                            "(PDAL when the built-in CSF's package is missing). PDAL: its Python bindings or the "
                            "pdal executable that QGIS has; an error when there is neither."))
        self.add_number(
            self.THRESHOLD, self.tr("Ground distance threshold (m)"), 0.2,
            self.tr("Points within this height of the ground surface are ground (PDAL's threshold option). "
                    "PDAL's default is 0.5 m; 0.2 m suits dense mobile-mapping clouds, where it keeps the "
                    "lowest parts of cars, walls and street furniture off the ground class."),
            minimum=0.01, advanced=True)
        self.add_number(
            self.CELL_SIZE, self.tr("Cloth resolution / cell size (m)"), 0.5,
            self.tr("CSF's cloth resolution or SMRF's cell size, in metres (PDAL's default: 1 m)."),
            minimum=0.05, advanced=True)
        self.add_crs(
            self.CLOUD_CRS, self.tr("Cloud CRS (when the file has none)"),
            self.tr("The cloud's CRS if the file does not record one; a CRS in the file is replaced by it. "
                    "The CRS is never guessed."), optional=True, advanced=True)
        self.add_boolean(
            self.RESET_CLASSES, self.tr("Reset existing classes"), False,
            self.tr("Set every non-ground point to class 1 (unclassified) instead of keeping its class."),
            advanced=True)
        self.add_boolean(
            self.OUTPUT_TILES, self.tr("Write one tile per input tile"), False,
            self.tr("Write each input tile to its own file (same name, same header) in a folder named after the "
                    "output, with a virtual point cloud (.vpc) listing them, instead of one file."))
        self.add_file_destination(
            self.OUTPUT, self.tr("Ground-classified cloud"), self.tr("LAZ (*.laz);;LAS (*.las)"),
            self.tr("The cropped cloud with ground as class 2; LAZ or LAS by the file extension. LAS is about "
                    "eight times larger (about 30 bytes a point) but needs no compression here nor decompression in "
                    "the stages that read it next: on a 1 km drive of 38 M points the whole chain ran in 0.84 "
                    "times the time with a LAS ground cloud. With one tile per input tile: the folder of this name "
                    "without its extension gets the tiles and <name>.vpc, which is then this output."))
        self.addOutput(QgsProcessingOutputString(self.ENGINE_USED, self.tr("Engine that ran")))
        self.addOutput(QgsProcessingOutputNumber(self.POINTS_IN, self.tr("Points read")))
        self.addOutput(QgsProcessingOutputNumber(self.POINTS_OUT, self.tr("Points written")))
        self.addOutput(QgsProcessingOutputNumber(self.GROUND_POINTS, self.tr("Ground points")))

    def _crop_geometries(self, parameters, context, cloud_crs, buffer_m, feedback):
        """WKB of the crop layer's geometries in the cloud's CRS (None without a crop layer).
        A crop layer without features or geometries is an error: cropping by nothing must
        not turn into processing the whole cloud."""
        source = self.parameterAsSource(parameters, self.CROP, context)
        if source is None:
            return None
        if QgsWkbTypes.geometryType(source.wkbType()) != Qgis.GeometryType.Polygon and buffer_m <= 0:
            raise QgsProcessingException(self.tr(
                "The crop layer holds points or lines: give a crop buffer in metres (> 0) to make "
                "a corridor around them"))
        transform = None
        if cloud_crs.isValid() and source.sourceCrs().isValid() and source.sourceCrs() != cloud_crs:
            feedback.pushInfo(self.tr("Reprojecting the crop layer from {} to {}").format(
                source.sourceCrs().authid(), cloud_crs.authid() or cloud_crs.description()))
            transform = QgsCoordinateTransform(source.sourceCrs(), cloud_crs, context.transformContext())
        geometries, n_features = [], 0
        for feature in source.getFeatures():
            if feedback.isCanceled():
                raise QgsProcessingException(self.tr("Cancelled: nothing was written."))
            n_features += 1
            geometry = feature.geometry()
            if geometry.isNull() or geometry.isEmpty():
                continue
            if transform is not None:
                geometry.transform(transform)
            geometries.append(bytes(geometry.asWkb()))
        if n_features == 0:
            raise QgsProcessingException(self.tr(
                "The crop layer {} has no feature: nothing to crop by. Leave the crop layer empty to "
                "process the whole cloud").format(source.sourceName()))
        if not geometries:
            raise QgsProcessingException(self.tr(
                "The crop layer {} has no geometry (its {} features are empty): nothing to crop by").format(
                source.sourceName(), n_features))
        return geometries

    def _check_crop_overlaps(self, crop, buffer_m, bounds_xy, input_path):
        """Error when the crop area (grown by the buffer) misses the cloud's bounds
        ``(xmin, ymin, xmax, ymax)``."""
        import shapely

        area = shapely.union_all([shapely.from_wkb(g) for g in crop])
        xmin, ymin, xmax, ymax = area.bounds
        cx0, cy0, cx1, cy1 = bounds_xy
        if not (xmin - buffer_m <= cx1 and xmax + buffer_m >= cx0
                and ymin - buffer_m <= cy1 and ymax + buffer_m >= cy0):
            raise QgsProcessingException(self.tr(
                "The crop area (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}) does not overlap the point cloud "
                "{} (x {:.1f} to {:.1f}, y {:.1f} to {:.1f}): nothing would be kept").format(
                xmin - buffer_m, xmax + buffer_m, ymin - buffer_m, ymax + buffer_m, input_path,
                cx0, cx1, cy0, cy1))

    @contextmanager
    def _pdal_errors(self, pdal_error_type, feedback):
        try:
            yield
        except pdal_error_type as error:
            details = str(getattr(error, "stderr", "") or "").strip()
            if details:
                feedback.pushWarning(self.tr("PDAL said: {}").format(details))
            raise QgsProcessingException(self.tr("PDAL failed: {}").format(error))

    def processAlgorithm(self, parameters, context, feedback):
        self.check_dependencies()
        from ..core.cloudsource import open_cloud
        from ..core.ground import CsfParams, PdalError, SmrfParams, run_ground_filter, run_ground_filter_tiles
        from ..core.ground.tiled import output_tile_names

        input_path = self.parameterAsFile(parameters, self.INPUT, context)
        output_path = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        as_tiles = self.parameterAsBoolean(parameters, self.OUTPUT_TILES, context)
        if not as_tiles and os.path.splitext(output_path)[1].lower() not in (".las", ".laz"):
            output_path = os.path.splitext(output_path)[0] + ".laz"
        user_crs = self.parameterAsCrs(parameters, self.CLOUD_CRS, context)
        buffer_m = self.parameterAsDouble(parameters, self.CROP_BUFFER, context)
        with self.core_errors():
            source = open_cloud(input_path)
            crs_wkt = user_crs.toWkt(Qgis.CrsWktVariant.Wkt2_2019Simplified) if user_crs.isValid() \
                else source.crs_wkt
        for tile in source.tiles:
            if os.path.exists(output_path) and os.path.samefile(tile.path, output_path):
                raise QgsProcessingException(self.tr("The output {} must not be the input file").format(output_path))
        cloud_crs = QgsCoordinateReferenceSystem.fromWkt(crs_wkt) if crs_wkt else QgsCoordinateReferenceSystem()
        if crs_wkt:
            check_metric_crs(user_crs if user_crs.isValid() else cloud_crs, input_path)
            with self.core_errors():
                check_cloud_extent(source, crs_wkt)
        crop = self._crop_geometries(parameters, context, cloud_crs, buffer_m, feedback)
        if crop:
            self._check_crop_overlaps(crop, buffer_m, source.bounds_xy, input_path)
        method = self.enum_name(parameters, self.METHOD, context)
        threshold_m = self.parameterAsDouble(parameters, self.THRESHOLD, context)
        cell_m = self.parameterAsDouble(parameters, self.CELL_SIZE, context)
        params = CsfParams(resolution=cell_m, threshold=threshold_m) if method == "csf" else \
            SmrfParams(cell=cell_m, threshold=threshold_m)
        common = dict(method=method, params=params, engine=self.enum_name(parameters, self.ENGINE, context),
                      crop_polygons=crop, crop_buffer_m=buffer_m if crop else 0.0,
                      crs_wkt=crs_wkt if user_crs.isValid() else None,
                      reset_classes=self.parameterAsBoolean(parameters, self.RESET_CLASSES, context),
                      progress=self.progress(feedback))
        if as_tiles:
            folder = os.path.splitext(output_path)[0]
            vpc_name = os.path.basename(folder) + ".vpc"
            feedback.pushInfo(self.tr("Writing one tile per input tile to the folder {}, listed in {}").format(
                folder, vpc_name))
            with self.core_errors(), self._pdal_errors(PdalError, feedback):
                output_tile_names(source, folder)  # the folder is replaced whole: it must hold no input tile
                result = run_ground_filter_tiles(source, self.output_folder(folder), vpc_name,
                                                 pdal_executable=configured_pdal_executable(), **common)
            output_path = os.path.join(folder, vpc_name)
        else:
            with self.core_errors(), self._pdal_errors(PdalError, feedback):
                result = run_ground_filter(source, self.output_file(output_path),
                                           pdal_executable=configured_pdal_executable(), **common)
        feedback.pushInfo(self.tr("Engine: {}; method: {}; {} points read, {} written, {} ground").format(
            result.engine, result.method.upper(), result.n_input, result.n_output, result.n_ground))
        return {self.OUTPUT: output_path, self.ENGINE_USED: result.engine,
                self.POINTS_IN: result.n_input, self.POINTS_OUT: result.n_output,
                self.GROUND_POINTS: result.n_ground}
