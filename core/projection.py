"""Detections -> candidate sign surfaces in the point cloud (``roadsigns:projectdetections``).

For each detection the viewing frustum of its box (the panorama box grown by a margin for
calibration error, from the panorama centre out to ``max_range_m``) is searched for the
first dense planar surface along the box-centre ray: the sign, not the wall behind it
(Balado et al. 2020: the box-centre ray meets the first plane of points).

How the cloud is searched (cost ~ linear in points + detections):

* one streaming read of the cloud (a LAS/LAZ file, a folder of tiles or a virtual point
  cloud, :mod:`.cloudsource`: only the tiles, or COPC nodes, under some frustum are read)
  keeps only the non-ground points under the union of the frusta's 2D footprints and spools
  them to disk in slices of the drive by their arc length along it
  (:func:`drive_blocks`, :mod:`.drivewindows`); the drive is then worked through in blocks
  of at most ``ProjectionParams.block_m`` metres and ``block_max_points`` points
  (:func:`slice_blocks`), each held in a :class:`~.pointcloud.TiledIndex` of small tiles,
  so memory follows the block, not the drive;
* within a block, each detection tests the tiles its footprint crosses, as views of the
  block index's arrays (no copies), so a detection only ever touches the tiles under its
  own frustum (``ProjectionResult.tiles_visited``), and nothing it allocates outlives it;
* points of class 2 (ground) are never candidates, nor stored.

Conventions: world ENU metres; boxes in the detections layer's form (``u0 < W``, ``u1`` may exceed
``W`` across the seam); ``q_world_from_pano_wxyz`` maps panorama rays to world
(Hamilton, scalar first); normals are unit world vectors oriented towards the station.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from . import geometry
from .cloudsource import CloudSource, open_cloud
from .detections import DETECTION_POSE_FIELDS, Detections
from .drivewindows import BLOCK_THREADS, DriveAxis, Spool, Track, Window, make_windows, map_in_order
from .errors import SILENT, InputError, Progress
from .pointcloud import DEFAULT_CHUNK_POINTS, GROUND_CLASS, CropRegion, TiledIndex, xyz_of
from .schema import Schema, fields

#: Default search depth along the rays, metres (Balado et al. use 15 m).
DEFAULT_MAX_RANGE_M = 30.0
#: What projection spools of each point: world position and its row in the LAS file.
SPOOL_DTYPE = np.dtype([("x", "f8"), ("y", "f8"), ("z", "f8"), ("index", "i8")])
#: Cells (m) of the coarse frustum test that decides which points are spooled.
FRUSTUM_CELL_M = 2.0
#: Slices (m of drive) the spooled points are kept in, each point in one; a block of
#: :func:`drive_blocks` reads the slices its detections' frusta may reach.
SLICE_M = 25.0
#: Detections whose frusta are built, or whose footprints' cells are found, at a time
#: (:meth:`Frusta.build`, :func:`frustum_cells`): the shapes on the way are a batch's.
FRUSTA_BATCH = 1024
#: Detections, consecutive along the drive, whose footprints one shape covers when the
#: reads of the cloud are planned (:meth:`Frusta.cover`): shapes of the whole drive are
#: held then, one a group rather than one a detection (one a detection held 5 MB more on
#: a 9 km drive than on 1 km; bench/README.md).
COVER_GROUP = 64
#: Standard errors by which :func:`convex_radius_m` moves a fitted curvature towards flat.
CURVATURE_CONFIDENCE = 2.0
#: Candidate status flags.
STATUS_OK, STATUS_NO_POINTS, STATUS_NO_SURFACE = "ok", "no_points", "no_surface"

#: Fields a candidate adds to its detection's (``cand_*``: the surface point, NULL when
#: there is none; ``normal_*``: unit world normal towards the station).
CANDIDATE_OWN_FIELDS: Schema = fields(
    ("cand_x", float), ("cand_y", float), ("cand_z", float), ("range_m", float), ("n_points", int),
    ("normal_e", float), ("normal_n", float), ("normal_u", float), ("quality", float), ("status", str))
#: The candidates layer (PointZ at the surface; no geometry unless ``status`` is ok).
CANDIDATE_FIELDS: Schema = DETECTION_POSE_FIELDS + CANDIDATE_OWN_FIELDS


# --------------------------------------------------------------------------------------
# Boxes and frusta
# --------------------------------------------------------------------------------------

def grow_boxes(box_px: np.ndarray, pano_size_px: np.ndarray, margin_deg: float,
               margin_frac: float) -> np.ndarray:
    """Boxes grown on every side by ``max(margin_deg, margin_frac x box size)``; v clipped to
    ``[0, H]``, u left unwrapped (seam handled by the tests)."""
    b = np.asarray(box_px, float)
    W, H = pano_size_px[:, 0].astype(float), pano_size_px[:, 1].astype(float)
    mu = np.maximum(margin_deg / 360.0 * W, margin_frac * (b[:, 2] - b[:, 0]))
    mv = np.maximum(margin_deg / 180.0 * H, margin_frac * (b[:, 3] - b[:, 1]))
    width = np.minimum(b[:, 2] - b[:, 0] + 2 * mu, W)
    uc = 0.5 * (b[:, 0] + b[:, 2])
    return np.column_stack([uc - width / 2, np.maximum(b[:, 1] - mv, 0.0), uc + width / 2,
                            np.minimum(b[:, 3] + mv, H)])


def box_coordinates(u, v, box, width_px):
    """Pixel(s) -> coordinates relative to ``box``: 0..1 across it in u and v (outside
    beyond), comparing columns across the seam (the nearest wrap of u is used)."""
    u0, v0, u1, v1 = box
    uc = 0.5 * (u0 + u1)
    du = np.mod(np.asarray(u, float) - uc + width_px / 2.0, width_px) - width_px / 2.0
    return du / (u1 - u0) + 0.5, (np.asarray(v, float) - v0) / (v1 - v0)


def box_boundary_rays_world(box_px, pano_size_px, R_world_from_pano, samples_per_edge=5):
    """Unit world rays along the outline of each box and through its centre, (n, m, 3)."""
    s = np.linspace(0.0, 1.0, samples_per_edge)
    a = np.concatenate([s, np.ones_like(s), s[::-1], np.zeros_like(s), [0.5]])
    c = np.concatenate([np.zeros_like(s), s, np.ones_like(s), s[::-1], [0.5]])
    b = np.asarray(box_px, float)
    u = b[:, :1] + a[None] * (b[:, 2:3] - b[:, :1])
    v = b[:, 1:2] + c[None] * (b[:, 3:4] - b[:, 1:2])
    d = geometry.pixel_to_ray(np.mod(u, pano_size_px[:, :1]), v, pano_size_px[:, :1],
                              pano_size_px[:, 1:2])
    return np.einsum("nij,nmj->nmi", R_world_from_pano, d)


@dataclass
class Frusta:
    """The search volumes of the detections: grown boxes, 3D bounds and 2D footprints.

    Detection ``k``'s footprint (its frustum's outline on the ground plane, padded for the
    far cap's bulge) is kept as vertices, ``outline_xy[outline_start[k]:outline_start[k + 1]]``
    (a closed ring), and made a shapely polygon only when asked (:meth:`footprints`): the
    GEOS polygons of a whole drive, held through the stage, grew with the drive (7 MB on
    9 km); the vertices take half that, and a block builds only its own."""

    boxes_px: np.ndarray        # (n, 4) grown boxes
    lo_world: np.ndarray        # (n, 3) bounding box of each frustum
    hi_world: np.ndarray
    outline_xy: np.ndarray      # (v, 2) the footprints' vertices, detection by detection
    outline_start: np.ndarray   # (n + 1,) int64: where each detection's vertices start

    def __len__(self) -> int:
        return len(self.boxes_px)

    @classmethod
    def build(cls, det: Detections, max_range_m: float, margin_deg: float,
              margin_frac: float, batch: int = FRUSTA_BATCH) -> "Frusta":
        """The frusta of ``det``, ``batch`` detections at a time: the rays and shapes made
        on the way are a batch's, not the drive's."""
        boxes = grow_boxes(det.box_px, det.pano_size_px, margin_deg, margin_frac)
        R = det.R_world_from_pano()
        # the far cap bulges between sampled rays by at most range x (1 - cos(step / 2))
        size_deg = np.maximum((boxes[:, 2] - boxes[:, 0]) / det.pano_size_px[:, 0] * 360.0,
                              (boxes[:, 3] - boxes[:, 1]) / det.pano_size_px[:, 1] * 180.0)
        step = np.radians(size_deg / 4.0)
        pad = 0.1 + max_range_m * (1.0 - np.cos(np.minimum(step, np.pi / 2) / 2.0))
        lo, hi = np.empty((len(det), 3)), np.empty((len(det), 3))
        outlines, counts = [], []
        for b0 in range(0, len(det), batch):
            b = slice(b0, b0 + batch)
            rays = box_boundary_rays_world(boxes[b], det.pano_size_px[b], R[b])
            pts = np.concatenate([det.centre_world[b, None, :], det.centre_world[b, None, :] + max_range_m * rays],
                                 axis=1)
            lo[b], hi[b] = pts.min(axis=1) - pad[b, None], pts.max(axis=1) + pad[b, None]
            hulls = shapely.convex_hull(shapely.multipoints(pts[:, :, :2]))
            xy, owner = shapely.get_coordinates(shapely.buffer(hulls, pad[b], quad_segs=2), return_index=True)
            outlines.append(xy)
            counts.append(np.bincount(owner, minlength=len(hulls)))
        outline_xy = np.concatenate(outlines) if outlines else np.zeros((0, 2))
        start = np.r_[0, np.cumsum(np.concatenate(counts))] if counts else np.zeros(1, np.int64)
        return cls(boxes, lo, hi, outline_xy, start.astype(np.int64))

    def _vertices(self, rows: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """The vertices of detections ``rows``' footprints, one after the other, and how many
        each has."""
        first, counts = self.outline_start[rows], np.diff(self.outline_start)[rows]
        at = np.repeat(first - np.r_[0, np.cumsum(counts)[:-1]], counts) + np.arange(int(counts.sum()))
        return self.outline_xy[at], counts

    def footprints(self, rows: Optional[np.ndarray] = None) -> np.ndarray:
        """The footprints of detections ``rows`` (all without), shapely polygons in their
        order: the same shapes as built, from the same vertices."""
        rows = np.arange(len(self)) if rows is None else np.asarray(rows, np.int64).reshape(-1)
        if not len(rows):
            return np.empty(0, dtype=object)
        xy, counts = self._vertices(rows)
        return shapely.polygons(shapely.linearrings(xy, indices=np.repeat(np.arange(len(rows)), counts)))

    def cover(self, rows: np.ndarray, group: int = COVER_GROUP, batch: int = FRUSTA_BATCH) -> np.ndarray:
        """Convex hulls of the footprints of detections ``rows`` taken ``group`` at a time in
        that order (give them in drive order): each footprint lies inside its group's hull, so
        they cover the footprints with one shape a group rather than one a detection. Made
        ``batch`` detections (whole groups) at a time: the points on the way are a batch's."""
        rows = np.asarray(rows, np.int64).reshape(-1)
        step = max(group, batch // group * group)
        hulls = [np.empty(0, dtype=object)]
        for b0 in range(0, len(rows), step):
            xy, counts = self._vertices(rows[b0:b0 + step])
            owner = np.repeat(np.arange(len(counts)) // group, counts)
            hulls.append(shapely.convex_hull(shapely.multipoints(xy, indices=owner)))
        return np.concatenate(hulls)


# --------------------------------------------------------------------------------------
# Point-set tools shared with refine
# --------------------------------------------------------------------------------------

def pca(xyz: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centroid, eigenvalues (descending) and eigenvectors (columns) of the covariance."""
    c = xyz.mean(axis=0)
    w, V = np.linalg.eigh(np.cov((xyz - c).T) if len(xyz) > 1 else np.zeros((3, 3)))
    return c, w[::-1].clip(min=0.0), V[:, ::-1]


def euclidean_clusters(xyz: np.ndarray, tolerance_m: float) -> np.ndarray:
    """Connected components of the points at most ``tolerance_m`` apart (labels 0..k-1)."""
    n = len(xyz)
    if n == 0:
        return np.zeros(0, np.int64)
    pairs = cKDTree(xyz).query_pairs(tolerance_m, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs), bool), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(graph, directed=False)[1]


@dataclass
class Plane:
    """A plane ``normal . (x - point) = 0``, its inliers and their RMS distance."""

    point: np.ndarray
    normal: np.ndarray
    inliers: np.ndarray
    rms_m: float

    def distance(self, xyz) -> np.ndarray:
        return (np.asarray(xyz) - self.point) @ self.normal


def fit_plane_ransac(xyz: np.ndarray, threshold_m: float, max_tilt_deg: Optional[float] = None,
                     iterations: int = 200, seed: int = 0, max_eval_points: int = 3000
                     ) -> Optional[Plane]:
    """RANSAC plane with least-squares refits; ``max_tilt_deg``: the plane may lean at most
    this much from vertical (its normal within that of horizontal). ``None`` when no
    admissible plane has 3 inliers. Deterministic for a given ``seed``."""
    n = len(xyz)
    if n < 3:
        return None
    rng = np.random.default_rng(seed)
    c0 = xyz.mean(axis=0)
    p = xyz - c0
    sample = rng.integers(0, n, (iterations, 3))
    a, b, c = p[sample[:, 0]], p[sample[:, 1]], p[sample[:, 2]]
    normals = np.cross(b - a, c - a)
    norm = np.linalg.norm(normals, axis=1)
    ok = norm > 1e-9
    normals[ok] /= norm[ok, None]
    if max_tilt_deg is not None:
        ok &= np.abs(normals[:, 2]) <= math.sin(math.radians(max_tilt_deg))
    if not np.any(ok):
        return None
    normals, a = normals[ok], a[ok]
    ev = p if n <= max_eval_points else p[rng.choice(n, max_eval_points, replace=False)]
    # each candidate's distances to the evaluated points: (ev - a) . n as ev . n - a . n, one
    # matrix product (m, k) rather than a (k, m, 3) array of differences
    offsets = np.einsum("ij,ij->i", a, normals)
    counts = np.count_nonzero(np.abs(ev @ normals.T - offsets) < threshold_m, axis=0)
    best = int(np.argmax(counts))
    normal, point = normals[best], a[best]
    inliers = np.abs((p - point) @ normal) < threshold_m
    for _ in range(3):  # least-squares refits on the inliers
        if inliers.sum() < 3:
            return None
        centroid, _, V = pca(p[inliers])
        cand = V[:, 2]
        if max_tilt_deg is not None and abs(cand[2]) > math.sin(math.radians(max_tilt_deg)):
            break
        normal, point = cand, centroid
        new = np.abs((p - point) @ normal) < threshold_m
        if np.array_equal(new, inliers):
            break
        inliers = new
    d = (p[inliers] - point) @ normal
    return Plane(point + c0, normal, inliers, float(np.sqrt(np.mean(d ** 2))) if len(d) else 0.0)


def convex_radius_m(xyz: np.ndarray, normal_to_viewer: np.ndarray) -> float:
    """Radius of curvature of a surface bulging towards the viewer (``inf`` when flat or
    hollow): a paraboloid ``w = a + b s + c t + k (s^2 + t^2)`` fitted robustly in the frame
    of the plane, ``w`` along ``normal_to_viewer``. Convex traffic mirrors give ~1-3 m; a
    flat sign with its pole behind looks hollow (k > 0) and is not mistaken for one.

    The radius is the flattest the points allow: ``k`` moved towards flat by
    ``CURVATURE_CONFIDENCE`` standard errors of its fit, so range noise on a small flat
    sign (a few dozen points, +-1 cm) is not read as a bulge of a few metres' radius."""
    if len(xyz) < 10:
        return math.inf
    n = np.asarray(normal_to_viewer, float)
    e1 = np.cross(n, [0.0, 0.0, 1.0])
    e1 = e1 / np.linalg.norm(e1) if np.linalg.norm(e1) > 1e-6 else np.array([1.0, 0.0, 0.0])
    e2 = np.cross(n, e1)
    rel = xyz - xyz.mean(axis=0)
    s, t, w = rel @ e1, rel @ e2, rel @ n
    A = np.column_stack([np.ones_like(s), s, t, s * s + t * t])
    keep = np.ones(len(w), bool)
    for _ in range(3):  # refits without the points off the surface (poles, brackets)
        coef, *_ = np.linalg.lstsq(A[keep], w[keep], rcond=None)
        res = w - A @ coef
        sigma = 1.4826 * np.median(np.abs(res[keep] - np.median(res[keep]))) + 1e-4
        new = np.abs(res) < 3.0 * sigma
        if new.sum() < 10 or np.array_equal(new, keep):
            break
        keep = new
    Ak = A[keep]
    dof = max(1, len(Ak) - 4)
    residual_var = float(np.sum((w[keep] - Ak @ coef) ** 2)) / dof
    k_se = math.sqrt(max(0.0, residual_var * float(np.linalg.pinv(Ak.T @ Ak)[3, 3])))
    k_flattest = coef[3] + CURVATURE_CONFIDENCE * k_se
    return 1.0 / (2.0 * -k_flattest) if k_flattest < -1e-9 else math.inf


# --------------------------------------------------------------------------------------
# Projection
# --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ProjectionParams:
    """Tuning of :func:`project_detections` (defaults suit 5-50 points/dm^2 MLS clouds)."""

    margin_deg: float = 0.25          # frustum margin, degrees, at least
    margin_frac: float = 0.10         # ... or this share of the box size per side
    min_range_m: float = 0.5
    tile_size_m: float = 5.0
    block_m: float = 150.0            # metres of drive indexed at a time (memory follows it)
    block_max_points: int = 1_500_000  # points a block reads, at most (but one slice of detections)
    block_threads: int = BLOCK_THREADS  # blocks searched at once (numpy and scipy release the GIL)
    cluster_tolerance_m: float = 0.15  # Euclidean clustering: at least this, or
    cluster_tolerance_per_m: float = 0.008  # this x range
    min_points: int = 12              # points a surface needs
    core_fraction: float = 0.6        # central share of the box that the centre ray samples
    plane_threshold_m: float = 0.04
    max_tilt_deg: float = 30.0        # a sign surface leans at most this from vertical
    min_inlier_share: float = 0.6     # of the cluster's core points on the plane
    min_extent_m: float = 0.05        # second principal spread: not a line (pole, wire)
    min_curvature_radius_m: float = 3.0  # flatter than this (convex mirrors are curved)


@dataclass
class ProjectionResult:
    """One candidate per detection (row k belongs to ``detections`` row k).

    ``xyz_world`` / ``normal_world`` are NaN and ``range_m`` NaN unless ``status == "ok"``;
    ``n_points``: points of the candidate surface; ``point_index``: their positions in the
    cloud (in the file, or tile by tile, :mod:`.cloudsource`; or in the input arrays) when
    :func:`project_detections` was asked to keep them, else empty arrays;
    ``quality`` in 0..1. ``tiles_visited`` / ``points_tested``: work per detection;
    ``n_tiles`` / ``n_indexed``: size of the index.
    """

    detections: Detections
    xyz_world: np.ndarray
    normal_world: np.ndarray
    range_m: np.ndarray
    n_points: np.ndarray
    quality: np.ndarray
    status: List[str]
    point_index: List[np.ndarray]
    tiles_visited: np.ndarray
    points_tested: np.ndarray
    n_tiles: int = 0
    n_indexed: int = 0
    warnings: List[str] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.detections)

    @classmethod
    def unprojected(cls, det: Detections) -> "ProjectionResult":
        n = len(det)
        nan3 = np.full((n, 3), np.nan)
        return cls(det, nan3, nan3.copy(), np.full(n, np.nan), np.zeros(n, np.int64),
                   np.zeros(n), [STATUS_NO_POINTS] * n, [np.zeros(0, np.int64)] * n,
                   np.zeros(n, np.int64), np.zeros(n, np.int64))

    def records(self) -> List[Dict]:
        """One dict of :data:`CANDIDATE_FIELDS` per candidate (the candidates layer)."""
        return list(self.iter_records())

    def iter_records(self) -> Iterator[Dict]:
        """:meth:`records` one at a time (the layer written without a dict per candidate held)."""
        for k, rec in enumerate(self.detections.iter_records(DETECTION_POSE_FIELDS)):
            rec.update({"cand_x": float(self.xyz_world[k, 0]),
                        "cand_y": float(self.xyz_world[k, 1]),
                        "cand_z": float(self.xyz_world[k, 2]), "range_m": float(self.range_m[k]),
                        "n_points": int(self.n_points[k]),
                        "normal_e": float(self.normal_world[k, 0]),
                        "normal_n": float(self.normal_world[k, 1]),
                        "normal_u": float(self.normal_world[k, 2]),
                        "quality": float(self.quality[k]), "status": self.status[k]})
            yield rec

    @classmethod
    def from_records(cls, rows: Sequence[Mapping[str, Any]]) -> "ProjectionResult":
        """Read back a candidates layer (the input of refine); ``point_index`` is empty."""
        rows = list(rows)
        det = Detections.from_records(rows)
        res = cls.unprojected(det)
        if not rows:
            return res
        missing = [f.name for f in CANDIDATE_OWN_FIELDS if f.name not in rows[0]]
        if missing:
            raise InputError("The candidates lack the field(s) {fields}; expected the output of "
                             "Project detections", fields=", ".join(missing))

        def number(row, name):
            try:
                return np.nan if row[name] is None else float(row[name])
            except (TypeError, ValueError, OverflowError):
                raise InputError("Detection {det_id}, field {field}: expected a number, found '{value}'",
                                 det_id=row.get("det_id"), field=name, value=str(row[name])[:60])

        def col(name):
            return np.array([number(r, name) for r in rows])

        for r in rows:
            if r["status"] is None:
                raise InputError("Detection {det_id}: the field {field} is empty",
                                 det_id=r.get("det_id"), field="status")

        res.xyz_world = np.column_stack([col("cand_x"), col("cand_y"), col("cand_z")])
        res.normal_world = np.column_stack([col("normal_e"), col("normal_n"), col("normal_u")])
        res.range_m, res.quality = col("range_m"), np.nan_to_num(col("quality"))
        res.n_points = np.nan_to_num(col("n_points")).astype(np.int64)
        res.status = [str(r["status"]) for r in rows]
        bad = [s for s in res.status if s not in (STATUS_OK, STATUS_NO_POINTS, STATUS_NO_SURFACE)]
        if bad:
            raise InputError("Unknown candidate status {status!r}; expected ok, no_points or "
                             "no_surface", status=bad[0])
        ok = np.array([s == STATUS_OK for s in res.status])
        if np.any(ok & ~np.all(np.isfinite(res.xyz_world), axis=1)):
            raise InputError("A candidate with status ok has no position")
        return res


def check_ground_classified(index: TiledIndex, source: str) -> None:
    """:class:`InputError` when an indexed cloud has points but none of class 2."""
    if len(index) and not np.any(index.attributes["classification"] == GROUND_CLASS):
        raise InputError("{source} has no ground points (class 2) where the signs are: run "
                         "roadsigns:groundfilter on it first (or classify the ground with "
                         "another tool)", source=source)


def build_index(cloud: Union[str, CloudSource, TiledIndex], region: Optional[CropRegion], tile_size_m: float,
                progress: Progress = SILENT) -> Tuple[TiledIndex, str]:
    """A :class:`TiledIndex` with intensity and classification (read from a cloud, any form
    of :func:`.cloudsource.open_cloud`, cropped to ``region``: only the tiles it meets are
    read), or the given index after checking its attributes."""
    if isinstance(cloud, TiledIndex):
        index, source = cloud, "The point cloud"
        missing = [d for d in ("intensity", "classification") if d not in index.attributes]
        if missing:
            raise InputError("The point index lacks {names}", names=", ".join(missing))
    else:
        cloud_source = open_cloud(cloud)
        source = cloud_source.path
        index = cloud_source.index(region, ("intensity", "classification"), tile_size_m, progress=progress)
    check_ground_classified(index, source)
    return index, source


def _footprint_cells(frusta: Frusta, rows: np.ndarray, cell_m: float, present: Optional[set] = None
                     ) -> Iterator[Tuple[int, np.ndarray, np.ndarray]]:
    """``(k, i, j)`` for each detection ``k`` of ``rows``: the columns ``i`` and rows ``j``
    (int64) of the square cells of ``cell_m`` metres that its footprint touches, of those in
    ``present`` (``(i, j)`` tuples) when given; detections touching none are skipped."""
    for k, footprint in zip(map(int, rows), frusta.footprints(rows)):
        i0, j0 = np.floor(frusta.lo_world[k, :2] / cell_m).astype(np.int64)
        i1, j1 = np.floor(frusta.hi_world[k, :2] / cell_m).astype(np.int64)
        i, j = (a.ravel() for a in np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1), indexing="ij"))
        if present is not None:
            kept = np.fromiter(((a, b) in present for a, b in zip(i.tolist(), j.tolist())), bool, len(i))
            i, j = i[kept], j[kept]
        if len(i):
            hit = shapely.intersects(footprint, shapely.box(i * cell_m, j * cell_m, (i + 1) * cell_m,
                                                            (j + 1) * cell_m))
            yield k, i[hit], j[hit]


def _frustum_members(xyz, det: Detections, k: int, frusta: Frusta, f: int, R: np.ndarray,
                     max_range_m: float, min_range_m: float) -> np.ndarray:
    """Rows of ``xyz`` inside detection ``k``'s frustum (grown box, range window), row ``f``
    of ``frusta``."""
    inside = np.all((xyz >= frusta.lo_world[f]) & (xyz <= frusta.hi_world[f]), axis=1)
    rows = np.flatnonzero(inside)
    if rows.size == 0:
        return rows
    W, H = det.pano_size_px[k]
    u, v, rng = geometry.world_to_pixel(xyz[rows], det.centre_world[k], R[k], W, H)
    a, b = box_coordinates(u, v, frusta.boxes_px[f], W)
    keep = (a >= 0) & (a <= 1) & (b >= 0) & (b <= 1) & (rng >= min_range_m) & (rng <= max_range_m)
    return rows[keep]


@dataclass
class Surface:
    xyz_world: np.ndarray
    normal_world: np.ndarray
    range_m: float
    members: np.ndarray   # rows of the frustum points on the surface
    quality: float


def find_surface(xyz: np.ndarray, centre: np.ndarray, ray: np.ndarray, a: np.ndarray,
                 b: np.ndarray, params: ProjectionParams) -> Tuple[str, Optional[Surface]]:
    """The first dense planar cluster along the box-centre ray among frustum points.

    ``a, b``: the points' coordinates relative to the (un-grown) box, 0..1 inside. Clusters
    are ranked by the median range of their points in the box's core (the central
    ``core_fraction``); the first one that is dense, planar, flat and not a line wins. Its
    curvature is judged on its points in the whole box: the core's lever arm is too short
    to tell a small sign's range noise from a mirror's bulge.
    """
    if len(xyz) < params.min_points:
        return STATUS_NO_POINTS, None
    rng = np.linalg.norm(xyz - centre, axis=1)
    tol = max(params.cluster_tolerance_m, params.cluster_tolerance_per_m * float(np.median(rng)))
    labels = euclidean_clusters(xyz, tol)
    half = params.core_fraction / 2.0
    core = (np.abs(a - 0.5) <= half) & (np.abs(b - 0.5) <= half)
    counts = np.bincount(labels)
    order = []
    for lab in np.flatnonzero(counts >= params.min_points):
        in_core = core & (labels == lab)
        if in_core.sum() >= max(3, params.min_points // 3):
            order.append((float(np.median(rng[in_core])), int(lab)))
    for _, lab in sorted(order):
        members = np.flatnonzero(labels == lab)
        pts = xyz[members]
        thr = params.plane_threshold_m + 0.001 * float(np.median(rng[members]))
        plane = fit_plane_ransac(pts, thr, params.max_tilt_deg, seed=int(lab))
        if plane is None:
            continue
        in_core = core[members]
        share = float(plane.inliers[in_core].mean())
        on = pts[plane.inliers]
        _, ev, _ = pca(on)
        if (share < params.min_inlier_share or np.sqrt(ev[1]) < params.min_extent_m
                or plane.inliers.sum() < params.min_points):
            continue
        normal = plane.normal if plane.normal @ (centre - plane.point) > 0 else -plane.normal
        in_box = (a[members] >= 0) & (a[members] <= 1) & (b[members] >= 0) & (b[members] <= 1)
        if convex_radius_m(pts[in_box], normal) < params.min_curvature_radius_m:
            break  # the first surface is curved (a convex mirror): nothing behind it counts
        denom = float(ray @ normal)
        point = None
        if denom < -0.1:  # the ray meets the front of the plane
            t = float((plane.point - centre) @ normal) / denom
            point = centre + t * ray
            if np.min(np.linalg.norm(on - point, axis=1)) > 2.0 * tol:
                point = None  # the ray passes through a hole or beside the surface
        if point is None:
            centre_pts = plane.inliers & in_core
            q = np.median(pts[centre_pts] if np.any(centre_pts) else on, axis=0)
            point = q - plane.distance(q) * normal
        # quality: plane support in the core x density x coverage of the box by the surface
        grid = (np.clip(a[members][plane.inliers], 0, 0.999) * 4).astype(int) * 4 + \
            (np.clip(b[members][plane.inliers], 0, 0.999) * 4).astype(int)
        coverage = len(np.unique(grid)) / 16.0
        quality = share * (1.0 - math.exp(-plane.inliers.sum() / 30.0)) * min(1.0, coverage / 0.6)
        return STATUS_OK, Surface(point, normal, float(np.linalg.norm(point - centre)),
                                  members[plane.inliers], float(quality))
    return STATUS_NO_SURFACE, None


def project_detections(detections: Detections, cloud: Union[str, CloudSource, TiledIndex],
                       max_range_m: float = DEFAULT_MAX_RANGE_M,
                       params: ProjectionParams = ProjectionParams(),
                       progress: Progress = SILENT, keep_point_index: bool = False) -> ProjectionResult:
    """Candidate sign surface per detection (see the module doc).

    ``cloud``: a ground-classified cloud (a LAS/LAZ file, a folder of tiles, a ``.vpc``, or
    a :class:`.cloudsource.CloudSource`), read once and worked through block by block along
    the drive (:func:`drive_blocks`), or a :class:`TiledIndex` holding
    ``intensity`` and ``classification`` (one block). Empty detections give an empty result
    and a warning; a cloud without ground class raises :class:`InputError`.
    ``keep_point_index``: keep each surface's point positions (``point_index``); the
    candidates layer does not carry them, and on a long drive they would be most of what the
    result holds (~7.5 kB a detection: 100 MB on a 9 km drive).
    """
    if not max_range_m or max_range_m <= params.min_range_m:
        raise InputError("The maximum range must exceed {min} m, got {value} m",
                         min=params.min_range_m, value=max_range_m)
    det = detections
    result = ProjectionResult.unprojected(det)
    if len(det) == 0:
        result.warnings.append(progress.warning("No detections to project; the candidates are empty"))
        return result
    det.validate()
    if isinstance(cloud, TiledIndex):
        index, source = build_index(cloud, None, params.tile_size_m)
        result.n_indexed, result.n_tiles = len(index), len(index.tile_keys)
        blocks: Iterator[Tuple[np.ndarray, TiledIndex]] = iter(
            [(np.arange(len(det)), _non_ground(index, params.tile_size_m))])
        searching = progress
    else:
        cloud_source = open_cloud(cloud)
        source = cloud_source.path
        reading, searching = progress.sub(0.0, 0.5), progress.sub(0.5, 1.0)
        blocks = drive_blocks(det, cloud_source, max_range_m, params, reading)
    R, rays = det.R_world_from_pano(), det.centre_rays_world()  # once, not per block

    def project(block: Tuple[np.ndarray, TiledIndex]) -> Tuple[int, int, int]:
        rows, index = block                   # each block fills its own rows of result
        # the block's own frusta (row j is detection rows[j]): none of the drive's is held
        frusta = Frusta.build(det.take(rows), max_range_m, params.margin_deg, params.margin_frac)
        _project_block(det, rows, index, frusta, R, rays, max_range_m, params, result, keep_point_index)
        return len(rows), len(index), len(index.tile_keys)

    n_done = 0
    for n_rows, n_points, n_tiles in map_in_order(project, blocks, params.block_threads, searching.check):
        if not isinstance(cloud, TiledIndex):  # a block of the spooled cloud
            result.n_indexed += n_points
            result.n_tiles += n_tiles
        n_done += n_rows
        searching.report(n_done / len(det))
        searching.step("Searching the detections' surfaces: {n} of {count}", n=n_done, count=len(det))
    if result.n_indexed == 0:
        result.warnings.append(progress.warning(
            "{path} has no point inside the detections' frusta; no candidate found", path=source))
        return result
    n_ok = sum(s == STATUS_OK for s in result.status)
    progress.info("{ok} of {count} detections found a surface in the cloud ({no_points} "
                  "without points, {no_surface} without a planar surface)", ok=n_ok,
                  count=len(det), no_points=result.status.count(STATUS_NO_POINTS),
                  no_surface=result.status.count(STATUS_NO_SURFACE))
    return result


def _non_ground(index: TiledIndex, tile_size_m: float) -> TiledIndex:
    """The points of ``index`` that are not ground (class 2), in a new index."""
    keep = index.attributes["classification"] != GROUND_CLASS
    return TiledIndex(index.xyz_world[keep], index.point_index[keep], {}, tile_size_m, index.crs_wkt)


def station_track(det: Detections) -> Optional[Track]:
    """The drive's track through the detections' panorama centres, in station order; None
    when they stand at fewer than two places (one block then)."""
    xyz = det.centre_world[det.station_rows()]
    moving = np.r_[True, np.linalg.norm(np.diff(xyz[:, :2], axis=0), axis=1) > 1e-6]
    return Track(xyz[moving]) if moving.sum() >= 2 else None


def drive_blocks(det: Detections, cloud: Union[str, CloudSource], max_range_m: float,
                 params: ProjectionParams, progress: Progress = SILENT,
                 chunk_points: int = DEFAULT_CHUNK_POINTS) -> Iterator[Tuple[np.ndarray, TiledIndex]]:
    """``(detection rows, index of the points their frusta may hold)`` block by block.

    One streaming read of the cloud (of the tiles, or COPC nodes, that the footprints'
    cover meets, :meth:`Frusta.cover`: a drive through a tiled city reads the tiles along it) keeps the
    non-ground points in the cells of :data:`FRUSTUM_CELL_M` that a frustum's footprint
    touches (:func:`drive_reach`; the exact frustum test comes later, per detection, in its
    block's own frusta) and
    spools each to the slice of :data:`SLICE_M` metres of drive holding its arc length along
    the drive (the track through the stations, :mod:`.drivewindows`). The chunks (of
    ``chunk_points``) are read in this thread, worked on ``params.block_threads`` at a time
    and spooled in reading order. A detection belongs to
    the slice of its station; a block is a run of slices (:func:`slice_blocks`: at most
    ``params.block_m`` long, and reading at most ``params.block_max_points`` points), and
    reads the slices within twice ``max_range_m`` of it. Blocks are indexed one at a time,
    so memory follows the block, not the drive; a block's points are bounded, not only its
    length, since the densest stretch of a longer drive is denser. :class:`InputError` when
    the cloud has points inside the frusta but none of class 2.
    """
    track = station_track(det)
    axis = DriveAxis(track) if track is not None else None
    length_m = axis.length_m if axis is not None else 0.0
    slices = make_windows(length_m, min(SLICE_M, params.block_m))
    inner_edges_m = np.array([w.s1_m for w in slices[:-1]])
    owner_s = axis.locate(det.centre_world)[0] if axis is not None else np.zeros(len(det))
    drive_order = np.argsort(owner_s, kind="stable")
    cells, cover = drive_reach(det, drive_order, max_range_m, params)
    owner_slice = np.searchsorted(inner_edges_m, owner_s, side="right")
    n_ground = n_inside = 0
    source = open_cloud(cloud)

    def chunk_rows(item: Tuple[np.ndarray, Any]) -> Tuple[int, int, np.ndarray, np.ndarray]:
        """A chunk's points in the cells: ``(points inside, ground points inside, the
        others' spool rows, their slices)``; of the chunk alone, so chunks are worked on in
        parallel and spooled in reading order."""
        point_index, chunk = item
        inside = in_sorted(cell_keys(np.asarray(chunk.x), np.asarray(chunk.y), FRUSTUM_CELL_M), cells)
        ground = np.asarray(chunk.classification)[inside] == GROUND_CLASS
        rows = np.empty(int((~ground).sum()), SPOOL_DTYPE)
        xyz = xyz_of(chunk[inside])[~ground]
        rows["x"], rows["y"], rows["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
        rows["index"] = point_index[inside][~ground]
        s_m = axis.locate(xyz)[0] if axis is not None else np.zeros(len(rows))
        return int(inside.sum()), int(ground.sum()), rows, np.searchsorted(inner_edges_m, s_m, side="right")

    with Spool({"points": SPOOL_DTYPE}, prefix="roadsigns-projection-") as spool:
        chunks = source.iter_indexed_chunks(chunk_points, progress, area=cover)
        del cover                # planned: the drive's shapes are not held through the reading
        for inside_n, ground_n, rows, where in map_in_order(chunk_rows, chunks, params.block_threads,
                                                            progress.check):
            n_inside += inside_n
            n_ground += ground_n
            for k in np.unique(where):
                spool.append("points", int(k), rows[where == k])
            del rows, where
        spool.flush()
        if n_inside and not n_ground:
            raise InputError("{source} has no ground points (class 2) where the signs are: run "
                             "roadsigns:groundfilter on it first (or classify the ground with "
                             "another tool)", source=source.path)
        counts = np.array([spool.count("points", k) for k in range(len(slices))], np.int64)
        for rows_k, first, last in slice_blocks(slices, owner_slice, counts, 2.0 * max_range_m,
                                                params.block_m, params.block_max_points):
            # the slices' points straight into the arrays the index takes, a slice at a time
            xyz = np.empty((int(counts[first:last + 1].sum()), 3))
            index = np.empty(len(xyz), np.int64)
            at = 0
            for k in range(first, last + 1):
                points = spool.read("points", k)
                end = at + len(points)
                xyz[at:end, 0], xyz[at:end, 1], xyz[at:end, 2] = points["x"], points["y"], points["z"]
                index[at:end] = points["index"]
                at = end
            del points
            block = TiledIndex(xyz, index, {}, params.tile_size_m)   # holds its own, sorted, copies
            del xyz, index       # not kept in this frame while the block is worked on
            yield rows_k, block
            del block


def drive_reach(det: Detections, drive_order: np.ndarray, max_range_m: float, params: ProjectionParams,
                batch: int = FRUSTA_BATCH) -> Tuple[np.ndarray, np.ndarray]:
    """``(cells, cover)`` of the whole drive: the sorted keys of the cells of
    :data:`FRUSTUM_CELL_M` that some detection's footprint touches (:func:`frustum_cells`) and
    the convex hulls covering the footprints, :data:`COVER_GROUP` detections a hull in
    ``drive_order`` (:meth:`Frusta.cover`). The frusta are built ``batch`` detections at a
    time in that order and let go: none of the drive's is held (each block builds its own)."""
    batch = max(COVER_GROUP, batch // COVER_GROUP * COVER_GROUP)   # whole groups: the cover's hulls as one build's
    cells = np.zeros(0, np.int64)
    hulls = [np.empty(0, dtype=object)]
    for b0 in range(0, len(drive_order), batch):
        frusta = Frusta.build(det.take(drive_order[b0:b0 + batch]), max_range_m, params.margin_deg,
                              params.margin_frac, batch=batch)
        cells = np.union1d(cells, frustum_cells(frusta, FRUSTUM_CELL_M))
        hulls.append(frusta.cover(np.arange(len(frusta)), group=COVER_GROUP))
        del frusta
    return cells, np.concatenate(hulls)


def slice_blocks(slices: List[Window], owner_slice: np.ndarray, counts: np.ndarray, reach_m: float,
                 block_m: float, max_points: int) -> Iterator[Tuple[np.ndarray, int, int]]:
    """``(detection rows, first slice, last slice)`` per block, in drive order: runs of the
    ``slices`` that own detections (``owner_slice``: each detection's slice), a run at most
    ``block_m`` long and its read (the slices within ``reach_m`` of it, both sides: ``counts``
    points each) at most ``max_points``, but one slice at least; ``first`` to ``last`` are
    the slices it reads."""
    n = len(slices)
    inner = np.array([w.s1_m for w in slices[:-1]])
    length_m = max((w.s1_m - w.s0_m for w in slices if np.isfinite(w.s1_m - w.s0_m)), default=block_m)
    most = max(1, int(round(block_m / length_m)) if np.isfinite(block_m) else n)
    owned = np.bincount(owner_slice, minlength=n) > 0
    total = np.r_[0, np.cumsum(counts)]

    def read(a: int, b: int) -> Tuple[int, int]:
        lo = int(np.searchsorted(inner, slices[a].s0_m - reach_m, side="right"))
        hi = min(int(np.searchsorted(inner, slices[b].s1_m + reach_m, side="left")), n - 1)
        return lo, hi

    a = 0
    while a < n:
        if not owned[a]:
            a += 1
            continue
        b = a
        while b + 1 < n and b + 1 - a < most:
            lo, hi = read(a, b + 1)
            if total[hi + 1] - total[lo] > max_points:
                break
            b += 1
        b = a + int(np.flatnonzero(owned[a:b + 1]).max())   # ends at a slice with detections
        lo, hi = read(a, b)
        yield np.flatnonzero((owner_slice >= a) & (owner_slice <= b)), lo, hi
        a = b + 1


def in_sorted(keys: np.ndarray, sorted_keys: np.ndarray) -> np.ndarray:
    """``np.isin(keys, sorted_keys)`` for a sorted ``sorted_keys``, by binary search: time and
    memory follow ``keys`` (a chunk), not ``sorted_keys`` (the cells of a whole drive), which
    ``np.isin`` would copy and sort with every chunk."""
    if not len(sorted_keys):
        return np.zeros(len(keys), bool)
    at = np.minimum(np.searchsorted(sorted_keys, keys), len(sorted_keys) - 1)
    return sorted_keys[at] == keys


def cell_keys(x: np.ndarray, y: np.ndarray, cell_m: float) -> np.ndarray:
    """One int64 key per point for its square cell of ``cell_m`` metres (world grid)."""
    return (np.floor(x / cell_m).astype(np.int64) << 32) + (np.floor(y / cell_m).astype(np.int64) & 0xFFFFFFFF)


def frustum_cells(frusta: Frusta, cell_m: float, batch: int = FRUSTA_BATCH) -> np.ndarray:
    """Sorted keys (:func:`cell_keys`) of the cells that some frustum's footprint touches,
    ``batch`` footprints at a time, each batch's cells merged into the drive's as it goes:
    what is held is the drive's distinct cells (neighbouring frusta share most of theirs)."""
    cells = np.zeros(0, np.int64)
    for b0 in range(0, len(frusta), batch):
        keys = [cell_keys((i + 0.5) * cell_m, (j + 0.5) * cell_m, cell_m)
                for _, i, j in _footprint_cells(frusta, np.arange(b0, min(b0 + batch, len(frusta))), cell_m)]
        if keys:
            cells = np.union1d(cells, np.concatenate(keys))
    return cells


def _project_block(det: Detections, rows: np.ndarray, index: TiledIndex, frusta: Frusta, R: np.ndarray,
                   rays: np.ndarray, max_range_m: float, params: ProjectionParams,
                   result: ProjectionResult, keep_point_index: bool) -> None:
    """Project the detections ``rows`` into ``index`` (non-ground points only), filling
    their rows of ``result``; ``frusta``: theirs, row ``j`` that of detection ``rows[j]``
    (:meth:`Frusta.build` of ``det.take(rows)``). One detection at a time, its frustum tested on each tile its
    footprint crosses (views of the index's arrays, no copies), its surface searched among
    the points inside. Nothing a detection allocates outlives it, so the heap a block leaves
    does not depend on how its detections' tiles interleave."""
    if len(index) == 0:
        return
    present = set(index.tile_keys)
    for f, i, j in _footprint_cells(frusta, np.arange(len(rows)), index.tile_size_m, present):
        k = int(rows[f])
        parts = []
        for key in zip(i.tolist(), j.tolist()):
            start, end = index.tile_rows(key)
            result.tiles_visited[k] += 1
            result.points_tested[k] += end - start
            inside = _frustum_members(index.xyz_world[start:end], det, k, frusta, f, R, max_range_m,
                                      params.min_range_m)
            if inside.size:
                parts.append(start + inside)
        if parts:
            _search_surface(det, k, np.concatenate(parts), index, R, rays, params, result, keep_point_index)


def _search_surface(det: Detections, k: int, members: np.ndarray, index: TiledIndex, R: np.ndarray,
                    rays: np.ndarray, params: ProjectionParams, result: ProjectionResult,
                    keep_point_index: bool) -> None:
    """The surface of detection ``k`` among its frustum's points (``members``: rows of
    ``index``), into row ``k`` of ``result``. The points are taken in the cloud's order
    (point index), whatever the tiles' order."""
    pidx = index.point_index[members]
    order = np.argsort(pidx, kind="stable")
    pidx = pidx[order]
    xyz = index.xyz_world[members[order]]
    W, H = det.pano_size_px[k]
    u, v, _ = geometry.world_to_pixel(xyz, det.centre_world[k], R[k], W, H)
    a, b = box_coordinates(u, v, det.box_px[k], W)
    status, surface = find_surface(xyz, det.centre_world[k], rays[k], a, b, params)
    result.status[k] = status
    if surface is not None:
        result.xyz_world[k] = surface.xyz_world
        result.normal_world[k] = surface.normal_world
        result.range_m[k] = surface.range_m
        result.n_points[k] = len(surface.members)
        result.quality[k] = surface.quality
        if keep_point_index:
            result.point_index[k] = pidx[surface.members]
