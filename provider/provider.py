"""The Processing provider ``roadsigns``: lists the algorithms, one per module, and the
Processing models shipped in ``models/``."""
import glob
import os

from qgis.core import QgsApplication, QgsProcessingModelAlgorithm, QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from ..algorithms.detectsigns import DetectSigns
from ..algorithms.evaluate import Evaluate
from ..algorithms.exporthandover import ExportHandover
from ..algorithms.findsignsincloud import FindSignsInCloud
from ..algorithms.fusesigns import FuseSigns
from ..algorithms.groundfilter import PDAL_SETTING, GroundFilter
from ..algorithms.i18n import Translatable, tr_core
from ..algorithms.importtrajectory import ImportTrajectory
from ..algorithms.paths import ICON_PATH, MODELS_DIR
from ..algorithms.projectdetections import ProjectDetections
from ..algorithms.refinesigns import RefineSigns

#: The algorithms, in the order of the chain.
ALGORITHMS = (ImportTrajectory, DetectSigns, GroundFilter, ProjectDetections, RefineSigns, FindSignsInCloud,
              FuseSigns, Evaluate, ExportHandover)


class RoadSignsProvider(Translatable, QgsProcessingProvider):
    def id(self):
        return "roadsigns"

    def name(self):
        return self.tr("Road sign inventory")

    def longName(self):
        return self.tr("Road sign inventory from mobile mapping (panoramas, trajectory, LiDAR)")

    def icon(self):
        return QIcon(ICON_PATH)

    def svgIconPath(self):
        return ICON_PATH

    def load(self):
        """Register the provider's settings (Processing ▸ Options ▸ Providers)."""
        try:
            from processing.core.ProcessingConfig import ProcessingConfig, Setting
            ProcessingConfig.settingIcons[self.name()] = self.icon()
            ProcessingConfig.addSetting(Setting(
                self.name(), PDAL_SETTING,
                self.tr("PDAL executable for the ground filter (empty: search PATH and QGIS)"), "",
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
            ProcessingConfig.removeSetting(PDAL_SETTING)
        except ImportError:
            pass

    def loadAlgorithms(self):
        for algorithm in ALGORITHMS:
            self.addAlgorithm(algorithm())
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


class ShippedModel(Translatable, QgsProcessingModelAlgorithm):
    """A model shipped with the plugin: its id is the model's name (``signinventory``); its
    display name and help are translated (the help texts as ``scripts/i18n.py`` extracts
    them from the .model3 file)."""

    def displayName(self):
        names = {"signinventory": self.tr("Sign inventory (whole chain)")}
        return names.get(self.name(), self.name())

    def shortHelpString(self):
        return tr_core(self.helpContent().get("ALG_DESC", ""))

    def shortDescription(self):
        return self.shortHelpString()

    def icon(self):
        return QIcon(ICON_PATH)

    def group(self):
        return self.tr("Road sign inventory")

    def helpString(self):
        return self.shortHelpString()

    def apply_parameter_help(self):
        """Parameter help (tooltips) from the model's help content, translated."""
        help_content = self.helpContent()
        for parameter in self.parameterDefinitions():
            if help_content.get(parameter.name()):
                parameter.setHelp(tr_core(help_content[parameter.name()]))

    def createInstance(self):
        model = ShippedModel()
        model.loadVariant(self.toVariant())
        model.apply_parameter_help()
        return model
