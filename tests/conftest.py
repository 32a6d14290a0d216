"""Test set-up: make the checkout importable as the package ``roadsigns``.

The checkout folder may have any name; a symlink ``<tmp>/roadsigns -> checkout`` is put
on ``sys.path`` (core tests import ``roadsigns.core``) and serves as ``QGIS_PLUGINPATH``
for the ``qgis_process`` tests (see ``tests/qgis/conftest.py``).
"""
import os
import shutil
import sys
import tempfile

import pytest

if os.path.isdir("/usr/share/proj"):  # pyproj inside a venv looks under the venv otherwise
    os.environ.setdefault("PROJ_DATA", "/usr/share/proj")
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.append(REPO_ROOT)  # dev tools: ``import devtools.trajsample``

#: The run's own temporary folder (``TMPDIR`` for this process and every ``qgis_process``
#: it starts), so :func:`pytest_sessionfinish` can tell what the tests left behind. Removed at
#: the end when nothing was left. Under pytest-xdist (``make test`` runs two workers) the
#: controller makes it and passes it on in ``RUN_TMP_ENV``; each worker takes a sub-folder
#: named by its id and reports what was left in it (:func:`pytest_testnodedown`).
RUN_TMP_ENV = "ROADSIGNS_TESTS_TMP"
_WORKER_ID = os.environ.get("PYTEST_XDIST_WORKER")
if _WORKER_ID and os.environ.get(RUN_TMP_ENV):
    SESSION_TMP = os.path.join(os.environ[RUN_TMP_ENV], _WORKER_ID)
    os.makedirs(SESSION_TMP, exist_ok=True)
else:
    SESSION_TMP = tempfile.mkdtemp(prefix="roadsigns-tests-")
    os.environ[RUN_TMP_ENV] = SESSION_TMP
os.environ["TMPDIR"] = SESSION_TMP
tempfile.tempdir = None  # gettempdir() reads TMPDIR again

from devtools import plugin_path as _plugin_path  # noqa: E402
from devtools import temp_folders as _devtools_temp_folders  # noqa: E402

PLUGIN_PATH = _plugin_path()
sys.path.insert(0, PLUGIN_PATH)
sys.path.append(os.path.join(REPO_ROOT, "tests"))  # shared test helpers: ``import helpers.contract``


#: What the xdist workers left in their folders (``<worker id>/<name>``), as they reported it.
_LEFT_BY_WORKERS = []


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """xdist's controller: a worker is done; keep what it reported left behind."""
    output = getattr(node, "workeroutput", {}) or {}
    _LEFT_BY_WORKERS.extend(os.path.join(node.workerinput["workerid"], name)
                            for name in output.get("roadsigns_left_behind", []))


def pytest_sessionfinish(session, exitstatus):
    """Fail the run when the plugin left a temporary folder of its own (``roadsigns-*``: window
    spools, block spools, half-written outputs) in the temporary folder of the tests or of the
    ``qgis_process`` runs they started: cancelled and failed runs must clean up too. The dev
    tools' own folders (plugin path, profiles) are removed when the process exits. An xdist
    worker hands its list to the controller, which fails the run."""
    ours = set(_devtools_temp_folders())
    left = sorted(name for name in os.listdir(SESSION_TMP)
                  if name.startswith("roadsigns-") and os.path.join(SESSION_TMP, name) not in ours)
    worker_output = getattr(session.config, "workeroutput", None)
    if worker_output is not None:
        worker_output["roadsigns_left_behind"] = left
        return
    left += _LEFT_BY_WORKERS
    if left:
        sys.stderr.write("\nTemporary folders left behind in {}: {}\n".format(SESSION_TMP, ", ".join(left)))
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
    elif exitstatus == 0:
        import atexit
        atexit.register(shutil.rmtree, SESSION_TMP, True)


@pytest.fixture(scope="session")
def plugin_path():
    """Folder holding ``roadsigns`` (a symlink to the checkout), for QGIS_PLUGINPATH."""
    return PLUGIN_PATH


@pytest.fixture(scope="session")
def drive_projected(tmp_path_factory):
    """A small analytic drive in EPSG:32633 (devtools/trajsample.py): CSV, SBET, poses, images."""
    from devtools import trajsample
    return trajsample.make_sample(str(tmp_path_factory.mktemp("drive_projected")))


@pytest.fixture(scope="session")
def drive_geographic(tmp_path_factory):
    """The same drive with lon/lat positions (EPSG:4326)."""
    from devtools import trajsample
    return trajsample.make_sample(str(tmp_path_factory.mktemp("drive_geographic")), crs="geographic")


@pytest.fixture(scope="session")
def scene_tiny_cloud(tmp_path_factory):
    """A generated scene (devtools/scenegen, preset tiny) without panoramas: LAZ with true classes."""
    from devtools.scenegen import generate_scene
    folder = str(tmp_path_factory.mktemp("scene_tiny_cloud"))
    generate_scene("tiny", seed=11, out_dir=folder, panoramas=False, masks=False)
    return folder


@pytest.fixture(scope="session")
def scene_tiny(tmp_path_factory):
    """The generated tiny scene with panoramas (2048 x 1024) and its scene.json truth."""
    import json

    from helpers.scenes import render_scene
    folder = render_scene(tmp_path_factory.mktemp("scene_tiny"), "tiny", 3, "--no-masks")
    with open(os.path.join(folder, "scene.json")) as f:
        return folder, json.load(f)
