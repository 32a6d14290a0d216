"""Where the plugin's files are: its folder, icon, bundled models, translations.

The lowest module of the adapters: no qgis import, used by the algorithms, the provider and
the plugin alike.
"""
import os

PLUGIN_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ICON_PATH = os.path.join(PLUGIN_DIR, "icons", "roadsigns.svg")
MODELS_DIR = os.path.join(PLUGIN_DIR, "models")
#: The detector shipped with the plugin (``roadsigns:detectsigns`` with an empty MODEL).
BUNDLED_MODEL = os.path.join(MODELS_DIR, "roadsigns.onnx")
I18N_DIR = os.path.join(PLUGIN_DIR, "i18n")
