"""The Processing provider ``roadsigns``: lists the algorithms, one per module."""
import glob
import os

from qgis.core import QgsApplication, QgsProcessingModelAlgorithm, QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from .i18n import tr

PLUGIN_DIR = os.path.dirname(os.path.dirname(__file__))
ICON_PATH = os.path.join(PLUGIN_DIR, "icons", "roadsigns.svg")
MODELS_DIR = os.path.join(PLUGIN_DIR, "models")


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
        # the shipped models resolve their steps through the registry, which holds this
        # provider only once load() has returned: load them again when it does
        QgsApplication.processingRegistry().providerAdded.connect(self._registered)
        self.refreshAlgorithms()
        return True

    def _registered(self, provider_id):
        if provider_id == self.id():
            QgsApplication.processingRegistry().providerAdded.disconnect(self._registered)
            self.refreshAlgorithms()

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
        self._load_models()

    def _load_models(self):
        """The Processing models shipped in ``models/`` (the whole chain), as algorithms."""
        if QgsApplication.processingRegistry().providerById(self.id()) is not self:
            return  # not registered yet: see load()
        for path in sorted(glob.glob(os.path.join(MODELS_DIR, "*.model3"))):
            model = ShippedModel()
            if model.fromFile(path):
                model.apply_parameter_help()
                self.addAlgorithm(model)


class ShippedModel(QgsProcessingModelAlgorithm):
    """A model shipped with the plugin: its id is the model's name (``signinventory``), its
    display name and help are translated."""

    DISPLAY_NAMES = {"signinventory": "Sign inventory (whole chain)"}

    def displayName(self):  # noqa: N802
        return tr(self.DISPLAY_NAMES.get(self.name(), self.name()))

    def shortHelpString(self):  # noqa: N802
        return tr(self.helpContent().get("ALG_DESC", ""))

    def shortDescription(self):  # noqa: N802
        return self.shortHelpString()

    def icon(self):
        return QIcon(ICON_PATH)

    def group(self):
        return tr("Road sign inventory")

    def helpString(self):  # noqa: N802
        return self.shortHelpString()

    def apply_parameter_help(self):
        """Parameter help (tooltips) from the model's help content, translated."""
        help_content = self.helpContent()
        for parameter in self.parameterDefinitions():
            if help_content.get(parameter.name()):
                parameter.setHelp(tr(help_content[parameter.name()]))

    def createInstance(self):  # noqa: N802
        model = ShippedModel()
        model.loadVariant(self.toVariant())
        model.apply_parameter_help()
        return model
