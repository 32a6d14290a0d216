"""What every Road Sign Inventory algorithm shares: tr, icon, help, core error handling.

Adapters read parameters, call ``core`` with a :class:`~roadsigns.core.errors.Progress`
bound to the Processing feedback, turn :class:`InputError` into a translated
``QgsProcessingException`` and write outputs only once core has finished.
"""
from contextlib import contextmanager

from qgis.core import Qgis, QgsProcessingAlgorithm, QgsProcessingException
from qgis.PyQt.QtGui import QIcon

from ..core.errors import Cancelled, InputError, Message, Progress
from ..dependencies import missing_message, shapely_geos_conflict
from ..provider.i18n import tr
from ..provider.provider import ICON_PATH


class RoadSignsAlgorithm(QgsProcessingAlgorithm):
    """Base class: subclasses set ``ALGORITHM_ID``, ``DISPLAY_NAME``, ``HELP``, ``REQUIRES``."""

    ALGORITHM_ID = ""
    DISPLAY_NAME = ""
    GROUP = "Road sign inventory"
    GROUP_ID = "roadsigns"
    HELP = ""
    #: one line for the Toolbox tooltip
    SHORT_DESCRIPTION = ""
    #: import names of the third-party packages the algorithm needs
    REQUIRES = ("numpy", "scipy", "pyproj")

    def tr(self, text):
        return tr(text)

    def createInstance(self):  # noqa: N802
        return type(self)()

    def name(self):
        return self.ALGORITHM_ID

    def displayName(self):  # noqa: N802
        return self.tr(self.DISPLAY_NAME)

    def group(self):
        return self.tr(self.GROUP)

    def groupId(self):  # noqa: N802
        return self.GROUP_ID

    def shortHelpString(self):  # noqa: N802
        return self.tr(self.HELP)

    def shortDescription(self):  # noqa: N802
        return self.tr(self.SHORT_DESCRIPTION)

    def icon(self):
        return QIcon(ICON_PATH)

    # --- helpers for subclasses -------------------------------------------------------

    def add(self, parameter, help_text, advanced=False):
        """Add a parameter with its help text (tooltip and help panel)."""
        parameter.setHelp(self.tr(help_text))
        if advanced:
            parameter.setFlags(parameter.flags() | Qgis.ProcessingParameterFlag.Advanced)
        self.addParameter(parameter)
        return parameter

    def add_number(self, name, label, default, help_text, minimum=None, maximum=None,
                   integer=False, advanced=False):
        """A double (or integer) parameter with its help text."""
        from qgis.core import QgsProcessingParameterNumber
        kind = Qgis.ProcessingNumberParameterType.Integer if integer else \
            Qgis.ProcessingNumberParameterType.Double
        parameter = QgsProcessingParameterNumber(name, self.tr(label), type=kind, defaultValue=default)
        if minimum is not None:
            parameter.setMinimum(minimum)
        if maximum is not None:
            parameter.setMaximum(maximum)
        return self.add(parameter, help_text, advanced)

    def add_las_file(self, name, label, help_text):
        """A LAS/LAZ input file parameter."""
        from qgis.core import QgsProcessingParameterFile
        return self.add(QgsProcessingParameterFile(
            name, self.tr(label), behavior=Qgis.ProcessingFileParameterBehavior.File,
            fileFilter=self.tr("LAS/LAZ point clouds (*.las *.laz *.LAS *.LAZ);;All files (*.*)")),
            help_text)

    def check_dependencies(self):
        message = missing_message(self.REQUIRES, self.tr)
        if not message and "shapely" in self.REQUIRES:
            message = shapely_geos_conflict(Qgis.geosVersion(), translate=self.tr)
        if message:
            raise QgsProcessingException(message)

    def progress(self, feedback):
        """A core Progress that forwards to ``feedback`` (percent, log, cancel)."""
        return Progress(on_progress=feedback.setProgress, is_cancelled=feedback.isCanceled,
                        on_info=lambda m: feedback.pushInfo(self.localise(m)),
                        on_warning=lambda m: feedback.pushWarning(self.localise(m)))

    #: core message fields whose (English) words are translated too ("Trajectory", ...)
    TRANSLATED_FIELDS = ("what", "role", "kind")

    def localise(self, message) -> str:
        """A core :class:`Message` (or an :class:`InputError`) in the user's language: its
        template through ``tr``, then its fields, those that are messages themselves or
        words (``TRANSLATED_FIELDS``) translated too. Other text is returned as it is."""
        if not isinstance(message, (Message, InputError)):
            return str(message)
        fields = {k: self.localise(v) if isinstance(v, Message) else
                  self.tr(v) if k in self.TRANSLATED_FIELDS and isinstance(v, str) else v
                  for k, v in message.fields.items()}
        text = self.tr(message.template)
        return text.format(**fields) if message.fields else text

    @contextmanager
    def core_errors(self):
        """Turn core exceptions into translated QgsProcessingException messages."""
        try:
            yield
        except InputError as error:
            raise QgsProcessingException(self.localise(error))
        except Cancelled:
            raise QgsProcessingException(self.tr("Cancelled: nothing was written."))
