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
   constrained to near-vertical, fitted to the bright points (to all the points when that
   plane turns far from the views' normal: a few bright specks on a faded face) -> points
   within 2.5 sigma of it (darker ones only where they form a surface: the back face) -> PCA
   dimensionality of each point's neighbourhood, dropping clearly linear points (the pole)
   -> convexity test (traffic mirrors are curved) -> the outline in the plane: the points'
   extent, widened up to the views' boxes cast on the plane (sampled points miss sharp
   corners; at most ``box_extent_allowance_m``); centre = centre of the outline, not the
   centroid -> a surface test: a panel whose plane continues beyond a vertical and a
   horizontal side and that is no brighter than that surface is a picture on a billboard or
   a wall, not a sign.
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
5. **Plausible signs** (:func:`plausible`). Dropped, each logged: a panel larger than its
   class allows (a billboard); a sign seen in one panorama only with a weak score, or one
   that other panoramas nearer to its face did not see (:func:`nearer_stations_that_missed`:
   a look-alike boxed once from afar).

Memory (:class:`CloudBlocks`): the cloud is read and refined in blocks of ``block_m`` (150 m)
along the drive, each merged group in the block holding its centre, each block holding only
the points within reach of its groups; the signs do not depend on the block length.

Classes: score-weighted vote of the views; ``score``: ``1 - prod(1 - s)`` over the views of
the winning class; ``best_image``: the view minimising range / cos(incidence).

Codes (:func:`vote_code`): the sign codes read in the views (the candidates' ``code`` and
``code_score``) are put to :func:`.signcodes.vote`, each view weighing its detection score
x its legible side (its crop's side x its box's aspect); the code is kept when it is not
``other`` and its support reaches ``code_confidence``; when its class (codes table) is not
the class vote's, the better supported of the two wins (``code_check``).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import numpy as np
import shapely
from scipy.cluster.hierarchy import fcluster, linkage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from scipy.spatial.distance import squareform

from . import geometry, signcodes
from .cloudsource import CloudSource, conform, open_cloud
from .detections import Detections
from .drivewindows import BLOCK_THREADS, DriveAxis, Spool, Track, make_windows, map_in_order
from .errors import SILENT, InputError, Message, Progress
from .pointcloud import (
    GROUND_CLASS,
    READ_CHUNK_POINTS,
    CloudWriter,
    CropRegion,
    PointSet,
    TiledIndex,
    output_header,
    xyz_of,
)
from .projection import (
    STATUS_NO_POINTS,
    STATUS_OK,
    Plane,
    ProjectionResult,
    box_coordinates,
    build_index,
    check_ground_classified,
    convex_radius_m,
    euclidean_clusters,
    fit_plane_ransac,
    grow_boxes,
    pca,
)
from .schema import Schema, fields, select
from .signcodes import (  # noqa: F401 (CodeVote and the constants are the refine API too)
    CLASS_FROM_CODE,
    CODE_DROPPED,
    DEFAULT_CODE_CONFIDENCE,
    DEFAULT_CROP_MARGIN,
    OTHER_CODE,
    SIGN_CODE_FIELDS,
    CodesTable,
    CodeVote,
    code_support,
    crop_view,
    decide_code,
    is_code,
)

DEFAULT_MERGE_RADIUS_M = 1.0
#: Default length (m along the drive) of the blocks the cloud is refined in (:class:`CloudBlocks`).
DEFAULT_BLOCK_M = 150.0
#: A point of a spooled block (:class:`CloudBlocks`): world coordinates, cloud index, the
#: two dimensions refinement reads (LAS intensity and class).
BLOCK_SPOOL_DTYPE = np.dtype([("xyz", "f8", (3,)), ("point_index", "i8"), ("intensity", "u2"),
                              ("classification", "u1")])
#: Blocks whose read region :class:`CloudBlocks` keeps built while spooling.
REGIONS_HELD = 16
#: A block's hull is buffered by this times its reach with 4 segments a quarter circle, so
#: the coarse polygon holds the region: its edges lie cos(pi/16) of the distance from the
#: hull, and GEOS may simplify the hull it buffers by 1 % of the distance.
HULL_MARGIN = 1.0 / math.cos(math.pi / 16) + 0.02
#: The sign layer (PointZ at the panel centre), one field per :class:`SignRecord` attribute;
#: the code fields (:data:`.signcodes.SIGN_CODE_FIELDS`) follow the score.
SIGN_FIELDS: Schema = fields(("sign_id", int), ("class", str), ("score", float)) + SIGN_CODE_FIELDS + fields(
    ("height", float), ("bottom_height", float),
    ("width", float), ("panel_height", float), ("azimuth", float), ("n_views", int),
    ("n_points", int), ("source_images", str), ("best_image", str), ("mean_intensity", float),
    ("planarity", float), ("position_source", str), ("x", float), ("y", float), ("z", float))
#: The panel outlines layer (PolygonZ: the panel's rectangle in its plane).
OUTLINE_FIELDS: Schema = select(SIGN_FIELDS, ("sign_id", "class", "width", "panel_height"))
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
    code: str = ""
    code_name: str = ""
    code_score: float = math.nan
    code_views: int = 0
    code_check: str = ""

    def as_dict(self) -> Dict:
        d = asdict(self)
        d["class"] = d.pop("klass")
        return {f.name: d[f.name] for f in SIGN_FIELDS}

    @property
    def xyz_world(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])


@dataclass(frozen=True)
class RefineParams:
    """Tuning of :func:`refine_signs`; lengths in metres, angles in degrees."""

    normal_agreement_deg: float = 30.0
    block_threads: int = BLOCK_THREADS   # blocks refined at once (numpy and scipy release the GIL)
    block_max_groups: int = 16           # a block holding more groups is cut, in drive order
    block_max_points: int = 400_000      # a spooled block holding more points is halved
    cross_class_factor: float = 0.5      # different classes merge within this share of the limits
    box_margin_deg: float = 0.12         # box grown for the point vote
    box_margin_frac: float = 0.03
    slab_m: float = 0.3                  # points within this of the candidates' plane
    cluster_tolerance_m: float = 0.12    # at least; else 2 x the 4th-neighbour spacing
    major_cluster_share: float = 0.15    # clusters this big are kept besides the seeds' ones
    plane_threshold_m: float = 0.04
    max_tilt_deg: float = 20.0           # panels lean at most this from vertical
    #: a plane through the bright points that turns more than this from the views' normal is
    #: not the face (a faded face with a few bright specks): the plane goes through all points
    max_bright_plane_turn_deg: float = 15.0
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
    #: sign passing the vehicle is seen from several stations, a lone weak box is mostly noise.
    #: With the rule off, five held-out streets (seeds 7, 11, tiny 3, dusk 21, glare 23) gave
    #: no false single-view sign with either detector of 27 November; the true ones scored
    #: 0.48-0.96, the lowest a rescued 14-25 px sign (models/README.md, "Bundled on 27 November")
    min_single_view_score: float = 0.4
    #: a sign seen in a single panorama is dropped when at least this many other panoramas
    #: that gave detections stand nearer to it, in front of its face and with it low enough
    #: in their views (:func:`nearer_stations_that_missed`), and none of them saw it: a real
    #: sign grows as the vehicle nears it, a look-alike boxed once from afar (such as a
    #: convex mirror) is not boxed again. 0: the rule is off
    single_view_max_nearer_misses: int = 2
    #: what "in front" and "nearer" mean there: within this angle of the face's normal
    #: (horizontal), this elevation above the panorama's horizon, at least this horizontal
    #: range, and at least this much nearer than the station that saw it
    view_check_max_angle_deg: float = 60.0
    view_check_max_elevation_deg: float = 20.0
    view_check_min_range_m: float = 4.0
    view_check_nearer_by_m: float = 1.0

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

#: Candidate rows (positions in a :class:`ProjectionResult`): a list or an integer array.
Rows = Union[Sequence[int], np.ndarray]


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


def vote_class(cand: ProjectionResult, rows: Rows) -> Tuple[str, float]:
    """Score-weighted class vote; score = 1 - prod(1 - s) over the winner's views."""
    det = cand.detections
    weights: Dict[str, float] = {}
    for k in rows:
        weights[det.class_name[k]] = weights.get(det.class_name[k], 0.0) + float(det.score[k])
    winner = max(sorted(weights), key=lambda c: weights[c])
    s = np.array([det.score[k] for k in rows if det.class_name[k] == winner])
    return winner, float(1.0 - np.prod(1.0 - np.clip(s, 0.0, 1.0)))


def _per_view(det: Detections, rows: Rows, of_box: Callable[[np.ndarray, int, int], float]) -> np.ndarray:
    """``of_box(box, panorama width, panorama height)`` for each view ``rows``."""
    return np.array([of_box(det.box_px[k], int(det.pano_size_px[k, 0]), int(det.pano_size_px[k, 1]))
                     for k in rows], float)


def crop_side_px(det: Detections, rows: Rows) -> np.ndarray:
    """Side (pixels) of the crop :func:`.signcodes.cut_crop` cuts for each view's box: the
    box's larger angular side with the default margin, at the panorama's density, clamped to
    8..256 px (the classifier's own margin scales every view of a sign alike)."""
    return _per_view(det, rows, lambda box, W, H: crop_view(box, W, H, DEFAULT_CROP_MARGIN)[0].width_px)


def box_aspect(det: Detections, rows: Rows) -> np.ndarray:
    """Each view's :func:`.signcodes.box_aspect`: 1 for a sign seen face on, small for one
    seen edge-on."""
    return _per_view(det, rows, signcodes.box_aspect)


def legible_side_px(det: Detections, rows: Rows) -> np.ndarray:
    """Each view's :func:`.signcodes.legible_side_px`: its crop's side (:func:`crop_side_px`)
    x its box's aspect (:func:`box_aspect`), the vote's weight per pixel of score."""
    return _per_view(det, rows, signcodes.legible_side_px)


def class_support(cand: ProjectionResult, rows: Rows, klass: str) -> float:
    """How well the views ``rows`` support the class ``klass`` (:func:`.signcodes.class_support`)."""
    rows = np.asarray(list(rows), np.int64)
    return signcodes.class_support([cand.detections.class_name[k] for k in rows], cand.detections.score[rows],
                                   klass)


def vote_code(cand: ProjectionResult, rows: Rows, klass: str, table: Optional[CodesTable] = None,
              confidence: float = DEFAULT_CODE_CONFIDENCE) -> CodeVote:
    """The code of a sign whose views (candidate rows) are ``rows`` and whose class vote
    (:func:`vote_class`) gave ``klass``.

    **Vote.** The views that read a code (non-empty ``code``) vote with
    :func:`.signcodes.vote`, view ``i`` weighing ``w_i = detection score x legible side``
    (:func:`legible_side_px`: the crop's side x the box's aspect) x its code probability
    ``p_i``. The winner's **support** is its share of the vote x the ``w``-weighted mean
    ``p`` of the views that read it (0..1; a code all views read with certainty has 1):
    ``code_score``. ``code_views``: the views that read it. ``code`` and ``code_name`` (from
    ``table``) are left empty when the winner is :data:`.signcodes.OTHER_CODE` or a class
    whose code the table lacks (``unlisted:...``, :func:`.signcodes.is_code`), or its support
    is below ``confidence`` (``code_score`` and ``code_views`` still describe the winner); no
    view with a code: all empty, ``code_score`` NaN.

    **Class check**, for a kept code whose class in ``table`` differs from ``klass`` (when
    ``klass`` is one of the six :data:`.signcodes.SIGN_CLASSES`): the class's support is
    :func:`class_support` (its share of the score-weighted class vote x the mean detection
    score of its views). The better supported one wins: a code with a strictly larger
    support gives the sign its class (``code_check = class_from_code``); else the code is
    emptied (``code_check = code_dropped``; ``code_score`` and ``code_views`` stay those of
    the dropped code). ``code_check`` is empty otherwise. Without a ``table`` the name is
    empty and there is no check.

    :class:`InputError` for a code that is not in ``table``.
    """
    det = cand.detections
    read = [int(k) for k in rows if det.code[k]]
    if not read:
        return CodeVote("", "", math.nan, 0, "", klass)
    codes = [det.code[k] for k in read]
    w = np.clip(np.nan_to_num(det.score[read]), 0.0, None) * legible_side_px(det, read)
    winner, support, n_views = code_support(codes, det.code_score[read], w)
    if table is not None and is_code(winner) and support >= confidence and winner not in table:
        k = read[codes.index(winner)]
        raise InputError("Detection {det_id} has the sign code {code}, which is not in the sign "
                         "codes table {table}: give the codes table the classifier was run with",
                         det_id=int(det.det_id[k]), code=winner, table=table.path)
    return decide_code(winner, support, n_views, klass, lambda: class_support(cand, rows, klass), table,
                       confidence)


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
    """A sign's panel in the cloud: centre and unit normal (world, towards the viewers),
    width and height (m), corners (TL, TR, BR, BL seen from the front, world), its points
    and its planarity. ``points`` is None once the sign is placed (:attr:`SignDraft.placed`
    holds what it needs of them): a drive's drafts then hold 8 bytes a panel point, not 35."""

    centre_world: np.ndarray
    normal_world: np.ndarray
    width_m: float
    height_m: float
    corners_world: np.ndarray
    points: Optional[PointSet]
    planarity: float


def panel_frame(normal: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(right, up) in-plane unit vectors of a panel facing ``normal`` (right as the viewer
    in front sees it)."""
    right = np.cross(-normal, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    return right, np.cross(right, -normal)


def extract_panel(cand: ProjectionResult, rows: np.ndarray, index: TiledIndex, bright: float,
                  params: RefineParams) -> Tuple[Optional[Panel], str]:
    """The panel of one group of views (candidate rows) from the cloud, or (None, reason);
    ``bright``: :func:`bright_level` of the cloud. The steps of the module doc, 2."""
    X, N = cand.xyz_world[rows], cand.normal_world[rows]
    c0 = np.median(X, axis=0)
    n0 = N.mean(axis=0)
    n0 /= np.linalg.norm(n0)
    pts = points_near_views(cand, rows, index, c0, n0, params)
    if len(pts) < params.min_panel_points:
        return None, Message("too few points")
    pts = points_in_boxes(cand, rows, pts, params)
    if len(pts) < params.min_panel_points:
        return None, Message("too few points in the boxes")
    spacing = point_spacing_m(pts.xyz_world)
    pts = seeded_clusters(pts, X, params)
    bright_mask = retroreflective_mask(pts.attributes["intensity"].astype(float), bright, params)
    on_plane = points_on_plane(pts, bright_mask, spacing, params, n0)
    if on_plane is None:
        return None, Message("no near-vertical plane")
    panel_pts, plane = on_plane
    panel_pts = drop_linear_points(panel_pts, spacing, params)
    if len(panel_pts) < params.min_panel_points:
        return None, Message("too few planar points")
    centroid, ev, V = pca(panel_pts.xyz_world)
    normal = panel_normal(ev, V, plane.normal, n0, params)
    if convex_radius_m(panel_pts.xyz_world, normal) < params.min_convex_radius_m:
        return None, CURVED_SURFACE
    planarity = float(1.0 - ev[2] / ev[1]) if ev[1] > 0 else 0.0
    panel, spacing_in_plane = panel_outline(cand, rows, panel_pts, centroid, normal, planarity,
                                            params)
    if on_larger_surface(panel, index, bright, spacing_in_plane, params):
        return None, LARGER_SURFACE
    return panel, ""


def points_near_views(cand: ProjectionResult, rows: np.ndarray, index: TiledIndex,
                      centre: np.ndarray, normal: np.ndarray, params: RefineParams) -> PointSet:
    """The non-ground points within reach of a panel at ``centre`` (world; 0.75 x the largest
    side the views' boxes imply, plus 0.3 m) and within ``slab_m`` of the plane through it
    facing ``normal`` (unit, world)."""
    w_est, h_est = box_size_estimate_m(cand, rows)
    radius = 0.75 * float(max(w_est.max(), h_est.max())) + 0.3
    pts = index.query_radius(centre, radius)
    return pts.subset((pts.attributes["classification"] != GROUND_CLASS)
                      & (np.abs((pts.xyz_world - centre) @ normal) < params.slab_m))


def points_in_boxes(cand: ProjectionResult, rows: np.ndarray, pts: PointSet,
                    params: RefineParams) -> PointSet:
    """The points ``pts`` that project inside the boxes (grown by ``box_margin_deg`` /
    ``box_margin_frac``) of at least half the views ``rows``."""
    det = cand.detections
    boxes = grow_boxes(det.box_px[rows], det.pano_size_px[rows], params.box_margin_deg,
                       params.box_margin_frac)
    R = geometry.matrix_from_quat_wxyz(det.q_world_from_pano_wxyz[rows])
    votes = np.zeros(len(pts), np.int64)
    for j, k in enumerate(rows):
        W, H = det.pano_size_px[k]
        u, v, _ = geometry.world_to_pixel(pts.xyz_world, det.centre_world[k], R[j], W, H)
        a, b = box_coordinates(u, v, boxes[j], W)
        votes += (a >= 0) & (a <= 1) & (b >= 0) & (b <= 1)
    return pts.subset(votes >= max(1, math.ceil(0.5 * len(rows))))


def seeded_clusters(pts: PointSet, seeds_world: np.ndarray, params: RefineParams) -> PointSet:
    """The points of the Euclidean clusters (tolerance ``cluster_tolerance_m``, at least twice
    the 4th-neighbour spacing: across scan lines) holding the point nearest a seed (the
    candidates' surface points, world), and of those holding ``major_cluster_share`` of the
    points or more (a scan gap may split a panel)."""
    labels = euclidean_clusters(pts.xyz_world, max(params.cluster_tolerance_m,
                                                   2.0 * point_spacing_m(pts.xyz_world, 4)))
    _, seeds = cKDTree(pts.xyz_world).query(seeds_world)
    counts = np.bincount(labels)
    big = np.flatnonzero(counts >= params.major_cluster_share * len(pts))
    return pts.subset(np.isin(labels, np.union1d(labels[seeds], big)))


def retroreflective_mask(intensity: np.ndarray, bright: float, params: RefineParams) -> np.ndarray:
    """Intensity filter: the points (bool mask) above the Otsu threshold of ``intensity``
    when they are a retroreflective mode (at least ``min_panel_points``, mean at least
    ``bright`` while the others' is below it); else all points (a faded face)."""
    mask = np.ones(len(intensity), bool)
    if len(intensity) >= 2 * params.min_panel_points and np.ptp(intensity) > 0:
        high = intensity >= otsu_threshold(intensity)
        if (high.sum() >= params.min_panel_points and intensity[high].mean() >= bright
                and intensity[~high].mean() < bright):
            mask = high
    return mask


def points_on_plane(pts: PointSet, bright_mask: np.ndarray, spacing_m: float,
                    params: RefineParams, views_normal: Optional[np.ndarray] = None
                    ) -> Optional[Tuple[PointSet, Plane]]:
    """RANSAC plane (leaning at most ``max_tilt_deg`` from vertical) through the points
    ``bright_mask``, and the points within 2.5 sigma of it (1.5 cm to ``plane_threshold_m``):
    the bright ones, and the darker ones whose neighbourhood (radius ``pca_radius_m``, at
    least 3 x ``spacing_m``) is planar (the back face seen where the front was not scanned),
    not linear (the pole). None when the plane has fewer than ``min_panel_points`` inliers.

    When that plane turns more than ``max_bright_plane_turn_deg`` from ``views_normal`` (unit,
    world: the candidates' mean normal) and the plane through all the points turns less, the
    bright points are specks on a faded face, not the face: all the points count as bright."""
    plane = fit_plane_ransac(pts.xyz_world[bright_mask], params.plane_threshold_m,
                             params.max_tilt_deg)
    min_cos = math.cos(math.radians(params.max_bright_plane_turn_deg))
    if views_normal is not None and not bright_mask.all() and (
            plane is None or abs(plane.normal @ views_normal) < min_cos):
        whole = fit_plane_ransac(pts.xyz_world, params.plane_threshold_m, params.max_tilt_deg)
        if whole is not None and abs(whole.normal @ views_normal) >= min_cos:
            plane, bright_mask = whole, np.ones(len(pts), bool)
    if plane is None or plane.inliers.sum() < params.min_panel_points:
        return None
    res = plane.distance(pts.xyz_world)
    sigma = 1.4826 * float(np.median(np.abs(res[bright_mask][plane.inliers])))
    tight = np.abs(res) < min(params.plane_threshold_m, max(0.015, 2.5 * sigma))
    keep = bright_mask.copy()
    dark = np.flatnonzero(tight & ~bright_mask)
    if dark.size >= 5:
        feats = dimensionality(pts.xyz_world[dark], max(params.pca_radius_m, 3.0 * spacing_m))
        keep[dark[np.argmax(feats, axis=1) == 1]] = True
    return pts.subset(tight & keep), plane


def drop_linear_points(panel: PointSet, spacing_m: float, params: RefineParams) -> PointSet:
    """Pole filter: drop the points whose neighbourhood (radius ``pca_radius_m``, at least
    3 x ``spacing_m``) is clearly linear (a1D >= ``linear_threshold``) or scattered (isolated
    points), unless that would take more than ``max_linear_share`` of the panel or leave
    fewer than ``min_panel_points`` (a face scanned in a few profiles looks linear
    everywhere). Edges of a panel look half linear: they stay."""
    feats = dimensionality(panel.xyz_world, max(params.pca_radius_m, 3.0 * spacing_m))
    keep = (feats[:, 0] < params.linear_threshold) & (np.argmax(feats, axis=1) != 2)
    if keep.sum() >= max(params.min_panel_points, (1.0 - params.max_linear_share) * len(panel)):
        return panel.subset(keep)
    return panel


def panel_normal(ev: np.ndarray, V: np.ndarray, plane_normal: np.ndarray, views_normal: np.ndarray,
                 params: RefineParams) -> np.ndarray:
    """The panel's unit normal (world) towards the viewers (the side of ``views_normal``),
    from its points' PCA (eigenvalues ``ev`` descending, eigenvectors ``V`` in columns): the
    least-spread axis; the RANSAC ``plane_normal`` when that leans more than
    ``max_tilt_deg`` from horizontal; ``views_normal`` when the points are a line (spread
    across less than ``min_spread_ratio`` x along: a sparse scan across the face)."""
    normal = V[:, 2]
    if (normal @ views_normal) < 0:
        normal = -normal
    if abs(normal[2]) > math.sin(math.radians(params.max_tilt_deg)):
        normal = plane_normal if plane_normal @ views_normal > 0 else -plane_normal
    if ev[1] < params.min_spread_ratio ** 2 * ev[0]:
        normal = views_normal
    return normal


def panel_outline(cand: ProjectionResult, rows: np.ndarray, points: PointSet, centroid: np.ndarray,
                  normal: np.ndarray, planarity: float, params: RefineParams) -> Tuple[Panel, float]:
    """The panel of ``points`` whose outline in the plane through ``centroid``
    facing ``normal`` is the points' extent, each side widened to the views' boxes cast on
    the plane by at most ``box_extent_allowance_m`` (or 4 point spacings), else by half a
    spacing (sampled points miss sharp corners); centre = centre of the outline. Also the
    points' spacing in the plane (m)."""
    right, up = panel_frame(normal)
    rel = points.xyz_world - centroid
    s, t = rel @ right, rel @ up
    spacing = point_spacing_m(np.column_stack([s, t, np.zeros_like(s)]))
    box_ext = box_extents_in_plane(cand, rows, centroid, normal, right, up)
    allowance = max(4.0 * spacing, params.box_extent_allowance_m)
    ext = []
    for e_pts, e_box in zip((-s.min(), s.max(), -t.min(), t.max()),
                            (-box_ext[0], box_ext[1], -box_ext[2], box_ext[3])):
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
    return Panel(centre, normal, float(s1 - s0), float(t1 - t0), corners, points, planarity), spacing


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
    assert panel.points is not None
    own = float(np.median(panel.points.attributes["intensity"]))
    return not (own >= bright and around.size and float(np.median(around)) < bright)


def box_extents_in_plane(cand: ProjectionResult, rows: Rows, origin: np.ndarray,
                         normal: np.ndarray, right: np.ndarray, up: np.ndarray,
                         samples: int = 17) -> np.ndarray:
    """The views' boxes cast on a panel's plane: median over the views of (left, right,
    bottom, top) in-plane coordinates (metres from ``origin`` along ``right`` / ``up``).

    Columns of a level panorama are vertical lines, so the box's left and right edges meet
    the plane at one ``s`` each; along the top edge the panel lies below every ray, so the
    top is the lowest hit (the bottom, the highest). NaN where no view meets the plane."""
    det = cand.detections
    g = np.linspace(0.0, 1.0, samples)
    out: List[List[float]] = []
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
        reducers: Tuple[Tuple[np.ndarray, Callable[[np.ndarray], Any]], ...] = (
            (s, np.median), (s, np.median), (t, np.max), (t, np.min))
        for j, (coord, reduce) in enumerate(reducers):
            m = valid[parts[j]]
            vals.append(float(reduce(coord[parts[j]][m])) if m.any() else np.nan)
        out.append(vals)
    extents = np.array(out, float)
    if not np.any(np.isfinite(extents)):
        return np.full(4, np.nan)
    return np.nanmedian(extents, axis=0)


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


#: :func:`ground_from_cloud` found nothing: the camera-height fallback applies.
NO_CLOUD_GROUND: Tuple[float, str] = (math.nan, "")


def ground_from_cloud(index: Optional[TiledIndex], centre: np.ndarray, bottom_z: float,
                      params: RefineParams) -> Tuple[float, str]:
    """Ground height below ``centre`` from the cloud (ground points, else the lowest points;
    the module doc) and how it was found; :data:`NO_CLOUD_GROUND` when neither applies. Reads
    points within ``max(ground_radii_m)`` (horizontally, a square) of ``centre``."""
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
    return NO_CLOUD_GROUND


def ground_with_fallbacks(index: Optional[TiledIndex], centre: np.ndarray, bottom_z: float,
                          station_z: np.ndarray, params: RefineParams,
                          from_cloud: Optional[Tuple[float, str]] = None) -> Tuple[float, str]:
    """Ground height below ``centre`` and how it was found (see the module doc);
    ``from_cloud``: :func:`ground_from_cloud`'s answer when already known (``index`` unused)."""
    found = ground_from_cloud(index, centre, bottom_z, params) if from_cloud is None else from_cloud
    if found[1]:
        return found
    return float(np.median(station_z)) - params.camera_height_m, CAMERA_HEIGHT


def best_view(cand: ProjectionResult, rows: Rows, centre: np.ndarray,
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
                sin_max = max(float(np.linalg.norm(np.cross(D[a], D[b])))
                              for a in members for b in members)
                if sin_max >= sin_min and depth_sigma_m(x, C[members], dist, sin_max,
                                                        params) <= params.max_depth_sigma_m:
                    out.append((rows[members], x))
                break
            members = np.delete(members, worst)
    return out


# --------------------------------------------------------------------------------------
# The whole step
# --------------------------------------------------------------------------------------

@dataclass
class SignDraft:
    """A sign before its record: the views (candidate rows) that found it, its panel in the
    cloud (None: placed at the views' median surface point, or triangulated), the
    triangulated point (world; image-only signs), the views (candidate rows) that joined it
    later, and whether another sign absorbed it (its views then count there)."""

    rows: np.ndarray
    panel: Optional[Panel] = None
    x_image: Optional[np.ndarray] = None
    joined: List[int] = field(default_factory=list)
    absorbed: bool = False
    #: :func:`ground_from_cloud` at its placement, when found block by block (None: ask the index)
    ground: Optional[Tuple[float, str]] = None
    #: its :func:`placement`, once found (its panel's points are then let go)
    placed: Optional["Placement"] = None

    @property
    def views(self) -> List[int]:
        """All its views (candidate rows): its own, then those that joined it."""
        return list(self.rows) + self.joined


@dataclass
class Placement:
    """Where a sign is: ``centre`` (world), unit ``normal`` (world, towards the viewers),
    panel width and height (m), ``bottom_z`` (world z of its lower edge), the LAS indices of
    its points, their mean intensity and the panel's planarity (NaN without points),
    ``source`` (the ``position_source``: lidar or image) and its outline (4 corners TL, TR,
    BR, BL seen from the front, world; None without a panel)."""

    centre: np.ndarray
    normal: np.ndarray
    width_m: float
    height_m: float
    bottom_z: float
    point_index: np.ndarray
    mean_intensity: float
    planarity: float
    source: str
    outline: Optional[np.ndarray]


def refine_signs(candidates: ProjectionResult, cloud: Union[str, TiledIndex, None],
                 merge_radius_m: float = DEFAULT_MERGE_RADIUS_M,
                 params: RefineParams = RefineParams(),
                 progress: Progress = SILENT, codes_table: Optional[CodesTable] = None,
                 code_confidence: float = DEFAULT_CODE_CONFIDENCE,
                 block_m: float = DEFAULT_BLOCK_M) -> RefineResult:
    """Signs from candidates (see the module doc).

    ``cloud``: the LAS/LAZ path (ground-classified; read only around the candidates) or a
    :class:`TiledIndex` with ``intensity`` and ``classification``. Empty candidates give an
    empty result with a warning. ``codes_table`` (names and classes of the codes) and
    ``code_confidence``: the code vote, :func:`vote_code`. ``block_m``: the cloud is read
    and refined in blocks of this length along the drive (:class:`CloudBlocks`; ``inf``:
    one block, the whole drive at once); the result does not depend on it.
    """
    if not merge_radius_m or merge_radius_m <= 0:
        raise InputError("The merge radius must be positive, got {value} m", value=merge_radius_m)
    result = RefineResult([], [], [], [], np.full(len(candidates), -1, np.int64))
    if len(candidates) == 0:
        warn(result, progress, "No candidates to refine; the sign layer is empty")
        return result
    groups = merge_candidates(candidates, merge_radius_m, params)
    progress.report(0.05)
    with CloudBlocks(candidates, groups, cloud, merge_radius_m, block_m, params, progress.sub(0.05, 0.3)) as blocks:
        drafts = blocks.extract_signs(params, progress.sub(0.3, 0.9))
        join_lone_views(candidates, drafts)
        join_signs_on_one_panel(candidates, drafts, params)
        unplaced = join_views_without_surface(candidates, drafts)
        image_only = triangulate_image_only(candidates, unplaced, params)
        blocks.ground_of(image_only, params)
    drafts += image_only
    stations = DetectedStations.of(candidates)
    for draft in drafts:
        if not draft.absorbed:
            add_sign(result, candidates, draft, None, params, progress, codes_table, code_confidence,
                     stations)
    warn_ground_fallbacks(result, params, progress)
    log_codes(result, progress)
    n_img = sum(s.position_source == "image" for s in result.signs)
    progress.info("{signs} signs from {candidates} candidates ({from_images} placed from the "
                  "images alone)", signs=len(result.signs), candidates=len(candidates),
                  from_images=n_img)
    progress.report(1.0)
    return result


def warn(result: RefineResult, progress: Progress, template: str, **values: object) -> None:
    """Log the warning ``template`` (English, ``{named}`` fields) and keep it in ``result``."""
    result.warnings.append(progress.warning(template, **values))


def cloud_around_candidates(cand: ProjectionResult, cloud: Union[str, TiledIndex, None],
                            merge_radius_m: float, progress: Progress = SILENT
                            ) -> Optional[TiledIndex]:
    """The cloud indexed in 5 m tiles with intensity and classification: ``cloud`` itself when
    it is an index, else read from the LAS/LAZ path within max(3.5, ``merge_radius_m`` + 2.5)
    m (horizontally) of the ``ok`` candidates; None without a cloud or such candidates.
    :class:`InputError` when it has no ground points (class 2)."""
    if isinstance(cloud, TiledIndex):
        return build_index(cloud, None, 5.0)[0]
    ok_xyz = cand.xyz_world[np.array(cand.status) == STATUS_OK]
    if cloud is None or not len(ok_xyz):
        return None
    region = CropRegion.corridor(max(3.5, merge_radius_m + 2.5), points_xy=ok_xyz[:, :2])
    return build_index(cloud, region, 5.0, progress)[0]


def median_of_counts(values: np.ndarray, counts: np.ndarray) -> float:
    """The median (as :func:`numpy.median`: the mean of the two middle ones for an even count)
    of the multiset holding ``counts[k]`` times ``values[k]``; NaN when empty."""
    order = np.argsort(values, kind="stable")
    v, c = np.asarray(values, float)[order], np.asarray(counts, np.int64)[order]
    n = int(c.sum())
    if n == 0:
        return math.nan
    cum = np.cumsum(c)
    lo = float(v[np.searchsorted(cum, (n - 1) // 2 + 1)])
    hi = float(v[np.searchsorted(cum, n // 2 + 1)])
    return 0.5 * (lo + hi)


def bright_level_of_histogram(hist: np.ndarray) -> float:
    """:func:`bright_level` of the non-ground intensities counted in ``hist`` (count per
    integer intensity), exact over all of them (no sample)."""
    values = np.arange(len(hist), dtype=float)
    med = median_of_counts(values, hist)
    if not np.isfinite(med):
        return math.inf
    return med + 4.0 * 1.4826 * median_of_counts(np.abs(values - med), hist)


def drive_axis_of(cand: ProjectionResult) -> Optional[DriveAxis]:
    """The drive as an axis through the candidates' stations (in time order when all have
    times, else by station id); None when they do not span a drive (fewer than 2 places)."""
    det = cand.detections
    if not len(det.station_id):
        return None
    first = det.station_rows()
    xyz, t = det.centre_world[first], det.time_s[first]
    order = np.argsort(t, kind="stable") if np.all(np.isfinite(t)) else np.arange(len(first))
    try:
        return DriveAxis(Track(xyz[order]))
    except InputError:
        return None


def cut_blocks(blocks: List[np.ndarray], s_m: np.ndarray, max_groups: int) -> List[np.ndarray]:
    """``blocks`` (group numbers per block) with every block of more than ``max_groups``
    groups cut into near-equal runs of them in drive order (``s_m``: the groups' arc length).
    A block's points, and so its memory, grow with its groups: a stretch dense with signs
    would otherwise hold more than any other, and the longer the drive, the denser its
    densest stretch."""
    out = []
    for gs in blocks:
        if len(gs) <= max_groups:
            out.append(gs)
            continue
        ordered = gs[np.argsort(s_m[gs], kind="stable")]
        out.extend(np.sort(part) for part in np.array_split(ordered, -(-len(gs) // max_groups)))
    return out


class CloudBlocks:
    """The cloud around the candidates, read and refined block by block along the drive.

    The merged groups (:func:`merge_candidates`, over the whole drive: candidates are few)
    are put in blocks of ``block_m`` metres along the drive (:mod:`.drivewindows`: arc length
    of the group's centre on the axis through the stations), each group in the one block
    holding its centre, so a group straddling a block seam is refined once, with all its
    points; a block of more than ``params.block_max_groups`` groups is cut (:func:`cut_blocks`).
    A block's points are read (a spatial query: only the tiles it meets; a
    :class:`TiledIndex` given is cut instead) within the reach of its groups (points near
    the views, the surface around the panel and the ground under it: :meth:`reach_m`), and
    kept only when the single-index read would hold them (``max(3.5, merge_radius_m + 2.5)``
    m from an ``ok`` candidate), so every query a group makes sees exactly the points it saw
    in one index: the result does not depend on ``block_m``. Only one block is held at a
    time. The bright level (:func:`bright_level`) is cloud wide: from a first pass over the
    blocks, a histogram of the non-ground intensities, each point counted in the block of
    its nearest ``ok`` candidate (exact; the one-index read samples 200 000 points, so
    above that size the level may differ slightly). Image-only signs take their ground from
    the points around them, one block of them at a time (:meth:`ground_of`).

    The cloud is read once: a single block is read and kept; several blocks are spooled
    first, in one pass over the tiles they meet, each block's points (coordinates, cloud
    index, intensity, class: :data:`BLOCK_SPOOL_DTYPE`) appended to a file of its own in a
    temporary folder, which each pass over the blocks, and the ground of image-only signs,
    then read back (:meth:`close`, or leaving a ``with`` block, removes it).

    Nothing held grows with the drive but the candidates and the drafts: the corridor of the
    ``ok`` candidates is built only around the points tested (:meth:`_corridor_mask`), and a
    block's read region only while chunks meet it (:meth:`_region`, at most
    :data:`REGIONS_HELD` at a time); the shapes of the whole drive took 10 MB on 9 km.
    """

    def __init__(self, cand: ProjectionResult, groups: Sequence[np.ndarray],
                 cloud: Union[str, CloudSource, TiledIndex, None], merge_radius_m: float,
                 block_m: float, params: RefineParams, progress: Progress = SILENT):
        self.cand, self.groups = cand, list(groups)
        self._spool: Optional[Spool] = None
        ok = np.array([s == STATUS_OK for s in cand.status], bool)
        self.ok_xy = cand.xyz_world[ok, :2]
        self.corridor_m = max(3.5, merge_radius_m + 2.5)
        self.index: Optional[TiledIndex] = None
        self.source: Optional[CloudSource] = None
        if isinstance(cloud, TiledIndex):
            self.index = build_index(cloud, None, 5.0)[0]
        elif cloud is not None and len(self.ok_xy):
            self.source = open_cloud(cloud)
        self._regions: Dict[int, CropRegion] = {}
        self.centres = np.array([np.median(cand.xyz_world[g], axis=0) for g in self.groups]
                                ).reshape(-1, 3)
        self.reach = np.array([self.reach_m(cand, g, params) for g in self.groups])
        self._axis = drive_axis_of(cand) if math.isfinite(block_m) and len(self.groups) else None
        self._block_edges_m = np.zeros(0)
        if self._axis is not None:
            windows = make_windows(self._axis.length_m, block_m)
            self._block_edges_m = np.array([w.s1_m for w in windows[:-1]])
        block_of_group = self._block_of(self.centres)
        self.blocks = [np.flatnonzero(block_of_group == b) for b in np.unique(block_of_group)]
        if self._axis is not None:   # blocks along a drive (not one block: block_m inf)
            self.blocks = cut_blocks(self.blocks, self._axis.locate(self.centres)[0], params.block_max_groups)
        self._cached: Optional[Tuple[int, TiledIndex]] = None
        self._boxes: Optional[np.ndarray] = None     # each block's read box (x0, y0, x1, y1), when asked for
        self._spool_ids = list(range(len(self.blocks)))   # block k's points: spool file _spool_ids[k]
        try:
            if self.source is not None and len(self.blocks) > 1:
                self._spool_blocks(progress)
                self._halve_dense_blocks(params.block_max_points, progress)
            self.bright = self._bright_level()
            progress.report(1.0)
        except BaseException:   # cancelled or a bad tile while reading: no spool folder left behind
            self.close()
            raise

    def __enter__(self) -> "CloudBlocks":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Remove the spooled blocks."""
        if self._spool is not None:
            self._spool.close()
            self._spool = None

    def _block_of(self, xyz_world: np.ndarray) -> np.ndarray:
        """The block (window number along the drive) holding each point ``(n, 3)``."""
        if self._axis is None or not len(xyz_world):
            return np.zeros(len(xyz_world), np.int64)
        return np.searchsorted(self._block_edges_m, self._axis.locate(xyz_world)[0], side="right")

    def _block_read(self, b: int) -> Tuple[np.ndarray, float]:
        """Where block ``b``'s points are read around (centres ``(n, 2)``) and how far."""
        return self._groups_read(self.blocks[b])

    def _groups_read(self, gs: np.ndarray) -> Tuple[np.ndarray, float]:
        """Where the points of groups ``gs`` are read around (centres ``(n, 2)``) and how far."""
        rows = np.concatenate([self.groups[g] for g in gs])
        xy = np.vstack([self.centres[gs, :2], self.cand.xyz_world[rows, :2]])
        return xy, max(float(self.reach[gs].max()), self.corridor_m + 0.5)

    @staticmethod
    def _box(xy: np.ndarray, radius_m: float) -> Tuple[float, float, float, float]:
        """The 2D box ``(x0, y0, x1, y1)`` of the points within ``radius_m`` of ``xy``."""
        (x0, y0), (x1, y1) = xy.min(axis=0) - radius_m, xy.max(axis=0) + radius_m
        return float(x0), float(y0), float(x1), float(y1)

    def _spool_blocks(self, progress: Progress) -> None:
        """One pass over the cloud: each block's points to its file (see the class doc)."""
        assert self.source is not None
        area, boxes = [], []
        for b in range(len(self.blocks)):
            xy, radius = self._block_read(b)
            boxes.append(self._box(xy, radius))
            # the tiles and chunks to read: a hull around the block's read region (a few
            # vertices a block; the region itself is built when a chunk meets it)
            area.append(shapely.convex_hull(shapely.multipoints(xy)).buffer(radius * HULL_MARGIN + 0.01, 4))
        self._spool = spool = Spool({"block": BLOCK_SPOOL_DTYPE}, prefix="roadsigns-refine-")
        box_of_block = np.array(boxes, np.float64).reshape(-1, 4)
        for index, chunk in self.source.iter_indexed_chunks(READ_CHUNK_POINTS, progress=progress, area=area):
            x, y = np.asarray(chunk.x), np.asarray(chunk.y)
            near = np.flatnonzero(self._corridor_mask(x, y))
            if not len(near):
                continue
            xn, yn = x[near], y[near]
            # only the blocks whose box meets the chunk's points: a chunk lies along a few of
            # them, and testing every block of the drive would grow with the drive
            meets = np.flatnonzero((box_of_block[:, 0] <= xn.max()) & (box_of_block[:, 2] >= xn.min())
                                   & (box_of_block[:, 1] <= yn.max()) & (box_of_block[:, 3] >= yn.min()))
            for b in meets:
                x0, y0, x1, y1 = boxes[b]
                sub = near[(xn >= x0) & (xn <= x1) & (yn >= y0) & (yn <= y1)]
                if not len(sub):
                    continue
                sub = sub[self._region(b).mask(x[sub], y[sub])]
                if not len(sub):
                    continue
                rows = np.zeros(len(sub), BLOCK_SPOOL_DTYPE)
                rows["xyz"] = xyz_of(chunk[sub])
                rows["point_index"] = np.asarray(index)[sub]
                rows["intensity"] = np.asarray(chunk.intensity)[sub]
                rows["classification"] = np.asarray(chunk.classification)[sub]
                spool.append("block", b, rows)
        spool.flush()
        self._regions.clear()

    def _halve_dense_blocks(self, max_points: int, progress: Progress = SILENT) -> None:
        """Halve every spooled block of more than ``max_points`` points and more than one
        group: its groups in two runs in drive order, each keeping the block's points within
        its own reach (:meth:`_groups_read`) in a spool file of its own; again while a half
        is over. A block's points follow its area more than its groups (correlation 0.5 on
        a 9 km drive), so the densest block, which two block threads hold at once with its
        index, grew with the drive (452 k points on 1 km, 564 k on 9 km)."""
        assert self._spool is not None
        s_m = self._axis.locate(self.centres)[0] if self._axis is not None else np.zeros(len(self.groups))
        next_id = [len(self.blocks)]

        def halved(gs: np.ndarray, sid: int) -> List[Tuple[np.ndarray, int]]:
            assert self._spool is not None
            if len(gs) < 2 or self._spool.count("block", sid) <= max_points:
                return [(gs, sid)]
            progress.check()
            rows = self._spool.read("block", sid)
            ordered = gs[np.argsort(s_m[gs], kind="stable")]
            parts = []
            for half in (np.sort(ordered[:len(gs) // 2]), np.sort(ordered[len(gs) // 2:])):
                xy, radius = self._groups_read(half)
                mine = CropRegion.corridor(radius, points_xy=xy).mask(rows["xyz"][:, 0], rows["xyz"][:, 1])
                parts.append((half, next_id[0]))
                self._spool.append("block", next_id[0], rows[mine])
                next_id[0] += 1
            del rows
            self._spool.discard("block", sid)
            return [piece for half, hid in parts for piece in halved(half, hid)]

        pieces = [piece for gs, sid in zip(self.blocks, self._spool_ids) for piece in halved(gs, sid)]
        self.blocks = [gs for gs, _ in pieces]
        self._spool_ids = [sid for _, sid in pieces]

    def _region(self, b: int) -> CropRegion:
        """Block ``b``'s read region, built when first asked for; only the last
        :data:`REGIONS_HELD` blocks' are kept (a chunk meets a few neighbouring blocks, and
        the tiles run along the drive)."""
        if b not in self._regions:
            if len(self._regions) >= REGIONS_HELD:
                del self._regions[next(iter(self._regions))]
            xy, radius = self._block_read(b)
            self._regions[b] = CropRegion.corridor(radius, points_xy=xy)
        return self._regions[b]

    def _corridor_in(self, lo_xy: np.ndarray, hi_xy: np.ndarray) -> CropRegion:
        """The corridor (``corridor_m`` around the ``ok`` candidates) as it is inside the box
        ``lo_xy``-``hi_xy``: built from the candidates that can reach the box, so its shape
        there is the drive-wide corridor's, without building that."""
        reach = self.corridor_m * (1.0 + 1e-9) + 1e-6
        near = np.all((self.ok_xy >= np.asarray(lo_xy) - reach) & (self.ok_xy <= np.asarray(hi_xy) + reach), axis=1)
        if not near.any():
            return CropRegion(shapely.Polygon())
        return CropRegion.corridor(self.corridor_m, points_xy=self.ok_xy[near])

    def _corridor_mask(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Which points ``(x, y)`` lie within ``corridor_m`` of an ``ok`` candidate (the
        one-index read's corridor, :func:`cloud_around_candidates`)."""
        if not len(x):
            return np.zeros(0, bool)
        return self._corridor_in(np.array([x.min(), y.min()]), np.array([x.max(), y.max()])).mask(x, y)

    def _spooled(self, b: int) -> TiledIndex:
        """Block ``b`` read back from its spool file."""
        assert self.source is not None and self._spool is not None
        return self._index_of(self._spool.read("block", self._spool_ids[b]))

    def _index_of(self, rows: np.ndarray) -> TiledIndex:
        """The index of spooled points (:data:`BLOCK_SPOOL_DTYPE`)."""
        assert self.source is not None
        # the fields as views: the index sorts them into arrays of its own (no copy between)
        return TiledIndex(rows["xyz"], rows["point_index"],
                          {"intensity": rows["intensity"], "classification": rows["classification"]},
                          5.0, self.source.crs_wkt)

    @staticmethod
    def reach_m(cand: ProjectionResult, rows: np.ndarray, params: RefineParams) -> float:
        """How far (horizontally) from the group's centre refining it may look: the points
        near the views (radius ``r``), the surface around a panel within ``r`` of it (at most
        ``sqrt 2 (r + 0.1 + surround_band_m)``) and the ground under it."""
        w_est, h_est = box_size_estimate_m(cand, rows)
        r = 0.75 * float(max(w_est.max(), h_est.max())) + 0.3
        around = math.sqrt(2) * (r + params.box_extent_allowance_m + params.surround_band_m)
        ground = math.sqrt(2) * max(params.ground_radii_m)
        return r + params.box_extent_allowance_m + max(around, ground) + 0.5

    def _read(self, centres_xy: np.ndarray, radius_m: float,
              progress: Progress = SILENT) -> TiledIndex:
        """The points within ``radius_m`` of ``centres_xy`` that the one-index read holds."""
        region = CropRegion.corridor(radius_m, points_xy=centres_xy)
        if self.index is not None:
            src = self.index
            m = region.mask(src.xyz_world[:, 0], src.xyz_world[:, 1])
            return TiledIndex(src.xyz_world[m], src.point_index[m],
                              {k: v[m] for k, v in src.attributes.items()}, src.tile_size_m,
                              src.crs_wkt)
        assert self.source is not None
        idx = self.source.index(region, ("intensity", "classification"), 5.0, READ_CHUNK_POINTS, progress)
        m = self._corridor_mask(idx.xyz_world[:, 0], idx.xyz_world[:, 1])
        if m.all():
            return idx
        out = TiledIndex(idx.xyz_world[m], idx.point_index[m],
                         {k: v[m] for k, v in idx.attributes.items()}, 5.0, idx.crs_wkt)
        del idx
        return out

    def _around(self, centres_xy: np.ndarray, radius_m: float) -> TiledIndex:
        """The points within ``radius_m`` of ``centres_xy`` that the one-index read holds:
        from the spooled blocks when there are some (:meth:`_spooled_around`: the cloud is not
        read again), else read (:meth:`_read`)."""
        if self._spool is not None:
            return self._spooled_around(centres_xy, radius_m)
        return self._read(centres_xy, radius_m)

    def _spooled_around(self, centres_xy: np.ndarray, radius_m: float) -> TiledIndex:
        """:meth:`_read` without reading the cloud: from the spool files of the blocks whose
        read box meets the area, each point once (a point near a seam is in two blocks).

        The same points: every point of the corridor (``corridor_m`` around an ``ok``
        candidate) is in the spool file of the block holding that candidate's group, whose
        region reaches at least ``corridor_m + 0.5`` around each of its candidates (a halved
        block's halves too), and only corridor points are spooled."""
        assert self._spool is not None
        if self._boxes is None:
            self._boxes = np.array([self._box(*self._groups_read(gs)) for gs in self.blocks]).reshape(-1, 4)
        x0, y0, x1, y1 = self._box(centres_xy, radius_m)
        region = CropRegion.corridor(radius_m, points_xy=centres_xy)
        bx, parts = self._boxes, []
        for b in np.flatnonzero((bx[:, 0] <= x1) & (bx[:, 2] >= x0) & (bx[:, 1] <= y1) & (bx[:, 3] >= y0)):
            for part in self._spool.read_parts("block", self._spool_ids[b]):   # not the whole block at once
                x, y = part["xyz"][:, 0], part["xyz"][:, 1]
                rows = part[(x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)]
                parts.append(rows[region.mask(rows["xyz"][:, 0], rows["xyz"][:, 1])])
        rows = np.concatenate(parts) if parts else np.zeros(0, BLOCK_SPOOL_DTYPE)
        return self._index_of(rows[np.unique(rows["point_index"], return_index=True)[1]])   # each once, in cloud order

    def _block(self, b: int, progress: Progress = SILENT) -> TiledIndex:
        """The points of block ``b``: within the reach of its groups and, for the bright
        level, within the corridor of its ``ok`` candidates."""
        if self._cached is not None and self._cached[0] == b:
            return self._cached[1]
        if self._spool is not None:
            return self._spooled(b)
        xy, radius = self._block_read(b)
        return self._read(xy, radius, progress)

    def _bright_level(self) -> float:
        if self.index is not None:
            return bright_level(self.index)
        if self.source is None or not self.blocks:
            return math.inf
        ok_rows = np.flatnonzero(np.array([s == STATUS_OK for s in self.cand.status], bool))
        block_of_row = np.full(len(self.cand), -1, np.int64)
        for b, gs in enumerate(self.blocks):
            for g in gs:
                block_of_row[self.groups[g]] = b
        block_of_ok = block_of_row[ok_rows]
        tree = cKDTree(self.ok_xy)
        hist = np.zeros(65536, np.int64)
        n_points = n_ground = 0
        for b in range(len(self.blocks)):
            idx = self._block(b)
            if len(self.blocks) == 1:
                self._cached = (b, idx)
            _, near = tree.query(idx.xyz_world[:, :2])
            cls = idx.attributes["classification"]
            mine = block_of_ok[near] == b
            n_points += int(mine.sum())
            n_ground += int(np.sum(mine & (cls == GROUND_CLASS)))
            inten = idx.attributes["intensity"][mine & (cls != GROUND_CLASS)]
            hist += np.bincount(np.asarray(inten, np.int64), minlength=65536)[:65536]
            del idx
        if n_points and not n_ground:   # the one-index read's error, for the whole drive
            check_ground_classified(TiledIndex(np.zeros((1, 3)), np.zeros(1, np.int64),
                                               {"classification": np.zeros(1)}), self.source.path)
        return bright_level_of_histogram(hist)

    def extract_signs(self, params: RefineParams, progress: Progress = SILENT) -> List[SignDraft]:
        """:func:`extract_signs` block by block (drafts in the order of the groups), each
        draft with the ground under its placement (:func:`ground_from_cloud`). Blocks are
        read here and refined ``params.block_threads`` at a time; their log comes in block
        order."""
        drafts: List[Optional[SignDraft]] = [None] * len(self.groups)
        has_cloud = self.index is not None or self.source is not None

        def read_blocks() -> Iterator[Tuple[np.ndarray, Optional[TiledIndex]]]:
            for b, gs in enumerate(self.blocks):
                index = self._block(b) if has_cloud else None
                self._cached = None
                yield gs, index

        def refine_block(block: Tuple[np.ndarray, Optional[TiledIndex]]):
            gs, index = block
            log, kept = progress.recorder()
            out = []
            for g in gs:
                draft = extract_draft(self.cand, self.groups[g], index, self.bright, params, log)
                if draft is not None:
                    place = placement(self.cand, draft)
                    draft.ground = ground_from_cloud(index, place.centre, place.bottom_z, params)
                    draft.placed = place    # the panel's points' coordinates are not needed after
                    if draft.panel is not None:
                        draft.panel = replace(draft.panel, points=None)
                out.append((int(g), draft))
            return out, kept

        done = 0
        for out, kept in map_in_order(refine_block, read_blocks(), params.block_threads, progress.check):
            progress.replay(kept)
            for g, draft in out:
                drafts[g] = draft
            done += len(out)
            progress.report(done / len(self.groups))
            progress.step("Refining the signs: {n} of {count} candidate groups", n=done, count=len(self.groups))
        return [d for d in drafts if d is not None]

    def ground_of(self, drafts: Sequence[SignDraft], params: RefineParams) -> None:
        """Set the ground (:func:`ground_from_cloud`) of ``drafts`` (image-only signs) from
        the points around them (:meth:`_around`: the spooled blocks, else a spatial query),
        gathered for one block of them at a time, so the points held grow with a block's
        signs, not with the drive's (each sign's query sees the same points as in one read
        of them all)."""
        if not drafts:
            return
        places = [placement(self.cand, d) for d in drafts]
        centres = np.array([p.centre for p in places]).reshape(-1, 3)
        radius = math.sqrt(2) * max(params.ground_radii_m) + 0.5
        near = np.ones(len(drafts), bool)
        if self.index is None:
            if self.source is None:
                for d in drafts:
                    d.ground = NO_CLOUD_GROUND
                return
            dist, _ = cKDTree(self.ok_xy).query(centres[:, :2])
            near = dist <= self.corridor_m + radius
        for d in np.flatnonzero(~near):
            drafts[d].ground = NO_CLOUD_GROUND
        rows = np.flatnonzero(near)
        block_of_row = self._block_of(centres[rows])

        def ground_of_block(mine: np.ndarray) -> None:
            index = self._around(centres[mine, :2], radius)
            for k in mine:
                drafts[k].ground = ground_from_cloud(index, places[k].centre, places[k].bottom_z, params)

        # one block at a time, each read's heap given back after it (as for every block)
        blocks = (rows[block_of_row == b] for b in np.unique(block_of_row))
        for _ in map_in_order(ground_of_block, blocks, 1, lambda: None):
            pass


def extract_signs(cand: ProjectionResult, groups: Sequence[np.ndarray], index: Optional[TiledIndex],
                  bright: float, params: RefineParams, progress: Progress = SILENT
                  ) -> List[SignDraft]:
    """One sign per group of views (candidate rows), with its panel from the cloud
    (:func:`extract_panel`). Groups whose panel is not a sign (:data:`NOT_A_SIGN`) are
    dropped; those whose panel could not be isolated (or without a cloud) keep no panel:
    the views agree on a surface, the sign is placed at their median. Both are logged."""
    drafts = []
    for g, rows in enumerate(groups):
        draft = extract_draft(cand, rows, index, bright, params, progress)
        if draft is not None:
            drafts.append(draft)
        progress.report((g + 1) / max(1, len(groups)))
    return drafts


def extract_draft(cand: ProjectionResult, rows: np.ndarray, index: Optional[TiledIndex],
                  bright: float, params: RefineParams, progress: Progress = SILENT
                  ) -> Optional[SignDraft]:
    """The sign of one group of views (:func:`extract_signs`); None when it is not a sign."""
    det = cand.detections
    panel, reason = (extract_panel(cand, rows, index, bright, params) if index is not None
                     else (None, Message("no point cloud")))
    if panel is None:
        if reason in NOT_A_SIGN:
            progress.info("Candidates {ids} dropped: {reason}", ids=det.det_id[rows].tolist(),
                          reason=reason)
            return None
        progress.info("Candidates {ids}: {reason}; placed at the candidates' median",
                      ids=det.det_id[rows].tolist(), reason=reason)
    return SignDraft(rows, panel)


def sign_centres(cand: ProjectionResult, drafts: Sequence[SignDraft]) -> np.ndarray:
    """Centre (world, ``(n, 3)``) of each sign: its panel's, else its own views' median
    surface point."""
    return np.array([d.panel.centre_world if d.panel is not None
                     else np.median(cand.xyz_world[d.rows], axis=0) for d in drafts]).reshape(-1, 3)


def sign_classes(cand: ProjectionResult, drafts: Sequence[SignDraft]) -> np.ndarray:
    """Class of each sign as its own views vote (:func:`vote_class`; joined views left out)."""
    return np.array([vote_class(cand, d.rows)[0] for d in drafts], dtype=np.str_)


def join_lone_views(cand: ProjectionResult, drafts: Sequence[SignDraft]) -> None:
    """A sign of a single view whose box holds the centre of a sign found by several views:
    that view saw the other sign, its own candidate is a surface behind it (a wall), in front
    (an occluder) or a stray part of it. The view joins the sign (of its class at any range,
    of another class only when not behind its own surface, 0.5 m allowed) and its own sign is
    absorbed. Updates ``drafts`` in place."""
    det = cand.detections
    centres, classes = sign_centres(cand, drafts), sign_classes(cand, drafts)
    several = np.array([len(d.rows) >= 2 for d in drafts], bool)
    for draft in drafts:
        if len(draft.rows) != 1:
            continue
        k = int(draft.rows[0])
        target = _sign_in_box(det, k, centres, several & (classes == det.class_name[k]), math.inf)
        if target < 0:
            target = _sign_in_box(det, k, centres, several, float(cand.range_m[k]) + 0.5)
        if target >= 0:
            drafts[target].joined.append(k)
            draft.absorbed = True


def join_signs_on_one_panel(cand: ProjectionResult, drafts: Sequence[SignDraft],
                            params: RefineParams) -> None:
    """Two signs whose centres are within ``same_panel_radius_m`` and whose normals agree
    (within ``normal_agreement_deg``, either way; or one has none) are one panel: the
    detector gave it two classes, or its views split. The sign with more views absorbs the
    other's views and those that joined it (its class is then the vote of all). Updates
    ``drafts`` in place."""
    centres = sign_centres(cand, drafts)
    normals = [d.panel.normal_world if d.panel is not None else None for d in drafts]
    cos_agree = math.cos(math.radians(params.normal_agreement_deg))
    by_views = sorted(range(len(drafts)), key=lambda n: -len(drafts[n].rows))
    for i, a in enumerate(by_views):
        if drafts[a].absorbed:
            continue
        for b in by_views[i + 1:]:
            if drafts[b].absorbed or \
                    np.linalg.norm(centres[a] - centres[b]) > params.same_panel_radius_m:
                continue
            na, nb = normals[a], normals[b]
            if na is not None and nb is not None and abs(float(np.dot(na, nb))) < cos_agree:
                continue
            drafts[a].joined.extend(list(drafts[b].rows) + drafts[b].joined)
            drafts[b].joined = []
            drafts[b].absorbed = True


def join_views_without_surface(cand: ProjectionResult, drafts: Sequence[SignDraft]) -> np.ndarray:
    """Views whose candidate found no surface (status not ``ok``) join the sign whose centre
    lies in their box: of their class at any range (a sign far ahead, beyond the scanner's
    reach, found by the views that came near it), else of any class within 60 m. Updates
    ``drafts`` in place; returns the candidate rows of the views that joined none."""
    det = cand.detections
    centres, classes = sign_centres(cand, drafts), sign_classes(cand, drafts)
    unplaced = []
    for k in np.flatnonzero(np.array(cand.status) != STATUS_OK):
        target = _sign_in_box(det, int(k), centres, classes == det.class_name[k], math.inf,
                              search_m=math.inf)
        if target < 0:
            target = _sign_in_box(det, int(k), centres, np.ones(len(centres), bool), math.inf)
        if target >= 0:
            drafts[target].joined.append(int(k))
        else:
            unplaced.append(int(k))
    return np.array(unplaced, np.int64)


def triangulate_image_only(cand: ProjectionResult, rows: np.ndarray, params: RefineParams
                           ) -> List[SignDraft]:
    """Signs placed from the images alone: the views ``rows`` (candidate rows) whose ray met
    no points (``no_points``; not those whose points held no surface), triangulated by
    :func:`triangulate_groups`."""
    no_points = np.array([k for k in rows if cand.status[k] == STATUS_NO_POINTS], np.int64)
    return [SignDraft(group, x_image=x) for group, x in triangulate_groups(cand, no_points, params)]


def placement(cand: ProjectionResult, draft: SignDraft) -> Placement:
    """Where the sign is: its panel; else the median of its own views' surface points (their
    mean normal) or its triangulated point (facing the views' mean station horizontally),
    sized by the boxes at that range (:func:`box_size_estimate_m`, frontal for a
    triangulated point), ``bottom_z`` half the panel height below the centre; the draft's
    own (:attr:`SignDraft.placed`) once found."""
    if draft.placed is not None:
        return draft.placed
    if draft.panel is not None:
        p = draft.panel
        assert p.points is not None, "a panel's points are let go only once it is placed"
        return Placement(p.centre_world, p.normal_world, p.width_m, p.height_m,
                         float(p.corners_world[:, 2].min()), p.points.point_index,
                         float(np.mean(p.points.attributes["intensity"])), p.planarity, "lidar",
                         p.corners_world)
    det, rows = cand.detections, np.asarray(draft.rows)
    if draft.x_image is None:
        w_est, h_est = box_size_estimate_m(cand, rows)
        centre = np.median(cand.xyz_world[rows], axis=0)
        normal = cand.normal_world[rows].mean(axis=0)
        source = "lidar"
    else:
        w_est, h_est = _image_size_estimate(cand, rows, draft.x_image)
        centre = draft.x_image
        to = det.centre_world[rows].mean(axis=0) - centre
        normal = np.array([to[0], to[1], 0.0])
        source = "image"
    width, height = float(np.median(w_est)), float(np.median(h_est))
    return Placement(centre, normal / np.linalg.norm(normal), width, height,
                     float(centre[2] - height / 2), np.zeros(0, np.int64), math.nan, math.nan,
                     source, None)


def source_images(cand: ProjectionResult, views: Sequence[int]) -> List[str]:
    """The images of the views (candidate rows), each once, in the order of the detection ids."""
    det = cand.detections
    images: List[str] = []
    for k in sorted(views, key=lambda k: det.det_id[k]):
        if det.image[k] not in images:
            images.append(det.image[k])
    return images


@dataclass(frozen=True)
class DetectedStations:
    """The panoramas that gave candidates, each once (:meth:`.Detections.station_rows`):
    ``images`` and their centres ``centre_world`` (n, 3)."""

    images: List[str]
    centre_world: np.ndarray

    @classmethod
    def of(cls, cand: ProjectionResult) -> "DetectedStations":
        det = cand.detections
        rows = det.station_rows()
        return cls([det.image[k] for k in rows], det.centre_world[rows].reshape(-1, 3))


def nearer_stations_that_missed(place: Placement, images: Sequence[str], stations: DetectedStations,
                                params: RefineParams) -> Tuple[int, float]:
    """How many of ``stations`` not among ``images`` (the panoramas that saw the sign) stand
    in front of the sign's face, nearer to it than the nearest panorama that saw it, and
    would show it low enough in their views; and that nearest horizontal range (m).

    In front: the horizontal direction to the station within ``view_check_max_angle_deg``
    of the face's normal. Nearer: a horizontal range of at least ``view_check_min_range_m``
    and ``view_check_nearer_by_m`` less than the seeing station's. Low enough: the sign's
    centre at most ``view_check_max_elevation_deg`` above the station's centre (a gantry
    overhead is above the horizon views). The sign is then bigger and nearer the horizon
    there than where it was seen.
    """
    seen_images = set(images)
    seen = np.array([image in seen_images for image in stations.images], bool)
    to_station = stations.centre_world - place.centre
    range_m = np.hypot(to_station[:, 0], to_station[:, 1])
    if not seen.any():
        return 0, math.nan
    seen_range_m = float(range_m[seen].min())
    normal = np.array([place.normal[0], place.normal[1]], float)
    if not np.all(np.isfinite(normal)) or np.linalg.norm(normal) < 1e-6:
        return 0, seen_range_m
    normal /= np.linalg.norm(normal)
    cos_angle = (to_station[:, :2] @ normal) / np.maximum(range_m, 1e-9)
    elevation_deg = np.degrees(np.arctan2(-to_station[:, 2], np.maximum(range_m, 1e-9)))
    should_see = (~seen & (cos_angle >= math.cos(math.radians(params.view_check_max_angle_deg)))
                  & (range_m >= params.view_check_min_range_m)
                  & (range_m <= seen_range_m - params.view_check_nearer_by_m)
                  & (elevation_deg <= params.view_check_max_elevation_deg))
    return int(should_see.sum()), seen_range_m


def plausible(cand: ProjectionResult, views: Sequence[int], klass: str, score: float,
              place: Placement, images: Sequence[str], params: RefineParams,
              progress: Progress = SILENT, stations: Optional[DetectedStations] = None) -> bool:
    """False, logged, for a panel larger than its class allows (:meth:`RefineParams.max_side_m`:
    a billboard?) and for a sign seen in one panorama only (``images``) with a score below
    ``min_single_view_score``, or missed by ``single_view_max_nearer_misses`` or more of the
    ``stations`` nearer to it (:func:`nearer_stations_that_missed`)."""
    ids = cand.detections.det_id[list(views)].tolist()
    if max(place.width_m, place.height_m) > params.max_side_m(klass):
        progress.info("Candidates {ids} dropped: a {width:.2f} x {height:.2f} m panel is too "
                      "large for a {sign_class} sign (a billboard?)",
                      ids=ids, width=place.width_m, height=place.height_m, sign_class=klass)
        return False
    if len(images) == 1 and score < params.min_single_view_score:
        progress.info("Candidates {ids} dropped: seen in one panorama only, with a score of "
                      "{score:.2f}", ids=ids, score=score)
        return False
    if len(images) == 1 and stations is not None and params.single_view_max_nearer_misses > 0:
        missed, seen_range_m = nearer_stations_that_missed(place, images, stations, params)
        if missed >= params.single_view_max_nearer_misses:
            progress.info("Candidates {ids} dropped: seen in one panorama only ({image}, {range:.1f} m "
                          "away), not in the {missed} panoramas nearer to its face",
                          ids=ids, image=images[0], range=seen_range_m, missed=missed)
            return False
    return True


def add_sign(result: RefineResult, cand: ProjectionResult, draft: SignDraft,
             index: Optional[TiledIndex], params: RefineParams, progress: Progress = SILENT,
             codes_table: Optional[CodesTable] = None,
             code_confidence: float = DEFAULT_CODE_CONFIDENCE,
             stations: Optional[DetectedStations] = None) -> None:
    """Append the record of a sign (numbered on from 1), its outline, points and ground
    source to ``result`` and point its views there in ``result.candidate_sign``, unless it is
    not :func:`plausible` (``stations``: the drive's panoramas, for its view check). Heights
    are above the ground under the centre (:func:`ground_with_fallbacks`); the code and the
    class check: :func:`vote_code`."""
    det = cand.detections
    views = draft.views
    klass, score = vote_class(cand, views)
    code = vote_code(cand, views, klass, codes_table, code_confidence)
    klass = code.klass
    place = placement(cand, draft)
    images = source_images(cand, views)
    if not plausible(cand, views, klass, score, place, images, params, progress, stations):
        return
    ground_z, ground_source = ground_with_fallbacks(index, place.centre, place.bottom_z,
                                                    det.centre_world[views, 2], params, draft.ground)
    n_sign = len(result.signs)
    result.signs.append(SignRecord(
        sign_id=n_sign + 1, klass=klass, score=score, height=float(place.centre[2] - ground_z),
        bottom_height=float(place.bottom_z - ground_z), width=float(place.width_m),
        panel_height=float(place.height_m), azimuth=float(geometry.azimuth_deg_of_enu(place.normal)),
        n_views=len(images), n_points=int(len(place.point_index)), source_images=";".join(images),
        best_image=det.image[best_view(cand, views, place.centre, place.normal)],
        mean_intensity=place.mean_intensity, planarity=place.planarity,
        position_source=place.source, x=float(place.centre[0]), y=float(place.centre[1]),
        z=float(place.centre[2]), code=code.code, code_name=code.name, code_score=code.score,
        code_views=code.views, code_check=code.check))
    result.outlines_world.append(place.outline)
    result.point_index.append(place.point_index)
    result.ground_source.append(ground_source)
    result.candidate_sign[views] = n_sign


def log_codes(result: RefineResult, progress: Progress) -> None:
    """One line on the signs' codes: how many have one, and the class checks."""
    if not any(s.code or s.code_check or s.code_views for s in result.signs):
        return
    progress.info("{coded} of {signs} signs have a sign code; {from_code} took their class from "
                  "the code, {dropped} codes were dropped for the class vote (code_check)",
                  coded=sum(bool(s.code) for s in result.signs), signs=len(result.signs),
                  from_code=sum(s.code_check == CLASS_FROM_CODE for s in result.signs),
                  dropped=sum(s.code_check == CODE_DROPPED for s in result.signs))


def warn_ground_fallbacks(result: RefineResult, params: RefineParams, progress: Progress) -> None:
    """One warning per ground fallback that signs of ``result`` used, with their count."""
    camera = Message("the stations' height minus {height} m", height=params.camera_height_m)
    for fallback, what in ((LOWEST_POINTS, Message("the lowest points below the sign")),
                           (CAMERA_HEIGHT, camera)):
        count = result.ground_source.count(fallback)
        if count:
            warn(result, progress, "{count} sign(s) have no ground points (class 2) within "
                 "{radius} m: their height is measured from {source}", count=count,
                 radius=max(params.ground_radii_m), source=what)


def _sign_in_box(det: Detections, k: int, centres: np.ndarray, eligible: np.ndarray, max_range_m: float,
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


def _image_size_estimate(cand: ProjectionResult, rows: np.ndarray, x: np.ndarray
                         ) -> Tuple[np.ndarray, np.ndarray]:
    """Panel size from the boxes at the triangulated point's range (frontal assumption)."""
    det = cand.detections
    b, W, H = det.box_px[rows], det.pano_size_px[rows, 0], det.pano_size_px[rows, 1]
    r = np.linalg.norm(det.centre_world[rows] - x, axis=1)
    eps = np.pi * (0.5 - 0.5 * (b[:, 1] + b[:, 3]) / H)
    return (r * (b[:, 2] - b[:, 0]) / W * 2 * np.pi * np.cos(eps),
            r * (b[:, 3] - b[:, 1]) / H * np.pi)


def write_sign_points(input_path: Union[str, CloudSource], output_path: str, point_index: Sequence[np.ndarray],
                      progress: Progress = SILENT) -> int:
    """Copy the points ``point_index`` (positions in the cloud ``input_path``: a LAS/LAZ file,
    a folder of tiles or a ``.vpc``, :mod:`.cloudsource`) to a LAS/LAZ file with everything
    of the input kept (of a cloud of tiles: the first tile's header, scales and offsets);
    only the tiles holding them are read. Returns the number written."""
    wanted = np.unique(np.concatenate([np.asarray(p, np.int64) for p in point_index])
                       if len(point_index) else np.zeros(0, np.int64))
    source = open_cloud(input_path)
    header = source.header
    needed = set(source.tile_of_index(wanted).tolist())
    tiles = [t for k, t in enumerate(source.tiles) if k in needed]
    with CloudWriter(output_path, output_header(header)) as writer:
        for index, chunk in source.iter_indexed_chunks(progress=progress, tiles=tiles):
            lo, hi = np.searchsorted(wanted, [index[0], index[-1] + 1]) if len(index) else (0, 0)
            if hi > lo:
                writer.write(conform(chunk[wanted[lo:hi] - index[0]], header))
        return writer.point_count
