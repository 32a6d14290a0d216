"""Synthetic mobile-mapping clouds for the point-cloud and ground tests (numpy + laspy).

A straight road along +x seen by a vehicle driving its centre line: carriageway
``|y| <= 3.5`` m, 0.15 m curbs, sidewalks and verges up to ``|y| = 15`` m, poles with sign
panels, parked cars, a building wall and trees. ``slope`` tilts the whole scene along x
(0.06 = 6 %). Coordinates are local metres plus a UTM-like ``origin``. Density falls off
with distance from the vehicle as for a real scanner. Truth: ``is_ground`` (road, curb
faces, sidewalks, verges, ground under trees); ``semantic`` codes as LAS classes (2
ground, 6 building, 5 vegetation, 1 cars/poles/signs).

Import from a test module with the relative-path trick::

    sys.path.insert(0, os.path.dirname(__file__)); import cloudgen
"""
from __future__ import annotations

from dataclasses import dataclass

import laspy
import numpy as np

CURB_Y_M = 3.5
CURB_HEIGHT_M = 0.15
HALF_WIDTH_M = 15.0
ORIGIN = (500000.0, 5400000.0, 100.0)


@dataclass
class Scene:
    xyz: np.ndarray               # (n, 3) world coordinates
    is_ground: np.ndarray         # (n,) bool
    semantic: np.ndarray          # (n,) uint8 LAS-like class
    return_number: np.ndarray
    number_of_returns: np.ndarray
    gps_time: np.ndarray
    intensity: np.ndarray

    def __len__(self):
        return len(self.xyz)


def ground_height(x, y, slope):
    """Terrain height (local) at (x, y): a plane of ``slope`` along x, raised curb sides."""
    return slope * np.asarray(x) + np.where(np.abs(y) > CURB_Y_M, CURB_HEIGHT_M, 0.0)


class _Builder:
    def __init__(self, rng, slope, noise_m):
        self.rng, self.slope, self.noise = rng, slope, noise_m
        self.parts = []

    def add(self, xyz_local, ground, semantic, nret=1, rnum=1):
        n = len(xyz_local)
        if n == 0:
            return
        xyz = np.asarray(xyz_local, float).copy()
        xyz += self.rng.normal(0.0, self.noise, xyz.shape)
        self.parts.append((xyz, np.full(n, ground), np.full(n, semantic, np.uint8),
                           np.full(n, rnum, np.uint8), np.full(n, nret, np.uint8)))

    def count(self, area_m2, density):
        return int(self.rng.poisson(max(area_m2 * density, 0.0)))

    def keep_by_range(self, xyz_local):
        """Thin points like a scanner at (x, 0, 2 m): density ~ 1/(1 + (range/8 m)^2)."""
        r = np.hypot(xyz_local[:, 1], xyz_local[:, 2] - 2.0)
        keep_p = 1.0 / (1.0 + (r / 8.0) ** 2)
        return xyz_local[self.rng.random(len(xyz_local)) < keep_p]


def road_scene(length_m: float = 60.0, slope: float = 0.0, density_per_m2: float = 250.0,
               seed: int = 0, noise_m: float = 0.01, origin=ORIGIN) -> Scene:
    rng = np.random.default_rng(seed)
    b = _Builder(rng, slope, noise_m)
    L = length_m
    gz = lambda x, y: ground_height(x, y, slope)  # noqa: E731

    # occluders (cars: footprints on the road; wall at y = 12; ground behind it unseen)
    cars = [(0.25 * L, 1.2, 4.5, 1.8), (0.7 * L, -3.0, 4.5, 1.8)]  # x0, y0, length, width
    wall_y, wall_x = 12.0, (0.1 * L, 0.9 * L)
    trees = [(0.15 * L, -9.0), (0.55 * L, -9.5), (0.85 * L, -8.5)]

    # ground surface (uniform sample, thinned by range)
    n = b.count(L * 2 * HALF_WIDTH_M, density_per_m2)
    x = rng.uniform(0, L, n)
    y = rng.uniform(-HALF_WIDTH_M, HALF_WIDTH_M, n)
    g = np.column_stack([x, y, gz(x, y)])
    g = b.keep_by_range(g)
    hidden = np.zeros(len(g), bool)
    for cx, cy, cl, cw in cars:
        hidden |= (g[:, 0] > cx) & (g[:, 0] < cx + cl) & (g[:, 1] > cy) & (g[:, 1] < cy + cw)
    hidden |= (g[:, 0] > wall_x[0]) & (g[:, 0] < wall_x[1]) & (g[:, 1] > wall_y)
    g = g[~hidden]
    under_tree = np.zeros(len(g), bool)
    for tx, ty in trees:
        under_tree |= np.hypot(g[:, 0] - tx, g[:, 1] - ty) < 2.0
    b.add(g[~under_tree], True, 2)
    b.add(g[under_tree], True, 2, nret=2, rnum=2)  # last returns under the crowns

    # curb faces (vertical, 0 .. 0.15 m), part of the ground
    for side in (-1, 1):
        n = b.count(L * CURB_HEIGHT_M, density_per_m2)
        x = rng.uniform(0, L, n)
        y = np.full(n, side * CURB_Y_M)
        z = slope * x + rng.uniform(0, CURB_HEIGHT_M, n)
        b.add(np.column_stack([x, y, z]), True, 2)

    vertical_density = 0.6 * density_per_m2
    # poles with sign panels (facing -x, towards the traffic)
    for i, px in enumerate(np.arange(0.1 * L, L, 15.0)):
        py = 4.5 if i % 2 == 0 else -4.5
        base = gz(px, py)
        n = b.count(2 * np.pi * 0.07 * 3.5, vertical_density)
        a = rng.uniform(0, 2 * np.pi, n)
        h = rng.uniform(0, 3.5, n)
        b.add(np.column_stack([px + 0.07 * np.cos(a), py + 0.07 * np.sin(a), base + h]),
              False, 1)
        n = b.count(0.6 * 0.6, 4 * vertical_density)
        b.add(np.column_stack([np.full(n, px - 0.1), py + rng.uniform(-0.3, 0.3, n),
                               base + rng.uniform(2.2, 2.8, n)]), False, 1)

    # parked cars: body from 0.3 m to 1.5 m, top and the sides facing the vehicle
    for cx, cy, cl, cw in cars:
        base = gz(cx + cl / 2, cy + cw / 2)
        near_y = cy if cy > 0 else cy + cw
        n = b.count(cl * cw, density_per_m2)
        top = np.column_stack([rng.uniform(cx, cx + cl, n), rng.uniform(cy, cy + cw, n),
                               np.full(n, base + 1.5)])
        n = b.count(cl * 1.2, vertical_density)
        side = np.column_stack([rng.uniform(cx, cx + cl, n), np.full(n, near_y),
                                base + rng.uniform(0.3, 1.5, n)])
        n = b.count(cw * 1.2, vertical_density)
        back = np.column_stack([np.full(n, cx), rng.uniform(cy, cy + cw, n),
                                base + rng.uniform(0.3, 1.5, n)])
        for part in (top, side, back):
            b.add(part, False, 1)

    # building wall, 6 m high
    n = b.count((wall_x[1] - wall_x[0]) * 6.0, vertical_density)
    x = rng.uniform(*wall_x, n)
    wall = np.column_stack([x, np.full(n, wall_y), gz(x, np.full(n, wall_y))
                            + rng.uniform(0, 6.0, n)])
    b.add(b.keep_by_range(wall), False, 6)

    # trees: trunk r 0.15 m to 2.5 m, crown sphere r 2 m at 4.5 m (first of two returns)
    for tx, ty in trees:
        base = gz(tx, ty)
        n = b.count(2 * np.pi * 0.15 * 2.5, vertical_density)
        a = rng.uniform(0, 2 * np.pi, n)
        b.add(np.column_stack([tx + 0.15 * np.cos(a), ty + 0.15 * np.sin(a),
                               base + rng.uniform(0, 2.5, n)]), False, 5)
        n = b.count(4 * np.pi * 4.0, vertical_density)
        d = rng.normal(size=(n, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        crown = np.array([tx, ty, base + 4.5]) + 2.0 * d * rng.uniform(0.7, 1.0, (n, 1))
        b.add(crown, False, 5, nret=2, rnum=1)

    xyz, ground, semantic, rnum, nret = (np.concatenate(p) for p in zip(*b.parts))
    order = np.argsort(xyz[:, 0], kind="stable")  # acquisition order along the road
    xyz, ground, semantic, rnum, nret = (a[order] for a in (xyz, ground, semantic, rnum, nret))
    xyz = xyz + np.asarray(origin, float)
    gps_time = 1000.0 + (xyz[:, 0] - origin[0]) / 10.0
    intensity = rng.integers(0, 65535, len(xyz)).astype(np.uint16)
    return Scene(xyz, ground, semantic, rnum, nret, gps_time, intensity)


def write_scene(path: str, scene: Scene, point_format: int = 6, crs_epsg=25833,
                classification=None) -> None:
    """Write a scene as LAS/LAZ (by extension) with mm scales; classes 0 unless given."""
    version = "1.4" if point_format >= 6 else "1.2"
    header = laspy.LasHeader(point_format=point_format, version=version)
    header.scales = np.array([0.001, 0.001, 0.001])
    header.offsets = np.floor(scene.xyz.min(axis=0))
    if crs_epsg is not None:
        import pyproj

        header.add_crs(pyproj.CRS.from_epsg(crs_epsg))
    las = laspy.LasData(header)
    las.x, las.y, las.z = scene.xyz[:, 0], scene.xyz[:, 1], scene.xyz[:, 2]
    las.return_number = scene.return_number
    las.number_of_returns = scene.number_of_returns
    las.intensity = scene.intensity
    if "gps_time" in las.point_format.dimension_names:
        las.gps_time = scene.gps_time
    if classification is not None:
        las.classification = classification
    las.write(path)
