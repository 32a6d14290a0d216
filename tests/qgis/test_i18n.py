"""Translations: every user-visible string (``scripts/i18n.py extract``: pylupdate5's contexts
and the core's texts in context RoadSigns) has a finished Simplified Chinese and Spanish
translation keeping its placeholders and HTML tags, the compiled ``.qm`` files say the same
as the ``.ts`` sources in each entry's own context, and ``qgis_process`` shows the algorithms
and core messages in the language of the QGIS locale setting."""
import ast
import importlib.util
import json
import os
import re
import subprocess

import pytest

from devtools.qgisrun import QgisProcess

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LANGUAGES = ("zh_Hans", "es")
CORE = "RoadSigns"


def _load_i18n_script():
    spec = importlib.util.spec_from_file_location("roadsigns_i18n_script",
                                                  os.path.join(REPO_ROOT, "scripts", "i18n.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


i18n = _load_i18n_script()


@pytest.fixture(scope="module")
def found():
    """{(context, source): places} as ``make i18n`` extracts them now."""
    return i18n.extract()


@pytest.fixture(scope="module")
def ts():
    """{language: {(context, source): Entry(translation, finished, locations)}}."""
    return {language: i18n.read_ts(i18n.ts_path(language)) for language in LANGUAGES}


def method_texts(module):
    """{class: {method: text}} of the methods of ``algorithms/<module>`` that return
    ``self.tr("literal")`` (displayName, shortDescription, shortHelpString, ...)."""
    with open(os.path.join(REPO_ROOT, "algorithms", module), encoding="utf-8") as f:
        tree = ast.parse(f.read())
    out = {}
    for cls in (n for n in tree.body if isinstance(n, ast.ClassDef)):
        for method in (n for n in cls.body if isinstance(n, ast.FunctionDef)):
            for node in ast.walk(method):
                call = getattr(node, "value", None) if isinstance(node, ast.Return) else None
                if isinstance(call, ast.Call) and getattr(call.func, "attr", None) == "tr" and call.args \
                        and isinstance(call.args[0], ast.Constant):
                    out.setdefault(cls.name, {})[method.name] = call.args[0].value
    return out


# --- extraction -------------------------------------------------------------------------

SYNTHETIC_CORE = '''
from .errors import InputError, Message

NOT_LAS = "Cannot read {path}: expected a LAS or LAZ file"


def read_table(path, required, what="table"):
    if not path:
        raise InputError(NOT_LAS, path=path)
    raise InputError("{what} file {path} is "
                     "empty", what=what, path=path)


def check_times(path, times, what):
    kind = "is duplicated" if times else "goes back in time"
    raise InputError("{what} file {path}: a time {kind}", what=what, path=path, kind=kind)


def warn(result, progress, template, **values):
    result.warnings.append(progress.warning(template, **values))


class Spool:
    def add(self, kind, rows):
        self.files[kind] = rows


def run(progress, result, spool):
    read_table("x.csv", ("time",), what="Trajectory")
    check_times("x.out", [], "SBET")
    progress.info("Trajectory: {count} samples", count=2)
    result.warnings.append(progress.warning("No target CRS given: using {crs}", crs="x"))
    result.messages.append(Message("Heights: pass through unchanged"))
    warn(result, progress, "No candidates to refine", role="reference signs")
    spool.add("points", [1])
    print("Not user visible")
    label = "Never extracted"
    return label
'''


def test_core_texts_are_found(tmp_path):
    """Templates of InputError, Message, progress.info/warning and of a function with a
    ``template`` parameter, module constants given as templates, and the words given to
    ``what``/``role``/``kind`` (by keyword, position, assignment or default) are found;
    other strings are not."""
    source = tmp_path / "synthetic.py"
    source.write_text(SYNTHETIC_CORE, encoding="utf-8")
    found = i18n.core_strings([str(source)])
    assert {text: kind for text, (kind, _) in found.items()} == {
        "Cannot read {path}: expected a LAS or LAZ file": "template",
        "{what} file {path} is empty": "template",
        "{what} file {path}: a time {kind}": "template",
        "Trajectory: {count} samples": "template",
        "No target CRS given: using {crs}": "template",
        "Heights: pass through unchanged": "template",
        "No candidates to refine": "template",
        "table": "field", "Trajectory": "field", "SBET": "field", "is duplicated": "field",
        "goes back in time": "field", "reference signs": "field"}
    assert found["Trajectory"][1][0][1] == SYNTHETIC_CORE.splitlines().index(
        '    read_table("x.csv", ("time",), what="Trajectory")') + 1


def test_extraction_finds_every_algorithm_name_and_help_in_its_class_context(found):
    """displayName, shortDescription and shortHelpString of every algorithm (read with ast
    here) in the context of its class; the core's templates, the dependency messages and
    the shipped model's help in context RoadSigns; the provider's and module-level texts."""
    seen = 0
    for name in sorted(os.listdir(os.path.join(REPO_ROOT, "algorithms"))):
        if name.endswith(".py"):
            for cls, texts in method_texts(name).items():
                for method in ("displayName", "shortDescription", "shortHelpString"):
                    if method in texts:
                        assert (cls, texts[method]) in found, (name, cls, method)
                        seen += 1
    assert seen >= 18
    from roadsigns.dependencies import MISSING, SHAPELY_CONFLICT
    for text in (MISSING, SHAPELY_CONFLICT, "Unknown {role} '{crs}': {error}", "Trajectory",
                 "Trajectory: {count} samples over {span:.1f} s"):
        assert (CORE, text) in found, text
    assert any(c == CORE and s.startswith("The whole road-sign inventory") for c, s in found)  # ALG_DESC
    assert ("RoadSignsAlgorithm", "Road sign inventory") in found
    assert ("RoadSignsProvider", "Road sign inventory") in found
    assert ("@default", "Road Sign Inventory") in found  # plugin.py, bare tr
    assert len(found) > 300


# --- coverage ---------------------------------------------------------------------------

@pytest.mark.parametrize("language", LANGUAGES)
def test_every_string_has_a_finished_translation_with_the_same_placeholders(found, ts, language):
    entries = ts[language]
    missing = [key for key in found if key not in entries]
    assert not missing, "{}: not in the .ts (run make i18n): {}".format(language, missing[:5])
    unfinished = [key for key in found if not entries[key].finished or not entries[key].translation.strip()]
    assert not unfinished, "{}: untranslated (see scripts/i18n.py check): {}".format(language, unfinished[:5])
    broken = [(key, i18n.problems(key[1], entries[key].translation)) for key in found]
    broken = [b for b in broken if b[1]]
    assert not broken, broken[:5]


def test_translations_are_checked_for_placeholders_and_tags():
    assert i18n.problems("{what} file {path}: <b>{n:.1f}</b> m", "archivo de {what} {path}: <b>{n:.1f}</b> m") == []
    assert i18n.problems("{what} file {path}", "archivo {path}") != []
    assert i18n.problems("{n:.1f} m", "{n} m") != []
    assert i18n.problems("<b>Crop</b>: polygons", "Recorte: polígonos") != []
    assert i18n.problems("{count} samples", "{count muestras") != []


QM_PROBE = r'''
import json, sys
from qgis.PyQt.QtCore import QCoreApplication, QTranslator
app = QCoreApplication([])
job = json.load(sys.stdin)
out = {}
for language, (path, keys) in job.items():
    translator = QTranslator()
    if not translator.load(path):
        out[language] = None
        continue
    QCoreApplication.installTranslator(translator)  # the way the plugin translates (UTF-8)
    out[language] = [QCoreApplication.translate(context, source) for context, source in keys]
    QCoreApplication.removeTranslator(translator)
json.dump(out, sys.stdout)
'''


def test_compiled_qm_files_match_the_ts_sources(found, ts):
    """Each .qm loads with QTranslator and gives, for every extracted (context, source),
    in that context, the .ts translation (so the .qm was compiled from the current .ts)."""
    keys = list(found)
    job = {language: (i18n.qm_path(language), keys) for language in LANGUAGES}
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    p = subprocess.run(["/usr/bin/python3", "-c", QM_PROBE], input=json.dumps(job), capture_output=True,
                       text=True, env=env, timeout=60)
    assert p.returncode == 0, p.stderr
    result = json.loads(p.stdout)
    for language in LANGUAGES:
        assert result[language] is not None, "{} does not load".format(i18n.qm_path(language))
        stale = [(key, got) for key, got in zip(keys, result[language]) if got != ts[language][key].translation]
        assert not stale, "{}: the .qm is stale (run scripts/i18n.py compile): {}".format(language, stale[:3])
        assert sum(got != key[1] for key, got in zip(keys, result[language])) > 0.9 * len(keys)


def test_chinese_locales_find_the_simplified_chinese_file():
    from roadsigns.algorithms.i18n import locale_candidates
    for locale in ("zh-Hans", "zh_CN", "zh_SG", "zh", "zh_Hans_CN"):
        assert "zh_Hans" in locale_candidates(locale), locale
    for locale in ("zh_TW", "zh-Hant", "zh_HK"):
        assert "zh_Hans" not in locale_candidates(locale), locale
    assert locale_candidates("es_MX") == ["es_MX", "es"]
    assert locale_candidates("es-ES.UTF-8") == ["es_ES", "es"]


# --- loading in qgis_process --------------------------------------------------------------

def set_locale(profile, locale):
    """Select ``locale`` in the profile's QGIS settings (locale/userLocale + overrideFlag)."""
    ini = os.path.join(profile, "profiles", "default", "QGIS", "QGIS3.ini")
    os.makedirs(os.path.dirname(ini), exist_ok=True)
    text = open(ini, encoding="utf-8").read() if os.path.exists(ini) else ""
    text = re.sub(r"(?ms)^\[locale\]\n.*?(?=^\[|\Z)", "", text)
    with open(ini, "w", encoding="utf-8") as f:
        f.write(text.rstrip("\n") + "\n\n[locale]\noverrideFlag=true\nuserLocale={}\n".format(locale))


@pytest.fixture(scope="module")
def qgis_localized(plugin_path, tmp_path_factory):
    profile = str(tmp_path_factory.mktemp("qgis-profile-i18n"))
    set_locale(profile, "es")  # before the first start: enabling the plugin keeps it
    qgis = QgisProcess(plugin_path, profile)
    return qgis, profile


@pytest.fixture(scope="module")
def bad_trajectory(tmp_path_factory):
    """A trajectory CSV without its heading column, image times and a panorama folder."""
    folder = tmp_path_factory.mktemp("i18n-drive")
    (folder / "images").mkdir()
    (folder / "trajectory.csv").write_text("time,x,y,z,roll,pitch\n0,500000,5000000,100,0,0\n"
                                           "1,500001,5000000,100,0,0\n")
    (folder / "times.csv").write_text("image,time\na.jpg,0.5\n")
    return folder


def _run_bad_trajectory(qgis, folder):
    return qgis.run("roadsigns:importtrajectory", TRAJECTORY=folder / "trajectory.csv",
                    IMAGE_TIMES=folder / "times.csv", IMAGES=folder / "images", TRAJECTORY_CRS="EPSG:32633",
                    OUTPUT=folder / "stations.gpkg")


def _assert_translated_error(run, found, entries, folder):
    assert run.returncode != 0, run.text
    template = next(s for c, s in found if c == CORE and "missing column(s)" in s)  # core/tables.py
    translated = entries[(CORE, template)].translation
    chunks = [c.strip(" :;,.") for c in re.split(r"\{[^{}]*\}", translated)]
    for chunk in chunks:
        if chunk:
            assert chunk in run.text, (chunk, run.text)
    for chunk in re.split(r"\{[^{}]*\}", template):
        if len(chunk.strip(" :;,.")) > 8:
            assert chunk.strip(" :;,.") not in run.text, ("English left", chunk, run.text)
    assert str(folder / "trajectory.csv") in run.text  # {path}
    assert "heading" in run.text                        # {missing}
    assert not re.search(r"\{[a-z_]*\}", run.text), run.text  # every field filled in


def test_spanish_locale_shows_translated_algorithms_and_errors(qgis_localized, found, ts, bad_trajectory):
    qgis, profile = qgis_localized
    es = ts["es"]
    set_locale(profile, "es")
    strings = method_texts("importtrajectory.py")["ImportTrajectory"]
    text = qgis("help", "roadsigns:importtrajectory")
    assert text.returncode == 0, text.text
    for method in ("displayName", "shortDescription", "shortHelpString"):
        assert es[("ImportTrajectory", strings[method])].translation in text.stdout, method
    assert strings["displayName"] not in text.stdout

    ground = method_texts("groundfilter.py")["GroundFilter"]
    run = qgis("--json", "help", "roadsigns:groundfilter")
    assert run.returncode == 0, run.text
    info = run.json
    assert info["algorithm_details"]["name"] == es[("GroundFilter", ground["displayName"])].translation
    assert info["algorithm_details"]["group"] == es[("RoadSignsAlgorithm", "Road sign inventory")].translation
    assert info["algorithm_details"]["short_description"] == \
        es[("GroundFilter", ground["shortDescription"])].translation
    options = info["parameters"]["METHOD"]["available_options"]
    assert options["0"] == es[("GroundFilter", "CSF (cloth simulation)")].translation
    english = {source for _, source in es}
    for parameter in info["parameters"].values():
        assert parameter["help"] not in english, "untranslated help: " + parameter["help"]
    assert es[("GroundFilter", "Reset existing classes")].translation == \
        info["parameters"]["RESET_CLASSES"]["description"]

    _assert_translated_error(_run_bad_trajectory(qgis, bad_trajectory), found, es, bad_trajectory)


def test_chinese_locale_shows_translated_algorithms_and_errors(qgis_localized, found, ts, bad_trajectory):
    qgis, profile = qgis_localized
    zh = ts["zh_Hans"]
    strings = method_texts("importtrajectory.py")["ImportTrajectory"]
    set_locale(profile, "zh-Hans")  # QGIS's own code for Simplified Chinese
    text = qgis("help", "roadsigns:importtrajectory")
    assert text.returncode == 0, text.text
    for method in ("displayName", "shortDescription", "shortHelpString"):
        assert zh[("ImportTrajectory", strings[method])].translation in text.stdout, method
    _assert_translated_error(_run_bad_trajectory(qgis, bad_trajectory), found, zh, bad_trajectory)

    set_locale(profile, "zh_CN")  # a system-style locale finds the zh_Hans file too
    run = qgis("--json", "help", "roadsigns:importtrajectory")
    assert run.returncode == 0, run.text
    assert run.json["algorithm_details"]["name"] == zh[("ImportTrajectory", strings["displayName"])].translation


def test_no_english_text_reaches_users_outside_tr():
    """Adapters' messages go through tr with literals (what pylupdate5 sees); core's log
    messages are templates with fields (``Message``, ``progress.info/warning``) that the
    adapters translate."""
    assert i18n.audit() == []


SYNTHETIC_ADAPTER = '''
class Algorithm(RoadSignsAlgorithm):
    LABEL = "Point cloud"

    def initAlgorithm(self, config=None):
        self.add_number(self.A, "Crop buffer (m)", 0.0, self.tr("Grow the crop by this."))
        self.add_enum(self.M, self.tr("Method"), [("csf", self.tr("CSF"))], "csf", self.tr("Pick one."))
        self.addOutput(QgsProcessingOutputNumber(self.N, self.tr(self.LABEL)))

    def processAlgorithm(self, parameters, context, feedback):
        feedback.pushInfo(self.tr("{} points written").format(3))
        feedback.pushWarning(f"Skipped {3} points")
        feedback.pushInfo(tr_core("Engine: {}"))
        raise QgsProcessingException("The crop layer is empty")
'''

SYNTHETIC_CORE_LOG = '''
from .errors import Message


def run(progress, result, n):
    progress.info("Read {n} points", n=n)
    progress.info(f"Read {n} points")
    progress.warning("Read {} points".format(n))
    result.warnings.append("No ground points")
    result.messages.append(Message("Read {n} points", n=n))
'''


def _lines_with(text, needles):
    return {k + 1 for k, line in enumerate(text.splitlines()) if any(n in line for n in needles)}


def test_audit_finds_english_text_outside_tr(tmp_path):
    """Each place that shows English is named once, by file and line; the others are not."""
    adapter, core = tmp_path / "adapter.py", tmp_path / "core_log.py"
    adapter.write_text(SYNTHETIC_ADAPTER, encoding="utf-8")
    core.write_text(SYNTHETIC_CORE_LOG, encoding="utf-8")
    lines = i18n.audit([str(adapter)], [str(core)])
    places = [tuple(line.split(": ", 1)[0].rsplit("/", 1)[-1].split(":")) for line in lines]
    expected = [("adapter.py", str(k)) for k in _lines_with(SYNTHETIC_ADAPTER, (
        '"Crop buffer (m)"', "self.tr(self.LABEL)", 'f"Skipped', 'tr_core("Engine', '"The crop layer is empty"'))]
    expected += [("core_log.py", str(k)) for k in _lines_with(SYNTHETIC_CORE_LOG, (
        'f"Read', ".format(n)", '"No ground points"'))]
    assert sorted(places) == sorted(expected), lines


def test_core_log_messages_are_translated(qgis_localized, ts, drive_projected, tmp_path):
    """A core log message (template, fields, and a field that is a message itself) shows in
    the locale's language, its fields filled in."""
    qgis, profile = qgis_localized
    set_locale(profile, "es")
    run = qgis.run("roadsigns:importtrajectory", TRAJECTORY=drive_projected["trajectory_csv"],
                   IMAGE_TIMES=drive_projected["image_times"], IMAGES=drive_projected["images"],
                   TRAJECTORY_CRS="EPSG:32633", OUTPUT=str(tmp_path / "stations.gpkg"))
    assert run.returncode == 0, run.text
    es = ts["es"]
    samples = es[(CORE, "Trajectory: {count} samples over {span:.1f} s")].translation
    assert re.search(re.escape(samples).replace(r"\{count\}", r"\d+").replace(r"\{span:\.1f\}", r"[\d.]+"),
                     run.text), run.text
    heights = es[(CORE, "Heights: pass through unchanged (the target CRS has no vertical datum)")].translation
    assert heights in run.text
    assert "Trajectory: " not in run.text and not re.search(r"\{[a-z_:.0-9]*\}", run.text)
