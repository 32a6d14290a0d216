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

import os

os.environ.setdefault("PROJ_DATA", "/usr/share/proj")  # pyproj inside a venv needs it



def roadsigns_geometry():
    """``roadsigns.core.geometry`` (the contract's frames) from this checkout."""
    from .. import import_roadsigns
    return import_roadsigns("roadsigns.core.geometry")


from .presets import PRESETS, Preset  # noqa: E402


def generate_scene(preset="tiny", seed=1, out_dir="scene", **options):
    """Write one scene; see :func:`devtools.scenegen.generate.generate_scene`."""
    from .generate import generate_scene as _generate

    return _generate(preset, seed, out_dir, **options)

__all__ = ["generate_scene", "PRESETS", "Preset", "roadsigns_geometry"]
