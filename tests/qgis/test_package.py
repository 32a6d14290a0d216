"""The plugin zip: runtime files only, and the chain runs from it in a fresh QGIS profile."""
import os
import subprocess
import sys
import zipfile

import pytest
from helpers.scenes import scene_mount

from devtools import REPO_ROOT
from devtools.oracle import oracle_detections
from devtools.qgisrun import QgisProcess

DEV_ONLY = ("tests/", "bench/", "devtools/", "scripts/", ".ci/", "Makefile", "requirements-dev.txt",
            "pytest.ini", ".gitignore")


@pytest.fixture(scope="module")
def plugin_zip(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("dist") / "roadsigns.zip")
    subprocess.run([sys.executable, os.path.join(REPO_ROOT, "scripts", "package.py"), "--out", out],
                   check=True, capture_output=True)
    return out


def test_zip_holds_the_runtime_files_only(plugin_zip):
    with zipfile.ZipFile(plugin_zip) as archive:
        names = archive.namelist()
    assert all(n.startswith("roadsigns/") for n in names)
    inner = [n[len("roadsigns/"):] for n in names]
    for required in ("metadata.txt", "__init__.py", "plugin.py", "provider/provider.py", "docs/formats.md",
                     "algorithms/importtrajectory.py", "core/geometry.py", "icons/roadsigns.svg"):
        assert required in inner
    assert not [n for n in inner if n.startswith(DEV_ONLY) or "__pycache__" in n or n.endswith(".pyc")]


def test_chain_runs_from_the_unpacked_zip(plugin_zip, scene_tiny, tmp_path):
    plugins = tmp_path / "plugins"
    with zipfile.ZipFile(plugin_zip) as archive:
        archive.extractall(plugins)
    qgis = QgisProcess(str(plugins), str(tmp_path / "profile"))
    listing = qgis("--json", "list").json["providers"]["roadsigns"]["algorithms"]
    assert len(listing) == 10  # nine algorithms and the shipped model
    scene_dir, scene = scene_tiny
    stations = str(tmp_path / "stations.gpkg")
    run = qgis.run("roadsigns:importtrajectory", POSES=os.path.join(scene_dir, "poses.csv"),
                   IMAGES=os.path.join(scene_dir, "images"), TRAJECTORY_CRS=scene["trajectory_crs"],
                   TARGET_CRS=scene["target_crs"], OUTPUT=stations, **scene_mount(scene))
    assert run.returncode == 0, run.text
    # the provider comes from the unpacked folder, not from the checkout
    assert os.path.realpath(qgis.env["QGIS_PLUGINPATH"]) == os.path.realpath(str(plugins))
    detections = str(tmp_path / "detections.gpkg")
    oracle_detections(scene_dir, stations, detections)
    ground = str(tmp_path / "ground.laz")
    assert qgis.run("roadsigns:groundfilter", INPUT=os.path.join(scene_dir, "cloud.laz"), CROP=stations,
                    CROP_BUFFER=25, RESET_CLASSES=True, OUTPUT=ground).returncode == 0
    candidates = str(tmp_path / "candidates.gpkg")
    assert qgis.run("roadsigns:projectdetections", DETECTIONS=detections, POINT_CLOUD=ground,
                    OUTPUT=candidates).returncode == 0
    signs = str(tmp_path / "signs.gpkg")
    assert qgis.run("roadsigns:refinesigns", CANDIDATES=candidates, POINT_CLOUD=ground,
                    OUTPUT=signs).returncode == 0
    run = qgis.run("roadsigns:evaluate", SIGNS=signs, REFERENCE=os.path.join(scene_dir, "reference_signs.csv"),
                   OUTPUT_REPORT=str(tmp_path / "report.html"))
    assert run.returncode == 0, run.text
    results = run.json["results"]
    assert results["PRECISION"] >= 0.97 and results["RECALL"] >= 0.95
