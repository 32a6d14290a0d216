#!/usr/bin/env python3
"""Benchmark core.projection: time against cloud size and number of detections.

The cloud is the test sign scene (tests/helpers/signscene.py, 160 m of road) repeated
1x, 3x, 9x along the road; the detections are those of the first copy, repeated 1x, 3x,
9x (same boxes, so the same work per detection). Prints, per case, the time to read the
LAS into the index (streaming, cropped to the frusta), the time of the search itself and
both as ratios to the smallest case, measured in this process. Expected: the search
grows with the detections and not with the cloud (each detection touches only the
tiles under its frustum); the read grows with the file.

    .venv/bin/python bench/bench_projection.py [--repeats 3] [--keep DIR]
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def _import_package():
    if os.path.isdir("/usr/share/proj"):  # pyproj inside a venv looks under the venv otherwise
        os.environ.setdefault("PROJ_DATA", "/usr/share/proj")
    sys.path.insert(0, REPO)
    from devtools import import_roadsigns
    import_roadsigns()
    sys.path.insert(0, os.path.join(REPO, "tests"))


def tiled_scene(base, copies: int):
    """The base scene repeated ``copies`` times along +x (the ground keeps its slope)."""
    from helpers import signscene

    shift = np.array([160.0, 0.0, 1.6])
    xyz = np.concatenate([base.xyz_world + k * shift for k in range(copies)])
    tiled = signscene.SignScene(xyz, np.tile(base.classification, copies),
                                np.tile(base.intensity, copies), base.station_centre_world,
                                base.station_q_wxyz, base.station_images, base.panels,
                                base.detections)
    return tiled


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=3, help="timing runs per case (best kept)")
    parser.add_argument("--keep", help="folder for the LAS files (default: a temporary one)")
    args = parser.parse_args(argv)
    _import_package()
    import shapely
    from helpers import signscene

    from roadsigns.core import projection as P
    from roadsigns.core.pointcloud import CropRegion, TiledIndex

    base = signscene.make_scene(seed=1)
    folder = args.keep or tempfile.mkdtemp(prefix="bench-projection-")
    rows = []
    for copies in (1, 3, 9):
        scene = tiled_scene(base, copies)
        path = os.path.join(folder, f"cloud_x{copies}.las")
        signscene.write_las(scene, path)
        for factor in (1, 3, 9):
            det = P.Detections.from_records(base.detections * factor)
            frusta = P.Frusta.build(det, P.DEFAULT_MAX_RANGE_M, 0.25, 0.1)
            best_read = best_search = np.inf
            for _ in range(args.repeats):
                t0 = time.perf_counter()
                index = TiledIndex.from_las(path, CropRegion(shapely.union_all(frusta.footprints())),
                                            dimensions=("intensity", "classification"),
                                            tile_size_m=5.0)
                t1 = time.perf_counter()
                res = P.project_detections(det, index)
                t2 = time.perf_counter()
                best_read, best_search = min(best_read, t1 - t0), min(best_search, t2 - t1)
            rows.append((len(scene.xyz_world), len(det), len(index), best_read, best_search,
                         float(res.points_tested.mean()), float(res.tiles_visited.mean())))
    r0, s0 = rows[0][3], rows[0][4]
    print(f"{'cloud pts':>10} {'detections':>10} {'indexed':>9} {'read s':>8} {'x':>6} "
          f"{'search s':>9} {'x':>6} {'s/det ms':>9} {'pts/det':>8} {'tiles/det':>9}")
    for n_pts, n_det, n_idx, t_read, t_search, pts_det, tiles_det in rows:
        print(f"{n_pts:>10d} {n_det:>10d} {n_idx:>9d} {t_read:>8.3f} {t_read / r0:>6.2f} "
              f"{t_search:>9.3f} {t_search / s0:>6.2f} {1000 * t_search / n_det:>9.2f} "
              f"{pts_det:>8.0f} {tiles_det:>9.1f}")
    print("ratios are to the first row; search time should follow the detections (x1/x3/x9) "
          "and not the cloud size.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
