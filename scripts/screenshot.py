"""Render the demo's styled sign layer headless into ``docs/signs.png`` (for the README).

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 scripts/screenshot.py [demo_out]
"""
import os
import sys

from qgis.core import (
    QgsApplication,
    QgsMapRendererParallelJob,
    QgsMapSettings,
    QgsProject,
    QgsRectangle,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSize
from qgis.PyQt.QtGui import QColor

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    demo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(REPO_ROOT, "demo_out")
    app = QgsApplication([], False)
    app.initQgis()
    layers = []
    for name in ("signs", "panel_outlines", "stations"):  # top first
        layer = QgsVectorLayer(os.path.join(demo, name + ".gpkg"), name, "ogr")
        if not layer.isValid():
            sys.exit("cannot read {}".format(layer.source()))
        QgsProject.instance().addMapLayer(layer)
        layers.append(layer)
    layers[2].renderer().symbol().setColor(QColor("#777777"))
    layers[2].renderer().symbol().setSize(1.2)
    extent = QgsRectangle(layers[0].extent())
    extent.combineExtentWith(layers[2].extent())
    extent.grow(6)
    settings = QgsMapSettings()
    settings.setLayers(layers)
    settings.setDestinationCrs(layers[0].crs())
    settings.setExtent(extent)
    settings.setOutputSize(QSize(900, 520))
    settings.setBackgroundColor(QColor("#f4f1ea"))
    job = QgsMapRendererParallelJob(settings)
    job.start()
    job.waitForFinished()
    out = os.path.join(REPO_ROOT, "docs", "signs.png")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    job.renderedImage().save(out)
    print("wrote", out)


if __name__ == "__main__":
    main()
