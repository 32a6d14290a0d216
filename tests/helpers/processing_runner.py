"""Run a table of algorithm calls inside ONE ``qgis_process`` start (a Processing script).

    qgis_process run tests/helpers/processing_runner.py -- TABLE=rows.json RESULTS=out.json

``rows.json``: ``{"work": folder, "rows": [{"id", "algorithm", "parameters", "cancel_at"}]}``;
``{out}`` in a parameter value is the row's own empty output folder ``work/<id>`` (or
holding the files of the row's ``existing``: {name: text}, outputs of an earlier run).
``"algorithm": "boundaryprobe"`` runs :func:`boundary_probe`. Each row
runs with ``processing.run`` in the qgis_process that loaded the plugin, with a feedback
that records everything the user would see (info, warnings, errors, debug, console) apart
from the QGIS message log, and that cancels once the progress reaches ``cancel_at``
percent. ``out.json`` gets per row: whether it succeeded, the exception's type and text,
the user-visible messages, the message log, the files left in its output folder (with
their permission bits) and its wall time; and the process umask.

Loading the provider once and running every row in-process keeps the table to a few
seconds where one ``qgis_process`` per row would take minutes (the manner of QGIS's own
``qgis_algorithm_tests*.yaml``: rows of algorithm, parameters and expected outcome).
"""
import gc
import json
import os
import time

from qgis.core import (
    QgsApplication,
    QgsProcessingAlgorithm,
    QgsProcessingContext,
    QgsProcessingFeedback,
    QgsProcessingParameterFile,
    QgsProcessingParameterString,
    QgsProject,
)


class RecordingFeedback(QgsProcessingFeedback):
    """Keeps what a user sees; cancels when the progress reaches ``cancel_at`` percent."""

    def __init__(self, cancel_at=None):
        super().__init__()
        self.seen = []
        self.cancel_at = cancel_at
        self.cancelled_at = None
        self.progressChanged.connect(self._progress)

    def _progress(self, percent):
        if self.cancel_at is not None and percent >= self.cancel_at and not self.isCanceled():
            self.cancelled_at = percent
            self.cancel()

    def reportError(self, error, fatalError=False):  # noqa: N802, N803 (Qt's names)
        self.seen.append(["error", error])

    def pushInfo(self, info):  # noqa: N802
        self.seen.append(["info", info])

    def pushWarning(self, warning):  # noqa: N802
        self.seen.append(["warning", warning])

    def pushDebugInfo(self, info):  # noqa: N802 (qgis_process prints it: the user sees it)
        self.seen.append(["debug", info])

    def pushCommandInfo(self, info):  # noqa: N802
        self.seen.append(["command", info])

    def pushConsoleInfo(self, info):  # noqa: N802
        self.seen.append(["console", info])


def _files(folder):
    out = []
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            path = os.path.join(root, name)
            out.append([os.path.relpath(path, folder) + ("/" if name in dirs else ""),
                        os.stat(path).st_mode & 0o777])
    return sorted(out)


def _plain(value):
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    return str(value)


def _substitute(value, out):
    if isinstance(value, str):
        return value.replace("{out}", out)
    if isinstance(value, list):
        return [_substitute(v, out) for v in value]
    return value


def boundary_probe():
    """A Road Sign Inventory algorithm that writes a layer and a file, then fails as asked
    (``MODE``): the boundary every algorithm runs in, tested end to end."""
    from qgis.core import Qgis, QgsFeature, QgsFields

    from roadsigns.algorithms.base import RoadSignsAlgorithm

    class PanicException(BaseException):  # what lazrs's Rust panics raise through pyo3
        pass

    class BoundaryProbe(RoadSignsAlgorithm):
        ALGORITHM_ID = "boundaryprobe"
        REQUIRES = ()

        def displayName(self):
            return "Boundary probe"

        def initAlgorithm(self, config=None):
            self.add_enum("MODE", "mode", [(m, m) for m in ("ok", "type_error", "panic", "os_error",
                                                           "memory", "cancel")], "ok", "")
            self.add_sink("OUTPUT", "layer", Qgis.ProcessingSourceType.VectorPoint, "")
            self.add_file_destination("REPORT", "report", "HTML files (*.html)", "")

        def processAlgorithm(self, parameters, context, feedback):
            mode = self.enum_name(parameters, "MODE", context)
            sink, dest_id = self.sink(parameters, "OUTPUT", context, QgsFields(), Qgis.WkbType.Point,
                                      context.project().crs())
            sink.addFeature(QgsFeature())
            report = self.parameterAsFileOutput(parameters, "REPORT", context)
            with open(self.output_file(report), "w") as f:
                f.write("<p>report</p>")
            if mode == "type_error":
                raise TypeError("a bug\nover two lines")
            if mode == "panic":
                raise PanicException("attempt to calculate the remainder with a divisor of zero")
            if mode == "os_error":
                raise OSError(28, "No space left on device", report)
            if mode == "memory":
                raise MemoryError()
            if mode == "cancel":
                feedback.cancel()
            return {"OUTPUT": dest_id, "REPORT": report}

    return BoundaryProbe()


def run_table(table):
    import processing

    log = []

    def on_message(message, tag, level):
        log.append([tag, int(level), message])

    QgsApplication.messageLog().messageReceived.connect(on_message)
    umask = os.umask(0)
    os.umask(umask)
    results = {"umask": umask, "rows": {}}
    for row in table["rows"]:
        out = os.path.join(table["work"], row["id"])
        os.makedirs(out, exist_ok=True)
        parameters = {k: _substitute(v, out) for k, v in row["parameters"].items()}
        feedback = RecordingFeedback(row.get("cancel_at"))
        context = QgsProcessingContext()
        context.setProject(QgsProject.instance())
        context.setFeedback(feedback)
        for name, text in row.get("existing", {}).items():
            with open(os.path.join(out, name), "w") as f:
                f.write(text)
        algorithm = boundary_probe() if row["algorithm"] == "boundaryprobe" else row["algorithm"]
        first_log = len(log)
        start = time.perf_counter()
        record = {"ok": True, "error": None, "error_type": None, "outputs": {}}
        try:
            outputs = processing.run(algorithm, parameters, context=context, feedback=feedback)
            record["outputs"] = {k: _plain(v) for k, v in outputs.items()}
        except BaseException as error:  # noqa: B902 (every outcome is recorded)
            record.update(ok=False, error=str(error), error_type=type(error).__name__)
            del error
        record["seconds"] = time.perf_counter() - start
        del context
        gc.collect()
        QgsApplication.processEvents()
        record.update(seen=feedback.seen, log=log[first_log:], files=_files(out),
                      cancelled_at=feedback.cancelled_at,
                      existing={name: open(os.path.join(out, name), errors="replace").read()
                                for name in row.get("existing", {}) if os.path.isfile(os.path.join(out, name))})
        results["rows"][row["id"]] = record
    return results


class RunTable(QgsProcessingAlgorithm):
    TABLE = "TABLE"
    RESULTS = "RESULTS"

    def name(self):
        return "runtable"

    def displayName(self):
        return "Run a table of algorithm calls"

    def createInstance(self):
        return RunTable()

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(self.TABLE, "Table (JSON)"))
        self.addParameter(QgsProcessingParameterString(self.RESULTS, "Results (JSON file to write)"))

    def processAlgorithm(self, parameters, context, feedback):
        with open(self.parameterAsFile(parameters, self.TABLE, context)) as f:
            table = json.load(f)
        results = run_table(table)
        with open(self.parameterAsString(parameters, self.RESULTS, context), "w") as f:
            json.dump(results, f, indent=1)
        return {}
