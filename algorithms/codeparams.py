"""The sign-code classifier's parameters, shared by the algorithms that read sign codes
(``detectsigns`` for every detection, ``fusesigns`` for the signs found in the cloud alone):
the parameter names as class constants, their declarations and the classifier they give."""
import os

from qgis.core import QgsProcessingException

from .paths import BUNDLED_CLASSIFIER, BUNDLED_CODES_TABLE


class ReadsCodes:
    """Mixin for a :class:`.base.RoadSignsAlgorithm` that reads sign codes."""

    READ_CODES = "READ_CODES"
    CLASSIFIER = "CLASSIFIER"
    CODES_TABLE = "CODES_TABLE"

    def add_code_parameters(self, what):
        """Declare READ_CODES, CLASSIFIER and CODES_TABLE; ``what``: the signs whose codes are
        read, as the help text names them (translated)."""
        self.add_boolean(
            self.READ_CODES, self.tr("Read the sign codes"), True,
            self.tr("Reads what each sign says (its code, such as DE:206 for stop) with the sign-code "
                    "classifier: {}. Unchecked, the code fields stay empty. When the bundled classifier is "
                    "missing, the log says so and no code is read.").format(what))
        self.add_file(
            self.CLASSIFIER, self.tr("Sign-code classifier (empty: the bundled one)"),
            self.tr("An ONNX classifier of sign crops: float input [N, 3, S, S] (RGB, 0..1), output [N, C], "
                    "the codes it answers in its metadata 'names' (each in the codes table, 'other', or "
                    "'unlisted:' and a class for a sign whose code the table lacks). The format is in "
                    "models/README.md (section <i>Sign-code classifier: the format</i>). Empty uses the "
                    "classifier bundled with the plugin (models/signcodes.onnx)."),
            file_filter=self.tr("ONNX models (*.onnx);;All files (*.*)"), optional=True, advanced=True)
        self.add_file(
            self.CODES_TABLE, self.tr("Sign codes table (empty: the bundled one)"),
            self.tr("The codes the classifier may answer, with their names and classes: UTF-8 text, "
                    "semicolon-separated, the header code;name;class (format in models/README.md). Empty uses "
                    "the bundled table of German codes (models/sign-codes-de.csv)."),
            file_filter=self.tr("CSV files (*.csv *.txt);;All files (*.*)"), optional=True, advanced=True)

    def code_classifier(self, parameters, context, feedback, threads=0):
        """The sign-code classifier to run (None when codes are not read, or when the bundled
        classifier is missing: a warning says so); core errors are raised as they are."""
        from ..core.signcodes import CodeClassifier, read_codes_table

        if not self.parameterAsBoolean(parameters, self.READ_CODES, context):
            feedback.pushInfo(self.tr("Sign codes are not read (Read the sign codes is off)."))
            return None
        path = self.parameterAsFile(parameters, self.CLASSIFIER, context)
        if not path:
            path = BUNDLED_CLASSIFIER
            if not os.path.isfile(path):
                feedback.pushWarning(self.tr("The bundled sign-code classifier {} is missing: no sign code is "
                                             "read.").format(path))
                return None
        elif not os.path.isfile(path):
            raise QgsProcessingException(self.tr("Sign-code classifier not found: {}").format(path))
        table = read_codes_table(self.parameterAsFile(parameters, self.CODES_TABLE, context) or BUNDLED_CODES_TABLE)
        classifier = CodeClassifier(path, table, threads=threads)
        feedback.pushInfo(self.tr("Sign codes: {}").format(classifier.describe()))
        return classifier
