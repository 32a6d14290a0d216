"""Where the plugin's files are: its folder, icon, bundled models, translations.

The lowest module of the adapters: no qgis import, used by the algorithms, the provider and
the plugin alike.
"""
import os

PLUGIN_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ICON_PATH = os.path.join(PLUGIN_DIR, "icons", "roadsigns.svg")
MODELS_DIR = os.path.join(PLUGIN_DIR, "models")
#: The detector shipped with the plugin (``roadsigns:detectsigns`` with an empty MODEL): the
#: float detector quantised to int8 (models/README.md: as accurate, about twice as fast).
BUNDLED_MODEL = os.path.join(MODELS_DIR, "roadsigns-int8.onnx")
#: The same detector in float32, which the int8 file is quantised from and training starts
#: from (``python -m devtools.train --init``); MODEL may name it.
BUNDLED_FLOAT_MODEL = os.path.join(MODELS_DIR, "roadsigns.onnx")
#: The sign-code classifier shipped with the plugin (``roadsigns:detectsigns`` with an empty
#: CLASSIFIER; format in models/README.md).
BUNDLED_CLASSIFIER = os.path.join(MODELS_DIR, "signcodes.onnx")
#: The codes table shipped with the plugin (empty CODES_TABLE of detectsigns and refinesigns).
BUNDLED_CODES_TABLE = os.path.join(MODELS_DIR, "sign-codes-de.csv")
I18N_DIR = os.path.join(PLUGIN_DIR, "i18n")
