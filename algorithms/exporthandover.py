"""roadsigns:exporthandover - the reviewed sign layer to a handover package: a GeoPackage and
a CSV in the schema of docs/formats.md (section 4.9), and an OpenStreetMap file."""
import os
from datetime import date

from qgis.core import (
    Qgis,
    QgsCoordinateTransform,
    QgsFeature,
    QgsFeatureSink,
    QgsGeometry,
    QgsPoint,
    QgsProcessingException,
    QgsProcessingOutputFile,
    QgsProcessingParameterEnum,
    QgsProcessingParameterField,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterString,
    QgsVectorFileWriter,
    QgsWkbTypes,
)

from .base import RoadSignsAlgorithm
from .layers import check_metric_crs, crs_for_pyproj, crs_label, qgs_fields, read_records


class ExportHandover(RoadSignsAlgorithm):
    ALGORITHM_ID = "exporthandover"
    REQUIRES = ("numpy", "pyproj")
    SIGNS = "SIGNS"
    STATIONS = "STATIONS"
    ROADS = "ROADS"
    ROAD_ID_FIELD = "ROAD_ID_FIELD"
    STATES = "STATES"
    NORTH = "NORTH"
    SURVEY_DATE = "SURVEY_DATE"
    TIME_BASE = "TIME_BASE"
    OSM_FORMAT = "OSM_FORMAT"
    COUNTRY = "COUNTRY"
    OSM_OFFSET = "OSM_OFFSET"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"
    GEOPACKAGE = "GEOPACKAGE"
    CSV = "CSV"
    OSM = "OSM"
    #: the review states, in the order of the STATES options (core.reviewstate.STATES)
    STATE_NAMES = ("accepted", "corrected", "rejected", "unsure", "unreviewed")

    def displayName(self):
        return self.tr("Export handover package")

    def shortDescription(self):
        return self.tr("The reviewed sign layer as a GeoPackage, a CSV and an OpenStreetMap file for handover.")

    def shortHelpString(self):
        return self.tr(
            "Writes the signs with the review states you choose (default: accepted and corrected) into a "
            "folder: <i>handover.gpkg</i> and <i>handover.csv</i> with one row per sign in a documented schema "
            "(docs/formats.md, section 4.9), and <i>osm_signs.osm</i> (or .geojson) for OpenStreetMap.<br><br>"
            "Each sign gets its code and class (after review), its position (x, y, z and WGS 84 longitude and "
            "latitude), mounting height, panel size, the azimuth its face looks towards (0-359, from true or "
            "grid north as chosen; the column azimuth_north says which), the side of the road and the lateral "
            "offset relative to the drive, the chainage along the drive (the stations' track), the nearest road "
            "segment's id and the fraction along it when a road network is given, condition and pole when the "
            "layer has them, survey date, first and last seen, source images and review status.<br><br>"
            "The OpenStreetMap nodes carry <i>traffic_sign</i> (the code, prefixed with the country) and "
            "<i>direction</i> (true north) and stand beside the road: a sign over the road is moved to its side "
            "of the drive.")

    def initAlgorithm(self, config=None):
        self.add_source(
            self.SIGNS, self.tr("Reviewed sign layer"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The sign layer after review (fields review_status, reviewed_code... as the review panel writes "
                    "them), in a projected CRS."))
        self.add_source(
            self.STATIONS, self.tr("Panorama stations"), Qgis.ProcessingSourceType.VectorPoint,
            self.tr("The output of Import trajectory for the same drive: its track gives side, offset and chainage, "
                    "its times first and last seen."))
        self.add_source(
            self.ROADS, self.tr("Road network (optional)"), Qgis.ProcessingSourceType.VectorLine,
            self.tr("Road segments (lines): each sign gets the nearest one's id and the fraction along it. Lines in "
                    "another CRS are reprojected."), optional=True)
        self.add(QgsProcessingParameterField(
            self.ROAD_ID_FIELD, self.tr("Road segment id field"), parentLayerParameterName=self.ROADS,
            optional=True), self.tr("The road network's field holding the segment ids; empty: the feature id."))
        self.add(QgsProcessingParameterEnum(
            self.STATES, self.tr("Review states to hand over"),
            options=[self.tr("accepted"), self.tr("corrected (accepted with a new class or code)"),
                     self.tr("rejected"), self.tr("needs another look"), self.tr("not reviewed")],
            allowMultiple=True, defaultValue=[0, 1]),
            self.tr("Only signs with these review states are written (several may be chosen)."))
        self.add_enum(
            self.NORTH, self.tr("Azimuth from"), [("true", self.tr("true north")), ("grid", self.tr("grid north"))],
            "true", self.tr("The facing azimuth is written clockwise from true north (grid azimuth plus meridian "
                            "convergence) or from grid north of the layer's CRS; the file says which."))
        self.add(QgsProcessingParameterString(
            self.SURVEY_DATE, self.tr("Survey date (YYYY-MM-DD)"), optional=True),
            self.tr("The date of the drive: with station times in GPS seconds of the week, first and last seen "
                    "become dates and times (UTC)."))
        self.add_enum(
            self.TIME_BASE, self.tr("Station times are"),
            [("gps_week_seconds", self.tr("GPS seconds of the week")), ("gps", self.tr("GPS time (seconds since "
                                                                                       "1980-01-06)")),
             ("unix", self.tr("UNIX time (seconds since 1970-01-01 UTC)"))], "gps_week_seconds",
            self.tr("The time base of the stations' time field (that of the trajectory)."))
        self.add_enum(
            self.OSM_FORMAT, self.tr("OpenStreetMap file"), [("osm", self.tr("OSM XML (.osm, opens in JOSM)")),
                                                             ("geojson", self.tr("GeoJSON (.geojson)"))], "osm",
            self.tr("The format of the OpenStreetMap nodes file."))
        self.add(QgsProcessingParameterString(
            self.COUNTRY, self.tr("Country prefix for traffic_sign"), optional=True),
            self.tr("ISO country code written before codes without one: DE gives traffic_sign=DE:206."))
        self.add_number(
            self.OSM_OFFSET, self.tr("Least distance of OSM nodes from the road (m)"), 2.0,
            self.tr("OpenStreetMap nodes closer than this to the drive (or to the nearest road line) are moved "
                    "away from it on the sign's side, so that no sign node sits on the road."),
            minimum=0.1, advanced=True)
        self.add(QgsProcessingParameterFolderDestination(self.OUTPUT_FOLDER, self.tr("Handover folder")),
                 self.tr("The folder the package is written to (created when missing; files of an earlier package "
                         "are replaced)."))
        self.addOutput(QgsProcessingOutputFile(self.GEOPACKAGE, self.tr("Handover GeoPackage")))
        self.addOutput(QgsProcessingOutputFile(self.CSV, self.tr("Handover CSV")))
        self.addOutput(QgsProcessingOutputFile(self.OSM, self.tr("OpenStreetMap file")))

    def processAlgorithm(self, parameters, context, feedback):
        from ..core import handover as H
        from ..core.refine import SIGN_FIELDS
        from ..core.reviewstate import REVIEW_STATUS, UNREVIEWED

        folder = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        with self.core_errors():
            H.check_output_folder(folder)  # before any work
        self.check_dependencies()
        states = tuple(self.STATE_NAMES[k] for k in sorted(self.parameterAsEnums(parameters, self.STATES, context)))
        if not states:
            raise QgsProcessingException(self.tr("Choose at least one review state to hand over."))
        survey_date = self._survey_date(parameters, context)

        signs_source = self.source(parameters, self.SIGNS, context)
        crs = signs_source.sourceCrs()
        if not crs.isValid():
            raise QgsProcessingException(self.tr("The sign layer has no CRS: set its projected CRS (layer "
                                                 "properties) and run again."))
        check_metric_crs(crs, self.tr("The sign layer"))
        required = H.SIGN_REQUIRED + ((REVIEW_STATUS.name,) if UNREVIEWED not in states else ())
        signs = read_records(signs_source, SIGN_FIELDS, self.tr("Reviewed sign layer"), feedback, required=required)
        self._positions(signs_source, signs)
        stations_source = self.source(parameters, self.STATIONS, context)
        if stations_source.sourceCrs().isValid() and stations_source.sourceCrs() != crs:
            raise QgsProcessingException(self.tr(
                "The stations are in {}, the sign layer in {}: use the stations of the drive the signs come "
                "from").format(crs_label(stations_source.sourceCrs()), crs_label(crs)))
        stations = read_records(stations_source, (), self.tr("Panorama stations"), feedback,
                                required=H.STATION_REQUIRED)
        roads = self._roads(parameters, context, crs, feedback)

        params = H.HandoverParams(
            states=states, north=self.enum_name(parameters, self.NORTH, context), survey_date=survey_date,
            time_base=self.enum_name(parameters, self.TIME_BASE, context),
            osm_offset_m=self.parameterAsDouble(parameters, self.OSM_OFFSET, context),
            country=self.parameterAsString(parameters, self.COUNTRY, context) or "")
        with self.core_errors():
            result = H.build_handover(signs, stations, crs_for_pyproj(crs), roads, params,
                                      self.progress(feedback).sub(0.0, 0.8))

        osm_format = self.enum_name(parameters, self.OSM_FORMAT, context)
        paths = {self.GEOPACKAGE: os.path.join(folder, H.GPKG_NAME), self.CSV: os.path.join(folder, H.CSV_NAME),
                 self.OSM: os.path.join(folder, H.OSM_NAMES[osm_format])}
        with self.core_errors():
            H.write_csv(self.output_file(paths[self.CSV]), result.records)
            writer = H.write_osm_xml if osm_format == "osm" else H.write_osm_geojson
            writer(self.output_file(paths[self.OSM]), result.nodes)
            self._write_geopackage(self.output_file(paths[self.GEOPACKAGE]), H.HANDOVER_FIELDS, H.LAYER_NAME,
                                   result.records, crs, context)
        feedback.setProgress(100)
        feedback.pushInfo(self.tr("Handover package: {} signs in {}").format(len(result.records), folder))
        return {self.OUTPUT_FOLDER: folder, **paths}

    def _survey_date(self, parameters, context):
        text = (self.parameterAsString(parameters, self.SURVEY_DATE, context) or "").strip()
        if not text:
            return None
        try:
            return date.fromisoformat(text)
        except ValueError:
            raise QgsProcessingException(self.tr("Survey date '{}' is not a date: write it as YYYY-MM-DD, e.g. "
                                                 "2024-03-14").format(text))

    def _positions(self, source, signs):
        """Each sign's x, y, z from its geometry (it may have been moved in review); the x, y,
        z fields for a feature without geometry; an error naming a sign with neither."""
        geometries = [f.geometry() for f in source.getFeatures()]
        for record, geometry in zip(signs, geometries):
            if geometry is not None and not geometry.isEmpty():
                point = geometry.constGet()
                if hasattr(point, "x"):
                    record["x"], record["y"] = point.x(), point.y()
                    if point.is3D():
                        record["z"] = point.z()
                    continue
            if record.get("x") is None or record.get("y") is None:
                raise QgsProcessingException(self.tr("Sign {} has neither a point geometry nor x and y "
                                                     "fields").format(record.get("sign_id")))

    def _roads(self, parameters, context, crs, feedback):
        """The road network as core lines in the sign layer's CRS; None without one."""
        import numpy as np

        from ..core.handover import Road

        source = self.parameterAsSource(parameters, self.ROADS, context)
        if source is None:
            return None
        id_field = self.parameterAsString(parameters, self.ROAD_ID_FIELD, context)
        if id_field and source.fields().indexOf(id_field) < 0:
            raise QgsProcessingException(self.tr("The road network has no field {}; fields found: {}").format(
                id_field, ", ".join(source.fields().names())))
        transform = None
        if source.sourceCrs().isValid() and source.sourceCrs() != crs:
            transform = QgsCoordinateTransform(source.sourceCrs(), crs, context.transformContext())
            feedback.pushInfo(self.tr("The road network is in {}: reprojected to {}, the sign layer's CRS.").format(
                crs_label(source.sourceCrs()), crs_label(crs)))
        if not id_field:
            feedback.pushInfo(self.tr("No road segment id field chosen: the road ids are the feature ids."))
        roads = []
        for feature in source.getFeatures():
            geometry = QgsGeometry(feature.geometry())
            if geometry.isEmpty():
                continue
            if transform is not None:
                geometry.transform(transform)
            if QgsWkbTypes.isCurvedType(geometry.wkbType()):
                geometry.convertToStraightSegment()
            lines = geometry.asMultiPolyline() if geometry.isMultipart() else [geometry.asPolyline()]
            parts = [np.array([[p.x(), p.y()] for p in line]) for line in lines if len(line) >= 2]
            if parts:
                value = feature[id_field] if id_field else feature.id()
                roads.append(Road(str(value) if value is not None else "", parts))
        if not roads:
            feedback.pushWarning(self.tr("The road network has no lines: road_id and road_fraction stay empty."))
        return roads

    def _write_geopackage(self, path, schema, layer_name, records, crs, context):
        options = QgsVectorFileWriter.SaveVectorOptions()
        options.driverName = "GPKG"
        options.layerName = layer_name
        options.fileEncoding = "UTF-8"
        fields = qgs_fields(schema)
        writer = QgsVectorFileWriter.create(path, fields, Qgis.WkbType.PointZ, crs, context.transformContext(),
                                            options)
        if writer.hasError() != QgsVectorFileWriter.WriterError.NoError:
            raise QgsProcessingException(self.tr("Cannot write {}: {}").format(path, writer.errorMessage()))
        for record in records:
            feature = QgsFeature(fields)
            feature.setGeometry(QgsGeometry(QgsPoint(record["x"], record["y"], record["z"] if record["z"] is not None
                                                     else float("nan"))))
            feature.setAttributes([f.value(record.get(f.name)) for f in schema])
            if not writer.addFeature(feature, QgsFeatureSink.Flag.FastInsert):
                raise QgsProcessingException(self.tr("Cannot write {}: {}").format(path, writer.errorMessage()))
        writer.flushBuffer()
        del writer
