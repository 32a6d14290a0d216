"""Reading features into plain records and writing records into sinks, for the adapters.

Records are dicts of Python values (``None`` for NULL), the form ``core`` reads and writes.
Field specs are ``(name, QMetaType.Type)`` pairs, one list per layer kind.
"""
import math

from qgis.core import (QgsCoordinateReferenceSystem, QgsFeature, QgsFeatureRequest,
                       QgsFeatureSink, QgsField, QgsFields, QgsProcessingException)
from qgis.PyQt.QtCore import QMetaType

from ..provider.i18n import tr

INT, DOUBLE, TEXT = QMetaType.Type.Int, QMetaType.Type.Double, QMetaType.Type.QString


def make_fields(spec):
    fields = QgsFields()
    for name, field_type in spec:
        fields.append(QgsField(name, field_type))
    return fields


def _plain(value):
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    return value


def read_records(source, required, label, feedback=None):
    """Attribute dicts of every feature of ``source``; error naming missing fields."""
    names = source.fields().names()
    missing = [f for f in required if f not in names]
    if missing:
        raise QgsProcessingException(
            tr("{layer}: missing field(s) {missing}; fields found: {found}").format(
                layer=label, missing=", ".join(missing), found=", ".join(names)))
    records = []
    for feature in source.getFeatures(QgsFeatureRequest()):
        if feedback is not None and feedback.isCanceled():
            break
        records.append({name: _plain(feature[name]) for name in names})
    return records


def _value(value, field_type):
    if value is None:
        return None
    if field_type == DOUBLE:
        value = float(value)
        return None if math.isnan(value) else value
    if field_type == INT:
        return int(value)
    return str(value)


def write_records(sink, fields, spec, records, geometries, feedback=None, progress_span=(0, 100)):
    """Add one feature per record (values taken by field name) with ``geometries[k]``
    (a QgsGeometry, or None for a feature without geometry)."""
    n = max(len(records), 1)
    start, end = progress_span
    for k, (record, geometry) in enumerate(zip(records, geometries)):
        if feedback is not None and feedback.isCanceled():
            break
        feature = QgsFeature(fields)
        if geometry is not None:
            feature.setGeometry(geometry)
        feature.setAttributes([_value(record.get(name), field_type) for name, field_type in spec])
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
