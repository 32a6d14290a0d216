"""The QGIS desktop, for real, under a virtual display: ``xvfb-run qgis --code drive_panel.py``
with a throw-away profile in which the plugin (the checkout, through ``QGIS_PLUGINPATH``) is
enabled. One QGIS start serves every test of this folder (about 20 s); the driver script
writes what it saw to ``results.json``.

Needs the ``qgis`` desktop and ``xvfb-run`` (Debian ``xvfb``; ``make setup`` installs both).
The display is Xvfb's whatever ``QT_QPA_PLATFORM`` the tests run with (xcb for QGIS).
"""
import json
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
DRIVER = os.path.join(HERE, "drive_panel.py")
TIMEOUT_S = 240


def write_profile(profiles_dir):
    """A QGIS profile ``default`` with the plugin enabled and no start-up questions."""
    folder = os.path.join(profiles_dir, "profiles", "default", "QGIS")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "QGIS3.ini"), "w") as f:
        f.write("[PythonPlugins]\nroadsigns=true\n\n[qgis]\ncheckVersion=false\n")
    return profiles_dir


def run_qgis(plugin_path, data_dir, out_dir, profiles_dir, mode="test", timeout=TIMEOUT_S):
    """Start the QGIS desktop under Xvfb with the driver script; returns the process result."""
    for tool in ("qgis", "xvfb-run"):
        if shutil.which(tool) is None:
            pytest.fail("{} is not installed: run `make setup` (scripts/setup.sh installs qgis and xvfb)".format(tool))
    site = [p for p in sys.path if p.endswith("site-packages") and os.path.isdir(p)]
    env = dict(os.environ)
    env.update({
        "QGIS_PLUGINPATH": plugin_path, "QT_QPA_PLATFORM": "xcb", "ROADSIGNS_GUI_DATA": data_dir,
        "ROADSIGNS_GUI_OUT": out_dir, "ROADSIGNS_GUI_MODE": mode, "PROJ_DATA": env.get("PROJ_DATA", "/usr/share/proj"),
        "PYTHONPATH": os.pathsep.join(site + [env.get("PYTHONPATH", "")]).strip(os.pathsep),
        "XDG_RUNTIME_DIR": env.get("XDG_RUNTIME_DIR") or os.path.join(profiles_dir, "xdg")})
    os.makedirs(env["XDG_RUNTIME_DIR"], mode=0o700, exist_ok=True)
    command = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", "qgis", "--profiles-path", profiles_dir,
               "--profile", "default", "--nologo", "--noversioncheck", "--code", DRIVER]
    return subprocess.run(command, env=env, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)


@pytest.fixture(scope="session")
def review_data(tmp_path_factory):
    from helpers import reviewdata
    return reviewdata.build(str(tmp_path_factory.mktemp("review_data")))


@pytest.fixture(scope="session")
def gui_run(plugin_path, review_data, tmp_path_factory):
    """The driver's results (``results.json``) and its output folder."""
    out = str(tmp_path_factory.mktemp("gui_out"))
    profiles = write_profile(str(tmp_path_factory.mktemp("qgis_profiles")))
    process = run_qgis(plugin_path, review_data["folder"], out, profiles)
    path = os.path.join(out, "results.json")
    assert os.path.exists(path), "QGIS wrote no results (exit {}):\n{}\n{}".format(
        process.returncode, process.stdout[-3000:], process.stderr[-3000:])
    with open(path) as f:
        results = json.load(f)
    results["out"] = out
    results["steps"] = {step["name"]: step for step in results["steps"]}
    return results
