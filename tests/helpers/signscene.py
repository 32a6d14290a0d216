"""A small road scene with sign panels of known pose, panorama stations and the detections a
perfect detector (plus box noise) would report, for the projection and refine tests.

Local frame: x along the road (the vehicle drives +x = east), y to the left (north),
z up; world = local + ``ORIGIN``. Ground (class 2) is the plane ``z = 0.01 x + 0.002 y``.
Panel points are uniform in the panel's shape (circle, triangles, octagon, rectangle)
with 1 cm noise along the normal; retroreflective faces are bright, faded ones and the
convex mirror are not. Detections come from projecting each panel's outline into every
station that sees its front face within ``DETECT_RANGE_M``, 1 px noise on the box edges.

Contents (``SignScene.signs``, local x, y):

1. prohibitory circle on a pole (20, -6);
2-3. warning triangle over an information square on one pole (40, -6.1);
4-5. two mandatory circles on one pole (60, -6);
6. information square facing the road, a wall 3 m behind it (82, -6);
7. faded yield (triangle down) on the left (100, 6.2), facing oncoming traffic;
8. a stop octagon out of the scanner's reach (no points), seen from exactly 3 stations;
9. information panel over the road facing backwards: its boxes cross the panorama seam;
10. mandatory circle (145, -6);
and a convex traffic mirror (135, 6.4) that the detector takes for a prohibitory sign.
Tests may pass their own panels: surfaces that are not signs (``is_sign=False``, e.g. a
billboard, ``detected=False`` for one the detector ignores) lose the points hidden by a
sign right in front of them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from roadsigns.core import geometry

ORIGIN = np.array([500000.0, 5400000.0, 100.0])
PANO_W, PANO_H = 4096, 2048
DETECT_RANGE_M = 28.0
CAMERA_HEIGHT_M = 2.4
STATION_X = np.arange(0.0, 155.0, 5.0)
SCALE = 65535.0


def ground_z_local(x, y):
    return 0.01 * np.asarray(x, float) + 0.002 * np.asarray(y, float)


@dataclass
class TruthPanel:
    sign_id: int
    cls: str
    shape: str                 # circle, triangle_up, triangle_down, octagon, rect
    centre_local: np.ndarray
    normal: np.ndarray
    width: float
    height: float
    is_sign: bool = True
    has_points: bool = True
    faded: bool = False
    pole: bool = True
    convex_radius_m: Optional[float] = None
    seen_from: Optional[List[int]] = None   # station indices (else: by range and facing)
    detected: bool = True      # False: a surface the detector does not report (a wall)
    reflectance: Optional[float] = None     # of a surface that is not a sign (else 0.55)
    scan_lines_s: Optional[List[float]] = None  # points only on vertical lines at these s (m)

    @property
    def right(self):
        r = np.cross(-self.normal, [0.0, 0.0, 1.0])
        return r / np.linalg.norm(r)

    @property
    def up(self):
        return np.cross(self.right, -self.normal)

    @property
    def centre_world(self):
        return self.centre_local + ORIGIN

    @property
    def ground_z_world(self):
        return float(ground_z_local(self.centre_local[0], self.centre_local[1])) + ORIGIN[2]

    @property
    def height_above_ground(self):
        return float(self.centre_world[2] - self.ground_z_world)

    @property
    def azimuth_deg(self):
        return float(geometry.azimuth_deg_of_enu(self.normal))

    def inside(self, s, t):
        """Mask of in-plane coordinates (s right, t up, metres from the centre) on the face."""
        a, b = self.width / 2, self.height / 2
        if self.shape == "circle":
            return (s / a) ** 2 + (t / b) ** 2 <= 1.0
        if self.shape == "triangle_up":
            return (np.abs(s) <= a * (b - t) / (2 * b)) & (np.abs(t) <= b)
        if self.shape == "triangle_down":
            return (np.abs(s) <= a * (t + b) / (2 * b)) & (np.abs(t) <= b)
        if self.shape == "octagon":
            return (np.abs(s) <= a) & (np.abs(t) <= b) & (np.abs(s) + np.abs(t) <= a * math.sqrt(2))
        return (np.abs(s) <= a) & (np.abs(t) <= b)

    def to_local(self, s, t):
        w = np.zeros_like(s)
        if self.convex_radius_m:
            w = -(s ** 2 + t ** 2) / (2 * self.convex_radius_m)  # edges fall back: convex
        return (self.centre_local + np.multiply.outer(s, self.right) + np.multiply.outer(t, self.up)
                + np.multiply.outer(w, self.normal))

    def outline_local(self, n=256):
        """Points of the face's outline (boundary of the shape mask)."""
        a, b = self.width / 2, self.height / 2
        g = np.linspace(-1, 1, n)
        s, t = np.meshgrid(g * a, g * b)
        m = self.inside(s, t)
        edge = m & ~(np.roll(m, 1, 0) & np.roll(m, -1, 0) & np.roll(m, 1, 1) & np.roll(m, -1, 1))
        edge |= m & ((np.abs(s) >= a * 0.999) | (np.abs(t) >= b * 0.999))
        return self.to_local(s[edge], t[edge])


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def default_panels() -> List[TruthPanel]:
    tan6 = math.tan(math.radians(6))
    oncoming_right = _unit([-1, tan6, 0])
    oncoming_left = _unit([-1, -tan6, 0])

    def at(x, y, h):
        return np.array([x, y, float(ground_z_local(x, y)) + h])

    return [
        TruthPanel(1, "prohibitory", "circle", at(20, -6.0, 2.6), oncoming_right, 0.6, 0.6),
        TruthPanel(2, "warning", "triangle_up", at(40, -6.1, 2.1 + 0.6 + 0.08 + 0.39),
                   oncoming_right, 0.9, 0.78),
        TruthPanel(3, "information", "rect", at(40, -6.1, 2.1 + 0.3), oncoming_right, 0.6, 0.6,
                   pole=False),
        TruthPanel(4, "mandatory", "circle", at(60, -6.0, 2.2 + 0.6 + 0.08 + 0.3),
                   oncoming_right, 0.6, 0.6),
        TruthPanel(5, "mandatory", "circle", at(60, -6.0, 2.2 + 0.3), oncoming_right, 0.6, 0.6,
                   pole=False),
        TruthPanel(6, "information", "rect", at(82, -6.0, 2.5), _unit([-0.17, 1, 0]), 0.6, 0.6),
        TruthPanel(7, "yield", "triangle_down", at(100, 6.2, 2.6), oncoming_left, 0.9, 0.78,
                   faded=True),
        TruthPanel(8, "stop", "octagon", at(118, -16.0, 4.0), _unit([-1, 0.3, 0]), 0.6, 0.6,
                   has_points=False, pole=False, seen_from=[19, 20, 21]),
        TruthPanel(9, "information", "rect", at(30, 0.2, 5.5), _unit([1, 0, 0]), 1.0, 0.6,
                   pole=False),
        TruthPanel(10, "mandatory", "circle", at(145, -6.0, 2.5), oncoming_right, 0.6, 0.6),
        TruthPanel(11, "prohibitory", "circle", at(135, 6.4, 2.6),
                   _unit([-math.cos(0.6), -math.sin(0.6), 0]), 0.8, 0.8, is_sign=False,
                   convex_radius_m=1.0),
    ]


@dataclass
class SignScene:
    xyz_world: np.ndarray
    classification: np.ndarray
    intensity: np.ndarray
    station_centre_world: np.ndarray
    station_q_wxyz: np.ndarray
    station_images: List[str]
    panels: List[TruthPanel]
    detections: List[dict] = field(default_factory=list)

    @property
    def signs(self) -> List[TruthPanel]:
        return [p for p in self.panels if p.is_sign]

    def n_views(self, sign_id: int) -> int:
        return sum(1 for d in self.detections if d["truth_id"] == sign_id)


def _sample_panel(p: TruthPanel, density, rng):
    area = p.width * p.height
    n = rng.poisson(area * density)
    s = rng.uniform(-p.width / 2, p.width / 2, n)
    t = rng.uniform(-p.height / 2, p.height / 2, n)
    if p.scan_lines_s:  # a face scanned at a grazing angle: a few profiles across it
        s = rng.choice(np.asarray(p.scan_lines_s, float), n) + rng.normal(0, 0.003, n)
        n = int(n * 0.1 * len(p.scan_lines_s))
        s, t = s[:n], t[:n]
    keep = p.inside(s, t)
    pts = p.to_local(s[keep], t[keep]) + rng.normal(0, 0.01, (keep.sum(), 1)) * p.normal
    return pts


def _behind_a_sign(pts, surface: TruthPanel, panels: List[TruthPanel]) -> np.ndarray:
    """Points of a surface hidden by a sign panel right in front of it (within 0.3 m): the
    scanner sees the sign there, not the wall behind it."""
    hidden = np.zeros(len(pts), bool)
    for q in panels:
        if q is surface or not q.has_points or not q.is_sign:
            continue
        rel = pts - q.centre_local
        depth = rel @ q.normal
        hidden |= (depth < 0) & (depth > -0.3) & q.inside(rel @ q.right, rel @ q.up)
    return hidden


def _cylinder(x, y, r, z0, z1, density, rng):
    n = rng.poisson(2 * np.pi * r * (z1 - z0) * density)
    a = rng.uniform(0, 2 * np.pi, n)
    return np.column_stack([x + r * np.cos(a), y + r * np.sin(a), rng.uniform(z0, z1, n)])


def make_scene(seed: int = 0, panel_density: float = 600.0, ground_density: float = 25.0,
               box_noise_px: float = 1.0, panels: Optional[List[TruthPanel]] = None,
               road_length_m: float = 160.0, stations_x=STATION_X) -> SignScene:
    rng = np.random.default_rng(seed)
    panels = default_panels() if panels is None else panels
    parts = []  # (xyz_local, class, intensity)

    def add(xyz, cls, reflectance, incidence=True):
        xyz = np.asarray(xyz, float).reshape(-1, 3)
        f = 0.7 if incidence else 1.0
        inten = np.clip(reflectance * f * SCALE * (1 + 0.06 * rng.standard_normal(len(xyz))), 0, SCALE)
        parts.append((xyz, np.full(len(xyz), cls, np.uint8), inten.astype(np.uint16)))

    # ground
    n = rng.poisson(road_length_m * 40 * ground_density)
    x, y = rng.uniform(-10, road_length_m - 10, n), rng.uniform(-20, 20, n)
    add(np.column_stack([x, y, ground_z_local(x, y) + rng.normal(0, 0.01, n)]), 2, 0.08)
    # a wall 3 m behind sign 6, a building front on the left
    n = rng.poisson(25 * 6 * 150)
    x, z = rng.uniform(70, 95, n), rng.uniform(0, 6, n)
    add(np.column_stack([x, np.full(n, -9.0), ground_z_local(x, -9.0) + z]), 6, 0.3)
    for p in panels:
        if not p.has_points:
            continue
        pts = _sample_panel(p, panel_density, rng)
        if not p.is_sign:
            pts = pts[~_behind_a_sign(pts, p, panels)]
            add(pts, 1, 0.55 if p.reflectance is None else p.reflectance)
        else:
            add(pts, 1, 0.22 if p.faded else 0.95, incidence=p.faded)
        if p.pole:
            top = max(q.centre_local[2] + q.height / 2 for q in panels
                      if np.linalg.norm(q.centre_local[:2] - p.centre_local[:2]) < 0.2) + 0.05
            axis = p.centre_local[:2] - 0.06 * p.normal[:2]
            g = float(ground_z_local(*axis))
            add(_cylinder(axis[0], axis[1], 0.035, g, top, panel_density * 0.6, rng), 1, 0.35)
    xyz = np.concatenate([q[0] for q in parts])
    cls = np.concatenate([q[1] for q in parts])
    inten = np.concatenate([q[2] for q in parts])
    order = rng.permutation(len(xyz))
    xyz, cls, inten = xyz[order] + ORIGIN, cls[order], inten[order]

    # stations: heading east, small pitch/roll; panorama frame = body frame
    centres, quats, images = [], [], []
    for i, sx in enumerate(stations_x):
        c = np.array([sx, 0.0, float(ground_z_local(sx, 0.0)) + CAMERA_HEIGHT_M]) + ORIGIN
        R = geometry.R_world_from_pano(0.3, -0.5, 90.0 + 0.5 * np.sin(i), np.eye(3))
        centres.append(c)
        quats.append(geometry.quat_wxyz_from_matrix(R))
        images.append(f"pano_{i:05d}.jpg")
    scene = SignScene(xyz, cls, inten, np.array(centres), np.array(quats), images, panels)
    scene.detections = make_detections(scene, box_noise_px, rng)
    return scene


def make_detections(scene: SignScene, box_noise_px: float, rng) -> List[dict]:
    rows = []
    det_id = 0
    for i, (c, q, image) in enumerate(zip(scene.station_centre_world, scene.station_q_wxyz,
                                          scene.station_images)):
        R = geometry.matrix_from_quat_wxyz(q)
        for p in scene.panels:
            if not p.detected:
                continue
            to_station = c - p.centre_world
            dist = float(np.linalg.norm(to_station))
            if p.seen_from is not None:
                if i not in p.seen_from:
                    continue
            elif not (3.0 <= dist <= DETECT_RANGE_M and p.normal @ to_station > 0.2 * dist):
                continue
            outline = p.outline_local() + ORIGIN
            u, v, _ = geometry.world_to_pixel(outline, c, R, PANO_W, PANO_H)
            uc, _, _ = geometry.world_to_pixel(p.centre_world, c, R, PANO_W, PANO_H)
            du = np.mod(u - uc + PANO_W / 2, PANO_W) - PANO_W / 2  # unwrap around the centre
            u0, u1 = uc + du.min(), uc + du.max()
            shift = np.floor(u0 / PANO_W) * PANO_W
            u0, u1 = u0 - shift, u1 - shift
            box = np.array([u0, v.min(), u1, v.max()]) + rng.normal(0, box_noise_px, 4)
            det_id += 1
            rows.append({"det_id": det_id, "station_id": i + 1, "image": image, "class": p.cls,
                         "score": float(rng.uniform(0.6, 0.95)), "u0": box[0], "v0": box[1],
                         "u1": box[2], "v1": box[3], "width": PANO_W, "height": PANO_H,
                         "x": c[0], "y": c[1], "z": c[2], "qw": q[0], "qx": q[1], "qy": q[2],
                         "qz": q[3], "truth_id": p.sign_id})
    return rows


def write_las(scene: SignScene, path: str) -> None:
    """Write the cloud as LAS/LAZ (class 2 ground, 1 unclassified objects, 6 building)."""
    from helpers import cloudgen

    n = len(scene.xyz_world)
    one = np.ones(n, np.uint8)
    cloudgen.write_scene(path, cloudgen.Scene(scene.xyz_world, scene.classification == 2,
                                              scene.classification, one, one,
                                              1000.0 + np.arange(n) * 1e-5, scene.intensity),
                         classification=scene.classification)
