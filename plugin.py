"""The QGIS plugin object: registers the Processing provider and checks dependencies."""
import sys

from qgis.core import Qgis, QgsApplication, QgsMessageLog

from .algorithms.i18n import install_translator, tr, tr_core
from .dependencies import PACKAGES, missing_message


class RoadSignsPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None
        self._translator = install_translator()

    def initProcessing(self):
        from .provider.provider import RoadSignsProvider
        if self.provider is None:
            self.provider = RoadSignsProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)
        message = missing_message(PACKAGES, tr_core)
        if message:
            QgsMessageLog.logMessage(message, tr("Road Sign Inventory"), Qgis.MessageLevel.Warning)
            if self.iface is None and not getattr(self, "_told", False):  # qgis_process: stderr
                sys.stderr.write(message + "\n")
                self._told = True
        return message

    def initGui(self):
        message = self.initProcessing()
        if message and self.iface is not None:
            self.iface.messageBar().pushMessage(tr("Road Sign Inventory"), message,
                                                level=Qgis.MessageLevel.Warning, duration=0)

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
