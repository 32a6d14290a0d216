"""What every Road Sign Inventory algorithm shares: tr, icon, parameter helpers, core errors,
and the boundary every run goes through.

Adapters declare their parameter names as class constants (``POINT_CLOUD = "POINT_CLOUD"``),
add parameters through the ``add_*`` helpers below with literal ``self.tr("...")`` labels
and help texts, read them, call ``core`` with a :class:`~roadsigns.core.errors.Progress`
bound to the Processing feedback, turn :class:`InputError` into a translated
``QgsProcessingException`` and write outputs only once core has finished.

**The boundary.** Every subclass's ``processAlgorithm`` is wrapped (``__init_subclass__``,
so an algorithm written later gets it too) so that a run either delivers all its outputs
or leaves nothing behind:

* layers created with :meth:`RoadSignsAlgorithm.sink` are closed and deleted if the run
  fails or is cancelled (a file they overwrite is moved aside first and put back);
* files and folders are written under the temporary names :meth:`output_file` and
  :meth:`output_folder` give, beside their destinations, and moved into place (with the
  user's normal permissions) only when ``processAlgorithm`` has returned and the user has
  not cancelled;
* every exception becomes a ``QgsProcessingException`` with a one-line cause: a core
  :class:`InputError` its translated message, a cancel "Cancelled: nothing was written.",
  anything else a short "Unexpected error" line, its traceback going to the QGIS message
  log (tab :data:`LOG_TAG`) only;
* when it ends, the memory it freed is given back to the system
  (:func:`~roadsigns.core.memory.release_freed_memory`), so the next algorithm of a model
  does not start on top of the last one's freed heap.
"""
import functools
import traceback
from contextlib import contextmanager

from qgis.core import (
    Qgis,
    QgsMessageLog,
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

from ..core.errors import Cancelled, InputError, Message, Progress, StepThrottle
from ..core.memory import release_freed_memory
from ..dependencies import missing_message, shapely_geos_conflict
from .i18n import Translatable, tr_core
from .layers import RunOutputs
from .paths import ICON_PATH

#: The QGIS message log tab that gets the tracebacks of unexpected errors.
LOG_TAG = "Road sign inventory"


def _one_line(text):
    return " ".join(line.strip() for line in str(text).splitlines() if line.strip())


def _boundary(process):
    """``processAlgorithm`` run inside the boundary (see the module doc)."""

    @functools.wraps(process)
    def processAlgorithm(self, parameters, context, feedback):
        self._run_outputs = RunOutputs(context)
        try:
            result = process(self, parameters, context, feedback)
            if feedback is not None and feedback.isCanceled():
                raise Cancelled("cancelled")
            self._run_outputs.commit()
            return result
        except (KeyboardInterrupt, SystemExit, GeneratorExit):
            self._run_outputs.rollback()
            raise
        except BaseException as error:  # Rust panics in lazrs reach Python as BaseException
            left = self._run_outputs.rollback()
            raise self.failure(error, left) from None
        finally:
            self._run_outputs = None
            release_freed_memory()    # the next algorithm of a model starts from what is live

    processAlgorithm.roadsigns_boundary = True
    return processAlgorithm


class RoadSignsAlgorithm(Translatable, QgsProcessingAlgorithm):
    """Base class: subclasses set ``ALGORITHM_ID`` and ``REQUIRES`` and define
    ``displayName``, ``shortDescription`` and ``shortHelpString`` with literal ``self.tr``."""

    ALGORITHM_ID = ""
    GROUP_ID = "roadsigns"
    #: import names of the third-party packages the algorithm needs
    REQUIRES = ("numpy", "scipy", "pyproj")

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        process = cls.__dict__.get("processAlgorithm")
        if process is not None and not getattr(process, "roadsigns_boundary", False):
            cls.processAlgorithm = _boundary(process)

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
        """A point cloud input: a LAS/LAZ file (COPC too), a virtual point cloud (.vpc) or a
        folder of LAS/LAZ tiles (a file parameter, so that the usual case is picked with the
        file dialog; its "All files (*)" filter lets a typed folder path through, which
        QGIS's folder parameters would not offer with a file dialog). The help says so."""
        return self.add_file(name, label, "{} {}".format(help_text, self.tr(
            "Accepted: one LAS/LAZ file (COPC too), a virtual point cloud (.vpc, e.g. from QGIS's Build "
            "virtual point cloud) listing tiles, or a folder of LAS/LAZ tiles (type or paste the folder's "
            "path). Tiles must share the point format and the CRS.")), file_filter=self.tr(
            "Point clouds (*.las *.laz *.vpc *.LAS *.LAZ *.VPC);;LAS/LAZ (*.las *.laz *.LAS *.LAZ);;"
            "Virtual point clouds (*.vpc *.VPC);;All files or a folder of tiles (*)"))

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
        output that was not asked for; a clear error when it cannot be created.

        Create it once every record is computed: should the run fail or be cancelled, the
        boundary closes and deletes it (and puts back the file it replaced)."""
        outputs = getattr(self, "_run_outputs", None)
        if outputs is not None:
            outputs.protect_layer(self.parameterAsOutputLayer(parameters, name, context))
        sink, dest_id = self.parameterAsSink(parameters, name, context, fields, wkb_type, crs)
        if sink is None and self.parameterDefinition(name) is not None and \
                not (self.parameterDefinition(name).flags() & Qgis.ProcessingParameterFlag.Optional):
            raise QgsProcessingException(self.invalidSinkError(parameters, name))
        if outputs is not None and sink is not None:
            outputs.add_layer(sink, dest_id)
        return sink, dest_id

    def output_file(self, path):
        """The temporary name (beside ``path``) to write the output file ``path`` to; the
        boundary moves it into place when the run succeeds. ``path`` itself outside a run."""
        outputs = getattr(self, "_run_outputs", None)
        return outputs.staged.file(path) if outputs is not None else path

    def output_folder(self, path):
        """As :meth:`output_file`, for a folder of outputs (created empty)."""
        outputs = getattr(self, "_run_outputs", None)
        return outputs.staged.folder(path) if outputs is not None else path

    # --- running core -------------------------------------------------------------------

    def check_dependencies(self):
        message = missing_message(self.REQUIRES, tr_core)
        if not message and "shapely" in self.REQUIRES:
            message = shapely_geos_conflict(Qgis.geosVersion(), translate=tr_core)
        if message:
            raise QgsProcessingException(message)

    def progress(self, feedback):
        """A core Progress that forwards to ``feedback`` (percent, log, cancel, and the
        current step as the progress text, at most every few seconds: :class:`StepThrottle`)."""
        return Progress(on_progress=feedback.setProgress, is_cancelled=feedback.isCanceled,
                        on_info=lambda m: feedback.pushInfo(self.localise(m)),
                        on_warning=lambda m: feedback.pushWarning(self.localise(m)),
                        on_step=StepThrottle(lambda m: feedback.setProgressText(self.localise(m))))

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

    def failure(self, error, left=()):
        """The ``QgsProcessingException`` (one line) a run that raised ``error`` ends with;
        ``left``: partial outputs that could not be removed."""
        if isinstance(error, QgsProcessingException):
            text = str(error)
        elif isinstance(error, InputError):
            text = self.localise(error)
        elif isinstance(error, Cancelled):
            text = self.tr("Cancelled: nothing was written.")
        else:
            QgsMessageLog.logMessage("{}: {}\n{}".format(self.displayName(), error, "".join(
                traceback.format_exception(type(error), error, error.__traceback__))), LOG_TAG,
                Qgis.MessageLevel.Warning)
            if isinstance(error, MemoryError):
                text = self.tr("Out of memory: nothing was written. Crop the point cloud (Ground filter with a "
                               "crop layer) or process the drive in parts.")
            elif isinstance(error, OSError):
                text = self.tr("Cannot read or write {}: {}. Nothing was written.").format(
                    error.filename or "", error.strerror or error)
            else:
                text = self.tr("Unexpected error ({}: {}); nothing was written. The details are in the QGIS "
                               "message log (Road sign inventory); please report them.").format(
                    type(error).__name__, _one_line(error)[:300])
        text = _one_line(text)
        if left:
            text = self.tr("{} However, these partial outputs could not be removed: {}").format(
                text, ", ".join(left))
        return QgsProcessingException(text)
