"""Translations: every user-visible string (``scripts/i18n.py extract``) has a finished
Simplified Chinese and Spanish translation keeping its placeholders and HTML tags, the
compiled ``.qm`` files say the same as the ``.ts`` sources, and ``qgis_process`` shows the
algorithms and core error messages in the language of the QGIS locale setting."""
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


def _load_i18n_script():
    spec = importlib.util.spec_from_file_location("roadsigns_i18n_script",
                                                  os.path.join(REPO_ROOT, "scripts", "i18n.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


i18n = _load_i18n_script()


@pytest.fixture(scope="module")
def found():
    return i18n.extract()


@pytest.fixture(scope="module")
def ts():
    return {language: i18n.read_ts(i18n.ts_path(language)) for language in LANGUAGES}


# --- extraction -------------------------------------------------------------------------

SYNTHETIC = '''
from qgis.PyQt.QtCore import QCoreApplication
from .errors import InputError

NOT_FOUND = "Cannot read {path}: no such file"
LABELS = {"A": "Label of a", "B": "Label of b"}
SHAPES = {"warning": 1, "stop": 2}


def tr(text):
    return QCoreApplication.translate("RoadSigns", text)


class Base:
    DISPLAY_NAME = ""
    GROUP = "The group"

    def tr(self, text):
        return tr(text)

    def displayName(self):
        return self.tr(self.DISPLAY_NAME)

    def group(self):
        return self.tr(self.GROUP)

    def add(self, parameter, help_text, advanced=False):
        parameter.setHelp(self.tr(help_text))

    def add_number(self, name, label, default, help_text, minimum=None):
        return self.add(Number(name, self.tr(label), default), help_text)

    def core_errors(self):
        try:
            pass
        except InputError as error:
            raise Exception(self.tr(error.template).format(**error.fields))


class Algorithm(Base):
    DISPLAY_NAME = "Do " "it"
    METHODS = ["First method", "Second method"]

    def init(self):
        shared_help = ("Shared help, "
                       "joined.")
        self.add_number("A", "Label A", 0, shared_help)
        self.add_number("B", label="Label B", default=1, help_text=shared_help)
        self.add(Enum("M", self.tr("Method"), options=[self.tr(m) for m in self.METHODS]),
                 "Pick a method.")
        for name in ("A", "B"):
            output(self.tr(LABELS[name]))
        legend = [tr(key) for key, value in SHAPES.items()]
        message = self.tr("{} done in {:.1f} s").format(1, 2.0)
        not_user_visible = "Never extracted"


def read(path, what):
    if not path:
        raise InputError(NOT_FOUND, path=path)
    raise InputError("{what} file {path} is "
                     "empty", what=what, path=path)


def caller():
    read("x.csv", what="Trajectory")
'''


def test_extraction_follows_tr_through_calls_attributes_and_constants(tmp_path):
    source = tmp_path / "synthetic.py"
    source.write_text(SYNTHETIC, encoding="utf-8")
    extractor = i18n.Extractor([str(source)])
    texts = set(extractor.run())
    assert texts == {
        "The group", "Do it", "Shared help, joined.", "Label A", "Label B", "Method", "Pick a method.",
        "First method", "Second method", "Label of a", "Label of b", "warning", "stop",
        "{} done in {:.1f} s", "Cannot read {path}: no such file", "{what} file {path} is empty",
        "Trajectory"}, texts
    assert not extractor.warnings, extractor.warnings


def test_extraction_finds_every_algorithm_name_and_help(found):
    """DISPLAY_NAME, SHORT_DESCRIPTION and HELP of every algorithm class (read with ast here)."""
    folder = os.path.join(REPO_ROOT, "algorithms")
    seen = 0
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".py"):
            continue
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            tree = ast.parse(f.read())
        for cls in (n for n in tree.body if isinstance(n, ast.ClassDef)):
            attributes = {t.id: node.value.value for node in cls.body if isinstance(node, ast.Assign)
                          for t in node.targets if isinstance(t, ast.Name)
                          and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)}
            for key in ("DISPLAY_NAME", "SHORT_DESCRIPTION", "HELP"):
                if attributes.get(key):
                    assert attributes[key] in found, (name, cls.name, key)
                    seen += 1
    assert seen >= 18
    assert len(found) > 200


# --- coverage ---------------------------------------------------------------------------

@pytest.mark.parametrize("language", LANGUAGES)
def test_every_string_has_a_finished_translation_with_the_same_placeholders(found, ts, language):
    entries = ts[language]
    missing = [s for s in found if s not in entries]
    assert not missing, "{}: not in the .ts (run scripts/i18n.py update): {}".format(language, missing[:5])
    unfinished = [s for s in found if entries[s].state != "finished" or not entries[s].translation.strip()]
    assert not unfinished, "{}: untranslated (see scripts/i18n.py check): {}".format(language, unfinished[:5])
    broken = [(s, i18n.problems(s, entries[s].translation)) for s in found]
    broken = [b for b in broken if b[1]]
    assert not broken, broken[:5]


QM_PROBE = r'''
import json, sys
from qgis.PyQt.QtCore import QCoreApplication, QTranslator
app = QCoreApplication([])
job = json.load(sys.stdin)
out = {}
for language, (path, sources) in job.items():
    translator = QTranslator()
    if not translator.load(path):
        out[language] = None
        continue
    QCoreApplication.installTranslator(translator)  # the way the plugin translates (UTF-8)
    out[language] = [QCoreApplication.translate("RoadSigns", s) for s in sources]
    QCoreApplication.removeTranslator(translator)
json.dump(out, sys.stdout)
'''


def test_compiled_qm_files_match_the_ts_sources(found, ts):
    """Each .qm loads with QTranslator and gives, for every extracted string, the .ts
    translation (so the .qm was compiled from the current .ts)."""
    sources = list(found)
    job = {language: (i18n.qm_path(language), sources) for language in LANGUAGES}
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    p = subprocess.run(["/usr/bin/python3", "-c", QM_PROBE], input=json.dumps(job), capture_output=True,
                       text=True, env=env, timeout=60)
    assert p.returncode == 0, p.stderr
    result = json.loads(p.stdout)
    for language in LANGUAGES:
        assert result[language] is not None, "{} does not load".format(i18n.qm_path(language))
        stale = [(s, got) for s, got in zip(sources, result[language]) if got != ts[language][s].translation]
        assert not stale, "{}: the .qm is stale (run scripts/i18n.py compile): {}".format(language, stale[:3])


def test_chinese_locales_find_the_simplified_chinese_file():
    from roadsigns.provider.i18n import locale_candidates
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


def _class_strings(module, class_name):
    with open(os.path.join(REPO_ROOT, "algorithms", module), encoding="utf-8") as f:
        tree = ast.parse(f.read())
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == class_name)
    return {t.id: node.value.value for node in cls.body if isinstance(node, ast.Assign)
            for t in node.targets if isinstance(t, ast.Name) and isinstance(node.value, ast.Constant)}


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
    template = next(s for s in found if "missing column(s)" in s)  # core/tables.py
    translated = entries[template].translation
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
    strings = _class_strings("importtrajectory.py", "ImportTrajectory")
    text = qgis("help", "roadsigns:importtrajectory")
    assert text.returncode == 0, text.text
    assert es[strings["DISPLAY_NAME"]].translation in text.stdout
    assert es[strings["SHORT_DESCRIPTION"]].translation in text.stdout
    assert es[strings["HELP"]].translation in text.stdout
    assert strings["DISPLAY_NAME"] not in text.stdout

    ground = _class_strings("groundfilter.py", "GroundFilter")
    run = qgis("--json", "help", "roadsigns:groundfilter")
    assert run.returncode == 0, run.text
    info = run.json
    assert info["algorithm_details"]["name"] == es[ground["DISPLAY_NAME"]].translation
    assert info["algorithm_details"]["group"] == es["Road sign inventory"].translation
    assert info["algorithm_details"]["short_description"] == es[ground["SHORT_DESCRIPTION"]].translation
    options = info["parameters"]["METHOD"]["available_options"]
    assert options["0"] == es["CSF (cloth simulation)"].translation
    for parameter in info["parameters"].values():
        assert es.get(parameter["help"]) is None, "untranslated help: " + parameter["help"]

    _assert_translated_error(_run_bad_trajectory(qgis, bad_trajectory), found, es, bad_trajectory)


def test_chinese_locale_shows_translated_algorithms_and_errors(qgis_localized, found, ts, bad_trajectory):
    qgis, profile = qgis_localized
    zh = ts["zh_Hans"]
    strings = _class_strings("importtrajectory.py", "ImportTrajectory")
    set_locale(profile, "zh-Hans")  # QGIS's own code for Simplified Chinese
    text = qgis("help", "roadsigns:importtrajectory")
    assert text.returncode == 0, text.text
    for key in ("DISPLAY_NAME", "SHORT_DESCRIPTION", "HELP"):
        assert zh[strings[key]].translation in text.stdout, key
    _assert_translated_error(_run_bad_trajectory(qgis, bad_trajectory), found, zh, bad_trajectory)

    set_locale(profile, "zh_CN")  # a system-style locale finds the zh_Hans file too
    run = qgis("--json", "help", "roadsigns:importtrajectory")
    assert run.returncode == 0, run.text
    assert run.json["algorithm_details"]["name"] == zh[strings["DISPLAY_NAME"]].translation


def test_no_english_text_reaches_users_outside_tr():
    """Adapters' messages go through tr; core's log messages are templates with fields
    (``Message``, ``progress.info/warning``) that the adapters translate."""
    assert i18n.audit() == []


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
    samples = es["Trajectory: {count} samples over {span:.1f} s"].translation
    assert re.search(re.escape(samples).replace(r"\{count\}", r"\d+").replace(r"\{span:\.1f\}", r"[\d.]+"),
                     run.text), run.text
    heights = es["Heights: pass through unchanged (the target CRS has no vertical datum)"].translation
    assert heights in run.text
    assert "Trajectory: " not in run.text and not re.search(r"\{[a-z_:.0-9]*\}", run.text)
