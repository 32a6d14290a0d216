"""Pictures of one sign from the panoramas that saw it, for the review panel: a chip from
each panorama (best first), and a wider view around the sign on demand.

Each picture is a perspective view (:class:`.panorama.PerspectiveView`, undistorted, as the
review chips of :mod:`.review`) centred on the ray from the panorama centre to the sign's
centre, found from the stations layer's pose (position and quaternion), so it needs no
detection box: it works for every panorama in ``source_images`` and for signs found in the
cloud alone. The order is "best first": the sign's ``best_image``, then the others by
range over the cosine of the incidence on the sign's face (as refine picks ``best_image``).
"""
from __future__ import annotations

import math
import os
from collections import OrderedDict
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import geometry
from .panorama import PerspectiveView, read_panorama
from .review import CHIP_SIZE_PX
from .reviewstate import image_names

#: the size (m) of a sign whose layer gives none
DEFAULT_PANEL_SIZE_M = 0.8
#: stations farther than this from a sign give no chip
MAX_VIEW_RANGE_M = 80.0
#: a sign with no source images (found in the cloud alone) is shown from the stations
#: within this range in front of its face
NEARBY_RANGE_M = 40.0
CONTEXT_HFOV_DEG = 90.0


@dataclass(frozen=True)
class SignView:
    """One panorama's picture of a sign: the station's image, the view and how well it
    sees the sign (range in metres, incidence on the face in degrees; NaN when the sign
    has no azimuth)."""

    image: str
    path: str
    view: PerspectiveView
    range_m: float
    incidence_deg: float
    best: bool

    @property
    def quality(self) -> float:
        """Range over the cosine of the incidence (smaller is better), as refine's best view."""
        cos_inc = math.cos(math.radians(self.incidence_deg)) if math.isfinite(self.incidence_deg) else 1.0
        return self.range_m / max(cos_inc, 0.1)


def _number(value, default: float) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    return number if math.isfinite(number) and number > 0 else default


def face_normal(azimuth_deg) -> Optional[np.ndarray]:
    """The horizontal unit normal (ENU) of a face looking towards ``azimuth_deg`` (grid)."""
    try:
        a = math.radians(float(azimuth_deg))
    except (TypeError, ValueError):
        return None
    if not math.isfinite(a):
        return None
    return np.array([math.sin(a), math.cos(a), 0.0])


def panorama_path(station: Dict, folder: Optional[str]) -> str:
    """Where a station's panorama is: in ``folder`` when given, else the stations layer's
    ``path`` (what the import wrote), else its ``image`` as it is."""
    if folder:
        return os.path.join(folder, str(station["image"]))
    return str(station.get("path") or station["image"])


def _view_towards(sign_xyz: np.ndarray, station: Dict, size_m: float, margin_frac: float,
                  size_px: Tuple[int, int], hfov_deg: Optional[float] = None) -> Tuple[PerspectiveView, float]:
    centre = np.array([float(station["x"]), float(station["y"]), float(station["z"])])
    R = geometry.matrix_from_quat_wxyz([float(station[k]) for k in ("qw", "qx", "qy", "qz")])
    d, rng = geometry.world_to_pano_ray(sign_xyz, centre, R)
    alpha, eps = geometry.ray_to_angles_rad(d)
    if hfov_deg is None:
        half = 0.5 * size_m * (1.0 + 2.0 * margin_frac)
        hfov_deg = float(np.clip(2.0 * math.degrees(math.atan2(half, max(float(rng), 0.1))), 2.0, 120.0))
    view = PerspectiveView(float(np.degrees(alpha)), float(np.degrees(eps)), hfov_deg, size_px[0], size_px[1])
    return view, float(rng)


def sign_views(sign: Dict, stations: Sequence[Dict], folder: Optional[str] = None, max_views: int = 8,
               size_px: int = CHIP_SIZE_PX, margin_frac: float = 0.5) -> List[SignView]:
    """The chip views of ``sign`` (a sign layer record: ``x, y, z`` and, when known,
    ``width``, ``panel_height``, ``azimuth``, ``source_images``, ``best_image``) from the
    ``stations`` (stations layer records) of its source images, best first, at most
    ``max_views``. A sign without source images is seen from the stations within
    :data:`NEARBY_RANGE_M` in front of its face (or around it, without an azimuth)."""
    xyz = np.array([float(sign["x"]), float(sign["y"]), float(sign["z"])])
    size_m = max(_number(sign.get("width"), DEFAULT_PANEL_SIZE_M), _number(sign.get("panel_height"), 0.0))
    normal = face_normal(sign.get("azimuth"))
    by_image = {str(s["image"]): s for s in stations}
    wanted = image_names(sign.get("source_images"))
    best = str(sign.get("best_image") or "")
    if wanted:
        chosen = [by_image[name] for name in wanted if name in by_image]
    else:
        chosen = []
        for station in stations:
            to = np.array([float(station["x"]), float(station["y"]), float(station["z"])]) - xyz
            dist = float(np.linalg.norm(to))
            if dist <= NEARBY_RANGE_M and (normal is None or float(np.dot(to, normal)) > 0):
                chosen.append(station)
    views = []
    for station in chosen:
        view, rng = _view_towards(xyz, station, size_m, margin_frac, (size_px, size_px))
        if rng > MAX_VIEW_RANGE_M and str(station["image"]) != best:
            continue
        incidence = math.nan
        if normal is not None and rng > 0:
            to = (np.array([float(station[k]) for k in ("x", "y", "z")]) - xyz) / rng
            incidence = math.degrees(math.acos(float(np.clip(np.dot(to, normal), -1.0, 1.0))))
        views.append(SignView(str(station["image"]), panorama_path(station, folder), view, rng, incidence,
                              str(station["image"]) == best))
    views.sort(key=lambda v: (not v.best, v.quality))
    return views[:max_views]


def context_view(sign: Dict, station: Dict, folder: Optional[str] = None, width_px: int = 960,
                 height_px: int = 540, hfov_deg: float = CONTEXT_HFOV_DEG
                 ) -> Tuple[SignView, Tuple[float, float, float, float]]:
    """A wide view from ``station`` centred on the sign, and the sign's box in it
    (x0, y0, x1, y1 view pixels: its panel, ``width`` x ``panel_height`` across the face)."""
    xyz = np.array([float(sign["x"]), float(sign["y"]), float(sign["z"])])
    view, rng = _view_towards(xyz, station, 0.0, 0.0, (width_px, height_px), hfov_deg)
    half_w = 0.5 * _number(sign.get("width"), DEFAULT_PANEL_SIZE_M)
    half_h = 0.5 * _number(sign.get("panel_height"), 2 * half_w)
    normal = face_normal(sign.get("azimuth"))
    if normal is None:  # face the station
        to = np.array([float(station[k]) for k in ("x", "y", "z")]) - xyz
        normal = np.array([to[0], to[1], 0.0]) / max(float(np.hypot(to[0], to[1])), 1e-9)
    across = np.array([normal[1], -normal[0], 0.0])
    corners = np.array([xyz + sx * half_w * across + sz * half_h * np.array([0.0, 0.0, 1.0])
                        for sx in (-1, 1) for sz in (-1, 1)])
    centre = np.array([float(station[k]) for k in ("x", "y", "z")])
    R = geometry.matrix_from_quat_wxyz([float(station[k]) for k in ("qw", "qx", "qy", "qz")])
    d, _ = geometry.world_to_pano_ray(corners, centre, R)
    x, y, front = view.ray_to_pixel(d)
    box = (float(np.nanmin(x)), float(np.nanmin(y)), float(np.nanmax(x)), float(np.nanmax(y))) \
        if np.all(front) else (math.nan,) * 4
    return SignView(str(station["image"]), panorama_path(station, folder), view, rng, math.nan,
                    str(station["image"]) == str(sign.get("best_image") or "")), box


class PanoramaCache:
    """The last few decoded panoramas (reading one is the slow part of cutting a view)."""

    def __init__(self, size: int = 3):
        self.size = size
        self._images: "OrderedDict[str, np.ndarray]" = OrderedDict()

    def get(self, path: str) -> np.ndarray:
        """The panorama at ``path`` (BGR); :class:`~.errors.InputError` when unreadable."""
        if path in self._images:
            self._images.move_to_end(path)
            return self._images[path]
        image = read_panorama(path)
        self._images[path] = image
        while len(self._images) > self.size:
            self._images.popitem(last=False)
        return image

    def cut(self, view: SignView) -> np.ndarray:
        """The picture of ``view`` (BGR uint8)."""
        return view.view.cut(self.get(view.path))
