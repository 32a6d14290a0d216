"""Run algorithms through a real ``qgis_process`` with a throw-away QGIS profile.

The profile (``QGIS_CUSTOM_CONFIG_PATH``) is made once per test session and the plugin
enabled in it with ``qgis_process plugins enable roadsigns`` (see devtools/qgisrun.py).
"""
import pytest
from helpers.scenes import scene_inputs

from devtools.qgisrun import QgisProcess


@pytest.fixture(scope="session")
def qgis_process(plugin_path, tmp_path_factory):
    return QgisProcess(plugin_path, str(tmp_path_factory.mktemp("qgis-profile")))


@pytest.fixture(scope="session")
def scene_tiny_stations(qgis_process, scene_tiny, tmp_path_factory):
    """The tiny scene's panorama stations, imported once through qgis_process."""
    scene_dir, scene = scene_tiny
    stations = str(tmp_path_factory.mktemp("stations") / "stations.gpkg")
    run = qgis_process.run("roadsigns:importtrajectory", OUTPUT=stations, **scene_inputs(scene_dir, scene))
    assert run.returncode == 0, run.text
    return stations
