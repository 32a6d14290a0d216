"""The sign layer's style: a symbol per class (shaped and coloured like the sign) and a
label with what the sign says (the figure of a speed limit, else the code's name; nothing
without a code) over its height; written as a QML beside the output and applied when QGIS
loads the output layer."""
import os

from qgis.core import (
    QgsCategorizedSymbolRenderer,
    QgsMarkerSymbol,
    QgsPalLayerSettings,
    QgsProcessingLayerPostProcessorInterface,
    QgsRendererCategory,
    QgsTextBufferSettings,
    QgsTextFormat,
    QgsVectorLayer,
    QgsVectorLayerSimpleLabeling,
)

from .i18n import tr

RED, BLUE, WHITE, DARK = "208,28,31,255", "31,95,191,255", "255,255,255,255", "29,29,27,255"
#: class -> (marker shape name, fill, stroke, rotation in degrees)
CLASS_SYMBOLS = {
    "warning": ("triangle", WHITE, RED, 0.0),
    "prohibitory": ("circle", WHITE, RED, 0.0),
    "mandatory": ("circle", BLUE, WHITE, 0.0),
    "information": ("square", BLUE, WHITE, 0.0),
    "stop": ("octagon", RED, WHITE, 22.5),
    "yield": ("triangle", WHITE, RED, 180.0),
}
HEIGHT_LABEL = "format_number(\"height\", 2) || ' m'"
#: The label: the figure in brackets of a code (``DE:274[50]`` -> ``50``, speed limits),
#: else ``code_name`` (else the code), on a line above the height. ``attribute()`` reads
#: NULL for a field the layer lacks, so layers without code fields get the height alone.
CODE_LABEL = (
    "with_variable('code', coalesce(attribute(@feature, 'code'), ''), "
    "CASE WHEN regexp_match(@code, '\\\\[[^\\\\]]+\\\\]') > 0 "
    "THEN regexp_substr(@code, '\\\\[([^\\\\]]+)\\\\]') || '\\n' "
    "WHEN @code <> '' THEN coalesce(nullif(attribute(@feature, 'code_name'), ''), @code) || '\\n' "
    "ELSE '' END) || " + HEIGHT_LABEL)


def _symbol(shape, fill, stroke, rotation_deg):
    return QgsMarkerSymbol.createSimple({"name": shape, "color": fill, "outline_color": stroke,
                                         "outline_width": "0.6", "size": "4.5",
                                         "angle": str(rotation_deg)})


def class_labels():
    """Sign class -> its name in the user's language, for the legend."""
    return {"warning": tr("warning"), "prohibitory": tr("prohibitory"), "mandatory": tr("mandatory"),
            "information": tr("information"), "stop": tr("stop"), "yield": tr("yield")}


def style_sign_layer(layer):
    """Categorised symbols by ``class`` (others grey) and a label: what the sign says over
    its height (:data:`CODE_LABEL`)."""
    labels = class_labels()
    categories = [QgsRendererCategory(name, _symbol(*spec), labels[name]) for name, spec in CLASS_SYMBOLS.items()]
    categories.append(QgsRendererCategory("", _symbol("diamond", "154,154,154,255", DARK, 0.0), tr("other")))
    layer.setRenderer(QgsCategorizedSymbolRenderer("class", categories))
    settings = QgsPalLayerSettings()
    settings.fieldName = CODE_LABEL
    settings.isExpression = True
    text = QgsTextFormat()
    text.setSize(8)
    buffer = QgsTextBufferSettings()
    buffer.setEnabled(True)
    buffer.setSize(0.8)
    text.setBuffer(buffer)
    settings.setFormat(text)
    layer.setLabeling(QgsVectorLayerSimpleLabeling(settings))
    layer.setLabelsEnabled(True)
    layer.triggerRepaint()


def write_sign_style(qml_path, crs):
    """Write the style as a QML file (QGIS loads ``signs.qml`` with ``signs.gpkg``)."""
    layer = QgsVectorLayer("PointZ?crs={}&field=class:string&field=height:double".format(
        crs.authid() or "EPSG:4326"), "signs", "memory")
    style_sign_layer(layer)
    message, ok = layer.saveNamedStyle(qml_path)
    return ok


class SignLayerStyler(QgsProcessingLayerPostProcessorInterface):
    """Applies the sign style to the output layer QGIS loads after the algorithm."""
    instance = None

    def postProcessLayer(self, layer, context, feedback):
        if isinstance(layer, QgsVectorLayer):
            style_sign_layer(layer)

    @staticmethod
    def create():
        SignLayerStyler.instance = SignLayerStyler()  # kept alive until QGIS calls it
        return SignLayerStyler.instance


def file_of(destination):
    """The file behind a vector destination ('/x/signs.gpkg|layername=signs' -> '/x/signs.gpkg')."""
    path = destination.split("|")[0]
    return path if os.path.splitext(path)[1] and os.path.isabs(path) else None
