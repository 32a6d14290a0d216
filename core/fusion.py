"""Image signs + cloud panels -> one sign layer saying which sources found each sign.

Inputs: the image chain's signs (records with :data:`.refine.SIGN_FIELDS`, as
``roadsigns:refinesigns`` writes them) and the panels found in the cloud alone
(:class:`.cloudsigns.CloudSign` or their records, :data:`.cloudsigns.CLOUD_SIGN_FIELDS`).

Matching: one-to-one (Hungarian, :func:`scipy.optimize.linear_sum_assignment`) between
image signs and panels whose centres are within ``match_radius_m`` (3D) and whose facing
azimuths differ by at most ``max_azimuth_diff_deg`` (two signs back to back on one pole
are two signs); the cost is the distance plus ``azimuth_weight_m`` per 90 degrees of
azimuth difference.

Result per sign (:data:`FUSED_SIGN_FIELDS`: the sign layer's fields, then ``source``,
``review``, ``image_sign_id``, ``cloud_sign_id``, ``retro_index``, ``condition``):

Image signs keep their sign code (the code fields of :data:`.refine.SIGN_FIELDS`); signs
found by the laser alone have none here (empty ``code``): ``fusesigns`` reads their class
and code from the panoramas afterwards (:func:`.viewclass.classify_from_views`).

* **image+lidar**: the image sign, confirmed; its class and score are kept; a position
  triangulated from images only (``position_source = image``) is replaced by the panel's;
  the panel gives ``retro_index`` and ``condition``.
* **lidar** (a panel no image sign explains): ``class = unknown``, ``review = 1``; score
  :data:`LIDAR_BASE_SCORE` + :data:`LIDAR_BRIGHT_SCORE` x the panel's retroreflective share
  + :data:`LIDAR_SUPPORT_SCORE` when a pole or gantry carries it (0.5 - 1.0). Classifying
  it from the panoramas that saw it is done elsewhere; :func:`panel_views` lists them.
* **image** (no panel at its place): where the cloud was searched (inside ``coverage``,
  the cloud stage's corridor; everywhere when ``None``) its score is multiplied by
  :data:`UNCONFIRMED_SCORE_FACTOR` (0.6: a sign the laser should have seen as a
  retroreflective plane and did not is as likely a false detection as a hidden sign) and
  ``review = 1``; outside it, unchanged.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import shapely
from scipy.optimize import linear_sum_assignment
from shapely.geometry.base import BaseGeometry

from . import geometry
from .errors import InputError
from .refine import SIGN_FIELDS
from .retroreflectivity import UNKNOWN
from .schema import Schema, fields, names

SOURCE_IMAGE, SOURCE_LIDAR, SOURCE_BOTH = "image", "lidar", "image+lidar"
SOURCES = (SOURCE_IMAGE, SOURCE_LIDAR, SOURCE_BOTH)
UNKNOWN_CLASS = "unknown"
#: Image signs the cloud should have confirmed and did not: score x this.
UNCONFIRMED_SCORE_FACTOR = 0.6
#: Score of a lidar-only sign: base + bright share x bright weight + support weight.
LIDAR_BASE_SCORE = 0.5
LIDAR_BRIGHT_SCORE = 0.3
LIDAR_SUPPORT_SCORE = 0.2
DEFAULT_MATCH_RADIUS_M = 1.0
DEFAULT_MAX_AZIMUTH_DIFF_DEG = 90.0
AZIMUTH_WEIGHT_M = 0.5
#: ``position_source`` of image signs placed by triangulating rays (no cloud surface).
TRIANGULATED = "image"


#: The fused sign layer: the sign layer's fields, then the fusion's.
FUSED_SIGN_FIELDS: Schema = SIGN_FIELDS + fields(
    ("source", str), ("review", int), ("image_sign_id", int), ("cloud_sign_id", int),
    ("retro_index", float), ("condition", str))


def _sign_field_names() -> tuple:
    return names(SIGN_FIELDS)


@dataclass
class FusionParams:
    match_radius_m: float = DEFAULT_MATCH_RADIUS_M
    max_azimuth_diff_deg: float = DEFAULT_MAX_AZIMUTH_DIFF_DEG
    azimuth_weight_m: float = AZIMUTH_WEIGHT_M
    unconfirmed_score_factor: float = UNCONFIRMED_SCORE_FACTOR


@dataclass
class FusionResult:
    signs: List[Dict[str, Any]]        # records of FUSED_SIGN_FIELDS
    n_both: int
    n_image_only: int
    n_lidar_only: int
    n_unconfirmed: int                 # image-only signs inside the coverage (score lowered)


def _panel_record(panel) -> Dict[str, Any]:
    return panel.as_dict() if hasattr(panel, "as_dict") else dict(panel)


def _xyz(records: Sequence[Dict[str, Any]], what: str) -> np.ndarray:
    out = np.zeros((len(records), 3))
    for i, r in enumerate(records):
        try:
            out[i] = [float(r["x"]), float(r["y"]), float(r["z"])]
        except (KeyError, TypeError, ValueError):
            raise InputError("{what} {index}: no position (x, y, z)", what=what, index=i + 1)
    if not np.isfinite(out).all():
        bad = int(np.flatnonzero(~np.isfinite(out).all(axis=1))[0])
        raise InputError("{what} {index}: position is not finite", what=what, index=bad + 1)
    return out


def _float_or_nan(value) -> float:
    """``value`` as a float, NaN for NULL (an unknown azimuth does not veto a match)."""
    return math.nan if value is None else float(value)


def _azimuth_diff_deg(a, b) -> np.ndarray:
    return np.abs(np.mod(np.asarray(a, float) - np.asarray(b, float) + 180.0, 360.0) - 180.0)


def match_signs(image_xyz: np.ndarray, image_azimuth_deg: np.ndarray, cloud_xyz: np.ndarray,
                cloud_azimuth_deg: np.ndarray, params: FusionParams) -> List[tuple]:
    """One-to-one pairs ``(image index, cloud index, distance_m)`` within the gates."""
    if len(image_xyz) == 0 or len(cloud_xyz) == 0:
        return []
    d = np.linalg.norm(image_xyz[:, None, :] - cloud_xyz[None, :, :], axis=2)
    az = _azimuth_diff_deg(image_azimuth_deg[:, None], cloud_azimuth_deg[None, :])
    az = np.where(np.isfinite(az), az, 0.0)    # an unknown azimuth does not veto
    ok = (d <= params.match_radius_m) & (az <= params.max_azimuth_diff_deg)
    big = 1e6
    cost = np.where(ok, d + params.azimuth_weight_m * az / 90.0, big)
    rows, cols = linear_sum_assignment(cost)
    return [(int(i), int(j), float(d[i, j])) for i, j in zip(rows, cols) if ok[i, j]]


def lidar_score(panel: Dict[str, Any]) -> float:
    """Score of a sign found by the laser alone (0.5 - 1.0)."""
    bright = float(panel.get("bright_share") or 0.0)
    supported = str(panel.get("support", "none")) != "none"
    return min(1.0, LIDAR_BASE_SCORE + LIDAR_BRIGHT_SCORE * bright + LIDAR_SUPPORT_SCORE * supported)


def _covered(coverage: Union[None, str, BaseGeometry], xyz: np.ndarray) -> np.ndarray:
    if coverage is None:
        return np.ones(len(xyz), bool)
    geom = shapely.from_wkt(coverage) if isinstance(coverage, str) else coverage
    if len(xyz) == 0:
        return np.zeros(0, bool)
    return np.asarray(shapely.intersects_xy(geom, xyz[:, 0], xyz[:, 1]), dtype=bool)


def fuse_signs(image_signs: Sequence[Dict[str, Any]], cloud_panels: Sequence[Any],
               coverage: Union[None, str, BaseGeometry] = None,
               params: Optional[FusionParams] = None) -> FusionResult:
    """Fused sign records (:data:`FUSED_SIGN_FIELDS`), image signs first in their order,
    then the lidar-only ones in the panels' order; ``sign_id`` renumbered from 1.

    ``coverage``: where the cloud was searched (a shapely geometry or WKT, e.g.
    ``CloudSignResult.coverage_wkt``); image signs outside it keep their score.
    """
    params = params or FusionParams()
    images = [dict(r) for r in image_signs]
    panels = [_panel_record(p) for p in cloud_panels]
    img_xyz = _xyz(images, "Image sign")
    cld_xyz = _xyz(panels, "Cloud panel")
    img_az = np.array([_float_or_nan(r.get("azimuth")) for r in images])
    cld_az = np.array([_float_or_nan(r.get("azimuth")) for r in panels])
    pairs = match_signs(img_xyz, img_az, cld_xyz, cld_az, params)
    by_image = {i: j for i, j, _ in pairs}
    matched_panels = {j for _, j, _ in pairs}
    covered = _covered(coverage, img_xyz)
    sign_names = _sign_field_names()
    out: List[Dict[str, Any]] = []
    n_unconfirmed = 0
    for i, rec in enumerate(images):
        fused = {k: rec.get(k) for k in sign_names}
        fused["image_sign_id"] = rec.get("sign_id")
        j = by_image.get(i)
        if j is not None:
            panel = panels[j]
            fused.update(source=SOURCE_BOTH, review=0, cloud_sign_id=panel.get("sign_id"),
                         retro_index=panel.get("retro_index"), condition=panel.get("condition", UNKNOWN))
            if str(rec.get("position_source", "")) == TRIANGULATED:
                for k in ("x", "y", "z", "height", "bottom_height", "width", "panel_height"):
                    if panel.get(k) is not None:
                        fused[k] = panel[k]
                fused["position_source"] = "lidar"
        else:
            fused.update(source=SOURCE_IMAGE, cloud_sign_id=None, retro_index=None, condition=UNKNOWN,
                         review=int(bool(covered[i])))
            if covered[i]:
                n_unconfirmed += 1
                score = rec.get("score")
                fused["score"] = None if score is None else float(score) * params.unconfirmed_score_factor
        out.append(fused)
    n_lidar = 0
    for j, panel in enumerate(panels):
        if j in matched_panels:
            continue
        n_lidar += 1
        fused = {k: None for k in sign_names}
        fused.update({k: panel.get(k) for k in ("x", "y", "z", "height", "bottom_height", "width",
                                                "panel_height", "azimuth", "n_points")})
        fused.update({"class": UNKNOWN_CLASS, "score": lidar_score(panel), "n_views": 0,
                      "code": "", "code_name": "", "code_score": None, "code_views": 0, "code_check": "",
                      "source_images": "", "best_image": "", "position_source": "lidar",
                      "mean_intensity": panel.get("intensity_median"), "source": SOURCE_LIDAR,
                      "review": 1, "image_sign_id": None, "cloud_sign_id": panel.get("sign_id"),
                      "retro_index": panel.get("retro_index"),
                      "condition": panel.get("condition", UNKNOWN)})
        out.append(fused)
    for number, rec in enumerate(out, start=1):
        rec["sign_id"] = number
    ordered = [{f: rec.get(f) for f in names(FUSED_SIGN_FIELDS)} for rec in out]
    return FusionResult(ordered, len(pairs), len(images) - len(pairs), n_lidar, n_unconfirmed)


# --------------------------------------------------------------------------------------
# Which panoramas saw a panel
# --------------------------------------------------------------------------------------

def panel_views(corners_world: np.ndarray, stations, normal_world: Optional[np.ndarray] = None,
                max_range_m: float = 40.0, min_cos_view: float = 0.2) -> List[Dict[str, Any]]:
    """The panoramas that see a panel and its pixel box in each.

    ``corners_world`` ``(k, 3)`` (a panel's outline, or one point); ``stations`` a
    :class:`.trajectory.Stations`. A station sees the panel when its centre is within
    ``max_range_m`` and, with ``normal_world`` given, in front of the face with
    ``cos(view angle) >= min_cos_view``. Boxes are ``[u0, v0, u1, v1]`` in the contract's
    form (``u0`` in ``[0, W)``, ``u1`` may exceed ``W`` across the seam); occlusion is not
    checked. Sorted by range.
    """
    corners = np.asarray(corners_world, dtype=np.float64).reshape(-1, 3)
    centre = corners.mean(axis=0)
    C = np.asarray(stations.xyz_world, dtype=np.float64)
    rng = np.linalg.norm(C - centre, axis=1)
    ok = rng <= max_range_m
    if normal_world is not None:
        n = np.asarray(normal_world, dtype=np.float64)
        cos_view = ((C - centre) @ n) / np.maximum(rng, 1e-9)
        ok &= cos_view >= min_cos_view
    out: List[Dict[str, Any]] = []
    for k in np.flatnonzero(ok):
        R = geometry.matrix_from_quat_wxyz(stations.q_world_from_pano_wxyz[k])
        W, H = float(stations.width_px[k]), float(stations.height_px[k])
        u, v, _ = geometry.world_to_pixel(corners, C[k], R, W, H)
        u = np.asarray(u, dtype=np.float64)
        if np.ptp(u) > W / 2.0:               # across the seam: unwrap the left ones
            u = np.where(u < W / 2.0, u + W, u)
        u0 = float(u.min())
        shift = -W if u0 >= W else 0.0
        out.append({"station": int(k), "image": stations.image[k], "range_m": float(rng[k]),
                    "box": [u0 + shift, float(np.min(v)), float(u.max()) + shift, float(np.max(v))]})
    out.sort(key=lambda d: d["range_m"])
    return out
