"""One reader and one writer for the plugin's layers (stations, detections, candidates,
signs, outlines): features <-> the plain records ``core`` reads and writes.

Records are dicts of Python values (``None`` for NULL) keyed by field name; each layer's
fields are a :mod:`core.schema <roadsigns.core.schema>` declared once in core. Here the
field kinds become QGIS field types.
"""
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsFeature,
    QgsFeatureRequest,
    QgsFeatureSink,
    QgsField,
    QgsFields,
    QgsProcessingException,
)
from qgis.PyQt.QtCore import QMetaType

from ..core.schema import names
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


def read_records(source, schema, label, feedback=None, required=None):
    """Attribute dicts of every feature of ``source`` (every field the layer has).

    The fields of ``schema`` (or only those named in ``required``) must be there: else an
    error naming the layer, the missing fields and the fields found.
    """
    found = source.fields().names()
    missing = [f for f in (required or names(schema)) if f not in found]
    if missing:
        raise QgsProcessingException(
            tr("{layer}: missing field(s) {missing}; fields found: {found}").format(
                layer=label, missing=", ".join(missing), found=", ".join(found)))
    records = []
    for feature in source.getFeatures(QgsFeatureRequest()):
        if feedback is not None and feedback.isCanceled():
            break
        records.append({name: _plain(feature[name]) for name in found})
    return records


def write_records(sink, schema, records, geometries, feedback=None, progress_span=(0, 100)):
    """Add one feature per record, its values taken by ``schema``'s field names and kinds,
    with ``geometries[k]`` (a QgsGeometry, or None for a feature without geometry)."""
    fields = qgs_fields(schema)
    n = max(len(records), 1)
    start, end = progress_span
    for k, (record, geometry) in enumerate(zip(records, geometries)):
        if feedback is not None and feedback.isCanceled():
            break
        feature = QgsFeature(fields)
        if geometry is not None:
            feature.setGeometry(geometry)
        feature.setAttributes([field.value(record.get(field.name)) for field in schema])
        sink.addFeature(feature, QgsFeatureSink.Flag.FastInsert)
        if feedback is not None and k % 100 == 0:
            feedback.setProgress(start + (end - start) * k / n)


def check_same_crs(layer_crs, cloud_crs_wkt, layer_label, cloud_path):
    """Error when a layer and the cloud are in different CRSs (both known)."""
    if not cloud_crs_wkt or not layer_crs.isValid():
        return
    cloud_crs = QgsCoordinateReferenceSystem.fromWkt(cloud_crs_wkt)
    if cloud_crs.isValid() and cloud_crs != layer_crs:
        raise QgsProcessingException(
            tr("{layer} is in {layer_crs}, the point cloud {cloud} in {cloud_crs}: import the "
               "trajectory with the cloud's CRS as target CRS so that every stage works in one "
               "CRS").format(layer=layer_label, layer_crs=layer_crs.authid() or layer_crs.description(),
                             cloud=cloud_path, cloud_crs=cloud_crs.authid() or cloud_crs.description()))
