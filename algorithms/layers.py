"""One reader and one writer for the plugin's layers (stations, detections, candidates,
signs, outlines): features <-> the plain records ``core`` reads and writes; the checks of
layer and cloud CRSs; and :class:`RunOutputs`, what a run has written so far, for the
boundary in :mod:`.base` to keep or remove.

Records are dicts of Python values (``None`` for NULL) keyed by field name, or, for the
layers of a whole drive (stations, detections, candidates), :class:`Columns` that read as
such records; each layer's fields are a :mod:`core.schema <roadsigns.core.schema>` declared
once in core. Here the field kinds become QGIS field types.
"""
import os
import re

from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsFeature,
    QgsFeatureRequest,
    QgsFeatureSink,
    QgsField,
    QgsFields,
    QgsProcessingException,
)
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QMetaType

from ..core.errors import Cancelled, InputError
from ..core.outputs import StagedOutputs, remove, temp_path_beside
from ..core.schema import Columns, names
from .i18n import tr

#: core field kind -> QGIS field type
FIELD_TYPES = {int: QMetaType.Type.Int, float: QMetaType.Type.Double, str: QMetaType.Type.QString}


def qgs_fields(schema):
    """The QgsFields of a core schema."""
    out = QgsFields()
    for field in schema:
        out.append(QgsField(field.name, FIELD_TYPES[field.kind]))
    return out


def _plain(value):
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    return value


def read_records(source, schema, label, feedback=None, required=None, allow_empty=False):
    """Attribute dicts of every feature of ``source`` (every field the layer has).

    The fields of ``schema`` (or only those named in ``required``) must be there: else an
    error naming the layer, the missing fields and the fields found. A layer without
    features is an error too, unless ``allow_empty``. Cancelling raises ``Cancelled``.
    """
    return list(_checked_records(source, schema, label, feedback, required, allow_empty))


def read_columns(source, schema, label, feedback=None, required=None, allow_empty=False):
    """The features of ``source`` as :class:`~roadsigns.core.schema.Columns` of ``schema``'s
    fields (those the layer has; the others read as NULL): a drive's detections or
    candidates as arrays, not a dict a feature. Checks and errors as :func:`read_records`."""
    columns = Columns(f for f in schema if f.name in source.fields().names())
    for record in _checked_records(source, schema, label, feedback, required, allow_empty):
        columns.append(record)
    return columns


def _checked_records(source, schema, label, feedback, required, allow_empty):
    """The attribute dicts of ``source``'s features, one at a time (see :func:`read_records`)."""
    found = source.fields().names()
    missing = [f for f in (required or names(schema)) if f not in found]
    if missing:
        raise QgsProcessingException(
            tr("{layer}: missing field(s) {missing}; fields found: {found}").format(
                layer=label, missing=", ".join(missing), found=", ".join(found)))
    typed = [f for f in schema if f.name in found and f.kind is not str]
    n = 0
    for feature in source.getFeatures(QgsFeatureRequest()):
        if feedback is not None and feedback.isCanceled():
            raise Cancelled("cancelled")
        record = {name: _plain(feature[name]) for name in found}
        for field in typed:  # a text field where a number belongs, from a layer made by hand
            try:
                field.value(record[field.name])
            except (TypeError, ValueError, OverflowError):
                raise QgsProcessingException(
                    tr("{layer}, feature {feature}: the field {field} holds '{value}', not a number").format(
                        layer=label, feature=n + 1, field=field.name,
                        value=str(record[field.name])[:60]))
        n += 1
        yield record
    if not n and not allow_empty:
        raise QgsProcessingException(tr("{layer}: the layer has no feature, nothing to process").format(
            layer=label))


def write_records(sink, schema, records, geometries, feedback=None, progress_span=(0, 100), count=None):
    """Add one feature per record, its values taken by ``schema``'s field names and kinds,
    with ``geometries[k]`` (a QgsGeometry, or None for a feature without geometry).
    ``records`` and ``geometries`` may be iterators (one feature made at a time), with
    ``count`` the number of records for progress. Cancelling raises ``Cancelled`` (the
    boundary then deletes the layer)."""
    fields = qgs_fields(schema)
    n = max(len(records) if count is None else count, 1)
    start, end = progress_span
    for k, (record, geometry) in enumerate(zip(records, geometries)):
        if feedback is not None and feedback.isCanceled():
            raise Cancelled("cancelled")
        feature = QgsFeature(fields)
        if geometry is not None:
            feature.setGeometry(geometry)
        feature.setAttributes([field.value(record.get(field.name)) for field in schema])
        if not sink.addFeature(feature, QgsFeatureSink.Flag.FastInsert):
            raise QgsProcessingException(tr("Cannot write feature {} to the output layer: {}").format(
                k + 1, sink.lastError() if hasattr(sink, "lastError") else ""))
        if feedback is not None and k % 100 == 0:
            feedback.setProgress(start + (end - start) * k / n)
    if feedback is not None and feedback.isCanceled():
        raise Cancelled("cancelled")


# --- CRSs -------------------------------------------------------------------------------

def crs_for_pyproj(crs: QgsCoordinateReferenceSystem):
    """Authority id when QGIS has one (what pyproj reads best), else WKT2; None if invalid."""
    if not crs.isValid():
        return None
    return crs.authid() or crs.toWkt(Qgis.CrsWktVariant.Wkt2_2019Simplified)


def crs_label(crs: QgsCoordinateReferenceSystem):
    return crs.authid() or crs.description()


def check_metric_crs(crs: QgsCoordinateReferenceSystem, label):
    """Error when ``crs`` (of the layer or file ``label``) is geographic: the stages measure
    in metres. A layer without CRS passes (it is taken to be in the cloud's CRS)."""
    if crs.isValid() and crs.isGeographic():
        raise QgsProcessingException(
            tr("{layer} is in {crs}, a geographic CRS (degrees): this needs a projected CRS in metres, "
               "the CRS of the point cloud (e.g. a UTM zone)").format(layer=label, crs=crs_label(crs)))


def check_layer_extent(source, label):
    """Error when the layer's coordinates lie outside the area of use of its CRS."""
    from ..core.crs import check_extent

    crs, extent = source.sourceCrs(), source.sourceExtent()
    if crs.isValid() and not extent.isNull() and not extent.isEmpty():
        check_extent(crs_for_pyproj(crs), (extent.xMinimum(), extent.yMinimum(), extent.xMaximum(),
                                           extent.yMaximum()), label)


def check_cloud_extent(cloud_path, crs_wkt):
    """Error when the cloud's bounds (its tiles' headers; a LAS/LAZ file, a folder of tiles or
    a .vpc) lie outside the area of use of ``crs_wkt``."""
    from ..core.cloudsource import open_cloud
    from ..core.crs import check_extent

    source = open_cloud(cloud_path)
    if source.point_count:
        check_extent(crs_wkt, source.bounds_xy, source.path)


def cloud_crs_wkt(user_crs: QgsCoordinateReferenceSystem, cloud_path):
    """The cloud's CRS as WKT: the one the user gave (``CLOUD_CRS``), else the file's (the
    tiles' of a folder or a .vpc, which must agree); an error when there is neither (a CRS
    is never guessed)."""
    if user_crs.isValid():
        return user_crs.toWkt(Qgis.CrsWktVariant.Wkt2_2019Simplified)
    wkt = read_cloud_crs_wkt(cloud_path)
    if not wkt:
        raise QgsProcessingException(
            tr("The point cloud {cloud} has no coordinate reference system: give it as Cloud CRS (an "
               "advanced parameter; a CRS is never guessed)").format(cloud=cloud_path))
    return wkt


def read_cloud_crs_wkt(cloud_path):
    """The CRS of a cloud (a LAS/LAZ file, a folder of tiles or a .vpc) as WKT, None when it
    has none; core's InputError when its tiles disagree or cannot be read."""
    from ..core.cloudsource import open_cloud

    return open_cloud(cloud_path).crs_wkt


def check_same_crs(layer_crs, cloud_crs_wkt, layer_label, cloud_path):
    """Error when a layer and the cloud are in different CRSs, when either is geographic
    (the stages measure in metres), or when the cloud has no CRS at all (give ``CLOUD_CRS``)."""
    if not cloud_crs_wkt:
        raise QgsProcessingException(
            tr("The point cloud {cloud} has no coordinate reference system: give it one with Ground "
               "filter (parameter Cloud CRS); a CRS is never guessed").format(cloud=cloud_path))
    cloud_crs = QgsCoordinateReferenceSystem.fromWkt(cloud_crs_wkt)
    if cloud_crs.isValid() and layer_crs.isValid() and cloud_crs != layer_crs:
        raise QgsProcessingException(
            tr("{layer} is in {layer_crs}, the point cloud {cloud} in {cloud_crs}: import the "
               "trajectory with the cloud's CRS as target CRS so that every stage works in one "
               "CRS").format(layer=layer_label, layer_crs=crs_label(layer_crs),
                             cloud=cloud_path, cloud_crs=crs_label(cloud_crs)))
    check_metric_crs(layer_crs, layer_label)
    check_metric_crs(cloud_crs, cloud_path)


# --- what a run has written ------------------------------------------------------------

#: files that belong to a vector dataset besides the file itself
_SIDECARS = {".shp": (".shx", ".dbf", ".prj", ".cpg", ".qpj", ".qix", ".sbn", ".sbx", ".fix", ".shp.xml",
                      ".qmd")}
_DATASET_SUFFIXES = ("-wal", "-shm", "-journal", ".aux.xml")
_PROVIDER_URI = re.compile(r"^[A-Za-z][A-Za-z0-9_]+:")


def dataset_files(path):
    """The files of the vector dataset ``path`` that exist (a shapefile's sidecars, a
    GeoPackage's journal...)."""
    stem, extension = os.path.splitext(path)
    candidates = [path] + [path + s for s in _DATASET_SUFFIXES] + \
        [stem + s for s in _SIDECARS.get(extension.lower(), ())]
    return [p for p in candidates if os.path.lexists(p)]


def destination_file(destination, context):
    """The file a layer destination names, and whether the whole file is the layer's
    (a plain path) or a layer is added to it (``path|layername=`` or an ``ogr:`` URI);
    ``(None, False)`` for memory layers and databases."""
    if not destination:
        return None, False
    match = re.match(r"^ogr:dbname='([^']+)'", destination)
    if match:
        return match.group(1), False
    if "|" in destination:
        return destination.split("|")[0], False
    if _PROVIDER_URI.match(destination) or not os.path.isabs(destination):
        return None, False
    if not os.path.splitext(destination)[1]:
        destination += "." + (context.preferredVectorFormat() or "gpkg")
    return destination, True


class RunOutputs:
    """What one run writes: staged files and folders (core's :class:`StagedOutputs`) and
    the layers it created, with the files those replaced moved aside. ``commit()`` keeps
    them all; ``rollback()`` removes them and puts the replaced files back, returning what
    it could not remove."""

    def __init__(self, context):
        self.context = context
        self.staged = StagedOutputs()
        self._sinks = []
        self._layers = []        # destination ids
        self._backups = []       # (moved-aside file, original)
        self._existing = set()   # files layers were added to, which existed before

    def protect_layer(self, destination):
        """Before QGIS creates the layer ``destination``: move aside the files it would replace."""
        path, whole_file = destination_file(destination, self.context)
        if path is None:
            return
        if not whole_file:
            if os.path.exists(path):
                self._existing.add(os.path.abspath(path))
            return
        for original in dataset_files(path):
            try:
                backup = temp_path_beside(original)
                os.replace(original, backup)
            except (OSError, InputError):  # locked (open on Windows): QGIS overwrites it, as before
                continue
            self._backups.append((backup, original))

    def add_layer(self, sink, dest_id):
        self._sinks.append(sink)
        self._layers.append(dest_id)

    def commit(self):
        self.staged.commit()
        self._sinks = []
        for backup, _ in self._backups:
            remove(backup)
        self._backups = []

    def rollback(self):
        left = []
        for sink in self._sinks:  # close the files before removing them
            if not sip.isdeleted(sink):
                sip.delete(sink)
        self._sinks = []
        for dest_id in self._layers:
            left += self._remove_layer(dest_id)
        for backup, original in reversed(self._backups):
            try:
                os.replace(backup, original)
            except OSError:
                left.append(backup)
        self._backups, self._layers = [], []
        return left + self.staged.rollback()

    def _remove_layer(self, dest_id):
        parts = str(dest_id).split("|")
        path = parts[0]
        if not os.path.isabs(path) or not os.path.exists(path):
            return []
        layer_name = next((p.split("=", 1)[1] for p in parts[1:] if p.startswith("layername=")), None)
        if layer_name is None or os.path.abspath(path) not in self._existing:
            return [p for p in dataset_files(path) if not remove(p)]
        try:
            from osgeo import ogr

            dataset = ogr.Open(path, update=1)
            for k in range(dataset.GetLayerCount()):
                if dataset.GetLayer(k).GetName() == layer_name:
                    dataset.DeleteLayer(k)
                    dataset = None
                    return []
        except Exception:  # OGR missing or the file locked: report the layer as left
            pass
        return ["{}|layername={}".format(path, layer_name)]
