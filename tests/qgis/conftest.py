"""Run algorithms through a real ``qgis_process`` with a throw-away QGIS profile.

The profile (``QGIS_CUSTOM_CONFIG_PATH``) is made once per test session and the plugin
enabled in it with ``qgis_process plugins enable roadsigns`` (see devtools/qgisrun.py).
"""
import pytest

from devtools.qgisrun import QgisProcess


@pytest.fixture(scope="session")
def qgis_process(plugin_path, tmp_path_factory):
    return QgisProcess(plugin_path, str(tmp_path_factory.mktemp("qgis-profile")))
