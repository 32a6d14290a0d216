"""Candidates -> one record per physical sign panel (``roadsigns:refinesigns``).

1. **Merge views.** Candidates (``status == "ok"``) are the same panel when they are within
   ``merge_radius_m``, their plane normals agree (within ``normal_agreement_deg``), they
   come from different panoramas and their centres lie within half a panel of each other
   vertically and along the plane (panel size from the box and the range), so panels
   stacked on one pole stay apart. Different classes merge only when twice as close (the
   class is then a vote). Groups are complete-linkage clusters: every pair agrees.
2. **Refine each panel** (Zhang et al. 2023): points near the views' centres inside most of
   their boxes -> Euclidean clustering grown from the candidates (clusters split off by scan
   gaps kept when large) -> intensity filter with an Otsu threshold on the cluster, applied
   only when it splits off a retroreflective mode that is bright for this cloud (``median +
   4 MAD`` of its non-ground points; faded faces keep all their points) -> RANSAC plane
   constrained to near-vertical, fitted to the bright points -> points within 2.5 sigma of it
   (darker ones only where they form a surface: the back face) -> PCA dimensionality of each
   point's neighbourhood, dropping clearly linear points (the pole) -> convexity test
   (traffic mirrors are curved) -> the outline in the plane: the points' extent, widened up
   to the views' boxes cast on the plane (sampled points miss sharp corners; at most
   ``box_extent_allowance_m``); centre = centre of the outline, not the centroid -> a
   surface test: a panel whose plane continues beyond a vertical and a horizontal side and
   that is no brighter than that surface is a picture on a billboard or a wall, not a sign.
3. **Attributes.** Facing azimuth: plane normal oriented towards the stations that saw the
   panel, degrees clockwise from grid north in [0, 360). Ground: a robust plane through
   the class-2 points within 0.4 / 0.75 / 1.5 / 3 m horizontally, taken at the panel centre;
   fallbacks, in order: the foot of the lowest non-ground points below the panel
   (``lowest_points``), the stations' height minus ``camera_height_m`` (``camera_height``);
   ``RefineResult.ground_source`` says which, and a warning counts them.
4. **Views without a surface of their own.** A view whose box holds the centre of a sign
   found by other views joins it (a lone view that hit the wall behind a sign seen by
   several views, too; at any range when the class is the same: a sign far ahead, beyond
   the scanner's reach, that nearer views found in the cloud). The remaining ``no_points``
   views are triangulated: same-class rays from different panoramas that pass within a
   tolerance of each other, at an angle of at least ``min_ray_angle_deg``, are grouped and
   intersected by least squares (outlying rays dropped), and kept when the point's depth
   along the rays is certain to ``max_depth_sigma_m`` (nearly parallel rays, as of a
   distant sign straight ahead, are not); ``position_source = image``.

Classes: score-weighted vote of the views; ``score``: ``1 - prod(1 - s)`` over the views of
the winning class; ``best_image``: the view minimising range / cos(incidence).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
from scipy.cluster.hierarchy import fcluster, linkage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from scipy.spatial.distance import squareform

from . import geometry
from .errors import SILENT, InputError, Message, Progress
from .pointcloud import (CloudWriter, CropRegion, PointSet, TiledIndex, iter_chunks,
                         output_header, read_header)
from .projection import (GROUND_CLASS, STATUS_NO_POINTS, STATUS_OK, ProjectionResult,
                         box_coordinates, build_index, convex_radius_m, euclidean_clusters,
                         fit_plane_ransac, grow_boxes, pca)

DEFAULT_MERGE_RADIUS_M = 1.0
#: The sign layer's fields, in the contract's order.
SIGN_FIELDS = ("sign_id", "class", "score", "height", "bottom_height", "width", "panel_height",
               "azimuth", "n_views", "n_points", "source_images", "best_image",
               "mean_intensity", "planarity", "position_source", "x", "y", "z")
GROUND_POINTS, LOWEST_POINTS, CAMERA_HEIGHT = "ground_points", "lowest_points", "camera_height"
#: reasons of :func:`extract_panel` that mean "not a sign" (the views are dropped); other
#: reasons only mean the panel could not be isolated (the views' candidates are kept)
CURVED_SURFACE = Message("curved surface (a convex mirror?)")
LARGER_SURFACE = Message("part of a larger flat surface (a picture on a billboard or a wall?)")
NOT_A_SIGN = (CURVED_SURFACE, LARGER_SURFACE)


@dataclass
class SignRecord:
    """One sign panel with exactly the contract's sign-layer fields (``klass`` = ``class``)."""

    sign_id: int
    klass: str
    score: float
    height: float
    bottom_height: float
    width: float
    panel_height: float
    azimuth: float
    n_views: int
    n_points: int
    source_images: str
    best_image: str
    mean_intensity: float
    planarity: float
    position_source: str
    x: float
    y: float
    z: float

    def as_dict(self) -> Dict:
        d = asdict(self)
        d["class"] = d.pop("klass")
        return {k: d[k] for k in SIGN_FIELDS}

    @property
    def xyz_world(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])


@dataclass
class RefineParams:
    """Tuning of :func:`refine_signs`; lengths in metres, angles in degrees."""

    normal_agreement_deg: float = 30.0
    cross_class_factor: float = 0.5      # different classes merge within this share of the limits
    box_margin_deg: float = 0.12         # box grown for the point vote
    box_margin_frac: float = 0.03
    slab_m: float = 0.3                  # points within this of the candidates' plane
    cluster_tolerance_m: float = 0.12    # at least; else 2 x the 4th-neighbour spacing
    major_cluster_share: float = 0.15    # clusters this big are kept besides the seeds' ones
    plane_threshold_m: float = 0.04
    max_tilt_deg: float = 20.0           # panels lean at most this from vertical
    pca_radius_m: float = 0.15           # at least; else 3 x the point spacing
    min_panel_points: int = 12
    box_extent_allowance_m: float = 0.10  # boxes may widen the points' outline (corners)
    linear_threshold: float = 0.7        # PCA: a point is on a line (pole) above this a1D
    max_linear_share: float = 0.5        # the pole filter drops at most this share of a panel
    min_spread_ratio: float = 0.2        # panel points spread across less than this x along: a line
    min_convex_radius_m: float = 3.0     # more curved than this: a mirror, not a sign
    #: a panel whose plane continues this far beyond a vertical and a horizontal side (share
    #: of occupied cells of the bands there) is part of a larger surface (a billboard)
    surround_band_m: float = 0.3
    surround_gap_m: float = 0.05
    surround_cell_m: float = 0.1
    surround_min_share: float = 0.5
    ground_radii_m: Tuple[float, ...] = (0.4, 0.75, 1.5, 3.0)
    min_ground_points: int = 8
    camera_height_m: float = 2.4         # panorama centre above the road (last fallback)
    ray_gap_m: float = 0.25              # triangulation: rays this close (plus 1 % of range)
    min_ray_angle_deg: float = 2.0
    max_triangulation_range_m: float = 80.0
    #: triangulated points whose depth along the rays is less certain than this are dropped:
    #: rays of a distant sign seen straight ahead from a straight drive are nearly parallel
    ray_angle_noise_deg: float = 0.1     # box centre and calibration, one sigma
    max_depth_sigma_m: float = 1.0
    same_panel_radius_m: float = 0.3     # two signs closer than this (centres) are one panel
    #: largest plausible panel side (m) per class; information signs (gantries) are larger
    max_panel_side_m: Tuple[Tuple[str, float], ...] = (("information", 6.0),)
    max_panel_side_default_m: float = 1.6
    #: a sign seen in a single panorama is kept only with at least this detector score: a real
    #: sign passing the vehicle is seen from several stations, a lone weak box is mostly noise
    min_single_view_score: float = 0.6

    def max_side_m(self, klass: str) -> float:
        return dict(self.max_panel_side_m).get(klass, self.max_panel_side_default_m)


@dataclass
class RefineResult:
    """Signs (records), their outlines (4 corners TL, TR, BR, BL seen from the front, world;
    ``None`` for image-only signs), the LAS indices of their points, the ground source of
    each, and per candidate the sign it went into (-1: none)."""

    signs: List[SignRecord]
    outlines_world: List[Optional[np.ndarray]]
    point_index: List[np.ndarray]
    ground_source: List[str]
    candidate_sign: np.ndarray
    warnings: List[str] = field(default_factory=list)

    def records(self) -> List[Dict]:
        return [s.as_dict() for s in self.signs]


# --------------------------------------------------------------------------------------
# Merging views
# --------------------------------------------------------------------------------------

def box_size_estimate_m(cand: ProjectionResult, rows: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Panel width and height (m) implied by the boxes at the candidates' range, the width
    corrected for the obliquity of the view (at most 3x)."""
    det = cand.detections
    b, W, H = det.box_px[rows], det.pano_size_px[rows, 0], det.pano_size_px[rows, 1]
    r = cand.range_m[rows]
    dalpha = (b[:, 2] - b[:, 0]) / W * 2 * np.pi
    deps = (b[:, 3] - b[:, 1]) / H * np.pi
    eps = np.pi * (0.5 - 0.5 * (b[:, 1] + b[:, 3]) / H)
    to_station = det.centre_world[rows] - cand.xyz_world[rows]
    cos_inc = np.abs(np.einsum("ij,ij->i", to_station, cand.normal_world[rows])) / np.maximum(
        np.linalg.norm(to_station, axis=1), 1e-9)
    return r * dalpha * np.cos(eps) / np.maximum(cos_inc, 1 / 3), r * deps


def merge_distance(cand: ProjectionResult, rows: np.ndarray, merge_radius_m: float,
                   params: RefineParams) -> np.ndarray:
    """Normalised pairwise distances (square matrix) between candidates ``rows``: <= 1 means
    "the same panel"; incompatible pairs get 1e3."""
    X, N = cand.xyz_world[rows], cand.normal_world[rows]
    w_est, h_est = box_size_estimate_m(cand, rows)
    diff = X[:, None, :] - X[None, :, :]
    dist = np.linalg.norm(diff, axis=2)
    nmean = N[:, None, :] + N[None, :, :]
    horiz = np.cross(nmean, [0.0, 0.0, 1.0])
    horiz /= np.maximum(np.linalg.norm(horiz, axis=2, keepdims=True), 1e-9)
    along = np.abs(np.einsum("ijk,ijk->ij", diff, horiz))
    half_h = 0.5 * np.maximum(h_est[:, None], h_est[None, :])
    half_w = 0.5 * np.maximum(w_est[:, None], w_est[None, :])
    d = np.maximum.reduce([dist / merge_radius_m, np.abs(diff[..., 2]) / np.maximum(half_h, 0.05),
                           along / np.maximum(half_w, 0.05)])
    classes = np.array([cand.detections.class_name[k] for k in rows])
    images = np.array([cand.detections.image[k] for k in rows])
    d = np.where(classes[:, None] == classes[None, :], d, d / params.cross_class_factor)
    bad = (N @ N.T < math.cos(math.radians(params.normal_agreement_deg))) | \
        (images[:, None] == images[None, :])
    d[bad] = 1e3
    np.fill_diagonal(d, 0.0)
    return d


def merge_candidates(cand: ProjectionResult, merge_radius_m: float,
                     params: RefineParams = RefineParams()) -> List[np.ndarray]:
    """Groups (arrays of candidate rows) of the ``ok`` candidates that are one panel."""
    ok = np.flatnonzero(np.array([s == STATUS_OK for s in cand.status], bool))
    if ok.size == 0:
        return []
    pairs = cKDTree(cand.xyz_world[ok]).query_pairs(merge_radius_m, output_type="ndarray")
    n = len(ok)
    graph = coo_matrix((np.ones(len(pairs), bool), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, comp = connected_components(graph, directed=False)
    groups = []
    for c in np.unique(comp):
        rows = ok[comp == c]
        if len(rows) == 1:
            groups.append(rows)
            continue
        d = merge_distance(cand, rows, merge_radius_m, params)
        labels = fcluster(linkage(squareform(d, checks=False), method="complete"), t=1.0,
                          criterion="distance")
        groups.extend(rows[labels == lab] for lab in np.unique(labels))
    return sorted(groups, key=lambda g: int(cand.detections.det_id[g].min()))


def vote_class(cand: ProjectionResult, rows: Sequence[int]) -> Tuple[str, float]:
    """Score-weighted class vote; score = 1 - prod(1 - s) over the winner's views."""
    det = cand.detections
    weights: Dict[str, float] = {}
    for k in rows:
        weights[det.class_name[k]] = weights.get(det.class_name[k], 0.0) + float(det.score[k])
    winner = max(sorted(weights), key=lambda c: weights[c])
    s = np.array([det.score[k] for k in rows if det.class_name[k] == winner])
    return winner, float(1.0 - np.prod(1.0 - np.clip(s, 0.0, 1.0)))


# --------------------------------------------------------------------------------------
# Point-level refinement
# --------------------------------------------------------------------------------------

def otsu_threshold(values: np.ndarray, bins: int = 256) -> float:
    """Otsu's threshold (maximal between-class variance) of a 1D sample."""
    hist, edges = np.histogram(values, bins=bins)
    centres = 0.5 * (edges[:-1] + edges[1:])
    w0 = np.cumsum(hist)
    w1 = w0[-1] - w0
    m0 = np.cumsum(hist * centres) / np.maximum(w0, 1)
    m1 = ((hist * centres).sum() - np.cumsum(hist * centres)) / np.maximum(w1, 1)
    between = w0 * w1 * (m0 - m1) ** 2
    return float(edges[int(np.argmax(between[:-1])) + 1])


def bright_level(index: TiledIndex, sample: int = 200_000) -> float:
    """Intensity above which a point is bright for this cloud: median + 4 MAD (scaled) of
    its non-ground points; retroreflective sign faces lie above, most other things below."""
    cls = index.attributes["classification"]
    inten = index.attributes["intensity"][cls != GROUND_CLASS].astype(float)
    if inten.size == 0:
        return math.inf
    if inten.size > sample:
        inten = inten[np.linspace(0, inten.size - 1, sample).astype(np.int64)]
    med = float(np.median(inten))
    return med + 4.0 * 1.4826 * float(np.median(np.abs(inten - med)))


def dimensionality(xyz: np.ndarray, radius_m: float, min_neighbours: int = 5) -> np.ndarray:
    """Per point the dimensionality features (a1D, a2D, a3D) of Demantke et al. from the
    singular values of its neighbourhood within ``radius_m``: linear, planar, scattered; they
    sum to 1. Points with fewer than ``min_neighbours`` neighbours get (0, 0, 1)."""
    n = len(xyz)
    pairs = cKDTree(xyz).query_pairs(radius_m, output_type="ndarray")
    i = np.concatenate([pairs[:, 0], pairs[:, 1], np.arange(n)])
    j = np.concatenate([pairs[:, 1], pairs[:, 0], np.arange(n)])
    A = coo_matrix((np.ones(len(i)), (i, j)), shape=(n, n)).tocsr()
    count = np.asarray(A.sum(axis=1)).ravel()
    rel = xyz - xyz.mean(axis=0)
    mean = (A @ rel) / count[:, None]
    outer = (rel[:, :, None] * rel[:, None, :]).reshape(n, 9)
    cov = ((A @ outer) / count[:, None]).reshape(n, 3, 3) - mean[:, :, None] * mean[:, None, :]
    sig = np.sqrt(np.clip(np.linalg.eigvalsh(cov)[:, ::-1], 0.0, None))
    s1 = np.maximum(sig[:, 0], 1e-12)
    feats = np.column_stack([(sig[:, 0] - sig[:, 1]) / s1, (sig[:, 1] - sig[:, 2]) / s1,
                             sig[:, 2] / s1])
    feats[count < min_neighbours] = (0.0, 0.0, 1.0)
    return feats


def point_spacing_m(xyz: np.ndarray, neighbour: int = 1) -> float:
    """Median distance to the ``neighbour``-th nearest point. With a line scanner the first
    neighbours lie on the same scan line; the 4th reaches across to the next line."""
    if len(xyz) <= neighbour:
        return 0.0
    d, _ = cKDTree(xyz).query(xyz, k=neighbour + 1)
    return float(np.median(d[:, neighbour]))


@dataclass
class Panel:
    centre_world: np.ndarray
    normal_world: np.ndarray
    width_m: float
    height_m: float
    corners_world: np.ndarray
    points: PointSet
    planarity: float


def panel_frame(normal: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(right, up) in-plane unit vectors of a panel facing ``normal`` (right as the viewer
    in front sees it)."""
    right = np.cross(-normal, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    return right, np.cross(right, -normal)


def extract_panel(cand: ProjectionResult, rows: np.ndarray, index: TiledIndex, bright: float,
                  params: RefineParams) -> Tuple[Optional[Panel], str]:
    """The panel of one group of views from the cloud, or (None, reason)."""
    det = cand.detections
    X, N = cand.xyz_world[rows], cand.normal_world[rows]
    c0 = np.median(X, axis=0)
    n0 = N.mean(axis=0)
    n0 /= np.linalg.norm(n0)
    w_est, h_est = box_size_estimate_m(cand, rows)
    radius = 0.75 * float(max(w_est.max(), h_est.max())) + 0.3
    pts = index.query_radius(c0, radius)
    pts = pts.subset((pts.attributes["classification"] != GROUND_CLASS)
                     & (np.abs((pts.xyz_world - c0) @ n0) < params.slab_m))
    if len(pts) < params.min_panel_points:
        return None, Message("too few points")
    # inside the boxes of most views
    boxes = grow_boxes(det.box_px[rows], det.pano_size_px[rows], params.box_margin_deg,
                       params.box_margin_frac)
    R = geometry.matrix_from_quat_wxyz(det.q_world_from_pano_wxyz[rows])
    votes = np.zeros(len(pts), np.int64)
    for j, k in enumerate(rows):
        Rk = R[j]
        W, H = det.pano_size_px[k]
        u, v, _ = geometry.world_to_pixel(pts.xyz_world, det.centre_world[k], Rk, W, H)
        a, b = box_coordinates(u, v, boxes[j], W)
        votes += (a >= 0) & (a <= 1) & (b >= 0) & (b <= 1)
    pts = pts.subset(votes >= max(1, math.ceil(0.5 * len(rows))))
    if len(pts) < params.min_panel_points:
        return None, Message("too few points in the boxes")
    # Euclidean clusters grown from the candidates
    spacing = point_spacing_m(pts.xyz_world)
    labels = euclidean_clusters(pts.xyz_world, max(params.cluster_tolerance_m,
                                                   2.0 * point_spacing_m(pts.xyz_world, 4)))
    _, seeds = cKDTree(pts.xyz_world).query(X)
    counts = np.bincount(labels)
    big = np.flatnonzero(counts >= params.major_cluster_share * len(pts))  # scan gaps split panels
    pts = pts.subset(np.isin(labels, np.union1d(labels[seeds], big)))
    # intensity: the retroreflective mode, when the cluster has one, defines the plane
    inten = pts.attributes["intensity"].astype(float)
    bright_mask = np.ones(len(pts), bool)
    if len(pts) >= 2 * params.min_panel_points and np.ptp(inten) > 0:
        high = inten >= otsu_threshold(inten)
        if (high.sum() >= params.min_panel_points and inten[high].mean() >= bright
                and inten[~high].mean() < bright):
            bright_mask = high
    # near-vertical plane
    plane = fit_plane_ransac(pts.xyz_world[bright_mask], params.plane_threshold_m,
                             params.max_tilt_deg)
    if plane is None or plane.inliers.sum() < params.min_panel_points:
        return None, Message("no near-vertical plane")
    res = plane.distance(pts.xyz_world)
    sigma = 1.4826 * float(np.median(np.abs(res[bright_mask][plane.inliers])))
    tight = np.abs(res) < min(params.plane_threshold_m, max(0.015, 2.5 * sigma))
    # darker points on the plane stay when they form a surface of their own (the back face
    # seen where the front was not scanned), not a line (the pole)
    dark = np.flatnonzero(tight & ~bright_mask)
    if dark.size >= 5:
        feats = dimensionality(pts.xyz_world[dark], max(params.pca_radius_m, 3.0 * spacing))
        bright_mask[dark[np.argmax(feats, axis=1) == 1]] = True
    panel = pts.subset(tight & bright_mask)
    # PCA dimensionality: keep the planar points (drops the pole)
    # (edges of a panel look half linear: only clearly linear points go, and isolated ones)
    feats = dimensionality(panel.xyz_world, max(params.pca_radius_m, 3.0 * spacing))
    keep = (feats[:, 0] < params.linear_threshold) & (np.argmax(feats, axis=1) != 2)
    if keep.sum() >= max(params.min_panel_points, (1.0 - params.max_linear_share) * len(panel)):
        panel = panel.subset(keep)
    if len(panel) < params.min_panel_points:
        return None, Message("too few planar points")
    centroid, ev, V = pca(panel.xyz_world)
    normal = V[:, 2]
    if (normal @ n0) < 0:
        normal = -normal
    if abs(normal[2]) > math.sin(math.radians(params.max_tilt_deg)):
        normal = plane.normal if plane.normal @ n0 > 0 else -plane.normal
    if ev[1] < params.min_spread_ratio ** 2 * ev[0]:
        normal = n0  # the points are a line (a sparse scan across the face): the views' normal
    if convex_radius_m(panel.xyz_world, normal) < params.min_convex_radius_m:
        return None, CURVED_SURFACE
    right, up = panel_frame(normal)
    rel = panel.xyz_world - centroid
    s, t = rel @ right, rel @ up
    spacing = point_spacing_m(np.column_stack([s, t, np.zeros_like(s)]))
    box_ext = box_extents_in_plane(cand, rows, centroid, normal, right, up)
    allowance = max(4.0 * spacing, params.box_extent_allowance_m)
    ext = []
    for side, (e_pts, e_box) in enumerate(zip((-s.min(), s.max(), -t.min(), t.max()),
                                              (-box_ext[0], box_ext[1], -box_ext[2], box_ext[3]))):
        # points lie inside the outline and miss its corners by up to a point spacing or so;
        # the boxes' edges, cast on the plane, say how far: trust them within an allowance
        delta = e_box - e_pts
        if 0.0 <= delta <= allowance:
            ext.append(e_box)
        else:
            ext.append(e_pts + (0.0 if delta < 0 else 0.5 * spacing))
    s0, s1, t0, t1 = -ext[0], ext[1], -ext[2], ext[3]
    centre = centroid + 0.5 * (s0 + s1) * right + 0.5 * (t0 + t1) * up
    corners = np.array([centroid + ss * right + tt * up
                        for ss, tt in ((s0, t1), (s1, t1), (s1, t0), (s0, t0))])
    planarity = float(1.0 - ev[2] / ev[1]) if ev[1] > 0 else 0.0
    result = Panel(centre, normal, float(s1 - s0), float(t1 - t0), corners, panel, planarity)
    if on_larger_surface(result, index, bright, spacing, params):
        return None, LARGER_SURFACE
    return result, ""


def surface_around_panel(panel: Panel, index: TiledIndex, spacing_m: float,
                         params: RefineParams) -> Tuple[np.ndarray, np.ndarray]:
    """How much the panel's plane continues beyond its outline: the share (0..1) of occupied
    cells in bands of ``surround_band_m`` along its (left, right, bottom, top) sides, from
    the non-ground points within ``plane_threshold_m`` of the plane; and those points'
    intensities."""
    right, up = panel_frame(panel.normal_world)
    hw, hh, band = 0.5 * panel.width_m, 0.5 * panel.height_m, params.surround_band_m
    gap = params.surround_gap_m
    pts = index.query_radius(panel.centre_world, math.hypot(hw + band, hh + band))
    rel = pts.xyz_world - panel.centre_world
    near = (np.abs(rel @ panel.normal_world) < params.plane_threshold_m) & \
        (pts.attributes["classification"] != GROUND_CLASS)
    s, t = rel[near] @ right, rel[near] @ up
    cell = max(params.surround_cell_m, 2.5 * spacing_m)
    depth = band - gap  # each band starts ``gap`` beyond its edge and runs outwards
    shares = [_occupied_share(-s - hw - gap, t + hh, depth, 2 * hh, cell),   # left
              _occupied_share(s - hw - gap, t + hh, depth, 2 * hh, cell),    # right
              _occupied_share(-t - hh - gap, s + hw, depth, 2 * hw, cell),   # bottom
              _occupied_share(t - hh - gap, s + hw, depth, 2 * hw, cell)]    # top
    return np.array(shares), pts.attributes["intensity"][near][
        (np.abs(s) > hw + gap) | (np.abs(t) > hh + gap)].astype(float)


def _occupied_share(x: np.ndarray, y: np.ndarray, width: float, height: float,
                    cell: float) -> float:
    """Share (0..1) of the ``cell``-sized cells of the rectangle [0, width] x [0, height]
    that hold at least one of the points (x, y)."""
    inside = (x >= 0) & (x <= width) & (y >= 0) & (y <= height)
    nx, ny = max(1, math.ceil(width / cell)), max(1, math.ceil(height / cell))
    ix = np.minimum((x[inside] / cell).astype(np.int64), nx - 1)
    iy = np.minimum((y[inside] / cell).astype(np.int64), ny - 1)
    return np.unique(ix * ny + iy).size / (nx * ny)


def on_larger_surface(panel: Panel, index: TiledIndex, bright: float, spacing_m: float,
                      params: RefineParams) -> bool:
    """True when the panel is a patch of a larger flat surface: its plane continues beyond
    both a vertical and a horizontal side (a sign stacked on another or beside another, or
    its pole, continues one way only) and the patch is no brighter than the surface around
    it (a retroreflective sign screwed onto a wall is kept)."""
    shares, around = surface_around_panel(panel, index, spacing_m, params)
    full = shares >= params.surround_min_share
    if not ((full[0] or full[1]) and (full[2] or full[3])):
        return False
    own = float(np.median(panel.points.attributes["intensity"]))
    return not (own >= bright and around.size and float(np.median(around)) < bright)


def box_extents_in_plane(cand: ProjectionResult, rows: Sequence[int], origin: np.ndarray,
                         normal: np.ndarray, right: np.ndarray, up: np.ndarray,
                         samples: int = 17) -> np.ndarray:
    """The views' boxes cast on a panel's plane: median over the views of (left, right,
    bottom, top) in-plane coordinates (metres from ``origin`` along ``right`` / ``up``).

    Columns of a level panorama are vertical lines, so the box's left and right edges meet
    the plane at one ``s`` each; along the top edge the panel lies below every ray, so the
    top is the lowest hit (the bottom, the highest). NaN where no view meets the plane."""
    det = cand.detections
    g = np.linspace(0.0, 1.0, samples)
    out = []
    for k in rows:
        u0, v0, u1, v1 = det.box_px[k]
        W, H = det.pano_size_px[k]
        us = u0 + g * (u1 - u0)
        vs = v0 + g * (v1 - v0)
        uu = np.concatenate([np.full(samples, u0), np.full(samples, u1), us, us])
        vv = np.concatenate([vs, vs, np.full(samples, v1), np.full(samples, v0)])
        R = geometry.matrix_from_quat_wxyz(det.q_world_from_pano_wxyz[k])
        d = geometry.pixel_to_ray(np.mod(uu, W), vv, W, H) @ R.T
        C = det.centre_world[k]
        denom = d @ normal
        with np.errstate(divide="ignore", invalid="ignore"):
            lam = ((origin - C) @ normal) / denom
        hit = C + lam[:, None] * d - origin
        s, t = hit @ right, hit @ up
        valid = (denom < -0.05) & (lam > 0)
        parts = np.split(np.arange(4 * samples), 4)
        vals = []
        reducers = ((s, np.median), (s, np.median), (t, np.max), (t, np.min))
        for j, (coord, reduce) in enumerate(reducers):
            m = valid[parts[j]]
            vals.append(reduce(coord[parts[j]][m]) if m.any() else np.nan)
        out.append(vals)
    out = np.array(out, float)
    if not np.any(np.isfinite(out)):
        return np.full(4, np.nan)
    return np.nanmedian(out, axis=0)


# --------------------------------------------------------------------------------------
# Ground and views
# --------------------------------------------------------------------------------------

def ground_height(index: TiledIndex, xy, radii_m: Sequence[float], min_points: int) -> float:
    """Height at ``xy`` of a plane fitted to the class-2 points within the first radius
    holding ``min_points`` (NaN when none does)."""
    x, y = float(xy[0]), float(xy[1])
    r_max = max(radii_m)
    pts = index.query_box([x - r_max, y - r_max, -np.inf], [x + r_max, y + r_max, np.inf])
    g = pts.attributes["classification"] == GROUND_CLASS
    dist = np.hypot(pts.xyz_world[:, 0] - x, pts.xyz_world[:, 1] - y)
    for r in sorted(radii_m):
        m = g & (dist <= r)
        if m.sum() >= min_points:
            # a plane through them (terrain slopes), refitted without outliers (curb steps)
            p = pts.xyz_world[m]
            A = np.column_stack([np.ones(len(p)), p[:, 0] - x, p[:, 1] - y])
            keep = np.ones(len(p), bool)
            for _ in range(3):
                coef, *_ = np.linalg.lstsq(A[keep], p[keep, 2], rcond=None)
                res = np.abs(p[:, 2] - A @ coef)
                new = res <= max(0.03, 2.5 * 1.4826 * float(np.median(res[keep])))
                if new.sum() < min_points or np.array_equal(new, keep):
                    break
                keep = new
            return float(coef[0])
    return math.nan


def ground_with_fallbacks(index: Optional[TiledIndex], centre: np.ndarray, bottom_z: float,
                          station_z: np.ndarray, params: RefineParams) -> Tuple[float, str]:
    """Ground height below ``centre`` and how it was found (see the module doc)."""
    if index is not None and len(index):
        z = ground_height(index, centre[:2], params.ground_radii_m, params.min_ground_points)
        if np.isfinite(z):
            return z, GROUND_POINTS
        x, y = centre[:2]
        pts = index.query_box([x - 0.5, y - 0.5, -np.inf], [x + 0.5, y + 0.5, bottom_z - 0.2])
        if len(pts) >= 3:
            low = float(np.percentile(pts.xyz_world[:, 2], 1))
            if low < bottom_z - 1.0:
                return low, LOWEST_POINTS
    return float(np.median(station_z)) - params.camera_height_m, CAMERA_HEIGHT


def best_view(cand: ProjectionResult, rows: Sequence[int], centre: np.ndarray,
              normal: Optional[np.ndarray]) -> int:
    """The view (candidate row) closest and most frontal: minimal range / cos(incidence)."""
    C = cand.detections.centre_world[list(rows)]
    to = C - centre
    r = np.linalg.norm(to, axis=1)
    cos_inc = np.ones(len(r)) if normal is None else np.clip((to @ normal) / r, 0.05, 1.0)
    return int(list(rows)[int(np.argmin(r / cos_inc))])


# --------------------------------------------------------------------------------------
# Image-only signs
# --------------------------------------------------------------------------------------

def intersect_rays(origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Least-squares point closest to all rays (unit directions)."""
    P = np.eye(3)[None] - directions[:, :, None] * directions[:, None, :]
    return np.linalg.solve(P.sum(axis=0), np.einsum("nij,nj->i", P, origins))


def ray_distance(point: np.ndarray, origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
    rel = point - origins
    along = np.einsum("ij,ij->i", rel, directions)
    return np.linalg.norm(rel - along[:, None] * directions, axis=1)


def depth_sigma_m(x: np.ndarray, origins: np.ndarray, gaps_m: np.ndarray, sin_max_angle: float,
                  params: RefineParams) -> float:
    """Rough one-sigma uncertainty (m) of a triangulated point along its rays: the lateral
    uncertainty (the rays' residual gaps, at least the angular noise at the range) over the
    sine of the widest angle between the rays."""
    rng = float(np.linalg.norm(x - origins, axis=1).max())
    lateral = max(float(np.sqrt(np.mean(gaps_m ** 2))),
                  rng * math.radians(params.ray_angle_noise_deg))
    return lateral / max(sin_max_angle, 1e-9)


def triangulate_groups(cand: ProjectionResult, rows: np.ndarray, params: RefineParams
                       ) -> List[Tuple[np.ndarray, np.ndarray]]:
    """Groups of rays (candidate rows) meeting at one point, and that point."""
    if len(rows) < 2:
        return []
    det = cand.detections
    C = det.centre_world[rows]
    D = det.centre_rays_world()[rows]
    classes = np.array([det.class_name[k] for k in rows])
    images = np.array([det.image[k] for k in rows])
    sin_min = math.sin(math.radians(params.min_ray_angle_deg))
    edges = []
    for i, j in cKDTree(C).query_pairs(2 * params.max_triangulation_range_m):
        if classes[i] != classes[j] or images[i] == images[j]:
            continue
        cross = np.cross(D[i], D[j])
        if np.linalg.norm(cross) < sin_min:
            continue
        w = C[i] - C[j]
        b = D[i] @ D[j]
        denom = 1.0 - b * b
        ti = (b * (D[j] @ w) - (D[i] @ w)) / denom
        tj = ((D[j] @ w) - b * (D[i] @ w)) / denom
        far = params.max_triangulation_range_m
        if not (1.0 < ti < far and 1.0 < tj < far):
            continue
        gap = np.linalg.norm((C[i] + ti * D[i]) - (C[j] + tj * D[j]))
        if gap <= params.ray_gap_m + 0.01 * max(ti, tj):
            edges.append((i, j))
    if not edges:
        return []
    e = np.array(edges)
    n = len(rows)
    _, comp = connected_components(coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)),
                                   directed=False)
    out = []
    for c in np.unique(comp):
        members = np.flatnonzero(comp == c)
        while len(members) >= 2:
            x = intersect_rays(C[members], D[members])
            dist = ray_distance(x, C[members], D[members])
            tol = params.ray_gap_m + 0.01 * np.linalg.norm(x - C[members], axis=1)
            worst = int(np.argmax(dist - tol))
            if dist[worst] <= tol[worst]:
                sin_max = max(np.linalg.norm(np.cross(D[a], D[b])) for a in members for b in members)
                if sin_max >= sin_min and depth_sigma_m(x, C[members], dist, sin_max,
                                                        params) <= params.max_depth_sigma_m:
                    out.append((rows[members], x))
                break
            members = np.delete(members, worst)
    return out


# --------------------------------------------------------------------------------------
# The whole step
# --------------------------------------------------------------------------------------

def refine_signs(candidates: ProjectionResult, cloud: Union[str, TiledIndex, None],
                 merge_radius_m: float = DEFAULT_MERGE_RADIUS_M,
                 params: RefineParams = RefineParams(),
                 progress: Progress = SILENT) -> RefineResult:
    """Signs from candidates (see the module doc).

    ``cloud``: the LAS/LAZ path (ground-classified; read only around the candidates) or a
    :class:`TiledIndex` with ``intensity`` and ``classification``. Empty candidates give an
    empty result with a warning.
    """
    if not merge_radius_m or merge_radius_m <= 0:
        raise InputError("The merge radius must be positive, got {value} m", value=merge_radius_m)
    cand = candidates
    det = cand.detections
    result = RefineResult([], [], [], [], np.full(len(cand), -1, np.int64))

    def warn(template, **fields):
        result.warnings.append(progress.warning(template, **fields))

    if len(cand) == 0:
        warn("No candidates to refine; the sign layer is empty")
        return result
    status = np.array(cand.status)
    groups = merge_candidates(cand, merge_radius_m, params)
    progress.report(0.05)

    # the cloud around the candidates
    ok_xyz = cand.xyz_world[status == STATUS_OK]
    index = None
    if isinstance(cloud, TiledIndex):
        index, _ = build_index(cloud, None, 5.0)
    elif cloud is not None and len(ok_xyz):
        region = CropRegion.corridor(max(3.5, merge_radius_m + 2.5), points_xy=ok_xyz[:, :2])
        index, _ = build_index(cloud, region, 5.0, progress.sub(0.05, 0.4))
    bright = bright_level(index) if index is not None else math.inf

    sub = progress.sub(0.4, 0.9)
    signs: List[Tuple[np.ndarray, Optional[Panel], Optional[np.ndarray]]] = []
    for g, rows in enumerate(groups):
        panel, reason = (extract_panel(cand, rows, index, bright, params) if index is not None
                         else (None, Message("no point cloud")))
        if panel is None:
            if reason in NOT_A_SIGN:
                progress.info("Candidates {ids} dropped: {reason}", ids=det.det_id[rows].tolist(),
                              reason=reason)
                continue
            # the views agree on a surface the refinement could not isolate: keep their mean
            progress.info("Candidates {ids}: {reason}; placed at the candidates' median",
                          ids=det.det_id[rows].tolist(), reason=reason)
        signs.append((rows, panel, None))
        sub.report((g + 1) / max(1, len(groups)))

    # a lone view whose box holds a sign found by several views saw that sign: its own
    # candidate is a surface behind (a wall), in front (an occluder) or a stray part of it;
    # it joins the sign (across classes only when the sign is not behind its surface)
    extra: Dict[int, List[int]] = {}
    centres = np.array([p.centre_world if p is not None else np.median(cand.xyz_world[r], axis=0)
                        for r, p, _ in signs]).reshape(-1, 3)
    several = np.array([len(r) >= 2 for r, _, _ in signs], bool)
    sign_class = np.array([vote_class(cand, r)[0] for r, _, _ in signs], dtype=object)
    lone = [n for n, (r, _, _) in enumerate(signs) if len(r) == 1]
    moved = set()
    for n in lone:
        k = int(signs[n][0][0])
        same = several & (sign_class == det.class_name[k])
        target = _sign_in_box(det, k, centres, same, math.inf)
        if target < 0:
            target = _sign_in_box(det, k, centres, several, cand.range_m[k] + 0.5)
        if target >= 0:
            extra.setdefault(target, []).append(k)
            moved.add(n)
    # two groups on one panel (the detector gave one panel two classes, or its views split):
    # one sign whose class is the vote of all its views; the group with more views absorbs
    normals = [p.normal_world if p is not None else None for _, p, _ in signs]
    cos_agree = math.cos(math.radians(params.normal_agreement_deg))
    by_views = sorted(range(len(signs)), key=lambda n: -len(signs[n][0]))
    for i, a in enumerate(by_views):
        if a in moved:
            continue
        for b in by_views[i + 1:]:
            if b in moved or np.linalg.norm(centres[a] - centres[b]) > params.same_panel_radius_m:
                continue
            if normals[a] is not None and normals[b] is not None and \
                    abs(float(np.dot(normals[a], normals[b]))) < cos_agree:
                continue
            extra.setdefault(a, []).extend(list(signs[b][0]) + extra.pop(b, []))
            moved.add(b)
    # views without a surface: attach to a sign whose centre lies in their box (of their class
    # at any range: a sign far ahead, beyond the scanner, found by the views that came near
    # it), else triangulate
    still = []
    for k in np.flatnonzero(status != STATUS_OK):
        same = sign_class == det.class_name[k]
        target = _sign_in_box(det, int(k), centres, same, math.inf, search_m=math.inf)
        if target < 0:
            target = _sign_in_box(det, int(k), centres, np.ones(len(centres), bool), math.inf)
        if target >= 0:
            extra.setdefault(target, []).append(int(k))
        else:
            still.append(int(k))
    loose = np.array(still, np.int64)
    no_points = np.array([k for k in loose if status[k] == STATUS_NO_POINTS], np.int64)
    for rows, x in triangulate_groups(cand, no_points, params):
        signs.append((rows, None, x))

    # records
    sources = []
    kept = [n for n in range(len(signs)) if n not in moved]
    for n_old in kept:
        rows, panel, x_img = signs[n_old]
        views = list(rows) + extra.get(n_old, [])
        klass, score = vote_class(cand, views)
        if panel is not None:
            centre, normal = panel.centre_world, panel.normal_world
            width, panel_h = panel.width_m, panel.height_m
            bottom = float(panel.corners_world[:, 2].min())
            pidx = panel.points.point_index
            mean_int = float(np.mean(panel.points.attributes["intensity"]))
            planarity, source, outline = panel.planarity, "lidar", panel.corners_world
        else:
            w_est, h_est = (box_size_estimate_m(cand, np.asarray(rows)) if x_img is None else
                            _image_size_estimate(cand, np.asarray(rows), x_img))
            if x_img is None:
                centre = np.median(cand.xyz_world[rows], axis=0)
                normal = cand.normal_world[rows].mean(axis=0)
                source = "lidar"
            else:
                centre = x_img
                to = det.centre_world[rows].mean(axis=0) - centre
                normal = np.array([to[0], to[1], 0.0])
                source = "image"
            normal = normal / np.linalg.norm(normal)
            width, panel_h = float(np.median(w_est)), float(np.median(h_est))
            bottom = float(centre[2] - panel_h / 2)
            pidx, mean_int, planarity, outline = np.zeros(0, np.int64), math.nan, math.nan, None
        if max(width, panel_h) > params.max_side_m(klass):
            progress.info("Candidates {ids} dropped: a {width:.2f} x {height:.2f} m panel is too "
                          "large for a {sign_class} sign (a billboard?)",
                          ids=det.det_id[views].tolist(), width=width, height=panel_h,
                          sign_class=klass)
            continue
        ground_z, gsource = ground_with_fallbacks(index, centre, bottom, det.centre_world[views, 2],
                                                  params)
        n_sign = len(result.signs)
        images = []
        for k in sorted(views, key=lambda k: det.det_id[k]):
            if det.image[k] not in images:
                images.append(det.image[k])
        if len(images) == 1 and score < params.min_single_view_score:
            progress.info("Candidates {ids} dropped: seen in one panorama only, with a score of "
                          "{score:.2f}", ids=det.det_id[views].tolist(), score=score)
            continue
        rec = SignRecord(
            sign_id=n_sign + 1, klass=klass, score=score, height=float(centre[2] - ground_z),
            bottom_height=float(bottom - ground_z), width=float(width), panel_height=float(panel_h),
            azimuth=float(geometry.azimuth_deg_of_enu(normal)), n_views=len(images),
            n_points=int(len(pidx)), source_images=";".join(images),
            best_image=det.image[best_view(cand, views, centre, normal)],
            mean_intensity=mean_int, planarity=planarity, position_source=source,
            x=float(centre[0]), y=float(centre[1]), z=float(centre[2]))
        result.signs.append(rec)
        result.outlines_world.append(outline)
        result.point_index.append(pidx)
        result.ground_source.append(gsource)
        sources.append(gsource)
        result.candidate_sign[views] = n_sign
    camera = Message("the stations' height minus {height} m", height=params.camera_height_m)
    for fallback, what in ((LOWEST_POINTS, Message("the lowest points below the sign")),
                           (CAMERA_HEIGHT, camera)):
        count = sources.count(fallback)
        if count:
            warn("{count} sign(s) have no ground points (class 2) within {radius} m: their "
                 "height is measured from {source}", count=count,
                 radius=max(params.ground_radii_m), source=what)
    n_img = sum(s.position_source == "image" for s in result.signs)
    progress.info("{signs} signs from {candidates} candidates ({from_images} placed from the "
                  "images alone)", signs=len(result.signs), candidates=len(cand), from_images=n_img)
    progress.report(1.0)
    return result


def _sign_in_box(det, k: int, centres: np.ndarray, eligible: np.ndarray, max_range_m: float,
                 search_m: float = 60.0) -> int:
    """The nearest eligible sign centre inside detection ``k``'s box (grown by 15 %, 0.5 deg)
    closer to its station than ``max_range_m``; -1 when there is none."""
    if not len(centres):
        return -1
    box = grow_boxes(det.box_px[k:k + 1], det.pano_size_px[k:k + 1], 0.5, 0.15)[0]
    W, H = det.pano_size_px[k]
    R = geometry.matrix_from_quat_wxyz(det.q_world_from_pano_wxyz[k])
    u, v, rng = geometry.world_to_pixel(centres, det.centre_world[k], R, W, H)
    a, b = box_coordinates(u, v, box, W)
    ok = eligible & (a >= 0) & (a <= 1) & (b >= 0) & (b <= 1) & (rng < min(max_range_m, search_m))
    return int(np.flatnonzero(ok)[np.argmin(rng[ok])]) if np.any(ok) else -1


def _image_size_estimate(cand: ProjectionResult, rows: np.ndarray, x: np.ndarray):
    """Panel size from the boxes at the triangulated point's range (frontal assumption)."""
    det = cand.detections
    b, W, H = det.box_px[rows], det.pano_size_px[rows, 0], det.pano_size_px[rows, 1]
    r = np.linalg.norm(det.centre_world[rows] - x, axis=1)
    eps = np.pi * (0.5 - 0.5 * (b[:, 1] + b[:, 3]) / H)
    return (r * (b[:, 2] - b[:, 0]) / W * 2 * np.pi * np.cos(eps),
            r * (b[:, 3] - b[:, 1]) / H * np.pi)


def write_sign_points(input_path: str, output_path: str, point_index: Sequence[np.ndarray],
                      progress: Progress = SILENT) -> int:
    """Copy the points ``point_index`` (positions in ``input_path``) to a LAS/LAZ file with
    everything of the input kept; returns the number written."""
    wanted = np.unique(np.concatenate([np.asarray(p, np.int64) for p in point_index])
                       if len(point_index) else np.zeros(0, np.int64))
    header = read_header(input_path)
    offset = 0
    with CloudWriter(output_path, output_header(header)) as writer:
        for chunk in iter_chunks(input_path, progress=progress):
            lo, hi = np.searchsorted(wanted, [offset, offset + len(chunk)])
            if hi > lo:
                writer.write(chunk[wanted[lo:hi] - offset])
            offset += len(chunk)
        return writer.point_count
