"""The real PDAL for the tests: ``../shared/tools/pdal-2.9.2`` beside the checkout.

Its README says what it holds: ``bin/pdal`` (the application) and the Python bindings'
wheel, which ``scripts/setup.sh`` installs into the venv (``make setup``). Tests that run
it call :func:`require` (through a fixture): without that folder they are skipped with a
message, but under ``CI=true`` they fail, because CI has it and they must run there.

:func:`hide_pdal` keeps PDAL away from a ``qgis_process`` run (the bindings are in the
venv, whose site-packages is on its ``PYTHONPATH``), to test the plugin without PDAL.
"""
from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import sys
from dataclasses import dataclass
from typing import Iterator

import numpy as np
import pytest

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PDAL_VERSION = "2.9.2"
PDAL_DIR = os.path.normpath(os.path.join(REPO_ROOT, "..", "shared", "tools", f"pdal-{PDAL_VERSION}"))
#: the provider setting / environment variable naming a ``pdal`` executable
#: (algorithms/groundfilter.py PDAL_SETTING)
PDAL_SETTING = "ROADSIGNS_PDAL_EXECUTABLE"


@dataclass(frozen=True)
class RealPdal:
    folder: str
    executable: str          # bin/pdal
    bindings_version: str    # what ``import pdal`` in the venv reports (pdal.info.version)


def _unavailable(reason: str) -> None:
    if os.environ.get("CI", "").lower() == "true":
        pytest.fail(f"CI=true but {reason}: CI must run the real-PDAL tests", pytrace=False)
    pytest.skip(reason)


def require() -> RealPdal:
    """The real PDAL, or skip (fail under ``CI=true``) saying what is missing."""
    executable = os.path.join(PDAL_DIR, "bin", "pdal")
    if not os.path.isdir(PDAL_DIR):
        _unavailable(f"no real PDAL: {PDAL_DIR} is absent (the tests of the PDAL engine with PDAL "
                     f"{PDAL_VERSION} need it)")
    if not os.access(executable, os.X_OK):
        _unavailable(f"{executable} is missing or not executable")
    try:
        import pdal
        version = str(pdal.info.version)
    except Exception as e:  # not installed, or a stub
        _unavailable(f"PDAL's Python bindings do not import in {sys.prefix} ({e}): run `make setup`, "
                     f"which installs them from {PDAL_DIR}/python")
    if version != PDAL_VERSION:
        _unavailable(f"the venv's PDAL bindings are PDAL {version}, not {PDAL_VERSION}: run `make setup`")
    return RealPdal(PDAL_DIR, executable, version)


#: what :func:`write_rich_cloud` writes besides the scene: header and extra dimensions
RICH_SCALES = (0.0005, 0.0005, 0.00025)
RICH_OFFSETS = (499987.5, 5399970.25, 93.0)
RICH_VLR = ("roadsigns_test", 42, b"a VLR PDAL must forward")


def write_rich_cloud(path: str, scene, crs_epsg=25833, seed: int = 0) -> None:
    """``scene`` (helpers.cloudgen) as LAS 1.4 point format 7 with everything a header may
    carry: odd scales and offsets, the CRS (unless ``crs_epsg`` is None), a user VLR, scalar
    and array extra bytes (``range_m`` f4, ``ring`` u2, ``normal`` 3 x f4), colours, user
    data, point source ids, and classes other than ground (the scene's: 1 objects, 5 trees,
    6 walls) with 5 % of the points set to class 2 at random, ground or not."""
    import laspy

    rng = np.random.default_rng(seed)
    n = len(scene)
    header = laspy.LasHeader(point_format=7, version="1.4")
    header.scales, header.offsets = np.array(RICH_SCALES), np.array(RICH_OFFSETS)
    if crs_epsg is not None:
        import pyproj

        header.add_crs(pyproj.CRS.from_epsg(crs_epsg))
    header.add_extra_dims([laspy.ExtraBytesParams("range_m", np.float32),
                           laspy.ExtraBytesParams("ring", np.uint16),
                           laspy.ExtraBytesParams("normal", "3f4")])
    header.vlrs.append(laspy.VLR(RICH_VLR[0], RICH_VLR[1], "test", RICH_VLR[2]))
    las = laspy.LasData(header)
    las.x, las.y, las.z = scene.xyz[:, 0], scene.xyz[:, 1], scene.xyz[:, 2]
    las.return_number, las.number_of_returns = scene.return_number, scene.number_of_returns
    las.intensity, las.gps_time = scene.intensity, scene.gps_time
    classes = scene.semantic.copy()
    classes[rng.random(n) < 0.05] = 2
    las.classification = classes
    las.red, las.green, las.blue = (rng.integers(0, 65536, n) for _ in range(3))
    las.user_data = rng.integers(0, 256, n)
    las.point_source_id = np.full(n, 7)
    las.range_m = rng.random(n).astype(np.float32) * 30
    las.ring = rng.integers(0, 32, n)
    las.normal = rng.normal(size=(n, 3)).astype(np.float32)
    las.write(path)


def hide_pdal(env: dict, folder: str) -> None:
    """Make ``env`` (a qgis_process environment) a QGIS without PDAL: a ``pdal`` package
    that fails to import shadows the bindings, and neither the setting's environment
    variable nor ``PATH`` leads to a ``pdal`` executable."""
    stub = os.path.join(folder, "no-pdal")
    os.makedirs(os.path.join(stub, "pdal"), exist_ok=True)
    with open(os.path.join(stub, "pdal", "__init__.py"), "w") as f:
        f.write('raise ImportError("PDAL hidden by the tests (tests/helpers/realpdal.py)")\n')
    env["PYTHONPATH"] = os.pathsep.join(p for p in (stub, env.get("PYTHONPATH", "")) if p)
    env.pop(PDAL_SETTING, None)
    path = [d for d in env.get("PATH", "").split(os.pathsep)
            if d and not os.path.isfile(os.path.join(d, "pdal"))]
    env["PATH"] = os.pathsep.join(path)


def set_provider_setting(profile: str, executable: str) -> None:
    """Set the provider setting (Processing > Options > Providers > Road sign inventory) in
    a qgis_process profile, as a user would in the options dialog."""
    ini = os.path.join(profile, "profiles", "default", "QGIS", "QGIS3.ini")
    os.makedirs(os.path.dirname(ini), exist_ok=True)
    text = open(ini).read() if os.path.exists(ini) else ""
    key = "Configuration\\" + PDAL_SETTING
    lines = [line for line in text.splitlines() if not line.startswith(key + "=")]
    if "[Processing]" not in lines:
        lines += ["", "[Processing]"]
    lines.insert(lines.index("[Processing]") + 1, f"{key}={executable}")
    with open(ini, "w") as f:
        f.write("\n".join(lines) + "\n")


@contextlib.contextmanager
def unwritable_folder(path: str) -> Iterator[str]:
    """A folder nobody may create files in, root included (``chattr +i`` where mode bits do
    not stop root); skipped where neither works."""
    os.makedirs(path, exist_ok=True)
    os.chmod(path, 0o555)
    immutable = False
    if _writable(path) and shutil.which("chattr"):
        immutable = subprocess.run(["chattr", "+i", path], capture_output=True).returncode == 0
    try:
        if _writable(path):
            pytest.skip(f"cannot make {path} unwritable here (root without chattr +i)")
        yield path
    finally:
        if immutable:
            subprocess.run(["chattr", "-i", path], check=True)
        os.chmod(path, 0o755)


def _writable(folder: str) -> bool:
    probe = os.path.join(folder, ".probe")
    try:
        with open(probe, "w"):
            pass
    except OSError:
        return False
    os.unlink(probe)
    return True


def _pdal_processes(parent: int) -> list:
    """Process ids of running ``pdal`` processes whose parent is ``parent``."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[1]) == parent and fields[0] not in "ZX" and \
                    os.path.basename(os.readlink(f"/proc/{pid}/exe")) == "pdal":
                found.append(int(pid))
        except (OSError, IndexError, ValueError):
            continue
    return found


def pdal_children() -> list:
    """Process ids of running ``pdal`` processes started by this process."""
    return _pdal_processes(os.getpid())


def orphaned_pdal() -> set:
    """Process ids of ``pdal`` processes left running by a parent that died (qgis_process
    killed on a timeout): compare before and after a run, and end the new ones."""
    return set(_pdal_processes(1))
