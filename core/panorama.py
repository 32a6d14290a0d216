"""Panorama images: sizes read from headers, the equirectangular check, decoding, and the
perspective views the detector runs on.

Pillow opens images lazily: ``Image.open(path).size`` reads the header only, never the
pixels, so importing thousands of panoramas stays quick. OpenCV (decoding, ``cv2.remap``)
is imported inside the functions that use it: the trajectory import does not need it.
"""
from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field
from typing import Dict, Optional, Tuple, Union

import numpy as np

from . import geometry
from .errors import InputError

#: The largest panorama read, in pixels: 32768 x 16384, a "32K" equirectangular panorama.
#: Pillow refuses images over its ``MAX_IMAGE_PIXELS`` (about 179 Mpx, a guard against
#: decompression bombs in web uploads), which 8K-16K rigs stitching at full resolution
#: exceed (20000 x 10000 is 200 Mpx): the plugin raises Pillow's limit deliberately to this
#: bound when it reads panoramas (never lowers it) and refuses larger images with a message.
MAX_PANORAMA_PIXELS = 32768 * 16384
MAX_PANORAMA_SIZE = "32768 x 16384"
#: The upward views (``detectsigns``' ``UPWARD_VIEWS``): two views of this width at this
#: pitch, straight ahead and behind, over the road where gantries and overhead panels are
#: (640 x 384 views: elevations +4..+66 deg at their centres; square ones -10..+80). Two
#: rather than a ring of six since 28 November: a view to the side cuts the signs beside the
#: road, which the horizon views see whole (models/README.md, "Upward views: the pair, on by
#: default").
UPWARD_PITCH_DEG = 35.0
UPWARD_HFOV_DEG = 90.0
#: The whole upward ring (six views at the same pitch and width), which training cuts.
UPWARD_RING_VIEWS = 6
#: Whether detection also looks upwards by default: yes since 28 November. On five held-out
#: streets the pair raised the gantry panels found in one panorama from 0.856 to 0.909 and
#: the signs a panorama can give from 0.958 to 0.970, precision 0.971 -> 0.970, for 1.22 x the
#: detection time (models/README.md, "Upward views: the pair, on by default"). The chain
#: found every gantry panel without them, from stations farther off; a drive with panoramas
#: far apart does not.
DEFAULT_UPWARD_VIEWS = True
#: Width (deg) of each view of the horizon ring.
HORIZON_HFOV_DEG = 80.0
#: Two more horizon views, straight ahead and behind, of this width: 1.5 x the pixels per
#: degree of the 80 deg ring on average, 1.67 x at the views' centres (a 4096 px panorama's
#: own density: 0.98 x, against the ring's 0.59 x), for small far signs (``detectsigns``'
#: ``FORE_AFT_VIEWS``).
FORE_AFT_HFOV_DEG = HORIZON_HFOV_DEG / 1.5
#: Whether detection adds them by default: yes since 25 November. Real signs need the pixels:
#: GTSDB 500-599 at the ring's density found 0.817 of the signs (second look on), with the
#: fore-and-aft density merged in 0.930; 376 held-out real signs pasted 0.537 and 0.691; five
#: held-out generated streets 0.879 and 0.906 per panorama, precision within 0.01 on all
#: three; 1.24 x the detection time (models/README.md, "Pixels for real signs").
DEFAULT_FORE_AFT_VIEWS = True
#: The horizon rings detection can cut: number of views -> yaw of the first (deg, 0 ahead).
#: 8 views overlap by 35 deg. 6 views overlap by 20 deg and are turned by 30 deg, so that
#: the seams ahead and behind fall inside the fore-and-aft views: 0.8-0.87 x the detection's
#: time, and on five held-out streets P / R 0.982 / 0.948 -> 0.988 / 0.946 in single
#: panoramas, 14-20 px 0.894 -> 0.882; through the chain, on three held-out streets with a
#: panorama every 5 m, the same 137 signs, and on drive1k's truth stretch one false sign more
#: (models/README.md, "A ring of six horizon views").
HORIZON_RINGS = {8: 0.0, 6: 30.0}
#: The horizon seen as one equirectangular band instead of a ring (:class:`BandView`;
#: ``ViewSet.default(horizon_views=HORIZON_BAND)``): 3264 x 448 px, 8.5 px a degree (the
#: 80 deg views: 6.7 at their centres, 11.3 at their sides), +-26.4 deg of elevation (the
#: views: +-21 to +-27), 12 deg of margin at each end. 4.4 views' pixels for the ring's 8;
#: measured in models/README.md, "The horizon as one band".
HORIZON_BAND = "band"
HORIZON_BAND_SIZE_PX = (3264, 448)
HORIZON_BAND_MARGIN_DEG = 12.0
#: What ``ViewSet.default``'s ``horizon_views`` takes, in the order of ``detectsigns``'
#: ``HORIZON_VIEWS`` options: the rings, then the band.
HORIZON_CHOICES = tuple(HORIZON_RINGS) + (HORIZON_BAND,)


def horizon_choice(text: str) -> Union[int, str]:
    """The :data:`HORIZON_CHOICES` entry written as ``text`` (``"8"``, ``"6"``, ``"band"``);
    ``ValueError`` for another."""
    value: Union[int, str] = int(text) if str(text).isdigit() else str(text)
    if value not in HORIZON_CHOICES:
        raise ValueError("horizon views {!r}: expected one of {}".format(text, ", ".join(map(str, HORIZON_CHOICES))))
    return value
#: The ring ``ViewSet.default`` cuts unless told otherwise (``detectsigns``' ``HORIZON_VIEWS``).
DEFAULT_HORIZON_VIEWS = 8


def boxes_from_seam(boxes_px: np.ndarray, width_px: float) -> np.ndarray:
    """Panorama boxes ``(n, 4)`` shifted by whole widths so that ``u0`` is in [0, W): the
    detection layers' form (``u1`` past W across the seam; docs/formats.md, boxes). In place;
    returns them."""
    if len(boxes_px):
        shift = np.floor(boxes_px[:, 0] / width_px) * width_px
        boxes_px[:, 0] -= shift
        boxes_px[:, 2] -= shift
    return boxes_px


def allow_large_panoramas() -> None:
    """Raise Pillow's decompression-bomb limit to :data:`MAX_PANORAMA_PIXELS` (process-wide)."""
    from PIL import Image

    if Image.MAX_IMAGE_PIXELS is not None and Image.MAX_IMAGE_PIXELS < MAX_PANORAMA_PIXELS:
        Image.MAX_IMAGE_PIXELS = MAX_PANORAMA_PIXELS


def read_image_size(path: str) -> Tuple[int, int]:
    """``(width_px, height_px)`` from the image header; :class:`InputError` if unreadable
    or larger than :data:`MAX_PANORAMA_PIXELS`."""
    from PIL import Image, UnidentifiedImageError

    allow_large_panoramas()
    try:
        with Image.open(path) as image:
            width_px, height_px = int(image.size[0]), int(image.size[1])
    except FileNotFoundError:
        raise InputError("Panorama not found: {path}", path=path)
    except Image.DecompressionBombError:
        raise InputError("The panorama {path} has more pixels than the {limit} the plugin reads",
                         path=path, limit=MAX_PANORAMA_SIZE)
    except (UnidentifiedImageError, OSError, ValueError, SyntaxError, EOFError) as e:
        raise InputError("Cannot read the panorama {path}: expected a JPEG or PNG image ({error})",
                         path=path, error=str(e))
    if width_px * height_px > MAX_PANORAMA_PIXELS:
        raise InputError("The panorama {path} is {width} x {height} pixels, more than the {limit} the "
                         "plugin reads", path=path, width=width_px, height=height_px,
                         limit=MAX_PANORAMA_SIZE)
    return width_px, height_px


def check_equirectangular(path: str, width_px: int, height_px: int) -> None:
    """Raise :class:`InputError` unless the image is W x H with W = 2H."""
    if width_px != 2 * height_px:
        raise InputError("The panorama {path} is {width} x {height} pixels: an equirectangular "
                         "panorama must be twice as wide as it is high",
                         path=path, width=width_px, height=height_px)


# --- pixels and perspective views -----------------------------------------------------
#
# A perspective view is a pinhole camera at the panorama centre, looking along the ray of
# azimuth ``yaw_deg`` (the panorama azimuth: 0 = centre column, clockwise +) and
# elevation ``pitch_deg`` (up +), without roll. Its image has x to the right and y down,
# square pixels, continuous coordinates with pixel centres at +0.5 (as the panorama's).
# In the panorama frame (x forward, y right, z down) its axes are
#   forward = angles_to_ray(yaw, pitch),  right = angles_to_ray(yaw + 90 deg, 0),
#   down = forward x right,
# and view pixel (x, y) sees the ray  forward + (x - w/2)/f * right + (y - h/2)/f * down,
# f = (w/2) / tan(hfov/2). Rays go to panorama pixels through ``core.geometry``.

#: Box edges are sampled at this many points each when mapped to the panorama: straight
#: view edges bend in the equirectangular image, and the extremes of azimuth and elevation
#: over a box (away from the poles) lie on its boundary.
BOX_EDGE_SAMPLES = 33


def read_panorama(path: str, require_equirectangular: bool = True) -> np.ndarray:
    """Decode a panorama to an ``H x W x 3`` BGR uint8 array (OpenCV's order).

    :class:`InputError` naming the file when it is missing, not a decodable image, or (by
    default) not W = 2H. Reads through ``np.fromfile`` so non-ASCII paths work on Windows.
    """
    import cv2

    if not os.path.isfile(path):
        raise InputError("Panorama not found: {path}", path=path)
    try:
        data = np.fromfile(path, dtype=np.uint8)
        image = cv2.imdecode(data, cv2.IMREAD_COLOR) if data.size else None
    except (OSError, cv2.error) as e:
        raise InputError("Cannot read the panorama {path}: {error}", path=path, error=str(e))
    if image is None:
        raise InputError("Cannot read the panorama {path}: the file is not a JPEG or PNG "
                         "image or is corrupt", path=path)
    if require_equirectangular:
        check_equirectangular(path, image.shape[1], image.shape[0])
    return image


class _CutImage:
    """What a view and the horizon band share: the image cut from a panorama through cached
    ``cv2.remap`` maps (:func:`_float_maps` of the class's ``pixel_to_ray``), and which boxes
    touch its borders (the margin from the class's ``_edge_margin_px``)."""

    width_px: int
    height_px: int

    def _edge_margin_px(self, margin_px: Optional[float]) -> float:
        raise NotImplementedError

    def remap_maps(self, pano_width_px: int, pano_height_px: int):
        """``cv2.remap`` maps (fixed-point pair) cutting this image from a W x H panorama; cached."""
        return _remap_maps(self, int(pano_width_px), int(pano_height_px))

    def cut(self, pano: np.ndarray, cached: bool = True) -> np.ndarray:
        """The image from a panorama array (no reduction; see :meth:`ViewSet.cut_all`).
        ``cached=False``: the maps are made for this cut alone and not kept (a view cut once,
        such as a zoomed look's tile)."""
        import cv2

        if cached:
            m1, m2 = self.remap_maps(pano.shape[1], pano.shape[0])
        else:
            m1, m2 = _float_maps(self, pano.shape[1], pano.shape[0])
        # BORDER_WRAP joins the columns across the +-180 deg seam; rows never leave the image
        # (map_y is clamped), so wrapping never joins top and bottom.
        return cv2.remap(pano, m1, m2, cv2.INTER_LINEAR, borderMode=cv2.BORDER_WRAP)

    def touches_edge(self, boxes_xyxy, margin_px: Optional[float] = None) -> np.ndarray:
        """Boxes within ``margin_px`` (default 1 % of the image's size, at least 2) of the
        border: likely cut by the image's edge."""
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        m = self._edge_margin_px(margin_px)
        return self.touches_side(b, m) | (b[:, 1] <= m) | (b[:, 3] >= self.height_px - m)

    def touches_side(self, boxes_xyxy, margin_px: Optional[float] = None) -> np.ndarray:
        """Boxes within ``margin_px`` (as :meth:`touches_edge`) of the left or right border."""
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        m = self._edge_margin_px(margin_px)
        return (b[:, 0] <= m) | (b[:, 2] >= self.width_px - m)


@dataclass(frozen=True)
class PerspectiveView(_CutImage):
    """One pinhole view cut from the panorama (see the module comment for the convention).

    ``stretch``: how many times the view's horizontal focal length (pixels a radian across,
    :attr:`focal_px`, set by ``hfov_deg`` and ``width_px``) is its vertical one
    (:attr:`focal_y_px`): 1 for square pixels; 2 shows a sign seen edge-on twice as wide,
    relative to its height, as the panorama does (``bench_detector``'s side views)."""

    yaw_deg: float
    pitch_deg: float = 0.0
    hfov_deg: float = 80.0
    width_px: int = 640
    height_px: int = 640
    stretch: float = 1.0
    #: A view is fitted into the detector's input size (see :class:`BandView`).
    own_size = False

    @property
    def focal_px(self) -> float:
        """Horizontal focal length, in pixels."""
        return 0.5 * self.width_px / np.tan(np.radians(0.5 * self.hfov_deg))

    @property
    def focal_y_px(self) -> float:
        """Vertical focal length, in pixels: :attr:`focal_px` over ``stretch``."""
        return self.focal_px / self.stretch

    @property
    def vfov_deg(self) -> float:
        return float(2.0 * np.degrees(np.arctan(0.5 * self.height_px / self.focal_y_px)))

    def axes(self) -> np.ndarray:
        """``3 x 3`` matrix whose columns are the view's right, down and forward rays in the
        panorama frame (an OpenCV camera frame: maps camera vectors to panorama vectors)."""
        yaw, pitch = np.radians(self.yaw_deg), np.radians(self.pitch_deg)
        forward = geometry.angles_to_ray(yaw, pitch)
        right = geometry.angles_to_ray(yaw + 0.5 * np.pi, 0.0)
        return np.stack([right, np.cross(forward, right), forward], axis=1)

    def pixel_to_ray(self, x_px, y_px) -> np.ndarray:
        """Continuous view pixel(s) -> unit rays ``(..., 3)`` in the panorama frame."""
        fx, fy = self.focal_px, self.focal_y_px
        cam = np.stack(np.broadcast_arrays((np.asarray(x_px, float) - 0.5 * self.width_px) / fx,
                                           (np.asarray(y_px, float) - 0.5 * self.height_px) / fy,
                                           1.0), axis=-1)
        d = cam @ self.axes().T
        return d / np.linalg.norm(d, axis=-1, keepdims=True)

    def ray_to_pixel(self, d):
        """Panorama-frame ray(s) -> continuous view pixel ``(x, y)`` and an in-front mask."""
        cam = np.asarray(d, float) @ self.axes()
        z = cam[..., 2]
        zs = np.where(z > 0, z, np.nan)
        fx, fy = self.focal_px, self.focal_y_px
        return 0.5 * self.width_px + fx * cam[..., 0] / zs, 0.5 * self.height_px + fy * cam[..., 1] / zs, z > 0

    def centre_u_px(self, pano_width_px: int) -> float:
        """Panorama column of the view's forward ray, in [0, W)."""
        return float(np.mod((self.yaw_deg / 360.0 + 0.5) * pano_width_px, pano_width_px))

    def boxes_to_pano(self, boxes_xyxy, pano_width_px: int, pano_height_px: int) -> np.ndarray:
        """View boxes ``(n, 4)`` x0, y0, x1, y1 -> panorama boxes ``(n, 4)`` u0, v0, u1, v1.

        The detections layer's form: u0 in [0, W) and u1 > u0, unwrapped past W for a box across
        the +-180 deg seam. A box holding the zenith (nadir) spans all columns and reaches
        row 0 (row H).
        """
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        W, H = pano_width_px, pano_height_px
        t = np.linspace(0.0, 1.0, BOX_EDGE_SAMPLES)
        x0, y0, x1, y1 = (b[:, k:k + 1] for k in range(4))
        xs = np.concatenate([x0 + t * (x1 - x0), np.broadcast_to(x1, (len(b), t.size)),
                             x1 + t * (x0 - x1), np.broadcast_to(x0, (len(b), t.size))], axis=1)
        ys = np.concatenate([np.broadcast_to(y0, (len(b), t.size)), y0 + t * (y1 - y0),
                             np.broadcast_to(y1, (len(b), t.size)), y1 + t * (y0 - y1)], axis=1)
        u, v = geometry.ray_to_pixel(self.pixel_to_ray(xs, ys), W, H)
        # Unwrap the columns around the view's centre column: a view sees less than 180 deg
        # either side of it, so this makes the boundary continuous.
        uc = self.centre_u_px(W)
        u = uc + np.mod(u - uc + 0.5 * W, W) - 0.5 * W
        out = boxes_from_seam(np.stack([u.min(axis=1), v.min(axis=1), u.max(axis=1), v.max(axis=1)], axis=1), W)
        for pole, row in ((np.array([0.0, 0.0, -1.0]), 0.0), (np.array([0.0, 0.0, 1.0]), float(H))):
            px, py, front = self.ray_to_pixel(pole)
            if front:
                inside = (b[:, 0] <= px) & (px <= b[:, 2]) & (b[:, 1] <= py) & (py <= b[:, 3])
                out[inside, 0], out[inside, 2] = 0.0, float(W)
                out[inside, 1 if row == 0.0 else 3] = row
        return out

    def centrality(self, boxes_xyxy) -> np.ndarray:
        """1 at the view's centre, 0 at the middle of its left/right edge (angle of the box
        centre's ray off the forward axis over hfov/2; negative in the corners)."""
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        d = self.pixel_to_ray(0.5 * (b[:, 0] + b[:, 2]), 0.5 * (b[:, 1] + b[:, 3]))
        off = np.degrees(np.arccos(np.clip(d @ self.axes()[:, 2], -1.0, 1.0)))
        return 1.0 - off / (0.5 * self.hfov_deg)

    def _edge_margin_px(self, margin_px: Optional[float]) -> float:
        return max(2.0, 0.01 * max(self.width_px, self.height_px)) if margin_px is None else margin_px

    @property
    def looks_up(self) -> bool:
        """Whether the view is pitched above the horizon (the upward views)."""
        return self.pitch_deg > 0.0

    def max_density_px_per_rad(self) -> float:
        """Highest sampling density of the view along its horizontal (at its left/right edge)."""
        return self.focal_px / np.cos(np.radians(0.5 * self.hfov_deg)) ** 2


@dataclass(frozen=True)
class BandView(_CutImage):
    """The horizon as one equirectangular band, which the detector runs on whole: the
    panorama's rows within ``vfov_deg / 2`` of the horizon, all 360 deg of azimuth and
    ``margin_deg`` more at each end (the columns wrap, so a sign across the +-180 deg seam
    is whole at one end), at one density in both directions. Column ``x`` (continuous, 0 at
    the left edge) is azimuth ``x / density - 180 - margin`` deg, row ``y`` elevation
    ``(height / 2 - y) / density`` deg: a box maps to the panorama by scaling alone. Within
    +-27 deg of the horizon the band stretches a sign across by at most 1 / cos 27 deg = 1.12,
    less than a perspective view of 80 deg does at its sides (1.70). The sides are multiples
    of 32, the detector's stride. A sign in a margin is seen twice, once at each end: the
    copies merge like the boxes of overlapping views, the one farther from an end ranked
    first (:meth:`centrality`)."""

    width_px: int = HORIZON_BAND_SIZE_PX[0]
    height_px: int = HORIZON_BAND_SIZE_PX[1]
    margin_deg: float = HORIZON_BAND_MARGIN_DEG
    yaw_deg = 0.0
    pitch_deg = 0.0
    looks_up = False
    #: The detector runs the band at its own size (``Detector.detect_many(own_size=True)``).
    own_size = True

    @property
    def hfov_deg(self) -> float:
        return 360.0 + 2.0 * self.margin_deg

    @property
    def density_px_per_deg(self) -> float:
        return self.width_px / self.hfov_deg

    @property
    def vfov_deg(self) -> float:
        return self.height_px / self.density_px_per_deg

    def pixel_to_angles_deg(self, x_px, y_px):
        """Continuous band pixel(s) -> (azimuth, elevation) in degrees (azimuth unwrapped)."""
        d = self.density_px_per_deg
        return (np.asarray(x_px, float) / d - 180.0 - self.margin_deg,
                (0.5 * self.height_px - np.asarray(y_px, float)) / d)

    def pixel_to_ray(self, x_px, y_px) -> np.ndarray:
        """Continuous band pixel(s) -> unit rays ``(..., 3)`` in the panorama frame."""
        alpha, eps = self.pixel_to_angles_deg(x_px, y_px)
        return geometry.angles_to_ray(np.radians(alpha), np.radians(eps))

    def ray_to_pixel(self, d):
        """Panorama-frame ray(s) -> continuous band pixel ``(x, y)`` (the copy in the core
        360 deg, not the margins') and a mask that is true everywhere (no ray is behind)."""
        alpha, eps = (np.degrees(a) for a in geometry.ray_to_angles_rad(d))
        k = self.density_px_per_deg
        return (alpha + 180.0 + self.margin_deg) * k, 0.5 * self.height_px - eps * k, np.ones(np.shape(alpha), bool)

    def centre_u_px(self, pano_width_px: int) -> float:
        """Panorama column of azimuth 0 (straight ahead), as for a view."""
        return 0.5 * float(pano_width_px)

    def boxes_to_pano(self, boxes_xyxy, pano_width_px: int, pano_height_px: int) -> np.ndarray:
        """Band boxes ``(n, 4)`` -> panorama boxes ``(n, 4)`` in the detections layer's form
        (as :meth:`PerspectiveView.boxes_to_pano`): a linear map of both sides."""
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        s = pano_width_px / 360.0 / self.density_px_per_deg       # panorama px per band px
        u0 = b[:, 0] * s - self.margin_deg * pano_width_px / 360.0
        u1 = b[:, 2] * s - self.margin_deg * pano_width_px / 360.0
        v_top = 0.5 * pano_height_px - 0.5 * self.height_px * s
        out = np.stack([u0, v_top + b[:, 1] * s, u1, v_top + b[:, 3] * s], axis=1)
        return boxes_from_seam(out, pano_width_px)

    def centrality(self, boxes_xyxy) -> np.ndarray:
        """0 at either end of the band, rising to 1 at ``2 * margin_deg`` from it: of a sign's
        two copies, the one that is not in a margin ranks first."""
        b = np.asarray(boxes_xyxy, float).reshape(-1, 4)
        x = 0.5 * (b[:, 0] + b[:, 2])
        from_end_deg = np.minimum(x, self.width_px - x) / self.density_px_per_deg
        return np.clip(from_end_deg / (2.0 * self.margin_deg), 0.0, 1.0)

    def _edge_margin_px(self, margin_px: Optional[float]) -> float:
        """1 % of the band's height (its width would be 33 px), at least 2."""
        return max(2.0, 0.01 * self.height_px) if margin_px is None else margin_px

    def max_density_px_per_rad(self) -> float:
        return float(np.degrees(1.0) * self.density_px_per_deg)


def _float_maps(view, W: int, H: int):
    """``cv2.remap`` maps (float x, float y) cutting ``view`` from a W x H panorama."""
    ys, xs = np.mgrid[0:view.height_px, 0:view.width_px].astype(float) + 0.5
    u, v = geometry.ray_to_pixel(view.pixel_to_ray(xs, ys), W, H)
    map_x = (u - 0.5).astype(np.float32)  # cv2 samples pixel centres at integer coordinates
    map_y = np.clip(v - 0.5, 0.0, H - 1.0).astype(np.float32)
    return map_x, map_y


@functools.lru_cache(maxsize=48)
def _remap_maps(view, W: int, H: int):
    import cv2

    map_x, map_y = _float_maps(view, W, H)
    return cv2.convertMaps(map_x, map_y, cv2.CV_16SC2)


@dataclass(frozen=True)
class ViewSet:
    """The perspective views a panorama is cut into (hashable: cached maps key on it)."""

    views: tuple = field(default_factory=tuple)

    @classmethod
    def ring(cls, n_views: int = 8, pitch_deg: float = 0.0, hfov_deg: float = 80.0,
             size_px=640, first_yaw_deg: float = 0.0) -> "ViewSet":
        """``n_views`` views at equal yaw steps from ``first_yaw_deg`` (0 = forward), one pitch.

        ``size_px``: an int (square) or ``(width, height)``.
        """
        w, h = (size_px, size_px) if isinstance(size_px, (int, float, np.number)) else size_px
        return cls(tuple(PerspectiveView(float(first_yaw_deg + k * 360.0 / n_views), float(pitch_deg),
                                         float(hfov_deg), int(w), int(h)) for k in range(n_views)))

    @classmethod
    def default(cls, size_px=640, upward: Optional[bool] = None,
                fore_aft: Optional[bool] = None, horizon_views: Union[int, str] = DEFAULT_HORIZON_VIEWS
                ) -> "ViewSet":
        """Horizon ring: ``horizon_views`` views of 80 deg across (a key of
        :data:`HORIZON_RINGS`; 8: 35 deg overlap; square views span elevations -40..+40 deg at
        their centres, about +-33 deg at their edges, 640 x 384 views +-26.7 deg); for overhead
        and gantry signs, ``upward``: two views ahead and behind of :data:`UPWARD_HFOV_DEG` at
        pitch :data:`UPWARD_PITCH_DEG`. ``size_px``: the detector's input size, an int or
        ``(width, height)``; ``upward`` None: :data:`DEFAULT_UPWARD_VIEWS`. ``fore_aft`` (None:
        :data:`DEFAULT_FORE_AFT_VIEWS`) adds two views of :data:`FORE_AFT_HFOV_DEG` ahead and
        behind, after the horizon ring. ``horizon_views`` :data:`HORIZON_BAND`: the horizon as
        one :class:`BandView` instead of a ring (the detector must take images of any size).
        ``ValueError`` for a ring not in :data:`HORIZON_RINGS`, nor the band."""
        if horizon_views == HORIZON_BAND:
            views = cls((BandView(),))
        elif horizon_views in HORIZON_RINGS:
            views = cls.ring(horizon_views, 0.0, HORIZON_HFOV_DEG, size_px,
                             first_yaw_deg=HORIZON_RINGS[horizon_views])
        else:
            raise ValueError("a horizon ring of {} views: expected one of {} or {!r}".format(
                horizon_views, sorted(HORIZON_RINGS), HORIZON_BAND))
        if fore_aft if fore_aft is not None else DEFAULT_FORE_AFT_VIEWS:
            views = views + cls.ring(2, 0.0, FORE_AFT_HFOV_DEG, size_px)
        if upward if upward is not None else DEFAULT_UPWARD_VIEWS:
            views = views + cls.ring(2, UPWARD_PITCH_DEG, UPWARD_HFOV_DEG, size_px)
        return views

    @classmethod
    def training(cls, size_px=640) -> "ViewSet":
        """What training cuts from a panorama: the default views (the fore-and-aft pair as
        :data:`DEFAULT_FORE_AFT_VIEWS` says) and the whole upward ring of
        :data:`UPWARD_RING_VIEWS`, whose side views show signs cut at their edges too."""
        return (cls.default(size_px, upward=False)
                + cls.ring(UPWARD_RING_VIEWS, UPWARD_PITCH_DEG, UPWARD_HFOV_DEG, size_px))

    def __add__(self, other: "ViewSet") -> "ViewSet":
        return ViewSet(self.views + other.views)

    def __len__(self) -> int:
        return len(self.views)

    def __iter__(self):
        return iter(self.views)

    def __getitem__(self, index: int) -> PerspectiveView:
        return self.views[index]

    def working_width(self, pano_width_px: int) -> int:
        """Width the panorama is reduced to before cutting, so views of 8K panoramas are not
        aliased: W / k for the largest whole k that keeps at least the densest view's
        sampling (INTER_AREA by a whole factor is fast); W when k = 1."""
        need = 2.0 * np.pi * max(v.max_density_px_per_rad() for v in self.views)
        k = int(pano_width_px // need)
        return int(pano_width_px) if k < 2 else int(pano_width_px) // k

    def prepare(self, pano: np.ndarray, width_px: Optional[int] = None) -> np.ndarray:
        """The panorama reduced to ``width_px`` (default :meth:`working_width`, the densest
        view's) with ``INTER_AREA``; the panorama itself when that is its width.

        Boxes map to the panorama by angles, so they come back in the original pixels
        whatever the reduction: pass the original W, H to :meth:`PerspectiveView.boxes_to_pano`.
        """
        import cv2

        W, H = pano.shape[1], pano.shape[0]
        w = self.working_width(W) if width_px is None else int(width_px)
        if w == W:
            return pano
        return cv2.resize(pano, (w, max(1, round(w * H / W))), interpolation=cv2.INTER_AREA)

    def cut_all(self, pano: np.ndarray):
        """Every view's image, in order (a generator). Each view is cut from the panorama
        reduced to its own working width (that of a set of itself alone), so denser views
        (ahead and behind) do not leave the others aliased on large panoramas; each
        reduction is made once."""
        reduced: Dict[int, np.ndarray] = {}
        for view in self.views:
            w = ViewSet((view,)).working_width(pano.shape[1])
            if w not in reduced:
                reduced[w] = self.prepare(pano, w)
            yield view.cut(reduced[w])
