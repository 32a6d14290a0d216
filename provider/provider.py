"""The Processing provider ``roadsigns``: lists the algorithms, one per module."""
import os

from qgis.core import QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from .i18n import tr

ICON_PATH = os.path.join(os.path.dirname(os.path.dirname(__file__)), "icons", "roadsigns.svg")


class RoadSignsProvider(QgsProcessingProvider):
    def id(self):
        return "roadsigns"

    def name(self):
        return tr("Road sign inventory")

    def longName(self):  # noqa: N802
        return tr("Road sign inventory from mobile mapping (panoramas, trajectory, LiDAR)")

    def icon(self):
        return QIcon(ICON_PATH)

    def svgIconPath(self):  # noqa: N802
        return ICON_PATH

    def load(self):
        """Register the provider's settings (Processing ▸ Options ▸ Providers)."""
        try:
            from processing.core.ProcessingConfig import ProcessingConfig, Setting
            from ..algorithms.groundfilter import PDAL_SETTING
            ProcessingConfig.settingIcons[self.name()] = self.icon()
            ProcessingConfig.addSetting(Setting(
                self.name(), PDAL_SETTING,
                tr("PDAL executable for the ground filter (empty: search PATH and QGIS)"), "",
                valuetype=Setting.FILE))
            ProcessingConfig.readSettings()
        except ImportError:  # the processing plugin is not there: no settings dialog
            pass
        self.refreshAlgorithms()
        return True

    def unload(self):
        try:
            from processing.core.ProcessingConfig import ProcessingConfig
            from ..algorithms.groundfilter import PDAL_SETTING
            ProcessingConfig.removeSetting(PDAL_SETTING)
        except ImportError:
            pass

    def loadAlgorithms(self):  # noqa: N802
        from ..algorithms.detectsigns import DetectSigns
        from ..algorithms.evaluate import Evaluate
        from ..algorithms.groundfilter import GroundFilter
        from ..algorithms.importtrajectory import ImportTrajectory
        from ..algorithms.projectdetections import ProjectDetections
        from ..algorithms.refinesigns import RefineSigns
        for algorithm in (ImportTrajectory(), DetectSigns(), GroundFilter(), ProjectDetections(),
                          RefineSigns(), Evaluate()):
            self.addAlgorithm(algorithm)
