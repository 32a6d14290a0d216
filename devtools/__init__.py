"""Developer tools of Road Sign Inventory (never shipped in the plugin zip).

The checkout may sit in a folder of any name, but the plugin is the package ``roadsigns``:
:func:`plugin_path` makes (once per process) a folder holding a symlink
``roadsigns -> checkout``, usable as ``QGIS_PLUGINPATH`` and on ``sys.path``. The
temporary folders the developer tools make (:func:`temp_folder`) are removed when the
process exits.
"""
import atexit
import importlib
import os
import shutil
import sys
import tempfile
from typing import List

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_PLUGIN_PATH: List[str] = []
_TEMP_FOLDERS: List[str] = []


def _remove_temp_folders() -> None:
    while _TEMP_FOLDERS:
        shutil.rmtree(_TEMP_FOLDERS.pop(), ignore_errors=True)


atexit.register(_remove_temp_folders)


def temp_folder(prefix: str) -> str:
    """A new temporary folder, removed (with what it holds) when this process exits."""
    folder = tempfile.mkdtemp(prefix=prefix)
    _TEMP_FOLDERS.append(folder)
    return folder


def temp_folders() -> List[str]:
    """The folders :func:`temp_folder` made that are still there (removed at exit)."""
    return [f for f in _TEMP_FOLDERS if os.path.isdir(f)]


def plugin_path() -> str:
    """A folder holding ``roadsigns`` (a symlink to this checkout), made once per process."""
    if not _PLUGIN_PATH:
        folder = temp_folder("roadsigns-pluginpath-")
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


def forked_map(function, items, jobs: int = 1) -> list:
    """``[function(item) for item in items]``, in ``jobs`` forked processes when ``jobs`` > 1
    (results in the items' order). Forked: the children start from this process's state (a
    renderer, a scene), so ``function`` may read module globals set before the call; fork only
    where no thread pool (OpenCV's, torch's) has started in this process."""
    items = list(items)
    if jobs > 1 and len(items) > 1:
        import multiprocessing

        with multiprocessing.get_context("fork").Pool(min(jobs, len(items))) as pool:
            return pool.map(function, items)
    return [function(item) for item in items]
