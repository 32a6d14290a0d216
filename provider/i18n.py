"""Translation of user-visible strings: ``tr()`` and the translator for the QGIS locale."""
import os

from qgis.PyQt.QtCore import QCoreApplication, QLocale, QSettings, QTranslator

CONTEXT = "RoadSigns"
I18N_DIR = os.path.join(os.path.dirname(os.path.dirname(__file__)), "i18n")


def tr(text: str) -> str:
    return QCoreApplication.translate(CONTEXT, text)


def qgis_locale() -> str:
    """The user's QGIS locale ("es", "zh-Hans", ...), as QGIS resolves it."""
    value = QSettings().value("locale/userLocale", "") or ""
    if not value or str(QSettings().value("locale/overrideFlag", "false")).lower() != "true":
        value = value or QLocale.system().name()
    return str(value)


def install_translator():
    """Load ``i18n/roadsigns_<locale>.qm`` (exact locale, then its language) if present."""
    locale = qgis_locale().replace("-", "_")
    for name in (locale, locale.split("_")[0]):
        path = os.path.join(I18N_DIR, "roadsigns_{}.qm".format(name))
        if os.path.exists(path):
            translator = QTranslator()
            if translator.load(path):
                QCoreApplication.installTranslator(translator)
                return translator
    return None
