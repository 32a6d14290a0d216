"""The QGIS plugin object: registers the Processing provider, checks dependencies and, in the
QGIS desktop, adds the sign review panel (a dock widget; Vector menu and toolbar)."""
import sys

from qgis.core import Qgis, QgsApplication, QgsMessageLog
from qgis.PyQt.QtCore import Qt
from qgis.PyQt.QtGui import QIcon

from .algorithms.i18n import install_translator, tr, tr_core
from .algorithms.paths import ICON_PATH
from .dependencies import PACKAGES, missing_message


class RoadSignsPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None
        self.review_panel = None
        self.review_action = None
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
        if self.iface is not None:
            self._add_review_panel()

    def _add_review_panel(self):
        from .gui.reviewpanel import ReviewPanel

        self.review_panel = ReviewPanel(self.iface, self.iface.mainWindow())
        self.iface.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, self.review_panel)
        self.review_panel.hide()
        self.review_action = self.review_panel.toggleViewAction()
        self.review_action.setIcon(QIcon(ICON_PATH))
        self.review_action.setText(tr("Sign review panel"))
        self.review_action.setObjectName("RoadSignsReviewAction")
        self.iface.addPluginToVectorMenu(tr("Road Sign Inventory"), self.review_action)
        self.iface.addVectorToolBarIcon(self.review_action)

    def unload(self):
        if self.review_panel is not None:
            self.iface.removePluginVectorMenu(tr("Road Sign Inventory"), self.review_action)
            self.iface.removeVectorToolBarIcon(self.review_action)
            self.review_panel.cleanup()
            self.iface.removeDockWidget(self.review_panel)
            self.review_panel.deleteLater()
            self.review_panel = self.review_action = None
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
