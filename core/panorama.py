"""Panorama image files: sizes read from headers, checks of the equirectangular shape.

Pillow opens images lazily: ``Image.open(path).size`` reads the header only, never the
pixels, so importing thousands of panoramas stays quick.
"""
from __future__ import annotations

from typing import Tuple

from .errors import InputError


def read_image_size(path: str) -> Tuple[int, int]:
    """``(width_px, height_px)`` from the image header; :class:`InputError` if unreadable."""
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as image:
            return int(image.size[0]), int(image.size[1])
    except FileNotFoundError:
        raise InputError("Panorama not found: {path}", path=path)
    except (UnidentifiedImageError, OSError, ValueError) as e:
        raise InputError("Cannot read the panorama {path}: expected a JPEG or PNG image ({error})",
                         path=path, error=str(e))


def check_equirectangular(path: str, width_px: int, height_px: int) -> None:
    """Raise :class:`InputError` unless the image is W x H with W = 2H."""
    if width_px != 2 * height_px:
        raise InputError("The panorama {path} is {width} x {height} pixels: an equirectangular "
                         "panorama must be twice as wide as it is high",
                         path=path, width=width_px, height=height_px)
