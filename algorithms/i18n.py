"""Translation of user-visible strings, and the translator for the user's QGIS locale.

Contexts, as Qt's ``pylupdate5`` extracts them (``make i18n``):

* ``self.tr("...")`` in a class: the class's name. :class:`Translatable` looks the text up
  in the contexts of the class and its bases, so a literal written in a base class
  (``RoadSignsAlgorithm``) is found from every algorithm;
* ``tr("...")`` in a module-level function: ``@default``;
* texts that are not literals at a ``tr`` call, the core's English message templates
  (``Message``, ``InputError``), the words of their translated fields and the shipped
  models' help: :data:`CORE_CONTEXT`, extracted by ``scripts/i18n.py``.
"""
import os

from qgis.PyQt.QtCore import QCoreApplication, QLocale, QSettings, QTranslator

from .paths import I18N_DIR

DEFAULT_CONTEXT = "@default"
CORE_CONTEXT = "RoadSigns"


def tr(text: str) -> str:
    """``text`` in the user's language (for module-level code: context ``@default``)."""
    return QCoreApplication.translate(DEFAULT_CONTEXT, text)


def tr_core(text: str) -> str:
    """A core message template, field word or model help text in the user's language."""
    return QCoreApplication.translate(CORE_CONTEXT, text)


class Translatable:
    """``self.tr(text)``: translated in the context of the class that wrote the literal."""

    def tr(self, text: str) -> str:
        for klass in type(self).__mro__:
            if klass is object:
                break
            translated = QCoreApplication.translate(klass.__name__, text)
            if translated != text:
                return translated
        return text


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
