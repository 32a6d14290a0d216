"""Sign panels in a window of the cloud, from geometry and retroreflectivity alone.

A window holds the non-ground points of a stretch of the drive with, per point, the height
above the ground model ``h``, the sensor position, the range-normalised intensity and the
local PCA features (:class:`WindowPoints`). Panels are found on two paths:

* **bright** (retroreflective sheeting): points above the adaptive threshold at sign
  heights, Euclidean clusters, planes;
* **dark** (faded faces, backs of signs): points whose neighbourhood is flat with a
  normal that is near horizontal and along the drive (walls along the road are not; beside
  a pole, the neighbourhood without the pole's points: :func:`features_off_poles`),
  away from bright points, Euclidean clusters, planes; these must be carried by a pole or
  a gantry (decided later, :mod:`.cloudsigns`).

Planes: RANSAC constrained to near-vertical planes (``max_tilt_deg``), repeated on what is
left of a cluster, without the points of a pole just behind the plane; the inliers are
split where they are not connected in the plane and at empty horizontal bands (stacked
panels on one pole, 5-10 cm apart); coplanar parts side by side at the same height are
joined again (a panel seen partly from the front and partly from behind; the back of a
panel cut by the shadow of its pole; with a pole in the gap, one edge alike is enough: a
triangle cut at its pole). Each part is measured in its plane (right/up axes;
extents padded by half a row or column spacing since sampled points stop short of the
edges; centre = centre of the extents) and kept when it passes the size and shape tests
(:class:`PanelParams`): size, area, aspect, fill of its box by its convex hull (a triangle
fills 0.5), thickness (RMS distance to the plane), curvature (a surface bulging towards
the sensor, as the shell of a tree crown, is not a panel), for dark parts the
surroundings (a plane that continues beyond a side and an end is a piece of a billboard
or a wall), the orientation constraint of the Utah I-15 paper: its normal within
``max_normal_to_track_deg`` of the driving direction (signs face the traffic; walls,
billboards and mirrors turned to the road do not), and its height above the ground.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .projection import convex_radius_m, euclidean_clusters, fit_plane_ransac, pca

UP = np.array([0.0, 0.0, 1.0])
#: Neighbours of the local PCA features.
FEATURE_NEIGHBOURS = 16
#: Points per block of the batched PCA (memory).
FEATURE_BLOCK = 100_000


@dataclass
class PanelParams:
    """Tuning of the panel search; lengths in metres, angles in degrees."""

    min_bright_height_m: float = 1.0      # bright points lower than this are not on signs
    bright_min_share: float = 0.3         # a panel with this share of bright points is retroreflective
    min_bottom_height_m: float = 1.0      # a panel's lower edge above the ground
    max_top_height_m: float = 10.0
    cluster_tolerance_m: float = 0.1
    plane_threshold_m: float = 0.04
    max_tilt_deg: float = 20.0            # panels lean at most this from vertical
    ransac_iterations: int = 300
    max_planes_per_cluster: int = 6
    min_points: int = 20
    in_plane_link_m: float = 0.12         # in-plane connectivity (at least)
    min_gap_m: float = 0.05               # an empty band this high (at least) splits panels
    gap_spacings: float = 1.5             # ... or this many vertical point spacings
    min_band_share: float = 0.2           # ... when both sides hold this share of the points
    min_width_m: float = 0.25
    max_width_m: float = 4.0
    min_height_m: float = 0.25
    max_height_m: float = 2.5
    min_area_m2: float = 0.05
    max_area_m2: float = 6.0
    max_aspect: float = 4.0
    min_fill: float = 0.4
    max_rms_m: float = 0.025
    min_convex_radius_m: float = 4.0      # bulging towards the sensor more: a crown or a mirror
    max_normal_to_track_deg: float = 25.0
    dark_max_flatness: float = 0.25       # local l3/l2 of a dark panel point at most
    dark_max_linearity: float = 0.9       # ... and not on a line (a pole, an edge)
    dark_max_normal_tilt_deg: float = 30.0
    dark_normal_slack_deg: float = 10.0   # a dark point's normal: the panel's test plus this
    max_cluster_extent_m: float = 12.0    # clusters larger than this are not searched for panels
    dark_clearance_m: float = 0.15        # dark points this close to bright ones belong to them
    edge_margin_m: float = 0.05           # face points this close to the outline: edge points
    edge_spacings: float = 1.5            # ... or this many point spacings
    merge_gap_m: float = 0.25             # coplanar parts side by side this close: one panel
    pole_surface_m: float = 0.02          # dark points this close to a pole's surface are the pole's
    pole_clearance_m: float = 0.03        # plane inliers this close to a pole's surface ...
    pole_depth_m: float = 0.015           # ... and this far behind the plane are the pole's
    #: points up to this far past a pole's surface (horizontally; but not within
    #: ``pole_clearance_m`` of it) take their local features from neighbours off the pole: the
    #: tip of a triangle seen from behind, beside its pole, is otherwise a mixture of panel and
    #: pole, neither flat nor facing the road (0: off)
    pole_feature_reach_m: float = 0.3
    merge_max_angle_deg: float = 10.0
    surround_band_m: float = 0.3          # a dark panel's plane continuing this far ...
    surround_gap_m: float = 0.05          # ... past this gap
    surround_cell_m: float = 0.1
    surround_depth_m: float = 0.15        # points this close to the plane continue it
    surround_min_share: float = 0.5       # ... over this share of a side and of an end: a billboard
    merge_edge_m: float = 0.15


@dataclass
class WindowPoints:
    """A window's candidate points and per-point quantities (all arrays ``(n, ...)``)."""

    xyz: np.ndarray            # world
    h: np.ndarray              # height above the ground model
    sensor: np.ndarray         # sensor position at the point's time
    intensity: np.ndarray      # raw
    intensity_rn: np.ndarray   # range-normalised (share of full scale)
    bright: np.ndarray         # bool
    s_m: np.ndarray            # arc length on the drive
    offset_m: np.ndarray       # signed lateral offset
    tangent_xy: np.ndarray     # driving direction at the point's place
    normal: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    linearity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    flatness: np.ndarray = field(default_factory=lambda: np.zeros(0))
    scattering: np.ndarray = field(default_factory=lambda: np.zeros(0))
    _tree: Optional[cKDTree] = None

    def __len__(self) -> int:
        return len(self.xyz)

    @property
    def tree(self) -> cKDTree:
        """A KD-tree of the points (built on first use)."""
        if self._tree is None:
            self._tree = cKDTree(self.xyz)
        return self._tree



def local_features(xyz: np.ndarray, k: int = FEATURE_NEIGHBOURS
                   ) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per point: unit normal (smallest principal axis of its ``k`` nearest neighbours),
    linearity ``(l1-l2)/l1``, flatness ``l3/l2`` (small on a surface however anisotropic
    the sampling: a scanner's rows are further apart than its points), scattering
    ``l3/l1``. The normal's sign is arbitrary."""
    n = len(xyz)
    normal = np.zeros((n, 3))
    lin, flat, sca = np.zeros(n), np.ones(n), np.ones(n)
    if n < 3:
        return normal, lin, flat, sca
    k = min(k, n)
    xyz = np.asarray(xyz, dtype=np.float64)
    tree = cKDTree(xyz)
    columns = [np.ascontiguousarray(xyz[:, j]) for j in range(3)]
    for b0 in range(0, n, FEATURE_BLOCK):
        b1 = min(n, b0 + FEATURE_BLOCK)
        _, idx = tree.query(xyz[b0:b1], k=k, workers=-1)
        w, normal[b0:b1] = sym3_eigen(*neighbour_covariances(columns, idx))   # ascending
        w = np.clip(w, 0.0, None)
        l1 = np.maximum(w[:, 2], 1e-12)
        lin[b0:b1] = (w[:, 2] - w[:, 1]) / l1
        flat[b0:b1] = w[:, 0] / np.maximum(w[:, 1], 1e-12)
        sca[b0:b1] = w[:, 0] / l1
    return normal, lin, flat, sca


def neighbour_covariances(columns: Sequence[np.ndarray], idx: np.ndarray) -> Tuple[np.ndarray, ...]:
    """Covariance entries ``(xx, yy, zz, xy, xz, yz)`` (population, ``/k``) of each row's
    neighbours ``idx`` ``(m, k)``, from the coordinate ``columns`` (x, y, z, each ``(n,)``),
    taken relative to each row's first neighbour (no loss of digits far from the origin)."""
    k = idx.shape[1]
    rel = []
    for c in columns:
        g = c[idx]
        g -= g[:, :1]
        rel.append(g)
    x, y, z = rel
    mx, my, mz = x.mean(axis=1), y.mean(axis=1), z.mean(axis=1)

    def moment(a, b, ma, mb):
        return np.einsum("ij,ij->i", a, b) / k - ma * mb

    return (moment(x, x, mx, mx), moment(y, y, my, my), moment(z, z, mz, mz),
            moment(x, y, mx, my), moment(x, z, mx, mz), moment(y, z, my, mz))


def sym3_eigen(xx: np.ndarray, yy: np.ndarray, zz: np.ndarray, xy: np.ndarray, xz: np.ndarray,
               yz: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (ascending, ``(m, 3)``) of many symmetric 3 x 3 matrices given by their
    entries, and the unit eigenvector of the smallest ``(m, 3)``, in closed form (the
    trigonometric solution of the characteristic cubic; the vector as the longest cross
    product of two rows of ``A - l3 I``). Agrees with ``numpy.linalg.eigh`` to rounding
    where the smallest eigenvalue is distinct, several times faster on millions of
    matrices; an isotropic matrix gets ``(0, 0, 1)``."""
    q = (xx + yy + zz) / 3.0
    off = xy * xy + xz * xz + yz * yz
    a, b, c = xx - q, yy - q, zz - q
    p = np.sqrt((a * a + b * b + c * c + 2.0 * off) / 6.0)
    ps = np.where(p > 0.0, p, 1.0)
    det = (a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz)) / (ps * ps * ps)
    phi = np.arccos(np.clip(0.5 * det, -1.0, 1.0)) / 3.0
    l1 = q + 2.0 * p * np.cos(phi)
    l3 = q + 2.0 * p * np.cos(phi + 2.0 * math.pi / 3.0)
    l2 = 3.0 * q - l1 - l3
    r0 = np.column_stack([xx - l3, xy, xz])
    r1 = np.column_stack([xy, yy - l3, yz])
    r2 = np.column_stack([xz, yz, zz - l3])
    crosses = np.stack([np.cross(r0, r1), np.cross(r0, r2), np.cross(r1, r2)])     # (3, m, 3)
    sq = np.einsum("kmi,kmi->km", crosses, crosses)
    best = np.argmax(sq, axis=0)
    rows = np.arange(len(q))
    v = crosses[best, rows]
    length = np.sqrt(sq[best, rows])
    ok = length > 0.0
    v[ok] /= length[ok, None]
    v[~ok] = UP
    return np.column_stack([l3, l2, l1]), v


def panel_frame(normal: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(right, up) in-plane unit vectors of a panel facing ``normal`` (right as a viewer in
    front of the face sees it; up along the plane's steepest ascent)."""
    right = np.cross(-np.asarray(normal, dtype=float), UP)
    norm = float(np.linalg.norm(right))
    right = right / norm if norm > 1e-9 else np.array([1.0, 0.0, 0.0])
    return right, np.cross(right, -np.asarray(normal, dtype=float))


def vertical_spacing_m(uv: np.ndarray, neighbours: int = 8) -> float:
    """Typical vertical distance between a point and the next one up (median over points of
    the smallest rise to a neighbour that lies more above than beside it). Scan lines sample
    panels in rows; a band between stacked panels must be wider than this to be seen."""
    return _spacing_along(uv, 1, neighbours)


def horizontal_spacing_m(uv: np.ndarray, neighbours: int = 8) -> float:
    """As :func:`vertical_spacing_m`, sideways."""
    return _spacing_along(uv, 0, neighbours)


def _spacing_along(uv: np.ndarray, axis: int, neighbours: int) -> float:
    if len(uv) < 3:
        return 0.0
    k = min(neighbours + 1, len(uv))
    _, idx = cKDTree(uv).query(uv, k=k)
    d = uv[idx[:, 1:]] - uv[:, None, :]
    step, side = d[..., axis], d[..., 1 - axis]
    rise = np.where((step > 0.005) & (np.abs(side) <= step), step, np.inf)
    best = rise.min(axis=1)
    best = best[np.isfinite(best)]
    return float(np.median(best)) if len(best) else 0.0


def spacing_m(uv: np.ndarray) -> float:
    """Median nearest-neighbour distance of in-plane points."""
    if len(uv) < 2:
        return 0.0
    d, _ = cKDTree(uv).query(uv, k=2)
    return float(np.median(d[:, 1]))


@dataclass
class PanelCandidate:
    """A planar part that passed the shape tests, measured in its plane."""

    rows: np.ndarray               # indices into the window's points
    centre: np.ndarray             # world, centre of the outline
    normal: np.ndarray             # unit, towards the sensors (turned later by the support)
    width_m: float
    height_m: float
    area_m2: float
    fill: float
    rms_m: float
    spacing_m: float
    bright_share: float
    bottom_height_m: float         # lower edge above ground
    centre_height_m: float
    s_m: float
    offset_m: float
    bright: bool
    corners: np.ndarray = field(default_factory=lambda: np.zeros((4, 3)))


def _split_connected(uv: np.ndarray, link_m: float) -> List[np.ndarray]:
    labels = euclidean_clusters(np.column_stack([uv, np.zeros(len(uv))]), link_m)
    return [np.flatnonzero(labels == k) for k in np.unique(labels)]


def _split_bands(v: np.ndarray, min_gap_m: float, min_share: float, min_points: int
                 ) -> List[np.ndarray]:
    """Split at empty horizontal bands at least ``min_gap_m`` high (stacked panels), where
    both sides hold at least ``min_share`` of the points: the narrow tip of a triangle,
    crossed by a single scan line, has gaps of a point spacing and stays whole."""
    order = np.argsort(v)
    vs = v[order]
    gaps = np.flatnonzero(np.diff(vs) >= min_gap_m)
    n = len(v)
    need = max(min_points, int(math.ceil(min_share * n)))
    ok = [g for g in gaps if g + 1 >= need and n - g - 1 >= need]
    if not ok:
        return [np.arange(n)]
    g = max(ok, key=lambda k: vs[k + 1] - vs[k])
    lower, upper = order[:g + 1], order[g + 1:]
    return ([lower[k] for k in _split_bands(v[lower], min_gap_m, min_share, min_points)]
            + [upper[k] for k in _split_bands(v[upper], min_gap_m, min_share, min_points)])


def _off_poles(xyz: np.ndarray, point: np.ndarray, normal: np.ndarray, poles: Sequence[Tuple[np.ndarray, float]],
               params: PanelParams) -> np.ndarray:
    """Mask of plane inliers that are not on a pole just behind the plane: a sign's pole
    runs a few centimetres behind its face, within the plane's threshold."""
    keep = np.ones(len(xyz), bool)
    d = (xyz - point) @ normal
    for axis_xy, radius in poles:
        near = np.linalg.norm(xyz[:, :2] - axis_xy, axis=1) <= radius + params.pole_clearance_m
        if not near.any():
            continue
        side = 1.0 if float((np.r_[axis_xy, point[2]] - point) @ normal) >= 0 else -1.0
        keep &= ~(near & (side * d > params.pole_depth_m))
    return keep


def segment_panels(pts: WindowPoints, rows: np.ndarray, params: PanelParams, seed: int,
                   poles: Sequence[Tuple[np.ndarray, float]] = ()) -> List[np.ndarray]:
    """Planar parts (row arrays) of one cluster: constrained RANSAC planes, repeated on the
    rest, without the points of ``poles`` (axis xy, radius) behind them, each split into
    connected parts and at empty horizontal bands."""
    out: List[np.ndarray] = []
    remaining = np.asarray(rows, dtype=np.int64)
    for k in range(params.max_planes_per_cluster):
        if len(remaining) < params.min_points:
            break
        plane = fit_plane_ransac(pts.xyz[remaining], params.plane_threshold_m,
                                 max_tilt_deg=params.max_tilt_deg,
                                 iterations=params.ransac_iterations, seed=seed + k)
        if plane is None or int(plane.inliers.sum()) < params.min_points:
            break
        inl = remaining[plane.inliers]
        if len(poles):
            inl = inl[_off_poles(pts.xyz[inl], plane.point, plane.normal, poles, params)]
        right, up = panel_frame(plane.normal)
        uv = np.column_stack([(pts.xyz[inl] - plane.point) @ right, (pts.xyz[inl] - plane.point) @ up])
        link = max(params.in_plane_link_m, 2.5 * spacing_m(uv))
        for part in _split_connected(uv, link):
            if len(part) < params.min_points:
                continue
            gap = max(params.min_gap_m, params.gap_spacings * vertical_spacing_m(uv[part]))
            for band in _split_bands(uv[part, 1], gap, params.min_band_share, params.min_points):
                if len(band) >= params.min_points:
                    out.append(inl[part[band]])
        remaining = remaining[~plane.inliers]
    return out


def measure_panel(pts: WindowPoints, rows: np.ndarray, ground_z, params: PanelParams
                  ) -> Tuple[Optional[PanelCandidate], str]:
    """Measure a planar part in its plane and run the size and shape tests; (None, reason)
    when it fails one."""
    xyz = pts.xyz[rows]
    centroid, eig, V = pca(xyz)
    normal = V[:, 2]
    if abs(normal[2]) > math.sin(math.radians(params.max_tilt_deg)):
        return None, "tilted"
    towards = (pts.sensor[rows] - xyz).mean(axis=0)
    if normal @ towards < 0:
        normal = -normal
    right, up = panel_frame(normal)
    rel = xyz - centroid
    uv = np.column_stack([rel @ right, rel @ up])
    d = rel @ normal
    rms = float(np.sqrt(np.mean(d ** 2)))
    raw = np.ptp(uv, axis=0)                  # cheap tests first: the extents before padding
    if raw[0] > params.max_width_m or raw[1] > params.max_height_m:
        return None, "too large"
    if raw[0] + 0.1 < params.min_width_m or raw[1] + 0.1 < params.min_height_m:
        return None, "too small"
    n_h = normal[:2] / max(float(np.linalg.norm(normal[:2])), 1e-9)
    t = np.median(pts.tangent_xy[rows], axis=0)
    t = t / max(float(np.linalg.norm(t)), 1e-9)
    off_track_deg = math.degrees(math.acos(min(1.0, abs(float(n_h @ t)))))
    if off_track_deg > params.max_normal_to_track_deg:
        return None, "not facing the road"
    spacing = spacing_m(uv)
    pad = 0.5 * np.array([horizontal_spacing_m(uv), vertical_spacing_m(uv)])
    lo, hi = uv.min(axis=0) - pad, uv.max(axis=0) + pad
    width, height = float(hi[0] - lo[0]), float(hi[1] - lo[1])
    mid = 0.5 * (lo + hi)
    centre = centroid + mid[0] * right + mid[1] * up
    hull = shapely.MultiPoint(uv - mid).convex_hull
    if hull.geom_type == "Polygon":
        hull = hull.buffer(0.5 * spacing, join_style="mitre")
    area = float(hull.area)
    fill = area / max(width * height, 1e-9)
    gz = float(ground_z(centre[None, :2])[0])
    bottom = float(centre[2] - 0.5 * height - gz)
    s_m = float(np.median(pts.s_m[rows]))
    offset = float(np.median(pts.offset_m[rows]))
    bright_share = float(np.mean(pts.bright[rows]))
    tests = (
        (width < params.min_width_m or height < params.min_height_m, "too small"),
        (width > params.max_width_m or height > params.max_height_m, "too large"),
        (not params.min_area_m2 <= area <= params.max_area_m2, "area"),
        (max(width, height) / max(min(width, height), 1e-9) > params.max_aspect, "aspect"),
        (fill < params.min_fill, "fill"),
        (rms > params.max_rms_m, "thick"),
        (convex_radius_m(xyz, normal) < params.min_convex_radius_m, "curved"),
        (bottom < params.min_bottom_height_m, "too low"),
        (bottom + height > params.max_top_height_m, "too high"),
    )
    for failed, reason in tests:
        if failed:
            return None, reason
    if bright_share < params.bright_min_share and on_larger_surface(pts, centre, normal, width, height, params):
        return None, "part of a larger surface"
    corners = np.array([centre + sx * 0.5 * width * right + sy * 0.5 * height * up
                        for sx, sy in ((-1, 1), (1, 1), (1, -1), (-1, -1))])
    return PanelCandidate(rows=np.asarray(rows), centre=centre, normal=normal, width_m=width,
                          height_m=height, area_m2=area, fill=fill, rms_m=rms, spacing_m=spacing,
                          bright_share=bright_share, bottom_height_m=bottom,
                          centre_height_m=float(centre[2] - gz), s_m=s_m, offset_m=offset,
                          bright=bright_share >= params.bright_min_share, corners=corners), "ok"


def _band_share(uv: np.ndarray, u_range: Tuple[float, float], v_range: Tuple[float, float],
                cell_m: float) -> float:
    """Share of the cells of the box ``u_range`` x ``v_range`` holding a point of ``uv``."""
    nu = max(1, int(round((u_range[1] - u_range[0]) / cell_m)))
    nv = max(1, int(round((v_range[1] - v_range[0]) / cell_m)))
    inside = ((uv[:, 0] >= u_range[0]) & (uv[:, 0] < u_range[1])
              & (uv[:, 1] >= v_range[0]) & (uv[:, 1] < v_range[1]))
    if not inside.any():
        return 0.0
    iu = np.minimum(((uv[inside, 0] - u_range[0]) / cell_m).astype(np.int64), nu - 1)
    iv = np.minimum(((uv[inside, 1] - v_range[0]) / cell_m).astype(np.int64), nv - 1)
    return len(np.unique(iu * nv + iv)) / float(nu * nv)


def on_larger_surface(pts: WindowPoints, centre: np.ndarray, normal: np.ndarray, width: float,
                      height: float, params: PanelParams) -> bool:
    """Whether a panel's plane continues beyond one of its vertical sides and one of its
    horizontal sides (bands of ``surround_band_m`` past a gap of ``surround_gap_m``, mostly
    occupied by coplanar points): a piece of a billboard or a wall, not a sign. A pole, a
    stacked panel or a gantry beam continue the plane on one side only."""
    right, up = panel_frame(normal)
    reach = 0.5 * math.hypot(width, height) + params.surround_gap_m + params.surround_band_m
    near = np.asarray(pts.tree.query_ball_point(centre, reach), dtype=np.int64)
    if len(near) == 0:
        return False
    rel = pts.xyz[near] - centre
    coplanar = np.abs(rel @ normal) <= params.surround_depth_m
    uv = np.column_stack([rel[coplanar] @ right, rel[coplanar] @ up])
    hw, hh = 0.5 * width, 0.5 * height
    g, b, c = params.surround_gap_m, params.surround_band_m, params.surround_cell_m
    sides = [_band_share(uv, (hw + g, hw + g + b), (-hh, hh), c),
             _band_share(uv, (-hw - g - b, -hw - g), (-hh, hh), c)]
    ends = [_band_share(uv, (-hw, hw), (hh + g, hh + g + b), c),
            _band_share(uv, (-hw, hw), (-hh - g - b, -hh - g), c)]
    return max(sides) >= params.surround_min_share and max(ends) >= params.surround_min_share


def _side_by_side(pts: WindowPoints, a: np.ndarray, b: np.ndarray, params: PanelParams,
                  poles: Sequence[Tuple[np.ndarray, float]] = ()) -> bool:
    """Whether planar parts ``a`` and ``b`` (rows) are one panel cut in two: coplanar, with
    the same top and bottom edges (within ``merge_edge_m``) and at most ``merge_gap_m``
    apart sideways. (A panel seen
    partly from the front, bright, and partly from behind, dark; the back of a panel split
    by the shadow of the pole in front of it.) Where one of ``poles`` (axis xy, radius)
    passes between them, one edge alike is enough: a triangle seen from behind, split at its
    pole, has one half with the tip and one without."""
    ca, _, Va = pca(pts.xyz[a])
    cb, _, Vb = pca(pts.xyz[b])
    na, nb = Va[:, 2], Vb[:, 2]
    if abs(float(na @ nb)) < math.cos(math.radians(params.merge_max_angle_deg)):
        return False
    if abs(float((cb - ca) @ na)) > 2.0 * params.plane_threshold_m:
        return False
    right, up = panel_frame(na)
    ua, va = (pts.xyz[a] - ca) @ right, (pts.xyz[a] - ca) @ up
    ub, vb = (pts.xyz[b] - ca) @ right, (pts.xyz[b] - ca) @ up
    gap = max(ub.min() - ua.max(), ua.min() - ub.max())
    if gap > params.merge_gap_m:
        return False
    top, bottom = abs(va.max() - vb.max()), abs(va.min() - vb.min())
    if max(top, bottom) <= params.merge_edge_m:
        return True
    if min(top, bottom) > params.merge_edge_m:
        return False                          # neither edge alike: stacked, other
    # the gap between the halves along ``right`` and a pole standing in it, close to the plane
    gap_lo, gap_hi = (ua.max(), ub.min()) if ub.min() >= ua.max() else (ub.max(), ua.min())
    for axis_xy, radius in poles:
        rel = np.r_[axis_xy, ca[2]] - ca
        s_pole = float(rel @ right)
        if abs(float(rel @ na)) <= params.merge_gap_m and \
                gap_lo - radius - params.pole_clearance_m <= s_pole <= gap_hi + radius + params.pole_clearance_m:
            return True
    return False


def _merge_parts(pts: WindowPoints, parts: List[np.ndarray], params: PanelParams,
                 poles: Sequence[Tuple[np.ndarray, float]] = ()) -> List[List[int]]:
    """Groups of part indices to measure as one (union of side-by-side pairs; ``poles``: see
    :func:`_side_by_side`)."""
    parent = list(range(len(parts)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    centres = np.array([pts.xyz[p].mean(axis=0) for p in parts]) if parts else np.zeros((0, 3))
    reach = np.array([float(np.max(np.linalg.norm(pts.xyz[p] - c, axis=1))) for p, c in zip(parts, centres)])
    for i in range(len(parts)):
        for j in range(i + 1, len(parts)):
            if float(np.linalg.norm(centres[i] - centres[j])) > reach[i] + reach[j] + params.merge_gap_m:
                continue
            if root(i) != root(j) and _side_by_side(pts, parts[i], parts[j], params, poles):
                parent[root(j)] = root(i)
    groups: dict = {}
    for i in range(len(parts)):
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def features_off_poles(pts: WindowPoints, poles: Sequence[Tuple[np.ndarray, float]],
                       params: PanelParams) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points' (normal, linearity, flatness), those of the points beside a pole
    (``poles``: axis xy, radius) taken again from their neighbours off the pole.

    Distances are horizontal from the pole's surface (radius + ``pole_surface_m``): points
    within it are the pole's; points from ``pole_clearance_m`` to ``pole_feature_reach_m``
    past it are taken again; points closer than ``pole_clearance_m`` keep theirs (the pole's
    own points just past its estimated surface would pass as a flat face and stretch the
    panel in front of it along the pole). The window's own arrays are not changed."""
    normal, linearity, flatness = pts.normal, pts.linearity, pts.flatness
    if params.pole_feature_reach_m <= 0 or not len(poles) or not len(pts):
        return normal, linearity, flatness
    normal, linearity, flatness = normal.copy(), linearity.copy(), flatness.copy()
    by_x = np.argsort(pts.xyz[:, 0], kind="stable")      # a pole's points: a slab of x, then exact
    x_sorted = pts.xyz[by_x, 0]
    for axis_xy, radius in poles:
        surface = radius + params.pole_surface_m
        # the neighbours come from twice the reach, so the points within the reach have them all
        outer = surface + 2.0 * params.pole_feature_reach_m
        lo = int(np.searchsorted(x_sorted, axis_xy[0] - outer, side="left"))
        hi = int(np.searchsorted(x_sorted, axis_xy[0] + outer, side="right"))
        slab = np.sort(by_x[lo:hi])
        d = np.linalg.norm(pts.xyz[slab, :2] - axis_xy, axis=1)
        inside = (d > surface) & (d <= outer)
        around, d = slab[inside], d[inside]
        if len(around) < FEATURE_NEIGHBOURS:
            continue
        n_a, lin_a, flat_a, _ = local_features(pts.xyz[around])
        near = (d > surface + params.pole_clearance_m) & (d <= surface + params.pole_feature_reach_m)
        rows = around[near]
        normal[rows], linearity[rows], flatness[rows] = n_a[near], lin_a[near], flat_a[near]
    return normal, linearity, flatness


def find_panels(pts: WindowPoints, ground_z, params: PanelParams, seed: int = 0,
                poles: Sequence[Tuple[np.ndarray, float]] = (), diagnostics: Optional[list] = None
                ) -> Tuple[List[PanelCandidate], dict]:
    """Panel candidates of a window (both paths) and counts of rejections by reason;
    ``poles``: (axis xy, radius) of the window's poles, whose points are kept out of the
    planes; ``diagnostics`` (a list) gets one dict per planar part measured (debugging)."""
    reasons: dict = {}
    cands: List[PanelCandidate] = []
    bright_rows = np.flatnonzero(pts.bright & (pts.h >= params.min_bright_height_m))
    tilt_sin = math.sin(math.radians(params.dark_max_normal_tilt_deg))
    normal, linearity, flatness = features_off_poles(pts, poles, params)
    n_h = normal[:, :2] / np.maximum(np.linalg.norm(normal[:, :2], axis=1, keepdims=True), 1e-9)
    along = np.abs(np.einsum("ij,ij->i", n_h, pts.tangent_xy))
    dark = (~pts.bright & (pts.h >= params.min_bottom_height_m) & (pts.h <= params.max_top_height_m)
            & (flatness <= params.dark_max_flatness) & (linearity <= params.dark_max_linearity)
            & (np.abs(normal[:, 2]) <= tilt_sin)
            & (along >= math.cos(math.radians(params.max_normal_to_track_deg + params.dark_normal_slack_deg))))
    if len(bright_rows):
        near_bright = cKDTree(pts.xyz[bright_rows]).query(pts.xyz[dark], k=1,
                                                          distance_upper_bound=params.dark_clearance_m)[0]
        dark_rows = np.flatnonzero(dark)[~np.isfinite(near_bright)]
    else:
        dark_rows = np.flatnonzero(dark)
    for axis_xy, radius in poles:             # a dense pole is locally flat: keep it out
        d = np.linalg.norm(pts.xyz[dark_rows, :2] - axis_xy, axis=1)
        dark_rows = dark_rows[d > radius + params.pole_surface_m]
    parts: List[np.ndarray] = []
    for rows_all in (bright_rows, dark_rows):
        if len(rows_all) < params.min_points:
            continue
        labels = euclidean_clusters(pts.xyz[rows_all], params.cluster_tolerance_m)
        order = np.argsort(labels, kind="stable")
        bounds = np.flatnonzero(np.r_[True, np.diff(labels[order]) != 0, True])
        for a, b in zip(bounds[:-1], bounds[1:]):
            rows = rows_all[order[a:b]]
            if len(rows) < params.min_points:
                continue
            ext = np.ptp(pts.xyz[rows], axis=0)
            if max(float(np.hypot(ext[0], ext[1])), float(ext[2])) > params.max_cluster_extent_m:
                reasons["too large"] = reasons.get("too large", 0) + 1
                continue
            parts.extend(segment_panels(pts, rows, params, seed, poles))

    def measure(rows: np.ndarray) -> Optional[PanelCandidate]:
        panel, reason = measure_panel(pts, rows, ground_z, params)
        if diagnostics is not None:
            diagnostics.append({"centre": pts.xyz[rows].mean(axis=0), "n": len(rows), "reason": reason,
                                "bright": bool(np.mean(pts.bright[rows]) >= params.bright_min_share)})
        if panel is None:
            reasons[reason] = reasons.get(reason, 0) + 1
        return panel

    for group in _merge_parts(pts, parts, params, poles):
        merged = measure(np.concatenate([parts[i] for i in group])) if len(group) > 1 else None
        if merged is not None:
            cands.append(merged)
            continue
        for i in group:                       # measured one by one when the union fails
            panel = measure(parts[i])
            if panel is not None:
                cands.append(panel)
    return cands, reasons
