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


def locale_candidates(locale: str) -> list:
    """File suffixes to try for ``locale``: exact locale, then its language; Chinese goes by
    script (zh_CN, zh_SG, zh -> zh_Hans; zh_TW, zh_HK, zh_MO -> zh_Hant)."""
    locale = locale.split(".")[0].split("@")[0].replace("-", "_")
    parts = locale.split("_")
    names = ["_".join(parts[:n]) for n in range(len(parts), 0, -1)]
    if parts[0].lower() == "zh":
        rest = {p.upper() for p in parts[1:]}
        script = "zh_Hant" if rest & {"HANT", "TW", "HK", "MO"} else "zh_Hans"
        names = names[:-1] + [script] + names[-1:]
    return [n for k, n in enumerate(names) if n and n not in names[:k]]


def install_translator():
    """Load ``i18n/roadsigns_<locale>.qm`` (exact locale, then its language) if present."""
    for name in locale_candidates(qgis_locale()):
        path = os.path.join(I18N_DIR, "roadsigns_{}.qm".format(name))
        if os.path.exists(path):
            translator = QTranslator()
            if translator.load(path):
                QCoreApplication.installTranslator(translator)
                return translator
    return None
