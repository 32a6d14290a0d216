"""The QGIS plugin object: registers the Processing provider and checks dependencies."""
import sys

from qgis.core import Qgis, QgsApplication, QgsMessageLog

from .dependencies import PACKAGES, missing_message
from .provider.i18n import install_translator, tr


class RoadSignsPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None
        self._translator = install_translator()

    def initProcessing(self):  # noqa: N802 (called by QGIS and qgis_process)
        from .provider.provider import RoadSignsProvider
        if self.provider is None:
            self.provider = RoadSignsProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)
        message = missing_message(PACKAGES, tr)
        if message:
            QgsMessageLog.logMessage(message, tr("Road Sign Inventory"), Qgis.MessageLevel.Warning)
            if self.iface is None and not getattr(self, "_told", False):  # qgis_process: stderr
                sys.stderr.write(message + "\n")
                self._told = True
        return message

    def initGui(self):  # noqa: N802
        message = self.initProcessing()
        if message and self.iface is not None:
            self.iface.messageBar().pushMessage(tr("Road Sign Inventory"), message,
                                                level=Qgis.MessageLevel.Warning, duration=0)

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
