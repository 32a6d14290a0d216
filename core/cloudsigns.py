"""Sign panels and poles from the point cloud alone (``roadsigns:findsignsincloud``).

From a ground-classified LAS/LAZ cloud and the drive's track (station positions and
times, or a trajectory line) it finds sign panels without any image, the poles and
gantries that carry them, and a retroreflectivity condition per panel (after the Utah I-15
mobile-LiDAR inventory paper: candidates above the road by height, an adaptive
intensity threshold, orientation-constrained RANSAC planes, shape tests, signs told from
light poles by height).

One streaming read of the cloud, then one pass over the windows; memory is bounded by a
window's points at any drive length, and a window holding more than
``window_max_points`` (the densest stretch of a longer drive is denser) is searched in
parts (:func:`.drivewindows.split_window`), each with its own margins:

1. **Read** (:meth:`.cloudsource.CloudSource.iter_chunks`: one file, or of a folder of tiles
   or a virtual point cloud only the tiles, or COPC nodes, that the corridor meets): points
   are located on the drive (:mod:`.drivewindows`); ground points (class 2) in the corridor
   are kept thinned to one per ``ground_cell_m`` cell and chunk (the first in the corridor;
   only as many ground points are located as that needs), non-ground points within
   ``corridor_m`` of the track and in a height band around the sensor are kept; all are appended to files per
   window of ``window_m`` of drive (plus ``margin_m`` on each side). The chunks are worked
   on ``window_threads`` at a time and appended in reading order. An intensity histogram
   by range (:class:`.retroreflectivity.IntensityHistogram`) gives, after the pass, the
   range exponent and the adaptive bright threshold (both stated in the log).
2. **Windows**, one at a time: height above a ground model (median of the nearest ground
   points), sensor positions, normalised intensity, local PCA features; poles
   (:mod:`.poles`); panels (:mod:`.cloudpanels`); each panel's support: a pole whose axis
   passes just behind it, else a gantry beam over its top. Dark panels (faded faces,
   backs of signs) need a support, must hang below ``dark_max_bottom_m`` on a pole (lamp
   heads are not signs) and stand free (at most ``dark_max_clutter`` points around them
   per panel point, their pole and a stacked panel aside: pieces of billboards and hedges
   do not). The face is the side away from the support (signs are mounted in front of
   their poles and beams), else the side the sensor saw; ``face_seen`` says whether the
   scanner saw the face at all. Objects are kept by the window whose core holds their
   centre (or foot), within ``corridor_m - edge_clearance_m`` of the track.

Then: gantry posts hidden at the top are found from their beam's far end, trunks under a
crown that carry nothing are dropped (trees), poles get their kind and carried signs, and
every panel its condition against the drive's reference
(:func:`.retroreflectivity.condition_of`).

Outputs: :class:`CloudSign` (:data:`CLOUD_SIGN_FIELDS`) and :class:`.poles.Pole`
(:data:`.poles.POLE_FIELDS`). Positions are world coordinates of the cloud's CRS; azimuths
are of the face normal, degrees clockwise from grid north in [0, 360).
"""
from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Callable, Dict, Iterator, List, Optional, Tuple, Union

import numpy as np
import shapely
from scipy.spatial import cKDTree

from . import geometry
from .cloudpanels import PanelCandidate, PanelParams, WindowPoints, find_panels, local_features, panel_frame
from .cloudsource import CloudSource, open_cloud
from .drivewindows import (
    BLOCK_THREADS,
    DriveAxis,
    Track,
    Window,
    WindowSpool,
    as_track,
    make_windows,
    map_in_order,
    split_window,
)
from .errors import SILENT, InputError, Message, Progress
from .pointcloud import DEFAULT_CHUNK_POINTS, GROUND_CLASS, xyz_of
from .poles import GANTRY, Pole, PoleParams, classify_pole, find_poles, promote_far_posts
from .projection import cell_keys
from .retroreflectivity import (
    GOOD_RATIO,
    MIN_RANGE_BINS,
    POOR_RATIO,
    SATURATED_SHARE_WARNING,
    ZERO_SHARE_WARNING,
    IntensityHistogram,
    IntensityModel,
    Threshold,
    condition_of,
    drive_reference,
    retro_index,
)
from .schema import fields

if TYPE_CHECKING:
    from .trajectory import Stations

#: The cloud sign layer's fields. ``x, y, z``: centre of the outline; ``height``: centre
#: above ground; ``azimuth``: of the face normal; ``intensity_*``: normalised intensity
#: (:mod:`.retroreflectivity`) of all the panel's points, median and 10th/90th percentiles;
#: ``retro_index``: median of the face's interior points (NULL when only the back was
#: scanned); ``bright_share``: share of points above the bright threshold; ``face_seen``:
#: 1 when the scanner saw the face; ``condition``: good / check / poor / unknown;
#: ``support``: pole, gantry or none; ``pole_id``: 0 when none; ``chainage_m``: arc length
#: along the track; ``outline_wkt``: the corners (top-left, top-right, bottom-right,
#: bottom-left seen from the front) as a POLYGON Z.
CLOUD_SIGN_FIELDS = fields(
    ("sign_id", int), ("x", float), ("y", float), ("z", float), ("height", float),
    ("bottom_height", float), ("width", float), ("panel_height", float), ("azimuth", float),
    ("normal_e", float), ("normal_n", float), ("normal_u", float), ("n_points", int),
    ("intensity_median", float), ("intensity_p10", float), ("intensity_p90", float),
    ("retro_index", float), ("bright_share", float), ("face_seen", int), ("condition", str),
    ("support", str), ("pole_id", int), ("range_m", float), ("chainage_m", float),
    ("outline_wkt", str))

SUPPORT_POLE, SUPPORT_GANTRY, SUPPORT_NONE = "pole", "gantry", "none"
#: Point record dtypes of the window files.
POINT_DTYPE = np.dtype([("x", "f8"), ("y", "f8"), ("z", "f8"), ("intensity", "f4"),
                        ("time", "f8"), ("s", "f4"), ("offset", "f4"),
                        ("tx", "f4"), ("ty", "f4")])
GROUND_DTYPE = np.dtype([("x", "f8"), ("y", "f8"), ("z", "f8")])
#: Nearest ground points averaged by the ground model, and how far they may be.
GROUND_NEIGHBOURS = 8
GROUND_MAX_DISTANCE_M = 3.0


@dataclass
class CloudSignParams:
    """Tuning of :func:`find_signs_in_cloud`; lengths in metres."""

    corridor_m: float = 12.0            # points this far from the track at most (lateral)
    end_margin_m: float = 5.0           # objects this far before the start / after the end
    sensor_band_m: Tuple[float, float] = (-6.0, 14.0)   # kept z relative to the track
    histogram_band_m: Tuple[float, float] = (-1.5, 8.0)  # z rel. track of the threshold's points
    edge_clearance_m: float = 1.0       # objects this close to the corridor's edge are cut by it
    window_m: float = 50.0
    # each side of a window: the head (arms, crown) of every pole the window owns lies within
    margin_m: float = PoleParams.head_radius_m
    window_max_points: int = 500_000    # a window holding more is searched in parts (split_window)
    window_threads: int = BLOCK_THREADS  # windows searched at once (numpy and scipy release the GIL)
    ground_cell_m: float = 0.25
    min_height_m: float = 0.1           # candidate points above the ground model
    feature_min_height_m: float = 0.75  # local PCA features only above this (panels, pole heads)
    max_height_m: float = 12.0
    range_exponent: Optional[float] = None   # None: estimated from the cloud
    threshold: Optional[float] = None        # range-normalised; None: adaptive
    retro_reference: Optional[float] = None  # None: the drive's own
    good_ratio: float = GOOD_RATIO
    poor_ratio: float = POOR_RATIO
    face_min_points: int = 10
    face_min_share: float = 0.3
    pole_link_m: float = 0.35           # pole axis this close to a panel's centre line
    pole_behind_max_m: float = 0.5      # ... and at most this far behind its plane
    pole_top_slack_m: float = 0.2       # ... and its top at most this below the panel's bottom
    pole_match_m: float = 0.3           # a panel's pole found again among the drive's poles
    min_width_to_pole: float = 2.0      # a panel is this many times as wide as its pole
    pole_points_max_lean_deg: float = 1.0  # points of poles this upright are kept out of panels
    dark_max_bottom_m: float = 5.0      # dark panels on poles hang lower than this
    clutter_margin_m: float = 0.5       # a dark panel's surroundings (beyond its outline, its plane)
    dark_max_clutter: float = 0.5       # ... hold at most this many points per panel point
    clutter_beam_clearance_m: float = 0.08  # under a gantry beam: the band left out below its top
    beam_above_m: float = 0.8           # a gantry beam within this above the panel's top
    beam_min_points: int = 10
    beam_gap_m: float = 0.02            # ... strictly above the panel's top (not the panel itself)
    beam_depth_m: float = 0.5           # ... within this of the panel's plane
    beam_layer_m: float = 0.6           # a beam: the top layer of a gantry post's head
    gantry_over_track_m: float = 3.0    # a gantry's beam passes this close to the track (over the road)
    gantry_link_m: float = 15.0         # gantry posts this far from a gantry panel (horizontal)
    gantry_link_along_m: float = 3.0    # ... and this close along the drive
    panels: PanelParams = field(default_factory=PanelParams)
    poles: PoleParams = field(default_factory=PoleParams)


@dataclass
class CloudSign:
    """A sign panel found in the cloud (fields of :data:`CLOUD_SIGN_FIELDS`)."""

    sign_id: int
    centre_world: np.ndarray
    normal_world: np.ndarray          # unit, out of the face
    corners_world: np.ndarray         # (4, 3) TL, TR, BR, BL seen from the front
    height: float
    bottom_height: float
    width: float
    panel_height: float
    n_points: int
    intensity_median: float
    intensity_p10: float
    intensity_p90: float
    retro_index: float
    bright_share: float
    face_seen: bool
    condition: str
    support: str
    pole_id: int
    range_m: float
    chainage_m: float
    support_xy: Optional[np.ndarray] = None   # foot of the carrying pole (linking)

    @property
    def azimuth_deg(self) -> float:
        return float(geometry.azimuth_deg_of_enu(self.normal_world))

    @property
    def outline_wkt(self) -> str:
        ring = list(self.corners_world) + [self.corners_world[0]]
        return "POLYGON Z (({}))".format(", ".join("{:.4f} {:.4f} {:.4f}".format(*c) for c in ring))

    def as_dict(self) -> Dict:
        n = self.normal_world
        return {"sign_id": self.sign_id, "x": float(self.centre_world[0]),
                "y": float(self.centre_world[1]), "z": float(self.centre_world[2]),
                "height": self.height, "bottom_height": self.bottom_height, "width": self.width,
                "panel_height": self.panel_height, "azimuth": self.azimuth_deg,
                "normal_e": float(n[0]), "normal_n": float(n[1]), "normal_u": float(n[2]),
                "n_points": self.n_points, "intensity_median": self.intensity_median,
                "intensity_p10": self.intensity_p10, "intensity_p90": self.intensity_p90,
                "retro_index": self.retro_index, "bright_share": self.bright_share,
                "face_seen": int(self.face_seen), "condition": self.condition,
                "support": self.support, "pole_id": self.pole_id, "range_m": self.range_m,
                "chainage_m": self.chainage_m, "outline_wkt": self.outline_wkt}


@dataclass
class CloudSignResult:
    """Signs and poles of a cloud, with what the log should say."""

    signs: List[CloudSign]
    poles: List[Pole]
    threshold: Threshold
    reference: float
    reference_source: str
    n_points: int
    n_candidates: int
    n_windows: int
    max_window_points: int            # the most points one window (or part of one) held: memory
    n_parts: int                      # windows and parts of dense windows searched (split_window)
    coverage_wkt: str
    crs_wkt: Optional[str]
    seconds: float
    messages: List[Message] = field(default_factory=list)
    warnings: List[Message] = field(default_factory=list)
    rejected: Dict[str, int] = field(default_factory=dict)

    def sign_records(self) -> List[Dict]:
        return [s.as_dict() for s in self.signs]

    def pole_records(self) -> List[Dict]:
        return [p.as_dict() for p in self.poles]


# --------------------------------------------------------------------------------------
# Ground model
# --------------------------------------------------------------------------------------

class GroundModel:
    """Ground height under any point: median z of the nearest ground points (within
    :data:`GROUND_MAX_DISTANCE_M`; beyond, the nearest one's)."""

    def __init__(self, xyz_world: np.ndarray):
        self.xyz = np.asarray(xyz_world, dtype=np.float64).reshape(-1, 3)
        self.tree = cKDTree(self.xyz[:, :2]) if len(self.xyz) else None

    def __call__(self, xy: np.ndarray) -> np.ndarray:
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        if self.tree is None:
            return np.full(len(xy), np.nan)
        k = min(GROUND_NEIGHBOURS, len(self.xyz))
        d, idx = self.tree.query(xy, k=k, workers=-1)
        d, idx = d.reshape(len(xy), k), idx.reshape(len(xy), k)
        z = np.where(d <= GROUND_MAX_DISTANCE_M, self.xyz[idx, 2], np.nan)
        far = np.isnan(z[:, 0])                     # distances ascend: the nearest is too far, all are
        z[far, 0] = self.xyz[idx[far, 0], 2]
        z.sort(axis=1)                              # NaN last: the median of each row's first n_valid
        n_valid = np.count_nonzero(~np.isnan(z), axis=1)
        rows = np.arange(len(z))
        return 0.5 * (z[rows, (n_valid - 1) // 2] + z[rows, n_valid // 2])


# --------------------------------------------------------------------------------------
# Input checks
# --------------------------------------------------------------------------------------

def _check_overlap(path: str, bounds_xy, axis: DriveAxis, corridor_m: float) -> None:
    """:class:`InputError` when the track's corridor misses the cloud's extent
    ``(xmin, ymin, xmax, ymax)``, saying by how much."""
    lo, hi = bounds_xy[:2], bounds_xy[2:]
    cloud_box = shapely.box(float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
    track = shapely.linestrings(axis.xyz_world[:, :2])
    gap = float(cloud_box.distance(track))
    if gap > corridor_m:
        raise InputError("The stations do not overlap the cloud {path}: the track passes {gap:.1f} m "
                         "from the cloud's extent ({xmin:.1f}, {ymin:.1f}) - ({xmax:.1f}, {ymax:.1f}), "
                         "more than the corridor of {corridor} m; are the cloud and the stations in "
                         "the same CRS and of the same drive?",
                         path=path, gap=gap, xmin=float(lo[0]), ymin=float(lo[1]), xmax=float(hi[0]),
                         ymax=float(hi[1]), corridor=corridor_m)


def _check_dimensions(path: str, header) -> bool:
    """Whether the file has ``gps_time``; :class:`InputError` without intensity or
    classification."""
    names = set(header.point_format.dimension_names)
    if "intensity" not in names:
        raise InputError("{path} has no intensity dimension (point format {fmt}): signs cannot be "
                         "found in it without images", path=path, fmt=header.point_format.id)
    if "classification" not in names:
        raise InputError("{path} has no classification dimension: run roadsigns:groundfilter on it "
                         "first", path=path)
    return "gps_time" in names


# --------------------------------------------------------------------------------------
# Pass 1: read and spool
# --------------------------------------------------------------------------------------

#: Slack (metres) beyond a ground cell's diagonal for the corridor test's bends along the
#: drive axis: a cell whose first point is farther outside than both has no point inside.
AXIS_SLACK_M = 0.5


def cell_reach_m(cell_m: float) -> float:
    """How far outside the corridor the first ground point of a ``cell_m`` cell may lie
    while another point of the cell is inside (its diagonal and :data:`AXIS_SLACK_M`)."""
    return math.sqrt(2.0) * cell_m + AXIS_SLACK_M


def _thin_ground(xyz: np.ndarray, cell_m: float,
                 inside: Callable[[np.ndarray], Tuple[np.ndarray, np.ndarray, np.ndarray]]
                 ) -> Tuple[np.ndarray, np.ndarray]:
    """Ground points ``xyz`` (in reading order) thinned to one per ``cell_m`` cell
    (:func:`.projection.cell_keys`): the first point of each cell inside the corridor, in
    reading order, and its arc length on the drive: ``(rows, s_m)``.

    ``inside(rows)`` gives two masks over ``rows``, inside the corridor and within
    :func:`cell_reach_m` of it, and the rows' arc lengths. It needs the points located on the
    drive, so it sees each cell's first point, and the other points only of the cells whose
    first point is outside but that near: most ground points are never located. (A cell whose
    first point is farther out lies wholly outside: the corridor test moves by no more than a
    point does.)"""
    if len(xyz) == 0:
        return np.zeros(0, np.int64), np.zeros(0)
    keys = cell_keys(xyz[:, 0], xyz[:, 1], cell_m)
    _, first = np.unique(keys, return_index=True)
    ok, near, s_first = inside(first)
    kept, kept_s = [first[ok]], [s_first[ok]]
    rest = np.flatnonzero(np.isin(keys, keys[first[near & ~ok]]))
    rest = rest[~np.isin(rest, first)]
    if len(rest):
        ok_rest, _, s_rest = inside(rest)
        rest, s_rest = rest[ok_rest], s_rest[ok_rest]
        _, first_inside = np.unique(keys[rest], return_index=True)
        kept.append(rest[first_inside])
        kept_s.append(s_rest[first_inside])
    rows, s_m = np.concatenate(kept), np.concatenate(kept_s)
    order = np.argsort(rows)
    return rows[order], s_m[order]


@dataclass
class _ChunkRecords:
    """What one chunk of the cloud gives the reading pass (:func:`_chunk_records`)."""
    n_read: int
    ground_s: np.ndarray              # arc length of each thinned ground point
    ground: np.ndarray                # GROUND_DTYPE
    points_s: np.ndarray
    points: np.ndarray                # POINT_DTYPE: the non-ground points kept
    hist_intensity: np.ndarray        # the threshold's points: raw intensity and range (m)
    hist_range_m: np.ndarray
    time_range: Tuple[float, float]   # of the points kept (inf, -inf: none or no times)


def _chunk_records(chunk, axis: DriveAxis, has_time: bool, params: CloudSignParams) -> _ChunkRecords:
    """The rows one chunk adds to the spool: its ground thinned and its other points in the
    corridor and the sensor's band, located on the drive. Depends on the chunk alone, so
    chunks are worked on in parallel and added in reading order."""
    lo_s, hi_s = -params.end_margin_m - params.margin_m, axis.length_m + params.end_margin_m + params.margin_m
    reach_m = cell_reach_m(params.ground_cell_m)
    xyz = xyz_of(chunk)
    is_ground = np.asarray(chunk.classification) == GROUND_CLASS
    g_all = np.flatnonzero(is_ground)

    def inside(rows: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        s_r, offset_r, _ = axis.locate(xyz[g_all[rows]])
        out_by = np.maximum(np.abs(offset_r) - params.corridor_m, np.maximum(lo_s - s_r, s_r - hi_s))
        return out_by <= 0.0, out_by <= reach_m, s_r

    thinned, g_s = _thin_ground(xyz[g_all], params.ground_cell_m, inside)
    g_rows = g_all[thinned]
    g = np.zeros(len(g_rows), GROUND_DTYPE)
    g["x"], g["y"], g["z"] = xyz[g_rows, 0], xyz[g_rows, 1], xyz[g_rows, 2]
    # the other points: located on the drive, kept in the corridor and the sensor's band
    above = np.flatnonzero(~is_ground)
    s, offset, idx = axis.locate(xyz[above])
    z_rel = xyz[above, 2] - axis.xyz_world[idx, 2]
    cand = ((np.abs(offset) <= params.corridor_m) & (s >= lo_s) & (s <= hi_s)
            & (z_rel >= params.sensor_band_m[0]) & (z_rel <= params.sensor_band_m[1]))
    rows, s, offset, idx, z_rel = above[cand], s[cand], offset[cand], idx[cand], z_rel[cand]
    intensity = np.asarray(chunk.intensity)[rows].astype(np.float32)
    times = np.asarray(chunk.gps_time)[rows].astype(np.float64) if has_time else np.full(len(rows), np.nan)
    time_range = (float(times.min()), float(times.max())) if has_time and len(rows) else (math.inf, -math.inf)
    kept = xyz[rows]
    rec = np.zeros(len(rows), POINT_DTYPE)
    rec["x"], rec["y"], rec["z"] = kept[:, 0], kept[:, 1], kept[:, 2]
    rec["intensity"], rec["time"] = intensity, times
    rec["s"], rec["offset"] = s, offset
    rec["tx"], rec["ty"] = axis.tangent_xy[idx, 0], axis.tangent_xy[idx, 1]
    band = (z_rel >= params.histogram_band_m[0]) & (z_rel <= params.histogram_band_m[1])
    hist_i, hist_r = intensity[:0], np.zeros(0)
    if band.any():
        in_band = kept[band]
        sensor = axis.sensor_positions(in_band, times[band] if has_time else None)
        hist_i, hist_r = intensity[band], np.linalg.norm(in_band - sensor, axis=1)
    return _ChunkRecords(len(chunk), g_s, g, s, rec, hist_i, hist_r, time_range)


def _spool_cloud(source: CloudSource, axis: DriveAxis, spool: WindowSpool, hist: IntensityHistogram,
                 has_time: bool, params: CloudSignParams, chunk_points: int, progress: Progress
                 ) -> Tuple[int, int, int, Tuple[float, float]]:
    """Pass 1: the cloud's chunks in the corridor read (in this thread), worked on
    ``params.window_threads`` at a time (:func:`_chunk_records`) and spooled in reading
    order: ``(points read, points kept, ground points kept, (first, last) GPS time)``."""
    n_read = n_cand = n_ground = 0
    t_min, t_max = math.inf, -math.inf
    # the tiles the corridor meets (the track lengthened at its ends is within it)
    reach = params.corridor_m + params.end_margin_m + params.margin_m
    corridor = shapely.linestrings(axis.xyz_world[:, :2]).buffer(reach, quad_segs=4)
    chunks = source.iter_chunks(chunk_points, progress, area=corridor)
    del corridor
    for part in map_in_order(lambda chunk: _chunk_records(chunk, axis, has_time, params), chunks,
                             params.window_threads, progress.check):
        n_read += part.n_read
        if len(part.ground):
            spool.add("ground", part.ground_s, part.ground)
            n_ground += len(part.ground)
        if len(part.points):
            spool.add("points", part.points_s, part.points)
            n_cand += len(part.points)
            t_min, t_max = min(t_min, part.time_range[0]), max(t_max, part.time_range[1])
        if len(part.hist_intensity):
            hist.add(part.hist_intensity, part.hist_range_m)
        del part
    spool.flush()
    return n_read, n_cand, n_ground, (t_min, t_max)


# --------------------------------------------------------------------------------------
# Pass 2: one window
# --------------------------------------------------------------------------------------

#: A found panel's rows once its window is done (:func:`_process_window`).
_NO_ROWS = np.zeros(0, np.int64)


@dataclass
class _Found:
    panel: PanelCandidate
    support: str
    support_xy: Optional[np.ndarray]
    normal: np.ndarray
    stats: Dict[str, float]
    face_seen: bool
    n_points: int


def _window_points(rows: np.ndarray, ground: GroundModel, axis: DriveAxis, model: IntensityModel,
                   threshold: float, params: CloudSignParams) -> WindowPoints:
    xyz = np.column_stack([rows["x"], rows["y"], rows["z"]])
    h = xyz[:, 2] - ground(xyz[:, :2])
    keep = np.isfinite(h) & (h >= params.min_height_m) & (h <= params.max_height_m)
    rows, xyz, h = rows[keep], xyz[keep], h[keep]
    times = rows["time"].astype(np.float64)
    sensor = axis.sensor_positions(xyz, None if np.isnan(times).all() else times)
    intensity = rows["intensity"].astype(np.float64)
    rn = model.range_normalised(intensity, np.linalg.norm(xyz - sensor, axis=1))
    tangent = np.column_stack([rows["tx"], rows["ty"]]).astype(np.float64)
    pts = WindowPoints(xyz=xyz, h=h, sensor=sensor, intensity=intensity, intensity_rn=rn,
                       bright=rn >= threshold, s_m=rows["s"].astype(np.float64),
                       offset_m=rows["offset"].astype(np.float64), tangent_xy=tangent)
    pts.normal, pts.linearity = np.zeros((len(xyz), 3)), np.zeros(len(xyz))
    pts.flatness, pts.scattering = np.ones(len(xyz)), np.ones(len(xyz))
    up = np.flatnonzero(h >= params.feature_min_height_m)   # panels and pole heads are higher
    pts.normal[up], pts.linearity[up], pts.flatness[up], pts.scattering[up] = local_features(xyz[up])
    return pts


def _support_of(panel: PanelCandidate, poles: List[Pole], params: CloudSignParams
                ) -> Tuple[str, Optional[np.ndarray], Optional[np.ndarray]]:
    """(support kind, the foot xy of the carrying pole, a point of the support behind the
    panel) or (``none``, None, None). A pole: its axis passes behind the panel's centre
    line (trunks under a crown only carry bright panels). A gantry: a post whose head
    reaches across the road near here, with its beam just over the panel's top."""
    right, _ = panel_frame(panel.normal)
    n_h = panel.normal[:2] / max(float(np.linalg.norm(panel.normal[:2])), 1e-9)
    best, best_d = None, math.inf
    for p in poles:
        if p.crown and not panel.bright:
            continue
        if p.is_gantry(params.poles) or panel.width_m < params.min_width_to_pole * p.diameter:
            continue                      # a gantry carries by its beam; a part of a pole is no panel
        if p.z_foot + p.height < panel.centre[2] - 0.5 * panel.height_m - params.pole_top_slack_m:
            continue
        rel = p.axis_xy_at(float(panel.centre[2])) - panel.centre[:2]
        across = abs(float(rel @ right[:2]))
        depth = abs(float(rel @ n_h))
        if across <= max(params.pole_link_m, 0.5 * panel.width_m) and depth <= params.pole_behind_max_m:
            d = math.hypot(across, depth)
            if d < best_d:
                best, best_d = p, d
    if best is not None:
        axis_xy = best.axis_xy_at(float(panel.centre[2]))
        return SUPPORT_POLE, np.array([best.x, best.y]), np.array([axis_xy[0], axis_xy[1], panel.centre[2]])
    top_z = panel.centre[2] + 0.5 * panel.height_m
    for p in poles:
        if (p.crown or not p.is_gantry(params.poles) or abs(p.s_m - panel.s_m) > params.gantry_link_along_m
                or math.hypot(p.x - panel.centre[0], p.y - panel.centre[1]) > params.gantry_link_m):
            continue
        beam = p.beam_xyz(params.beam_layer_m)
        rel = beam - panel.centre
        above = ((beam[:, 2] >= top_z + params.beam_gap_m) & (beam[:, 2] <= top_z + params.beam_above_m)
                 & (np.abs(rel @ right) <= 0.5 * panel.width_m) & (np.abs(rel @ panel.normal) <= params.beam_depth_m))
        if int(above.sum()) >= params.beam_min_points:
            return SUPPORT_GANTRY, np.array([p.x, p.y]), beam[above].mean(axis=0)
    return SUPPORT_NONE, None, None


def _clutter(panel: PanelCandidate, pts: WindowPoints, support: str, support_xy: Optional[np.ndarray],
             params: CloudSignParams) -> float:
    """Points around a panel (within ``clutter_margin_m`` beyond its outline and of its
    plane) per point of the panel, leaving out its pole, coplanar panels stacked with it
    and, on a gantry, the beam above: a sign stands free; a piece of a billboard or of a
    hedge does not."""
    right, up = panel_frame(panel.normal)
    m = params.clutter_margin_m
    reach = 0.5 * math.hypot(panel.width_m, panel.height_m) + m
    near = np.asarray(pts.tree.query_ball_point(panel.centre, reach * math.sqrt(2.0)), dtype=np.int64)
    near = np.setdiff1d(near, panel.rows)
    if len(near) == 0:
        return 0.0
    rel = pts.xyz[near] - panel.centre
    u, v, d = rel @ right, rel @ up, rel @ panel.normal
    hw, hh = 0.5 * panel.width_m, 0.5 * panel.height_m
    around = (np.abs(u) <= hw + m) & (np.abs(v) <= hh + m) & (np.abs(d) <= m)
    stacked = (np.abs(d) <= 2.0 * params.panels.plane_threshold_m) & (np.abs(u) <= hw)
    around &= ~stacked
    if support == SUPPORT_POLE and support_xy is not None:
        around &= np.linalg.norm(pts.xyz[near, :2] - support_xy, axis=1) > params.poles.top_radius_m
    elif support == SUPPORT_GANTRY:
        around &= v <= hh - params.beam_gap_m - params.clutter_beam_clearance_m
    return float(np.count_nonzero(around)) / max(len(panel.rows), 1)


def _panel_stats(panel: PanelCandidate, normal: np.ndarray, pts: WindowPoints, model: IntensityModel,
                 params: CloudSignParams) -> Tuple[Dict[str, float], bool]:
    """Intensity statistics of a panel's points and its retro index from the face's
    interior points; whether the face was scanned."""
    rows = panel.rows
    xyz = pts.xyz[rows]
    to_sensor = pts.sensor[rows] - xyz
    r = np.linalg.norm(to_sensor, axis=1)
    cos_inc = (to_sensor @ normal) / np.maximum(r, 1e-9)
    value = model.normalised(pts.intensity[rows], r, cos_inc)
    front = cos_inc > 0
    face_seen = (int(front.sum()) >= params.face_min_points
                 and float(front.mean()) >= params.face_min_share)
    right, up = panel_frame(normal)
    rel = xyz - panel.centre
    uv = np.column_stack([rel @ right, rel @ up])
    margin = max(params.panels.edge_margin_m, params.panels.edge_spacings * panel.spacing_m)
    hull = shapely.MultiPoint(uv).convex_hull
    inner_geom = hull.buffer(-margin) if hull.geom_type == "Polygon" else shapely.Polygon()
    interior = (shapely.contains_xy(inner_geom, uv[:, 0], uv[:, 1]) if not inner_geom.is_empty
                else np.zeros(len(uv), bool))
    stats = {"median": float(np.median(value)), "p10": float(np.percentile(value, 10)),
             "p90": float(np.percentile(value, 90)),
             "retro": retro_index(value[front], interior[front]) if face_seen else float("nan"),
             "range": float(np.median(r))}
    return stats, face_seen


def _process_window(window: Window, rows: np.ndarray, ground_rows: np.ndarray, axis: DriveAxis,
                    model: IntensityModel, threshold: float, params: CloudSignParams,
                    rejected: Dict[str, int], diagnostics: Optional[list] = None
                    ) -> Tuple[List[_Found], List[Pole]]:
    ground = GroundModel(np.column_stack([ground_rows["x"], ground_rows["y"], ground_rows["z"]]))
    pts = _window_points(rows, ground, axis, model, threshold, params)
    if len(pts) == 0:
        return [], []
    poles = find_poles(pts.xyz, pts.h, pts.sensor, pts.scattering, ground, params.poles)
    for p in poles:
        p.s_m = float(axis.locate(np.array([[p.x, p.y]]))[0][0])
        if p.reach_m >= params.poles.gantry_reach_m and len(p.head_xyz):
            p.spans_road = bool(np.abs(axis.locate(p.head_xyz)[1]).min() <= params.gantry_over_track_m)
    edge = params.corridor_m - params.edge_clearance_m
    s_lo, s_hi = -params.end_margin_m, axis.length_m + params.end_margin_m
    pole_axes = [(np.array([p.x, p.y]), max(0.5 * p.diameter, params.poles.min_radius_m)) for p in poles
                 if p.lean_deg <= params.pole_points_max_lean_deg]
    panels, reasons = find_panels(pts, ground, params.panels, seed=window.index, poles=pole_axes,
                                  diagnostics=diagnostics)
    for k, v in reasons.items():
        rejected[k] = rejected.get(k, 0) + v
    found: List[_Found] = []
    for panel in panels:
        if not window.owns(panel.s_m) or abs(panel.offset_m) > edge or not s_lo <= panel.s_m <= s_hi:
            continue
        support, support_xy, behind = _support_of(panel, poles, params)
        if not panel.bright and support == SUPPORT_POLE and panel.bottom_height_m > params.dark_max_bottom_m:
            support = SUPPORT_NONE            # dark parts high on a pole: lamp heads, arms
        if not panel.bright and support != SUPPORT_NONE and _clutter(panel, pts, support, support_xy, params) \
                > params.dark_max_clutter:
            rejected["cluttered"] = rejected.get("cluttered", 0) + 1
            continue
        if support == SUPPORT_NONE and not panel.bright:
            rejected["dark without support"] = rejected.get("dark without support", 0) + 1
            if diagnostics is not None:
                diagnostics.append({"centre": panel.centre, "n": len(panel.rows), "reason": "dark without support",
                                    "bright": False})
            continue
        normal = panel.normal.copy()
        if behind is not None:
            depth = float((behind - panel.centre) @ normal)
            if depth > 0.0:
                normal = -normal          # the support is in front: the scanner saw the back
        stats, face_seen = _panel_stats(panel, normal, pts, model, params)
        # its rows index this window's points: the drive keeps the panel's measures, not them
        found.append(_Found(replace(panel, rows=_NO_ROWS), support, support_xy, normal, stats, face_seen,
                            len(panel.rows)))
    owned_poles = [p for p in poles if window.owns(p.s_m) and s_lo <= p.s_m <= s_hi
                   and abs(float(axis.locate(np.array([[p.x, p.y]]))[1][0])) <= edge]
    for p in owned_poles:  # a head's points serve its window, and a gantry's the drive (promote_far_posts);
        if not p.is_gantry(params.poles) or p.crown:   # a drive keeps thousands of other poles
            p.head_xyz = np.zeros((0, 3))              # not head_xyz[:0]: a view keeps its base
    return found, owned_poles


@dataclass
class _WindowResult:
    n_points: int
    window_index: int
    found: List[_Found] = field(default_factory=list)
    poles: List[Pole] = field(default_factory=list)
    rejected: Dict[str, int] = field(default_factory=dict)
    diagnostics: Optional[list] = None


# --------------------------------------------------------------------------------------
# The stage
# --------------------------------------------------------------------------------------

def find_signs_in_cloud(cloud_path: Union[str, CloudSource], track: Union[Track, "Stations", np.ndarray],
                        params: Optional[CloudSignParams] = None,
                        chunk_points: int = DEFAULT_CHUNK_POINTS, progress: Progress = SILENT,
                        work_folder: Optional[str] = None, diagnostics: Optional[list] = None
                        ) -> CloudSignResult:
    """Sign panels and poles of a ground-classified cloud (a LAS/LAZ file, a folder of tiles,
    a ``.vpc`` or a :class:`.cloudsource.CloudSource`) along ``track`` (a
    :class:`.drivewindows.Track`, panorama ``Stations`` or an ``(n, 3)`` trajectory line in the
    cloud's CRS).

    ``work_folder``: where the window files go (a temporary folder inside it, deleted at
    the end; the system's temporary folder by default); ``diagnostics`` (a list, for
    debugging) gets a dict per planar part measured and per panel rejected. Raises :class:`InputError` for a
    cloud without intensity (or only zeros), without ground points, or out of the track's
    reach (saying how far); cancelling raises :class:`~.errors.Cancelled`.
    """
    params = params or CloudSignParams()
    started = time.perf_counter()
    source = open_cloud(cloud_path if isinstance(cloud_path, CloudSource) else os.fspath(cloud_path))
    cloud_path = source.path
    header = source.header
    has_time = _check_dimensions(cloud_path, header)
    axis = DriveAxis(as_track(track))
    _check_overlap(cloud_path, source.bounds_xy, axis, params.corridor_m)
    windows = make_windows(axis.length_m, params.window_m)
    hist = IntensityHistogram()
    messages: List[Message] = []
    warnings: List[Message] = []
    rejected: Dict[str, int] = {}
    with WindowSpool(windows, params.margin_m, {"points": POINT_DTYPE, "ground": GROUND_DTYPE},
                     folder=work_folder) as spool:
        n_read, n_cand, n_ground, (t_min, t_max) = _spool_cloud(
            source, axis, spool, hist, has_time, params, chunk_points, progress.sub(0.0, 0.5))
        if n_cand == 0 and n_ground == 0:
            raise InputError("No point of {path} lies within {corridor} m of the stations' track "
                             "({n} points read)", path=cloud_path, corridor=params.corridor_m, n=n_read)
        if n_ground == 0:
            raise InputError("{path} has no ground points (class 2) along the track: run "
                             "roadsigns:groundfilter on it first (or classify the ground with another "
                             "tool)", path=cloud_path)
        if hist.n_total and hist.n_zero == hist.n_total:
            raise InputError("{path} has no intensity: all {n} points near the track have intensity 0; "
                             "signs cannot be found in it without images", path=cloud_path, n=hist.n_total)
        if has_time and axis.has_times() and not axis.times_overlap(t_min, t_max):
            warnings.append(progress.warning(
                "The cloud's GPS times [{t0:.1f}, {t1:.1f}] do not meet the stations' times: ranges "
                "are taken from the nearest track position instead (is one of them in GPS week "
                "seconds and the other in adjusted standard GPS time?)", t0=t_min, t1=t_max))
        threshold = hist.threshold(params.range_exponent)
        if params.threshold is not None:
            threshold.value = float(params.threshold)
        model = IntensityModel(range_exponent=threshold.range_exponent)
        messages.append(progress.info(
            "Intensity: range exponent {alpha:.2f} ({source}), bright threshold {thr:.3f} of full scale "
            "at 10 m ({method}; background level {bg:.3f}, bright mode {mode:.3f}; {n} non-ground points near the "
            "road)", alpha=threshold.range_exponent,
            source=("given" if params.range_exponent is not None else
                    "estimated from {} range bins".format(threshold.range_bins_used)
                    if threshold.range_bins_used >= MIN_RANGE_BINS else
                    "not estimated: {} range bins with bright returns".format(threshold.range_bins_used)),
            thr=threshold.value, method=threshold.method, bg=threshold.background, mode=threshold.bright_mode,
            n=threshold.n_points))
        if threshold.zero_share >= ZERO_SHARE_WARNING:
            warnings.append(progress.warning(
                "{share:.0%} of the points near the road have intensity 0: the bright threshold "
                "{thr:.3f} of full scale may be meaningless", share=threshold.zero_share,
                thr=threshold.value))
        if threshold.saturated_share >= SATURATED_SHARE_WARNING:
            warnings.append(progress.warning(
                "{share:.0%} of the points near the road have saturated intensity: the bright threshold "
                "{thr:.3f} of full scale and the condition of the signs may be meaningless",
                share=threshold.saturated_share, thr=threshold.value))
        found: List[_Found] = []
        poles: List[Pole] = []
        max_window_points = n_parts = 0
        win_progress = progress.sub(0.5, 0.98)

        def read_windows() -> Iterator[Tuple[Window, np.ndarray, np.ndarray]]:
            for window in windows:            # read in this thread, searched in the pool's
                rows, ground_rows = spool.read("points", window.index), spool.read("ground", window.index)
                parts = split_window(window, rows["s"], params.margin_m, params.window_max_points,
                                     params.margin_m)
                if len(parts) == 1:
                    yield parts[0][0], rows, ground_rows
                    del rows
                    continue
                # a dense window is not held while its parts are searched: each part's rows are read
                # from the window's file as the part starts (the ground is thinned: each takes the window's)
                del rows
                for part, part_rows in parts:
                    yield part, spool.read("points", window.index, part_rows), ground_rows

        def search(item: Tuple[Window, np.ndarray, np.ndarray]) -> _WindowResult:
            window, rows, ground_rows = item
            out = _WindowResult(n_points=len(rows) + len(ground_rows), window_index=window.index,
                                diagnostics=[] if diagnostics is not None else None)
            if len(rows) and len(ground_rows):
                out.found, out.poles = _process_window(window, rows, ground_rows, axis, model, threshold.value,
                                                       params, out.rejected, out.diagnostics)
            return out

        for res in map_in_order(search, read_windows(), params.window_threads, win_progress.check):
            max_window_points = max(max_window_points, res.n_points)
            n_parts += 1
            found.extend(res.found)
            poles.extend(res.poles)
            for k, v in res.rejected.items():
                rejected[k] = rejected.get(k, 0) + v
            if diagnostics is not None and res.diagnostics:
                diagnostics.extend(res.diagnostics)
            win_progress.report((res.window_index + 1) / len(windows))   # a window's parts share it
            win_progress.step("Searching the drive for signs and poles: window {n} of {count}",
                              n=res.window_index + 1, count=len(windows))
    signs, poles = _finish(found, poles, threshold, params, messages, progress)
    ref = drive_reference(np.array([f.stats["retro"] for f in found if f.panel.bright and f.face_seen]),
                          threshold.value, params.retro_reference)
    coverage = shapely.linestrings(axis.xyz_world[:, :2]).buffer(params.corridor_m)
    messages.append(progress.info(
        "Found {signs} sign panels ({bright} retroreflective) and {poles} poles in {n} points "
        "({cand} kept near the road, {windows} windows of {w} m); condition reference {ref:.3f} ({src})",
        signs=len(signs), bright=sum(1 for f in found if f.panel.bright), poles=len(poles), n=n_read,
        cand=n_cand, windows=len(windows), w=params.window_m, ref=ref[0], src=ref[1]))
    progress.report(1.0)
    return CloudSignResult(signs=signs, poles=poles, threshold=threshold, reference=ref[0],
                           reference_source=ref[1], n_points=n_read, n_candidates=n_cand,
                           n_windows=len(windows), max_window_points=max_window_points, n_parts=n_parts,
                           coverage_wkt=coverage.wkt,
                           crs_wkt=source.crs_wkt, seconds=time.perf_counter() - started,
                           messages=messages, warnings=warnings, rejected=rejected)


def _finish(found: List[_Found], poles: List[Pole], threshold: Threshold, params: CloudSignParams,
            messages: List[Message], progress: Progress) -> Tuple[List[CloudSign], List[Pole]]:
    """Number the signs and poles along the drive, link them, set kinds and conditions."""
    found.sort(key=lambda f: (f.panel.s_m, f.panel.centre[2]))
    poles.sort(key=lambda p: p.s_m)
    promote_far_posts(poles, params.poles)
    for k, p in enumerate(poles, start=1):
        p.pole_id = k
    reference, _ = drive_reference(
        np.array([f.stats["retro"] for f in found if f.panel.bright and f.face_seen]),
        threshold.value, params.retro_reference)
    feet = np.array([[p.x, p.y] for p in poles]) if poles else np.zeros((0, 2))
    signs: List[CloudSign] = []
    carried: Dict[int, List[int]] = {}
    for k, f in enumerate(found, start=1):
        pole_id = 0
        if f.support == SUPPORT_POLE and f.support_xy is not None and len(feet):
            d = np.linalg.norm(feet - f.support_xy, axis=1)
            j = int(np.argmin(d))
            if d[j] <= params.pole_match_m:
                pole_id = poles[j].pole_id
                carried.setdefault(j, []).append(k)
        elif f.support == SUPPORT_GANTRY:
            for j, p in enumerate(poles):
                if (p.is_gantry(params.poles) and abs(p.s_m - f.panel.s_m) <= params.gantry_link_along_m
                        and math.hypot(p.x - f.panel.centre[0], p.y - f.panel.centre[1]) <= params.gantry_link_m):
                    carried.setdefault(j, []).append(k)
                    pole_id = pole_id or p.pole_id
        panel = f.panel
        normal = f.normal
        corners = panel.corners
        if float(normal @ panel.normal) < 0:   # seen from behind: the face's corners mirror
            corners = corners[[1, 0, 3, 2]]
        condition = condition_of(f.stats["retro"], reference, f.face_seen, params.good_ratio, params.poor_ratio)
        signs.append(CloudSign(
            sign_id=k, centre_world=panel.centre, normal_world=normal, corners_world=corners,
            height=panel.centre_height_m, bottom_height=panel.bottom_height_m, width=panel.width_m,
            panel_height=panel.height_m, n_points=f.n_points, intensity_median=f.stats["median"],
            intensity_p10=f.stats["p10"], intensity_p90=f.stats["p90"], retro_index=f.stats["retro"],
            bright_share=panel.bright_share, face_seen=f.face_seen, condition=condition,
            support=f.support, pole_id=pole_id, range_m=f.stats["range"], chainage_m=panel.s_m,
            support_xy=f.support_xy))
    for j, p in enumerate(poles):
        p.sign_ids = sorted(carried.get(j, []))
        p.kind = classify_pole(p, len(p.sign_ids), params.poles)
    # trunks under a crown are trees unless they carry a sign or a gantry beam; number the rest
    kept = [p for p in poles if not p.crown or p.sign_ids or p.kind == GANTRY]
    renumber = {p.pole_id: k for k, p in enumerate(kept, start=1)}
    for p in kept:
        p.pole_id = renumber[p.pole_id]
    for sign in signs:
        sign.pole_id = renumber.get(sign.pole_id, 0)
    poles = kept
    n_gantry = sum(1 for p in poles if p.kind == GANTRY)
    if n_gantry:
        messages.append(progress.info("{n} gantry posts", n=n_gantry))
    return signs, poles
