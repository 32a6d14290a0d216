"""Developer tools of Road Sign Inventory (never shipped in the plugin zip).

The checkout may sit in a folder of any name, but the plugin is the package ``roadsigns``:
:func:`plugin_path` makes (once per process) a folder holding a symlink
``roadsigns -> checkout``, usable as ``QGIS_PLUGINPATH`` and on ``sys.path``.
"""
import importlib
import os
import sys
import tempfile

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_PLUGIN_PATH = []


def plugin_path() -> str:
    """A folder holding ``roadsigns`` (a symlink to this checkout), made once per process."""
    if not _PLUGIN_PATH:
        folder = tempfile.mkdtemp(prefix="roadsigns-pluginpath-")
        os.symlink(REPO_ROOT, os.path.join(folder, "roadsigns"))
        _PLUGIN_PATH.append(folder)
    return _PLUGIN_PATH[0]


def import_roadsigns(module: str = "roadsigns"):
    """Import ``roadsigns`` (or one of its modules) from this checkout."""
    try:
        return importlib.import_module(module)
    except ImportError:
        sys.path.insert(0, plugin_path())
        return importlib.import_module(module)
