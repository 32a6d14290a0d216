"""Deterministic synthetic mobile-mapping scenes with known truth (dev tool, not shipped).

A scene is one road in the projected target CRS (EPSG:32633, ENU metres) with buildings,
trees, cars, poles, lamp posts, road signs of the six default classes and distractors. The
same primitives are ray cast by a simulated profiling laser scanner (``cloud.laz``) and by
an equirectangular panorama camera (``images/*.jpg``); the trajectory, image times, per-image
poses, an SBET file, the reference signs CSV and ``scene.json`` (metadata and per-image true
boxes) are written alongside, all following ``shared/CONTRACT.md``.

API: :func:`generate_scene`; CLI: ``python -m devtools.scenegen --preset tiny --seed 1 --out DIR``.
"""
from __future__ import annotations

import importlib
import os
import sys
import tempfile

os.environ.setdefault("PROJ_DATA", "/usr/share/proj")  # pyproj inside a venv needs it

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def roadsigns_geometry():
    """Import ``roadsigns.core.geometry`` (the contract's frames), making the checkout importable.

    The checkout may have any folder name; as in ``tests/conftest.py`` a symlink
    ``<tmp>/roadsigns -> checkout`` is put on ``sys.path`` when ``roadsigns`` is not importable.
    """
    try:
        return importlib.import_module("roadsigns.core.geometry")
    except ImportError:
        pass
    link_dir = tempfile.mkdtemp(prefix="scenegen-roadsigns-")
    os.symlink(REPO_ROOT, os.path.join(link_dir, "roadsigns"))
    sys.path.insert(0, link_dir)
    for name in [m for m in sys.modules if m == "roadsigns" or m.startswith("roadsigns.")]:
        del sys.modules[name]
    return importlib.import_module("roadsigns.core.geometry")


from .presets import PRESETS, Preset  # noqa: E402


def generate_scene(preset="tiny", seed=1, out_dir="scene", **options):
    """Write one scene; see :func:`devtools.scenegen.generate.generate_scene`."""
    from .generate import generate_scene as _generate

    return _generate(preset, seed, out_dir, **options)

__all__ = ["generate_scene", "PRESETS", "Preset", "roadsigns_geometry"]
