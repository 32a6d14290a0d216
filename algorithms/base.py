"""What every Road Sign Inventory algorithm shares: tr, icon, parameter helpers, core errors.

Adapters declare their parameter names as class constants (``POINT_CLOUD = "POINT_CLOUD"``),
add parameters through the ``add_*`` helpers below with literal ``self.tr("...")`` labels
and help texts, read them, call ``core`` with a :class:`~roadsigns.core.errors.Progress`
bound to the Processing feedback, turn :class:`InputError` into a translated
``QgsProcessingException`` and write outputs only once core has finished.
"""
from contextlib import contextmanager

from qgis.core import (
    Qgis,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtGui import QIcon

from ..core.errors import Cancelled, InputError, Message, Progress
from ..dependencies import missing_message, shapely_geos_conflict
from .i18n import Translatable, tr_core
from .paths import ICON_PATH


class RoadSignsAlgorithm(Translatable, QgsProcessingAlgorithm):
    """Base class: subclasses set ``ALGORITHM_ID`` and ``REQUIRES`` and define
    ``displayName``, ``shortDescription`` and ``shortHelpString`` with literal ``self.tr``."""

    ALGORITHM_ID = ""
    GROUP_ID = "roadsigns"
    #: import names of the third-party packages the algorithm needs
    REQUIRES = ("numpy", "scipy", "pyproj")

    def createInstance(self):
        return type(self)()

    def name(self):
        return self.ALGORITHM_ID

    def group(self):
        return self.tr("Road sign inventory")

    def groupId(self):
        return self.GROUP_ID

    def icon(self):
        return QIcon(ICON_PATH)

    # --- parameters: one helper per kind; labels and help come translated --------------

    def add(self, parameter, help_text, advanced=False):
        """Add ``parameter`` with its help text (tooltip and help panel)."""
        parameter.setHelp(help_text)
        if advanced:
            parameter.setFlags(parameter.flags() | Qgis.ProcessingParameterFlag.Advanced)
        self.addParameter(parameter)
        return parameter

    def add_number(self, name, label, default, help_text, minimum=None, maximum=None,
                   integer=False, advanced=False):
        """A double (or integer) parameter."""
        kind = Qgis.ProcessingNumberParameterType.Integer if integer else \
            Qgis.ProcessingNumberParameterType.Double
        parameter = QgsProcessingParameterNumber(name, label, type=kind, defaultValue=default)
        if minimum is not None:
            parameter.setMinimum(minimum)
        if maximum is not None:
            parameter.setMaximum(maximum)
        return self.add(parameter, help_text, advanced)

    def add_boolean(self, name, label, default, help_text, advanced=False):
        return self.add(QgsProcessingParameterBoolean(name, label, defaultValue=default), help_text, advanced)

    def add_enum(self, name, label, options, default, help_text, advanced=False):
        """A choice among ``options``: (name core takes, translated label) pairs. Read it
        with :meth:`enum_name`, which gives the name, never the index."""
        self._enum_names = getattr(self, "_enum_names", {})
        self._enum_names[name] = [key for key, _ in options]
        keys = self._enum_names[name]
        return self.add(QgsProcessingParameterEnum(name, label, options=[text for _, text in options],
                                                   defaultValue=keys.index(default)), help_text, advanced)

    def add_crs(self, name, label, help_text, default=None, optional=False, advanced=False):
        return self.add(QgsProcessingParameterCrs(name, label, defaultValue=default, optional=optional),
                        help_text, advanced)

    def add_source(self, name, label, geometry, help_text, optional=False):
        """A vector layer input of ``geometry`` (a ``Qgis.ProcessingSourceType``)."""
        return self.add(QgsProcessingParameterFeatureSource(name, label, [geometry], optional=optional),
                        help_text)

    def add_file(self, name, label, help_text, file_filter="", folder=False, optional=False,
                 advanced=False):
        """An input file (``file_filter`` in Qt's form) or, with ``folder``, a folder."""
        behavior = Qgis.ProcessingFileParameterBehavior.Folder if folder else \
            Qgis.ProcessingFileParameterBehavior.File
        return self.add(QgsProcessingParameterFile(name, label, behavior=behavior, optional=optional,
                                                   fileFilter=file_filter), help_text, advanced)

    def add_las_file(self, name, label, help_text):
        """A LAS/LAZ point cloud input file."""
        return self.add_file(name, label, help_text, file_filter=self.tr(
            "LAS/LAZ point clouds (*.las *.laz *.LAS *.LAZ);;All files (*.*)"))

    def add_sink(self, name, label, geometry, help_text, optional=False):
        """A vector layer output of ``geometry``; an optional one is not created by default."""
        return self.add(QgsProcessingParameterFeatureSink(name, label, type=geometry, optional=optional,
                                                          createByDefault=not optional), help_text)

    def add_file_destination(self, name, label, file_filter, help_text, optional=False):
        """An output file; an optional one is not created by default."""
        return self.add(QgsProcessingParameterFileDestination(
            name, label, file_filter, optional=optional, createByDefault=not optional), help_text)

    def enum_name(self, parameters, name, context):
        """The name (as core takes it) of the option chosen for the enum ``name``."""
        return self._enum_names[name][self.parameterAsEnum(parameters, name, context)]

    def source(self, parameters, name, context):
        """The feature source ``name``; a clear error when it cannot be read."""
        source = self.parameterAsSource(parameters, name, context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, name))
        return source

    def sink(self, parameters, name, context, fields, wkb_type, crs):
        """``(sink, destination id)`` of the output ``name``; ``(None, None)`` for an optional
        output that was not asked for; a clear error when it cannot be created."""
        sink, dest_id = self.parameterAsSink(parameters, name, context, fields, wkb_type, crs)
        if sink is None and self.parameterDefinition(name) is not None and \
                not (self.parameterDefinition(name).flags() & Qgis.ProcessingParameterFlag.Optional):
            raise QgsProcessingException(self.invalidSinkError(parameters, name))
        return sink, dest_id

    # --- running core -------------------------------------------------------------------

    def check_dependencies(self):
        message = missing_message(self.REQUIRES, tr_core)
        if not message and "shapely" in self.REQUIRES:
            message = shapely_geos_conflict(Qgis.geosVersion(), translate=tr_core)
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
        template through ``tr_core``, then its fields, those that are messages themselves or
        words (``TRANSLATED_FIELDS``) translated too. Other text is returned as it is."""
        if not isinstance(message, (Message, InputError)):
            return str(message)
        fields = {k: self.localise(v) if isinstance(v, Message) else
                  tr_core(v) if k in self.TRANSLATED_FIELDS and isinstance(v, str) else v
                  for k, v in message.fields.items()}
        text = tr_core(message.template)
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
