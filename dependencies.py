"""Which third-party Python packages the plugin needs, which are missing, how to install them.

No qgis import: the check runs before anything heavy is imported, so a missing package
gives a clear message and the exact command to install it instead of a traceback.
"""
from __future__ import annotations

import importlib.util
import os
import sys
from typing import Iterable, List

from .core.errors import Message

#: import name -> pip requirement
PACKAGES = {
    "numpy": "numpy",
    "scipy": "scipy",
    "pyproj": "pyproj",
    "PIL": "pillow",
    "cv2": "opencv-python-headless",
    "onnxruntime": "onnxruntime",
    "shapely": "shapely>=2",
    "laspy": "laspy[lazrs]",
    "lazrs": "laspy[lazrs]",
    "threadpoolctl": "threadpoolctl",
}


def _installed(module: str) -> bool:
    try:
        if importlib.util.find_spec(module) is None:
            return False
    except (ImportError, ValueError):
        return False
    if module == "shapely":
        try:
            from importlib.metadata import version
            return int(version("shapely").split(".")[0]) >= 2
        except Exception:
            return True
    return True


def missing(modules: Iterable[str] = PACKAGES) -> List[str]:
    """Import names among ``modules`` that cannot be imported (shapely 1.x counts as missing)."""
    return [m for m in modules if not _installed(m)]


def pip_requirements(modules: Iterable[str]) -> List[str]:
    out: List[str] = []
    for m in modules:
        req = PACKAGES.get(m, m)
        if req not in out:
            out.append(req)
    return out


def install_command(modules: Iterable[str], platform: str = sys.platform) -> str:
    """The command a user runs to install ``modules`` into the Python that QGIS uses."""
    reqs = " ".join('"{}"'.format(r) if any(c in r for c in "[>=<") else r
                    for r in pip_requirements(modules))
    if platform.startswith("win"):
        return "python -m pip install --upgrade {}   (in the OSGeo4W Shell, as administrator)".format(reqs)
    if platform == "darwin":
        python = os.path.join(sys.exec_prefix, "bin", "python3")
        return "{} -m pip install --upgrade {}".format(python, reqs)
    return "python3 -m pip install --user --break-system-packages --upgrade {}".format(reqs)


#: message templates, translated by the caller before formatting (``translate`` arguments);
#: ``Message`` marks them as core templates (context RoadSigns, scripts/i18n.py extracts them)
SHAPELY_CONFLICT = Message(
    "The installed shapely is a wheel with its own copy of GEOS, which clashes with QGIS's GEOS {geos} "
    "on Linux and crashes QGIS. Install shapely built against the system GEOS: sudo apt install "
    "libgeos-dev && python3 -m pip install --user --break-system-packages --force-reinstall --no-deps "
    "--no-binary shapely \"shapely>=2\"")
MISSING = Message("Road Sign Inventory needs the Python package(s) {packages}, not found in QGIS's "
                  "Python. Install with: {command}")


def _same(text: str) -> str:
    return text


def shapely_geos_conflict(qgis_geos_version: str, platform: str = sys.platform, translate=_same) -> str:
    """'' unless shapely is a wheel with its own GEOS on Linux, where its GEOS's C++ symbols
    clash with the GEOS QGIS links and crash QGIS; then the message with the fix."""
    if not platform.startswith("linux"):
        return ""
    try:
        spec = importlib.util.find_spec("shapely")
    except (ImportError, ValueError):
        return ""
    if spec is None or not spec.origin:
        return ""
    site = os.path.dirname(os.path.dirname(spec.origin))
    if not os.path.isdir(os.path.join(site, "shapely.libs")):
        return ""
    return translate(SHAPELY_CONFLICT).format(geos=qgis_geos_version)


def missing_message(modules: Iterable[str], translate=_same) -> str:
    """'' when all are present, else one sentence naming them and the command."""
    absent = missing(modules)
    if not absent:
        return ""
    return translate(MISSING).format(packages=", ".join(pip_requirements(absent)),
                                     command=install_command(absent))
