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

    def loadAlgorithms(self):  # noqa: N802
        from ..algorithms.detectsigns import DetectSigns
        from ..algorithms.evaluate import Evaluate
        from ..algorithms.importtrajectory import ImportTrajectory
        for algorithm in (ImportTrajectory(), DetectSigns(), Evaluate()):
            self.addAlgorithm(algorithm)
